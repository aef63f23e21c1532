"""The action of the pendulum's linear boundary-value problem against closed forms.

References: solution θ(t) = [θ0 sin ω(T − t) + θ1 sin ωt]/sin ωT, lecture notes (1.21);
action S = m l² ω [(θ0² + θ1²) cos ωT − 2 θ0 θ1]/(2 sin ωT), notes (2.4); δS = p δq − H δt,
notes (7.1–7.15); the phase-space action ∫ (p q̇ − H) dt, notes §5; the free rotor
θ0 + (θ1 − θ0) t/T and its action m l² (θ1 − θ0)²/(2T), notes (1.22) and (2.5);
x cot x = 1 − Σ 2^(2n) |B_2n| x^(2n)/(2n)!, DLMF 4.19.6.  The independent references are
the notes' closed forms in 50-digit mpmath (mpmath differentiates them for ∂S/∂θ and ∂S/∂T).
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from conftest import pendulum_text
from reportgen.archive.store import read_archive, write_archive
from reportgen.core import pendulum_action as action
from reportgen.core import pendulum_theory as theory
from reportgen.core.models import pendulum as core
from reportgen.kinds import load_scene
from reportgen.scene.config import parse_config_text
from reportgen.scene.content import fmt

G, L, M = 9.81, 1.0, 1.0
W = math.sqrt(G / L)
I = M * L**2
ENDS = [(0.2, -0.1, 1.3), (0.3, 0.25, 0.4), (-0.5, 1.0, 2.5), (1.0, 1.0, 7.0)]


def mp_action(theta0, theta1, T, omega, inertia=I):
    """Notes (2.4) as written, at 50 digits or more (the float inputs taken exactly)."""
    with mp.workdps(max(mp.mp.dps, 50)):
        a, b, T, w = (mp.mpf(v) for v in (theta0, theta1, T, omega))
        return inertia * w / (2 * mp.sin(w * T)) * ((a * a + b * b) * mp.cos(w * T) - 2 * a * b)


def mp_free(theta0, theta1, T, inertia=I):
    with mp.workdps(50):
        return inertia * (mp.mpf(theta1) - mp.mpf(theta0)) ** 2 / (2 * mp.mpf(T))


# --------------------------------------------------------------- closed forms

@pytest.mark.parametrize("x", [1e-9, 1e-4, 0.1, 0.3, 0.4999, 0.5, 0.7, 2.0, 3.0])
def test_x_cot_x_minus_one_on_both_sides_of_the_series(x):
    with mp.workdps(50):
        reference = float(mp.mpf(x) * mp.cot(mp.mpf(x)) - 1)  # DLMF 4.19.6
    assert theory.x_cot_x_minus_one(x) == pytest.approx(reference, rel=2e-15)


@pytest.mark.parametrize("theta0, theta1, T", ENDS)
def test_action_matches_the_notes_and_the_existing_closed_form(theta0, theta1, T):
    S = theory.linear_action(theta0, theta1, T, W, I)
    assert S == pytest.approx(float(mp_action(theta0, theta1, T, W)), rel=1e-13, abs=1e-15)
    # the boundary_value_problem's closed form, notes (2.4), agrees away from ωT → 0
    assert S == pytest.approx(core.linear_boundary_action(theta0, theta1, T, W, I),
                              rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("fraction", [1e-2, 1e-5, 1e-9])
def test_action_excess_keeps_its_figures_as_omega_goes_to_zero(fraction):
    theta0, theta1, T = 0.2, -0.1, 1.3
    w = W * fraction
    with mp.workdps(50):
        excess = float(mp_action(theta0, theta1, T, w) - mp_free(theta0, theta1, T))
    assert theory.linear_action_excess(theta0, theta1, T, w, I) == pytest.approx(excess,
                                                                                 rel=1e-13)
    # the direct formula loses the excess there: the reason for the series
    naive = core.linear_boundary_action(theta0, theta1, T, w, I) - float(
        mp_free(theta0, theta1, T))
    if fraction <= 1e-9:
        assert abs(naive / excess - 1) > 0.1


@pytest.mark.parametrize("theta0, theta1, T", ENDS)
def test_end_momenta_and_energy_are_the_derivatives_of_the_notes_action(theta0, theta1, T):
    # notes (7.1–7.15): ∂S/∂θ0 = −p(0), ∂S/∂θ1 = p(T), ∂S/∂T = −E, by mpmath's derivative
    with mp.workdps(50):
        d0 = float(mp.diff(lambda a: mp_action(a, theta1, T, W), theta0))
        d1 = float(mp.diff(lambda b: mp_action(theta0, b, T, W), theta1))
        dT = float(mp.diff(lambda s: mp_action(theta0, theta1, s, W), T))
    p0, p1 = theory.linear_end_momenta(theta0, theta1, T, W, I)
    energy = theory.linear_energy(theta0, theta1, T, W, I)
    assert -p0 == pytest.approx(d0, rel=1e-12)
    assert p1 == pytest.approx(d1, rel=1e-12)
    assert -energy == pytest.approx(dT, rel=1e-12)
    # and E is the energy of the path, notes (1.21), at every t
    t = np.linspace(0.0, T, 101)
    q, q_dot = action.linear_path(t, theta0, theta1, T, W)
    assert np.allclose(0.5 * I * (q_dot**2 + W**2 * q**2), energy, rtol=1e-12, atol=0)
    assert q[0] == pytest.approx(theta0, abs=1e-15) and q[-1] == pytest.approx(theta1, abs=1e-14)


def test_richardson_derivative_is_fourth_order():
    # on S(T), singular at T = π/ω: the error falls 16-fold per halving of h
    def S(T):
        return theory.linear_action(0.2, -0.1, T, W, I)

    exact = -theory.linear_energy(0.2, -0.1, 1.3, W, I)
    steps = np.array([0.04, 0.02, 0.01, 0.005])
    errors = [abs(action.richardson_derivative(S, 1.3, h) - exact) for h in steps]
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert slope == pytest.approx(4.0, abs=0.15)


# ----------------------------------------------------- the scene's analyses

@pytest.fixture(scope="module")
def small():
    """pendulum_small's boundary-value problem: θ(0) = 0.2 rad, θ(1.3 s) = −0.1 rad."""
    text = pendulum_text(theta=0.2, t_end=2.0, samples=101, extra="""
        [boundary]
        theta0 = 0.2
        theta1 = -0.1
        T = 1.3
        """)
    return load_scene(parse_config_text(text)).simulate().analysis


