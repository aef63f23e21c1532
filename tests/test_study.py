"""Work-precision study on the pendulum (exact solution: DLMF 22.19.2, see pendulum.py)."""

import numpy as np
import pytest

from reportgen.core.integrators import METHODS
from reportgen.core.models import pendulum
from reportgen.core.study import matched_error_speedup, work_precision

G, L, THETA0 = 9.81, 1.0, 1.0
T = pendulum.exact_period(THETA0, 0.0, G, L)
T_EVAL = np.linspace(0.0, 2 * T, 201)
Y0 = np.array([THETA0, 0.0])
METHODS_SMALL = ["dop853", "rk45", "yoshida6", "gauss6", "scipy_dop853", "scipy_rk45",
                 "scipy_lsoda", "scipy_radau"]


def exact(t):
    return np.column_stack(pendulum.exact_solution(t, THETA0, 0.0, G, L))


@pytest.fixture(scope="module")
def study():
    return work_precision(pendulum.model(G, L), Y0, T_EVAL, reference=exact,
                          methods=METHODS_SMALL, tolerances=[1e-6, 1e-8, 1e-10, 1e-12],
                          steps=[T / 50, T / 100], repeats=1)


def test_rows_for_ours_and_peers(study):
    assert study.reference_kind == "exact"
    names = {r["method"] for r in study.rows}
    assert names == set(METHODS_SMALL)
    for r in study.rows:
        assert r["status"] == "ok"
        assert np.isfinite(r["error_max"]) and np.isfinite(r["error_final"])
        assert r["error_final"] <= r["error_max"]
        assert r["wall_time_s"] > 0 and r["nfev"] > 0
        assert (r["kind"] == "adaptive") == METHODS[r["method"]].adaptive
        assert np.isnan(r["h"]) != np.isnan(r["tolerance"])
    dop = [r["error_max"] for r in study.rows if r["method"] == "dop853"]
    assert dop[0] > dop[1] > dop[2]


def test_records_are_a_structured_array(study):
    rec = study.to_records()
    assert rec.dtype.names[:2] == ("method", "label")
    assert rec.dtype["method"].kind == "S"  # h5py stores fixed-width bytes directly
    assert len(rec) == len(study.rows)


def test_matched_error_speedup(study):
    out = matched_error_speedup(study, baseline="scipy_dop853", baseline_rtol=1e-10)
    assert out["baseline"]["method"] == "scipy_dop853"
    best = {m["method"]: m for m in out["matches"]}
    assert "dop853" in best
    assert best["dop853"]["error_max"] <= out["baseline"]["error_max"]
    assert best["dop853"]["speedup"] > 1.0


def test_reference_run_and_method_filter():
    from test_integrators import DAMPED  # non-separable model

    res = work_precision(DAMPED, np.array([1.0, 0.0]), np.linspace(0.0, 3.0, 31),
                         methods=["dop853", "verlet", "gauss4"], tolerances=[1e-8],
                         steps=[0.05], repeats=1)
    assert res.reference_kind.startswith("reference run: dop853 rtol=1e-14")
    assert res.skipped == ["verlet"]
    assert {r["method"] for r in res.rows} == {"dop853", "gauss4"}
    assert res.reference_agreement < 1e-11
