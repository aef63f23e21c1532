"""What a scene run produces, in memory: the same shape the archive stores.

``Results`` is written by :mod:`reportgen.archive.store` and read back into the same
classes, so the report step sees exactly what a fresh run saw.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: a run's *numerical health*, best first (SPEC.md "HDF5 layout"): "ok"; "inaccurate" (it
#: ran cleanly, but its error against its reference is not small against the scene's own
#: scale, :data:`ACCURACY_TOLERANCE`); "unstable" (an invariant drifted, or a named explicit
#: method met stiffness); "failed" (the solver gave up, or the state is not finite).  An
#: unstable run is worse than an inaccurate one: its error is not even controlled, and an
#: inaccurate run's data can still be read (a looser tolerance, a too-long fixed step).
STATUSES = ("ok", "inaccurate", "unstable", "failed")

#: a run (or a study row) is "inaccurate" when its largest error against its reference
#: exceeds this fraction of the scene's own scale (:class:`AccuracyScale`; a Kepler orbit's
#: semi-major axis, say: an error of 1 mm on a 1 m orbit is the limit)
ACCURACY_TOLERANCE = 1e-3


def worst_status(*statuses: str) -> str:
    """The worst of several statuses: failed > unstable > inaccurate > ok."""
    return max(statuses, key=STATUSES.index, default="ok")


@dataclass(frozen=True)
class AccuracyScale:
    """The size an error against a reference is measured against (a scene's own scale).

    ``value`` in ``unit``; ``what`` names it ("the orbit's semi-major axis a").  A run's
    error is small when it is at most :data:`ACCURACY_TOLERANCE` × ``value``.
    """

    value: float
    what: str
    unit: str = ""

    @property
    def limit(self) -> float:
        """The largest error that still counts as accurate."""
        return ACCURACY_TOLERANCE * self.value

    def verdict(self, error: float) -> str:
        """"inaccurate" when ``error`` (finite) exceeds :attr:`limit`, else "ok"."""
        return "inaccurate" if math.isfinite(error) and error > self.limit else "ok"

    def reason(self, error: float) -> str:
        """Why ``error`` is inaccurate: "error 6.2 > 0.001 × the orbit's semi-major axis a
        (1 m)" (the error is a max over the state's components, which may mix units)."""
        unit = f" {self.unit}" if self.unit else ""
        return (f"error {error:.2g} > {ACCURACY_TOLERANCE:g} × {self.what} "
                f"({self.value:.3g}{unit})")


@dataclass
class RunRecord:
    """One integrated trajectory: ``/runs/<name>``.

    Attributes
    ----------
    t : ndarray, shape (N,)
    y : ndarray, shape (N, d)
    columns : list of str, length d
    invariants : dict of str -> ndarray, shape (N,)
    attrs : dict
        method, rtol, atol, nfev, wall_time_s, status, message and anything the
        integrator adds (nsteps, nreject, h, compile_time_s, method_reason), and
        ``scale_<q>``: the size each invariant's drift is measured against.
    reference : dict of str -> ndarray, shape (N,)
        The exact solution (or an independent reference run) sampled on ``t``, per
        column name: ``/runs/<name>/reference/<column>``; ``attrs["reference_label"]``
        says what it is.
    """

    t: np.ndarray
    y: np.ndarray
    columns: list[str]
    invariants: dict[str, np.ndarray] = field(default_factory=dict)
    attrs: dict[str, Any] = field(default_factory=dict)
    reference: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def status(self) -> str:
        return str(self.attrs.get("status", "ok"))

    @property
    def message(self) -> str:
        return str(self.attrs.get("message", ""))

    def column(self, name: str) -> np.ndarray:
        return self.y[:, self.columns.index(name)]

    def __getitem__(self, name: str) -> np.ndarray:
        return self.column(name)


@dataclass(frozen=True)
class AuditCase:
    """One extreme case of a kind for ``reportgen audit``: a config (as a dict) and what
    makes it hard.  ``methods``: alternatives tried besides ``"auto"``."""

    name: str
    config: dict[str, Any]
    what: str
    methods: tuple[str, ...] = ()


@dataclass
class Check:
    """A headline number against its exact or independent reference."""

    quantity: str
    value: float
    reference: float
    unit: str = ""
    source: str = ""
    #: what the error is relative to; default |reference|.  Give the natural size of
    #: the quantity (an amplitude, m g l) when the reference itself can be near zero.
    scale: float | None = None

    @property
    def abs_error(self) -> float:
        return abs(self.value - self.reference)

    @property
    def rel_error(self) -> float:
        scale = abs(self.reference) if self.scale is None else abs(self.scale)
        if scale == 0 or not math.isfinite(scale):
            return self.abs_error
        return self.abs_error / scale


@dataclass
class Results:
    """Everything one scene run produced."""

    runs: dict[str, RunRecord] = field(default_factory=dict)
    analysis: dict[str, Any] = field(default_factory=dict)
    checks: list[Check] = field(default_factory=list)
    study: np.ndarray | None = None  # structured array: /study/error_vs_runtime
    study_attrs: dict[str, Any] = field(default_factory=dict)
    status: str = "ok"
    message: str = ""
    wall_time_s: float = 0.0
    #: a sweep's family (:class:`reportgen.scene.sweep.SweepData`): ``/sweep``
    sweep: Any = None
    #: whether :meth:`reportgen.scene.simulation.Simulation.judge_accuracy` has run on it
    accuracy_judged: bool = False

    def flag(self, status: str, message: str) -> None:
        """Raise the scene status to ``status`` (never lowers it) and add a message."""
        self.status = worst_status(self.status, status)
        self.message = "; ".join(m for m in (self.message, message) if m)
