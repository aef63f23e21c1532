"""Config values with units ("40 deg", "500 N/m", "1.3 kg m^2"): converted to each key's
declared unit when the config is validated; the archive's resolved config holds the
converted numbers, its config text what was written."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import h5py
import pytest

from conftest import REPO, pendulum_text
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, parse_config_text, read_config

#: the speed of light [cm/s] and the unified atomic mass unit [kg] (CODATA 2018)
C_CM = 2.99792458e10
U_KG = 1.66053906660e-27


def scene(text: str):
    return load_scene(parse_config_text(text))


def problems(text: str) -> list[str]:
    with pytest.raises(ConfigError) as info:
        scene(text)
    return info.value.problems


def test_degrees_through_validate_and_the_archive(write_config, cli, tmp_path):
    path = write_config("deg", pendulum_text(theta='"40 deg"', samples=201,
                                             extra='[report]\nformats = ["html"]\n'))
    code, out, err = cli("validate", path)
    assert code == 0, err
    assert load_scene(read_config(path)).config.initial.theta == pytest.approx(0.6981317,
                                                                                abs=1e-7)
    code, _, err = cli("run", path, "--out", tmp_path / "out")
    assert code == 0, err
    with h5py.File(tmp_path / "out" / "deg" / "run.h5") as f:
        resolved = json.loads(f["config_resolved"][()])
        text = f["config"][()]
    assert resolved["initial"]["theta"] == pytest.approx(math.radians(40), rel=1e-15)
    assert 'theta = "40 deg"' in (text.decode() if isinstance(text, bytes) else text)


def test_wrong_dimension_exits_2_naming_file_key_rule_and_value(write_config, cli):
    path = write_config("kg", pendulum_text(theta='"3 kg"'))
    code, _, err = cli("validate", path)
    assert code == 2
    assert (f"{path}: key 'initial.theta': must be an angle in rad; give e.g. \"40 deg\"; "
            "kg measures mass (got '3 kg')") in err


@pytest.mark.parametrize("value", ['"3 furlongz"', '"3 deg!"', '"deg 3"', '"10**10**10 deg"',
                                   '"3"', '"1e999 deg"'])
def test_unknown_unit_or_unparseable_exits_2(write_config, cli, value):
    path = write_config("bad", pendulum_text(theta=value))
    code, _, err = cli("validate", path)
    assert code == 2
    assert f"{path}: key 'initial.theta': must be" in err
    assert "got " in err


def test_numbers_keep_meaning_the_declared_unit_and_pint_stays_unloaded():
    code = ("import sys; from reportgen.kinds import load_scene; "
            "from reportgen.scene.config import parse_config_text; "
            f"s = load_scene(parse_config_text({pendulum_text(theta=0.5)!r})); "
            "assert s.config.initial.theta == 0.5; assert 'pint' not in sys.modules")
    done = subprocess.run([sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_units_of_every_field_kind():
    base = pendulum_text()
    cases = [  # (edit of the pendulum config, key, value in the declared unit)
        (("l = 1.0", 'l = "25 cm"'), ("params", "l"), 0.25),
        (("g = 9.81", 'g = "981 cm/s^2"'), ("params", "g"), 9.81),
        (("t_end = 10.0", 't_end = "2 min"'), ("run", "t_end"), 120.0),
        (("theta = 1.0", 'theta = "0.25 turn"'), ("initial", "theta"), math.pi / 2),
        (("theta = 1.0", 'theta = 1.0\ntheta_dot = "60 rpm"'), ("initial", "theta_dot"),
         2 * math.pi),
    ]
    for edit, (table, key), expected in cases:
        config = scene(base.replace(*edit, 1)).config
        assert getattr(getattr(config, table), key) == pytest.approx(expected, rel=1e-12), edit


def test_a_converted_value_still_meets_the_keys_rules():
    found = problems(pendulum_text().replace("l = 1.0", 'l = "-3 cm"', 1))
    assert len(found) == 1 and "key 'params.l': " in found[0] and "greater than 0" in found[0]


def test_rigid_body_moments_and_a_list_with_units():
    config = scene("""
        kind = "rigid_body"
        [params]
        I1 = "1.3 kg m^2"
        I2 = "20000 kg cm^2"
        I3 = 3.0
        [initial]
        omega = ["1 rad/s", "30 rpm", 0.1]
        [run]
        t_end = 1.0
        """.replace("\n        ", "\n")).config
    assert (config.params.I1, config.params.I2, config.params.I3) == pytest.approx(
        (1.3, 2.0, 3.0), rel=1e-12)
    assert config.initial.omega == pytest.approx([1.0, math.pi, 0.1], rel=1e-12)


def test_normal_modes_pendula_spring_in_n_per_m():
    config = scene("""
        kind = "normal_modes"
        [pendula]
        n = 2
        k = "500 N/m"
        l = "50 cm"
        """.replace("\n        ", "\n")).config
    assert (config.pendula.k, config.pendula.l) == (500.0, 0.5)


CO2_SI = """
kind = "normal_modes"
title = "CO2 given in SI"
units = "SI"
report = {formats = ["html"]}

[[atoms]]
mass = "15.999 u"
position = ["-116 pm", 0.0, 0.0]

[[atoms]]
mass = "1.9944e-26 kg"
position = [0.0, 0.0, 0.0]

