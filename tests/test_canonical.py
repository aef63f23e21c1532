"""Canonical transformations from a generating function (reportgen.core.canonical).

References (Goldstein, Poole & Safko, Classical Mechanics, 3rd ed.):
* §9.1, Table 9.1: F1(q, Q, t): p = ∂F1/∂q, P = −∂F1/∂Q; F2(q, P, t): p = ∂F2/∂q,
  Q = ∂F2/∂P; K = H + ∂F/∂t for both.
* §9.2: F1 = qQ exchanges coordinates and momenta (Q = p, P = −q); F2 = qP is the
  identity; F2 = f(q, t)·P is a point transformation.
* §9.3, (9.26)–(9.30): the oscillator's F1 = (mωq²/2) cot Q gives q = √(2P/mω) sin Q,
  p = √(2Pmω) cos Q, K = ωP, so P = E/ω and Q = ωt + α.
* §9.4: a map is canonical iff its Jacobian M satisfies MᵀJM = J (symplectic condition).
* §9.5: the fundamental Poisson brackets {Q_i, P_j} = δ_ij, i.e. M J Mᵀ = J.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy

from reportgen.core import numeric
from reportgen.core.canonical import (
    generating_function,
    hamiltonian_along,
    new_hamiltonian,
    new_variables,
    phase_jacobian,
    poisson_brackets,
    relations_latex,
    symplectic_defect,
    symplectic_defect_of,
)
from reportgen.core.expressions import parse_expression
from reportgen.core.mechanics import PhaseSpace

M, OMEGA = 2.0, 3.0
OSCILLATOR = {"m": M, "omega": OMEGA}
J2 = np.array([[0.0, 1.0], [-1.0, 0.0]])


def H_of(space, text, params=None):
    return parse_expression(text, space.symbols_for_h(), params)


def oscillator_trajectory(t, q0=0.9, p0=-1.7):
    """q(t) = q0 cos ωt + p0/(mω) sin ωt, p = m q̇: the oscillator's closed-form motion."""
    c, s = np.cos(OMEGA * t), np.sin(OMEGA * t)
    return q0 * c + p0 / (M * OMEGA) * s, p0 * c - M * OMEGA * q0 * s


def column(a):
    return np.asarray(a)[:, None]


# ------------------------------------------------------------- F1 = qQ: the exchange
def test_exchange_F1_swaps_coordinate_and_momentum_on_the_oscillator():
    # Goldstein §9.2 / Table 9.1: F1 = qQ gives Q = p, P = −q, K(Q, P) = H(q = −P, p = Q)
    space = PhaseSpace.of(["q"])
    ct = generating_function(space, "q*Q", "F1", ["Q"])
    assert ct.P[0].name == "P_Q"  # the default name of the new momentum
    t = np.linspace(0.0, 5.0, 2001)
    q, p = oscillator_trajectory(t)
    Q, P = new_variables(ct, column(q), column(p), t)
    assert np.array_equal(Q[:, 0], p) and np.array_equal(P[:, 0], -q)

    H = H_of(space, "p_q**2/(2*m) + m*omega**2*q**2/2", OSCILLATOR)
    K = new_hamiltonian(ct, H)
    Qs, Ps = ct.Q[0], ct.P[0]
    assert sympy.simplify(K - (Qs**2 / (2 * M) + M * OMEGA**2 * Ps**2 / 2)) == 0
    along = hamiltonian_along(ct, H, column(q), column(p), Q, P, t)
    energy = p**2 / (2 * M) + M * OMEGA**2 * q**2 / 2
    assert np.abs(along - energy).max() <= 1e-13 * energy.max()

    defect = symplectic_defect(ct, column(q), column(p), Q, P, t)
    assert defect.shape == t.shape and defect.max() <= 1e-13
    np.testing.assert_array_equal(phase_jacobian(ct, column(q), column(p), Q, P, t)[0],
                                  [[0.0, 1.0], [-1.0, 0.0]])  # ∂(Q, P)/∂(q, p)


def test_relations_for_the_report_read_as_the_textbook_writes_them():
    ct = generating_function(PhaseSpace.of(["q"]), "q*Q", "F1", ["Q"], ["P"])
    assert relations_latex(ct) == [
        "F_{1} = Q q",
        r"p_{q} = \frac{\partial F_{1}}{\partial q} = Q",
        r"P = -\frac{\partial F_{1}}{\partial Q} = - q",
        "K = H",
    ]


