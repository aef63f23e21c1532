"""Hamilton–Jacobi residuals and {Q, P} computed, for the oscillator and the central force.

References (each assertion cites the one it uses):
* Hamilton's characteristic function of the oscillator, W = ∫ √(2mE − m²ω²q²) dq
  (lecture notes (7.33–7.34); Goldstein §10.2), and its action ∮ p dq = 2πE/ω
  (Goldstein §10.6: J = 2πE/ω).
* Kepler radial motion: ∮ p_r dr = −2πL + πk √(2μ/(−E)) (Goldstein §10.8, J_r = −J_θ +
  πk√(2m/(−E)) with J_θ = 2πL), so ∫_{r_min}^{r_max} p_r dr = π(k√(μ/(−2E)) − L); with
  V = −k/r − ε/r² the centrifugal L² becomes L² − 2με (Landau & Lifshitz §15 problem 3).
* A map is canonical iff {Q, P} = 1 (Goldstein §9.5); the swap F1 = qQ gives Q = p,
  P = −q (notes (6.6–6.11)).
Independent references are scipy's adaptive quadrature (QUADPACK) and arcsin/brentq.
"""

from __future__ import annotations

import io
import math
import textwrap

import numpy as np
import pytest
from scipy import integrate, optimize
from test_oscillator import TEXT as OSCILLATOR_TEXT

from reportgen.core import hamilton_jacobi as hj
from reportgen.core.models import oscillator as osc
from reportgen.kinds import load_scene
from reportgen.scene.config import parse_config_text


def quad(f, a, b):
    """∫_a^b f by QUADPACK, to 1e-14 (the square-root endpoints are integrable)."""
    value, _ = integrate.quad(f, a, b, epsabs=0.0, epsrel=1e-13, limit=400)
    return value


# --------------------------------------------------------------- the quadrature of W
M, OMEGA, E_OSC = 2.0, 1.5, 2.3125  # configs/oscillator.toml: q0 = 1, p0 = 0.5
A_OSC = math.sqrt(2 * E_OSC / (M * OMEGA**2))


def oscillator_W():
    return hj.CharacteristicQuadrature.of(lambda q: 2 * M * E_OSC - (M * OMEGA * q) ** 2,
                                          -A_OSC, A_OSC)


def test_oscillator_characteristic_function_against_quadpack_and_arcsin():
    W = oscillator_W()
    q = np.linspace(-0.9 * A_OSC, 0.95 * A_OSC, 7)
    # QUADPACK of the integrand √(2mE − m²ω²q²) from −A (notes (7.33)–(7.34))
    ref = [quad(lambda s: math.sqrt(max(2 * M * E_OSC - (M * OMEGA * s) ** 2, 0.0)),
                -A_OSC, x) for x in q]
    assert np.max(np.abs(W(q) - ref)) < 1e-13 * E_OSC / OMEGA
    # the textbook antiderivative (mω/2)(q√(A² − q²) + A² arcsin(q/A)) + πE/(2ω), away from
    # the turning points where arcsin is well conditioned
    textbook = (0.5 * M * OMEGA * (q * np.sqrt(A_OSC**2 - q**2) + A_OSC**2 * np.arcsin(q / A_OSC))
                + math.pi * E_OSC / (2 * OMEGA))
    assert np.max(np.abs(osc.characteristic_function(q, E_OSC, M, OMEGA) - textbook)) \
        < 1e-14 * E_OSC / OMEGA
    # half the action J = 2πE/ω (Goldstein §10.6)
    assert W.half_action == pytest.approx(math.pi * E_OSC / OMEGA, rel=1e-14)


def test_gradient_solves_the_time_independent_equation():
    W = oscillator_W()
    # the turning points themselves and points a rounding past them are included
    q = np.concatenate([np.linspace(-A_OSC, A_OSC, 201), [A_OSC * (1 + 1e-14), -A_OSC * 1.5]])
    q_at, p = W.gradient(q)
    assert np.all(np.abs(q_at) <= A_OSC)
    H = p**2 / (2 * M) + M * OMEGA**2 * q_at**2 / 2  # H(q, ∂W/∂q) = E, notes (7.32)–(7.33)
    assert np.max(np.abs(H / E_OSC - 1)) < 1e-10
    inside = slice(20, 181)  # away from the turning points: p itself to 1e-11
    closed = M * OMEGA * np.sqrt(A_OSC**2 - q[inside] ** 2)
    assert np.max(np.abs(p[inside] - closed)) < 1e-11 * math.sqrt(2 * M * E_OSC)


