"""heyoka's translation of our models (reportgen.core.heyoka_systems) against the models.

Independent check of each translation: heyoka compiles its own symbolic right-hand side
(``hy.cfunc``), and at random states near the config's initial state it must give what our
compiled ``model.rhs`` gives (``model.f``), to rounding.  Then heyoka's Taylor integrator
on the translated system must follow our DOP853 at tight tolerances on a few models.
heyoka is an optional extra: without it these tests are skipped.
"""

from __future__ import annotations

import math
import zlib

import numpy as np
import pytest
import sympy

hy = pytest.importorskip("heyoka")

from reportgen.core import formula  # noqa: E402
from reportgen.core import heyoka_systems as hs  # noqa: E402
from reportgen.core.integrators import integrate  # noqa: E402
from reportgen.pipeline.stages import validate_all  # noqa: E402
from reportgen.support.layout import collect_configs  # noqa: E402

#: heyoka's right-hand side vs ours, |Δf_i| over ‖f‖∞ at each state: both evaluate the
#: same formula in float64 (measured ≤ 7e-16 on every shipped model); a wrong term, sign
#: or parameter is off by far more
RHS_RTOL = 1e-13
#: states per model, drawn near the initial state
SAMPLES = 6


def _initial_state(scene, model) -> np.ndarray:
    """The state ``scene`` starts ``model`` from (as its simulate builds it)."""
    kind = scene.kind
    if kind == "central_force":
        i = scene.config.initial
        return np.array([i.x, i.y, i.vx, i.vy])
    if kind == "fput":
        return np.concatenate(scene.initial_state())
    if kind == "hamiltonian":
        return scene.initial_state()
    if kind == "heavy_top":
        return scene._integration(next(iter(scene.starts.values())))[1]
    if kind == "normal_modes":  # y = (q, M v), M from the packed M⁻¹
        q0, v0 = scene.initial_state()
        n = q0.size
        M = np.linalg.inv(model.params[1:1 + n * n].reshape(n, n))
        return np.concatenate([q0, M @ v0])
    if kind == "oscillator":  # the swapped model starts at (Q, P) = (p, −q)
        i = scene.config.initial
        return np.array([i.q, i.p]) if model.columns == ("q", "p") else np.array([i.p, -i.q])
    if kind == "pendulum":
        i = scene.config.initial
        return np.array([i.theta, i.theta_dot])
    if kind == "rigid_body":
        q0 = np.array(scene.config.initial.attitude, dtype=float)
        return np.concatenate([scene.omega0, q0 / np.linalg.norm(q0)])
    if kind == "three_body" and scene.config.restricted is not None:
        from reportgen.core.models import restricted_three_body

        y0 = scene.restricted_state()
        if model.dim == 5:  # Thiele–Burrau
            return restricted_three_body.to_regularized(*y0, scene.config.restricted.mu)
        return y0
    if kind == "three_body":
        return scene._y0()
    if kind == "two_center":
        from reportgen.core.models import two_center_regularized

        y0 = scene.config.initial_state()
        if model.dim == 5:
            return two_center_regularized.to_regularized(*y0, scene.config.params.a)
        return np.array(y0)
    raise AssertionError(f"kind {kind!r}: no initial state known to this test; add it")


def _integrating_models():
    out = []
    for scene in validate_all(collect_configs(["configs"])):
        for k, model in enumerate(scene.models()):
            out.append(pytest.param(scene, model, id=f"{scene.source.name}-{k}"))
    return out


MODELS = _integrating_models()


def _check_rhs(model, states, times):
    """heyoka's compiled right-hand side equals ``model.f`` at each (time, state)."""
    pairs = hs.system(hy, model)
    assert pairs is not None, hs.why_not(model)
    assert hs.why_not(model) == ""
    variables = [v for v, _ in pairs]
    assert [str(v) for v in variables] == list(model.columns)
    cf = hy.cfunc([f for _, f in pairs], variables)
    got = cf(np.ascontiguousarray(states.T), time=np.asarray(times, dtype=float))
    for k, (t, y) in enumerate(zip(times, states, strict=True)):
        want = model.f(t, y)
        assert np.all(np.isfinite(want)), (t, y)
        scale = float(np.max(np.abs(want)))
        assert np.max(np.abs(got[:, k] - want)) <= RHS_RTOL * scale, (
            f"{model.name} at t={t}, y={y}: heyoka {got[:, k]} vs ours {want}")


