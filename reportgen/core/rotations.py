r"""Rotations: Euler angles (z-x-z), angular velocity from Euler-angle rates, SU(2) -> SO(3),
unit quaternions, and the conversions between them.

Conventions
-----------
* A rotation is an *active* matrix ``R`` that maps body-frame components to
  space-frame components, ``v_space = R v_body``; its columns are the body axes
  seen from space.  Goldstein's (passive) transformation matrix is ``A = R^T``.
* Euler angles (φ, θ, ψ) in the z-x-z convention of Goldstein §4.4 and Landau &
  Lifshitz §35 (lecture notes (9.17)–(9.19)): ``R = R_z(φ) R_x(θ) R_z(ψ)``, i.e.
  ``A = R_z(ψ)^T R_x(θ)^T R_z(φ)^T`` (Goldstein eq. 4.46).
* Quaternions are ``q = (w, x, y, z)`` with ``w = cos(α/2)``, ``(x, y, z) = sin(α/2) n``
  for a rotation by α about the unit vector n; ``R(q) v = q v q*``.
* SU(2): ``U(q) = w 1 − i (x σx + y σy + z σz) = exp(−i α n·σ / 2)``, and
  ``R_ij = ½ tr(σ_i U σ_j U†)`` (lecture notes (9.4)–(9.16)); U and −U give the
  same R (the double cover).

References
----------
.. [1] Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., §4.4 (4.46), §4.9 (4.87).
.. [2] Landau & Lifshitz, *Mechanics*, 3rd ed., §35, eq. (35.1).
"""

from __future__ import annotations

import math

import numpy as np

PAULI = np.array([[[0, 1], [1, 0]], [[0, -1j], [1j, 0]], [[1, 0], [0, -1]]], dtype=complex)


def rot_x(a: float) -> np.ndarray:
    """Active rotation by ``a`` [rad] about the x axis, shape (3, 3)."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_z(a: float) -> np.ndarray:
    """Active rotation by ``a`` [rad] about the z axis, shape (3, 3)."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def euler_matrix(phi: float, theta: float, psi: float) -> np.ndarray:
    """Body -> space rotation ``R = R_z(φ) R_x(θ) R_z(ψ)`` (z-x-z Euler angles, (9.17)–(9.19)).

    Goldstein's matrix A (space -> body components, eq. 4.46) is the transpose.
    """
    return rot_z(phi) @ rot_x(theta) @ rot_z(psi)


def euler_from_matrix(R: np.ndarray) -> tuple[float, float, float]:
    """(φ, θ, ψ) with θ in [0, π] such that ``euler_matrix(φ, θ, ψ) = R``.

    For θ = 0 or π (gimbal lock) only φ ± ψ is defined; ψ = 0 is returned.
    """
    R = np.asarray(R, dtype=float)
    theta = math.acos(max(-1.0, min(1.0, R[2, 2])))
    if abs(math.sin(theta)) < 1e-12:
        psi = 0.0
        phi = math.atan2(R[1, 0], R[0, 0]) if R[2, 2] > 0 else math.atan2(-R[1, 0], R[0, 0])
        return phi, theta, psi
    # third column of R: body z axis in space = (sinφ sinθ, −cosφ sinθ, cosθ)
    phi = math.atan2(R[0, 2], -R[1, 2])
    # third row: (sinθ sinψ, sinθ cosψ, cosθ)
    psi = math.atan2(R[2, 0], R[2, 1])
    return phi, theta, psi


def omega_from_euler_rates(phi, theta, psi, phi_dot, theta_dot, psi_dot, frame="body"):
    """Angular velocity from Euler angles and their rates (lecture notes (10.20)).

    Body frame (Landau & Lifshitz (35.1), Goldstein (4.87))::

        ω1 = φ̇ sinθ sinψ + θ̇ cosψ
        ω2 = φ̇ sinθ cosψ − θ̇ sinψ
        ω3 = φ̇ cosθ + ψ̇

    ``frame="space"`` returns ``R ω_body``.  Works elementwise on arrays; returns
    ndarray of shape (..., 3).
    """
    phi, theta, psi = (np.asarray(a, dtype=float) for a in (phi, theta, psi))
    body = np.stack([
        phi_dot * np.sin(theta) * np.sin(psi) + theta_dot * np.cos(psi),
        phi_dot * np.sin(theta) * np.cos(psi) - theta_dot * np.sin(psi),
        phi_dot * np.cos(theta) + psi_dot,
    ], axis=-1)
    if frame == "body":
        return body
    if frame == "space":
        return np.stack([
            theta_dot * np.cos(phi) + psi_dot * np.sin(theta) * np.sin(phi),
            theta_dot * np.sin(phi) - psi_dot * np.sin(theta) * np.cos(phi),
            phi_dot + psi_dot * np.cos(theta),
        ], axis=-1)
    raise ValueError(f"frame: expected 'body' or 'space', got {frame!r}")


# ------------------------------------------------------------------ quaternions
def quat_multiply(p, q) -> np.ndarray:
    """Hamilton product p ⊗ q of quaternions (w, x, y, z); broadcasts over leading axes."""
    p, q = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    pw, pv = p[..., :1], p[..., 1:]
    qw, qv = q[..., :1], q[..., 1:]
    w = pw * qw - np.sum(pv * qv, axis=-1, keepdims=True)
    v = pw * qv + qw * pv + np.cross(pv, qv)
    return np.concatenate([w, v], axis=-1)


