"""Heavy symmetric top against its closed form (lecture notes §10.1, eqs. 10.21-10.50;
Goldstein 3rd ed. §5.7, eqs. 5.62-5.73).

References checked here:
- f(u) = (1 − u²)(α − βu) − (b − au)² = β(u − u1)(u2 − u)(u3 − u)   (10.31; Goldstein 5.71)
- T = 4K(k²)/√(β(u3 − u1)), k² = (u2 − u1)/(u3 − u1)                (notes (10.31); Goldstein §5.7)
- Δφ per period = ∮ (b − au)/(1 − u²) dt                               (10.26)
- u(t) = u1 + (u2 − u1) sn²(½√(β(u3 − u1)) t + τ0 | k²)   (Jacobi form of Goldstein 5.72)
- steady precession I1 cos θ φ̇² − I3ω3 φ̇ + Mgl = 0 and (10.46)        (10.45-10.46)
- sleeping top stable iff I3²ω3² > 4 I1 Mgl                            (10.49-10.50)
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest
from scipy import integrate as sp_integrate
from scipy import special

from reportgen.archive.store import read_archive
from reportgen.core import heavy_top_kinematics as kinematics
from reportgen.core import heavy_top_theory as theory
from reportgen.core.integrators import integrate
from reportgen.core.models import heavy_top as model_core
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, parse_config_text

I1, I3, MGL = 1.0, 0.5, 1.0  # the SPEC example top; sleeping threshold ω3 = 4 rad/s


def top_text(theta=1.0, theta_dot=0.0, phi_dot=1.5, omega3=6.0, t_end=30.0, samples=3000,
             study="false", extra=""):
    phi = "" if phi_dot is None else f"phi_dot = {phi_dot!r}"
    return textwrap.dedent(f"""
        kind = "heavy_top"
        title = "test top"

        [params]
        I1 = {I1}
        I3 = {I3}
        Mgl = {MGL}

        [initial]
        theta = {theta!r}
        theta_dot = {theta_dot!r}
        {phi}
        omega3 = {omega3!r}

        [run]
        t_end = {t_end}
        samples = {samples}
        study = {study}
        """) + textwrap.dedent(extra)


def scene(text):
    return load_scene(parse_config_text(text))


# states: (θ0, θ̇0, φ̇0, ω3) covering loops, waves, cusps, a moving start, a top passing close
# to the vertical, nearly sleeping tops on both sides of the threshold, and a steady top
STATES = {
    "loops (SPEC example)": (1.0, 0.0, 1.5, 6.0),
    "waves": (1.0, 0.0, 0.2, 6.0),
    "cusps": (1.0, 0.0, 0.0, 6.0),
    "moving start": (0.7, -0.9, 0.4, 5.0),
    "near the vertical": (0.3, 0.5, 3.0, 12.0),
    "sleeping, stable, tilt 1e-6": (1e-6, 0.0, 0.0, 6.0),
    "sleeping, unstable, tilt 1e-6": (1e-6, 0.0, 0.0, 2.8),
}


def closed(state):
    c = theory.constants(I1, I3, MGL, *state)
    return c, theory.roots(c)


@pytest.mark.parametrize("name", STATES)
def test_cubic_factorizes_with_ordered_roots(name):
    # (10.31): f(u) = β(u − u1)(u2 − u)(u3 − u) with u1 ≤ cos θ0 ≤ u2 ≤ 1 < u3
    c, r = closed(STATES[name])
    assert r.u1 <= math.cos(STATES[name][0]) * (1 + 1e-15) + 1e-15
    assert math.cos(STATES[name][0]) <= r.u2 + 1e-15 and r.u2 <= 1.0 < r.u3
    u = np.linspace(-1.0, 1.0, 41)
    scale = c.beta * (1 + abs(r.u3)) * 4 + (abs(c.b) + abs(c.a)) ** 2
    assert np.max(np.abs(theory.f_u(u, c) - c.beta * (u - r.u1) * (r.u2 - u) * (r.u3 - u))) \
        <= 1e-13 * scale
    # in w = 1 − u the small roots keep their relative accuracy: g(w_i) ≈ 0 to rounding
    for w in (r.w1, r.w2):
        h = max(w, 1e-300) * 1e-9
        assert abs(theory.g_w(w, c)) <= abs(theory.g_w(w + h, c) - theory.g_w(w - h, c)) + 1e-300


@pytest.mark.parametrize("name", STATES)
def test_period_and_precession_closed_form_vs_quadrature(name):
    c, r = closed(STATES[name])
    T, dphi = theory.nutation_period(r, c), theory.precession_per_period(r, c)
    # closed form (Carlson R_F, R_J) vs adaptive quadrature of ∮du/√f and ∮φ̇ du/√f (10.26)
    assert abs(T / theory.nutation_period_quadrature(r, c) - 1) <= 1e-9
    assert abs(dphi / theory.precession_quadrature(r, c) - 1) <= 1e-9
    if r.mc > 1e-6:  # scipy's ellipk, a third, independent K: T = 4K(k²)/√(β(u3 − u1))
        assert abs(T / (4 * special.ellipk(r.m) / math.sqrt(c.beta * (r.u3 - r.u1))) - 1) <= 1e-12


def test_precession_quadrature_in_time_by_direct_integration_of_phi_dot():
    # Δφ as ∫ φ̇ dt of the ODE u̇ = ±√f, φ̇ = (b − au)/(1 − u²) (10.26), by solve_ivp over
    # one period of the sn² solution: independent of both the Π form and the χ substitution
    c, r = closed(STATES["loops (SPEC example)"])
    T = theory.nutation_period(r, c)
    t = np.linspace(0.0, T, 20001)
    _w, u = theory.u_closed_form(t, r, c)
    phi_dot = (c.b - c.a * u) / (1 - u**2)
    dphi = sp_integrate.simpson(phi_dot, x=t)
    assert abs(dphi / theory.precession_per_period(r, c) - 1) <= 1e-9


@pytest.mark.parametrize("preset,case", [("fig4.3a", "loops"), ("fig4.3b", "waves"),
                                         ("fig4.3c", "cusps")])
def test_fig43_presets_measured_against_closed_form(preset, case):
    s = scene(f'kind = "heavy_top"\npreset = "{preset}"\n[run]\nt_end = 30.0\nstudy = false\n')
    results = s.simulate()
    a, run = results.analysis, results.runs["main"]
    assert a["case"] == case
    for col in ("theta", "phi", "psi", "axis_x", "axis_y", "axis_z"):  # SPEC archive columns
        assert col in run.columns
    for key in ("u1", "u2", "nutation_period", "precession_per_period", "case",
                "sleeping_threshold_omega3"):
        assert key in a
    # period and precession measured from θ(t), φ(t) of the quaternion integration
    assert abs(a["nutation_period_measured"] / a["nutation_period"] - 1) <= 1e-6
    assert abs(a["precession_measured"] / a["precession_per_period"] - 1) <= 1e-6
    # closed-form u(t) in Jacobi sn² against the integrated axis
    assert a["u_max_error"] <= 1e-9
    # the axis stays between the turning circles θ1 = arccos u2, θ2 = arccos u1
    assert np.all(run["theta"] >= a["theta1"] - 1e-9) and np.all(run["theta"] <= a["theta2"] + 1e-9)
    # the derived axis is (sin θ sin φ, −sin θ cos φ, cos θ) (Goldstein eq. 4.46, z-x-z)
    th, ph = run["theta"], run["phi"]
    assert np.max(np.abs(run["axis_x"] - np.sin(th) * np.sin(ph))) <= 1e-12
    assert np.max(np.abs(run["axis_y"] + np.sin(th) * np.cos(ph))) <= 1e-12
    assert results.status == "ok" and run.status == "ok"
    # loops: φ̇ changes sign; waves: never; cusps: touches zero on the upper circle
    phid = run["phi_dot"]
    if case == "loops":
        assert phid.min() < -0.1 and phid.max() > 0.1
    elif case == "waves":
        assert phid.min() > 0.0
    else:
        assert phid.min() >= -1e-6 and phid.min() <= 1e-3


def test_classification_near_each_boundary():
    # released with θ̇0 = 0 at θ0: φ̇0 = 0 is the top turning point with b/a = u2 (cusps);
    # φ̇0 = β/a makes the *upper* circle have φ̇ = 0 for a start on the lower one:
    # α = βc and b = ac with c = b/a give a φ̇0² sin² = β φ̇0 sin² (from (10.25), (10.30))
    a = I3 * 6.0 / I1
    beta = 2 * MGL / I1
    for phi_dot, expected in [(0.0, "cusps"), (1e-6, "waves"), (-1e-6, "loops"),
                              (1e-8, "waves"), (-1e-8, "loops"),
                              (beta / a, "cusps"), (beta / a * (1 + 1e-6), "loops"),
                              (beta / a * (1 - 1e-6), "waves")]:
        c, r = closed((1.0, 0.0, phi_dot, 6.0))
        assert theory.classify(r, c) == expected, (phi_dot, expected)
    # the steady rates (10.45) give no nutation
    slow, fast = theory.steady_precession_rates(I1, I3, MGL, 1.0, 6.0)
    for rate in (slow, fast):
        assert theory.classify(*reversed(closed((1.0, 0.0, rate, 6.0)))) == "steady"
        # ... and a start 1e-6 off the steady rate nutates (slightly), with a period close
        # to the small-oscillation limit 2π/√(β(u3 − u1)) of the steady top
        c, r = closed((1.0, 0.0, rate * (1 + 1e-6), 6.0))
        assert theory.classify(r, c) in ("loops", "waves")
        c0, r0 = closed((1.0, 0.0, rate, 6.0))
        assert theory.nutation_period(r, c) == pytest.approx(
            2 * math.pi / math.sqrt(c0.beta * (r0.u3 - r0.u1)), rel=1e-5)


def test_sleeping_top_exactly_vertical_runs_without_nan():
    for omega3, stable in ((6.0, True), (2.8, False)):
        s = scene(top_text(theta=0.0, phi_dot=0.0, omega3=omega3, t_end=20.0, samples=401))
        results = s.simulate()
        run, a = results.runs["main"], results.analysis
        assert np.all(np.isfinite(run.y))
        assert np.max(run["theta"]) == 0.0 and np.all(run["axis_z"] == 1.0)
        assert a["case"] == "sleeping" and a["sleeping_stable"] is stable
        if stable:  # small-oscillation limit 2π/√(a² − 2β) of the linearised (10.47-10.48)
            aa, beta = I3 * omega3 / I1, 2 * MGL / I1
            assert a["nutation_period"] == pytest.approx(2 * math.pi / math.sqrt(aa**2 - 2 * beta),
                                                         rel=1e-13)
        else:
            assert math.isnan(a["nutation_period"])
        # on the vertical the rotation is all spin: φ stays 0, ψ advances at ω3
        assert np.all(run["phi"] == 0.0)
        assert abs((run["phi"][-1] + run["psi"][-1]) - omega3 * 20.0) <= 1e-9 * omega3 * 20


def test_sleeping_sweep_small_tilt_stays_small_above_threshold_grows_below():
    text = top_text(theta=1e-6, phi_dot=0.0, omega3=6.0, t_end=5.0, samples=201, extra="""
        [sleeping]
        tilt = 1e-6
        omega3_over_threshold = [0.5, 0.9, 1.1, 2.0]
        t_end = 60.0
        """)
    results = scene(text).simulate()
    a = results.analysis
    # (10.50): ω3² = 4 I1 Mgl / I3²
    assert a["sleeping_threshold_omega3"] == pytest.approx(math.sqrt(4 * I1 * MGL / I3**2),
                                                           rel=1e-15)
    sw = a["sleeping_sweep"]
    for ratio, tmax in zip(sw["omega3_over_threshold"], sw["theta_max"], strict=True):
        if ratio > 1:
            assert tmax < 1e-5, (ratio, tmax)
        else:
            assert tmax > 0.5, (ratio, tmax)
    # the early exponential growth matches the linear rate ½√(2β − a²) (10.48)
    t, th = sw["t"], sw["theta"][0]
    first_rise = np.arange(t.size) < np.argmax(th > 1e-2)
    window = first_rise & (th > 1e-4)
    slope = np.polyfit(t[window], np.log(th[window]), 1)[0]
    assert slope == pytest.approx(sw["growth_rate"][0], rel=0.02)


def test_steady_precession_keeps_theta_and_rate():
    for which in ("slow", "fast"):
        text = top_text(phi_dot=None, t_end=10.0, samples=1001).replace(
            "omega3 = 6.0", f'omega3 = 6.0\nsteady = "{which}"')
        results = scene(text).simulate()
        run, a = results.runs["main"], results.analysis
        rate = a[f"steady_rate_{which}"]
        # (10.45): I1 cos θ φ̇² − I3 ω3 φ̇ + Mgl = 0
        assert abs(I1 * math.cos(1.0) * rate**2 - I3 * 6.0 * rate + MGL) <= 1e-13 * (I3 * 6 * rate)
        assert a["case"] == "steady"
        assert np.max(np.abs(run["theta"] - 1.0)) <= 1e-9
        assert abs(a["mean_phi_dot"] / rate - 1) <= 1e-9


@pytest.mark.parametrize("preset", ["fig4.3a", "sleeping_stable", "steady_fast"])
def test_stored_curves_are_the_closed_forms(preset):
    # the report draws only what simulate stored: each curve against its formula
    s = scene(f'kind = "heavy_top"\npreset = "{preset}"\n[run]\nstudy = false\n')
    results = s.simulate()
    a, run = results.analysis, results.runs["main"]
    theta0 = s.config.initial.theta
    beta = 2 * MGL / I1
    # f(u) = β(u − u1)(u2 − u)(u3 − u) (10.31); in w = 1 − u: β(w2 − w)(w − w1)(w − w3)
    cc = a["cubic_curve"]
    x, f = cc["x"], cc["f"]
    if cc["variable"] == "u":
        factored = beta * (x - a["u1"]) * (a["u2"] - x) * (a["u3"] - x)
        assert cc["start"] == pytest.approx(math.cos(theta0), abs=1e-15)
    else:
        w1, w2, w3 = a["one_minus_u2"], a["one_minus_u1"], 1 - a["u3"]
        factored = beta * (w2 - x) * (x - w1) * (x - w3)
        assert 0.0 < w2 < 1e-3 and cc["start"] == pytest.approx(2 * math.sin(theta0 / 2) ** 2)
    assert np.max(np.abs(f - factored)) <= 1e-9 * np.max(np.abs(f))
    # V'(θ) = Mgl cos θ + I1 (b − a cos θ)²/(2 sin²θ) (10.28), E' = I1 α/2 (10.30)
    ep = a["effective_potential"]
    th = ep["theta"]
    V = MGL * np.cos(th) + 0.5 * I1 * (a["b"] - a["a"] * np.cos(th)) ** 2 / np.sin(th) ** 2
    if ep["minus_Mgl"]:  # near the vertical: V' − Mgl, E' − Mgl
        assert np.max(np.abs(ep["V"] + MGL - V)) <= 1e-12 * MGL
        assert ep["energy"] + MGL == pytest.approx(0.5 * I1 * a["alpha"], abs=1e-13)
    else:
        assert np.max(np.abs(ep["V"] / V - 1)) <= 1e-12
        assert ep["energy"] == pytest.approx(0.5 * I1 * a["alpha"], rel=1e-14)
        # the turning angles are where E' = V'(θ): there f(u) = 0
        for t_turn in (a["theta1"], a["theta2"]):
            v = MGL * math.cos(t_turn) + 0.5 * I1 * (a["b"] - a["a"] * math.cos(t_turn)) ** 2 \
                / math.sin(t_turn) ** 2
            assert v == pytest.approx(ep["energy"], abs=1e-10 * MGL)
    # steady rates: both roots of I1 cos θ0 φ̇² − I3 ω3 φ̇ + Mgl = 0 (10.45) on the grid,
    # from the bound I3² ω3² = 4 I1 Mgl cos θ0 (10.46)
    sr = a["steady_rates"]
    assert (I3 * sr["omega3_min"]) ** 2 == pytest.approx(4 * I1 * MGL * math.cos(theta0),
                                                          rel=1e-14)
    assert np.all(sr["omega3"] > sr["omega3_min"]) and sr["omega3"].size == 400
    for rate in (sr["slow"], sr["fast"]):
        residual = I1 * math.cos(theta0) * rate**2 - I3 * sr["omega3"] * rate + MGL
        assert np.max(np.abs(residual) / (I3 * sr["omega3"] * np.abs(rate))) <= 1e-12
    assert np.all(sr["slow"] < sr["fast"])
    # θ(t) of the sn² closed form on the output grid against the integrated θ(t), and the
    # stored difference in cos θ against the largest one the analysis reports
    assert run.attrs["reference_label"].startswith("closed form")
    assert np.max(np.abs(run.reference["theta"] - run["theta"])) <= 1e-7
    err = a["cos_theta_error"]
    width = a["one_minus_u1"] - a["one_minus_u2"] if err["relative_to_width"] else 1.0
    assert np.max(np.abs(err["difference"])) * width == pytest.approx(a["u_max_error"],
                                                                      rel=1e-3, abs=1e-15)


@pytest.mark.parametrize("change,keys", [
    ({"I3 = 0.5": "I3 = 2.5"}, "params.I3"),
    ({"theta = 1.0": "theta = 3.5"}, "initial.theta"),
    ({"omega3 = 6.0": "omega3 = 0.0", "phi_dot = 1.5": "phi_dot = 0.0"}, "initial.omega3"),
    ({"phi_dot = 1.5": 'phi_dot = 1.5\nsteady = "slow"'}, "initial.phi_dot / initial.steady"),
    ({"phi_dot = 1.5": 'steady = "slow"', "omega3 = 6.0": "omega3 = 1.0"},
     "initial.omega3 / initial.steady"),  # (10.46) fails
    ({"theta = 1.0": "theta = 0.0"}, "initial.phi_dot"),
    ({"study = false": 'study = false\n[report]\nsections = ["polhode"]'}, "report.sections"),
])
def test_bad_input_is_an_error_naming_the_keys(change, keys):
    text = top_text()
    for old, new in change.items():
        text = text.replace(old, new)
    with pytest.raises(ConfigError) as exc:
        scene(text)
    assert keys in str(exc.value)


def test_expect_case_must_match_the_parameters():
    text = 'kind = "heavy_top"\npreset = "fig4.3a"\n[initial]\nphi_dot = 0.2\n'
    with pytest.raises(ConfigError) as exc:
        scene(text)
    assert "expect_case" in str(exc.value) and "waves" in str(exc.value)


def test_quaternion_euler_angles_round_trip():
    rng = np.random.default_rng(3)
    for _ in range(20):
        phi, theta, psi = rng.uniform(-3, 3), rng.uniform(0.01, 3.1), rng.uniform(-3, 3)
        q = model_core.euler_to_quaternion(phi, theta, psi)[None, :]
        th, ph, ps = kinematics.euler_angles(q)
        assert th[0] == pytest.approx(theta, abs=1e-13)
        # φ, ψ modulo 2π
        assert math.remainder(ph[0] - phi, 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
        assert math.remainder(ps[0] - psi, 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
        e3 = kinematics.symmetry_axis(q)[0]
        assert np.allclose(e3, [math.sin(theta) * math.sin(phi), -math.sin(theta) * math.cos(phi),
                                math.cos(theta)], atol=1e-14)


@pytest.mark.parametrize("start, step_ratio", [
    ((0.7, -0.9, 0.4, 5.0), 0.7), ((0.9, 0.0, 0.3, 6.0), 0.5),
    ((0.05, 0.3, 0.0, 2.0), 0.8), ((0.0, 0.2, 0.0, 8.0), 0.8)])
def test_spin_free_form_is_the_body_motion_in_fewer_steps(start, step_ratio):
    # The scene integrates the frame F' that follows the axis without spinning and turns
    # it by ω3 t afterwards (models.heavy_top.body_state); it must be the body model's
    # motion, through the vertical too (θ0 = 0), and cheaper wherever the top spins.
    t = np.linspace(0.0, 20.0, 301)
    body = integrate(model_core.model(I1, I3, MGL), model_core.initial_state(*start), t,
                     rtol=1e-13, atol=1e-15)
    free = integrate(model_core.spin_free_model(I1, I3, MGL, start[3]),
                     model_core.spin_free_initial_state(*start[:3]), t, rtol=1e-13, atol=1e-15)
    assert body.ok and free.ok
    assert np.max(np.abs(model_core.body_state(t, free.y, start[3]) - body.y)) < 1e-10
    assert free.nsteps < step_ratio * body.nsteps


#: the top of issue 15: (θ0, θ̇0, φ̇0, ω3) and (I1, I3, Mgl), over 60 s
ISSUE_TOP, ISSUE_TOP_BODY = (0.9, 0.0, 0.3, 6.0), (1.3, 0.45, 0.9)


def _issue_top():
    """The issue's top: its start, body, output times, constants and θ(t) from
    cos θ = u1 + (u2 − u1) sn²(λt + τ0 | k²) (Goldstein 5.72)."""
    t = np.linspace(0.0, 60.0, 201)
    c = theory.constants(*ISSUE_TOP_BODY, *ISSUE_TOP)
    return ISSUE_TOP, ISSUE_TOP_BODY, t, c, theory.theta_closed_form(t, theory.roots(c), c)


def test_spin_free_theta_matches_the_elliptic_closed_form():
    # θ(t) of the spin-free run against the sn² closed form, the top of issue 15 over
    # 60 s: the error follows the tolerance.
    start, (i1, i3, mgl), t, _, exact = _issue_top()
    model = model_core.spin_free_model(i1, i3, mgl, start[3])
    y0 = model_core.spin_free_initial_state(*start[:3])
    errors = [float(np.max(np.abs(kinematics.tilt_angle(
        integrate(model, y0, t, rtol=rtol, atol=rtol * 1e-2).y[:, :4]) - exact)))
        for rtol in (1e-8, 1e-10, 1e-12)]
    assert errors[0] < 1e-6 and errors[1] < 1e-8 and errors[2] < 1e-10
    assert errors[0] > 10 * errors[1] > 100 * errors[2]


@pytest.mark.parametrize("start", [(0.7, -0.9, 0.4, 5.0), (0.9, 0.0, 0.3, 6.0),
                                   (2.5, 0.4, -0.3, 3.0), (1.2, 0.0, 0.8, 0.0)])
def test_reduced_form_is_the_body_motion(start):
    # Lagrange's reduction (w = 1 − cos θ, ẅ = g'(w)/2, φ and ψ as quadratures) mapped
    # back to (q, ω) is the body model's motion: a hanging top (θ0 = 2.5, θ up to 2.93)
    # and one with no spin (ω3 = 0, a spherical pendulum) included; each keeps away from
    # the vertical, where the reduction is singular.
    t = np.linspace(0.0, 20.0, 301)
    body = integrate(model_core.model(I1, I3, MGL), model_core.initial_state(*start), t,
                     rtol=1e-13, atol=1e-15)
    c = theory.constants(I1, I3, MGL, *start)
    model = model_core.reduced_model(I1, I3, MGL, start[3], c.A, c.B)
    red = integrate(model, model_core.reduced_initial_state(*start[:2]), t, rtol=1e-13,
                    atol=1e-15)
    assert body.ok and red.ok
    assert np.max(np.abs(model_core.reduced_body_state(red.y, model.params) - body.y)) < 1e-10


def test_reduced_theta_matches_the_elliptic_closed_form_with_fewer_steps():
    # θ(t) of the reduced run against the sn² closed form (Goldstein 5.72) on the top of
    # issue 15: the error follows the tolerance; it takes fewer steps than the spin-free
    # form for the same accuracy.
    start, (i1, i3, mgl), t, c, exact = _issue_top()
    model = model_core.reduced_model(i1, i3, mgl, start[3], c.A, c.B)
    y0 = model_core.reduced_initial_state(*start[:2])
    runs = [integrate(model, y0, t, rtol=rtol, atol=rtol * 1e-2) for rtol in (1e-8, 1e-10, 1e-12)]
    errors = [float(np.max(np.abs(theory.theta_of_w(r.y[:, 0]) - exact))) for r in runs]
    assert errors[0] < 1e-6 and errors[1] < 2e-10 and errors[2] < 1e-11
    assert errors[0] > 10 * errors[1] > 100 * errors[2]
    free = integrate(model_core.spin_free_model(i1, i3, mgl, start[3]),
                     model_core.spin_free_initial_state(*start[:3]), t, rtol=1e-10, atol=1e-12)
    assert runs[1].nsteps < free.nsteps


def test_reduced_form_on_the_vertical_fails_cleanly():
    # w = 0 with B = 0 is 0/0 in φ̇: the driver (compiled for this model, the division
    # inlined) reports NONFINITE instead of raising.
    model = model_core.reduced_model(I1, I3, MGL, 5.0, 0.0, 0.0)
    sol = integrate(model, np.zeros(4), np.linspace(0.0, 1.0, 11))
    assert not sol.ok and sol.code.name == "NONFINITE"


@pytest.mark.parametrize("initial, run, expected", [
    ("theta = 0.9\ntheta_dot = 0.0\nphi_dot = 0.3\nomega3 = 6.0", "", "reduced"),
    ("theta = 0.05\ntheta_dot = 0.0\nphi_dot = 0.0\nomega3 = 5.0", "", "spin_free"),
    ("theta = 0.0\ntheta_dot = 0.0\nphi_dot = 0.0\nomega3 = 5.0", "", "spin_free"),
    ("theta = 0.9\ntheta_dot = 0.0\nphi_dot = 0.3\nomega3 = 6.0",
     'formulation = "spin_free"', "spin_free"),
    ("theta = 0.05\ntheta_dot = 0.0\nphi_dot = 0.0\nomega3 = 5.0",
     'formulation = "reduced"', "reduced")])
def test_formulation_auto_keeps_the_reduced_form_off_the_vertical(initial, run, expected):
    from reportgen.kinds.heavy_top import HeavyTopScene

    scene = HeavyTopScene.from_source(parse_config_text(
        f'kind = "heavy_top"\ntitle = "t"\n[params]\nI1 = 1.0\nI3 = 0.5\nMgl = 1.0\n'
        f"[initial]\n{initial}\n[run]\nt_end = 5.0\n{run}\n"))
    assert scene.formulation(next(iter(scene.starts.values())))[0] == expected


def test_reduced_formulation_of_a_top_through_the_vertical_is_refused():
    from reportgen.kinds.heavy_top import HeavyTopScene

    with pytest.raises(ConfigError, match=r"run\.formulation.*singular on the vertical"):
        HeavyTopScene.from_source(parse_config_text(
            'kind = "heavy_top"\ntitle = "t"\n[params]\nI1 = 1.0\nI3 = 0.5\nMgl = 1.0\n'
            "[initial]\ntheta = 0.0\ntheta_dot = 0.0\nphi_dot = 0.0\nomega3 = 5.0\n"
            '[run]\nt_end = 5.0\nformulation = "reduced"\n'))


def test_bench_textbook_row_reaches_the_euler_angle_scripts_theta_error():
    # reportgen bench: scipy DOP853 on the Euler-angle equations against our run (the
    # reduced form here) at the loosest rtol reaching its θ error (both against the
    # closed form).
    from reportgen.commands.bench import heavy_top_textbook
    from reportgen.kinds.heavy_top import HeavyTopScene
    from reportgen.scene.config import parse_config_text

    scene = HeavyTopScene.from_source(parse_config_text(
        'kind = "heavy_top"\ntitle = "t"\n[params]\nI1 = 1.3\nI3 = 0.45\nMgl = 0.9\n'
        "[initial]\ntheta = 0.9\ntheta_dot = 0.0\nphi_dot = 0.3\nomega3 = 6.0\n"
        "[run]\nt_end = 10.0\n"))
    lines = []
    row = heavy_top_textbook(scene, print=lines.append)
    assert 0 < row["peer_error"] < 1e-8 and row["peer_nfev"] > 100
    ours = row["ours"]
    assert ours["error"] <= row["peer_error"] and ours["speedup"] > 1
    assert ours["formulation"] == "reduced"
    assert "textbook" in lines[0]


def test_integration_conserves_energy_and_momenta():
    y0 = model_core.initial_state(0.7, -0.9, 0.4, 5.0)
    t = np.linspace(0.0, 20.0, 401)
    sol = integrate(model_core.model(I1, I3, MGL), y0, t, method="dop853", rtol=1e-12, atol=1e-14)
    inv = model_core.invariants(sol.y, I1, I3, MGL)
    c = theory.constants(I1, I3, MGL, 0.7, -0.9, 0.4, 5.0)
    # E' = I1 α/2 and p_φ = I1 b (10.25, 10.30) from the Euler-angle initial state
    assert inv["energy"][0] == pytest.approx(0.5 * I1 * c.alpha + 0.5 * I3 * 25.0, rel=1e-14)
    assert inv["p_phi"][0] == pytest.approx(I1 * c.b, rel=1e-14)
    for values in inv.values():
        assert np.max(np.abs(values - values[0])) <= 1e-10 * max(1.0, abs(values[0]))


def test_cli_run_writes_archive_per_spec_with_study(write_config, cli, tmp_path):
    cfg = write_config("top", 'kind = "heavy_top"\npreset = "fig4.3c"\n'
                              '[run]\nt_end = 6.0\nsamples = 600\n')
    code, _out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err
    data = read_archive(tmp_path / "o" / "top" / "run.h5")
    a = data.analysis
    assert a["case"] == "cusps"
    assert set(data.runs["main"].invariants) == {"energy", "p_phi", "p_psi"}
    assert data.study is not None and len(data.study) > 0
    assert abs(a["nutation_period_measured"] / a["nutation_period"] - 1) <= 1e-6
    html = (tmp_path / "o" / "top" / "report.html").read_text()
    assert "Nutation locus" in html and "Steady precession" not in html
