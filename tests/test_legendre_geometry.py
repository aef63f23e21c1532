"""The Legendre transform as geometry (lecture notes (4.15)–(4.28)) and its failure for a
function linear in the velocities (notes (4.13)–(4.14)), issue 42.

References, each worked out by hand here, independent of the code's differences:

* the unit sphere z = √(1 − x² − y²) (notes (4.19)): ∂z/∂x = −x/z, so the tangent plane
  (4.20) has ξ = x₀/z₀, η = y₀/z₀; the plane x·x₀ = 1 (4.21) meets the z axis at
  ω = 1/z₀ = z₀ + x₀ξ + y₀η (4.24); 1 + ξ² + η² = 1/z₀², so ω(ξ, η) = √(1 + ξ² + η²) and
  ∂ω/∂ξ = ξ/ω = x₀, ∂ω/∂η = y₀ (4.26)–(4.27).  With ω = z + xξ + yη the relation is
  ω − z = xξ + yη; as (4.28) prints it, ω + z − xξ − yη = 2z;
* a quadratic surface z = ½ xᵀA x (A symmetric, invertible): (ξ, η) = −A x, so the tangent
  point of (ξ, η) is x = −A⁻¹(ξ, η) and ω = z − xᵀA x = −½ (ξ, η) A⁻¹ (ξ, η)ᵀ (the
  quadratic form of notes (4.9)–(4.12), with the plane's sign convention);
* the spherical pendulum L = ml²/2 (θ̇² + sin²θ φ̇²) + mgl cos θ of
  ``configs/hamiltonian_spherical_pendulum.toml``: ∂²L/∂q̇² = diag(ml², ml² sin²θ),
  p = (ml² θ̇, ml² sin²θ φ̇) (notes (4.30)), H = p·q̇ − L = ml²/2 (θ̇² + sin²θ φ̇²) − mgl cos θ
  (notes (4.31)), so the intercept of L's tangent plane is ω = L − p·q̇ = −H;
* L = x ẏ − (x² + y²)/2 of ``configs/hamiltonian_first_order_oscillator.toml``: p = (0, x),
  ∂²L/∂q̇² = 0 (rank 0), as the linear function f = C·x of notes (4.13)–(4.14).
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

from reportgen.core import legendre_geometry as geometry
from reportgen.kinds import load_scene
from reportgen.kinds.hamiltonian.report_legendre import LegendreGeometrySections
from reportgen.scene.config import parse_config_text


def _sphere_grid():
    s = 0.2 * np.arange(-4, 5)
    X, Y = np.meshgrid(s, s)
    inside = X**2 + Y**2 <= 0.85**2
    return X[inside], Y[inside]


# ------------------------------------------------------------------ core: the unit sphere
def test_unit_sphere_tangent_planes_against_the_notes_closed_forms():
    x0, y0 = _sphere_grid()
    z0 = np.sqrt(1 - x0**2 - y0**2)
    planes = geometry.tangent_planes(geometry.unit_hemisphere, x0, y0, 2.5e-4)
    # (4.20): ξ = x₀/z₀, η = y₀/z₀ (measured: 1.7e-12)
    assert np.max(np.abs(planes.xi - x0 / z0)) <= 1e-10
    assert np.max(np.abs(planes.eta - y0 / z0)) <= 1e-10
    # (4.21): ω = 1/z₀; the closed form √(1 + ξ² + η²) (measured: 7.9e-13, 2.2e-16)
    assert np.max(np.abs(planes.omega - 1 / z0)) <= 1e-10
    assert np.max(np.abs(planes.omega - np.sqrt(1 + planes.xi**2 + planes.eta**2))) <= 1e-14
    # and core's closed forms are these
    xi, eta = geometry.unit_sphere_slopes(x0, y0)
    np.testing.assert_allclose(xi, x0 / z0, rtol=0, atol=1e-15)
    np.testing.assert_allclose(geometry.unit_sphere_plane_function(xi, eta), 1 / z0,
                               rtol=1e-14)


def test_plane_function_gives_the_points_back_notes_4_26_4_27():
    x0, y0 = _sphere_grid()
    planes = geometry.tangent_planes(geometry.unit_hemisphere, x0, y0, 2.5e-4)
    dxi, deta = geometry.plane_function_slopes(geometry.unit_hemisphere, planes.xi,
                                               planes.eta, (x0, y0), 2.5e-4, 1.5e-3)
    # ∂ω/∂ξ = x₀, ∂ω/∂η = y₀ (measured: 1.2e-12)
    assert np.max(np.abs(dxi - x0)) <= 1e-10 and np.max(np.abs(deta - y0)) <= 1e-10
    # each shifted ω is the closed form's: ω(ξ, η) = √(1 + ξ² + η²) (measured: 2e-16)
    shifted = geometry.plane_function(geometry.unit_hemisphere, planes.xi + 0.01, planes.eta,
                                      (x0, y0), 2.5e-4)
    np.testing.assert_allclose(shifted, np.sqrt(1 + (planes.xi + 0.01) ** 2 + planes.eta**2),
                               rtol=1e-13)


def test_the_sign_of_4_28_measured_on_the_sphere():
    x0, y0 = _sphere_grid()
    z0 = np.sqrt(1 - x0**2 - y0**2)
    xi, eta = x0 / z0, y0 / z0
    minus, plus, size = geometry.dual_residuals(np.sqrt(1 + xi**2 + eta**2), z0, x0, y0,
                                                xi, eta)
    assert np.max(np.abs(minus)) <= 1e-15 * np.max(size)  # ω − z = xξ + yη
    np.testing.assert_allclose(plus, 2 * z0, rtol=1e-14)  # ω + z − xξ − yη = 2z, not 0


def test_a_quadratic_surface_is_transformed_exactly():
    # z = ½ xᵀA x: tangent point x = −A⁻¹ξ, ω = −½ ξᵀA⁻¹ξ (closed form above)
    A = np.array([[2.0, 0.6], [0.6, 1.0]])

    def z(x, y):
        return 0.5 * (A[0, 0] * x * x + 2 * A[0, 1] * x * y + A[1, 1] * y * y)

    xi = np.array([0.3, -1.2, 2.0])
    eta = np.array([-0.7, 0.4, 1.5])
    s = np.stack([xi, eta])
    x_exact = -np.linalg.solve(A, s)
    x, y = geometry.tangent_point(z, xi, eta, (np.zeros(3), np.zeros(3)), 1e-3)
    np.testing.assert_allclose(np.stack([x, y]), x_exact, rtol=0, atol=1e-12)
    omega = geometry.plane_function(z, xi, eta, (np.zeros(3), np.zeros(3)), 1e-3)
    np.testing.assert_allclose(omega, -0.5 * np.sum(s * np.linalg.solve(A, s), axis=0),
                               rtol=1e-13)


def test_the_difference_stencil_is_fourth_order():
    # error of f′ for f = sin at x = 0.7 against cos 0.7: slope 4 in log(error)/log(h)
    steps = np.array([0.08, 0.04, 0.02, 0.01])
    errors = np.array([abs(float(geometry.derivative(np.sin, 0.7, h)) - math.cos(0.7))
                       for h in steps])
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert slope == pytest.approx(4.0, abs=0.1)


# -------------------------------------------------------------- the kind: stored facts
@pytest.fixture(scope="module")
def pendulum(shipped_archives):
    return shipped_archives("hamiltonian_spherical_pendulum")


def test_spherical_pendulum_stores_the_sphere_and_its_lagrangian_surface(pendulum):
    a = pendulum.analysis
    m, l, g, theta = 1.0, 1.0, 9.81, 1.0  # the config's constants and θ(0)
    np.testing.assert_allclose(np.asarray(a["legendre_velocity_hessian"]),
                               np.diag([m * l**2, m * l**2 * math.sin(theta) ** 2]),
                               rtol=1e-14, atol=1e-15)
    assert a["legendre_convex"]
    # the notes' sphere (measured: 1.7e-12, 2.2e-16, 7.9e-13, 1.2e-12)
    assert a["legendre_sphere_slope_error"] <= 1e-10
    assert a["legendre_sphere_omega_error"] <= 1e-14
    assert a["legendre_sphere_intercept_error"] <= 1e-10
    assert a["legendre_sphere_derivative_error"] <= 1e-10
    sphere = a["legendre_sphere"]
    x0, y0 = np.asarray(sphere["x0"]), np.asarray(sphere["y0"])
    z0 = np.sqrt(1 - x0**2 - y0**2)
    np.testing.assert_allclose(np.asarray(sphere["omega"]), 1 / z0, rtol=1e-10)
    np.testing.assert_allclose(np.asarray(sphere["domega_dxi"]), x0, rtol=0, atol=1e-10)
    # (4.28) measured: ω − z = xξ + yη holds, the printed ω + z = xξ + yη misses by 2z
    assert a["legendre_sphere_relation"] == "minus"
    assert a["legendre_sphere_sign_minus"] <= 1e-15 * a["legendre_sphere_sign_scale"]
    assert a["legendre_sphere_sign_plus"] == pytest.approx(2 * np.max(z0), rel=1e-12)
    # z = L(θ̇, φ̇) at θ = 1, φ = 0: ξ = −p, ω = −H, by hand
    surface = a["legendre_lagrangian"]
    x, y = np.asarray(surface["x"]), np.asarray(surface["y"])
    s2 = math.sin(theta) ** 2
    L = m * l**2 / 2 * (x**2 + s2 * y**2) + m * g * l * math.cos(theta)
    H = m * l**2 / 2 * (x**2 + s2 * y**2) - m * g * l * math.cos(theta)
    np.testing.assert_allclose(np.asarray(surface["z"]), L, rtol=1e-14)
    np.testing.assert_allclose(np.asarray(surface["xi"]), -m * l**2 * x, rtol=0, atol=1e-10)
    np.testing.assert_allclose(np.asarray(surface["eta"]), -m * l**2 * s2 * y, rtol=0,
                               atol=1e-10)
    np.testing.assert_allclose(np.asarray(surface["omega"]), -H, rtol=0, atol=1e-10)
    np.testing.assert_allclose(np.asarray(surface["domega_dxi"]), x, rtol=0, atol=1e-10)
    np.testing.assert_allclose(np.asarray(surface["domega_deta"]), y, rtol=0, atol=1e-10)
    # measured: 4.5e-12, 1.3e-11, 4.9e-12, 3.6e-15
    assert a["legendre_lagrangian_slope_error"] <= 1e-10
    assert a["legendre_lagrangian_omega_error"] <= 1e-10
    assert a["legendre_lagrangian_derivative_error"] <= 1e-10
    assert a["legendre_lagrangian_relation"] == "minus"
    assert a["legendre_lagrangian_sign_plus"] == pytest.approx(2 * np.max(np.abs(L)),
                                                               rel=1e-12)


def test_the_section_is_on_the_page_with_its_measured_sign(pendulum):
    from reportgen.kinds import KINDS
    from reportgen.rendering.report import report_text
    from reportgen.scene.citations import problems
    from reportgen.scene.claims import contradictions

    assert "legendre_geometry" in KINDS[pendulum.kind].default_sections(pendulum)
    text = report_text(pendulum)
    assert "Measured, the dual relation holds as ω − z = xξ + yη" in text
    assert "H = p·q̇ − L, the Hamiltonian of notes (4.31)" in text
    assert contradictions(pendulum, text) == []
    html = (pendulum.path.parent / "report.html").read_text(encoding="utf-8")
    assert '<section id="legendre_geometry">' in html
    assert problems(html) == []


@pytest.mark.parametrize("relation, said, unsaid", [
    ("minus", "holds as ω − z = xξ + yη", "holds as printed"),
    ("plus", "holds as printed", "holds as ω − z"),
    ("neither", "Neither sign", "holds as"),
])
def test_the_sign_sentence_is_chosen_by_the_stored_relation(relation, said, unsaid):
    a = {"legendre_sphere_relation": relation, "legendre_sphere_sign_minus": 1e-16,
         "legendre_sphere_sign_plus": 2.0, "legendre_relation_threshold": 1e-9}
    words = LegendreGeometrySections.relation_words(a, "legendre_sphere")
    assert said in words and unsaid not in words


def _scene(L: str, coordinates: list[str], initial: dict) -> dict:
    text = textwrap.dedent(f"""
        kind = "hamiltonian"
        [system]
        coordinates = {coordinates!r}
        L = "{L}"
        [initial]
        """) + "".join(f"{k} = {v!r}\n" for k, v in initial.items()) + textwrap.dedent("""
        [run]
        t_end = 2.0
        samples = 201
        study = false
        [report]
        sections = ["equations", "legendre_geometry"]
        """)
    return load_scene(parse_config_text(text)).simulate().analysis


def test_the_section_is_computed_only_where_the_scene_asks_for_it():
    """Promise 3: the unit sphere is a lecture of its own; a scene that does not name the
    section keeps the Hessian's facts but gets no tangent planes, and no section."""
    text = textwrap.dedent("""
        kind = "hamiltonian"
        [system]
        coordinates = ["x", "y"]
        L = "(x_dot**2 + y_dot**2)/2 - (x**2 + y**2)/2"
        [initial]
        x = 1.0
        y = 0.0
        x_dot = 0.0
        y_dot = 0.5
        [run]
        t_end = 2.0
        samples = 201
        study = false
        """)
    a = load_scene(parse_config_text(text)).simulate().analysis
    assert bool(a["legendre_convex"]) and "legendre_sphere" not in a


