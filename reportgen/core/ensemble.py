r"""Ensembles: many members of one model integrated in one compiled, multi-threaded call.

Lecture figures are often about families of runs (the pendulum's period against its
amplitude, say).  Run one by one, each member pays Python's overhead; here a compiled
driver loops over the members, on as many threads as numba is set to use (each a
compiled loop over its share without the GIL), and integrates each with our DOP853
-- the steps of :func:`reportgen.core.integrators.compiled.erk_adaptive`, bit for bit --
recording per member only what a sweep needs: the final state, a status, the counters,
the first zero crossings of one component (located on the step's 7th-order dense
output) and, for a few chosen members, the states on a shared output grid.  Memory is
O(M (d + max_events) + len(store) N d) for M members and N output times.

Public API::

    run_ensemble(model, Y0, P, t_end, t0=0.0, rtol=1e-10, atol=1e-12, event=None,
                 direction=0, max_events=0, terminal=False, t_eval=None, store=(),
                 max_steps=1_000_000, block=1024, progress=None) -> Ensemble
    pendulum_periods(theta0, g, l, rtol=1e-12, atol=1e-12, ...) -> (periods, status)

Design
------
* The model's ``rhs`` reaches the driver as a numba C callback (:mod:`.integrators.kernels`),
  typed by its signature, so the driver compiles once for every model and numba's
  on-disk cache serves later processes.
* The driver's loop only calls :func:`dop853_member`, a serial driver of one member
  whose work arrays it allocates itself; members share nothing but read-only inputs, so
  results do not depend on the number of threads, on their schedule or on the blocks.
* Callback rules of :mod:`.integrators.compiled` hold: ``rhs`` is called from
  :func:`dop853_member`'s own body with whole work arrays (a callback inside a helper,
  even an ``inline="always"`` one, measured ~40 ns more per helper call); the error
  norm, the step-size controller, the stage sums and the dense output are compiled.py's
  helpers, so the step sequence is erk_adaptive's.  A pendulum member costs ~31 ns per
  evaluation of ``rhs``, step arithmetic included.
* Threads, not ``prange``: a ``parallel=True`` wrapper compiled in 4.5 s on an empty
  cache (LLVM optimising the member's code again inside numba's gufunc) besides the
  member's 4.3 s; the ``nogil`` loop adds ~1 s (measured, first call with an empty
  cache 9.4 -> 5.6 s), runs as fast on two threads, and leaves numba's threading layers
  alone: GNU OpenMP (``omp``, the default here) is not fork-safe, and reportgen forks
  (scene workers, figure and PDF helpers, ``watch``).  Loading from the cache: 0.2 s.
  Like the other drivers, once per numba cache folder for all models.

References
----------
.. [1] Hairer, Norsett, Wanner, *Solving ODEs I*, 2nd ed. (1993), II.6 (dense output
       and event location) and II.10 (DOP853, its error estimate and interpolant).
.. [2] NIST DLMF 19.2.8 and 22.19(i): the pendulum's period 4 K(k) / omega0,
       k = sin(theta0 / 2).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numba
import numpy as np

from .integrators.compiled import (
    EPS,
    MAXSTEPS,
    NONFINITE,
    OK,
    UNDERFLOW,  # noqa: F401 (re-exported: a member's status)
    accept_step,
    all_finite,
    copy_into,
    dense_eval,
    dop853_component,
    dop853_dense_coefficients,
    error_norm,
    initial_step,
    rk_update,
    stage_state,
    step_factor,
    stop_status,
    store_row,
)
from .integrators.explicit_rk import DOP853
from .integrators.kernels import kernels_for
from .integrators.status import Status
from .model import OdeModel

#: :func:`pendulum_periods`: theta0 outside (0, pi), or g / l not positive, or not finite
NOT_LIBRATING = Status.NOT_LIBRATING.code
#: :func:`pendulum_periods`: fewer than two upward crossings before the horizon
NO_PERIOD = Status.NO_PERIOD.code
#: a member's integer status -> its spelling: :class:`.integrators.status.Status`, whose
#: ``from_code`` reads a code; kept for ``STATUS_NAMES.get(int(c), ...)``
STATUS_NAMES = {s.code: s.value for s in Status}


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
def dop853_member(rhs, A, b, c, E, E3, P, nst, kind, err_exp, order, y0, p, t0, t_end,
                  rtol, atol, max_steps, comp, direction, terminal, events, t_eval, Y,
                  store, y_end, counters):
    """Integrate one member from ``y0`` at ``t0`` to ``t_end`` with DOP853 (``kind`` 1).

    The steps are :func:`.compiled.erk_adaptive`'s with ``t_eval = [t0, ..., t_end]``:
    same initial step, error norm, controller and dense output, so the states agree
    to the bit.  After each accepted step (t_old, t]:

    * a zero crossing of ``y[comp]`` in ``direction`` (:func:`crosses`) is located on
      the step's interpolant (:func:`interpolant_root`) and its time appended to
      ``events`` until it is full (``terminal``: the member then stops);
    * if ``store``, the outputs ``Y[j]`` at ``t_eval[j]`` in (t_old, t] are filled.

    The interpolant's three extra stages are computed only for steps that need them.

    Parameters
    ----------
    p : (k,) the member's parameters (copied: callbacks get whole arrays).
    events : (max_events,) crossing times, written in order.
    t_eval, Y : (N,), (N, d) output grid in [t0, t_end] and its states (if ``store``).
    y_end : (d,) out: the state at ``t_end``; the last accepted state if the member
        stopped early (terminal events) or failed.
    counters : int64[3] out: (nfev, accepted steps, rejected steps), accumulated.

    Returns
    -------
    (status, number of events, time of ``y_end``)
    """
    d = y0.size
    n_rows = A.shape[0]
    n_out = t_eval.size if store else 0
    max_events = events.size
    y = np.empty(d)
    y_old = np.empty(d)
    y_new = np.empty(d)
    f_new = np.empty(d)
    ytmp = np.empty(d)
    ftmp = np.empty(d)
    scale = np.empty(d)
    params = np.empty(p.size)
    K = np.zeros((n_rows, d))
    F = np.zeros((P.shape[0] + 3, d))
    copy_into(y, y0)
    copy_into(params, p)
    copy_into(y_end, y0)
    t = t0
    if not all_finite(y):
        return NONFINITE, 0, t
    rhs(t, y, params, f_new)
    store_row(K, nst, f_new)
    counters[0] += 1
    if not all_finite(f_new):
        return NONFINITE, 0, t
    h = initial_step(rhs, t, y, f_new, params, order, rtol, atol, t_end - t0)
    counters[0] += 1
    t_old = t
    rejected = False
    err = 0.0
    n_ev = 0
    j = 0
    while j < n_out and t_eval[j] <= t:  # outputs at t0
        store_row(Y, j, y)
        j += 1
    status = OK
    while t < t_end:
        if counters[1] + counters[2] >= max_steps:  # attempted steps, as erk_adaptive
            status = MAXSTEPS
            break
        # NaN fails every comparison, so a NaN step stops here (``h < min_step`` was False
        # for it: the loop spun); h >= 10 eps |t| also means t + h > t (no zero progress)
        if not (10.0 * EPS * max(abs(t), 1e-300) <= h < math.inf):
            status = stop_status(t + h, err)
            break
        # one attempt t -> t + h, as in erk_adaptive
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
        err = error_norm(kind, E, E3, nst, h, y, y_new, K, f_new, scale, rtol, atol)
        factor = step_factor(err, err_exp, rejected)
        h *= factor
        if err >= 1.0:
            counters[2] += 1
            rejected = True
            continue
        rejected = False
        counters[1] += 1
        t_old = t
        accept_step(nst, y_old, y, y_new, K, f_new)
        t = t_new
        hit = n_ev < max_events and crosses(y_old[comp], y[comp], direction)
        if hit or t > t_end or (j < n_out and t_eval[j] < t):
            hd = t - t_old
            for s in range(nst + 1, n_rows):  # the extra stages of the interpolant
                stage_state(A, s, y_old, hd, K, ytmp)
                rhs(t_old + c[s] * hd, ytmp, params, ftmp)
                store_row(K, s, ftmp)
            dop853_dense_coefficients(nst, P, hd, y_old, y, K, F)
            counters[0] += n_rows - nst - 1
        if hit:
            x = interpolant_root(F, y_old, comp, y_old[comp], y[comp])
            t_ev = t_old + x * (t - t_old)
            if t_ev <= t_end:
                events[n_ev] = t_ev
                n_ev += 1
        while j < n_out and t_eval[j] <= t:
            if t_eval[j] == t:
                store_row(Y, j, y)
            else:
                dense_eval(kind, nst, P, t_old, t - t_old, y_old, K, F, t_eval[j], Y[j])
            j += 1
        if terminal and 0 < max_events == n_ev and t < t_end:
            copy_into(y_end, y)
            return OK, n_ev, t
    if status != OK:
        copy_into(y_end, y)
        return status, n_ev, t
    if t == t_end:
        copy_into(y_end, y)
    else:
        dense_eval(kind, nst, P, t_old, t - t_old, y_old, K, F, t_end, y_end)
    return OK, n_ev, t_end


@numba.njit(cache=True, nogil=True)
def dop853_ensemble(rhs, A, b, c, E, E3, P, nst, kind, err_exp, order, m0, m1, stride,
                    Y0, Pm, t0, t_end, rtol, atol, max_steps, comp, direction, terminal,
                    t_eval, slot, Ystore, y_end, t_final, status, counters, events,
                    n_events):
    """Members ``m0, m0 + stride, ... < m1`` of an ensemble, one :func:`dop853_member`
    each, without the GIL (:func:`run_ensemble` gives each thread its own ``m0``).

    ``Y0`` (M, d) and ``Pm`` (M, k): initial states and parameters; ``slot`` (M,): the
    member's row of ``Ystore`` (S, N, d), or -1 if its trajectory is not kept.  Results
    go to row m of ``y_end`` (M, d), ``t_final`` (M,), ``status`` (M,), ``counters``
    (M, 3), ``events`` (M, max_events), ``n_events`` (M,).  The other arguments are
    :func:`dop853_member`'s.
    """
    for m in range(m0, m1, stride):
        s = slot[m]
        st, ne, tf = dop853_member(
            rhs, A, b, c, E, E3, P, nst, kind, err_exp, order, Y0[m], Pm[m], t0, t_end,
            rtol, atol, max_steps, comp, direction, terminal, events[m], t_eval,
            Ystore[max(s, 0)], s >= 0, y_end[m], counters[m])
        status[m] = st
        n_events[m] = ne
        t_final[m] = tf


@dataclass
class Ensemble:
    """Per-member results of :func:`run_ensemble` (M members, state dimension d).

    Attributes
    ----------
    y_end : ndarray, shape (M, d)
        State at ``t_end``; for a member that stopped early (terminal events) or failed,
        its last accepted state, at ``t_final``.
    t_final : ndarray, shape (M,)
    status : ndarray of int, shape (M,)
        ``OK``, ``NONFINITE``, ``UNDERFLOW`` or ``MAXSTEPS`` (:mod:`.integrators.compiled`;
        :meth:`.integrators.status.Status.from_code` names them).
    counters : ndarray of int64, shape (M, 3)
        (function evaluations, accepted steps, rejected steps).
    events : ndarray, shape (M, max_events)
        Times of the first zero crossings, NaN where there were fewer.
    n_events : ndarray of int, shape (M,)
    t_eval : ndarray, shape (N,)
    store : ndarray of int, shape (S,)
        Members whose trajectories were kept, in ``y_store`` order.
    y_store : ndarray, shape (S, N, d)
        Their states at ``t_eval`` (NaN after a member stopped or failed).
    wall_time_s : float
        Time of the compiled calls; in a process's first call it includes compiling
        the driver or loading it from numba's cache (~0.2 s).
    """

    y_end: np.ndarray
    t_final: np.ndarray
    status: np.ndarray
    counters: np.ndarray
    events: np.ndarray
    n_events: np.ndarray
    t_eval: np.ndarray
    store: np.ndarray
    y_store: np.ndarray
    wall_time_s: float


def _member_params(model: OdeModel, P, M: int) -> np.ndarray:
    if P is None:
        P = model.params
    P = np.asarray(P, dtype=np.float64)
    if P.ndim == 1:
        P = np.broadcast_to(P, (M, P.size))
    if P.ndim != 2 or P.shape[0] != M:
        raise ValueError(f"P: expected shape (k,) or ({M}, k), got {P.shape}")
    return np.ascontiguousarray(P)


def _event_component(model: OdeModel, event) -> int:
    if isinstance(event, str):
        if event not in model.columns:
            raise ValueError(f"event: expected one of {model.columns}, got {event!r}")
        return model.columns.index(event)
    comp = int(event)
    if not 0 <= comp < model.dim:
        raise ValueError(f"event: expected a component index in [0, {model.dim}), got {event}")
    return comp


def run_ensemble(model: OdeModel, Y0, P=None, t_end: float = 1.0, *, t0: float = 0.0,
                 rtol: float = 1e-10, atol: float = 1e-12, event: int | str | None = None,
                 direction: int = 0, max_events: int = 0, terminal: bool = False,
                 t_eval=None, store: Sequence[int] = (), max_steps: int = 1_000_000,
                 block: int = 1024, progress: Callable[[float], None] | None = None
                 ) -> Ensemble:
    """Integrate M members of ``model`` from ``t0`` to ``t_end`` with DOP853, in parallel.

    Parameters
    ----------
    model : OdeModel
        Only its ``rhs`` is used (and ``params`` when ``P`` is None).
    Y0 : array_like, shape (M, d)
        Initial states.  A non-finite row gives that member ``NONFINITE`` at once.
    P : array_like, shape (M, k) or (k,), optional
        Parameters per member (``(k,)``: shared); default ``model.params``.
    t_end, t0 : float
        Common time span.
    rtol, atol : float
        Tolerances of every member, as in ``integrate(..., method="dop853")``.
    event : int or str, optional
        Component (index or column name) whose zero crossings are recorded.
    direction : {+1, -1, 0}
        Crossings going up, going down, or both.
    max_events : int
        How many crossings to keep per member (the first ones, up to ``t_end``).
    terminal : bool
        Stop a member as soon as it has ``max_events`` crossings.
    t_eval : array_like, shape (N,), optional
        Increasing output times in [t0, t_end] for the ``store`` members.
    store : sequence of int
        Members whose states at ``t_eval`` are kept (memory S N d).
    max_steps : int
        Budget of attempted steps (accepted + rejected) per member (``MAXSTEPS`` beyond it).
    block : int
        Members per compiled call; ``progress(fraction)`` is called after each.
        Results do not depend on it (nor on ``numba.set_num_threads``).

    Notes
    -----
    The members' steps are those of ``integrate(model, y0, t_eval, "dop853", rtol,
    atol)`` with ``t_eval`` spanning [t0, t_end], so the states agree to the bit.
    A crossing is found when the component changes sign over a step; two crossings
    within one step (a step longer than half an oscillation) would go unseen, and a
    zero exactly at ``t0`` is not a crossing.
    """
    Y0 = np.ascontiguousarray(Y0, dtype=np.float64)
    if Y0.ndim != 2 or Y0.shape[1] != model.dim:
        raise ValueError(f"Y0: expected shape (M, {model.dim}) for model '{model.name}', "
                         f"got {Y0.shape}")
    M, d = Y0.shape
    Pm = _member_params(model, P, M)
    t0, t_end = float(t0), float(t_end)
    if not (math.isfinite(t0) and math.isfinite(t_end) and t_end > t0):
        raise ValueError(f"t_end: expected a finite time after t0 = {t0}, got {t_end}")
    if not (rtol > 0.0 and atol > 0.0):  # the error scale atol + rtol |y| divides
        raise ValueError(f"rtol, atol: expected positive tolerances, got {rtol}, {atol}")
    if direction not in (-1, 0, 1):
        raise ValueError(f"direction: expected +1, -1 or 0, got {direction}")
    if max_events < 0 or (max_events > 0 and event is None):
        raise ValueError("max_events: expected >= 0, and an event component when > 0")
    comp = _event_component(model, event) if event is not None else 0
    t_eval = np.ascontiguousarray([] if t_eval is None else t_eval, dtype=np.float64)
    if t_eval.ndim != 1 or (t_eval.size and not (
            t_eval[0] >= t0 and t_eval[-1] <= t_end and np.all(np.diff(t_eval) > 0))):
        raise ValueError(f"t_eval: expected increasing times in [{t0}, {t_end}]")
    store = np.asarray(store, dtype=np.int64).reshape(-1)
    if store.size and (store.min() < 0 or store.max() >= M or np.unique(store).size < store.size):
        raise ValueError(f"store: expected distinct member indices in [0, {M})")
    if block < 1:
        raise ValueError(f"block: expected >= 1, got {block}")
    slot = np.full(M, -1, dtype=np.int64)
    slot[store] = np.arange(store.size)
    Ystore = np.full((max(store.size, 1), t_eval.size, d), np.nan)
    y_end = np.empty((M, d))
    t_final = np.empty(M)
    status = np.empty(M, dtype=np.int64)
    counters = np.zeros((M, 3), dtype=np.int64)
    events = np.full((M, max_events), np.nan)
    n_events = np.zeros(M, dtype=np.int64)
    rhs = kernels_for(model).rhs
    tableau = DOP853().driver_args()

    threads = max(1, numba.get_num_threads())

    def members(first: int, m1: int) -> None:
        dop853_ensemble(rhs, *tableau, first, m1, threads, Y0, Pm, t0, t_end, float(rtol),
                        float(atol), int(max_steps), comp, int(direction), bool(terminal),
                        t_eval, slot, Ystore, y_end, t_final, status, counters, events,
                        n_events)

    wall = 0.0
    with ThreadPoolExecutor(max_workers=threads) as pool:
        for m0 in range(0, M, block):
            m1 = min(m0 + block, M)
            start = time.perf_counter()
            # thread k takes members m0 + k, m0 + k + threads, ...: neighbouring members
            # cost alike, so the threads share the block evenly; each writes its own rows
            list(pool.map(members, range(m0, min(m0 + threads, m1)), [m1] * threads))
            wall += time.perf_counter() - start
            if progress is not None:
                progress(m1 / M)
    return Ensemble(y_end=y_end, t_final=t_final, status=status, counters=counters,
                    events=events, n_events=n_events, t_eval=t_eval, store=store,
                    y_store=Ystore[:store.size], wall_time_s=wall)


def pendulum_periods(theta0, g, l, rtol: float = 1e-12, atol: float = 1e-12,
                     block: int = 1024, progress: Callable[[float], None] | None = None,
                     max_steps: int = 1_000_000) -> tuple[np.ndarray, np.ndarray]:
    """Periods of pendulums released from rest at amplitudes ``theta0``, integrated.

    Each member starts at (theta0, 0) with omega0^2 = g / l; its period is the time
    between its first two upward zero crossings of theta (at 3T/4 and 7T/4), located on
    DOP853's dense output.  To compare with 4 K(k) sqrt(l / g), k = sin(theta0 / 2)
    (DLMF 19.2.8, 22.19(i)).

    Parameters
    ----------
    theta0, g, l : array_like, broadcast together
        Amplitude [rad] in (0, pi), gravity [m/s^2], length [m].

    rtol, atol : float
        Near the separatrix the period is ill-conditioned: dT / T ~ (dE / omega0^2) /
        (4 k'^2 K(k)), k' = cos(theta0 / 2), for an energy error dE (from dK/dk, DLMF
        19.4.1), ~110 dE / omega0^2 at theta0 = 3.1.  There rtol = 1e-10 gives 1e-8
        relative error in T, the default 1e-12 gives 1.5e-10.

    Returns
    -------
    periods : ndarray
        [s]; NaN where ``status`` is not ``OK``.
    status : ndarray of int
        ``OK``; ``NOT_LIBRATING`` for theta0 outside (0, pi) (rotation or separatrix),
        g / l not positive, or anything not finite; else the integration's status
        (:class:`Ensemble`), or ``NO_PERIOD``.

    Notes
    -----
    The members run until their second crossing (terminal events) within the horizon
    t_end = 2 max T_bound, where T <= T_bound = 2 pi / (omega0 cos(theta0 / 2)) because
    K(k) <= (pi / 2) / sqrt(1 - k^2) (bound the integrand of DLMF 19.2.8).
    """
    from .models import pendulum

    theta0, g, l = np.broadcast_arrays(np.asarray(theta0, dtype=np.float64),
                                       np.asarray(g, dtype=np.float64),
                                       np.asarray(l, dtype=np.float64))
    shape = theta0.shape
    theta0, g, l = theta0.ravel(), g.ravel(), l.ravel()
    with np.errstate(divide="ignore", invalid="ignore"):
        omega2 = g / l
        valid = (np.isfinite(theta0) & (theta0 > 0.0) & (theta0 < math.pi)
                 & np.isfinite(omega2) & (omega2 > 0.0))
    periods = np.full(theta0.size, np.nan)
    status = np.full(theta0.size, NOT_LIBRATING, dtype=np.int64)
    idx = np.nonzero(valid)[0]
    if idx.size:
        bound = 2.0 * math.pi / (np.sqrt(omega2[idx]) * np.cos(0.5 * theta0[idx]))
        Y0 = np.column_stack([theta0[idx], np.zeros(idx.size)])
        ens = run_ensemble(pendulum.model(1.0, 1.0), Y0, omega2[idx, None],
                           t_end=2.0 * float(bound.max()), rtol=rtol, atol=atol, event=0,
                           direction=1, max_events=2, terminal=True, max_steps=max_steps,
                           block=block, progress=progress)
        found = (ens.status == OK) & (ens.n_events == 2)
        periods[idx[found]] = ens.events[found, 1] - ens.events[found, 0]
        status[idx] = np.where(found, OK, np.where(ens.status == OK, NO_PERIOD, ens.status))
    return periods.reshape(shape), status.reshape(shape)
