"""The ``hamiltonian`` kind, issue 33: surfaces of section located on the integrator's steps,
bracket checks relative to the size of their terms, generating functions of all four types
and infinitesimal canonical transformations, and Noether charges of a declared symmetry.

Every reference is independent of the kind's derivation: Hénon–Heiles' H written out, scipy's
DOP853 event location, closed forms worked out by hand below.

References (Goldstein, Poole & Safko, Classical Mechanics, 3rd ed.):
* §9.1, Table 9.1: F3(p, Q, t): q = −∂F3/∂p, P = −∂F3/∂Q; F4(p, P, t): q = −∂F4/∂p,
  Q = ∂F4/∂P; F3 = pQ gives Q = −q, P = −p and F4 = pP gives Q = p, P = −q;
* §9.4–§9.5: canonical iff MᵀJM = J, iff {Qᵢ, Pⱼ} = δᵢⱼ;
* §9.6: the infinitesimal canonical transformation δq = ε ∂G/∂p, δp = −ε ∂G/∂q and
  δH = ε{H, G}; §2.7 / §8.2: Noether's theorem, the charge Σ ∂L/∂q̇ δq (− F).
Lecture notes (6.4)–(6.5) and (6.12)–(6.14) (types 1 and 3; all four: Goldstein Table
9.1), (6.16–6.18) (infinitesimal), (3.9–3.16) (Noether), (3.48–3.49) (L + dF/dt).
Hénon & Heiles, Astron. J. 69, 73 (1964): H = (p_x² + p_y²)/2 + (x² + y²)/2 + x²y − y³/3.
Hairer, Nørsett & Wanner, Solving ODEs I, §II.6: event location on dense output.
"""

from __future__ import annotations

import textwrap

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp

from reportgen.core import canonical, formula, mechanics, numeric
from reportgen.core.expressions import parse_expression
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, parse_config_text


def scene_of(text: str):
    return load_scene(parse_config_text(textwrap.dedent(text)))


def henon_heiles_energy(x, y, px, py):
    """H of Hénon & Heiles (1964), written out."""
    return (px**2 + py**2) / 2 + (x**2 + y**2) / 2 + x**2 * y - y**3 / 3


def henon_heiles_rhs(t, s):
    x, y, px, py = s
    return [px, py, -x - 2 * x * y, -y - x**2 + y**2]


def henon_heiles(samples: int, t_end: float, energy: float = 0.14, extra: str = "",
                 section: str = 'coordinate = "x"\naxes = ["y", "p_y"]') -> str:
    return f"""
kind = "hamiltonian"
[system]
coordinates = ["x", "y"]
H = "(p_x**2 + p_y**2)/2 + (x**2 + y**2)/2 + x**2*y - y**3/3"
[initial]
x = 0.0
y = 0.1
p_y = 0.0
energy = {energy!r}
[section]
{section}
[run]
t_end = {t_end!r}
samples = {samples}
study = false
{extra}
"""


# ------------------------------------------------------------ 1. crossings on the steps
@pytest.fixture(scope="module")
def sparse_section():
    """H = 0.14, t = 600 stored at only 1,201 samples (Δt = 0.5, ~12 per oscillation):
    interpolating between samples put the crossings 1.1e-4 off the energy surface."""
    scene = scene_of(henon_heiles(1201, 600.0))
    return scene, scene.simulate()


def test_crossings_lie_on_the_energy_surface_whatever_the_samples(sparse_section):
    _, results = sparse_section
    a = results.analysis
    state = a["poincare"]["state"]
    assert a["poincare_located"] == "steps" and len(state) >= 80
    # H written out by hand at every crossing, against H(0) = 0.14
    H = henon_heiles_energy(*state.T)
    assert np.max(np.abs(H - 0.14)) / 0.14 <= 1e-9
    assert a["poincare_H_relative_error"] <= 1e-9
    assert a["poincare_H_relative_error"] == pytest.approx(np.max(np.abs(H - 0.14)) / 0.14,
                                                            rel=1e-6)
    # on the surface x = 0 to rounding, crossed upward (ẋ = p_x > 0)
    assert np.max(np.abs(state[:, 0])) <= 1e-13 and np.all(state[:, 2] > 0)
    check = next(c for c in results.checks if c.quantity.startswith("H at the crossing"))
    assert check.rel_error == pytest.approx(a["poincare_H_relative_error"], rel=1e-12)


