"""Hamilton–Jacobi quadratures (reportgen.core.hamilton_jacobi) against Cartesian integrations.

References:
* Central potential: W = W_r(r) + W_θ(θ) + L_z φ and its quadratures (Goldstein §10.5,
  §10.8; Landau & Lifshitz §15, §48); the reference is Newton's r̈ = −k r/(m|r|³)
  integrated by DOP853 and converted to spherical coordinates with the point
  transformation p_q = p · ∂r/∂q (p_r = p·r̂, p_θ = r p·θ̂, p_φ = x p_y − y p_x).
* Two fixed centres: z = x + i y = a cosh(ξ + i η); the separated equations
  p_ξ² = F(ξ), p_η² = G(η) (lecture notes 7.59, Charlier); the reference is
  r̈ = −μ1 (r − c1)/r1³ − μ2 (r − c2)/r2³ by DOP853; momenta map as
  p_ξ − i p_η = (dz/dζ)(p_x − i p_y) (p_q = p · ∂r/∂q for the conformal map).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp

from reportgen.core import expressions, numeric
from reportgen.core import hamilton_jacobi as hj
from reportgen.core.models import two_center

RTOL = 1e-13  # of the DOP853 references
AGREE = 1e-8  # quadrature against the references
CONSTANT = 1e-10  # relative spread of a first integral along a reference


# ------------------------------------------------------------------ central potential
M, K = 1.5, 2.0
# (r, θ, φ, p_r, p_θ, p_φ): e = 0.635, i = 54° (prograde); e = 0.543, i = 124° (retrograde)
PROGRADE = (1.0, 1.1, 0.4, 0.9, 0.9, 0.7)
RETROGRADE = (0.8, 1.2, -2.5, 1.0, 1.0, -0.7)


def kepler_period(m, k, state0):
    E = float(hj.central_integrals(*state0, m, k)["E"])
    return 2 * math.pi * math.sqrt(m * (-k / (2 * E)) ** 3 / k)  # Kepler's third law


def spherical_to_cartesian(r, theta, phi, p_r, p_theta, p_phi):
    st, ct, sp, cp = np.sin(theta), np.cos(theta), np.sin(phi), np.cos(phi)
    r_hat = np.array([st * cp, st * sp, ct])
    theta_hat = np.array([ct * cp, ct * sp, -st])
    phi_hat = np.array([-sp, cp, 0.0 * sp])
    return r * r_hat, p_r * r_hat + p_theta / r * theta_hat + p_phi / (r * st) * phi_hat


def central_reference(m, k, state0, t):
    """Newton's equations in Cartesian coordinates, by DOP853, as Cartesian (q, p)."""
    q0, p0 = spherical_to_cartesian(*state0)

    def newton(_, y):
        q = y[:3]
        return np.concatenate([y[3:] / m, -k * q / np.linalg.norm(q) ** 3])

    sol = solve_ivp(newton, (t[0], t[-1]), np.concatenate([q0, p0]), method="DOP853",
                    rtol=RTOL, atol=RTOL, t_eval=t)
    assert sol.success
    return sol.y[:3], sol.y[3:]


def cartesian_to_spherical(q, p, phi0):
    """(r, θ, φ, p_r, p_θ, p_φ) with φ unwrapped from the branch of phi0."""
    x, y, z = q
    r = np.sqrt(x * x + y * y + z * z)
    theta = np.arctan2(np.hypot(x, y), z)
    phi = np.unwrap(np.arctan2(y, x))
    phi += 2 * math.pi * np.round((phi0 - phi[0]) / (2 * math.pi))
    theta_hat = np.array([np.cos(theta) * np.cos(phi), np.cos(theta) * np.sin(phi),
                          -np.sin(theta)])
    return {"r": r, "theta": theta, "phi": phi, "p_r": np.sum(q * p, axis=0) / r,
            "p_theta": r * np.sum(theta_hat * p, axis=0), "p_phi": x * p[1] - y * p[0]}


def worst_central_error(got, want):
    """Largest difference over all six variables, relative to each one's size (≥ 1)."""
    return max(np.max(np.abs(got[v] - want[v])) / max(1.0, np.max(np.abs(want[v])))
               for v in want)


