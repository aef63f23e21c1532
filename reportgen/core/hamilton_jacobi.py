r"""Hamilton–Jacobi solutions by quadrature for the two presets of the ``hamiltonian`` kind.

For these two Hamiltonians the Hamilton–Jacobi equation separates (lecture notes §7;
Goldstein §10.5); the report compares the separated first integrals and the motion that
the quadratures of the separated characteristic function W give with a numerical
integration of Hamilton's equations.  Plain floats and arrays in and out.

**Central potential** V = −k/r in spherical coordinates (r, θ, φ), mass m
(:data:`CENTRAL_H`)::

    W = ∫ √(2m(E + k/r) − L²/r²) dr + ∫ √(L² − L_z²/sin²θ) dθ + L_z φ

    ∂W/∂E   = t − t_p :  r = a(1 − e cos u),  u − e sin u = n (t − t_p)   (Kepler's equation)
    ∂W/∂L   = −ω      :  λ = ω + f            (f true anomaly, λ argument of latitude)
    ∂W/∂L_z = −Ω      :  cos θ = sin i sin λ,  tan(φ − Ω) = cos i tan λ,  cos i = L_z/L

with a = −k/2E, e² = 1 + 2EL²/(mk²), n = √(k/(m a³)) (Goldstein §10.8; Landau–Lifshitz
§15, §48).  Along the orbit p_r = √(mka) e sin u / r, p_θ = −L sin i cos λ / sin θ,
p_φ = L_z.

**Two fixed centres** in the plane, elliptic coordinates x = a cosh ξ cos η,
y = a sinh ξ sin η; the centre of G·M = μ1 sits at (+a, 0) (η = 0 side, distance
r1 = a(cosh ξ − cos η)) and μ2 at (−a, 0) (r2 = a(cosh ξ + cos η)); the particle has
mass m (:data:`TWO_CENTRES_H`)::

    H = (p_ξ² + p_η²) / (2 m a² D) − m μ1/r1 − m μ2/r2,     D = cosh²ξ − cos²η.

With the fictitious time dt = m a² D dτ, dξ/dτ = p_ξ and dη/dτ = p_η, and the
energy equation splits into two one-dimensional motions (Charlier; notes (7.59))::

    p_ξ² = F(ξ) =  β + 2 m a² E cosh²ξ + 2 m² a (μ1 + μ2) cosh ξ
    p_η² = G(η) = −β − 2 m a² E cos²η  + 2 m² a (μ1 − μ2) cos η

solved by τ = ∫ dξ/√F = ∫ dη/√G and t = m a² (∫ cosh²ξ dτ − ∫ cos²η dτ).

References
----------
.. [1] Lecture notes §7 (Hamilton–Jacobi; two fixed centres, eqs. 7.46–7.61).
.. [2] Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., §10.5 (separation of
       variables), §10.7–10.8 (the Kepler problem in action-angle variables).
.. [3] Landau & Lifshitz, *Mechanics*, 3rd ed., §15 (Kepler's problem), §48 (separation
       in spherical and elliptic coordinates).
.. [4] Charlier, C. L., *Die Mechanik des Himmels*, vol. 1 (1902), the problem of two
       fixed centres.
.. [5] Trefethen, L. N. & Weideman, J. A. C., "The exponentially convergent trapezoidal
       rule", *SIAM Review* 56 (2014) 385–458 (quadrature of periodic integrands).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import polynomial

CENTRAL_H = "(p_r**2 + p_theta**2/r**2 + p_phi**2/(r**2*sin(theta)**2))/(2*m) - k/r"

TWO_CENTRES_H = ("(p_xi**2 + p_eta**2)/(2*m*a**2*(cosh(xi)**2 - cos(eta)**2))"
                 " - m*mu1/(a*(cosh(xi) - cos(eta))) - m*mu2/(a*(cosh(xi) + cos(eta)))")

_EPS = np.finfo(np.float64).eps
_ROOT_MAX_STEPS = 200  # safeguarded Newton: bisection alone needs ~60 on a float64 bracket
_FOURIER_TAIL = 1e-14  # highest Fourier coefficients, relative to the function's scale
_FOURIER_MAX_NODES = 2**15  # more means a separatrix (period → ∞) is too close
_ON_AXIS = 1e-7  # libration amplitudes below this are rounding: motion on the x-axis


# ------------------------------------------------------------------ central potential
def central_integrals(r, theta, phi, p_r, p_theta, p_phi, m, k) -> dict:
    """The separated constants of :data:`CENTRAL_H` at each state.

    Parameters
    ----------
    r, theta, phi, p_r, p_theta, p_phi : array_like, shape (n,)
        Spherical coordinates (θ from the +z axis) and their conjugate momenta.
    m, k : float
        Mass and strength of V = −k/r.

    Returns
    -------
    dict of ndarray, shape (n,)
        ``E`` (the Hamiltonian), ``L2`` = p_θ² + p_φ²/sin²θ (the θ separation constant,
        |L|²) and ``Lz`` = p_φ (φ is cyclic).
    """
    r, theta, p_r, p_theta, p_phi = (np.asarray(v, dtype=np.float64)
                                     for v in (r, theta, p_r, p_theta, p_phi))
    L2 = p_theta**2 + (p_phi / np.sin(theta)) ** 2
    return {"E": (p_r**2 + L2 / r**2) / (2.0 * m) - k / r, "L2": L2, "Lz": p_phi.copy()}


def central_quadrature(m, k, state0, t) -> dict:
    """Bound motion in V = −k/r from the quadratures of W (module docstring), on ``t``.

    Parameters
    ----------
    m, k : float
        Mass and strength of the attraction, both > 0.
    state0 : sequence of 6 floats
        (r, θ, φ, p_r, p_θ, p_φ) at t = 0; 0 < θ < π unless p_φ = 0.
    t : array_like, shape (n,)
        Times.

    Returns
    -------
    dict of ndarray, shape (n,)
        ``r``, ``theta``, ``phi``, ``p_r``, ``p_theta``, ``p_phi``.  φ is continuous
        (not wrapped to (−π, π]) and starts at the given φ; θ ∈ (0, π) oscillates between
        the turning points π/2 ∓ i, p_θ changing sign there.

    Notes
    -----
    Equatorial orbits (L_z = ±L, sin i = 0) need no special case: the node is taken at
    the initial φ, θ ≡ π/2 and p_θ ≡ 0.  Polar orbits with p_φ = 0 exactly are a chart
    singularity of (θ, φ): Hamilton's equations of :data:`CENTRAL_H` carry θ through the
    poles at constant φ, and so does this solution (θ = θ0 ± (f − f0), unbounded).

    Raises
    ------
    ValueError
        For E ≥ 0 (unbound), L = 0 (radial, collision orbit) or θ0 outside (0, π) with
        p_φ ≠ 0.
    """
    r0, theta0, phi0, pr0, ptheta0, pphi0 = (float(v) for v in state0)
    t = np.asarray(t, dtype=np.float64)
    if not (m > 0 and k > 0):
        raise ValueError(f"central_quadrature: m = {m!r}, k = {k!r}; expected both > 0")
    if pphi0 != 0 and not 0 < theta0 < math.pi:
        raise ValueError(f"central_quadrature: theta0 = {theta0!r} with p_phi != 0; "
                         "expected 0 < theta0 < pi")
    c0 = central_integrals(r0, theta0, phi0, pr0, ptheta0, pphi0, m, k)
    E, L2, Lz = float(c0["E"]), float(c0["L2"]), float(c0["Lz"])
    if not E < 0:
        raise ValueError(f"central_quadrature: E = {E:.6g}; expected a bound orbit (E < 0)")
    if not L2 > 0:
        raise ValueError("central_quadrature: L = 0, a radial orbit into the centre")
    L = math.sqrt(L2)
    radial = _KeplerRadial.of(m, k, E, r0, pr0)
    u = radial.eccentric_anomaly(t)
    f = radial.true_anomaly(u)
    f0 = radial.true_anomaly(np.array(radial.u0))
    out = {"r": radial.r(u), "p_r": radial.p_r(u), "p_phi": np.full_like(t, Lz)}
    if Lz == 0:  # polar: θ runs through the poles, p_θ = m r² θ̇ = ±L
        sign = math.copysign(1.0, ptheta0)
        out.update(theta=theta0 + sign * (f - f0), phi=np.full_like(t, phi0),
                   p_theta=np.full_like(t, sign * L))
        return _central_in_order(out)
    # ∂W/∂L: the argument of latitude λ = ω + f; at t = 0 from
    # sin i sin λ0 = cos θ0 and sin i cos λ0 = −p_θ0 sin θ0 / L (no division by sin i)
    lam0 = math.atan2(math.cos(theta0), -ptheta0 * math.sin(theta0) / L)
    lam = lam0 + (f - f0)
    cos_i = Lz / L
    sin_i = math.hypot(ptheta0, pphi0 * math.cos(theta0) / math.sin(theta0)) / L
    cos_theta = sin_i * np.sin(lam)
    sin_theta = np.hypot(np.cos(lam), cos_i * np.sin(lam))
    out.update(theta=np.arctan2(sin_theta, cos_theta),
               p_theta=-L * sin_i * np.cos(lam) / sin_theta,
               phi=phi0 + _node_longitude(lam, cos_i) - _node_longitude(lam0, cos_i))
    return _central_in_order(out)


def _central_in_order(out):
    return {key: np.asarray(out[key], dtype=np.float64)
            for key in ("r", "theta", "phi", "p_r", "p_theta", "p_phi")}


def _node_longitude(lam, cos_i):
    """φ − Ω from ∂W/∂L_z: tan(φ − Ω) = cos i tan λ, continuous in λ (cos i ≠ 0).

    Written as s λ + atan2((cos i − s) sin λ cos λ, cos²λ + |cos i| sin²λ), s = sign cos i,
    whose second term is periodic: the denominator never vanishes.
    """
    s = math.copysign(1.0, cos_i)
    sin, cos = np.sin(lam), np.cos(lam)
    return s * lam + np.arctan2((cos_i - s) * sin * cos, cos * cos + abs(cos_i) * sin * sin)


@dataclass(frozen=True)
class _KeplerRadial:
    """The radial quadrature ∂W/∂E = t − t_p of V = −k/r: r = a(1 − e cos u)."""

    a: float
    e: float
    mean_motion: float  # n = √(k/(m a³))
    momentum_scale: float  # √(m k a): r p_r = √(m k a) e sin u
    u0: float  # eccentric anomaly at t = 0

    @classmethod
    def of(cls, m, k, E, r0, pr0):
        a = -k / (2.0 * E)
        scale = math.sqrt(m * k * a)
        e_cos, e_sin = 1.0 - r0 / a, r0 * pr0 / scale
        return cls(a, math.hypot(e_cos, e_sin), math.sqrt(k / (m * a**3)), scale,
                   math.atan2(e_sin, e_cos))

    def eccentric_anomaly(self, t):
        """u(t) from Kepler's equation u − e sin u = M0 + n t, continuous in t."""
        mean = self.u0 - self.e * math.sin(self.u0) + self.mean_motion * t
        turns = np.round(mean / (2 * math.pi))
        reduced = mean - 2 * math.pi * turns
        return 2 * math.pi * turns + _solve_kepler(reduced, self.e)

    def true_anomaly(self, u):
        """f(u), continuous: tan(f/2) = √((1+e)/(1−e)) tan(u/2) as u + 2 atan2(b sin u, 1 − b cos u)."""
        b = self.e / (1.0 + math.sqrt(1.0 - self.e**2))
        return u + 2.0 * np.arctan2(b * np.sin(u), 1.0 - b * np.cos(u))

    def r(self, u):
        return self.a * (1.0 - self.e * np.cos(u))

    def p_r(self, u):
        return self.momentum_scale * self.e * np.sin(u) / self.r(u)


