"""Rotations: Euler angles (z-x-z), ω from Euler-angle rates (10.20), SU(2) -> SO(3), quaternions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from reportgen.core import rotations as rot

RNG = np.random.default_rng(7)
ANGLES = [(0.3, 1.1, -0.7), (2.5, 0.2, 1.9), (-1.2, 2.9, 0.4)]


def random_quat():
    q = RNG.normal(size=4)
    return q / np.linalg.norm(q)


@pytest.mark.parametrize("angles", ANGLES)
def test_euler_matrix_is_rotation_and_round_trips(angles):
    R = rot.euler_matrix(*angles)
    assert np.allclose(R @ R.T, np.eye(3), atol=1e-14)
    assert math.isclose(np.linalg.det(R), 1.0, abs_tol=1e-14)
    assert np.allclose(rot.euler_from_matrix(R), angles, atol=1e-12)
    # Goldstein (4.46): A = R^T, third row of A = body z axis in space = (sinθ sinφ, −sinθ cosφ, cosθ)
    phi, theta, _ = angles
    assert np.allclose(R[:, 2], [math.sin(theta) * math.sin(phi),
                                 -math.sin(theta) * math.cos(phi), math.cos(theta)], atol=1e-14)


@pytest.mark.parametrize("angles", ANGLES)
def test_quaternion_matrix_euler_agree(angles):
    q = rot.euler_to_quat(*angles)
    assert np.allclose(rot.quat_to_matrix(q), rot.euler_matrix(*angles), atol=1e-14)
    assert np.allclose(rot.quat_to_euler(q), angles, atol=1e-12)
    q2 = rot.matrix_to_quat(rot.euler_matrix(*angles))
    assert np.allclose(q2, q * np.sign(q[0]), atol=1e-14)


def test_quaternion_product_is_matrix_product():
    for _ in range(5):
        p, q = random_quat(), random_quat()
        assert np.allclose(rot.quat_to_matrix(rot.quat_multiply(p, q)),
                           rot.quat_to_matrix(p) @ rot.quat_to_matrix(q), atol=1e-14)
        v = RNG.normal(size=3)
        qv = rot.quat_multiply(rot.quat_multiply(q, np.concatenate([[0.0], v])),
                               rot.quat_conjugate(q))
        assert np.allclose(qv[1:], rot.quat_rotate(q, v), atol=1e-14)


def test_matrix_to_quat_all_pivots():
    # rotations by ~π about each axis exercise Shepperd's non-trace branches
    for axis in np.eye(3):
        q = rot.quat_from_axis_angle(axis + 0.01, 3.1)
        R = rot.quat_to_matrix(q)
        assert np.allclose(rot.quat_to_matrix(rot.matrix_to_quat(R)), R, atol=1e-14)


def test_su2_double_cover_and_homomorphism():
    for _ in range(5):
        q1, q2 = random_quat(), random_quat()
        U1, U2 = rot.su2_from_quat(q1), rot.su2_from_quat(q2)
        assert np.allclose(U1 @ U1.conj().T, np.eye(2), atol=1e-14)
        assert math.isclose(np.linalg.det(U1).real, 1.0, abs_tol=1e-14)
        # (9.4)–(9.16): R(U) agrees with the quaternion route, U and −U give the same R
        assert np.allclose(rot.so3_from_su2(U1), rot.quat_to_matrix(q1), atol=1e-14)
        assert np.allclose(rot.so3_from_su2(-U1), rot.so3_from_su2(U1), atol=1e-14)
        assert np.allclose(rot.so3_from_su2(U1 @ U2), rot.so3_from_su2(U1) @ rot.so3_from_su2(U2),
                           atol=1e-14)
        assert np.allclose(rot.su2_to_quat(U1), q1, atol=1e-14)
    # a 2π rotation is −1 in SU(2) but the identity in SO(3)
    U = rot.su2_from_quat(rot.quat_from_axis_angle([0, 0, 1], 2 * math.pi))
    assert np.allclose(U, -np.eye(2), atol=1e-14)
    assert np.allclose(rot.so3_from_su2(U), np.eye(3), atol=1e-14)


def test_omega_from_euler_rates_against_differentiated_matrix():
    """(10.20) / Landau (35.1) against skew(Rᵀ Ṙ) from a central difference of R(t)."""
    a0, rates = np.array([0.4, 0.9, -1.3]), np.array([0.7, -0.3, 2.1])
    h = 1e-6
    R = rot.euler_matrix(*a0)
    dR = (rot.euler_matrix(*(a0 + h * rates)) - rot.euler_matrix(*(a0 - h * rates))) / (2 * h)
    W_body = R.T @ dR
    body = np.array([W_body[2, 1], W_body[0, 2], W_body[1, 0]])
    W_space = dR @ R.T
    space = np.array([W_space[2, 1], W_space[0, 2], W_space[1, 0]])
    assert np.allclose(rot.omega_from_euler_rates(*a0, *rates), body, atol=1e-8)
    assert np.allclose(rot.omega_from_euler_rates(*a0, *rates, frame="space"), space, atol=1e-8)
    assert np.allclose(R @ body, space, atol=1e-8)


# ------------------------------------------------------------ axis and angle (ex. 4.5)
def passive_about_z(Phi):
    """Goldstein §4.4, the first factor D of (4.46): the axes turned by Φ about z (passive)."""
    c, s = math.cos(Phi), math.sin(Phi)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def random_axis():
    n = RNG.normal(size=3)
    return n / np.linalg.norm(n)


def test_rotation_formula_is_passive_and_matches_expm_and_quaternions():
    from scipy.linalg import expm

    # about z, (4.62) is Goldstein's D (first factor of 4.46): components in axes turned by +Φ
    assert np.allclose(rot.rotation_formula_matrix([0.0, 0.0, 1.0], 0.7), passive_about_z(0.7),
                       atol=1e-15)
    for _ in range(5):
        n, Phi = random_axis(), RNG.uniform(0.0, math.pi)
        A = rot.rotation_formula_matrix(n, Phi)
        assert np.allclose(A, expm(-Phi * rot.skew(n)), atol=1e-14)
        assert np.allclose(A, rot.expm_by_diagonalization(-Phi * rot.skew(n)), atol=1e-14)
        assert np.allclose(A.T, rot.quat_to_matrix(rot.quat_from_axis_angle(n, Phi)), atol=1e-14)
        r = RNG.normal(size=3)
        assert np.allclose(rot.rotation_formula(r, n, Phi), A @ r, atol=1e-14)
        # the active rotation (Rodrigues) is the formula with −Φ
        assert np.allclose(rot.rotate_about(r, n, Phi), A.T @ r, atol=1e-14)


def test_turn_about_the_body_diagonal_permutes_the_axes():
    """2π/3 about (1, 1, 1)/√3 sends x -> y -> z -> x (active), so the passive (4.62) gives
    e_x the components (0, 0, 1): the turned axes are x′ = e_y, y′ = e_z, z′ = e_x."""
    A = rot.rotation_formula_matrix(np.ones(3) / math.sqrt(3), 2 * math.pi / 3)
    assert np.allclose(A, [[0, 1, 0], [0, 0, 1], [1, 0, 0]], atol=1e-15)


@pytest.mark.parametrize("Phi", [1e-7, 0.4, 2.0, 2.2, 3.0, math.pi - 1e-9, math.pi])
def test_axis_and_angle_recovered_from_the_matrix(Phi):
    for _ in range(4):
        n = random_axis()
        R = rot.quat_to_matrix(rot.quat_from_axis_angle(n, Phi))
        n_back, Phi_back = rot.axis_angle_from_matrix(R)
        assert abs(Phi_back - Phi) < 2e-15 + 1e-15 * Phi
        if Phi == math.pi:
            n_back *= np.sign(n_back @ n)  # n and −n are the same half turn
        # near π the antisymmetric part is ~sin Φ ~ 1e-9: only the symmetric part keeps n
        # to 1e-15 there (v/|v| would be off by ~1e-7); near 0 the axis is ill-defined
        # in proportion to 1/Φ
        assert np.allclose(n_back, n, atol=1e-15 / min(Phi, 1.0) + 2e-16), (Phi, n_back - n)


# ------------------------------------------------------ Euler angles z-y-z (ex. 4.7, 4.8)
def goldstein_446(phi, theta, psi):
    """Goldstein 3rd ed. eq. (4.46), element by element (the passive A)."""
    cf, sf, ct, st, cp, sp = (math.cos(phi), math.sin(phi), math.cos(theta), math.sin(theta),
                              math.cos(psi), math.sin(psi))
    return np.array([[cp * cf - ct * sf * sp, cp * sf + ct * cf * sp, sp * st],
                     [-sp * cf - ct * sf * cp, -sp * sf + ct * cf * cp, cp * st],
                     [st * sf, -st * cf, ct]])


@pytest.mark.parametrize("angles", ANGLES)
def test_zxz_and_zyz_matrices(angles):
    phi, theta, psi = angles
    assert np.allclose(rot.euler_matrix(*angles).T, goldstein_446(*angles), atol=1e-15)
    assert np.allclose(rot.euler_matrix_elements(*angles), goldstein_446(*angles), atol=1e-15)
    zyz = rot.euler_matrix(*angles, convention="zyz")
    # the y-convention: z-x-z angles φ + π/2, θ, ψ − π/2 (R_y(θ) = R_z(π/2) R_x(θ) R_z(−π/2))
    assert np.allclose(zyz, rot.euler_matrix(phi + math.pi / 2, theta, psi - math.pi / 2),
                       atol=1e-15)
    assert np.allclose(zyz.T, goldstein_446(phi + math.pi / 2, theta, psi - math.pi / 2),
                       atol=1e-15)
    assert np.allclose(rot.euler_matrix_elements(*angles, convention="zyz"), zyz.T, atol=1e-15)
    # in z-y-z, (θ, φ) are the polar angles of the body z axis (Goldstein, y-convention)
    assert np.allclose(zyz[:, 2], [math.sin(theta) * math.cos(phi),
                                   math.sin(theta) * math.sin(phi), math.cos(theta)], atol=1e-15)
    # and the conversion functions are each other's inverse
    assert np.allclose(rot.zxz_to_zyz(*rot.zyz_to_zxz(*angles)), angles, atol=1e-15)
    for conv in ("zxz", "zyz"):
        assert np.allclose(rot.euler_matrices(np.array([angles, angles]), conv)[1],
                           rot.euler_matrix(*angles, convention=conv), atol=1e-15)


@pytest.mark.parametrize("convention", ["zxz", "zyz"])
def test_omega_both_conventions_against_central_differences(convention):
    """ω from rates against skew(Rᵀ Ṙ) / skew(Ṙ Rᵀ) with Ṙ by a central difference
    (independent of both the formulas and the complex step)."""
    a0, rates = np.array([0.4, 0.9, -1.3]), np.array([0.7, -0.3, 2.1])
    h = 1e-6
    R = rot.euler_matrix(*a0, convention=convention)
    dR = (rot.euler_matrix(*(a0 + h * rates), convention=convention)
          - rot.euler_matrix(*(a0 - h * rates), convention=convention)) / (2 * h)
    body, space = rot.vee(R.T @ dR), rot.vee(dR @ R.T)
    assert np.allclose(rot.omega_from_euler_rates(*a0, *rates, convention=convention), body,
                       atol=1e-8)
    assert np.allclose(rot.omega_from_euler_rates(*a0, *rates, frame="space",
                                                  convention=convention), space, atol=1e-8)
    step = rot.omega_by_complex_step(a0[None], rates[None], convention)
    assert np.allclose(step["body"][0], body, atol=1e-8)
    assert np.allclose(step["space"][0], space, atol=1e-8)
    # the complex step has no cancellation: formula and Ṙ agree to rounding
    assert np.allclose(step["body"][0], rot.omega_from_euler_rates(
        *a0, *rates, convention=convention), atol=1e-15)
    assert step["asymmetry"][0] < 1e-15


def test_omega_is_the_same_in_both_conventions():
    a, rates = np.array([0.3, 1.2, -0.4]), np.array([0.5, 0.2, -1.1])
    other = rot.zyz_to_zxz(*a)
    for frame in ("body", "space"):
        assert np.allclose(rot.omega_from_euler_rates(*a, *rates, frame=frame, convention="zyz"),
                           rot.omega_from_euler_rates(*other, *rates, frame=frame),
                           atol=1e-15)
    # body ω3 = φ̇ cos θ + ψ̇ in both (the body z axis is the same)
    assert math.isclose(rot.omega_from_euler_rates(*a, *rates, convention="zyz")[2],
                        rates[0] * math.cos(a[1]) + rates[2], rel_tol=1e-15)


def test_euler_construction_line_of_nodes():
    phi, theta, psi = 0.5, 0.8, 0.3
    for conv, k in (("zxz", 0), ("zyz", 1)):
        c = rot.euler_construction(phi, theta, psi, conv)
        R = rot.euler_matrix(phi, theta, psi, conv)
        # the line of nodes lies in both the space xy plane and the body x′y′ plane
        assert abs(c["node"][2]) < 1e-16 and abs(c["node"] @ R[:, 2]) < 1e-15
        # the arcs end where the angles say: φ arc at N, θ arc at z′, ψ arc at x′ / y′
        assert np.allclose(c["arc_phi"][-1], c["node"], atol=1e-15)
        assert np.allclose(c["arc_theta"][-1], R[:, 2], atol=1e-15)
        assert np.allclose(c["arc_psi"][-1], R[:, k], atol=1e-15)


# ------------------------------------------------ stereographic projection (ex. 4.11)
def random_su2():
    return rot.su2_from_quat(random_quat())


def test_stereographic_projection_closed_forms():
    south, north = np.array([0.0, 0.0, -1.0]), np.array([0.0, 0.0, 1.0])
    assert rot.stereographic(south) == 0
    assert np.isinf(rot.stereographic(north))
    assert np.allclose(rot.inverse_stereographic(np.inf), north, atol=0)
    # the equator is the unit circle; ζ = (x − iy)/(1 − z) (plane seen from below)
    t = np.linspace(0, 2 * np.pi, 9)
    eq = np.stack([np.cos(t), np.sin(t), 0 * t], axis=-1)
    assert np.allclose(rot.stereographic(eq), np.exp(-1j * t), atol=1e-15)
    assert np.allclose(rot.stereographic(eq, orientation=1), np.exp(1j * t), atol=1e-15)
    x = rot.fibonacci_sphere(400)
    assert np.allclose(np.linalg.norm(x, axis=1), 1.0, atol=1e-15)
    assert np.all(np.abs(x[:, 2]) < 1)
    for o in (-1, 1):
        assert np.allclose(rot.inverse_stereographic(rot.stereographic(x, orientation=o),
                                                     orientation=o), x, atol=1e-15)
    # near the pole: |ζ| ~ 1e200 would overflow |ζ|² in the naive formulas
    assert np.allclose(rot.inverse_stereographic(1e200 + 1e200j), north, atol=1e-16)
    near = np.array([1e-9, 0.0, math.sqrt(1 - 1e-18)])
    assert np.allclose(rot.inverse_stereographic(rot.stereographic(near)), near, atol=1e-15)


def test_mobius_of_a_turn_about_z():
    """U = exp(−iασz/2) = diag(e^{−iα/2}, e^{iα/2}) turns by +α about z; with
    ζ = (x − iy)/(1 − z) that multiplies ζ by e^{−iα}: (aζ + b)/(−b̄ζ + ā) = e^{−iα} ζ."""
    alpha = 0.9
    U = rot.su2_from_axis_angle([0, 0, 1], alpha)
    assert np.allclose(U, np.diag([np.exp(-0.5j * alpha), np.exp(0.5j * alpha)]), atol=1e-15)
    zeta = np.array([0.3 + 0.2j, -1.5 + 0.1j])
    assert np.allclose(rot.mobius(U, zeta), np.exp(-1j * alpha) * zeta, atol=1e-15)
    assert np.allclose(rot.so3_from_su2(U), rot.rot_z(alpha), atol=1e-15)


def test_mobius_map_is_the_rotation_R_not_its_transpose():
    x = rot.fibonacci_sphere(300)
    for _ in range(5):
        U = random_su2()
        R = rot.so3_from_su2(U)
        image = rot.inverse_stereographic(rot.mobius(U, rot.stereographic(x)))
        assert np.max(np.linalg.norm(image - x @ R.T, axis=1)) < 1e-13
        # the usual orientation of the plane gives R(Ū) instead
        std = rot.inverse_stereographic(rot.mobius(U, rot.stereographic(x, orientation=1)),
                                        orientation=1)
        assert np.max(np.linalg.norm(std - x @ rot.so3_from_su2(U.conj()).T, axis=1)) < 1e-13
        # and the transpose is far off for a generic U (not a half turn)
        assert np.max(np.linalg.norm(image - x @ R, axis=1)) > 0.1
        assert np.max(np.linalg.norm(std - x @ R, axis=1)) > 0.1
        # R read off the Möbius map alone (images of e_x, e_y and e_z ↦ ∞ ↦ a/(−b̄))
        assert np.allclose(rot.so3_from_mobius(U), R, atol=1e-14)
        # double cover: −U is the same Möbius map and the same rotation
        assert np.allclose(rot.mobius(-U, rot.stereographic(x)),
                           rot.mobius(U, rot.stereographic(x)), rtol=1e-14)
    # with the usual orientation, an axis in the x–z plane makes R(Ū) = Rᵀ
    U = rot.su2_from_axis_angle([0.6, 0.0, 0.8], 1.1)
    assert np.allclose(rot.so3_from_su2(U.conj()), rot.so3_from_su2(U).T, atol=1e-15)


def test_mobius_maps_compose_like_su2_and_not_like_transposes():
    """U -> Möbius map keeps the order of products; R -> Rᵀ reverses it, which is why no
    orientation of the plane can make the Möbius map Rᵀ for every U."""
    U1, U2 = random_su2(), random_su2()
    zeta = rot.stereographic(rot.fibonacci_sphere(50))
    assert np.allclose(rot.mobius(U1 @ U2, zeta), rot.mobius(U1, rot.mobius(U2, zeta)),
                       rtol=1e-12)
    R1, R2 = rot.so3_from_su2(U1), rot.so3_from_su2(U2)
    assert np.allclose(rot.so3_from_su2(U1 @ U2).T, R2.T @ R1.T, atol=1e-14)
    assert not np.allclose(rot.so3_from_su2(U1 @ U2).T, R1.T @ R2.T, atol=1e-3)


def test_cayley_klein_element():
    U = rot.su2_from_cayley_klein(0.8, 0.36 + 0.48j)
    assert np.allclose(U @ U.conj().T, np.eye(2), atol=1e-15)
    assert math.isclose(np.linalg.det(U).real, 1.0, abs_tol=1e-15)
    # U = w − i(x σx + y σy + z σz): w = Re a, x = −Im b, y = −Re b, z = −Im a
    assert np.allclose(rot.su2_to_quat(U), [0.8, -0.48, -0.36, 0.0], atol=1e-15)
    assert np.allclose(rot.mobius(U, np.inf), 0.8 / -(0.36 - 0.48j), atol=1e-15)
