"""A first-order Lagrangian L = a(q, t)·q̇ − V(q, t) in the ``hamiltonian`` kind (notes
(3.36–3.38)): reduced, not refused.

Every reference is worked out by hand in this file, from Lagrange's equations
d/dt ∂L/∂q̇ − ∂L/∂q = 0 (Goldstein §1.4) applied to each L directly, not from the kind's
ω q̇ = ∇V + ∂a/∂t:

* L = x ẏ − (x² + y²)/2: for x, −(ẏ − x) = 0; for y, d/dt x + y = 0.  So ẋ = −y, ẏ = x, and
  from (1, 0): x = cos t, y = sin t.  V = (x² + y²)/2 = 1/2.  x is the momentum of y
  (L = p q̇ − H with q = y, p = x): {y, x} = 1.
* L = u ẋ + v ẏ − H(x, y, u, v) (Hamilton's principle in phase space, Goldstein §8.5):
  ẋ = ∂H/∂u, ẏ = ∂H/∂v, u̇ = −∂H/∂x, v̇ = −∂H/∂y: Hamilton's equations, integrated by
  scipy for the Hénon–Heiles H (Hénon & Heiles, Astron. J. 69, 73 (1964)).
* L = x² ẏ/2 − y: for x, −(x ẏ) = 0, so ẏ = 0; for y, d/dt(x²/2) + 1 = 0, so x ẋ = −1 and
  x = √(1 − 2t) from x(0) = 1 (ω = x vanishes at x = 0, reached at t = 1/2).
* L = (x + t) ẏ − (x² + y²)/2: for x, ẏ = x; for y, ẋ + 1 + y = 0.  With Y = y + 1:
  ẋ = −Y, Ẏ = x, from (1, 1): x = cos t − sin t, y = sin t + cos t − 1.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp

from reportgen.core import formula, mechanics
from reportgen.kinds import load_scene
from reportgen.scene.config import parse_config_text


def scene_of(text: str):
    return load_scene(parse_config_text(textwrap.dedent(text)))


def config(L: str, coordinates=("x", "y"), initial=None, t_end=10.0, extra="") -> str:
    initial = initial or {"x": 1.0, "y": 0.0}
    lines = "\n".join(f"{k} = {v!r}" for k, v in initial.items())
    return f"""
