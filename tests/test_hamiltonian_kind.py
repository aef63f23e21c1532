"""The ``hamiltonian`` kind: systems written as H or L, derived by SymPy, compiled by numba.

Every reference here is independent of reportgen's derivation: equations of motion worked
out by hand in this file and integrated with scipy's DOP853, energies T + V written out,
Poisson brackets computed by hand.

References (Goldstein, Poole & Safko, Classical Mechanics, 3rd ed.):
* §1.4: Lagrange's equations d/dt ∂L/∂q̇ − ∂L/∂q = 0 (the hand derivations below);
* §8.1: p = ∂L/∂q̇, H = p·q̇ − L and Hamilton's equations q̇ = ∂H/∂p, ṗ = −∂H/∂q;
* §8.2: a cyclic coordinate (∂H/∂q = 0) has a conserved momentum;
* §9.5–§9.6: Poisson brackets; df/dt = {f, H} + ∂f/∂t;
* §3.7: the Kepler problem, force −k r/r³.
Hénon & Heiles, Astron. J. 69, 73 (1964): H = (p_x² + p_y²)/2 + (x² + y²)/2 + x²y − y³/3.
Fradkin, Am. J. Phys. 33, 207 (1965): the isotropic oscillator's conserved tensor A_ij.
"""

from __future__ import annotations

import html
import json
import math
import os
import re
import subprocess
import sys
import textwrap
import tokenize
import tomllib
from io import StringIO
from pathlib import Path

import h5py
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from reportgen.core import formula
from reportgen.core.expressions import parse_expression
from reportgen.kinds import load_scene
from reportgen.scene.config import parse_config_text, to_toml

REPO = Path(__file__).resolve().parent.parent
HAND_RTOL = HAND_ATOL = 1e-13  # the hand integrations' tolerances (scipy DOP853)


def scene_of(text: str):
    return load_scene(parse_config_text(textwrap.dedent(text)))


def hand_integration(rhs, y0, t, **kwargs):
    """scipy DOP853 at rtol = atol = 1e-13 on ``t``: the independent reference."""
    sol = solve_ivp(rhs, (t[0], t[-1]), np.asarray(y0, dtype=float), method="DOP853",
                    t_eval=t, rtol=HAND_RTOL, atol=HAND_ATOL, **kwargs)
    assert sol.success, sol.message
    return sol


# ------------------------------------------------------------------ the systems
# Planar Kepler problem, k ≠ 1 so that a lost constant shows.
K = 1.3
KEPLER = f"""
kind = "hamiltonian"
[params]
k = {K}
[system]
coordinates = ["x", "y"]
H = "(p_x**2 + p_y**2)/2 - k/sqrt(x**2 + y**2)"
[observables]
Lz = "x*p_y - y*p_x"
Px = "p_x"
[initial]
x = 1.0
y = 0.0
p_x = 0.2
p_y = 1.0
[run]
t_end = 10.0
samples = 401
rtol = 1e-13
study = false
"""

# Hénon–Heiles at E = 1/12 with p_x solved for (the shipped regular config, shortened).
HH_ENERGY = 1.0 / 12.0
HENON_HEILES = f"""
kind = "hamiltonian"
[system]
coordinates = ["x", "y"]
H = "(p_x**2 + p_y**2)/2 + (x**2 + y**2)/2 + x**2*y - y**3/3"
[initial]
x = 0.0
y = 0.1
p_y = 0.0
energy = {HH_ENERGY!r}
[section]
coordinate = "x"
axes = ["y", "p_y"]
[run]
t_end = 40.0
samples = 4001
rtol = 1e-13
study = false
"""

# Double pendulum, unequal masses and rods, started with both rods moving.
M1, M2, L1, L2, G = 1.0, 0.7, 1.0, 0.8, 9.81
DP0 = {"a": 1.0, "b": 0.4, "a_dot": 0.3, "b_dot": -0.5}
DOUBLE = f"""
kind = "hamiltonian"
[params]
m1 = {M1}
m2 = {M2}
l1 = {L1}
l2 = {L2}
g = {G}
[system]
coordinates = ["a", "b"]
L = \"\"\"(m1 + m2)/2*l1**2*a_dot**2 + m2/2*l2**2*b_dot**2 + m2*l1*l2*a_dot*b_dot*cos(a - b)
       + (m1 + m2)*g*l1*cos(a) + m2*g*l2*cos(b)\"\"\"
[initial]
a = {DP0["a"]}
b = {DP0["b"]}
a_dot = {DP0["a_dot"]}
b_dot = {DP0["b_dot"]}
[run]
t_end = 8.0
samples = 801
rtol = 1e-13
study = false
"""

# Spherical pendulum, m l² ≠ 1.
MS, LS = 0.8, 1.3
SP0 = {"theta": 1.0, "phi": 0.2, "theta_dot": 0.3, "phi_dot": 2.5}
SPHERICAL = f"""
kind = "hamiltonian"
[params]
m = {MS}
l = {LS}
g = {G}
[system]
coordinates = ["theta", "phi"]
L = "m*l**2/2*(theta_dot**2 + sin(theta)**2*phi_dot**2) + m*g*l*cos(theta)"
[initial]
theta = {SP0["theta"]}
phi = {SP0["phi"]}
theta_dot = {SP0["theta_dot"]}
phi_dot = {SP0["phi_dot"]}
[run]
t_end = 10.0
samples = 1001
rtol = 1e-13
study = false
"""


@pytest.fixture(scope="module")
def kepler():
    scene = scene_of(KEPLER)
    return scene, scene.simulate()


