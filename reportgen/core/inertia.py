r"""Inertia tensors of shapes and point sets, the parallel-axis shift, principal axes and the
stability of free rotation about each principal axis.

All solid shapes are uniform, in their own frame: centre of mass at the origin,
symmetry / half-diagonal axes along x, y, z.

References
----------
.. [1] Landau & Lifshitz, *Mechanics*, 3rd ed., §32 and its Problem 2 (moments of the
       box, cylinder, cone, ellipsoid about the centre of mass).
.. [2] Lecture notes (8.49): parallel-axis theorem I_ij = I^cm_ij + M (d² δ_ij − d_i d_j);
       (10.12)–(10.14): linear stability of rotation about a principal axis;
       textbook exercises 4.6 (cone) and 4.9 (octahedron).
"""

from __future__ import annotations

import math

import numpy as np


def tensor_box(mass: float, a: float, b: float, c: float) -> np.ndarray:
    """Box with full side lengths a, b, c along x, y, z: I_xx = M (b² + c²)/12 (Landau §32 P.2)."""
    return mass / 12.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])


def tensor_cylinder(mass: float, radius: float, height: float) -> np.ndarray:
    """Solid cylinder, axis z: I_zz = M R²/2, I_xx = I_yy = M (R²/4 + h²/12) (Landau §32 P.2)."""
    perp = mass * (radius**2 / 4.0 + height**2 / 12.0)
    return np.diag([perp, perp, 0.5 * mass * radius**2])


def tensor_ellipsoid(mass: float, a: float, b: float, c: float) -> np.ndarray:
    """Solid ellipsoid, semi-axes a, b, c: I_xx = M (b² + c²)/5 (Landau §32 P.2)."""
    return mass / 5.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])


def cone_apex_height(height: float) -> float:
    """Apex above the centre of mass on the axis: 3h/4 (the CM lies h/4 above the base)."""
    return 0.75 * height


def tensor_cone(mass: float, radius: float, height: float) -> np.ndarray:
    """Solid right circular cone about its centre of mass, axis z (exercise 4.6).

    I_zz = 3 M R²/10,  I_xx = I_yy = 3 M (R² + h²/4)/20  (Landau §32 Problem 2).
    """
    perp = 3.0 * mass * (radius**2 + height**2 / 4.0) / 20.0
    return np.diag([perp, perp, 0.3 * mass * radius**2])


def tensor_octahedron(mass: float, a: float, b: float, c: float) -> np.ndarray:
    """Solid octahedron |x|/a + |y|/b + |z|/c ≤ 1 (half-diagonals a, b, c; exercise 4.9).

    ∫ x² dm = M a²/10 (Dirichlet's integral over the simplex: ∫u² = 2!/5! per octant,
    volume 1/6 per octant), hence I_xx = M (b² + c²)/10.
    """
    return mass / 10.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])


def centre_of_mass(masses, positions) -> np.ndarray:
    m = np.asarray(masses, dtype=float)
    r = np.asarray(positions, dtype=float).reshape(-1, 3)
    return m @ r / m.sum()


def tensor_points(masses, positions, about=None) -> np.ndarray:
    """I_ij = Σ m (r² δ_ij − r_i r_j) of point masses about ``about`` (default: their CM)."""
    m = np.asarray(masses, dtype=float)
    r = np.asarray(positions, dtype=float).reshape(-1, 3)
    origin = centre_of_mass(m, r) if about is None else np.asarray(about, dtype=float)
    d = r - origin
    r2 = np.sum(d * d, axis=1)
    return np.sum(m[:, None, None] * (r2[:, None, None] * np.eye(3)
                                      - d[:, :, None] * d[:, None, :]), axis=0)


def parallel_axis(tensor_cm, mass: float, d) -> np.ndarray:
    """Tensor about the point at ``d`` from the CM: I + M (|d|² 1 − d dᵀ)  (lecture notes (8.49))."""
    d = np.asarray(d, dtype=float)
    return np.asarray(tensor_cm, dtype=float) + mass * (d @ d * np.eye(3) - np.outer(d, d))


def rotate_tensor(tensor, R) -> np.ndarray:
    """The tensor of the body rotated by R (body -> space): R I Rᵀ."""
    R = np.asarray(R, dtype=float)
    return R @ np.asarray(tensor, dtype=float) @ R.T