# ------------------------------------------------------------- F2: identity and polar
def test_identity_F2():
    # Goldstein §9.2: F2 = Σ q_i P_i gives Q = q, P = p, K = H
    space = PhaseSpace.of(["x", "y"])
    ct = generating_function(space, "x*P_X + y*P_Y", "F2", ["X", "Y"], ["P_X", "P_Y"])
    rng = np.random.default_rng(7)
    q, p, t = rng.normal(size=(50, 2)), rng.normal(size=(50, 2)), np.linspace(0, 1, 50)
    Q, P = new_variables(ct, q, p, t)
    assert np.array_equal(Q, q) and np.array_equal(P, p)
    H = H_of(space, "(p_x**2 + p_y**2)/2 + x**4 - x*y")
    X, Y = ct.Q
    PX, PY = ct.P
    assert sympy.simplify(new_hamiltonian(ct, H) - ((PX**2 + PY**2) / 2 + X**4 - X * Y)) == 0
    brackets = poisson_brackets(ct, q, p, Q, P, t)
    assert np.abs(brackets - np.block([[np.zeros((2, 2)), np.eye(2)],
                                       [-np.eye(2), np.zeros((2, 2))]])).max() == 0


POLAR = "P_r*sqrt(x**2 + y**2) + P_phi*atan2(y, x)"
KEPLER = {"m": 1.5, "k": 2.0}


def kepler_orbit(a=1.3, e=0.6, samples=3001):
    """Exact eccentric orbit of H = p²/2m − k/r from the eccentric anomaly E ∈ [0, 4π]:
    x = a(cos E − e), y = b sin E, Ė = n/(1 − e cos E), t = (E − e sin E)/n (Kepler's
    equation, Goldstein §3.8)."""
    m, k = KEPLER["m"], KEPLER["k"]
    mu = k / m
    b, n = a * np.sqrt(1 - e**2), np.sqrt(mu / a**3)
    E = np.linspace(0.0, 4 * np.pi, samples)
    E_dot = n / (1 - e * np.cos(E))
    q = np.stack([a * (np.cos(E) - e), b * np.sin(E)], axis=1)
    p = m * np.stack([-a * np.sin(E) * E_dot, b * np.cos(E) * E_dot], axis=1)
    return q, p, (E - e * np.sin(E)) / n


def polar_transform():
    space = PhaseSpace.of(["x", "y"])
    return space, generating_function(space, POLAR, "F2", ["r", "phi"])


def test_polar_point_transformation_matches_the_hand_formulas():
    # Goldstein §9.2 (point transformation F2 = f(q)·P): r = |q|, φ = atan2(y, x),
    # p_r = (x p_x + y p_y)/r, p_φ = x p_y − y p_x
    space, ct = polar_transform()
    q, p, t = kepler_orbit()
    Q, P = new_variables(ct, q, p, t)
    x, y, px, py = q[:, 0], q[:, 1], p[:, 0], p[:, 1]
    r = np.hypot(x, y)
    np.testing.assert_allclose(Q[:, 0], r, rtol=1e-15)
    np.testing.assert_allclose(Q[:, 1], np.arctan2(y, x), rtol=0, atol=1e-15)
    np.testing.assert_allclose(P[:, 0], (x * px + y * py) / r, rtol=0, atol=1e-14)
    np.testing.assert_allclose(P[:, 1], x * py - y * px, rtol=1e-14)

    # K for the 2-D Kepler problem is the textbook polar H = p_r²/2m + p_φ²/2mr² − k/r
    H = H_of(space, "(p_x**2 + p_y**2)/(2*m) - k/sqrt(x**2 + y**2)", KEPLER)
    K = hamiltonian_along(ct, H, q, p, Q, P, t)
    m, k = KEPLER["m"], KEPLER["k"]
    polar = P[:, 0] ** 2 / (2 * m) + P[:, 1] ** 2 / (2 * m * Q[:, 0] ** 2) - k / Q[:, 0]
    assert np.abs(K - polar).max() <= 1e-14
    assert np.abs(K - (-k / (2 * 1.3))).max() <= 1e-14  # E = −k/2a on the exact orbit
    # the inverse map x = r cos φ, y = r sin φ is not linear: no closed form is attempted
    assert ct.linear is not None and new_hamiltonian(ct, H) is None

    defect = symplectic_defect(ct, q, p, Q, P, t)
    assert defect.max() <= 1e-13
    brackets = poisson_brackets(ct, q, p, Q, P, t)  # {Q_i, P_j} = δ_ij (Goldstein §9.5)
    np.testing.assert_allclose(brackets[:, :2, 2:], np.broadcast_to(np.eye(2), (len(t), 2, 2)),
                               rtol=0, atol=1e-14)


