"""Config validation: every rule gives one line naming file, key, rule and value; exit 2."""

from __future__ import annotations

import math

import pytest

from conftest import REPO, pendulum_text
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, read_config


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
    path = write_config("bad", text)
    assert sorted(problems(path)) == [
        f"{path}: key 'params.l': must be greater than 0 (got -1.0)",
        f"{path}: key 'run.samples': must be greater than or equal to 2 (got 0)",
    ]


#: a pendulum with independent problems in three tables, and the line each must give
def _four_problems(path):
    text = (pendulum_text()
            .replace("l = 1.0", "l = -1.0")                                # [params]
            .replace("theta = 1.0", "theta = nan")                         # [initial]
            .replace("samples = 1001", "samples = 1\nstepsize = 0.01"))    # [run], twice
    lines = [f"{path}: key 'params.l': must be greater than 0 (got -1.0)",
             f"{path}: key 'initial.theta': must be a finite number (got nan)",
             f"{path}: key 'run.samples': must be greater than or equal to 2 (got 1)",
             f"{path}: key 'run.stepsize': unknown key (got 0.01)"]
    return text, lines


def test_every_problem_is_one_line_in_one_config_error(write_config, tmp_path):
    path = tmp_path / "many.toml"
    text, lines = _four_problems(path)
    assert write_config("many", text) == path
    assert sorted(problems(path)) == sorted(lines)


def test_cli_validate_reports_every_problem_and_writes_nothing(write_config, cli, tmp_path,
                                                               monkeypatch):
    path = tmp_path / "many.toml"
    text, lines = _four_problems(path)
    write_config("many", text)
    work = tmp_path / "cwd"
    work.mkdir()
    monkeypatch.chdir(work)
    before = sorted(tmp_path.rglob("*"))
    code, out, err = cli("validate", path)
    assert code == 2
    assert out == ""
    assert sorted(err.splitlines()) == sorted(lines)
    assert sorted(tmp_path.rglob("*")) == before  # nothing written, not even an output folder


def test_key_inside_a_union_of_tables_is_the_config_key(write_config):
    # [shape] is one of several tables told apart by `type`: the key is shape.radius,
    # not pydantic's location shape.cone.radius
    path = write_config("cone", """
        kind = "inertia"
        [shape]
        type = "cone"
        mass = 1.0
        radius = -1.0
        height = 1.0
    """)
    assert problems(path) == [f"{path}: key 'shape.radius': must be greater than 0 (got -1.0)"]
    path = write_config("sphere", 'kind = "inertia"\n[shape]\ntype = "sphere"\nmass = 1.0\n')
    (line,) = problems(path)
    assert line.startswith(f"{path}: key 'shape.type': must be one of 'cone', 'box'")
    assert line.endswith("(got 'sphere')")


def test_value_no_alternative_accepts_is_one_problem(write_config):
    # impulse.at is [x, y, z] or "apex": a number is neither, and that is one line
    path = write_config("at", """
        kind = "rigid_body"
        preset = "cone_impulse"
        [impulse]
        P = [1.0, 0.0, 0.0]
        at = 5
    """)
    assert problems(path) == [f"{path}: key 'impulse.at': must be an array or 'apex' (got 5)"]


def test_array_item_and_odd_key_names(write_config):
    path = write_config("nm", """
        kind = "normal_modes"
        "é" = 1
        [[atoms]]
        element = "C"
        position = [0.0, 0.0, 0.0]
        [[atoms]]
        mass = -2.0
        position = [1.0, 0.0, 0.0]
    """)
    assert sorted(problems(path)) == [
        f"{path}: key '\"é\"': unknown key (got 1)",
        f"{path}: key 'atoms.1.mass': must be greater than 0 (got -2.0)",
    ]


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


def test_state_just_off_the_separatrix_is_accepted(write_config, cli):
    # θ0 = π − 1e-8 at rest: k² = sin²(θ0/2) rounds to 1, but 1 − k² = cos²(θ0/2)
    # = sin²(5e-9) = 2.5e-17 is still resolved, so this is libration, not the separatrix
    theta0 = 3.1415926435897931
    assert math.sin(theta0 / 2) ** 2 == 1.0
    assert math.cos(theta0 / 2) ** 2 == pytest.approx(2.5e-17, rel=1e-6)
    path = write_config("near", pendulum_text(theta=theta0))
    scene = load_scene(read_config(path))
    assert scene.kind == "pendulum"
    assert scene.config.initial.theta == theta0 and scene.config.initial.theta_dot == 0.0
    code, out, err = cli("validate", path)
    assert (code, err) == (0, "") and out.startswith(f"{path}: ok (pendulum: ")


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
    code, out, err = cli("validate", tmp_path)
    assert code == 2 and out == ""
    (line,) = err.splitlines()
    first, second = tmp_path / "a" / "same.toml", tmp_path / "b" / "same.toml"
    assert line.startswith(f"{second}: scene name 'same' (the file name) is also used by {first}")


