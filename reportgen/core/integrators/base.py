"""What every integrator method is: capability flags plus one hook that runs it.

Subclass contract
-----------------
1. Set the class attributes ``name``, ``label``, ``order`` and the capability flags
   (``adaptive``, ``symplectic``, ``implicit``, ``needs_separable``, ``symmetric``,
   ``peer``).  Flags are data: tests and the study select methods by them.
2. Compiled methods implement ``start(kern, model, y0, t_eval, Y, rtol, atol, h)``
   returning a :class:`Run` whose ``advance(i0, i1)`` fills ``Y[i0:i1]`` and returns a
   status code from ``_kernel_template`` (``OK`` ...).  Bookkeeping (chunking,
   progress, timing, failure messages, the Solution) is done once, in
   :func:`reportgen.core.integrators.integrate`.
3. ``check(model)`` raises :class:`MethodMismatch` before any work when the method
   cannot run on the model.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


class MethodMismatch(Exception):
    """The method needs structure the model does not offer (raised before any work)."""


@dataclass(frozen=True)
class Solution:
    """Result of :func:`integrate`.

    Attributes
    ----------
    t : ndarray, shape (N,)
        The requested output times, exactly.
    y : ndarray, shape (N, d)
        State at ``t``; NaN after the last good output of a failed run.
    h : float or None
        Largest step actually used by a fixed-step method (<= the requested h).
    nsteps, nreject : int
        Accepted / rejected steps (-1 when the peer solver does not report them).
    wall_time_s : float
        Integration time, excluding compilation (``compile_time_s``, which is 0
        when the kernel was already compiled or loaded in this process).
    """

    t: np.ndarray
    y: np.ndarray
    method: str
    rtol: float
    atol: float
    h: float | None
    nfev: int
    nsteps: int
    nreject: int
    status: str
    message: str
    wall_time_s: float
    compile_time_s: float

    @property
    def ok(self) -> bool:
        return self.status == "ok"


class Method:
    """Base class: capability flags and the structure check."""

    name: str = ""
    label: str = ""
    order: int = 0
    adaptive: bool = False
    symplectic: bool = False
    implicit: bool = False
    needs_separable: bool = False
    symmetric: bool = False
    peer: bool = False

    def check(self, model) -> None:
        if self.needs_separable and model.separable is None:
            raise MethodMismatch(
                f"method '{self.name}' needs a separable Hamiltonian H = T(p) + V(q); "
                f"model '{model.name}' has none"
            )

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name!r} order={self.order}>"


class Run:
    """One integration in progress: ``advance(i0, i1)`` fills outputs ``i0..i1-1``."""

    counters: np.ndarray
    t_fail: float = float("nan")
    h_used: float | None = None

    def advance(self, i0: int, i1: int) -> int:
        raise NotImplementedError
