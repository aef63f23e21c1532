r"""Three bodies with one pair Kustaanheimo–Stiefel regularized (Stiefel & Scheifele §§ 9, 20).

Bodies i, j form the regularized pair and k is the third.  In the centre-of-mass frame
the motion is that of the relative vector x = r_j − r_i (reduced mass μ1 = m_i m_j/m_ij)
and of the third body about the pair's centre of mass, ρ = r_k − (m_i r_i + m_j r_j)/m_ij
(reduced mass μ2 = m_k m_ij/M):

    ẍ = −G m_ij x/|x|³ + P,   P = G m_k (d_jk/r_jk³ − d_ik/r_ik³),
    ρ̈ = −G (M/m_ij) (m_i d_ik/r_ik³ + m_j d_jk/r_jk³),

with d_ik = r_k − r_i = ρ + (m_j/m_ij) x and d_jk = r_k − r_j = ρ − (m_i/m_ij) x.  The pair
is written in KS variables u ∈ R⁴, x = L(u) u, |x| = |u|², with the fictitious time s,
dt/ds = |x|, and its Kepler energy per unit reduced mass h = |ẋ|²/2 − G m_ij/|x| carried as
a state variable:

    u'' = (h/2) u + (|x|/2) L(u)ᵀ P,    h' = 2 u'·L(u)ᵀ P,
    ρ' = |x| V,   V' = |x| ρ̈,   t' = |x|.

The equations are regular at a collision of i and j; the pair's separation is a state
variable of its own (|u|²) instead of the difference of two positions of order one, so a
close encounter of the pair loses no digits to rounding.  Encounters of k with i or j are
not regularized (the adaptive step follows them).  The same time transformation slows
the outer motion while the pair is close, which is what the step control needs anyway.

State (16): u1..u4, u1'..u4', h, ρx, ρy, ρz, Vx, Vy, Vz, t; params = (G, m_i, m_j, m_k).

References
----------
.. [1] Kustaanheimo, P. & Stiefel, E., J. reine angew. Math. 218 (1965) 204–219.
.. [2] Stiefel, E. L. & Scheifele, G., *Linear and Regular Celestial Mechanics*,
       Springer (1971), §§ 9 and 20.
.. [3] Aarseth, S. J., *Gravitational N-Body Simulations*, Cambridge (2003), § 4.4.
"""

from __future__ import annotations

import numba
import numpy as np

from ..model import OdeModel
from . import nbody

COLUMNS = ("u1", "u2", "u3", "u4", "u1_s", "u2_s", "u3_s", "u4_s", "h",
           "rho_x", "rho_y", "rho_z", "V_x", "V_y", "V_z", "t")


def _ks_transpose(u, a):
    """L(u)ᵀ (a, 0) for a 3-vector a (the KS matrix of Stiefel & Scheifele § 9)."""
    return np.array([u[0] * a[0] + u[1] * a[1] + u[2] * a[2],
                     -u[1] * a[0] + u[0] * a[1] + u[3] * a[2],
                     -u[2] * a[0] - u[3] * a[1] + u[0] * a[2],
                     u[3] * a[0] - u[2] * a[1] + u[1] * a[2]])


