"""Compiled integrator drivers, compiled once for every model and cached on disk.

The model's functions are *arguments*: ``rhs``, ``jac``, ``drift`` and ``kick`` arrive
as numba C callbacks (:func:`numba.cfunc`, built per model by :mod:`.kernels`).  numba
types a cfunc argument by its signature alone (``FunctionType[void(float64, ...)]``), so
each driver here is compiled once per process for all models, and numba's on-disk
cache (keyed by argument types) hits in the next process.  The signatures are fixed:

    rhs(t, y, params, out)     jac(t, y, params, out)     drift(p, params, out)
    kick(q, params, out)

with ``t`` float64 and every array float64 and C-contiguous (1-D; ``jac``'s ``out`` 2-D).

The call itself costs ~1 ns, but numba's reference counting of arrays can add
~10-50 ns around it: its optimizer removes the increment/decrement pairs only when no
opaque call sits between them.  Hence three rules, measured on the pendulum (RK4 step:
75 ns with the model inlined as before, 265 ns without the rules, 77 ns with them):

* callbacks are called from the drivers' own bodies, not from a helper that takes
  arrays (its arguments are counted on entry and exit around the call); ``fd_jac``
  and ``initial_step`` are the exceptions, called once per step or per run;
* callbacks get whole arrays (arguments, or work arrays such as ``ftmp`` made here),
  never views such as ``K[s]``; results are copied into place (``store_row``);
* the small helpers of the step loops are ``inline="always"`` (numba-level inlining).

Compile time: the drivers compile once per numba cache folder (~6 s for all four on
an empty cache), and with them the numba library code they use.  Whole-array
expressions (``a[:] = b``, ``y0 + h * f``) and ``np.linalg.inv`` / ``@`` would add ~1.5 s
of broadcasting, shape-error, LAPACK and error-message machinery; hence plain loops
and the small LU solver (:func:`lu_factor`) below.

Shared conventions
------------------
* ``t_eval`` (N,), ``Y`` (N, d) output; a driver fills ``Y[i0:i1]``.
* ``y`` (d,) is the current state, updated in place, so consecutive calls over
  consecutive index ranges ("chunks") continue one integration.
* ``counters`` int64[3] = (nfev, accepted steps, rejected steps), accumulated.
* The return value is a status code (``OK`` ...) ; the failure time is left in
  ``state[0]`` (adaptive) or returned through ``tfail`` (fixed-step).

Every run ends
--------------
A loop that cannot make progress stops with a status instead of spinning:

* adaptive loops count *attempted* steps (accepted + rejected) against ``max_steps``;
  the step-size test is ``not (min_step <= h < inf)``, min_step = 10 eps max(|t|, 1e-300):
  a NaN or infinite step fails it (``h < min_step`` was False for NaN and the loop spun),
  and so does any step that would make no progress (h >= min_step implies t + h > t for a
  finite t); it ends the run as NONFINITE when t + h or the last attempt was not finite
  (:func:`stop_status`), else as UNDERFLOW.  (Measured: the explicit ``t < t + h`` on
  top cost the 2-state pendulum's specialized DOP853 step ~2.5 %, the test as written
  nothing measurable);
* an attempt whose state or right-hand side at its end is not finite is rejected with
  ``err = inf`` (:func:`error_norm`); a norm that merely overflows with finite values
  reads ``ERR_OVERFLOW`` (:func:`overflow_or_inf`: rejected alike, but the underflow
  that may follow is not "non-finite");
* a fixed step's count per output interval (:func:`steps_in`) is refused (BAD_STEP)
  when h is not positive and finite or the count exceeds ``MAX_FIXED_STEPS``.
"""

import math

import numba
import numpy as np

from .status import Status

# the drivers' status codes: plain ints (numba freezes them into the machine code),
# defined once by :class:`.status.Status`
OK = Status.OK.code
NONFINITE = Status.NONFINITE.code
UNDERFLOW = Status.STEP_UNDERFLOW.code
MAXSTEPS = Status.MAX_STEPS.code
NEWTON = Status.NEWTON.code
BAD_STEP = Status.BAD_STEP.code