kind = "hamiltonian"
[system]
coordinates = {list(coordinates)!r}
L = "{L}"
[initial]
{lines}
[run]
t_end = {t_end}
samples = 501
rtol = 1e-13
study = false
{extra}
"""


OSCILLATOR = config("x*y_dot - (x**2 + y**2)/2")


@pytest.fixture(scope="module")
def oscillator():
    scene = scene_of(OSCILLATOR)
    return scene, scene.simulate()


def test_oscillator_follows_its_closed_form(oscillator):
    scene, results = oscillator
    run = results.runs["main"]
    assert list(run.columns) == ["x", "y"]  # the state is q alone
    # hand: x = cos t, y = sin t (module docstring)
    assert np.max(np.abs(run["x"] - np.cos(run.t))) <= 1e-9
    assert np.max(np.abs(run["y"] - np.sin(run.t))) <= 1e-9


def test_oscillator_conserves_its_energy_V(oscillator):
    _, results = oscillator
    run, a = results.runs["main"], results.analysis
    assert a["H0"] == 0.5  # V = (x² + y²)/2 at (1, 0)
    v = (run["x"] ** 2 + run["y"] ** 2) / 2  # written out, not the kind's V
    assert np.max(np.abs(v - 0.5)) <= 1e-10
    assert np.max(np.abs(run.invariants["H"] - v)) <= 1e-14
    assert run.attrs["drift_H"] <= 1e-10


def test_oscillator_reduction_has_the_hand_signs():
    system = formula.build_system(["x", "y"], L="x*y_dot - (x**2 + y**2)/2")
    x, y = system.space.q
    fo = system.first_order
    assert fo.omega == sympy.Matrix([[0, 1], [-1, 0]])  # ω_xy = ∂a_y/∂x − ∂a_x/∂y = 1
    assert tuple(fo.qdot) == (-y, x)  # ẋ = −y, ẏ = x (hand, module docstring)
    assert fo.bracket(system.space, y, x) == 1  # x is the momentum of y
    # ḟ = {f, V}: {x, V} = ẋ, {y, V} = ẏ
    assert sympy.simplify(fo.bracket(system.space, x, system.H) + y) == 0
    assert sympy.simplify(fo.bracket(system.space, y, system.H) - x) == 0


def test_oscillator_checks_in_the_archive(oscillator):
    _, a = oscillator[0], oscillator[1].analysis
    assert a["first_order"] and a["first_order_linear"]
    assert a["first_order_bracket_generates"] and a["first_order_energy_rate_zero"]
    assert a["first_order_det0"] == 1.0 and a["first_order_det_sign_kept"]
    # exp(tA) q0 against the hand closed form: A = [[0, −1], [1, 0]]
    assert np.array_equal(a["first_order_A"], [[0.0, -1.0], [1.0, 0.0]])
    t = oscillator[1].runs["main"].t
    closed = np.asarray(a["first_order_closed_form"])
    assert np.max(np.abs(closed - np.column_stack([np.cos(t), np.sin(t)]))) <= 1e-12
    assert a["first_order_closed_form_error"] <= 1e-9
    assert a["first_order_el_residual"] <= 1e-12 * a["first_order_el_scale"]


def test_phase_space_lagrangian_gives_hamiltons_equations():
    H = "(u**2 + v**2)/2 + (x**2 + y**2)/2 + x**2*y - y**3/3"
    q0 = {"x": 0.0, "y": 0.1, "u": 0.35, "v": 0.0}
    scene = scene_of(config(f"u*x_dot + v*y_dot - ({H})", ("x", "y", "u", "v"), q0, 20.0))
    results = scene.simulate()
    run = results.runs["main"]

    def hand(t, s):  # Hamilton's equations of the Hénon–Heiles H, by hand
        x, y, u, v = s
        return [u, v, -x - 2 * x * y, -y - x**2 + y**2]

    ref = solve_ivp(hand, (0, 20.0), list(q0.values()), method="DOP853", t_eval=run.t,
                    rtol=1e-13, atol=1e-13)
    assert np.max(np.abs(run.y - ref.y.T)) <= 1e-9
    assert not results.analysis["first_order_linear"]
    assert run.attrs["drift_H"] <= 1e-10


def test_varying_omega_follows_its_closed_form():
    # ω = x (not constant): x = √(1 − 2t), y = 0 (module docstring)
    scene = scene_of(config("x**2*y_dot/2 - y", t_end=0.4))
    results = scene.simulate()
    run = results.runs["main"]
    assert np.max(np.abs(run["x"] - np.sqrt(1 - 2 * run.t))) <= 1e-9
    assert np.max(np.abs(run["y"])) <= 1e-12
    a = results.analysis
    assert a["first_order_det_sign_kept"]
    assert math.isclose(a["first_order_det_min"], math.sqrt(1 - 0.8) ** 2, rel_tol=1e-8)


def test_time_dependent_a_adds_its_rate():
    # ∂a/∂t = (0, 1): x = cos t − sin t, y = sin t + cos t − 1 (module docstring)
    scene = scene_of(config("(x + t)*y_dot - (x**2 + y**2)/2"))
    results = scene.simulate()
    run = results.runs["main"]
    t = run.t
    assert np.max(np.abs(run["x"] - (np.cos(t) - np.sin(t)))) <= 1e-9
    assert np.max(np.abs(run["y"] - (np.sin(t) + np.cos(t) - 1))) <= 1e-9
    assert results.analysis["time_dependent"] and "H" not in run.invariants
    assert not results.analysis["first_order_bracket_generates"]


# ------------------------------------------------------------------ refused, with the reason
REFUSED = {
    # id: (L, coordinates, initial, key, words the message holds)
    "odd": ("x*y_dot + y*z_dot - x**2 - z**2", ("x", "y", "z"),
            {"x": 1.0, "y": 0.0, "z": 0.0}, "system.L", "odd number"),
    "closed_a": ("x*x_dot + y*y_dot - x**2 - y**2", ("x", "y"), None, "system.L",
                 "det ω = 0 for every q"),
    "no_velocity": ("x*y", ("x", "y"), None, "system.L", "det ω = 0 for every q"),
    "singular_not_linear": ("x_dot**2/2 + x*y_dot - y**2", ("x", "y"),
                            {"x": 1.0, "y": 0.0, "x_dot": 0.0, "y_dot": 1.0}, "system.L",
                            "not linear in the velocities either"),
    "velocities_given": ("x*y_dot - (x**2 + y**2)/2", ("x", "y"),
                         {"x": 1.0, "y": 0.0, "x_dot": 0.0, "y_dot": 1.0}, "initial.x_dot",
                         "the velocities and the energy follow from the coordinates"),
    "energy_given": ("x*y_dot - (x**2 + y**2)/2", ("x", "y"),
                     {"x": 1.0, "y": 0.0, "energy": 0.5}, "initial.energy",
                     "velocities and energy follow from them"),
    "singular_start": ("x**2*y_dot/2 - y", ("x", "y"), {"x": 0.0, "y": 0.0}, "initial",
                       "det ω = 0 at the initial point"),
    "regular_without_velocities": ("(x_dot**2 + y_dot**2)/2 - x**2", ("x", "y"), None,
                                   "initial.x_dot", "required key is missing"),
}


@pytest.mark.parametrize("case", sorted(REFUSED))
def test_refused_with_its_reason(case, write_config, cli):
    L, coordinates, initial, key, words = REFUSED[case]
    path = write_config(f"fo_{case}", config(L, coordinates, initial))
    code, _, err = cli("validate", path)
    assert code == 2, err
    line = next(ln for ln in err.splitlines() if str(path) in ln)
    assert f"key '{key}'" in line and words in line, err
    assert "Traceback" not in err


def test_the_example_validates(write_config, cli):
    code, out, err = cli("validate", write_config("fo_ok", OSCILLATOR))
    assert code == 0, err


def test_a_section_is_refused(write_config, cli):
    path = write_config("fo_section", config("u*x_dot + v*y_dot - (u**2 + v**2 + x**2 + y**2)/2",
                                             ("x", "y", "u", "v"),
                                             {"x": 1.0, "y": 0.0, "u": 0.0, "v": 0.5},
                                             extra='[section]\ncoordinate = "x"'))
    code, _, err = cli("validate", path)
    assert code == 2 and "key 'section'" in err and "first-order" in err, err


def test_first_order_detection_is_symbolic():
    space = mechanics.PhaseSpace.of(["x", "y"])
    x, y = space.q
    xd, yd = space.qdot
    assert mechanics.linear_in_velocities(space, x * yd - sympy.sin(y) * xd + x**2)
    assert not mechanics.linear_in_velocities(space, x * yd + xd**2)