[[atoms]]
mass = 2.6567e-26
position = ["1.16 Å", "0 m", 0.0]

[[bonds]]
atoms = [0, 1]
k = "1600 N/m"

[[bonds]]
atoms = [1, 2]
k = "16 mdyn/Å"

[[angles]]
atoms = [0, 1, 2]
k = "0.57 mdyn Å/rad^2"
"""


def test_co2_in_si_units_against_a_hand_calculation(tmp_path, cli):
    """Symmetric stretch of O=C=O: the carbon stays still, each O on its spring:
    ω = √(k/m_O), ν̃ = ω/(2πc) = 1302.8 cm⁻¹ for k = 1600 N/m, m_O = 15.999 u."""
    path = tmp_path / "co2_si.toml"
    path.write_text(CO2_SI)
    config = load_scene(read_config(path)).config
    assert config.atoms[0].mass == pytest.approx(15.999 * U_KG, rel=1e-12)
    assert config.atoms[0].position[0] == pytest.approx(-1.16e-10, rel=1e-12)
    assert config.bonds[1].k == pytest.approx(1600.0, rel=1e-12)
    assert config.angles[0].k == pytest.approx(0.57e-8 * 1e-10, rel=1e-12)  # mdyn·Å = 1e-18 J
    code, _, err = cli("run", path, "--out", tmp_path / "out")
    assert code == 0, err
    with h5py.File(tmp_path / "out" / "co2_si" / "run.h5") as f:
        wavenumbers = f["analysis/wavenumbers"][()]
    symmetric = math.sqrt(1600.0 / (15.999 * U_KG)) / (2 * math.pi * C_CM)
    assert symmetric == pytest.approx(1302.8, abs=0.1)
    assert min(abs(wavenumbers - symmetric)) < 1e-6 * symmetric


def test_normal_modes_unit_errors_name_the_array_item():
    found = problems(CO2_SI.replace('k = "1600 N/m"', 'k = "1600 kg"'))
    assert len(found) == 1
    assert "key 'bonds.0.k': must be a spring constant in N/m" in found[0]
    assert "(got '1600 kg')" in found[0]


def test_dimensionless_keys_take_text_numbers():
    config = scene(pendulum_text().replace("samples = 1001",
                                           'samples = 1001\nrtol = "1e-10"')).config
    assert config.run.rtol == 1e-10


def test_a_range_error_on_an_angle_in_degrees_hints_at_deg():
    text = (REPO / "configs" / "heavy_top_fig4.3a.toml").read_text()
    found = problems(text.replace("theta = 0.872664625997165", "theta = 50", 1))
    assert found == ["<archive config>: key 'initial.theta': must satisfy 0 ≤ θ < π (got 50.0); "
                     'angles are in rad; write "50 deg" for degrees']
    config = scene(text.replace("theta = 0.872664625997165", 'theta = "50 deg"', 1)).config
    assert config.initial.theta == pytest.approx(0.872664625997165, rel=1e-14)


def test_units_inside_a_tagged_table():
    text = (REPO / "configs" / "inertia_cone.toml").read_text()
    config = scene(text.replace("euler_angles = [0.4, 0.7, 0.0]",
                                'euler_angles = ["0.4 rad", "700 mrad", "0 deg"]', 1)
                   .replace("height = 2.0", 'height = "200 cm"', 1)).config
    assert config.shape.euler_angles == pytest.approx([0.4, 0.7, 0.0], rel=1e-14)
    assert config.shape.height == pytest.approx(2.0, rel=1e-14)


def test_hertz_is_refused_for_an_angular_rate():
    found = problems(pendulum_text().replace("theta = 1.0", 'theta = 1.0\ntheta_dot = "2 Hz"'))
    assert len(found) == 1 and "key 'initial.theta_dot'" in found[0]
    assert "ambiguous" in found[0] and "(got '2 Hz')" in found[0]


@pytest.mark.parametrize("given, said", [
    ("2 hertz", "ambiguous"), ("2 kHz", "ambiguous"), ("2 dB/s", "is not a unit of angle")])
def test_hertz_spelled_out_is_refused_like_hz(given, said):
    """Issue 48 I: "1 hertz" was taken as 1 rad/s while "Hz" was refused."""
    found = problems(pendulum_text().replace("theta = 1.0", f'theta = 1.0\ntheta_dot = "{given}"'))
    assert len(found) == 1 and "key 'initial.theta_dot'" in found[0] and said in found[0], found


@pytest.mark.parametrize("given", ["1 dB", "1 neper", "1 byte", "1 percent", "1 grade"])
def test_pure_numbers_that_are_no_angle_are_refused_for_an_angle(given):
    """Issue 48 I: pint counts angles as pure numbers, so "1 dB" was 1.26 rad, "1 byte"
    8 rad; only units of angle convert to one ("40 deg", "1 turn", "700 mrad")."""
    found = problems(pendulum_text().replace("theta = 1.0", f'theta = "{given}"'))
    assert len(found) == 1 and "key 'initial.theta'" in found[0], found
    assert "is not a unit of angle" in found[0], found
    for fine, rad in (("1 turn", 2 * math.pi), ("700 mrad", 0.7), ("30 arcmin", math.pi / 360)):
        assert scene(pendulum_text().replace("theta = 1.0", f'theta = "{fine}"')
                     ).config.initial.theta == pytest.approx(rad, rel=1e-14)
