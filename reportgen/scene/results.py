"""What a scene run produces, in memory: the same shape the archive stores.

``Results`` is written by :mod:`reportgen.archive.store` and read back into the same
classes, so the report step sees exactly what a fresh run saw.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

STATUSES = ("ok", "unstable", "failed")


def worst_status(*statuses: str) -> str:
    """The worst of several statuses: failed > unstable > ok."""
    return max(statuses, key=STATUSES.index, default="ok")


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

    def flag(self, status: str, message: str) -> None:
        """Raise the scene status to ``status`` (never lowers it) and add a message."""
        self.status = worst_status(self.status, status)
        self.message = "; ".join(m for m in (self.message, message) if m)