def _near(y0, rng, n=SAMPLES, spread=1e-2):
    """``n`` states within ~``spread`` (relative) of ``y0``, zero components moved too."""
    y0 = np.asarray(y0, dtype=float)
    size = np.abs(y0) + np.mean(np.abs(y0))
    return y0 + spread * size * rng.standard_normal((n, y0.size))


def test_every_shipped_model_is_covered():
    """The configs integrate models of every integrating kind (so the enumeration sees
    them), and none of them lacks a translation (a new model without one fails here)."""
    kinds = {p.values[0].kind for p in MODELS}
    assert kinds >= {"central_force", "fput", "hamiltonian", "heavy_top", "normal_modes",
                     "oscillator", "pendulum", "rigid_body", "three_body", "two_center"}, kinds
    missing = [(p.values[0].source.name, hs.why_not(p.values[1])) for p in MODELS
               if hs.system(hy, p.values[1]) is None]
    assert not missing, missing


@pytest.mark.parametrize(("scene", "model"), MODELS)
def test_rhs_matches_ours_near_the_initial_state(scene, model):
    rng = np.random.default_rng(zlib.crc32(scene.source.name.encode()))
    y0 = _initial_state(scene, model)
    assert y0.shape == (model.dim,)
    _check_rhs(model, _near(y0, rng), rng.uniform(0.0, 3.0, SAMPLES))


# ------------------------------------------- branches and models no shipped config reaches
def _random_check(model, y0, seed=0):
    rng = np.random.default_rng(seed)
    _check_rhs(model, _near(y0, rng), rng.uniform(0.0, 3.0, SAMPLES))


@pytest.mark.parametrize(("n", "epsilon"), [(1.0, 0.0), (1.0, 0.3), (1.7, 0.0), (0.6, -0.2)])
def test_kepler_branches(n, epsilon):
    """kepler.rhs's n = 1 and ε ≠ 0 branches (params (k n/μ, n, 2ε/μ))."""
    from reportgen.core.models import kepler

    _random_check(kepler.model(0.7, 0.4, n, epsilon), [0.9, -0.3, 0.2, 1.1])


def test_rigid_body_with_the_normalizing_term():
    """rigid_body.rhs with κ ≠ 0 (the term off in every config) and |q| ≠ 1."""
    from reportgen.core.models import rigid_body

    _random_check(rigid_body.model(1.0, 2.0, 3.5, kappa=0.8),
                  [0.3, -1.2, 0.7, 0.8, 0.3, -0.4, 0.5])


def test_unused_and_regularized_models():
    """The full heavy top, the Levi-Civita Kepler problem and the KS three-body model (in s
    and in t) are translated too, though no config integrates them."""
    from reportgen.core.models import heavy_top, kepler_regularized, nbody, three_body_ks

    _random_check(heavy_top.model(1.3, 0.45, 0.9),
                  heavy_top.initial_state(0.6, 0.2, 0.5, 6.0))
    _random_check(kepler_regularized.model(-0.6), [0.7, 0.2, -0.1, 0.4, 0.0])
    # positions (x, y, z) of bodies 1-3, then their velocities
    y = np.array([0.0, 0.0, 0.0, 0.4, 0.1, 0.05, 2.0, -1.0, 0.5,
                  0.0, -0.3, 0.1, 0.2, 0.9, -0.1, -0.4, 0.3, 0.2])
    masses = (1.0, 0.8, 0.3)
    for fictitious in (True, False):
        reg = three_body_ks.model(1.0, masses, (0, 1), fictitious_time=fictitious)
        _random_check(reg, three_body_ks.to_regularized(y, 1.0, masses, (0, 1), t=0.2))
    assert hs.system(hy, nbody.model(1.0, masses)) is not None


