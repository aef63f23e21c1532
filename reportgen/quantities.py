"""A run's scalar results with their units: what :attr:`reportgen.Run.results` gives.

Each result is a :class:`Result`: its value as the archive stores it, with the unit, the
description and the symbol the kind declares for it (``kinds/<kind>/results.py``, the
declaration every archive attribute, axis label and table header comes from), so that a
notebook does not guess what a bare number means:

>>> r = Result("period", 2.0064, "s", "period of the oscillation", "T")
>>> float(r), r.value, r.unit
(2.0064, 2.0064, 's')
>>> str(r)
'2.0064 s'
>>> f"{r:.2f}"
'2.01'

``r.quantity`` is the value as a pint Quantity (pint's application registry, the one
pint-xarray uses).  A number in the config's own units (a formula system's time, three
bodies in the units the config chose) is declared "1" and says so in ``config_units``.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

__all__ = ["Result", "ResultSet"]

#: how a declared unit in the config's own units begins (as config descriptions write it)
_OWN_UNITS = "config units"


@dataclass(frozen=True)
class Result:
    """One scalar result of a run.

    Parameters
    ----------
    name : str
        Its name in ``/analysis`` ("period"; "group/name" for one of a subgroup).
    value : bool, int, float or str
        As stored.
    unit : str
        A unit pint reads ("s", "rad/s", "kg m^2"), "1" for a pure number or one in the
        config's own units, "" for text, flags and undeclared results.
    description : str
        The declaration's words ("period of the oscillation").
    symbol : str
        TeX without dollars (``T``, ``\\omega_0``), "" when none.
    config_units : str
        For a number in the config's own units: what it measures in them ("config units
        of time"); "" otherwise.
    """

    name: str
    value: bool | int | float | str
    unit: str = ""
    description: str = ""
    symbol: str = ""
    config_units: str = ""

    def __float__(self) -> float:
        return float(self.value)

    def __int__(self) -> int:
        return int(self.value)

    def __bool__(self) -> bool:
        return bool(self.value)

    def __str__(self) -> str:
        shown = self.unit if self.unit not in ("", "1") else ""
        return f"{self.value} {shown}".strip() if shown else str(self.value)

    def __format__(self, spec: str) -> str:
        return format(self.value, spec) if spec else str(self)

    @property
    def quantity(self):
        """The value as a pint Quantity in pint's application registry (dimensionless for
        "1"); TypeError for text and flags."""
        import pint

        if isinstance(self.value, bool | str):
            raise TypeError(f"result {self.name!r} is {type(self.value).__name__}, not a "
                            "number with a unit")
        registry = pint.get_application_registry()
        if self.unit in ("", "1"):
            return registry.Quantity(self.value, "dimensionless")
        return self.value * registry.parse_expression(self.unit)  # "4.075 fs": a multiple


class ResultSet(Mapping[str, Result]):
    """A run's results by name (``results["period"]``, or ``results.period`` for a name
    that is an identifier); :meth:`values_only` gives the plain numbers."""

    def __init__(self, results: Mapping[str, Result]):
        self._results = dict(results)

    def __getitem__(self, name: str) -> Result:
        return self._results[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._results)

    def __len__(self) -> int:
        return len(self._results)

    def __getattr__(self, name: str) -> Result:
        try:
            return self.__dict__["_results"][name]
        except KeyError:
            raise AttributeError(name) from None

    def __dir__(self):
        return [*super().__dir__(), *(k for k in self._results if k.isidentifier())]

    def __repr__(self) -> str:
        return "ResultSet(" + ", ".join(f"{k}={v}" for k, v in self._results.items()) + ")"

    def values_only(self) -> dict[str, Any]:
        """``{name: value}``: the bare values (what ``run.results`` held before units)."""
        return {k: r.value for k, r in self._results.items()}


def declared_result(name: str, value, declared, config_units: str = "") -> Result:
    """The :class:`Result` of ``value`` under its declaration ``declared`` (a
    :class:`~reportgen.scene.schema.Quantity`); a declared unit in the config's own units
    ("config units of time") becomes "1" with that text in ``config_units``."""
    unit = str(declared.unit)
    if unit.startswith(_OWN_UNITS):
        unit, config_units = "1", config_units or unit
    if isinstance(value, bool | str):
        unit = ""
    return Result(name=name, value=value, unit=unit, description=str(declared.description),
                  symbol=str(declared.symbol), config_units=config_units)


def archive_results(data) -> ResultSet:
    """The scalar results of an archive read by :func:`~reportgen.archive.store.read_archive`
    (``/analysis`` and its subgroups, "group/name"), each under its kind's declaration
    (the kind's ``result_quantity``: a formula system's follows its config); the
    ``config_units`` the archive stored with it (format 3)."""
    import json

    import numpy as np

    from .archive.h5io import QUANTITIES_ATTR
    from .kinds import get_kind
    from .scene.schema import Quantity, flatten

    try:
        kind = get_kind(data.kind)
    except KeyError:
        kind = None
    stored = _stored_quantities(data.path, QUANTITIES_ATTR, json)
    out: dict[str, Result] = {}
    for name, value in flatten(data.analysis):
        if isinstance(value, bytes):
            value = value.decode("utf-8")
        elif isinstance(value, np.generic):
            value = value.item()
        if not isinstance(value, bool | int | float | str):
            continue
        try:
            declared = kind.result_quantity(data, name) if kind is not None else None
        except Exception:  # noqa: BLE001 - a kind's lookup failing costs only the words
            declared = None
        if declared is None:
            declared = Quantity(name, "", "", name.replace("_", " ").replace("/", ": "))
        out[name] = declared_result(name, value, declared,
                                    str(stored.get(name, {}).get("config_units", "")))
    return ResultSet(out)


def _stored_quantities(path, attr: str, json) -> dict[str, dict]:
    """The CF attributes an archive stored for the scalar results of ``/analysis`` and its
    subgroups (their attr ``__quantities__``), by "group/name"."""
    import h5py

    out: dict[str, dict] = {}
    if path is None:
        return out

    def read(prefix: str, group) -> None:
        raw = group.attrs.get(attr)
        if raw is not None:
            try:
                found = json.loads(raw.decode("utf-8") if isinstance(raw, bytes) else raw)
            except (ValueError, TypeError):
                found = {}
            if isinstance(found, dict):
                out.update({f"{prefix}{k}": v for k, v in found.items() if isinstance(v, dict)})
        for key, item in group.items():
            if isinstance(item, h5py.Group):
                read(f"{prefix}{key}/", item)

    try:
        with h5py.File(path, "r") as f:
            if isinstance(f.get("analysis"), h5py.Group):
                read("", f["analysis"])
    except OSError:
        return {}
    return out
