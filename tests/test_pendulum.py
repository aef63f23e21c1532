"""Pendulum scene against closed forms.

References: exact period T = 4 K(k) sqrt(l/g), k = sin(θ0/2) (DLMF 22.19.4; lecture notes §1);
θ(t) from sin(θ/2) = k sn(K(m) − ω0 t | m), m = k² (DLMF 22.19.2);
linear boundary-value solution (1.21) and its action (2.4).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import special

from conftest import pendulum_text
from reportgen.archive.store import read_archive, write_archive
from reportgen.core.models import pendulum as core
from reportgen.kinds import load_scene
from reportgen.scene.config import parse_config_text


def simulate(text):
    return load_scene(parse_config_text(text)).simulate()


def archived(text, path):
    """Simulate ``text`` and read it back from an archive at ``path``: what a report sees."""
    scene = load_scene(parse_config_text(text))
    write_archive(path, kind=scene.kind, title=scene.title, scene="test", config_text=text,
                  config_sha256="0", results=scene.simulate(),
                  resolved_config=scene.resolved_config())
    return type(scene), read_archive(path)


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
    from reportgen.scene.config import ConfigError

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
    # the unbudgeted study: with the default 1 s budget a slow (shared) machine may
    # rightly stop a peer and name it in over_budget instead (tests/test_study.py)
    results = simulate(pendulum_text(theta=1.0, t_end=5.0, samples=201, study="true",
                                     extra="study_budget = inf\n"))
    study = results.study
    methods = {m.decode() if isinstance(m, bytes) else m for m in study["method"]}
    assert {"dop853", "scipy_dop853", "scipy_rk45", "scipy_radau", "scipy_lsoda"} <= methods
    assert results.study_attrs["reference_kind"] == "exact"
    ok = study["status"] == (b"ok" if isinstance(study["status"][0], bytes) else "ok")
    assert np.all(np.isfinite(study["error_max"][ok]))


def test_archive_holds_the_curves_the_report_draws(tmp_path):
    theta0 = 1.2
    w0 = math.sqrt(9.81)
    kind, data = archived(pendulum_text(theta=theta0, t_end=6.0, samples=601), tmp_path / "a.h5")
    a, run = data.analysis, data.runs["main"]
    # period curve T(θ0) = 4 K(sin²(θ0/2)) / ω0 (DLMF 22.19.4), sampled over 0 < θ0 < π
    curve = a["period_curve"]
    assert curve["amplitude"][0] > 0 and curve["amplitude"][-1] < math.pi
    assert np.allclose(curve["period"], 4 * special.ellipk(np.sin(curve["amplitude"] / 2) ** 2)
                       / w0, rtol=1e-14, atol=0)
    assert a["amplitude"] == pytest.approx(theta0, rel=1e-14)  # released from rest
    # reference: sin(θ/2) = k sn(K(m) − ω0 t | m) (DLMF 22.19.2), released-from-rest form
    m = math.sin(theta0 / 2) ** 2
    sn, cn, _, _ = special.ellipj(special.ellipk(m) - w0 * run.t, m)
    assert np.max(np.abs(run.reference["theta"] - 2 * np.arcsin(math.sqrt(m) * sn))) < 1e-12
    assert np.max(np.abs(run.reference["theta_dot"] + 2 * math.sqrt(m) * w0 * cn)) < 1e-11
    assert run.attrs["reference_label"] == "exact (Jacobi sn)"
    # small-angle solution (1.19): θ0 cos ω0 t
    small = a["small_angle_solution"]
    assert np.allclose(small["theta"], theta0 * np.cos(w0 * run.t), rtol=0, atol=1e-14)
    # phase portrait: level sets of θ̇²/2 − ω0² cos θ, separatrix at ω0² (E = m g l)
    pp = a["phase_portrait"]
    TH, THD = np.meshgrid(pp["theta"], pp["theta_dot"])
    assert np.allclose(pp["energy"], 0.5 * THD**2 - 9.81 * np.cos(TH), rtol=0, atol=1e-12)
    assert pp["separatrix"] == pytest.approx(9.81, rel=1e-15)
    assert pp["theta_dot"][-1] >= np.max(np.abs(run["theta_dot"]))
    # no boundary problem configured: the report leaves its section out
    assert "boundary_value" not in kind.default_sections(data)
    assert kind.section_period(data).figures and kind.section_time_series(data).figures


def test_rotation_archive_has_no_libration_curves(tmp_path):
    text = pendulum_text(theta=0.0, t_end=4.0, samples=801).replace(
        "theta = 0.0", "theta = 0.0\ntheta_dot = 7.0")
    kind, data = archived(text, tmp_path / "r.h5")
    assert data.analysis["motion"] == "rotation"
    assert "small_angle_solution" not in data.analysis and "amplitude" not in data.analysis
    content = kind.section_period(data)
    assert any("rotates" in n for n in content.notes)


def test_reference_run_where_the_elliptic_form_is_unresolved(tmp_path):
    # θ0 = π − 1e-5: 1 − k² = sin²(5e-6) = 2.5e-11, below EXACT_SOLUTION_MIN_M1
    theta0 = math.pi - 1e-5
    assert core.complementary_parameter(theta0, 0.0, math.sqrt(9.81)) < core.EXACT_SOLUTION_MIN_M1
    kind, data = archived(pendulum_text(theta=theta0, t_end=1.5, samples=301), tmp_path / "s.h5")
    run = data.runs["main"]
    assert run.attrs["reference_label"] == "reference run (DOP853, rtol 1e-14)"
    # lingering at the top: θ stays within 1e-3 of π for 1.5 s (δ cosh ω0 t < 1e-3)
    assert np.max(np.abs(run.reference["theta"] - math.pi)) < 1e-3
    assert np.max(np.abs(run["theta"] - run.reference["theta"])) < 1e-6
    assert "small_angle_solution" in data.analysis
    assert kind.section_time_series(data).figures


def test_boundary_value_section_from_the_archive(tmp_path):
    text = pendulum_text(t_end=2.0, samples=101, extra="""
        [boundary]
        theta0 = 0.3
        theta1 = -0.2
        T = 2.5
        """)
    kind, data = archived(text, tmp_path / "b.h5")
    assert "boundary_value" in kind.default_sections(data)
    content = kind.section_boundary_value(data)
    # the report's one number rule: 6 significant figures (reportgen.scene.content.fmt)
    exact = data.analysis["boundary_value"]["action_exact"]
    assert content.tables[0].rows[0][1] == f"{exact:.6g}"