EPS = 2.220446049250313e-16
SAFETY = 0.9  # step-size controller constants as in scipy.integrate._ivp.rk
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
#: the error norm of an attempt with finite values whose norm overflowed: rejected with
#: the same factor as inf (MIN_FACTOR), told apart from a non-finite attempt
ERR_OVERFLOW = 1e300
#: most steps a fixed-step kernel takes over one output interval (counts stay exact doubles
#: and far from int64 overflow)
MAX_FIXED_STEPS = 2.0 ** 53


@numba.njit(cache=True)
def copy_into(dst, src):
    """``dst[:] = src`` for 1-D arrays of equal length, as a loop (see the module doc)."""
    for i in range(src.size):
        dst[i] = src[i]


@numba.njit(cache=True)
def fd_jac(rhs, t, y, params, out):
    """Forward-difference Jacobian, used when the model has no ``jac``."""
    d = y.size
    f0 = np.empty(d)
    f1 = np.empty(d)
    yp = np.empty(d)
    copy_into(yp, y)
    rhs(t, y, params, f0)
    for j in range(d):
        dy = math.sqrt(EPS) * max(1.0, abs(y[j]))
        yp[j] = y[j] + dy
        rhs(t, yp, params, f1)
        for i in range(d):
            out[i, j] = (f1[i] - f0[i]) / dy
        yp[j] = y[j]


@numba.njit(cache=True)
def all_finite(y):
    for i in range(y.size):
        if not math.isfinite(y[i]):
            return False
    return True


@numba.njit(cache=True)
def increasing(t):
    """Whether ``t`` is strictly increasing (False on a NaN)."""
    for i in range(1, t.size):
        if not t[i] > t[i - 1]:
            return False
    return True


@numba.njit(cache=True)
def rms_scaled(x, scale):
    acc = 0.0
    for i in range(x.size):
        v = x[i] / scale[i]
        acc += v * v
    return math.sqrt(acc / x.size)


@numba.njit(cache=True)
def initial_step(rhs, t0, y0, f0, params, order, rtol, atol, span):
    """Starting step size, Hairer-Norsett-Wanner I, sec. II.4 (as scipy select_initial_step):
    a guess h0 from |y0| and |f0| (:func:`initial_guess`), then one evaluation at
    y0 + h0 f0 to estimate the second derivative (:func:`initial_choice`)."""
    d = y0.size
    scale = np.empty(d)
    y1 = np.empty(d)
    h0, d1 = initial_guess(y0, f0, rtol, atol, span, scale, y1)
    f1 = np.empty(d)
    rhs(t0 + h0, y1, params, f1)
    return initial_choice(f0, f1, h0, d1, scale, order, span)


@numba.njit(cache=True)
def initial_guess(y0, f0, rtol, atol, span, scale, y1):
    """(h0, d1 = ‖f0‖) of :func:`initial_step`; fills ``scale`` (atol + |y0| rtol) and
    ``y1 = y0 + h0 f0``."""
    d = y0.size
    for i in range(d):
        scale[i] = atol + abs(y0[i]) * rtol
    d0 = rms_scaled(y0, scale)
    d1 = rms_scaled(f0, scale)
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    if not h0 > 0.0:  # ‖f0‖ overflowed to inf (every f0[i] finite): 0.01 d0/d1 is 0
        h0 = 1e-6
    h0 = min(h0, span)
    for i in range(d):
        y1[i] = y0[i] + h0 * f0[i]
    return h0, d1


@numba.njit(cache=True)
def initial_choice(f0, f1, h0, d1, scale, order, span):
    """The step of :func:`initial_step` from f0 = f(y0), its norm ``d1`` and
    f1 = f(y0 + h0 f0) (overwritten)."""
    for i in range(f0.size):
        f1[i] -= f0[i]
    if not h0 > 0.0:  # an empty span
        return h0
    d2 = rms_scaled(f1, scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (order + 1))
    return min(min(100.0 * h0, h1), span)  # two-argument min/max compile to one instruction


