"""Our Taylor-series integrator (reportgen.core.taylor, method "taylor").

Independent checks: the coefficient recurrences against high-precision Taylor
coefficients of a composite function (mpmath, SymPy's arbitrary-precision backend); the
pendulum against its Jacobi-elliptic solution (DLMF 22.19); Kepler's e = 0.7 orbit
against Kepler's equation (Goldstein (3.76)–(3.80)) and its energy; a formula model
(Hénon–Heiles) against our DOP853; a blow-up that must fail, not hang.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy

from reportgen.core import formula, taylor
from reportgen.core.integrators import METHODS, MethodMismatch, SolveCode, integrate
from reportgen.core.models import kepler, pendulum
from reportgen.core.taylor.decompose import Unsupported, decompose


# ------------------------------------------------------------------- the recurrences
def test_coefficients_match_high_precision_taylor_series():
    """x' = 1 (x = s), y' = g(x, t) with g composite of every recurrence (products,
    quotients, r^α, √, sin/cos, tan, sinh/cosh, exp, log, |·|, integer powers): the
    generated coefficients of y are ∫ g's series, so (k + 1) y_[k+1] must equal g's k-th
    Taylor coefficient at s0 = 1/2 for k ≤ 20 -- computed independently by mpmath at 60
    digits (``mpmath.taylor``, differentiation in arbitrary precision; SymPy's own
    ``series`` of this g takes minutes)."""
    x, y, t = sympy.symbols("x y t")
    g = (sympy.exp(sympy.sin(x)) / sympy.sqrt(1 + t**2)
         + sympy.log(2 + sympy.cos(t)) * x ** sympy.Float(-1.5)
         + sympy.sinh(x) * sympy.cosh(t / 3) + sympy.tan(x) / (3 + t)
         + x ** sympy.Float(2.7) - 2 * (x - t + 1) ** 3 / (1 + x * t) ** 2
         + sympy.Abs(sympy.cos(x) - 2) + sympy.sqrt(x + 2 * t))
    dec = decompose([sympy.Integer(1), g], [x, y], t)
    assert {op.kind for op in dec.ops} >= {"lin", "mul", "sqr", "div", "pow", "sqrt",
                                           "sincos", "sinhcosh", "exp", "log", "abs"}
    order = 21
    got = {}
    for unrolled in (False, True):  # both generated forms
        system = _compile(dec, order if unrolled else None)
        X = np.zeros((order + 1, 2))
        W = np.zeros((dec.n_rows, order + 1))
        inv = np.array([0.0] + [1.0 / k for k in range(1, order + 2)])
        system.coefficients(0.5, np.array([0.5, 0.0]), W, X, order, inv)
        got[unrolled] = np.array([(k + 1) * X[k + 1, 1] for k in range(order)])
    gs = sympy.lambdify(sympy.Symbol("s"), g.subs({x: sympy.Symbol("s"),
                                                   t: sympy.Symbol("s")}), "mpmath")
    with mpmath.workdps(60):
        want = np.array([float(c) for c in mpmath.taylor(gs, mpmath.mpf(1) / 2, order - 1)])
    # the coefficients grow like 2^k (the pole of x^-1.5 at distance 1/2): each is
    # compared to its own size; round-off of the recurrences stays near 1e-14 of it
    for unrolled, g_k in got.items():
        assert np.all(np.abs(g_k - want) <= 1e-12 * np.abs(want) + 1e-14), (
            unrolled, (g_k - want) / want)


def _compile(dec, order=None):
    """The generated module of ``dec``: unrolled for ``order``, or looped (None)."""
    from reportgen.core.codegen import load_module
    from reportgen.core.taylor.codegen import CODE_VERSION, module_source, unrolled_source

    codes = {"OK": 0, "NONFINITE": 1, "STEP_UNDERFLOW": 2, "MAX_STEPS": 3}
    source = (module_source(dec, codes) if order is None
              else unrolled_source(dec, order, codes))
    return load_module(source, "taylor", CODE_VERSION)


def test_unsupported_function_is_a_mismatch():
    """A right-hand side with atan has no recurrence here: a MethodMismatch before work."""
    q, p = sympy.symbols("q p")
    with pytest.raises(Unsupported, match="atan"):
        decompose([p, -sympy.atan(q)], [q, p])
    system = formula.build_system(["q"], H="p_q**2/2 + atan(q)**2")
    model = formula.compiled_model(system, name="atan")
    with pytest.raises(MethodMismatch, match="atan"):
        integrate(model, [0.1, 0.0], np.linspace(0, 1, 3), method="taylor")


def test_order_from_tolerance():
    """Jorba & Zou 2005 §3.2.1: p = ⌈−ln(tol)/2 + 1⌉ (heyoka's order, e.g. 16 at 1e-13)."""
    assert [taylor.order_for_tol(t) for t in (1e-6, 1e-9, 1e-13, 1e-16)] == [8, 12, 16, 20]


# ------------------------------------------------------------------ closed-form runs
@pytest.mark.parametrize(("tol", "bound"), [(1e-6, 5e-6), (1e-10, 5e-10), (1e-14, 2e-12)])
def test_pendulum_against_the_elliptic_solution(tol, bound):
    """θ0 = 2.5 rad libration over ~8 periods against the Jacobi-elliptic θ(t),
    θ̇(t) (DLMF 22.19.2, pendulum.exact_solution).  The error follows the tolerance
    (measured 1.4e-6, 1.4e-10, 1.5e-13 of the amplitude scale); at 1e-14 the bound
    allows the closed form's own error (scipy's ellipj and the elliptic integral: ~1e-13
    after 8 periods)."""
    g, l, th0 = 9.81, 1.0, 2.5
    model = pendulum.model(g, l)
    t = np.linspace(0.0, 20.0, 401)
    sol = integrate(model, [th0, 0.0], t, method="taylor", rtol=tol)
    assert sol.ok and sol.code is SolveCode.OK
    th, thd = pendulum.exact_solution(t, th0, 0.0, g, l)
    err = max(np.max(np.abs(sol.y[:, 0] - th)), np.max(np.abs(sol.y[:, 1] - thd)) / 6.0)
    assert err <= bound, err
    assert sol.nsteps > 0 and sol.wall_time_s > 0.0


def test_pendulum_error_scales_with_tol():
    """Tighter tolerance, smaller error: each 1e-4 step in tol gains ≥ 1e3 in error."""
    model = pendulum.model(9.81, 1.0)
    t = np.linspace(0.0, 10.0, 101)
    th, _ = pendulum.exact_solution(t, 2.0, 0.0, 9.81, 1.0)
    errs = [np.max(np.abs(integrate(model, [2.0, 0.0], t, method="taylor",
                                    rtol=tol).y[:, 0] - th)) for tol in (1e-5, 1e-9)]
    assert errs[1] < 1e-3 * errs[0], errs


def test_kepler_e07_against_keplers_equation():
    """The e = 0.7 orbit (K = 1, a = 1) over 5 periods against Kepler's equation solved
    by Newton (kepler.kepler_state, Goldstein (3.76)–(3.80)); the energy −K/(2a)
    (Goldstein (3.61)) held to the tolerance."""
    e, K = 0.7, 1.0
    y0 = np.array([1.0 - e, 0.0, 0.0, math.sqrt(K * (1 + e) / (1 - e))])  # pericentre
    model = kepler.model(K, 1.0)
    el = kepler.orbital_elements(*y0, K)
    assert math.isclose(el["eccentricity"], e, rel_tol=1e-12)
    t = np.linspace(0.0, 5.0 * el["period"], 501)
    sol = integrate(model, y0, t, method="taylor", rtol=1e-13)
    assert sol.ok
    exact = np.column_stack(kepler.kepler_state(t, el))
    assert np.max(np.abs(sol.y - exact)) <= 1e-10, np.max(np.abs(sol.y - exact))
    x, yy, vx, vy = sol.y.T
    energy = 0.5 * (vx**2 + vy**2) - K / np.hypot(x, yy)
    assert np.max(np.abs(energy + K / (2 * el["semi_major_axis"]))) <= 1e-12
    loose = integrate(model, y0, t, method="taylor", rtol=1e-7)
    err_loose = np.max(np.abs(loose.y - exact))
    assert 1e-10 < err_loose < 1e-2, err_loose  # a looser tol costs accuracy


def test_formula_model_against_dop853():
    """Hénon–Heiles (configs/hamiltonian_henon_heiles_regular.toml's H, E = 1/12 orbit)
    from the formula kind's SymPy system: at tol 1e-14 ours follows compiled DOP853 at
    rtol 1e-14 (an independent method) to 1e-10 over t = 100."""
    system = formula.build_system(
        ["x", "y"], H="(p_x**2 + p_y**2)/2 + (x**2 + y**2)/2 + x**2*y - y**3/3")
    model = formula.compiled_model(system, name="henon_heiles")
    y, py = 0.1, 0.0
    px = math.sqrt(2 * (1 / 12) - y**2 + 2 * y**3 / 3 - py**2)  # x = 0 on E = 1/12
    y0 = np.array([0.0, y, px, py])
    t = np.linspace(0.0, 100.0, 1001)
    ref = integrate(model, y0, t, method="dop853", rtol=1e-14, atol=1e-16)
    sol = integrate(model, y0, t, method="taylor", rtol=1e-14)
    assert sol.ok and ref.ok
    assert np.max(np.abs(sol.y - ref.y)) <= 1e-10, np.max(np.abs(sol.y - ref.y))
    H = (0.5 * (sol.y[:, 2] ** 2 + sol.y[:, 3] ** 2) + 0.5 * (sol.y[:, 0] ** 2 + sol.y[:, 1] ** 2)
         + sol.y[:, 0] ** 2 * sol.y[:, 1] - sol.y[:, 1] ** 3 / 3)
    assert np.max(np.abs(H - 1 / 12)) <= 1e-14


def test_time_dependent_formula_model():
    """A driven oscillator H = p²/2 + q²/2 − q cos(2t) (the time enters the recurrences):
    q̈ + q = cos 2t from rest at q0 = 1 has q = (4/3) cos t − (1/3) cos 2t."""
    system = formula.build_system(["q"], H="p_q**2/2 + q**2/2 - q*cos(2*t)")
    model = formula.compiled_model(system, name="driven")
    t = np.linspace(0.0, 30.0, 301)
    sol = integrate(model, [1.0, 0.0], t, method="taylor", rtol=1e-13)
    exact = 4 / 3 * np.cos(t) - np.cos(2 * t) / 3
    assert np.max(np.abs(sol.y[:, 0] - exact)) <= 1e-11


# ------------------------------------------------------------------ failure, bookkeeping
def test_blow_up_fails_and_ends():
    """H = p q²: q' = q², so from q(0) = 1 q = 1/(1 − t) blows up at t = 1 (and
    p = p0 (1 − t)²).  A run to t = 2 ends failed (step underflow or non-finite), NaN
    at the outputs past the blow-up, the outputs before it right."""
    system = formula.build_system(["q"], H="p_q*q**2")
    model = formula.compiled_model(system, name="blow_up")
    t = np.linspace(0.0, 2.0, 21)
    sol = integrate(model, [1.0, 1.0], t, method="taylor", rtol=1e-10)
    assert not sol.ok and sol.status == "failed"
    assert sol.code in (SolveCode.STEP_UNDERFLOW, SolveCode.NONFINITE)
    before = t < 1.0
    # the output at t = 1 itself may come from a last step that reaches 1.0 in rounding
    assert np.all(np.isnan(sol.y[t > 1.0]))
    assert np.allclose(sol.y[before, 0], 1.0 / (1.0 - t[before]), rtol=1e-8)
    assert np.allclose(sol.y[before, 1], (1.0 - t[before]) ** 2, rtol=1e-8)
    assert "failed after t = " in sol.message


def test_method_is_registered_and_not_auto():
    """'taylor' is a registered adaptive method, not a peer; compile time is reported
    once per model (0 on the next run)."""
    m = METHODS["taylor"]
    assert m.adaptive and not m.peer and not m.compiled
    model = pendulum.model(9.81, 2.0)
    t = np.linspace(0.0, 1.0, 5)
    first = integrate(model, [0.3, 0.0], t, method="taylor", rtol=1e-8)
    second = integrate(model, [0.3, 0.0], t, method="taylor", rtol=1e-8)
    assert first.compile_time_s > 0.0 and second.compile_time_s == 0.0
    assert np.array_equal(first.y, second.y)


def test_looped_module_agrees_with_the_unrolled_one(monkeypatch):
    """A system too big to unroll runs the looped module (one for every order): forced
    here on the pendulum, it meets the elliptic solution (DLMF 22.19.2) as the unrolled
    module does, with the same steps (the step sizes differ by rounding only)."""
    model = pendulum.model(9.81, 1.0)
    t = np.linspace(0.0, 10.0, 101)
    th, _ = pendulum.exact_solution(t, 2.5, 0.0, 9.81, 1.0)
    unrolled = integrate(model, [2.5, 0.0], t, method="taylor", rtol=1e-12)
    monkeypatch.setattr(taylor, "MAX_UNROLLED_TERMS", 0)
    looped_model = pendulum.model(9.81, 1.0)  # a new model: a new system, no module yet
    looped = integrate(looped_model, [2.5, 0.0], t, method="taylor", rtol=1e-12)
    system, _ = taylor.build(looped_model)
    assert None in system.modules and 16 not in system.modules
    assert looped.nsteps == unrolled.nsteps
    for sol in (looped, unrolled):
        assert np.max(np.abs(sol.y[:, 0] - th)) <= 1e-10
    assert np.max(np.abs(looped.y - unrolled.y)) <= 1e-12


def test_step_budget_ends_the_run():
    """max_steps bounds a run: the pendulum over 20 s needs ~360 steps; 50 end it with
    MAX_STEPS, NaN after the last output reached."""
    from reportgen.core.integrators.taylor import Taylor

    model = pendulum.model(9.81, 1.0)
    t = np.linspace(0.0, 20.0, 201)
    sol = Taylor().solve(model, np.array([2.5, 0.0]), t, 1e-12, 1e-12, max_steps=50)
    assert sol.code is SolveCode.MAX_STEPS and sol.nsteps == 50
    reached = np.all(np.isfinite(sol.y), axis=1)
    assert reached[0] and not reached[-1] and 1 < reached.sum() < t.size


def _order_0(dec, t, y):
    """The right-hand sides of ``dec`` at (t, y), its operations evaluated one by one in
    Python (the order-0 coefficients; independent of the generated code)."""
    v = np.zeros(dec.n_rows)
    v[:dec.n_state] = y
    if dec.time_row is not None:
        v[dec.time_row] = t
    fn = {"sqrt": math.sqrt, "exp": math.exp, "log": math.log, "abs": abs,
          "sign": lambda a: math.copysign(1.0, a) if a else 0.0}
    for op in dec.ops:
        a = [v[r] for r in op.args]
        k, o = op.kind, op.out[0]
        if k == "lin":
            v[o] = op.consts[0] + sum(w * x for w, x in zip(op.consts[1:], a, strict=True))
        elif k == "mul":
            v[o] = op.consts[0] * a[0] * a[1]
        elif k == "sqr":
            v[o] = op.consts[0] * a[0] ** 2
        elif k == "div":
            v[o] = op.consts[0] * (a[0] if len(a) == 2 else 1.0) / a[-1]
        elif k == "pow":
            v[o] = a[0] ** op.consts[0]
        elif k == "sincos":
            v[o], v[op.out[1]] = math.sin(a[0]), math.cos(a[0])
        elif k == "sinhcosh":
            v[o], v[op.out[1]] = math.sinh(a[0]), math.cosh(a[0])
        else:
            v[o] = fn[k](a[0])
    return np.array([f if isinstance(f, float) else v[f] for f in dec.outputs])


def _shipped_models():
    from reportgen.pipeline.stages import validate_all
    from reportgen.support.layout import collect_configs

    out = []
    for scene in validate_all(collect_configs(["configs"])):
        for k, model in enumerate(scene.models()):
            out.append(pytest.param(model, id=f"{scene.source.name}-{k}"))
    return out


#: shipped models with no Taylor form yet (no heyoka translation of their right-hand side)
NO_TAYLOR_FORM: set[str] = set()


def _unshipped_models():
    """Models no config integrates, and branches none reaches (as
    tests/test_heyoka_systems.py lists them)."""
    from reportgen.core.models import heavy_top, kepler_regularized, nbody, rigid_body, three_body_ks

    masses = (1.0, 0.8, 0.3)
    models = [heavy_top.model(1.3, 0.45, 0.9), kepler_regularized.model(-0.6),
              nbody.model(1.0, masses), rigid_body.model(1.0, 2.0, 3.5, kappa=0.8),
              kepler.model(0.7, 0.4, 1.7, 0.3), kepler.model(0.7, 0.4, 1.0, 0.3)]
    models += [three_body_ks.model(1.0, masses, (0, 1), fictitious_time=f) for f in (True, False)]
    return [pytest.param(m, id=f"{m.name}-{k}") for k, m in enumerate(models)]


@pytest.mark.parametrize("model", _shipped_models() + _unshipped_models())
def test_every_shipped_model_decomposes_to_its_rhs(model):
    """Every shipped model has a Taylor form (or is listed in NO_TAYLOR_FORM, with the
    reason in its MethodMismatch), and the form's right-hand sides equal ``model.f`` (our
    compiled code) at random states and times, to rounding."""
    module = getattr(model.rhs, "__module__", "")
    if module.rsplit(".", 1)[-1] in NO_TAYLOR_FORM:
        with pytest.raises(MethodMismatch, match="no SymPy form"):
            METHODS["taylor"].check(model)
        return
    dec = taylor._decomposition(model)
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(8):
        y, t = rng.uniform(0.2, 0.9, model.dim), float(rng.uniform(0.0, 3.0))
        want = model.f(t, y)
        if not np.all(np.isfinite(want)):
            continue
        got = _order_0(dec, t, y)
        assert np.max(np.abs(got - want)) <= 1e-12 * max(1.0, np.max(np.abs(want))), (
            model.name, got, want)
        checked += 1
    assert checked >= 4
