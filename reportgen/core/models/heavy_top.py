r"""The heavy symmetric top: compiled equations of motion and the closed-form analysis.

Equations of motion
-------------------
The attitude is a unit quaternion ``q`` (body -> space) and the body angular
velocity ``omega``; the state is ``y = (q_w, q_x, q_y, q_z, omega_1, omega_2,
omega_3)``.  Euler's equations with the gravity torque
``tau = l e3 x (-M g z) = M g l (g2, -g1, 0)`` (``g`` = the space vertical in
body axes) and ``q' = q (x) (0, omega) / 2`` have no coordinate singularity:
the sleeping top (θ = 0) is an ordinary point.  θ, φ, ψ (Goldstein's z-x-z
Euler angles) and the space-frame symmetry axis are derived afterwards.

Closed form (lecture notes §10.1, eqs. 10.21-10.50; Goldstein 3rd ed. §5.7,
eqs. 5.62-5.73)
----------------------------------------------------------------------------
``a = I3 ω3 / I1``, ``b = p_φ / I1`` (10.25), ``α = 2E'/I1`` with
``E' = E - I3 ω3²/2`` and ``β = 2 M g l / I1`` (10.30).  With ``u = cos θ``,
``u'^2 = f(u) = (1 - u²)(α - β u) - (b - a u)²``, and since f is a cubic with
leading coefficient +β, ``f(u) = β (u - u1)(u2 - u)(u3 - u)`` with
``u1 ≤ u2 ≤ 1 < u3``; u(t) = u1 + (u2 - u1) sn²(λ t | m), λ = ½ √(β(u3 - u1)),
m = k² = (u2 - u1)/(u3 - u1), nutation period T = 2K(m)/λ = 4K(m)/√(β(u3 - u1)).

Numerics: everything is evaluated in ``w = 1 - u = 2 sin²(θ/2)``, with
``A = α - β`` and ``B = b - a`` computed from the initial state without
cancellation, so that tops close to the vertical (tilts of 1e-6, ``w ~ 1e-12``)
keep full relative accuracy.  In w the cubic is

    g(w) = w (2 - w)(A + β w) - (B + a w)²
         = -β w³ + (2β - A - a²) w² + 2(A - a B) w - B²,

with roots ``w1 = 1 - u2 ≤ w2 = 1 - u1`` and ``w3 = 1 - u3 < 0``.

References
----------
.. [1] Lecture notes §10.1, eqs. (10.21)-(10.50).
.. [2] Goldstein, Poole, Safko, *Classical Mechanics*, 3rd ed., §5.7, eqs. 5.62-5.73,
       Fig. 5.9 (2nd ed. §4.4 ... Fig. 4.3 in the notes' numbering), exercise 4.10.
.. [3] NIST DLMF 19.25.1-2 (complete elliptic integrals in Carlson form), 22.2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np
from scipy import integrate as sp_integrate
from scipy import special

from ..model import OdeModel

COLUMNS = ("q_w", "q_x", "q_y", "q_z", "omega_1", "omega_2", "omega_3")

# params = (I1, I3, Mgl)


@numba.njit(cache=True)
def rhs(t, y, params, out):
    i1, i3, mgl = params[0], params[1], params[2]
    qw, qx, qy, qz = y[0], y[1], y[2], y[3]
    w1, w2, w3 = y[4], y[5], y[6]
    n2 = qw * qw + qx * qx + qy * qy + qz * qz
    # space vertical in body axes: third row of R(q) / |q|²
    g1 = 2.0 * (qx * qz - qw * qy) / n2
    g2 = 2.0 * (qy * qz + qw * qx) / n2
    out[0] = -0.5 * (qx * w1 + qy * w2 + qz * w3)
    out[1] = 0.5 * (qw * w1 + qy * w3 - qz * w2)
    out[2] = 0.5 * (qw * w2 + qz * w1 - qx * w3)
    out[3] = 0.5 * (qw * w3 + qx * w2 - qy * w1)
    # Euler's equations, I2 = I1, torque M g l (g2, -g1, 0)
    out[4] = ((i1 - i3) * w2 * w3 + mgl * g2) / i1
    out[5] = ((i3 - i1) * w3 * w1 - mgl * g1) / i1
    out[6] = 0.0


def model(I1: float, I3: float, Mgl: float) -> OdeModel:
    """Compiled heavy symmetric top, state ``(q_w, q_x, q_y, q_z, ω1, ω2, ω3)``."""
    return OdeModel(name="heavy_top", columns=COLUMNS, rhs=rhs,
                    params=np.array([I1, I3, Mgl], dtype=np.float64))


# ----------------------------------------------------------------- quaternions
def euler_to_quaternion(phi, theta, psi):
    """Unit quaternion (w, x, y, z) of the z-x-z rotation R = Rz(φ) Rx(θ) Rz(ψ)."""
    c, s = math.cos(0.5 * theta), math.sin(0.5 * theta)
    return np.array([c * math.cos(0.5 * (phi + psi)), s * math.cos(0.5 * (phi - psi)),
                     s * math.sin(0.5 * (phi - psi)), c * math.sin(0.5 * (phi + psi))])


def initial_state(theta, theta_dot, phi_dot, omega3):
    """State y0 at φ = ψ = 0: ω1 = θ̇, ω2 = φ̇ sin θ (Goldstein eq. 4.87 with ψ = 0)."""
    q = euler_to_quaternion(0.0, theta, 0.0)
    return np.concatenate([q, [theta_dot, phi_dot * math.sin(theta), omega3]])


def symmetry_axis(q):
    """Space components of the body symmetry axis e3 = R(q) ẑ; q shape (N, 4), any norm."""
    qw, qx, qy, qz = (q[:, i] for i in range(4))
    n2 = qw**2 + qx**2 + qy**2 + qz**2
    return np.column_stack([2 * (qx * qz + qw * qy) / n2, 2 * (qy * qz - qw * qx) / n2,
                            (qw**2 - qx**2 - qy**2 + qz**2) / n2])


def euler_angles(q):
    """θ, φ, ψ (z-x-z) from quaternions, shape (N, 4); NaN-free on the vertical.

    With q = (cos(θ/2) cos((φ+ψ)/2), sin(θ/2) cos((φ−ψ)/2), sin(θ/2) sin((φ−ψ)/2),
    cos(θ/2) sin((φ+ψ)/2)), φ+ψ and φ−ψ come from two atan2's; on the vertical
    (θ = 0) only φ+ψ is defined: there the rotation is booked as spin (φ = 0, ψ = φ+ψ),
    so an upright sleeping top does not precess.  φ and ψ are unwrapped in time.
    """
    qw, qx, qy, qz = (q[:, i] for i in range(4))
    theta = 2.0 * np.arctan2(np.hypot(qx, qy), np.hypot(qw, qz))
    plus = 2.0 * np.arctan2(qz, qw)
    on_axis = (qx == 0.0) & (qy == 0.0)
    minus = np.where(on_axis, -plus, 2.0 * np.arctan2(qy, qx))
    plus, minus = np.unwrap(plus), np.unwrap(minus)
    return theta, 0.5 * (plus + minus), 0.5 * (plus - minus)


def axis_kinematics(y, I1, I3, Mgl):
    """Symmetry axis e3, its velocity and acceleration in space, each shape (N, 3).

    ė3 = ω_s × e3 and ë3 = ω̇_s × e3 + ω_s × ė3 with ω_s = R ω, ω̇_s = R ω̇ (the
    body-frame derivative from the equations of motion).
    """
    q = y[:, :4] / np.linalg.norm(y[:, :4], axis=1)[:, None]
    R = rotation_matrices(q)
    e3 = R[:, :, 2]
    omega_s = np.einsum("nij,nj->ni", R, y[:, 4:7])
    params = np.array([I1, I3, Mgl])
    dy = np.empty_like(y)
    out = np.empty(7)
    for n in range(len(y)):
        rhs(0.0, y[n], params, out)
        dy[n] = out
    domega_s = np.einsum("nij,nj->ni", R, dy[:, 4:7])
    e3_dot = np.cross(omega_s, e3)
    e3_ddot = np.cross(domega_s, e3) + np.cross(omega_s, e3_dot)
    return e3, e3_dot, e3_ddot


def rotation_matrices(q):
    """R(q) for unit quaternions q, shape (N, 4) -> (N, 3, 3)."""
    w, x, y, z = (q[:, i] for i in range(4))
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=1),
    ], axis=1)


def invariants(y, I1, I3, Mgl):
    """Energy E, p_φ = L·ẑ and p_ψ = I3 ω3 along a trajectory y, shape (N, 7)."""
    q = y[:, :4] / np.linalg.norm(y[:, :4], axis=1)[:, None]
    w1, w2, w3 = y[:, 4], y[:, 5], y[:, 6]
    zb = rotation_matrices(q)[:, 2, :]  # space ẑ in body axes
    energy = 0.5 * I1 * (w1**2 + w2**2) + 0.5 * I3 * w3**2 + Mgl * zb[:, 2]
    p_phi = I1 * (w1 * zb[:, 0] + w2 * zb[:, 1]) + I3 * w3 * zb[:, 2]
    return {"energy": energy, "p_phi": p_phi, "p_psi": I3 * w3}


# ------------------------------------------------------------- closed form
class NoAdmissibleInterval(ValueError):
    """f(u) has no interval u1 ≤ u ≤ u2 ≤ 1 < u3 containing the initial state."""


@dataclass(frozen=True)
class TopConstants:
    """The constants of the motion in the lecture notes' notation (10.25, 10.30)."""

    a: float  # I3 ω3 / I1
    b: float  # p_φ / I1
    alpha: float  # 2 E' / I1
    beta: float  # 2 M g l / I1
    A: float  # α − β, without cancellation
    B: float  # b − a, without cancellation
    w0: float  # 1 − cos θ0 = 2 sin²(θ0/2)
    theta0: float
    theta_dot0: float