def test_crossings_do_not_depend_on_the_samples(sparse_section):
    # the steps are DOP853's own (never shortened for an output), so the crossings located
    # on them are the same, to the bit, for 1,201 or 12,001 stored samples
    _, sparse = sparse_section
    dense = scene_of(henon_heiles(12001, 600.0)).simulate()
    for name in ("t", "state"):
        assert np.array_equal(sparse.analysis["poincare"][name],
                              dense.analysis["poincare"][name])


def test_crossings_match_scipy_event_location(sparse_section):
    # scipy's DOP853 at rtol 1e-13 locating the same events on its own dense output: the
    # orbit at H = 0.14 is regular, so the two integrations stay close for t ≤ 100
    _, results = sparse_section
    pts = results.analysis["poincare"]

    def surface(t, s):
        return s[0]

    surface.direction = 1.0
    y0 = results.runs["main"].y[0]
    sol = solve_ivp(henon_heiles_rhs, (0.0, 100.0), y0, method="DOP853", rtol=1e-13,
                    atol=1e-13, events=surface)
    t_ev = sol.t_events[0][sol.t_events[0] > 1e-9]  # t = 0 is on the surface, not a crossing
    ours = pts["t"][pts["t"] <= 100.0]
    assert len(ours) == len(t_ev) >= 10
    assert np.max(np.abs(ours - t_ev)) <= 1e-8


@pytest.mark.parametrize("direction, scipy_direction", [("down", -1.0), ("both", 0.0)])
def test_down_and_both_directions_match_scipy_events(direction, scipy_direction):
    # the surface y = 0.2, which the orbit at H = 1/12 reaches on some oscillations only:
    # with "both", the turning points of y below or above 0.2 are roots of the second
    # factor ẏ and must be dropped (formula.section_rows)
    text = henon_heiles(2001, 120.0, energy=1 / 12,
                        section=f'coordinate = "y"\nvalue = 0.2\ndirection = "{direction}"')
    results = scene_of(text).simulate()
    pts = results.analysis["poincare"]

    def surface(t, s):
        return s[1] - 0.2

    surface.direction = scipy_direction
    y0 = results.runs["main"].y[0]
    sol = solve_ivp(henon_heiles_rhs, (0.0, 120.0), y0, method="DOP853", rtol=1e-13,
                    atol=1e-13, events=surface)
    t_ev = sol.t_events[0]
    assert len(pts["t"]) == len(t_ev) >= 8
    assert np.max(np.abs(pts["t"] - t_ev)) <= 1e-8
    assert np.max(np.abs(pts["state"][:, 1] - 0.2)) <= 1e-13
    slopes = pts["state"][:, 3]  # ẏ = p_y
    if direction == "down":
        assert np.all(slopes < 0)
    else:
        assert np.any(slopes < 0) and np.any(slopes > 0)


def test_a_fixed_step_method_falls_back_to_the_samples():
    # no continuous extension: located between samples, and said so
    results = scene_of(henon_heiles(6001, 60.0, extra='method = "rk4"\nh = 0.01')).simulate()
    a = results.analysis
    assert a["poincare_located"] == "samples"
    assert a["poincare_H_relative_error"] <= 1e-6  # interpolation, not the steps


def test_section_factors_print_the_value_as_its_float():
    # the level is printed by repr of its float (no config text), and is that float exactly
    system = formula.build_system(["x", "y"], H="(p_x**2 + p_y**2)/2 + x**2*y")
    source = formula.section_source(system, 1, 0.1, "down")
    assert "0.1" in source and "y[1]" in source
    (g,) = formula.section_factors(system, 1, 0.1, "down")
    assert float(g.subs(system.state_symbols[1], 0.0)) == 0.1
    assert len(formula.section_factors(system, 1, 0.1, "both")) == 2
    with pytest.raises(ValueError, match="direction"):
        formula.section_factors(system, 0, 0.0, "sideways")


def test_shipped_chaotic_section_shows_h_at_the_crossings(shipped_archives):
    from reportgen.kinds.hamiltonian import HamiltonianScene

    data = shipped_archives("hamiltonian_henon_heiles_chaotic")
    a = data.analysis
    assert a["poincare_located"] == "steps"
    state = np.asarray(a["poincare"]["state"])
    H0 = 1 / 6
    assert np.max(np.abs(henon_heiles_energy(*state.T) - H0)) / H0 <= 1e-9
    content = HamiltonianScene.section_poincare(data)
    facts = dict(content.facts)
    from reportgen.scene.content import fmt_err

    shown = fmt_err(a["poincare_H_relative_error"])
    # relative to the energy scale max(|H0|, |T0|, |V0|) of the run's drift, not to |H(0)|
    assert facts["max |H − H(0)| at the crossings, relative to the energy scale"] == shown
    assert shown in content.figures[0].caption