@numba.njit(cache=True, inline="always")
def stage_state(A, s, y, h, K, ytmp):
    """``ytmp = y + h sum_j a_sj K[j]``, where stage ``s`` evaluates f (at t + c_s h)."""
    for i in range(y.size):
        acc = 0.0
        for j in range(s):
            acc += A[s, j] * K[j, i]
        ytmp[i] = y[i] + h * acc


@numba.njit(cache=True, inline="always")
def rk_update(b, nst, y, h, K, out):
    """``out = y + h sum_s b_s K[s]`` (``out`` may be ``y``: each entry is read first)."""
    for i in range(y.size):
        acc = 0.0
        for s in range(nst):
            acc += b[s] * K[s, i]
        out[i] = y[i] + h * acc


@numba.njit(cache=True, inline="always")
def store_row(K, s, f):
    """``K[s] = f`` (a stage row, or an output row ``Y[j] = y``)."""
    for i in range(f.size):
        K[s, i] = f[i]


@numba.njit(cache=True)
def dense_eval(kind, nst, P, t_old, h, y_old, K, F, tout, out):
    """Continuous extension of the last accepted step at ``tout``.

    kind 0: polynomial form y_old + h K^T P [x, x^2, ...] (scipy RkDenseOutput).
    kind 1: DOP853 form, nested evaluation of the precomputed ``F`` (Hairer's contd8).
    """
    d = y_old.size
    x = (tout - t_old) / h
    if kind == 0:
        npow = P.shape[1]
        for i in range(d):
            acc = 0.0
            xp = 1.0
            for k in range(npow):
                xp *= x
                q = 0.0
                for j in range(nst + 1):
                    q += K[j, i] * P[j, k]
                acc += q * xp
            out[i] = y_old[i] + h * acc
    else:
        nf = F.shape[0]
        for i in range(d):
            acc = 0.0
            for r in range(nf):
                acc += F[nf - 1 - r, i]
                if r % 2 == 0:
                    acc *= x
                else:
                    acc *= 1.0 - x
            out[i] = acc + y_old[i]


@numba.njit(cache=True)
def dop853_component(F, y_old, i, x):
    """Component ``i`` of the DOP853 interpolant at ``x`` in [0, 1], and its x-derivative.

    The nested form of :func:`dense_eval` (same operations, so the same value
    to the bit) with the derivative carried along by the product rule: the ensemble's
    event location and the fictitious-time driver's output search use it.
    """
    nf = F.shape[0]
    acc = 0.0
    dacc = 0.0
    for r in range(nf):
        acc += F[nf - 1 - r, i]
        if r % 2 == 0:
            dacc = dacc * x + acc
            acc *= x
        else:
            dacc = dacc * (1.0 - x) - acc
            acc *= 1.0 - x
    return acc + y_old[i], dacc


@numba.njit(cache=True, inline="always")
def crosses(g0, g1, direction):
    """Whether a component going from g0 to g1 over a step crosses zero in ``direction``.

    Up (+1): g0 < 0 <= g1; down (-1): g0 > 0 >= g1; 0: either.  A value exactly zero at
    the end of one step counts there and not again at the start of the next.
    """
    if direction >= 0 and g0 < 0.0 <= g1:
        return True
    return direction <= 0 and g0 > 0.0 >= g1


@numba.njit(cache=True)
def interpolant_root(F, y_old, i, g0, g1):
    """Where component ``i`` of the step's interpolant vanishes, as x in [0, 1].

    g0 (nonzero) and g1 are the component at the step's ends, of opposite signs or
    g1 = 0.  Newton's method from the secant guess, kept inside the bracket that it
    shrinks, with bisection whenever a Newton step would leave it; it stops when a
    step moves x by less than 4 eps, i.e. the crossing time is the interpolant's root
    to ~1e-15 of the step (HNW I, II.6).
    """
    if g1 == 0.0:
        return 1.0
    lo = 0.0
    hi = 1.0
    x = g0 / (g0 - g1)
    for _ in range(100):
        v, dv = dop853_component(F, y_old, i, x)
        if v == 0.0:
            return x
        if (v < 0.0) == (g0 < 0.0):
            lo = x
        else:
            hi = x
        x_new = x - v / dv if dv != 0.0 else -1.0  # -1: outside, bisect
        if not (lo < x_new < hi):
            x_new = 0.5 * (lo + hi)
        if abs(x_new - x) <= 4.0 * EPS or hi - lo <= 4.0 * EPS:
            return x_new
        x = x_new
    return x