def test_end_derivatives_of_the_computed_action(small):
    e = small["end_variation"]
    p0, p1 = theory.linear_end_momenta(0.2, -0.1, 1.3, W, I)
    energy = theory.linear_energy(0.2, -0.1, 1.3, W, I)
    # measured: 1.3e-12, 4.2e-14, 1.6e-12 (the brief asks for 1e-8)
    assert e["dS_dtheta0"] == pytest.approx(-p0, rel=1e-10)
    assert e["dS_dtheta1"] == pytest.approx(p1, rel=1e-10)
    assert e["dS_dT"] == pytest.approx(-energy, rel=1e-10)
    assert e["energy"] == energy and e["momentum_end"] == p1


def test_phase_space_action_is_stationary_on_the_solution(small):
    v = small["phase_space_action"]
    S = float(mp_action(0.2, -0.1, 1.3, W))
    assert v["action_hamiltonian"] == pytest.approx(S, rel=1e-13)
    assert v["action_lagrangian"] == pytest.approx(S, rel=1e-13)
    T = 1.3
    for i, k in enumerate(v["mode"]):
        wk2 = (k * math.pi / T) ** 2
        # S is quadratic in (q, p): its second variations, by hand from H = p²/2I + I ω² q²/2
        exact = {"q": -I * W**2 * T / 2, "p": -I * wk2 * T / 2, "qp": I * T * (wk2 - W**2) / 2}
        for name, second in exact.items():
            assert abs(v[f"first_variation_{name}"][i]) < 1e-13 * abs(second)
            assert v[f"second_variation_{name}"][i] == pytest.approx(second, rel=1e-10)
            assert v[f"second_variation_{name}_exact"][i] == pytest.approx(second, rel=1e-14)
        # about the free path (not a solution) the first variation is −∫ I ω² q δq dt ≠ 0
        free = -I * W**2 * T / (k * math.pi) * (0.2 - (-1) ** k * -0.1)
        assert v["first_variation_free_path"][i] == pytest.approx(free, rel=1e-10)
        assert abs(free) > 0.1
    # ω0 T = 4.07 > π: the k = 1 Lagrangian variation lowers the action
    assert v["second_variation_qp"][0] < 0 < v["second_variation_qp"][1]