# ------------------------------------------------------------ 2. bracket checks
def test_roundoff_scale_adds_the_sizes_of_the_parts():
    x, y = sympy.symbols("x y", real=True)
    # |x y| + |2 x| at x = 3, y = −1: 3 + 6 (the value itself is −3 − 6 = −9)
    assert float(mechanics.roundoff_scale(x * y - 2 * x, {x: 3.0, y: -1.0})) == 9.0
    # a sum inside a product counts by its parts: (x − y)² → (|x| + |y|)²
    assert float(mechanics.roundoff_scale((x - y) ** 2, {x: 3.0, y: 3.0})) == 36.0


def central_system():
    from reportgen.kinds.hamiltonian.config import PRESETS

    pre = PRESETS["central_potential"]
    return formula.build_system(pre["system"]["coordinates"], H=pre["system"]["H"],
                                observables={**pre["observables"], "z": "r*cos(theta)"},
                                params=pre["params"])


def test_jacobi_terms_of_conserved_observables_are_round_off():
    # {Lx, {Ly, H}} = {Ly, {H, Lx}} = 0 and {H, {Lx, Ly}} = {H, Lz} = 0 identically
    # (Goldstein §9.7): evaluated they are ~1e-14, rounding of parts ~1e2, and must be
    # recognised as zero; with z = r cos θ (not conserved) two terms are not
    from reportgen.kinds.hamiltonian.analysis import jacobi_terms

    system = central_system()
    rng = np.random.default_rng(3)
    y = rng.uniform(0.5, 1.4, (40, 6))
    vals = system.values(y, np.zeros(40))
    obs = system.observables
    _, sizes, rounding, vanish = jacobi_terms(system.space, obs["Lx"], obs["Ly"], system.H,
                                              vals, (40,))
    assert all(vanish) and max(sizes) > 0  # nonzero numbers, yet rounding
    values, sizes, rounding, vanish = jacobi_terms(system.space, obs["L2"], obs["z"],
                                                   system.H, vals, (40,))
    # {z, {H, L2}} vanishes ({H, L2} = 0); the other two are equal and opposite
    assert vanish == [False, True, False]
    assert min(sizes[0], sizes[2]) > 1e-3
    assert np.max(np.abs(values[0] + values[2])) <= 1e-13 * sizes[0]


def test_shipped_central_config_tests_the_jacobi_identity_on_nonzero_terms():
    from pathlib import Path

    text = (Path(__file__).resolve().parent.parent / "configs"
            / "hamiltonian_central_3d.toml").read_text()
    results = load_scene(parse_config_text(text + "\nstudy = false\n")).simulate()
    a = results.analysis
    assert a["jacobi_tested"] and a["jacobi_triple"][1] == "r*cos(theta)"
    terms = np.asarray(a["jacobi_terms"])
    assert np.sum(terms > 1e-3) >= 2
    assert a["jacobi_relative"] <= 1e-14  # rounding of terms of order one
    check = next(c for c in results.checks if c.quantity.startswith("Jacobi identity"))
    assert check.scale == a["jacobi_scale"] and check.rel_error == pytest.approx(
        a["jacobi_relative"], rel=1e-12, abs=1e-300)


def test_jacobi_is_not_tested_when_every_term_vanishes():
    # H = c (a constant): every bracket with H is zero, so all three terms vanish for any f,
    # g -- the identity is not tested, and the report says so instead of "holds"
    from reportgen.kinds.hamiltonian import HamiltonianScene
    from reportgen.kinds.hamiltonian.analysis import jacobi_terms

    system = central_system()
    c = sympy.Float(0.7)
    vals = system.values(np.random.default_rng(1).uniform(0.5, 1.4, (20, 6)), np.zeros(20))
    obs = system.observables
    _, _, _, vanish = jacobi_terms(system.space, obs["L2"], obs["z"], c, vals, (20,))
    assert all(vanish)
    words = HamiltonianScene.jacobi_words({"jacobi_tested": False,
                                           "jacobi_terms": np.array([0.0, 0.0, 0.0]),
                                           "jacobi_max": 0.0, "jacobi_scale": 0.0})
    assert words.startswith("not tested: every term is round-off")
    words = HamiltonianScene.jacobi_words({"jacobi_tested": True, "jacobi_terms": [2.0, 1.0],
                                           "jacobi_max": 1e-6, "jacobi_scale": 3.0,
                                           "jacobi_relative": 1e-6 / 3.0})
    assert words.startswith("FAILS")  # 3e-7 of the terms is far above rounding


