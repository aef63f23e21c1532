r"""The Legendre transform as geometry in a ``hamiltonian`` run (notes (4.15)–(4.28)).

For every regular L: the Hessian ∂²L/∂q̇ᵢ∂q̇ⱼ at the initial point, its eigenvalues and
whether it is positive definite (:func:`velocity_hessian`).  When L has two velocities and
that Hessian is positive definite, the surface z = L(q̇₁, q̇₂) at the initial coordinates
is convex, one tangent plane per slope, and the notes' construction applies
(:func:`legendre_geometry`):

* the notes' example, the unit sphere z = √(1 − x² − y²) (4.19), on a grid of tangent
  points: the plane coordinates ξ, η, ω (4.23)–(4.24) by differences, against the plane
  (4.20), the intercept 1/z₀ of (4.21) and the closed form ω = √(1 + ξ² + η²); ∂ω/∂ξ = x₀,
  ∂ω/∂η = y₀ (4.26)–(4.27) by differences of ω(ξ, η); the sign of (4.28) measured;
* the same for z = L(q̇₁, q̇₂) on a grid of velocities: ξ = −p, η = −p (4.30), ω = −H (4.31)
  against the scene's own H at p = ∂L/∂q̇, ∂ω/∂ξ = q̇₁, ∂ω/∂η = q̇₂, and (4.28) again.

The numerics are :mod:`reportgen.core.legendre_geometry`'s (no closed form in them).
"""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module

numeric = lazy_module("reportgen.core.numeric")
geometry = lazy_module("reportgen.core.legendre_geometry")

#: the Hessian ∂²L/∂q̇∂q̇ is positive definite when its smallest eigenvalue is above this
#: fraction of its largest |eigenvalue|
CONVEX_RTOL = 1e-9
#: a relation (ω ∓ z = xξ + yη) holds when its largest residual is below this fraction of
#: the largest size of its terms (the differences leave ~1e-12 of it)
RELATION_RTOL = 1e-9
#: the tangent points of the unit sphere: a square grid of this spacing ...
SPHERE_SPACING = 0.2
#: ... inside the circle x² + y² ≤ SPHERE_RADIUS² (z₀ ≥ 0.53: the slopes stay below 1.7)
SPHERE_RADIUS = 0.85
#: the step of the slopes' differences, relative to the coordinates' scale: the stencil's
#: h⁴ error and rounding/h balance near it (measured on the sphere: 1.7e-12)
SLOPE_STEP = 2.5e-4
#: the step of ω's differences in ξ and η, relative to the slopes' scale
PLANE_STEP = 1e-3
#: velocities per axis of the grid on which L is transformed
VELOCITY_SAMPLES = 5
#: points of the drawn curves (the sphere's cut y = 0 and its dual curve)
CURVE_POINTS = 201


def velocity_hessian(a: dict, system, q0, qdot0) -> bool:
    """∂²L/∂q̇ᵢ∂q̇ⱼ (SymPy) at the initial point (t = 0), its eigenvalues, and whether it is
    positive definite (every eigenvalue above :data:`CONVEX_RTOL` of the largest |one|)."""
    space = system.space
    values = {**dict(zip(space.q, np.asarray(q0, dtype=float), strict=True)),
              **dict(zip(space.qdot, np.asarray(qdot0, dtype=float), strict=True)),
              space.t: 0.0, **{system.param_symbols[k]: v for k, v in system.params.items()}}
    hessian = np.array([[float(numeric.evaluate(m.diff(v), values)) for v in space.qdot]
                        for m in system.legendre.momenta])
    eigenvalues = np.linalg.eigvalsh(0.5 * (hessian + hessian.T))
    top = float(np.max(np.abs(eigenvalues)))
    convex = bool(top > 0 and np.all(eigenvalues > CONVEX_RTOL * top))
    a["legendre_velocity_hessian"] = hessian
    a["legendre_velocity_hessian_eigenvalues"] = eigenvalues
    a["legendre_convex"] = convex
    a["legendre_convex_threshold"] = CONVEX_RTOL
    return convex