def test_newton_path_agrees_with_the_linear_solve():
    # the same polar momenta by Newton continuation (forced) instead of the exact solve
    _, ct = polar_transform()
    q, p, t = kepler_orbit(samples=20000)
    exact = new_variables(ct, q, p, t)
    iterated = new_variables(ct, q, p, t, method="newton")
    for a, b in zip(exact, iterated, strict=True):
        assert np.abs(a - b).max() <= 1e-13 * np.abs(a).max()


def test_jacobian_by_implicit_differentiation_matches_finite_differences():
    # MᵀJM = J also holds for M⁻¹ or a wrongly ordered M: compare M itself with central
    # differences of the hand-written polar map
    _, ct = polar_transform()
    q, p, t = kepler_orbit(samples=40)

    def polar_map(z):
        x, y, px, py = z.T
        r = np.hypot(x, y)
        return np.stack([r, np.arctan2(y, x), (x * px + y * py) / r, x * py - y * px], axis=1)

    z, h = np.concatenate([q, p], axis=1), 1e-6
    fd = np.stack([(polar_map(z + h * e) - polar_map(z - h * e)) / (2 * h)
                   for e in np.eye(4)], axis=2)
    Q, P = new_variables(ct, q, p, t)
    np.testing.assert_allclose(phase_jacobian(ct, q, p, Q, P, t), fd, rtol=0, atol=1e-8)


# ------------------------------------------------------------- action-angle: Newton
def action_angle():
    space = PhaseSpace.of(["q"])
    return space, generating_function(space, "m*omega*q**2/2*cos(Q)/sin(Q)", "F1", ["Q"],
                                      ["P"], OSCILLATOR)


def test_action_angle_variables_of_the_oscillator():
    # Goldstein (9.26)–(9.30): p = mωq cot Q, P = mωq²/(2 sin²Q) = E/ω, K = ωP, Q = ωt + α.
    # p = ∂F1/∂q is not linear in Q: this is the Newton path.
    space, ct = action_angle()
    assert ct.linear is None
    A, alpha = 1.3, 0.7
    t = np.linspace(0.0, 10.0, 20000)  # ~4.8 periods: Q crosses the poles of cot ~10 times
    q, p = A * np.sin(OMEGA * t + alpha), M * OMEGA * A * np.cos(OMEGA * t + alpha)
    Q, P = new_variables(ct, column(q), column(p), t)
    energy = M * OMEGA**2 * A**2 / 2
    assert np.abs(P[:, 0] - energy / OMEGA).max() <= 1e-14 * energy / OMEGA
    # p/q = mω cot Q fixes Q modulo π only ((q, p) and (−q, −p) share Q mod π and P)
    drift = Q[:, 0] - OMEGA * t - alpha
    assert np.abs(np.angle(np.exp(2j * drift)) / 2).max() <= 1e-13
    # the continuation follows one branch through every pole: Q = ωt + α exactly,
    # starting on the principal branch (−π/2, π/2] at the first sample
    assert np.abs(drift - drift[0]).max() <= 1e-13
    assert abs(drift[0]) <= 1e-14

    H = H_of(space, "p_q**2/(2*m) + m*omega**2*q**2/2", OSCILLATOR)
    K = hamiltonian_along(ct, H, column(q), column(p), Q, P, t)
    assert np.abs(K - OMEGA * P[:, 0]).max() <= 1e-14 * energy
    assert new_hamiltonian(ct, H) is None  # q from P = mωq²/(2 sin²Q) is not linear
    assert symplectic_defect(ct, column(q), column(p), Q, P, t).max() <= 1e-13