def _solve_kepler(mean_anomaly, e):
    """u with u − e sin u = M to rounding; the root lies within e of M."""
    def kepler(u):
        return u - e * np.sin(u), 1.0 - e * np.cos(u)
    return _increasing_root(kepler, mean_anomaly, mean_anomaly - e, mean_anomaly + e,
                            mean_anomaly + e * np.sin(mean_anomaly))


# ------------------------------------------------------------------ two fixed centres
def two_centres_integrals(xi, eta, p_xi, p_eta, m, mu1, mu2, a) -> dict:
    r"""E and the separation constant β of :data:`TWO_CENTRES_H` at each state.

    β = p_ξ² − 2 m a² E cosh²ξ − 2 m² a (μ1 + μ2) cosh ξ
      = −p_η² − 2 m a² E cos²η + 2 m² a (μ1 − μ2) cos η      (notes 7.59, times m²)

    For μ1 = μ2 = μ this is m² times the β of (7.59) in
    :mod:`reportgen.core.models.two_center`, whose ξ, η are our cosh ξ, cos η and whose
    E is per unit mass: β = m² (−C − 2 a² E/m) with C = ``separation_constant(x, y,
    p_x/m, p_y/m, μ, a)`` (its C1 at (−a, 0) is our μ2, immaterial for equal masses).

    Parameters
    ----------
    xi, eta, p_xi, p_eta : array_like, shape (n,)
        Elliptic coordinates (module docstring) and their conjugate momenta.
    m, mu1, mu2, a : float
        Particle mass, G·M of the centres at (+a, 0) and (−a, 0), half their distance.

    Returns
    -------
    dict of ndarray, shape (n,)
        ``E`` and ``beta``.
    """
    xi, eta, p_xi, p_eta = (np.asarray(v, dtype=np.float64) for v in (xi, eta, p_xi, p_eta))
    ch, c = np.cosh(xi), np.cos(eta)
    D = ch * ch - c * c
    V = -m * ((mu1 + mu2) * ch + (mu1 - mu2) * c) / (a * D)
    E = (p_xi**2 + p_eta**2) / (2.0 * m * a * a * D) + V
    beta = p_xi**2 - 2.0 * m * a * a * E * ch * ch - 2.0 * m * m * a * (mu1 + mu2) * ch
    return {"E": E, "beta": beta}