@pytest.mark.parametrize("m", [1, 2])
def test_fput_sizes(m):
    """fput.rhs for chains of m = 1 and 2 pairs (the end springs' indices)."""
    from reportgen.core.models import fput

    q, p = fput.gni_initial(m, 30.0)
    _random_check(fput.model(m, 30.0), np.concatenate([q, p]) + 0.1)


def test_formula_nodes_from_sympy_lacks():
    """A formula H with abs (|x| and sign(x) in the equations, neither of which
    from_sympy translates), the constant E, a rational 1/3, time and a negative constant:
    heyoka matches the generated code, and the time enters through ``time=``."""
    system = formula.build_system(
        ["x", "y"], H="p_x**2/2 + p_y**2/(2*m) + k*x*abs(x) + abs(y) + x**2*y/3"
                      " + E*cos(w*t)*y + c*y**4",
        params={"m": 1.3, "k": 0.7, "w": 2.0, "c": -0.05})
    model = formula.compiled_model(system, name="nodes")
    assert model.extra["formula_system"] is system
    used = {type(n).__name__ for e in system.hamilton.rhs for n in sympy.preorder_traversal(e)}
    assert {"Abs", "sign", "Exp1", "Rational"} <= used, used
    _random_check(model, [0.4, -0.3, 0.2, 0.5])
    # the same states on both sides of x = 0 (sign(x) flips)
    rng = np.random.default_rng(3)
    states = _near([0.0, -0.3, 0.2, 0.5], rng)
    states[:, 0] = np.where(np.arange(SAMPLES) % 2, 0.01, -0.01)
    _check_rhs(model, states, rng.uniform(0.0, 3.0, SAMPLES))


def test_formula_parameters_are_read_at_call_time():
    """The constants come from ``model.params`` when system() is called: a model of the
    same system with other numbers gives another right-hand side."""
    import dataclasses

    system = formula.build_system(["x"], H="p_x**2/2 + k*x**2/2", params={"k": 2.0})
    model = formula.compiled_model(system)
    other = dataclasses.replace(model, params=np.array([5.0]))
    pairs = hs.system(hy, other)
    cf = hy.cfunc([f for _, f in pairs], [v for v, _ in pairs])
    np.testing.assert_allclose(cf(np.array([0.3, 0.1])), [0.1, -5.0 * 0.3], rtol=1e-15)


def test_a_model_without_translation():
    from reportgen.core.model import OdeModel

    model = OdeModel(name="foreign", columns=("a",), rhs=lambda t, y, p, out: None,
                     params=np.zeros(0))
    assert hs.system(hy, model) is None
    assert "no heyoka translation" in hs.why_not(model)


# ---------------------------------------------------------------- Taylor vs DOP853
def _by_name(name):
    for p in MODELS:
        if p.values[0].source.name == name:
            return p.values
    raise AssertionError(name)


@pytest.mark.parametrize(("name", "t_end"), [
    ("pendulum_large", 6.0),
    ("three_body_figure_eight", 2.0),
    ("hamiltonian_double_pendulum", 3.0),
    ("two_center_near_collision", 1.0),  # Thiele–Burrau: t is the fictitious time s
    # springs at rest at the start (q_{i+1} − q_i = 0): a real power d**3 would give NaN
    # derivatives there in heyoka; the translation multiplies instead
    ("fput_stiff_soft", 2.0),
])
def test_taylor_integration_agrees_with_dop853(name, t_end):
    """heyoka's Taylor method at its default tolerance (ε) and our DOP853 at rtol 1e-13
    integrate the same equations: the states agree to ~1e-9 relative over a short run."""
    scene, model = _by_name(name)
    y0 = _initial_state(scene, model)
    t = np.linspace(0.0, t_end, 11)
    ours = integrate(model, y0, t, method="dop853", rtol=1e-13, atol=1e-15)
    assert ours.status == "ok", ours.message
    ta = hy.taylor_adaptive(hs.system(hy, model), y0, compact_mode=model.dim > 12)
    outcome, *_, states = ta.propagate_grid(t)
    assert outcome == hy.taylor_outcome.time_limit
    scale = float(np.max(np.abs(ours.y)))
    assert math.isfinite(scale)
    assert np.max(np.abs(states - ours.y)) <= 1e-9 * scale
