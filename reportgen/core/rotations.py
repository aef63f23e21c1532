r"""Rotations: the axis-angle formula, Euler angles (z-x-z and z-y-z), angular velocity from
Euler-angle rates, SU(2) -> SO(3), stereographic projection and Möbius maps, unit quaternions,
and the conversions between them.

Conventions
-----------
* A rotation is an *active* matrix ``R`` that maps body-frame components to
  space-frame components, ``v_space = R v_body``; its columns are the body axes
  seen from space.  Goldstein's (passive) transformation matrix is ``A = R^T``.
* Euler angles (φ, θ, ψ) in the z-x-z convention of Goldstein §4.4 and Landau &
  Lifshitz §35 (lecture notes (9.17)–(9.19)): ``R = R_z(φ) R_x(θ) R_z(ψ)``, i.e.
  ``A = R_z(ψ)^T R_x(θ)^T R_z(φ)^T`` (Goldstein eq. 4.46).  The z-y-z convention
  (Goldstein's "y-convention") turns about the intermediate y axis instead:
  ``R = R_z(φ) R_y(θ) R_z(ψ)``.  Since ``R_y(θ) = R_z(π/2) R_x(θ) R_z(−π/2)``,
  ``R_zyz(φ, θ, ψ) = R_zxz(φ + π/2, θ, ψ − π/2)``.
* Goldstein's rotation formula (eq. 4.62), ``r' = r cos Φ + n (n·r)(1 − cos Φ) + (r × n) sin Φ``,
  is passive: r' are the components of r in axes turned by +Φ about n.  Its matrix is
  ``A(n, Φ) = R(n, Φ)^T = exp(−Φ [n]×)``; the active rotation is ``R(n, Φ) = exp(Φ [n]×)``.
* Quaternions are ``q = (w, x, y, z)`` with ``w = cos(α/2)``, ``(x, y, z) = sin(α/2) n``
  for a rotation by α about the unit vector n; ``R(q) v = q v q*``.
* SU(2): ``U(q) = w 1 − i (x σx + y σy + z σz) = exp(−i α n·σ / 2)``, and
  ``R_ij = ½ tr(σ_i U σ_j U†)`` (lecture notes (9.4)–(9.16)); U and −U give the
  same R (the double cover).
* Stereographic projection from the north pole onto the equatorial plane, with the plane
  seen from below: ``ζ = (x − i y)/(1 − z)``, the spinor ratio ξ1/ξ2 of a point
  ``x = ξ†σξ / ξ†ξ``.  With this orientation the Möbius map
  ``ζ -> (a ζ + b)/(−b̄ ζ + ā)`` of ``U = [[a, b], [−b̄, ā]]`` is the rotation R(U) above
  (``U† σ_i U = R_ij σ_j``).  With the other orientation ``ζ = (x + i y)/(1 − z)`` the same
  Möbius map is R(Ū); it is never R(U)^T for every U, because U -> Möbius map keeps the
  order of products and R -> R^T reverses it.

References
----------
.. [1] Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., §4.4 (4.46), §4.9 (4.87).
.. [2] Landau & Lifshitz, *Mechanics*, 3rd ed., §35, eq. (35.1).
.. [3] Goldstein, Poole & Safko, 3rd ed., eq. (4.62) (the rotation formula) and the
       y-convention of the Euler angles; Needham, *Visual Complex Analysis*, ch. 6
       (rotations of the Riemann sphere as Möbius maps); Penrose & Rindler, *Spinors and
       Space-Time* vol. 1, ch. 1 (the spinor ratio as a stereographic coordinate).
.. [4] Squire & Trapp, "Using complex variables to estimate derivatives of real
       functions", SIAM Review 40 (1998) 110: the complex-step derivative.
"""

from __future__ import annotations

import math

import numpy as np

PAULI = np.array([[[0, 1], [1, 0]], [[0, -1j], [1j, 0]], [[1, 0], [0, -1]]], dtype=complex)


