"""Heavy top asked for by its nutation band ([band]) and u(t) through ℘ (exercise 4.10).

References checked here:
- the two conserved momenta and the reduced energy, p_φ = I1 φ̇ sin²θ + I3 ω3 cos θ and
  E′ = ½I1(θ̇² + φ̇² sin²θ) + Mgl cos θ (Goldstein 3rd ed. 5.62, 5.64), take the same value
  on both turning circles (θ̇ = 0) of the solved release
- the Fig. 4.3 cases by the sign of φ̇ = (b − a cos θ)/sin²θ (10.26) on the circles
  (Goldstein §5.7): loops change sign, waves keep it, cusps have φ̇ = 0 on the upper one
- u(t) = (4/β)℘(t + x0 + ω′) + (u1 + u2 + u3)/3 against the Jacobi sn² form
  u1 + (u2 − u1) sn²(λt + τ0 | k²) (notes (10.31); Goldstein §5.7), and T = 2ω = 4K(k²)/√(β(u3 − u1))
"""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import h5py
import numpy as np
import pytest

from reportgen.archive.store import read_archive
from reportgen.core import heavy_top_theory as theory
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, parse_config_text

REPO = Path(__file__).resolve().parent.parent
I1, I3, MGL = 1.0, 0.5, 1.0


def band_text(theta_min, theta_max, case, omega3=None, t_end=20.0, samples=2000, extra="",
              params=(I1, I3, MGL)):
    spin = "" if omega3 is None else f"omega3 = {omega3!r}"
    return textwrap.dedent(f"""
        kind = "heavy_top"
        title = "band test"

        [params]
        I1 = {params[0]!r}
        I3 = {params[1]!r}
        Mgl = {params[2]!r}

        [band]
        theta_min = {theta_min!r}
        theta_max = {theta_max!r}
        case = "{case}"
        {spin}

        [run]
        t_end = {t_end}
        samples = {samples}
        study = false
        """) + textwrap.dedent(extra)


def scene(text):
    return load_scene(parse_config_text(text))


def turning_circle_invariants(theta_min, theta_max, phi_dot0, omega3, params=(I1, I3, MGL)):
    """(p_φ, E′) on the upper circle and on the lower one, φ̇ there from p_φ conservation
    (Goldstein 5.62, 5.64 with θ̇ = 0 at both turning circles)."""
    i1, i3, mgl = params
    p_phi = i1 * phi_dot0 * math.sin(theta_min) ** 2 + i3 * omega3 * math.cos(theta_min)
    phi_dot_low = (p_phi - i3 * omega3 * math.cos(theta_max)) / (i1 * math.sin(theta_max) ** 2)
    energy_up = 0.5 * i1 * (phi_dot0 * math.sin(theta_min)) ** 2 + mgl * math.cos(theta_min)
    energy_low = 0.5 * i1 * (phi_dot_low * math.sin(theta_max)) ** 2 + mgl * math.cos(theta_max)
    return phi_dot_low, energy_up, energy_low


# hidden bands: high on the sphere, across the equator (σ = u1 + u2 < 0 for the last two,
# where waves run backwards), with the default spin and with spins given in the config
BANDS = [
    (0.6, 1.1, "loops", None), (0.6, 1.1, "waves", None), (0.6, 1.1, "cusps", None),
    (0.3, 0.45, "loops", 20.0), (0.45, 0.9, "waves", 4.0), (1.0, 2.0, "loops", 3.5),
    (1.0, 2.0, "waves", 1.0), (2.0, 2.8, "cusps", None), (2.0, 2.8, "waves", -3.0),
    (0.7, 1.3, "loops", -9.0),
]


