"""The claim-carrying sentences of a ``hamiltonian`` report about the Legendre transform
as geometry (notes (4.15)–(4.28)) and its failure for an L linear in the velocities (notes
(4.13)–(4.14)) (:mod:`.claims`, which registers these with its own).

Each predicate measures again without the stored verdict: the unit sphere's relation from
the closed forms of (4.19)–(4.21) at the archived tangent points; L's from the Lagrangian
and Hamiltonian derived again from the archived config, its momenta by differences of L;
the velocity Hessian by second differences of L.
"""

from __future__ import annotations

import numpy as np

from ...scene.claims import claim
from .claims import NONZERO, _system, _velocity_curvature

#: a relation holds when its residual is below this fraction of its terms (the archived
#: ones sit at ~1e-15; differences of L here leave ~1e-9)
HOLDS = 1e-7
#: the step of the differences of L in a velocity, relative to the velocities' scale
STEP = 1e-4


def _initial_q(data, system) -> dict:
    a = data.analysis
    return {q: float(a[f"initial_{name}"])
            for name, q in zip(system.space.names, system.space.q, strict=True)}


def _lagrangian_at(system, fixed: dict, velocities: np.ndarray) -> np.ndarray:
    from ...core import numeric

    vals = {**fixed, **dict(zip(system.space.qdot, velocities.T, strict=True))}
    return np.broadcast_to(numeric.evaluate(system.L, vals), velocities.shape[:1])


def _fixed(data, system) -> dict:
    return {**_initial_q(data, system), system.space.t: 0.0,
            **{system.param_symbols[k]: v for k, v in system.params.items()}}


@claim("hamiltonian: (4.28) holds with ω − z for the unit sphere",
       r"Measured, the dual relation holds as ω − z = xξ \+ yη")
def sphere_relation(data) -> bool | str:
    """at the archived tangent points, ω = √(1 + ξ² + η²) with ξ = x₀/z₀, η = y₀/z₀ (the
    closed forms of (4.19)–(4.21)) satisfies ω − z = xξ + yη and not ω + z = xξ + yη"""
    sphere = data.analysis["legendre_sphere"]
    x, y = np.asarray(sphere["x0"], dtype=float), np.asarray(sphere["y0"], dtype=float)
    z = np.sqrt(1.0 - x**2 - y**2)
    xi, eta = x / z, y / z
    omega = np.sqrt(1.0 + xi**2 + eta**2)
    size = float(np.max(np.abs(omega) + z + np.abs(x * xi) + np.abs(y * eta)))
    minus = float(np.max(np.abs(omega - z - x * xi - y * eta)))
    plus = float(np.max(np.abs(omega + z - x * xi - y * eta)))
    if minus > HOLDS * size or plus <= NONZERO * size:
        return f"ω − z − xξ − yη up to {minus:.2g}, ω + z − xξ − yη up to {plus:.2g}"
    return True


@claim("hamiltonian: (4.28) for z = L is H = p·q̇ − L",
       r"For z = L the measured relation ω − z = xξ \+ yη")
def lagrangian_relation(data) -> bool | str:
    """at the archived velocities and the initial coordinates, the Hamiltonian derived
    again from the config, at the momenta p = ∂L/∂q̇ by central differences of L, is
    p·q̇ − L, and not p·q̇ + L"""
    from ...core import numeric

    system = _system(data)
    surface = data.analysis["legendre_lagrangian"]
    v = np.column_stack([np.asarray(surface[k], dtype=float) for k in ("x", "y")])
    fixed = _fixed(data, system)
    h = STEP * max(float(np.max(np.abs(v))), 1.0)
    p = np.column_stack([(_lagrangian_at(system, fixed, v + h * e)
                          - _lagrangian_at(system, fixed, v - h * e)) / (2 * h)
                         for e in np.eye(2)])
    L = _lagrangian_at(system, fixed, v)
    H = np.broadcast_to(numeric.evaluate(system.H, {**fixed, **dict(zip(
        system.space.p, p.T, strict=True))}), L.shape)
    pv = np.sum(p * v, axis=1)
    size = float(np.max(np.abs(H) + np.abs(pv) + np.abs(L)))
    minus = float(np.max(np.abs(H - pv + L)))
    plus = float(np.max(np.abs(H - pv - L)))
    if minus > HOLDS * size or plus <= NONZERO * size:
        return f"H − p·q̇ + L up to {minus:.2g}, H − p·q̇ − L up to {plus:.2g}"
    return True


@claim("hamiltonian: L convex in the velocities", r"positive definite, eigenvalues")
def convex_in_velocities(data) -> bool | str:
    """the second differences of L (derived again from the config) in the velocities, at
    the initial coordinates, make a positive-definite matrix"""
    system = _system(data)
    n = system.n
    fixed = _fixed(data, system)
    v0 = np.zeros((1, n))
    h = 0.5
    hessian = np.empty((n, n))
    for i in range(n):
        for j in range(n):
            ei, ej = np.eye(n)[i] * h, np.eye(n)[j] * h
            hessian[i, j] = float((_lagrangian_at(system, fixed, v0 + ei + ej)
                                   - _lagrangian_at(system, fixed, v0 + ei - ej)
                                   - _lagrangian_at(system, fixed, v0 - ei + ej)
                                   + _lagrangian_at(system, fixed, v0 - ei - ej))[0]
                                  / (4 * h * h))
    eigenvalues = np.linalg.eigvalsh(0.5 * (hessian + hessian.T))
    if not np.all(eigenvalues > NONZERO * max(float(np.max(np.abs(eigenvalues))), 1e-300)):
        return f"the velocity Hessian has eigenvalues {eigenvalues}"
    return True


@claim("hamiltonian: no Legendre transform of a linear L",
       r"has rank 0 and p = ∂L/∂q̇ = a\(q, t\) contains no velocity")
def linear_in_velocities(data) -> bool | str:
    """the second differences of L (derived again from the config) in every velocity
    vanish near the orbit: p = ∂L/∂q̇ does not depend on q̇"""
    curvature, size = _velocity_curvature(data, _system(data))
    if curvature > 1e-9 * max(size, 1.0):
        return f"L is not linear in the velocities (second difference {curvature:.3g})"
    return True