@numba.njit(cache=True)
def dop853_dense_coefficients(nst, P, h, y_old, y_new, K, F):
    """The coefficients F of the 7th-order interpolant (K has the three extra stages)."""
    d = y_old.size
    for i in range(d):
        dy = y_new[i] - y_old[i]
        F[0, i] = dy
        F[1, i] = h * K[0, i] - dy
        F[2, i] = 2.0 * dy - h * (K[nst, i] + K[0, i])
        for k in range(P.shape[0]):
            acc = 0.0
            for j in range(K.shape[0]):
                acc += P[k, j] * K[j, i]
            F[3 + k, i] = h * acc


@numba.njit(cache=True, inline="always")
def error_norm(kind, E, E3, nst, h, y, y_new, K, f_new, scale, rtol, atol):
    """Scaled RMS norm of the local error of the step y -> y_new; inf if ``y_new`` or
    ``f_new`` is not finite, ``ERR_OVERFLOW`` if only the norm is not (both are rejected).

    ``K[:nst]`` are the step's stages and ``f_new`` = f(t + h, y_new) (``K[nst]`` still
    holds f(t, y), needed if the step is rejected).  kind 0: the embedded estimate
    ``h sum E_s K_s``; kind 1: DOP853's combined 5th/3rd-order estimate (Hairer's
    dop853.f, scipy DOP853).  Accepted when < 1.
    """
    d = y.size
    probe = 0.0  # sum of y_new * 0: exactly 0 when y_new is finite, else NaN
    for i in range(d):
        scale[i] = atol + max(abs(y[i]), abs(y_new[i])) * rtol
        probe += y_new[i] * 0.0
    if kind == 0:
        acc2 = 0.0
        for i in range(d):
            e = E[nst] * f_new[i]
            for s in range(nst):
                e += E[s] * K[s, i]
            e = h * e / scale[i]
            acc2 += e * e
        err = math.sqrt(acc2 / d)
    else:
        e5n = 0.0
        e3n = 0.0
        for i in range(d):
            e5 = E[nst] * f_new[i]
            e3 = E3[nst] * f_new[i]
            for s in range(nst):
                e5 += E[s] * K[s, i]
                e3 += E3[s] * K[s, i]
            e5 /= scale[i]
            e3 /= scale[i]
            e5n += e5 * e5
            e3n += e3 * e3
        if e5n == 0.0 and e3n == 0.0:
            err = 0.0
        else:
            err = h * e5n / math.sqrt((e5n + 0.01 * e3n) * d)
    if not (math.isfinite(err) and probe == 0.0 and all_finite(f_new)):
        err = overflow_or_inf(probe, f_new)
    return err


@numba.njit(cache=True)
def overflow_or_inf(probe, f_new):
    """The error norm of an attempt whose norm is not finite or whose values are not:
    ``ERR_OVERFLOW`` when the state (``probe``, the sum of ``y_new * 0``: 0 exactly when
    ``y_new`` is finite, else NaN) and ``f_new`` = f(t + h, y_new) are finite, inf when
    one is not (the stages feed ``y_new``).  Only called then: the finiteness test of
    every step is folded into the error norm's loops (a separate pass over ``y_new``
    cost erk_adaptive ~10 % per step, measured)."""
    if probe == 0.0 and all_finite(f_new):
        return ERR_OVERFLOW
    return math.inf


@numba.njit(cache=True, inline="always")
def stop_status(t_next, err):
    """Why the step-size test stopped a run: NONFINITE when the next time ``t_next`` =
    t + h (so the step h, or t) or the last attempt (``err`` = inf, :func:`error_norm`)
    was not finite, else UNDERFLOW (h < 10 eps |t|, or t + h == t)."""
    if math.isfinite(t_next) and math.isfinite(err):
        return UNDERFLOW
    return NONFINITE


