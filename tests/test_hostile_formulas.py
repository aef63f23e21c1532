"""Issue 35, items 5-7: aliased and non-normalized names, formula size limits, user errors
that used to crash, nested TOML, and the default wall-clock limit of a batch."""

from __future__ import annotations

import contextlib
import io
import textwrap
from pathlib import Path

import pytest

from reportgen.commands.cli import main
from reportgen.core import expressions


def _cli(*args) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = main([str(a) for a in args])
    return code, err.getvalue()


def _hamiltonian(system: str, initial: str, extra: str = "") -> str:
    return textwrap.dedent(f"""
        kind = "hamiltonian"
        [run]
        t_end = 1.0
        samples = 11
        study = false
        [system]
        {system}
        [initial]
        {initial}
        {extra}
        """)


def _refused(tmp_path, text: str, *needles: str) -> str:
    cfg = tmp_path / "scene.toml"
    cfg.write_text(text, encoding="utf-8")
    code, err = _cli("validate", cfg)
    assert code == 2, err
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1 and "Traceback" not in err, err
    for needle in needles:
        assert needle in lines[0], lines[0]
    return lines[0]


# ------------------------------------------------------------------ item 5: names
@pytest.mark.parametrize("system, initial, what", [
    ('coordinates = ["x", "p_x"]\nH = "p_x**2/2 + p_p_x**2/2 + x**2/2"',
     "x = 1.0\np_x = 0.0\np_p_x = 0.0", "momentum of 'x'"),
    ('coordinates = ["x", "x_dot"]\nL = "x_dot**2/2 - x**2/2"',
     "x = 1.0\nx_dot = 0.0\nx_dot_dot = 0.0", "velocity of 'x'"),
])
def test_aliased_coordinates_are_refused(tmp_path, system, initial, what):
    _refused(tmp_path, _hamiltonian(system, initial), "system.coordinates", what)


def test_full_width_name_in_a_formula_is_refused(tmp_path):
    _refused(tmp_path, _hamiltonian('coordinates = ["x"]\nH = "p_x**2/2 + ｘ**2/2"',
                                    "x = 1.0\np_x = 0.0"), "system.H", "'ｘ'", "'x'", "NFKC")


@pytest.mark.parametrize("name, why", [("ｑ", "NFKC"), ("lambda", "keyword"),
                                       ("I", "reserved"), ("sin", "reserved")])
def test_unusable_coordinate_names(tmp_path, name, why):
    _refused(tmp_path, _hamiltonian(f'coordinates = ["{name}"]\nH = "p_{name}**2/2"',
                                    f"\"{name}\" = 1.0\n\"p_{name}\" = 0.0"), "system.coordinates", why)


def test_full_width_constant_name_is_refused(tmp_path):
    _refused(tmp_path, _hamiltonian('coordinates = ["x"]\nH = "p_x**2/2 + x**2/2"',
                                    "x = 1.0\np_x = 0.0", "[params]\n\"ｋ\" = 1.0"),
             "params.", "NFKC")


# ------------------------------------------------------------------ item 6: limits
@pytest.mark.parametrize("H", ["p_x**2/2 + x**64**64", "p_x**2/2 + ((x**64)**64)**64",
                               "(x + p_x + 1)**64", "p_x**2/2 + x**40"])
def test_formula_degree_is_bounded(tmp_path, H):
    _refused(tmp_path, _hamiltonian(f'coordinates = ["x"]\nH = "{H}"', "x = 0.1\np_x = 0.0"),
             "system.H", f"total degree above {expressions.MAX_DEGREE}")


def test_formula_node_count_is_bounded(tmp_path):
    group = "(" + " + ".join(["x*p_x"] * 30) + ")"
    H = " + ".join([group] * 4)
    assert len(H) < expressions.MAX_LENGTH
    _refused(tmp_path, _hamiltonian(f'coordinates = ["x"]\nH = "{H}"', "x = 0.1\np_x = 0.0"),
             "system.H", f"larger than {expressions.MAX_NODES} nodes")


def test_too_many_observables(tmp_path):
    obs = "\n".join(f'o{i} = "x*{i}"' for i in range(300))
    _refused(tmp_path, _hamiltonian('coordinates = ["x"]\nH = "p_x**2/2 + x**2/2"',
                                    "x = 0.1\np_x = 0.0", "[observables]\n" + obs),
             "observables", f"at most {expressions.MAX_OBSERVABLES}")


