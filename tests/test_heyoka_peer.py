"""heyoka as a peer of the work-precision study (``method = "heyoka"``), and the matched-error
comparison against it (:func:`reportgen.core.study.against_peer`) that the report's note and
``reportgen bench``'s table are made from.

heyoka is an optional extra: the tests that run it skip where it is not installed; the
comparison logic and the study without heyoka are tested everywhere."""

from __future__ import annotations

import math

import numpy as np
import pytest

from reportgen.core import study as study_mod
from reportgen.core.integrators import METHODS, heyoka_peer, integrate
from reportgen.core.models import pendulum
from reportgen.support.peers import against_peer


def _row(method, error, wall, tol=math.nan, h=math.nan, status="ok"):
    return {"method": method, "label": method, "tolerance": tol, "h": h, "error_max": error,
            "wall_time_s": wall, "status": status, "compile_time_s": 0.1}


def test_against_peer_takes_our_fastest_run_at_least_as_accurate_and_no_peer_as_ours():
    rows = [
        _row("heyoka", 3e-7, 1.0e-3, tol=1e-6),
        _row("heyoka", 2e-10, 2.0e-3, tol=1e-9),
        _row("heyoka", 5e-15, 4.0e-3, tol=1e-14),       # below the range compared
        _row("heyoka", 1e-3, 0.5e-3, tol=1e-4),         # above it
        _row("dop853", 1e-7, 0.2e-3, tol=1e-8),
        _row("dop853", 1e-10, 0.5e-3, tol=1e-11),
        _row("gauss6", 1e-10, 0.4e-3, h=0.01),          # faster at 2e-10: the match
        _row("dop853", 1e-11, 9e-3, tol=1e-12, status="failed"),
        _row("scipy_dop853", 1e-12, 1e-4, tol=1e-12),   # a peer is never "ours"
    ]
    out = against_peer(rows)
    assert [m["tolerance"] for m in out] == [1e-6, 1e-9]
    first, second = out
    assert first["ours"]["method"] == "dop853" and first["ours"]["tolerance"] == 1e-8
    assert first["ratio"] == pytest.approx(1.0e-3 / 0.2e-3)
    assert second["ours"]["method"] == "gauss6"
    assert second["ratio"] == pytest.approx(2.0e-3 / 0.4e-3)
    # nothing of ours as accurate: ratio 0 and no match
    lone = against_peer([_row("heyoka", 1e-12, 1e-3, tol=1e-12),
                                   _row("dop853", 1e-9, 1e-4, tol=1e-10)])
    assert lone[0]["ours"] is None and lone[0]["ratio"] == 0.0


def test_heyoka_is_a_peer_and_its_ladder_runs_past_scipys_floor():
    m = METHODS["heyoka"]
    assert m.peer and m.adaptive and not m.compiled
    ladder = study_mod.heyoka_tolerances(study_mod.DEFAULT_TOLERANCES)
    assert ladder[: len(study_mod.DEFAULT_TOLERANCES)] == sorted(
        study_mod.DEFAULT_TOLERANCES, reverse=True)
    assert ladder[-2:] == [1e-13, 1e-14]
    assert all(a > b for a, b in zip(ladder, ladder[1:], strict=False))


def test_without_heyoka_the_study_neither_runs_nor_lists_it(monkeypatch):
    monkeypatch.setattr(study_mod, "heyoka_module", lambda: None)
    monkeypatch.setattr(heyoka_peer, "heyoka_module", lambda: None)
    model = pendulum.model(9.81, 1.0)
    t = np.linspace(0.0, 2.0, 21)
    res = study_mod.work_precision(model, np.array([1.0, 0.0]), t, tolerances=(1e-6,),
                                   methods=None, steps=[0.05], repeats=1, budget_s=math.inf)
    assert "heyoka" not in {r["method"] for r in res.rows}
    assert "heyoka" not in res.skipped
    assert not METHODS["heyoka"].fits(model)


