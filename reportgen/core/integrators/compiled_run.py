"""One compiled run: compilation, chunking, progress, failures -> Solution.

:func:`run_compiled` is the bookkeeping of every compiled method's run
(:func:`reportgen.core.integrators.integrate` calls it after looking the method up); it
knows no registry, so a method that runs another one inside it (``levi_civita`` runs
``gauss6``) calls it directly.
"""

from __future__ import annotations

import time

import numpy as np

from . import compiled as codes
from .base import Method, Solution
from .explicit_rk import DOP853
from .kernels import kernels_for
from .status import Status

#: why a run failed, for people (MAX_STEPS: :func:`fail_reason`)
_FAIL_REASON = {
    Status.NONFINITE: "the state, the right-hand side or the step size became non-finite "
                      "(not a number, or infinite)",
    Status.STEP_UNDERFLOW: "the step size fell to round-off (below ten machine epsilons "
                           "of t, where t + h no longer differs from t)",
    Status.NEWTON: "the Newton iteration for the implicit stages did not converge "
                   "(try a smaller h)",
    Status.BAD_STEP: f"no usable fixed step (h not positive and finite, or more than "
                     f"{codes.MAX_FIXED_STEPS:.3g} steps per output interval)",
}


def fail_reason(code: Status, max_steps: int) -> str:
    """Why a run that ended with ``code`` failed, in words."""
    return _FAIL_REASON.get(code, f"more than {max_steps} attempted steps (the step budget)")


_N_CHUNKS = 20
_WARMED: set = set()

#: the rehearsal before a timed run (:func:`warm_up_run`) stops after this long [s], ...
WARM_UP_BUDGET_S = 2e-4
#: ... after this many attempted steps of an adaptive method ...
WARM_UP_STEPS = 1000
#: ... and stores at most this many values (outputs times components)
WARM_UP_VALUES = 1 << 18


def _validate(model, y0, t_eval):
    y0 = np.ascontiguousarray(y0, dtype=np.float64)
    t_eval = np.ascontiguousarray(t_eval, dtype=np.float64)
    if y0.shape != (model.dim,):
        raise ValueError(f"y0: expected shape ({model.dim},) for model '{model.name}', "
                         f"got {y0.shape}")
    if t_eval.ndim != 1 or t_eval.size < 1:
        raise ValueError(f"t_eval: expected a 1-D array of output times, got shape "
                         f"{t_eval.shape}")
    if not codes.increasing(t_eval):  # compiled: ~4x cheaper than numpy's on a short grid
        raise ValueError("t_eval: expected strictly increasing times")
    if not codes.all_finite(y0):
        raise ValueError(f"y0: expected finite values, got {y0}")
    return y0, t_eval


def _compile(method: Method, kern, model, y0, t_eval) -> float:
    """Compile (or load from the on-disk cache) the method's driver and the model's
    callbacks it calls, by running it on a tiny problem; the seconds it took."""
    key = (id(kern), type(method).__name__)
    if key in _WARMED:
        return 0.0
    tiny = np.array([t_eval[0], t_eval[0] + 1e-9 * max(1.0, abs(t_eval[0]))])
    Y = np.full((2, y0.size), np.nan)
    t0 = time.perf_counter()
    method.start(kern, model, y0, tiny, Y, 1e-3, 1e-6, tiny[1] - tiny[0], 100).advance(0, 2)
    _WARMED.add(key)
    return time.perf_counter() - t0


