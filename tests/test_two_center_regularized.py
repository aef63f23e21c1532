"""two_center in the Thiele–Burrau regularized variables (z = a cosh(p + iq), dt/ds = r1 r2;
Szebehely, *Theory of Orbits* (1967), ch. 3): the model, the outputs located at physical
times, agreement with the Cartesian run on a smooth orbit, conservation of E and of the
separation constant through close approaches, and the automatic choice of formulation."""

from __future__ import annotations

import numpy as np
import pytest

from reportgen.core.integrators import integrate
from reportgen.core.integrators.fictitious_time import integrate_fictitious_time
from reportgen.core.models import two_center as cart
from reportgen.core.models import two_center_regularized as reg
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, parse_config_text

MU, A = 1.0, 1.0
PLANETARY = (0.0, 1.6, 1.05, 0.0)  # configs/two_center_planetary.toml: ≥ 0.89 a from a centre
#: configs/two_center_satellite.toml: about the centre at (1, 0), its region holds it
SATELLITE = (1.6, 0.0, 0.0, 1.2)
#: from (2, 0) with angular momentum 0.01 about C2 = (1, 0): pericentre ≈ L²/2μ = 5e-5
NEAR_COLLISION = (2.0, 0.0, 0.0, 0.01)

TEXT = """
kind = "two_center"
[params]
mu = 1.0
a = 1.0
[initial]
x = {x!r}
y = {y!r}
vx = {vx!r}
vy = {vy!r}
[run]
t_end = {t_end}
samples = 2001
rtol = {rtol}
atol = 1e-16
study = false
{extra}
"""


def scene(state, t_end=20.0, rtol=1e-14, extra=""):
    x, y, vx, vy = state
    return load_scene(parse_config_text(TEXT.format(x=x, y=y, vx=vx, vy=vy, t_end=t_end,
                                                    rtol=rtol, extra=extra)))


def regularized_run(state, t, rtol=1e-13):
    model, z0 = reg.initial_state(*state, MU, A)
    sol = integrate_fictitious_time(model, z0, t, reg.T_INDEX, rtol=rtol, atol=rtol * 1e-2)
    assert sol.ok, sol.message
    return model, sol


def test_conversions_and_jacobian():
    # round trip through the regularized variables, and K = r1 r2 (H − E) = 0 at the start
    rng = np.random.default_rng(3)
    for x, y, vx, vy in rng.normal(size=(20, 4)):
        z = reg.to_regularized(x, y, vx, vy, A, t=0.5)
        back = np.array(reg.from_regularized(z, A)).ravel()
        assert np.allclose(back, [x, y, vx, vy, 0.5], rtol=1e-12, atol=1e-12)
        E = float(cart.energy(x, y, vx, vy, MU, A))
        model = reg.model(MU, A, E)
        beta_p, beta_q = reg.separation_beta(z, MU, A, E)  # equal exactly when K = 0
        C = float(cart.separation_constant(x, y, vx, vy, MU, A))
        assert beta_p[0] == pytest.approx(cart.beta(E, C, A), abs=1e-10 * (1 + abs(C)))
        assert beta_q[0] == pytest.approx(cart.beta(E, C, A), abs=1e-10 * (1 + abs(C)))
        # analytic Jacobian against central differences
        jac = model.jacobian(0.0, z)
        fd = np.empty((5, 5))
        for j in range(5):
            dz = np.zeros(5)
            dz[j] = 1e-6
            fd[:, j] = (model.f(0.0, z + dz) - model.f(0.0, z - dz)) / 2e-6
        assert np.allclose(jac, fd, rtol=1e-6, atol=1e-6)
    with pytest.raises(ValueError, match="centre"):
        reg.to_regularized(A, 0.0, 0.1, 0.0, A)


def test_smooth_orbit_agrees_with_cartesian():
    t = np.linspace(0.0, 60.0, 3001)
    model, sol = regularized_run(PLANETARY, t)
    # outputs located at the physical times, not interpolated in t
    assert np.max(np.abs(sol.y[:, reg.T_INDEX] - t)) <= 1e-13
    X = np.column_stack(reg.from_regularized(sol.y, A)[:4])
    ref = integrate(cart.model(MU, A), np.array(PLANETARY), t, rtol=1e-13, atol=1e-15)
    assert np.max(np.abs(X - ref.y)) <= 1e-9


