"""three_body: figure-eight (Chenciner & Montgomery 2000, period 6.32591398 from Simó),
Pythagorean problem (Szebehely & Peters 1967: bodies 4 and 5 end as a binary, 3 escapes),
Sun–Earth–Moon mass ratios (notes 3.35) and the Jacobi kinetic energy (diagonal in
Jacobi's coordinates, which are not the notes')."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from reportgen.core.models import nbody as core
from reportgen.kinds import load_scene
from reportgen.kinds.three_body import ThreeBodyScene
from reportgen.scene.config import ConfigError, parse_config_text


def simulate(text):
    return load_scene(parse_config_text(text)).simulate()


def test_columns_order():
    assert core.COLUMNS[:3] == ("x1", "y1", "z1") and core.COLUMNS[9:12] == ("vx1", "vy1", "vz1")
    assert len(set(core.COLUMNS)) == 18


def test_figure_eight_returns_after_one_period():
    r = simulate('kind = "three_body"\npreset = "figure_eight"\n[run]\nt_end = 6.32591398\n'
                 'samples = 201\nstudy = false\n')
    a = r.analysis
    assert a["return_position_error"] <= 1e-6
    assert a["energy_error_max"] <= 1e-10
    run = r.runs["main"]
    assert run.columns == list(core.COLUMNS)
    # independent of the scene's own return check: the stored last sample is t = T
    assert np.max(np.abs(run.y[-1, :9] - run.y[0, :9])) <= 1e-6
    assert r.status == "ok"
    # equal masses: not a hierarchical triple, so the report shows no moon section
    assert a["hierarchical"] is False and "moon_relative_position" not in a
    # the encounter curves the report draws are the pair distances of the stored run
    pos = run.y[:, :9].reshape(-1, 3, 3)
    np.testing.assert_array_equal(a["pair_distances"]["r13"],
                                  np.linalg.norm(pos[:, 2] - pos[:, 0], axis=1))
    assert a["min_pair_distance"] == min(float(np.min(d)) for d in a["pair_distances"].values())


def test_pythagorean_to_t70_energy_and_final_binary():
    r = simulate('kind = "three_body"\npreset = "pythagorean"\n[run]\nt_end = 70.0\n'
                 'samples = 7001\nrtol = 1e-13\natol = 1e-15\nstudy = false\n')
    assert r.analysis["energy_error_max"] <= 1e-8 and r.status == "ok"
    y = r.runs["main"].y[-1:]
    pos, vel = core.split(y)
    m = np.array([3.0, 4.0, 5.0])
    # bodies 2 and 3 (masses 4 and 5) bound: two-body energy < 0 (Szebehely & Peters 1967)
    d = np.linalg.norm(pos[0, 2] - pos[0, 1])
    vrel = np.linalg.norm(vel[0, 2] - vel[0, 1])
    assert 0.5 * vrel**2 - (m[1] + m[2]) / d < 0
    assert np.linalg.norm(pos[0, 0]) > 5.0  # mass 3 has left
    # the behaviour is page text: the growth law in words, no caret exponent (e^(t/T))
    assert "exp(t/T)" in r.analysis["behaviour"] and "^" not in r.analysis["behaviour"]


def test_loose_tolerance_is_flagged_not_silent():
    r = simulate('kind = "three_body"\npreset = "pythagorean"\n[run]\nt_end = 70.0\n'
                 'samples = 701\nrtol = 1e-6\natol = 1e-8\nstudy = false\n')
    assert r.status == "unstable" and "energy" in r.message


def test_sun_earth_moon_mass_ratios_and_jacobi():
    r = simulate('kind = "three_body"\npreset = "sun_earth_moon"\n[run]\nt_end = 0.5\n'
                 'samples = 2001\nstudy = false\n')
    m = load_scene(parse_config_text('kind = "three_body"\npreset = "sun_earth_moon"\n')).masses
    assert 1e-6 < m[1] / m[0] < 1e-5 and 1e-8 < m[2] / m[0] < 1e-7  # notes (3.35)
    a = r.analysis
    assert a["jacobi_kinetic_identity_error"] < 1e-13
    # Moon about Earth: 0.0025696 AU, ~27.3 d; the measured mean period within 2 % of Kepler's
    assert abs(a["moon_period_measured"] / a["moon_kepler_period"] - 1) < 0.02
    assert a["moon_reference_error"] < 1e-9
    assert r.status == "ok"
    # what the moon section draws is stored: the Moon's track about the Earth and the Jacobi ρ1, ρ2
    y = r.runs["main"].y
    assert a["hierarchical"] is True
    np.testing.assert_array_equal(a["moon_relative_position"], y[:, 6:9] - y[:, 3:6])
    np.testing.assert_array_equal(a["jacobi_coordinates"]["rho1"], y[:, 3:6] - y[:, 0:3])
    assert a["mass_ratios"]["m2_m1"] == m[1] / m[0] and a["mass_ratios"]["m3_m1"] == m[2] / m[0]
    # the Moon at 0.0025696 AU (384 400 km), inclined 5.145° (the preset's data)
    assert a["moon_semi_major_axis"] == pytest.approx(0.0025696, rel=1e-6)
    assert math.degrees(a["moon_inclination"]) == pytest.approx(5.145, abs=1e-9)
    # sidereal month 27.32 d = 0.0748 yr (Kepler's third law with the preset's masses)
    assert a["moon_kepler_period"] * 365.25 == pytest.approx(27.3, rel=0.01)


def test_collision_is_an_error():
    text = ('kind = "three_body"\n[params]\nmasses = [1.0, 1.0, 1.0]\n[initial]\n'
            'positions = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]\n'
            'velocities = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]\n'
            '[run]\nt_end = 1.0\n')
    try:
        load_scene(parse_config_text(text))
    except ConfigError as exc:
        assert "initial.positions" in str(exc)
    else:
        raise AssertionError("collision accepted")
    bad = text.replace("[1.0, 1.0, 1.0]", "[1.0, -1.0, 1.0]").replace(
        "[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0", "[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0")
    try:
        load_scene(parse_config_text(bad))
    except ConfigError as exc:
        assert "params.masses" in str(exc)
    else:
        raise AssertionError("negative mass accepted")


def test_osculating_orbit_kepler_third_law():
    # circular orbit of radius R with speed √(K/R), tilted by i about the x axis:
    # a = R, inclination i, T = 2π √(R³/K) (Kepler's third law, notes 3.31)
    K, R, inc = 4 * math.pi**2, 2.0, math.radians(30.0)
    v = math.sqrt(K / R)
    orbit = core.osculating_orbit([R, 0.0, 0.0], [0.0, v * math.cos(inc), v * math.sin(inc)], K)
    assert orbit["semi_major_axis"] == pytest.approx(R, rel=1e-14)
    assert orbit["inclination"] == pytest.approx(inc, rel=1e-14)
    assert orbit["period"] == pytest.approx(2 * math.pi * math.sqrt(R**3 / K), rel=1e-14)
    np.testing.assert_allclose(orbit["normal"], [0.0, -math.sin(inc), math.cos(inc)], atol=1e-15)
    # unbound (v above escape speed √(2K/R)): a < 0 and no period
    hyper = core.osculating_orbit([R, 0.0, 0.0], [0.0, 1.5 * math.sqrt(2 * K / R), 0.0], K)
    assert hyper["semi_major_axis"] < 0 and math.isnan(hyper["period"])


def test_revolutions_counts_signed_turns():
    phi = np.linspace(0.0, 2.5 * 2 * math.pi, 1001)
    rel = np.stack([np.cos(phi), np.sin(phi), np.zeros_like(phi)], axis=1)
    assert core.revolutions(rel, [0.0, 0.0, 1.0]) == pytest.approx(2.5, rel=1e-12)
    assert core.revolutions(rel, [0.0, 0.0, -1.0]) == pytest.approx(-2.5, rel=1e-12)


def test_natural_scales_bound_the_invariants():
    scene = load_scene(parse_config_text('kind = "three_body"\npreset = "pythagorean"\n'))
    y0 = scene._y0()
    s = core.natural_scales(y0, 1.0, scene.masses)
    # Burrau's bodies start at rest, r12 = 5, r13 = 4, r23 = 3 (each mass opposite the side
    # of its own length): E(0) = −U(0) = −(3·4/5 + 3·5/4 + 4·5/3) (G = 1)
    u0 = 12 / 5 + 15 / 4 + 20 / 3
    assert s["energy"] == pytest.approx(u0, rel=1e-14)
    assert float(core.energy(y0, 1.0, scene.masses)[0]) == pytest.approx(-u0, rel=1e-14)
    assert s["momentum_x"] == s["momentum_y"] > 0 and s["angular_momentum_z"] > 0


def test_default_sections_from_the_archive_alone():
    def data(hierarchical, period):
        return SimpleNamespace(analysis={"hierarchical": hierarchical},
                               config=SimpleNamespace(period=period))
    names = ThreeBodyScene.default_sections(data(False, None))
    assert "moon" not in names and "periodicity" not in names and "orbits" in names
    names = ThreeBodyScene.default_sections(data(True, 6.3))
    assert "moon" in names and "periodicity" in names


def test_figure_eight_with_one_mass_changed_is_not_the_choreography():
    """The figure-eight preset with m3 = 1.02 keeps the preset's period, but its orbit does
    not return after it (0.3 away): its words must not name the choreography or equal
    masses, and no check holds it to a return it does not make."""
    text = ('kind = "three_body"\npreset = "figure_eight"\n[params]\nmasses = [1.0, 1.0, 1.02]\n'
            '[run]\nt_end = 12.0\nsamples = 1201\nstudy = false\n')
    scene = load_scene(parse_config_text(text))
    r = scene.simulate()
    assert ThreeBodyScene.preset_as_given(scene.config) is None
    assert r.analysis["return_position_error"] > 0.1
    assert not any("after one period" in c.quantity for c in r.checks)
    data = SimpleNamespace(analysis=r.analysis, config=scene.config, runs=r.runs, sweep=None)
    case = ThreeBodyScene.prose_case(data)
    assert not case["figure_eight"] and not case["periodic"] and not case["equal_masses"]
    words = ThreeBodyScene.describe(data)
    assert "figure-eight" not in words and "equal" not in words and "not periodic" in words
    # the preset as given keeps its name, its return check and its words
    given = load_scene(parse_config_text('kind = "three_body"\npreset = "figure_eight"\n'
                                         '[run]\nstudy = false\n'))
    r = given.simulate()
    assert any("after one period" in c.quantity and "Chenciner" in c.source
               for c in r.checks)
    data = SimpleNamespace(analysis=r.analysis, config=given.config, runs=r.runs, sweep=None)
    assert ThreeBodyScene.describe(data).startswith("Three equal masses on the figure-eight")