def test_heyoka_on_the_pendulum_against_the_elliptic_closed_form():
    pytest.importorskip("heyoka")
    g, l, theta0 = 9.81, 1.0, 1.0
    model = pendulum.model(g, l)
    t = np.linspace(0.0, 10.0, 201)
    exact = np.column_stack(pendulum.exact_solution(t, theta0, 0.0, g, l))  # DLMF 22.19.2
    first = integrate(model, [theta0, 0.0], t, method="heyoka", rtol=1e-12)
    again = integrate(model, [theta0, 0.0], t, method="heyoka", rtol=1e-12)
    assert first.status == "ok" and first.nsteps > 0 and first.nfev == -1
    assert again.compile_time_s == 0.0  # built once per model and tolerance
    np.testing.assert_array_equal(first.y, again.y)  # state and time reset before each run
    assert np.max(np.abs(first.y - exact)) < 1e-10
    loose = integrate(model, [theta0, 0.0], t, method="heyoka", rtol=1e-6)
    err_loose = np.max(np.abs(loose.y - exact))
    assert 1e-10 < err_loose < 1e-4  # the tolerance is honoured, not ignored


def test_the_study_measures_heyoka_and_the_report_note_compares_at_matched_error():
    pytest.importorskip("heyoka")
    from reportgen.scene.report import _heyoka_note

    g, l, theta0 = 9.81, 1.0, 1.0
    model = pendulum.model(g, l)
    t = np.linspace(0.0, 10.0, 201)
    res = study_mod.work_precision(
        model, np.array([theta0, 0.0]), t,
        reference=lambda tt: np.column_stack(pendulum.exact_solution(tt, theta0, 0.0, g, l)),
        methods=["dop853", "heyoka"], tolerances=(1e-6, 1e-9, 1e-12), repeats=1,
        budget_s=math.inf)
    mine = [r for r in res.rows if r["method"] == "heyoka"]
    tols = [r["tolerance"] for r in mine]
    # its ladder, past scipy's floor, until two runs sit at the round-off floor
    assert tols == [1e-6, 1e-9, 1e-12, 1e-13, 1e-14][:len(tols)] and len(tols) >= 4
    assert mine[0]["error_max"] > mine[2]["error_max"]
    assert mine[0]["compile_time_s"] > 0.0
    note = _heyoka_note(res.to_records())
    matched = against_peer(res.rows)
    assert matched and f"at {len(matched)} of its errors" in note
    assert "nan" not in note and "heyoka_" not in note


def test_the_peer_rule_the_report_reads_agrees_with_the_registry():
    from reportgen.support.peers import is_peer

    for name, m in METHODS.items():
        if name != "radau":  # the stiff fallback (scipy's Radau): never a study row
            assert is_peer(name) == m.peer, name


def test_the_bench_table_gives_each_scene_its_worst_ratio_and_a_reason_below_one():
    from reportgen.commands.bench import behind_reason, heyoka_table

    ahead_rows = [_row("heyoka", 1e-8, 2e-4, tol=1e-8), _row("taylor", 5e-9, 1e-4, tol=1e-8)]
    behind_rows = [
        _row("heyoka", 1e-8, 2e-4, tol=1e-8), _row("heyoka", 3e-12, 3e-4, tol=1e-12),
        _row("taylor", 5e-9, 1e-4, tol=1e-8), _row("taylor", 8e-12, 1.5e-4, tol=1e-11),
        _row("taylor", 7e-12, 1.6e-4, tol=1e-12),  # its floor: a decade gained < 2x
        _row("dop853", 2e-12, 9e-4, tol=1e-14), _row("dop853", 1e-7, 1e-4, tol=1e-9)]
    results = [{"scene": "a", "heyoka": against_peer(ahead_rows), "rows": ahead_rows,
                "range": (1e-13, 1e-6)},
               {"scene": "b", "heyoka": against_peer(behind_rows), "rows": behind_rows,
                "range": (1e-13, 1e-6)}]
    lines = []
    table = heyoka_table(results, print=lines.append)
    a, b = table
    assert a["ratio"] == pytest.approx(2.0) and a["reason"] == "" and a["ahead"] == 1
    assert b["ratio"] == pytest.approx(3e-4 / 9e-4) and b["ahead"] == 1
    assert "errors stop at 7.0e-12" in b["reason"] and "dop853 rtol 1e-14" in b["reason"]
    assert any("1 of 2 scenes at or ahead" in line for line in lines)
    # a Taylor run that matches but is slower says so, with both tolerances
    slow = behind_reason(behind_rows, {"error_max": 8e-12, "tolerance": 1e-11, "ratio": 0.8,
                                       "ours": {"method": "taylor", "tolerance": 1e-12,
                                                "h": math.nan}})
    assert "takes 1.25x heyoka's time (tol 1e-11)" in slow
