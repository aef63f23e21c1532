r"""``central_force``: the apsidal angle and the radial period of a bound orbit, accurate
down to the circular limit (Goldstein (3.37); Landau & Lifshitz §14).

In u = 1/r the orbit obeys (du/dφ)² = f(u) = 2μ(E − V)/L² − u² (Goldstein §3.5).  For the
power law V = −k/rⁿ, f(u) = a + b uⁿ − u² with b = 2μk/L²; its roots u₁ = 1/r_max and
u₂ = 1/r_min fix a and b, and the second divided difference gives, without cancellation,

    f(u) = (u − u₁)(u₂ − u) G(u),   G(u) = 1 − b · x ↦ xⁿ [u₁, u, u₂],

so that with u = c − d cos θ (c, d the mean and half-difference of the roots)

    ψ = ∫₀^π dθ / √G(u),     T_r = 2 ∫₀^π μ/(L u²) dθ / √G(u).

The divided differences are integrals of the derivatives over a simplex
(Hermite–Genocchi), taken by Gauss–Legendre rules: G and hence ψ keep full precision as
the orbit tends to a circle (where ψ → π/√(2 − n)), where E − V_eff, the difference of
two nearly equal numbers, loses it as 1/e².  For V = −k/r − ε/r² the radial motion is
Kepler's with L² → L² − 2με: ψ = π/√(1 − 2με/L²), T_r = 2π√(μa³/k), a = −k/(2E)
(Landau & Lifshitz §15, problem 3).  Plain floats in and out.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.polynomial.legendre import leggauss

#: nodes in θ of the apsidal and period integrals (the integrands are analytic in θ)
ANGLE_NODES = 160
#: nodes per direction of the simplex rules of the divided differences, used while the
#: roots are close, (u₂ − u₁)/(u₂ + u₁) = e ≤ WIDE (xⁿ⁻² varies by < 25 % over them)
SIMPLEX_NODES = 24
WIDE = 0.05

_THETA, _THETA_W = leggauss(ANGLE_NODES)
_S, _S_W = leggauss(SIMPLEX_NODES)
_S, _S_W = 0.5 * (_S + 1.0), 0.5 * _S_W  # on [0, 1]


def _first_difference(u1: float, u2: float, n: float) -> float:
    """x ↦ xⁿ [u₁, u₂] = ∫₀¹ n (u₁ + s (u₂ − u₁))ⁿ⁻¹ ds."""
    x = u1 + _S * (u2 - u1)
    return float(np.sum(_S_W * n * x ** (n - 1.0)))


def _second_difference(u1: float, u: np.ndarray, u2: float, n: float) -> np.ndarray:
    """x ↦ xⁿ [u₁, u, u₂] for every u: the integral of n(n − 1) xⁿ⁻² over the simplex
    x = u₁ + s (u − u₁) + t (u₂ − u₁), s, t ≥ 0, s + t ≤ 1 (Duffy: t = (1 − s) w)."""
    s = _S[:, None]
    w = _S[None, :]
    weight = (_S_W[:, None] * _S_W[None, :]) * (1.0 - s)
    u = np.asarray(u, dtype=np.float64)[..., None, None]
    x = u1 + s * (u - u1) + (1.0 - s) * w * (u2 - u1)
    return np.sum(weight * n * (n - 1.0) * x ** (n - 2.0), axis=(-2, -1))


def _difference(u, v, n: float):
    """x ↦ xⁿ [u, v] = (uⁿ − vⁿ)/(u − v) directly, vⁿ·expm1(n log1p((u − v)/v))/(u − v)
    (n vⁿ⁻¹ where u = v)."""
    u, v = np.broadcast_arrays(np.asarray(u, dtype=np.float64), np.asarray(v, dtype=np.float64))
    h = u - v
    same = h == 0.0
    safe = np.where(same, 1.0, h)
    return np.where(same, n * v ** (n - 1.0),
                    v**n * np.expm1(n * np.log1p(h / v)) / safe)


def _power_integrand(r_min: float, r_max: float, n: float):
    """u(θ) and 1/√G(u(θ)) on the Gauss nodes in θ ∈ [0, π]."""
    u1, u2 = 1.0 / r_max, 1.0 / r_min
    theta = 0.5 * math.pi * (_THETA + 1.0)
    u = 0.5 * (u1 + u2) - 0.5 * (u2 - u1) * np.cos(theta)
    if u2 - u1 <= WIDE * (u2 + u1):  # close roots: the simplex rules, exact to rounding
        b = (u1 + u2) / _first_difference(u1, u2, n)  # f(u₁) = f(u₂) = 0
        second = _second_difference(u1, u, u2, n)
    else:  # far apart: differences of differences lose only ~ε/e
        b = (u1 + u2) / float(_difference(u2, u1, n))
        second = (_difference(u2, u, n) - _difference(u, u1, n)) / (u2 - u1)
    G = 1.0 - b * second
    return u, 1.0 / np.sqrt(G)


def apsidal_angle_power(r_min: float, r_max: float, n: float) -> float:
    """Apsidal angle ψ (pericentre to apocentre) of the bound orbit of V = −k/rⁿ with
    turning points ``r_min`` ≤ ``r_max`` (equal: the near-circular limit π/√(2 − n))."""
    _, inv_sqrt_g = _power_integrand(r_min, r_max, n)
    return 0.5 * math.pi * float(np.sum(_THETA_W * inv_sqrt_g))


def radial_period_power(r_min: float, r_max: float, n: float, L: float, mu: float) -> float:
    """Radial period T_r (pericentre to pericentre) of the same orbit, angular momentum L
    and reduced mass μ: dt = μ/(L u²) dφ."""
    u, inv_sqrt_g = _power_integrand(r_min, r_max, n)
    return math.pi * float(np.sum(_THETA_W * mu / (abs(L) * u * u) * inv_sqrt_g))


def apsidal_angle_family_power(eccentricities, n: float) -> np.ndarray:
    """ψ against e = (r_max − r_min)/(r_max + r_min) for V = −k/rⁿ: a power law has no
    length scale, so ψ depends on the orbit's shape alone."""
    return np.array([apsidal_angle_power(1.0 - e, 1.0 + e, n) for e in eccentricities])


def apsidal_angle_inverse_cube(L: float, mu: float, epsilon: float) -> float:
    """ψ = π/√(1 − 2με/L²) of V = −k/r − ε/r² (ε = 0: Kepler's π), at every eccentricity."""
    return math.pi / math.sqrt(1.0 - 2.0 * mu * epsilon / (L * L))


def radial_period_inverse_cube(energy: float, mu: float, k: float) -> float:
    """T_r = 2π√(μa³/k), a = −k/(2E): the radial motion of V = −k/r − ε/r² is Kepler's."""
    a = -k / (2.0 * energy)
    return 2.0 * math.pi * math.sqrt(mu * a**3 / k)