def warm_up_run(method: Method, kern, model, y0, t_eval, rtol, atol, h) -> float:
    """Rehearse the run about to be timed, into arrays of its own, and return the seconds
    it took: the same driver from ``y0`` over the first outputs of ``t_eval`` (a fixed-step
    method: one step of ``h`` per output), in chunks of 4, 8, 16 ... outputs, the first
    always, the next while :data:`WARM_UP_BUDGET_S` has not passed, until the outputs
    (at most :data:`WARM_UP_VALUES` values) run out or :data:`WARM_UP_STEPS` adaptive steps
    are spent.  A run shorter than the budget is rehearsed whole, a longer one for about
    the budget (its cold cost is then a few % of it at most).

    Why: :func:`run_compiled` times the run right after this.  Its types are resolved and
    its code loaded once per process (:func:`_compile`, ``compile_time_s``), yet a run
    after other work still took 20-30 µs more than the same run repeated (the heavy tops
    in ``reportgen run``, measured: no page faults, no numba dispatch -- 0.7 µs warm --,
    the Python setup 1.7 µs warm and ~20 µs cold, the driver 8-15 µs more on its first
    pass; after unrelated work, 75 µs more): the interpreter's and the driver's code and
    data were out of the CPU's caches and predictors, and a few steps on the head alone
    left ~8 µs of it.  That cost belongs to what ran before, not to the integration: after
    the rehearsal the timed run takes what a user calling the integration again gets.
    The rehearsal's own time is kept (``warm_up_time_s``), outside ``wall_time_s``, and
    it cannot change the trajectory: it writes only its own arrays (every ``start``
    copies ``y0``) and the drivers keep no state between calls (bit for bit, tested)."""
    d = y0.size
    n = min(t_eval.size, max(2, WARM_UP_VALUES // max(d, 1)))
    if n < 2:
        return 0.0
    grid = (t_eval[:n] if method.adaptive
            else t_eval[0] + float(h) * np.arange(n, dtype=np.float64))
    Y = np.full((n, d), np.nan)
    t0 = time.perf_counter()
    run = method.start(kern, model, y0, grid, Y, rtol, atol, None if method.adaptive else h,
                       WARM_UP_STEPS)
    i0, size = 0, 4
    while True:  # the first chunk always, then on while the budget lasts
        i1 = min(n, i0 + size)
        if run.advance(i0, i1) != codes.OK:
            break
        i0, size = i1, 2 * size
        if i0 >= n or time.perf_counter() - t0 >= WARM_UP_BUDGET_S:
            break
    return time.perf_counter() - t0


def default_step(method: Method, kern, model, y0, t_eval, rtol) -> float:
    """Fixed step for ``h=None``, from two short probes (a heuristic: pass ``h`` when it matters).

    1. Time scale: the span Tp covered by 200 steps of DOP853 at rtol 1e-6 (or the
       whole span if shorter).
    2. Richardson: run the method over Tp with h1 = Tp/64 and h1/2; the error of the
       h1 run is about |y_h1 - y_h1/2| / (1 - 2^-p).  Choose h so that this error over
       Tp would be ``rtol * max(1, |y0|)``: like an adaptive method's rtol it bounds the
       error per stretch of ~200 natural steps, not over arbitrarily long runs.
    """

    span = t_eval[-1] - t_eval[0]
    whole = np.array([t_eval[0], t_eval[-1]])
    scout = DOP853().start(kern, model, y0, whole, np.full((2, y0.size), np.nan), 1e-6, 1e-8,
                           None, 200)
    scout.advance(0, 2)
    reached = float(scout.state[0]) - t_eval[0]
    tp = span if not (0.0 < reached < span) else reached
    h1 = tp / 64.0
    probe = np.array([t_eval[0], t_eval[0] + tp])
    ends = []
    for h in (h1, h1 / 2):
        Y = np.full((2, y0.size), np.nan)
        # a failed probe (e.g. a non-finite Newton matrix) leaves Y[1] NaN
        method.start(kern, model, y0, probe, Y, rtol, rtol, h).advance(0, 2)
        ends.append(Y[1])
    err = float(np.max(np.abs(ends[0] - ends[1]))) / (1.0 - 2.0 ** -method.order)
    target = rtol * max(1.0, float(np.max(np.abs(y0))))
    if not np.isfinite(err):
        return h1 / 64.0
    if err == 0.0:
        return h1
    h = h1 * (target / err) ** (1.0 / method.order)
    return float(min(max(h, tp * 1e-9), tp / 4.0))


def run_compiled(method: Method, model, y0, t_eval, rtol, atol, h, progress, max_steps,
                 warm_up: bool = True):
    """Run a compiled ``method``: compile or load its driver (``compile_time_s``), set the
    run up, warm it (:func:`warm_up_run`, ``warm_up_time_s``; not with ``warm_up`` False),
    then the timed run.

    ``wall_time_s`` is the time of the driver calls that produce the returned trajectory,
    from its first step to its last output: compiling, the default step's probes, the
    allocation of the outputs and work arrays, the warm-up and the progress callbacks are
    outside it."""
    kern = kernels_for(model)
    compile_s = _compile(method, kern, model, y0, t_eval)
    N, d = t_eval.size, y0.size
    if not method.adaptive and h is None and N > 1:

        compile_s += _compile(DOP853(), kern, model, y0, t_eval)  # the probe's scout
        h = default_step(method, kern, model, y0, t_eval, rtol)  # not in wall_time_s
    step = None if method.adaptive else float(h if h is not None else 1.0)
    Y = np.full((N, d), np.nan)
    run = method.start(kern, model, y0, t_eval, Y, rtol, atol, step, max_steps)
    # fixed-step: stop at the output interval where the step budget runs out (the counts
    # are floats: a tiny h needs more steps than any int holds, never a negative count)
    i_end = N
    if not method.adaptive:
        over = np.nonzero(~(run.steps_before <= max_steps))[0]
        if over.size:
            i_end = int(over[0])
    n_chunks = _N_CHUNKS if (progress is not None and i_end > _N_CHUNKS) else 1
    bounds = ((0, i_end) if n_chunks == 1
              else np.linspace(0, i_end, n_chunks + 1).round().astype(int))
    warm_s = warm_up_run(method, kern, model, y0, t_eval, rtol, atol, step) if warm_up else 0.0
    status = codes.OK
    wall = 0.0
    for k in range(n_chunks):
        t0 = time.perf_counter()
        status = run.advance(int(bounds[k]), int(bounds[k + 1]))
        wall += time.perf_counter() - t0
        if progress is not None:
            progress(float(bounds[k + 1]) / N)
        if status != codes.OK:
            break
    if status == codes.OK and i_end < N:
        status = codes.MAXSTEPS
        run.t_fail = float(t_eval[i_end - 1])
    counters = run.counters
    code = Status.from_code(status)  # the driver tells a collapsed NaN step from underflow
    message = "ok"
    if code is not Status.OK:
        reason = fail_reason(code, max_steps)
        if code is Status.MAX_STEPS and i_end < N:
            reason += (f": h = {run.h:.3g} needs {run.steps_before[i_end]:.4g} steps to reach "
                       f"t = {t_eval[i_end]:.6g}")
        bad = ~np.all(np.isfinite(Y), axis=1)
        last = int(np.argmax(bad)) - 1 if bad.any() else N - 1
        message = (f"{method.name} failed at t = {run.t_fail:.6g}: {reason}; "
                   f"outputs valid up to t = {t_eval[max(last, 0)]:.6g}")
        if code is Status.STEP_UNDERFLOW and run.__dict__.get("y") is not None:
            message += f" (|y| = {np.max(np.abs(run.y)):.3g}; the solution may blow up)"
    return Solution(
        t=t_eval.copy(), y=Y, method=method.name, rtol=float(rtol), atol=float(atol),
        h=None if method.adaptive else run.h_used, nfev=int(counters[0]),
        nsteps=int(counters[1]), nreject=int(counters[2]), code=code, message=message,
        wall_time_s=wall, compile_time_s=compile_s, warm_up_time_s=warm_s)
