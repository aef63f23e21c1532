"""Small oscillations from a written potential (textbook §5.1, issue 42 item 6): the
equilibrium of U(q) or L(q, q̇) found from a guess, A = ∂²U/∂q∂q and M taken there, the
generalized eigenproblem A a = ω² M a; the double pendulum against its closed forms."""

from __future__ import annotations

import math

import h5py
import numpy as np
import pytest

import claimgen
from reportgen.core import small_oscillations as so
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, parse_config_text

REPO_CONFIG = "configs/normal_modes_double_pendulum.toml"

#: the double pendulum's Lagrangian, angles from the downward vertical
DOUBLE_L = ("(m1 + m2)/2*l1**2*a_dot**2 + m2/2*l2**2*b_dot**2"
            " + m2*l1*l2*a_dot*b_dot*cos(a - b)"
            " + (m1 + m2)*g*l1*cos(a) + m2*g*l2*cos(b)")
DOUBLE_U = "-(m1 + m2)*g*l1*cos(a) - m2*g*l2*cos(b)"
DOUBLE_T = ("(m1 + m2)/2*l1**2*a_dot**2 + m2/2*l2**2*b_dot**2"
            " + m2*l1*l2*a_dot*b_dot*cos(a - b)")
DOUBLE_M = '[["(m1 + m2)*l1**2", "m2*l1*l2*cos(a - b)"], ["m2*l1*l2*cos(a - b)", "m2*l2**2"]]'


def scene(text: str):
    return load_scene(parse_config_text(text))


def double_pendulum(m1=1.0, m2=1.0, l1=1.0, l2=1.0, g=9.81, form="L",
                    guess="{ a = 0.3, b = -0.2 }", extra=""):
    system = {"L": f'L = "{DOUBLE_L}"', "T": f'U = "{DOUBLE_U}"\nT = "{DOUBLE_T}"',
              "M": f'U = "{DOUBLE_U}"\nM = {DOUBLE_M}'}[form]
    return f"""
kind = "normal_modes"
units = "SI"
[params]
m1 = {m1}
m2 = {m2}
l1 = {l1}
l2 = {l2}
g = {g}
[system]
coordinates = ["a", "b"]
coordinate_unit = "rad"
{system}
guess = {guess}
{extra}
"""


def secular_omega2_by_hand(m1, m2, l1, l2, g):
    """ω² of the double pendulum from det(A − ω² M) = 0 with M and A written by hand at
    θ = 0: M = [[(m1+m2) l1², m2 l1 l2], [m2 l1 l2, m2 l2²]], A = diag((m1+m2) g l1,
    m2 g l2); the quadratic a ω⁴ − b ω² + c = 0 (a = det M, c = det A), solved."""
    M = [[(m1 + m2) * l1 ** 2, m2 * l1 * l2], [m2 * l1 * l2, m2 * l2 ** 2]]
    A = [[(m1 + m2) * g * l1, 0.0], [0.0, m2 * g * l2]]
    a = M[0][0] * M[1][1] - M[0][1] ** 2
    b = M[0][0] * A[1][1] + M[1][1] * A[0][0]
    c = A[0][0] * A[1][1]
    root = math.sqrt(b * b - 4 * a * c)
    return np.array([(b - root) / (2 * a), (b + root) / (2 * a)])


def landau_omega2(m1, m2, l1, l2, g):
    """Landau & Lifshitz, Mechanics, §23 problem 2 (the coplanar double pendulum):
    ω² = g/(2 m1 l1 l2) {(m1 + m2)(l1 + l2) ∓ √[(m1 + m2)((m1 + m2)(l1 + l2)² − 4 m1 l1 l2)]};
    the same quartic as Kibble & Berkshire, Classical Mechanics, 5th ed., eq. (11.21)."""
    s = m1 + m2
    root = math.sqrt(s * (s * (l1 + l2) ** 2 - 4 * m1 * l1 * l2))
    return g / (2 * m1 * l1 * l2) * np.array([s * (l1 + l2) - root, s * (l1 + l2) + root])


# ----------------------------------------------------------------- the double pendulum
def test_equal_double_pendulum_against_the_closed_form():
    """m1 = m2, l1 = l2: ω² = (2 ∓ √2) g/l (Landau & Lifshitz §23 problem 2 with equal
    masses and lengths; det([[2 − 2λ, −λ], [−λ, 1 − λ]]) = 0 for λ = ω² l/g)."""
    g, length = 9.81, 1.0
    res = scene(double_pendulum(g=g, l1=length, l2=length)).simulate()
    a = res.analysis
    exact = np.sqrt(np.array([2 - math.sqrt(2), 2 + math.sqrt(2)]) * g / length)
    assert np.max(np.abs(a["frequencies"] / exact - 1)) < 1e-14
    assert np.all(a["equilibrium"] == 0.0)  # hanging straight down, not at 10⁻¹⁶⁵ rad
    assert a["equilibrium_stability"] == "stable" and a["hessian_positive_definite"]
    assert list(a["mode_type"]) == ["in phase", "out of phase"]
    # the lower mode: θ₂/θ₁ = +√2, the upper: −√2 (same closed form)
    ratios = a["modes"][1] / a["modes"][0]
    assert np.allclose(ratios, [math.sqrt(2), -math.sqrt(2)], rtol=1e-13)


