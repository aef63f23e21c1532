"""Edges of the command line (issue 32 C): one kind and its presets from `reportgen kinds`,
"did you mean" for misspelled keys, one message form, `validate` refusing what `run`
refuses, `validate --resolved`, and `figures CONFIG --out` writing where `run` does."""

from __future__ import annotations

import tomllib

import pytest

from conftest import pendulum_text
from reportgen.kinds import KINDS

HEAVY_TOP = """\
kind = "heavy_top"

[params]
I1 = 1.0
I3 = 0.5
Mgl = 1.0

[initial]
theta = 0.8726646259971648
theta_dot = 0.0
phi_dot = -0.3168071689827444
{omega3} = 5.0

[run]
{t_end} = 32.0
{samples} = 3201
"""


def heavy_top(omega3="omega3", t_end="t_end", samples="samples") -> str:
    return HEAVY_TOP.format(omega3=omega3, t_end=t_end, samples=samples)


# -------------------------------------------------------------- did you mean
@pytest.mark.parametrize("wrong, key, meant, got", [
    ({"omega3": "omgea3"}, "initial.omgea3", "omega3", "5.0"),
    ({"t_end": "tend"}, "run.tend", "t_end", "32.0"),
    ({"samples": "sample"}, "run.sample", "samples", "3201"),
])
def test_a_misspelled_key_is_one_message_with_did_you_mean(write_config, cli, wrong, key,
                                                           meant, got):
    path = write_config("top", heavy_top(**wrong))
    code, out, err = cli("validate", path)
    assert code == 2 and out == ""
    lines = err.splitlines()
    assert lines == [f"{path}: key '{key}': unknown key; did you mean '{meant}'? (got {got})"]


def test_three_misspellings_give_three_lines_and_no_missing_key(write_config, cli):
    path = write_config("top", heavy_top("omgea3", "tend", "sample"))
    code, _, err = cli("validate", path)
    assert code == 2
    assert "required key is missing" not in err
    assert sorted(err.splitlines()) == sorted([
        f"{path}: key 'initial.omgea3': unknown key; did you mean 'omega3'? (got 5.0)",
        f"{path}: key 'run.tend': unknown key; did you mean 't_end'? (got 32.0)",
        f"{path}: key 'run.sample': unknown key; did you mean 'samples'? (got 3201)",
    ])


def test_an_unknown_key_close_to_nothing_gets_no_guess(write_config, cli):
    path = write_config("top", heavy_top().replace("phi_dot =", "zzzzzz = 1.0\nphi_dot ="))
    code, _, err = cli("validate", path)
    assert code == 2
    assert err.splitlines() == [f"{path}: key 'initial.zzzzzz': unknown key (got 1.0)"]


# ---------------------------------------------------------- one message form
def test_a_scene_rule_naming_its_key_reads_like_every_other_message(write_config, cli):
    """heavy_top raises "params.I3: ..." itself; the line shows it as key 'params.I3'."""
    path = write_config("top", heavy_top().replace("I3 = 0.5", "I3 = 2.5"))
    code, _, err = cli("validate", path)
    assert code == 2
    (line,) = err.splitlines()
    assert line.startswith(f"{path}: key 'params.I3': a symmetric body needs I3 ≤ I1 + I2"), line


# -------------------------------------------------------------------- kinds
def test_kinds_one_kind_lists_its_keys_sections_and_presets_in_words(cli):
    code, out, err = cli("kinds", "heavy_top")
    assert code == 0 and err == ""
    lines = out.splitlines()
    assert lines[0].startswith("heavy_top — ")
    assert not any(line.split(" — ")[0] in KINDS for line in lines[1:]
                   if not line.startswith(" "))  # no other kind
    assert any(line.split()[:1] == ["t_end"] and "end time of the integration [s]" in line
               for line in lines)  # the shared [run] keys, with their units
    assert any(line.strip().startswith("sections: ") for line in lines)
    # each preset in words, the title its config alone gets
    fig = next(line for line in lines if line.strip().startswith("fig4.3a "))
    assert "looping nutation" in fig
    assert len(lines) < 80  # against 358 for every kind