def constants(I1, I3, Mgl, theta, theta_dot, phi_dot, omega3) -> TopConstants:
    """a, b, α, β (10.25, 10.30) of the initial state, plus A = α − β and B = b − a.

    E' = ½ I1 (θ̇² + φ̇² sin²θ) + M g l cos θ (Goldstein 5.64 with E' = E − I3 ω3²/2);
    p_φ = I1 φ̇ sin²θ + I3 ω3 cos θ (Goldstein 5.62).
    """
    s2 = math.sin(theta) ** 2
    w0 = 2.0 * math.sin(0.5 * theta) ** 2
    a = I3 * omega3 / I1
    beta = 2.0 * Mgl / I1
    B = phi_dot * s2 - a * w0  # b − a
    A = theta_dot**2 + phi_dot**2 * s2 - beta * w0  # α − β
    return TopConstants(a=a, b=a + B, alpha=beta + A, beta=beta, A=A, B=B, w0=w0,
                        theta0=theta, theta_dot0=theta_dot)


def f_u(u, c: TopConstants):
    """f(u) = (1 − u²)(α − β u) − (b − a u)²  (10.31; Goldstein 5.71)."""
    u = np.asarray(u, dtype=np.float64)
    return (1 - u**2) * (c.alpha - c.beta * u) - (c.b - c.a * u) ** 2


