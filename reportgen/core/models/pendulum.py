r"""The plane pendulum  m l^2 \ddot\theta + m g l \sin\theta = 0.

State ``y = (theta, theta_dot)``; with the mass-normalised momentum
``p = theta_dot`` the Hamiltonian per unit ``m l^2`` is separable,
``H = p^2/2 - omega0^2 cos(theta)``, ``omega0^2 = g / l``.

References
----------
.. [1] Lecture notes §1, eqs. (1.17)-(1.21); §2, eq. (2.4).
.. [2] Lawden, D. F., *Elliptic Functions and Applications*, Springer (1989), §5.2.
.. [3] NIST DLMF §22.19(i), "Classical Dynamics: The Pendulum".
.. [4] NIST DLMF §19.2(ii), complete elliptic integral K(k).
"""

from __future__ import annotations

import math

import numba
import numpy as np
from scipy import special

from ..crossings import mean_period, upward_crossings
from ..model import OdeModel, Separable
from ..pendulum_theory import (  # noqa: F401 - part of this module's interface
    EXACT_SOLUTION_MIN_M1,
    complementary_parameter,
    modulus_squared,
)

# params = (omega0^2,)


@numba.njit(cache=True, error_model="numpy")
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
        # DOP853 on a driver with rhs inlined and d = 2: 22 -> 19-20 ns per evaluation,
        # pendulum_small 220x -> 254x scipy (benchmarks/README.md, "Loop vectorization")
        specialize=True,
    )


def energy(theta, theta_dot, g, l, m=1.0):
    """Total energy  E = m l^2 theta_dot^2 / 2 - m g l cos(theta)  [J]."""
    return 0.5 * m * l**2 * np.asarray(theta_dot) ** 2 - m * g * l * np.cos(theta)




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


def reduced_energy(theta, theta_dot, omega0):
    """Energy per unit m l^2,  E / (m l^2) = theta_dot^2 / 2 - omega0^2 cos(theta)  [1/s^2].

    The phase-plane function whose level sets are the pendulum's orbits; the
    separatrix is the level ``omega0^2`` (E = m g l) through (±pi, 0).

    Parameters
    ----------
    theta : ndarray, any shape
        Angle [rad].
    theta_dot : ndarray, same shape as ``theta`` (or broadcastable)
        Angular velocity [rad/s].
    omega0 : float
        sqrt(g / l) [rad/s].

    Returns
    -------
    ndarray, the broadcast shape of ``theta`` and ``theta_dot``
    """
    return 0.5 * np.asarray(theta_dot) ** 2 - omega0**2 * np.cos(theta)


def separatrix_level(omega0):
    """Reduced energy of the separatrix, E / (m l^2) = omega0^2 (E = m g l) [1/s^2]."""
    return omega0**2


def libration_period(amplitude, omega0):
    """Exact period of a libration released from rest at ``amplitude`` [s].

    T = 4 K(k^2) / omega0 with k = sin(amplitude / 2) (lecture notes §1; DLMF 22.19.4;
    K in the parameter convention of DLMF 19.2.8, scipy ``ellipk``).

    Parameters
    ----------
    amplitude : ndarray, shape (N,)
        theta0 in (0, pi) [rad].
    omega0 : float
        sqrt(g / l) [rad/s].

    Returns
    -------
    ndarray, shape (N,)
        Period [s]; grows like 4 log(4 / cos(theta0/2)) / omega0 as theta0 -> pi.
    """
    return 4 * special.ellipk(np.sin(np.asarray(amplitude) / 2) ** 2) / omega0


def libration_amplitude(theta0, theta_dot0, omega0):
    """Amplitude 2 asin(k) of a libration (k^2 < 1) [rad], k^2 from :func:`modulus_squared`."""
    return 2 * math.asin(min(1.0, math.sqrt(modulus_squared(theta0, theta_dot0, omega0))))


def measured_period(t, theta, theta_dot, theta0, theta_dot0, g, l, min_samples_per_period=16):
    """Mean period measured from a sampled trajectory [s].

    Libration: mean spacing of upward crossings of theta through its centre (the
    nearest multiple of 2 pi to ``theta0``).  Rotation: mean time per full turn,
    from the crossings of theta - theta0 through successive multiples of 2 pi.  Each
    crossing is refined with the quintic Hermite interpolant of theta, theta_dot and
    theta_ddot = -omega0^2 sin(theta) (:func:`reportgen.core.crossings.upward_crossings`).

    Parameters
    ----------
    t, theta, theta_dot : ndarray, shape (N,)
        Times [s], angle [rad] and angular velocity [rad/s].
    theta0, theta_dot0 : float
        The initial state (decides libration or rotation and the centre).
    g, l : float
        [m/s^2], [m].
    min_samples_per_period : int
        Crossings are located reliably only with this many samples per period.

    Returns
    -------
    float
        NaN when the output is too sparse (fewer than ``min_samples_per_period``
        samples per exact period) or covers fewer than two periods.
    """
    omega0 = math.sqrt(g / l)
    n_periods = (t[-1] - t[0]) / exact_period(theta0, theta_dot0, g, l)
    if n_periods * min_samples_per_period > len(t) - 1:
        return float("nan")
    accel = -omega0**2 * np.sin(theta)
    if complementary_parameter(theta0, theta_dot0, omega0) > 0.0:
        centre = 2 * math.pi * round(theta0 / (2 * math.pi))
        return mean_period(upward_crossings(t, theta, theta_dot, accel, level=centre))
    sign = 1.0 if theta_dot0 >= 0 else -1.0
    x = sign * (theta - theta[0])  # increases monotonically while rotating
    turns = int(np.floor(x[-1] / (2 * math.pi)))
    times = [0.0] + [upward_crossings(t, x, sign * theta_dot, sign * accel,
                                      level=2 * math.pi * n)[0]
                     for n in range(1, turns + 1)]
    return mean_period(np.array(times))