def two_centres_quadrature(m, mu1, mu2, a, state0, t) -> dict:
    r"""Bound motion about two fixed centres from Charlier's quadratures, on ``t``.

    ξ(τ) and η(τ) are the separated motions p_ξ² = F(ξ), p_η² = G(η) of the module
    docstring in the fictitious time τ (dt = m a² D dτ), each written with a phase ψ
    that grows at a smooth positive rate; τ(ψ) and t(τ) are quadratures of periodic
    integrands (trapezoid rule, exponentially convergent [5]), inverted by Newton's method.

    Supported: E < 0 and

    * ξ librating between the roots of F — either between two confocal ellipses
      (0 < ξ1 ≤ |ξ| ≤ ξ2), or across the segment between the centres (−ξ2 ≤ ξ ≤ ξ2:
      the flow of :data:`TWO_CENTRES_H` continues through ξ = 0 to negative ξ, the same
      points with η → −η);
    * η librating about 0 (near the μ1 side) or about π (near μ2) between roots of G, or
      circulating (G > 0 for all η, η monotone with the sign of p_η).

    Refused: motion along the x-axis into a centre (ξ ≡ 0, or η ≡ 0 or π with ξ
    reaching 0), which is a collision.  Any other orbit that reaches ξ = 0 and η ∈ {0, π}
    together hits a centre only if the two phases happen to coincide there (a set of
    measure zero); the quadrature, regular in τ, then continues it as an elastic bounce.

    Parameters
    ----------
    m, mu1, mu2, a : float
        Particle mass, G·M of the centres at (+a, 0) and (−a, 0), half their distance.
    state0 : sequence of 4 floats
        (ξ, η, p_ξ, p_η) at t = 0.
    t : array_like, shape (n,)
        Times.

    Returns
    -------
    dict of ndarray, shape (n,)
        ``xi``, ``eta``, ``p_xi``, ``p_eta``; η is continuous from the given η0.

    Raises
    ------
    ValueError
        For E ≥ 0 (unbound), a start on a centre, a collision orbit along the x-axis, or
        an orbit so close to a separatrix (asymptotic, infinite-period motion in ξ or η)
        that the quadrature does not converge; also for m ≤ 0 or a ≤ 0.
    """
    xi0, eta0, pxi0, peta0 = (float(v) for v in state0)
    t = np.asarray(t, dtype=np.float64)
    if not (m > 0 and a > 0):
        raise ValueError(f"two_centres_quadrature: m = {m!r}, a = {a!r}; expected both > 0")
    if math.cosh(xi0) ** 2 - math.cos(eta0) ** 2 == 0:
        raise ValueError("two_centres_quadrature: the initial state is on a centre "
                         "(a collision)")
    c0 = two_centres_integrals(xi0, eta0, pxi0, peta0, m, mu1, mu2, a)
    E, beta = float(c0["E"]), float(c0["beta"])
    if not E < 0:
        raise ValueError(f"two_centres_quadrature: E = {E:.6g}; expected a bound orbit "
                         "(E < 0)")
    A = 2.0 * m * a * a * E  # F = A cosh²ξ + B_xi cosh ξ + β,  G = −A cos²η + B_eta cos η − β
    xi_motion = _xi_motion(A, 2.0 * m * m * a * (mu1 + mu2), beta, xi0)
    eta_motion = _eta_motion(A, 2.0 * m * m * a * (mu1 - mu2), beta, eta0, peta0)
    if _along_the_axis_into_a_centre(xi_motion, eta_motion):
        raise ValueError("two_centres_quadrature: a collision orbit (the motion stays on "
                         "the x-axis and runs into a centre)")
    xi = _SeparatedCoordinate.of(xi_motion, np.cosh, xi0, pxi0)
    eta = _SeparatedCoordinate.of(eta_motion, np.cos, eta0, peta0)
    tau = _fictitious_time(t, xi, eta, m * a * a)
    psi_xi, psi_eta = xi.phase(tau), eta.phase(tau)
    return {"xi": xi.motion.coordinate(psi_xi), "eta": eta.motion.coordinate(psi_eta),
            "p_xi": xi.motion.momentum(psi_xi), "p_eta": eta.motion.momentum(psi_eta)}


