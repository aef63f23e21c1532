"""three_body: figure-eight (Chenciner & Montgomery 2000, period 6.32591398 from Simó),
Pythagorean problem (Szebehely & Peters 1967: bodies 4 and 5 end as a binary, 3 escapes),
Sun–Earth–Moon mass ratios (notes 3.35) and the Jacobi kinetic energy (3.33)."""

from __future__ import annotations

import numpy as np

from reportgen.config import ConfigError, parse_config_text
from reportgen.core.models import nbody as core
from reportgen.scenes import load_scene


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


def test_loose_tolerance_is_flagged_not_silent():
    r = simulate('kind = "three_body"\npreset = "pythagorean"\n[run]\nt_end = 70.0\n'
                 'samples = 701\nrtol = 1e-6\natol = 1e-8\nstudy = false\n')
    assert r.status == "unstable" and "energy" in r.message


def test_sun_earth_moon_mass_ratios_and_jacobi():
    r = simulate('kind = "three_body"\npreset = "sun_earth_moon"\n[run]\nt_end = 0.5\n'
                 'samples = 2001\nstudy = false\n')
    m = load_scene(parse_config_text('kind = "three_body"\npreset = "sun_earth_moon"\n')).masses
    assert 1e-6 < m[1] / m[0] < 1e-5 and 1e-8 < m[2] / m[0] < 1e-7  # (3.35)
    a = r.analysis
    assert a["jacobi_kinetic_identity_error"] < 1e-13
    # Moon about Earth: 0.0025696 AU, ~27.3 d; the measured mean period within 2 % of Kepler's
    assert abs(a["moon_period_measured"] / a["moon_kepler_period"] - 1) < 0.02
    assert a["moon_reference_error"] < 1e-9
    assert r.status == "ok"


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
