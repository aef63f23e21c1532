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

Every solid also has a quadrature (``quadrature_*``): point masses at Gauss–Legendre
nodes (and equally spaced azimuths) that integrate the density times any polynomial of
degree ≤ 2 in x, y, z exactly, so the volume, the centre of mass and the tensor they give
(:func:`centre_of_mass`, :func:`tensor_points`) are an independent computation of the
closed forms, equal to them at round-off.
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


def cone_volume(radius: float, height: float) -> float:
    """πR²h/3."""
    return math.pi * radius**2 * height / 3.0


def tensor_octahedron(mass: float, a: float, b: float, c: float) -> np.ndarray:
    """Solid octahedron |x|/a + |y|/b + |z|/c ≤ 1 (half-diagonals a, b, c; exercise 4.9).

    ∫ x² dm = M a²/10 (Dirichlet's integral over the simplex: ∫u² = 2!/5! per octant,
    volume 1/6 per octant), hence I_xx = M (b² + c²)/10.
    """
    return mass / 10.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])


def octahedron_volume(a: float, b: float, c: float) -> float:
    """|x|/a + |y|/b + |z|/c ≤ 1: eight simplices of volume abc/6, 4abc/3."""
    return 4.0 * a * b * c / 3.0


def tensor_octahedron_rectangle(mass: float, a: float, b: float, h: float) -> np.ndarray:
    """Solid octahedron on a rectangular equator: the double pyramid over the a × b
    rectangle |x| ≤ a/2, |y| ≤ b/2 in z = 0 with apexes at (0, 0, ±h) (textbook ex. 4.9).

    The slice at height z is the rectangle a s × b s, s = 1 − |z|/h, so with
    V = 2 ∫₀ʰ ab s² dz = 2abh/3:
    ∫ x² dV = 2 ∫₀ʰ (a s)³ (b s)/12 dz = a³bh/30, i.e. ⟨x²⟩ = a²/20 (⟨y²⟩ = b²/20), and
    ∫ z² dV = 2ab ∫₀ʰ s² z² dz = 2abh³ B(3, 3) = abh³/15, i.e. ⟨z²⟩ = h²/10; hence
    I_xx = M (b²/20 + h²/10), I_yy = M (a²/20 + h²/10), I_zz = M (a² + b²)/20.
    A square equator a = b = s with h = s/√2 (the regular octahedron) gives M s²/10
    about every axis.
    """
    return mass / 20.0 * np.diag([b * b + 2 * h * h, a * a + 2 * h * h, a * a + b * b])


def octahedron_rectangle_volume(a: float, b: float, h: float) -> float:
    """Two pyramids of base ab and height h: 2abh/3."""
    return 2.0 * a * b * h / 3.0


