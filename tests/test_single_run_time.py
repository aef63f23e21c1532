"""The archived run time (issue 34: a single run's archived wall time against the warm best
of the same run).

A compiled run is rehearsed just before it is timed
(:func:`reportgen.core.integrators.compiled_run.warm_up_run`).  Checked here, without
timing anything that could flake: the rehearsal changes the trajectory in no bit, it is
the run itself (its outputs equal the timed run's, bit for bit), it is bounded, its
seconds are archived beside ``wall_time_s``, and the progress callbacks are outside the
timed run.
"""

from __future__ import annotations

import textwrap
import time

import h5py
import numba
import numpy as np
import pytest

from reportgen.archive.store import write_archive
from reportgen.core.integrators import METHODS, compiled_run, integrate
from reportgen.core.model import OdeModel, Separable
from reportgen.kinds import load_scene
from reportgen.scene.config import parse_config_text


@numba.njit(cache=True)
def osc_rhs(t, y, params, out):
    out[0] = y[1]
    out[1] = -params[0] * y[0]


@numba.njit(cache=True)
def osc_drift(p, params, out):
    out[0] = p[0]


@numba.njit(cache=True)
def osc_kick(q, params, out):
    out[0] = -params[0] * q[0]


def oscillator() -> OdeModel:
    """q'' = −4 q: every compiled method fits it (separable for the compositions)."""
    return OdeModel(name="oscillator", columns=("q", "p"), rhs=osc_rhs,
                    params=np.array([4.0]), separable=Separable(n=1, drift=osc_drift,
                                                                kick=osc_kick))


Y0 = np.array([1.0, 0.5])
T = np.linspace(0.0, 20.0, 2001)
#: one of each compiled driver: erk_adaptive, the written-out DOP853, erk_fixed,
#: splitting_fixed, collocation_fixed
DRIVERS = {"rk45": {"rtol": 1e-9, "atol": 1e-12}, "dop853": {"rtol": 1e-11, "atol": 1e-13},
           "rk4": {"h": 0.005}, "yoshida4": {"h": 0.01}, "gauss4": {"h": 0.01}}


class _Spy:
    """Wraps a method's ``start``: keeps every run it starts, with its output times."""

    def __init__(self, method):
        self.method, self.start, self.runs = method, method.start, []

    def __call__(self, kern, model, y0, t_eval, Y, *args):
        run = self.start(kern, model, y0, t_eval, Y, *args)
        self.runs.append((np.array(t_eval), Y, run))
        return run


@pytest.mark.parametrize("name", DRIVERS)
def test_rehearsal_leaves_the_trajectory_bit_for_bit(name, monkeypatch):
    model, y0 = oscillator(), Y0.copy()
    rehearsed = integrate(model, y0, T, method=name, **DRIVERS[name])
    assert np.array_equal(y0, Y0)  # the rehearsal copied y0, wrote nothing into it
    monkeypatch.setattr(compiled_run, "warm_up_run", lambda *a: 0.0)
    plain = integrate(model, y0, T, method=name, **DRIVERS[name])
    assert rehearsed.ok and plain.ok
    assert np.array_equal(rehearsed.y, plain.y)
    assert (rehearsed.nfev, rehearsed.nsteps, rehearsed.nreject) == (
        plain.nfev, plain.nsteps, plain.nreject)
    assert rehearsed.warm_up_time_s > 0.0 and plain.warm_up_time_s == 0.0


@pytest.mark.parametrize("name", ["dop853", "rk45"])
def test_a_short_run_is_rehearsed_whole(name, monkeypatch):
    """Within the budget the rehearsal is the run itself: the same driver from the same
    state over the same outputs, so its outputs are the timed run's, bit for bit."""
    method = METHODS[name]
    spy = _Spy(method)
    monkeypatch.setattr(method, "start", spy)
    monkeypatch.setattr(compiled_run, "WARM_UP_BUDGET_S", float("inf"))
    sol = integrate(oscillator(), Y0, T, method=name, **DRIVERS[name])
    # the timed run is set up, then rehearsed (_compile's tiny run may come before both)
    (t_run, Y_run, _), (t_warm, Y_warm, _) = spy.runs[-2:]
    assert Y_run is sol.y and np.array_equal(t_run, T)
    assert np.array_equal(t_warm, T) and np.array_equal(Y_warm, sol.y)


