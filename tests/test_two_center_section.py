"""The surface of section y = 0 of Euler's two fixed centres from many orbits: the crossings
located during the run (Cartesian and Thiele–Burrau regularized), checked against scipy's
event location and against the second integral; kept per member in
``/sweep/points/poincare``, resumable, and drawn only in a sweep's report."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from reportgen.archive.store import read_archive
from reportgen.core.integrators import integrate
from reportgen.core.integrators.fictitious_time import integrate_fictitious_time
from reportgen.core.models import two_center, two_center_regularized
from reportgen.kinds import load_scene
from reportgen.kinds.two_center import TwoCenterScene
from reportgen.pipeline.stages import run_scene
from reportgen.scene.config import ConfigError, parse_config_text
from reportgen.scene.sweep import partial_folder

MU = A = 1.0
ENERGY = -0.5
#: crossings kept per member in the family: fewer than the ~30 of each orbit by t = 300
CAP = 20
#: x0 = 2.95 starts on a ring orbit (C > 4aμ) whose inner edge ξ = 4 − x0 comes within
#: 0.05 a of a centre: `formulation = "auto"` regularizes it; the other two run Cartesian
FAMILY_X0 = (2.3, 2.6, 2.95)

FAMILY = """
kind = "two_center"
title = "two centres, section family"

[params]
mu = {mu!r}
a = {a!r}

[initial]
x = 2.5
y = 0.0
vx = 0.0
energy = {energy!r}

[run]
t_end = 300.0
samples = 601
study = false
{report}
[sweep]
initial.x = {xs}
store = 0
max_points = {cap}
block = {block}
"""


def family(block: int = 0, report: str = "") -> str:
    return FAMILY.format(mu=MU, a=A, energy=ENERGY, xs=list(FAMILY_X0), cap=CAP, block=block,
                         report=report)


# ---------------------------------------------------- closed forms, written out here
def potential(x, y):
    return -MU / np.hypot(x + A, y) - MU / np.hypot(x - A, y)


def energy(x, y, vx, vy):
    return 0.5 * (vx**2 + vy**2) + potential(x, y)


def separation_constant(x, y, vx, vy):
    """C = L1 L2 + 2aμ(cos θ1 − cos θ2), L_i the angular momentum about centre i
    (Whittaker, Analytical Dynamics §50; lecture notes 7.59 in Cartesian form)."""
    L1 = (x + A) * vy - y * vx
    L2 = (x - A) * vy - y * vx
    return L1 * L2 + 2 * A * MU * ((x + A) / np.hypot(x + A, y) - (x - A) / np.hypot(x - A, y))


def ring_start(x0: float) -> np.ndarray:
    """On the section at x0 with ẋ = 0 and ẏ > 0 from the energy."""
    return np.array([x0, 0.0, 0.0, math.sqrt(2 * (ENERGY - potential(x0, 0.0)))])


def scale_of_c(state) -> float:
    """The run's scale of C (two_center.py: max(|L1 L2|, 2aμ) at t = 0)."""
    x, y, vx, vy = state
    return max(abs(((x + A) * vy - y * vx) * ((x - A) * vy - y * vx)), 2 * A * MU)


# ------------------------------------------------------------ the located crossings
def test_cartesian_crossings_are_scipys_and_the_run_is_dop853_bit_for_bit():
    """In the model's own time the stepped run gives the plain DOP853 run's outputs bit for
    bit, and its crossings of y = 0 with ẏ > 0 are those scipy's DOP853 locates with
    its event function y, to 1e-9 in time and state."""
    y0, t = ring_start(2.5), np.linspace(0.0, 100.0, 501)
    model = two_center.model(MU, A)
    sol = integrate_fictitious_time(model, y0, t, None, rtol=1e-12, atol=1e-14,
                                    section=two_center.AXIS_SECTION)
    plain = integrate(model, y0, t, method="dop853", rtol=1e-12, atol=1e-14)
    assert sol.ok and np.array_equal(sol.y, plain.y) and sol.nsteps == plain.nsteps

    def event(_, s):
        return s[1]

    event.direction = 1
    ref = solve_ivp(lambda _, s: model.f(0.0, s), (0.0, 100.0), y0, method="DOP853",
                    rtol=1e-13, atol=1e-15, events=event)
    later = ref.t_events[0] > 0  # scipy counts the start on the section; it is no crossing
    found, ref_t, ref_y = sol.crossings, ref.t_events[0][later], ref.y_events[0][later]
    assert len(found) == len(ref_t) >= 9
    assert np.max(np.abs(found[:, 0] - ref_t)) < 1e-9
    assert np.max(np.abs(found[:, 1:] - ref_y)) < 1e-9
    assert np.max(np.abs(found[:, 2])) < 1e-15 and np.all(found[:, 4] > 0)