def test_the_canonical_bracket_check_is_relative_to_its_terms():
    # {Q, P} of Q = q/a, P = a p (a canonical scaling) with a = 1e8: the bracket's terms
    # are 1 each, its departure rounding; a map scaling both by 1.01 departs by 0.0201
    M = np.array([[[1e-8, 0.0], [0.0, 1e8]]])
    J = canonical.symplectic_unit(1)
    B = M @ J @ np.swapaxes(M, -1, -2)
    assert canonical.bracket_departure(B, canonical.bracket_sizes(M)) <= 1e-15
    M = 1.01 * np.eye(2)[None]
    B = M @ J @ np.swapaxes(M, -1, -2)
    assert canonical.bracket_departure(B, canonical.bracket_sizes(M)) == pytest.approx(
        0.0201 / 1.0201, rel=1e-12)


# ------------------------------------------------------------ 3. F3, F4, infinitesimal
def column(a):
    return np.asarray(a)[:, None]


def test_F3_pQ_and_F4_pP_are_goldsteins_maps():
    # Goldstein Table 9.1: F3 = pQ gives Q = −q, P = −p; F4 = pP gives Q = p, P = −q
    space = mechanics.PhaseSpace.of(["q"])
    rng = np.random.default_rng(5)
    q, p, t = rng.normal(size=40), rng.normal(size=40), np.linspace(0, 1, 40)
    ct3 = canonical.generating_function(space, "p_q*Q", "F3", ["Q"], ["P"])
    Q, P = canonical.new_variables(ct3, column(q), column(p), t)
    assert np.array_equal(Q[:, 0], -q) and np.array_equal(P[:, 0], -p)
    ct4 = canonical.generating_function(space, "p_q*P", "F4", ["Q"], ["P"])
    Q, P = canonical.new_variables(ct4, column(q), column(p), t)
    assert np.array_equal(Q[:, 0], p) and np.array_equal(P[:, 0], -q)
    J = canonical.symplectic_unit(1)
    for ct in (ct3, ct4):
        Q, P = canonical.new_variables(ct, column(q), column(p), t)
        np.testing.assert_array_equal(canonical.poisson_brackets(ct, column(q), column(p), Q,
                                                                 P, t)[0], J)
    assert canonical.relations_latex(ct3)[1] == r"q = -\frac{\partial F_{3}}{\partial p_{q}} = - Q"
    with pytest.raises(ValueError, match=r"degenerate: det ∂²F3/∂p∂Q"):
        canonical.generating_function(space, "p_q + Q", "F3", ["Q"])


def kepler_orbit(a=1.3, e=0.6, m=1.5, k=2.0, samples=3001):
    """The exact eccentric Kepler orbit from the eccentric anomaly E ∈ [0, 4π] (Goldstein
    §3.8): x = a(cos E − e), y = b sin E, Ė = n/(1 − e cos E)."""
    b, n = a * np.sqrt(1 - e**2), np.sqrt(k / m / a**3)
    E = np.linspace(0.0, 4 * np.pi, samples)
    E_dot = n / (1 - e * np.cos(E))
    q = np.stack([a * (np.cos(E) - e), b * np.sin(E)], axis=1)
    p = m * np.stack([-a * np.sin(E) * E_dot, b * np.cos(E) * E_dot], axis=1)
    return q, p, (E - e * np.sin(E)) / n