def rot_x(a: float) -> np.ndarray:
    """Active rotation by ``a`` [rad] about the x axis, shape (3, 3)."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(a: float) -> np.ndarray:
    """Active rotation by ``a`` [rad] about the y axis, shape (3, 3)."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(a: float) -> np.ndarray:
    """Active rotation by ``a`` [rad] about the z axis, shape (3, 3)."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


EULER_CONVENTIONS = ("zxz", "zyz")


def euler_matrix(phi: float, theta: float, psi: float, convention: str = "zxz") -> np.ndarray:
    """Body -> space rotation ``R = R_z(φ) R_x(θ) R_z(ψ)`` (z-x-z Euler angles, (9.17)–(9.19)),
    or ``R_z(φ) R_y(θ) R_z(ψ)`` for ``convention="zyz"``.

    Goldstein's matrix A (space -> body components, eq. 4.46) is the transpose.
    """
    middle = {"zxz": rot_x, "zyz": rot_y}[_convention(convention)]
    return rot_z(phi) @ middle(theta) @ rot_z(psi)


def _convention(convention: str) -> str:
    if convention not in EULER_CONVENTIONS:
        raise ValueError(f"convention: expected 'zxz' or 'zyz', got {convention!r}")
    return convention


def euler_matrices(angles, convention: str = "zxz") -> np.ndarray:
    """:func:`euler_matrix` for many angle triples at once, shape (..., 3, 3).

    ``angles``, shape (..., 3): (φ, θ, ψ).  Works on complex angles too (the
    complex-step derivative in :func:`omega_by_complex_step` relies on it).
    """
    a = np.asarray(angles)
    phi, theta, psi = a[..., 0], a[..., 1], a[..., 2]
    cf, sf, ct, st, cp, sp = (np.cos(phi), np.sin(phi), np.cos(theta), np.sin(theta),
                              np.cos(psi), np.sin(psi))
    zero, one = np.zeros_like(cf), np.ones_like(cf)
    if _convention(convention) == "zxz":
        middle = [[one, zero, zero], [zero, ct, -st], [zero, st, ct]]
    else:
        middle = [[ct, zero, st], [zero, one, zero], [-st, zero, ct]]
    first = np.moveaxis(np.array([[cf, -sf, zero], [sf, cf, zero], [zero, zero, one]]), (0, 1),
                        (-2, -1))
    second = np.moveaxis(np.array(middle), (0, 1), (-2, -1))
    third = np.moveaxis(np.array([[cp, -sp, zero], [sp, cp, zero], [zero, zero, one]]), (0, 1),
                        (-2, -1))
    return first @ second @ third


def euler_matrix_elements(phi: float, theta: float, psi: float,
                          convention: str = "zxz") -> np.ndarray:
    """Goldstein's passive matrix A = R^T written out element by element, shape (3, 3).

    z-x-z: Goldstein eq. (4.46); z-y-z: the same with φ -> φ + π/2, ψ -> ψ − π/2 worked
    out (Goldstein's y-convention).  An independent check on the
    product of elementary rotations in :func:`euler_matrix`.
    """
    cf, sf, ct, st = math.cos(phi), math.sin(phi), math.cos(theta), math.sin(theta)
    cp, sp = math.cos(psi), math.sin(psi)
    if _convention(convention) == "zxz":
        return np.array([
            [cp * cf - ct * sf * sp, cp * sf + ct * cf * sp, sp * st],
            [-sp * cf - ct * sf * cp, -sp * sf + ct * cf * cp, cp * st],
            [st * sf, -st * cf, ct]])
    return np.array([
        [-sp * sf + ct * cf * cp, sp * cf + ct * sf * cp, -cp * st],
        [-cp * sf - ct * cf * sp, cp * cf - ct * sf * sp, sp * st],
        [st * cf, st * sf, ct]])


def zyz_to_zxz(phi, theta, psi) -> tuple:
    """z-x-z angles of the rotation with z-y-z angles (φ, θ, ψ): (φ + π/2, θ, ψ − π/2)."""
    return phi + 0.5 * math.pi, theta, psi - 0.5 * math.pi


def zxz_to_zyz(phi, theta, psi) -> tuple:
    """z-y-z angles of the rotation with z-x-z angles (φ, θ, ψ): (φ − π/2, θ, ψ + π/2)."""
    return phi - 0.5 * math.pi, theta, psi + 0.5 * math.pi


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


def omega_from_euler_rates(phi, theta, psi, phi_dot, theta_dot, psi_dot, frame="body",
                           convention="zxz"):
    """Angular velocity from Euler angles and their rates (lecture notes (10.20)).

    ω = φ̇ e_z + θ̇ e_N + ψ̇ e_3 with e_N the line of nodes (the intermediate x axis for
    z-x-z, y axis for z-y-z) and e_3 the body z axis.  z-x-z, body frame (Landau &
    Lifshitz (35.1), Goldstein (4.87))::

        ω1 = φ̇ sinθ sinψ + θ̇ cosψ
        ω2 = φ̇ sinθ cosψ − θ̇ sinψ
        ω3 = φ̇ cosθ + ψ̇

    z-y-z, body frame (the same with ψ -> ψ − π/2; derived in the module docstring's
    reference [3])::

        ω1 = −φ̇ sinθ cosψ + θ̇ sinψ
        ω2 = φ̇ sinθ sinψ + θ̇ cosψ
        ω3 = φ̇ cosθ + ψ̇

    ``frame="space"`` returns ``R ω_body``, written out.  Works elementwise on arrays;
    returns ndarray of shape (..., 3).
    """
    phi, theta, psi = (np.asarray(a, dtype=float) for a in (phi, theta, psi))
    sf, cf, st, ct, sp, cp = (np.sin(phi), np.cos(phi), np.sin(theta), np.cos(theta),
                              np.sin(psi), np.cos(psi))
    zxz = _convention(convention) == "zxz"
    if frame == "body":
        if zxz:
            return np.stack([phi_dot * st * sp + theta_dot * cp,
                             phi_dot * st * cp - theta_dot * sp,
                             phi_dot * ct + psi_dot], axis=-1)
        return np.stack([-phi_dot * st * cp + theta_dot * sp,
                         phi_dot * st * sp + theta_dot * cp,
                         phi_dot * ct + psi_dot], axis=-1)
    if frame == "space":
        if zxz:  # e_N = (cosφ, sinφ, 0), e_3 = (sinθ sinφ, −sinθ cosφ, cosθ)
            return np.stack([theta_dot * cf + psi_dot * st * sf,
                             theta_dot * sf - psi_dot * st * cf,
                             phi_dot + psi_dot * ct], axis=-1)
        # e_N = (−sinφ, cosφ, 0), e_3 = (sinθ cosφ, sinθ sinφ, cosθ)
        return np.stack([-theta_dot * sf + psi_dot * st * cf,
                         theta_dot * cf + psi_dot * st * sf,
                         phi_dot + psi_dot * ct], axis=-1)
    raise ValueError(f"frame: expected 'body' or 'space', got {frame!r}")


def vee(W) -> np.ndarray:
    """The vector w of the antisymmetric part of W (..., 3, 3): ½(W − Wᵀ) = [w]×."""
    W = np.asarray(W)
    return 0.5 * np.stack([W[..., 2, 1] - W[..., 1, 2], W[..., 0, 2] - W[..., 2, 0],
                           W[..., 1, 0] - W[..., 0, 1]], axis=-1)


def euler_matrices_and_rate(angles, rates, convention: str = "zxz",
                            step: float = 1e-20) -> tuple[np.ndarray, np.ndarray]:
    """R and Ṙ along a path of Euler angles, shapes (..., 3, 3): Ṙ by the complex step
    ``Ṙ = Im R(a + i h ȧ) / h`` (Squire & Trapp 1998), exact to rounding for any small h
    since no difference is taken.  ``angles``, ``rates``: shape (..., 3)."""
    a = np.asarray(angles, dtype=float)
    Rc = euler_matrices(a + 1j * step * np.asarray(rates, dtype=float), convention)
    return Rc.real, Rc.imag / step


def omega_by_complex_step(angles, rates, convention: str = "zxz",
                          step: float = 1e-20) -> dict[str, np.ndarray]:
    """ω from differentiating the rotation matrix along a path of Euler angles, not from
    the rate formulas.

    ``angles``, ``rates``: shape (N, 3), the path (φ, θ, ψ)(t) and its derivative.  Ṙ
    comes from the complex step ``Ṙ = Im R(a + i h ȧ) / h`` (Squire & Trapp 1998), exact
    to rounding for any small h since no difference is taken.  Returns ``space`` =
    vee(Ṙ Rᵀ) and ``body`` = vee(Rᵀ Ṙ), shape (N, 3), and ``asymmetry``, shape (N,):
    max |W + Wᵀ| of W = Ṙ Rᵀ, which vanishes because R Rᵀ = 1.
    """
    R, Rdot = euler_matrices_and_rate(angles, rates, convention, step)
    W = Rdot @ np.swapaxes(R, -1, -2)
    return {"space": vee(W), "body": vee(np.swapaxes(R, -1, -2) @ Rdot),
            "asymmetry": np.max(np.abs(W + np.swapaxes(W, -1, -2)), axis=(-2, -1))}


def euler_construction(phi: float, theta: float, psi: float, convention: str = "zxz",
                       n_arc: int = 40) -> dict[str, np.ndarray]:
    """The picture of Euler angles: space axes, line of nodes, body axes and the three
    angle arcs, as points in space (for a figure).

    The line of nodes e_N is the intermediate x axis (z-x-z) or y axis (z-y-z) after the
    turn by φ about z.  Arcs (n_arc, 3): φ in the xy plane from the space axis to e_N;
    θ from e_z to the body axis e_3 about e_N; ψ in the body plane from e_N to the
    body axis it becomes (x' or y').
    """
    k = 0 if _convention(convention) == "zxz" else 1
    R = euler_matrix(phi, theta, psi, convention)
    Rf = rot_z(phi)
    node = Rf[:, k]
    s = np.linspace(0.0, 1.0, n_arc)[:, None]

    def arc(start, axis, angle):
        return rotate_about(start, axis, s * angle)

    ez = np.array([0.0, 0.0, 1.0])
    return {"space_axes": np.eye(3), "body_axes": R, "node": node,
            "arc_phi": arc(np.eye(3)[k], ez, phi),
            "arc_theta": arc(ez, node, theta),
            "arc_psi": arc(node, R[:, 2], psi)}


def rotate_about(r, n, angle) -> np.ndarray:
    """Active rotation of r about the unit vector n by ``angle`` (broadcasts; angle may
    be an array of shape (..., 1)): Rodrigues' formula, Goldstein (4.62) with Φ -> −Φ."""
    r, n = np.asarray(r, dtype=float), np.asarray(n, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    return r * c + n * np.sum(n * r, axis=-1, keepdims=True) * (1 - c) + np.cross(n, r) * s


# ---------------------------------------------------------------- axis and angle
def rotation_formula(r, n, Phi: float) -> np.ndarray:
    """Goldstein's rotation formula (4.62), passive:
    ``r' = r cos Φ + n (n·r)(1 − cos Φ) + (r × n) sin Φ``.

    r' are the components of the vector r in axes turned by +Φ about the unit vector n
    (equivalently, r turned by −Φ).  r: shape (..., 3); n: shape (3,), unit.
    """
    r, n = np.asarray(r, dtype=float), np.asarray(n, dtype=float)
    c, s = math.cos(Phi), math.sin(Phi)
    return (r * c + np.multiply.outer(r @ n, n) * (1.0 - c) + np.cross(r, n) * s)


def rotation_formula_matrix(n, Phi: float) -> np.ndarray:
    """Goldstein's passive matrix A(n, Φ) built from (4.62): column j is the formula applied
    to the basis vector e_j.  ``A = R(n, Φ)^T``."""
    return rotation_formula(np.eye(3), n, Phi).T


def expm_by_diagonalization(M) -> np.ndarray:
    """exp(M) of a real diagonalizable 3×3 matrix as V diag(e^λ) V⁻¹ (numpy ``eig``): a
    matrix exponential that knows nothing of Rodrigues' formula (the independent check of
    :func:`rotation_formula_matrix`; ``scipy.linalg.expm`` agrees, see the tests)."""
    lam, V = np.linalg.eig(np.asarray(M, dtype=float))
    return (V @ np.diag(np.exp(lam)) @ np.linalg.inv(V)).real


def axis_angle_from_matrix(R) -> tuple[np.ndarray, float]:
    """(n, Φ) with Φ in [0, π] of an active rotation matrix ``R = R(n, Φ)``.

    cos Φ = (tr R − 1)/2 and the antisymmetric part ½(R − Rᵀ) = sin Φ [n]× give Φ by
    atan2 and, for Φ < 2π/3, n.  Nearer π the antisymmetric part fades and n comes from
    the symmetric part ½(R + Rᵀ) − cos Φ·1 = (1 − cos Φ) n nᵀ, its sign from sin Φ n.
    At Φ = π, n and −n are the same rotation; the one with its largest component
    positive is returned.  Φ = 0 has no axis: n = e_z.
    """
    R = np.asarray(R, dtype=float)
    c = 0.5 * (np.trace(R) - 1.0)
    v = vee(R)
    s = float(np.linalg.norm(v))
    Phi = math.atan2(s, c)
    if s == 0.0 and c > 0:
        return np.array([0.0, 0.0, 1.0]), 0.0
    if c > -0.5:
        return v / s, Phi
    B = 0.5 * (R + R.T) - c * np.eye(3)
    k = int(np.argmax(np.diag(B)))
    n = B[:, k] / math.sqrt(B[k, k] * (1.0 - c))
    if float(n @ v) < 0 or (float(n @ v) == 0 and n[np.argmax(np.abs(n))] < 0):
        n = -n
    return n / np.linalg.norm(n), Phi


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
    """Cross-product matrix [v]×: skew(v) @ u = v × u; ``v`` of shape (..., 3) gives the
    matrices of shape (..., 3, 3)."""
    v = np.asarray(v, dtype=float)
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    zero = np.zeros_like(x)
    return np.stack([np.stack([zero, -z, y], -1), np.stack([z, zero, -x], -1),
                     np.stack([-y, x, zero], -1)], -2)


def su2_from_cayley_klein(a: complex, b: complex) -> np.ndarray:
    """``U = [[a, b], [−b̄, ā]]`` (Cayley–Klein parameters, |a|² + |b|² = 1), shape (2, 2)."""
    a, b = complex(a), complex(b)
    return np.array([[a, b], [-b.conjugate(), a.conjugate()]])


def su2_from_axis_angle(axis, angle: float) -> np.ndarray:
    """``U = exp(−i α n·σ/2)``: the SU(2) element whose R(U) turns by α about n."""
    return su2_from_quat(quat_from_axis_angle(axis, angle))


def su2_exp(axis, angle: float) -> np.ndarray:
    """``exp(−i α n·σ/2)`` by the eigenvectors of the Hermitian n·σ (eigenvalues ±1), shape
    (2, 2): a matrix exponential that knows nothing of the closed form
    cos(α/2) 1 − i sin(α/2) n·σ (the SU(2) map of lecture notes (9.4)–(9.8); Goldstein §4.5)
    it checks."""
    n = np.asarray(axis, dtype=float)
    n = n / np.linalg.norm(n)
    lam, V = np.linalg.eigh(np.einsum("k,kab->ab", n, PAULI))
    return V @ np.diag(np.exp(-0.5j * angle * lam)) @ V.conj().T


def so3_from_su2_many(U) -> np.ndarray:
    """:func:`so3_from_su2` for many elements at once: U shape (..., 2, 2) -> R shape
    (..., 3, 3), ``R_ij = ½ Re tr(σ_i U σ_j U†)``."""
    U = np.asarray(U, dtype=complex)
    Ud = np.conj(np.swapaxes(U, -1, -2))
    return 0.5 * np.einsum("iab,...bc,jcd,...da->...ij", PAULI, U, PAULI, Ud).real


def su2_elementary(axis: str, angle) -> np.ndarray:
    """``U_k(α) = cos(α/2) 1 − i sin(α/2) σ_k`` for k = "x", "y", "z", written out;
    broadcasts over ``angle``, shape (..., 2, 2).  R(U_k(α)) is :func:`rot_x` (``rot_y``,
    ``rot_z``) of α."""
    a = 0.5 * np.asarray(angle, dtype=float)
    c, s = np.cos(a), np.sin(a)
    zero = np.zeros_like(c)
    if axis == "x":
        rows = [[c + 0j, -1j * s], [-1j * s, c + 0j]]
    elif axis == "y":
        rows = [[c + 0j, -s + 0j], [s + 0j, c + 0j]]
    elif axis == "z":
        rows = [[c - 1j * s, zero + 0j], [zero + 0j, c + 1j * s]]
    else:
        raise ValueError(f"axis: expected 'x', 'y' or 'z', got {axis!r}")
    return np.moveaxis(np.array(rows, dtype=complex), (0, 1), (-2, -1))


def su2_euler(angles, convention: str = "zxz") -> np.ndarray:
    """The SU(2) form of the Euler angles (lecture notes (9.18)): ``U = U_z(φ) U_x(θ) U_z(ψ)``
    (z-x-z) or ``U_z(φ) U_y(θ) U_z(ψ)`` (z-y-z), shape (..., 2, 2) for ``angles`` (..., 3);
    ``so3_from_su2(U)`` is :func:`euler_matrix`.  Each factor is 4π-periodic: φ + 2π
    gives −U (the same R)."""
    a = np.asarray(angles, dtype=float)
    middle = {"zxz": "x", "zyz": "y"}[_convention(convention)]
    return (su2_elementary("z", a[..., 0]) @ su2_elementary(middle, a[..., 1])
            @ su2_elementary("z", a[..., 2]))


def su2_euler_cayley_klein(phi, theta, psi, convention: str = "zxz") -> tuple:
    """The Cayley–Klein parameters of :func:`su2_euler`, multiplied out:
    ``a = cos(θ/2) e^{−i(φ+ψ)/2}`` and ``b = −i sin(θ/2) e^{−i(φ−ψ)/2}`` (z-x-z) or
    ``b = −sin(θ/2) e^{−i(φ−ψ)/2}`` (z-y-z), with U = [[a, b], [−b̄, ā]]; broadcasts."""
    phi, theta, psi = (np.asarray(x, dtype=float) for x in (phi, theta, psi))
    a = np.cos(0.5 * theta) * np.exp(-0.5j * (phi + psi))
    b = np.sin(0.5 * theta) * np.exp(-0.5j * (phi - psi))
    return a, (-1j * b if _convention(convention) == "zxz" else -b)


def su2_axis_angle(U) -> tuple[np.ndarray, float]:
    """(m, α) with ``U = cos(α/2) 1 − i sin(α/2) m·σ`` (Euler's theorem in SU(2); the
    SU(2) map of lecture notes (9.4)–(9.8)), α in [0, 2π]: α > π when ½ tr U < 0, and −U
    is then the turn by 2π − α about −m.  α = 0 has no axis: m = e_z."""
    q = su2_to_quat(U)
    v = float(np.linalg.norm(q[1:]))
    if v == 0.0:
        return np.array([0.0, 0.0, 1.0]), 0.0 if q[0] > 0 else 2.0 * math.pi
    return q[1:] / v, 2.0 * math.atan2(v, float(q[0]))


# ------------------------------------------------- stereographic projection, Möbius maps
NORTH_POLE = np.array([0.0, 0.0, 1.0])


def stereographic(x, *, orientation: int = -1) -> np.ndarray:
    """Projection of unit vectors x (..., 3) from the north pole onto the equatorial plane:
    ``ζ = (x + orientation·i y)/(1 − z)``, complex, shape (...,); the pole goes to ∞.

    ``orientation = −1`` (the default, the plane seen from below) is the spinor ratio
    ξ1/ξ2 for which the Möbius map of U is R(U); ``+1`` is the usual Riemann-sphere
    coordinate, for which it is R(Ū) (module docstring).  On the upper half the equal
    form ``(1 + z)/(x − orientation·i y)`` is used: 1 − z cancels near the pole.
    """
    x = np.asarray(x, dtype=float)
    plane = x[..., 0] + orientation * 1j * x[..., 1]
    upper = x[..., 2] > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        zeta = np.where(upper, (1.0 + x[..., 2]) / np.conj(plane), plane / (1.0 - x[..., 2]))
    return np.where(upper & (plane == 0), complex(np.inf, 0.0), zeta)


def inverse_stereographic(zeta, *, orientation: int = -1) -> np.ndarray:
    """The point on the unit sphere projecting to ζ (complex, ∞ allowed), shape (..., 3).

    Written in w = 1/ζ where |ζ| > 1, so large ζ (points near the pole) keep full
    relative accuracy and ζ = ∞ is the pole itself.
    """
    zeta = np.asarray(zeta, dtype=complex)
    big = ~(np.abs(zeta) <= 1.0)  # also ∞ and nan
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(big, 1.0 / np.where(big, zeta, 1.0), 0.0)
    w = np.where(np.isinf(zeta), 0.0, w)
    small = np.where(big, 0.0, zeta)
    w2, z2 = np.abs(w) ** 2, np.abs(small) ** 2
    # x + orientation·i y = 2 ζ/(1 + |ζ|²) = 2 w̄/(1 + |w|²);  z = (|ζ|² − 1)/(|ζ|² + 1)
    plane = np.where(big, 2.0 * np.conj(w) / (1.0 + w2), 2.0 * small / (1.0 + z2))
    z = np.where(big, (1.0 - w2) / (1.0 + w2), (z2 - 1.0) / (z2 + 1.0))
    return np.stack([plane.real, orientation * plane.imag, z], axis=-1)


def mobius_isometry_defect(V, zeta) -> float:
    """max | |f′(ζ)| (1 + |ζ|²)/(1 + |f(ζ)|²) − 1 | over the finite ζ, for f the Möbius map of
    V (det V = 1, f′ = 1/(V21 ζ + V22)²): zero where f keeps the sphere's distances,
    dℓ = 2|dζ|/(1 + |ζ|²) (textbook ex. 4.11(d)), as it does for V in SU(2); the pole of f
    is left out."""
    V = np.asarray(V, dtype=complex)
    z = np.asarray(zeta, dtype=complex)
    z = z[np.isfinite(z)]
    den = V[1, 0] * z + V[1, 1]
    keep = np.abs(den) > 1e-8 * (1.0 + np.abs(z))
    z, den = z[keep], den[keep]
    image = (V[0, 0] * z + V[0, 1]) / den
    ratio = np.abs(np.linalg.det(V) / den**2) * (1.0 + np.abs(z) ** 2) / (1.0 + np.abs(image) ** 2)
    return float(np.max(np.abs(ratio - 1.0)))


def mobius(U, zeta) -> np.ndarray:
    """The Möbius map ``ζ -> (U11 ζ + U12)/(U21 ζ + U22)`` on the extended plane (∞ allowed):
    ∞ -> U11/U21, −U22/U21 -> ∞."""
    U = np.asarray(U, dtype=complex)
    zeta = np.asarray(zeta, dtype=complex)
    inf = np.isinf(zeta)
    z = np.where(inf, 0.0, zeta)
    num = U[0, 0] * z + U[0, 1]
    den = U[1, 0] * z + U[1, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        image = num / den
        at_inf = U[0, 0] / U[1, 0] if U[1, 0] != 0 else complex(np.inf, 0.0)
    image = np.where(den == 0.0, complex(np.inf, 0.0), image)
    return np.where(inf, at_inf, image)


def so3_from_mobius(U, *, orientation: int = -1) -> np.ndarray:
    """The rotation a Möbius map makes of the sphere, read off the map alone: column j is
    the image of the axis tip e_j (projected, mapped, projected back).  With the default
    orientation this is R(U) of :func:`so3_from_su2`."""
    tips = stereographic(np.eye(3), orientation=orientation)
    return inverse_stereographic(mobius(U, tips), orientation=orientation).T


def stereographic_derivative(x, t, *, step: float = 1e-20) -> np.ndarray:
    """dζ/ds of ``ζ = (x − i y)/(1 − z)`` at unit vectors x (..., 3) along unit tangents t
    (..., 3), complex, shape (...,): the complex step (Squire & Trapp 1998) on the real
    and imaginary parts u = x/(1 − z), v = −y/(1 − z), exact to rounding.  Its modulus
    is the conformal factor 1/(1 − z) in every direction t ⊥ x."""
    x, t = np.asarray(x, dtype=float), np.asarray(t, dtype=float)
    p = x + 1j * step * t
    den = 1.0 - p[..., 2]
    return (p[..., 0] / den).imag / step - 1j * (p[..., 1] / den).imag / step


def tangent_frame(x) -> tuple[np.ndarray, np.ndarray]:
    """Two orthonormal tangents of the unit sphere at x (..., 3), off the poles: e_φ
    (along the circle of latitude, eastward) and e_θ = e_φ × x (southward).  Shapes
    (..., 3)."""
    x = np.asarray(x, dtype=float)
    rho = np.hypot(x[..., 0], x[..., 1])
    east = np.stack([-x[..., 1], x[..., 0], np.zeros_like(rho)], axis=-1) / rho[..., None]
    return east, np.cross(east, x)


def fibonacci_sphere(n: int) -> np.ndarray:
    """n nearly uniform unit vectors, shape (n, 3): the golden-angle spiral with
    z_k = 1 − (2k + 1)/n, which never lands on either pole."""
    k = np.arange(n)
    z = 1.0 - (2.0 * k + 1.0) / n
    r = np.sqrt(1.0 - z * z)
    phi = k * math.pi * (3.0 - math.sqrt(5.0))
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


def latitude_circle(z: float, n: int = 181) -> np.ndarray:
    """The circle of latitude at height z on the unit sphere, shape (n, 3), closed."""
    t = np.linspace(0.0, 2.0 * math.pi, n)
    r = math.sqrt(1.0 - z * z)
    return np.stack([r * np.cos(t), r * np.sin(t), np.full_like(t, z)], axis=-1)
