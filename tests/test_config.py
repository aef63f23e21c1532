"""Config validation: every rule gives one line naming file, key, rule and value; exit 2."""

from __future__ import annotations

import pytest

from conftest import pendulum_text
from reportgen.config import ConfigError, read_config
from reportgen.scenes import load_scene


def problems(path):
    with pytest.raises(ConfigError) as info:
        load_scene(read_config(path))
    return info.value.problems


@pytest.mark.parametrize(
    ("edit", "key", "rule"),
    [
        (("l = 1.0", "l = -1.0"), "params.l", "greater than 0"),
        (("l = 1.0", "l = 0.0"), "params.l", "greater than 0"),
        (("g = 9.81", "g = 0"), "params.g", "greater than 0"),
        (("samples = 1001", "samples = 1"), "run.samples", "greater than or equal to 2"),
        (("t_end = 10.0", "t_end = -5.0"), "run.t_end", "greater than 0"),
        (("t_end = 10.0", "t_end = 0.0"), "run.t_end", "greater than 0"),
        (("g = 9.81", 'g = "9.81"'), "params.g", "valid number"),
        (("l = 1.0", "l = nan"), "params.l", "finite"),
        (("t_end = 10.0", "t_end = inf"), "run.t_end", "finite"),
        (("g = 9.81", "g = 9.81\nmass = 2.0"), "params.mass", "unknown key"),
        (("[run]", "[rum]"), "rum", "unknown key"),
        (("theta = 1.0", "theta_dot = 0.0"), "initial.theta", "required key is missing"),
        (("samples = 1001", "samples = 10.5"), "run.samples", "valid integer"),
    ],
)
def test_each_rule_names_file_key_rule_and_value(write_config, edit, key, rule):
    path = write_config("bad", pendulum_text().replace(*edit, 1))
    found = problems(path)
    assert any(str(path) in p and f"'{key}'" in p and rule in p for p in found), found


def test_value_received_is_quoted(write_config):
    path = write_config("bad", pendulum_text().replace("l = 1.0", "l = -3.5"))
    assert "(got -3.5)" in problems(path)[0]


def test_all_problems_reported_in_one_pass(write_config):
    text = pendulum_text().replace("l = 1.0", "l = -1.0").replace("samples = 1001", "samples = 0")
    assert len(problems(write_config("bad", text))) == 2


def test_unknown_kind_and_missing_kind(write_config):
    assert "key 'kind'" in problems(write_config("a", 'kind = "pendulm"\n'))[0]
    assert "key 'kind': required" in problems(write_config("b", 'title = "x"\n'))[0]


def test_unknown_section_is_an_error(write_config):
    text = pendulum_text(extra='\n[report]\nsections = ["polhode"]\n')
    (line,) = problems(write_config("bad", text))
    assert "report.sections" in line and "polhode" in line and "time_series" in line


def test_unknown_method_and_preset(write_config):
    text = pendulum_text().replace("study = false", 'study = false\nmethod = "euler"')
    assert "run.method" in problems(write_config("m", text))[0]
    assert "key 'preset'" in problems(write_config("p", 'kind = "pendulum"\npreset = "nope"\n'))[0]


def test_broken_toml_is_one_line(write_config):
    (line,) = problems(write_config("broken", "kind = \"pendulum\"\n[params\n"))
    assert "invalid TOML" in line and "broken.toml" in line


def test_separatrix_state_rejected(write_config):
    # g = 4, l = 1: ω0 = 2, and θ̇0 = 2 ω0 from the bottom is exactly the separatrix (k = 1)
    text = pendulum_text(theta=0.0).replace("g = 9.81", "g = 4.0").replace(
        "theta = 0.0", "theta = 0.0\ntheta_dot = 4.0")
    assert any("separatrix" in p for p in problems(write_config("sep", text)))


def test_state_just_off_the_separatrix_is_accepted(write_config):
    # θ0 = π − 1e-8: k² rounds to 1 but 1 − k² = 2.5e-17 is still resolved
    load_scene(read_config(write_config("near", pendulum_text(theta=3.1415926435897931))))


def test_preset_is_overridden_by_explicit_keys(write_config):
    path = write_config("pre", """
        kind = "pendulum"
        preset = "large_amplitude"
        [initial]
        theta = 0.5
    """)
    scene = load_scene(read_config(path))
    assert scene.config.initial.theta == 0.5
    assert scene.config.params.g == 9.81  # from the preset


def test_cli_validate_exit_2_and_nothing_written(write_config, cli, tmp_path):
    good = write_config("good", pendulum_text())
    bad = write_config("zbad", pendulum_text().replace("l = 1.0", "l = -1.0"))
    out = tmp_path / "out"
    code, _, err = cli("run", good, bad, "--out", out, "--jobs", 1)
    assert code == 2
    assert "zbad.toml: key 'params.l'" in err
    assert "Traceback" not in err
    assert not out.exists()  # nothing run: not even the good scene
    code, out_text, _ = cli("validate", good)
    assert code == 0 and "ok" in out_text


def test_duplicate_scene_names_rejected(tmp_path, cli):
    for sub in ("a", "b"):
        (tmp_path / sub).mkdir()
        (tmp_path / sub / "same.toml").write_text(pendulum_text())
    code, _, err = cli("validate", tmp_path)
    assert code == 2 and "same" in err


def test_missing_path_is_usage_error(cli, tmp_path):
    code, _, err = cli("validate", tmp_path / "nope.toml")
    assert code == 2 and "no such file" in err
