"""Symbolic mechanics from written formulas (issue 14's groundwork): Hamilton's equations,
the Legendre transform, Poisson brackets and cyclic coordinates, against textbook forms."""

from __future__ import annotations

import numpy as np
import pytest
import sympy

from reportgen.core.expressions import parse_expression
from reportgen.core.mechanics import (
    PhaseSpace,
    cyclic_coordinates,
    hamiltonian_system,
    legendre,
    poisson_bracket,
)


def H_of(space, text, params=None):
    return parse_expression(text, space.symbols_for_h(), params)


def L_of(space, text, params=None):
    return parse_expression(text, space.symbols_for_l(), params)


def test_kepler_equations_and_angular_momentum():
    s = PhaseSpace.of(["x", "y"])
    x, y = s.q
    px, py = s.p
    sys_ = hamiltonian_system(s, H_of(s, "(p_x**2 + p_y**2)/2 - k/sqrt(x**2 + y**2)",
                                      {"k": 1.0}))
    r3 = (x**2 + y**2) ** sympy.Rational(3, 2)
    assert sys_.qdot == (px, py)
    assert sympy.simplify(sys_.pdot[0] + x / r3) == 0  # ṗ_x = −k x / r³ (Goldstein 3.x)
    assert sympy.simplify(sys_.pdot[1] + y / r3) == 0
    Lz = H_of(s, "x*p_y - y*p_x")
    assert poisson_bracket(s, Lz, sys_.H) == 0  # conserved: {L_z, H} = 0
    assert poisson_bracket(s, x, px) == 1  # canonical: {q, p} = 1
    assert cyclic_coordinates(s, sys_.H) == []


def test_polar_lagrangian_gives_the_central_force_hamiltonian():
    # L = m(ṙ² + r²φ̇²)/2 + k/r  ->  H = p_r²/2m + p_φ²/(2mr²) − k/r (Goldstein 8.x)
    s = PhaseSpace.of(["r", "phi"])
    r, phi = s.q
    pr, pphi = s.p
    leg = legendre(s, L_of(s, "m*(r_dot**2 + r**2*phi_dot**2)/2 + k/r", {"m": 2.0, "k": 3.0}))
    expected = pr**2 / 4 + pphi**2 / (4 * r**2) - 3 / r
    assert sympy.simplify(leg.H - expected) == 0
    assert leg.velocities == (pr / 2, pphi / (2 * r**2))
    assert cyclic_coordinates(s, leg.H) == ["phi"]  # p_φ conserved


def test_charged_particle_legendre_with_a_linear_term():
    # L = ½(ẋ² + ẏ²) + B(xẏ − yẋ)/2 (uniform field, symmetric gauge): p = q̇ + A,
    # H = ½[(p_x + By/2)² + (p_y − Bx/2)²]
    s = PhaseSpace.of(["x", "y"])
    x, y = s.q
    px, py = s.p
    leg = legendre(s, L_of(s, "(x_dot**2 + y_dot**2)/2 + B*(x*y_dot - y*x_dot)/2", {"B": 2.0}))
    assert sympy.simplify(leg.H - ((px + y) ** 2 + (py - x) ** 2) / 2) == 0


def test_legendre_checked_numerically_on_a_point():
    # H(q, p(q, q̇)) = p·q̇ − L at an arbitrary point, for the double-pendulum-like L
    s = PhaseSpace.of(["a", "b"])
    L = L_of(s, "a_dot**2 + b_dot**2/2 + a_dot*b_dot*cos(a - b) + 9.81*(2*cos(a) + cos(b))")
    leg = legendre(s, L)
    point = {s.q[0]: 0.3, s.q[1]: -0.7, s.qdot[0]: 1.1, s.qdot[1]: -0.4}
    momenta = [float(m.subs(point)) for m in leg.momenta]
    H_num = float(leg.H.subs({s.q[0]: 0.3, s.q[1]: -0.7, s.p[0]: momenta[0],
                              s.p[1]: momenta[1]}))
    direct = sum(p * float(v) for p, v in zip(momenta, (1.1, -0.4), strict=True)) \
        - float(L.subs(point))
    assert H_num == pytest.approx(direct, rel=1e-12)


def test_jacobi_identity_on_a_sample():
    s = PhaseSpace.of(["x", "y"])
    f = H_of(s, "x*p_y - y*p_x")
    g = H_of(s, "p_x**2 + x*y")
    h = H_of(s, "sin(x)*p_y + y**2")
    pb = lambda a, b: poisson_bracket(s, a, b)  # noqa: E731
    jacobi = pb(f, pb(g, h)) + pb(g, pb(h, f)) + pb(h, pb(f, g))
    rng = np.random.default_rng(3)
    for _ in range(5):
        point = dict(zip(s.q + s.p, rng.normal(size=4), strict=True))
        assert abs(float(jacobi.subs(point))) < 1e-12


def test_irregular_or_non_quadratic_lagrangians_refused():
    s = PhaseSpace.of(["x", "y"])
    with pytest.raises(ValueError, match="singular"):
        legendre(s, L_of(s, "(x_dot + y_dot)**2/2"))
    with pytest.raises(ValueError, match="not quadratic"):
        legendre(s, L_of(s, "x_dot**4"))
    with pytest.raises(ValueError, match="distinct"):
        PhaseSpace.of(["x", "x"])