def g_w(w, c: TopConstants):
    """f in w = 1 − u: g(w) = w (2 − w)(A + β w) − (B + a w)²."""
    return w * (2.0 - w) * (c.A + c.beta * w) - (c.B + c.a * w) ** 2


def _quadratic_roots(beta, q1, q0):
    """Roots (negative, non-negative) of −β w² + q1 w + q0 = 0 with q0 ≥ 0, no cancellation."""
    disc = math.sqrt(q1 * q1 + 4.0 * beta * q0)
    if q1 >= 0.0:
        pos = (q1 + disc) / (2.0 * beta)
        neg = -q0 / (beta * pos) if pos > 0 else 0.0
    else:
        neg = (q1 - disc) / (2.0 * beta)
        pos = -q0 / (beta * neg)
    return neg, pos


@dataclass(frozen=True)
class Roots:
    """Roots of f(u) in both variables; w = 1 − u."""

    w1: float
    w2: float
    w3: float
    sleeping: bool  # started exactly on the vertical at rest: an equilibrium

    @property
    def u1(self):
        return 1.0 - self.w2

    @property
    def u2(self):
        return 1.0 - self.w1

    @property
    def u3(self):
        return 1.0 - self.w3

    @property
    def m(self):
        """k² = (u2 − u1)/(u3 − u1)."""
        return (self.w2 - self.w1) / (self.w2 - self.w3)

    @property
    def mc(self):
        """1 − k² = (u3 − u2)/(u3 − u1), accurate when k² → 1."""
        return (self.w1 - self.w3) / (self.w2 - self.w3)