@pytest.fixture(scope="module", params=[PROGRADE, RETROGRADE], ids=["prograde", "retrograde"])
def central_orbit(request):
    state0 = request.param
    t = np.linspace(0.0, 5 * kepler_period(M, K, state0), 2001)  # five orbits
    q, p = central_reference(M, K, state0, t)
    return state0, t, cartesian_to_spherical(q, p, state0[2])


def test_central_quadrature_matches_the_cartesian_integration(central_orbit):
    state0, t, ref = central_orbit
    got = hj.central_quadrature(M, K, state0, t)
    assert float(hj.central_integrals(*state0, M, K)["E"]) < 0
    assert np.ptp(ref["theta"]) > 1.5  # θ oscillates through both turning points π/2 ∓ i
    assert np.ptp(ref["phi"]) > 4 * 2 * math.pi  # φ unwrapped over several turns
    assert worst_central_error(got, ref) <= AGREE
    # the initial state comes back (t[0] = 0)
    np.testing.assert_allclose([got[v][0] for v in ref], state0, rtol=1e-14, atol=1e-14)


def test_central_integrals_are_constant_along_the_cartesian_integration(central_orbit):
    # E, |L|² and L_z: the separation constants of W (Goldstein §10.5)
    state0, _, ref = central_orbit
    c = hj.central_integrals(*(ref[v] for v in ("r", "theta", "phi", "p_r", "p_theta",
                                                "p_phi")), M, K)
    c0 = hj.central_integrals(*state0, M, K)
    for name in ("E", "L2", "Lz"):
        assert np.max(np.abs(c[name] / c0[name] - 1)) <= CONSTANT, name
    # L² is |r × p|² in Cartesian form (independent of the spherical formula)
    q, p = spherical_to_cartesian(*state0)
    assert float(c0["L2"]) == pytest.approx(float(np.sum(np.cross(q, p) ** 2)), rel=1e-14)


def test_central_mutations_are_caught(central_orbit, monkeypatch):
    state0, t, ref = central_orbit
    # a constant off by 1e-7 …
    assert worst_central_error(hj.central_quadrature(M, K * (1 + 1e-7), state0, t), ref) > AGREE
    # … or the sign of the cyclic momentum lost in ∂W/∂L_z (node longitude)
    honest = hj.central_integrals

    def lz_sign_lost(*args):
        out = honest(*args)
        return {**out, "Lz": np.abs(out["Lz"])}

    monkeypatch.setattr(hj, "central_integrals", lz_sign_lost)
    mutated = hj.central_quadrature(M, K, state0, t)
    if state0[5] < 0:  # only the retrograde orbit is affected
        assert worst_central_error(mutated, ref) > AGREE
    else:
        assert worst_central_error(mutated, ref) <= AGREE


@pytest.mark.parametrize("p_phi", [0.8, -0.8])
def test_central_equatorial_orbit_is_the_limit_sin_i_0(p_phi):
    # θ0 = π/2, p_θ0 = 0: L_z = ±L, θ ≡ π/2, the θ-quadrature degenerates
    state0 = (1.0, math.pi / 2, 0.3, 0.5, 0.0, p_phi)
    t = np.linspace(0.0, 3 * kepler_period(M, K, state0), 801)
    ref = cartesian_to_spherical(*central_reference(M, K, state0, t), state0[2])
    got = hj.central_quadrature(M, K, state0, t)
    # θ0 = π/2 rounded is inclined by ~1e-16: θ stays within rounding of π/2
    assert np.max(np.abs(got["theta"] - math.pi / 2)) <= 1e-15
    assert np.max(np.abs(got["p_theta"])) <= 1e-15
    assert worst_central_error(got, ref) <= AGREE


def test_central_polar_orbit_runs_through_the_poles():
    # p_φ = 0: Hamilton's equations of CENTRAL_H carry θ through 0 and π at constant φ;
    # compare positions in Cartesian form, where the chart does not matter
    state0 = (1.0, 0.7, 0.3, 0.4, -1.0, 0.0)
    t = np.linspace(0.0, 3 * kepler_period(M, K, state0), 801)
    q_ref, p_ref = central_reference(M, K, state0, t)
    got = hj.central_quadrature(M, K, state0, t)
    q, p = spherical_to_cartesian(*(got[v] for v in ("r", "theta", "phi", "p_r", "p_theta",
                                                     "p_phi")))
    assert got["theta"].min() < -2 * math.pi  # θ falls by 2π per orbit
    assert np.max(np.abs(q - q_ref)) <= AGREE and np.max(np.abs(p - p_ref)) <= AGREE