# ------------------------------------------------------------------ item 7: user errors
@pytest.mark.parametrize("piece", ["sqrt(-1)", "log(0)", "acos(2)", "(-1)**0.5"])
def test_non_real_constants_refused_at_validation(tmp_path, piece):
    _refused(tmp_path, _hamiltonian(f'coordinates = ["x"]\nH = "p_x**2/2 + x**2/2 + {piece}*x"',
                                    "x = 0.1\np_x = 0.0"), "system.H", "finite real")


def test_unreachable_energy_is_refused(tmp_path):
    _refused(tmp_path, _hamiltonian('coordinates = ["x"]\nH = "p_x**2/2 - exp(-p_x**2)"',
                                    "x = 0.0\nenergy = 1e30"), "initial.energy",
             "not reachable", "[-1,")


def test_pendulum_with_absurd_gravity_is_refused(tmp_path):
    _refused(tmp_path, textwrap.dedent("""
        kind = "pendulum"
        [params]
        g = 1e300
        l = 1.0
        [initial]
        theta = 1.0
        [run]
        t_end = 1.0
        """), "params.g", "energy scale")
    _refused(tmp_path, textwrap.dedent("""
        kind = "pendulum"
        [params]
        g = 1e20
        l = 1.0
        [initial]
        theta = 1.0
        [run]
        t_end = 1.0
        """), "params.g", "periods")


@pytest.mark.parametrize("depth", [40, 10000])
def test_deeply_nested_toml(tmp_path, depth):
    _refused(tmp_path, 'kind = "pendulum"\nx = ' + "[" * depth + "]" * depth,
             "config nesting too deep")


def test_free_particle_runs(tmp_path):
    cfg = tmp_path / "free.toml"
    cfg.write_text(_hamiltonian('coordinates = ["x"]\nH = "p_x**2/2"', "x = 0.0\np_x = 1.0"))
    code, err = _cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err


def test_three_body_names_are_text(tmp_path):
    cfg = tmp_path / "tb.toml"
    cfg.write_text(textwrap.dedent(r"""
        kind = "three_body"
        preset = "figure_eight"
        names = ["$\\frac{", "$", "a $b"]
        [run]
        t_end = 1.0
        study = false
        """))
    code, err = _cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err


# ------------------------------------------------------------------ the default time limit
def test_default_time_limit_stops_a_scene_in_process(tmp_path):
    from reportgen.pipeline.stages import run_batch

    cfg = tmp_path / "slow.toml"
    cfg.write_text(textwrap.dedent("""
        kind = "pendulum"
        [params]
        g = 9.81
        l = 1.0
        [initial]
        theta = 1.0
        [run]
        t_end = 1e5
        method = "scipy_dop853"
        """))
    outcomes = run_batch([str(cfg)], out_root=str(tmp_path / "o"), jobs=1, formats=("html",),
                         time_limit=1.0, in_process_limit=True, stream=io.StringIO())
    assert outcomes[0].status == "failed"
    assert "time limit of 1 s exceeded" in outcomes[0].message


def test_time_limit_option():
    from reportgen.commands.cli import DEFAULT_TIME_LIMIT, build_parser

    assert DEFAULT_TIME_LIMIT == 600
    assert build_parser().parse_args(["run", "x", "--time-limit", "0"]).time_limit == 0
    with pytest.raises(SystemExit):
        with contextlib.redirect_stderr(io.StringIO()):
            build_parser().parse_args(["run", "x", "--time-limit", "-1"])


def test_kepler_at_the_origin_ends_with_a_named_status(tmp_path, cli):
    """The shipped Cartesian-to-polar Kepler config with the body at the origin: the run
    ends at once as non-finite (the force is infinite there), the study's scipy peers
    (Radau raises on the NaN Jacobian) are failed rows, not a crash; exit 1, no error.log."""
    import h5py

    text = (Path(__file__).resolve().parent.parent / "configs" /
            "hamiltonian_kepler_polar.toml").read_text(encoding="utf-8")
    config = tmp_path / "origin.toml"
    config.write_text(text.replace("x = 1.0", "x = 0.0"), encoding="utf-8")
    code, _, err = cli("run", config, "--out", tmp_path / "out", "--format", "html",
                       "--jobs", "1")
    assert code == 1 and "Traceback" not in err
    folder = tmp_path / "out" / "origin"
    assert not (folder / "error.log").exists()
    with h5py.File(folder / "run.h5", "r") as f:
        assert f["runs/main"].attrs["solver_status"] == "nonfinite"
        assert "non-finite" in f.attrs["message"]


