r"""Two bodies in a central potential, reduced to the relative coordinate (lecture notes §3).

With r = r1 − r2, M = m1 + m2 and the reduced mass μ = m1 m2 / M the two-body
Lagrangian separates into the centre of mass (free motion) and one body of mass
μ in the potential V(r) (3.18–3.22).  Per unit reduced mass the relative motion
is the separable Hamiltonian  H/μ = v²/2 + V(r)/μ  with state y = (x, y, vx, vy).

Potentials (k > 0 is an attraction)::

    kepler              V = −k/r
    power               V = −k/rⁿ          (0 < n < 2: bound near-circular orbits exist)
    kepler_inverse_cube V = −k/r − ε/r²    (a 1/r³ correction to the force)

References
----------
.. [1] Lecture notes §3, eqs. (3.17)–(3.31).
.. [2] Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., §3.1–3.9 (3.9: LRL vector).
.. [3] Landau & Lifshitz, *Mechanics*, 3rd ed., §14–15 (apsidal angle, problem 2 of §14).
.. [4] Danby, *Fundamentals of Celestial Mechanics*, 2nd ed., §6.6 (Kepler's equation).
"""

from __future__ import annotations

import math

import numba
import numpy as np
from scipy import optimize, special

from ..model import OdeModel, Separable

# params = (c_n, n, c_3): acceleration a = −(c_n r^(−n−2) + c_3 r^(−4)) r_vec
#   c_n = k n / μ   (from V = −k/rⁿ: dV/dr = k n r^(−n−1))
#   c_3 = 2 ε / μ   (from V = −ε/r²: dV/dr = 2 ε r^(−3))


# inlined into its callers: see "Helpers" in reportgen.core.model
@numba.njit(cache=True, inline="always")
def _accel_factor(x, y, params):
    r2 = x * x + y * y
    if params[1] == 1.0:
        f = params[0] / (r2 * math.sqrt(r2))
    else:
        f = params[0] * r2 ** (-0.5 * (params[1] + 2.0))
    if params[2] != 0.0:
        f += params[2] / (r2 * r2)
    return f


@numba.njit(cache=True)
def rhs(t, y, params, out):
    f = _accel_factor(y[0], y[1], params)
    out[0] = y[2]
    out[1] = y[3]
    out[2] = -f * y[0]
    out[3] = -f * y[1]


@numba.njit(cache=True)
def drift(p, params, out):
    out[0] = p[0]
    out[1] = p[1]


@numba.njit(cache=True)
def kick(q, params, out):
    f = _accel_factor(q[0], q[1], params)
    out[0] = -f * q[0]
    out[1] = -f * q[1]


def model(k: float, mu: float, n: float = 1.0, epsilon: float = 0.0) -> OdeModel:
    """Relative motion r̈ = −∇V(r)/μ for V = −k/rⁿ − ε/r², state (x, y, vx, vy)."""
    # the inverse-square force offers its Levi-Civita regularization (GM = k/μ) to the
    # regularized methods (levi_civita, levi_civita_dop853)
    extra = {}
    if n == 1.0 and epsilon == 0.0:
        from .kepler_regularized import LeviCivitaTransform

        extra["levi_civita"] = LeviCivitaTransform(k / mu, orbital_elements)
    return OdeModel(name="central force", columns=("x", "y", "vx", "vy"), rhs=rhs,
                    params=np.array([k * n / mu, float(n), 2.0 * epsilon / mu]),
                    separable=Separable(n=2, drift=drift, kick=kick), extra=extra)


# --------------------------------------------------------------------- potentials
def potential(r, k, n=1.0, epsilon=0.0):
    """V(r) = −k/rⁿ − ε/r²."""
    r = np.asarray(r, dtype=np.float64)
    return -k / r**n - epsilon / r**2


def potential_derivative(r, k, n=1.0, epsilon=0.0):
    """dV/dr (the magnitude of the attraction)."""
    r = np.asarray(r, dtype=np.float64)
    return k * n / r ** (n + 1) + 2.0 * epsilon / r**3


def effective_potential(r, L, mu, k, n=1.0, epsilon=0.0):
    """V_eff(r) = L²/(2 μ r²) + V(r) (notes (7.40)–(7.41)): the radial motion's potential."""
    r = np.asarray(r, dtype=np.float64)
    return L**2 / (2.0 * mu * r**2) + potential(r, k, n, epsilon)


def reduced_mass(m1, m2):
    """μ = m1 m2 / (m1 + m2) (3.22)."""
    return m1 * m2 / (m1 + m2)