def _along_the_axis_into_a_centre(xi_motion, eta_motion):
    """ξ ≡ 0 (the segment between the centres), or η ≡ 0 or π while ξ passes through 0."""
    if xi_motion.centre != 0.0:  # between two ellipses: never at a centre
        return False
    return xi_motion.half < _ON_AXIS or (isinstance(eta_motion, _Libration)
                                         and eta_motion.half < _ON_AXIS)


def _fictitious_time(t, xi, eta, scale):
    """τ with t = scale (σ_ξ(τ) − σ_η(τ)), σ = ∫ cosh²ξ dτ resp. ∫ cos²η dτ, dt/dτ = scale·D ≥ 0."""
    rate = scale * (xi.weight_mean - eta.weight_mean)  # mean dt/dτ
    spread = scale * (xi.weight_spread + eta.weight_spread)  # bounds t − rate·τ

    def time(tau):
        psi_xi, psi_eta = xi.phase(tau), eta.phase(tau)
        value = scale * (xi.weight_integral(tau) - eta.weight_integral(tau))
        slope = scale * (xi.weight(psi_xi) - eta.weight(psi_eta))
        return value, slope

    return _increasing_root(time, t, (t - spread) / rate, (t + spread) / rate, t / rate)


# ------------------------------------------------------- separated 1-D motions in τ
@dataclass(frozen=True)
class _Libration:
    """q = centre + half sin ψ between the turning points centre ∓ half.

    ``reduced(q)`` = F(q)/((q − lo)(hi − q)) > 0 is evaluated without cancellation, so
    dψ/dτ = √reduced is smooth and positive through the turning points, where
    dq/dτ = half cos ψ √reduced = p changes sign with cos ψ.
    """

    centre: float
    half: float
    reduced: Callable[[np.ndarray], np.ndarray]

    def coordinate(self, psi):
        return self.centre + self.half * np.sin(psi)

    def rate(self, psi):
        return np.sqrt(self.reduced(self.coordinate(psi)))

    def momentum(self, psi):
        return self.half * np.cos(psi) * self.rate(psi)

    def initial_phase(self, q0, p0):
        if self.half == 0:  # at the bottom of the well: q ≡ centre
            return 0.0
        s = min(max((q0 - self.centre) / self.half, -1.0), 1.0)
        rate0 = float(np.sqrt(self.reduced(np.array(self.centre + self.half * s))))
        return math.atan2(s, p0 / (self.half * rate0))


@dataclass(frozen=True)
class _Circulation:
    """q = sign·ψ, rotating through 2π: dq/dτ = sign √F(q), F > 0 everywhere."""

    sign: float
    F: Callable[[np.ndarray], np.ndarray]

    def coordinate(self, psi):
        return self.sign * psi

    def rate(self, psi):
        return np.sqrt(self.F(self.coordinate(psi)))

    def momentum(self, psi):
        return self.sign * self.rate(psi)

    def initial_phase(self, q0, p0):
        return self.sign * q0