def _nested_exp(depth: int) -> str:
    text = "x"
    for _ in range(depth):
        text = f"exp({text})"
    return text


@pytest.mark.parametrize("potential, x0", [("log(x)", "0.0"), (_nested_exp(20), "1.0")],
                         ids=["log-at-0", "exp-20-deep"])
def test_an_infinite_force_at_the_start_ends_nonfinite(tmp_path, cli, potential, x0):
    """H = p²/2m + V with V'(x0) infinite (log at 0: −1/x; exp nested 20 deep overflows):
    f(t0, y0) is not finite, so no first step can be chosen.  The adaptive drivers divided
    by the zero step HNW's guess gives when ‖f0‖ = ∞ (ZeroDivisionError, exit 1 with a
    traceback in error.log); they now end at once as non-finite, like any run whose state
    stops being finite."""
    import h5py

    config = tmp_path / "start.toml"
    config.write_text(_hamiltonian('coordinates = ["x"]\nH = "p_x**2/2 + ' + potential + '"',
                                   f"x = {x0}\np_x = 1.0"), encoding="utf-8")
    code, _, err = cli("run", config, "--out", tmp_path / "out", "--format", "html",
                       "--jobs", "1")
    assert code == 1 and "Traceback" not in err and "ZeroDivisionError" not in err
    folder = tmp_path / "out" / "start"
    assert not (folder / "error.log").exists()
    with h5py.File(folder / "run.h5", "r") as f:
        assert f["runs/main"].attrs["solver_status"] == "nonfinite"


def test_the_first_step_survives_a_slope_whose_norm_overflows():
    """Every f0[i] finite (1e200) but ‖f0‖² overflowing: HNW's guess 0.01 ‖y0‖/‖f0‖ is 0,
    and the second-derivative estimate divided by it.  The guess is now the fallback
    10⁻⁶ (capped by the span), and an empty span gives a zero step, not a division."""
    import numpy as np

    from reportgen.core.integrators import compiled

    y0, f0 = np.array([1.0, 2.0]), np.array([1e200, -1e200])
    scale, y1 = np.empty(2), np.empty(2)
    h0, d1 = compiled.initial_guess(y0, f0, 1e-9, 1e-12, 10.0, scale, y1)
    assert d1 == np.inf and h0 == 1e-6
    h = compiled.initial_choice(f0, f0.copy(), h0, d1, scale, 8, 10.0)
    assert 0.0 <= h <= 1e-4
    assert compiled.initial_choice(f0, f0.copy(), 0.0, d1, scale, 8, 0.0) == 0.0


_DEGREE_32 = 'L = "(x_dot**2 + y_dot**2)*(1 + x**2 + y**2)**15/2 - x**2"'


@pytest.mark.parametrize("command", ["validate", "run"])
def test_validation_ends_within_the_time_limit(tmp_path, command):
    """Issue 48 C: a Lagrangian of degree 32, within every formula bound, took 485 s to
    validate (its symbolic work doubles with each +2 of the exponent), and `run
    --time-limit 30` was still validating at 150 s.  Validation now runs under the same
    limit as the run: `validate` exits 2 naming the file and the limit, `run` fails the
    scene as one stopped by its limit (exit 1) and writes nothing of it."""
    import time

    config = tmp_path / "degree32.toml"
    config.write_text(_hamiltonian('coordinates = ["x", "y"]\n' + _DEGREE_32,
                                   "x = 0.1\ny = 0.0\nx_dot = 0.0\ny_dot = 0.1"),
                      encoding="utf-8")
    extra = ["--out", tmp_path / "out"] if command == "run" else []
    start = time.monotonic()
    code, err = _cli(command, config, *extra, "--time-limit", "2")
    assert time.monotonic() - start < 60 and "Traceback" not in err
    assert "time limit of 2 s exceeded while validating it" in err, err
    if command == "validate":  # a config that cannot be validated in time: exit 2
        assert code == 2 and "degree32.toml: time limit" in err
    else:  # a scene stopped by its limit, as when it runs too long: failed, nothing written
        assert code == 1 and not (tmp_path / "out" / "degree32").exists()
