"""Work-precision study on the pendulum (exact solution: DLMF 22.19.2, see pendulum.py)."""

import math

import numpy as np
import pytest

from reportgen.core.integrators import METHODS
from reportgen.core.integrators.heyoka_peer import heyoka_module
from reportgen.core.models import pendulum
from reportgen.core.study import OPT_IN, matched_error_speedup, work_precision

G, L, THETA0 = 9.81, 1.0, 1.0
T = pendulum.exact_period(THETA0, 0.0, G, L)
T_EVAL = np.linspace(0.0, 2 * T, 201)
Y0 = np.array([THETA0, 0.0])
#: what the study runs by default on a separable model: ours and the scipy peers
#: (``radau``, the pipeline's stiff fallback, is the same solver as ``scipy_radau``)
#: and heyoka where it is installed (an optional extra)
STUDIED = {n for n, m in METHODS.items() if m.compiled or m.peer
           if n != "heyoka" or heyoka_module() is not None} - set(OPT_IN)


def exact(t):
    return np.column_stack(pendulum.exact_solution(t, THETA0, 0.0, G, L))


@pytest.fixture(scope="module")
def study():
    return work_precision(pendulum.model(G, L), Y0, T_EVAL, reference=exact,
                          tolerances=[1e-6, 1e-8, 1e-10, 1e-12], steps=[T / 100, T / 200],
                          repeats=1, budget_s=math.inf)  # every method's rows, however busy


def test_rows_for_ours_and_peers(study):
    assert study.reference_kind == "exact"
    names = {r["method"] for r in study.rows}
    assert names == STUDIED
    for r in study.rows:
        assert r["status"] == "ok"
        assert np.isfinite(r["error_max"]) and np.isfinite(r["error_final"])
        assert r["error_final"] <= r["error_max"]
        # heyoka counts steps, not evaluations: nfev -1 (heyoka_peer's docstring)
        assert r["wall_time_s"] > 0 and (r["nfev"] > 0 or r["method"] == "heyoka")
        assert (r["kind"] == "adaptive") == METHODS[r["method"]].adaptive
        assert np.isnan(r["h"]) != np.isnan(r["tolerance"])
    for name in [n for n in STUDIED if METHODS[n].compiled]:
        # rows are loosest first: the error falls with the tolerance / step (ours only:
        # scipy clamps rtol and its dense output limits its tightest runs)
        errs = [r["error_max"] for r in study.rows if r["method"] == name]
        assert len(errs) >= 2 and errs[0] > errs[1], (name, errs)
    dop = [r["error_max"] for r in study.rows if r["method"] == "dop853"]
    assert dop[0] > dop[1] > dop[2]


def test_records_are_a_structured_array(study):
    rec = study.to_records()
    assert rec.dtype.names[:2] == ("method", "label")
    assert rec.dtype["method"].kind == "S"  # h5py stores fixed-width bytes directly
    assert len(rec) == len(study.rows)


def test_method_labels_keep_their_typography_through_the_archive_table(study, tmp_path):
    # Labels are UTF-8 in the fixed-width byte fields ("Störmer–Verlet", en dashes in
    # "Gauss–Legendre"): they must fit the field and come back as written.
    import h5py

    from reportgen.archive.h5io import read_table, table

    assert METHODS["verlet"].label.startswith("Störmer–Verlet")
    width = study.to_records().dtype["label"].itemsize
    assert all(len(m.label.encode("utf-8")) <= width for m in METHODS.values())
    with h5py.File(tmp_path / "t.h5", "w") as f:
        table(f, "study", study.to_records())
    with h5py.File(tmp_path / "t.h5", "r") as f:
        back = read_table(f["study"])
    assert sorted(set(back["label"])) == sorted({r["label"] for r in study.rows})
    assert "Störmer–Verlet (numba)" in set(back["label"])


def test_matched_error_speedup(study):
    # wall times are measurements: check the bookkeeping, not which method is faster
    out = matched_error_speedup(study, baseline="scipy_dop853", baseline_rtol=1e-10)
    base = out["baseline"]
    assert base["method"] == "scipy_dop853" and base["tolerance"] == 1e-10
    best = {m["method"]: m for m in out["matches"]}
    assert "dop853" in best
    assert not any(METHODS[name].peer for name in best)
    speedups = [m["speedup"] for m in out["matches"]]
    assert speedups == sorted(speedups, reverse=True)
    for name, m in best.items():
        assert set(m) == {"method", "label", "tolerance", "h", "error_max", "wall_time_s",
                          "nfev", "speedup"}
        assert m["error_max"] <= base["error_max"]
        assert np.isfinite(m["speedup"]) and m["speedup"] > 0
        assert m["speedup"] == pytest.approx(base["wall_time_s"] / m["wall_time_s"])
        # the fastest of the method's runs that reach the baseline's error
        runs = [r for r in study.rows if r["method"] == name and r["status"] == "ok"
                and r["error_max"] <= base["error_max"]]
        assert m["wall_time_s"] == min(r["wall_time_s"] for r in runs)