@pytest.mark.parametrize("m1, m2, l1, l2", [(1.0, 3.0, 0.5, 2.0), (5.0, 0.2, 1.3, 0.4),
                                            (2.0, 2.0, 1.0, 3.0)])
def test_general_double_pendulum_against_the_secular_equation_by_hand(m1, m2, l1, l2):
    g = 9.81
    res = scene(double_pendulum(m1, m2, l1, l2, g)).simulate()
    a = res.analysis
    by_hand = secular_omega2_by_hand(m1, m2, l1, l2, g)
    assert np.max(np.abs(a["omega_squared"] / by_hand - 1)) < 1e-13
    assert np.max(np.abs(a["omega_squared"] / landau_omega2(m1, m2, l1, l2, g) - 1)) < 1e-13
    M = [[(m1 + m2) * l1 ** 2, m2 * l1 * l2], [m2 * l1 * l2, m2 * l2 ** 2]]
    assert np.allclose(a["mass_matrix"], M, rtol=1e-15, atol=0)
    assert np.allclose(a["hessian"], np.diag([(m1 + m2) * g * l1, m2 * g * l2]), rtol=1e-14,
                       atol=1e-13)
    # the report's own check: the 2 × 2 secular equation in closed form
    assert a["closed_form_max_rel_error"] < 1e-13
    assert a["hessian_finite_difference"] < 1e-6  # the central difference agrees


@pytest.mark.parametrize("form", ["T", "M"])
def test_u_with_t_or_m_gives_what_l_gives(form):
    """The same pendulum written as U and T, or U and M(q): the same M, A and ω."""
    ref = scene(double_pendulum(1.0, 3.0, 0.5, 2.0)).simulate().analysis
    other = scene(double_pendulum(1.0, 3.0, 0.5, 2.0, form=form)).simulate().analysis
    assert other["given"] == form
    for key in ("mass_matrix", "hessian", "omega_squared"):
        assert np.allclose(other[key], ref[key], rtol=1e-14, atol=1e-13), key


def test_shipped_config_matches_the_closed_form():
    res = scene(open(REPO_CONFIG, encoding="utf-8").read()).simulate()
    exact = np.sqrt(np.array([2 - math.sqrt(2), 2 + math.sqrt(2)]) * 9.81)
    assert np.max(np.abs(res.analysis["frequencies"] / exact - 1)) < 1e-14
    # the search started away from the equilibrium and reached it
    assert np.any(res.analysis["equilibrium_guess"] != 0)
    assert res.analysis["equilibrium_gradient_norm"] < 1e-14


# ------------------------------------------------------------- an equilibrium off zero
def test_a_mass_on_a_vertical_spring_finds_its_sagged_equilibrium():
    """U = ½ k (x − a)² − m g x: x₀ = a + m g/k, ω = √(k/m) (Goldstein §6.1)."""
    k, m, a0, g = 40.0, 2.0, 0.5, 9.81
    res = scene(f"""
kind = "normal_modes"
[params]
k = {k}
m = {m}
a0 = {a0}
g = {g}
[system]
coordinates = ["x"]
U = "k/2*(x - a0)**2 - m*g*x"
T = "m/2*x_dot**2"
""").simulate()
    a = res.analysis
    assert abs(a["equilibrium"][0] - (a0 + m * g / k)) < 1e-15 * (a0 + m * g / k) * 4
    assert abs(a["frequencies"][0] / math.sqrt(k / m) - 1) < 1e-15
    assert a["equilibrium_residual"] <= so.STATIONARY_RTOL


def test_a_flat_direction_is_neutral_and_said_so(tmp_path):
    """U independent of y: A is positive semidefinite with one zero eigenvalue; the words
    follow the stored classification (and the claims registry checks them)."""
    config = {"kind": "normal_modes", "params": {"k": 2.0},
              "system": {"coordinates": ["x", "y"], "U": "k/2*x**2",
                         "T": "(x_dot**2 + y_dot**2)/2 + x_dot*y_dot/4",
                         "guess": {"x": 0.4}}}
    found, text = claimgen.contradictions_of(config, tmp_path)
    assert found == []
    assert "neutral to second order" in text and "A is positive definite" not in text
    assert "neutral in some directions" in text


