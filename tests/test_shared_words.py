"""The shared report text says config keys and integrator names in words (issue 31's
gate, "config" rule): a check stored as "θ(t_end)" reads "θ(t = 4 s)", a sweep member
"(initial.theta = 3.09)" reads "(θ₀ = 3.09 rad)", the study's notes name no config key
and no method identifier, a swept key's figure label is its symbol and unit.  The archive
keeps the names it stored (tests and the gallery look checks up by them)."""

from __future__ import annotations

import html
import re

import pytest

from conftest import pendulum_text
from reportgen.archive.store import read_archive
from reportgen.kinds import get_kind
from reportgen.pipeline.stages import run_scene
from reportgen.rendering.gate import _figure_text_findings, _text_findings
from reportgen.rendering.report import prose_text
from reportgen.scene.gallery import check_headline
from reportgen.scene.report import method_words
from reportgen.scene.schema import config_quantity, quantity_of_description, symbol_text

NBSP = "\u00a0"


def _visible(report_html: str) -> str:
    """The report's text without the appended configuration, tags and entities, its
    sub- and superscripts as Unicode (θ<sub>0</sub> reads θ₀); no-break spaces kept."""
    body = report_html.split('<section id="config">')[0]
    body = re.sub(r"<style>.*?</style>|<svg.*?</svg>", " ", body, flags=re.S)
    body = re.sub(r"<(sub|sup)>([^<]*)</\1>",
                  lambda m: m.group(2).translate(_SCRIPT[m.group(1)]), body)
    return html.unescape(re.sub(r"<[^>]+>", " ", body))