@pytest.mark.parametrize("L, coordinates, initial, convex, shown", [
    # ẋ² − ẏ²: regular (det −1) but indefinite: a saddle, no section
    ("(x_dot**2 - y_dot**2)/2 - (x**2 + y**2)/2", ["x", "y"],
     {"x": 1.0, "y": 0.5, "x_dot": 0.0, "y_dot": 0.3}, False, False),
    # one velocity: the rule asks for two
    ("x_dot**2/2 - x**2/2", ["x"], {"x": 1.0, "x_dot": 0.0}, True, False),
    # a magnetic term b·q̇ (charged particle in a uniform field): convex, shown
    ("(x_dot**2 + y_dot**2)/2 + (x*y_dot - y*x_dot)/2 - (x**2 + y**2)/2", ["x", "y"],
     {"x": 1.0, "y": 0.0, "x_dot": 0.0, "y_dot": 0.5}, True, True),
])
def test_the_rule_is_two_velocities_and_a_positive_definite_hessian(L, coordinates, initial,
                                                                     convex, shown):
    a = _scene(L, coordinates, initial)
    assert bool(a["legendre_convex"]) is convex
    assert ("legendre_sphere" in a) is shown
    if shown:  # ω = −H with the magnetic term too (p = q̇ + b): measured 1e-12
        assert a["legendre_lagrangian_omega_error"] <= 1e-10
        assert a["legendre_lagrangian_relation"] == "minus"


