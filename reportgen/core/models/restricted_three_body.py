r"""The planar circular restricted three-body problem in the rotating frame.

Two primaries of masses 1 − μ and μ (0 < μ ≤ 1/2) move on circles about their centre of
mass; in the frame rotating with them (units G = m1 + m2 = 1, separation a = 1, mean
motion n = 1) they rest at (−μ, 0) and (1 − μ, 0).  A test particle obeys

    ẍ − 2ẏ = ∂Ω/∂x,   ÿ + 2ẋ = ∂Ω/∂y,   Ω = (x² + y²)/2 + (1 − μ)/r1 + μ/r2,

r1, r2 its distances to the primaries, and conserves the Jacobi constant

    C = 2Ω − (ẋ² + ẏ²)                                 (Murray & Dermott §3.3).

The motion is confined to 2Ω ≥ C, bounded by the zero-velocity curves 2Ω = C (§3.10);
the five Lagrange points are the critical points of Ω (§3.5–3.6, Szebehely ch. 4).

Regularization (Thiele–Burrau, as Birkhoff's for both primaries at once; Szebehely
ch. 3).  With the origin moved to the midpoint of the primaries, z − d = a cosh u,
u = p + i q, a = 1/2, d = 1/2 − μ: the primaries are the branch points u = iπ (mass 1 − μ)
and u = 0 (mass μ), and

    r1 = 2a (sinh²(p/2) + cos²(q/2)),   r2 = 2a (sinh²(p/2) + sin²(q/2)),
    |dz/du|² = a² (sinh² p + sin² q) = r1 r2.

The rotating-frame Hamiltonian H = |π|²/2 − Im(z̄ π) − (1 − μ)/r1 − μ/r2 (π = ż + i z the
canonical momentum, complex; H = −C/2) becomes, with the canonical momenta
P = conj(dz/du) π and the fictitious time s, dt/ds = r1 r2, on the level K = 0,

    K = |P|²/2 − Im(z̄ (dz/du) P) − (1 − μ) r2 − μ r1 − E r1 r2,    E = −C/2,      (R)

an entire function of (p, q, P): both collisions are regular points of the motion in s.

State of the regularized model (p, q, P_p, P_q, t); params (μ, E).  The Cartesian model
(x, y, ẋ, ẏ) serves runs far from the primaries and the error-against-run-time study.

References
----------
.. [1] Murray, C. D. & Dermott, S. F., *Solar System Dynamics*, Cambridge (1999), ch. 3
       (§3.3 the Jacobi integral, §3.4 the Tisserand relation, §3.5–3.6 the Lagrange
       points, §3.10 zero-velocity curves) and §9.4 (chaos in the circular restricted
       problem: surfaces of section y = 0, ẏ > 0 in (x, ẋ)).
.. [2] Szebehely, V., *Theory of Orbits*, Academic Press (1967): ch. 3 (regularization,
       the Thiele–Burrau and Birkhoff transformations), ch. 4 (the Lagrange points and
       their quintic equations), ch. 10 (the Jacobi constant and the curves of zero
       velocity).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..model import OdeModel
from . import two_center, two_center_regularized

COLUMNS = ("x", "y", "vx", "vy")
REGULARIZED_COLUMNS = ("p", "q", "P_p", "P_q", "t")
#: index of the physical time in the regularized state
T_INDEX = 4
#: half the separation of the primaries (the Thiele–Burrau map's a)
HALF = 0.5

#: the section y = 0 crossed with ẏ > 0: in Cartesian variables the factor y (the two-centre
#: problem's line through its centres, the same function of the state) ...
AXIS_SECTION = two_center.AXIS_SECTION
#: ... and in the Thiele–Burrau variables y = a sinh p sin q, the factors p and sin q (the
#: same map as the two fixed centres'; dt/ds = r1 r2 > 0 keeps the direction)
REGULARIZED_AXIS_SECTION = two_center_regularized.AXIS_SECTION


# ------------------------------------------------------------------ Cartesian model
@numba.njit(cache=True, error_model="numpy")
def rhs(t, y, params, out):
    """d/dt of (x, y, ẋ, ẏ): ẍ = 2ẏ + Ω_x, ÿ = −2ẋ + Ω_y."""
    mu = params[0]
    x, yy, vx, vy = y[0], y[1], y[2], y[3]
    d1x, d2x = x + mu, x - 1.0 + mu
    r1s = d1x * d1x + yy * yy
    r2s = d2x * d2x + yy * yy
    c1 = (1.0 - mu) / (r1s * math.sqrt(r1s))
    c2 = mu / (r2s * math.sqrt(r2s))
    out[0] = vx
    out[1] = vy
    out[2] = 2.0 * vy + x - c1 * d1x - c2 * d2x
    out[3] = -2.0 * vx + yy - (c1 + c2) * yy


def model(mu: float) -> OdeModel:
    """The Cartesian equations of the rotating frame for mass ratio ``mu``."""
    return OdeModel(name="restricted three-body problem (rotating frame)", columns=COLUMNS,
                    rhs=rhs, params=np.array([float(mu)]), specialize=True)


# ------------------------------------------------------------- regularized model
@numba.njit(cache=True, error_model="numpy")
def regularized_rhs(s, y, params, out):
    """d/ds of (p, q, P_p, P_q, t) from (R) (see the module docstring)."""
    mu, E = params[0], params[1]
    a = HALF
    d = 0.5 - mu
    sh, ch = math.sinh(y[0]), math.cosh(y[0])
    sq, cq = math.sin(y[1]), math.cos(y[1])
    Pp, Pq = y[2], y[3]
    X = a * ch * cq + d       # barycentric position
    Y = a * sh * sq
    A = a * sh * cq           # dz/du = A + iB
    B = a * ch * sq
    Ap = a * ch * cq          # ∂A/∂p = ∂B/∂q
    Bp = a * sh * sq          # ∂B/∂p = −∂A/∂q
    g = A * A + B * B         # r1 r2
    out[0] = Pp - (X * B - Y * A)
    out[1] = Pq - (X * A + Y * B)
    out[2] = ((X * Bp - Y * Ap) * Pp + (g + X * Ap + Y * Bp) * Pq
              + a * sh + 2.0 * E * a * a * sh * ch)
    out[3] = ((X * Ap + Y * Bp - g) * Pp + (Y * Ap - X * Bp) * Pq
              + (1.0 - 2.0 * mu) * a * sq + 2.0 * E * a * a * sq * cq)
    out[4] = a * a * (sh * sh + sq * sq)


def regularized_model(mu: float, jacobi: float) -> OdeModel:
    """(R) for mass ratio ``mu`` on the level of the Jacobi constant ``jacobi``;
    independent variable s."""
    return OdeModel(name="restricted three-body problem (Thiele–Burrau regularized)",
                    columns=REGULARIZED_COLUMNS, rhs=regularized_rhs,
                    params=np.array([float(mu), -0.5 * float(jacobi)]))


def to_regularized(x, y, vx, vy, mu, t=0.0) -> np.ndarray:
    """(x, y, ẋ, ẏ) -> (p, q, P_p, P_q, t): u = arccosh((z − d)/a), P = conj(dz/du) π with
    π = ż + i z.  Raises ValueError at a primary, where u is a branch point."""
    z = complex(x, y)
    if z in (complex(-mu, 0.0), complex(1.0 - mu, 0.0)):
        raise ValueError(f"(x, y) = ({x:g}, {y:g}) is a primary: no regularized state")
    u = np.arccosh((z - (0.5 - mu)) / HALF)
    P = np.conj(HALF * np.sinh(u)) * (complex(vx, vy) + 1j * z)
    return np.array([u.real, u.imag, P.real, P.imag, t])


def from_regularized(state: np.ndarray, mu: float) -> np.ndarray:
    """(N, 5) regularized states -> (N, 4) x, y, ẋ, ẏ."""
    state = np.atleast_2d(state)
    u = state[:, 0] + 1j * state[:, 1]
    P = state[:, 2] + 1j * state[:, 3]
    z = HALF * np.cosh(u) + (0.5 - mu)
    with np.errstate(divide="ignore", invalid="ignore"):
        z_dot = P / np.conj(HALF * np.sinh(u)) - 1j * z
    return np.column_stack([z.real, z.imag, z_dot.real, z_dot.imag])


def regularized_hamiltonian(state: np.ndarray, mu: float, jacobi: float) -> np.ndarray:
    """K of (R) along (N, 5) states: zero on the motion (its drift is the run's error)."""
    state = np.atleast_2d(state)
    a, d, E = HALF, 0.5 - mu, -0.5 * jacobi
    sh, ch = np.sinh(state[:, 0]), np.cosh(state[:, 0])
    sq, cq = np.sin(state[:, 1]), np.cos(state[:, 1])
    Pp, Pq = state[:, 2], state[:, 3]
    X, Y = a * ch * cq + d, a * sh * sq
    A, B = a * sh * cq, a * ch * sq
    r1 = 2 * a * (np.sinh(state[:, 0] / 2) ** 2 + np.cos(state[:, 1] / 2) ** 2)
    r2 = 2 * a * (np.sinh(state[:, 0] / 2) ** 2 + np.sin(state[:, 1] / 2) ** 2)
    G = (X * B - Y * A) * Pp + (X * A + Y * B) * Pq
    return 0.5 * (Pp ** 2 + Pq ** 2) - G - (1 - mu) * r2 - mu * r1 - E * (A * A + B * B)


# ------------------------------------------------------------------- the integral
def distances(x, y, mu):
    """(r1, r2): distances to the primaries at (−μ, 0) (mass 1 − μ) and (1 − μ, 0) (mass μ)."""
    x = np.asarray(x, dtype=np.float64)
    return np.hypot(x + mu, y), np.hypot(x - 1.0 + mu, y)


def effective_potential(x, y, mu):
    """Ω = (x² + y²)/2 + (1 − μ)/r1 + μ/r2."""
    r1, r2 = distances(x, y, mu)
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    return 0.5 * (x * x + y * y) + (1.0 - mu) / r1 + mu / r2


def jacobi_constant(x, y, vx, vy, mu):
    """C = 2Ω − (ẋ² + ẏ²) (Murray & Dermott §3.3)."""
    vx, vy = np.asarray(vx, dtype=np.float64), np.asarray(vy, dtype=np.float64)
    return 2.0 * effective_potential(x, y, mu) - (vx * vx + vy * vy)


def section_vy2(x, vx, jacobi, mu):
    """ẏ² on the section y = 0 at (x, ẋ) on the level C = ``jacobi``: 2Ω(x, 0) − C − ẋ²,
    negative where the level does not reach (its zero is the section's edge)."""
    return 2.0 * effective_potential(x, 0.0, mu) - jacobi - np.asarray(vx) ** 2


def omega_x_on_axis(x, mu):
    """∂Ω/∂x on the line y = 0: x − (1 − μ)(x + μ)/|x + μ|³ − μ(x − 1 + μ)/|x − 1 + μ|³."""
    x = np.asarray(x, dtype=np.float64)
    d1, d2 = x + mu, x - 1.0 + mu
    return x - (1.0 - mu) * d1 / np.abs(d1) ** 3 - mu * d2 / np.abs(d2) ** 3


def lagrange_points(mu: float) -> dict[str, tuple[float, float, float]]:
    """The five Lagrange points as name -> (x, y, C there).

    L1 (between the primaries), L2 (beyond the smaller one), L3 (beyond the larger one)
    are the zeros of ∂Ω/∂x on y = 0 in their three intervals, found by bisection
    (Brent's method); L4, L5 form equilateral triangles with the primaries, where
    C = 3 − μ(1 − μ) (Murray & Dermott §3.5–3.6).
    """
    from scipy.optimize import brentq

    m1, m2 = -mu, 1.0 - mu
    eps = 1e-12

    def root(lo, hi):
        return brentq(omega_x_on_axis, lo, hi, args=(mu,), xtol=1e-15, rtol=1e-15,
                      maxiter=200)

    xs = {"L1": root(m1 + eps, m2 - eps), "L2": root(m2 + eps, m2 + 2.0),
          "L3": root(m1 - 2.0, m1 - eps)}
    out = {k: (float(x), 0.0, float(2.0 * effective_potential(x, 0.0, mu)))
           for k, x in xs.items()}
    h = math.sqrt(3.0) / 2.0
    for name, y in (("L4", h), ("L5", -h)):
        out[name] = (0.5 - mu, y, float(2.0 * effective_potential(0.5 - mu, y, mu)))
    return out


def zero_velocity_grid(mu: float, jacobi: float, extent: tuple[float, float, float, float],
                       n: int = 401) -> dict[str, np.ndarray]:
    """2Ω − C on an n×n grid of the plane (x0, x1, y0, y1): negative in the forbidden
    region, zero on the zero-velocity curves (Murray & Dermott §3.10).  Capped at a few
    times C next to the primaries, where Ω grows without bound (the contour is unchanged)."""
    x0, x1, y0, y1 = extent
    gx, gy = np.linspace(x0, x1, n), np.linspace(y0, y1, n)
    X, Y = np.meshgrid(gx, gy)
    with np.errstate(divide="ignore"):
        level = 2.0 * effective_potential(X, Y, mu) - jacobi
    return {"x": gx, "y": gy, "level": np.minimum(level, 4.0 * abs(jacobi))}


def outer_zero_velocity_radius(mu: float, jacobi: float) -> float:
    """The largest |x| where the zero-velocity curve 2Ω = C crosses the line y = 0
    (beyond L2 or L3; 2Ω grows as x² there), 0 if it crosses it nowhere outside them."""
    from scipy.optimize import brentq

    points = lagrange_points(mu)

    def level(x):
        return 2.0 * float(effective_potential(x, 0.0, mu)) - jacobi

    found = [0.0]
    for name, sign in (("L2", 1.0), ("L3", -1.0)):
        start = points[name][0]
        if level(start) >= 0.0:
            continue
        far = start + sign * max(2.0, math.sqrt(abs(jacobi)) + 2.0)
        found.append(abs(brentq(level, start, far, xtol=1e-12)))
    return max(found)


def section_speed(x, jacobi, mu) -> float:
    """ẏ ≥ 0 at (x, 0) with ẋ = 0 on the level C: √(2Ω(x, 0) − C); NaN where 2Ω < C."""
    vy2 = float(section_vy2(x, 0.0, jacobi, mu))
    return math.sqrt(vy2) if vy2 >= 0.0 else math.nan
