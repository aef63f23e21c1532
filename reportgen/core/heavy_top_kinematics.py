r"""Kinematics of the heavy-top state and measurements on an integrated trajectory.

The state is the one of :mod:`reportgen.core.models.heavy_top`: a quaternion
``q = (q_w, q_x, q_y, q_z)`` (body -> space, any norm) and the body angular velocity
``(ω1, ω2, ω3)``.  From it: Goldstein's z-x-z Euler angles θ, φ, ψ, the space-frame
symmetry axis e3 with its velocity and acceleration, θ̇ and φ̇ from the axis (defined on
the vertical too), and w = 1 − cos θ without cancellation.  The nutation period and the
precession per period are measured from the samples by Hermite-refined level crossings
(:mod:`reportgen.core.crossings`), and the turning values of θ by Hermite-refined extrema,
independently of the closed form in :mod:`reportgen.core.heavy_top_theory`.

References
----------
.. [1] Goldstein, Poole, Safko, *Classical Mechanics*, 3rd ed., §4.4 (z-x-z Euler
       angles, eq. 4.46), §4.9 (angular velocity, eq. 4.87), §5.7.
.. [2] Lecture notes §10.1, eqs. (10.21)-(10.50).
"""

from __future__ import annotations

import math

import numpy as np

from .crossings import _quintic_hermite, mean_period, upward_crossings
from .heavy_top_theory import STEADY_RTOL
from .models.heavy_top import rhs, rotation_matrices


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
    theta = tilt_angle(q)
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



def tilt_angle(q):
    """θ = 2 atan2(|(q_x, q_y)|, |(q_w, q_z)|): tilt of the symmetry axis from the vertical.

    Parameters
    ----------
    q : ndarray, shape (N, 4)
        Quaternions (any norm).

    Returns
    -------
    ndarray, shape (N,)
        θ [rad], accurate near the vertical (no arccos).
    """
    qw, qx, qy, qz = (q[:, i] for i in range(4))
    return 2.0 * np.arctan2(np.hypot(qx, qy), np.hypot(qw, qz))


def one_minus_cos_theta(q):
    """w = 1 − cos θ = 2 (q_x² + q_y²)/|q|² without cancellation.

    Parameters
    ----------
    q : ndarray, shape (N, 4)
        Quaternions (any norm).

    Returns
    -------
    ndarray, shape (N,)
    """
    return 2.0 * (q[:, 1] ** 2 + q[:, 2] ** 2) / np.sum(q**2, axis=1)


def derived_motion(y, I1, I3, Mgl) -> dict[str, np.ndarray]:
    """Euler angles, symmetry axis and rates along a trajectory of the quaternion state.

    θ̇ and φ̇ come from the axis e3 = (ρ sin φ, −ρ cos φ, cos θ), ρ = sin θ:
    θ̇ = ρ̇ e3_z − ė3_z ρ and φ̇ = (e3_x ė3_y − e3_y ė3_x)/ρ² (10.26 measured, not
    assumed); exactly on the vertical (ρ = 0) φ is undefined and both rates are 0.

    Parameters
    ----------
    y : ndarray, shape (N, 7)
        States (q_w, q_x, q_y, q_z, ω1, ω2, ω3).
    I1, I3, Mgl : float
        [kg m²], [kg m²], [J].

    Returns
    -------
    dict of str -> ndarray
        ``theta``, ``phi``, ``psi`` [rad], shape (N,); ``axis`` shape (N, 3);
        ``theta_dot``, ``phi_dot`` [rad/s]; ``w`` = 1 − cos θ with ``w_dot``, ``w_ddot``
        (its first two time derivatives, from the equations of motion).
    """
    q = y[:, :4] / np.linalg.norm(y[:, :4], axis=1)[:, None]
    theta, phi, psi = euler_angles(q)
    e3, e3_dot, e3_ddot = axis_kinematics(y, I1, I3, Mgl)
    rho = np.hypot(e3[:, 0], e3[:, 1])
    on_axis = rho == 0.0  # exactly vertical: φ undefined, rates stored as 0
    safe = np.where(on_axis, 1.0, rho)
    rho_dot = np.where(on_axis, 0.0, (e3[:, 0] * e3_dot[:, 0] + e3[:, 1] * e3_dot[:, 1]) / safe)
    theta_dot = rho_dot * e3[:, 2] - e3_dot[:, 2] * rho
    phi_dot = np.where(on_axis, 0.0,
                       (e3[:, 0] * e3_dot[:, 1] - e3[:, 1] * e3_dot[:, 0]) / safe**2)
    w = 2.0 * (q[:, 1] ** 2 + q[:, 2] ** 2)  # 1 − cos θ without cancellation (|q| = 1)
    return {"theta": theta, "phi": phi, "psi": psi, "axis": e3, "theta_dot": theta_dot,
            "phi_dot": phi_dot, "w": w, "w_dot": -e3_dot[:, 2], "w_ddot": -e3_ddot[:, 2]}