def body_positions(x, y, m1, m2):
    """Tracks of both bodies in the centre-of-mass frame (3.20)–(3.21): r1 = m2 r/M, r2 = −m1 r/M."""
    M = m1 + m2
    r = np.stack([np.asarray(x), np.asarray(y)], axis=-1)
    return m2 / M * r, -m1 / M * r


def energy(x, y, vx, vy, mu, k, n=1.0, epsilon=0.0):
    """E = μ v²/2 + V(r) of the relative motion (the centre of mass is at rest)."""
    r = np.hypot(x, y)
    return 0.5 * mu * (np.asarray(vx) ** 2 + np.asarray(vy) ** 2) + potential(r, k, n, epsilon)


def angular_momentum(x, y, vx, vy, mu):
    """L_z = μ (x vy − y vx): the Noether charge of rotations (3.23–3.27)."""
    return mu * (np.asarray(x) * vy - np.asarray(y) * vx)


def lrl_vector(x, y, vx, vy, mu, k):
    """Laplace–Runge–Lenz vector A = p × L − μ k r̂ (Goldstein eq. 3.82), components (Ax, Ay).

    For V = −k/r it is conserved, points to the pericentre and |A| = μ k e.
    """
    x, y, vx, vy = (np.asarray(a, dtype=np.float64) for a in (x, y, vx, vy))
    L = mu * (x * vy - y * vx)
    r = np.hypot(x, y)
    # p × (L ẑ) = (p_y L, −p_x L)
    return mu * vy * L - mu * k * x / r, -mu * vx * L - mu * k * y / r


# ----------------------------------------------------------- Kepler orbit elements
def orbital_elements(x, y, vx, vy, K):
    """Elements of the Kepler orbit through (x, y, vx, vy) with K = k/μ = G M.

    Returns a dict with eccentricity e, semi_major_axis a (negative for
    hyperbolae, inf for the parabola), specific energy, specific angular
    momentum h, argument of pericentre omega, mean motion and period (bound
    orbits, Kepler's third law T = 2π √(a³/K), Goldstein eq. 3.71) and
    the mean anomaly at the initial state (bound orbits).
    """
    r = math.hypot(x, y)
    v2 = vx * vx + vy * vy
    h = x * vy - y * vx
    eps = 0.5 * v2 - K / r
    ex = vy * h / K - x / r  # e = (v × h)/K − r̂, the LRL vector / (μ k)
    ey = -vx * h / K - y / r
    e = math.hypot(ex, ey)
    out = {"eccentricity": e, "specific_energy": eps, "h": h, "K": K, "bound": eps < 0.0}
    out["semi_major_axis"] = -K / (2.0 * eps) if eps != 0.0 else math.inf
    out["pericentre"] = h * h / (K * (1.0 + e))
    if e > 1e-12:
        out["omega"] = math.atan2(ey, ex)
    else:  # circular: measure angles from the initial position
        out["omega"] = math.atan2(y, x)
    if eps < 0.0:
        a = out["semi_major_axis"]
        n = math.sqrt(K / a**3)
        out["mean_motion"] = n
        out["period"] = 2.0 * math.pi / n
        out["apocentre"] = a * (1.0 + e)
        # e cos E = 1 − r/a,  e sin E = r·v / √(K a)   (Danby §6.3)
        ecosE, esinE = 1.0 - r / a, (x * vx + y * vy) / math.sqrt(K * a)
        if e > 1e-12:
            E0 = math.atan2(esinE, ecosE)
        else:
            E0 = 0.0
        out["mean_anomaly0"] = E0 - e * math.sin(E0)
    return out


def solve_kepler(M, e, tol=1e-12, max_iter=60):
    """Eccentric anomaly E with E − e sin E = M (Kepler's equation), vectorised.

    Newton's method from Danby's starter E0 = M + 0.85 e sign(sin M) (Danby §6.6),
    which converges for every 0 ≤ e < 1 including e → 1.
    """
    M = np.asarray(M, dtype=np.float64)
    Mr = np.mod(M + math.pi, 2.0 * math.pi) - math.pi  # reduce to [−π, π)
    E = Mr + 0.85 * e * np.sign(np.sin(Mr))
    for _ in range(max_iter):
        f = E - e * np.sin(E) - Mr
        step = f / (1.0 - e * np.cos(E))
        E = E - step
        if np.all(np.abs(step) <= tol * (1.0 + np.abs(E))):
            # quadratic convergence: one more step takes 1e-12 to round-off
            E = E - (E - e * np.sin(E) - Mr) / (1.0 - e * np.cos(E))
            break
    else:
        raise RuntimeError(f"solve_kepler: Newton did not converge for e = {e}")
    return E + (M - Mr)


