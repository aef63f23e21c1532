"""The planar circular restricted three-body problem (``three_body`` with ``[restricted]``):
the Jacobi constant, the Lagrange points against Szebehely's quintics, the Thiele–Burrau
regularized equations against the Cartesian ones, the crossings of the surface of section
y = 0, the μ → 0 limit (Kepler in a rotating frame, Tisserand's relation) and the config
rules.

References: Murray & Dermott, *Solar System Dynamics* (1999) §3.2–3.6 and §3.10;
Szebehely, *Theory of Orbits* (1967) §4.4 (the collinear points' quintics)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from reportgen.archive.store import read_archive
from reportgen.core.integrators import integrate
from reportgen.core.integrators.fictitious_time import integrate_fictitious_time
from reportgen.core.models import restricted_three_body as r3
from reportgen.kinds import load_scene
from reportgen.pipeline.stages import run_scene
from reportgen.scene.config import ConfigError, parse_config_text

EARTH_MOON = 0.01215


def cartesian_run(mu, y0, t, rtol=1e-13):
    return integrate(r3.model(mu), np.asarray(y0, float), t, method="dop853", rtol=rtol,
                     atol=rtol * 1e-2)


def regularized_run(mu, y0, t, rtol=1e-13, section=None):
    C = float(r3.jacobi_constant(*y0, mu))
    return integrate_fictitious_time(r3.regularized_model(mu, C), r3.to_regularized(*y0, mu),
                                     t, r3.T_INDEX, rtol=rtol, atol=rtol * 1e-2,
                                     section=section)


def start(mu, x0, C):
    return np.array([x0, 0.0, 0.0, r3.section_speed(x0, C, mu)])


# ---------------------------------------------------------------- the integral
@pytest.mark.parametrize("x0", [0.5, -0.5, 0.9])
def test_jacobi_constant_is_conserved_by_both_formulations(x0):
    """C = 2Ω − v² (Murray & Dermott §3.3) is constant along the exact motion: along the
    Cartesian run and the regularized one it stays within 1e-10 of C(0) (relative to 2Ω),
    and the regularized Hamiltonian K = r1 r2 (H + C/2) stays 0."""
    C = 3.18
    y0 = start(EARTH_MOON, x0, C)
    assert r3.jacobi_constant(*y0, EARTH_MOON) == pytest.approx(C, abs=1e-14)
    t = np.linspace(0.0, 50.0, 2001)
    for y in (cartesian_run(EARTH_MOON, y0, t).y,
              r3.from_regularized(regularized_run(EARTH_MOON, y0, t).y, EARTH_MOON)):
        drift = np.abs(r3.jacobi_constant(*y.T, EARTH_MOON) - C)
        terms = 2.0 * r3.effective_potential(y[:, 0], y[:, 1], EARTH_MOON)
        assert np.max(drift / terms) < 1e-10
    K = r3.regularized_hamiltonian(regularized_run(EARTH_MOON, y0, t).y, EARTH_MOON, C)
    assert np.max(np.abs(K)) < 1e-11


def test_regularized_and_cartesian_runs_agree():
    """The Thiele–Burrau equations are the same motion: over t = 20 (several turns about
    the Earth, no close approach) both runs at rtol 1e-13 agree to 1e-9 in every
    component, and the back-and-forth conversion is the identity."""
    y0 = start(EARTH_MOON, 0.5, 3.17)
    np.testing.assert_allclose(r3.from_regularized(r3.to_regularized(*y0, EARTH_MOON),
                                                   EARTH_MOON)[0], y0, atol=1e-14)
    t = np.linspace(0.0, 20.0, 201)
    cart = cartesian_run(EARTH_MOON, y0, t).y
    reg = r3.from_regularized(regularized_run(EARTH_MOON, y0, t).y, EARTH_MOON)
    assert np.max(np.abs(cart - reg)) < 1e-9


# -------------------------------------------------------------- Lagrange points
def quintic_roots(mu):
    """x of L1, L2, L3 from Szebehely's quintics (Theory of Orbits §4.4), γ the distance
    from the nearer primary; each has one positive real root:

        L1: γ⁵ − (3 − μ)γ⁴ + (3 − 2μ)γ³ − μγ² + 2μγ − μ = 0,   x = 1 − μ − γ
        L2: γ⁵ + (3 − μ)γ⁴ + (3 − 2μ)γ³ − μγ² − 2μγ − μ = 0,   x = 1 − μ + γ
        L3: γ⁵ + (2 + μ)γ⁴ + (1 + 2μ)γ³ − (1 − μ)γ² − 2(1 − μ)γ − (1 − μ) = 0,
            x = −μ − γ."""
    def positive(coefficients):
        roots = np.roots(coefficients)
        real = roots[np.abs(roots.imag) < 1e-9].real
        return float(real[real > 0][0])

    g1 = positive([1, -(3 - mu), 3 - 2 * mu, -mu, 2 * mu, -mu])
    g2 = positive([1, 3 - mu, 3 - 2 * mu, -mu, -2 * mu, -mu])
    g3 = positive([1, 2 + mu, 1 + 2 * mu, -(1 - mu), -2 * (1 - mu), -(1 - mu)])
    return 1 - mu - g1, 1 - mu + g2, -mu - g3


@pytest.mark.parametrize("mu", [1e-6, 9.537e-4, EARTH_MOON, 0.1, 0.3, 0.5])
def test_collinear_lagrange_points_are_the_quintics_roots(mu):
    """L1, L2, L3 found as zeros of ∂Ω/∂x on y = 0 (Brent) are the roots of Szebehely's
    quintics to 1e-12; their C = 2Ω there is the test's own evaluation of
    (x² + y²) + 2(1 − μ)/r1 + 2μ/r2; L4, L5 have C = 3 − μ(1 − μ) (Murray & Dermott
    §3.6); and C_L1 ≥ C_L2 ≥ C_L3 > C_L4 (the order the regions open in, §3.10)."""
    points = r3.lagrange_points(mu)
    for name, x in zip(("L1", "L2", "L3"), quintic_roots(mu), strict=True):
        assert points[name][0] == pytest.approx(x, abs=1e-12)
        C = x * x + 2 * (1 - mu) / abs(x + mu) + 2 * mu / abs(x - 1 + mu)
        assert points[name][2] == pytest.approx(C, rel=1e-13)
    for name in ("L4", "L5"):
        x, y, C = points[name]
        assert (x, abs(y)) == pytest.approx((0.5 - mu, math.sqrt(3) / 2), abs=1e-15)
        assert C == pytest.approx(3 - mu * (1 - mu), rel=1e-14)
    C = [points[k][2] for k in ("L1", "L2", "L3", "L4")]
    assert C[0] >= C[1] - 1e-14 and C[1] >= C[2] - 1e-14 and C[2] > C[3]


def test_lagrange_points_in_closed_form_and_for_earth_moon():
    """μ = 1/2 (Copenhagen problem): L1 is the midpoint x = 0 with C = 4 (2Ω = 0 + 2·(1/2
    /(1/2))·2), L2 and L3 symmetric.  Small μ: L1, L2 at 1 − μ ∓ (μ/3)^(1/3) to leading
    order (Hill's radius, Murray & Dermott §3.6), the next term ±(μ/3)^(2/3)/3.
    Earth–Moon μ = 0.01215: x and C as tabulated by Koon, Lo, Marsden & Ross, *Dynamical
    Systems, the Three-Body Problem and Space Mission Design* (2011) §2.5: L1 0.8369,
    C 3.1883; L2 1.1557, C 3.1722; L3 −1.0051, C 3.0121."""
    p = r3.lagrange_points(0.5)
    assert p["L1"][0] == pytest.approx(0.0, abs=1e-14) and p["L1"][2] == pytest.approx(4.0)
    assert p["L2"][0] == pytest.approx(-p["L3"][0], abs=1e-12)
    mu = 1e-9
    h = (mu / 3) ** (1 / 3)
    p = r3.lagrange_points(mu)
    assert p["L1"][0] == pytest.approx(1 - mu - h + h * h / 3, abs=3 * h ** 3)
    assert p["L2"][0] == pytest.approx(1 - mu + h + h * h / 3, abs=3 * h ** 3)
    p = r3.lagrange_points(EARTH_MOON)
    for name, x, C in (("L1", 0.8369, 3.1883), ("L2", 1.1557, 3.1722),
                       ("L3", -1.0051, 3.0121)):
        assert p[name][0] == pytest.approx(x, abs=6e-5)
        assert p[name][2] == pytest.approx(C, abs=6e-5)


# ------------------------------------------------------------ μ → 0: Kepler
def kepler_state(a, e, M):
    """(x, y, ẋ, ẏ) on a Kepler ellipse about a unit mass at the origin (GM = 1),
    pericentre on +x, mean anomaly M: Kepler's equation E − e sin E = M by Newton."""
    E = M
    for _ in range(50):
        E -= (E - e * math.sin(E) - M) / (1 - e * math.cos(E))
    r = a * (1 - e * math.cos(E))
    x, y = a * (math.cos(E) - e), a * math.sqrt(1 - e * e) * math.sin(E)
    n = a ** -1.5
    Edot = n / (1 - e * math.cos(E))
    return np.array([x, y, -a * math.sin(E) * Edot,
                     a * math.sqrt(1 - e * e) * math.cos(E) * Edot]), r


def to_rotating(state, t):
    """An inertial state as the frame rotating at n = 1 sees it at time t (the frames
    agree at t = 0): r' = R(−t) r, v' = R(−t)(v − ẑ × r)."""
    x, y, vx, vy = state
    c, s = math.cos(t), math.sin(t)
    ux, uy = vx + y, vy - x
    return np.array([c * x + s * y, -s * x + c * y, c * ux + s * uy, -s * ux + c * uy])


@pytest.mark.parametrize(("a", "e"), [(0.5, 0.3), (2.0, 0.6), (0.8, 0.0)])
def test_mu_to_zero_is_kepler_in_a_rotating_frame_with_tisserand_constant(a, e):
    """μ = 0: the particle moves on a Kepler ellipse about the unit mass, seen from the
    frame rotating at n = 1.  Its Jacobi constant is Tisserand's C = 1/a + 2√(a(1 − e²))
    (Murray & Dermott §3.4: 2/r − v² = 1/a from the energy, and the frame's terms give 2h,
    h = √(a(1 − e²))); the rotating-frame runs (Cartesian and regularized) follow the
    closed-form orbit turned back by the frame's angle t to 1e-9."""
    y_in, _ = kepler_state(a, e, 0.3)
    y0 = to_rotating(y_in, 0.0)
    assert r3.jacobi_constant(*y0, 0.0) == pytest.approx(1 / a + 2 * math.sqrt(a * (1 - e * e)),
                                                          rel=1e-14)
    period = 2 * math.pi * a ** 1.5
    t = np.linspace(0.0, 3 * period, 301)
    n = a ** -1.5
    exact = np.array([to_rotating(kepler_state(a, e, 0.3 + n * ti)[0], ti) for ti in t])
    assert np.max(np.abs(cartesian_run(0.0, y0, t).y - exact)) < 1e-9
    reg = r3.from_regularized(regularized_run(0.0, y0, t).y, 0.0)
    assert np.max(np.abs(reg - exact)) < 1e-9


def test_small_mu_keeps_tisserand_within_the_perturbation():
    """μ = 1e-7: a particle far from the small primary keeps C exactly; its osculating
    Keplerian a and e about the large primary change only by O(μ), so Tisserand's
    combination of them stays within 1e-5 of C (Murray & Dermott §3.4)."""
    mu = 1e-7
    y_in, _ = kepler_state(0.6, 0.2, 0.0)
    y0 = to_rotating(y_in, 0.0)
    t = np.linspace(0.0, 100.0, 501)
    y = cartesian_run(mu, y0, t).y
    C = r3.jacobi_constant(*y.T, mu)
    assert np.ptp(C) < 1e-11
    # inertial state relative to the large primary at (−μ, 0) of the rotating frame
    x, yy, vx, vy = y.T
    X, Y = x + mu, yy
    ux, uy = vx - yy, vy + x  # v_inertial = v + ẑ × r (barycentric), the primary moves slowly
    energy = 0.5 * (ux ** 2 + uy ** 2) - 1 / np.hypot(X, Y)
    h = X * uy - Y * ux
    a = -0.5 / energy
    tisserand = 1 / a + 2 * h
    assert np.max(np.abs(tisserand - C[0])) < 1e-5


# ---------------------------------------------------------- surface of section
def test_crossings_lie_on_the_section_and_the_jacobi_surface():
    """Every located crossing has y = 0 (to rounding of y = a sinh p sin q), ẏ > 0 and
    C(x, 0, ẋ, ẏ) = C(0) to 1e-10 of 2Ω (so (x, ẋ) lies inside the edge ẏ² = 2Ω(x, 0) −
    C − ẋ² ≥ 0); and the regularized crossings are the Cartesian run's own (located on the
    Cartesian DOP853 steps, the same section y = 0) to 1e-8."""
    C = 3.18
    y0 = start(EARTH_MOON, 0.45, C)
    t = np.array([0.0, 60.0])
    reg = regularized_run(EARTH_MOON, y0, t, section=r3.REGULARIZED_AXIS_SECTION)
    found = r3.from_regularized(reg.crossings[:, 1:], EARTH_MOON)
    assert len(found) >= 10
    assert np.max(np.abs(found[:, 1])) < 1e-12 and np.all(found[:, 3] > 0)
    terms = 2.0 * r3.effective_potential(found[:, 0], 0.0, EARTH_MOON)
    assert np.max(np.abs(r3.jacobi_constant(*found.T, EARTH_MOON) - C) / terms) < 1e-10
    assert np.all(r3.section_vy2(found[:, 0], found[:, 2], C, EARTH_MOON) >= -1e-9)
    cart = integrate_fictitious_time(r3.model(EARTH_MOON), y0, t, None, rtol=1e-13,
                                     atol=1e-15, section=r3.AXIS_SECTION)
    assert len(cart.crossings) == len(found)
    np.testing.assert_allclose(cart.crossings[:, 0], reg.crossings[:, 0], atol=1e-8)
    np.testing.assert_allclose(cart.crossings[:, 1:], found, atol=1e-8)


FAMILY = """
kind = "three_body"
title = "restricted family"
names = ["Earth", "Moon", "particle"]

[restricted]
mu = 0.01215
x = 0.5
jacobi = {C!r}

[run]
t_end = 60.0
samples = 61
rtol = 1e-13
atol = 1e-15

[sweep]
restricted.x = {xs!r}
store = 0
"""


def test_a_family_stores_its_crossings_and_checks_the_jacobi_constant(tmp_path):
    """A restricted sweep: every member's crossings in /sweep/points/poincare on y = 0 with
    ẏ > 0 at the family's C; a member at a forbidden x0 inside the range is invalid with
    the rule in its message (the others run); the family check of C at the crossings."""
    path = tmp_path / "fam.toml"
    # at C = 3.19 > C_L1 the zero-velocity curve closes L1: 0.8245 < x < 0.8488 is
    # forbidden; 0.86 starts in the region about the Moon
    path.write_text(FAMILY.format(C=3.19, xs=[-0.5, 0.83, 0.86]))
    outcome = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    data = read_archive(tmp_path / "out" / "fam" / "run.h5")
    assert list(data.sweep.status) == ["ok", "invalid", "ok"]
    assert "restricted.jacobi" in data.sweep.message[1] and "forbids" in data.sweep.message[1]
    assert not outcome.ok  # a member without a result flags the family
    pts = data.sweep.points["poincare"]
    state = np.asarray(pts.columns["state"])
    assert set(np.asarray(pts.member)) == {0, 2}
    assert np.max(np.abs(state[:, 1])) < 1e-12 and np.all(state[:, 3] > 0)
    terms = 2 * r3.effective_potential(state[:, 0], 0.0, EARTH_MOON)
    assert np.max(np.abs(r3.jacobi_constant(*state.T, EARTH_MOON) - 3.19) / terms) < 1e-10
    check = next(c for c in data.checks if "crossings" in c.quantity)
    assert check.rel_error < 1e-10 and check.reference == pytest.approx(3.19, abs=1e-14)
    assert data.analysis["poincare_jacobi"] == pytest.approx(3.19, abs=1e-14)
    assert data.analysis["region"] == "closed"


# ------------------------------------------------------------------ config rules
def restricted(body: str, sweep: str = "") -> str:
    return (f'kind = "three_body"\n[restricted]\n{body}\n[run]\nt_end = 10.0\n'
            + (f"[sweep]\n{sweep}\n" if sweep else ""))


@pytest.mark.parametrize(("body", "key", "words"), [
    ("mu = 0.0\nx = 0.5\njacobi = 3.0", "restricted.mu", "greater than 0"),
    ("mu = -0.1\nx = 0.5\njacobi = 3.0", "restricted.mu", "greater than 0"),
    ("mu = 0.7\nx = 0.5\njacobi = 3.0", "restricted.mu", "less than or equal to 0.5"),
    ("mu = 0.01215\nx = -0.9\njacobi = 3.18", "restricted.jacobi", "forbids"),
    ("mu = 0.01215\nx = 0.5", "restricted.vy / restricted.jacobi", "exactly one"),
    ("mu = 0.01215\nx = -0.01215\nvy = 1.0", "restricted.x / restricted.y", "collision"),
])
def test_bad_restricted_configs_exit_2_with_one_line(tmp_path, cli, body, key, words):
    path = tmp_path / "bad.toml"
    path.write_text(restricted(body))
    code, out, err = cli("run", path, "--out", tmp_path / "out")
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and f"key '{key}'" in lines[0] and words in lines[0], err
    assert not (tmp_path / "out" / "bad").exists()


def test_a_sweep_whose_end_is_forbidden_is_refused(tmp_path, cli):
    path = tmp_path / "sweep.toml"
    path.write_text(restricted("mu = 0.01215\nx = 0.5\njacobi = 3.18",
                               "restricted.x = { start = -0.95, stop = 0.5, num = 10 }"))
    code, _, err = cli("validate", path)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "restricted.x = -0.95" in lines[0] and "forbids" in lines[0]


def test_restricted_and_full_problem_do_not_mix():
    with pytest.raises(ConfigError) as info:
        load_scene(parse_config_text(restricted("mu = 0.1\nx = 0.5\nvy = 0.1")
                                     + "[params]\nmasses = [1.0, 1.0, 1.0]\n"))
    assert "leave out [params]" in info.value.problems[0]
    with pytest.raises(ConfigError) as info:
        load_scene(parse_config_text('kind = "three_body"\n[run]\nt_end = 1.0\n'))
    assert "[restricted]" in info.value.problems[0]


def test_vy_is_solved_from_the_jacobi_constant():
    """ẏ = +√(2Ω(x, y) − C − ẋ²): the start's C is the configured one."""
    scene = load_scene(parse_config_text(restricted("mu = 0.01215\nx = 0.3\nvx = 0.1\n"
                                                    "jacobi = 3.1")))
    x, y, vx, vy = scene.config.restricted.initial_state()
    assert vy > 0 and r3.jacobi_constant(x, y, vx, vy, EARTH_MOON) == pytest.approx(3.1,
                                                                                   abs=1e-13)


def test_a_restricted_sweep_with_another_named_method_is_refused(tmp_path, cli):
    """Members locate their crossings on DOP853's steps in the regularized variables: a
    sweep naming another method exits 2 on key run.method before anything runs."""
    path = tmp_path / "rk.toml"
    path.write_text(restricted("mu = 0.01215\nx = 0.5\njacobi = 3.18",
                               "restricted.x = [0.4, 0.5]").replace(
        "t_end = 10.0\n", 't_end = 10.0\nmethod = "rk45"\n'))
    code, out, err = cli("run", path, "--out", tmp_path / "out")
    assert code == 2 and "key 'run.method'" in err and "DOP853" in err, err
    assert not (tmp_path / "out").exists()


def test_a_single_run_with_a_named_method_integrates_the_cartesian_equations():
    """A single run naming another method than DOP853 integrates the Cartesian equations
    (the regularized ones are DOP853's); its C stays within its tolerance's reach."""
    scene = load_scene(parse_config_text(restricted("mu = 0.01215\nx = 0.5\njacobi = 3.18")
                                         .replace("t_end = 10.0\n", 't_end = 10.0\n'
                                                  'method = "rk45"\nstudy = false\n')))
    (model,) = scene.models()
    assert model.columns == r3.COLUMNS
    results = scene.simulate()
    assert results.analysis["formulation"] == "cartesian"
    assert results.analysis["jacobi_error_relative"] < 1e-8
