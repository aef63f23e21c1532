"""SU(2) → SO(3) in the lecture notes' own terms, notes §9 (9.4)–(9.16) (issue 42): the
parametrization u(α, β, γ), M(r) with det M = 1 − r², M → uMu†, and the special cases in
which u turns by twice its angle, each against an independent computation; and the two
places where the notes as printed differ from the map ((9.10)'s last entry, the case
(9.12))."""

from __future__ import annotations

import math

import numpy as np
import pytest

from reportgen.core import rotations
from reportgen.kinds.rotation.notes_su2 import notes_su2, notes_u


@pytest.mark.parametrize("angles", [(0.3, 0.7, 1.1), (1.2, -2.0, 0.4), (0.0, 0.5, 0.0),
                                    (math.pi / 2, 0.0, -2.3)])
def test_the_angles_read_off_u_and_every_check_at_rounding(angles):
    values, errors = notes_su2(notes_u(*angles))
    alpha, beta, gamma = angles
    assert values["alpha"] == pytest.approx(alpha, abs=1e-12)
    if 0 < alpha:
        assert values["gamma"] == pytest.approx(gamma, abs=1e-12)
    if alpha < math.pi / 2:
        assert values["beta"] == pytest.approx(beta, abs=1e-12)
    assert max(errors.values()) < 1e-14, errors


def test_u_is_unitary_and_r_of_u_is_the_axis_angle_turn_it_encodes():
    """An independent route: u of (9.4) is U(n, Φ) = cos(Φ/2) − i sin(Φ/2) n·σ for the
    n, Φ of its quaternion, and R(u) is Rodrigues' R(n, Φ)."""
    u = notes_u(0.8, 0.3, -1.4)
    assert np.allclose(u @ u.conj().T, np.eye(2), atol=1e-15)
    assert abs(np.linalg.det(u) - 1) < 1e-15
    n, Phi = rotations.su2_axis_angle(u)
    c, s = math.cos(Phi), math.sin(Phi)
    rodrigues = c * np.eye(3) + (1 - c) * np.outer(n, n) + s * rotations.skew(n)
    assert np.max(np.abs(rotations.so3_from_su2(u) - rodrigues)) < 1e-14


def test_the_notes_as_printed():
    """(9.10) ends in sin 2α where the map gives cos 2α; α = π/2, β = 0 of (9.12) is a
    half-turn about an axis in the x-y plane for every γ, not R₃(2γ)."""
    for gamma in (-2.0, 0.3, 1.0):
        values, _ = notes_su2(notes_u(0.6, 0.2, gamma))
        assert values["printed_9_10_entry"] == pytest.approx(abs(math.sin(1.2) - math.cos(1.2)))
        assert values["case_9_12_trace"] == pytest.approx(-1.0, abs=1e-14)
        assert abs(values["case_9_12_axis"][2]) < 1e-14
        assert values["case_9_12_vs_third_axis"] > 1.0  # z goes to −z, R₃ keeps it


def test_a_mobius_map_keeps_the_spheres_distances_exactly_when_it_is_unitary():
    """Textbook ex. 4.11(d): f keeps dℓ = 2|dζ|/(1 + |ζ|²) for U in SU(2); the boost
    diag(2, ½) (det 1) maps ζ → 4ζ, whose ratio 4(1 + |ζ|²)/(1 + 16|ζ|²) is 4 at ζ = 0."""
    rng = np.random.default_rng(7)
    zeta = rng.normal(size=200) + 1j * rng.normal(size=200)
    for angles in [(0.3, 0.7, 1.1), (1.2, -2.0, 0.4)]:
        U = notes_u(*angles)
        assert rotations.mobius_isometry_defect(U, zeta) < 1e-14
        assert rotations.mobius_isometry_defect(U @ np.diag([2.0, 0.5]), zeta) > 0.5
    assert rotations.mobius_isometry_defect(np.diag([2.0, 0.5]), np.array([0j])) == 3.0


def test_eulers_angles_in_the_notes_su2_need_half_angles():
    """(9.18)'s product U₃(ψ)U₁(θ)U₃(φ) is u(θ/2, φ + ψ, ψ − φ + π/2); its rotation is
    (9.17)'s R₃(ψ)R₁(θ)R₃(φ) only with ψ/2, φ/2 — with the full angles it turns by 2ψ and
    2φ: against the Euler matrix of reportgen.core.rotations, independently built."""
    phi, theta, psi = 0.5, 0.8, 0.3
    values, errors = notes_su2(notes_u(0.2, 0.1, 0.4), (phi, theta, psi))
    assert errors["notes_euler_identification"] < 1e-15
    assert errors["notes_euler_half_angles"] < 1e-15
    assert values["printed_9_18_full_angles"] > 0.1
    # (9.17) as printed is the transpose of core's active z-x-z R(φ, θ, ψ) with φ and ψ
    # exchanged: R₃(ψ)R₁(θ)R₃(φ) of the notes = R_z(φ)R_x(θ)R_z(ψ) transposed
    def notes_R3(a):
        return np.array([[math.cos(a), math.sin(a), 0], [-math.sin(a), math.cos(a), 0],
                         [0, 0, 1]])

    def notes_R1(a):
        return np.array([[1, 0, 0], [0, math.cos(a), math.sin(a)],
                         [0, -math.sin(a), math.cos(a)]])
    printed = notes_R3(psi) @ notes_R1(theta) @ notes_R3(phi)
    assert np.max(np.abs(printed - rotations.euler_matrix(phi, theta, psi).T)) < 1e-14
    halved = (notes_u(0.0, psi / 2, 0.0) @ notes_u(theta / 2, 0.0, math.pi / 2)
              @ notes_u(0.0, phi / 2, 0.0))
    assert np.max(np.abs(rotations.so3_from_su2(halved) - printed)) < 1e-14
