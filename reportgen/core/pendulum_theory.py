"""Pendulum constants of the motion that need no numerics library: the elliptic parameter
k^2 and its complement 1 - k^2 (config validation uses them without importing numba or
scipy).  The solutions and the compiled model are in :mod:`reportgen.core.models.pendulum`.
"""

from __future__ import annotations

import math


def modulus_squared(theta0, theta_dot0, omega0):
    """Elliptic parameter m = k^2 of the motion, k^2 = sin^2(theta0/2) + (theta_dot0 / 2 omega0)^2.

    m < 1: libration with amplitude 2 asin(k); m > 1: rotation; m = 1: separatrix.
    """
    return math.sin(0.5 * theta0) ** 2 + (theta_dot0 / (2.0 * omega0)) ** 2


def complementary_parameter(theta0, theta_dot0, omega0):
    """1 - k^2 = cos^2(theta0/2) - (theta_dot0 / 2 omega0)^2, computed without cancellation.

    Near the separatrix k^2 rounds to 1 long before 1 - k^2 loses its digits
    (theta0 = pi - 1e-8 gives 1 - k^2 = 2.5e-17).
    """
    return math.cos(0.5 * theta0) ** 2 - (theta_dot0 / (2.0 * omega0)) ** 2


#: |1 - k^2| below this: on the separatrix.  E differs from the separatrix energy
#: 2 m g l (measured from the bottom) by |1 - k^2| of it, E - E_s = -2 m g l (1 - k^2), and
#: 1e-12 is finer than an integration at the default rtol holds the energy: such a run cannot
#: tell libration from rotation, and the exact period 4K(k)/omega0 ~ (2/omega0) ln(16/|1 - k^2|)
#: is set by the residue alone
SEPARATRIX_ON = 1e-12
#: |1 - k^2| below this: near the separatrix.  The motion then spends more than half of
#: each period (or turn) beyond 135 degrees from the bottom: 56 % at 1 - k^2 = 1e-2, 57 % at
#: k^2 - 1 = 1e-2 (t(theta) = F(phi | k^2)/omega0, DLMF 22.19.2), and ~80 % at 1e-6
SEPARATRIX_NEAR = 1e-2


def separatrix_proximity(m1) -> str:
    """"on", "near" or "far": |1 - k^2| against :data:`SEPARATRIX_ON` and
    :data:`SEPARATRIX_NEAR` (``m1`` = 1 - k^2, :func:`complementary_parameter`)."""
    gap = abs(m1)
    if gap < SEPARATRIX_ON:
        return "on"
    return "near" if gap < SEPARATRIX_NEAR else "far"


def motion_case(m1) -> str:
    """The case the words of a report follow: "libration", "rotation" (each far from the
    separatrix), "libration near the separatrix", "rotation near the separatrix", or
    "separatrix" (:func:`separatrix_proximity`; the sign of 1 - k^2 decides the side)."""
    proximity = separatrix_proximity(m1)
    if proximity == "on":
        return "separatrix"
    side = "libration" if m1 > 0.0 else "rotation"
    return f"{side} near the separatrix" if proximity == "near" else side


#: below this |1 - k^2| scipy's double-precision ellipj no longer resolves the motion
#: (measured against 40-digit mpmath: 4e-9 error at 1 - k^2 = 2.5e-7 over 12 periods)
EXACT_SOLUTION_MIN_M1 = 1e-8


# ------------------------------------------------- the linear boundary-value problem
# θ'' = −ω² θ, θ(0) = θ0, θ(T) = θ1, solution notes (1.21)
#     θ(t) = [θ0 sin ω(T − t) + θ1 sin ωt] / sin ωT,
# action notes (2.4), I = m l², x = ωT:
#     S = I ω [(θ0² + θ1²) cos x − 2 θ0 θ1] / (2 sin x)
#       = I/(2T) [(θ1 − θ0)² x cot x − 2 θ0 θ1 x tan(x/2)]      (x cot x − x/sin x = −x tan(x/2))
# The second form has no 0/0 as x → 0 and tends to the free particle's I (θ1 − θ0)²/(2T),
# notes (2.5); S − S_free needs x cot x − 1 by its series below |x| = 1/2.

#: x cot x = 1 − Σ c_n x^(2n), c_n = 2^(2n) |B_2n| / (2n)! (DLMF 4.19.6), n = 1 … 10
_XCOTX = tuple(4.0**n * b / math.factorial(2 * n) for n, b in enumerate(
    (1 / 6, 1 / 30, 1 / 42, 1 / 30, 5 / 66, 691 / 2730, 7 / 6, 3617 / 510, 43867 / 798,
     174611 / 330), start=1))
#: below this |x| the series of x cot x − 1: its first omitted term, 2 ζ(22) (x/π)^22, is
#: 6e-17 of the sum at x = 1/2; above it the cancellation in x cot x − 1 costs < 1e-14
SERIES_BELOW = 0.5