def test_regularized_crossings_near_collision_are_scipys_in_the_fictitious_time():
    """The near-collision orbit (from (2, 0) with ẏ = 0.01, ~5e-5 from the centre at each
    pericentre) in the Thiele–Burrau variables: its upward crossings of y = a sinh p sin q
    = 0 are those scipy finds with events p = 0 and sin q = 0 in s (kept where ẏ > 0),
    on both folds (the segment between the centres and the axis outside them), and C is
    constant across them."""
    y0, t_end = np.array([2.0, 0.0, 0.0, 0.01]), 30.0
    model, z0 = two_center_regularized.initial_state(*y0, MU, A)
    sol = integrate_fictitious_time(model, z0, np.linspace(0.0, t_end, 301),
                                    two_center_regularized.T_INDEX, rtol=1e-12, atol=1e-14,
                                    section=two_center_regularized.AXIS_SECTION)
    found = sol.crossings

    def stop(_, z):
        return z[4] - t_end

    stop.terminal = True
    ref = solve_ivp(lambda _, z: model.f(0.0, z), (0.0, 1e3), z0, method="DOP853",
                    rtol=1e-13, atol=1e-15, events=[lambda _, z: z[0],
                                                    lambda _, z: math.sin(z[1]), stop])
    states = np.concatenate([ref.y_events[0], ref.y_events[1]])
    x, y, vx, vy, t = two_center_regularized.from_regularized(states, A)
    keep = (vy > 0) & (t > 0)  # the start on the section is no crossing
    expected = states[keep][np.argsort(t[keep])]
    assert len(found) == len(expected) >= 10
    assert np.max(np.abs(found[:, 0] - expected[:, 4])) < 1e-9
    x, y, vx, vy, _ = two_center_regularized.from_regularized(found[:, 1:], A)
    assert np.any(x < A) and np.any(x > A)  # both folds: p = 0 and sin q = 0
    assert np.max(np.abs(y)) < 1e-12 and np.all(vy > 0)
    C = separation_constant(x, y, vx, vy)
    assert np.max(np.abs(C - separation_constant(*y0))) / scale_of_c(y0) < 1e-9


