r"""Ensembles: many members of one model integrated in one compiled, multi-threaded call.

Lecture figures are often about families of runs (a period against an amplitude, say;
a kind builds such a sweep on :func:`run_ensemble`).  Run one by one, each member pays
Python's overhead; here a compiled driver loops over the members, on as many threads as
numba is set to use (each a compiled loop over its share without the GIL), and
integrates each with our DOP853
-- the steps of :func:`reportgen.core.integrators.compiled.erk_adaptive`, bit for bit --
recording per member only what a sweep needs: the final state, a status, the counters,
the first zero crossings of one component (located on the step's 7th-order dense
output) and, for a few chosen members, the states on a shared output grid.  Memory is
O(M (d + max_events) + len(store) N d) for M members and N output times.

Public API::

    run_ensemble(model, Y0, P, t_end, t0=0.0, rtol=1e-10, atol=1e-12, event=None,
                 direction=0, max_events=0, terminal=False, t_eval=None, store=(),
                 max_steps=1_000_000, block=1024, progress=None) -> Ensemble

Design
------
* The model's ``rhs`` reaches the driver as a numba C callback (:mod:`.integrators.kernels`),
  typed by its signature, so the driver compiles once for every model and numba's
  on-disk cache serves later processes.
* The driver's loop only calls :func:`dop853_member`, a serial driver of one member
  whose work arrays it allocates itself; members share nothing but read-only inputs, so
  results do not depend on the number of threads, on their schedule or on the blocks.
* :func:`dop853_member` is generated from the one DOP853 template
  (:mod:`.integrators._gen_dop853`, into :mod:`.integrators._dop853_unrolled`) beside the
  driver :func:`integrate` runs: the same text for the stop tests, stages, error norm and
  step-size controller, so the step sequence is the driver's (and erk_adaptive's), bit
  for bit, and a change to the step is made in one place.  Callback rules of
  :mod:`.integrators.compiled` hold: ``rhs`` is called from the member's own body with
  whole work arrays (a callback inside a helper, even an ``inline="always"`` one,
  measured ~40 ns more per helper call).
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
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numba
import numpy as np

from .integrators._dop853_unrolled import dop853_member
from .integrators.compiled import (  # noqa: F401 (re-exported: a member's status, events)
    EPS,
    MAXSTEPS,
    NONFINITE,
    OK,
    UNDERFLOW,
    crosses,
    interpolant_root,
)
from .integrators.kernels import kernels_for
from .integrators.status import Status
from .model import OdeModel

#: a member's integer status -> its spelling: :class:`.integrators.status.Status`, whose
#: ``from_code`` reads a code; kept for ``STATUS_NAMES.get(int(c), ...)``
STATUS_NAMES = {s.code: s.value for s in Status}


@numba.njit(cache=True, nogil=True)
def dop853_ensemble(rhs, m0, m1, stride, Y0, Pm, t0, t_end, rtol, atol, max_steps, comp,
                    direction, terminal, t_eval, slot, Ystore, y_end, t_final, status,
                    counters, events, n_events):
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
            rhs, Y0[m], Pm[m], t0, t_end, rtol, atol, max_steps, comp, direction, terminal,
            events[m], t_eval, Ystore[max(s, 0)], s >= 0, y_end[m], counters[m])
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

    threads = max(1, numba.get_num_threads())

    def members(first: int, m1: int) -> None:
        dop853_ensemble(rhs, first, m1, threads, Y0, Pm, t0, t_end, float(rtol),
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

