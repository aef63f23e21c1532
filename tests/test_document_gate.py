"""The document gate (issue 31): what a reader must never meet in a report.

Each rule of :mod:`reportgen.rendering.gate` is shown to fire on a small figure or page
seeded with exactly that defect, and to stay quiet on its clean twin.  Then every shipped
report (study on, PDF on: the study tables are the widest) and a few generated ones must
leave an empty ``gate.json``.
"""

from __future__ import annotations

import io
import json
import textwrap
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

from conftest import pendulum_text
from reportgen.pipeline.stages import run_scene
from reportgen.rendering.gate import GATE_FILE, figure_findings, page_findings


# ------------------------------------------------------------------ helpers
def drawn(fig) -> list[str]:
    """The figure's findings once saved, as the report saves it."""
    fig.savefig(io.BytesIO(), format="svg")
    return figure_findings(fig)


def figure(**kw):
    fig = Figure(figsize=(6, 4), layout="constrained", **kw)
    return fig, fig.add_subplot()


def rules(findings: list[str]) -> set[str]:
    """The rule names in findings ("... : rule: ...")."""
    names = {"series", "legend", "label", "limits", "text", "overflow", "number", "config",
             "python", "tex", "fill", "type", "provenance"}
    return {part.strip() for f in findings for part in f.split(":") if part.strip() in names}


PAGE_CSS = """
@page { size: A4; margin: 18mm 16mm 20mm 16mm; }
body { font-family: "DejaVu Sans", sans-serif; font-size: 11pt; }
table { border-collapse: collapse; } td { border: 1px solid #999; }
"""


def laid_out(body: str, config: str = 'kind = "pendulum"\n[initial]\ntheta = 0.2\n'):
    """A WeasyPrint document of ``body`` followed by a configuration section."""
    import weasyprint

    html = (f"<html><head><style>{PAGE_CSS}</style></head><body>{body}"
            f"<section id='config'><h2>Configuration</h2><pre class='config'>{config}</pre>"
            "</section></body></html>")
    return weasyprint.HTML(string=html).render()


def paragraphs(n: int, word: str = "pendulum") -> str:
    return "".join(f"<p>The {word} swings to and fro, line {i} of the story.</p>"
                   for i in range(n))


# ------------------------------------------------------------------ figure rules
def test_series_that_look_alike_are_found():
    t = np.linspace(0, 1, 50)
    fig, ax = figure()
    ax.plot(t, t, color="C0", label="integrated")
    ax.plot(t, t**2, color="C0", label="exact")
    ax.set(xlabel="time t [s]", ylabel="θ [rad]", ylim=(-2, 2))
    ax.legend(loc="lower right")
    found = drawn(fig)
    assert rules(found) == {"series"}, found
    assert "'integrated' and 'exact'" in found[0]

    fig, ax = figure()
    ax.plot(t, t, color="C0", label="integrated")
    ax.plot(t, t**2, color="C0", ls="--", label="exact")  # a line style tells them apart
    ax.plot(t, t**3, color="C0", ls="none", marker="o", label="samples")
    ax.set(xlabel="time t [s]", ylabel="θ [rad]", ylim=(-2, 2))
    ax.legend(loc="lower right")
    assert drawn(fig) == []


def test_a_legend_over_the_data_is_found():
    x = np.linspace(0, 1, 200)
    fig, ax = figure()
    ax.plot(x, 0.5 + 0 * x, label="level")
    ax.plot(x, 0.1 + 0 * x, label="floor")
    ax.set(xlabel="x [m]", ylabel="y [m]", ylim=(0, 1))
    ax.legend(loc="center")
    found = drawn(fig)
    assert rules(found) == {"legend"}, found
    assert "'level'" in found[0] and "'floor'" not in found[0]

    fig, ax = figure()  # the same lines, the legend in the empty top right
    ax.plot(x, 0.5 * x, label="level")
    ax.plot(x, 0.1 + 0 * x, label="floor")
    ax.set(xlabel="x [m]", ylabel="y [m]", ylim=(0, 1))
    ax.legend(loc="upper right")
    assert drawn(fig) == []


