"""Point transformations q = q(q′) of a Lagrangian (lecture notes (3.39)–(3.47), issue 42
item 5): L′(q′, q̇′) = L(q(q′), J q̇′) has the Euler–Lagrange expressions of L contracted
with the Jacobian, E_{q′}(L′) = Jᵀ E_q(L), so the two give the same motion.

References: lecture notes (3.39)–(3.47); Goldstein, Poole & Safko, Classical Mechanics,
3rd ed., §1.4 (Lagrange's equations hold in any generalized coordinates) and §3.7 (the
Kepler Lagrangian in polar coordinates, m(ṙ² + r²φ̇²)/2 + k/r, written out by hand below).
"""

from __future__ import annotations

import textwrap

import numpy as np
import pytest
import sympy

from reportgen.core import mechanics
from reportgen.core.expressions import parse_expression
from reportgen.core.point_transformation import point_transformation


def _transform(coords, L, new, old, constants=("m", "k")):
    space, new_space = mechanics.PhaseSpace.of(coords), mechanics.PhaseSpace.of(new)
    consts = {c: sympy.Symbol(c, positive=True) for c in constants}
    L = parse_expression(L, {**space.symbols_for_l(), **consts})
    old = [parse_expression(f, {**new_space.symbols_for_h(), **consts}) for f in old]
    return space, new_space, consts, point_transformation(space, L, old, new_space,
                                                          consts.values())


# ------------------------------------------------------------ the symbolic identities
def test_kepler_in_polar_coordinates_by_hand_and_the_notes_identities():
    _, new, c, pt = _transform(["x", "y"], "m*(x_dot**2 + y_dot**2)/2 + k/sqrt(x**2 + y**2)",
                               ["r", "phi"], ["r*cos(phi)", "r*sin(phi)"])
    r, phi = new.q
    r_dot, phi_dot = new.qdot
    # Goldstein §3.7, with |r| for a real r: L′ = m(ṙ² + r²φ̇²)/2 + k/|r|
    by_hand = c["m"] * (r_dot**2 + r**2 * phi_dot**2) / 2 + c["k"] / sympy.Abs(r)
    assert sympy.simplify(pt.L_new - by_hand) == 0
    assert sympy.simplify(pt.det - r) == 0  # det ∂(x, y)/∂(r, φ) = r, notes (3.40)
    assert pt.velocity_identity and pt.second_identity  # notes (3.42), (3.43)
    assert pt.covariant and list(pt.covariance_residual) == [0, 0]  # notes (3.47)


def test_a_linear_map_of_a_coupled_oscillator_is_covariant():
    # x = u + 2v, y = u − v (det −3): E_u, E_v are the rows of Jᵀ E by hand
    _, _, _, pt = _transform(["x", "y"], "m*(x_dot**2 + y_dot**2)/2 - k*(x**2 + x*y + y**2)/2",
                             ["u", "v"], ["u + 2*v", "u - v"])
    assert pt.det == -3 and pt.covariant and pt.velocity_identity and pt.second_identity


def test_a_map_that_is_not_a_point_transformation_is_refused():
    space, new = mechanics.PhaseSpace.of(["x"]), mechanics.PhaseSpace.of(["u"])
    L = parse_expression("x_dot**2/2 - x**2/2", space.symbols_for_l())
    for bad in (new.qdot[0] + new.q[0], new.q[0] * new.t):
        with pytest.raises(ValueError, match="point transformation"):
            point_transformation(space, L, [bad], new)


def test_a_wrong_contraction_is_not_passed_off_as_covariant():
    # E(L′) against Jᵀ E(L) is an identity; against J E(L) (no transpose) it is not, for a
    # map whose Jacobian is not symmetric: the check can fail
    space, new, _, pt = _transform(["x", "y"], "m*(x_dot**2 + y_dot**2)/2 - k*x**2/2",
                                   ["u", "v"], ["u + 2*v", "v"])
    from reportgen.core.mechanics import accelerations, euler_lagrange

    J = pt.jacobian
    acc_old, acc_new = accelerations(space), accelerations(new)
    # a linear map: q̈ = J q̈′
    to_new = {**dict(zip(space.q, pt.old, strict=True)),
              **dict(zip(space.qdot, pt.velocities, strict=True)),
              **{a: sum(J[i, k] * acc_new[k] for k in range(2))
                 for i, a in enumerate(acc_old)}}
    m, k = sympy.Symbol("m", positive=True), sympy.Symbol("k", positive=True)
    L = m * (space.qdot[0]**2 + space.qdot[1]**2) / 2 - k * space.q[0]**2 / 2
    E_old = [e.xreplace(to_new) for e in euler_lagrange(space, L)]
    E_new = euler_lagrange(new, pt.L_new)
    wrong = [sympy.simplify(E_new[j] - sum(J[j, i] * E_old[i] for i in range(2)))
             for j in range(2)]
    assert any(w != 0 for w in wrong) and pt.covariant


# ------------------------------------------------------------ the shipped scene
@pytest.fixture(scope="module")
def kepler(shipped_archives):
    return shipped_archives("hamiltonian_kepler_point_transform")