def test_F3_polar_point_transformation_matches_the_hand_formulas():
    # F3 = −(p_x r cos φ + p_y r sin φ): x = r cos φ, y = r sin φ, P_r = p·r̂, P_φ = x p_y − y p_x
    space = mechanics.PhaseSpace.of(["x", "y"])
    ct = canonical.generating_function(space, "-(p_x*r*cos(phi) + p_y*r*sin(phi))", "F3",
                                       ["r", "phi"], ["P_r", "P_phi"])
    q, p, t = kepler_orbit()
    Q, P = canonical.new_variables(ct, q, p, t)
    x, y = q.T
    r = np.hypot(x, y)
    np.testing.assert_allclose(Q[:, 0], r, rtol=1e-13)
    # φ followed continuously through ±π over two revolutions
    np.testing.assert_allclose(Q[:, 1], np.unwrap(np.arctan2(y, x)), rtol=0, atol=1e-12)
    np.testing.assert_allclose(P[:, 0], (x * p[:, 0] + y * p[:, 1]) / r, rtol=0, atol=1e-12)
    np.testing.assert_allclose(P[:, 1], x * p[:, 1] - y * p[:, 0], rtol=0, atol=1e-12)
    assert canonical.symplectic_defect(ct, q, p, Q, P, t).max() <= 1e-12
    M = canonical.phase_jacobian(ct, q, p, Q, P, t)
    B = M @ canonical.symplectic_unit(2) @ np.swapaxes(M, -1, -2)
    assert canonical.bracket_departure(B, canonical.bracket_sizes(M)) <= 1e-14
    # K from the explicit relation, linear in p (Goldstein §8.1's polar H)
    m, k = 1.5, 2.0
    H = parse_expression("(p_x**2 + p_y**2)/(2*m) - k/sqrt(x**2 + y**2)",
                         space.symbols_for_h(), {"m": m, "k": k})
    K = canonical.new_hamiltonian(ct, H)
    rs, Pr, Pphi = ct.Q[0], ct.P[0], ct.P[1]
    values = {rs: np.array([0.7, 1.9]), Pr: np.array([0.3, -1.1]), Pphi: np.array([2.0, 0.4]),
              ct.Q[1]: np.array([0.2, 2.9])}
    hand = (values[Pr] ** 2 + values[Pphi] ** 2 / values[rs] ** 2) / (2 * m) - k / values[rs]
    np.testing.assert_allclose(numeric.evaluate(K, values), hand, rtol=1e-14)


def test_F3_jacobian_matches_finite_differences():
    space = mechanics.PhaseSpace.of(["x", "y"])
    ct = canonical.generating_function(space, "-(p_x*r*cos(phi) + p_y*r*sin(phi))", "F3",
                                       ["r", "phi"], ["P_r", "P_phi"])

    def polar(q, p):
        x, y = q.T
        r = np.hypot(x, y)
        return np.stack([r, np.arctan2(y, x), (x * p[:, 0] + y * p[:, 1]) / r,
                         x * p[:, 1] - y * p[:, 0]], axis=1)

    rng = np.random.default_rng(9)
    q, p = rng.uniform(0.3, 1.2, (4, 2)), rng.normal(size=(4, 2))
    t = np.zeros(4)
    Q, P = canonical.new_variables(ct, q, p, t)
    h = 1e-6
    fd = np.empty((4, 4, 4))
    for j in range(4):
        dz = np.zeros(4)
        dz[j] = h
        up, down = (polar(q + s * dz[:2], p + s * dz[2:]) for s in (1, -1))
        fd[:, :, j] = (up - down) / (2 * h)
    np.testing.assert_allclose(canonical.phase_jacobian(ct, q, p, Q, P, t), fd, rtol=0,
                               atol=1e-8)


OSC = {"m": 1.7, "omega": 1.3}