# ------------------------------------------------------------------ quadratures
def _gauss(n: int, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on [lo, hi] (exact for degree ≤ 2n − 1)."""
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (hi - lo) * x + 0.5 * (hi + lo), 0.5 * (hi - lo) * w


def _grid(*factors) -> tuple[np.ndarray, ...]:
    """Tensor product of 1-D (nodes, weights): the flattened node coordinates and the
    product of the weights."""
    nodes = np.meshgrid(*[f[0] for f in factors], indexing="ij")
    weights = np.prod(np.meshgrid(*[f[1] for f in factors], indexing="ij"), axis=0)
    return tuple(n.ravel() for n in nodes) + (weights.ravel(),)


def _elements(mass: float, volume_weights, positions) -> tuple[np.ndarray, np.ndarray, float]:
    """Point masses of a uniform body from volume weights: density M / Σ w."""
    vol = float(np.sum(volume_weights))
    return mass * np.asarray(volume_weights) / vol, np.asarray(positions), vol


def quadrature_cone(mass: float, radius: float, height: float, n: int = 4, n_phi: int = 8):
    """The solid cone as point masses, measured from its apex, axis along −z.

    Depth s ∈ [0, h] below the apex (Gauss–Legendre), radius ρ = (R s/h) u with
    u ∈ [0, 1] (Gauss–Legendre, volume element (R s/h)² u du), azimuth φ at ``n_phi``
    equal steps (exact for trigonometric polynomials of degree < n_phi).  Exact for the
    volume, the first and the second moments: the integrands are polynomials of degree
    ≤ 4 in s and ≤ 3 in u.

    Returns
    -------
    masses : ndarray (N,) [kg]; positions : ndarray (N, 3) [m], apex at the origin;
    volume : float [m³] (the sum of the volume weights).
    """
    s, u, phi, w = _grid(_gauss(n, 0.0, height), _gauss(n, 0.0, 1.0),
                         (2 * np.pi * np.arange(n_phi) / n_phi, np.full(n_phi, 2 * np.pi / n_phi)))
    rho = radius * s / height * u
    jac = (radius * s / height) ** 2 * u
    pts = np.column_stack([rho * np.cos(phi), rho * np.sin(phi), -s])
    return _elements(mass, w * jac, pts)


def quadrature_cylinder(mass: float, radius: float, height: float, n: int = 3, n_phi: int = 8):
    """The solid cylinder (axis z, centred) as point masses (as :func:`quadrature_cone`)."""
    z, u, phi, w = _grid(_gauss(n, -height / 2, height / 2), _gauss(n, 0.0, 1.0),
                         (2 * np.pi * np.arange(n_phi) / n_phi, np.full(n_phi, 2 * np.pi / n_phi)))
    rho = radius * u
    pts = np.column_stack([rho * np.cos(phi), rho * np.sin(phi), z])
    return _elements(mass, w * radius**2 * u, pts)


def quadrature_box(mass: float, a: float, b: float, c: float, n: int = 2):
    """The box of full sides a, b, c (centred) as point masses."""
    x, y, z, w = _grid(_gauss(n, -a / 2, a / 2), _gauss(n, -b / 2, b / 2),
                       _gauss(n, -c / 2, c / 2))
    return _elements(mass, w, np.column_stack([x, y, z]))


def quadrature_ellipsoid(mass: float, a: float, b: float, c: float, n: int = 3,
                         n_phi: int = 8):
    """The ellipsoid of semi-axes a, b, c as point masses: r ∈ [0, 1] (weight r²),
    cos θ ∈ [−1, 1] (Gauss–Legendre), φ equally spaced, scaled by (a, b, c)."""
    r, mu, phi, w = _grid(_gauss(n, 0.0, 1.0), _gauss(n, -1.0, 1.0),
                          (2 * np.pi * np.arange(n_phi) / n_phi, np.full(n_phi, 2 * np.pi / n_phi)))
    st = np.sqrt(1.0 - mu * mu)
    pts = np.column_stack([a * r * st * np.cos(phi), b * r * st * np.sin(phi), c * r * mu])
    return _elements(mass, w * r * r * a * b * c, pts)


def quadrature_octahedron(mass: float, a: float, b: float, c: float, n: int = 3):
    """The octahedron |x|/a + |y|/b + |z|/c ≤ 1 as point masses.

    Slice at height z: the rhombus |x|/a' + |y|/b' ≤ 1, a' = a σ, b' = b σ,
    σ = 1 − |z|/c, the image of the square u, v ∈ [−1, 1] under x = a'(u + v)/2,
    y = b'(u − v)/2 (area element a'b'/2 du dv)."""
    z, u, v, w = _grid(_gauss_two_halves(n, c),
                       _gauss(n, -1.0, 1.0), _gauss(n, -1.0, 1.0))
    sig = 1.0 - np.abs(z) / c
    pts = np.column_stack([a * sig * (u + v) / 2, b * sig * (u - v) / 2, z])
    return _elements(mass, w * a * b * sig**2 / 2, pts)


def quadrature_octahedron_rectangle(mass: float, a: float, b: float, h: float, n: int = 3):
    """The double pyramid over the a × b rectangle with apexes at ±h as point masses:
    slice at z the rectangle a σ × b σ, σ = 1 − |z|/h."""
    z, u, v, w = _grid(_gauss_two_halves(n, h), _gauss(n, -0.5, 0.5), _gauss(n, -0.5, 0.5))
    sig = 1.0 - np.abs(z) / h
    pts = np.column_stack([a * sig * u, b * sig * v, z])
    return _elements(mass, w * a * b * sig**2, pts)


def _gauss_two_halves(n: int, half: float) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre on [−half, 0] and [0, half]: |z| is a polynomial on each."""
    lo, wl = _gauss(n, -half, 0.0)
    hi, wh = _gauss(n, 0.0, half)
    return np.concatenate([lo, hi]), np.concatenate([wl, wh])


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