# inlined into its callers: see "Helpers" in reportgen.core.model
@numba.njit(cache=True, inline="always")
def _derivatives(y, params, out):
    """d/ds of the state, dt/ds = |x|; returns |x|."""
    G, mi, mj, mk = params[0], params[1], params[2], params[3]
    mij = mi + mj
    u0, u1, u2, u3 = y[0], y[1], y[2], y[3]
    r = u0 * u0 + u1 * u1 + u2 * u2 + u3 * u3
    x0 = u0 * u0 - u1 * u1 - u2 * u2 + u3 * u3
    x1 = 2.0 * (u0 * u1 - u2 * u3)
    x2 = 2.0 * (u0 * u2 + u1 * u3)
    ci, cj = mj / mij, mi / mij
    dik0, dik1, dik2 = y[9] + ci * x0, y[10] + ci * x1, y[11] + ci * x2
    djk0, djk1, djk2 = y[9] - cj * x0, y[10] - cj * x1, y[11] - cj * x2
    rik2 = dik0 * dik0 + dik1 * dik1 + dik2 * dik2
    rjk2 = djk0 * djk0 + djk1 * djk1 + djk2 * djk2
    fik = G / (rik2 * np.sqrt(rik2))
    fjk = G / (rjk2 * np.sqrt(rjk2))
    p0 = mk * (fjk * djk0 - fik * dik0)
    p1 = mk * (fjk * djk1 - fik * dik1)
    p2 = mk * (fjk * djk2 - fik * dik2)
    ltp0 = u0 * p0 + u1 * p1 + u2 * p2  # L(u)ᵀ (P, 0), as in _ks_transpose
    ltp1 = -u1 * p0 + u0 * p1 + u3 * p2
    ltp2 = -u2 * p0 - u3 * p1 + u0 * p2
    ltp3 = u3 * p0 - u2 * p1 + u1 * p2
    half_h, half_r = 0.5 * y[8], 0.5 * r
    for a in range(4):
        out[a] = y[4 + a]
    out[4] = half_h * u0 + half_r * ltp0
    out[5] = half_h * u1 + half_r * ltp1
    out[6] = half_h * u2 + half_r * ltp2
    out[7] = half_h * u3 + half_r * ltp3
    out[8] = 2.0 * (y[4] * ltp0 + y[5] * ltp1 + y[6] * ltp2 + y[7] * ltp3)
    c = -(mi + mj + mk) / mij * r
    out[9] = r * y[12]
    out[10] = r * y[13]
    out[11] = r * y[14]
    out[12] = c * (mi * fik * dik0 + mj * fjk * djk0)
    out[13] = c * (mi * fik * dik1 + mj * fjk * djk1)
    out[14] = c * (mi * fik * dik2 + mj * fjk * djk2)
    out[15] = r
    return r


@numba.njit(cache=True)
def rhs(s, y, params, out):
    _derivatives(y, params, out)


@numba.njit(cache=True)
def rhs_physical(t, y, params, out):
    """The same system with t as the independent variable (d/dt = (1/|x|) d/ds)."""
    inv_r = 1.0 / _derivatives(y, params, out)
    for a in range(15):
        out[a] *= inv_r
    out[15] = 1.0


def model(G: float, masses, pair=(1, 2), fictitious_time=True) -> OdeModel:
    """The regularized system for Cartesian ``masses`` (m1, m2, m3) with ``pair`` (0-based
    body indices i, j) regularized; ``extra`` records the pair and the third body.

    ``fictitious_time``: the independent variable is s (dt/ds = |x|, regular at a collision
    of the pair); False: it is t itself, so that outputs fall at given physical times (the
    pair's separation is still a variable of its own, but the equations are singular at
    its collision and the step shrinks at close approaches as in Cartesian coordinates).
    """
    i, j, k = _order(pair)
    m = np.asarray(masses, dtype=np.float64)
    return OdeModel(name="three-body (KS pair)", columns=COLUMNS,
                    rhs=rhs if fictitious_time else rhs_physical,
                    params=np.array([G, m[i], m[j], m[k]]),
                    extra={"order": (i, j, k), "G": float(G), "masses": m})


def _order(pair):
    i, j = (int(b) for b in pair)
    if sorted((i, j)) not in ([0, 1], [0, 2], [1, 2]):
        raise ValueError(f"pair: expected two distinct bodies among 0, 1, 2, got {pair}")
    return i, j, 3 - i - j


def _ks_coordinates(x):
    """u with L(u) u = x (Stiefel & Scheifele § 9, the branch that avoids cancellation)."""
    r = float(np.linalg.norm(x))
    if x[0] >= 0:
        u0 = np.sqrt(0.5 * (r + x[0]))
        return np.array([u0, x[1] / (2 * u0), x[2] / (2 * u0), 0.0])
    u1 = np.sqrt(0.5 * (r - x[0]))
    return np.array([x[1] / (2 * u1), u1, 0.0, x[2] / (2 * u1)])