def roots(c: TopConstants) -> Roots:
    """Roots u1 ≤ u2 ≤ 1 < u3 of f(u) (10.31), as w = 1 − u, to full relative accuracy.

    g(w0) = θ̇0² sin²θ0 ≥ 0 at the initial state while g(0) = −B² ≤ 0 and
    g(2) = −(B + 2a)² ≤ 0, so w1 ∈ [0, w0] and w2 ∈ [w0, 2] are bracketed.  When
    θ̇0 = 0 (or θ0 = 0) w0 is itself a root and the other two follow from the deflated
    quadratic; w3 < 0 from Vieta's product w1 w2 w3 = −B²/β.
    """
    beta, a, A, B, w0 = c.beta, c.a, c.A, c.B, c.w0
    c2 = 2.0 * beta - A - a * a
    c1 = 2.0 * (A - a * B)
    g0 = c.theta_dot0**2 * math.sin(c.theta0) ** 2
    if w0 == 0.0 and c.theta_dot0 == 0.0:
        # the sleeping top: double root w = 0; third root w = c2/β, u3 = a²/β − 1
        return Roots(0.0, 0.0, c2 / beta, sleeping=True)
    if g0 == 0.0:
        q1 = c2 - beta * w0
        q0 = B * B / w0 if w0 > 0.0 else c1  # remainder-free deflation by (w − w0)
        neg, pos = _quadratic_roots(beta, q1, max(q0, 0.0))
        w1, w2 = min(w0, pos), max(w0, pos)
        w3 = neg
    else:
        def g(w):
            return g_w(w, c)

        w1 = 0.0 if B == 0.0 else _brentq(g, 0.0, w0)
        w2 = _brentq(g, w0, 2.0)
        if w1 > 0.0:
            w3 = -B * B / (beta * w1 * w2)
        else:  # B = 0: deflate w = 0, then w2 w3 = −c1/β
            w3 = -c1 / (beta * w2)
    return Roots(w1, w2, w3, sleeping=False)


def _brentq(g, lo, hi):
    if g(lo) == 0.0:
        return lo
    if g(hi) == 0.0:
        return hi
    return float(_optimize().brentq(g, lo, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps,
                                    maxiter=500))


def _optimize():
    from scipy import optimize

    return optimize


def check_admissible(r: Roots, c: TopConstants) -> None:
    """Raise NoAdmissibleInterval unless u1 ≤ u0 ≤ u2 ≤ 1 < u3 (or the sleeping equilibrium)."""
    if r.sleeping:
        return
    ok = (0.0 <= r.w1 <= r.w2 <= 2.0 and r.w3 < 0.0 and all(map(math.isfinite, (r.w1, r.w2, r.w3)))
          and r.w1 <= c.w0 * (1 + 1e-12) and c.w0 <= r.w2 * (1 + 1e-12))
    if not ok:
        raise NoAdmissibleInterval(
            f"f(u) has no admissible interval u1 ≤ cos θ0 ≤ u2 ≤ 1 < u3 "
            f"(roots u = {1 - r.w2:.6g}, {1 - r.w1:.6g}, {1 - r.w3:.6g}; cos θ0 = {1 - c.w0:.6g})")