def test_central_differences_converge_at_sixth_order(monkeypatch):
    """The Richardson-combined five-point difference errs as step⁶: a wrong coefficient
    would show as a lower slope (diffrax's order test)."""
    mu, k, e = 0.5, 0.5, 0.5
    E = -k / 2.0  # a = 1
    L = math.sqrt(mu * k * (1 - e * e))
    r_min, r_max = 1 - e, 1 + e  # a(1 ∓ e)
    W = hj.CharacteristicQuadrature.of(lambda r: 2 * mu * (E + k / r) - L * L / r**2,
                                       r_min, r_max, pole=0.0)
    r = np.array([0.7, 1.0, 1.3])
    exact = np.sqrt(2 * mu * (E + k / r) - L * L / r**2)
    steps = np.array([0.2, 0.1, 0.05])
    errors = []
    for step in steps:
        monkeypatch.setattr(hj, "W_ANGLE_STEP", step)
        monkeypatch.setattr(hj, "W_ANGLE_STEP_PER_DISTANCE", 1e3)
        errors.append(np.max(np.abs(W.gradient(r)[1] - exact)))
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert 5.5 < slope < 6.6, (errors, slope)


@pytest.mark.parametrize("e", [0.05, 0.3, 0.7, 0.95, 0.99])
def test_kepler_radial_characteristic_against_quadpack(e):
    mu, k = 0.5, 0.5
    E = -k / 2.0  # a = 1
    L = math.sqrt(mu * k * (1 - e * e))
    r_min, r_max = hj.kepler_radial_turning_points(mu, k, E, L * L)
    # the apsides a(1 ∓ e) of the ellipse (Goldstein (3.61)-(3.62))
    assert (r_min, r_max) == pytest.approx((1 - e, 1 + e), rel=1e-14)

    def p_r(r):
        return math.sqrt(max(2 * mu * (E + k / r) - L * L / r**2, 0.0))

    r = np.linspace(r_min, r_max, 6)[1:]
    ref = np.array([quad(p_r, r_min, x) for x in r])
    size = math.pi * k * math.sqrt(mu / (-2 * E))
    assert np.max(np.abs(hj.kepler_radial_characteristic(r, mu, k, E, L * L) - ref)) \
        < 1e-12 * size
    W = hj.CharacteristicQuadrature.of(lambda x: 2 * mu * (E + k / x) - L * L / x**2,
                                       r_min, r_max, pole=0.0,
                                       reduced=lambda x: -2 * mu * E / x**2)
    assert np.max(np.abs(W(r) - ref)) < 1e-12 * size
    # half the radial action, π(k√(μ/(−2E)) − L) (Goldstein §10.8)
    assert W.half_action == pytest.approx(size - math.pi * L, rel=1e-13)


def test_turning_points_must_bracket():
    with pytest.raises(ValueError, match="a < b"):
        hj.CharacteristicQuadrature.of(lambda x: 1.0 - x * x, 1.0, -1.0)
    with pytest.raises(ValueError, match="pole"):
        hj.CharacteristicQuadrature.of(lambda x: 1.0 - x * x, -1.0, 1.0, pole=0.0)
    with pytest.raises(ValueError, match="bound"):
        hj.kepler_radial_turning_points(1.0, 1.0, 0.1, 1.0)


# --------------------------------------------------------------- {Q, P} of the swap
def test_swap_bracket_symbolic_and_by_differences():
    assert osc.swap_poisson_bracket() == 1.0  # canonical (Goldstein §9.5)
    q, p = np.linspace(-2, 2, 9), np.linspace(3, -1, 9)
    assert np.max(np.abs(osc.map_poisson_bracket(osc.swap, q, p, 1e-3, 1e-3) - 1)) < 1e-12
    # a nonlinear canonical map (Q, P) = (q, p + q²) has {Q, P} = 1; differences are
    # exact but for rounding at second order in the step for a quadratic
    assert np.max(np.abs(osc.map_poisson_bracket(lambda a, b: (a, b + a * a), q, p,
                                                 1e-4, 1e-4) - 1)) < 1e-10
    # and the check can fail: (Q, P) = (2q, p) is not canonical, {Q, P} = 2
    assert np.allclose(osc.map_poisson_bracket(lambda a, b: (2 * a, b), q, p, 1e-3, 1e-3),
                       2.0, rtol=0, atol=1e-12)


# --------------------------------------------------------------- the oscillator scene
OSCILLATOR = OSCILLATOR_TEXT  # m = 2, ω = 1.5, q0 = 1, p0 = 0.5 over t = 25