def linear_boundary_solution(t, theta0, theta1, T, omega0):
    """Solution (1.21) of the linearised boundary-value problem theta'' = -omega0^2 theta,
    theta(0) = theta0, theta(T) = theta1:

    theta(t) = [theta0 sin omega0 (T - t) + theta1 sin omega0 t] / sin omega0 T.

    Parameters
    ----------
    t : ndarray, shape (N,)
        Times in [0, T] [s].

    Returns
    -------
    ndarray, shape (N,)
        theta [rad]; undefined at conjugate points sin(omega0 T) = 0.
    """
    t = np.asarray(t, dtype=np.float64)
    return (theta0 * np.sin(omega0 * (T - t)) + theta1 * np.sin(omega0 * t)) \
        / math.sin(omega0 * T)


def linear_boundary_action(theta0, theta1, T, omega0, inertia):
    """Action (2.4) S = ∫ L dt along the solution (1.21) of the linear problem [J·s]:

    S = I omega0 [(theta0^2 + theta1^2) cos omega0 T - 2 theta0 theta1] / (2 sin omega0 T),

    with ``inertia`` I = m l^2 [kg m^2] and L = I theta_dot^2 / 2 - I omega0^2 theta^2 / 2.
    """
    return inertia * omega0 / (2 * math.sin(omega0 * T)) * (
        (theta0**2 + theta1**2) * math.cos(omega0 * T) - 2 * theta0 * theta1)


def boundary_value_problem(theta0, theta1, T, g, l, m=1.0, n=401):
    """The boundary-value problem theta(0) = theta0, theta(T) = theta1, linear and nonlinear.

    The linearised problem (1.21) in closed form and by ``scipy.integrate.solve_bvp``
    (tol 1e-10), its action (2.4) in closed form and by Simpson quadrature of the
    Lagrangian on 20001 points, and the nonlinear pendulum's solution with the same
    ends and its action (a different problem, shown for comparison).

    Parameters
    ----------
    theta0, theta1 : float
        End values [rad].
    T : float
        End time [s]; not a conjugate point (sin(omega0 T) != 0).
    g, l, m : float
        [m/s^2], [m], [kg].
    n : int
        Output samples on [0, T].

    Returns
    -------
    dict
        ``t`` (n,), ``theta_exact``, ``theta_numeric``, ``theta_nonlinear`` (n,) [rad]
        (NaN if the nonlinear solve failed); ``action_exact``, ``action_numeric``,
        ``action_nonlinear`` [J·s]; ``nonlinear_converged`` (bool).
    """
    from scipy import integrate as sp_integrate  # 0.2 s to import: only this section uses it

    w, M = math.sqrt(g / l), m * l**2
    t = np.linspace(0.0, T, n)
    exact = linear_boundary_solution(t, theta0, theta1, T, w)
    action_exact = linear_boundary_action(theta0, theta1, T, w, M)

    def linear(_t, y):
        return np.vstack([y[1], -w**2 * y[0]])

    def nonlinear(_t, y):
        return np.vstack([y[1], -w**2 * np.sin(y[0])])

    def bc(ya, yb):
        return np.array([ya[0] - theta0, yb[0] - theta1])

    guess = np.vstack([exact, np.gradient(exact, t)])
    lin = sp_integrate.solve_bvp(linear, bc, t, guess, tol=1e-10, max_nodes=100000)
    non = sp_integrate.solve_bvp(nonlinear, bc, t, guess, tol=1e-10, max_nodes=100000)
    fine = np.linspace(0.0, T, 20001)

    def action(sol, potential):
        th, thd = sol.sol(fine)
        lagrangian = 0.5 * M * thd**2 - potential(th)
        return float(sp_integrate.simpson(lagrangian, x=fine))

    action_numeric = action(lin, lambda th: 0.5 * M * w**2 * th**2)
    action_nonlinear = action(non, lambda th: M * w**2 * (1 - np.cos(th)))
    return {
        "t": t,
        "theta_exact": exact,
        "theta_numeric": lin.sol(t)[0],
        "theta_nonlinear": non.sol(t)[0] if non.success else np.full_like(t, np.nan),
        "action_exact": float(action_exact),
        "action_numeric": action_numeric,
        "action_nonlinear": action_nonlinear if non.success else float("nan"),
        "nonlinear_converged": bool(non.success),
    }