#: relative width below which u2 − u1 counts as zero (no nutation).  With θ̇0 = 0 the
#: start w0 is an exact root and a rounded steady rate (10.45) splits the double root
#: by only ~1e-15 relative (measured over θ0 ∈ [0.3, 2.8], ω3 ∈ [3, 50])
STEADY_RTOL = 1e-10
#: |b/a − u2| below this fraction of (u2 − u1) counts as b/a = u2 (cusps)
CUSP_RTOL = 1e-10


def classify(r: Roots, c: TopConstants) -> str:
    """Fig. 4.3 case from where b/a falls relative to [u1, u2] (notes §10.1; Goldstein §5.7).

    "loops": u1 < b/a < u2 (φ̇ changes sign); "cusps": b/a = u2 (φ̇ = 0 at the top
    turning circle); "waves": b/a outside [u1, u2].  Degenerate cases: "sleeping"
    (on the vertical at rest) and "steady" (u1 = u2, steady precession).
    b/a = u1 cannot occur: there f'(u1) = −β(1 − u1²) < 0.
    """
    if r.sleeping:
        return "sleeping"
    width = r.w2 - r.w1
    if width <= STEADY_RTOL * max(r.w2, 1e-300):
        return "steady"
    if c.a == 0.0:
        return "waves"  # φ̇ = b/(1 − u²) keeps the sign of b
    x = -c.B / c.a  # 1 − b/a
    if abs(x - r.w1) <= CUSP_RTOL * width:
        return "cusps"
    return "loops" if r.w1 < x < r.w2 else "waves"


def carlson_pi(n, one_minus_n, mc):
    """Complete elliptic integral of the third kind Π(n | m), m = 1 − mc (DLMF 19.25.2).

    1 − n is passed separately: for an axis passing close to the vertical n → 1
    and 1 − n computed by subtraction would lose its digits.
    """
    return special.elliprf(0.0, mc, 1.0) + n / 3.0 * special.elliprj(0.0, mc, 1.0, one_minus_n)


def nutation_rate(r: Roots, c: TopConstants) -> float:
    """λ = ½ √(β (u3 − u1)): u(t) = u1 + (u2 − u1) sn²(λ t | k²)."""
    return 0.5 * math.sqrt(c.beta * (r.w2 - r.w3))


def nutation_period(r: Roots, c: TopConstants) -> float:
    """T = 2K(k²)/λ = 4K(k²)/√(β (u3 − u1)) (FIELD-NOTES; Goldstein 5.72-5.73).

    k² = 0 (steady precession; sleeping top) gives the small-oscillation limit
    2π/√(β (u3 − u1)); NaN for an unstable sleeping top (u3 ≤ 1).
    """
    if r.w3 >= 0.0 or r.w2 - r.w3 <= 0.0:
        return math.nan
    return 2.0 * special.elliprf(0.0, r.mc, 1.0) / nutation_rate(r, c)


def precession_per_period(r: Roots, c: TopConstants) -> float:
    """Δφ over one nutation period, from φ̇ = (b − a u)/(1 − u²) (10.26) in closed form.

    Partial fractions φ̇ = ½[(b − a)/(1 − u) + (b + a)/(1 + u)] and u(τ) = u1 +
    (u2 − u1) sn²τ turn ∫ φ̇ dt into complete integrals of the third kind:
    Δφ = (1/λ)[(b − a)/(1 − u1) Π(n₋|m) + (b + a)/(1 + u1) Π(n₊|m)],
    n₋ = (u2 − u1)/(1 − u1), n₊ = −(u2 − u1)/(1 + u1).  NaN for the sleeping top.
    """
    if r.sleeping or r.w3 >= 0.0:
        return math.nan
    lam = nutation_rate(r, c)
    d = r.w2 - r.w1
    total = 0.0
    if c.B != 0.0:
        total += c.B / r.w2 * carlson_pi(d / r.w2, r.w1 / r.w2, r.mc)
    if c.B + 2.0 * c.a != 0.0:
        total += (c.B + 2.0 * c.a) / (2.0 - r.w2) * carlson_pi(
            -d / (2.0 - r.w2), (2.0 - r.w1) / (2.0 - r.w2), r.mc)
    return total / lam