@pytest.fixture(scope="module")
def oscillator():
    return load_scene(parse_config_text(OSCILLATOR)).simulate()


def test_oscillator_stores_computed_bracket_and_residuals(oscillator):
    a, run = oscillator.analysis, oscillator.runs["main"]
    e0 = 0.5 * 0.5**2 / 2.0 + 0.5 * 2.0 * 1.5**2 * 1.0**2  # p0²/2m + mω²q0²/2
    assert a["poisson_bracket_QP"] == 1.0
    assert 0 <= a["poisson_bracket_QP_defect"] < 1e-12
    assert a["hj_residual"] < 1e-14  # the integrand solves (7.33) to rounding
    assert a["hj_residual_quadrature"] < 1e-10  # notes (7.16), all by differences
    assert a["hj_characteristic_residual_quadrature"] < 1e-10  # notes (7.32)–(7.33)
    assert a["hj_characteristic_quadrature_error"] < 1e-13
    assert a["hj_half_action"] == pytest.approx(math.pi * e0 / 1.5, rel=1e-13)
    # p² − (∂W/∂q)² = 2m(H(q, p) − E) on a branch, so |p − ∂W/∂q| ≤ √(2m|H − E|): the
    # momentum difference is bounded by the energy error the invariants record
    drift = np.max(np.abs(run.invariants["energy"] - e0)) / e0
    assert 0 < a["hj_momentum_difference"] <= math.sqrt(drift) * (1 + 1e-6) + 1e-15
    names = [c.quantity for c in oscillator.checks]
    assert "{Q, P} by central differences, worst sample" in names
    worst = next(c for c in oscillator.checks if c.quantity.startswith("H(q, ∂W/∂q)"))
    assert worst.rel_error == pytest.approx(a["hj_characteristic_residual_quadrature"])


def test_oscillator_report_shows_the_residuals(oscillator, tmp_path):
    from reportgen.archive.store import read_archive, write_archive

    scene = load_scene(parse_config_text(OSCILLATOR))
    path = tmp_path / "run.h5"
    write_archive(path, kind=scene.kind, title=scene.title, scene="test",
                  config_text=OSCILLATOR, config_sha256="0", results=oscillator,
                  resolved_config=scene.resolved_config())
    data = read_archive(path)
    content = type(scene).section_hamilton_jacobi(data)
    (table,) = content.tables
    cells = [cell for row in table.rows for cell in row]
    assert any("notes (7.16)" in c for c in cells) and any("notes (7.32)–(7.33)" in c for c in cells)
    from reportgen.scene.content import fmt_err
    assert fmt_err(data.analysis["hj_residual_quadrature"]) in cells
    facts = dict(type(scene).section_canonical_swap(data).facts)
    assert any("central differences" in k for k in facts)


# --------------------------------------------------------------- the central force
def central(params="", initial="x = 0.3\ny = 0.0\nvx = 0.0\nvy = 2.3804761428476167",
            run="t_end = 12.566370614359172\nsamples = 801"):
    return textwrap.dedent(f"""
        kind = "central_force"
        [params]
        m1 = 1.0
        m2 = 1.0
        k = 0.5
        {params}
        [initial]
        {initial}
        [run]
        study = false
        rtol = 1e-13
        atol = 1e-15
        {run}
        """)


def initial_constants(x, y, vx, vy, mu, k, n=1.0, eps=0.0):
    r = math.hypot(x, y)
    return 0.5 * mu * (vx * vx + vy * vy) - k / r**n - eps / r**2, mu * (x * vy - y * vx)


def test_kepler_scene_residuals_and_closed_forms():
    res = load_scene(parse_config_text(central())).simulate()
    a = res.analysis
    E, L = initial_constants(0.3, 0.0, 0.0, 2.3804761428476167, 0.5, 0.5)
    half = math.pi * (0.5 * math.sqrt(0.5 / (-2 * E)) - L)  # Goldstein §10.8
    assert a["hj_half_action_closed_form"] == pytest.approx(half, rel=1e-14)
    assert a["hj_half_action"] == pytest.approx(half, rel=1e-13)
    assert a["hj_residual"] < 1e-14
    assert a["hj_residual_quadrature"] < 1e-10
    assert a["hj_characteristic_residual_quadrature"] < 1e-10
    assert a["hj_characteristic_quadrature_error"] < 1e-13
    assert 0 < a["hj_momentum_difference"] < 1e-5
    hj_arrays = a["hamilton_jacobi"]
    run = res.runs["main"]
    assert np.allclose(hj_arrays["radius"], np.hypot(run["x"], run["y"]), rtol=0, atol=0)
    # the curve is ∂W/∂r = √(2μ(E + k/r) − L²/r²) between the apsides 0.3 and 1.7 m
    r = hj_arrays["curve_r"]
    assert r[0] == pytest.approx(0.3, rel=1e-13) and r[-1] == pytest.approx(1.7, rel=1e-13)
    assert np.allclose(hj_arrays["curve_p_r"],
                       np.sqrt(np.maximum(2 * 0.5 * (E + 0.5 / r) - L * L / r**2, 0)),
                       rtol=0, atol=1e-13)
    checks = {c.quantity: c for c in res.checks}
    assert checks["∫ pᵣ dr from rₘᵢₙ to rₘₐₓ, by quadrature"].rel_error < 1e-13