def test_no_geometry_for_a_hamiltonian_given_as_h():
    text = textwrap.dedent("""
        kind = "hamiltonian"
        [system]
        coordinates = ["x", "y"]
        H = "(p_x**2 + p_y**2)/2 + (x**2 + y**2)/2"
        [initial]
        x = 1.0
        y = 0.0
        p_x = 0.0
        p_y = 1.0
        [run]
        t_end = 2.0
        samples = 201
        study = false
        """)
    a = load_scene(parse_config_text(text)).simulate().analysis
    assert not any(k.startswith("legendre_") for k in a)


# ---------------------------------------------------- the linear L: the transform fails
def test_first_order_lagrangian_stores_why_the_transform_fails(shipped_archives):
    from reportgen.rendering.report import report_text
    from reportgen.scene.claims import contradictions

    data = shipped_archives("hamiltonian_first_order_oscillator")
    a = data.analysis
    # L = x ẏ − (x² + y²)/2: p = (0, x) whatever q̇; ∂²L/∂q̇² = 0, rank 0
    assert int(a["first_order_velocity_hessian_rank"]) == 0
    assert not a["first_order_momenta_contain_velocities"]
    np.testing.assert_array_equal(np.asarray(a["first_order_velocity_hessian"]),
                                  np.zeros((2, 2)))
    assert a["first_order_momentum_spread"] == 0.0
    assert a["first_order_momentum_scale"] == pytest.approx(1.0)  # |p_y| = x(0) = 1
    text = report_text(data)
    assert "has rank 0 and p = ∂L/∂q̇ = a(q, t) contains no velocity" in text
    assert "the linear function of notes (4.13)–(4.14)" in text
    assert contradictions(data, text) == []