@pytest.fixture(scope="module")
def henon_heiles():
    scene = scene_of(HENON_HEILES)
    return scene, scene.simulate()


@pytest.fixture(scope="module")
def double_pendulum():
    scene = scene_of(DOUBLE)
    return scene, scene.simulate()


@pytest.fixture(scope="module")
def spherical():
    scene = scene_of(SPHERICAL)
    return scene, scene.simulate()


# ------------------------------------------------------ equations derived by hand
def kepler_rhs(t, s):
    # Goldstein §3.7: r̈ = −k r/r³; state (x, y, p_x, p_y) with p = ṙ (unit mass)
    x, y, px, py = s
    r3 = (x * x + y * y) ** 1.5
    return [px, py, -K * x / r3, -K * y / r3]


def henon_heiles_rhs(t, s):
    # Hénon & Heiles (1964): ṗ_x = −∂V/∂x = −x − 2xy, ṗ_y = −∂V/∂y = −y − x² + y²
    x, y, px, py = s
    return [px, py, -x - 2 * x * y, -y - x * x + y * y]


def henon_heiles_energy(x, y, px, py):
    return (px**2 + py**2) / 2 + (x**2 + y**2) / 2 + x**2 * y - y**3 / 3


def double_pendulum_accelerations(t, s):
    """(ȧ, ḃ, ä, b̈) from Lagrange's equations (Goldstein §1.4), worked by hand:

    ∂L/∂ȧ = (m1+m2) l1² ȧ + m2 l1 l2 ḃ cos(a−b),  ∂L/∂a = −m2 l1 l2 ȧḃ sin(a−b) − (m1+m2) g l1 sin a
    ⇒ (m1+m2) l1 ä + m2 l2 cos(a−b) b̈ = −m2 l2 ḃ² sin(a−b) − (m1+m2) g sin a
    ∂L/∂ḃ = m2 l2² ḃ + m2 l1 l2 ȧ cos(a−b),       ∂L/∂b = m2 l1 l2 ȧḃ sin(a−b) − m2 g l2 sin b
    ⇒ l1 cos(a−b) ä + l2 b̈ = l1 ȧ² sin(a−b) − g sin b
    solved for (ä, b̈) by Cramer's rule.
    """
    a, b, ad, bd = s
    c, sn = math.cos(a - b), math.sin(a - b)
    m11, m12 = (M1 + M2) * L1, M2 * L2 * c
    m21, m22 = L1 * c, L2
    r1 = -M2 * L2 * bd**2 * sn - (M1 + M2) * G * math.sin(a)
    r2 = L1 * ad**2 * sn - G * math.sin(b)
    det = m11 * m22 - m12 * m21
    return [ad, bd, (r1 * m22 - m12 * r2) / det, (m11 * r2 - m21 * r1) / det]


def double_pendulum_momenta(a, b, ad, bd):
    # p = ∂L/∂q̇ (Goldstein §8.1), from the L above
    c = np.cos(a - b)
    return ((M1 + M2) * L1**2 * ad + M2 * L1 * L2 * bd * c,
            M2 * L2**2 * bd + M2 * L1 * L2 * ad * c)


def double_pendulum_energy(a, b, ad, bd):
    # T + V: T the quadratic part of L, V = −(m1+m2) g l1 cos a − m2 g l2 cos b
    T = ((M1 + M2) / 2 * L1**2 * ad**2 + M2 / 2 * L2**2 * bd**2
         + M2 * L1 * L2 * ad * bd * math.cos(a - b))
    V = -(M1 + M2) * G * L1 * math.cos(a) - M2 * G * L2 * math.cos(b)
    return T + V


def spherical_accelerations(t, s):
    """Lagrange's equations of L = m l²(θ̇² + sin²θ φ̇²)/2 + m g l cos θ, by hand:
    θ̈ = sin θ cos θ φ̇² − (g/l) sin θ;  d/dt(m l² sin²θ φ̇) = 0 ⇒ φ̈ = −2 cot θ θ̇ φ̇."""
    th, ph, thd, phd = s
    return [thd, phd, math.sin(th) * math.cos(th) * phd**2 - G / LS * math.sin(th),
            -2.0 * math.cos(th) / math.sin(th) * thd * phd]


def spherical_momenta(th, thd, phd):
    return MS * LS**2 * thd, MS * LS**2 * np.sin(th) ** 2 * phd


def spherical_energy(th, thd, phd):
    return MS * LS**2 / 2 * (thd**2 + math.sin(th) ** 2 * phd**2) - MS * G * LS * math.cos(th)


# ------------------------------------------------ 1. trajectories against hand-derived
def test_kepler_trajectory_matches_hand_integration(kepler):
    scene, results = kepler
    run = results.runs["main"]
    assert run.columns == ["x", "y", "p_x", "p_y"]
    ref = hand_integration(kepler_rhs, [1.0, 0.0, 0.2, 1.0], run.t)
    assert np.max(np.abs(run.y - ref.y.T)) <= 1e-8


def test_henon_heiles_trajectory_matches_hand_integration(henon_heiles):
    scene, results = henon_heiles
    run = results.runs["main"]
    ref = hand_integration(henon_heiles_rhs, run.y[0], run.t)
    assert np.max(np.abs(run.y - ref.y.T)) <= 1e-8


def test_double_pendulum_from_L_matches_hand_derived_equations(double_pendulum):
    scene, results = double_pendulum
    run = results.runs["main"]
    assert run.columns == ["a", "b", "p_a", "p_b"]
    ref = hand_integration(double_pendulum_accelerations,
                           [DP0["a"], DP0["b"], DP0["a_dot"], DP0["b_dot"]], run.t)
    a, b, ad, bd = ref.y
    p_a, p_b = double_pendulum_momenta(a, b, ad, bd)
    want = np.column_stack([a, b, p_a, p_b])
    assert np.max(np.abs(run.y - want)) <= 1e-8