def test_near_collision_conserves_energy_and_separation_constant():
    t = np.linspace(0.0, 20.0, 2001)
    model, sol = regularized_run(NEAR_COLLISION, t, rtol=1e-14)
    x, y, vx, vy, _ = reg.from_regularized(sol.y, A)
    # the orbit does pass close to C2: at its turning points ξ = 1 and η ≈ 1
    xi, eta = cart.elliptic_coordinates(x, y, A)
    assert np.min(A * (xi - np.abs(eta))) < 0.05
    # energy in physical variables, relative to E (Cartesian DOP853 is off by ~1e-4 here)
    E = cart.energy(x, y, vx, vy, MU, A)
    assert np.max(np.abs(E / E[0] - 1)) <= 1e-10
    # the separation constant (notes 7.59; Whittaker §50, Cartesian form in two_center.py)
    C = cart.separation_constant(x, y, vx, vy, MU, A)
    assert np.max(np.abs(C - C[0])) <= 1e-10 * max(abs(C[0]), 2 * A * MU)
    # and in the regularized variables: the p part of K is β on its own
    beta_p, beta_q = reg.separation_beta(sol.y, MU, A, model.params[2])
    beta = cart.beta(E[0], C[0], A)
    assert np.max(np.abs(beta_p - beta)) <= 1e-10 * abs(beta)
    assert np.max(np.abs(beta_q - beta)) <= 1e-10 * abs(beta)


def test_near_collision_scene_flagged_cartesian_ok_regularized():
    cartesian = scene(NEAR_COLLISION, rtol=1e-13,
                      extra='formulation = "cartesian"').simulate().runs["main"]
    auto = scene(NEAR_COLLISION, rtol=1e-13).simulate().runs["main"]
    assert auto.attrs["formulation"] == "regularized"
    assert auto.attrs["status"] == "ok" and auto.attrs["drift_energy"] <= 1e-10
    assert auto.columns == ["x", "y", "vx", "vy"]
    assert cartesian.attrs["formulation"] == "cartesian"
    assert (cartesian.attrs["status"] != "ok"
            or cartesian.attrs["drift_energy"] >= 1e3 * auto.attrs["drift_energy"])


def test_free_fall_through_the_collision():
    # from rest on the axis: an exact collision with C2 at t_c; Cartesian DOP853 cannot
    # pass it, the regularized run bounces back (y = 0 throughout) with E conserved
    state = (2.0, 0.0, 0.0, 0.0)
    t = np.linspace(0.0, 5.0, 501)
    assert not integrate(cart.model(MU, A), np.array(state), t, rtol=1e-12, atol=1e-14).ok
    model, sol = regularized_run(state, t)
    x, y, vx, vy, _ = reg.from_regularized(sol.y, A)
    E = cart.energy(x, y, vx, vy, MU, A)
    assert np.max(np.abs(E / E[0] - 1)) <= 1e-10
    assert np.max(np.abs(y)) <= 1e-12 and np.min(x) > A  # never past the centre
    assert np.max(x) == pytest.approx(2.0, abs=1e-6)  # back to rest at x = 2 (fine grid)


@pytest.mark.parametrize("state, extra, expected", [
    (PLANETARY, "", "cartesian"),                        # far from both centres
    (SATELLITE, "", "regularized"),                      # its region holds C2
    (NEAR_COLLISION, "", "regularized"),
    (NEAR_COLLISION, 'method = "rk45"', "cartesian"),    # a named non-DOP853 method
    (PLANETARY, 'formulation = "regularized"', "regularized"),
    ((3.0, 0.0, 0.0, 1.5), "", "cartesian"),             # unbound (E > 0)
])
def test_auto_formulation(state, extra, expected):
    formulation, reason = scene(state, extra=extra).formulation()
    assert formulation == expected and reason


def test_auto_criterion_is_the_region_of_motion():
    # closest_approach_bound is a lower bound of min(r1, r2) along the run
    for state in (PLANETARY, SATELLITE, (0.0, 2.5, 0.7, 0.1)):
        E = float(cart.energy(*state, MU, A))
        C = float(cart.separation_constant(*state, MU, A))
        bound = cart.closest_approach_bound(E, C, MU, A)
        _, sol = regularized_run(state, np.linspace(0.0, 60.0, 60001), rtol=1e-12)
        x, y = reg.from_regularized(sol.y, A)[:2]
        r1, r2 = cart.distances(x, y, A)
        closest = float(np.min(np.minimum(r1, r2)))
        assert bound <= closest + 1e-9
        assert closest <= bound + 0.05  # and a close one: the run comes near it


def test_regularized_needs_dop853():
    with pytest.raises(ConfigError, match="run.method"):
        scene(PLANETARY, extra='formulation = "regularized"\nmethod = "yoshida6"')