@pytest.mark.parametrize("state0, match", [
    ((1.0, 1.1, 0.4, 3.0, 0.9, 0.7), "bound"),  # E > 0
    ((1.0, 1.1, 0.4, 0.3, 0.0, 0.0), "radial"),  # L = 0
    ((1.0, 4.0, 0.4, 0.3, 0.9, 0.7), "theta0"),  # θ0 outside (0, π)
])
def test_central_refusals(state0, match):
    with pytest.raises(ValueError, match=match):
        hj.central_quadrature(M, K, state0, np.linspace(0.0, 1.0, 5))


def test_central_h_formula_is_the_cartesian_hamiltonian():
    rng = np.random.default_rng(7)
    n = 200
    state = (rng.uniform(0.3, 3.0, n), rng.uniform(0.1, 3.0, n), rng.uniform(-4, 4, n),
             *rng.normal(0.0, 1.5, (3, n)))
    q, p = spherical_to_cartesian(*state)
    cartesian = np.sum(p * p, axis=0) / (2 * M) - K / np.linalg.norm(q, axis=0)
    names = ("r", "theta", "phi", "p_r", "p_theta", "p_phi")
    symbols = {name: sympy.Symbol(name, real=True) for name in names}
    H = expressions.parse_expression(hj.CENTRAL_H, symbols, {"m": M, "k": K})
    values = {symbols[name]: v for name, v in zip(names, state, strict=True)}
    np.testing.assert_allclose(numeric.evaluate(H, values), cartesian, rtol=1e-12)
    np.testing.assert_allclose(hj.central_integrals(*state, M, K)["E"], cartesian, rtol=1e-12)


# ------------------------------------------------------------------ two fixed centres
def to_elliptic(x, y, px, py, a):
    """(ξ, η, p_ξ, p_η) from z = a cosh ζ (principal branch, ξ ≥ 0)."""
    zeta = np.arccosh((x + 1j * y) / a)
    w = a * np.sinh(zeta) * (px - 1j * py)
    return zeta.real, zeta.imag, w.real, -w.imag


def to_cartesian(xi, eta, p_xi, p_eta, a):
    zeta = xi + 1j * eta
    z, w = a * np.cosh(zeta), (p_xi - 1j * p_eta) / (a * np.sinh(zeta))
    return z.real, z.imag, w.real, -w.imag


def two_centres_reference(m, mu1, mu2, a, cartesian0, t):
    """Newton's equations in the plane by DOP853: (x, y, p_x, p_y) on t."""
    def newton(_, s):
        x, y, px, py = s
        c1, c2 = mu1 / math.hypot(x - a, y) ** 3, mu2 / math.hypot(x + a, y) ** 3
        return [px / m, py / m, -m * (c1 * (x - a) + c2 * (x + a)), -m * (c1 + c2) * y]

    sol = solve_ivp(newton, (t[0], t[-1]), cartesian0, method="DOP853", rtol=RTOL,
                    atol=RTOL, t_eval=t)
    assert sol.success
    return sol.y


# (m, μ1, μ2, a, (x, y, p_x, p_y) at t = 0, t_end ≈ 5 revolutions)
ORBITS = {
    # η librating about 0: satellite orbit of μ1, ξ through 0 (across the segment); the
    # names are the literature's (Waalkens, Dullin & Richter, Physica D 196 (2004))
    "librating-equal": (1.0, 1.0, 1.0, 1.0, (1.3, 0.0, 0.1, 1.7), 6.0),
    "librating-unequal": (1.0, 1.0, 0.3, 1.0, (1.5, 0.0, 0.1, 1.35), 12.0),
    # η librating about π: satellite orbit of μ2
    "librating-about-pi": (1.0, 0.3, 1.0, 1.0, (-1.5, 0.0, -0.1, -1.35), 12.0),
    # η circulating: planetary orbits between two confocal ellipses …
    "circulating-equal": (1.0, 1.0, 1.0, 1.0, (0.0, 2.0, -0.95, 0.1), 60.0),
    "circulating-unequal": (1.3, 1.0, 0.4, 1.0, (0.0, 2.0, -1.105, 0.13), 60.0),
    # … and lemniscate orbits across the segment between the centres
    "circulating-across": (1.0, 1.0, 1.0, 1.0, (1.4, 0.0, 0.1, 1.8), 6.0),
}
ETA_MOTION = {"librating-equal": "about 0", "librating-unequal": "about 0",
              "librating-about-pi": "about pi", "circulating-equal": "circulating",
              "circulating-unequal": "circulating", "circulating-across": "circulating"}