def kepler_state(t, elements):
    """(x, y, vx, vy) at times t on the bound Kepler orbit given by :func:`orbital_elements`.

    Mean anomaly M = M0 + n t, Kepler's equation for E, then the perifocal
    position a(cos E − e), b sin E rotated by ω (Goldstein eqs. 3.76–3.80).
    """
    el = elements
    a, e, n, w = el["semi_major_axis"], el["eccentricity"], el["mean_motion"], el["omega"]
    sense = 1.0 if el["h"] >= 0 else -1.0
    E = solve_kepler(el["mean_anomaly0"] + n * np.asarray(t, dtype=np.float64), e)
    cE, sE = np.cos(E), np.sin(E)
    b = a * math.sqrt(1.0 - e * e)
    xp, yp = a * (cE - e), sense * b * sE
    rate = n / (1.0 - e * cE)
    vxp, vyp = -a * sE * rate, sense * b * cE * rate
    c, s = math.cos(w), math.sin(w)
    return c * xp - s * yp, s * xp + c * yp, c * vxp - s * vyp, s * vxp + c * vyp


# ---------------------------------------------------------------- radial motion
def circular_radius(L, mu, k, n=1.0, epsilon=0.0):
    """Radius of the circular orbit with angular momentum L: V_eff'(r) = 0."""
    def g(r):
        return -L**2 / (mu * r**3) + float(potential_derivative(r, k, n, epsilon))

    lo, hi = 1e-12, 1.0
    while g(hi) < 0:
        hi *= 2.0
    while g(lo) > 0 and lo < hi:  # pragma: no cover - g(lo) < 0 for any admissible potential
        lo *= 0.5
    return optimize.brentq(g, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=500)


def turning_points(E, L, mu, k, n=1.0, epsilon=0.0):
    """Radii where E = V_eff(r) (the apsides), (r_min, r_max); r_max = inf if unbound."""
    def g(r):
        return float(effective_potential(r, L, mu, k, n, epsilon)) - E

    rc = circular_radius(L, mu, k, n, epsilon)
    if g(rc) >= 0.0:  # circular orbit (to round-off)
        return rc, rc
    lo = rc
    while g(lo) < 0.0:
        lo *= 0.5
    r_min = optimize.brentq(g, lo, rc, xtol=1e-15, rtol=1e-15, maxiter=500)
    if E >= 0.0:
        return r_min, math.inf
    hi = rc
    while g(hi) < 0.0:
        hi *= 2.0
    r_max = optimize.brentq(g, rc, hi, xtol=1e-15, rtol=1e-15, maxiter=500)
    return r_min, r_max


_GAUSS_LEGENDRE = special.roots_legendre(160)


def _radial_quadrature(integrand_factor, r_min, r_max, E, L, mu, k, n, epsilon):
    """∫_{r_min}^{r_max} f(r) dr / √(2(E − V_eff)/μ) with r = c − d cos θ (no endpoint singularity)."""
    c, d = 0.5 * (r_max + r_min), 0.5 * (r_max - r_min)

    def g_at(theta):
        # g = 2(E − V_eff(r))/μ / ((r − r_min)(r_max − r)): smooth, positive on [r_min, r_max]
        r = c - d * math.cos(theta)
        kinetic = 2.0 * (E - float(effective_potential(r, L, mu, k, n, epsilon))) / mu
        return r, kinetic / ((r - r_min) * (r_max - r))

    edge = 1e-4  # within 1e-4 rad of a turning point 0/0 rounds badly; g varies there by O(1e-8)

    def integrand(theta):
        r = c - d * math.cos(theta)
        _, g = g_at(min(max(theta, edge), math.pi - edge))
        # dr = d sin θ dθ and (r − r_min)(r_max − r) = d² sin² θ, so dr/√(prod g) = dθ/√g
        return integrand_factor(r) / math.sqrt(abs(g))

    # The integrand is smooth (analytic) in θ, so Gauss–Legendre converges exponentially;
    # an adaptive rule would chase the rounding noise of E − V_eff near circular orbits.
    nodes, weights = _GAUSS_LEGENDRE
    theta = 0.5 * math.pi * (nodes + 1.0)
    return 0.5 * math.pi * float(sum(w * integrand(x) for x, w in zip(theta, weights,
                                                                          strict=True)))