def test_infinitesimal_dilation_of_the_oscillator_in_closed_form():
    # G = x p_x + y p_y: Q = (1 + ε) q, P = (1 − ε) p.  By hand: {Q_x, P_x} = 1 − ε²
    # (others 0); ε{H, G} = ε(mω² r² − p²/m) = 2ε(V − T); H quadratic, so exactly
    # ΔH = 2ε(V − T) + ε² H (wᵀ∇²H w = p²/m + mω² r² = 2H)
    space = mechanics.PhaseSpace.of(["x", "y"])
    eps = 1e-3
    it = canonical.infinitesimal(space, "x*p_x + y*p_y", eps, ["X", "Y"], ["PX", "PY"])
    rng = np.random.default_rng(2)
    q, p, t = rng.normal(size=(30, 2)), rng.normal(size=(30, 2)), np.zeros(30)
    Q, P = canonical.infinitesimal_new_variables(it, q, p, t)
    np.testing.assert_allclose(Q, (1 + eps) * q, rtol=1e-15)
    np.testing.assert_allclose(P, (1 - eps) * p, rtol=1e-15)
    B, R = canonical.infinitesimal_brackets(it)
    assert all(sympy.expand(e) == 0 for e in B - R)
    values = {s: v for s, v in zip(space.q + space.p, [*q.T, *p.T], strict=True)}
    values[it.epsilon] = eps
    QxPx = numeric.evaluate(B[0, 2], values)
    np.testing.assert_allclose(QxPx, 1 - eps**2, rtol=1e-15)
    assert np.all(numeric.evaluate(B[0, 3], values) == 0)
    m, w = OSC["m"], OSC["omega"]
    H = parse_expression("(p_x**2 + p_y**2)/(2*m) + m*omega**2*(x**2 + y**2)/2",
                         space.symbols_for_h(), OSC)
    dH, first, second = canonical.change_of_hamiltonian(it, H)
    T = (p**2).sum(axis=1) / (2 * m)
    V = m * w**2 * (q**2).sum(axis=1) / 2
    np.testing.assert_allclose(numeric.evaluate(first, values), 2 * eps * (V - T),
                               rtol=1e-13)
    np.testing.assert_allclose(numeric.evaluate(dH, values),
                               2 * eps * (V - T) + eps**2 * (T + V), rtol=1e-10, atol=1e-17)
    np.testing.assert_allclose(numeric.evaluate(second, values), eps**2 * (T + V),
                               rtol=1e-13)


def test_infinitesimal_rotation_leaves_a_central_H_unchanged_to_first_order():
    # G = Lz generates rotations: {H, Lz} = 0 for V(r).  The unnormalised rotation scales
    # r² and p² by 1 + ε² exactly, so by hand ΔH = ε² p²/2 − (1/r)(1/√(1 + ε²) − 1) for
    # Kepler's H: no first-order change, and ΔH − ε²/2 wᵀ∇²H w is of fourth order (H(Q, P)
    # depends on ε² only), so halving ε divides it by 16
    space = mechanics.PhaseSpace.of(["x", "y"])
    H = parse_expression("(p_x**2 + p_y**2)/2 - 1/sqrt(x**2 + y**2)", space.symbols_for_h())
    rng = np.random.default_rng(4)
    q, p = rng.uniform(0.5, 1.5, (20, 2)), rng.normal(size=(20, 2))
    r, p2 = np.hypot(*q.T), (p**2).sum(axis=1)
    residuals = []
    for eps in (1e-2, 5e-3):
        it = canonical.infinitesimal(space, "x*p_y - y*p_x", eps, ["X", "Y"])
        dH, first, second = canonical.change_of_hamiltonian(it, H)
        assert sympy.simplify(first) == 0
        values = {s: v for s, v in zip(space.q + space.p, [*q.T, *p.T], strict=True)}
        values[it.epsilon] = eps
        d, s2 = (numeric.evaluate(e, values) for e in (dH, second))
        hand = eps**2 * p2 / 2 - (1 / np.sqrt(1 + eps**2) - 1) / r
        np.testing.assert_allclose(d, hand, rtol=1e-9)  # ΔH ~ 1e-4: rounding of H ~ 1e-16
        residuals.append(np.max(np.abs(d - s2)))
    assert residuals[0] / residuals[1] == pytest.approx(16.0, rel=0.01)


def test_shipped_isotropic_oscillator_shows_the_dilation():
    from pathlib import Path

    text = (Path(__file__).resolve().parent.parent / "configs"
            / "hamiltonian_isotropic_oscillator.toml").read_text()
    results = load_scene(parse_config_text(text + "\nstudy = false\n")).simulate()
    a = results.analysis
    assert a["transform_kind"] == "G" and a["transform_bracket_symbolic"]
    eps = a["transform_epsilon"]
    assert a["transform_bracket_max"] == pytest.approx(eps**2, rel=1e-6)  # |{Q, P} − 1| = ε²
    assert a["transform_bracket_agreement"] <= 1e-14
    # exact to second order (H quadratic): what is left is rounding of ΔH ~ 1e-3
    assert a["transform_second_order_residual"] <= 1e-14
    run = results.runs["main"]
    x, y, px, py = run.y.T
    T, V = (px**2 + py**2) / 2, 1.69 * (x**2 + y**2) / 2
    np.testing.assert_allclose(a["transform"]["dH"], 2 * eps * (V - T) + eps**2 * (T + V),
                               rtol=0, atol=1e-15)


