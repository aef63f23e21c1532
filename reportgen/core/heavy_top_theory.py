r"""The heavy symmetric top in closed form (lecture notes §10.1, eqs. 10.21-10.50;
Goldstein 3rd ed. §5.7, eqs. 5.62-5.73).

The equations of motion (quaternion state, right-hand side, invariants) are in
:mod:`reportgen.core.models.heavy_top`; kinematics of a trajectory and measurements
on it in :mod:`reportgen.core.heavy_top_kinematics`.  This module holds the theory the
integration is checked against: the roots of f(u), the Fig. 4.3 case, nutation period
and precession per period (Carlson forms, and quadrature as an independent check),
u(t) in Jacobi sn², the effective potential, the steady precession rates and the
sleeping-top threshold; the initial state that puts each Fig. 4.3 case on a given band
θmin ≤ θ ≤ θmax; and u(t) through Weierstrass's ℘ (exercise 4.10), evaluated with
:mod:`reportgen.core.weierstrass` independently of the sn² form, with the nutation period
as the loop integral ∮du/√f(u) round the cut [u1, u2] (:func:`period_loops`).

``a = I3 ω3 / I1``, ``b = p_φ / I1`` (10.25), ``α = 2E'/I1`` with
``E' = E - I3 ω3²/2`` and ``β = 2 M g l / I1`` (10.30).  With ``u = cos θ``,
``u'^2 = f(u) = (1 - u²)(α - β u) - (b - a u)²``, and since f is a cubic with
leading coefficient +β, ``f(u) = β (u - u1)(u2 - u)(u3 - u)`` with
``u1 ≤ u2 ≤ 1 < u3``; u(t) = u1 + (u2 - u1) sn²(λ t | m), λ = ½ √(β(u3 - u1)),
m = k² = (u2 - u1)/(u3 - u1), nutation period T = 2K(m)/λ = 4K(m)/√(β(u3 - u1)) (the
Jacobi form of Goldstein's quadrature t = ∫du/√f(u), eq. 5.72, inverted with DLMF §22.15).
With u = (4/β)℘ + (u1 + u2 + u3)/3 the same equation becomes ℘'² = 4℘³ − g2℘ − g3
(exercise 4.10): u(t) = (4/β)℘(t + x0 + ω′) + (u1 + u2 + u3)/3.

Numerics: everything is evaluated in ``w = 1 - u = 2 sin²(θ/2)``, with
``A = α - β`` and ``B = b - a`` computed from the initial state without
cancellation, so that tops close to the vertical (tilts of 1e-6, ``w ~ 1e-12``)
keep full relative accuracy.  In w the cubic is

    g(w) = w (2 - w)(A + β w) - (B + a w)²
         = -β w³ + (2β - A - a²) w² + 2(A - a B) w - B²,

with roots ``w1 = 1 - u2 ≤ w2 = 1 - u1`` and ``w3 = 1 - u3 < 0``.

Units: moments of inertia [kg m²], M g l [J], angles [rad], rates [rad/s], times [s].

References
----------
.. [1] Lecture notes §10.1, eqs. (10.21)-(10.50).
.. [2] Goldstein, Poole, Safko, *Classical Mechanics*, 3rd ed., §5.7, eqs. 5.62-5.73,
       Fig. 5.9 (2nd ed. §4.4 ... Fig. 4.3 in the notes' numbering); the notes'
       exercise 4.10 (u(t) through Weierstrass's ℘).
.. [3] NIST DLMF 19.25.1-2 (complete elliptic integrals in Carlson form), 22.2, 22.15,
       §23.6 (℘ and its half-periods).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy

from . import weierstrass
from .special import ellipf_carlson, ellipk_carlson, ellippi_carlson, jacobi_sn_agm


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
#: |φ̇| on the upper circle below this fraction of |φ̇| on the lower one counts as
#: b/a = u2 (cusps)
CUSP_RTOL = 1e-10


def classify(r: Roots, c: TopConstants) -> str:
    """Fig. 4.3 case from where b/a falls relative to [u1, u2] (notes §10.1; Goldstein §5.7).

    "loops": u1 < b/a < u2 (φ̇ changes sign); "cusps": b/a = u2 (φ̇ = 0 at the top
    turning circle: |φ̇| there at most ``CUSP_RTOL`` times |φ̇| on the lower one); "waves":
    b/a outside [u1, u2].  Degenerate cases: "sleeping"
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
    # φ̇ = (b − a u)/(1 − u²) = a (w − x)/(w (2 − w)) on the circles: cusps when φ̇ on the upper
    # one vanishes against φ̇ on the lower (not b/a against the band's width: near the vertical
    # 1 − u² ≈ 2w magnifies a tiny w1 − x into a finite φ̇)
    upper = abs(r.w1 - x) * r.w2 * (2.0 - r.w2)
    lower = abs(r.w2 - x) * r.w1 * (2.0 - r.w1)
    if upper <= CUSP_RTOL * lower or (r.w1 == 0.0 and x == 0.0):
        return "cusps"
    return "loops" if r.w1 < x < r.w2 else "waves"