def test_kinds_shows_free_key_tables_as_tables_not_dicts(cli):
    code, out, _ = cli("kinds", "hamiltonian")
    assert code == 0 and "dict[" not in out
    rows = {line.split()[0]: line for line in out.splitlines() if line.strip()}
    assert "optional table of free keys: name = number" in rows["[params]"]
    assert "required table of free keys: name = number" in rows["[initial]"]
    assert "optional table of free keys: name = text" in rows["[observables]"]


def test_kinds_presets_lists_each_preset_and_its_key_values(cli):
    code, out, err = cli("kinds", "pendulum", "--presets")
    assert code == 0 and err == ""
    lines = out.splitlines()
    presets = KINDS["pendulum"].presets
    for name, data in presets.items():
        i = next(i for i, line in enumerate(lines) if line.startswith(f"  {name} — "))
        assert "Plane pendulum" in lines[i]
        block = []
        for line in lines[i + 1:]:
            if not line.startswith("      "):
                break
            block.append(line.strip().split(" = ", 1))
        values = dict(block)
        assert float(values["initial.theta"]) == data["initial"]["theta"]
    code, every, _ = cli("kinds", "--presets")
    assert code == 0 and out.strip() in every
    for cls in KINDS.values():
        for name in cls.presets:
            assert f"  {name} — " in every, name


def test_kinds_unknown_kind_is_usage_with_did_you_mean(cli):
    code, out, err = cli("kinds", "heavytop")
    assert code == 2 and out == ""
    assert "no kind 'heavytop'; did you mean 'heavy_top'?" in err
    code, _, err = cli("kinds", "heavytop", "--presets")
    assert code == 2 and "did you mean 'heavy_top'?" in err


# ---------------------------------------------------- validate refuses as run
@pytest.mark.parametrize("lagrangian", ["q_dot*q - q**2/2", "q_dot - q**2/2"])
def test_validate_refuses_a_singular_lagrangian(write_config, cli, lagrangian):
    """L linear in q̇ with one coordinate: ∂²L/∂q̇² = 0, no Legendre transform, and as a
    first-order Lagrangian its ω is 1 × 1 antisymmetric, so zero: run refuses it, so does
    validate, with that reason."""
    path = write_config("sing", f"""\
        kind = "hamiltonian"
        [system]
        coordinates = ["q"]
        L = "{lagrangian}"
        [initial]
        q = 1.0
        q_dot = 0.0
        [run]
        t_end = 1.0
        """)
    code, out, err = cli("validate", path)
    assert code == 2 and out == ""
    assert err.startswith(f"{path}: key 'system.L': ") and "det ω = 0" in err, err


def test_validate_passes_a_regular_lagrangian(write_config, cli):
    path = write_config("reg", """\
        kind = "hamiltonian"
        [system]
        coordinates = ["q"]
        L = "q_dot**2/2 - q**2/2"
        [initial]
        q = 1.0
        q_dot = 0.0
        [run]
        t_end = 1.0
        """)
    code, out, err = cli("validate", path)
    assert code == 0 and "ok (hamiltonian" in out, err


# --------------------------------------------------------- validate --resolved
def test_validate_resolved_is_toml_with_the_preset_overrides_and_defaults(write_config, cli):
    path = write_config("p", 'kind = "pendulum"\npreset = "large_amplitude"\n'
                             "[run]\nsamples = 501\n")
    code, out, err = cli("validate", "--resolved", path)
    assert code == 0, err
    resolved = tomllib.loads(out)
    preset = KINDS["pendulum"].presets["large_amplitude"]
    assert resolved["params"] == {**resolved["params"], **preset["params"]}
    assert resolved["initial"] == {**resolved["initial"], **preset["initial"]}
    assert resolved["run"]["t_end"] == preset["run"]["t_end"]
    assert resolved["run"]["samples"] == 501  # the config's own key wins
    assert resolved["run"]["method"] == "auto" and resolved["run"]["rtol"] == 1e-12  # defaults
    # and the resolved text is itself a config that validates to the same scene
    again = write_config("again", out)
    code, out2, err = cli("validate", "--resolved", again)
    assert code == 0, err
    assert tomllib.loads(out2) == resolved