@numba.njit(cache=True, inline="always")
def step_factor(err, err_exp, rejected):
    """Factor of the next step size after an attempt with error norm ``err`` (as scipy's
    RungeKutta._step_impl): the step is accepted when err < 1, and right after a
    rejection an accepted step may not grow."""
    if err < 1.0:
        if err == 0.0:
            factor = MAX_FACTOR
        else:
            factor = min(MAX_FACTOR, SAFETY * err ** err_exp)
        if rejected:
            factor = min(1.0, factor)
    elif math.isfinite(err):
        factor = max(MIN_FACTOR, SAFETY * err ** err_exp)
    else:
        factor = MIN_FACTOR
    return factor


@numba.njit(cache=True, inline="always")
def accept_step(nst, y_old, y, y_new, K, f_new):
    """Accept the step y -> y_new: y_old = y, y = y_new, ``K[nst]`` = f_new (FSAL)."""
    for i in range(y.size):
        y_old[i] = y[i]
        y[i] = y_new[i]
        K[nst, i] = f_new[i]


@numba.njit(cache=True)
def erk_adaptive(rhs, A, b, c, E, E3, P, nst, kind, err_exp, order,
                 t_eval, i0, i1, Y, y, y_old, K, F, state, counters,
                 params, rtol, atol, max_steps):
    """Embedded explicit Runge-Kutta with step-size control and dense output.

    The step is never shortened to land on an output time: outputs inside an
    accepted step come from its continuous extension, and the last step may end
    past ``t_eval[i1-1]``; the next call first serves outputs from that step, so
    chunked and unchunked runs are identical.

    state : float64[5] = (t, h, t_old, step_rejected, dense_ready); h = 0 asks for
        an initial step.  ``K[nst]`` holds f(t, y) between steps (FSAL).
    max_steps : budget of attempted steps, ``counters[1] + counters[2]`` (MAXSTEPS).

    Returns OK, MAXSTEPS, UNDERFLOW or NONFINITE (see "Every run ends" above).
    """
    d = y.size
    t = state[0]
    h = state[1]
    t_old = state[2]
    rejected = state[3] != 0.0
    dense_ready = state[4] != 0.0
    ytmp = np.empty(d)
    ftmp = np.empty(d)
    y_new = np.empty(d)
    f_new = np.empty(d)
    scale = np.empty(d)
    span = t_eval[t_eval.size - 1] - t_eval[0]
    status = OK
    err = 0.0  # the last attempt's error norm (a call resumes after an accepted step)
    if h == 0.0:
        # fresh start: f(t0, y0) into K[nst]
        rhs(t, y, params, f_new)
        store_row(K, nst, f_new)
        counters[0] += 1
        if not all_finite(f_new):  # f(t0, y0) is not finite: no step can be chosen
            return NONFINITE
        h = initial_step(rhs, t, y, f_new, params, order, rtol, atol, span)
        counters[0] += 1
        t_old = t
    j = i0
    while j < i1:
        # serve every output inside the last accepted step (t_old, t]
        while j < i1 and t_eval[j] <= t:
            if t_eval[j] == t:
                store_row(Y, j, y)
            else:
                if kind == 1 and not dense_ready:
                    hd = t - t_old
                    for s in range(nst + 1, K.shape[0]):  # the extra stages of DOP853
                        stage_state(A, s, y_old, hd, K, ytmp)
                        rhs(t_old + c[s] * hd, ytmp, params, ftmp)
                        store_row(K, s, ftmp)
                    dop853_dense_coefficients(nst, P, hd, y_old, y, K, F)
                    counters[0] += K.shape[0] - nst - 1
                    dense_ready = True
                dense_eval(kind, nst, P, t_old, t - t_old, y_old, K, F, t_eval[j], Y[j])
            j += 1
        if j >= i1:
            break
        if counters[1] + counters[2] >= max_steps:  # attempted steps
            status = MAXSTEPS
            break
        # NaN fails every comparison, so a NaN step stops here (``h < min_step`` was False
        # for it: the loop spun); h >= 10 eps |t| also means t + h > t (no zero progress)
        if not (10.0 * EPS * max(abs(t), 1e-300) <= h < math.inf):
            status = stop_status(t + h, err)
            break
        # one attempt t -> t + h;  K[0] = f(t, y) is K[nst] of the previous step
        for i in range(d):
            K[0, i] = K[nst, i]
        for s in range(1, nst):
            stage_state(A, s, y, h, K, ytmp)
            rhs(t + c[s] * h, ytmp, params, ftmp)
            store_row(K, s, ftmp)
        rk_update(b, nst, y, h, K, y_new)
        t_new = t + h
        rhs(t_new, y_new, params, f_new)
        counters[0] += nst
        # K[nst] must stay f(t, y) if the step is rejected, so the error uses f_new
        err = error_norm(kind, E, E3, nst, h, y, y_new, K, f_new, scale, rtol, atol)
        factor = step_factor(err, err_exp, rejected)
        if err < 1.0:
            rejected = False
            counters[1] += 1
            t_old = t
            accept_step(nst, y_old, y, y_new, K, f_new)
            t = t_new
            dense_ready = False
        else:
            counters[2] += 1
            rejected = True
        h *= factor
    state[0] = t
    state[1] = h
    state[2] = t_old
    state[3] = 1.0 if rejected else 0.0
    state[4] = 1.0 if dense_ready else 0.0
    return status