def hermite_cubic(t, x, xdot, times):
    """Cubic Hermite interpolation of x(t) with slopes xdot, evaluated at ``times``.

    Parameters
    ----------
    t, x, xdot : ndarray, shape (N,)
        Sample times (increasing), values and exact derivatives.
    times : ndarray, shape (K,)

    Returns
    -------
    ndarray, shape (K,)
    """
    idx = np.clip(np.searchsorted(t, times) - 1, 0, len(t) - 2)
    h = t[idx + 1] - t[idx]
    s = (times - t[idx]) / h
    h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
    h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
    return h00 * x[idx] + h10 * h * xdot[idx] + h01 * x[idx + 1] + h11 * h * xdot[idx + 1]


def measure_nutation(t, motion, *, w1, w2, period, min_samples_per_period=16):
    """Nutation period and precession per period measured from a trajectory.

    Upward crossings of w = 1 − cos θ through the middle of [w1, w2] (quintic Hermite
    from w, ẇ, ẅ, :func:`reportgen.core.crossings.upward_crossings`); φ at those times
    by cubic Hermite interpolation of the stored φ, φ̇.

    Parameters
    ----------
    t : ndarray, shape (N,)
        Sample times [s].
    motion : dict
        :func:`derived_motion` of the trajectory (``w``, ``w_dot``, ``w_ddot``, ``phi``,
        ``phi_dot``).
    w1, w2 : float
        Turning points 1 − u2 ≤ 1 − u1 of the closed form.
    period : float
        Expected nutation period [s], for the sampling check only.
    min_samples_per_period : int
        Crossings are located reliably only with this many samples per period.

    Returns
    -------
    period, precession : float
        [s] and [rad]; NaN without nutation (w2 − w1 ≤ STEADY_RTOL w2), with fewer
        samples per period than asked, or with fewer than two crossings.
    """
    if w2 - w1 <= STEADY_RTOL * w2:
        return math.nan, math.nan
    if not math.isfinite(period) or (t[-1] / period) * min_samples_per_period > len(t):
        return math.nan, math.nan
    level = 0.5 * (w1 + w2)
    times = upward_crossings(t, motion["w"], motion["w_dot"], motion["w_ddot"], level=level)
    T = mean_period(times)
    if times.size < 2:
        return T, math.nan
    phis = hermite_cubic(t, motion["phi"], motion["phi_dot"], times)
    return T, float((phis[-1] - phis[0]) / (times.size - 1))


def extreme_values(t, x, xdot, xddot) -> tuple[float, float]:
    """Smallest and largest value of x(t) between and on the samples, to O(h⁶).

    Where ẋ changes sign between two samples, x is replaced by the quintic Hermite
    interpolant of x, ẋ, ẍ at both ends (as for the level crossings) and its extremum
    found by Newton's method on its derivative; the turning values of a sampled nutation
    (θ1, θ2 from w = 1 − cos θ) come out to the integration's accuracy, not the grid's.

    Parameters
    ----------
    t, x, xdot, xddot : ndarray, shape (N,)
        Sample times (increasing), values and their first two exact time derivatives.

    Returns
    -------
    (float, float)
        min and max of x over [t[0], t[-1]].
    """
    lo, hi = float(np.min(x)), float(np.max(x))
    turn = np.nonzero(np.sign(xdot[:-1]) * np.sign(xdot[1:]) < 0)[0]
    for i in turn:
        h = t[i + 1] - t[i]
        c = _quintic_hermite(h, x[i], xdot[i], xddot[i], x[i + 1], xdot[i + 1], xddot[i + 1])
        s = xdot[i] / (xdot[i] - xdot[i + 1])  # linear guess for ẋ = 0
        for _ in range(30):
            d1 = (((5 * c[5] * s + 4 * c[4]) * s + 3 * c[3]) * s + 2 * c[2]) * s + c[1]
            d2 = ((20 * c[5] * s + 12 * c[4]) * s + 6 * c[3]) * s + 2 * c[2]
            if d2 == 0.0:
                break
            step = d1 / d2
            s = min(1.0, max(0.0, s - step))
            if abs(step) < 1e-15:
                break
        value = ((((c[5] * s + c[4]) * s + c[3]) * s + c[2]) * s + c[1]) * s + c[0]
        lo, hi = min(lo, value), max(hi, value)
    return lo, hi