def to_regularized(y, G, masses, pair=(1, 2), t=0.0) -> np.ndarray:
    """Cartesian state (18,) of :mod:`.nbody` -> the 16 regularized variables at time ``t``.

    The centre-of-mass position and velocity are dropped: :func:`to_cartesian` returns the
    motion in the centre-of-mass frame.
    """
    i, j, k = _order(pair)
    m = np.asarray(masses, dtype=np.float64)
    pos, vel = (a[0] for a in nbody.split(np.asarray(y, dtype=np.float64)))
    mij = m[i] + m[j]
    x, xdot = pos[j] - pos[i], vel[j] - vel[i]
    rho = pos[k] - (m[i] * pos[i] + m[j] * pos[j]) / mij
    V = vel[k] - (m[i] * vel[i] + m[j] * vel[j]) / mij
    u = _ks_coordinates(x)
    u_s = _ks_transpose(u, 0.5 * xdot)
    h = 0.5 * float(xdot @ xdot) - G * mij / float(np.linalg.norm(x))
    return np.concatenate([u, u_s, [h], rho, V, [t]])


def relative(states):
    """(N, 16) regularized states -> x, ẋ, ρ, V (each (N, 3)) and t (N,)."""
    states = np.atleast_2d(states)
    u, w = states[:, 0:4].T, states[:, 4:8].T
    r = np.sum(u * u, axis=0)
    x = np.stack([u[0]**2 - u[1]**2 - u[2]**2 + u[3]**2, 2 * (u[0] * u[1] - u[2] * u[3]),
                  2 * (u[0] * u[2] + u[1] * u[3])], axis=1)
    xdot = (2.0 / r)[:, None] * np.stack([
        u[0] * w[0] - u[1] * w[1] - u[2] * w[2] + u[3] * w[3],
        u[1] * w[0] + u[0] * w[1] - u[3] * w[2] - u[2] * w[3],
        u[2] * w[0] + u[3] * w[1] + u[0] * w[2] + u[1] * w[3]], axis=1)
    return x, xdot, states[:, 9:12], states[:, 12:15], states[:, 15]


def to_cartesian(reg: OdeModel, states) -> tuple[np.ndarray, np.ndarray]:
    """(N, 16) regularized states -> (Cartesian states (N, 18) in the centre-of-mass frame,
    physical times (N,))."""
    i, j, k = reg.extra["order"]
    m = reg.extra["masses"]
    mij, M = m[i] + m[j], m.sum()
    x, xdot, rho, V, t = relative(states)
    pos, vel = np.empty((len(t), 3, 3)), np.empty((len(t), 3, 3))
    for out, rel, outer in ((pos, x, rho), (vel, xdot, V)):
        centre = -(m[k] / M) * outer  # the pair's centre of mass
        out[:, i] = centre - (m[j] / mij) * rel
        out[:, j] = centre + (m[i] / mij) * rel
        out[:, k] = centre + outer
    return np.concatenate([pos.reshape(-1, 9), vel.reshape(-1, 9)], axis=1), t


def energy(reg: OdeModel, states):
    """Total energy from the physical relative variables (x, ẋ, ρ, V), shape (N,).

    The same quantity as :func:`.nbody.energy` of :func:`to_cartesian`, without the
    rounding of the pair's separation as a difference of two positions.
    """
    i, j, k = reg.extra["order"]
    m, G = reg.extra["masses"], reg.extra["G"]
    mij, M = m[i] + m[j], m.sum()
    x, xdot, rho, V, _ = relative(states)
    r = np.linalg.norm(x, axis=1)
    r_ik = np.linalg.norm(rho + (m[j] / mij) * x, axis=1)
    r_jk = np.linalg.norm(rho - (m[i] / mij) * x, axis=1)
    kinetic = 0.5 * (m[i] * m[j] / mij * np.sum(xdot**2, 1) + m[k] * mij / M * np.sum(V**2, 1))
    return kinetic - G * (m[i] * m[j] / r + m[i] * m[k] / r_ik + m[j] * m[k] / r_jk)
