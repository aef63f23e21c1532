r"""The plane pendulum  m l^2 \ddot\theta + m g l \sin\theta = 0.

State ``y = (theta, theta_dot)``; with the mass-normalised momentum
``p = theta_dot`` the Hamiltonian per unit ``m l^2`` is separable,
``H = p^2/2 - omega0^2 cos(theta)``, ``omega0^2 = g / l``.

References
----------
.. [1] Lecture notes §1, eqs. (1.17)-(1.21); §2, eq. (2.4).
.. [2] Lawden, D. F., *Elliptic Functions and Applications*, Springer (1989), §5.2.
.. [3] NIST DLMF §22.19(i), "Classical Dynamics: The Pendulum".
"""

from __future__ import annotations

import math

import numba
import numpy as np
from scipy import special

from ..model import OdeModel, Separable

# params = (omega0^2,)


@numba.njit(cache=True)
def rhs(t, y, params, out):
    out[0] = y[1]
    out[1] = -params[0] * math.sin(y[0])


@numba.njit(cache=True)
def jac(t, y, params, out):
    out[0, 0] = 0.0
    out[0, 1] = 1.0
    out[1, 0] = -params[0] * math.cos(y[0])
    out[1, 1] = 0.0


@numba.njit(cache=True)
def drift(p, params, out):
    out[0] = p[0]


@numba.njit(cache=True)
def kick(q, params, out):
    out[0] = -params[0] * math.sin(q[0])


def model(g: float, l: float) -> OdeModel:
    """Compiled pendulum with ``omega0^2 = g / l``."""
    return OdeModel(
        name="pendulum",
        columns=("theta", "theta_dot"),
        rhs=rhs,
        params=np.array([g / l]),
        separable=Separable(n=1, drift=drift, kick=kick),
        jac=jac,
    )


def energy(theta, theta_dot, g, l, m=1.0):
    """Total energy  E = m l^2 theta_dot^2 / 2 - m g l cos(theta)  [J]."""
    return 0.5 * m * l**2 * np.asarray(theta_dot) ** 2 - m * g * l * np.cos(theta)


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


#: below this |1 - k^2| scipy's double-precision ellipj no longer resolves the motion
#: (measured against 40-digit mpmath: 4e-9 error at 1 - k^2 = 2.5e-7 over 12 periods)
EXACT_SOLUTION_MIN_M1 = 1e-8


def exact_period(theta0, theta_dot0, g, l):
    """Exact period [s]: 4 K(k^2) sqrt(l/g) for libration, 2 K(1/k^2) / (k omega0) per revolution.

    Uses K(1 - m1) with the complementary parameter m1 = 1 - k^2 (scipy ``ellipkm1``),
    accurate arbitrarily close to the separatrix; infinite on it.
    (DLMF 22.19.4 and 22.19.7.)
    """
    omega0 = math.sqrt(g / l)
    m1 = complementary_parameter(theta0, theta_dot0, omega0)
    if m1 > 0.0:
        return 4.0 * special.ellipkm1(m1) / omega0
    if m1 < 0.0:
        m = 1.0 - m1
        # K(1/m) = K(1 - p) with p = 1 - 1/m = -m1/m
        return 2.0 * special.ellipkm1(-m1 / m) / (math.sqrt(m) * omega0)
    return math.inf


def _incomplete_F(phi, m):
    """F(phi | m) for any real phi, continued quasi-periodically: F(phi + n pi) = F(phi) + 2 n K."""
    n = np.round(np.asarray(phi) / math.pi)
    return special.ellipkinc(phi - n * math.pi, m) + 2.0 * n * special.ellipk(m)


def exact_solution(t, theta0, theta_dot0, g, l):
    """Exact (theta, theta_dot) at times ``t`` in Jacobi elliptic functions.

    Libration (k < 1): sin(theta/2) = k sn(u | k^2), theta_dot = 2 k omega0 cn(u | k^2),
    u = u0 + omega0 t.  Rotation (k > 1): theta/2 = s am(u | 1/k^2),
    theta_dot = 2 s k omega0 dn(u | 1/k^2), u = u0 + k omega0 t, s = sign(theta_dot0).

    Parameters
    ----------
    t : ndarray, shape (N,)
        Times [s].

    Returns
    -------
    theta, theta_dot : ndarray, shape (N,)
    """
    t = np.asarray(t, dtype=np.float64)
    omega0 = math.sqrt(g / l)
    m = modulus_squared(theta0, theta_dot0, omega0)
    if m == 0.0:
        return np.zeros_like(t), np.zeros_like(t)
    k = math.sqrt(m)
    if m < 1.0:
        phi0 = math.atan2(math.sin(0.5 * theta0) / k, theta_dot0 / (2.0 * k * omega0))
        u = _incomplete_F(phi0, m) + omega0 * t
        sn, cn, _dn, _ph = special.ellipj(u, m)
        # theta0 may carry whole turns; the libration is about the nearest 2 pi multiple.
        shift = 2.0 * math.pi * round(theta0 / (2.0 * math.pi))
        return 2.0 * np.arcsin(k * sn) + shift, 2.0 * k * omega0 * cn
    if m > 1.0:
        s = 1.0 if theta_dot0 >= 0.0 else -1.0
        mm = 1.0 / m
        u = _incomplete_F(s * 0.5 * theta0, mm) + k * omega0 * t
        _sn, _cn, dn, ph = special.ellipj(u, mm)
        return 2.0 * s * ph, 2.0 * s * k * omega0 * dn
    raise ValueError("exact_solution: the separatrix (k = 1) has no periodic closed form here")


def small_angle_solution(t, theta0, theta_dot0, g, l):
    """Linearised solution (1.19): theta = theta0 cos(omega0 t) + theta_dot0/omega0 sin(omega0 t)."""
    omega0 = math.sqrt(g / l)
    t = np.asarray(t, dtype=np.float64)
    c, s = np.cos(omega0 * t), np.sin(omega0 * t)
    return theta0 * c + theta_dot0 / omega0 * s, -theta0 * omega0 * s + theta_dot0 * c
