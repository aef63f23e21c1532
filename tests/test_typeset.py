"""The one typesetter (issue 41): minus signs, a × 10ⁿ, real subscripts, on pages and in
figures; and an axis's multiplier folded into its label."""

from __future__ import annotations

import io

import numpy as np
import pytest
from matplotlib.figure import Figure

from reportgen.rendering.gate import figure_findings
from reportgen.rendering.plots.finish import finish_figure
from reportgen.scene.typeset import (
    figure_text,
    html_text,
    plain_text,
    typeset_html,
    visible_text,
)


@pytest.mark.parametrize("text, html", [
    ("E = -0.34 J", "E = −0.34 J"),
    ("θ(T) = -0.1 rad", "θ(T) = −0.1 rad"),
    ("(-1, 0) and [-2.5]", "(−1, 0) and [−2.5]"),
    ("V = -k/r", "V = −k/r"),
    ("error 4.2e-15", "error 4.2\u00a0×\u00a010<sup>−15</sup>"),
    ("a 1e-6 tilt", "a 10<sup>−6</sup> tilt"),
    ("3.4E+07 m", "3.4\u00a0×\u00a010<sup>7</sup> m"),
    ("-2.5e-3", "−2.5\u00a0×\u00a010<sup>−3</sup>"),
    ("rtol=1e-12", "rtol 10<sup>−12</sup>"),
    ("I1 = I2", "I<sub>1</sub> = I<sub>2</sub>"),
    ("θ1, θ̇0 and ω3.", "θ<sub>1</sub>, θ̇<sub>0</sub> and ω<sub>3</sub>."),
    ("2π/ω0", "2π/ω<sub>0</sub>"),
    ("r12 and K11", "r<sub>12</sub> and K<sub>11</sub>"),
    ("θ₀ = 1 rad, s⁻¹, r¹·²", "θ<sub>0</sub> = 1 rad, s<sup>−1</sup>, r<sup>1·2</sup>"),
    ("V_eff and θ_exact", "V<sub>eff</sub> and θ<sub>exact</sub>"),
    ("r^0.4 and r^{-2}", "r<sup>0.4</sup> and r<sup>−2</sup>"),
    ("a < b & c", "a &lt; b &amp; c"),
])
def test_text_is_typeset(text, html):
    assert str(html_text(text)) == html


@pytest.mark.parametrize("text", [
    "RK45, DOP853 and H2O", "a well-known x-axis", "pp. 119-131 on 2026-12-07",
    "Fig. 4.3a", "x86_64", "Gauss–Legendre 6", "3n − 6 modes", "member 12",
])
def test_what_is_not_a_number_or_a_symbol_is_left_alone(text):
    assert str(html_text(text)) == text


def test_plain_and_figure_forms():
    assert plain_text("error 4.2e-15, I1 = -3") == "error 4.2\u00a0×\u00a010⁻¹⁵, I₁ = −3"
    assert figure_text("rtol 1e-10, $\\theta_1$ and u2") == \
        "rtol 10$^{-10}$, $\\theta_1$ and u$_{2}$"
    assert figure_text("cost $5") == "cost $5"  # a lone dollar is text


def test_a_page_is_typeset_outside_code_svg_and_style():
    page = ("<html><head><title>θ0 = -1</title><style>p{margin:-1em}</style></head><body>"
            "<p>E = -0.34 J, 1e-9</p><code>t_end = -1e-3</code><pre>x = -1</pre>"
            "<svg><text>-1e-3</text></svg><p title='-1'>I1</p></body></html>")
    out = typeset_html(page)
    assert "<title>θ₀ = −1</title>" in out
    assert "<p>E = −0.34 J, 10<sup>−9</sup></p>" in out
    for kept in ("p{margin:-1em}", "<code>t_end = -1e-3</code>", "<pre>x = -1</pre>",
                 "<text>-1e-3</text>", "title='-1'"):
        assert kept in out
    assert "<p title='-1'>I<sub>1</sub></p>" in out
    assert typeset_html(out) == out  # typesetting twice changes nothing


def test_visible_text_reads_sub_and_superscripts():
    page = ("<body><p>I<sub>1</sub> = 2 × 10<sup>−15</sup></p>"
            "<section id=\"config\"><pre>t_end = 1</pre></section></body>")
    assert visible_text(page) == "I₁ = 2 × 10⁻¹⁵"


def _saved(fig) -> str:
    buf = io.BytesIO()
    fig.savefig(buf, format="svg")
    return buf.getvalue().decode()


def test_an_axis_multiplier_becomes_a_scaled_label():
    fig = Figure(figsize=(5, 3), layout="constrained")
    ax = fig.add_subplot()
    t = np.linspace(0, 1, 50)
    ax.plot(t, 3e-11 * np.sin(6 * t), label="drift at rtol 1e-12")
    ax.set(xlabel="time t [s]", ylabel="energy drift [J]")
    ax.legend(loc="upper right")
    finish_figure(fig)
    assert ax.get_ylabel() == "energy drift [$10^{-11}$ J]"
    assert ax.get_legend().get_texts()[0].get_text() == "drift at rtol 10$^{-12}$"
    svg = _saved(fig)
    assert "1e−11" not in svg and "1e-11" not in svg
    assert not ax.yaxis.get_offset_text().get_visible()
    assert figure_findings(fig) == []
    finish_figure(fig)  # twice: nothing more
    assert ax.get_ylabel() == "energy drift [$10^{-11}$ J]"


def test_an_offset_becomes_full_tick_values_and_a_dimensionless_label_a_bracket():
    fig = Figure(figsize=(5, 3), layout="constrained")
    ax, bx = fig.subplots(1, 2)
    t = np.linspace(0, 1, 50)
    ax.plot(t, 1.0 + 1e-7 * t)
    ax.set(xlabel="t [s]", ylabel="H (dimensionless)")
    bx.plot(t, 2e-9 * t)
    bx.set(xlabel="t [s]", ylabel="relative drift (dimensionless)")
    finish_figure(fig)
    fig.canvas.draw() if hasattr(fig.canvas, "draw") else None
    _saved(fig)
    assert ax.yaxis.get_major_formatter().offset == 0
    assert ax.yaxis.get_offset_text().get_text() in ("", None) or \
        not ax.yaxis.get_offset_text().get_visible()
    assert bx.get_ylabel() == "relative drift [$10^{-9}$]"