# ------------------------------------------------------------------ figures
def test_figures_config_out_is_the_output_root_as_in_run(write_config, tmp_path, cli,
                                                         monkeypatch):
    monkeypatch.chdir(tmp_path)  # a run into ./output would show here
    config = write_config("p3", pendulum_text(t_end=3.0, samples=201,
                                              extra='[report]\nformats = ["html"]\n'))
    root = tmp_path / "runs"
    code, _, err = cli("figures", config, "--out", root, "--format", "svg")
    assert code == 0, err
    assert (root / "p3" / "run.h5").exists()  # where `reportgen run --out runs` puts it
    assert list((root / "p3" / "figures-report").glob("*.svg"))
    assert not (tmp_path / "output").exists()
    code, _, err = cli("figures", config, "--out", root, "--root", tmp_path / "else")
    assert code == 2 and "--out and --root" in err
    # an archive and an output root: the files go to ROOT/<scene>/, as `run` lays it out
    archive = root / "p3" / "run.h5"
    code, _, err = cli("figures", archive, "--out", tmp_path / "talk", "--format", "svg",
                       "--only", "time_series*")
    assert code == 0, err
    assert list((tmp_path / "talk" / "p3" / "figures-report").glob("time_series*.svg"))
    # animate takes a config too; --out and --root mean the same output root
    code, _, err = cli("animate", config, "--root", root, "--format", "gif", "--dpi", "30",
                       "--fps", "10", "--duration", "3")
    assert code == 0, err
    assert (root / "p3" / "animation.gif").exists()
    code, _, err = cli("animate", archive, "--out", tmp_path / "talk", "--format", "gif",
                       "--dpi", "30", "--fps", "10", "--duration", "3")
    assert code == 0, err
    assert (tmp_path / "talk" / "p3" / "animation.gif").exists()
    assert not (tmp_path / "output").exists()


@pytest.mark.parametrize("text, line", [
    ('kind = "heavytop"\n', "key 'kind': must be one of {kinds}; did you mean 'heavy_top'? "
                            "(got 'heavytop')"),
    ('kind = "pendulum"\npreset = "smallangle"\n',
     "key 'preset': must be one of large_amplitude, near_separatrix, rotation, small_angle; "
     "did you mean 'small_angle'? (got 'smallangle')"),
])
def test_a_misspelled_kind_or_preset_gets_did_you_mean(write_config, cli, text, line):
    path = write_config("k", text)
    code, _, err = cli("validate", path)
    assert code == 2
    assert err.splitlines() == [f"{path}: " + line.format(kinds=", ".join(KINDS))]


# ------------------------------------------------------ a terminal without Unicode
def test_inspect_on_an_ascii_terminal_escapes_what_it_cannot_print(tmp_path, cli):
    """Issue 48 G: `inspect` of an archive under a non-ASCII path, its output encoding
    ASCII (PYTHONIOENCODING=ascii, LC_ALL=C), ended in exit 1 and a UnicodeEncodeError;
    the characters are printed as escapes."""
    import os
    import subprocess
    import sys

    folder = tmp_path / "ünïcødé"
    folder.mkdir()
    config = folder / "θ.toml"
    config.write_text(pendulum_text(t_end=1.0, samples=51, title="pendule à θ = 1")
                      + '\n[report]\nformats = ["html"]\n', encoding="utf-8")
    code, _, err = cli("run", config, "--out", folder / "öut", "--jobs", "1")
    assert code == 0, err
    proc = subprocess.run([sys.executable, "-m", "reportgen", "inspect",
                           str(folder / "öut" / "θ" / "run.h5")], capture_output=True,
                          env={**os.environ, "PYTHONIOENCODING": "ascii"}, timeout=120)
    assert proc.returncode == 0, proc.stderr.decode("ascii", "replace")
    out = proc.stdout.decode("ascii")  # nothing but ASCII came out
    assert "\\xfcn\\xef" in out and "pendule \\xe0 \\u03b8 = 1" in out
