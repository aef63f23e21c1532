r"""``central_force``: the Hamilton–Jacobi equations along a bound run (notes (7.16),
(7.32), (7.42)–(7.45)).

In plane polar coordinates the relative motion has H = p_r²/2μ + p_θ²/(2μr²) + V(r); θ is
cyclic, and the complete integral is S = W − E t with Hamilton's characteristic function
(Goldstein §10.5; lecture notes §7)::

    W(r, θ; E, α_θ) = W_r(r) + α_θ θ,    W_r = ∫_{r_min}^r √(2μ(E − V(r')) − α_θ²/r'²) dr'.

Along the run, with E and α_θ = L its initial energy and angular momentum, ∂W/∂r is taken
once from the integrand's closed form and once by central differences of W_r computed by
quadrature (:class:`reportgen.core.hamilton_jacobi.CharacteristicQuadrature`), ∂W/∂θ and
∂S/∂t by central differences too; the residuals of ∂S/∂t + H(q, ∂S/∂q) = 0 and of
H(q, ∂W/∂q) = E are relative to |E|.  For V = −k/r (and −k/r − ε/r², which only replaces
α_θ² by α_θ² − 2με) W_r and the half radial action have closed forms to check the
quadrature against (Goldstein §10.8).  Plain arrays in, a dict of results and checks out.
"""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.results import Check

hj = lazy_module("reportgen.core.hamilton_jacobi")
kepler = lazy_module("reportgen.core.models.kepler")

#: central-difference steps of ∂W/∂θ [rad] and of ∂S/∂t [the run's length]: S is linear in
#: both, so only rounding enters, ~ ε |S| / step (θ is taken in (−π, π], a branch of W, to
#: keep |α_θ θ| small: at a pericentre p_θ²/(2μr²) may be 40 |E|)
ANGLE_STEP = 1e-2
TIME_STEP = 1e-2
#: points of the ±∂W/∂r curve drawn, and of its quadrature derivative marked on it
CURVE_POINTS, MARKS = 401, 24
#: (r_max − r_min)/(r_max + r_min) below this is a circle: W_r ≡ 0, nothing to evaluate
MIN_ECCENTRICITY = 1e-6


def polar(x, y, vx, vy, mu):
    """r, θ ∈ (−π, π], p_r = μ ṙ and p_θ = μ r² θ̇ of the relative motion, shape (N,)."""
    r = np.hypot(x, y)
    return r, np.arctan2(y, x), mu * (x * vx + y * vy) / r, mu * (x * vy - y * vx)


def applies(r_min: float, r_max: float) -> bool:
    """Whether the radial motion librates between two distinct turning points."""
    return math.isfinite(r_max) and r_max - r_min > MIN_ECCENTRICITY * (r_max + r_min)


