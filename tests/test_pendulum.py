"""Pendulum scene against closed forms.

References: exact period T = 4 K(k) sqrt(l/g), k = sin(θ0/2) (DLMF 22.19.4; lecture notes §1);
θ(t) from sin(θ/2) = k sn(K(m) − ω0 t | m), m = k² (DLMF 22.19.2; FIELD-NOTES);
linear boundary-value solution (1.21) and its action (2.4).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import special

from conftest import pendulum_text
from reportgen.config import parse_config_text
from reportgen.core.models import pendulum as core
from reportgen.scenes import load_scene


def simulate(text):
    return load_scene(parse_config_text(text)).simulate()


@pytest.mark.parametrize("theta0", [0.2, 1.0, 2.5])
def test_period_and_trajectory_against_elliptic_solution(theta0):
    results = simulate(pendulum_text(theta=theta0, t_end=30.0, samples=3001))
    a = results.analysis
    exact_period = 4 * special.ellipk(math.sin(theta0 / 2) ** 2) * math.sqrt(1.0 / 9.81)
    assert a["period"] == pytest.approx(exact_period, rel=1e-14)
    assert abs(a["period_measured"] / exact_period - 1) <= 1e-10
    run = results.runs["main"]
    # the released-from-rest form, independent of exact_solution's general-phase code
    m = math.sin(theta0 / 2) ** 2
    sn, _, _, _ = special.ellipj(special.ellipk(m) - math.sqrt(9.81) * run.t, m)
    theta_exact = 2 * np.arcsin(math.sqrt(m) * sn)
    assert np.max(np.abs(run["theta"] - theta_exact)) <= 1e-9
    assert results.status == "ok"


def test_rotating_pendulum_period():
    results = simulate(pendulum_text(theta=0.0, t_end=10.0, samples=2001).replace(
        "theta = 0.0", "theta = 0.0\ntheta_dot = 7.0"))
    a = results.analysis
    assert a["motion"] == "rotation"
    k2 = (7.0 / (2 * math.sqrt(9.81))) ** 2
    # time per revolution 2K(1/k²)/(k ω0) (DLMF 22.19.7)
    assert a["period"] == pytest.approx(2 * special.ellipk(1 / k2) / (math.sqrt(k2 * 9.81)),
                                        rel=1e-14)
    assert abs(a["period_measured"] / a["period"] - 1) <= 1e-9


def test_exact_solution_general_phase_matches_integration_from_midswing():
    # start from a state with both θ and θ̇ non-zero: the phase u0 must be found correctly
    from reportgen.core.integrators import integrate

    t = np.linspace(0.0, 10.0, 501)
    for th0, thd0 in [(0.7, -1.9), (-2.0, 1.0), (0.3, 6.5)]:
        sol = integrate(core.model(9.81, 1.0), np.array([th0, thd0]), t, method="dop853",
                        rtol=1e-13, atol=1e-14)
        th, thd = core.exact_solution(t, th0, thd0, 9.81, 1.0)
        assert np.max(np.abs(sol.y[:, 0] - th)) < 1e-9
        assert np.max(np.abs(sol.y[:, 1] - thd)) < 1e-8


def test_boundary_value_action_against_closed_form():
    text = pendulum_text(t_end=2.0, samples=101, extra="""
        [boundary]
        theta0 = 0.3
        theta1 = -0.2
        T = 2.5
        """)
    bvp = simulate(text).analysis["boundary_value"]
    w, M, T = math.sqrt(9.81), 1.0, 2.5
    # S = M ω [(θ0² + θ1²) cos ωT − 2 θ0 θ1] / (2 sin ωT)   (2.4 on 1.21)
    closed = M * w * ((0.09 + 0.04) * math.cos(w * T) - 2 * 0.3 * -0.2) / (2 * math.sin(w * T))
    assert bvp["action_exact"] == pytest.approx(closed, rel=1e-14)
    assert abs(bvp["action_numeric"] / closed - 1) < 1e-8
    assert bvp["theta_exact"][0] == pytest.approx(0.3) and bvp["theta_exact"][-1] == pytest.approx(-0.2)
    assert np.max(np.abs(bvp["theta_numeric"] - bvp["theta_exact"])) < 1e-8


def test_conjugate_point_is_rejected():
    from reportgen.config import ConfigError

    T = math.pi / math.sqrt(9.81)  # sin(ω T) = 0: no unique linear solution
    with pytest.raises(ConfigError, match="boundary.T"):
        load_scene(parse_config_text(pendulum_text(extra=f"""
            [boundary]
            theta0 = 0.1
            theta1 = 0.2
            T = {T!r}
            """)))


def test_energy_is_conserved_and_status_ok():
    results = simulate(pendulum_text(theta=2.0, t_end=20.0, samples=1001))
    run = results.runs["main"]
    assert run.attrs["drift_energy"] < 1e-10
    assert run.status == "ok"


def test_study_has_exact_reference_and_peers():
    results = simulate(pendulum_text(theta=1.0, t_end=5.0, samples=201, study="true"))
    study = results.study
    methods = {m.decode() if isinstance(m, bytes) else m for m in study["method"]}
    assert {"dop853", "scipy_dop853", "scipy_rk45", "scipy_radau", "scipy_lsoda"} <= methods
    assert results.study_attrs["reference_kind"] == "exact"
    ok = study["status"] == (b"ok" if isinstance(study["status"][0], bytes) else "ok")
    assert np.all(np.isfinite(study["error_max"][ok]))
