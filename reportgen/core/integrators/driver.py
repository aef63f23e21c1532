"""``integrate``: look the method up, validate, and run it (compiled runs:
:mod:`.compiled_run`)."""

from __future__ import annotations

import numba
import numpy as np

from ..model import OdeModel, Separable
from .base import MethodMismatch, Solution, SolveCode
from .compiled_run import _validate, run_compiled
from .registry import METHODS


def integrate(model, y0, t_eval, method: str = "dop853", rtol: float = 1e-10,
              atol: float = 1e-12, h: float | None = None, progress=None,
              max_steps: int = 10_000_000, warm_up: bool = True) -> Solution:
    """Integrate ``model`` from ``y0`` at ``t_eval[0]``, returning the state at ``t_eval``.

    Parameters
    ----------
    model : OdeModel
    y0 : ndarray, shape (d,)
    t_eval : ndarray, shape (N,)
        Strictly increasing output times; ``t_eval[0]`` is the start time.
    method : str
        A key of ``METHODS``.
    rtol, atol : float
        Tolerances of the adaptive methods (and the target of the default ``h``).
    h : float or None
        Step of fixed-step methods: each output interval is cut into equal steps
        <= h.  None: see :func:`default_step`.  Ignored by adaptive methods.
    progress : callable(fraction) or None
        Called between ~20 chunks of the output grid; chunking leaves the result
        unchanged (adaptive runs carry their step across chunks).
    max_steps : int
        Budget of attempted steps, accepted and rejected (a fixed-step run: its steps,
        counted before any is taken); ``code`` MAX_STEPS beyond it.
    warm_up : bool
        Rehearse a compiled run just before timing it
        (:func:`.compiled_run.warm_up_run`); False where nobody reads the time of this one
        run (a reference run, a probe) or the caller times repeats itself (the study).

    Notes
    -----
    Adaptive methods never shorten a step to hit an output time; the last step may
    end past ``t_eval[-1]`` (the right-hand side is evaluated up to one step beyond
    it) and the last outputs come from the dense output, as all others.

    Raises
    ------
    MethodMismatch
        Before any work, if the method needs structure the model lacks.
    ValueError
        Malformed ``y0`` / ``t_eval`` / unknown method / ``h`` not positive and finite.
        Numerical failures never raise: they give ``status="failed"``, a
        :class:`SolveCode` (:class:`.status.Status`) in ``code`` and a message; every run
        ends (a NaN step size is NONFINITE, a step that makes no progress STEP_UNDERFLOW,
        a fixed step too small for the budget MAX_STEPS).
    """

    if method not in METHODS:
        raise ValueError(f"method: expected one of {sorted(METHODS)}, got {method!r}")
    m = METHODS[method]
    m.check(model)
    y0, t_eval = _validate(model, y0, t_eval)
    if h is not None and not (h > 0 and np.isfinite(h)):
        raise ValueError(f"h: expected a positive step, got {h}")
    if not m.compiled:
        return m.solve(model, y0, t_eval, rtol, atol, progress)
    if t_eval.size == 1:
        return Solution(t=t_eval.copy(), y=y0[None, :].copy(), method=method, rtol=rtol,
                        atol=atol, h=h, nfev=0, nsteps=0, nreject=0, code=SolveCode.OK,
                        message="ok", wall_time_s=0.0, compile_time_s=0.0)
    return run_compiled(m, model, y0, t_eval, rtol, atol, h, progress, max_steps, warm_up)


__all__ = ["integrate", "warm_up", "MethodMismatch", "SolveCode", "Solution"]


@numba.njit(cache=True)
def _unit_rhs(t, y, params, out):
    """y'' = -y: the model :func:`warm_up` runs every driver on."""
    out[0] = y[1]
    out[1] = -y[0]


@numba.njit(cache=True)
def _unit_drift(p, params, out):
    out[0] = p[0]


@numba.njit(cache=True)
def _unit_kick(q, params, out):
    out[0] = -q[0]


#: one method per compiled driver (the rest share these drivers)
WARM_UP_METHODS = {"dop853": {"rtol": 1e-6, "atol": 1e-8}, "rk45": {"rtol": 1e-6, "atol": 1e-8},
                   "rk4": {"h": 0.05},
                   "verlet": {"h": 0.05}, "gauss4": {"h": 0.05}}


def warm_up(methods=tuple(WARM_UP_METHODS)) -> None:
    """Load the drivers of ``methods`` (default: every driver), compiling them first if
    numba's cache is empty, by running each once on a 2-D oscillator.  A batch calls this
    before forking its scene processes, so they inherit loaded drivers instead of each
    loading -- or, on a cold cache, each compiling -- the same code."""
    model = OdeModel(name="warm-up", columns=("q", "p"), rhs=_unit_rhs,
                     params=np.zeros(1), separable=Separable(n=1, drift=_unit_drift,
                                                             kick=_unit_kick))
    y0, t = np.array([1.0, 0.0]), np.array([0.0, 0.1])
    for method in methods:
        integrate(model, y0, t, method=method, **WARM_UP_METHODS[method])
