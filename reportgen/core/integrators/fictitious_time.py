r"""DOP853 in a fictitious time s, with outputs at given physical times t.

A regularized model is integrated in s (``y' = f(s, y)``) and carries the physical time
as one of its components, ``t' = g(y) > 0`` away from the singular instants (a
Sundman-type transformation dt = g ds).  Outputs are wanted at physical times
``t_1 < t_2 < ...``, whose s is not known in advance.

:func:`located_outputs` steps the compiled DOP853 driver (:mod:`._dop853_unrolled`) one
accepted step at a time (the step sequence is the driver's own: it never shortens a step
for an output).  When a step [s_old, s_new] carries t past t_k, s_k with t(s_k) = t_k is
found inside it by Newton's method on the t component of the step's 7th-order
continuous extension (a polynomial in s), safeguarded by bisection on the bracket (t is
increasing in s); the output is the extension's state at s_k.  So the outputs are as
accurate as the steps (no interpolation in t), and |t(s_k) − t_k| is at the level of
rounding.  (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.6, dense output
and event location; the same root finding as for an event function t(s) − t_k.)

Cost: the continuous extension is formed on every step (3 extra evaluations of f on
top of 12); an output costs a few evaluations of the extension's t component (Newton on
its polynomial, no evaluation of f) and one of the whole state.
"""

from __future__ import annotations

import math
import time

import numba
import numpy as np

from . import compiled as codes
from ._dop853_unrolled import dop853_adaptive
from .base import Solution
from .compiled_run import _CODE, _FAIL_REASON
from .kernels import kernels_for

_N_CHUNKS = 20
#: bisection steps are taken when a Newton iterate leaves the bracket; this many in all
MAX_LOCATE_ITERATIONS = 60
#: rows of the DOP853 stage array K (12 stages, the FSAL row and 3 for the interpolant)
_K_ROWS = 16


@numba.njit(cache=True)
def located_outputs(rhs, t_index, times, i0, i1, Y, probe, buf, y, y_old, K, F, state,
                    counters, params, rtol, atol, max_steps, located):
    """Fill ``Y[i0:i1]`` with the state at the physical times ``times[i0:i1]``.

    ``y``, ``y_old``, ``K``, ``F``, ``state``, ``counters`` are the DOP853 driver's (see
    :func:`.compiled.erk_adaptive`: ``state`` = (s, h, s_old, …), ``F`` the coefficients of
    the last step's continuous extension), carried across calls.  ``probe`` (3,) = (s0, s
    asked of the driver, s0 + span used for its initial step); ``buf`` (3, d) receives the
    driver's output; ``located`` (2,) = (s, t) of the last output, the lower end of the
    next bracket.  Returns (status, index of the first output not filled).
    """
    d = y.size
    for k in range(i0, i1):
        target = times[k]
        # 1. accepted steps until the last one ends at or past the output time; asking
        # for the output just after the step's start makes the driver take exactly one
        # step and form its continuous extension F
        while y[t_index] < target:
            probe[1] = np.nextafter(state[0], np.inf)
            status = dop853_adaptive(rhs, probe, 1, 2, buf, y, y_old, K, F, state, counters,
                                     params, rtol, atol, max_steps)
            if status != codes.OK:
                return status, k
            if not codes.all_finite(y):
                return codes.NONFINITE, k
        # 2. Newton in x = (s − s_old)/h on t(x) = target, bracketed by [x_lo, x_hi]
        s_old, h = state[2], state[0] - state[2]
        x_lo, t_lo = 0.0, y_old[t_index]
        if located[0] > s_old:
            x_lo, t_lo = (located[0] - s_old) / h, located[1]
        x_hi, t_hi = 1.0, y[t_index]
        x = x_lo + (x_hi - x_lo) * ((target - t_lo) / (t_hi - t_lo)) if t_hi > t_lo else x_hi
        tol = 4.0 * codes.EPS * max(abs(target), 1.0)
        for _ in range(MAX_LOCATE_ITERATIONS):
            t_x, dt_dx = codes.dop853_component(F, y_old, t_index, x)
            miss = t_x - target
            if abs(miss) <= tol or x_hi - x_lo <= 4.0 * codes.EPS:
                break
            if miss > 0.0:
                x_hi = x
            else:
                x_lo = x
            x_next = x - miss / dt_dx if dt_dx > 0.0 else math.nan
            x = x_next if x_lo < x_next < x_hi else 0.5 * (x_lo + x_hi)
        for i in range(d):
            Y[k, i] = codes.dop853_component(F, y_old, i, x)[0]
        located[0] = s_old + x * h
        located[1] = Y[k, t_index]
    return codes.OK, i1


