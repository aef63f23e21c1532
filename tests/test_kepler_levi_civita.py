"""``levi_civita`` (Levi-Civita regularized Kepler + Gauss-Legendre 6) against closed forms.

References: the Kepler orbit at time t from Kepler's equation E − e sin E = M and the
perifocal position a(cos E − e), b sin E (Murray & Dermott, *Solar System Dynamics* §2.4;
Goldstein §3.8 eqs. 3.76–3.80), computed by ``kepler.kepler_state``, which shares no code
with the regularized integration; third law T = 2π√(a³/GM) (Goldstein eq. 3.71); E, L and
the LRL vector conserved (Goldstein §3.9).  In Levi-Civita variables all three are
quadratic invariants of the oscillator w'' = (h/2) w, which Gauss collocation conserves
exactly (Hairer, Lubich & Wanner, *Geometric Numerical Integration* IV.2), hence the
round-off bounds below.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

from reportgen.core.integrators import MethodMismatch, choose_auto, integrate
from reportgen.core.integrators.regularized import STEP_CONSTANT, steps_per_orbit
from reportgen.core.models import kepler
from reportgen.kinds import load_scene
from reportgen.scene.config import parse_config_text

GM = 1.0
MODEL = kepler.model(k=1.0, mu=1.0)  # GM = k/μ = 1


def pericentre_state(e: float) -> np.ndarray:
    """a = 1, GM = 1 (period 2π), at pericentre r = 1 − e with speed √((1 + e)/(1 − e))."""
    return np.array([1.0 - e, 0.0, 0.0, math.sqrt((1.0 + e) / (1.0 - e))])


def exact(y0, t) -> np.ndarray:
    return np.column_stack(kepler.kepler_state(t, kepler.orbital_elements(*y0, GM)))


def run(y0, t, rtol=1e-12):
    sol = integrate(MODEL, y0, t, method="levi_civita", rtol=rtol)
    assert sol.ok and sol.method == "levi_civita"
    return sol


# a generic state: orbit tilted (ω ≠ 0), started between the apsides, retrograde
GENERIC = np.array([0.3, 0.4, 1.2, -0.9])


@pytest.mark.parametrize("y0", [pericentre_state(0.5), pericentre_state(0.95),
                                pericentre_state(0.99), GENERIC],
                         ids=["e0.5", "e0.95", "e0.99", "generic"])
def test_orbit_at_output_times_matches_keplers_equation(y0):
    el = kepler.orbital_elements(*y0, GM)
    t = np.linspace(0.0, 3.0 * el["period"], 1501) + 0.37  # t0 ≠ 0: only differences matter
    sol = run(y0, t)
    ref = exact(y0, t - t[0])
    pos = np.max(np.hypot(*(sol.y[:, :2] - ref[:, :2]).T)) / el["semi_major_axis"]
    # velocity relative to the pericentre speed: its error is the phase error times the
    # acceleration, GM/r² = 1e4 at the pericentre of e = 0.99
    vel = np.max(np.hypot(*(sol.y[:, 2:] - ref[:, 2:]).T)) / np.max(np.hypot(*ref[:, 2:].T))
    assert pos < 1e-11 and vel < 1e-10, (pos, vel)
    assert np.array_equal(sol.t, t) and np.array_equal(sol.y[0], y0)


def test_energy_angular_momentum_and_lrl_at_round_off_over_many_orbits():
    e, orbits = 0.9, 300
    y0 = pericentre_state(e)
    t = np.linspace(0.0, orbits * 2 * math.pi, 3001)
    y = run(y0, t).y.T
    energy = kepler.energy(*y, 1.0, 1.0)
    L = kepler.angular_momentum(*y, 1.0)
    ax, ay = kepler.lrl_vector(*y, 1.0, 1.0)
    assert np.max(np.abs(energy / energy[0] - 1)) < 5e-14
    assert np.max(np.abs(L / L[0] - 1)) < 5e-14
    assert np.max(np.hypot(ax - ax[0], ay - ay[0])) < 5e-14  # |A| = μ k e = 0.9
    # the phase (the time of each point on the orbit) carries the method's error, ∝ t
    ref = exact(y0, t)
    assert np.max(np.hypot(*(y[:2] - ref[:, :2].T))) < orbits * 1e-11


@pytest.mark.parametrize("e", [0.0, 0.7, 0.99])
def test_returns_to_pericentre_after_each_period(e):
    # third law: a = 1, GM = 1 -> T = 2π; at t = kT the orbit is back at its pericentre
    # (r_p, 0) with velocity (0, v_p).  A lag δt shows as vx = −(GM/r_p²) δt (the
    # acceleration there is −GM/r_p² x̂), so the period is checked to |δt|/t.
    y0 = pericentre_state(e)
    period = kepler.orbital_elements(*y0, GM)["period"]
    assert period == pytest.approx(2 * math.pi, rel=1e-14)
    t = period * np.arange(6.0)
    y = run(y0, t).y
    r_p = y0[0]
    lag = -y[1:, 2] * r_p**2 / GM
    assert np.max(np.abs(lag / t[1:])) < 1e-12, lag  # rtol 1e-12: the error per orbit
    assert np.max(np.abs(y[:, :2] - y0[:2])) < 1e-11
    assert np.max(np.abs(y[:, 3] / y0[3] - 1)) < 1e-11


def test_eccentricity_099_far_beyond_dop853():
    # 20 orbits at e = 0.99: levi_civita at rtol 1e-12 is more accurate than DOP853 at
    # rtol 1e-14 (measured 1.6e-12 against 6e-10 over 10 orbits; policy.REGULARIZE_…)
    y0 = pericentre_state(0.99)
    t = np.linspace(0.0, 20 * 2 * math.pi, 4001)
    ref = exact(y0, t)
    lc = run(y0, t).y
    dop = integrate(MODEL, y0, t, method="dop853", rtol=1e-14, atol=1e-16).y
    err_lc = np.max(np.hypot(*(lc[:, :2] - ref[:, :2]).T))
    err_dop = np.max(np.hypot(*(dop[:, :2] - ref[:, :2]).T))
    assert err_lc < 1e-11 and err_lc < err_dop / 10, (err_lc, err_dop)


def test_sixth_order_in_the_step():
    # steps per orbit N from rtol; the error over one orbit (outputs far apart, so the steps
    # are the method's own) falls as N⁻⁶: fit the slope of log error against log N
    y0 = pericentre_state(0.6)
    t = np.linspace(0.0, 2 * math.pi, 3)
    ref = exact(y0, t)
    speed = math.sqrt(1.6 / 0.4)
    ns = np.array([16, 20, 24, 32])
    errs = []
    for n in ns:
        rtol = STEP_CONSTANT * speed / n**6 * (1 + 1e-9)
        assert steps_per_orbit(rtol, 0.6) == n
        errs.append(np.max(np.abs(run(y0, t, rtol).y - ref)))
    slope = np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert np.all(np.array(errs) > 1e-13), errs  # above round-off
    assert -6.6 < slope < -5.4, (slope, errs)


# ------------------------------------------------------------------- the policy's choice
@pytest.mark.parametrize("e", [0.0, 0.5, 0.899, 0.9, 0.99])
def test_auto_chooses_levi_civita_for_bound_kepler_orbits(e):
    assert choose_auto(MODEL, 1e-12, y0=pericentre_state(e))[0] == "levi_civita"


def test_auto_keeps_dop853_for_other_forces_and_unbound_orbits():
    power = kepler.model(k=1.0, mu=1.0, n=1.2)
    assert choose_auto(power, 1e-12, y0=pericentre_state(0.95))[0] == "dop853"
    hyperbola = np.array([0.05, 0.0, 0.0, 8.0])  # v²/2 − 1/r = 12 > 0
    assert choose_auto(MODEL, 1e-12, y0=hyperbola)[0] == "dop853"


SCENE = """
kind = "central_force"
[params]
m1 = 1.0
m2 = 1.0
k = 0.5
{potential}
[initial]
x = 0.05
y = 0.0
vx = 0.0
vy = {vy}
[run]
t_end = 31.41592653589793
samples = 1001
method = "{method}"
study = false
"""


E095_SPEED = math.sqrt(39.0)  # √((1 + e)/(1 − e)) at e = 0.95, a = 1


def scene_text(method="auto", potential="", vy=E095_SPEED):
    return textwrap.dedent(SCENE.format(method=method, potential=potential, vy=vy))


def test_scene_auto_runs_levi_civita_and_passes_its_kepler_checks():
    results = load_scene(parse_config_text(scene_text())).simulate()
    main = results.runs["main"]
    assert main.attrs["method"] == "levi_civita" and main.attrs["status"] == "ok"
    assert "e = 0.95" in main.attrs["method_reason"]
    a = results.analysis
    assert a["kepler_position_error_max"] < 1e-11
    assert main.attrs["drift_energy"] < 1e-14
    bad = [c for c in results.checks if not c.rel_error < 1e-10]
    assert results.checks and not bad, bad


@pytest.mark.parametrize("potential, rule", [
    ('potential = "power"\nn = 1.2', "params.potential = \"kepler\" (got potential 'power')"),
    ('potential = "kepler_inverse_cube"\nepsilon = 0.001',
     "(got potential 'kepler_inverse_cube')"),
])
@pytest.mark.parametrize("method", ["levi_civita", "levi_civita_dop853"])
def test_levi_civita_refused_for_other_forces(write_config, cli, potential, rule, method):
    path = write_config("lc_power", scene_text(method=method, potential=potential))
    code, _, err = cli("validate", path)
    assert code == 2
    (line,) = [x for x in err.splitlines() if f'"{method}"' in x]
    assert line.startswith(f"{path}: key 'run.method': ") and rule in line


@pytest.mark.parametrize("method", ["levi_civita", "levi_civita_dop853"])
def test_levi_civita_refused_for_an_unbound_orbit(write_config, cli, method):
    path = write_config("lc_unbound", scene_text(method=method, vy=8.0))
    code, _, err = cli("validate", path)
    assert code == 2 and f"{path}: key 'run.method': " in err and "bound orbit" in err


@pytest.mark.parametrize("method", ["levi_civita", "levi_civita_dop853"])
def test_method_checks_the_model_before_any_work(method):
    with pytest.raises(MethodMismatch, match="inverse-square"):
        integrate(kepler.model(k=1.0, mu=1.0, n=1.2), pericentre_state(0.5),
                  np.linspace(0.0, 1.0, 3), method=method)
    with pytest.raises(MethodMismatch):
        integrate(kepler.model(k=1.0, mu=1.0, epsilon=1e-3), pericentre_state(0.5),
                  np.linspace(0.0, 1.0, 3), method=method)
    with pytest.raises(ValueError, match="bound orbit"):
        integrate(MODEL, np.array([1.0, 0.0, 0.0, 1.5]), np.linspace(0.0, 1.0, 3),
                  method=method)


@pytest.mark.parametrize("y0", [pericentre_state(0.7), pericentre_state(0.95),
                                pericentre_state(0.99), GENERIC],
                         ids=["e0.7", "e0.95", "e0.99", "generic"])
def test_levi_civita_dop853_follows_keplers_equation_in_few_steps(y0):
    """DOP853 on the regularized oscillator: its positions at the physical times converge
    to Kepler's equation as rtol falls (≥ 10x less error per 100x tolerance), and at
    equal rtol it is more accurate than DOP853 on the Cartesian equations with a fraction
    of its evaluations, the more so the more eccentric the orbit (the oscillator is as
    smooth at pericentre as anywhere)."""
    el = kepler.orbital_elements(*y0, GM)
    t = np.linspace(0.0, 10.0 * el["period"], 801) + 0.37
    ref = exact(y0, t - t[0])

    def position_error(sol):
        return float(np.max(np.hypot(*(sol.y[:, :2] - ref[:, :2]).T))) / el["semi_major_axis"]

    errors = []
    for rtol in (1e-8, 1e-10, 1e-12):
        sol = integrate(MODEL, y0, t, method="levi_civita_dop853", rtol=rtol, atol=rtol * 1e-2)
        assert sol.ok and sol.method == "levi_civita_dop853", sol.message
        assert np.array_equal(sol.y[0], y0) and sol.wall_time_s > 0.0
        errors.append(position_error(sol))
    assert errors[2] < 1e-9 and errors[1] < errors[0] / 10 and errors[2] < errors[1] / 10
    cartesian = integrate(MODEL, y0, t, method="dop853", rtol=1e-12, atol=1e-14)
    assert errors[2] < position_error(cartesian)
    e = el["eccentricity"]
    bound = 0.5 if e < 0.6 else 0.25 if e < 0.9 else 0.15
    assert sol.nfev < bound * cartesian.nfev, (sol.nfev, cartesian.nfev)
