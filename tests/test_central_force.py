"""central_force against closed forms.

References: Kepler's equation E − e sin E = M and the perifocal position a(cos E − e),
b sin E (Danby, *Fundamentals of Celestial Mechanics* §6.3–6.6); third law T = 2π√(a³/(k/μ))
(notes 3.31); LRL vector |A| = μ k e (Goldstein eq. 3.82–3.83); exact apsidal angle
π/√(1 − 2με/L²) for V = −k/r − ε/r² (Landau & Lifshitz §15 problem 3); near-circular
apsidal angle π/√(2 − n) for V = −k/rⁿ (Landau & Lifshitz §14 problem 2).
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

from reportgen.core.models import kepler as core
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, parse_config_text

KEPLER_E07 = "x = 0.3\ny = 0.0\nvx = 0.0\nvy = 2.3804761428476167"
RUN_E07 = "t_end = 62.83185307179586\nsamples = 4001\nrtol = 1e-13\natol = 1e-15"


def text(params="", initial="", run="", extra=""):
    initial, run = initial or KEPLER_E07, run or RUN_E07
    return textwrap.dedent(f"""
        kind = "central_force"
        [params]
        m1 = 1.0
        m2 = 1.0
        k = 0.5
        {params}
        [initial]
        {initial}
        [run]
        study = false
        {run}
        """) + extra


def simulate(t):
    return load_scene(parse_config_text(t)).simulate()


def test_kepler_e07_positions_period_elements():
    r = simulate(text())
    a = r.analysis
    # e = 0.7, a = 1, T = 2π for k/μ = 1, r_peri = 0.3, v_peri = √(1.7/0.3) (vis-viva)
    assert a["eccentricity"] == pytest.approx(0.7, abs=1e-14)
    assert a["semi_major_axis"] == pytest.approx(1.0, rel=1e-14)
    assert a["period"] == pytest.approx(2 * math.pi, rel=1e-14)
    assert a["kepler_position_error_max"] <= 1e-9
    assert abs(a["period_measured"] / (2 * math.pi) - 1) < 1e-10
    assert abs(a["semi_major_axis_measured"] - 1.0) < 1e-10
    assert a["lrl_eccentricity_drift"] < 1e-10
    assert r.status == "ok"
    # independent of kepler_state: at t = T/2 the body is at apocentre (−1.7, 0)
    run = r.runs["main"]
    i = int(np.argmin(np.abs(run.t - math.pi)))
    assert run.t[i] == pytest.approx(math.pi, abs=1e-12)
    assert run["x"][i] == pytest.approx(-1.7, abs=1e-9) and abs(run["y"][i]) < 1e-9


def test_kepler_curves_stored_for_the_report():
    # everything the report draws is in the results; checked against closed forms
    r = simulate(text())
    a, run = r.analysis, r.runs["main"]
    # reference on the output grid: apocentre (−1.7, 0) at t = T/2 = π
    i = int(np.argmin(np.abs(run.t - math.pi)))
    assert run.reference["x"][i] == pytest.approx(-1.7, abs=1e-12)
    assert abs(run.reference["y"][i]) < 1e-12
    assert "Kepler" in run.attrs["reference_label"]
    # the drawn ellipse: r1 + r2 = 2a about the foci 0 and −2ae ê (focal property)
    x, y = a["kepler_orbit"]["x"], a["kepler_orbit"]["y"]
    ex, ey = a["eccentricity_vector"]
    assert math.hypot(ex, ey) == pytest.approx(0.7, abs=1e-13)  # |A|/(μk) = e
    assert np.max(np.abs(np.hypot(x, y) + np.hypot(x + 2 * ex, y + 2 * ey) - 2.0)) < 1e-12
    # V_eff for V = −k/r: r_c = L²/(μk), V_eff(r_c) = −μk²/(2L²) (Goldstein §3.3)
    mu, k, L = 0.5, 0.5, a["angular_momentum"]
    curve = a["effective_potential_curve"]
    assert curve["circular_radius"] == pytest.approx(L**2 / (mu * k), rel=1e-12)
    assert curve["circular_energy"] == pytest.approx(-mu * k**2 / (2 * L**2), rel=1e-12)
    dr = curve["r"][1] - curve["r"][0]
    assert abs(curve["r"][int(np.argmin(curve["effective_potential"]))]
               - L**2 / (mu * k)) <= dr
    assert np.allclose(curve["effective_potential"] - curve["potential"],
                       L**2 / (2 * mu * curve["r"] ** 2), rtol=1e-12, atol=0.0)
    # both bodies about the centre of mass: m1 r1 + m2 r2 = 0, r1 − r2 = r (3.19)
    r1, r2 = a["body_tracks"]["r1"], a["body_tracks"]["r2"]
    assert np.max(np.abs(r1 + r2)) < 1e-15  # m1 = m2
    assert np.allclose(r1[:, 0] - r2[:, 0], run["x"], rtol=0, atol=1e-15)
    # |A|/(μk) − e along the run
    assert np.max(np.abs(a["lrl_eccentricity_error"])) == pytest.approx(
        a["lrl_eccentricity_drift"], rel=1e-12)


def test_eccentricity_vector_is_not_scaled_by_a():
    # a = −k/(2E) ≠ 1 here: the LRL direction stored for the figure has length e, not a e
    r = simulate(text(params="", initial="x = 1.0\ny = 0.5\nvx = -0.3\nvy = 1.4",
                      run="t_end = 10.0\nsamples = 501").replace("m2 = 1.0", "m2 = 3.0")
                 .replace("k = 0.5", "k = 1.0"))
    a = r.analysis
    assert abs(a["semi_major_axis"] - 1.0) > 0.5
    assert math.hypot(*a["eccentricity_vector"]) == pytest.approx(a["eccentricity"],
                                                                  rel=1e-12)


def test_solve_kepler_extreme_eccentricity():
    M = np.linspace(-20, 20, 2001)
    for e in (0.0, 0.5, 0.9, 0.99, 0.999):
        E = core.solve_kepler(M, e)
        assert np.max(np.abs(E - e * np.sin(E) - M)) < 1e-13


def test_kepler_e099_against_kepler_equation():
    # e = 0.99: r_peri = 0.01, v_peri = √(1.99/0.01); 3 orbits
    r = simulate(text(initial="x = 0.01\ny = 0.0\nvx = 0.0\nvy = 14.106735979665885",
                      run="t_end = 18.84955592153876\nsamples = 3001\nrtol = 1e-13\n"
                          "atol = 1e-15"))
    a = r.analysis
    assert a["eccentricity"] == pytest.approx(0.99, abs=1e-12)
    assert a["kepler_position_error_max"] < 1e-7
    assert r.status == "ok"
    assert "period_measured_note" in a  # the pericentre passage is not resolved by 3001 samples


def test_inverse_cube_correction_apsidal_angle_exact():
    r = simulate(text(params='potential = "kepler_inverse_cube"\nepsilon = 0.01',
                      initial="x = 1.0\ny = 0.0\nvx = 0.0\nvy = 0.9",
                      run="t_end = 60.0\nsamples = 12001\nrtol = 1e-13\natol = 1e-15"))
    a = r.analysis
    mu, L = 0.5, 0.5 * 0.9
    closed = math.pi / math.sqrt(1 - 2 * mu * 0.01 / L**2)  # Landau & Lifshitz §15 problem 3
    assert a["apsidal_angle_exact"] == pytest.approx(closed, rel=1e-10)
    assert abs(a["apsidal_angle_measured"] / closed - 1) < 1e-9
    # the family drawn in the report: the same angle at every eccentricity
    family = a["apsidal_angle_family"]
    assert family["eccentricity"].size > 10 and np.ptp(family["eccentricity"]) > 0.1
    assert np.allclose(family["angle"], closed, rtol=1e-7, atol=0.0)
    # pericentre markers: at the stored pericentre times, r is the turning point r_min
    peri = a["pericentre_positions"]
    assert peri["x"].size == a["pericentre_times"].size >= 2
    r_min = a["turning_points"][0]
    assert np.allclose(np.hypot(peri["x"], peri["y"]), r_min, rtol=1e-3)


def test_power_law_apsidal_angle_near_circular_limit():
    # V = −k/r^1.2 nearly circular: apsidal angle → π/√(2 − n) (Landau & Lifshitz §14)
    mu, k, n = 0.5, 0.5, 1.2
    L = 0.5 * 1.0
    rc = core.circular_radius(L, mu, k, n)
    E = float(core.effective_potential(rc, L, mu, k, n)) + 1e-6
    assert core.apsidal_angle(E, L, mu, k, n) == pytest.approx(math.pi / math.sqrt(0.8),
                                                               rel=1e-4)


def test_power_law_scene_measured_apsidal_angle():
    r = simulate(text(params='potential = "power"\nn = 1.2',
                      initial="x = 1.0\ny = 0.0\nvx = 0.0\nvy = 0.8",
                      run="t_end = 80.0\nsamples = 8001\nrtol = 1e-13\natol = 1e-15"))
    a = r.analysis
    assert abs(a["apsidal_angle_measured"] / a["apsidal_angle_exact"] - 1) < 1e-9
    assert abs(a["period_measured"] / a["period"] - 1) < 1e-9
    assert 0 < a["eccentricity"] < 1 and r.status == "ok"
    # the family drawn in the report tends to π/√(2 − n) as e → 0 (Landau & Lifshitz §14)
    family = a["apsidal_angle_family"]
    i = int(np.argmin(family["eccentricity"]))
    assert family["eccentricity"][i] < 0.02
    assert family["angle"][i] == pytest.approx(math.pi / math.sqrt(0.8), rel=2e-5)
    j = int(np.argmin(np.abs(family["eccentricity"] - a["eccentricity"])))
    assert family["angle"][j] == pytest.approx(a["apsidal_angle_exact"], rel=1e-10)


def test_unbound_orbit_has_no_period():
    r = simulate(text(initial="x = 1.0\ny = 0.0\nvx = 0.0\nvy = 1.6",
                      run="t_end = 5.0\nsamples = 101"))
    assert "period" not in r.analysis and "period_note" in r.analysis
    assert r.analysis["eccentricity"] > 1
    assert "kepler_orbit" not in r.analysis and "apsidal_angle_family" not in r.analysis
    assert not r.runs["main"].reference


def test_report_sections_from_the_archive(write_config, cli, tmp_path):
    # an unbound orbit has no Kepler checks and no apsides: decided from the archive alone
    from reportgen.archive.store import read_archive
    from reportgen.kinds.central_force import CentralForceScene

    cfg = write_config("hyp", text(initial="x = 1.0\ny = 0.0\nvx = 0.0\nvy = 1.6",
                                   run="t_end = 5.0\nsamples = 101"))
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    data = read_archive(tmp_path / "o" / "hyp" / "run.h5")
    assert CentralForceScene.default_sections(data) == [
        "orbit", "two_body", "effective_potential", "invariants", "error_vs_runtime"]
    figures = sorted(p.name for p in (tmp_path / "o" / "hyp" / "figures").glob("*.svg"))
    assert figures == ["effective_potential-effective_potential.svg",
                       "invariants-invariants.svg", "orbit-orbit.svg", "two_body-two_body.svg"]


def test_symplectic_method_runs_on_separable_model():
    # h divides the output spacing 2π·10/400 into 315 whole steps (about 0.0005)
    r = simulate(text(run="t_end = 62.83185307179586\nsamples = 401\nmethod = \"yoshida6\"\n"
                          f"h = {62.83185307179586 / 400 / 315!r}"))
    run = r.runs["main"]
    assert run.attrs["method"] == "yoshida6"
    assert run.attrs["drift_energy"] < 1e-8


@pytest.mark.parametrize("params, initial, key", [
    ("k = -1.0", "", "params.k"),
    ('potential = "power"', "", "params.n"),
    ('potential = "power"\nn = 2.5', "", "params.n"),
    ("", "x = 0.0\ny = 0.0\nvx = 1.0\nvy = 0.0", "initial.x"),
    ("", "x = 1.0\ny = 0.0\nvx = 1.0\nvy = 0.0", "initial.x"),
])
def test_bad_input_names_the_key(params, initial, key):
    t = text(params=params, initial=initial)
    if params == "k = -1.0":
        t = t.replace("k = 0.5\n", "")
    with pytest.raises(ConfigError) as exc:
        load_scene(parse_config_text(t))
    assert key in str(exc.value)


def test_pipeline_writes_archive_with_required_columns(write_config, cli, tmp_path):
    import h5py

    from reportgen.archive.h5io import read_table

    cfg = write_config("kep", text(run="t_end = 12.566370614359172\nsamples = 801\n"
                                       "study = true\nrtol = 1e-12").replace(
        "study = false\n", ""))
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    with h5py.File(tmp_path / "o" / "kep" / "run.h5") as f:
        cols = [c.decode() if isinstance(c, bytes) else c for c in f["runs/main/y"].attrs["columns"]]
        assert cols == ["x", "y", "vx", "vy"]
        for key in ("eccentricity", "semi_major_axis", "period"):
            assert key in f["analysis"].attrs
        assert len(read_table(f["study/error_vs_runtime"])) > 3


def test_power_law_is_named_with_its_exponent_typeset():
    # on a page V = −k/r^1.2 is V = −k/r¹·²: no caret exponent (the document gate's tex rule)
    from reportgen.kinds.central_force import CentralForceScene
    from reportgen.kinds.central_force.report import power_potential

    assert power_potential("1.2") == "V = −k/r¹·²"
    assert power_potential("−0.5") == "V = −k/r⁻⁰·⁵"
    scene = load_scene(parse_config_text(text(params='potential = "power"\nn = 1.2',
                                              initial="x = 1.0\ny = 0.0\nvx = 0.0\nvy = 0.8")))
    assert CentralForceScene.default_title(scene.config) == (
        "Central potential V = −k/r¹·²: two bodies started at r = 1 m")


@pytest.mark.parametrize("near_label", ["near-circular limit π/√(2 − n)",
                                        "closed form π/√(1 − 2με/L²)"])
def test_apsidal_angle_figure_passes_the_gate(near_label):
    # the eccentricity label in mathtext (r_max, r_min typeset), the legend off the data,
    # and the dashed line named as the caller says (the 1/r³ case: a closed form)
    import io

    from reportgen.rendering.gate import figure_findings
    from reportgen.rendering.plots import gravitation

    e = np.linspace(0.0, 0.6, 61)
    limit = math.pi / math.sqrt(0.8)
    angle = limit + 0.1 * e**2
    fig = gravitation.apsidal_angle_family(e, angle, near_circular=limit,
                                           measured=(0.54, float(angle[54])),
                                           exact_label="exact quadrature at this L",
                                           near_label=near_label)
    fig.savefig(io.BytesIO(), format="svg")
    assert figure_findings(fig) == []
    assert near_label in [t.get_text() for t in fig.axes[0].get_legend().texts]