def test_spherical_pendulum_from_L_matches_hand_derived_equations(spherical):
    scene, results = spherical
    run = results.runs["main"]
    assert run.columns == ["theta", "phi", "p_theta", "p_phi"]
    ref = hand_integration(spherical_accelerations,
                           [SP0["theta"], SP0["phi"], SP0["theta_dot"], SP0["phi_dot"]], run.t)
    th, ph, thd, phd = ref.y
    want = np.column_stack([th, ph, *spherical_momenta(th, thd, phd)])
    assert np.max(np.abs(run.y - want)) <= 1e-8


# ---------------------------------------------------------- 2. H(0) from L is T + V
def test_energy_of_double_pendulum_from_L_is_T_plus_V(double_pendulum):
    scene, results = double_pendulum
    e = double_pendulum_energy(DP0["a"], DP0["b"], DP0["a_dot"], DP0["b_dot"])
    assert abs(results.analysis["H0"] - e) <= 1e-12 * max(1.0, abs(e))
    assert abs(results.runs["main"].invariants["H"][0] - e) <= 1e-12 * max(1.0, abs(e))
    # the initial momenta are ∂L/∂q̇ at the written velocities
    p0 = double_pendulum_momenta(DP0["a"], DP0["b"], DP0["a_dot"], DP0["b_dot"])
    assert np.max(np.abs(scene.initial_state()[2:] - p0)) <= 1e-14
    assert results.analysis["given"] == "L" and not results.analysis["kinetic_potential_split"]


def test_energy_of_spherical_pendulum_from_L_is_T_plus_V(spherical):
    scene, results = spherical
    e = spherical_energy(SP0["theta"], SP0["theta_dot"], SP0["phi_dot"])
    assert abs(results.analysis["H0"] - e) <= 1e-12 * max(1.0, abs(e))
    assert abs(results.runs["main"].invariants["H"][0] - e) <= 1e-12 * max(1.0, abs(e))
    p0 = spherical_momenta(SP0["theta"], SP0["theta_dot"], SP0["phi_dot"])
    assert np.max(np.abs(scene.initial_state()[2:] - p0)) <= 1e-14


# ------------------------------------------------------------ 3. Poisson brackets
def bracket_function(text: str, names: list[str]):
    """The archived bracket string as a function of ``names`` (parsed by the allow-list
    parser, not eval), so that it can be compared with a hand result numerically."""
    import sympy

    symbols = {n: sympy.Symbol(n, real=True) for n in names}
    expr = parse_expression(text, symbols)
    return sympy.lambdify([symbols[n] for n in names], expr, "numpy")


def test_angular_momentum_commutes_with_a_central_H(kepler):
    scene, results = kepler
    a, run = results.analysis, results.runs["main"]
    # {Lz, H} = 0 for any V(r) (Goldstein §9.6: Lz generates rotations, H is invariant)
    assert a["poisson_Lz"] == "0" and a["conserved_Lz"] is True
    assert "Lz" in run.invariants and run.attrs["drift_Lz"] <= 1e-9
    lz0 = 1.0 * 1.0 - 0.0 * 0.2
    assert np.max(np.abs(run.invariants["Lz"] - lz0)) <= 1e-9
    assert run.attrs["drift_H"] <= 1e-9
    assert a["cyclic"] == []  # Cartesian coordinates: none is cyclic


def test_a_moving_observable_has_the_hand_bracket_and_is_not_an_invariant(kepler):
    scene, results = kepler
    a, run = results.analysis, results.runs["main"]
    # {p_x, H} = −∂H/∂x = −k x/(x² + y²)^(3/2) (Goldstein §9.5 with f = p_x)
    assert a["conserved_Px"] is False and a["poisson_Px"] != "0"
    bracket = bracket_function(a["poisson_Px"], ["x", "y", "k"])
    x, y = run["x"], run["y"]
    hand = -K * x / (x**2 + y**2) ** 1.5
    assert np.max(np.abs(bracket(x, y, K) - hand)) <= 1e-12 * np.max(np.abs(hand))
    rng = np.random.default_rng(7)
    xs, ys, ks = rng.uniform(-2, 2, 50), rng.uniform(-2, 2, 50), rng.uniform(0.5, 3, 50)
    assert np.allclose(bracket(xs, ys, ks), -ks * xs / (xs**2 + ys**2) ** 1.5,
                       rtol=1e-13, atol=0)
    assert abs(a["poisson_Px_max"] - np.max(np.abs(hand))) <= 1e-12 * np.max(np.abs(hand))
    assert "Px" not in run.invariants and "drift_Px" not in run.attrs
    assert np.array_equal(a["observables"]["Px"], run["p_x"])  # its time series instead
    assert run.attrs["status"] == "ok"
    # {Lz, Px} = {x p_y − y p_x, p_x} = p_y (hand), the pairwise table
    pairs = a["pair_brackets"]
    assert (pairs["f"], pairs["g"], pairs["bracket"]) == (["Lz"], ["Px"], ["p_y"])


# ------------------------------------------- 4. isotropic oscillator, cyclic, Jacobi
ISO_M, ISO_OMEGA = 1.0, 1.3  # as in configs/hamiltonian_isotropic_oscillator.toml


