"""Prose that matches the scene: default titles, subtitles in words, and explanations
and captions chosen by the scene's case (symmetric or asymmetric body, bound or not)."""

from __future__ import annotations

import html
import re
import textwrap
import tomllib
from pathlib import Path

import pytest

from reportgen.kinds import load_scene
from reportgen.kinds.hamiltonian.symbols import symbol_tex, symbol_text, symbol_words
from reportgen.kinds.normal_modes.report import counted, formula
from reportgen.scene.base import REGISTRY
from reportgen.scene.config import SourceConfig

CONFIGS = Path(__file__).resolve().parent.parent / "configs"


def scene_of(name: str, text: str):
    text = textwrap.dedent(text).lstrip()
    return load_scene(SourceConfig(Path(f"{name}.toml"), text, tomllib.loads(text)))


def visible_text(page: str) -> str:
    """The words a reader sees: no SVG (figures, typeset equations), style or config; sub-
    and superscripts as Unicode characters (I<sub>1</sub> reads I₁)."""
    for pattern in (r"<svg.*?</svg>", r"<style.*?</style>", r'<pre class="config">.*?</pre>',
                    r"<head>.*?</head>"):
        page = re.sub(pattern, " ", page, flags=re.S)
    return html.unescape(re.sub(r"<[^>]+>", " ", _scripts(page)))