def nutation_rate(r: Roots, c: TopConstants) -> float:
    """λ = ½ √(β (u3 − u1)): u(t) = u1 + (u2 − u1) sn²(λ t | k²)."""
    return 0.5 * math.sqrt(c.beta * (r.w2 - r.w3))


def nutation_period(r: Roots, c: TopConstants) -> float:
    """T = 2K(k²)/λ = 4K(k²)/√(β (u3 − u1)): the period of t = ∫du/√f(u), notes (10.31)
    (Goldstein §5.7).

    k² = 0 (steady precession; sleeping top) gives the small-oscillation limit
    2π/√(β (u3 − u1)); NaN for an unstable sleeping top (u3 ≤ 1).
    """
    if r.w3 >= 0.0 or r.w2 - r.w3 <= 0.0:
        return math.nan
    return 2.0 * ellipk_carlson(r.mc) / nutation_rate(r, c)


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
        total += c.B / r.w2 * ellippi_carlson(d / r.w2, r.w1 / r.w2, r.mc)
    if c.B + 2.0 * c.a != 0.0:
        total += (c.B + 2.0 * c.a) / (2.0 - r.w2) * ellippi_carlson(
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
    value, _err = scipy.integrate.quad(integrand, 0.0, 0.5 * math.pi, epsabs=0.0, epsrel=1e-12,
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
    """cos θ(t) = u1 + (u2 − u1) sn²(λ t + τ0 | k²): the Jacobi form of the quadrature
    t = ∫du/√f(u), notes (10.31) (Goldstein §5.7; DLMF §22.15).

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
    tau0 = ellipf_carlson(s0, r.mc)  # F(φ | k²) with sin²φ = s0
    if -math.sin(c.theta0) * c.theta_dot0 < 0.0:
        tau0 = 2.0 * ellipk_carlson(r.mc) - tau0
    sn = jacobi_sn_agm(nutation_rate(r, c) * t + tau0, r.mc)
    w = r.w2 - d * sn**2
    return w, 1.0 - w


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


def theta_of_w(w):
    """θ = 2 arcsin √(w/2) from w = 1 − cos θ, accurate near the vertical.

    Parameters
    ----------
    w : float or array_like, shape (N,)
        1 − cos θ (clipped to [0, 2]).

    Returns
    -------
    float or ndarray, shape (N,)
        θ [rad], in [0, π].
    """
    if np.ndim(w) == 0:
        return 2.0 * math.asin(math.sqrt(min(1.0, max(0.0, 0.5 * float(w)))))
    return 2.0 * np.arcsin(np.sqrt(np.clip(0.5 * np.asarray(w, dtype=np.float64), 0.0, 1.0)))


def theta_closed_form(t, r: Roots, c: TopConstants) -> np.ndarray:
    """θ(t) of the Jacobi closed form u(t) = u1 + (u2 − u1) sn²(λt + τ0 | k²).

    Parameters
    ----------
    t : array_like, shape (N,)
        Times [s].

    Returns
    -------
    ndarray, shape (N,)
        θ [rad], from w = 1 − u without cancellation (:func:`u_closed_form`, :func:`theta_of_w`).
    """
    w, _u = u_closed_form(t, r, c)
    return theta_of_w(w)


def effective_potential_near_vertical(theta, I1, Mgl, c: TopConstants):
    """V'(θ) − M g l and E' − M g l evaluated in w = 1 − cos θ (10.28, 10.30).

    Near the vertical V' − Mgl is of order θ² and V' itself would cancel: with
    w = 2 sin²(θ/2), b − a cos θ = B + a w and sin²θ = w (2 − w),

        V'(θ) − Mgl = −Mgl w + ½ I1 (B + a w)² / (w (2 − w)),   E' − Mgl = ½ I1 A.

    Parameters
    ----------
    theta : array_like, shape (N,)
        Tilt angles, 0 < θ < π [rad].
    I1, Mgl : float
        [kg m²], [J].
    c : TopConstants

    Returns
    -------
    V : ndarray, shape (N,)
        V'(θ) − Mgl [J].
    energy : float
        E' − Mgl [J].
    """
    theta = np.asarray(theta, dtype=np.float64)
    w = 2.0 * np.sin(0.5 * theta) ** 2
    V = -Mgl * w + 0.5 * I1 * (c.B + c.a * w) ** 2 / (w * (2.0 - w))
    return V, 0.5 * I1 * c.A


def steady_precession_min_omega3(I1, I3, Mgl, theta):
    """Smallest spin with steady precession at tilt θ: I3² ω3² = 4 I1 M g l cos θ (10.46).

    Returns ω3 [rad/s], NaN for cos θ ≤ 0 (steady precession at any spin).
    """
    cos = math.cos(theta)
    return 2.0 * math.sqrt(I1 * Mgl * cos) / I3 if cos > 0 else math.nan


def steady_precession_curve(I1, I3, Mgl, theta, omega3):
    """Both steady precession rates (10.45) on a grid of spins.

    Parameters
    ----------
    theta : float
        Tilt θ0 [rad].
    omega3 : array_like, shape (N,)
        Spins ω3 [rad/s].

    Returns
    -------
    slow, fast : ndarray, shape (N,)
        φ̇ [rad/s] of :func:`steady_precession_rates` (NaN where (10.46) fails).
    """
    rates = np.array([steady_precession_rates(I1, I3, Mgl, theta, x) for x in omega3])
    return rates[:, 0], rates[:, 1]


def invariant_scales(I1, I3, Mgl, omega3, c: TopConstants) -> dict[str, float]:
    """Natural sizes of E, p_φ and p_ψ, against which their drift is measured.

    energy: max(|E'| + I3 ω3²/2, M g l) with E' = I1 α/2 (10.30); momenta:
    max(|I3 ω3|, |I1 b|, √(I1 M g l)) (10.25), so that neither a slow spin nor a
    vanishing p_φ makes the scale zero.  Units: [J], [kg m²/s].
    """
    spin = 0.5 * I3 * omega3**2
    energy = max(abs(0.5 * I1 * c.alpha) + spin, Mgl)
    momentum = max(abs(I3 * omega3), abs(I1 * c.b), math.sqrt(I1 * Mgl))
    return {"energy": energy, "p_phi": momentum, "p_psi": momentum}


def period_sensitivity(I1, I3, Mgl, theta, theta_dot, phi_dot, omega3, energy_error, period):
    """|ΔT/T| if E' were off by ``energy_error`` [J] (conditioning of the nutation period).

    The error is put into the initial θ̇ (θ̇² → θ̇² + 2 ΔE/I1) and T recomputed.  Near the
    sleeping top the roots close to u = 1 are set by differences of order θ² in E' and
    p_φ: there an energy error of 1e-12 shifts the period by percents.  NaN if T is not
    finite or the perturbed state has no admissible interval.
    """
    theta_dot = math.sqrt(theta_dot**2 + 2.0 * energy_error / I1)
    c = constants(I1, I3, Mgl, theta, theta_dot, phi_dot, omega3)
    try:
        perturbed = nutation_period(roots(c), c)
    except (ValueError, ArithmeticError):
        return math.nan
    return abs(perturbed / period - 1.0) if math.isfinite(period) else math.nan


# ------------------------------------------------------------ a nutation band
class ImpossibleBand(ValueError):
    """No top of the given parameters nutates over the band with the asked case and spin."""


#: |ω3| within this relative distance of the cusp spin counts as the cusp spin
CUSP_SPIN_RTOL = 1e-9
#: the band's turning angles must come back to this accuracy [rad]
BAND_ATOL = 1e-9


@dataclass(frozen=True)
class BandSpins:
    """Which spins put each Fig. 4.3 case on the band θmin ≤ θ ≤ θmax (a = I3ω3/I1).

    A top released on the upper circle (θ̇ = 0) with φ̇0 = p has u2 = cos θmin as a root;
    u1 = cos θmax is the other root iff (10.31) gives, with c1 = sin²θmax, c2 = sin²θmin,
    d = u2 − u1 and σ = u1 + u2,

        c2 σ p² − 2 a c2 p + (c1 β − a² d) = 0,   p = [a ± √(c1 (a² − βσ)/c2)]/σ.

    p = 0 (released at rest: cusps) needs a² = a_c² = β c1/d; for |a| > a_c the smaller
    root has p < 0 < φ̇(u1): loops; every other real root has φ̇ of one sign: waves.
    Real roots need a² ≥ βσ, so waves need |a| ≥ √(βσ) when σ > 0.
    """

    I1: float
    I3: float
    theta_min: float
    theta_max: float
    a_cusps: float  # the only |a| with cusps
    a_waves_min: float  # waves need |a| ≥ this (σ > 0), else any spin
    sigma: float  # u1 + u2 = cos θmin + cos θmax

    @property
    def omega3_cusps(self) -> float:
        return self.I1 * self.a_cusps / self.I3

    @property
    def omega3_waves_min(self) -> float:
        return self.I1 * self.a_waves_min / self.I3

    def possible(self) -> str:
        """Which spins give which case, for error messages."""
        wc = f"{self.omega3_cusps:.10g}"
        if self.sigma > 0.0:
            waves = f"|ω3| ≥ {self.omega3_waves_min:.10g} rad/s"
        elif self.sigma < 0.0:
            waves = "any ω3"
        else:
            waves = f"0 < |ω3| < {wc} rad/s"
        return (f"on the band [{self.theta_min:.10g}, {self.theta_max:.10g}] rad cusps need "
                f"|ω3| = {wc} rad/s, loops |ω3| > {wc} rad/s, waves {waves}")

    def default_omega3(self, case: str) -> float:
        """The spin used when the config gives none: the cusp spin for cusps, 1.5 times it
        for loops, and for waves halfway between the smallest wave spin and the cusp spin."""
        a = {"cusps": self.a_cusps, "loops": 1.5 * self.a_cusps,
             "waves": 0.5 * (self.a_waves_min + self.a_cusps)}[case]
        return self.I1 * a / self.I3


def band_spins(I1, I3, Mgl, theta_min, theta_max) -> BandSpins:
    """The spin ranges of :class:`BandSpins` for 0 < θmin < θmax < π."""
    beta = 2.0 * Mgl / I1
    c1 = math.sin(theta_max) ** 2
    d = 2.0 * math.sin(0.5 * (theta_max + theta_min)) * math.sin(0.5 * (theta_max - theta_min))
    sigma = 2.0 * math.cos(0.5 * (theta_max + theta_min)) * math.cos(0.5 * (theta_max - theta_min))
    return BandSpins(I1=I1, I3=I3, theta_min=theta_min, theta_max=theta_max,
                     a_cusps=math.sqrt(beta * c1 / d),
                     a_waves_min=math.sqrt(beta * sigma) if sigma > 0.0 else 0.0, sigma=sigma)


def band_release_rates(I1, I3, Mgl, theta_min, theta_max, omega3) -> list[float]:
    """Every φ̇0 of a release on the upper circle (θ0 = θmin, θ̇0 = 0) whose motion turns on
    θmax: the real roots of the quadratic of :class:`BandSpins` (0, 1 or 2 of them)."""
    beta = 2.0 * Mgl / I1
    a = abs(I3 * omega3 / I1)
    sign = -1.0 if omega3 < 0.0 else 1.0  # ω3 → −ω3 mirrors the motion: φ̇ → −φ̇
    c1, c2 = math.sin(theta_max) ** 2, math.sin(theta_min) ** 2
    d = 2.0 * math.sin(0.5 * (theta_max + theta_min)) * math.sin(0.5 * (theta_max - theta_min))
    sigma = 2.0 * math.cos(0.5 * (theta_max + theta_min)) * math.cos(0.5 * (theta_max - theta_min))
    disc = c1 * (a * a - beta * sigma) / c2
    if disc < 0.0:
        return []
    big = a + math.sqrt(disc)  # a ± √disc without cancellation: the other root from Vieta
    rates = []
    if big > 0.0:
        rates.append((c1 * beta - a * a * d) / (c2 * big))
    if sigma != 0.0:
        rates.append(big / sigma)
    return [sign * p for p in rates if math.isfinite(p)]


def band_start(I1, I3, Mgl, theta_min, theta_max, case, omega3=None):
    """Initial state (θ0, θ̇0, φ̇0, ω3) nutating over [θmin, θmax] with the Fig. 4.3 ``case``.

    The top is released on the upper turning circle, θ0 = θmin, θ̇0 = 0, with φ̇0 from
    :func:`band_release_rates` (cusps: φ̇0 = 0 exactly).  ``omega3`` None: the spin of
    :meth:`BandSpins.default_omega3`.  Where two releases give waves, the one with the
    smaller |φ̇0| (lower energy E′) is taken.  Raises :class:`ImpossibleBand` naming the
    possible spins when no release gives the case, or when the roots of f(u) do not come
    back to the band within ``BAND_ATOL``.
    """
    spins = band_spins(I1, I3, Mgl, theta_min, theta_max)
    if omega3 is None:
        omega3 = spins.default_omega3(case)
    if case == "cusps":
        if abs(abs(omega3) / spins.omega3_cusps - 1.0) > CUSP_SPIN_RTOL:
            raise ImpossibleBand(f"no cusps at ω3 = {omega3:.10g} rad/s: {spins.possible()}")
        omega3 = math.copysign(spins.omega3_cusps, omega3)
        candidates = [0.0]
    else:
        candidates = band_release_rates(I1, I3, Mgl, theta_min, theta_max, omega3)
    found = []
    for phi_dot in candidates:
        c = constants(I1, I3, Mgl, theta_min, 0.0, phi_dot, omega3)
        r = roots(c)
        if classify(r, c) == case:
            found.append((abs(phi_dot), phi_dot, r))
    if not found:
        raise ImpossibleBand(f"no {case} at ω3 = {omega3:.10g} rad/s: {spins.possible()}")
    _size, phi_dot, r = min(found, key=lambda x: x[0])
    miss = max(abs(theta_of_w(r.w1) - theta_min), abs(theta_of_w(r.w2) - theta_max))
    if not miss <= BAND_ATOL:
        raise ImpossibleBand(f"the turning angles of the solved top miss the band by "
                             f"{miss:.3g} rad (ill-conditioned so close to the poles)")
    return theta_min, 0.0, phi_dot, omega3


# --------------------------------------------------- u(t) through Weierstrass's ℘
@dataclass(frozen=True)
class WeierstrassForm:
    """u(t) = λ ℘(t + x0 + ω′; g2, g3) + μ with λ = 4/β, μ = (u1 + u2 + u3)/3 (exercise 4.10).

    Substituting u = λ℘ + μ in u̇² = f(u) = β(u − u1)(u − u2)(u − u3) gives
    ℘'² = 4(℘ − e1)(℘ − e2)(℘ − e3) = 4℘³ − g2℘ − g3 with e_j = β(u_j − μ)/4
    (e1 ↔ u3, e2 ↔ u2, e3 ↔ u1).  On z = ω′ + x (x real) ℘ is real and runs between
    ℘(ω′) = e3 (u = u1) and ℘(ω + ω′) = e2 (u = u2): the motion is the horizontal line
    through ω′ in the period rectangle, one nutation period per real period 2ω.
    """

    e1: float
    e2: float
    e3: float
    g2: float
    g3: float
    omega: float  # real half-period ω1
    omega_prime: float  # |ω3|, ω3 = iω′
    x0: float  # z(0) = x0 + iω′
    scale: float  # λ = 4/β
    shift: float  # μ = (u1 + u2 + u3)/3
    lattice: weierstrass.Lattice


def weierstrass_form(r: Roots, c: TopConstants) -> WeierstrassForm | None:
    """The ℘ form of u(t) for a nutating top (None without nutation: steady, sleeping).

    The roots e_j and their differences are formed from w = 1 − u without cancellation;
    the phase x0 solves λ(℘(ω′ + x0) − e3) = u0 − u1 by bisection on ℘ itself, on the
    rising half x0 ∈ [0, ω] when u̇0 > 0, else on the falling one (2ω − x0).
    """
    if r.sleeping or r.w2 - r.w1 <= STEADY_RTOL * max(r.w2, 1e-300) or r.w3 >= 0.0:
        return None
    beta = c.beta
    mean_w = (r.w1 + r.w2 + r.w3) / 3.0
    e1, e2, e3 = (0.25 * beta * (mean_w - r.w3), 0.25 * beta * (mean_w - r.w1),
                  0.25 * beta * (mean_w - r.w2))
    gaps = (0.25 * beta * (r.w2 - r.w3), 0.25 * beta * (r.w1 - r.w3),
            0.25 * beta * (r.w2 - r.w1))  # e1 − e3, e1 − e2, e2 − e3
    omega, omega_prime = weierstrass.half_periods_from_gaps(*gaps)
    lattice = weierstrass.Lattice.rectangular(omega, omega_prime)
    g2, g3 = weierstrass.invariants(e1, e2, e3)
    scale = 4.0 / beta
    x0 = _weierstrass_phase(lattice, (r.w2 - c.w0) / scale, gaps[2])
    if -math.sin(c.theta0) * c.theta_dot0 < 0.0:
        x0 = 2.0 * omega - x0
    return WeierstrassForm(e1=e1, e2=e2, e3=e3, g2=g2, g3=g3, omega=omega,
                           omega_prime=omega_prime, x0=x0, scale=scale,
                           shift=1.0 - mean_w, lattice=lattice)


def _weierstrass_phase(lattice: weierstrass.Lattice, target: float, top: float) -> float:
    """x in [0, ω] with ℘(ω′ + x) − e3 = target (0 ≤ target ≤ e2 − e3 = ``top``)."""
    omega, omega_prime = lattice.omega1.real, lattice.omega3.imag
    if target <= 0.0:
        return 0.0
    if target >= top:
        return omega

    def excess(x):
        z = np.array([complex(x, omega_prime)])
        return float(weierstrass.wp_minus_e3(z, lattice)[0].real) - target

    low, high = excess(0.0), excess(omega)
    if low * high > 0.0:
        # a start on a turning circle: the target lies within the series' rounding of an
        # end, where ℘ is stationary, and no sign change brackets it
        return 0.0 if abs(low) <= abs(high) else omega
    return float(_optimize().brentq(excess, 0.0, omega, xtol=1e-16 * omega, rtol=4 * np.finfo(float).eps,
                                    maxiter=200))


def w_weierstrass(t, form: WeierstrassForm, r: Roots) -> np.ndarray:
    """w = 1 − u(t) of the ℘ form on the times ``t``, shape (N,).

    u − u1 = λ(℘(z) − e3) with z = t + x0 + iω′; ℘ − e3 is one theta quotient squared
    (:func:`reportgen.core.weierstrass.wp_minus_e3`), so w = w2 − λ(℘ − e3) keeps the
    digits of the roots in w.
    """
    z = np.asarray(t, dtype=np.float64) + complex(form.x0, form.omega_prime)
    excess = weierstrass.wp_minus_e3(z, form.lattice)
    return r.w2 - form.scale * excess.real


def weierstrass_ode_residual(t, form: WeierstrassForm, r: Roots, c: TopConstants) -> float:
    """max |λ²℘′(z)² − f(u)| / max f(u) over the times ``t``, u = λ℘(z) + μ, z = t + x0 + iω′.

    The check of the scaling λ = 4/β: u̇² = λ²℘′² must equal f(u) = β(u − u1)(u2 − u)(u3 − u)
    (evaluated in w = 1 − u from the roots, without cancellation), ℘′ from its own theta
    quotient (:func:`reportgen.core.weierstrass.wp_prime`), not from differentiating u.
    """
    z = np.asarray(t, dtype=np.float64) + complex(form.x0, form.omega_prime)
    w = w_weierstrass(t, form, r)
    u_dot_sq = form.scale**2 * weierstrass.wp_prime(z, form.lattice).real ** 2
    f = c.beta * (w - r.w1) * (r.w2 - w) * (w - r.w3)
    return float(np.max(np.abs(u_dot_sq - f)) / np.max(np.abs(f)))


# ------------------------------------------- the period as a loop integral round the cut
@dataclass(frozen=True)
class PeriodLoops:
    """The nutation period as integrals round the cut [u1, u2] (textbook ex. 4.10).

    ``loop``: T = ∮ du/√f(u) counter-clockwise round an ellipse about the cut, by the
    trapezoidal rule; ``sine_squared``: T = 2∫_{u1}^{u2} du/√f(u) with u = u1 + (u2 − u1)
    sin²s; ``wp_loop``: ∮ d℘/√(4℘³ − g2℘ − g3) round [e3, e2] in ℘'s plane, which is 2ω,
    ℘'s real period.  With u = λ℘ + μ, λ = 4/β, du/√f(u) = d℘/√(4℘³ − g2℘ − g3) exactly, so
    all three are T = 2ω (see :class:`WeierstrassForm`).
    """

    loop: weierstrass.PeriodIntegral
    sine_squared: weierstrass.PeriodIntegral
    wp_loop: weierstrass.PeriodIntegral


def period_loops(r: Roots, c: TopConstants) -> PeriodLoops | None:
    """:class:`PeriodLoops` of a nutating top (None without nutation, as for ℘).

    The cubic enters through its differences only: u2 − u1 = w2 − w1, u3 − u2 = w1 − w3,
    and in ℘'s plane e2 − e3 = β(u2 − u1)/4, e1 − e2 = β(u3 − u2)/4.
    """
    if r.sleeping or r.w2 - r.w1 <= STEADY_RTOL * max(r.w2, 1e-300) or r.w3 >= 0.0:
        return None
    width, gap = r.w2 - r.w1, r.w1 - r.w3
    return PeriodLoops(
        loop=weierstrass.loop_period(c.beta, width, gap),
        sine_squared=weierstrass.sine_squared_period(c.beta, width, gap),
        wp_loop=weierstrass.loop_period(4.0, 0.25 * c.beta * width, 0.25 * c.beta * gap))