def x_cot_x_minus_one(x):
    """x cot x − 1 to full relative precision (−x²/3 − x⁴/45 − …, DLMF 4.19.6 near 0)."""
    if abs(x) < SERIES_BELOW:
        x2, total, power = x * x, 0.0, 1.0
        for c in _XCOTX:
            power *= x2
            total -= c * power
        return total
    return x * math.cos(x) / math.sin(x) - 1.0


def x_over_sin_x(x):
    """x / sin x, 1 at x = 0."""
    return 1.0 if x == 0.0 else x / math.sin(x)


def free_particle_action(theta0, theta1, T, inertia):
    """Action of the free rotor θ = θ0 + (θ1 − θ0) t/T, notes (1.22) and (2.5) [J·s]:
    S_free = I (θ1 − θ0)² / (2T), ``inertia`` I = m l² [kg m²]."""
    return inertia * (theta1 - theta0) ** 2 / (2.0 * T)


def linear_action_excess(theta0, theta1, T, omega, inertia):
    """S − S_free of the linear problem [J·s], exact and precise down to ω = 0:

    S − S_free = I/(2T) [(θ1 − θ0)² (x cot x − 1) − 2 θ0 θ1 x tan(x/2)],   x = ωT,

    → −(I ω² T / 6)(θ0² + θ0 θ1 + θ1²) (:func:`free_path_potential_action`) as ω → 0.
    """
    x = omega * T
    return inertia / (2.0 * T) * ((theta1 - theta0) ** 2 * x_cot_x_minus_one(x)
                                  - 2.0 * theta0 * theta1 * x * math.tan(0.5 * x))


def linear_action(theta0, theta1, T, omega, inertia):
    """Action, notes (2.4), of the solution, notes (1.21), of the linearised problem [J·s]:
    S_free + (S − S_free) (:func:`linear_action_excess`), so ω → 0 loses no figures."""
    return (free_particle_action(theta0, theta1, T, inertia)
            + linear_action_excess(theta0, theta1, T, omega, inertia))


def free_path_potential_action(theta0, theta1, T, omega, inertia):
    """∫ V dt along the free path θ0 + (θ1 − θ0) t/T, V = I ω² θ²/2 [J·s]:
    I ω² T (θ0² + θ0 θ1 + θ1²)/6.  Minus it is the first-order change of S with ω²
    (S is stationary on the free path, notes §2)."""
    return inertia * omega**2 * T * (theta0**2 + theta0 * theta1 + theta1**2) / 6.0


def linear_end_momenta(theta0, theta1, T, omega, inertia):
    """p(0) and p(T) = I θ̇ at the ends of the solution, notes (1.21) [J·s]:

    p(0) = I ω (θ1 − θ0 cos x)/sin x,   p(T) = I ω (θ1 cos x − θ0)/sin x,   x = ωT,

    by notes (7.1–7.15) −∂S/∂θ0 and ∂S/∂θ1 of the action, notes (2.4).  At ω = 0 both are
    the free rotor's I (θ1 − θ0)/T.
    """
    x = omega * T
    scale = inertia / T * x_over_sin_x(x)
    cos_x = math.cos(x)
    return scale * (theta1 - theta0 * cos_x), scale * (theta1 * cos_x - theta0)


def linear_energy(theta0, theta1, T, omega, inertia):
    """Energy E = I θ̇²/2 + I ω² θ²/2 of the solution, notes (1.21) [J]:

    E = I ω² (θ0² + θ1² − 2 θ0 θ1 cos x) / (2 sin² x)
      = I/(2T²) (x/sin x)² [(θ1 − θ0)² + 4 θ0 θ1 sin²(x/2)],   x = ωT,

    equal to −∂S/∂T by notes (7.1–7.15).
    """
    x = omega * T
    return inertia / (2.0 * T * T) * x_over_sin_x(x) ** 2 * (
        (theta1 - theta0) ** 2 + 4.0 * theta0 * theta1 * math.sin(0.5 * x) ** 2)


def conjugate_distance(T, omega):
    """Distance [s] from T to the nearest time k π/ω, k = 0, 1, … at which the linear problem
    is singular (S and its derivatives ∝ 1/sin ωT): the scale of a finite-difference step."""
    if omega == 0.0:
        return T
    half_period = math.pi / omega
    k = round(T / half_period)
    return min(T, abs(T - k * half_period)) if k else T


def phase_space_second_variations(T, omega, inertia, k):
    """d²S/dε² of the phase-space action S = ∫ (p q̇ − H) dt, notes §5, H = p²/(2I) + I ω² q²/2,
    under δq = ε sin(ω_k t), δp = ε I ω_k cos(ω_k t), ω_k = kπ/T [J·s per rad²]:

    δq alone: −I ω² T/2;   δp alone: −I ω_k² T/2;   both (δp = I δq̇): I T (ω_k² − ω²)/2.

    S is quadratic in (q, p), so these are exact; the last is the Lagrangian action's second
    variation ∫ (I δθ̇² − I ω² δθ²) dt, negative for k < ωT/π (beyond a conjugate point).
    """
    wk2 = (k * math.pi / T) ** 2
    half = 0.5 * inertia * T
    return -half * omega**2, -half * wk2, half * (wk2 - omega**2)
