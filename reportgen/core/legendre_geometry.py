r"""The Legendre transform as geometry: a surface and the family of its tangent planes.

Lecture notes (4.15)–(4.28), after Courant & Hilbert.  A surface z = z(x, y) (4.15) has at
(x₀, y₀, z₀) the tangent plane (4.18) z − z₀ = (x − x₀) ∂z/∂x + (y − y₀) ∂z/∂y.  Written as
(x, y, z)·(ξ, η, 1) = ω (4.22), the plane has the *plane coordinates*::

    ξ = −∂z/∂x,   η = −∂z/∂y                 (4.23)
    ω = z₀ + x₀ ξ + y₀ η                      (4.24)

and the family ω(ξ, η) (4.25) gives the points back, ∂ω/∂ξ = x₀, ∂ω/∂η = y₀ (4.26)–(4.27).
With these definitions the dual relation is ω − z = xξ + yη; the notes print it (4.28) as
ω + z = xξ + yη, which :func:`dual_residuals` measures next to it.

Everything here is numerical, on a callable ``height(x, y) -> z`` (ndarrays, broadcast):
the slopes by the fourth-order central difference :func:`derivative`, the tangent point of
given plane coordinates by Newton's method on those slopes (:func:`tangent_point`), and
∂ω/∂ξ, ∂ω/∂η by central differences of ω(ξ, η) itself (:func:`plane_function_slopes`): no
closed form is used, so the closed forms of the notes' unit sphere (:func:`unit_hemisphere`
and the functions after it) are an independent check.

References
----------
.. [1] Lecture notes §4, eqs. (4.15)–(4.28); the unit sphere (4.19)–(4.21).
.. [2] R. Courant & D. Hilbert, *Methods of Mathematical Physics* II, ch. I (the
       Legendre transformation as the duality of points and tangent planes).
.. [3] Fornberg, *Math. Comp.* 51, 699 (1988): the central stencil
       f′(x) ≈ [f(x − 2h) − 8 f(x − h) + 8 f(x + h) − f(x + 2h)] / 12h, error h⁴ f⁽⁵⁾/30.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

#: a surface: height(x, y) -> z, on arrays that broadcast
Height = Callable[[np.ndarray, np.ndarray], np.ndarray]

#: the fourth-order central first-derivative stencil: (offset in steps, weight) [3]
STENCIL = ((-2, 1.0 / 12.0), (-1, -8.0 / 12.0), (1, 8.0 / 12.0), (2, -1.0 / 12.0))
#: Newton iterations at most for a tangent point (from a nearby start, 3 to 5 suffice)
NEWTON_ITERATIONS = 30


def derivative(f: Callable[[np.ndarray], np.ndarray], x, step: float) -> np.ndarray:
    """f′(x) by the fourth-order central stencil :data:`STENCIL` with step ``step``."""
    x = np.asarray(x, dtype=float)
    return sum(w * np.asarray(f(x + k * step), dtype=float) for k, w in STENCIL) / step


def slopes(height: Height, x, y, step: float) -> tuple[np.ndarray, np.ndarray]:
    """(∂z/∂x, ∂z/∂y) of the surface at (x, y), by :func:`derivative`."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    return (derivative(lambda u: height(u, y), x, step),
            derivative(lambda v: height(x, v), y, step))


@dataclass(frozen=True)
class TangentPlanes:
    """The tangent planes at points (x₀, y₀) of a surface, in plane coordinates.

    Attributes
    ----------
    z : ndarray
        The height z₀ = z(x₀, y₀).
    xi, eta : ndarray
        ξ = −∂z/∂x, η = −∂z/∂y at the point (notes (4.23)), by differences.
    omega : ndarray
        ω = z₀ + x₀ξ + y₀η (notes (4.24)): where the plane meets the z axis.
    """

    z: np.ndarray
    xi: np.ndarray
    eta: np.ndarray
    omega: np.ndarray


