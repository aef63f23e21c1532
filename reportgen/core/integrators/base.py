"""What every integrator method is: capability flags plus one hook that runs it.

Subclass contract
-----------------
1. Set the class attributes ``name``, ``label``, ``order`` and the capability flags
   (``adaptive``, ``symplectic``, ``implicit``, ``needs_separable``, ``needs_kepler``,
   ``symmetric``, ``peer``, ``compiled``).  Flags are data: tests and the study select methods by them.
2. Compiled methods implement ``start(kern, model, y0, t_eval, Y, rtol, atol, h)``
   (``kern``: the drivers bound to the model, :func:`.kernels.kernels_for`) returning a
   :class:`Run` whose ``advance(i0, i1)`` fills ``Y[i0:i1]`` and returns a driver's
   integer status code (:attr:`.status.Status.code`; :mod:`.compiled`'s ``OK`` ...).
   Bookkeeping (chunking, progress, timing, the failure :class:`SolveCode` and message,
   the Solution) is done once, in :func:`reportgen.core.integrators.integrate`.
3. ``check(model)`` raises :class:`MethodMismatch` before any work when the method
   cannot run on the model.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .status import Status


class MethodMismatch(Exception):
    """The method needs structure the model does not offer (raised before any work)."""


#: How one integrator run ended: the structured cause behind ``Solution.message``.
#: Decisions (the solver policy, the stability verdict) read this code, never the
#: message text, which is for people.  The one vocabulary of :mod:`.status` (the name
#: is kept): OK, NONFINITE, STEP_UNDERFLOW, MAX_STEPS, NEWTON, BAD_STEP, SOLVER_ERROR.
SolveCode = Status


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
    code : SolveCode
        How the run ended; ``status`` is ``"ok"`` exactly when ``code`` is OK.
    message : str
        ``"ok"``, or a sentence saying where and why the run failed (for people).
    wall_time_s : float
        Integration time, excluding compilation (``compile_time_s``, which is 0
        when the kernel was already compiled or loaded in this process).
    crossings : ndarray, shape (K, 1 + d), or None
        Where a run asked for a surface of section crossed it (see
        :class:`reportgen.core.model.SurfaceOfSection`): the physical time, then the
        integrated state, one row per crossing in time order; None when none was asked.
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
    code: SolveCode
    message: str
    wall_time_s: float
    compile_time_s: float
    crossings: np.ndarray | None = None
    #: a compiled run's rehearsal just before it (:func:`.compiled_run.warm_up_run`), in
    #: neither ``wall_time_s`` nor ``compile_time_s``; 0 for the others
    warm_up_time_s: float = 0.0

    @property
    def ok(self) -> bool:
        return self.code is SolveCode.OK

    @property
    def status(self) -> str:
        """``"ok"`` or ``"failed"`` (the cause is :attr:`code`)."""
        return "ok" if self.ok else "failed"


def cut_at_first_bad(Y: np.ndarray, n_ok: int, t_eval: np.ndarray) -> tuple[int, bool, float]:
    """Outputs ``Y`` of a whole-run method (a peer's, the Taylor run's), of which the first
    ``n_ok`` rows were produced: every row from the first non-finite one among those (else
    from ``n_ok``) is set to NaN.  Returns (that first bad row, ``len(Y)`` when every row is
    good; whether it is a non-finite one; the time of the last good output)."""
    finite = np.all(np.isfinite(Y[:n_ok]), axis=1)
    nonfinite = not finite.all()
    bad = int(np.argmin(finite)) if nonfinite else int(n_ok)
    Y[bad:] = np.nan
    return bad, nonfinite, float(t_eval[bad - 1]) if bad > 0 else float(t_eval[0])


class Method:
    """Base class: capability flags and the structure check."""

    name: str = ""
    label: str = ""
    order: int = 0
    adaptive: bool = False
    symplectic: bool = False
    implicit: bool = False
    needs_separable: bool = False
    #: integrates only the pure inverse-square force: the model carries its Levi-Civita
    #: regularization, ``extra["levi_civita"]`` (an object with ``gm`` and the
    #: transformation's functions; the Kepler model offers one)
    needs_kepler: bool = False
    symmetric: bool = False
    #: a scipy solver run for comparison in the study (not offered by ``auto``)
    peer: bool = False
    #: a numba kernel driven by :func:`~.compiled_run.run_compiled` (else the method's ``solve``)
    compiled: bool = True

    def check(self, model) -> None:
        if self.needs_separable and model.separable is None:
            raise MethodMismatch(
                f"method '{self.name}' needs a separable Hamiltonian H = T(p) + V(q); "
                f"model '{model.name}' has none"
            )
        if self.needs_kepler and "levi_civita" not in model.extra:
            raise MethodMismatch(
                f"method '{self.name}' needs the pure inverse-square force V = −k/r (its "
                f"regularization holds for no other); model '{model.name}' is not one"
            )

    def fits(self, model) -> bool:
        """Whether :meth:`check` accepts ``model``."""
        try:
            self.check(model)
        except MethodMismatch:
            return False
        return True

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name!r} order={self.order}>"


class Run:
    """One integration in progress: ``advance(i0, i1)`` fills outputs ``i0..i1-1``."""

    counters: np.ndarray
    t_fail: float = float("nan")
    h_used: float | None = None

    def advance(self, i0: int, i1: int) -> int:
        raise NotImplementedError


#: What the policy made of one run (archived as the run attr ``solver_status``): the one
#: vocabulary, :class:`.status.Status`.  The policy gives only the members of
#: :data:`.status.POLICY_STATUSES` (OK, STIFF, MAX_STEPS, NONFINITE, FAILED, SWITCHED):
#: every other failure is archived as FAILED (:attr:`.status.Status.policy`).  Verdicts:
#: ok/switched -> "ok", stiff -> "unstable", every failure -> "failed".
RunStatus = Status

#: integrator outcome -> policy status (before the stiffness checks)
STATUS_OF_CODE = {s: s.policy for s in Status}