@pytest.mark.parametrize("theta_min,theta_max,case,omega3", BANDS)
def test_band_gives_its_case_turning_circles_and_span(theta_min, theta_max, case, omega3):
    s = scene(band_text(theta_min, theta_max, case, omega3))
    results = s.simulate()
    run, a = results.runs["main"], results.analysis
    assert results.status == "ok" and list(results.runs) == ["main"]
    # the request, to 1e-9 (the roots of f(u) and the classification)
    assert a["case"] == case
    assert abs(a["theta1"] - theta_min) <= 1e-9 and abs(a["theta2"] - theta_max) <= 1e-9
    # released on the upper circle; the spin given is kept
    assert a["theta0"] == theta_min and a["theta_dot0"] == 0.0
    if omega3 is not None:
        assert a["omega3"] == omega3
    # conserved p_φ and E′ agree on both turning circles (Goldstein 5.62, 5.64)
    phi_dot_low, e_up, e_low = turning_circle_invariants(theta_min, theta_max, a["phi_dot0"],
                                                         a["omega3"])
    assert e_low == pytest.approx(e_up, rel=1e-12, abs=1e-12 * MGL)
    # the integrated trajectory spans the band: extremes between samples refined by Hermite
    # interpolation within the integration's accuracy, and no sample outside the band
    assert abs(a["theta_min_measured"] - theta_min) <= 1e-8
    assert abs(a["theta_max_measured"] - theta_max) <= 1e-8
    theta = run["theta"]
    assert theta.min() >= theta_min - 1e-9 and theta.max() <= theta_max + 1e-9
    assert theta.max() >= theta_max - 1e-3  # the grid reaches the lower circle, too
    # the case from the sign of φ̇ (10.26) on the circles and along the run (Goldstein §5.7)
    phi_dot_up = a["phi_dot0"]
    phid = run["phi_dot"]
    if case == "loops":
        assert phi_dot_up * phi_dot_low < 0 and phid.min() < 0 < phid.max()
    elif case == "waves":
        assert phi_dot_up * phi_dot_low > 0 and (phid.min() > 0 or phid.max() < 0)
    else:
        assert phi_dot_up == 0.0 and phi_dot_low != 0.0
        assert np.max(np.abs(phid[theta <= theta_min + 1e-6])) <= 1e-6
    # ℘ against sn² on the output grid
    assert a["weierstrass_max_difference"] <= 1e-10
    summary = a["band"]["runs"]["main"]
    assert summary["case"] == case and summary["theta2"] == a["theta2"]


def test_cusp_spin_is_the_one_of_the_textbook():
    # a top released at rest on θ1 turns on θ2 where E′ and p_φ agree:
    # a² = β sin²θ2/(cos θ1 − cos θ2), a = I3 ω3/I1, β = 2Mgl/I1 (Goldstein 5.62, 5.64)
    for theta_min, theta_max, params in ((0.6, 1.1, (I1, I3, MGL)), (1.2, 2.5, (2.0, 1.5, 0.3))):
        a = math.sqrt(2 * params[2] / params[0] * math.sin(theta_max) ** 2
                      / (math.cos(theta_min) - math.cos(theta_max)))
        spins = theory.band_spins(*params, theta_min, theta_max)
        assert spins.omega3_cusps == pytest.approx(params[0] * a / params[1], rel=1e-14)
        results = scene(band_text(theta_min, theta_max, "cusps", params=params)).simulate()
        assert results.analysis["omega3"] == pytest.approx(spins.omega3_cusps, rel=1e-15)
        assert results.analysis["case"] == "cusps"


@pytest.mark.parametrize("case,omega3,possible", [
    ("cusps", 3.0, "cusps need |ω3| = 4.134323029"),
    ("loops", 4.0, "loops |ω3| > 4.134323029"),
    ("waves", 2.0, "waves |ω3| ≥ 3.198664392"),
])
def test_impossible_spin_is_an_error_naming_the_possible_spins(case, omega3, possible):
    with pytest.raises(ConfigError) as exc:
        scene(band_text(0.6, 1.1, case, omega3))
    text = str(exc.value)
    assert "band.omega3" in text and possible in text and f"no {case}" in text


@pytest.mark.parametrize("band,keys", [
    ((0.0, 1.0), "band.theta_min / band.theta_max"),
    ((1.0, 0.5), "band.theta_min / band.theta_max"),
    ((0.5, math.pi), "band.theta_min / band.theta_max"),
])
def test_bad_band_is_an_error_naming_the_keys(band, keys):
    with pytest.raises(ConfigError) as exc:
        scene(band_text(*band, "loops"))
    assert keys in str(exc.value)


def test_initial_and_band_exclude_each_other():
    both = band_text(0.6, 1.1, "loops", extra="""
        [initial]
        theta = 1.0
        phi_dot = 0.0
        omega3 = 6.0
        """)
    with pytest.raises(ConfigError, match="initial / band"):
        scene(both)
    neither = band_text(0.6, 1.1, "loops").replace('[band]\ntheta_min = 0.6\ntheta_max = 1.1\n'
                                                   'case = "loops"\n', "")
    assert "[band]" not in neither
    with pytest.raises(ConfigError, match="initial"):
        scene(neither)
    with pytest.raises(ConfigError, match="expect_case"):
        scene(band_text(0.6, 1.1, "loops").replace('title = "band test"',
                                                   'title = "t"\nexpect_case = "loops"'))