def test_shipped_F3_config_integrates_K_against_the_image():
    from pathlib import Path

    text = (Path(__file__).resolve().parent.parent / "configs"
            / "hamiltonian_kepler_polar_f3.toml").read_text()
    results = load_scene(parse_config_text(text + "\nstudy = false\n")).simulate()
    a = results.analysis
    assert a["transform_kind"] == "F3" and "transformed" in results.runs
    assert a["transform_bracket_relative"] <= 1e-14
    assert a["transform_run_difference"] <= 1e-9
    run = results.runs["main"]
    x, y, px, py = run.y.T
    np.testing.assert_allclose(a["transform"]["P"][:, 1], x * py - y * px, rtol=0, atol=1e-13)
    np.testing.assert_allclose(a["transform"]["Q"][:, 0], np.hypot(x, y), rtol=1e-13)


@pytest.mark.parametrize("table, message", [
    ('F3 = "p_x*X + p_y*Y"\nG = "x*p_x"\ncoordinates = ["X", "Y"]', "give exactly one of"),
    ('F2 = "x*P_X + y*P_Y"\nepsilon = 0.1\ncoordinates = ["X", "Y"]', "only with G"),
    ('F3 = "x*X + p_y*Y"\ncoordinates = ["X", "Y"]', "undefined name 'x'"),
    ('F3 = "p_x*X + p_y*Y"', "required key is missing"),
    ('G = "x*p_x"\nepsilon = 0.0', "finite nonzero"),
    ('G = "x*p_x + X"', "undefined name 'X'"),
])
def test_transform_config_errors_name_the_key(table, message):
    text = f"""
kind = "hamiltonian"
[system]
coordinates = ["x", "y"]
H = "(p_x**2 + p_y**2)/2 + (x**2 + y**2)/2"
[transform]
{table}
[initial]
x = 1.0
y = 0.0
p_x = 0.0
p_y = 1.0
[run]
t_end = 1.0
"""
    with pytest.raises(ConfigError, match=message):
        scene_of(text)


# ------------------------------------------------------------ 4. Noether charges
ROTATION = """
kind = "hamiltonian"
[params]
m = 1.3
k = 0.8
[system]
coordinates = ["x", "y"]
L = "m/2*(x_dot**2 + y_dot**2) - k*(x**2 + y**2)**2/4"
[noether]
delta = {{ x = "-y", y = "x" }}
{extra}
[initial]
x = 1.0
y = 0.2
x_dot = 0.3
y_dot = 0.7
[run]
t_end = 30.0
study = false
"""


def test_rotation_charge_is_the_angular_momentum_and_is_conserved():
    # Noether (notes (3.9–3.16)): δx = −y, δy = x leaves L invariant; Q = m(x ẏ − y ẋ)
    results = scene_of(ROTATION.format(extra="")).simulate()
    a = results.analysis
    assert a["noether_symmetry"] and a["noether_bracket_zero"]
    assert a["noether_charge0"] == pytest.approx(1.3 * (1.0 * 0.7 - 0.2 * 0.3), rel=1e-15)
    run = results.runs["main"]
    x, y, px, py = run.y.T
    np.testing.assert_allclose(run.invariants["noether_charge"], x * py - y * px, rtol=1e-14)
    assert a["noether_drift"] <= 1e-9 and run.attrs["drift_noether_charge"] <= 1e-9


def test_galilean_boost_changes_L_by_a_total_derivative():
    # a free particle in 1-D, δx = t: δL = m ẋ = d(m x)/dt (notes (3.48–3.49)), so
    # Q = m t ẋ − m x is conserved: by hand Q = −m x(0) along x = x0 + v t
    text = """
    kind = "hamiltonian"
    [params]
    m = 2.0
    [system]
    coordinates = ["x"]
    L = "m/2*x_dot**2"
    [noether]
    delta = { x = "t" }
    F = "m*x"
    [initial]
    x = 0.4
    x_dot = 1.5
    [run]
    t_end = 10.0
    study = false
    """
    results = scene_of(text).simulate()
    a = results.analysis
    assert a["noether_symmetry"] and a["noether_bracket_zero"]
    np.testing.assert_allclose(results.runs["main"].invariants["noether_charge"], -2.0 * 0.4,
                               rtol=1e-12)
    # without F it is not a symmetry (δL = m ẋ ≠ 0): said, and the "charge" moves
    a = scene_of(text.replace('F = "m*x"', "")).simulate().analysis
    assert not a["noether_symmetry"] and not a["noether_bracket_zero"]
    assert np.ptp(a["noether_values"]) > 1.0


