r"""Euler's problem of two fixed centres, regularized at both centres at once.

The Thiele–Burrau (Birkhoff) transformation z = x + i y = a cosh u, u = p + i q, maps
the plane onto elliptic coordinates, ξ = cosh p = (r1 + r2)/2a, η = cos q =
(r1 − r2)/2a (the ξ, η of :mod:`.two_center`), with

    r1 = a (cosh p + cos q),   r2 = a (cosh p − cos q),
    |dz/du|² = a² (sinh² p + sin² q) = r1 r2.

The centres are the branch points u = iπ (C1) and u = 0 (C2), where dz/du = 0.  With
the fictitious time s, dt/ds = r1 r2, the Hamiltonian K = r1 r2 (H − E) on the level
K = 0 (E the particle's energy) is

    K = ½ (P_p² + P_q²) − 2 a μ cosh p − a² E (sinh² p + sin² q)               (R)

an entire function: both collisions are regular points of the motion in s.  K is the sum
of a function of (p, P_p) and one of (q, P_q), so its equations are two uncoupled
one-dimensional oscillators and the quadrature for t:

    p' = P_p,   P_p' = 2 a μ sinh p + a² E sinh 2p,
    q' = P_q,   P_q' = a² E sin 2q,                  t' = a² (sinh² p + sin² q),

and each part is conserved separately; the p part is the separation constant of (7.59):

    β = P_p² − 4 a μ cosh p − 2 a² E cosh² p = −P_q² − 2 a² E cos² q,

since P_p² = (ξ² − 1) p_ξ² and P_q² = (1 − η²) p_η².  Velocities: ż = P / conj(a sinh u)
with P = P_p + i P_q = du/ds.

State (p, q, P_p, P_q, t); params = (μ, a, E), E fixed by the initial condition.

References
----------
.. [1] Szebehely, V., *Theory of Orbits*, Academic Press (1967), ch. 3 (regularization:
       the Thiele–Burrau and Birkhoff transformations of the two-centre problem).
.. [2] Whittaker, E. T., *A Treatise on the Analytical Dynamics of Particles and Rigid
       Bodies*, 4th ed. (1937), §50 (the separated equations of Euler's problem).
.. [3] Lecture notes §7, eq. (7.59).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..model import OdeModel, SurfaceOfSection
from . import two_center

COLUMNS = ("p", "q", "P_p", "P_q", "t")
#: index of the physical time in the state
T_INDEX = 4


@numba.njit(cache=True)
def rhs(s, y, params, out):
    """d/ds of (p, q, P_p, P_q, t) from (R)."""
    mu, a, E = params[0], params[1], params[2]
    sp, sq = math.sinh(y[0]), math.sin(y[1])
    out[0] = y[2]
    out[1] = y[3]
    out[2] = 2.0 * a * mu * sp + a * a * E * math.sinh(2.0 * y[0])
    out[3] = a * a * E * math.sin(2.0 * y[1])
    out[4] = a * a * (sp * sp + sq * sq)  # r1 r2, without the cancellation of cosh² − cos²


@numba.njit(cache=True)
def jac(s, y, params, out):
    mu, a, E = params[0], params[1], params[2]
    for i in range(5):
        for j in range(5):
            out[i, j] = 0.0
    out[0, 2] = 1.0
    out[1, 3] = 1.0
    out[2, 0] = 2.0 * a * mu * math.cosh(y[0]) + 2.0 * a * a * E * math.cosh(2.0 * y[0])
    out[3, 1] = 2.0 * a * a * E * math.cos(2.0 * y[1])
    out[4, 0] = a * a * math.sinh(2.0 * y[0])
    out[4, 1] = a * a * math.sin(2.0 * y[1])


@numba.njit(cache=True)
def axis_factors(s, y, params, out):
    """The line through the centres, y = a sinh p sin q = 0, as two factors: p = 0 (the
    segment between the centres, ξ = 1) and sin q = 0 (the axis outside them, η = ±1).
    Their product has the sign of y; near a centre (u = 0 or iπ) an orbit crosses both
    within one step, where y itself would not change sign over it."""
    out[0] = y[0]
    out[1] = math.sin(y[1])


#: the line through the centres, y = 0, crossed with ẏ > 0 (dt/ds = r1 r2 > 0: the same
#: direction in s)
AXIS_SECTION = SurfaceOfSection(factors=axis_factors, count=2)


def model(mu: float, a: float, E: float) -> OdeModel:
    """(R) for centres μ at (±a, 0) and the particle's energy E; independent variable s."""
    return OdeModel(name="two fixed centres (Thiele–Burrau regularized)", columns=COLUMNS,
                    rhs=rhs, jac=jac, params=np.array([mu, a, E]))


def to_regularized(x, y, vx, vy, a, t=0.0) -> np.ndarray:
    """(x, y, ẋ, ẏ) -> (p, q, P_p, P_q, t): u = arccosh(z/a), P = conj(a sinh u) ż.

    Raises ValueError at a centre, where u is a branch point and P is undefined."""
    z = complex(x, y)
    if z in (complex(a, 0.0), complex(-a, 0.0)):
        raise ValueError(f"(x, y) = ({x:g}, {y:g}) is a centre: no regularized state")
    u = np.arccosh(z / a)
    P = np.conj(a * np.sinh(u)) * complex(vx, vy)
    return np.array([u.real, u.imag, P.real, P.imag, t])


def from_regularized(state: np.ndarray, a: float):
    """(N, 5) regularized states -> x, y, vx, vy, t, each (N,)."""
    state = np.atleast_2d(state)
    u = state[:, 0] + 1j * state[:, 1]
    P = state[:, 2] + 1j * state[:, 3]
    z = a * np.cosh(u)
    z_dot = P / np.conj(a * np.sinh(u))
    return z.real, z.imag, z_dot.real, z_dot.imag, state[:, T_INDEX]


def separation_beta(state: np.ndarray, mu: float, a: float, E: float) -> tuple:
    """(β from the p part, β from the q part) of (R) along (N, 5) states; both are β."""
    state = np.atleast_2d(state)
    ch, c = np.cosh(state[:, 0]), np.cos(state[:, 1])
    from_p = state[:, 2] ** 2 - 4.0 * a * mu * ch - 2.0 * a * a * E * ch * ch
    from_q = -state[:, 3] ** 2 - 2.0 * a * a * E * c * c
    return from_p, from_q


def initial_state(x, y, vx, vy, mu, a):
    """(the model (R) at the particle's energy, its initial state)."""
    E = float(two_center.energy(x, y, vx, vy, mu, a))
    return model(mu, a, E), to_regularized(x, y, vx, vy, a)