@pytest.fixture(scope="module")
def isotropic():
    """The shipped config without the study, plus x(0) written as a function of (x, p_x, t):
    X0 = x cos ωt − p_x/(mω) sin ωt, conserved only with its ∂X0/∂t."""
    data = tomllib.loads((REPO / "configs" / "hamiltonian_isotropic_oscillator.toml")
                         .read_text(encoding="utf-8"))
    assert data["params"] == {"m": ISO_M, "omega": ISO_OMEGA}
    data["run"]["study"] = False
    data["observables"]["X0"] = "x*cos(omega*t) - p_x/(m*omega)*sin(omega*t)"
    scene = load_scene(parse_config_text(to_toml(data)))
    return scene, scene.simulate()


def test_isotropic_oscillator_conserves_Lz_and_the_Fradkin_tensor(isotropic):
    scene, results = isotropic
    a, run = results.analysis, results.runs["main"]
    for name in ("Lz", "A_xx", "A_yy", "A_xy"):
        assert a[f"poisson_{name}"] == "0", name
        assert a[f"conserved_{name}"] is True
        assert name in run.invariants and run.attrs[f"drift_{name}"] <= 1e-9, name
    # {p_x², H} = −2 p_x ∂H/∂x = −2 m ω² x p_x (hand): not conserved
    assert a["conserved_p_x2"] is False and "p_x2" not in run.invariants
    bracket = bracket_function(a["poisson_p_x2"], ["x", "p_x", "m", "omega"])
    hand = -2 * ISO_M * ISO_OMEGA**2 * run["x"] * run["p_x"]
    assert np.max(np.abs(bracket(run["x"], run["p_x"], ISO_M, ISO_OMEGA) - hand)) <= 1e-13
    # X0: {X0, H} = p_x cos ωt/m + ω x sin ωt ≠ 0, but dX0/dt = {X0, H} + ∂X0/∂t = 0
    assert a["poisson_X0"] != "0" and a["conserved_X0"] is True
    x0_bracket = bracket_function(a["poisson_X0"], ["x", "p_x", "t", "m", "omega"])
    t = run.t
    hand = (run["p_x"] * np.cos(ISO_OMEGA * t) / ISO_M
            + ISO_OMEGA * run["x"] * np.sin(ISO_OMEGA * t))
    assert np.max(np.abs(x0_bracket(run["x"], run["p_x"], t, ISO_M, ISO_OMEGA) - hand)) <= 1e-13
    assert "X0" in run.invariants and run.attrs["drift_X0"] <= 1e-9
    assert np.max(np.abs(run.invariants["X0"] - 1.0)) <= 1e-9  # x(0) = 1
    # {Lz, A_xx} = p_x p_y/m + m ω² x y = 2 A_xy (hand, Fradkin's su(2) algebra)
    pairs = dict(zip(zip(a["pair_brackets"]["f"], a["pair_brackets"]["g"], strict=True),
                     a["pair_brackets"]["bracket"], strict=True))
    lz_axx = bracket_function(pairs["Lz", "A_xx"], ["x", "y", "p_x", "p_y", "m", "omega"])
    x, y, px, py = run.y.T
    two_axy = px * py / ISO_M + ISO_M * ISO_OMEGA**2 * x * y
    assert np.max(np.abs(lz_axx(x, y, px, py, ISO_M, ISO_OMEGA) - two_axy)) <= 1e-13
    assert pairs["A_xx", "A_yy"] == "0"
    # the Jacobi identity on (Lz, A_xx, H); every term vanishes here (both conserved), so
    # the non-trivial check is on Kepler and the double pendulum below
    assert a["jacobi_max"] <= 1e-13


def test_brackets_and_invariants_are_typeset_not_printed_as_identifiers(cli, tmp_path):
    """The isotropic oscillator's report names A_xy, L_z, p_x as typeset symbols (their
    TeX, from the archive, as the equation's accessible name), never as the config's
    identifiers in the page text; the brackets between observables are the archived TeX."""
    from conftest import without_study

    config = without_study(REPO / "configs" / "hamiltonian_isotropic_oscillator.toml",
                           tmp_path / "iso.toml")
    code, _, err = cli("run", config, "--out", tmp_path / "o", "--jobs", 1)
    assert code == 0, err
    folder = tmp_path / "o" / "iso"
    with h5py.File(folder / "run.h5") as f:
        a = f["analysis"]
        pairs = dict(zip(zip(a["pair_brackets"].attrs["f"], a["pair_brackets"].attrs["g"],
                             strict=True), a["pair_brackets"].attrs["latex"], strict=True))
        jacobi = list(a.attrs["jacobi_triple_latex"])
    # {A_xx, A_yy} = 0 and {Lz, A_xx} = 2 A_xy (Fradkin), as SymPy prints them
    assert pairs["A_xx", "A_yy"] == "0" and "p_{x} p_{y}" in pairs["Lz", "A_xx"]
    assert jacobi[2] == "H" and "p_{x}" in jacobi[0]  # f = Lz = x p_y − y p_x
    page = (folder / "report.html").read_text(encoding="utf-8")
    brackets = page[page.index('<section id="brackets">'):page.index('<section id="config">')]
    for tex in (r"\{L_{z}, A_{xx}\}", "A_{xy}", "p_{x_{2}}", pairs["Lz", "A_xx"]):
        assert f'aria-label="{html.escape(tex)}"' in brackets, tex
    invariants = page[page.index('<section id="invariants">'):
                      page.index('<section id="brackets">')]
    assert 'aria-label="A_{xy}"' in invariants and 'aria-label="L_{z}"' in invariants
    text = re.sub(r"<svg.*?</svg>|<pre class=\"config\">.*?</pre>|<head>.*?</head>", " ",
                  page, flags=re.S)
    text = html.unescape(re.sub(r"<[^>]+>", " ", text))
    for identifier in ("A_xx", "A_xy", "A_yy", "p_x", "p_y", "Lz", "$"):
        assert identifier not in text, identifier