def test_a_stable_equilibrium_is_said_stable(tmp_path):
    config = {"kind": "normal_modes", "params": {"k": 2.0},
              "system": {"coordinates": ["x", "y"], "U": "k/2*x**2 + (x - y)**2 + y**4",
                         "M": [[1.0, 0.0], [0.0, "2 + x**2"]], "guess": {"x": 0.4, "y": -0.1}}}
    found, text = claimgen.contradictions_of(config, tmp_path)
    assert found == []
    assert "A is positive definite" in text and "neutral" not in text


def test_a_family_over_a_constant_is_labelled_in_the_systems_units(write_config, tmp_path):
    """A sweep over a named constant: each member against the closed form, and the family's
    figures in rad/s (the config's SI), not in the config's own unnamed units."""
    from reportgen.archive.store import read_archive
    from reportgen.kinds.normal_modes import NormalModesScene
    from reportgen.pipeline.stages import run_scene

    text = open(REPO_CONFIG, encoding="utf-8").read()
    path = write_config("family", text + '\n[sweep]\n"params.m2" = [0.5, 1.0, 4.0]\nstore = 0\n')
    outcome = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    data = read_archive(tmp_path / "out" / "family" / "run.h5")
    m2 = data.sweep.values["params.m2"]
    for i, m in enumerate(m2):
        expected = np.sqrt(landau_omega2(1.0, float(m), 1.0, 1.0, 9.81))
        got = [data.sweep.analysis[f"frequencies_{j}"][i] for j in (1, 2)]
        assert np.allclose(got, expected, rtol=1e-13)
    assert NormalModesScene.result_quantity(data, "frequencies_1").unit == "rad/s"
    assert NormalModesScene.config_quantity(data, "params.m2").symbol == "m_{2}"


# ---------------------------------------------------------------- what the archive keeps
def test_the_archive_keeps_the_equilibrium_with_units(write_config, cli, tmp_path):
    cfg = write_config("dp", open(REPO_CONFIG, encoding="utf-8").read())
    code, _, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err
    with h5py.File(tmp_path / "o" / "dp" / "run.h5") as f:
        an = f["analysis"]
        for name, unit in (("equilibrium", "rad"), ("equilibrium_guess", "rad"),
                           ("equilibrium_gradient", "J"), ("mass_matrix", "kg m^2"),
                           ("hessian", "J")):
            assert an[name].attrs["units"] == unit, name
            assert an[name].attrs["long_name"], name
        for name in ("equilibrium_gradient_norm", "equilibrium_residual",
                     "hessian_positive_definite", "equilibrium_stability",
                     "hessian_finite_difference"):
            assert name in an.attrs or name in an, name
    html = (tmp_path / "o" / "dp" / "report.html").read_text()
    assert '<section id="equilibrium">' in html
    assert "A is positive definite" in html and "Born–Oppenheimer" not in html


def test_a_molecule_names_the_born_oppenheimer_picture_and_fig_5_1(write_config, cli,
                                                                    tmp_path):
    """Where the scene is given as atoms (stored source "molecule"), the page names the
    Born–Oppenheimer picture and cites textbook Fig. 5.1; a written potential does not."""
    cfg = write_config("co2", 'kind = "normal_modes"\npreset = "co2"\n')
    code, _, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err
    from reportgen.scene.sources import visible_blocks

    html = (tmp_path / "o" / "co2" / "report.html").read_text()
    named = [b for b in visible_blocks(html) if "Born–Oppenheimer" in b]
    assert len(named) == 1 and "textbook Fig. 5.1" in named[0]


