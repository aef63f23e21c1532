"""Units at the edges and `reportgen kinds` (issue 32): every numeric key that `reportgen
kinds` lists declares its unit; the brackets newly given accept unit text where they
should and refuse it where the kind works in the config's own units; a number that reads
as degrees gets the hint; every preset is described, in `kinds` (and on the documentation
site: tests/test_docs.py); the tables' descriptions cite their documents by name."""

from __future__ import annotations

import math
import re

import pytest

from conftest import REPO, pendulum_text
from reportgen.kinds import KINDS, load_scene
from reportgen.scene.config import ConfigError, parse_config_text
from reportgen.scene.schema import quantity_of_description
from reportgen.scene.units import unit_kind

#: the unified atomic mass unit [kg] (CODATA 2018) and 1 mdyn/Å in N/m: the molecular time
#: unit τ = √(u/(mdyn/Å)) of normal_modes (4.075 fs)
U_KG = 1.66053906660e-27
TAU_S = math.sqrt(U_KG / 100.0)


def scene(text: str):
    return load_scene(parse_config_text(text))


def problems(text: str) -> list[str]:
    with pytest.raises(ConfigError) as info:
        scene(text)
    return info.value.problems


# ------------------------------------------------- every listed key has its unit
#: a row of the listing: key, type and rule, default (or required/optional), meaning
_ROW = re.compile(r" {2,}")


def listed_rows(text: str) -> list[tuple[str, str, str]]:
    """(key, type, meaning) of every key row of a `reportgen kinds` listing, and of every
    table of free keys (type "table of free keys: name = number")."""
    rows = []
    for line in text.splitlines():
        parts = _ROW.split(line.strip())
        if len(parts) >= 3 and parts[2].split()[0] in ("required", "optional", "default"):
            rows.append((parts[0], parts[1], parts[3] if len(parts) > 3 else ""))
        elif parts[0].startswith("[") and "table of free keys: " in line:
            free = line.split("table of free keys: ", 1)[1]
            rows.append((parts[0], free.split(" — ")[0], free.partition(" — ")[2]))
    return rows


def is_quantity(kind: str) -> bool:
    """Whether a listed type holds physical numbers: floats (alone, in a union, in arrays)
    and tables of free numbers.  Whole numbers are counts, indices or orders (samples,
    number of masses, atom indices), not quantities; text, flags and names are not."""
    return bool(re.search(r"\bfloat\b", kind)) or kind == "name = number"


def test_every_numeric_key_listed_by_kinds_declares_a_unit(cli):
    code, out, err = cli("kinds")
    assert code == 0 and err == ""
    rows = listed_rows(out)
    assert len(rows) > 250  # every kind's keys and the shared tables, not a parse failure
    quantities = [(key, kind, meaning) for key, kind, meaning in rows if is_quantity(kind)]
    assert len(quantities) > 120
    missing = [f"{key}: {meaning}" for key, kind, meaning in quantities
               if not quantity_of_description(meaning)[1]]
    assert not missing, "numeric keys without a [unit]:\n" + "\n".join(missing)
    unreadable = [f"{key}: {meaning}" for key, kind, meaning in quantities
                  if unit_kind(quantity_of_description(meaning)[1]) == "unreadable"]
    assert not unreadable, "units neither pint, dimensionless, the config's own nor chosen " \
                           "by another key:\n" + "\n".join(unreadable)
    # the known gaps of issue 32, each now with its unit (a check on the parser above too)
    found = {(key, quantity_of_description(meaning)[1]) for key, kind, meaning in quantities}
    for key, unit in [("omega", "dimensionless"), ("G", "config units of length³/(mass·time²)"),
                      ("masses", "config units of mass"), ("rtol", "dimensionless"),
                      ("study_budget", "s"), ("positions", "config units of length"),
                      ("velocities", "config units of length/time"), ("[params]", "config units"),
                      ("[initial]", "config units"), ("M", "per `units`: kg or m₀")]:
        assert (key, unit) in found, (key, unit)