_SCRIPT = {"sub": str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉"),
           "sup": str.maketrans("0123456789−", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")}


def _config_findings(text: str) -> list[str]:
    return [f for f in _text_findings(text, False, {"run", "initial", "params", "sweep"},
                                      {"t_end", "study_budget", "theta"})
            if f.startswith("config")]


@pytest.mark.parametrize("tex, text", [
    (r"\theta_0", "θ₀"), (r"\dot{\theta}_0", "θ̇₀"), (r"\dot{\varphi}_{0}", "φ̇₀"),
    (r"v_{x,0}", "vₓ,₀"), (r"\omega_{3}", "ω₃"), ("k^2", "k²"),
    (r"\langle\mathrm{d}\varphi/\mathrm{d}t\rangle", "⟨dφ/dt⟩"), ("y(0)", "y(0)"),
    # what Unicode has no sub/superscript for is not forced into plain text
    ("T_{exact}", None), (r"p_{\phi}(0)", None), (r"\frac{a}{b}", None)])
def test_tex_symbols_as_page_text(tex, text):
    assert symbol_text(tex) == text


def test_a_config_description_is_cut_to_its_quantity():
    # the heavy top's precession rate: a code quote and a note after the unit
    desc = "precession rate φ̇0 [rad/s] (or give `steady`)"
    assert quantity_of_description(desc) == ("precession rate φ̇0", "rad/s",
                                             r"\dot{\varphi}_{0}")
    assert quantity_of_description("spin ω3 = ψ̇ + φ̇ cos θ [rad/s]") == (
        "spin ω3", "rad/s", r"\omega_{3}")
    # a condition on the value is not part of the quantity; a list in brackets is no unit
    assert quantity_of_description("tilt from the vertical, 0 ≤ θ < π [rad]") == (
        "tilt from the vertical", "rad", "")
    assert quantity_of_description("[ω1, ω2, ω3] body-frame angular velocity [rad/s]")[1:] \
        == ("rad/s", "")
    # a lone Latin letter after a comma is a component, not a symbol
    assert quantity_of_description("relative velocity, x [m/s]") == (
        "relative velocity, x", "m/s", "")

    q = config_quantity(get_kind("heavy_top").Config, "initial.phi_dot")
    assert q.label() == r"$(\mathrm{d}\varphi/\mathrm{d}t)_{0}$ [rad/s]"
    assert q.text == "φ̇₀"
    assert _figure_text_findings([q.label()], "axes 1") == []


@pytest.mark.parametrize("name, words", [
    ("scipy_rk45", "scipy RK45"), ("scipy_radau", "scipy Radau"),
    ("scipy_lsoda", "scipy LSODA"), ("scipy_dop853", "scipy DOP853"),
    ("levi_civita", "Levi-Civita"), ("levi_civita_dop853", "Levi-Civita + DOP853"),
    ("dop853", "DOP853"), ("gauss6", "gauss6")])
def test_method_names_in_words(name, words):
    assert method_words(name) == words
    assert not _config_findings(f"the method {method_words(name)} ran")


def test_an_archive_path_in_prose_is_code_on_one_line():
    text = prose_text("All runs are in the archive's /study/error_vs_runtime. A/B stays.")
    assert '<code class="path">/study/error_vs_runtime</code>.' in text
    assert "A/B stays" in text and prose_text("<b>") == "&lt;b&gt;"


@pytest.fixture(scope="module")
def pendulum(tmp_path_factory):
    root = tmp_path_factory.mktemp("words")
    path = root / "swing.toml"
    path.write_text(pendulum_text(theta=0.4, t_end=4.0, samples=401, study="true",
                                  extra="study_budget = 0.3\n"))
    outcome = run_scene(str(path), str(root / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    return root / "out" / "swing"


def test_checks_at_the_end_of_the_run_are_said_in_words(pendulum):
    data = read_archive(pendulum / "run.h5")
    names = [c.quantity for c in data.checks]
    assert "θ(t_end)" in names  # the archive keeps the stored name
    text = _visible((pendulum / "report.html").read_text(encoding="utf-8"))
    assert f"θ(t{NBSP}={NBSP}4{NBSP}s)" in text
    assert "t_end" not in text
    scene = get_kind("pendulum")
    assert scene.check_words(data, "energy E(t_end)") == f"energy E(t{NBSP}={NBSP}4{NBSP}s)"
    assert scene.check_words(data, "|A| at t_end") == f"|A| at t{NBSP}={NBSP}4{NBSP}s"
    # a swept member's values, and a key left bare
    assert scene.check_words(data, "worst member (initial.theta = 3.09691)") == \
        "worst member (θ₀ = 3.097 rad)"
    assert scene.check_words(data, "set by initial.theta_dot") == \
        "set by initial angular velocity"
    assert scene.check_words(data, "run.h5 and np.pi stay") == "run.h5 and np.pi stay"
    data.checks = [c for c in data.checks if c.quantity == "θ(t_end)"]  # the card's check
    line = check_headline(data, words=lambda t: scene.check_words(data, t))
    assert line.replace(NBSP, " ").startswith("θ(t = 4 s) ")
    assert check_headline(data).startswith("θ(t = 4) ")  # no kind at hand: no unit


def test_the_study_notes_name_no_config_key_nor_method_identifier(pendulum):
    data = read_archive(pendulum / "run.h5")
    scene = get_kind("pendulum")
    data.study_attrs["over_budget"] = "scipy_rk45,scipy_radau"
    content = scene.section_error_vs_runtime(data)
    notes = " ".join(content.notes)
    assert "budget of 0.3 s" in notes
    assert "scipy RK45, scipy Radau." in notes
    for text in [*content.notes, content.tables[0].caption]:
        assert not _config_findings(text), text
    caption = content.tables[0].caption  # the archive's path is the colophon's, not here
    assert "/study" not in caption and "the archive's study table" in caption
    report = (pendulum / "report.html").read_text(encoding="utf-8")
    assert "study_budget" not in _visible(report) and "[run]" not in _visible(report)


def test_a_sweep_says_its_swept_key_by_symbol_and_unit(tmp_path):
    path = tmp_path / "family.toml"
    path.write_text(pendulum_text(t_end=3.0, samples=201, extra="""
        [sweep]
        initial.theta = { start = 0.5, stop = 3.0, num = 4 }
        store = 2
        """))
    outcome = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    text = _visible((tmp_path / "out" / "family" / "report.html").read_text(encoding="utf-8"))
    assert "4 (a grid of θ₀ from 0.5 to 3 rad)" in text
    assert "θ₀ = 3 rad" in text  # the kept members' table
    assert "(θ₀ = " in text  # the check of the worst member
    assert "initial.theta" not in text and "[sweep]" not in text
    assert not _config_findings(text)