def integrate_fictitious_time(model, y0, t_eval, t_index: int, rtol: float = 1e-12,
                              atol: float = 1e-14, progress=None,
                              max_steps: int = 10_000_000) -> Solution:
    """DOP853 on ``model`` in its fictitious time, outputs at the physical times ``t_eval``.

    Parameters
    ----------
    model : OdeModel
        Right-hand side in s; component ``t_index`` is the physical time, dt/ds > 0.
    y0 : ndarray, shape (d,)
        Initial state, with ``y0[t_index] == t_eval[0]``.
    t_eval : ndarray, shape (N,)
        Strictly increasing physical output times.
    rtol, atol, max_steps : as :func:`~.driver.integrate` (steps are in s).

    Returns
    -------
    Solution
        ``t`` = ``t_eval``; ``y`` (N, d) the model's states at those times (NaN after a
        failure); counters of the s-integration.
    """
    y0 = np.array(y0, dtype=np.float64)
    t_eval = np.ascontiguousarray(t_eval, dtype=np.float64)
    if y0.shape != (model.dim,) or not np.all(np.isfinite(y0)):
        raise ValueError(f"y0: expected {model.dim} finite values, got {y0}")
    if t_eval.ndim != 1 or t_eval.size < 1 or np.any(np.diff(t_eval) <= 0):
        raise ValueError("t_eval: expected a 1-D array of strictly increasing times")
    if y0[t_index] != t_eval[0]:
        raise ValueError(f"y0[{t_index}] = {y0[t_index]!r}: expected the start time "
                         f"t_eval[0] = {t_eval[0]!r}")
    kern = kernels_for(model)
    params = np.ascontiguousarray(model.params, dtype=np.float64)
    N, d = t_eval.size, y0.size
    Y = np.full((N, d), np.nan)
    Y[0] = y0
    f0 = model.f(0.0, y0)
    # s span for the driver's first step: the whole run at the starting rate
    span = (t_eval[-1] - t_eval[0]) / f0[t_index] if f0[t_index] > 0 else 1.0
    probe = np.array([0.0, 0.0, span if math.isfinite(span) and span > 0 else 1.0])
    work = dict(buf=np.zeros((3, d)), y=y0.copy(), y_old=y0.copy(), K=np.zeros((_K_ROWS, d)),
                F=np.zeros((7, d)), state=np.zeros(5), counters=np.zeros(3, dtype=np.int64),
                located=np.array([0.0, t_eval[0]]))
    compile_s = _compile(kern, model, y0, t_index)
    n_chunks = _N_CHUNKS if (progress is not None and N > _N_CHUNKS) else 1
    bounds = np.linspace(1, N, n_chunks + 1).round().astype(int)
    t0 = time.perf_counter()
    status, reached = codes.OK, N
    for k in range(n_chunks):
        status, reached = _advance(kern, t_index, t_eval, int(bounds[k]), int(bounds[k + 1]),
                                   Y, probe, params, rtol, atol, max_steps, work)
        if progress is not None:
            progress(float(bounds[k + 1]) / N)
        if status != codes.OK:
            break
    wall = time.perf_counter() - t0
    code = _CODE[int(status)]
    counters = work["counters"]
    message = "ok"
    if status != codes.OK:
        Y[reached:] = np.nan
        reason = _FAIL_REASON.get(code, f"max_steps = {max_steps} exceeded")
        message = (f"dop853 in fictitious time failed at s = {work['state'][0]:.6g} "
                   f"(t = {work['y'][t_index]:.6g}): {reason}; outputs valid up to "
                   f"t = {t_eval[max(reached - 1, 0)]:.6g}")
    return Solution(t=t_eval.copy(), y=Y, method="dop853", rtol=float(rtol), atol=float(atol),
                    h=None, nfev=int(counters[0]), nsteps=int(counters[1]),
                    nreject=int(counters[2]), code=code, message=message, wall_time_s=wall,
                    compile_time_s=compile_s)


def _advance(kern, t_index, t_eval, i0, i1, Y, probe, params, rtol, atol, max_steps, w):
    status, reached = located_outputs(
        kern.rhs, t_index, t_eval, i0, i1, Y, probe, w["buf"], w["y"], w["y_old"], w["K"],
        w["F"], w["state"], w["counters"], params, float(rtol), float(atol), int(max_steps),
        w["located"])
    return int(status), int(reached)


_WARMED: set = set()


def _compile(kern, model, y0, t_index) -> float:
    """Compile (or load) :func:`located_outputs` with the model's callback; seconds taken."""
    if id(kern) in _WARMED:
        return 0.0
    t_start = time.perf_counter()
    d = y0.size
    times = np.array([y0[t_index], np.nextafter(y0[t_index], np.inf)])
    w = dict(buf=np.zeros((3, d)), y=y0.copy(), y_old=y0.copy(), K=np.zeros((_K_ROWS, d)),
             F=np.zeros((7, d)), state=np.zeros(5), counters=np.zeros(3, dtype=np.int64),
             located=np.array([0.0, times[0]]))
    _advance(kern, t_index, times, 1, 2, np.zeros((2, d)), np.array([0.0, 0.0, 1e-9]),
             np.ascontiguousarray(model.params, dtype=np.float64), 1e-3, 1e-6, 100, w)
    _WARMED.add(id(kern))
    return time.perf_counter() - t_start