def test_the_listing_parser_sees_the_non_quantities_as_such(cli):
    """Text, flags, names and counts are listed but are not quantities."""
    code, out, _ = cli("kinds", "three_body")
    assert code == 0
    kinds = {key: kind for key, kind, _ in listed_rows(out)}
    assert not is_quantity(kinds["names"]) and not is_quantity(kinds["length_unit"])
    assert not is_quantity(kinds["samples"]) and not is_quantity(kinds["study"])
    assert is_quantity(kinds["period"]) and is_quantity(kinds["positions"])


# ------------------------------------------------ brackets accept the right text
def test_study_budget_in_minutes_and_tolerances_as_pure_numbers():
    config = scene(pendulum_text().replace("samples = 1001", 'samples = 1001\n'
                                           'study_budget = "2 min"\natol = "1e-13"')).config
    assert config.run.study_budget == pytest.approx(120.0, rel=1e-15)  # 2 × 60 s
    assert config.run.atol == 1e-13
    found = problems(pendulum_text().replace("samples = 1001", 'samples = 1001\nrtol = "1e-9 s"'))
    assert len(found) == 1 and "key 'run.rtol': must be a dimensionless number" in found[0]


THREE_BODY = 'kind = "three_body"\npreset = "figure_eight"\n'


@pytest.mark.parametrize("table, key", [
    ('[run]\nt_end = "6.3 yr"\n', "run.t_end"),
    ('[params]\nmasses = ["1 kg", 1.0, 1.0]\n', "params.masses"),
    ('[initial]\npositions = [["1 AU", 0, 0], [-1, 0, 0], [0, 0, 0]]\n', "initial.positions"),
])
def test_keys_in_the_configs_own_units_refuse_unit_text(write_config, cli, table, key):
    path = write_config("tb", THREE_BODY + table)
    code, out, err = cli("validate", path)
    assert code == 2 and out == ""
    (line,) = err.splitlines()
    assert line.startswith(f"{path}: key '{key}': must be a plain number in the config's own "
                           "units"), line
    assert "(got " in line


def test_three_body_plain_numbers_keep_the_configs_units():
    """No conversion: the figure-eight's t_end is its period in its own time unit
    (Simó's 6.32591398 with G = m = 1)."""
    config = scene(THREE_BODY + "[run]\nt_end = 12.0\n").config
    assert config.run.t_end == 12.0
    assert scene(THREE_BODY).config.run.t_end == pytest.approx(6.32591398, rel=1e-9)


def test_a_chain_in_si_converts_its_masses_springs_and_evolution():
    config = scene('kind = "normal_modes"\nunits = "SI"\n[chain]\nn = 3\nm = "2 g"\n'
                   'k = "0.5 kN/m"\n[evolve]\ndisplacement = ["1 cm", 0.0, 0.0]\n'
                   'velocity = ["3 mm/s", 0.0, 0.0]\nt_end = "1 min"\n').config
    assert (config.chain.m, config.chain.k) == pytest.approx((0.002, 500.0), rel=1e-14)
    assert config.evolve.displacement == pytest.approx([0.01, 0.0, 0.0], rel=1e-14)
    assert config.evolve.velocity == pytest.approx([0.003, 0.0, 0.0], rel=1e-14)
    assert config.evolve.t_end == config.run.t_end == pytest.approx(60.0, rel=1e-15)


def test_a_dimensionless_chain_refuses_unit_text():
    found = problems('kind = "normal_modes"\n[chain]\nn = 3\nm = "2 g"\n')
    assert len(found) == 1 and "key 'chain.m': must be a plain number here" in found[0]
    assert "chosen by `units`" in found[0] and "(got '2 g')" in found[0]