def _xi_motion(A, B, beta, xi0):
    """ξ between the roots of F = A (cosh ξ − c1)(cosh ξ − c2), A < 0."""
    c1, c2 = _quadratic_roots(A, B, beta)
    x2 = math.acosh(max(c2, 1.0))  # c2 ≥ cosh ξ0 but for rounding
    if c1 > 1:  # between the ellipses ξ1 and ξ2, on the side of ξ0's sign
        x1 = math.acosh(c1)

        def reduced(xi):
            xi = np.abs(xi)
            return (-A * np.sinh(0.5 * (xi + x1)) * _sinhc(0.5 * (xi - x1))
                    * np.sinh(0.5 * (x2 + xi)) * _sinhc(0.5 * (x2 - xi)))

        return _Libration(math.copysign(0.5 * (x1 + x2), xi0), 0.5 * (x2 - x1), reduced)

    def reduced_across(xi):  # through the segment between the centres
        return (-A * (np.cosh(xi) - c1) * 0.5 * _sinhc(0.5 * (x2 + xi))
                * _sinhc(0.5 * (x2 - xi)))

    return _Libration(0.0, x2, reduced_across)


def _eta_motion(A, B, beta, eta0, peta0):
    """η from G = −A cos²η + B cos η − β (−A > 0): circulating, or librating about 0 or π."""
    def G(eta):
        c = np.cos(eta)
        return (-A * c + B) * c - beta

    vertex = min(max(B / (2.0 * A), -1.0), 1.0)  # minimum of G over cos η ∈ [−1, 1]
    if (-A * vertex + B) * vertex - beta > 0:
        return _Circulation(math.copysign(1.0, peta0), G)
    w1, w2 = _quadratic_roots(-A, B, -beta)  # G = −A (cos η − w1)(cos η − w2)
    if math.cos(eta0) >= vertex:  # about η = 0: cos η ≥ w2
        centre, far_root, amplitude = 0.0, w1, math.acos(min(w2, 1.0))
        sign = 1.0
    else:  # about η = π: with ζ = η − π, cos ζ ≥ −w1
        centre, far_root, amplitude = math.pi, w2, math.acos(max(-w1, -1.0))
        sign = -1.0
    centre += 2 * math.pi * round((eta0 - centre) / (2 * math.pi))

    def reduced(eta):
        zeta = eta - centre
        return (-A * (sign * np.cos(zeta) - far_root) * sign * 0.5
                * _sinc(0.5 * (amplitude + zeta)) * _sinc(0.5 * (amplitude - zeta)))

    return _Libration(centre, amplitude, reduced)


def _quadratic_roots(A, B, C):
    """Real roots r1 ≤ r2 of A x² + B x + C without cancellation (A ≠ 0)."""
    disc = max(B * B - 4.0 * A * C, 0.0)  # < 0 only by rounding at a double root
    q = -0.5 * (B + math.copysign(math.sqrt(disc), B))
    roots = (q / A, C / q) if q != 0 else (0.0, 0.0)
    return min(roots), max(roots)


def _sinhc(x):
    """sinh(x)/x, 1 at 0."""
    x = np.asarray(x, dtype=np.float64)
    safe = np.where(x == 0, 1.0, x)
    return np.where(x == 0, 1.0, np.sinh(safe) / safe)


def _sinc(x):
    """sin(x)/x, 1 at 0."""
    return np.sinc(np.asarray(x) / math.pi)


@dataclass(frozen=True)
class _SeparatedCoordinate:
    """One separated coordinate as a function of τ: its phase ψ(τ) and σ(τ) = ∫ g(q) dτ.

    τ̃(ψ) = ∫_0^ψ dψ/rate is a secular term plus a 2π-periodic one; its inverse ψ(τ̃) and
    σ are secular plus periodic in τ̃ with the period T = τ̃(2π); all three are Fourier
    series from the periodic trapezoid rule.  τ = τ̃ − τ̃(ψ0), so ψ(0) = ψ0.
    """

    motion: _Libration | _Circulation
    weight: Callable[[np.ndarray], np.ndarray]  # g(q): cosh² ξ or cos² η
    phase_series: _Fourier  # ψ(τ̃)
    weight_series: _Fourier  # ∫_0^τ̃ g dτ̃
    tau0: float  # τ̃(ψ0)

    @classmethod
    def of(cls, motion, metric_root, q0, p0):
        """``metric_root``: cosh for ξ, cos for η (D = cosh²ξ − cos²η)."""
        def weight(psi):
            return metric_root(motion.coordinate(psi)) ** 2

        tau_of_psi = _Fourier.fit(lambda psi: 1.0 / motion.rate(psi), 2 * math.pi).integral()
        period = 2 * math.pi * tau_of_psi.slope

        def phase_at(tau):  # ψ with τ̃(ψ) = τ
            spread = tau_of_psi.spread
            return _increasing_root(lambda psi: (tau_of_psi(psi), 1.0 / motion.rate(psi)),
                                    tau, (tau - spread) / tau_of_psi.slope,
                                    (tau + spread) / tau_of_psi.slope,
                                    tau / tau_of_psi.slope)

        secular = 2 * math.pi / period
        phase = _Fourier.fit(lambda tau: phase_at(tau) - secular * tau, period,
                             scale=2 * math.pi).with_slope(secular)
        weight_series = _Fourier.fit(lambda tau: weight(phase_at(tau)), period).integral()
        psi0 = motion.initial_phase(q0, p0)
        return cls(motion, weight, phase, weight_series, float(tau_of_psi(np.array(psi0))))

    def phase(self, tau):
        return self.phase_series(tau + self.tau0)

    def weight_integral(self, tau):
        return self.weight_series(tau + self.tau0) - self.weight_series(np.array(self.tau0))

    @property
    def weight_mean(self):
        return self.weight_series.slope

    @property
    def weight_spread(self):
        return 2.0 * self.weight_series.spread


