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