def _scripts(page: str) -> str:
    """``<sub>``/``<sub>`` runs as Unicode sub- and superscript characters."""
    table = {"sub": str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉"),
             "sup": str.maketrans("0123456789−", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")}
    return re.sub(r"<(sub|sup)>([^<]*)</\1>",
                  lambda m: m.group(2).translate(table[m.group(1)]), page)


# ------------------------------------------------------------------ default titles
UNTITLED = {  # one config per kind without a title and without a titled preset
    "pendulum": """kind = "pendulum"
        [params]
        g = 9.81
        l = 1.0
        [initial]
        theta = 2.5
        [run]
        t_end = 10.0""",
    "oscillator": """kind = "oscillator"
        [params]
        m = 1.0
        omega = 2.0
        [initial]
        q = 1.0
        p = 0.0
        [run]
        t_end = 10.0""",
    "central_force": """kind = "central_force"
        [params]
        m1 = 1.0
        m2 = 1.0
        k = 0.5
        [initial]
        x = 1.0
        y = 0.0
        vx = 0.0
        vy = 0.6
        [run]
        t_end = 10.0""",
    "three_body": """kind = "three_body"
        preset = "pythagorean\"""",
    "fput": """kind = "fput"
        [run]
        t_end = 10.0""",
    "two_center": """kind = "two_center"
        [params]
        mu = 1.0
        a = 1.0
        [initial]
        x = 0.0
        y = 1.6
        vx = 1.05
        vy = 0.0
        [run]
        t_end = 10.0""",
    "rigid_body": """kind = "rigid_body"
        [params]
        I1 = 1.0
        I2 = 2.0
        I3 = 3.0
        [initial]
        omega = [0.01, 2.0, 0.01]
        [run]
        t_end = 10.0""",
    "heavy_top": """kind = "heavy_top"
        [params]
        I1 = 1.0
        I3 = 0.5
        Mgl = 1.0
        [band]
        theta_min = 0.8
        theta_max = 1.0
        case = "loops"
        [run]
        t_end = 10.0""",
    "normal_modes": """kind = "normal_modes"
        [[atoms]]
        element = "O"
        position = [-1.16, 0.0, 0.0]
        [[atoms]]
        element = "C"
        position = [0.0, 0.0, 0.0]
        [[atoms]]
        element = "O"
        position = [1.16, 0.0, 0.0]
        [[bonds]]
        atoms = [0, 1]
        k = 16.0
        [[bonds]]
        atoms = [1, 2]
        k = 16.0
        [[angles]]
        atoms = [0, 1, 2]
        k = 0.57""",
    "inertia": """kind = "inertia"
        [shape]
        type = "cone"
        mass = 1.0
        radius = 0.5
        height = 2.0""",
    "rotation": """kind = "rotation"
        preset = "all\"""",
    "hamiltonian": """kind = "hamiltonian"
        [params]
        g = 9.81
        [system]
        coordinates = ["theta"]
        L = "theta_dot**2/2 + g*cos(theta)"
        [initial]
        theta = 1.0
        theta_dot = 0.0
        [run]
        t_end = 10.0""",
}

EXPECTED = {
    "pendulum": "Plane pendulum librating from θ0 = 2.5 rad",
    "oscillator": "Harmonic oscillator, ω = 2 rad/s, from q0 = 1 m, p0 = 0 kg m/s",
    # μ = 1/2, E = ½·½·0.36 − 0.5 = −0.41, L = 0.3: e = √(1 − 2·0.41·0.09/(0.5·0.25))
    "central_force": "Kepler orbit, e = 0.64",
    "three_body": "Pythagorean three-body problem (masses 3, 4, 5)",
    "fput": "Fermi–Pasta–Ulam–Tsingou chain: 3 stiff springs, ω = 50",
    # E = 1.05²/2 − 2/√(1 + 1.6²)
    "two_center": "Two fixed centres (μ = 1, a = 1): a bound orbit at E = −0.5087",
    "rigid_body": "Torque-free asymmetric body (I = 1, 2, 3 kg m²) spun near its "
                  "intermediate axis",
    "heavy_top": "Heavy top: looping nutation, θ from 45.8° to 57.3°",
    "normal_modes": "Normal modes of CO₂ (3 atoms, 2 bonds, 1 bending angle)",
    "inertia": "Inertia of a solid cone (M = 1 kg, R = 0.5 m, h = 2 m)",
    "rotation": "Rotations: axis and angle, Euler angles (z-x-z) and SU(2) → SO(3) by "
                "Möbius maps",
    "hamiltonian": "Lagrangian L = θ̇²/2 + g cos(θ)",
}


def test_every_kind_has_an_untitled_case():
    assert set(UNTITLED) == set(REGISTRY) == set(EXPECTED)


@pytest.mark.parametrize("kind", sorted(UNTITLED))
def test_default_title_in_words(kind):
    scene = scene_of("untitled_scene", UNTITLED[kind])
    assert scene.config.title == ""
    assert scene.title == EXPECTED[kind]
    assert "untitled_scene" not in scene.title and "_" not in scene.title


@pytest.mark.parametrize("path", sorted(CONFIGS.glob("*.toml")), ids=lambda p: p.stem)
def test_shipped_config_without_its_title_gets_a_real_one(path):
    text = re.sub(r"(?m)^title\s*=.*$", "", path.read_text(encoding="utf-8"))
    scene = scene_of(path.stem, text)
    fallback = f"{scene.kind.replace('_', ' ')} ({path.stem})"
    assert scene.title and scene.title != fallback and f"({path.stem})" not in scene.title
    assert scene.title[0].isupper() and "-0." not in scene.title


def test_default_titles_follow_the_case():
    escape = UNTITLED["central_force"].replace("vy = 0.6", "vy = 1.5")
    # μ = 1/2, E = ½·½·2.25 − 0.5 = 1/16, L = 0.75: e = √(1 + 2·(1/16)·0.5625/(0.5·0.25))
    assert scene_of("s", escape).title == "Kepler hyperbola: escape, e = 1.25"
    symmetric = UNTITLED["rigid_body"].replace("I2 = 2.0", "I2 = 1.0").replace("I3 = 3.0",
                                                                                "I3 = 1.5")
    assert scene_of("s", symmetric).title == (
        "Torque-free symmetric body (I = 1, 1, 1.5 kg m²), ω0 = (0.01, 2, 0.01) rad/s")
    rotating = UNTITLED["pendulum"].replace("theta = 2.5", "theta = 0.0\n        theta_dot = 7.0")
    assert scene_of("s", rotating).title == (
        "Plane pendulum rotating over the top (θ0 = 0 rad, θ̇0 = 7 rad/s)")
    unbound = UNTITLED["two_center"].replace("vx = 1.05", "vx = 2.0")
    assert "unbound (escaping)" in scene_of("s", unbound).title


def test_a_family_title_names_its_size_and_key():
    text = UNTITLED["pendulum"] + """
        [sweep]
        initial.theta = { start = 0.1, stop = 1.0, num = 4 }"""
    # not the base config's "librating from θ0 = 2.5 rad": no member starts there
    assert scene_of("s", text).title == ("Plane pendulum: a family of 4 runs over initial "
                                         "angle from the downward vertical")


# ------------------------------------------------------------------ words, not syntax
def test_counted_and_formula():
    assert counted(1, "angle") == "1 angle" and counted(2, "bond") == "2 bonds"
    assert counted(0, "angle") == "0 angles"
    assert formula(["O", "C", "O"]) == "CO₂" and formula(["H", "O", "H"]) == "H₂O"
    assert formula(["C", "H", "H", "H", "H"]) == "CH₄" and formula(["O", None]) == ""


def test_config_names_read_as_symbols():
    # TeX for figures, typeset equations and table cells: an index or a subscript name
    assert symbol_tex("p_phi") == r"p_{\phi}" and symbol_tex("theta1") == r"\theta_{1}"
    assert symbol_tex("A_xy") == "A_{xy}" and symbol_tex("Lz") == "L_{z}"  # a component
    assert symbol_tex("p_theta1") == r"p_{\theta_{1}}" and symbol_tex("a_dot") == r"\dot{a}"
    assert symbol_tex("energy") == r"\mathrm{energy}" and symbol_tex("xi") == r"\xi"
    # Unicode where it has the subscript, else the underscore (prose says it in words)
    assert symbol_text("theta1") == "θ₁" and symbol_text("p_phi") == "pᵩ"
    assert symbol_text("A_xx") == "Aₓₓ" and symbol_text("a_dot") == "ȧ"
    assert symbol_text("p_y") == "p_y" and symbol_text("Lz") == "L_z"
    assert symbol_words("p_y", ["x", "y"]) == "the momentum conjugate to y"
    assert symbol_words("p_y", ["q"]) == "p_y" and symbol_words("theta", ["theta"]) == "θ"


# ------------------------------------------------------------------ rendered reports
def run_report(cli, tmp_path, name: str, text: str) -> str:
    cfg = tmp_path / f"{name}.toml"
    cfg.write_text(textwrap.dedent(text).lstrip(), encoding="utf-8")
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err
    return (tmp_path / "o" / name / "report.html").read_text(encoding="utf-8")


RIGID = """kind = "rigid_body"
    [params]
    I1 = {I1}
    I2 = {I2}
    I3 = {I3}
    [initial]
    omega = {omega}
    [run]
    t_end = 10.0
    samples = 501
    study = false
    """


def test_symmetric_body_report_says_symmetric(cli, tmp_path):
    page = visible_text(run_report(cli, tmp_path, "sym", RIGID.format(
        I1=1.0, I2=1.0, I3=1.5, omega="[0.3, 0.0, 2.0]")))
    assert "I₁ < I₂ < I₃" not in page and "I1 < I2 < I3" not in page
    assert "intermediate axis" not in page and "Dzhanibekov" not in page
    assert "separatri" not in page.replace("there is no separatrix", "").replace(
        "no separatrix divides them", "")
    assert "No axis is unstable" in page and "oblate" in page
    assert "prograde" in page  # oblate: ω⊥ turns with the spin in the body frame
    assert "Torque-free symmetric body (I = 1, 1, 1.5 kg m²)" in page  # default title


def test_asymmetric_body_report_keeps_the_elliptic_case(cli, tmp_path):
    page = " ".join(visible_text(run_report(cli, tmp_path, "asym", RIGID.format(
        I1=1.0, I2=2.0, I3=3.0, omega="[2.0, 0.1, 0.1]"))).split())
    assert "I₁ < I₂ < I₃" in page and "intermediate axis (here axis 2)" in page
    assert "does not start near the intermediate axis, so it shows no flip" in page
    assert "Dzhanibekov" not in page and not re.search(r"\bsymmetric body", page)
    assert "unstable about the intermediate axis 2" in page  # the table's caption


def test_normal_modes_subtitle_is_in_words(cli, tmp_path):
    page = run_report(cli, tmp_path, "co2", 'kind = "normal_modes"\npreset = "co2"\n')
    shown = visible_text(page)
    assert "[[" not in shown and "zero-based" not in shown and "1 angles" not in shown
    assert "A linear triatomic molecule, CO₂: 3 atoms, 2 bonds, 1 bending angle" in shown


def test_hamiltonian_report_shows_no_python_or_tex(cli, tmp_path):
    page = run_report(cli, tmp_path, "sph", """kind = "hamiltonian"
        [params]
        g = 9.81
        [system]
        coordinates = ["theta", "phi"]
        L = "(theta_dot**2 + sin(theta)**2*phi_dot**2)/2 + g*cos(theta)"
        [initial]
        theta = 1.0
        phi = 0.0
        theta_dot = 0.0
        phi_dot = 1.0
        [run]
        t_end = 5.0
        study = false
        """)
    shown = visible_text(page)
    assert "**" not in shown and "\\" not in shown
    assert "momentum conjugate to θ" in shown


# ------------------------------------------------------------------ case prose (issue 31)
def subtitle(page: str) -> str:
    """The header's subtitle (describe(data)) as shown."""
    found = re.search(r'<p class="kind">(.*?)</p>', page, flags=re.S)
    assert found, "no subtitle"
    return " ".join(html.unescape(re.sub(r"<[^>]+>", " ", _scripts(found.group(1)))).split())


def test_steady_top_is_not_described_by_nutation(cli, tmp_path):
    page = run_report(cli, tmp_path, "steady", """kind = "heavy_top"
        preset = "steady_fast"
        [run]
        t_end = 5.0
        study = false
        """)
    shown = " ".join(visible_text(page).split())
    assert "no nutation band" in shown and "E' sits at the minimum of V'" in shown
    assert "This top is started at the fast rate" in shown
    assert "the axis draws loops" not in shown and "θ oscillates between" not in shown
    # φ̇ of the fast root, (I3ω3 + √(I3²ω3² − 4 I1 Mgl cos θ0))/(2 I1 cos θ0) with the
    # preset's I1 = 1, I3 = 0.5, Mgl = 1, ω3 = 6, θ0 = 1: (3 + √(9 − 4 cos 1))/(2 cos 1)
    assert re.search(r"steady precession at θ₀ = 57\.3°, φ̇ = 5\.196 rad/s \(the fast root",
                     subtitle(page))


@pytest.mark.parametrize("preset,side,words", [
    ("sleeping_stable", "above", "so its tilt stays of the order of the initial"),
    ("sleeping_unstable", "below", "so its tilt grows, initially at")])
def test_sleeping_top_prose_matches_its_side(cli, tmp_path, preset, side, words):
    page = run_report(cli, tmp_path, preset, f"""kind = "heavy_top"
        preset = "{preset}"
        [run]
        study = false
        """)
    shown = " ".join(visible_text(page).split())
    assert words in shown
    assert f"{side} its sleeping threshold 4 rad/s" in subtitle(page)  # 2√(I1 Mgl)/I3 = 4
    other = "below" if side == "above" else "above"
    assert f"{other} it, so its" not in shown


def test_escaping_kepler_orbit_is_not_described_as_bound(cli, tmp_path):
    page = run_report(cli, tmp_path, "escape", UNTITLED["central_force"].replace(
        "vy = 0.6", "vy = 1.5") + "\n        study = false\n")
    shown = " ".join(visible_text(page).split())
    # E = 1/16 > 0, e = 1.25 (test_default_titles_follow_the_case): a hyperbola
    assert "the orbit is a hyperbola (e = 1.25)" in shown and "single turning point" in shown
    assert "oscillates between the turning points" not in shown
    assert "closes on itself" not in shown
    assert subtitle(page).startswith("An escaping orbit in V = −k/r, a hyperbola with e = 1.25")


@pytest.mark.parametrize("theta,theta_dot,expect,absent", [
    (0.2, 0.0, "At this amplitude the two nearly agree", "runs ahead"),
    (0.0, 7.0, "goes over the top", "This orbit lies inside it")])
def test_pendulum_prose_follows_its_motion(cli, tmp_path, theta, theta_dot, expect, absent):
    text = UNTITLED["pendulum"].replace("theta = 2.5", f"theta = {theta}\n        "
                                        f"theta_dot = {theta_dot}")
    page = run_report(cli, tmp_path, "pend", text + "\n        study = false\n")
    shown = " ".join(visible_text(page).split())
    assert expect in shown and absent not in shown
    if theta_dot:
        assert subtitle(page).startswith("A pendulum rotating over the top")
    else:  # T/T0 − 1 ≈ θ0²/16 = 0.0025 (the first term of 2K(k)/π)
        assert "0.25 % longer than the small-angle 2π√(l/g)" in subtitle(page)


def test_figure_eight_prose_is_its_own(cli, tmp_path):
    page = run_report(cli, tmp_path, "eight", """kind = "three_body"
        preset = "figure_eight"
        [run]
        study = false
        """)
    shown = " ".join(visible_text(page).split())
    assert "Pythagorean" not in shown and "there are no close encounters" in shown
    assert subtitle(page).startswith(
        "Three equal masses on the figure-eight choreography, period 6.32591")


def test_planetary_orbit_prose(cli, tmp_path):
    """The ring round both centres is a planetary orbit, as the literature names it, and
    the prose cites where the names come from (Waalkens, Dullin & Richter 2004)."""
    page = run_report(cli, tmp_path, "planet", UNTITLED["two_center"]
                      + "\n        study = false\n")
    shown = " ".join(visible_text(page).split())
    assert "This orbit is a planetary orbit" in shown and "encircles both centres" in shown
    assert "This orbit is a satellite orbit" not in shown
    assert subtitle(page).startswith("A planetary orbit round both centres at E = ")
    assert "(Waalkens, Dullin & Richter 2004)" in shown
    assert "<b>Waalkens, Dullin &amp; Richter</b>" in page  # its entry in the sources list


def test_satellite_orbit_prose(cli, tmp_path):
    """The orbit about one centre is a satellite orbit (Waalkens, Dullin & Richter 2004)."""
    page = run_report(cli, tmp_path, "sat", """kind = "two_center"
        [params]
        mu = 1.0
        a = 1.0
        [initial]
        x = 1.6
        y = 0.0
        vx = 0.0
        vy = 1.2
        [run]
        t_end = 10.0
        study = false
        """)
    shown = " ".join(visible_text(page).split())
    assert "This orbit is a satellite orbit" in shown and "about the centre at (1, 0)" in shown
    assert "This orbit is a planetary orbit" not in shown
    assert subtitle(page).startswith("A satellite orbit about the centre at (1, 0) at E = ")


def test_symmetric_body_tables_say_marginal_in_words(cli, tmp_path):
    page = visible_text(run_report(cli, tmp_path, "sym", RIGID.format(
        I1=1.0, I2=1.0, I3=1.5, omega="[0.3, 0.0, 2.0]")))
    assert "— (marginal: symmetric body)" in page
    assert not re.search(r"wobble frequency: 0 ", page)
    assert "I_mid" not in page and "polhode (symmetric body)" in page


def test_a_family_subtitle_names_what_it_varies(cli, tmp_path):
    page = run_report(cli, tmp_path, "fam", UNTITLED["pendulum"] + """
        study = false
        [sweep]
        initial.theta = { start = 0.5, stop = 1.5, num = 3 }
        """)
    assert subtitle(page) == ("Plane pendulum: a family of 3 runs over initial angle from "
                              "the downward vertical, 0.5 to 1.5 rad")