@dataclass(frozen=True)
class _Fourier:
    """slope·x + Re Σ_k coef[k] exp(i k 2π x/period), k = 0 … K."""

    period: float
    slope: float
    coef: np.ndarray  # complex, shape (K + 1,)

    @classmethod
    def fit(cls, func, period, scale=0.0):
        """Interpolant of a smooth periodic ``func`` on n equispaced nodes, n doubled
        until the top quarter of its coefficients is below 1e-14 of max(|func|, scale)."""
        n = 32
        while n <= _FOURIER_MAX_NODES:
            values = func(period * np.arange(n) / n)
            coef = np.fft.rfft(values)[: n // 2] / n  # without the Nyquist term
            coef[1:] *= 2.0
            size = max(float(np.max(np.abs(values))), scale)
            if np.max(np.abs(coef[3 * n // 8:])) <= _FOURIER_TAIL * size:
                return cls(period, 0.0, coef)
            n *= 2
        raise ValueError("two_centres_quadrature: the separated motion is too close to a "
                         "separatrix (its quadrature did not converge)")

    def with_slope(self, slope):
        return _Fourier(self.period, slope, self.coef)

    def integral(self):
        """∫_0^x of this periodic series (its slope must be 0)."""
        k = np.arange(1, self.coef.size)
        coef = np.empty_like(self.coef)
        coef[1:] = self.coef[1:] / (1j * k * (2 * math.pi / self.period))
        coef[0] = -np.sum(coef[1:].real)
        return _Fourier(self.period, float(self.coef[0].real), coef)

    @property
    def spread(self):
        """A bound on |value − slope·x|."""
        return float(abs(self.coef[0].real) + np.sum(np.abs(self.coef[1:])))

    def __call__(self, x):
        x = np.asarray(x, dtype=np.float64)
        turns = np.floor(x / self.period)
        z = np.exp(2j * math.pi / self.period * (x - turns * self.period))
        return self.slope * x + polynomial.polyval(z, self.coef).real


# -------------------------------------- characteristic function of one libration
#: Gauss–Legendre nodes: doubled from the first until the half action settles to this
_W_RTOL = 1e-15
_W_NODES_FIRST, _W_NODES_MAX = 16, 4096
#: step of the central differences in the angle ψ (rad), at most, and per unit distance d
#: of the integrand's nearest singularity from the real ψ axis (d ≈ √(2(1 − e)) at a Kepler
#: pericentre): five-point differences at two steps, Richardson-combined, err by ~ (step/d)⁶
#: (the residual of H(x, ∂W/∂x) = E by ~ 1e-9 at e = 0.999, ~ 1e-11 at e = 0.99); rounding
#: adds ~ ε/step
W_ANGLE_STEP = 1e-3
W_ANGLE_STEP_PER_DISTANCE = 1e-2
#: the angle kept from a turning point where ∂W/∂x = (dW/dψ)/(h sin ψ) is formed: the
#: point moves by h ψ²/2 = 5e-13 h, and (rounding/sin ψ)² stays below 1e-20 of E
W_ANGLE_FLOOR = 1e-6
#: samples per block of the vectorized quadrature (block × nodes values at a time)
_W_BLOCK = 2048
_FIVE_POINT = ((-2.0, 1.0 / 12.0), (-1.0, -8.0 / 12.0), (1.0, 8.0 / 12.0), (2.0, -1.0 / 12.0))


@dataclass(frozen=True)
class CharacteristicQuadrature:
    r"""Hamilton's characteristic function of one separated coordinate by quadrature.

    For a coordinate x librating between the simple roots a < b of F(x) = p_x² (F > 0
    between them), the branch p_x ≥ 0 of W (notes (7.32)–(7.34); Goldstein §10.3)::

        W(x) = ∫_a^x √F(x') dx'.

    In the angle ψ of x = c − h cos ψ (c = (a + b)/2, h = (b − a)/2) the integrand
    g(ψ) = h |sin ψ| √F(x(ψ)) = h² sin²ψ √(F/((x − a)(b − x))) is analytic and even about
    ψ = 0 and ψ = π: W(ψ) is analytic through both turning points, Gauss–Legendre on
    [0, ψ] converges exponentially, and central differences in ψ may straddle a turning
    point.  ∂W/∂x = (dW/dψ)/(h sin ψ), dW/dψ by a five-point central difference of the
    quadrature: a derivative independent of the integrand's closed form.

    Build with :meth:`of`.  ``F`` is called with arrays of any shape; ``reduced``, when
    given, is F/((x − a)(b − x)) in a form free of cancellation (−2μE/r² for the Kepler
    radial motion), and the integrand is then h² sin²ψ √reduced: F itself is a small
    difference of large terms near the turning points and on a nearly circular orbit.
    """

    F: Callable[[np.ndarray], np.ndarray]
    a: float
    b: float
    nodes: int  # Gauss–Legendre nodes on [0, ψ]
    reduced: Callable[[np.ndarray], np.ndarray] | None = None
    pole: float | None = None  # a real x outside [a, b] where F is singular (r = 0)

    @classmethod
    def of(cls, F, a, b, *, reduced=None, pole=None) -> CharacteristicQuadrature:
        """The quadrature with as many nodes as the half action ∫_a^b √F dx needs to
        settle (doubling from 16): to 1e-15, or to its rounding noise — the change on
        doubling no longer halves, as when F is a small difference of large terms (a
        nearly circular orbit).  ValueError unless a < b, or if it never settles."""
        a, b = float(a), float(b)
        if not a < b:
            raise ValueError(f"CharacteristicQuadrature: turning points a = {a!r}, "
                             f"b = {b!r}; expected a < b")
        if pole is not None and a <= pole <= b:
            raise ValueError(f"CharacteristicQuadrature: pole = {pole!r} lies between the "
                             f"turning points {a!r} and {b!r}")
        n = _W_NODES_FIRST
        last, change = cls(F, a, b, n, reduced, pole).half_action, math.inf
        while n < _W_NODES_MAX:
            n *= 2
            value = cls(F, a, b, n, reduced, pole).half_action
            if abs(value - last) <= _W_RTOL * abs(value):
                return cls(F, a, b, n, reduced, pole)
            if n >= 4 * _W_NODES_FIRST and abs(value - last) > 0.5 * change:
                return cls(F, a, b, n // 2, reduced, pole)  # at the noise floor: no gain
            last, change = value, abs(value - last)
        raise ValueError("CharacteristicQuadrature: the half action did not converge "
                         f"with {_W_NODES_MAX} Gauss–Legendre nodes")

    @property
    def centre(self) -> float:
        return 0.5 * (self.a + self.b)

    @property
    def half_width(self) -> float:
        return 0.5 * (self.b - self.a)

    @property
    def angle_step(self) -> float:
        """The central-difference step in ψ: :data:`W_ANGLE_STEP`, or less near a pole
        x_p, whose distance from the real ψ axis is d = arccosh(|c − x_p|/h)."""
        if self.pole is None:
            return W_ANGLE_STEP
        d = math.acosh(abs(self.centre - self.pole) / self.half_width)
        return min(W_ANGLE_STEP, W_ANGLE_STEP_PER_DISTANCE * d)

    def angle(self, x):
        """ψ ∈ [0, π] of x = c − h cos ψ; x outside [a, b] (an integration's rounding
        past a turning point) is taken at the nearer turning point."""
        u = (self.centre - np.asarray(x, dtype=np.float64)) / self.half_width
        return np.arccos(np.clip(u, -1.0, 1.0))

    def coordinate(self, psi):
        return self.centre - self.half_width * np.cos(psi)

    def integrand(self, psi):
        """dW/dψ = h |sin ψ| √F(x(ψ)) (F < 0 by rounding at a turning point read as 0), or
        h² sin²ψ √reduced(x(ψ))."""
        psi = np.asarray(psi, dtype=np.float64)
        x, h, sin = self.coordinate(psi), self.half_width, np.sin(psi)
        if self.reduced is not None:
            return h * h * sin * sin * np.sqrt(np.asarray(self.reduced(x), dtype=np.float64))
        F = np.asarray(self.F(x), dtype=np.float64)
        return h * np.abs(sin) * np.sqrt(np.maximum(F, 0.0))

    def at_angle(self, psi):
        """W at the angles ψ, by Gauss–Legendre on [0, ψ]; any real ψ (the integrand is even
        about 0 and π, so W continues analytically past both turning points)."""
        psi = np.asarray(psi, dtype=np.float64)
        x, w = _gauss_legendre(self.nodes)
        half = 0.5 * psi[..., None]
        return np.sum(w * self.integrand(half * (1.0 + x)), axis=-1) * half[..., 0]

    def __call__(self, x):
        """W(x) on the branch p_x ≥ 0, shape of ``x``."""
        return self.at_angle(self.angle(x))

    @property
    def half_action(self) -> float:
        """∫_a^b √F dx = W(b): half the action variable J = ∮ p_x dx (Goldstein §10.6)."""
        return float(self.at_angle(np.array(math.pi)))

    def gradient(self, x):
        """∂W/∂x at ``x`` by central differences of the quadrature (class docstring).

        dW/dψ is the five-point difference at steps s and s/2 combined by Richardson
        extrapolation, D = (16 D(s/2) − D(s))/15 (error O(s⁶)), with s = :attr:`angle_step`.

        Returns
        -------
        x_at, dW_dx : ndarray, shape of ``x``
            Where the derivative was taken: ``x`` itself, or for x within h ψ²/2 of a turning
            point (ψ < 1e-6; also x past it) the point at ψ = 1e-6 from it, where the quotient
            (dW/dψ)/(h sin ψ) is still formed without loss; and ∂W/∂x there (≥ 0).
        """
        psi = np.clip(self.angle(x), W_ANGLE_FLOOR, math.pi - W_ANGLE_FLOOR)
        flat, out = psi.ravel(), np.empty(psi.size)
        for lo in range(0, flat.size, _W_BLOCK):
            block = flat[lo:lo + _W_BLOCK]
            out[lo:lo + _W_BLOCK] = self._angle_derivative(block)
        dW_dpsi = out.reshape(psi.shape)
        return self.coordinate(psi), dW_dpsi / (self.half_width * np.sin(psi))

    def _angle_derivative(self, psi):
        """dW/dψ at ``psi`` by Richardson-combined five-point central differences."""
        def five_point(step):
            return sum(c * self.at_angle(psi + k * step) for k, c in _FIVE_POINT) / step

        step = self.angle_step
        return (16.0 * five_point(0.5 * step) - five_point(step)) / 15.0


def _gauss_legendre(n):
    """Nodes and weights of the n-point Gauss–Legendre rule on [−1, 1]."""
    return np.polynomial.legendre.leggauss(n)


def kepler_radial_turning_points(mu, k, E, C) -> tuple[float, float]:
    """r_min, r_max: the roots of 2μE r² + 2μk r − C, each without cancellation,
    C/(B + √D) and (B + √D)/(−2μE) with B = μk, D = B² + 2μE C (E < 0, C > 0)."""
    A, B = 2.0 * mu * E, mu * k
    if not (A < 0 and C > 0):
        raise ValueError(f"kepler_radial_turning_points: E = {E!r}, C = {C!r}; expected "
                         "E < 0 and C > 0 (a bound orbit)")
    root_D = math.sqrt(max(B * B + A * C, 0.0))
    return C / (B + root_D), (B + root_D) / -A


def kepler_radial_characteristic(r, mu, k, E, C):
    r"""W_r(r) = ∫_{r_min}^r √(2μE + 2μk/r' − C/r'²) dr' in closed form, E < 0, C > 0.

    The radial part of W = W_r(r) + α_θ θ for V = −k/r in the plane, C = α_θ² (C = L² − 2με
    when V carries a further −ε/r²).  With R = A r² + 2B r − C (A = 2μE, B = μk) and
    D = B² + AC, integrating √R/r = (Ar + B)/√R + B/√R − C/(r√R) term by term (the last
    with s = 1/r)::

        W_r = √R + (B/√−A)(arcsin u + π/2) − √C (π/2 − arcsin v),
        u = (−A r − B)/√D,  v = (C/r − B)/√D,

    u running from −1 at r_min to 1 at r_max, v from 1 to −1, so that
    W_r(r_max) = π(B/√−A − √C) = π(k√(μ/(−2E)) − α_θ), half the radial action
    (Goldstein §10.8).  Evaluated as √R = √(−A (r − r_min)(r_max − r)),
    arcsin u + π/2 = 2 atan2(√(1 + u), √(1 − u)) and π/2 − arcsin v alike, with 1 ± u and
    1 ± v proportional to r − r_min and r_max − r.  r outside [r_min, r_max] is taken at
    the nearer turning point.
    """
    r = np.asarray(r, dtype=np.float64)
    A, B = 2.0 * mu * E, mu * k
    r_min, r_max = kepler_radial_turning_points(mu, k, E, C)
    r = np.clip(r, r_min, r_max)
    below, above = r - r_min, r_max - r  # R = −A (r − r_min)(r_max − r)
    # arcsin u + π/2 and π/2 − arcsin v from 1 ± u, 1 ± v without cancellation: arcsin
    # near ±1 would lose half the digits next to the turning points
    u_term = 2.0 * np.arctan2(np.sqrt(below), np.sqrt(above))
    v_term = 2.0 * np.arctan2(np.sqrt(below / r_min), np.sqrt(above / r_max))
    return (np.sqrt(-A * below * above) + B / math.sqrt(-A) * u_term
            - math.sqrt(C) * v_term)


# ------------------------------------------------------------------ root finding
def _increasing_root(residual, target, lo, hi, guess):
    """Elementwise x in [lo, hi] with f(x) = target for an increasing f.

    ``residual(x)`` returns (f(x), f'(x)).  Newton's method safeguarded as in Numerical
    Recipes' ``rtsafe``: a bisection of the bracket (which shrinks with every evaluation)
    whenever a Newton step would leave it or is not half the step before last; stops
    once a step is within rounding (4 ε of the bracket's magnitude).
    """
    target = np.asarray(target, dtype=np.float64)
    shape = target.shape
    target = target.ravel()
    lo, hi, x = (np.array(np.broadcast_to(v, shape), dtype=np.float64).ravel()
                 for v in (lo, hi, guess))
    tol = 4 * _EPS * np.maximum(np.maximum(np.abs(lo), np.abs(hi)), np.finfo(float).tiny)
    last = before_last = hi - lo
    active = np.arange(x.size)
    for _ in range(_ROOT_MAX_STEPS):
        if active.size == 0:
            return x.reshape(shape)
        xa = x[active]
        f, df = residual(xa)
        r = f - target[active]
        lo[active] = lo_a = np.where(r <= 0, xa, lo[active])
        hi[active] = hi_a = np.where(r >= 0, xa, hi[active])
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = r / df
        use_newton = ((xa - newton >= lo_a) & (xa - newton <= hi_a)
                      & (2 * np.abs(newton) <= before_last[active]))
        step = np.where(use_newton, newton, -0.5 * (hi_a - lo_a))
        x[active] = np.where(use_newton, xa - newton, 0.5 * (lo_a + hi_a))
        before_last[active], last[active] = last[active], np.abs(step)
        active = active[np.abs(step) > tol[active]]
    raise RuntimeError("safeguarded Newton did not converge")  # unreachable: bisection
