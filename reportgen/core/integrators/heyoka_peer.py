"""heyoka (Taylor series, LLVM JIT) as a peer of the study and ``reportgen bench``.

heyoka is an optional extra (``pip install 'reportgen[heyoka]'``).  It integrates the
same equations as our model: :func:`reportgen.core.heyoka_systems.system` translates
the model's right-hand side (a hand-written one for each of our models, SymPy's for the
formula kind).  heyoka takes one tolerance, used as both relative and absolute
(``tol`` = our rtol; our atol is 1e-2 rtol).

Timing follows the study's conventions: building the integrator (heyoka's JIT
compilation) is ``compile_time_s``, paid by the first run at a tolerance only; a run's
``wall_time_s`` is ``propagate_grid`` with the state and time reset, nothing else.
heyoka reports steps, not right-hand-side evaluations (a Taylor step evaluates the
series' recurrences once): ``nsteps`` is its step count and ``nfev`` is -1.
"""

from __future__ import annotations

import functools
import time

import numpy as np

from .base import Method, MethodMismatch, Solution, SolveCode, cut_at_first_bad


@functools.cache
def heyoka_module():
    """heyoka, or None when it is not installed."""
    try:
        import heyoka
    except ImportError:
        return None
    return heyoka


def heyoka_version() -> str:
    hy = heyoka_module()
    return getattr(hy, "__version__", "") if hy is not None else ""


#: built integrators (JIT-compiled once per model and tolerance in a process); the model
#: itself is kept beside each, so that an id is never reused while its entry lives
_BUILT: dict[tuple, tuple] = {}
_MAX_BUILT = 64


def _integrator(model, y0, tol: float):
    """(heyoka integrator for ``model`` at ``tol``, JIT seconds now spent: 0 when built
    before in this process)."""
    key = (id(model), float(tol))
    hit = _BUILT.get(key)
    if hit is not None and hit[0] is model:
        return hit[1], 0.0
    from ..heyoka_systems import system

    hy = heyoka_module()
    pairs = system(hy, model)
    start = time.perf_counter()
    # not compact mode: it compiles big systems faster (three bodies at tol 1e-15: 0.67 s
    # -> 0.28 s) but runs them slower (the figure-eight: 1.5x), and heyoka is compared on
    # its run time, the JIT reported beside it
    ta = hy.taylor_adaptive(pairs, list(map(float, y0)), tol=float(tol))
    jit = time.perf_counter() - start
    if len(_BUILT) >= _MAX_BUILT:
        _BUILT.clear()
    _BUILT[key] = (model, ta)
    return ta, jit


class Heyoka(Method):
    """heyoka's adaptive Taylor integrator on the model's own equations."""

    #: heyoka picks its order from the tolerance (8 at 1e-6, 13 at 1e-10, 19 at 1e-15,
    #: measured): the highest it takes is given
    name, label, order = "heyoka", "heyoka Taylor (LLVM)", 20
    adaptive = True
    peer = True
    compiled = False

    def check(self, model) -> None:
        if heyoka_module() is None:
            raise MethodMismatch("method 'heyoka' needs heyoka: pip install 'reportgen[heyoka]'")
        from ..heyoka_systems import why_not

        reason = why_not(model)
        if reason:
            raise MethodMismatch(f"method 'heyoka': model '{model.name}' has no heyoka "
                                 f"translation ({reason})")

    def solve(self, model, y0, t_eval, rtol, atol, progress=None,
              time_limit: float | None = None) -> Solution:
        """One ``propagate_grid`` run at ``tol = rtol`` (``atol`` is not used: heyoka's one
        tolerance is relative and absolute at once).  ``time_limit`` is not enforced:
        heyoka's runs are compiled, milliseconds on our scenes (a Python callback after
        every step to stop one would cost more than the step)."""
        self.check(model)
        y0 = np.asarray(y0, dtype=np.float64)
        t_eval = np.asarray(t_eval, dtype=np.float64)
        ta, jit = _integrator(model, y0, rtol)
        N, d = t_eval.size, y0.size
        Y = np.full((N, d), np.nan)
        start = time.perf_counter()
        ta.time = float(t_eval[0])
        ta.state[:] = y0
        outcome, _min_h, _max_h, nsteps, _cb, grid = ta.propagate_grid(t_eval)
        wall = time.perf_counter() - start
        grid = np.asarray(grid, dtype=np.float64).reshape(-1, d)
        n_ok = min(len(grid), N)
        Y[:n_ok] = grid[:n_ok]
        bad, nonfinite, t_last = cut_at_first_bad(Y, n_ok, t_eval)
        hy = heyoka_module()
        code, message = SolveCode.OK, "ok"
        if outcome != hy.taylor_outcome.time_limit or bad < N:
            nonfinite = nonfinite or outcome == hy.taylor_outcome.err_nf_state
            code = SolveCode.NONFINITE if nonfinite else SolveCode.SOLVER_ERROR
            message = (f"{self.label} failed after t = {t_last:.6g}: "
                       f"{str(outcome).rsplit('.', 1)[-1].replace('_', ' ')}")
        if progress is not None:
            progress(1.0)
        return Solution(t=t_eval.copy(), y=Y, method=self.name, rtol=float(rtol),
                        atol=float(rtol), h=None, nfev=-1, nsteps=int(nsteps), nreject=-1,
                        code=code, message=message, wall_time_s=wall,
                        compile_time_s=jit)