def test_spherical_pendulum_phi_is_cyclic_and_p_phi_conserved(spherical):
    scene, results = spherical
    a, run = results.analysis, results.runs["main"]
    assert list(a["cyclic"]) == ["phi"]  # H does not contain φ (Goldstein §8.2)
    assert "p_phi" in run.invariants and "p_theta" not in run.invariants
    assert run.attrs["drift_p_phi"] <= 1e-9 and run.attrs["drift_H"] <= 1e-9
    p_phi0 = MS * LS**2 * math.sin(SP0["theta"]) ** 2 * SP0["phi_dot"]
    assert np.max(np.abs(run["p_phi"] - p_phi0)) <= 1e-12
    # the Legendre transform holds along the run
    assert a["legendre_momentum_error"] <= 1e-12 and a["legendre_energy_error"] <= 1e-12


# -------------------------------------------- 5. hostile formulas through the CLI
KEPLER_L = f"""
kind = "hamiltonian"
[params]
k = {K}
[system]
coordinates = ["x", "y"]
L = "(x_dot**2 + y_dot**2)/2 + k/sqrt(x**2 + y**2)"
[initial]
x = 1.0
y = 0.0
x_dot = 0.2
y_dot = 1.0
[run]
t_end = 1.0
samples = 11
study = false
"""

# (case id, key, formula, what the message must say); CANARY is replaced by a path
HOSTILE = [
    ("import_system", "system.H", "__import__('os').system('touch CANARY')",
     "a call of something other than a function name"),
    ("import_call", "system.L", "__import__('os').system('touch CANARY') + x_dot**2",
     "a call of something other than a function name"),
    ("import_bare", "observables.evil", "__import__('os')", "unknown function '__import__'"),
    ("class_bases", "system.H", "().__class__.__bases__", "an attribute"),
    ("attribute", "system.H", "x.real + p_x**2/2", "an attribute 'x.real'"),
    ("subscript", "observables.evil", "p_x[0]", "a subscript 'p_x[0]'"),
    ("lambda", "system.L", "(lambda: x_dot)()**2", "a call of something other than"),
    ("bare_lambda", "observables.evil", "lambda: x", "a lambda"),
    ("string", "system.L", "'x_dot**2' + x_dot**2", "a string"),
    ("fstring", "observables.evil", "f'{x}'", "a string"),
    ("comprehension", "system.H", "[p_x for p_x in (1,)][0]", "a subscript"),
    ("generator", "observables.evil", "sum(p_x for x in (1,))", "unknown function 'sum'"),
    ("keyword", "observables.evil", "atan2(x, y=p_x)", "a keyword argument"),
    ("syntax", "system.H", "p_x**2/2 +* x", "not a formula"),
    ("undefined", "system.H", "p_x**2/2 + z", "undefined name 'z'"),
    ("dunder_name", "system.H", "__builtins__", "a name starting with _"),
    ("open", "observables.evil", "open('CANARY', 'w')", "unknown function 'open'"),
    ("eval", "system.L", "eval('x_dot**2')", "unknown function 'eval'"),
    ("walrus", "system.L", "x_dot**2 + (x := 1)", "an assignment"),
]


def hostile_config(folder: Path, case) -> Path:
    name, key, text, _ = case
    canary = folder / f"CANARY_{name}"
    text = text.replace("CANARY", str(canary))
    base = KEPLER if key != "system.L" else KEPLER_L
    base = base.replace('Px = "p_x"\n', "")
    if key == "system.H":
        body = base.replace('H = "(p_x**2 + p_y**2)/2 - k/sqrt(x**2 + y**2)"',
                            f"H = {json.dumps(text)}")
    elif key == "system.L":
        body = base.replace('L = "(x_dot**2 + y_dot**2)/2 + k/sqrt(x**2 + y**2)"',
                            f"L = {json.dumps(text)}")
    else:
        body = base.replace("[observables]\n", f"[observables]\nevil = {json.dumps(text)}\n")
    assert body != base
    path = folder / f"hostile_{name}.toml"
    path.write_text(textwrap.dedent(body).lstrip(), encoding="utf-8")
    return path