def test_impossible_band_exits_2_and_writes_nothing(write_config, cli, tmp_path):
    cfg = write_config("band", band_text(0.6, 1.1, "loops", 1.0))
    code, _out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1)
    assert code == 2
    assert "band.omega3" in err and "loops |ω3| > 4.134323029" in err
    assert not (tmp_path / "o" / "band").exists()


def test_case_all_writes_three_runs_and_fig43(write_config, cli, tmp_path):
    cfg = write_config("fig43", band_text(0.8, 1.0, "all", t_end=12.0, samples=1200))
    code, _out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err
    path = tmp_path / "o" / "fig43" / "run.h5"
    data = read_archive(path)
    assert set(data.runs) == {"main", "loops", "waves", "cusps"}
    with h5py.File(path, "r") as f:  # /runs/main is /runs/loops: one group, two names
        assert f["runs/main"].id == f["runs/loops"].id
    band = data.analysis["band"]
    assert band["case"] == "all"
    for name in ("loops", "waves", "cusps"):
        run = band["runs"][name]
        assert run["case"] == name
        assert abs(run["theta1"] - 0.8) <= 1e-9 and abs(run["theta2"] - 1.0) <= 1e-9
        assert abs(run["theta_max_measured"] - 1.0) <= 1e-8
        assert run["weierstrass_max_difference"] <= 1e-10
        theta = data.runs[name]["theta"]
        assert theta.min() >= 0.8 - 1e-9 and theta.max() <= 1.0 + 1e-9
        # the stretch Fig. 4.3 draws covers at least two nutation periods
        stop = int(run["locus_stop"])
        assert data.runs[name].t[stop - 1] >= 2 * run["nutation_period"] - 0.02
    # spins: cusps its own, loops faster, waves slower (BandSpins.default_omega3)
    spins = theory.band_spins(I1, I3, MGL, 0.8, 1.0)
    assert band["runs"]["cusps"]["omega3"] == pytest.approx(spins.omega3_cusps, rel=1e-15)
    assert band["runs"]["loops"]["omega3"] == pytest.approx(1.5 * spins.omega3_cusps, rel=1e-15)
    assert spins.omega3_waves_min < band["runs"]["waves"]["omega3"] < spins.omega3_cusps
    # main is the loops run: the top-level analysis describes it
    assert data.analysis["case"] == "loops"
    html = (tmp_path / "o" / "fig43" / "report.html").read_text()
    assert 'id="fig4_3"' in html and 'id="fig-fig4_3' in html
    assert 'id="weierstrass"' in html and "(textbook exercise 4.10)" in html
    assert 'id="nutation_locus"' not in html  # drawn for all three in Fig. 4.3


def test_all_with_a_spin_applies_it_to_loops_and_waves_only():
    s = scene(band_text(0.6, 1.1, "all", 7.0, t_end=5.0, samples=500))
    starts = s.starts
    assert starts["loops"].omega3 == 7.0 and starts["waves"].omega3 == 7.0
    assert starts["cusps"].omega3 == pytest.approx(
        theory.band_spins(I1, I3, MGL, 0.6, 1.1).omega3_cusps, rel=1e-15)
    # at 7 rad/s > the cusp spin the only waves are the fast-precessing ones: Δφ ≈ 2π
    results = s.simulate()
    assert {r["case"] for r in results.analysis["band"]["runs"].values()} == {"loops", "waves",
                                                                           "cusps"}


# the sleeping tops start tilted by 1e-6 rad and nutate (to 1.3e-6 rad below the
# threshold's stable side, to 1.59 rad on its unstable side): ℘ describes them too
NUTATING = ["heavy_top_fig4.3a.toml", "heavy_top_fig4.3b.toml", "heavy_top_fig4.3c.toml",
            "heavy_top_fig4.3.toml", "heavy_top_sleeping_stable.toml",
            "heavy_top_sleeping_unstable.toml"]
NOT_NUTATING = ["heavy_top_steady_slow.toml", "heavy_top_steady_fast.toml"]