def test_the_rehearsal_is_bounded(monkeypatch):
    method = METHODS["dop853"]
    spy = _Spy(method)
    monkeypatch.setattr(method, "start", spy)
    model, kern = oscillator(), compiled_run.kernels_for(oscillator())
    rtol, atol = DRIVERS["dop853"]["rtol"], DRIVERS["dop853"]["atol"]
    # budget spent: the first chunk only (4 outputs)
    monkeypatch.setattr(compiled_run, "WARM_UP_BUDGET_S", 0.0)
    compiled_run.warm_up_run(method, kern, model, Y0, T, rtol, atol, None)
    _t, Y, _run = spy.runs[-1]
    assert np.all(np.isfinite(Y[:4])) and np.all(np.isnan(Y[4:]))
    # the stored values: at most WARM_UP_VALUES (outputs times components)
    monkeypatch.setattr(compiled_run, "WARM_UP_BUDGET_S", float("inf"))
    monkeypatch.setattr(compiled_run, "WARM_UP_VALUES", 64)
    compiled_run.warm_up_run(method, kern, model, Y0, T, rtol, atol, None)
    assert spy.runs[-1][1].shape == (32, 2)
    # the adaptive steps: at most WARM_UP_STEPS attempted, over one long output interval
    monkeypatch.setattr(compiled_run, "WARM_UP_STEPS", 5)
    compiled_run.warm_up_run(method, kern, model, Y0, np.array([0.0, 1e3]), rtol, atol, None)
    _t, Y, run = spy.runs[-1]
    assert run.counters[1] + run.counters[2] == 5 and np.all(np.isnan(Y[1]))
    # a fixed-step method: one step of h per output, whatever the output spacing
    rk4 = METHODS["rk4"]
    spy4 = _Spy(rk4)
    monkeypatch.setattr(rk4, "start", spy4)
    compiled_run.warm_up_run(rk4, kern, model, Y0, np.array([0.0, 1e3]), 0.0, 0.0, 0.01)
    t_warm, _Y, run = spy4.runs[-1]
    assert np.array_equal(t_warm, [0.0, 0.01]) and run.counters[1] == 1


def test_progress_callbacks_are_outside_the_wall_time():
    """Twenty callbacks of 20 ms each (0.4 s) around a run of well under a millisecond:
    the timed run holds the driver calls only."""
    calls = []

    def slow(fraction):
        calls.append(fraction)
        time.sleep(0.02)

    sol = integrate(oscillator(), Y0, T, method="dop853", progress=slow,
                    **DRIVERS["dop853"])
    assert len(calls) == 20 and calls[-1] == 1.0
    assert sol.wall_time_s < 0.2


TOP = textwrap.dedent("""
    kind = "heavy_top"
    title = "test top"

    [params]
    I1 = 1.0
    I3 = 0.5
    Mgl = 1.0

    [initial]
    theta = 1.0
    theta_dot = 0.0
    phi_dot = 0.5
    omega3 = 6.0

    [run]
    t_end = 8.0
    samples = 801
    study = false
    """)


def test_the_heavy_top_archives_its_run_and_warm_up_times(tmp_path, monkeypatch):
    """The heavy top's main run (the specialized DOP853 driver): the archive holds its
    wall, compile and warm-up times, and the rehearsal changed no bit of it."""
    scene = load_scene(parse_config_text(TOP))
    results = scene.simulate()
    path = tmp_path / "run.h5"
    write_archive(path, kind=scene.kind, title=scene.title, scene="top",
                  config_text=scene.source.text, config_sha256=scene.source.sha256,
                  results=results, schema=scene.results_schema())
    with h5py.File(path, "r") as f:
        attrs = dict(f["runs/main"].attrs)
        y = f["runs/main/y"][...]
    assert attrs["method"] == "dop853"
    for key in ("wall_time_s", "warm_up_time_s"):
        assert np.isfinite(attrs[key]) and attrs[key] > 0.0, key
    assert np.isfinite(attrs["compile_time_s"]) and attrs["compile_time_s"] >= 0.0
    monkeypatch.setattr(compiled_run, "warm_up_run", lambda *a: 0.0)
    again = load_scene(parse_config_text(TOP)).simulate().runs["main"]
    assert again.attrs["warm_up_time_s"] == 0.0
    assert np.array_equal(again.y, y)
    assert again.attrs["nfev"] == attrs["nfev"]