def test_missing_path_is_usage_error(cli, tmp_path):
    code, out, err = cli("validate", tmp_path / "nope.toml")
    assert (code, out) == (2, "")
    assert err == f"reportgen: {tmp_path / 'nope.toml'}: no such file or folder\n"


def test_rigid_body_problems_in_different_tables_come_together(write_config, cli):
    """A missing [run] and I3 > I1 + I2 are both reported in one run (the triangle rule
    lives on the [params] table, so it is checked even when another table fails)."""
    path = write_config("rb", """
        kind = "rigid_body"
        [params]
        I1 = 1.0
        I2 = 1.0
        I3 = 3.0
        [initial]
        omega = [0.1, 0.2, 1.0]
        """)
    code, out, err = cli("validate", path)
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert any(f"{path}: key 'run': required key is missing" in line for line in lines), err
    assert any(str(path) in line and "params.I3" in line and "triangle inequality" in line
               and "I3 = 3.0" in line for line in lines), err


# ------------------------------------------- validate builds the models (run.method fits)
#: every shipped config, and those whose validated config (presets applied) has [run]
SHIPPED = sorted((REPO / "configs").glob("*.toml"))
SHIPPED_WITH_RUN = [p for p in SHIPPED if load_scene(read_config(p)).config.run is not None]


def _with_method(text: str, method: str) -> str:
    """``text`` with ``method`` set in its [run] table (added when the file has none)."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.strip() == "[run]":
            lines.insert(i + 1, f'method = "{method}"')
            return "\n".join(lines) + "\n"
    return text.rstrip("\n") + f'\n\n[run]\nmethod = "{method}"\n'


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_models_exactly_when_the_config_integrates(path):
    """models() is what [run] integrates: none for inertia or normal modes without
    [evolve] (neither has a [run]), at least one model for every other shipped config."""
    scene = load_scene(read_config(path))
    models = scene.models()
    assert bool(models) == (scene.config.run is not None), (path.name, models)
    if scene.kind == "inertia" or (scene.kind == "normal_modes" and scene.config.evolve is None):
        assert models == []
    for model in models:
        assert model.dim == len(model.columns) > 0
    scene.build_models()  # the shipped method ("auto") accepts every model


@pytest.mark.parametrize("path", SHIPPED_WITH_RUN, ids=lambda p: p.stem)
def test_models_are_the_ones_simulate_integrates(path, monkeypatch):
    """The first model simulate() passes to integrate() is models()[0] (same system)."""

    class Integrated(Exception):
        pass

    def integrate(model, *args, **kwargs):
        raise Integrated(model)

    scene = load_scene(read_config(path))
    (expected, *_) = scene.models()
    monkeypatch.setattr(scene, "integrate", integrate)
    with pytest.raises(Integrated) as info:
        scene.simulate()
    (model,) = info.value.args
    assert (model.name, list(model.columns), model.separable is None) == (
        expected.name, list(expected.columns), expected.separable is None)


@pytest.mark.parametrize("path", SHIPPED_WITH_RUN, ids=lambda p: p.stem)
def test_validate_rejects_a_splitting_method_on_a_non_separable_model(path, write_config, cli,
                                                                      tmp_path):
    """yoshida6 needs H = T(p) + V(q): `validate` (and `run`, before anything runs) exits 2
    naming file, key and reason for every shipped config whose model has no separable
    form, and accepts it for the others."""
    config = write_config(path.stem, _with_method(path.read_text(), "yoshida6"))
    try:
        scene = load_scene(read_config(config))
    except ConfigError as exc:
        # a two_center sweep locates its surface of section's crossings on DOP853's steps:
        # another named method is refused by name whatever the model
        assert "a two_center [sweep] locates each member's crossings" in str(exc), exc
        code, out, err = cli("validate", config)
        assert code == 2 and out == "" and f"{config}: key 'run.method'" in err, err
        return
    assert scene.config.run.method == "yoshida6"
    models = scene.models()
    assert models, "a config with [run] integrates some model"
    non_separable = [m for m in models if m.separable is None]
    code, out, err = cli("validate", config)
    if not non_separable:
        assert (code, err) == (0, "") and out.startswith(f"{config}: ok")
        return
    assert code == 2 and out == "" and "Traceback" not in err
    assert any(line.startswith(f"{config}: key 'run.method'") and "separable" in line
               and "yoshida6" in line for line in err.splitlines()), err
    out_dir = tmp_path / "out"
    code, _, err = cli("run", config, "--out", out_dir, "--jobs", 1)
    assert code == 2 and "run.method" in err and "separable" in err
    assert not out_dir.exists()


def test_some_shipped_model_is_not_separable():
    """The rejection above is exercised: some shipped config integrates a model with no
    separable form (the rigid body, the heavy top)."""
    scenes = [load_scene(read_config(p)) for p in SHIPPED_WITH_RUN]
    kinds = {s.kind for s in scenes if any(m.separable is None for m in s.models())}
    assert {"rigid_body", "heavy_top"} <= kinds, kinds
