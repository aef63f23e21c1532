r"""An impulse P struck at a point p of the body at t = 0 (textbook ex. 4.6(c)): what it
does to the translation and the rotation, and the paths in space that follow.

Just after the blow (impulse theorem, lecture notes §8) the centre of mass moves at
V = P/M and the angular momentum about it has jumped by p × P, so ω⁺ = ω + I⁻¹ (p × P)
(:func:`reportgen.core.models.rigid_body.omega_after_impulse`).  With no force and no
torque afterwards, the centre of mass drifts on the straight line V t and the body
turns as Euler's equations say; the struck point moves on r_p(t) = V t + R(t) p, with
R(t) the integrated attitude (the centre of mass at the origin at t = 0).

Two checks from the run:

* the centre of mass, found again from the run: the body as the point masses of its
  quadrature (:meth:`~reportgen.kinds.inertia.config._ShapeBase.mass_elements`), each
  placed by the struck point's path and the attitude, r_i = r_p + R (b_i − p), and moving
  at v_i = v_p + ω × R (b_i − p); their mean position and momentum over M must be V t and
  V = P/M at every sample (at round-off, because the quadrature's centre of mass is the
  closed-form one);
* for a symmetric body, the struck point's path against the closed form: the body turns
  uniformly about L at |L|/I⊥ and about its figure axis at Ω of notes (10.10),
  R(t) = Rot(L̂, |L| t/I⊥) R(0) Rot(e_s, Ω t) (Landau & Lifshitz §33).
"""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module

rotations = lazy_module("reportgen.core.rotations")


def rotation_matrices(quat) -> np.ndarray:
    """(N, 3, 3) body -> space matrices of unit quaternions [w, x, y, z]."""
    q = np.asarray(quat, dtype=float)
    q = q / np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
    ], axis=1)


def _axis_rotations(axis, angles) -> np.ndarray:
    """(N, 3, 3) rotations by ``angles`` about the unit vector ``axis`` (Rodrigues)."""
    n = np.asarray(axis, dtype=float)
    n = n / np.linalg.norm(n)
    K = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
    a = np.asarray(angles, dtype=float)[:, None, None]
    return np.eye(3) + np.sin(a) * K + (1.0 - np.cos(a)) * (K @ K)


def impulse_motion(t, omega, quat, moments, *, P, point, omega_before, mass=None,
                   elements=None, symmetric=None) -> dict:
    """The impulse's effect and the paths in space after it.

    Parameters
    ----------
    t : (N,) [s]; omega : (N, 3) body-frame ω after the impulse [rad/s];
    quat : (N, 4) attitude body -> space, the run's; moments : (3,) principal moments
    along the body axes [kg m²].
    P : (3,) impulse, body frame [kg m/s]; point : (3,) struck point from the centre of
    mass, body frame [m]; omega_before : (3,) body-frame ω before the blow [rad/s].
    mass : M [kg], or None (a body given by its moments only: no translation).
    elements : (masses (K,), positions (K, 3)) the body's point masses from the
    closed-form centre of mass, body frame, or None.
    symmetric : (s, Ω) the figure axis (0-based) and body-frame precession rate
    notes (10.10) of a symmetric body, or None.

    Returns
    -------
    dict of the ``impulse/…`` results (see ``results.py``).
    """
    t = np.asarray(t, dtype=float)
    I = np.asarray(moments, dtype=float)
    P = np.asarray(P, dtype=float)
    p = np.asarray(point, dtype=float)
    R = rotation_matrices(quat)
    R0 = R[0]
    angular = np.cross(p, P)
    out = {"P": P, "P_space": R0 @ P, "point": p, "angular_impulse": angular,
           "omega_before": np.asarray(omega_before, dtype=float),
           "delta_omega": angular / I}
    if mass is None:
        return out
    V = R0 @ P / mass
    omega_space = np.einsum("nij,nj->ni", R, np.asarray(omega, dtype=float))
    arm = np.einsum("nij,j->ni", R, p)  # struck point from the centre of mass, space frame
    cm_path = t[:, None] * V
    point_path = cm_path + arm
    point_velocity = V + np.cross(omega_space, arm)
    out.update(mass=float(mass), cm_velocity=V, cm_path=cm_path, point_path=point_path,
               point_velocity_initial=point_velocity[0])
    if elements is not None:
        m, b = (np.asarray(x, dtype=float) for x in elements)
        M = float(np.sum(m))
        # Σ m_i (b_i − p) / M, then each sample: mean position and momentum / M of the
        # elements placed from the struck point's path and the attitude
        offset = m @ (b - p) / M
        lever = np.einsum("nij,j->ni", R, offset)
        cm_run = point_path + lever
        v_run = point_velocity + np.cross(omega_space, lever)
        err_v = np.abs(v_run - V)
        worst = np.unravel_index(int(np.argmax(err_v)), err_v.shape)
        out.update(nodes=int(len(m)),
                   cm_velocity_run_worst=float(v_run[worst]),
                   cm_velocity_run_worst_component=int(worst[1]),
                   cm_velocity_run_max_error=float(err_v[worst]),
                   cm_path_run_max_error=float(np.max(np.linalg.norm(cm_run - cm_path,
                                                                     axis=1))))
    if symmetric is not None:
        s, Omega = symmetric
        b = (s + 1) % 3
        L_space = R0 @ (I * np.asarray(omega, dtype=float)[0])
        rate = float(np.linalg.norm(L_space) / I[b])
        e_s = np.zeros(3)
        e_s[s] = 1.0
        body = _axis_rotations(e_s, Omega * t)
        exact_R = _axis_rotations(L_space, rate * t) @ R0 @ body
        exact = cm_path + np.einsum("nij,j->ni", exact_R, p)
        out.update(precession_rate=rate, point_path_exact=exact,
                   point_path_max_error=float(np.max(np.linalg.norm(point_path - exact,
                                                                    axis=1))))
    return out