def test_action_angle_jacobian_matches_finite_differences():
    # the F1 branch of the implicit differentiation, against Q = atan(mωq/p) and
    # P = p²/(2mω) + mωq²/2 (both from (9.26)–(9.28))
    _, ct = action_angle()
    q, p = np.array([0.3, -0.8, 1.1]), np.array([1.2, 0.9, -2.0])
    t = np.zeros(3)
    Q, P = new_variables(ct, column(q), column(p), t)

    def action_angle_map(q, p):
        return np.stack([np.arctan(M * OMEGA * q / p), p**2 / (2 * M * OMEGA)
                         + M * OMEGA * q**2 / 2], axis=1)

    h = 1e-6
    fd = np.stack([(action_angle_map(q + h, p) - action_angle_map(q - h, p)) / (2 * h),
                   (action_angle_map(q, p + h) - action_angle_map(q, p - h)) / (2 * h)],
                  axis=2)
    np.testing.assert_allclose(phase_jacobian(ct, column(q), column(p), Q, P, t), fd,
                               rtol=0, atol=1e-8)


def test_no_solution_is_reported_with_the_sample():
    # at q = 0, p ≠ 0 the equation p = mωq cot Q has no solution (Q would sit on a pole)
    _, ct = action_angle()
    t = np.linspace(0.0, 1.0, 50)
    q, p = np.linspace(0.4, 0.9, 50), np.ones(50)
    q[0] = 0.0
    with pytest.raises(ValueError, match=r"no solution for Q at sample 0 \(t = 0\)"):
        new_variables(ct, column(q), column(p), t)
    q[0], q[17] = 0.4, 0.0
    with pytest.raises(ValueError, match="at sample 17"):
        new_variables(ct, column(q), column(p), t)


# ------------------------------------------------------------- time-dependent F2
def test_moving_frame_K_is_H_plus_dF2_dt():
    # Galilean boost x = x' + Vt, p = p' + mV: F2 = (mV + P) q − V t P (a time-dependent
    # F2 of Goldstein Table 9.1); K = H + ∂F2/∂t = H − V P
    space = PhaseSpace.of(["q"])
    V = 0.4
    ct = generating_function(space, "(m*V + P)*q - V*t*P", "F2", ["Q"], ["P"],
                             {**OSCILLATOR, "V": V})
    t = np.linspace(0.0, 6.0, 3001)
    q, p = oscillator_trajectory(t)
    Q, P = new_variables(ct, column(q), column(p), t)
    np.testing.assert_allclose(Q[:, 0], q - V * t, rtol=0, atol=1e-15)
    np.testing.assert_allclose(P[:, 0], p - M * V, rtol=0, atol=1e-15)

    H = H_of(space, "p_q**2/(2*m) + m*omega**2*q**2/2", OSCILLATOR)
    energy = p**2 / (2 * M) + M * OMEGA**2 * q**2 / 2
    K_along = hamiltonian_along(ct, H, column(q), column(p), Q, P, t)
    assert np.abs(K_along - (energy - V * P[:, 0])).max() <= 1e-14 * energy.max()

    K = new_hamiltonian(ct, H)
    Qs, Ps, ts = ct.Q[0], ct.P[0], space.t
    textbook = (Ps + M * V) ** 2 / (2 * M) + M * OMEGA**2 * (Qs + V * ts) ** 2 / 2 - V * Ps
    assert sympy.simplify(K - textbook) == 0
    assert relations_latex(ct)[-1] == r"K = H + \frac{\partial F_{2}}{\partial t} = H - 0.4 P"
    # K generates the motion in the new variables: Q̇ = ∂K/∂P, Ṗ = −∂K/∂Q along the
    # exact trajectory, where Q̇ = q̇ − V = p/m − V and Ṗ = ṗ = −mω²q
    values = {Qs: Q[:, 0], Ps: P[:, 0], ts: t}
    Q_dot, P_dot = numeric.evaluate_many([sympy.diff(K, Ps), -sympy.diff(K, Qs)], values)
    assert np.abs(Q_dot - (p / M - V)).max() <= 1e-14
    assert np.abs(P_dot - (-M * OMEGA**2 * q)).max() <= 1e-13