def _env() -> dict[str, str]:
    """The test's environment (its temporary XDG cache) with this checkout importable."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(REPO), env.get("PYTHONPATH")]))
    return env


@pytest.fixture(scope="module")
def hostile_runs(tmp_path_factory):
    """Every hostile config through `python -m reportgen validate` and `run`, one process
    each (each file's problem is reported with every other's)."""
    folder = tmp_path_factory.mktemp("hostile")
    paths = [hostile_config(folder, case) for case in HOSTILE]

    def reportgen(*args):
        return subprocess.run([sys.executable, "-m", "reportgen", *map(str, args)],
                              cwd=folder, capture_output=True, text=True, timeout=120,
                              env=_env())

    validate = reportgen("validate", *paths)
    run = reportgen("run", *paths, "--out", folder / "out", "--format", "html")
    return folder, validate, run


def test_hostile_runs_are_refused_as_a_whole(hostile_runs):
    folder, validate, run = hostile_runs
    for proc in (validate, run):
        assert proc.returncode == 2, proc.stderr
        assert "Traceback" not in proc.stderr + proc.stdout
        assert ": ok" not in proc.stdout
    assert not list(folder.rglob("CANARY*"))
    assert not list(folder.rglob("run.h5"))


@pytest.mark.parametrize("case", HOSTILE, ids=[c[0] for c in HOSTILE])
def test_hostile_formula_is_named_by_file_key_and_problem(hostile_runs, case, cli):
    folder, validate, run = hostile_runs
    name, key, _, problem = case
    path = folder / f"hostile_{name}.toml"
    for stderr in (validate.stderr, run.stderr):
        lines = [ln for ln in stderr.splitlines() if ln.startswith(f"{path}:")]
        assert len(lines) == 1, stderr
        assert f"key '{key}'" in lines[0] and problem in lines[0], lines[0]
    # each file on its own: exit status 2 from both commands
    assert cli("validate", path)[0] == 2
    code, _, err = cli("run", path, "--out", folder / "alone", "--jobs", 1, "--format", "html")
    assert code == 2 and f"key '{key}'" in err
    assert not (folder / "alone" / path.stem / "run.h5").exists()
    assert not (folder / f"CANARY_{name}").exists() and not (folder / "CANARY").exists()


# ------------------------------------------------- 6. what reaches the generated code
ALLOWED_NAMES = {
    "math", "numba", "njit", "def", "rhs", "jac", "drift", "kick", "t", "y", "p", "q",
    "params", "out", "pass", "if", "else", "abs", "import", "cache", "True", "error_model",
    "rhs_callback", "jac_callback", "drift_callback", "kick_callback",
    # math functions the printer may call
    "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "asinh",
    "acosh", "atanh", "exp", "log", "sqrt", "copysign",
}

# unusual names, and every function of the allow-list (abs of a constant only: abs of a
# coordinate is the xfail below)
UNUSUAL = """
kind = "hamiltonian"
[params]
kappa = 1.7
lam = 0.4
[system]
coordinates = ["alpha", "Omega_2"]
H = \"\"\"p_alpha**2/(2*kappa) + p_Omega_2**2/2 + lam*(1 - cos(alpha))
       + p_alpha*(asin(tanh(Omega_2))/pi + acos(tanh(Omega_2))*E + atan2(Omega_2, alpha)
                  + log(2 + cosh(Omega_2)) + atan(Omega_2))/10
       + tanh(Omega_2)*sinh(alpha) + exp(-Omega_2**2) + tan(alpha/4)*sqrt(1 + alpha**2)
       + abs(kappa - 2)*Omega_2**3\"\"\"