# ------------------------------------------------------------------ refused configs
BASE = 'kind = "normal_modes"\n[system]\ncoordinates = ["x"]\n'
BASE_K = 'kind = "normal_modes"\n[params]\nk = 1.0\n[system]\ncoordinates = ["x"]\n'
BAD = [
    (BASE_K + 'U = "k*x**2/2 + z"\nT = "x_dot**2/2"\n', "key 'system.U': undefined name 'z'"),
    (BASE_K + 'U = "k*x**2*t"\nT = "x_dot**2/2"\n', "time-independent equilibrium"),
    (BASE + 'U = "__import__(\'os\')"\nT = "x_dot**2/2"\n', "key 'system.U'"),
    (BASE_K + 'U = "k*x.real"\nT = "x_dot**2/2"\n', "an attribute"),
    (BASE + 'U = "exp(x)"\nT = "x_dot**2/2"\n',
     "key 'system.guess': no stationary point of U found from the guess (x = 0)"),
    (BASE_K + 'U = "k*cos(x)"\nT = "x_dot**2/2"\n',
     "key 'system.guess': the stationary point found from the guess (x = 0) is x = 0, not a "
     "minimum of U"),
    (BASE + 'U = "x**4"\nT = "x_dot**2/2"\nguess = { x = 0.5 }\n',
     "key 'system.U': A = ∂²U/∂q∂q vanishes"),
    (BASE_K + 'L = "x_dot**2/2 + k*x*x_dot - x**2/2"\n',
     "key 'system.L': a term linear in the velocity x_dot"),
    (BASE + 'U = "x**2"\nT = "x_dot**2/2 + x**2"\n', "key 'system.T': T has a part without"),
    (BASE + 'U = "x**2"\nT = "x_dot**4"\n', "key 'system.T': not quadratic in the velocities"),
    (BASE + 'U = "x**2"\nM = [[-1.0]]\n', "key 'system.M': the mass matrix M is not positive"),
    (BASE + 'U = "x**2"\nM = [[1.0, 0.0]]\n', "key 'system.M': must be 1 × 1"),
    (BASE + 'U = "x**2"\n', "key 'system': give L alone, or U with one of T and M"),
    (BASE + 'U = "x**2"\nT = "x_dot**2"\nL = "x_dot**2"\n', "key 'system': give L alone"),
    (BASE + 'U = "x**2"\nT = "x_dot**2"\nguess = { y = 1.0 }\n',
     "key 'system.guess.y': not a coordinate of the system (expected x; got 1.0)"),
    ('kind = "normal_modes"\nunits = "SI"\n[system]\ncoordinates = ["x"]\nU = "x**2"\n'
     'T = "x_dot**2"\n', "key 'system.coordinate_unit': units = \"SI\" needs"),
    ('kind = "normal_modes"\n[params]\nk = 1.0\n[chain]\nn = 3\n',
     "key 'params.k': named constants are for the formulas of [system]"),
    ('kind = "normal_modes"\n[params]\nx = 1.0\n[system]\ncoordinates = ["x"]\nU = "x**2"\n'
     'T = "x_dot**2"\n', "key 'params.x': a constant may not take the name of a coordinate"),
    (BASE_K + 'U = "x**2"\nT = "x_dot**2"\n', "key 'params.k': a constant no formula uses"),
    ('kind = "normal_modes"\n[system]\ncoordinates = ["x", "x_dot"]\nU = "x**2"\n'
     'T = "x_dot**2"\n', "key 'system.coordinates': aliased names"),
]


@pytest.mark.parametrize("body, message", BAD, ids=[m[:40] for _, m in BAD])
def test_bad_potential_is_one_line_naming_the_key(body, message):
    """Validated and its models built (what ``validate`` and ``run`` do): a ConfigError of
    one line naming the file, the key, the rule and the value, never a traceback."""
    with pytest.raises(ConfigError) as exc:
        scene(body).build_models()
    lines = exc.value.problems
    assert len(lines) == 1 and message in lines[0], lines


def test_validate_and_run_exit_2_on_a_potential_without_equilibrium(write_config, cli,
                                                                    tmp_path):
    cfg = write_config("flat", BASE + 'U = "exp(x)"\nT = "x_dot**2/2"\n')
    for command in (("validate", cfg), ("run", cfg, "--out", tmp_path / "o", "--jobs", 1)):
        code, out, err = cli(*command)
        assert code == 2, (command, out, err)
        assert "flat.toml: key 'system.guess': no stationary point" in err
        assert "Traceback" not in err
    assert not (tmp_path / "o" / "flat" / "run.h5").exists()


def test_config_text_is_never_evaluated(monkeypatch):
    """The formulas go through the allow-list parser only (no eval, exec or sympify)."""
    import builtins

    import sympy

    def refuse(*_args, **_kwargs):
        raise AssertionError("config text evaluated")

    monkeypatch.setattr(builtins, "eval", refuse)
    monkeypatch.setattr(builtins, "exec", refuse)
    monkeypatch.setattr(sympy, "sympify", refuse)
    system = so.potential_system(["a", "b"], L=DOUBLE_L,
                                 params={"m1": 1.0, "m2": 1.0, "l1": 1.0, "l2": 1.0, "g": 9.81})
    found = so.find_equilibrium(system, [0.3, -0.2])
    assert found.stability == "stable"


def test_secular_closed_form_is_the_eigensolver():
    rng = np.random.default_rng(5)
    for _ in range(20):
        B, C = rng.normal(size=(2, 2)), rng.normal(size=(2, 2))
        M, A = B @ B.T + 0.1 * np.eye(2), C @ C.T
        import scipy.linalg

        assert np.allclose(so.secular_omega2(M, A), scipy.linalg.eigh(A, M, eigvals_only=True),
                           rtol=1e-10, atol=1e-12)