def test_a_molecules_evolution_time_in_femtoseconds_is_in_tau():
    """Molecular units: time in τ = √(u/(mdyn/Å)) = 4.075 fs; 100 fs is 100 fs / τ."""
    text = (REPO / "configs" / "normal_modes_co2.toml").read_text()
    config = scene(text + '\n[evolve]\ndisplacement = [["2 pm", 0, 0], [0, 0, 0], [0, 0, 0]]\n'
                          'velocity = [["1 Å/fs", 0, 0], [0, 0, 0], [0, 0, 0]]\n'
                          't_end = "100 fs"\n').config
    assert config.evolve.t_end == pytest.approx(100e-15 / TAU_S, rel=1e-12)
    assert config.run.t_end == config.evolve.t_end
    assert config.evolve.displacement[0][0] == pytest.approx(0.02, rel=1e-14)  # 2 pm in Å
    # 1 Å/fs = (τ / 1 fs) Å/τ
    assert config.evolve.velocity[0][0] == pytest.approx(TAU_S / 1e-15, rel=1e-12)


@pytest.mark.parametrize("potential, k, expected", [
    ("", '"50 J cm"', 0.5),                                    # 50 J·cm = 0.5 J·m
    ('potential = "power"\nn = 1.5\n', '"1 J cm^1.5"', 1e-3),  # (10⁻² m)^1.5 = 10⁻³ m^1.5
])
def test_central_force_strength_in_its_potentials_unit(potential, k, expected):
    text = (REPO / "configs" / "kepler_e07.toml").read_text().replace(
        "k = 0.5", f"{potential}k = {k}", 1)
    assert scene(text).config.params.k == pytest.approx(expected, rel=1e-12)


def test_angles_newly_bracketed_take_degrees():
    config = scene('kind = "rotation"\n[euler]\nangles = ["30 deg", "0.25 turn", 0.1]\n'
                   '[su2]\naxis = [0, 0, 1]\nangle = "270 deg"\n').config
    assert config.euler.angles == pytest.approx([math.pi / 6, math.pi / 2, 0.1], rel=1e-14)
    assert config.su2.angle == pytest.approx(1.5 * math.pi, rel=1e-14)
    config = scene(pendulum_text(extra='\n[boundary]\ntheta0 = "10 deg"\ntheta1 = -0.1\n'
                                       'T = "500 ms"\n')).config
    assert config.boundary.theta0 == pytest.approx(math.radians(10), rel=1e-14)
    assert config.boundary.T == pytest.approx(0.5, rel=1e-15)


def test_fput_is_dimensionless_through_and_through():
    text = 'kind = "fput"\npreset = "gni"\n'
    assert scene(text + '[params]\nomega = "50"\n').config.params.omega == 50.0
    found = problems(text + '[run]\nt_end = "2 s"\n')
    assert len(found) == 1 and "key 'run.t_end': must be a dimensionless number" in found[0]


# -------------------------------------------------------------- the degrees hint
def test_a_pendulum_started_at_40_is_refused_with_the_degrees_hint(write_config, cli):
    path = write_config("p", pendulum_text(theta=40))
    code, out, err = cli("validate", path)
    assert code == 2 and out == ""
    assert err.splitlines() == [f"{path}: key 'initial.theta': must satisfy |θ| ≤ 2π (got 40.0); "
                                'angles are in rad; write "40 deg" for degrees']
    path = write_config("p", pendulum_text(theta='"40 deg"'))
    assert cli("validate", path)[0] == 0


@pytest.mark.parametrize("theta, ok", [(6.0, True), (-6.28, True), (7.0, False),
                                       (-40.0, False)])
def test_a_pendulum_start_within_a_full_turn_is_accepted(theta, ok):
    text = pendulum_text(theta=theta)
    if ok:
        assert scene(text).config.initial.theta == theta
    else:
        (line,) = problems(text)
        assert f'write "{theta:g} deg" for degrees' in line, line