[initial]
alpha = 0.1
Omega_2 = 0.2
p_alpha = 0.0
p_Omega_2 = 0.0
[run]
t_end = 1.0
study = false
"""

# names that coincide with the generated module's own (math, numba, out, params, y, x0)
COLLIDING = """
kind = "hamiltonian"
[params]
out = 2.0
params = 0.5
y = 3.0
x0 = 0.25
[system]
coordinates = ["math", "numba"]
H = "p_math**2/(2*out) + p_numba**2/2 + y*math**2*numba + x0*cos(math) + params*sqrt(1 + numba**2)"
[initial]
math = 0.1
numba = 0.2
p_math = 0.0
p_numba = 0.0
[run]
t_end = 1.0
study = false
"""


def generated_tokens(source: str):
    return list(tokenize.generate_tokens(StringIO(source).readline))


@pytest.mark.parametrize("which", ["kepler", "henon_heiles", "double", "spherical", "unusual",
                                   "colliding"])
def test_generated_module_holds_no_config_text(which, request):
    texts = {"unusual": UNUSUAL, "colliding": COLLIDING}
    if which in texts:
        scene = scene_of(texts[which])
    else:
        scene = request.getfixturevalue({"double": "double_pendulum"}.get(which, which))[0]
    source = formula.module_source(scene.system())
    tokens = generated_tokens(source)
    names = {tok.string for tok in tokens if tok.type == tokenize.NAME}
    stray = {n for n in names if n not in ALLOWED_NAMES
             and not (n.startswith("x") and n[1:].isdigit())}
    assert not stray, stray
    strings = [tok for tok in tokens if tok.type == tokenize.STRING]
    assert strings[0].start == (1, 0)  # the module docstring, then the error model only
    assert strings[0].string == '"""Generated by reportgen.core.formula; do not edit."""'
    assert {tok.string for tok in strings[1:]} == {'"numpy"'}
    assert not [tok for tok in tokens if tok.type == tokenize.COMMENT]
    if which == "unusual":
        for f in ("asin", "acos", "atan2", "atan", "log", "tan", "exp", "sinh", "cosh",
                  "tanh", "sqrt", "sin", "cos"):
            assert f"math.{f}(" in source, f  # every function really was printed
        assert "abs(" in source


def test_colliding_names_compute_the_hand_derived_rhs():
    """Config names equal to the generated code's own do not change what it computes:
    the module's rhs (run as Python, not compiled) against ṁ = p_m/out, ṅ = p_n,
    ṗ_m = −(2 y m n − x0 sin m), ṗ_n = −(y m² + params n/√(1 + n²)) (hand)."""
    system = scene_of(COLLIDING).system()
    assert list(system.param_symbols) == ["out", "params", "y", "x0"]
    module = formula.load_module(formula.module_source(system))
    out_, params_, y_, x0_ = 2.0, 0.5, 3.0, 0.25
    rng = np.random.default_rng(11)
    for state in rng.uniform(-1.5, 1.5, (20, 4)):
        m, n, pm, pn = state
        got = np.empty(4)
        module.rhs.py_func(0.3, state.copy(), system.param_array(), got)
        hand = [pm / out_, pn, -(2 * y_ * m * n - x0_ * math.sin(m)),
                -(y_ * m**2 + params_ * n / math.sqrt(1 + n**2))]
        assert np.allclose(got, hand, rtol=1e-14, atol=1e-15), (state, got, hand)


@pytest.mark.parametrize("which", ["kepler", "double_pendulum"])
def test_jacobi_identity_holds_on_the_run(which, request):
    # {f,{g,H}} + {g,{H,f}} + {H,{f,g}} = 0 (Goldstein §9.5), with terms that do not vanish:
    # Kepler (Lz, Px, H) and the double pendulum (a, p_a, H)
    scene, results = request.getfixturevalue(which)
    a = results.analysis
    assert a["jacobi_triple"][2] == "H" and a["jacobi_scale"] > 0.1
    assert a["jacobi_max"] <= 1e-14 * a["jacobi_scale"]


# abs() of a coordinate: the Jacobian holds d sign(x)/dx = 2 DiracDelta(x), compiled and
# evaluated as 0 (it is zero but at x = 0)
def test_abs_of_a_coordinate_runs_or_is_refused_cleanly(write_config, cli, tmp_path):
    path = write_config("vee", """
        kind = "hamiltonian"
        [system]
        coordinates = ["x"]
        H = "p_x**2/2 + abs(x)"
        [initial]
        x = 1.0
        p_x = 0.0
        [run]
        t_end = 5.0
        samples = 101
        study = false
        """)
    code, _, err = cli("run", path, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0 or (code == 2 and "system.H" in err), err
    assert "ValueError" not in err


# ---------------------------------------- 7. valid as text, but no Legendre transform
BAD_L = {
    # id: (L, what the message says); V = (x² + y²)/2 throughout
    "quartic": ("x_dot**4/4 + y_dot**2/2", "not quadratic in the velocities"),
    "relativistic": ("-sqrt(1 - x_dot**2 - y_dot**2)", "not quadratic in the velocities"),
    "rank_one": ("(x_dot + y_dot)**2/2", "singular"),
    "one_velocity": ("x_dot**2/2", "singular"),
    # x*y_dot - y*x_dot alone is a first-order Lagrangian now (notes (3.36-3.38)): it is
    # reduced, not refused (tests/test_hamiltonian_first_order.py)
    "no_velocity": ("x*y", "singular"),
}


@pytest.mark.parametrize("case", sorted(BAD_L))
def test_lagrangian_without_legendre_transform_is_a_config_error(case, write_config, cli,
                                                                  tmp_path):
    L, problem = BAD_L[case]
    path = write_config(f"bad_{case}", f"""
        kind = "hamiltonian"
        [system]
        coordinates = ["x", "y"]
        L = "{L} - (x**2 + y**2)/2"
        [initial]
        x = 1.0
        y = 0.0
        x_dot = 0.0
        y_dot = 0.5
        [run]
        t_end = 1.0
        samples = 11
        study = false
        """)
    code, _, err = cli("run", path, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 2, err
    line = next(ln for ln in err.splitlines() if str(path) in ln)
    assert "system.L" in line and problem in line, err
    assert "Traceback" not in err
    assert not (tmp_path / "o" / path.stem / "run.h5").exists()


def test_power_of_constants_passes_validate_but_run_refuses_it(write_config, cli, tmp_path):
    # 9**9**9**9 is a formula to the allow-list; SymPy would try to evaluate it
    text = KEPLER.replace('H = "(p_x**2 + p_y**2)/2 - k/sqrt(x**2 + y**2)"',
                          'H = "(p_x**2 + p_y**2)/2 - k/sqrt(x**2 + y**2) + 9**9**9**9*x"')
    path = write_config("tower", text)
    code, _, err = cli("run", path, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 2 and "system.H" in err and "exponent above 64" in err, err
    assert not (tmp_path / "o" / path.stem / "run.h5").exists()


# --------------------------------------------------- 8. the state from an energy
def test_left_out_momentum_is_solved_for_the_energy(henon_heiles):
    scene, results = henon_heiles
    x, y, px, py = scene.initial_state()
    assert (x, y, py) == (0.0, 0.1, 0.0) and px > 0  # the root p_x ≥ 0
    assert abs(henon_heiles_energy(x, y, px, py) - HH_ENERGY) <= 1e-13
    # p_x = √(2(E − V(0, 0.1))) with V = y²/2 − y³/3 at x = 0 (Hénon & Heiles 1964)
    assert abs(px - math.sqrt(2 * (HH_ENERGY - (0.1**2 / 2 - 0.1**3 / 3)))) <= 1e-14
    assert abs(results.analysis["H0"] - HH_ENERGY) <= 1e-13


def test_left_out_velocity_is_solved_for_the_energy():
    energy = -1.5  # between V(θ = 1) = −m g l cos 1 ≈ −5.51 and 0
    text = SPHERICAL.replace(f'phi_dot = {SP0["phi_dot"]}', f"energy = {energy}")
    scene = scene_of(text)
    th, ph, p_th, p_ph = scene.initial_state()
    thd = p_th / (MS * LS**2)
    phd = p_ph / (MS * LS**2 * math.sin(th) ** 2)
    assert (th, ph) == (SP0["theta"], SP0["phi"])
    assert abs(thd - SP0["theta_dot"]) <= 1e-15
    assert phd > 0
    assert abs(spherical_energy(th, thd, phd) - energy) <= 1e-13


def test_energy_below_the_minimum_is_refused(write_config, cli, tmp_path):
    # V(0, 0.1) = 0.1²/2 − 0.1³/3 ≈ 0.00467 > E: no p_x gives H = E
    path = write_config("too_low", HENON_HEILES.replace(repr(HH_ENERGY), "0.001"))
    code, _, err = cli("run", path, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 2, err
    line = next(ln for ln in err.splitlines() if str(path) in ln)
    assert "initial.energy" in line and "below" in line, err
    assert "Traceback" not in err
    assert not (tmp_path / "o" / path.stem / "run.h5").exists()


# ------------------------------------------------- 9. the archive, read by xarray
def test_archive_opens_in_xarray_with_named_state_columns(kepler, write_config, cli,
                                                          tmp_path):
    import xarray as xr

    path = write_config("kepler", KEPLER)
    code, _, err = cli("run", path, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err
    archive = tmp_path / "o" / "kepler" / "run.h5"
    with xr.open_dataset(archive, group="runs/main", engine="h5netcdf",
                         phony_dims="sort") as ds:
        assert ds["y"].dims == ("t", "component")
        assert list(ds["component"].values) == ["x", "y", "p_x", "p_y"]
        y = ds["y"].values
        p_y = ds["y"].sel(component="p_y").values
        t = ds["t"].values
    run = kepler[1].runs["main"]
    assert np.array_equal(t, run.t)
    assert np.max(np.abs(y - run.y)) <= 1e-10  # the same run, in another process
    assert np.array_equal(p_y, y[:, 3])
    with h5py.File(archive, "r") as f:
        a, main = f["analysis"].attrs, f["runs/main"]
        assert a["poisson_Lz"] == "0" and bool(a["conserved_Lz"]) is True
        assert a["given"] == "H" and abs(a["H0"] - (0.2**2 + 1.0**2) / 2 + K) <= 1e-15
        assert sorted(main["invariants"]) == ["H", "Lz"]
        assert main.attrs["status"] == "ok" and main.attrs["drift_Lz"] <= 1e-9
        assert np.array_equal(f["analysis/observables/Px"][()], y[:, 2])


# ---------------------------------------------------- 10. the surface of section
def test_poincare_crossings_match_hand_integration_events(henon_heiles):
    scene, results = henon_heiles
    run = results.runs["main"]
    points = results.analysis["poincare"]
    assert results.analysis["poincare_surface"] == ["x", "0.0", "up"]
    assert results.analysis["poincare_axes"] == ["y", "p_y"]

    def surface(t, s):
        return s[0]

    surface.direction = 1.0
    sol = hand_integration(henon_heiles_rhs, run.y[0], run.t, events=surface)
    t_ev, s_ev = sol.t_events[0], sol.y_events[0]
    keep = t_ev > 1e-9  # the orbit starts on the surface: t = 0 is not a crossing
    t_ev, s_ev = t_ev[keep], s_ev[keep]
    assert len(points["t"]) == len(t_ev) >= 5
    assert np.max(np.abs(points["t"] - t_ev)) <= 1e-6
    assert np.max(np.abs(points["u"] - s_ev[:, 1])) <= 1e-6
    assert np.max(np.abs(points["v"] - s_ev[:, 3])) <= 1e-6


def test_preset_formulas_are_the_ones_the_quadratures_solve():
    # the kind keeps the two separable presets' H as text (importing the kind imports no
    # numerics); they must be core.hamilton_jacobi's, character for character
    from reportgen.core import hamilton_jacobi
    from reportgen.kinds.hamiltonian import HamiltonianScene, _PresetFormulas

    assert _PresetFormulas.CENTRAL_H == hamilton_jacobi.CENTRAL_H
    assert _PresetFormulas.TWO_CENTRES_H == hamilton_jacobi.TWO_CENTRES_H
    presets = HamiltonianScene.presets
    assert presets["central_potential"]["system"]["H"] == hamilton_jacobi.CENTRAL_H
    assert presets["two_centres"]["system"]["H"] == hamilton_jacobi.TWO_CENTRES_H


@pytest.mark.parametrize("text, coordinates, expected", [
    ("p_q**2/2 + q**4/4", ["q"], "p²/2 + q⁴/4"),  # one coordinate: its momentum is p
    ("p_theta**2/(2*m*l**2) - m*g*l*cos(theta)", ["theta"], "p²/(2ml²) − mgl cos(θ)"),
    ("m*l**2/2*(theta_dot**2 + phi_dot**2)", ["theta", "phi"], "ml²/2·(θ̇² + φ̇²)"),
    ("x - (y - z) + 2*x", ["x"], "x − (y − z) + 2x"),
    ("(p_x**2 + p_y**2)/2", ["x", "y"], None),  # p_y has no Unicode subscript
    ("x**0.5", ["x"], None),  # not a small whole power
])
def test_formula_text_spells_a_formula_in_the_authors_order(text, coordinates, expected):
    from reportgen.kinds.hamiltonian.symbols import formula_text
    assert formula_text(text, coordinates) == expected


def test_untitled_formula_system_is_titled_by_its_hamiltonian():
    quartic = Path(__file__).parent / "data" / "variants" / "hamiltonian_quartic.toml"
    scene = load_scene(parse_config_text(quartic.read_text(encoding="utf-8")))
    assert scene.config.title == "" and scene.title == "Hamiltonian H = p²/2 + q⁴/4"


def test_a_long_hamiltonian_is_broken_between_its_terms():
    from reportgen.kinds.hamiltonian.symbols import dot_tex, split_sum
    term = r"\frac{p_{a}^{2}}{" + " + ".join(["l_{1}^{2} m_{1}"] * 12) + "}"
    lines = split_sum("H", " + ".join([term] * 4))
    assert len(lines) == 4 and lines[0].startswith("H = ")
    assert all(line.startswith(r"\qquad + ") for line in lines[1:])
    assert split_sum("H", "a - b") == ["H = a - b"]
    assert dot_tex("p_{a}") == r"\dot{p}_{a}" and dot_tex("x") == r"\dot{x}"