def residuals(t, state, *, mu, k, n, epsilon, energy, angular_momentum,
              potential_name) -> tuple[dict, list[Check]]:
    """The Hamilton–Jacobi results of a bound run (module docstring).

    Parameters
    ----------
    t : ndarray, shape (N,)
    state : tuple of 4 ndarrays, shape (N,)
        x, y, vx, vy of the relative coordinate.
    mu, k, n, epsilon : float
        Reduced mass and V = −k/rⁿ − ε/r².
    energy, angular_momentum : float
        E and α_θ = L of the initial state: the complete integral's constants.
    potential_name : str
        "kepler", "kepler_inverse_cube" (closed forms exist) or "power".

    Returns
    -------
    analysis : dict
        ``hj_*`` scalars and the ``hamilton_jacobi`` group the report draws.
    checks : list of Check
    """
    E, L = float(energy), float(angular_momentum)
    r, theta, p_r, p_theta = polar(*state, mu)
    closed = potential_name in ("kepler", "kepler_inverse_cube")
    C = L * L - 2.0 * mu * epsilon  # α_θ² in the centrifugal term, with V's −ε/r² in it

    def V(radius):
        return kepler.potential(radius, k, n, epsilon)

    def F(radius):  # p_r² on the surface H = E: (∂W/∂r)²
        return 2.0 * mu * (E - V(radius)) - L * L / radius**2

    def H(radius, momentum_r, momentum_theta):
        return (momentum_r**2 + momentum_theta**2 / radius**2) / (2.0 * mu) + V(radius)

    if closed:
        r_min, r_max = hj.kepler_radial_turning_points(mu, k, E, C)
        W_r = hj.CharacteristicQuadrature.of(F, r_min, r_max, pole=0.0,
                                             reduced=lambda radius: -2.0 * mu * E / radius**2)
    else:
        r_min, r_max = kepler.turning_points(E, L, mu, k, n, epsilon)
        W_r = hj.CharacteristicQuadrature.of(F, r_min, r_max, pole=0.0)

    # ∂W/∂r from the integrand, at the run's r (a rounding past a turning point taken at it)
    r_in = np.clip(r, r_min, r_max)
    from_integrand = H(r_in, np.sqrt(np.maximum(F(r_in), 0.0)), L)
    # from W by quadrature: ∂W/∂r, ∂W/∂θ and ∂S/∂t by central differences
    r_at, dW_dr = W_r.gradient(r)
    W_at = W_r(r_at)
    dW_dtheta = ((W_at + L * (theta + ANGLE_STEP)) - (W_at + L * (theta - ANGLE_STEP))) \
        / (2.0 * ANGLE_STEP)
    tau = TIME_STEP * float(t[-1])
    S_later = W_at + L * theta - E * (t + tau)
    S_earlier = W_at + L * theta - E * (t - tau)
    dS_dt = (S_later - S_earlier) / (2.0 * tau)
    by_quadrature = H(r_at, dW_dr, dW_dtheta)

    # the integrated momenta against ∂W/∂q on their branch (p_r's sign)
    curve_r = W_r.coordinate(np.linspace(0.0, math.pi, CURVE_POINTS))
    curve_p = np.sqrt(np.maximum(F(curve_r), 0.0))
    branch = np.sign(p_r) * np.sqrt(np.maximum(F(r), 0.0))
    momentum = max(float(np.max(np.abs(p_r - branch))) / float(np.max(curve_p)),
                   float(np.max(np.abs(p_theta - L))) / abs(L))
    mark_r, mark_p = W_r.gradient(W_r.coordinate(
        np.linspace(0.0, math.pi, MARKS + 2)[1:-1]))

    scale = abs(E)
    out = {
        "hj_residual": float(np.max(np.abs(from_integrand - E)) / scale),
        "hj_residual_quadrature": float(np.max(np.abs(dS_dt + by_quadrature)) / scale),
        "hj_characteristic_residual_quadrature":
            float(np.max(np.abs(by_quadrature - E)) / scale),
        "hj_half_action": W_r.half_action,
        "hj_momentum_difference": momentum,
        "hamilton_jacobi": {"radius": r, "radial_momentum": p_r, "curve_r": curve_r,
                            "curve_p_r": curve_p, "marks_r": mark_r, "marks_p_r": mark_p},
    }
    worst = int(np.argmax(np.abs(by_quadrature - E)))
    checks = [Check("H(r, ∂W/∂r, ∂W/∂θ), W by quadrature, worst sample",
                    float(by_quadrature[worst]), E, "J", "E, notes (7.32)", scale=scale)]
    if closed:
        # half the radial action, π(k√(μ/(−2E)) − √C): relative to its first term, the
        # size of the two whose difference it is (small for a nearly circular orbit)
        size = math.pi * k * math.sqrt(mu / (-2.0 * E))
        exact = size - math.pi * math.sqrt(C)
        out["hj_half_action_closed_form"] = exact
        out["hj_characteristic_quadrature_error"] = float(
            np.max(np.abs(W_r(r) - hj.kepler_radial_characteristic(r, mu, k, E, C))) / size)
        words = "π(k√(μ/(−2E)) − L)" if epsilon == 0 else "π(k√(μ/(−2E)) − √(L² − 2με))"
        checks.append(Check("∫ pᵣ dr from rₘᵢₙ to rₘₐₓ, by quadrature", W_r.half_action,
                            exact, "J·s", f"{words}, Goldstein §10.8", scale=size))
    return out, checks