def test_a_legend_over_scatter_points_is_found():
    rng = np.random.default_rng(3)
    fig, ax = figure()
    ax.scatter(rng.uniform(0, 1, 400), rng.uniform(0, 1, 400), s=4, label="section")
    ax.set(xlabel="q [m]", ylabel="p [kg m/s]", xlim=(0, 1), ylim=(0, 1))
    ax.legend(loc="upper left")
    assert rules(drawn(fig)) == {"legend"}

    fig, ax = figure()
    ax.scatter(rng.uniform(0, 1, 400), rng.uniform(0, 1, 400), s=4, label="section")
    ax.set(xlabel="q [m]", ylabel="p [kg m/s]", xlim=(0, 1), ylim=(0, 1))
    fig.legend(loc="outside lower center")  # below the axes: covers nothing
    assert drawn(fig) == []


@pytest.mark.parametrize("label", ["", "θ", "angle theta", "[rad]"])
def test_an_axis_without_a_symbol_and_unit_is_found(label):
    fig, ax = figure()
    ax.plot([0, 1], [0, 1])
    ax.set(xlabel="time t [s]", ylabel=label)
    found = drawn(fig)
    assert rules(found) == {"label"} and "y axis" in found[0], found


def test_labelled_axes_pass_and_hidden_or_word_axes_are_exempt():
    fig = Figure(figsize=(6, 5), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    top.plot([0, 1], [0, 1])
    top.set_ylabel("ΔE/E₀ (dimensionless)")
    bottom.plot([0, 1], [1, 0])
    bottom.set(xlabel="time t [s]", ylabel="ω [rad/s]")
    top.label_outer()  # its x tick labels hidden: the x label is the bottom one's
    assert drawn(fig) == []

    fig, ax = figure()  # categories on y, a picture with its axes off
    ax.barh(["DOP853", "Radau", "leapfrog"], [3, 2, 1])
    ax.set_xlabel("wall time t [s]")
    pic = fig.add_axes((0.7, 0.7, 0.2, 0.2))
    pic.plot([0, 1], [0, 1])
    pic.axis("off")
    assert drawn(fig) == []


@pytest.mark.parametrize("label", ["", "energy E"])
def test_a_colour_bar_needs_its_unit(label):
    def with_bar(label):
        fig, ax = figure()
        image = ax.imshow(np.arange(12.0).reshape(3, 4), extent=(0, 4, 0, 3))
        ax.set(xlabel="x [m]", ylabel="y [m]")
        fig.colorbar(image, ax=ax, label=label)
        return drawn(fig)

    found = with_bar(label)
    assert rules(found) == {"label"} and "colour bar" in found[0], found
    assert with_bar("energy E [J]") == []


def test_an_annotated_point_outside_the_limits_is_found():
    fig, ax = figure()
    ax.plot([0, 1], [0, 1])
    ax.set(xlabel="x [m]", ylabel="y [m]", xlim=(0, 1), ylim=(0, 1))
    ax.annotate("turning point", xy=(1.5, 0.5), xytext=(0.5, 0.5))
    found = drawn(fig)
    assert rules(found) == {"limits"} and "turning point" in found[0], found

    fig, ax = figure()
    ax.plot([0, 1], [0, 1])
    ax.plot([3.0], [0.5], "o", label="pericentre")  # a highlight marker off the axes
    ax.set(xlabel="x [m]", ylabel="y [m]", xlim=(0, 1), ylim=(0, 1))
    assert rules(drawn(fig)) == {"limits"}

    fig, ax = figure()
    ax.plot([0, 1], [0, 1])
    ax.plot([1.0], [1.0], "o")  # on the corner: inside
    ax.annotate("turning point", xy=(0.5, 0.5), xytext=(0.2, 0.8),
                arrowprops={"arrowstyle": "->"})
    ax.set(xlabel="x [m]", ylabel="y [m]", xlim=(0, 1), ylim=(0, 1))
    assert drawn(fig) == []


def test_guide_lines_and_unlabelled_families_are_not_series():
    """axhline/axvline are guides, not data under a legend; an unlabelled family of
    curves in one colour is one series."""
    fig, ax = figure()
    x = np.linspace(0, 1, 100)
    for k in range(5):
        ax.plot(x, 0.1 * k * x, color="0.5", lw=0.8)
    ax.plot(x, 0.05 + 0 * x, color="C1", label="separatrix")
    ax.axhline(0.85, color="k", lw=0.5)
    ax.set(xlabel="q [rad]", ylabel="p [rad/s]", ylim=(0, 1))
    ax.legend(loc="upper left")
    assert drawn(fig) == []


def test_labels_past_the_figure_or_over_each_other_are_found():
    fig = Figure(figsize=(6, 3), layout="constrained")
    left, right = fig.subplots(1, 2)
    for ax in (left, right):
        ax.plot([0, 1], [0, 1])
        ax.set(ylabel="y [m]", xlabel="initial precession rate φ̇₀ [rad/s] of each member "
                                      "of the family (dimensionless)")
    found = drawn(fig)
    assert rules(found) == {"text"} and "overlaps" in " ".join(found), found

    fig = Figure(figsize=(6, 3), layout="constrained")
    for ax in fig.subplots(1, 2):
        ax.plot([0, 1], [0, 1])
        ax.set(ylabel="y [m]", xlabel="precession rate φ̇₀ [rad/s]")
    assert drawn(fig) == []


@pytest.mark.parametrize("label, rule", [
    ("θ(t_end) [rad]", "config"),
    ("|r − r_Kepler| [m]", "tex"),
    ("energy E**2 [J²]", "python"),
    ("rate (or give `steady`) [rad/s]", "config"),
])
def test_words_in_a_figure_are_held_to_the_text_rules(label, rule):
    fig, ax = figure()
    ax.plot([0, 1], [0, 1], label=label)
    ax.plot([0, 1], [1, 1.5], label="$\\theta_{1}$ [rad]")  # mathtext is typeset: fine
    ax.set(xlabel="time t [s]", ylabel="θ [rad]", ylim=(0, 3))
    ax.legend(loc="upper left")
    found = drawn(fig)
    assert rules(found) == {rule}, found


# ------------------------------------------------------------------ page rules
def test_a_table_wider_than_the_page_is_found():
    wide = "<table><tr>" + "".join(f"<td>1.23456789012{i:02d}</td>" for i in range(14)) \
        + "</tr></table>"
    found = page_findings(laid_out("<p>Numbers.</p>" + wide))
    assert rules(found) == {"overflow"}, found
    assert "1.2345678901200" in found[0]
    narrow = "<table><tr>" + "".join(f"<td>{i}.5</td>" for i in range(14)) + "</tr></table>"
    assert page_findings(laid_out("<p>Numbers.</p>" + narrow)) == []


def test_a_long_unbreakable_word_is_found():
    found = page_findings(laid_out("<p>" + "x" * 150 + "</p>"))
    assert rules(found) == {"overflow"}, found


@pytest.mark.parametrize("cell, also", [
    ("nan", ()), ("NaN", ()), ("inf", ()), ("−inf", ()), ("−0", ()), ("−0.000", ()),
    ("-0.000", ("type",)), ("−0.0e+00", ("type",)),  # a hyphen, E-notation: type findings too
])
def test_a_number_that_is_not_one_is_found(cell, also):
    found = page_findings(laid_out(f"<table><tr><td>period T [s]</td><td>{cell}</td></tr>"
                                   "</table>"))
    assert rules(found) == {"number", *also}, found


@pytest.mark.parametrize("text, rule", [
    ("Fig. 2: the angle for initial.theta = 0.2 rad.", "config"),
    ("The study budget is set by [run] study.", "config"),
    ("The molecule's [[atoms]] list.", "config"),
    ("The angle θ(t_end) at the end.", "config"),
    ("The energy grows like theta**2 for small angles.", "python"),
    ("Its value is 2*omega at resonance.", "python"),
    ("We compare np.sqrt of the energy.", "python"),
    ("Both agree when E == 0.", "python"),
    ("The angle \\theta_{1} of the first pendulum.", "tex"),
    ("The potential V = −k/r^2 of gravity.", "tex"),
    ("The angular momentum L_z is conserved.", "tex"),
    ("The energy $E = T + V$ is conserved.", "tex"),
])
def test_config_python_and_tex_in_prose_are_found(text, rule):
    found = page_findings(laid_out(f"<p>{text}</p>"))
    assert rules(found) == {rule}, found


def test_legitimate_prose_passes():
    body = ("<h1>Heavy top — Fig. 4.3 as printed</h1>"
            "<p class='kind'>The archive <code>run.h5</code>; <code>reportgen cache info</code>."
            "</p>"
            "<p>Kepler orbit with e = 0.95, period 10.25 s, θ₀ = −0.5 rad, ω² = g/l; "
            "see Fig. 4.3 and (1.19), i.e. the small-angle limit, e.g. at t = 0 s; "
            "errors 1.2 × 10<sup>−13</sup> (rtol 10<sup>−12</sup>); DOP853, RK45 and "
            "scipy's Radau; 3 × 10⁻⁵; I<sub>1</sub> = I<sub>3</sub>, θ<sub>0</sub>, "
            "r<sub>12</sub>; a well-known x-axis; pp. 119-131; H2O.</p>"
            "<table><tr><th>quantity</th><th>value [rad/s]</th></tr>"
            "<tr><td>ω₁ at t = 0</td><td>−0.25</td></tr>"
            "<tr><td>date</td><td>2026-01-05</td></tr></table>")
    assert page_findings(laid_out(body)) == []


@pytest.mark.parametrize("text, rule", [
    ("The energy E = -0.34 J at the start.", "type"),
    ("The final angle θ(T) = (-0.1) rad.", "type"),
    ("An error of 4.2e-15 against the closed form.", "type"),
    ("A tilt of 1E-6 rad.", "type"),
    ("A symmetric body, I1 = I2, spins.", "type"),
    ("The angle θ1 of the first rod.", "type"),
    ("The masses m1 and m2 in kg.", "type"),
    ("The spin I3ω3 of the top.", "type"),  # a product of subscripted symbols
    ("Below ω3² = 4I1Mgl/I3² it tilts.", "type"),
    ("The trajectory is in /runs/main of the archive.", "provenance"),
    ("Integrated at rtol=0.5 with DOP853.", "provenance"),
    ("The peers call <code>solve_ivp</code> here.", "config"),
    ("Scene pendulum_large of the pack.", "config"),
])
def test_typography_and_provenance_in_the_body_are_found(text, rule):
    found = page_findings(laid_out(f"<p>{text}</p>"))
    assert rules(found) == {rule}, found


def test_the_configuration_section_is_exempt():
    config = "[initial]\ntheta = 0.2   # a**2 \\theta_{1} nan -0\n[run]\nt_end = 1.0\n"
    assert page_findings(laid_out("<p>The report.</p>", config=config)) == []
    found = page_findings(laid_out("<p>Runs until <code>t_end</code>.</p>", config=config))
    assert rules(found) == {"config"}, found  # a config key even in a code span


def test_an_almost_empty_page_is_found():
    page_break = "<div style='break-before: page'></div>"
    short = paragraphs(60) + page_break + paragraphs(3) + page_break + paragraphs(60)
    found = page_findings(laid_out(short))
    assert rules(found) == {"fill"} and found[0].startswith("page 3:"), found
    full = paragraphs(60) + page_break + paragraphs(30) + page_break + paragraphs(25)
    assert page_findings(laid_out(full)) == []
    # the last page too: a footer or two lines of the configuration alone is a finding
    found = page_findings(laid_out(paragraphs(60) + page_break + paragraphs(2)))
    assert rules(found) == {"fill"}, found


# ------------------------------------------------------------------ the product
def test_the_pdf_worker_returns_the_page_findings(tmp_path):
    from reportgen.rendering.pdf import PdfWorker

    worker = PdfWorker()
    try:
        found = worker.write_pdf("<html><body><p>period nan s</p></body></html>",
                                 tmp_path / "x.pdf", tmp_path)
    finally:
        worker.close()
    assert (tmp_path / "x.pdf").read_bytes().startswith(b"%PDF")
    assert rules(found) == {"number"}, found


def test_a_report_writes_its_gate_file(tmp_path, write_config):
    """gate.json holds the figures' findings (kept in figures/sections.json) and the
    pages'; a defect seeded in the title reaches it."""
    config = write_config("pend", pendulum_text(title="Pendulum with initial.theta = 1",
                                                t_end=5.0, samples=201))
    outcome = run_scene(str(config), str(tmp_path / "out"), force=True,
                        formats=("html", "pdf"))
    assert outcome.status == "ok", outcome.message
    folder = tmp_path / "out" / "pend"
    findings = json.loads((folder / GATE_FILE).read_text(encoding="utf-8"))
    assert any("config: key 'initial.theta'" in f for f in findings), findings
    manifest = json.loads((folder / "figures" / "sections.json").read_text(encoding="utf-8"))
    assert all(isinstance(fig["gate"], list)
               for s in manifest["sections"] for fig in s["figures"])


def gate_of(folder: Path) -> list[str]:
    return json.loads((folder / GATE_FILE).read_text(encoding="utf-8"))


# Every shipped report and a varied config of every kind: tests/test_shipped_pages.py.
GENERATED = {
    "pendulum_long_title": pendulum_text(
        title="A pendulum released far from its lowest point, watched for long enough to "
              "see the period lengthen against the small-angle estimate (θ0 = 2.5 rad)",
        theta=2.5, t_end=20.0, samples=2001, study="true"),
    "bent_molecule": textwrap.dedent("""
        kind = "normal_modes"
        title = "A bent symmetric triatomic written from scratch"
        [[atoms]]
        mass = 16.0
        position = [-0.76, 0.59, 0.0]
        [[atoms]]
        mass = 32.0
        position = [0.0, 0.0, 0.0]
        [[atoms]]
        mass = 16.0
        position = [0.76, 0.59, 0.0]
        [[bonds]]
        atoms = [0, 1]
        k = 10.0
        [[bonds]]
        atoms = [1, 2]
        k = 10.0
        [[angles]]
        atoms = [0, 1, 2]
        k = 0.8
        """),
}


@pytest.mark.parametrize("name", sorted(GENERATED))
def test_generated_reports_pass_the_gate(name, tmp_path):
    config = tmp_path / f"{name}.toml"
    config.write_text(GENERATED[name].lstrip(), encoding="utf-8")
    outcome = run_scene(str(config), str(tmp_path / "out"), formats=("html", "pdf"))
    assert outcome.status in ("ok", "unstable"), outcome.message
    findings = gate_of(tmp_path / "out" / name)
    assert findings == [], f"{name}: {len(findings)} findings\n" + "\n".join(findings)


def test_a_sweep_with_an_odd_count_of_results_labels_its_lowest_visible_panels():
    # five results on a 3 x 2 grid: the sixth panel is hidden, so the second column's x
    # label goes on its second panel, with its tick labels (not on the hidden one)
    from reportgen.rendering.plots.common import sweep_results

    x = np.linspace(1.0, 2.0, 30)
    analysis = {f"r{k}": x ** k for k in range(1, 6)}
    fig = sweep_results({"initial.x": x}, analysis, np.ones(x.size, bool),
                        keys={"initial.x": ("$x_0$", "m")},
                        ylabels={f"r{k}": f"result {k} [m]" for k in range(1, 6)})
    drawn(fig)
    assert figure_findings(fig) == []
    shown = [ax for ax in fig.axes if ax.get_visible()]
    labelled = [ax for ax in shown if ax.get_xlabel()]
    assert len(shown) == 5 and len(labelled) == 2
    for ax in labelled:
        assert any(t.get_visible() and t.get_text() for t in ax.get_xticklabels())