def applies(a: dict) -> bool:
    """The rule, from the stored facts: two velocities and ∂²L/∂q̇∂q̇ positive definite."""
    return len(a.get("legendre_velocity_hessian_eigenvalues", ())) == 2 \
        and bool(a.get("legendre_convex", False))


def _relation(minus, plus, scale) -> str:
    """Which of ω − z = xξ + yη ("minus") and ω + z = xξ + yη ("plus", as (4.28) prints
    it) holds, each to :data:`RELATION_RTOL` of the largest size of the terms ("both",
    "neither")."""
    bound = RELATION_RTOL * float(np.max(scale))
    m, p = float(np.max(np.abs(minus))) <= bound, float(np.max(np.abs(plus))) <= bound
    return {(True, False): "minus", (False, True): "plus", (True, True): "both"}.get(
        (m, p), "neither")


def _store_relation(a: dict, prefix: str, omega, z, x, y, xi, eta) -> None:
    minus, plus, scale = geometry.dual_residuals(omega, z, x, y, xi, eta)
    a[f"{prefix}_sign_minus"] = float(np.max(np.abs(minus)))
    a[f"{prefix}_sign_plus"] = float(np.max(np.abs(plus)))
    a[f"{prefix}_sign_scale"] = float(np.max(scale))
    a[f"{prefix}_relation"] = _relation(minus, plus, scale)


def unit_sphere(a: dict) -> None:
    """The notes' example (4.19)–(4.28) on a grid of tangent points of the unit sphere."""
    k = np.arange(-int(SPHERE_RADIUS / SPHERE_SPACING), int(SPHERE_RADIUS / SPHERE_SPACING) + 1)
    X, Y = np.meshgrid(SPHERE_SPACING * k, SPHERE_SPACING * k)
    inside = X**2 + Y**2 <= SPHERE_RADIUS**2
    x0, y0 = X[inside], Y[inside]
    surface = geometry.unit_hemisphere
    planes = geometry.tangent_planes(surface, x0, y0, SLOPE_STEP)
    xi_closed, eta_closed = geometry.unit_sphere_slopes(x0, y0)  # (4.20)
    omega_closed = geometry.unit_sphere_plane_function(planes.xi, planes.eta)
    plane_step = PLANE_STEP * max(float(np.max(np.abs(planes.xi))), 1.0)
    dxi, deta = geometry.plane_function_slopes(surface, planes.xi, planes.eta, (x0, y0),
                                               SLOPE_STEP, plane_step)
    a["legendre_sphere"] = {"x0": x0, "y0": y0, "z0": planes.z, "xi": planes.xi,
                            "eta": planes.eta, "omega": planes.omega,
                            "omega_closed": omega_closed, "domega_dxi": dxi,
                            "domega_deta": deta}
    a["legendre_sphere_slope_error"] = float(max(np.max(np.abs(planes.xi - xi_closed)),
                                                 np.max(np.abs(planes.eta - eta_closed))))
    a["legendre_sphere_omega_error"] = float(np.max(np.abs(planes.omega - omega_closed)))
    a["legendre_sphere_intercept_error"] = float(np.max(np.abs(planes.omega * planes.z - 1)))
    a["legendre_sphere_derivative_error"] = float(max(np.max(np.abs(dxi - x0)),
                                                      np.max(np.abs(deta - y0))))
    # (4.28) with ω a function of the plane coordinates alone (its closed form), z of the
    # point: not ω − z − xξ − yη = 0 by the definition (4.24) again
    _store_relation(a, "legendre_sphere", omega_closed, planes.z, x0, y0, planes.xi,
                    planes.eta)
    a["legendre_relation_threshold"] = RELATION_RTOL
    a["legendre_slope_step"] = SLOPE_STEP
    a["legendre_plane_step"] = plane_step
    # the drawn curves: the cut y = 0 of the sphere and its dual curve ω(ξ) at η = 0
    x = np.linspace(-1.0, 1.0, CURVE_POINTS)
    a["legendre_sphere_curve"] = {"x": x, "z": geometry.unit_hemisphere(x, 0.0)}
    row = np.abs(planes.xi[y0 == 0.0])
    reach = 1.1 * float(np.max(row)) if row.size else 2.0
    xi = np.linspace(-reach, reach, CURVE_POINTS)
    a["legendre_sphere_dual"] = {"xi": xi,
                                 "omega": geometry.unit_sphere_plane_function(xi, 0.0)}