def _chi_integral(r: Roots, c: TopConstants, weight) -> float:
    """4 ∫_0^{π/2} weight(w) dχ / √(β (w − w3)),  w = w1 + (w2 − w1) cos²χ.

    The substitution u = u1 + (u2 − u1) sin²χ turns dt = du/√f(u) into the smooth
    2 dχ/√(β (u3 − u)), so quad reaches ~1e-13 (asked for 1e-12) without elliptic functions.
    """
    d = r.w2 - r.w1
    gap = r.w1 - r.w3  # u3 − u2, kept apart so w − w3 does not cancel near the top circle

    def integrand(chi):
        cos2 = math.cos(chi) ** 2
        return weight(r.w1 + d * cos2) / math.sqrt(c.beta * (gap + d * cos2))

    # near k² = 1 the integrand peaks in a layer of width ~√(1 − k²) at χ = π/2:
    # break the interval geometrically towards it so quad resolves the layer
    width = math.sqrt(max(r.mc, 1e-300))
    points = [0.5 * math.pi - width * 10.0**j for j in range(int(-math.log10(width)) + 1)]
    points = [p for p in points if 0.0 < p < 0.5 * math.pi]
    value, _err = sp_integrate.quad(integrand, 0.0, 0.5 * math.pi, epsabs=0.0, epsrel=1e-12,
                                    limit=1000, points=points or None)
    return 4.0 * value


def nutation_period_quadrature(r: Roots, c: TopConstants) -> float:
    """Independent T: ∮ du/√f(u) by adaptive quadrature (no elliptic functions)."""
    if r.sleeping or r.w3 >= 0.0:
        return math.nan
    return _chi_integral(r, c, lambda w: 1.0)


def precession_quadrature(r: Roots, c: TopConstants) -> float:
    """Independent Δφ: ∮ φ̇ du/√f(u), φ̇ = ½[B/w + (B + 2a)/(2 − w)] (10.26), by quadrature."""
    if r.sleeping or r.w3 >= 0.0:
        return math.nan
    return _chi_integral(r, c, lambda w: 0.5 * (c.B / w + (c.B + 2 * c.a) / (2.0 - w)))


def u_closed_form(t, r: Roots, c: TopConstants):
    """cos θ(t) = u1 + (u2 − u1) sn²(λ t + τ0 | k²) (FIELD-NOTES; Goldstein ex. 4.10).

    τ0 places the initial state: sn²τ0 = (u0 − u1)/(u2 − u1), on the rising branch
    (τ0 ∈ [0, K]) when u̇0 = −sin θ0 θ̇0 > 0, else on the falling one (2K − τ0).
    Returns w = 1 − u(t) (accurate near the vertical) and u(t).
    """
    t = np.asarray(t, dtype=np.float64)
    d = r.w2 - r.w1
    if d <= 0.0 or r.sleeping:
        w = np.full_like(t, c.w0)
        return w, 1.0 - w
    s0 = min(1.0, max(0.0, (r.w2 - c.w0) / d))
    # F(φ|m) = sin φ R_F(cos²φ, 1 − m sin²φ, 1) (DLMF 19.25.5), 1 − m sin²φ = cos²φ + mc sin²φ
    tau0 = math.sqrt(s0) * float(special.elliprf(1.0 - s0, (1.0 - s0) + r.mc * s0, 1.0))
    if -math.sin(c.theta0) * c.theta_dot0 < 0.0:
        tau0 = 2.0 * special.elliprf(0.0, r.mc, 1.0) - tau0
    sn = jacobi_sn(nutation_rate(r, c) * t + tau0, r.mc)
    w = r.w2 - d * sn**2
    return w, 1.0 - w