def test_a_transformation_that_is_no_symmetry_is_said_so():
    results = scene_of(ROTATION.format(extra="").replace('delta = { x = "-y", y = "x" }',
                                                         'delta = { x = "x", y = "y" }')
                       ).simulate()
    a = results.analysis
    assert not a["noether_symmetry"]
    assert "noether_charge" not in results.runs["main"].invariants


@pytest.mark.parametrize("table, system, message", [
    ('delta = { x = "-y", z = "x" }', 'L = "x_dot**2/2 + y_dot**2/2"', "not a coordinate"),
    ('delta = { x = "-y_dot" }', 'L = "x_dot**2/2 + y_dot**2/2"', "undefined name 'y_dot'"),
    ('delta = { x = "-y" }', 'H = "p_x**2/2 + p_y**2/2"', "needs the Lagrangian"),
])
def test_noether_config_errors_name_the_key(table, system, message):
    text = f"""
kind = "hamiltonian"
[system]
coordinates = ["x", "y"]
{system}
[noether]
{table}
[initial]
x = 1.0
y = 0.0
{'x_dot' if 'L' in system else 'p_x'} = 0.0
{'y_dot' if 'L' in system else 'p_y'} = 1.0
[run]
t_end = 1.0
"""
    with pytest.raises(ConfigError, match=message):
        scene_of(text)


# ------------------------------------------------------------ 5. Legendre, L + dF/dt
def test_euler_lagrange_of_the_pendulum_by_hand():
    # L = m l² θ̇²/2 + m g l cos θ: E = m l² θ̈ + m g l sin θ (Goldstein §1.4)
    space = mechanics.PhaseSpace.of(["theta"])
    m, l, g = (sympy.Symbol(n, positive=True) for n in "mlg")
    L = parse_expression("m*l**2/2*theta_dot**2 + m*g*l*cos(theta)",
                         {**space.symbols_for_l(), "m": m, "l": l, "g": g})
    (E,) = mechanics.euler_lagrange(space, L)
    (acc,) = mechanics.accelerations(space)
    assert sympy.simplify(E - (m * l**2 * acc + m * g * l * sympy.sin(space.q[0]))) == 0


def test_total_derivative_leaves_the_equations_and_shifts_p_and_H():
    # notes (3.48–3.49): L' = L + dF/dt, F = m g l t cos θ; by hand p'_θ = p_θ − m g l t sin θ,
    # p'_φ = p_φ and H'(q, p') = H(q, p) − ∂F/∂t = H − m g l cos θ
    from pathlib import Path

    text = (Path(__file__).resolve().parent.parent / "configs"
            / "hamiltonian_spherical_pendulum.toml").read_text()
    results = load_scene(parse_config_text(text + "\nstudy = false\n")).simulate()
    a = results.analysis
    assert a["total_derivative_same_equations"] and a["total_derivative_H_same"]
    assert list(a["total_derivative_difference_latex"]) == ["0", "0"]
    assert a["total_derivative_H_error"] <= 1e-9 * a["total_derivative_H_scale"]
    assert a["total_derivative_shift_latex"][1] == "0"
    # and the passive variables of the Legendre transform: ∂H/∂q = −∂L/∂q (notes (4.8))
    assert a["legendre_passive_error"] <= 1e-13 * a["legendre_passive_scale"]


def test_F_with_a_velocity_is_refused_and_a_non_derivative_term_changes_the_equations():
    space = mechanics.PhaseSpace.of(["x"])
    L = parse_expression("x_dot**2/2 - x**2/2", space.symbols_for_l())
    H = mechanics.legendre(space, L).H
    with pytest.raises(ValueError, match="F depends on x_dot"):
        mechanics.add_total_derivative(space, L, H, space.qdot[0] * space.q[0])
    # and adding a non-derivative term changes the equations: x² t (not d/dt of anything
    # in q, t alone) is caught as a change, never passed off as "the same"
    td = mechanics.add_total_derivative(space, L, H, space.q[0] ** 2 * space.t)
    assert td.same_equations  # d/dt(x² t) = 2 x ẋ t + x² is a total derivative: same
    L2 = L + space.q[0] ** 2 * space.t
    E0, E2 = mechanics.euler_lagrange(space, L)[0], mechanics.euler_lagrange(space, L2)[0]
    assert sympy.simplify(E2 - E0) != 0