def tangent_planes(height: Height, x, y, step: float) -> TangentPlanes:
    """The tangent plane of the surface at each point (x, y): notes (4.23)–(4.24)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    z = np.asarray(height(x, y), dtype=float)
    zx, zy = slopes(height, x, y, step)
    xi, eta = -zx, -zy
    return TangentPlanes(z=z, xi=xi, eta=eta, omega=z + x * xi + y * eta)


def tangent_point(height: Height, xi, eta, start, step: float) -> tuple[np.ndarray, np.ndarray]:
    """The point (x, y) whose tangent plane has the slopes (ξ, η): the root of
    ∂z/∂x + ξ = ∂z/∂y + η = 0 by Newton's method from ``start`` = (x, y), the slopes by
    :func:`slopes` and their Jacobian (the Hessian of z) by central differences of them.

    The Hessian must be invertible near the root (a surface of one tangent plane per
    slope, as a convex or concave one)."""
    xi, eta = np.asarray(xi, dtype=float), np.asarray(eta, dtype=float)
    x = np.array(np.broadcast_to(start[0], np.broadcast(xi, eta).shape), dtype=float)
    y = np.array(np.broadcast_to(start[1], x.shape), dtype=float)
    for _ in range(NEWTON_ITERATIONS):
        zx, zy = slopes(height, x, y, step)
        gx, gy = zx + xi, zy + eta
        right, left = slopes(height, x + step, y, step), slopes(height, x - step, y, step)
        up, down = slopes(height, x, y + step, step), slopes(height, x, y - step, step)
        zxx = (right[0] - left[0]) / (2 * step)
        zyy = (up[1] - down[1]) / (2 * step)
        zxy = 0.5 * ((right[1] - left[1]) + (up[0] - down[0])) / (2 * step)
        det = zxx * zyy - zxy**2
        dx = (zyy * gx - zxy * gy) / det
        dy = (zxx * gy - zxy * gx) / det
        x, y = x - dx, y - dy
        size = 1.0 + np.maximum(np.abs(x), np.abs(y))
        if np.all(np.maximum(np.abs(dx), np.abs(dy)) <= 1e-14 * size):
            break
    return x, y


def plane_function(height: Height, xi, eta, start, step: float) -> np.ndarray:
    """ω(ξ, η) of notes (4.25): the intercept z + xξ + yη of the tangent plane of slopes
    (ξ, η), at its tangent point found by :func:`tangent_point` from ``start``.

    ω is stationary in the tangent point (∂/∂x of z + xξ + yη is ∂z/∂x + ξ = 0), so an error
    δ in the point changes it by O(δ²) only."""
    x, y = tangent_point(height, xi, eta, start, step)
    return np.asarray(height(x, y), dtype=float) + x * xi + y * eta


def plane_function_slopes(height: Height, xi, eta, start, step: float,
                          plane_step: float) -> tuple[np.ndarray, np.ndarray]:
    """(∂ω/∂ξ, ∂ω/∂η) by :func:`derivative` of :func:`plane_function` in ξ and in η with
    step ``plane_step``, each shifted ω from its own tangent point: notes (4.26)–(4.27)
    measured, not assumed (they say x₀ and y₀)."""
    xi, eta = np.asarray(xi, dtype=float), np.asarray(eta, dtype=float)
    return (derivative(lambda s: plane_function(height, s, eta, start, step), xi, plane_step),
            derivative(lambda s: plane_function(height, xi, s, start, step), eta, plane_step))


def dual_residuals(omega, z, x, y, xi, eta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(ω − z − xξ − yη, ω + z − xξ − yη, |ω| + |z| + |xξ| + |yη|) at each point: the
    relation the definitions (4.23)–(4.24) give, the one notes (4.28) prints, and the size
    of their terms (what a residual is rounding against)."""
    omega, z = np.asarray(omega, dtype=float), np.asarray(z, dtype=float)
    xx, yy = np.asarray(x, dtype=float) * xi, np.asarray(y, dtype=float) * eta
    return (omega - z - xx - yy, omega + z - xx - yy,
            np.abs(omega) + np.abs(z) + np.abs(xx) + np.abs(yy))


# ------------------------------------------------------------------ the notes' unit sphere
def unit_hemisphere(x, y) -> np.ndarray:
    """z = √(1 − x² − y²), the upper unit hemisphere (notes (4.19))."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    return np.sqrt(1.0 - x**2 - y**2)


def unit_sphere_slopes(x0, y0) -> tuple[np.ndarray, np.ndarray]:
    """(ξ, η) = (x₀/z₀, y₀/z₀): the coefficients of the tangent plane (4.20),
    z − z₀ + (x − x₀) x₀/z₀ + (y − y₀) y₀/z₀ = 0, read as (4.22)."""
    z0 = unit_hemisphere(x0, y0)
    return np.asarray(x0, dtype=float) / z0, np.asarray(y0, dtype=float) / z0


def unit_sphere_plane_function(xi, eta) -> np.ndarray:
    """ω(ξ, η) = √(1 + ξ² + η²) of the unit sphere.

    The tangent plane x·x₀ = 1 (4.21) meets the z axis at ω = 1/z₀; with ξ = x₀/z₀,
    η = y₀/z₀ (4.20), 1 + ξ² + η² = (z₀² + x₀² + y₀²)/z₀² = 1/z₀², so ω = √(1 + ξ² + η²),
    and ∂ω/∂ξ = ξ/ω = x₀, ∂ω/∂η = η/ω = y₀ as (4.26)–(4.27) say."""
    xi, eta = np.asarray(xi, dtype=float), np.asarray(eta, dtype=float)
    return np.sqrt(1.0 + xi**2 + eta**2)