def jacobi_sn(x, mc):
    """sn(x | m), m = 1 − mc, by the arithmetic-geometric mean (DLMF 22.20(ii)).

    Takes the complementary parameter mc so that k² → 1 keeps full accuracy (scipy's
    ``ellipj`` switches to a first-order expansion for 1 − m < 1e-9, which loses all
    digits after a few periods of the slow nutation of a nearly sleeping top).
    """
    x = np.asarray(x, dtype=np.float64)
    a, b = 1.0, math.sqrt(mc)
    cs = [math.sqrt(max(0.0, 1.0 - mc))]
    As = [a]
    while abs(cs[-1]) > 1e-17 * a and len(cs) < 60:
        a, b, cn = 0.5 * (a + b), math.sqrt(a * b), 0.5 * (a - b)
        cs.append(cn)
        As.append(a)
    n = len(cs) - 1
    phi = (2.0**n) * As[-1] * x
    for j in range(n, 0, -1):
        phi = 0.5 * (phi + np.arcsin(np.clip(cs[j] / As[j] * np.sin(phi), -1.0, 1.0)))
    return np.sin(phi)


def effective_potential(theta, I1, Mgl, c: TopConstants):
    """V'(θ) = M g l cos θ + I1 (b − a cos θ)²/(2 sin²θ)  (10.28; Goldstein 5.65)."""
    theta = np.asarray(theta, dtype=np.float64)
    return Mgl * np.cos(theta) + 0.5 * I1 * (c.b - c.a * np.cos(theta)) ** 2 / np.sin(theta) ** 2


def reduced_energy(I1, Mgl, theta, theta_dot, phi_dot):
    """E' = E − I3 ω3²/2 = ½ I1 (θ̇² + φ̇² sin²θ) + M g l cos θ (Goldstein 5.64)."""
    return 0.5 * I1 * (theta_dot**2 + phi_dot**2 * math.sin(theta) ** 2) + Mgl * math.cos(theta)


def steady_precession_rates(I1, I3, Mgl, theta, omega3):
    """The two steady precession rates (10.45): I1 cos θ φ̇² − I3 ω3 φ̇ + M g l = 0.

    φ̇ = [I3 ω3 ± √(I3² ω3² − 4 I1 M g l cos θ)]/(2 I1 cos θ); real iff (10.46)
    I3² ω3² ≥ 4 I1 M g l cos θ.  Returned as (slow, fast); the slow root in the
    cancellation-free form 2 M g l/(I3 ω3 ± √D).  (NaN, NaN) if (10.46) fails;
    fast = NaN at cos θ = 0 (one root only).
    """
    p = I3 * omega3
    cos = math.cos(theta)
    disc = p * p - 4.0 * I1 * Mgl * cos
    if disc < 0.0:
        return math.nan, math.nan
    sq = math.copysign(math.sqrt(disc), p) if p != 0.0 else math.sqrt(disc)
    big = p + sq
    slow = 2.0 * Mgl / big if big != 0.0 else math.nan
    fast = big / (2.0 * I1 * cos) if cos != 0.0 else math.nan
    return slow, fast


def sleeping_threshold_omega3(I1, I3, Mgl):
    """ω3 above which the sleeping top is stable: ω3² = 4 I1 M g l / I3² (10.49-10.50)."""
    return 2.0 * math.sqrt(I1 * Mgl) / I3


def sleeping_growth_rate(I1, I3, Mgl, omega3):
    """Linear growth rate of a small tilt of the sleeping top, ½ √(2β − a²), 0 if stable.

    The tilt ξ = x + i y obeys ξ̈ − i a ξ̇ − (β/2) ξ = 0 (10.47-10.48), exponents
    i[a ± √(a² − 2β)]/2.
    """
    a, beta = I3 * omega3 / I1, 2.0 * Mgl / I1
    return 0.5 * math.sqrt(max(0.0, 2.0 * beta - a * a))