@pytest.mark.parametrize("text, key, hint", [
    # heavy top: 0 ≤ θ < π fails for 4, which in degrees (0.07 rad) it meets
    ((REPO / "configs" / "heavy_top_fig4.3a.toml").read_text().replace(
        "theta = 0.872664625997165", "theta = 4", 1), "initial.theta", "4 deg"),
    ((REPO / "configs" / "heavy_top_fig4.3.toml").read_text().replace(
        'theta_min = "50 deg"', "theta_min = 50", 1).replace(
        'theta_max = "60 deg"', "theta_max = 60", 1), "band.theta_min / band.theta_max",
     "50 deg"),
    ('kind = "rotation"\n[axis_angle]\nangle = 120\n', "axis_angle.angle", "120 deg"),
    ('kind = "rotation"\n[su2]\naxis = [0, 0, 1]\nangle = 100\n', "su2.angle", "100 deg"),
    ('kind = "inertia"\n[shape]\ntype = "cone"\nmass = 1.0\nradius = 0.5\n'
     'height = 2.0\neuler_angles = [0.0, 40, 0.0]\n', "shape.euler_angles", "40 deg"),
    ((REPO / "configs" / "heavy_top_sleeping_stable.toml").read_text()
     + "\n[sleeping]\ntilt = 5\n", "sleeping.tilt", "5 deg"),
])
def test_a_range_rule_failing_for_a_number_meant_in_degrees_hints(text, key, hint):
    (line,) = problems(text)
    assert line.startswith(f"<archive config>: key '{key}': must satisfy "), line
    assert line.endswith(f'; angles are in rad; write "{hint}" for degrees'), line


@pytest.mark.parametrize("text, key", [
    # negative: wrong in degrees too, so no hint
    ((REPO / "configs" / "heavy_top_fig4.3a.toml").read_text().replace(
        "theta = 0.872664625997165", "theta = -0.5", 1), "initial.theta"),
    ('kind = "rotation"\n[axis_angle]\nangle = -1.0\n', "axis_angle.angle"),
])
def test_no_degrees_hint_where_degrees_would_not_help(text, key):
    (line,) = problems(text)
    assert f"key '{key}': must satisfy" in line and "deg" not in line, line


# ------------------------------------------------------------------- presets
def test_kinds_describes_every_preset_of_every_kind(cli):
    for cls in KINDS.values():
        code, out, _ = cli("kinds", cls.kind)
        assert code == 0
        for name in cls.presets:
            line = next((line for line in out.splitlines()
                         if line.strip().split(" ", 1)[0] == name), None)
            assert line is not None, (cls.kind, name)
            words = line.strip()[len(name):].strip()
            assert len(words) > 10 and "needs more keys" not in words, (cls.kind, name, words)


def test_heavy_top_presets_say_which_case_of_fig43_they_show(cli):
    code, out, _ = cli("kinds", "heavy_top")
    lines = {line.split()[0]: line for line in out.splitlines() if line.startswith("      ")}
    for preset, case in [("fig4.3a", "looping"), ("fig4.3b", "wavy"), ("fig4.3c", "cusped")]:
        assert case in lines[preset], lines[preset]
        assert KINDS["heavy_top"].presets[preset]["expect_case"] in ("loops", "waves", "cusps")


# ----------------------------------------------------------------- citations
#: a citation that names no document: "(1.21)", "Fig. 4.3", "exercise 4.6c", "ex. 4.5"
BARE = re.compile(r"(?<!notes )(?<!Goldstein )\(\d+\.\d+[a-z]?\)"
                  r"|(?<!textbook )\bFig\. \d|(?<!textbook )\b(?:ex\.|exercises?) \d")


def test_kinds_cites_documents_by_name(cli):
    code, out, _ = cli("kinds")
    assert code == 0
    code, presets, _ = cli("kinds", "--presets")
    bare = [line.strip() for line in (out + presets).splitlines() if BARE.search(line)]
    assert not bare, "\n".join(bare)
    assert "notes (1.21)" in out and "textbook Fig. 4.3" in out  # what BARE lets through
    assert BARE.search("the boundary-value problem (1.21)") and BARE.search("(exercise 4.6c)")