@pytest.mark.parametrize("name", NUTATING + NOT_NUTATING)
def test_weierstrass_difference_on_every_shipped_top(name):
    text = (REPO / "configs" / name).read_text()
    s = scene(text.replace("[run]\n", "[run]\nstudy = false\n") if "[run]" in text
              else text + "\n[run]\nstudy = false\nt_end = 30.0\n")
    results = s.simulate()
    a = results.analysis
    if name in NUTATING:
        # SPEC: ≤ 1e-10 on every nutating heavy-top scene
        assert a["weierstrass_max_difference"] <= 1e-10
        for run in a.get("band", {}).get("runs", {}).values():
            assert run["weierstrass_max_difference"] <= 1e-10
        wp = a["weierstrass"]
        # T = 2ω from the AGM against 4K(k²)/√(β(u3 − u1)) in Carlson form
        assert wp["period"] == pytest.approx(a["nutation_period"], rel=1e-13)
        # g2, g3 are the invariants of the roots e_j = β(u_j − μ)/4, μ = (u1 + u2 + u3)/3
        beta = a["beta"]
        mu = (a["u1"] + a["u2"] + a["u3"]) / 3
        e = [beta * (u - mu) / 4 for u in (a["u3"], a["u2"], a["u1"])]
        assert [wp["e1"], wp["e2"], wp["e3"]] == pytest.approx(e, rel=1e-12, abs=1e-14)
        assert wp["g2"] == pytest.approx(-4 * (e[0] * e[1] + e[0] * e[2] + e[1] * e[2]),
                                         rel=1e-12)
        assert wp["g3"] == pytest.approx(4 * e[0] * e[1] * e[2], rel=1e-12)
        # u℘ stored on the output grid, against the integrated axis
        run = results.runs["main"]
        u_wp = run.reference["cos_theta_weierstrass"]
        assert u_wp.shape == run.t.shape
        assert np.max(np.abs(u_wp - run["axis_z"])) <= 1e-8
    else:  # no nutation: no ℘ (SPEC promise 3)
        assert "weierstrass" not in a and "weierstrass_max_difference" not in a
        assert "cos_theta_weierstrass" not in results.runs["main"].reference


def test_weierstrass_phase_for_a_moving_start():
    # θ̇0 ≠ 0: x0 is found on ℘ itself, on the rising or the falling half of the period
    for theta_dot in (-0.9, 0.9):
        c = theory.constants(I1, I3, MGL, 0.7, theta_dot, 0.4, 5.0)
        r = theory.roots(c)
        form = theory.weierstrass_form(r, c)
        t = np.linspace(0.0, 15.0, 1501)
        w_sn, _u = theory.u_closed_form(t, r, c)
        assert np.max(np.abs(theory.w_weierstrass(t, form, r) - w_sn)) <= 1e-12
        assert (form.x0 < form.omega) == (theta_dot < 0)  # u̇0 = −sin θ0 θ̇0 > 0: rising


def test_sleeping_scene_shows_weierstrass_only_when_asked():
    text = (REPO / "configs" / "heavy_top_sleeping_unstable.toml").read_text()
    text = text.replace("[run]\n", "[run]\nstudy = false\n") if "[run]" in text else (
        text + "\n[run]\nstudy = false\nt_end = 30.0\n")
    plain = scene(text)
    asked = scene(text + '\n[report]\nsections = ["cubic", "weierstrass"]\n')
    assert plain.computes("weierstrass") and asked.physics_key() == plain.physics_key()
    results = plain.simulate()
    a = results.analysis
    # the 1e-6 tilt below the threshold falls to θ2 ≈ 1.59 rad and back: ℘ describes it
    assert a["theta2"] > 1.5 and a["weierstrass_max_difference"] <= 1e-10
    # the scene is about the threshold: its report shows ℘ only when asked
    from reportgen.archive.store import ArchiveData, ConfigView

    data = ArchiveData(path=Path("x.h5"), attrs={}, config_text="", provenance={},
                       analysis=a, runs=results.runs,
                       config=ConfigView.of(plain.resolved_config()))
    assert "weierstrass" not in type(plain).default_sections(data)


def test_weierstrass_is_in_the_analysis_when_the_report_leaves_it_out():
    # SPEC: /analysis weierstrass_max_difference for a nutating top, whatever sections show
    text = band_text(0.6, 1.1, "waves") + '\n[report]\nsections = ["nutation_locus"]\n'
    a = scene(text).simulate().analysis
    assert a["weierstrass_max_difference"] <= 1e-10