def lagrangian_surface(a: dict, system, q0, qdot0) -> None:
    """z = L(q̇₁, q̇₂) at the initial coordinates (t = 0) on a grid of velocities about the
    initial ones: its tangent planes, against the scene's momenta and Hamiltonian."""
    space = system.space
    constants = {system.param_symbols[k]: v for k, v in system.params.items()}
    fixed = {**dict(zip(space.q, np.asarray(q0, dtype=float), strict=True)), space.t: 0.0,
             **constants}

    def surface(x, y):
        shape = np.broadcast(x, y).shape
        return np.broadcast_to(numeric.evaluate(system.L, {**fixed, space.qdot[0]: x,
                                                           space.qdot[1]: y}), shape)

    scale = max(float(np.max(np.abs(qdot0))), 1.0)
    k = np.linspace(-1.0, 1.0, VELOCITY_SAMPLES)
    X, Y = np.meshgrid(qdot0[0] + scale * k, qdot0[1] + scale * k)
    x, y = X.ravel(), Y.ravel()
    step = SLOPE_STEP * scale
    planes = geometry.tangent_planes(surface, x, y, step)
    vals = {**fixed, space.qdot[0]: x, space.qdot[1]: y}
    p = np.column_stack(numeric.evaluate_many(system.legendre.momenta, vals, shape=x.shape))
    H = np.broadcast_to(numeric.evaluate(system.H, {**fixed, space.p[0]: p[:, 0],
                                                    space.p[1]: p[:, 1]}), x.shape)
    slope_scale = max(float(np.max(np.abs(planes.xi))), float(np.max(np.abs(planes.eta))),
                      1e-300)
    plane_step = PLANE_STEP * slope_scale
    dxi, deta = geometry.plane_function_slopes(surface, planes.xi, planes.eta, (x, y), step,
                                               plane_step)
    a["legendre_lagrangian"] = {"x": x, "y": y, "z": np.array(planes.z), "xi": planes.xi,
                                "eta": planes.eta, "omega": planes.omega, "p": p,
                                "H": np.array(H), "domega_dxi": dxi, "domega_deta": deta}
    a["legendre_lagrangian_slope_error"] = float(max(np.max(np.abs(planes.xi + p[:, 0])),
                                                     np.max(np.abs(planes.eta + p[:, 1]))))
    a["legendre_lagrangian_momentum_scale"] = float(np.max(np.abs(p)))
    a["legendre_lagrangian_omega_error"] = float(np.max(np.abs(planes.omega + H)))
    a["legendre_lagrangian_energy_scale"] = float(np.max(np.abs(H)))
    a["legendre_lagrangian_derivative_error"] = float(max(np.max(np.abs(dxi - x)),
                                                          np.max(np.abs(deta - y))))
    a["legendre_lagrangian_velocity_scale"] = float(max(np.max(np.abs(x)), np.max(np.abs(y))))
    # (4.28) with ω(ξ, η) = −H(q, p = −(ξ, η)): the scene's H at the plane coordinates
    omega_of_planes = -np.broadcast_to(numeric.evaluate(system.H, {
        **fixed, space.p[0]: -planes.xi, space.p[1]: -planes.eta}), x.shape)
    _store_relation(a, "legendre_lagrangian", omega_of_planes, planes.z, x, y, planes.xi,
                    planes.eta)


def legendre_geometry(a: dict, system, q0, qdot0, planes: bool = True) -> None:
    """The Hessian facts for every regular L; the unit sphere and L's own tangent planes
    when ``planes`` (the scene asks for the section) and :func:`applies` (two velocities,
    ∂²L/∂q̇∂q̇ positive definite)."""
    velocity_hessian(a, system, q0, qdot0)
    if not (planes and applies(a)):
        return
    unit_sphere(a)
    lagrangian_surface(a, system, np.asarray(q0, dtype=float), np.asarray(qdot0, dtype=float))