def test_power_law_half_action_against_quadpack():
    params = 'potential = "power"\nn = 1.2'
    initial = "x = 1.0\ny = 0.0\nvx = 0.0\nvy = 0.8"
    res = load_scene(parse_config_text(central(params, initial, "t_end = 8.0\nsamples = 801"))
                     ).simulate()
    a = res.analysis
    mu, k, n = 0.5, 0.5, 1.2
    E, L = initial_constants(1.0, 0.0, 0.0, 0.8, mu, k, n)

    def F(r):
        return 2 * mu * (E + k / r**n) - L * L / r**2

    r_min = optimize.brentq(F, 0.05, 0.99, xtol=1e-15)  # the start r = 1 is the apocentre
    ref = quad(lambda r: math.sqrt(max(F(r), 0.0)), r_min, 1.0)
    assert a["hj_half_action"] == pytest.approx(ref, rel=1e-10)
    assert a["hj_characteristic_residual_quadrature"] < 1e-10
    assert a["hj_residual_quadrature"] < 1e-10
    assert "hj_half_action_closed_form" not in a  # no closed form for V = −k/r^1.2


def test_inverse_cube_keeps_the_kepler_closed_form():
    params = 'potential = "kepler_inverse_cube"\nepsilon = 0.01'
    initial = "x = 1.0\ny = 0.0\nvx = 0.0\nvy = 0.8"
    res = load_scene(parse_config_text(central(params, initial, "t_end = 8.0\nsamples = 801"))
                     ).simulate()
    a = res.analysis
    mu, k, eps = 0.5, 0.5, 0.01
    E, L = initial_constants(1.0, 0.0, 0.0, 0.8, mu, k, 1.0, eps)
    # L² → L² − 2με in the centrifugal term (Landau & Lifshitz §15 problem 3)
    half = math.pi * (k * math.sqrt(mu / (-2 * E)) - math.sqrt(L * L - 2 * mu * eps))
    assert a["hj_half_action"] == pytest.approx(half, rel=1e-12)
    assert a["hj_characteristic_quadrature_error"] < 1e-13


def test_unbound_orbit_has_no_hamilton_jacobi_section(tmp_path):
    from reportgen.archive.store import read_archive, write_archive

    text = central(initial="x = 1.0\ny = 0.0\nvx = 0.0\nvy = 1.6",
                   run="t_end = 5.0\nsamples = 101")
    scene = load_scene(parse_config_text(text))
    res = scene.simulate()
    assert not any(k.startswith("hj_") for k in res.analysis)
    path = tmp_path / "run.h5"
    write_archive(path, kind=scene.kind, title=scene.title, scene="test", config_text=text,
                  config_sha256="0", results=res, resolved_config=scene.resolved_config())
    assert "hamilton_jacobi" not in type(scene).default_sections(read_archive(path))


def test_kepler_hamilton_jacobi_section_from_the_archive(tmp_path):
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from reportgen.archive.store import read_archive, write_archive
    from reportgen.rendering.gate import figure_findings

    text = central()
    scene = load_scene(parse_config_text(text))
    path = tmp_path / "run.h5"
    write_archive(path, kind=scene.kind, title=scene.title, scene="test", config_text=text,
                  config_sha256="0", results=scene.simulate(),
                  resolved_config=scene.resolved_config())
    data = read_archive(path)
    assert "hamilton_jacobi" in type(scene).default_sections(data)
    content = type(scene).section_hamilton_jacobi(data)
    (figure,) = content.figures
    FigureCanvasAgg(figure.figure)
    figure.figure.savefig(io.BytesIO(), format="svg")  # laid out as the report saves it
    assert figure_findings(figure.figure) == []
    cells = [cell for row in content.tables[0].rows for cell in row]
    assert any("Goldstein §10.8" in c for c in cells)