def quat_conjugate(q) -> np.ndarray:
    q = np.asarray(q, dtype=float)
    return q * np.array([1.0, -1.0, -1.0, -1.0])


def quat_from_axis_angle(axis, angle: float) -> np.ndarray:
    """Unit quaternion of a rotation by ``angle`` [rad] about ``axis`` (normalized here)."""
    n = np.asarray(axis, dtype=float)
    n = n / np.linalg.norm(n)
    return np.concatenate([[math.cos(0.5 * angle)], math.sin(0.5 * angle) * n])


def quat_to_matrix(q) -> np.ndarray:
    """Rotation matrix R(q) (body -> space), shape (..., 3, 3); q need not be normalized."""
    q = np.asarray(q, dtype=float)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    R = np.empty(q.shape[:-1] + (3, 3))
    R[..., 0, 0] = 1 - 2 * (y * y + z * z)
    R[..., 0, 1] = 2 * (x * y - w * z)
    R[..., 0, 2] = 2 * (x * z + w * y)
    R[..., 1, 0] = 2 * (x * y + w * z)
    R[..., 1, 1] = 1 - 2 * (x * x + z * z)
    R[..., 1, 2] = 2 * (y * z - w * x)
    R[..., 2, 0] = 2 * (x * z - w * y)
    R[..., 2, 1] = 2 * (y * z + w * x)
    R[..., 2, 2] = 1 - 2 * (x * x + y * y)
    return R


def matrix_to_quat(R) -> np.ndarray:
    """Unit quaternion (w ≥ 0) of a rotation matrix (Shepperd's method: the largest pivot)."""
    R = np.asarray(R, dtype=float)
    tr = np.trace(R)
    diag = [tr, R[0, 0], R[1, 1], R[2, 2]]
    k = int(np.argmax(diag))
    if k == 0:
        w = 0.5 * math.sqrt(1.0 + tr)
        q = [w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w),
             (R[1, 0] - R[0, 1]) / (4 * w)]
    elif k == 1:
        x = 0.5 * math.sqrt(1.0 + 2 * R[0, 0] - tr)
        q = [(R[2, 1] - R[1, 2]) / (4 * x), x, (R[0, 1] + R[1, 0]) / (4 * x),
             (R[0, 2] + R[2, 0]) / (4 * x)]
    elif k == 2:
        y = 0.5 * math.sqrt(1.0 + 2 * R[1, 1] - tr)
        q = [(R[0, 2] - R[2, 0]) / (4 * y), (R[0, 1] + R[1, 0]) / (4 * y), y,
             (R[1, 2] + R[2, 1]) / (4 * y)]
    else:
        z = 0.5 * math.sqrt(1.0 + 2 * R[2, 2] - tr)
        q = [(R[1, 0] - R[0, 1]) / (4 * z), (R[0, 2] + R[2, 0]) / (4 * z),
             (R[1, 2] + R[2, 1]) / (4 * z), z]
    q = np.array(q)
    return q if q[0] >= 0 else -q


def quat_rotate(q, v) -> np.ndarray:
    """Space components ``R(q) v`` of body-frame vectors v, shape (..., 3)."""
    return np.einsum("...ij,...j->...i", quat_to_matrix(q), np.asarray(v, dtype=float))


def euler_to_quat(phi: float, theta: float, psi: float) -> np.ndarray:
    """Quaternion of ``euler_matrix(φ, θ, ψ)``: q_z(φ) ⊗ q_x(θ) ⊗ q_z(ψ)."""
    ez, ex = (0.0, 0.0, 1.0), (1.0, 0.0, 0.0)
    return quat_multiply(quat_multiply(quat_from_axis_angle(ez, phi),
                                       quat_from_axis_angle(ex, theta)),
                         quat_from_axis_angle(ez, psi))


def quat_to_euler(q) -> tuple[float, float, float]:
    return euler_from_matrix(quat_to_matrix(q))


# ------------------------------------------------------------------------ SU(2)
def su2_from_quat(q) -> np.ndarray:
    """``U = w 1 − i (x σx + y σy + z σz)`` (unitary, det 1 for |q| = 1), shape (2, 2)."""
    w, x, y, z = np.asarray(q, dtype=float)
    return w * np.eye(2) - 1j * (x * PAULI[0] + y * PAULI[1] + z * PAULI[2])


def su2_to_quat(U) -> np.ndarray:
    """Inverse of :func:`su2_from_quat`: w = Re tr U / 2, (x, y, z) = i tr(σ U) / 2."""
    U = np.asarray(U, dtype=complex)
    w = 0.5 * np.trace(U).real
    v = [(0.5j * np.trace(s @ U)).real for s in PAULI]
    return np.array([w, *v])


def so3_from_su2(U) -> np.ndarray:
    """The double cover SU(2) -> SO(3): ``R_ij = ½ tr(σ_i U σ_j U†)`` ((9.4)–(9.16))."""
    U = np.asarray(U, dtype=complex)
    Ud = U.conj().T
    R = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            R[i, j] = 0.5 * np.trace(PAULI[i] @ U @ PAULI[j] @ Ud).real
    return R


def skew(v) -> np.ndarray:
    """Cross-product matrix [v]×: skew(v) @ u = v × u."""
    x, y, z = v
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