def test_reference_run_and_method_filter():
    from test_integrators import DAMPED  # non-separable model

    res = work_precision(DAMPED, np.array([1.0, 0.0]), np.linspace(0.0, 3.0, 31),
                         methods=["dop853", "verlet", "gauss4"], tolerances=[1e-8],
                         steps=[0.05], repeats=1)
    assert res.reference_kind.startswith("a reference run, compiled DOP853 at rtol 1e-14")
    assert res.skipped == ["verlet"]
    assert {r["method"] for r in res.rows} == {"dop853", "gauss4"}
    assert res.reference_agreement < 1e-11


def test_budget_cuts_ladders_but_keeps_every_method_and_the_baseline():
    """A (nearly) zero budget: every method still gets its first rung, scipy DOP853 still
    reaches the rtol-1e-10 baseline and our adaptive methods its tolerance, and no other
    ladder goes past its first rung."""
    model = pendulum.model(G, L)
    tolerances = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12]
    kw = dict(reference=exact, tolerances=tolerances, steps=[T / 50, T / 100, T / 200],
              repeats=2)
    tight = work_precision(model, Y0, T_EVAL, budget_s=1e-9, **kw)
    free = work_precision(model, Y0, T_EVAL, budget_s=float("inf"), **kw)
    per_method = {}
    for r in tight.rows:
        per_method.setdefault(r["method"], []).append(r)
    assert set(per_method) == STUDIED
    for name, rows in per_method.items():
        if name == "scipy_dop853":
            # the first rung, then straight on to the baseline
            assert [r["tolerance"] for r in rows] == [1e-4, 1e-10]
        elif METHODS[name].compiled and METHODS[name].adaptive:
            # ours always reach the baseline's tolerance (milliseconds), not beyond
            assert [r["tolerance"] for r in rows] == [1e-4, 1e-6, 1e-8, 1e-10]
        else:
            assert len(rows) == 1, (name, rows)
            assert rows[0]["repeats"] == 1  # no time left for repeats either
    assert matched_error_speedup(tight)["baseline"]["tolerance"] == 1e-10
    assert len(free.rows) > len(tight.rows)
    assert {r["method"] for r in free.rows if r["tolerance"] == 1e-12} >= {"dop853", "rk45"}


def test_peer_cache_key_depends_on_the_budget():
    from reportgen.core.study import peer_key

    args = ("scipy_dop853", pendulum.model(G, L), Y0, T_EVAL, [("rtol", 1e-6)], exact(T_EVAL))
    assert peer_key(*args, 1.0) != peer_key(*args, 2.0)
    assert peer_key(*args, 1.0) == peer_key(*args, 1.0)


def test_peer_runs_over_their_share_are_stopped_and_named(monkeypatch):
    """A peer whose loosest run overruns its share is stopped (no row) and listed in
    ``over_budget``; the baseline peer keeps the full time cap."""
    import reportgen.core.study as study_mod

    monkeypatch.setattr(study_mod, "MIN_PEER_RUN_S", 0.0)
    t_eval = np.linspace(0.0, 20 * T, 401)
    res = work_precision(pendulum.model(G, L), Y0, t_eval, reference=exact,
                         methods=["dop853", "scipy_rk45", "scipy_dop853"],
                         tolerances=[1e-4, 1e-10], repeats=1, budget_s=1e-9)
    assert res.over_budget == ["scipy_rk45"]
    assert {r["method"] for r in res.rows} == {"dop853", "scipy_dop853"}
    assert matched_error_speedup(res)["baseline"]["tolerance"] == 1e-10


def test_peer_time_limit():
    from reportgen.core.integrators.scipy_peer import PeerTimeLimit, ScipyRK45

    t_eval = np.linspace(0.0, 20 * T, 401)
    with pytest.raises(PeerTimeLimit):
        ScipyRK45().solve(pendulum.model(G, L), Y0, t_eval, 1e-10, 1e-12, time_limit=0.0)
    sol = ScipyRK45().solve(pendulum.model(G, L), Y0, t_eval, 1e-6, 1e-8, time_limit=60.0)
    assert sol.status == "ok"