def test_free_particle_limit(small):
    f = small["free_particle_limit"]
    theta0, theta1, T = 0.2, -0.1, 1.3
    assert f["omega"][0] == W and f["omega"][-1] == 0.0
    assert f["action_free"] == pytest.approx(float(mp_free(theta0, theta1, T)), rel=1e-15)
    assert f["action"][-1] == f["action_free"] and f["action_excess"][-1] == 0.0
    for w, S, excess, leading, deviation in zip(*(f[k][:-1] for k in (
            "omega", "action", "action_excess", "action_excess_leading", "path_excess")), strict=True):
        assert S == pytest.approx(float(mp_action(theta0, theta1, T, w)), rel=1e-13)
        x = w * T
        if x < 0.1:
            # S − S_free = −∫ V dt along the free path + O(ω⁴): the relative gap is O(x²)
            assert excess / leading - 1 == pytest.approx(0.0, abs=0.1 * x * x)
        # the path's departure, max over t, against 50-digit mpmath on the same grid
        with mp.workdps(50):
            ts = [mp.mpf(v) for v in np.linspace(0.0, T, 2001)]
            ref = max(abs((theta0 * mp.sin(w * (T - s)) + theta1 * mp.sin(w * s)) / mp.sin(w * T)
                          - (theta0 + (theta1 - theta0) * s / T)) for s in ts[::50])
        assert deviation == pytest.approx(float(ref), rel=1e-3)  # a coarser grid of maxima
    # S → S_free: each decade of ω brings S two decades closer
    gaps = np.abs(f["action"][1:-1] - f["action_free"])
    assert np.all(gaps[1:] < gaps[:-1])


def test_section_shows_the_three_analyses(tmp_path):
    text = pendulum_text(t_end=2.0, samples=101, extra="""
        [boundary]
        theta0 = 0.2
        theta1 = -0.1
        T = 1.3
        """)
    scene = load_scene(parse_config_text(text))
    write_archive(tmp_path / "a.h5", kind=scene.kind, title=scene.title, scene="test",
                  config_text=text, config_sha256="0", results=scene.simulate(),
                  resolved_config=scene.resolved_config())
    data = read_archive(tmp_path / "a.h5")
    kind = type(scene)
    content = kind.section_boundary_value(data)
    actions, ends, variations, limit = content.tables
    assert [r[0] for r in actions.rows][2:4] == [
        "linear, closed form, Simpson quadrature of L",
        "linear, closed form, Simpson quadrature of p θ̇ − H, notes §5"]
    assert [r[0] for r in ends.rows] == ["∂S/∂θ0 [J·s]", "∂S/∂θ1 [J·s]", "∂S/∂T [J]"]
    assert all(float(r[3]) < 1e-9 for r in ends.rows)
    assert len(variations.rows) == 9 and len(limit.rows) == 6
    assert "notes (7.1–7.15)" in ends.caption and "notes §5" in variations.caption
    assert "notes (2.5)" in limit.caption and "notes (1.22)" in limit.caption
    free = data.analysis["free_particle_limit"]["action_free"]
    assert limit.rows[-1][:3] == ["0", fmt(free), "0"]  # g = 0: the free rotor exactly
    assert kind.prose_case(data)["conjugate"]  # ω0 T = 4.07 > π