@pytest.fixture(scope="module", params=list(ORBITS))
def two_centres_orbit(request):
    m, mu1, mu2, a, cartesian0, t_end = ORBITS[request.param]
    t = np.linspace(0.0, t_end, 2001)
    ref = two_centres_reference(m, mu1, mu2, a, cartesian0, t)
    state0 = tuple(float(v) for v in to_elliptic(*cartesian0, a))
    return request.param, (m, mu1, mu2, a), state0, t, ref


def worst_two_centres_error(got, ref, a):
    """Largest position difference (via x, y: no angle wrapping) and largest momentum
    difference relative to the momentum scale, the reference's momenta mapped with
    the quadrature's own ζ (so the branch ξ ↔ −ξ, η ↔ −η is the quadrature's)."""
    x, y, _, _ = to_cartesian(got["xi"], got["eta"], got["p_xi"], got["p_eta"], a)
    w = a * np.sinh(got["xi"] + 1j * got["eta"]) * (ref[2] - 1j * ref[3])
    scale = max(1.0, np.max(np.abs(w)))
    return max(np.max(np.hypot(x - ref[0], y - ref[1])) / a,
               np.max(np.abs(got["p_xi"] - w.real)) / scale,
               np.max(np.abs(got["p_eta"] + w.imag)) / scale)


def test_two_centres_quadrature_matches_the_cartesian_integration(two_centres_orbit):
    name, (m, mu1, mu2, a), state0, t, ref = two_centres_orbit
    got = hj.two_centres_quadrature(m, mu1, mu2, a, state0, t)
    assert float(hj.two_centres_integrals(*state0, m, mu1, mu2, a)["E"]) < 0
    assert worst_two_centres_error(got, ref, a) <= AGREE
    np.testing.assert_allclose([got[v][0] for v in ("xi", "eta", "p_xi", "p_eta")],
                               state0, rtol=1e-13, atol=1e-13)
    # the case the orbit was chosen for
    eta = got["eta"]
    if ETA_MOTION[name] == "circulating":
        assert np.all(np.diff(eta) * np.sign(state0[3]) > 0) and np.ptp(eta) > 2 * math.pi
    else:
        centre = 0.0 if ETA_MOTION[name] == "about 0" else math.pi
        assert np.max(np.abs(np.cos(eta - centre) - 1)) < 1.8  # |η − centre| < π
        assert np.any(got["p_eta"] > 0) and np.any(got["p_eta"] < 0)  # turning points
    assert np.any(got["p_xi"] > 0) and np.any(got["p_xi"] < 0)  # ξ librates


def test_two_centres_integrals_are_constant_along_the_cartesian_integration(
        two_centres_orbit):
    # E and β of the separated equations (notes 7.59) on the reference trajectory
    _, (m, mu1, mu2, a), state0, _, ref = two_centres_orbit
    c = hj.two_centres_integrals(*to_elliptic(*ref, a), m, mu1, mu2, a)
    c0 = hj.two_centres_integrals(*state0, m, mu1, mu2, a)
    for name in ("E", "beta"):
        assert np.max(np.abs(c[name] / c0[name] - 1)) <= CONSTANT, name
    # the η-side form of β gives the same number (the separation itself)
    xi, eta, p_xi, p_eta = to_elliptic(*ref, a)
    eta_side = (-p_eta**2 - 2 * m * a * a * c["E"] * np.cos(eta) ** 2
                + 2 * m * m * a * (mu1 - mu2) * np.cos(eta))
    assert np.max(np.abs(eta_side / c["beta"] - 1)) <= CONSTANT


