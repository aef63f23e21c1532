"""Work-precision study: error against wall time for every method that fits a model.

Conventions (DiffEqDevTools): one warm-up run, then the minimum wall time of
``repeats`` runs; compilation is reported separately and never mixed into wall time.
Errors are absolute max-norms of ``y - y_ref``: ``error_max`` over all output times
and components, ``error_final`` over the components at the last output time.

Reference
---------
``reference=None`` uses two independent reference runs, each checked against the
other (their max difference is ``reference_agreement``):

* ``dop853`` (ours) at rtol = 1e-14, atol = 1e-16 -- for every row except ours
  dop853's own;
* ``gauss6`` with a step halved until its estimated error is below 1e-13 (max 5
  halvings; see :func:`_reference_runs`) -- for the ``dop853`` rows, so no method is
  measured against itself.  Where it does not converge (near collisions), the dop853
  reference serves those rows too, and ``reference_kind`` says so.

Both are >= 100x tighter than the default tightest tolerance 1e-12.  scipy's
solvers are not used as references because they clamp rtol >= 100 eps.  They are made
once and reused by every row.

Budget
------
A study costs what it is worth: ``budget_s`` (default 1 s, ``[run] study_budget``) is
the time the timed runs of one study may take together (compile time and the
reference runs not included: a reference is never cut short).  Methods run in order,
ours first; each gets an equal share of what is left, so time one method leaves unused
goes to the next (the scipy peers, ~20 us per right-hand-side call, are last and get
most of it).  A ladder stops before a rung whose predicted cost (the last rung's, times
the growth seen between the last two) would overrun the method's share; repeats are cut
to what the share allows.  A peer's run is stopped once it overruns its share (but
never before ``MIN_PEER_RUN_S``); a peer whose loosest run is stopped has no rows and is
named in ``over_budget``.  Exempt: scipy DOP853 at rtol 1e-10, the baseline every
speed-up in the report is measured against, is run (looser rungs on the way may be
skipped) unless it takes longer than ``TIME_CAP_S``; and our compiled adaptive methods
always run down to rtol 1e-10 (milliseconds).  ``budget_s = inf`` gives the unbudgeted
study (``reportgen bench``), in which a peer's run is still stopped after
``PEER_RUN_CAP_S``.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import os
import platform
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import Protocol

import numpy as np
import scipy

from .integrators import METHODS, integrate
from .integrators.heyoka_peer import heyoka_module, heyoka_version
from .integrators.scipy_peer import PeerTimeLimit

DEFAULT_TOLERANCES = tuple(10.0 ** -k for k in range(4, 13))
#: ``reportgen bench``'s ladder for our adaptive methods: the decades, and quarter decades
#: from 1e-8 to 1e-12, where the run matching scipy DOP853 at rtol 1e-10 lies; in decades
#: the matched run is up to 10x tighter than needed (measured: 1.2-1.3x scipy's evaluations)
FINE_TOLERANCES = tuple(sorted(set(DEFAULT_TOLERANCES)
                               | {10.0 ** (-k / 4) for k in range(32, 49)}, reverse=True))
ATOL_OVER_RTOL = 1e-2
TIME_CAP_S = 1.0  # a run slower than this ends the method's sweep (next one ~2x slower)
DEFAULT_BUDGET_S = 1.0  # timed runs of one study, all methods together
BASELINE = ("scipy_dop853", 1e-10)  # the run every speed-up is measured against
MIN_PEER_RUN_S = 0.2  # a peer's first run may always take this long
#: no peer run goes on longer than this, budget or not: a slower one would end the method's
#: sweep anyway (TIME_CAP_S), and scipy's Radau on a near-collision orbit ran 76 s to fail
PEER_RUN_CAP_S = 10 * TIME_CAP_S
REPEAT_BELOW_S = 0.1  # slower runs are timed once (noise is small relative to their time)
MIN_RTOL = {"scipy_radau": 1e-10, "scipy_lsoda": 1e-12}
HEYOKA = "heyoka"
#: methods a study runs only when asked (``extra_methods``): the Taylor integrator compiles
#: a module per order for each model (cold: 8.6 s for the pendulum, 40 s for three bodies;
#: ~10 ms from numba's cache), too dear for every report's study; ``reportgen bench`` asks
OPT_IN = frozenset({"taylor"})


def heyoka_tolerances(tolerances) -> list[float]:
    """heyoka's ladder: the peers' tolerances, then on in decades to 1e-14 (its Taylor
    order grows with the digits asked for, so its tight end is where it is strongest)."""
    ladder = sorted(tolerances, reverse=True)
    tight = min(ladder, default=1e-4)
    return ladder + [10.0 ** -k for k in range(4, 15) if 10.0 ** -k < tight * (1 - 1e-9)]
SCIPY_FLOOR = 100 * np.finfo(float).eps

_RECORD_DTYPE = np.dtype([
    ("method", "S24"), ("label", "S48"), ("kind", "S8"), ("tolerance", "f8"), ("h", "f8"),
    ("error_final", "f8"), ("error_max", "f8"), ("wall_time_s", "f8"), ("nfev", "i8"),
    ("compile_time_s", "f8"), ("status", "S12"), ("repeats", "i4"),
    ("measured_at", "S20"), ("machine", "S96"), ("cached", "?"), ("message", "S160"),
])
#: the study table's declaration: what each column of ``/study/error_vs_runtime`` holds
RECORD_FIELDS = {
    "method": "the method's registry name", "label": "the method's name as printed",
    "kind": "adaptive or fixed", "tolerance": "rtol (adaptive; atol = 1e-2 rtol), else NaN",
    "h": "the step (fixed-step), else NaN",
    "error_final": "max |y - y_ref| over the components at the last output time",
    "error_max": "max |y - y_ref| over all output times and components",
    "wall_time_s": "minimum wall time over the repeats [s], compile time excluded",
    "nfev": "right-hand-side evaluations", "compile_time_s": "compile time [s]",
    "status": "ok, inaccurate (error_max above ACCURACY_TOLERANCE of the scene's scale: "
              "the table's attrs accuracy_scale, accuracy_scale_what) or failed",
    "repeats": "timed runs", "measured_at": "when (UTC)", "machine": "where",
    "cached": "taken from the peer measurement cache",
    "message": "why a failed row failed (the solver's message), or why it is inaccurate",
}
assert set(RECORD_FIELDS) == set(_RECORD_DTYPE.names)
#: bump when a peer row's meaning changes (invalidates cached peer measurements)
PEER_ROWS_FORMAT = 3  # 2: measured under a study budget; 3: rows carry a message


class RowCache(Protocol):
    """Where measured peer rows are kept between runs (e.g.
    :class:`reportgen.support.cache.PeerCache`)."""

    def get(self, key: str) -> list[dict] | None: ...

    def put(self, key: str, rows: list[dict]) -> None: ...


def machine() -> str:
    """What a measurement was taken on (host, processor, cores)."""
    return (f"{platform.node() or 'unknown host'} ({platform.machine()}, "
            f"{os.cpu_count() or '?'} cores)")[:96]


def measurement_stamp() -> dict:
    """When and where rows measured now were measured (the study table's last columns)."""
    return {"measured_at": datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
            "machine": machine(), "cached": False}


def peer_key(method: str, model, y0, t_eval, grid, y_ref, budget_s: float = math.inf) -> str:
    """The problem a peer's rows measure: model (name, columns, parameters), initial state,
    output grid, tolerance ladder, reference, the study's rules (time cap, budget) and
    library versions."""
    h = hashlib.sha256()
    h.update(json.dumps({"method": method, "model": model.name, "columns": list(model.columns),
                         "grid": [list(g) for g in grid], "time_cap": TIME_CAP_S,
                         "budget": None if math.isinf(budget_s) else budget_s,
                         "repeat_below": REPEAT_BELOW_S, "format": PEER_ROWS_FORMAT,
                         "scipy": scipy.__version__, "numpy": np.__version__,
                         **({"heyoka": heyoka_version()} if method == HEYOKA else {})},
                        sort_keys=True).encode("utf-8"))
    for array in (np.asarray(model.params, dtype=np.float64), y0, t_eval, y_ref):
        h.update(np.ascontiguousarray(array, dtype=np.float64).tobytes())
    return h.hexdigest()


@dataclass
class StudyResult:
    """Rows of the study (one dict per run) and how the reference was made."""

    rows: list[dict]
    reference_kind: str
    reference_agreement: float = math.nan
    #: the largest |value| of the reference (the default accuracy scale)
    reference_size: float = math.nan
    skipped: list[str] = field(default_factory=list)
    #: methods whose first run did not finish within their share of the budget (no rows)
    over_budget: list[str] = field(default_factory=list)

    def to_records(self) -> np.ndarray:
        """Structured array (byte strings, fixed width) ready for an HDF5 table."""
        rec = np.zeros(len(self.rows), dtype=_RECORD_DTYPE)
        for i, row in enumerate(self.rows):
            for name in _RECORD_DTYPE.names:
                value = row.get(name, "") if name == "message" else row[name]
                if isinstance(value, str):  # cut to the column's width, whole characters
                    width = _RECORD_DTYPE[name].itemsize
                    value = value.encode("utf-8")[:width].decode("utf-8", "ignore")
                    value = value.encode("utf-8")
                rec[name][i] = value
        return rec


def judge_records(records: np.ndarray, limit: float, reason) -> int:
    """Mark every "ok" row of a study table (:meth:`StudyResult.to_records`, rows a kind
    added included) whose ``error_max`` exceeds ``limit`` "inaccurate", with ``message``
    = ``reason(error_max)``, in place.  Returns how many rows it marked."""
    ok = np.char.strip(records["status"].astype("S12")) == b"ok"
    err = records["error_max"].astype(float)
    bad = np.flatnonzero(ok & np.isfinite(err) & (err > limit))
    width = records.dtype["message"].itemsize
    for i in bad:
        records["status"][i] = b"inaccurate"
        text = reason(float(err[i])).encode("utf-8")[:width].decode("utf-8", "ignore")
        records["message"][i] = text.encode("utf-8")
    return len(bad)


def reference_run(model, y0, t_eval) -> np.ndarray:
    """The reference-run recipe every kind shares where no closed form exists: compiled
    DOP853 at rtol 1e-14, atol 1e-16 (tighter than scipy allows).  Returns y, shape (N, d)."""
    return integrate(model, y0, t_eval, method="dop853", rtol=1e-14, atol=1e-16,
                     warm_up=False).y


def _reference_runs(model, y0, t_eval):
    """The two references (module docstring).  The gauss6 step is halved until the finer
    run's error -- estimated from the difference of the last two runs, which for an
    order-6 method in its asymptotic regime (the difference itself fell >= 32x) is about
    63x that error -- is below 1e-13 of the solution's size, ``_GAUSS_REF_MAX_HALVINGS``
    times at most.  A run that fails (its Newton iteration diverging at a close approach,
    say) is not compared.
    A gauss6 run that never met the test is no reference (None): at a near collision a
    fixed step does not converge in reach (hamiltonian_two_centres: 14.8 million
    evaluations still 2.3e-4 from the dop853 reference, which scipy converges to).  Not
    budgeted: a reference cut short for time would put a floor under every error."""
    ref_dop = integrate(model, y0, t_eval, method="dop853", rtol=1e-14, atol=1e-16,
                        warm_up=False)
    span = t_eval[-1] - t_eval[0]
    prev = integrate(model, y0, t_eval, method="gauss6", h=2.0 * span / max(ref_dop.nsteps, 1),
                     warm_up=False)
    last_diff = math.inf
    converged = False
    for _ in range(_GAUSS_REF_MAX_HALVINGS):
        # halve the step actually used (a step longer than the output spacing is cut to it)
        cur = integrate(model, y0, t_eval, method="gauss6", h=prev.h / 2.0, warm_up=False)
        ok = prev.status == "ok" and cur.status == "ok"
        diff = float(np.max(np.abs(cur.y - prev.y))) if ok else math.inf
        prev = cur
        if not ok:
            continue
        scale = max(1.0, float(np.max(np.abs(cur.y))))
        asymptotic = diff * 32.0 <= last_diff
        converged = diff <= 1e-13 * scale or (asymptotic and diff / 63.0 <= 1e-13 * scale)
        if converged:
            break
        last_diff = diff
    return ref_dop, (prev if converged else None)


#: halvings of the gauss6 reference's step at most, failed runs included (each doubles its
#: cost: a sixth added 0.8-1.5 s to the near-collision and chaotic scenes, which do not
#: converge in reach anyway)
_GAUSS_REF_MAX_HALVINGS = 5


def _timed(run, repeats: int, allowance: float = math.inf):
    """Warm-up (also compiles), then the min wall time of up to ``repeats`` runs.

    A warm-up slower than ``REPEAT_BELOW_S`` is itself the single timed run
    (compile time is excluded from ``wall_time_s`` in any case); repeats stop before
    they would take more than ``allowance`` seconds.  Returns (solution, compile time,
    timed runs, seconds spent on timed work).
    """
    first = run()
    spent = first.wall_time_s
    if first.wall_time_s >= REPEAT_BELOW_S or repeats < 1:
        return first, first.compile_time_s, 1, spent
    best, n = first, 0
    while n < repeats and (n == 0 or spent + first.wall_time_s <= allowance):
        try:
            sol = run()
        except PeerTimeLimit:  # a repeat slower than the first: keep what was measured
            break
        spent += sol.wall_time_s
        if n == 0 or sol.wall_time_s < best.wall_time_s:
            best = sol
        n += 1
    return best, first.compile_time_s, max(n, 1), spent


class Budget:
    """Seconds of timed runs left for a study, shared out method by method."""

    def __init__(self, total: float):
        self.total = float(total)
        self.spent = 0.0

    def share(self, methods_left: int) -> float:
        """An equal part of what is left for the next of ``methods_left`` methods."""
        return max(self.total - self.spent, 0.0) / max(methods_left, 1)


def predicted_cost(costs: list[float]) -> float:
    """The next rung's cost: the last one's times the growth between the last two
    (between 1.2x and 8x; 4x when only one rung is known)."""
    if not costs:
        return 0.0
    if len(costs) < 2 or costs[-2] <= 0.0:
        return 4.0 * costs[-1]
    return costs[-1] * min(max(costs[-1] / costs[-2], 1.2), 8.0)


def _at_round_off_floor(rows, name) -> bool:
    """The last run of ``name`` below 1e-11 and less than 2x below an earlier one: smaller
    steps only cost time.  The earlier run is the one before it on a fixed-step ladder, and
    on a tolerance ladder the one a decade looser or more (``reportgen bench`` steps in
    quarter decades, where two neighbours are never 2x apart)."""
    mine = [r for r in rows if r["method"] == name]
    if len(mine) < 2 or not mine[-1]["error_max"] < 1e-11:
        return False
    last = mine[-1]
    earlier = mine[-2]
    if math.isfinite(last["tolerance"]):
        looser = [r for r in mine[:-1] if r["tolerance"] >= 10.0 * last["tolerance"] * (1 - 1e-9)]
        if not looser:
            return False
        earlier = looser[-1]
    return last["error_max"] > 0.5 * earlier["error_max"]


def default_steps(model, y0, t_eval) -> np.ndarray:
    """Fixed steps h0 / 2^(k/2), k = 0..11.

    h0 = the mean step of dop853 at rtol 1e-6 (a long step for a low-order method),
    but no longer than the output spacing (longer steps would be cut to it anyway).
    """
    probe = integrate(model, y0, t_eval, method="dop853", rtol=1e-6, atol=1e-8, warm_up=False)
    h0 = (t_eval[-1] - t_eval[0]) / max(probe.nsteps, 1)
    if t_eval.size > 1:
        h0 = min(h0, float(np.min(np.diff(t_eval))))
    return h0 * 2.0 ** (-0.5 * np.arange(12))


def _bound_orbit(model, y0) -> bool:
    """Whether the Kepler orbit through ``y0`` is bound: the regularized methods
    (``needs_kepler``) integrate only those, so an escaping orbit's study leaves them out
    rather than failing on them."""
    from .integrators.policy import _bound_kepler_eccentricity

    return _bound_kepler_eccentricity(model, y0) is not None


def work_precision(model, y0, t_eval, reference=None, methods=None, tolerances=None,
                   steps=None, repeats=3, progress=None, our_tolerances=None,
                   cache: RowCache | None = None,
                   budget_s: float = DEFAULT_BUDGET_S,
                   reference_kind: str = "exact", extra_methods=()) -> StudyResult:
    """Run the work-precision sweep.

    Parameters
    ----------
    model : OdeModel
    y0 : ndarray, shape (d,)
    t_eval : ndarray, shape (N,)
    reference : callable ``t_eval -> ndarray (N, d)`` or None
        Exact solution (or an independent accurate one, named by ``reference_kind``);
        None makes reference runs (see module docstring).
    methods : list of str or None
        Default: every method in ``METHODS`` that fits the model (``radau`` is the
        same solver as the ``scipy_radau`` peer and is left out, and the methods of
        :data:`OPT_IN` are run only when named in ``extra_methods``).
    tolerances : sequence of float
        rtol values for adaptive methods (atol = 1e-2 rtol), loosest first.
    our_tolerances : sequence of float or None
        rtol values for our (not the peers') adaptive methods; default ``tolerances``
        (``reportgen bench``: :data:`FINE_TOLERANCES`).
    steps : sequence of float
        Steps of fixed-step methods, largest first; default :func:`default_steps`.
    repeats : int
        Timed runs after the warm-up (a warm-up slower than 0.1 s is the only run).
    cache : RowCache or None
        Peer (scipy) rows are taken from it when it holds this problem (``cached`` is
        then true and ``measured_at`` / ``machine`` say where they come from) and stored
        in it after measuring.  Our own methods are always measured.
    budget_s : float
        Seconds the timed runs may take together (see the module docstring); ``inf``
        for no budget.

    A method's sweep stops at the first run slower than ``TIME_CAP_S`` or failing, a
    fixed-step sweep once its error stalls at the round-off floor, and any sweep
    before a rung that would overrun its share of the budget.
    """
    y0 = np.asarray(y0, dtype=np.float64)
    t_eval = np.asarray(t_eval, dtype=np.float64)
    tolerances = sorted(DEFAULT_TOLERANCES if tolerances is None else tolerances, reverse=True)
    ours = tolerances if our_tolerances is None else sorted(our_tolerances, reverse=True)
    if methods is None:  # a method for one force law only (levi_civita) is not "skipped";
        # nor is heyoka where it is not installed (an optional extra)
        methods = [n for n, m in METHODS.items()
                   if n != "radau" and not (m.needs_separable and model.separable is None)
                   and (not m.needs_kepler or (m.fits(model) and _bound_orbit(model, y0)))
                   and (n != HEYOKA or heyoka_module() is not None)
                   and (n not in OPT_IN or n in extra_methods)]
    skipped = [n for n in methods if not METHODS[n].fits(model)]
    methods = [n for n in methods if n not in skipped]
    if steps is None and any(not METHODS[n].adaptive for n in methods):
        steps = default_steps(model, y0, t_eval)
    steps = sorted(steps if steps is not None else [], reverse=True)

    if reference is not None:
        y_ref = np.asarray(reference(t_eval), dtype=np.float64)
        refs = {"default": y_ref, "dop853": y_ref}
        agreement = math.nan
    else:
        ref_dop, ref_gauss = _reference_runs(model, y0, t_eval)
        reference_kind = "a reference run, compiled DOP853 at rtol 1e-14 and atol 1e-16"
        if ref_gauss is not None:
            refs = {"default": ref_dop.y, "dop853": ref_gauss.y}
            agreement = float(np.max(np.abs(ref_dop.y - ref_gauss.y)))
            reference_kind += (f" (for the DOP853 rows an independent one, Gauss–Legendre "
                               f"6th order at step {ref_gauss.h:.3g})")
        else:  # better than dop853 rows measured against an unconverged one: said so
            refs = {"default": ref_dop.y}
            agreement = math.nan
            reference_kind += (", also for the DOP853 rows (the independent Gauss–Legendre "
                               "reference did not converge at the steps tried)")

    rows: list[dict] = []
    stamp = measurement_stamp()
    budget = Budget(budget_s)
    for k, name in enumerate(methods):
        m = METHODS[name]
        y_ref = refs.get(name, refs["default"])
        if name == HEYOKA:  # no floor: heyoka goes on past scipy's, as our methods do
            grid = [("rtol", r) for r in heyoka_tolerances(tolerances)]
        elif m.adaptive:
            grid = [("rtol", r) for r in (tolerances if m.peer else ours)
                    if r >= MIN_RTOL.get(name, 0.0) and (not m.peer or r >= SCIPY_FLOOR)]
        else:
            grid = [("h", h) for h in steps]
        key = (peer_key(name, model, y0, t_eval, grid, y_ref, budget_s)
               if m.peer and cache else None)
        stored = cache.get(key) if key is not None else None
        if stored is not None:
            rows.extend({**row, "cached": True} for row in stored)
        else:
            measured = _sweep(model, y0, t_eval, name, grid, y_ref, repeats, stamp, budget,
                              len(methods) - k)
            rows.extend(measured)
            if key is not None:
                cache.put(key, measured)
        if progress is not None:
            progress((k + 1) / len(methods))
    return StudyResult(rows=rows, reference_kind=reference_kind,
                       reference_agreement=agreement, skipped=skipped,
                       reference_size=float(np.max(np.abs(refs["default"]), initial=0.0)),
                       over_budget=[n for n in methods if not any(r["method"] == n
                                                                  for r in rows)])


def _sweep(model, y0, t_eval, name, grid, y_ref, repeats, stamp, budget: Budget,
           methods_left: int) -> list[dict]:
    """The rows of one method over its tolerance or step ladder (see work_precision)."""
    m = METHODS[name]
    allowance = budget.share(methods_left)
    rows: list[dict] = []
    costs: list[float] = []
    spent = 0.0
    seen_h = set()
    for what, value in grid:
        baseline = name == BASELINE[0] and what == "rtol" and math.isclose(value, BASELINE[1])
        before_baseline = name == BASELINE[0] and what == "rtol" and value > BASELINE[1]
        over = bool(costs) and spent + predicted_cost(costs) > allowance
        if over and before_baseline:
            continue  # straight on to the baseline rung
        # our compiled adaptive methods always reach the baseline's tolerance (a few ms),
        # so the matched-error comparison never lacks them
        ours_to_baseline = (m.compiled and what == "rtol"
                            and value >= BASELINE[1] * (1.0 - 1e-9))
        if over and not (baseline or ours_to_baseline):
            break
        kw = dict(rtol=value, atol=value * ATOL_OVER_RTOL) if what == "rtol" else dict(h=value)
        if m.peer:
            # a peer's run is stopped when it overruns its share (the baseline: the cap)
            limit = TIME_CAP_S if baseline else min(max(allowance - spent, 0.0), PEER_RUN_CAP_S)
            run = functools.partial(m.solve, model, y0, t_eval, kw["rtol"], kw["atol"],
                                    time_limit=max(limit, MIN_PEER_RUN_S))
        else:
            # _timed takes the best of repeats after a warm-up run: no rehearsal each
            run = functools.partial(integrate, model, y0, t_eval, method=name, warm_up=False,
                                    **kw)
        try:
            sol, compile_s, n, cost = _timed(run, repeats, max(allowance - spent, 0.0))
        except PeerTimeLimit:
            lost = max(allowance - spent, MIN_PEER_RUN_S)
            spent += lost
            budget.spent += lost
            if before_baseline:
                continue
            break
        spent += cost
        budget.spent += cost
        costs.append(cost / max(n, 1))
        if sol.h is not None:
            if sol.h in seen_h:  # several requested steps cut to the same one
                continue
            seen_h.add(sol.h)
        err = np.abs(sol.y - y_ref)
        rows.append(dict(
            method=name, label=m.label, kind="adaptive" if m.adaptive else "fixed",
            tolerance=value if what == "rtol" else math.nan,
            h=sol.h if sol.h is not None else math.nan,
            error_final=float(np.max(err[-1])), error_max=float(np.max(err)),
            wall_time_s=sol.wall_time_s, nfev=sol.nfev, compile_time_s=compile_s,
            status=sol.status, repeats=n, **stamp,
            message="" if sol.status == "ok" else _failure_reason(sol)))
        if sol.wall_time_s > TIME_CAP_S:
            break
        # a fixed step too long for the method (an implicit method's Newton iteration at
        # the Kepler pericentre, say) is no reason to skip the shorter ones: a fixed-step
        # ladder ends at a failure only once one of its runs succeeded
        if sol.status != "ok" and (m.adaptive or any(r["status"] == "ok" for r in rows)):
            break
        if _at_round_off_floor(rows, name):
            break
    return rows


def _failure_reason(sol) -> str:
    """Why a run failed, for its study row: the solver's message, else its status code."""
    message = str(getattr(sol, "message", "") or "")
    if message and message != "ok":
        return message
    code = getattr(sol, "code", None)
    return str(getattr(code, "value", code) or sol.status)


#: statuses of a row whose error and time were measured (an inaccurate run's error is
#: large, not unknown)
_MEASURED = ("ok", "inaccurate")


def matched_error_speedup(rows, baseline="scipy_dop853", baseline_rtol=1e-10):
    """For each of our methods (the registry's compiled ones and a kind's own rows, such as
    the rigid body's axis splitting), the fastest run at least as accurate as the baseline.

    The baseline is the ``baseline`` run at ``baseline_rtol``; accuracy is ``error_max``.

    Returns
    -------
    dict with ``baseline`` (its row) and ``matches``: one dict per method that reached
    the baseline's error -- method, label, tolerance, h, error_max, wall_time_s and
    ``speedup`` = baseline wall time / this wall time.
    """
    rows = rows.rows if isinstance(rows, StudyResult) else rows
    base = [r for r in rows if r["method"] == baseline and r["status"] in _MEASURED
            and math.isclose(r["tolerance"], baseline_rtol, rel_tol=1e-9)]
    if not base:
        raise ValueError(f"baseline: no ok run of {baseline!r} at rtol={baseline_rtol:g}")
    b = base[0]
    matches = []
    for name in dict.fromkeys(r["method"] for r in rows):
        if name in METHODS and METHODS[name].peer:
            continue  # a kind's own method (the rigid body's splitting2/4) is ours
        good = [r for r in rows if r["method"] == name and r["status"] in _MEASURED
                and r["error_max"] <= b["error_max"]]
        if good:
            best = min(good, key=lambda r: r["wall_time_s"])
            matches.append({key: best[key] for key in
                            ("method", "label", "tolerance", "h", "error_max", "wall_time_s",
                             "nfev")}
                           | {"speedup": b["wall_time_s"] / best["wall_time_s"]})
    matches.sort(key=lambda r: -r["speedup"])
    return {"baseline": b, "matches": matches}