def principal_axes(tensor) -> tuple[np.ndarray, np.ndarray]:
    """Principal moments (ascending) and axes by diagonalization.

    Returns
    -------
    moments : ndarray, shape (3,)
    axes : ndarray, shape (3, 3)
        Column k is the unit principal axis of ``moments[k]``; right-handed (det +1),
        each column's largest component positive where the sign is free.
    """
    tensor = np.asarray(tensor, dtype=float)
    tensor = 0.5 * (tensor + tensor.T)
    moments, axes = np.linalg.eigh(tensor)
    for k in range(3):
        col = axes[:, k]
        if col[np.argmax(np.abs(col))] < 0:
            axes[:, k] = -col
    if np.linalg.det(axes) < 0:
        axes[:, 2] = -axes[:, 2]
    return moments, axes


def triangle_violation(moments) -> int | None:
    """Index k with I_k > I_i + I_j (no real body has it), or None."""
    moments = [float(x) for x in moments]
    for k in range(3):
        others = sum(moments) - moments[k]
        if moments[k] > others * (1.0 + 1e-12):
            return k
    return None


def axis_stability(moments, spin: float = 1.0, rtol: float = 1e-12) -> list[dict]:
    """Linear stability of steady rotation at rate ``spin`` about each principal axis.

    Perturbing rotation Ω about axis i, Euler's equations linearize to
    ω̈_j = Ω² (I_k − I_i)(I_i − I_j)/(I_j I_k) ω_j  (lecture notes (10.12)–(10.14)):
    growth at Ω √((I_k − I_i)(I_i − I_j)/(I_j I_k)) when I_i lies between I_j and I_k
    (the intermediate axis), oscillation at Ω √((I_i − I_j)(I_i − I_k)/(I_j I_k)) otherwise;
    an axis of a degenerate pair has zero rate (marginal, neutrally stable).

    Returns one dict per axis (the order of ``moments``): moment, verdict
    ("stable" | "unstable" | "marginal"), growth_rate, oscillation_frequency [1/s].
    """
    I = np.asarray(moments, dtype=float)
    scale = float(np.max(I))
    out = []
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        s = (I[k] - I[i]) * (I[i] - I[j]) / (I[j] * I[k])
        if abs(I[i] - I[j]) <= rtol * scale or abs(I[i] - I[k]) <= rtol * scale:
            verdict, growth, freq = "marginal", 0.0, 0.0
        elif s > 0:
            verdict, growth, freq = "unstable", abs(spin) * math.sqrt(s), 0.0
        else:
            verdict, growth, freq = "stable", 0.0, abs(spin) * math.sqrt(-s)
        out.append({"moment": float(I[i]), "verdict": verdict, "growth_rate": growth,
                    "oscillation_frequency": freq})
    return out


def inertia_ellipsoid(moments, axes, n_u: int = 36, n_v: int = 18) -> dict:
    """The inertia ellipsoid Σ I_k x_k² = 1 (principal coordinates x_k) in the lab frame.

    Its semi-axes are 1/√I_k along the principal axes (Landau & Lifshitz §32; Poinsot's
    construction, lecture notes §10).

    Parameters
    ----------
    moments : array_like, shape (3,)
        Principal moments [kg m²].
    axes : array_like, shape (3, 3)
        Column k: lab-frame unit vector of principal axis k.
    n_u, n_v : int
        Grid of the surface in azimuth u ∈ [0, 2π] and polar angle v ∈ [0, π].

    Returns
    -------
    dict
        ``semi_axes`` (3,) = 1/√I_k [(kg m²)^−½]; ``surface`` (n_u, n_v, 3): lab-frame
        points of the ellipsoid on the (u, v) grid.
    """
    semi = 1.0 / np.sqrt(np.asarray(moments, dtype=float))
    u, v = np.mgrid[0:2 * np.pi:complex(0, n_u), 0:np.pi:complex(0, n_v)]
    local = np.stack([semi[0] * np.cos(u) * np.sin(v), semi[1] * np.sin(u) * np.sin(v),
                      semi[2] * np.cos(v)], axis=-1)
    return {"semi_axes": semi, "surface": local @ np.asarray(axes, dtype=float).T}
