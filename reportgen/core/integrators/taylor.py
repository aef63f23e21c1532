"""Our adaptive Taylor-series method (:mod:`reportgen.core.taylor`) as an integrator.

The model's right-hand side, as SymPy expressions, is decomposed into elementary
operations whose coefficient recurrences are generated as one numba module per model;
the whole run (steps, step sizes, dense output) is one compiled call.  One tolerance,
relative and absolute at once as heyoka's (``tol`` = our rtol; ``atol`` is not used);
the order p = ⌈−ln(tol)/2 + 1⌉ and the step follow Jorba & Zou 2005 §3.

Timing follows the study's conventions: generating and compiling the module (or loading
numba's disk cache) is ``compile_time_s``, paid by a model's first run in a process;
``wall_time_s`` is the compiled run alone.  A Taylor step evaluates the recurrences once,
not the right-hand side: ``nsteps`` counts the steps, ``nfev`` is -1.
"""

from __future__ import annotations

import numpy as np

from .base import Method, MethodMismatch, Solution, SolveCode, cut_at_first_bad


class Taylor(Method):
    """Adaptive Taylor series of order ⌈−ln(tol)/2 + 1⌉ (Jorba & Zou 2005)."""

    #: the order follows the tolerance (8 at 1e-6, 12 at 1e-9, 16 at 1e-13, 20 at 1e-16,
    #: :func:`reportgen.core.taylor.order_for_tol`): the highest the study asks for is given
    name, label, order = "taylor", "Taylor series, adaptive order (numba)", 20
    adaptive = True
    compiled = False

    def check(self, model) -> None:
        from ..taylor import why_not

        reason = why_not(model)
        if reason:
            raise MethodMismatch(f"method 'taylor': model '{model.name}' has no Taylor "
                                 f"recurrences ({reason})")

    def solve(self, model, y0, t_eval, rtol, atol, progress=None,
              time_limit: float | None = None, max_steps: int = 10_000_000) -> Solution:
        """One compiled run at ``tol = rtol``.  ``time_limit`` is not enforced (the run is
        one compiled call; ``max_steps`` bounds it)."""
        from ..taylor import build, taylor_run

        try:
            system, compile_s = build(model)
        except ValueError as exc:  # Unsupported: check() was skipped by the caller
            raise MethodMismatch(f"method 'taylor': {exc}") from exc
        y0 = np.asarray(y0, dtype=np.float64)
        t_eval = np.asarray(t_eval, dtype=np.float64)
        Y, code, nsteps, t_last, wall, module_s = taylor_run(system, y0, t_eval, rtol,
                                                             max_steps=max_steps)
        compile_s += module_s
        status = SolveCode.from_code(code)
        message = "ok"
        if status is SolveCode.OK:  # a finite step whose dense output overflowed?
            _bad, nonfinite, t_cut = cut_at_first_bad(Y, len(Y), t_eval)
            if nonfinite:
                status, t_last = SolveCode.NONFINITE, t_cut
        if status is not SolveCode.OK:
            why = {SolveCode.NONFINITE: "non-finite state or step",
                   SolveCode.STEP_UNDERFLOW: "step size underflow",
                   SolveCode.MAX_STEPS: f"step budget of {max_steps} used up"}.get(status, status)
            message = f"{self.label} failed after t = {t_last:.6g}: {why}"
        if progress is not None:
            progress(1.0)
        return Solution(t=t_eval.copy(), y=Y, method=self.name, rtol=float(rtol),
                        atol=float(rtol), h=None, nfev=-1, nsteps=nsteps, nreject=0,
                        code=status, message=message, wall_time_s=wall,
                        compile_time_s=compile_s)