def test_matched_error_speedup_counts_a_kinds_own_method(study):
    """A kind's own rows (the rigid body's axis splitting, not in the registry) are ours:
    counted, not a KeyError (``reportgen bench`` failed on the rigid-body scenes)."""
    base = matched_error_speedup(study)["baseline"]
    own = {**base, "method": "splitting2", "label": "axis splitting, order 2",
           "error_max": base["error_max"] / 2, "wall_time_s": base["wall_time_s"] / 100}
    out = matched_error_speedup([*study.rows, own])
    best = {m["method"]: m for m in out["matches"]}
    assert best["splitting2"]["speedup"] == pytest.approx(100.0)


def test_our_tolerances_refine_our_ladder_only():
    """``reportgen bench``'s ladder: our adaptive methods run the quarter decades around
    the baseline, the peers keep the decades (the baseline stays at rtol 1e-10)."""
    from reportgen.core.study import FINE_TOLERANCES

    assert {1e-8, 10 ** -8.25, 10 ** -10.5, 1e-12} <= set(FINE_TOLERANCES)
    res = work_precision(pendulum.model(G, L), Y0, T_EVAL, reference=exact,
                         methods=["dop853", "scipy_dop853"], tolerances=[1e-8, 1e-10],
                         our_tolerances=[1e-8, 10 ** -8.5, 1e-9, 10 ** -9.5, 1e-10],
                         repeats=1, budget_s=float("inf"))
    ladder = {n: [r["tolerance"] for r in res.rows if r["method"] == n]
              for n in ("dop853", "scipy_dop853")}
    assert ladder["scipy_dop853"] == [1e-8, 1e-10]
    assert ladder["dop853"] == [1e-8, 10 ** -8.5, 1e-9, 10 ** -9.5, 1e-10]
    # a finer ladder can only lower the matched run's cost: the quarter decades' errors
    # fall between the decades'
    errors = [r["error_max"] for r in res.rows if r["method"] == "dop853"]
    assert errors == sorted(errors, reverse=True)


def test_unconverged_gauss_reference_gives_way_to_the_dop853_one(monkeypatch):
    """With no gauss6 run meeting its convergence test (here: no halving allowed) the
    dop853 rows are measured against the dop853 reference, finite, and the reference
    says so; before, an unconverged or failed gauss6 run was used (hamiltonian_two_centres:
    every dop853 error was nan, and our best match was rk45 at 30x)."""
    from reportgen.core import study as study_module

    monkeypatch.setattr(study_module, "_GAUSS_REF_MAX_HALVINGS", 0)
    res = work_precision(pendulum.model(G, L), Y0, T_EVAL, methods=["dop853", "rk45"],
                         tolerances=[1e-6, 1e-8], repeats=1)
    assert "also for the DOP853 rows" in res.reference_kind
    errors = [r["error_max"] for r in res.rows if r["method"] == "dop853"]
    assert errors and all(0 < e < 1e-4 for e in errors)
    assert np.isnan(res.reference_agreement)
    # and converged, it is the independent reference (the default)
    monkeypatch.undo()
    res = work_precision(pendulum.model(G, L), Y0, T_EVAL, methods=["dop853"],
                         tolerances=[1e-8], repeats=1)
    assert "Gauss–Legendre 6th order at step" in res.reference_kind and res.reference_agreement < 1e-11


def test_a_fixed_step_ladder_goes_on_past_steps_too_long_for_the_method():
    """Gauss collocation's Newton iteration fails at the pericentre of an e = 0.95 Kepler
    orbit with the longest steps of the ladder; the shorter steps still run (the ladder
    used to end at its first rung and the study showed the method as failed)."""
    import math

    from reportgen.core.models import kepler

    e = 0.95
    y0 = np.array([1.0 - e, 0.0, 0.0, math.sqrt((1.0 + e) / (1.0 - e))])
    t = np.linspace(0.0, 2.0 * math.pi, 51)
    el = kepler.orbital_elements(*y0, 1.0)
    res = work_precision(kepler.model(1.0, 1.0), y0, t, methods=["gauss6"], repeats=1,
                         reference=lambda ts: np.column_stack(kepler.kepler_state(ts, el)),
                         steps=[0.2, 0.1, 0.05, 0.02, 0.01, 0.005], budget_s=math.inf)
    status = [r["status"] for r in res.rows]
    assert status[0] == "failed" and "ok" in status, status
    first_ok = status.index("ok")
    assert all(s == "failed" for s in status[:first_ok])
    ok = [r for r in res.rows if r["status"] == "ok"]
    assert ok[-1]["error_max"] < ok[0]["error_max"]