# ------------------------------------------------------------------ the family's archive
@pytest.fixture(scope="module")
def family_run(tmp_path_factory):
    """The capped family, run once: (config path, scene folder)."""
    root = tmp_path_factory.mktemp("tc_family")
    path = root / "tc.toml"
    path.write_text(family())
    outcome = run_scene(str(path), str(root / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    return path, root / "out" / "tc"


def test_every_crossing_lies_on_the_curve_its_two_integrals_predict(family_run):
    """Physics: at every stored crossing y = 0 and ẏ > 0, E = the family's energy and the
    separation constant equals its orbit's C(0) to 1e-9 of its scale (Cartesian and
    regularized members alike); so (x, ẋ) lies on ẋ² = 2(E − V(x, 0)) − (C − 4aμ[|x| < a])
    / (x² − a²), the closed curve of the orbit on the section."""
    _, folder = family_run
    sweep = read_archive(folder / "run.h5").sweep
    pts = sweep.points["poincare"]
    assert pts.components == ("x", "y", "vx", "vy") and list(pts.attrs["axes"]) == ["x", "vx"]
    assert list(sweep.labels["formulation"]) == ["cartesian", "cartesian", "regularized"]
    state, member = pts.columns["state"], np.asarray(pts.member)
    x, y, vx, vy = state.T
    assert np.max(np.abs(y)) < 1e-12 and np.all(vy > 0)
    assert np.max(np.abs(energy(*state.T) - ENERGY)) < 1e-9
    for i, x0 in enumerate(FAMILY_X0):
        rows = member == i
        start = ring_start(x0)
        C0 = separation_constant(*start)
        assert sweep.analysis["separation_constant"][i] == pytest.approx(C0, rel=1e-14)
        drift = np.abs(separation_constant(*state[rows].T) - C0) / scale_of_c(start)
        assert np.max(drift) < 1e-9, (x0, np.max(drift))
        predicted = 2 * (ENERGY - potential(x[rows], 0.0)) - (
            C0 - 4 * A * MU * (np.abs(x[rows]) < A)) / (x[rows] ** 2 - A**2)
        assert np.max(np.abs(vx[rows] ** 2 - predicted)) < 1e-8
        # a ring orbit (C > 4aμ) crosses upward outside the right centre, between the
        # ellipses ξ = 4 − x0 and ξ = x0 (its roots of 7.59 at E = −1/2, μ = a = 1)
        assert C0 > 4 * A * MU
        assert np.all((x[rows] >= A * (4 - x0) - 1e-9) & (x[rows] <= A * x0 + 1e-9))
    assert np.nanmax(sweep.analysis["poincare_C_error"]) < 1e-9


def test_crossings_round_trip_capped(family_run):
    """Each member's first CAP crossings, bit for bit as its own run finds them;
    ``poincare_points`` counts them all."""
    path, folder = family_run
    sweep = read_archive(folder / "run.h5").sweep
    pts = sweep.points["poincare"]
    member = np.asarray(pts.member)
    total = sweep.analysis["poincare_points"]
    assert pts.attrs["max_points"] == CAP and np.all(total > CAP)
    assert list(pts.counts(sweep.size)) == [CAP] * sweep.size
    scene = load_scene(parse_config_text(path.read_text(), path))
    for i in (0, 2):
        alone = scene.member({"initial.x": FAMILY_X0[i]}).simulate()
        found = alone.analysis["poincare"]
        assert total[i] == len(found["t"])
        for name in ("t", "u", "v", "state"):
            assert np.array_equal(pts.columns[name][member == i],
                                  np.asarray(found[name])[:CAP]), name


def test_xarray_opens_the_points_with_named_dimensions(family_run):
    xr = pytest.importorskip("xarray")
    _, folder = family_run
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with xr.open_dataset(folder / "run.h5", group="sweep/points/poincare",
                             engine="h5netcdf", phony_dims="sort") as ds:
            assert set(ds.dims) == {"point", "component"}, ds.dims
            assert ds["member"].dims == ("point",) and ds["u"].dims == ("point",)
            assert ds["state"].dims == ("point", "component")
            assert list(ds["component"].values) == ["x", "y", "vx", "vy"]
            assert ds.sizes["point"] == len(FAMILY_X0) * CAP


def test_the_family_section_only_in_a_sweeps_report(family_run, tmp_path):
    """The sweep's report shows the section from many orbits with the capping said; one
    run of the same config computes no crossings (nothing of them in its archive) and
    shows its usual sections only."""
    path, folder = family_run
    html = (folder / "report.html").read_text()
    assert 'id="poincare_family"' in html
    assert f"the first {CAP} crossings of each orbit" in html
    assert (folder / "figures" / "poincare_family-poincare_family.svg").exists()
    single = tmp_path / "one.toml"
    single.write_text(family().split("[sweep]")[0])
    outcome = run_scene(str(single), str(tmp_path / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    data = read_archive(tmp_path / "out" / "one" / "run.h5")
    assert data.sweep is None
    assert not [k for k in data.analysis if k.startswith("poincare") or k == "formulation"]
    assert "stepped" not in data.runs["main"].attrs["method_reason"]
    assert [s.name for s in TwoCenterScene.chosen_sections(data)] == ["orbit", "invariants"]
    assert 'id="poincare_family"' not in (tmp_path / "out" / "one" / "report.html").read_text()


def test_resume_after_a_killed_block_keeps_the_points(tmp_path, monkeypatch):
    """Blocks of one member: the run killed in its second block resumes there, and the
    points equal an uninterrupted run's, member indices included."""
    path = tmp_path / "tc.toml"
    path.write_text(family(block=1))
    whole = run_scene(str(path), str(tmp_path / "whole"), formats=("html",))
    assert whole.ok, whole.message
    original = TwoCenterScene.sweep_block

    def killed_in_second_block(self, lo, hi, values):
        if lo == 1:
            raise KeyboardInterrupt  # stands in for kill -9
        return original(self, lo, hi, values)

    monkeypatch.setattr(TwoCenterScene, "sweep_block", killed_in_second_block)
    with pytest.raises(KeyboardInterrupt):
        run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    scene = load_scene(parse_config_text(path.read_text(), path))
    partial = partial_folder(tmp_path / "out" / "tc", scene.physics_key())
    assert len(list(partial.glob("block-*.npz"))) == 1
    ran = []
    monkeypatch.setattr(TwoCenterScene, "sweep_block",
                        lambda self, lo, hi, values: ran.append(lo)
                        or original(self, lo, hi, values))
    again = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    assert again.ok and ran == [1, 2]
    resumed = read_archive(tmp_path / "out" / "tc" / "run.h5").sweep
    reference = read_archive(tmp_path / "whole" / "tc" / "run.h5").sweep
    assert int(resumed.attrs["resumed"]) == 1
    got, want = resumed.points["poincare"], reference.points["poincare"]
    assert np.array_equal(got.member, want.member) and set(got.member) == {0, 1, 2}
    assert got.components == want.components and got.attrs == want.attrs
    for name, values in want.columns.items():
        assert np.array_equal(got.columns[name], values), name


# ------------------------------------------------------------------------ bad input
@pytest.mark.parametrize(("change", "key", "rule"), [
    (("[run]\n", '[run]\nmethod = "rk45"\n'), "run.method",
     'expected "auto" or "dop853", got \'rk45\''),
    (("energy = -0.5", "energy = -0.5\nvy = 1.0"), "initial.vy / initial.energy",
     "give exactly one of them (got both)"),
    (("energy = -0.5", ""), "initial.vy / initial.energy",
     "give exactly one of them (got neither)"),
])
def test_bad_section_configs_exit_2_naming_the_key(change, key, rule, tmp_path, cli):
    path = tmp_path / "bad.toml"
    path.write_text(family().replace(*change))
    code, out, err = cli("validate", path)
    assert code == 2 and out == "" and "Traceback" not in err
    assert str(path) in err and key in err and rule in err, err
    with pytest.raises(ConfigError):
        load_scene(parse_config_text(path.read_text(), path))


def test_an_energy_below_the_potential_is_named_with_the_floor(tmp_path, cli):
    """A member whose energy leaves ẏ imaginary at its start (the corner x0 = 10, where
    V(10, 0) = −0.202 > E = −1/2) is named with the sweep, the key, the bound and the
    value, before anything runs."""
    path = tmp_path / "low.toml"
    path.write_text(family().replace("[2.3, 2.6, 2.95]", "[2.3, 10.0]"))
    code, _, err = cli("validate", path)
    assert code == 2 and "key 'sweep': the member with initial.x = 10 is invalid" in err, err
    assert "key 'initial.energy': must be at least V(x, y) + vx²/2 = -0.20202020202" in err, err
    assert "(got -0.5)" in err


def test_a_named_method_is_accepted_without_the_section(tmp_path, cli):
    """Without poincare_family among the sections no crossings are located, so any method
    may run the members."""
    path = tmp_path / "rk.toml"
    path.write_text(family(report='[report]\nsections = ["sweep_results"]\n').replace(
        "[run]\n", '[run]\nmethod = "rk45"\n'))
    code, out, err = cli("validate", path)
    assert (code, err) == (0, ""), err
    scene = load_scene(parse_config_text(path.read_text(), path))
    member = scene.member({"initial.x": 2.3})
    assert not member.wants_section("poincare_family")
