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

Surface of section.  Stepped this way, each accepted step's continuous extension is at
hand, so the crossings of a surface of section
(:class:`reportgen.core.model.SurfaceOfSection`, a product of factors g_k(y)) are
located during the run: a factor that changes sign over a step is followed to its root on
the extension (Illinois' regula falsi, to a few eps of the step), and the crossing is kept
when the product goes from negative to positive there.  So the crossings are as accurate
as the steps, whatever the output grid.  The same loop runs a model in its own time
(``t_index = None``, a Cartesian run): then the driver's independent variable is the
physical time, the outputs are the extension at their own times, and the steps are the
plain DOP853 run's (same initial step, never shortened for an output), so the outputs
agree with :func:`~.driver.integrate`'s to the bit.
"""

from __future__ import annotations

import math
import time

import numba
import numpy as np

from . import compiled as codes
from ._dop853_unrolled import dop853_adaptive
from .base import Solution
from .compiled_run import fail_reason
from .kernels import RHS_SIG, as_cfunc, kernels_for
from .status import Status

_N_CHUNKS = 20
#: bisection steps are taken when a Newton iterate leaves the bracket; this many in all
MAX_LOCATE_ITERATIONS = 60
#: rows of the DOP853 stage array K (12 stages, the FSAL row and 3 for the interpolant)
_K_ROWS = 16


@numba.njit(cache=True, inline="always")
def _now(t_index, y, state):
    """The physical time at the end of the last step: a component of the state, or the
    driver's own independent variable (``t_index`` < 0)."""
    return y[t_index] if t_index >= 0 else state[0]


@numba.njit(cache=True)
def _extension_state(F, y_old, x, out):
    """The whole state on the step's continuous extension at ``x`` in [0, 1]."""
    for i in range(out.size):
        out[i] = codes.dop853_component(F, y_old, i, x)[0]


@numba.njit(cache=True)
def _factor_root(section, k, F, y_old, s_at, params, g0, g1, y_x, g_x):
    """x in [0, 1] where factor ``k`` of the section vanishes on the step's extension.

    g0 (nonzero) and g1 are the factor at the step's ends, of opposite signs or g1 = 0.
    Illinois' regula falsi (the end kept twice has its value halved), bisecting whenever
    an iterate leaves the bracket; stops when the bracket is 4 eps wide or the factor is
    zero.  Leaves the state and every factor at the root in ``y_x`` and ``g_x``.
    """
    lo, hi, f_lo, f_hi = 0.0, 1.0, g0, g1
    x = 1.0
    side = 0
    if g1 != 0.0:
        for _ in range(MAX_LOCATE_ITERATIONS):
            x = hi - f_hi * (hi - lo) / (f_hi - f_lo) if f_hi != f_lo else 0.5 * (lo + hi)
            if not lo < x < hi:
                x = 0.5 * (lo + hi)
            _extension_state(F, y_old, x, y_x)
            section(s_at, y_x, params, g_x)
            fx = g_x[k]
            if fx == 0.0:
                return x
            if (fx < 0.0) == (f_hi < 0.0):
                hi, f_hi = x, fx
                if side == -1:
                    f_lo *= 0.5
                side = -1
            else:
                lo, f_lo = x, fx
                if side == 1:
                    f_hi *= 0.5
                side = 1
            if hi - lo <= 4.0 * codes.EPS:
                break
    _extension_state(F, y_old, x, y_x)
    section(s_at, y_x, params, g_x)
    return x


@numba.njit(cache=True)
def _section_crossings(section, n_factors, t_index, t_last, state, y_old, y, F, params,
                       g_old, g_new, g_x, y_x, found, crossings, n_crossings):
    """The upward crossings of the section within the last accepted step, appended in
    time order to ``crossings`` (rows: physical time, then the state; grown when full,
    and returned).  ``g_old`` holds the factors at the step's start and receives those at
    its end.  Crossings after ``t_last`` (the step past the last output) are left out."""
    s_old, h = state[2], state[0] - state[2]
    section(state[0], y, params, g_new)
    n_found = 0
    for k in range(n_factors):
        g0, g1 = g_old[k], g_new[k]
        if not ((g0 < 0.0 <= g1) or (g0 > 0.0 >= g1)):
            continue
        x = _factor_root(section, k, F, y_old, s_old, params, g0, g1, y_x, g_x)
        others = 1.0
        for j in range(n_factors):
            if j != k:
                others *= 1.0 if g_x[j] > 0.0 else -1.0 if g_x[j] < 0.0 else 0.0
        # the product rises through zero: factor k rises where the others are positive,
        # or falls where they are negative; at a zero of two factors (a fold point) the
        # crossing is not defined and is skipped
        if others == 0.0 or (g1 > g0) != (others > 0.0):
            continue
        t_x = y_x[t_index] if t_index >= 0 else s_old + x * h
        if t_x > t_last:
            continue
        found[n_found, 0] = x
        found[n_found, 1] = t_x
        for i in range(y_x.size):
            found[n_found, 2 + i] = y_x[i]
        n_found += 1
    for k in range(n_factors):
        g_old[k] = g_new[k]
    for a in range(n_found):  # in time order (a step holds at most n_factors)
        first = a
        for b in range(a + 1, n_found):
            if found[b, 0] < found[first, 0]:
                first = b
        for c in range(found.shape[1]):
            found[a, c], found[first, c] = found[first, c], found[a, c]
        n = n_crossings[0]
        if n == crossings.shape[0]:
            grown = np.empty((2 * n + 16, crossings.shape[1]))
            for r in range(n):
                for c in range(crossings.shape[1]):
                    grown[r, c] = crossings[r, c]
            crossings = grown
        for c in range(crossings.shape[1]):
            crossings[n, c] = found[a, 1 + c]
        n_crossings[0] = n + 1
    return crossings


@numba.njit(cache=True)
def located_outputs(rhs, t_index, times, i0, i1, Y, probe, buf, y, y_old, K, F, state,
                    counters, params, rtol, atol, max_steps, located, section, n_factors,
                    g_old, g_new, g_x, y_x, found, crossings, n_crossings):
    """Fill ``Y[i0:i1]`` with the state at the physical times ``times[i0:i1]``.

    ``y``, ``y_old``, ``K``, ``F``, ``state``, ``counters`` are the DOP853 driver's (see
    :func:`.compiled.erk_adaptive`: ``state`` = (s, h, s_old, …), ``F`` the coefficients of
    the last step's continuous extension), carried across calls.  ``probe`` (3,) = (s0, s
    asked of the driver, s0 + span used for its initial step); ``buf`` (3, d) receives the
    driver's output; ``located`` (2,) = (s, t) of the last output, the lower end of the
    next bracket.  ``t_index`` < 0: the driver's variable is the physical time.

    With ``n_factors`` > 0, the crossings of the section (``section``, its factors) are
    collected after every step (:func:`_section_crossings`); ``g_old`` (n_factors,) holds
    the factors at the current state, ``g_new``, ``g_x`` (n_factors,), ``y_x`` (d,) and
    ``found`` (n_factors, 2 + d) are work arrays, ``n_crossings`` (1,) counts the rows
    filled.  Returns (status, index of the first output not filled, ``crossings``, which
    may be a larger copy).
    """
    d = y.size
    t_last = times[times.size - 1]
    # output rows [1, 2) of buf as int64s, not literals: the driver's compiled code is then
    # the one driver.integrate uses (a literal argument is a separate specialization)
    row, end = np.int64(1), np.int64(2)
    for k in range(i0, i1):
        target = times[k]
        # 1. accepted steps until the last one ends at or past the output time; asking
        # for the output just after the step's start makes the driver take exactly one
        # step and form its continuous extension F
        while _now(t_index, y, state) < target:
            probe[1] = np.nextafter(state[0], np.inf)
            status = dop853_adaptive(rhs, probe, row, end, buf, y, y_old, K, F, state, counters,
                                     params, rtol, atol, max_steps)
            if status != codes.OK:
                return status, k, crossings
            if not codes.all_finite(y):
                return codes.NONFINITE, k, crossings
            if n_factors > 0:
                crossings = _section_crossings(section, n_factors, t_index, t_last, state,
                                               y_old, y, F, params, g_old, g_new, g_x, y_x,
                                               found, crossings, n_crossings)
        s_old, h = state[2], state[0] - state[2]
        if t_index < 0:
            # the model's own time: the output is the extension at its time
            if target == state[0]:
                for i in range(d):
                    Y[k, i] = y[i]
            else:
                x = (target - s_old) / h
                for i in range(d):
                    Y[k, i] = codes.dop853_component(F, y_old, i, x)[0]
            continue
        # 2. Newton in x = (s − s_old)/h on t(x) = target, bracketed by [x_lo, x_hi]
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
    return codes.OK, i1, crossings


@numba.njit(cache=True)
def _no_section(t, y, params, out):
    """Stands in when no section is asked for (``n_factors`` = 0); never called."""


def integrate_fictitious_time(model, y0, t_eval, t_index: int | None, rtol: float = 1e-12,
                              atol: float = 1e-14, progress=None,
                              max_steps: int = 10_000_000, section=None) -> Solution:
    """DOP853 on ``model`` in its fictitious time, outputs at the physical times ``t_eval``.

    Parameters
    ----------
    model : OdeModel
        Right-hand side in s; component ``t_index`` is the physical time, dt/ds > 0.
    y0 : ndarray, shape (d,)
        Initial state, with ``y0[t_index] == t_eval[0]``.
    t_eval : ndarray, shape (N,)
        Strictly increasing physical output times.
    t_index : int or None
        The component holding the physical time; None: the model runs in the physical
        time itself (steps and outputs as :func:`~.driver.integrate`'s DOP853, stepped
        here for the section's sake).
    rtol, atol, max_steps : as :func:`~.driver.integrate` (steps are in s).
    section : SurfaceOfSection or None
        Locate its upward crossings during the run (see the module docstring).

    Returns
    -------
    Solution
        ``t`` = ``t_eval``; ``y`` (N, d) the model's states at those times (NaN after a
        failure); counters of the s-integration; ``crossings`` (K, 1 + d) the physical
        time and the state at each crossing up to ``t_eval[-1]`` (None without a section).
    """
    y0 = np.array(y0, dtype=np.float64)
    t_eval = np.ascontiguousarray(t_eval, dtype=np.float64)
    if y0.shape != (model.dim,) or not np.all(np.isfinite(y0)):
        raise ValueError(f"y0: expected {model.dim} finite values, got {y0}")
    if t_eval.ndim != 1 or t_eval.size < 1 or not codes.increasing(t_eval):
        raise ValueError("t_eval: expected a 1-D array of strictly increasing times")
    own_time = t_index is None
    if not own_time and y0[t_index] != t_eval[0]:
        raise ValueError(f"y0[{t_index}] = {y0[t_index]!r}: expected the start time "
                         f"t_eval[0] = {t_eval[0]!r}")
    index = -1 if own_time else int(t_index)
    kern = kernels_for(model)
    params = np.ascontiguousarray(model.params, dtype=np.float64)
    N, d = t_eval.size, y0.size
    Y = np.full((N, d), np.nan)
    Y[0] = y0
    if own_time:
        s0, span = t_eval[0], t_eval[-1] - t_eval[0]
    else:
        f0 = model.f(0.0, y0)
        # s span for the driver's first step: the whole run at the starting rate
        s0 = 0.0
        span = (t_eval[-1] - t_eval[0]) / f0[t_index] if f0[t_index] > 0 else 1.0
    probe = np.array([s0, s0, s0 + (span if math.isfinite(span) and span > 0 else 1.0)])
    work = _work(y0, s0, t_eval[0])
    work.update(_section_work(section, params, s0, y0))
    compile_s = _compile(kern, model, y0, index, work["section"])
    n_chunks = _N_CHUNKS if (progress is not None and N > _N_CHUNKS) else 1
    bounds = (np.linspace(1, N, n_chunks + 1).round().astype(int).tolist() if n_chunks > 1
              else [1, N])
    t0 = time.perf_counter()
    status, reached = codes.OK, N
    for k in range(n_chunks):
        status, reached = _advance(kern, index, t_eval, bounds[k], bounds[k + 1],
                                   Y, probe, params, rtol, atol, max_steps, work)
        if progress is not None:
            progress(float(bounds[k + 1]) / N)
        if status != codes.OK:
            break
    wall = time.perf_counter() - t0
    code = Status.from_code(status)
    counters = work["counters"]
    message = "ok"
    if status != codes.OK:
        Y[reached:] = np.nan
        reason = fail_reason(code, max_steps)
        where = "t" if own_time else "s"
        now = work["state"][0] if own_time else work["y"][t_index]
        message = (f"dop853{'' if own_time else ' in fictitious time'} failed at "
                   f"{where} = {work['state'][0]:.6g} (t = {now:.6g}): {reason}; outputs valid "
                   f"up to t = {t_eval[max(reached - 1, 0)]:.6g}")
    crossings = (work["crossings"][:work["n_crossings"][0]].copy() if section is not None
                 else None)
    return Solution(t=t_eval.copy(), y=Y, method="dop853", rtol=float(rtol), atol=float(atol),
                    h=None, nfev=int(counters[0]), nsteps=int(counters[1]),
                    nreject=int(counters[2]), code=code, message=message, wall_time_s=wall,
                    compile_time_s=compile_s, crossings=crossings)


def _work(y0, s0, t0) -> dict:
    """The driver's state carried across calls (see :func:`located_outputs`)."""
    d = y0.size
    return dict(buf=np.zeros((3, d)), y=y0.copy(), y_old=y0.copy(), K=np.zeros((_K_ROWS, d)),
                F=np.zeros((7, d)), state=np.array([s0, 0.0, s0, 0.0, 0.0]),
                counters=np.zeros(3, dtype=np.int64), located=np.array([s0, t0]))


_NO_SECTION: dict[int, dict] = {}


def _section_work(section, params, s0, y0) -> dict:
    """The section's callback, its factors at ``y0`` and the work arrays of the search
    (one unused factor and no rows without a section: those are never written, so one set
    per dimension serves every run)."""
    d = y0.size
    if section is None and d in _NO_SECTION:
        return _NO_SECTION[d]
    m = section.count if section is not None else 0
    g_old = np.zeros(max(m, 1))
    if section is not None:
        section.factors(float(s0), y0, params, g_old)
    work = dict(section=as_cfunc(section.factors if section is not None else _no_section,
                                 RHS_SIG),
                n_factors=m, g_old=g_old, g_new=np.zeros(max(m, 1)), g_x=np.zeros(max(m, 1)),
                y_x=np.zeros(d), found=np.zeros((max(m, 1), 2 + d)),
                crossings=np.zeros((64 if m else 0, 1 + d)),
                n_crossings=np.zeros(1, dtype=np.int64))
    if section is None:
        _NO_SECTION[d] = work
    return work


def _advance(kern, t_index, t_eval, i0, i1, Y, probe, params, rtol, atol, max_steps, w):
    status, reached, w["crossings"] = located_outputs(
        kern.rhs, t_index, t_eval, i0, i1, Y, probe, w["buf"], w["y"], w["y_old"], w["K"],
        w["F"], w["state"], w["counters"], params, float(rtol), float(atol), int(max_steps),
        w["located"], w["section"], int(w["n_factors"]), w["g_old"], w["g_new"], w["g_x"],
        w["y_x"], w["found"], w["crossings"], w["n_crossings"])
    return int(status), int(reached)


_WARMED: set = set()


def _compile(kern, model, y0, t_index, section) -> float:
    """Compile (or load) :func:`located_outputs` with the model's callbacks; seconds taken."""
    key = (id(kern), id(section))
    if key in _WARMED:
        return 0.0
    t_start = time.perf_counter()
    d = y0.size
    t0 = y0[t_index] if t_index >= 0 else 0.0
    times = np.array([t0, np.nextafter(t0, np.inf)])
    params = np.ascontiguousarray(model.params, dtype=np.float64)
    w = _work(y0, 0.0, t0)
    w.update(_section_work(None, params, 0.0, y0), section=section)
    _advance(kern, t_index, times, 1, 2, np.zeros((2, d)), np.array([0.0, 0.0, 1e-9]),
             params, 1e-3, 1e-6, 100, w)
    _WARMED.add(key)
    return time.perf_counter() - t_start