@numba.njit(cache=True)
def steps_in(dt, h_max):
    """Number of equal steps <= h_max that cover ``dt`` (as ``explicit_rk._fixed_steps``),
    or -1 when there is none to take: h_max not positive and finite, or more than
    ``MAX_FIXED_STEPS`` (the int conversion would overflow: one step, silently)."""
    if not 0.0 < h_max < math.inf:
        return -1
    x = dt / h_max * (1.0 - 1e-12)
    if not x <= MAX_FIXED_STEPS:
        return -1
    return max(1, int(math.ceil(x)))


@numba.njit(cache=True)
def erk_fixed(rhs, A, b, c, nst, t_eval, i0, i1, Y, y, h_max, params, counters, tfail):
    """Explicit RK with constant steps; each output interval is cut into equal steps <= h_max.

    Fills Y[j] for j in [i0, i1), j >= 1; y enters at t_eval[i0 - 1].
    """
    d = y.size
    K = np.empty((nst, d))
    ytmp = np.empty(d)
    ftmp = np.empty(d)
    for j in range(i0, i1):
        t0 = t_eval[j - 1]
        n = steps_in(t_eval[j] - t0, h_max)
        if n < 0:
            tfail[0] = t0
            return BAD_STEP
        h = (t_eval[j] - t0) / n
        for k in range(n):
            t = t0 + k * h
            rhs(t, y, params, ftmp)
            store_row(K, 0, ftmp)
            for s in range(1, nst):
                stage_state(A, s, y, h, K, ytmp)
                rhs(t + c[s] * h, ytmp, params, ftmp)
                store_row(K, s, ftmp)
            rk_update(b, nst, y, h, K, y)
            counters[0] += nst
            counters[1] += 1
            if not all_finite(y):
                tfail[0] = t + h
                return NONFINITE
        store_row(Y, j, y)
    return OK