def test_the_orbit_in_polar_coordinates_is_the_cartesian_orbit(kepler):
    a = kepler.analysis
    assert a["point_transform_covariant"] and a["point_transform_velocity_identity"]
    assert a["point_transform_second_identity"]
    assert list(a["point_transform_residual_latex"]) == ["0", "0"]
    assert str(a["point_transform_det_latex"]) == "r"
    # r(0) = 1, φ(0) = 0 from (x, y) = (1, 0); p_r = m ṙ = 0, p_φ = m r² φ̇ = 1.3
    np.testing.assert_allclose(np.asarray(a["point_transform_initial"]), [1, 0, 0, 1.3],
                               rtol=0, atol=1e-15)
    # measured: 3.7e-11 (coordinates), 1.2e-10 (momenta) at rtol 1e-12 over 80 time units
    assert a["point_transform_q_difference"] <= 1e-9
    assert a["point_transform_p_difference"] <= 1e-9
    assert a["point_transform_agree"] and a["point_transform_run_status"] == "ok"
    assert a["point_transform_samples"] == len(kepler.runs["main"].t)
    # polar columns are orthogonal: |det J| is the product of their lengths
    assert a["point_transform_det_min"] == pytest.approx(1.0, abs=1e-12)


def test_the_section_is_on_the_page_and_its_citations_resolve(kepler):
    from reportgen.kinds import KINDS
    from reportgen.rendering.report import report_text
    from reportgen.scene.citations import problems
    from reportgen.scene.claims import contradictions

    assert "point_transform" in KINDS[kepler.kind].default_sections(kepler)
    text = report_text(kepler)
    assert "yes: every component of the difference simplifies to 0" in text
    assert contradictions(kepler, text) == []
    html = (kepler.path.parent / "report.html").read_text(encoding="utf-8")
    assert '<section id="point_transform">' in html
    assert "notes (3.39)–(3.47)" in html
    assert problems(html) == []


def test_the_section_is_absent_without_the_table(shipped_archives):
    from reportgen.kinds import KINDS

    pendulum = shipped_archives("hamiltonian_spherical_pendulum")
    assert not any(k.startswith("point_transform") for k in pendulum.analysis)
    assert "point_transform" not in KINDS[pendulum.kind].default_sections(pendulum)


# ------------------------------------------------------------ refused configs: exit 2
OSCILLATOR = """
kind = "hamiltonian"
[system]
coordinates = ["x", "y"]
{system}
[point_transform]
{table}
[initial]
x = {x0}
y = 0.0
{velocities}
[run]
t_end = 1.0
samples = 11
study = false
"""

POLAR = 'coordinates = ["r", "phi"]\nx = "r*cos(phi)"\ny = "r*sin(phi)"\n' \
        'initial = { r = 1.0, phi = 0.0 }'
L_OSC = 'L = "(x_dot**2 + y_dot**2)/2 - (x**2 + y**2)/2"'
QDOT = "x_dot = 0.0\ny_dot = 1.0"

REFUSED = [
    # (case, table, key named, rule's words, x0, system, velocities)
    ("singular_at_the_start", POLAR, "point_transform.coordinates", "singular", 0.0,
     L_OSC, QDOT),
    ("singular_everywhere", 'coordinates = ["u", "v"]\nx = "u + v"\ny = "2*u + 2*v"\n'
     "initial = { u = 1.0, v = 0.0 }", "point_transform.coordinates", "singular", 1.0,
     L_OSC, QDOT),
    ("depends_on_time", POLAR.replace('"r*cos(phi)"', '"r*cos(phi) + t"'),
     "point_transform.x", "t", 1.0, L_OSC, QDOT),
    ("depends_on_a_velocity", POLAR.replace('"r*cos(phi)"', '"r*cos(phi) + r_dot"'),
     "point_transform.x", "r_dot", 1.0, L_OSC, QDOT),
    ("an_old_name", POLAR.replace('["r", "phi"]', '["x", "phi"]'),
     "point_transform.coordinates", "not an old coordinate", 1.0, L_OSC, QDOT),
    ("too_few_names", POLAR.replace('["r", "phi"]', '["r"]'),
     "point_transform.coordinates", "one per coordinate", 1.0, L_OSC, QDOT),
    ("a_stray_key", POLAR + '\nz = "r"', "point_transform.z", "not a key", 1.0, L_OSC,
     QDOT),
    ("a_missing_formula", POLAR.replace('y = "r*sin(phi)"\n', ""), "point_transform.y",
     "missing", 1.0, L_OSC, QDOT),
    ("a_missing_start", POLAR.replace("initial = { r = 1.0, phi = 0.0 }",
                                      "initial = { r = 1.0 }"),
     "point_transform.initial.phi", "missing", 1.0, L_OSC, QDOT),
    ("given_H", POLAR, "point_transform", "system.L", 1.0,
     'H = "(p_x**2 + p_y**2)/2 + (x**2 + y**2)/2"', "p_x = 0.0\np_y = 1.0"),
]


@pytest.mark.parametrize("case", REFUSED, ids=[c[0] for c in REFUSED])
def test_a_bad_point_transform_is_refused_with_exit_2(case, cli, tmp_path):
    name, table, key, words, x0, system, velocities = case
    path = tmp_path / f"{name}.toml"
    path.write_text(textwrap.dedent(OSCILLATOR.format(system=system, table=table, x0=x0,
                                                      velocities=velocities)))
    code, _, err = cli("validate", path)
    assert code == 2, err
    assert f"{path}" in err and f"key '{key}'" in err and words in err, err
    assert "Traceback" not in err
