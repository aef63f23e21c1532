"""scipy.integrate.solve_ivp as peers (for the study) and as the stiff fallback.

These call the model's Python ``f`` / ``jacobian`` wrappers, so each right-hand-side
call pays Python overhead (~µs); output comes from scipy's dense output via ``t_eval``.
"""

from __future__ import annotations

import time
import warnings

import numpy as np

from .base import Method, Solution, SolveCode, cut_at_first_bad

EPS = np.finfo(float).eps
SCIPY_MIN_RTOL = 100 * EPS  # solve_ivp clamps rtol below this (with a warning)


def _solve_ivp():
    """scipy's solve_ivp, imported when a peer first runs (listing methods stays light)."""
    from scipy.integrate import solve_ivp

    return solve_ivp


class PeerTimeLimit(Exception):
    """A peer run stopped at its ``time_limit`` (the study's budget), without a result."""


class ScipyMethod(Method):
    adaptive = True
    peer = True
    compiled = False
    scipy_name: str

    def solve(self, model, y0, t_eval, rtol, atol, progress=None,
              time_limit: float | None = None) -> Solution:
        """One solve_ivp run.  ``time_limit`` (seconds): raise :class:`PeerTimeLimit`
        once the run has taken longer (checked every 32 right-hand-side calls)."""
        rtol_eff = max(float(rtol), SCIPY_MIN_RTOL)
        kwargs = {}
        if self.implicit or self.scipy_name == "LSODA":
            jac = model.jacobian if model.jac is not None else None
            if jac is not None:
                kwargs["jac"] = jac
        N, d = t_eval.size, y0.size
        Y = np.full((N, d), np.nan)
        fun = model.f if time_limit is None else _with_deadline(model.f, time_limit)
        t0 = time.perf_counter()
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                res = _solve_ivp()(fun, (t_eval[0], t_eval[-1]), y0, method=self.scipy_name,
                                   t_eval=t_eval, rtol=rtol_eff, atol=atol, **kwargs)
        except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
            # scipy raises where our drivers stop (a NaN Jacobian in Radau's LU, say): the
            # run failed, non-finite; it is one row of the study, not the scene's crash
            return Solution(t=t_eval.copy(), y=Y, method=self.name, rtol=rtol_eff,
                            atol=float(atol), h=None, nfev=0, nsteps=-1, nreject=-1,
                            code=SolveCode.NONFINITE,
                            message=f"{self.label} failed at t = {t_eval[0]:.6g}: {exc}",
                            wall_time_s=time.perf_counter() - t0, compile_time_s=0.0)
        wall = time.perf_counter() - t0
        n_ok = res.t.size
        if n_ok:
            Y[:n_ok] = res.y.T
        bad, nonfinite, t_last = cut_at_first_bad(Y, n_ok, t_eval)
        code, message = SolveCode.OK, "ok"
        if not res.success or bad < N:
            # solve_ivp reports failure as prose only; what we can tell structurally is
            # a non-finite state (ours to check) versus any other solver failure
            code = SolveCode.NONFINITE if nonfinite else SolveCode.SOLVER_ERROR
            message = (f"{self.label} failed after t = {t_last:.6g}: "
                       f"{res.message if not res.success else 'non-finite state'}")
        if progress is not None:
            progress(1.0)
        return Solution(t=t_eval.copy(), y=Y, method=self.name, rtol=rtol_eff, atol=float(atol),
                        h=None, nfev=int(res.nfev), nsteps=-1, nreject=-1, code=code,
                        message=message, wall_time_s=wall, compile_time_s=0.0)


def _with_deadline(f, seconds: float):
    deadline = time.perf_counter() + seconds
    calls = 0

    def fun(t, y):
        nonlocal calls
        calls += 1
        if calls % 32 == 0 and time.perf_counter() > deadline:
            raise PeerTimeLimit(f"stopped after {seconds:.3g} s")
        return f(t, y)

    return fun


class ScipyRK45(ScipyMethod):
    name, label, order, scipy_name = "scipy_rk45", "scipy RK45", 5, "RK45"


class ScipyDOP853(ScipyMethod):
    name, label, order, scipy_name = "scipy_dop853", "scipy DOP853", 8, "DOP853"


class ScipyLSODA(ScipyMethod):
    name, label, order, scipy_name = "scipy_lsoda", "scipy LSODA", 12, "LSODA"


class ScipyRadau(ScipyMethod):
    name, label, order, scipy_name = "scipy_radau", "scipy Radau", 5, "Radau"
    implicit = True


class RadauFallback(ScipyRadau):
    """The stiff path of the pipeline (same solver as the ``scipy_radau`` peer)."""

    name, label = "radau", "scipy Radau (stiff fallback)"
    peer = False