def test_two_centres_mutations_are_caught(two_centres_orbit, monkeypatch):
    _, (m, mu1, mu2, a), state0, t, ref = two_centres_orbit
    # a constant off by 1e-7 …
    perturbed = hj.two_centres_quadrature(m, mu1 * (1 + 1e-7), mu2, a, state0, t)
    assert worst_two_centres_error(perturbed, ref, a) > AGREE
    # … or a wrong sign in β (its cosh ξ term) …
    honest = hj.two_centres_integrals

    def beta_sign_wrong(xi, eta, p_xi, p_eta, m, mu1, mu2, a):
        out = honest(xi, eta, p_xi, p_eta, m, mu1, mu2, a)
        return {**out, "beta": out["beta"] + 4 * m * m * a * (mu1 + mu2) * np.cosh(xi)}

    with monkeypatch.context() as patch:
        patch.setattr(hj, "two_centres_integrals", beta_sign_wrong)
        try:
            wrong = worst_two_centres_error(
                hj.two_centres_quadrature(m, mu1, mu2, a, state0, t), ref, a)
        except ValueError:  # or no longer a motion at all
            wrong = math.inf
    assert wrong > AGREE
    # … and that wrong β is not conserved along the reference
    xi, eta, p_xi, p_eta = to_elliptic(*ref, a)
    b = beta_sign_wrong(xi, eta, p_xi, p_eta, m, mu1, mu2, a)["beta"]
    assert np.max(np.abs(b / b[0] - 1)) > 1e-3


def test_two_centres_beta_is_m2_times_the_two_center_kinds_beta():
    # equal masses, per unit mass there: β = m² (−C − 2 a² E/m) (two_center, notes 7.59)
    rng = np.random.default_rng(3)
    m, mu, a = 1.7, 0.8, 1.3
    x, y, px, py = rng.uniform(-3, 3, 50), rng.uniform(-3, 3, 50), *rng.normal(0, 1, (2, 50))
    ours = hj.two_centres_integrals(*to_elliptic(x, y, px, py, a), m, mu, mu, a)
    E_unit = two_center.energy(x, y, px / m, py / m, mu, a)
    C = two_center.separation_constant(x, y, px / m, py / m, mu, a)
    np.testing.assert_allclose(ours["E"], m * E_unit, rtol=1e-12)
    np.testing.assert_allclose(ours["beta"], m * m * two_center.beta(E_unit, C, a),
                               rtol=1e-10, atol=1e-12)


def test_two_centres_h_formula_is_the_cartesian_hamiltonian():
    rng = np.random.default_rng(11)
    m, mu1, mu2, a = 1.3, 1.0, 0.4, 0.9
    n = 300
    state = (rng.uniform(-2.0, 2.0, n), rng.uniform(-4.0, 4.0, n), *rng.normal(0, 2, (2, n)))
    x, y, px, py = to_cartesian(*state, a)
    cartesian = ((px**2 + py**2) / (2 * m) - m * mu1 / np.hypot(x - a, y)
                 - m * mu2 / np.hypot(x + a, y))
    names = ("xi", "eta", "p_xi", "p_eta")
    symbols = {name: sympy.Symbol(name, real=True) for name in names}
    H = expressions.parse_expression(hj.TWO_CENTRES_H, symbols,
                                     {"m": m, "mu1": mu1, "mu2": mu2, "a": a})
    values = {symbols[name]: v for name, v in zip(names, state, strict=True)}
    np.testing.assert_allclose(numeric.evaluate(H, values), cartesian, rtol=1e-12)
    np.testing.assert_allclose(hj.two_centres_integrals(*state, m, mu1, mu2, a)["E"],
                               cartesian, rtol=1e-12)


@pytest.mark.parametrize("cartesian0, match", [
    ((0.0, 2.0, -2.0, 0.1), "bound"),  # E > 0
    ((1.0, 0.0, 0.0, 0.0), "centre"),  # starts on the centre μ1
    ((1.5, 0.0, 0.0, 0.0), "collision"),  # at rest on the axis: falls into μ1 (η ≡ 0)
    ((0.3, 0.0, 0.2, 0.0), "collision"),  # on the segment between the centres (ξ ≡ 0)
    ((-2.0, 0.0, 0.3, 0.0), "collision"),  # on the axis beyond μ2 (η ≡ π)
])
def test_two_centres_refusals(cartesian0, match):
    state0 = [float(v) for v in to_elliptic(*cartesian0, 1.0)]
    with pytest.raises(ValueError, match=match):
        hj.two_centres_quadrature(1.0, 1.0, 0.5, 1.0, state0, np.linspace(0.0, 1.0, 5))
