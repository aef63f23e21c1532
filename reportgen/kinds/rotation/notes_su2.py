"""SU(2) → SO(3) in the lecture notes' own terms, notes §9 (9.4)–(9.16): the
parametrization u(α, β, γ), M(r) with det M = 1 − r², M → uMu†, and the special cases in
which u turns by twice its angle; and two places where the notes as printed differ from the
map ((9.10)'s last entry, the case (9.12)).  Plain arrays in, dicts out."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module

rotations = lazy_module("reportgen.core.rotations")


def notes_u(alpha: float, beta: float, gamma: float) -> np.ndarray:
    """u(α, β, γ) = [[cos α e^{iβ}, sin α e^{iγ}], [−sin α e^{−iγ}, cos α e^{−iβ}]], the
    notes' parametrization of SU(2), notes (9.4)."""
    c, s = math.cos(alpha), math.sin(alpha)
    return np.array([[c * np.exp(1j * beta), s * np.exp(1j * gamma)],
                     [-s * np.exp(-1j * gamma), c * np.exp(-1j * beta)]])


def notes_su2(U: np.ndarray, euler=(0.0, 0.0, 0.0)) -> tuple[dict, dict]:
    """SU(2) → SO(3) in the lecture notes' own terms, notes (9.4)–(9.16), for the scene's
    U: its angles (α, β, γ) of (9.4); M(r) = 1 + xσ₁ + yσ₂ + zσ₃ of (9.5) at sample points,
    det M = 1 − r² (9.6), M → uMu† (9.7) keeping it, r′ read off uMu† against R(U) r (9.8);
    the special cases at the scene's angles: β = γ = 0 gives R₂(2α) (9.9)–(9.10), α = 0
    gives R₃(2β) (9.11), β = 0, γ = π/2 gives R₁(2α) (9.15)–(9.16) — the angle doubled.
    Two facts about the notes as printed: the last entry of (9.10) reads sin 2α where the
    map gives cos 2α, and the case α = π/2, β = 0 of (9.12) is measured (its trace and axis)
    against the R₃(2γ) the notes state.  And Euler's angles, notes (9.17)–(9.18), at
    ``euler`` = (φ, θ, ψ): the product U₃(ψ) U₁(θ) U₃(φ) of (9.18) is u(θ/2, φ + ψ,
    ψ − φ + π/2), the identification (9.18) makes; with U₃(β) = diag(e^{iβ}, e^{−iβ})
    turning by 2β (9.11), it is R₃(ψ) R₁(θ) R₃(φ) of (9.17) only with ψ/2 and φ/2 in place
    of ψ and φ (a check), and with (9.18)'s full angles it is R₃(2ψ) R₁(θ) R₃(2φ) (its
    distance from (9.17)'s R stored).  Returns (values, errors)."""
    alpha = math.acos(min(1.0, abs(U[0, 0])))
    beta = float(np.angle(U[0, 0])) if abs(U[0, 0]) > 1e-12 else 0.0
    gamma = float(np.angle(U[0, 1])) if abs(U[0, 1]) > 1e-12 else 0.0
    u = notes_u(alpha, beta, gamma)
    # points of several lengths, inside and outside the unit sphere (det M changes sign)
    r = rotations.fibonacci_sphere(12) * np.linspace(0.25, 1.75, 12)[:, None]
    x, y, z = r.T
    M = np.array([[1 + z, x - 1j * y], [x + 1j * y, 1 - z]]).transpose(2, 0, 1)
    turned = u @ M @ np.conj(u.T)
    r_turned = np.column_stack([turned[:, 0, 1].real, -turned[:, 0, 1].imag,
                                0.5 * (turned[:, 0, 0] - turned[:, 1, 1]).real])
    R = rotations.so3_from_su2(U)

    def doubled(axis: int, angle: float) -> np.ndarray:
        """The notes' R₁, R₂, R₃ of a doubled angle, as (9.16), (9.10), (9.11) print them
        (with cos 2α as the last entry of (9.10))."""
        c, s = math.cos(angle), math.sin(angle)
        return {1: np.array([[1, 0, 0], [0, c, s], [0, -s, c]]),
                2: np.array([[c, 0, -s], [0, 1, 0], [s, 0, c]]),
                3: np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]])}[axis]

    def off(a: np.ndarray, b: np.ndarray) -> float:
        return float(np.max(np.abs(a - b)))

    errors = {
        "notes_parametrization": off(u, U),
        "notes_determinant": off(np.linalg.det(M), 1.0 - np.sum(r * r, axis=1)),
        "notes_determinant_kept": off(np.linalg.det(turned), np.linalg.det(M)),
        "notes_map_vs_rotation": off(r_turned, r @ R.T),
        "notes_second_axis": off(rotations.so3_from_su2(notes_u(alpha, 0.0, 0.0)),
                                 doubled(2, 2 * alpha)),
        "notes_third_axis": off(rotations.so3_from_su2(notes_u(0.0, beta, 0.0)),
                                doubled(3, 2 * beta)),
        "notes_first_axis": off(rotations.so3_from_su2(notes_u(alpha, 0.0, 0.5 * math.pi)),
                                doubled(1, 2 * alpha)),
    }
    phi, theta, psi = (float(a) for a in euler)

    def third(b: float) -> np.ndarray:  # U₃(β) = diag(e^{iβ}, e^{−iβ}), α = γ = 0 of (9.4)
        return notes_u(0.0, b, 0.0)

    first = notes_u(0.5 * theta, 0.0, 0.5 * math.pi)  # U₁ of (9.18): turns by θ, (9.16)
    product = third(psi) @ first @ third(phi)
    euler_R = doubled(3, psi) @ doubled(1, theta) @ doubled(3, phi)  # (9.17) as printed
    errors["notes_euler_identification"] = off(
        product, notes_u(0.5 * theta, phi + psi, psi - phi + 0.5 * math.pi))
    errors["notes_euler_half_angles"] = off(
        rotations.so3_from_su2(third(0.5 * psi) @ first @ third(0.5 * phi)), euler_R)
    case = rotations.so3_from_su2(notes_u(0.5 * math.pi, 0.0, gamma))
    m, _ = rotations.su2_axis_angle(notes_u(0.5 * math.pi, 0.0, gamma))
    values = {
        "alpha": alpha, "beta": beta, "gamma": gamma, "points": r,
        "printed_9_10_entry": abs(math.sin(2 * alpha) - math.cos(2 * alpha)),
        "case_9_12_trace": float(np.trace(case)),
        "case_9_12_axis": m,
        "case_9_12_vs_third_axis": off(case, doubled(3, 2 * gamma)),
        "euler_angles": np.array([phi, theta, psi]),
        "printed_9_18_full_angles": off(rotations.so3_from_su2(product), euler_R),
    }
    return values, errors
