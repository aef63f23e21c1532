"""The user cache of peer (scipy) measurements: keyed by the problem, bypassable,
inspectable, and the report says when rows come from it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from conftest import pendulum_text
from reportgen.core.models import pendulum
from reportgen.core.study import work_precision
from reportgen.support.cache import NO_CACHE_ENV, PeerCache

G, L, THETA0 = 9.81, 1.0, 1.0
TOLERANCES = (1e-6, 1e-8)
METHODS = ["dop853", "scipy_dop853", "scipy_rk45"]


def _study(cache, t_end=2.0, theta0=THETA0):
    t = np.linspace(0.0, t_end, 51)
    exact = lambda ts: np.column_stack(pendulum.exact_solution(ts, theta0, 0.0, G, L))  # noqa: E731
    return work_precision(pendulum.model(G, L), np.array([theta0, 0.0]), t, reference=exact,
                          methods=METHODS, tolerances=TOLERANCES, repeats=1, cache=cache,
                          budget_s=math.inf)  # no peer stopped on a slow, shared machine


def _by_method(result, method):
    return [r for r in result.rows if r["method"] == method]


def test_peer_rows_are_measured_once_and_reused(tmp_path):
    cache = PeerCache(tmp_path)
    first = _study(cache)
    assert len(cache.entries()) == 2  # one entry per peer method; ours are not cached
    assert not any(r["cached"] for r in first.rows)
    second = _study(cache)
    for peer in ("scipy_dop853", "scipy_rk45"):
        old, new = _by_method(first, peer), _by_method(second, peer)
        assert new and all(r["cached"] for r in new)
        for a, b in zip(old, new, strict=True):
            assert b["error_max"] == a["error_max"] and b["wall_time_s"] == a["wall_time_s"]
            assert b["measured_at"] == a["measured_at"] and b["machine"] == a["machine"]
    ours = _by_method(second, "dop853")
    assert ours and not any(r["cached"] for r in ours)  # re-timed every run
    records = second.to_records()
    assert records["cached"].sum() == sum(len(_by_method(second, p))
                                          for p in ("scipy_dop853", "scipy_rk45"))


@pytest.mark.parametrize("change", [{"t_end": 3.0}, {"theta0": 0.5}])
def test_another_problem_is_a_miss(tmp_path, change):
    cache = PeerCache(tmp_path)
    _study(cache)
    other = _study(cache, **change)
    assert not any(r["cached"] for r in other.rows)
    assert len(cache.entries()) == 4


def test_a_corrupt_entry_is_a_miss_and_is_replaced(tmp_path):
    cache = PeerCache(tmp_path)
    _study(cache)
    for path in cache.entries():
        path.write_text("{not json")
    again = _study(cache)
    assert not any(r["cached"] for r in again.rows)
    assert all(cache.get(p.stem) for p in cache.entries())


def test_rows_survive_the_json_round_trip(tmp_path):
    cache = PeerCache(tmp_path)
    rows = [{"method": "scipy_rk45", "tolerance": 1e-6, "h": math.nan, "error_max": 1e-7}]
    cache.put("k", rows)
    back = cache.get("k")
    assert back[0]["method"] == "scipy_rk45" and math.isnan(back[0]["h"])


def test_cache_command_and_no_cache_flag(write_config, tmp_path, cli, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    monkeypatch.delenv(NO_CACHE_ENV, raising=False)
    config = write_config("pend", pendulum_text(t_end=2.0, samples=101, study="true"))
    out = tmp_path / "out"
    code, _, err = cli("run", config, "--out", out, "--jobs", "1", "--format", "html",
                       "--no-cache")
    assert code == 0, err
    assert not PeerCache(tmp_path / "xdg" / "reportgen").entries()
    monkeypatch.delenv(NO_CACHE_ENV, raising=False)  # --no-cache set it for this process
    assert cli("run", config, "--out", out, "--jobs", "1", "--format", "html",
               "--force")[0] == 0
    entries = PeerCache(tmp_path / "xdg" / "reportgen").entries()
    assert entries
    html = (out / "pend" / "report.html").read_text(encoding="utf-8")
    assert "peer measurement cache" not in html  # measured in this run
    assert cli("run", config, "--out", out, "--jobs", "1", "--format", "html",
               "--force")[0] == 0
    html = (out / "pend" / "report.html").read_text(encoding="utf-8")
    assert "taken from the peer measurement cache" in html
    code, text, _ = cli("cache", "info")
    assert code == 0 and f"{len(entries)} entries" in text and "measured between" in text
    code, text, _ = cli("cache", "clear")
    assert code == 0 and f"removed {len(entries)} entries" in text
    assert not PeerCache(tmp_path / "xdg" / "reportgen").entries()