# ------------------------------------------------------------- the symplectic check itself
def test_symplectic_defect_detects_non_canonical_jacobians():
    rotation = np.array([[np.cos(0.3), np.sin(0.3)], [-np.sin(0.3), np.cos(0.3)]])
    shear = np.array([[1.0, 2.5], [0.0, 1.0]])
    assert symplectic_defect_of(np.stack([rotation, shear, J2])).max() <= 1e-15
    # a 1 % scaling: MᵀJM = 1.0201 J, so the defect is 0.0201
    assert symplectic_defect_of((1.01 * rotation)[None])[0] == pytest.approx(0.0201, rel=1e-12)
    # volume-preserving (det 1) but not symplectic in 2 degrees of freedom: q1 → 2 q1,
    # q2 → q2/2 with the momenta unchanged; MᵀJM has {q1, p1} = 2
    squeeze = np.diag([2.0, 0.5, 1.0, 1.0])
    assert np.linalg.det(squeeze) == 1.0
    assert symplectic_defect_of(squeeze[None])[0] == pytest.approx(1.0)


# ------------------------------------------------------------- what is refused
@pytest.mark.parametrize("names, kind, F", [
    (["q"], "F1", "q + Q"),  # ∂²F/∂q∂Q = 0
    (["x", "y"], "F2", "(x + y)*(P_X + P_Y)"),  # rank 1
    (["q"], "F1", "(cos(q)**2 + sin(q)**2 - 1)*q*Q + Q**2"),  # zero only after simplifying
])
def test_degenerate_generating_functions_are_refused(names, kind, F):
    new = [n.upper() for n in names]
    with pytest.raises(ValueError, match="degenerate: det ∂²F[12]/∂q∂[QP] is identically zero"):
        generating_function(PhaseSpace.of(names), F, kind, new)


@pytest.mark.parametrize("kind, F, stray", [
    ("F2", "x*P_X + p_y*P_Y", "p_y"),  # an old momentum
    ("F2", "x*P_X + y*Y", "Y"),  # a new coordinate in F2(q, P, t)
    ("F1", "x*X + y*P_Y", "P_Y"),  # a new momentum in F1(q, Q, t)
])
def test_stray_symbols_are_named(kind, F, stray):
    with pytest.raises(ValueError, match=f"{kind} depends on {stray}; it may depend only on"):
        generating_function(PhaseSpace.of(["x", "y"]), F, kind, ["X", "Y"])


def test_unknown_names_and_expressions_with_stray_symbols():
    space = PhaseSpace.of(["q"])
    with pytest.raises(ValueError, match="undefined name 'z'"):
        generating_function(space, "q*Q + z", "F1", ["Q"])
    z = sympy.Symbol("z")
    with pytest.raises(ValueError, match="F1 depends on z"):
        generating_function(space, sympy.Symbol("q") * sympy.Symbol("Q") + z, "F1", ["Q"])
    # symbols of a given expression are matched by name, whatever their assumptions
    ct = generating_function(space, sympy.Symbol("q") * sympy.Symbol("Q"), "F1", ["Q"])
    assert ct.momenta == (ct.Q[0],)


@pytest.mark.parametrize("kind, coordinates, momenta, message", [
    ("F5", ["X", "Y"], None, "kind 'F5': expected one of F1, F2, F3, F4"),
    ("F2", ["X"], None, "expected 2 new coordinate names"),
    ("F2", ["X", "X"], None, "distinct: P_X, X repeated"),  # and the default P_X
    ("F2", ["X", "Y"], ["P_X", "X"], "distinct: X repeated"),
    ("F2", ["x", "Y"], None, "x: already a name of the old system"),
    ("F2", ["X", "Y"], ["p_x", "P_Y"], "p_x: already a name of the old system"),
    ("F2", ["X", "t"], None, "t: already a name of the old system"),
    ("F2", ["X", "2Y"], None, "'2Y' is not a valid name"),
])
def test_new_names_are_checked(kind, coordinates, momenta, message):
    with pytest.raises(ValueError, match=message):
        generating_function(PhaseSpace.of(["x", "y"]), "x*P_X + y*P_Y", kind, coordinates,
                            momenta)


def test_sample_shapes_are_checked():
    _, ct = polar_transform()
    with pytest.raises(ValueError, match=r"q: expected shape \(3, 2\), got \(3,\)"):
        new_variables(ct, np.ones(3), np.ones((3, 2)), np.zeros(3))