@numba.njit(cache=True)
def splitting_fixed(drift, kick, a, bk, n, t_eval, i0, i1, Y, y, h_max, params, counters,
                    tfail):
    """Symmetric composition of Stormer-Verlet (kick-drift-kick) for H = T(p) + V(q).

    One step of size h: p += bk[0] h F(q); for i: q += a[i] h T'(p); p += bk[i+1] h F(q).
    The force at the end of a step is the force at the start of the next, so a step
    of an m-stage composition costs m kick evaluations.
    """
    q = np.empty(n)
    p = np.empty(n)
    for i in range(n):
        q[i] = y[i]
        p[i] = y[n + i]
    force = np.empty(n)
    vel = np.empty(n)
    kick(q, params, force)
    counters[0] += 1
    m = a.size
    for j in range(i0, i1):
        ns = steps_in(t_eval[j] - t_eval[j - 1], h_max)
        if ns < 0:
            tfail[0] = t_eval[j - 1]
            return BAD_STEP
        h = (t_eval[j] - t_eval[j - 1]) / ns
        for k in range(ns):
            for i in range(n):
                p[i] += bk[0] * h * force[i]
            for st in range(m):
                drift(p, params, vel)
                for i in range(n):
                    q[i] += a[st] * h * vel[i]
                kick(q, params, force)
                for i in range(n):
                    p[i] += bk[st + 1] * h * force[i]
            counters[0] += m
            counters[1] += 1
            if not (all_finite(q) and all_finite(p)):
                tfail[0] = t_eval[j - 1] + (k + 1) * h
                return NONFINITE
        for i in range(n):
            Y[j, i] = q[i]
            Y[j, n + i] = p[i]
    for i in range(n):
        y[i] = q[i]
        y[n + i] = p[i]
    return OK


@numba.njit(cache=True)
def lu_factor(M, perm):
    """LU factorization with partial pivoting, in place (``perm[k]``: row swapped with k).

    False if ``M`` is not finite or exactly singular.  Written out rather than
    ``np.linalg``: ``inv`` and ``@`` cost ~1 s of numba internals to compile, and these
    loops are as fast for the matrices of Gauss collocation (s d <= ~60).
    """
    n = M.shape[0]
    for i in range(n):
        for j in range(n):
            if not math.isfinite(M[i, j]):
                return False
    for k in range(n):
        piv = k
        big = abs(M[k, k])
        for i in range(k + 1, n):
            if abs(M[i, k]) > big:
                piv = i
                big = abs(M[i, k])
        if big == 0.0:
            return False
        perm[k] = piv
        if piv != k:
            for j in range(n):
                tmp = M[k, j]
                M[k, j] = M[piv, j]
                M[piv, j] = tmp
        inv = 1.0 / M[k, k]
        for i in range(k + 1, n):
            f = M[i, k] * inv
            M[i, k] = f
            if f != 0.0:
                for j in range(k + 1, n):
                    M[i, j] -= f * M[k, j]
    return True


@numba.njit(cache=True)
def lu_solve(LU, perm, x):
    """x <- M^{-1} x, with ``LU``, ``perm`` from :func:`lu_factor` of M."""
    n = x.size
    for k in range(n):
        p = perm[k]
        if p != k:
            tmp = x[k]
            x[k] = x[p]
            x[p] = tmp
    for i in range(n):  # L y = P x, L unit lower triangular
        acc = x[i]
        for j in range(i):
            acc -= LU[i, j] * x[j]
        x[i] = acc
    for i in range(n - 1, -1, -1):  # U x = y
        acc = x[i]
        for j in range(i + 1, n):
            acc -= LU[i, j] * x[j]
        x[i] = acc / LU[i, i]