def apsidal_angle(E, L, mu, k, n=1.0, epsilon=0.0):
    """Angle swept from pericentre to apocentre, ∫ (L/μr²) dr / ṙ (Goldstein eq. 3.37).

    Exact for any bound orbit (quadrature); π for Kepler.
    """
    r_min, r_max = turning_points(E, L, mu, k, n, epsilon)
    return _radial_quadrature(lambda r: L / (mu * r * r), r_min, r_max, E, L, mu, k, n, epsilon)


def radial_period(E, L, mu, k, n=1.0, epsilon=0.0):
    """Time from pericentre to pericentre, 2 ∫ dr / ṙ (Goldstein eq. 3.17)."""
    r_min, r_max = turning_points(E, L, mu, k, n, epsilon)
    return 2.0 * _radial_quadrature(lambda r: 1.0, r_min, r_max, E, L, mu, k, n, epsilon)


def apsidal_angle_near_circular(n=1.0):
    """π/√(2 − n) for V = −k/rⁿ, i.e. π/√(3 + β) for a force ∝ r^β, β = −(n + 1).

    Small oscillations of r about the circular orbit have ω_r² = (3 + β) ω_φ²
    (Landau & Lifshitz §14 problem 2; Goldstein §3.6, the Bertrand-theorem
    argument eq. 3.47), so the apsidal angle is π ω_φ/ω_r.  Kepler (n = 1): π.
    """
    return math.pi / math.sqrt(2.0 - n)


def apsidal_angle_inverse_cube(L, mu, epsilon):
    """Exact apsidal angle π/√(1 − 2με/L²) for V = −k/r − ε/r² at any eccentricity.

    The ε/r² term adds to the centrifugal term: L² → L² − 2με, so the orbit is
    r = p/(1 + e cos γφ) with γ = √(1 − 2με/L²) (Landau & Lifshitz §15 problem 3).
    """
    return math.pi / math.sqrt(1.0 - 2.0 * mu * epsilon / L**2)


def potential_second_derivative(r, k, n=1.0, epsilon=0.0):
    """d²V/dr²."""
    r = np.asarray(r, dtype=np.float64)
    return -k * n * (n + 1.0) / r ** (n + 2) - 6.0 * epsilon / r**4


def apsides_from_samples(t, x, y, vx, vy, mu, k, n=1.0, epsilon=0.0, which="pericentre"):
    """Pericentre (or apocentre) passages located in the stored trajectory.

    The zeros of ṙ going up (down for ``which="apocentre"``) are refined with the
    quintic Hermite interpolant of ṙ, r̈, r⃛ (exact from the radial equation
    r̈ = h²/r³ − V'(r)/μ, 3.29, with
    h = L/μ); r and the unwrapped polar angle φ are then interpolated the same
    way (φ̇ = h/r², φ̈ = −2 h ṙ/r³).

    Returns
    -------
    times, radii, angles : ndarray, shape (K,)
    """
    from ..crossings import _quintic_hermite, upward_crossings

    t = np.asarray(t, dtype=np.float64)
    r = np.hypot(x, y)
    h = x * vy - y * vx
    h0 = float(h[0])
    rdot = (x * vx + y * vy) / r
    rddot = h0**2 / r**3 - potential_derivative(r, k, n, epsilon) / mu
    r3dot = (-3.0 * h0**2 / r**4 - potential_second_derivative(r, k, n, epsilon) / mu) * rdot
    sign = 1.0 if which == "pericentre" else -1.0
    times = upward_crossings(t, sign * rdot, sign * rddot, sign * r3dot)
    phi = np.unwrap(np.arctan2(y, x))
    phidot = h0 / r**2
    phiddot = -2.0 * h0 * rdot / r**3
    radii, angles = np.empty(times.size), np.empty(times.size)
    for j, tc in enumerate(times):
        i = min(int(np.searchsorted(t, tc, side="right")) - 1, t.size - 2)
        dt = t[i + 1] - t[i]
        s = (tc - t[i]) / dt
        for out, (f, fd, fdd) in ((radii, (r, rdot, rddot)), (angles, (phi, phidot, phiddot))):
            c = _quintic_hermite(dt, f[i], fd[i], fdd[i], f[i + 1], fd[i + 1], fdd[i + 1])
            out[j] = ((((c[5] * s + c[4]) * s + c[3]) * s + c[2]) * s + c[1]) * s + c[0]
    return times, radii, angles

