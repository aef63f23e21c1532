"""The step a config asks for is the step the run takes, or the config is refused.

A fixed-step method steps from output to output, so ``run.h`` must divide the output
spacing t_end/(samples − 1) into whole steps; an adaptive method (or ``auto``) takes no
step.  Anything else is exit 2 with the reason and a value that would work, from
``validate`` and ``run`` alike — never a silent change of step (issue: ``h = 0.6`` with
RK4 once ran at the output spacing 0.015, 40 times smaller, while the report said 0.6).
"""

from __future__ import annotations

import json

import h5py
import numpy as np
import pytest

from conftest import pendulum_text
from reportgen.core.integrators import METHODS
from reportgen.scene.integration import step_problem

FIXED = sorted(name for name, m in METHODS.items() if not m.adaptive)
ADAPTIVE = sorted(name for name, m in METHODS.items() if m.adaptive)


def test_the_fixed_step_methods_are_the_ones_we_think():
    assert FIXED == ["gauss4", "gauss6", "rk4", "verlet", "yoshida4", "yoshida6", "yoshida8"]


@pytest.mark.parametrize("method", FIXED)
def test_every_fixed_step_method_runs_at_the_requested_step(method, write_config, cli,
                                                            tmp_path):
    """h = 0.05 with outputs 0.1 apart: two steps per output, archived h = 0.05 and
    twice as many steps as outputs; the energy of the pendulum stays bounded (a
    step this size is well inside every method's stability interval: ω h = 0.16)."""
    config = write_config("p", pendulum_text(theta=0.5, t_end=10.0, samples=101,
                                             extra=f'method = "{method}"\nh = 0.05\n'))
    code, _, err = cli("run", config, "--out", tmp_path / "o", "--format", "html")
    assert code in (0, 1), err  # 1: "inaccurate" is a verdict, not a refusal
    with h5py.File(tmp_path / "o" / "p" / "run.h5") as f:
        run = f["runs/main"]
        assert run.attrs["method"] == method
        assert run.attrs["h"] == pytest.approx(0.05, rel=1e-12)
        assert run.attrs["nsteps"] == 200
        energy = run["invariants/energy"][()]
        assert np.all(np.isfinite(energy))


def test_h_06_with_rk4_runs_at_06_and_is_flagged(write_config, cli, tmp_path):
    """The issue's case made honourable: h = 0.6 with one output per step runs at 0.6,
    and RK4 at ω h = 1.9 on θ0 = 1 rad loses energy fast: the run is flagged unstable
    (exit 1), never drawn as ok."""
    config = write_config("rk4", pendulum_text(theta=1.0, t_end=30.0, samples=51,
                                               extra='method = "rk4"\nh = 0.6\n'))
    code, _, err = cli("run", config, "--out", tmp_path / "o", "--format", "html")
    assert code == 1 and "unstable" in err, err
    with h5py.File(tmp_path / "o" / "rk4" / "run.h5") as f:
        assert f["runs/main"].attrs["h"] == pytest.approx(0.6, rel=1e-12)
        assert f["runs/main"].attrs["nsteps"] == 50
        assert f.attrs["status"] == "unstable"
    # its pages still pass the document gate (no marker at the NaN measured period)
    assert json.loads((tmp_path / "o" / "rk4" / "gate.json").read_text()) == []
    assert "step h = 0.6 s" in (tmp_path / "o" / "rk4" / "report.html").read_text()


@pytest.mark.parametrize("samples, h, words", [
    (2001, 0.6, "samples = 51 (an output after every step)"),  # the config
    (2001, 0.7, "h = t_end/n for a whole n with samples = n + 1 (n = 42"),
    (2001, 0.01, "h = 0.0075 (2 steps) or 0.015 (1) would"),
])
def test_a_step_that_cannot_be_honoured_is_refused_by_validate_and_run(
        samples, h, words, write_config, cli, tmp_path):
    config = write_config("bad", pendulum_text(t_end=30.0, samples=samples,
                                               extra=f'method = "rk4"\nh = {h}\n'))
    for command in (("validate",), ("run", "--out", tmp_path / "o")):
        code, _, err = cli(command[0], config, *command[1:])
        assert code == 2, err
        assert f"{config}: key 'run.h': " in err and words in err and f"(got {h:g})" in err
        assert err.count("\n") == 1
    assert not (tmp_path / "o" / "bad").exists()


@pytest.mark.parametrize("method", [*ADAPTIVE[:3], "auto"])
def test_a_step_given_to_an_adaptive_method_is_refused(method):
    problem = step_problem(method, 0.01, 10.0, 1001)
    assert problem is not None and "(got 0.01)" in problem


def test_decimal_steps_that_divide_the_spacing_pass():
    """0.005 / 0.001 is 5.000000000000001 in binary: a whole number of steps."""
    assert step_problem("rk4", 0.001, 10.0, 2001) is None
    assert step_problem("verlet", 0.1, 0.3, 4) is None
    assert step_problem("gauss6", None, 10.0, 2001) is None
    assert step_problem("dop853", None, 10.0, 2001) is None