@numba.njit(cache=True)
def collocation_fixed(rhs, jac, use_fd_jac, A, A_lo, b, b_lo, c, t_eval, i0, i1, Y, y, h_max,
                      params, counters, tfail, max_iter):
    """Implicit Runge-Kutta (Gauss-Legendre collocation) with constant steps.

    Stage increments Z_i = Y_i - y solve Z = h (A (x) I) F(y + Z) by simplified
    Newton with the matrix I - h A (x) J(t, y) frozen over the step (Hairer-Wanner II,
    sec. IV.8, eq. (8.9)).  The new state is y + h sum_i b_i f(Y_i), with the f(Y_i) of
    the last iteration, added with compensated summation (Hairer, McLachlan &
    Razakarivony 2008): y + sum_i d_i Z_i, d = b^T A^{-1} (eq. (8.2b)) multiplies the
    iteration's round-off by |d| ~ 5.  The tableau is passed as pairs of doubles (``A`` +
    ``A_lo``, ``b`` + ``b_lo``), so that it is symplectic to well below one rounding
    (:class:`..symplectic.GaussLegendre`).  ``jac`` is ignored when ``use_fd_jac`` (the
    model has none): then J comes from finite differences of ``rhs``.
    """
    d = y.size
    s = c.size
    sd = s * d
    J = np.empty((d, d))
    M = np.empty((sd, sd))
    perm = np.empty(sd, dtype=np.int64)
    Z = np.empty((s, d))
    Fz = np.empty((s, d))
    G = np.empty(sd)
    ytmp = np.empty(d)
    ftmp = np.empty(d)
    comp = np.empty(d)
    floor = np.empty(d)
    for i in range(d):
        comp[i] = 0.0
    for j in range(i0, i1):
        t0 = t_eval[j - 1]
        ns = steps_in(t_eval[j] - t0, h_max)
        if ns < 0:
            tfail[0] = t0
            return BAD_STEP
        h = (t_eval[j] - t0) / ns
        for k in range(ns):
            t = t0 + k * h
            if use_fd_jac:
                fd_jac(rhs, t, y, params, J)
                counters[0] += d + 1
            else:
                jac(t, y, params, J)
            for p in range(s):
                for q in range(s):
                    for i in range(d):
                        for l in range(d):
                            v = -h * A[p, q] * J[i, l]
                            if p == q and i == l:
                                v += 1.0
                            M[p * d + i, q * d + l] = v
            # a component near zero is known no better than the rounding of the terms of
            # h f_i, which may be large and cancel (a stiff spring at rest): its Newton
            # test is relative to h sum_l |J_il y_l|, else it stalls above 4 eps forever
            for i in range(d):
                acc = 0.0
                for l in range(d):
                    acc += abs(J[i, l] * y[l])
                floor[i] = max(h * acc, 1e-300)
            if not lu_factor(M, perm):  # J not finite (or h a_ii lambda = 1 to the last bit)
                tfail[0] = t
                return NONFINITE
            for p in range(s):
                for i in range(d):
                    Z[p, i] = 0.0
            prev = math.inf
            converged = False
            for it in range(max_iter):
                for p in range(s):
                    for i in range(d):
                        ytmp[i] = y[i] + Z[p, i]
                    rhs(t + c[p] * h, ytmp, params, ftmp)
                    store_row(Fz, p, ftmp)
                counters[0] += s
                for p in range(s):
                    for i in range(d):
                        acc = 0.0
                        lo = 0.0
                        for q in range(s):
                            acc += A[p, q] * Fz[q, i]
                            lo += A_lo[p, q] * Fz[q, i]
                        G[p * d + i] = Z[p, i] - h * (acc + lo)
                lu_solve(M, perm, G)  # G <- dZ = M^{-1} G
                nrm = 0.0
                for p in range(s):
                    for i in range(d):
                        Z[p, i] -= G[p * d + i]
                        # per component: one large component (a clock t, say) must not
                        # loosen the test for the others
                        scale = max(max(abs(y[i]), abs(Z[p, i])), floor[i])
                        nrm = max(nrm, abs(G[p * d + i]) / scale)
                if not math.isfinite(nrm):
                    break
                if nrm <= 4.0 * EPS:
                    converged = True
                    break
                # round-off floor: no more contraction and already tiny
                if it > 0 and nrm >= 0.9 * prev and nrm <= 1e-10:
                    converged = True
                    break
                prev = nrm
            if not converged:
                tfail[0] = t
                return NEWTON
            for i in range(d):
                acc = 0.0
                lo = 0.0
                for p in range(s):
                    acc += b[p] * Fz[p, i]
                    lo += b_lo[p] * Fz[p, i]
                acc = h * (acc + lo)
                # compensated (Kahan) summation of y + increment: without it the rounding
                # of ~1e5 small increments random-walks past the method's invariants
                inc = acc - comp[i]
                total = y[i] + inc
                comp[i] = (total - y[i]) - inc
                y[i] = total
            counters[1] += 1
            if not all_finite(y):
                tfail[0] = t + h
                return NONFINITE
        store_row(Y, j, y)
    return OK
