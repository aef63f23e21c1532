"""One rule for the numbers of a report (reportgen.scene.content): 6 significant figures,
2 for errors, never ``nan`` or a negative zero, exact 0 and 1 in matrices, and more figures
only in a deliberate value-against-reference comparison -- checked on the formatters and
on rendered reports."""

from __future__ import annotations

import html
import math
import re
from pathlib import Path

import numpy as np
import pytest

from reportgen.scene.content import (
    COMPARISON_DIGITS,
    DIGITS,
    NO_VALUE,
    comparison_digits,
    fmt,
    fmt_err,
    fmt_matrix,
    fmt_pair,
)

CONFIGS = Path(__file__).resolve().parent.parent / "configs"


def significant_figures(text: str) -> int:
    mantissa = text.lstrip("-").split("e")[0].replace(".", "").lstrip("0")
    return len(mantissa)


@pytest.mark.parametrize(("x", "text"), [
    (0.79999999999994, "0.8"),          # float noise is gone
    (1 / 3, "0.333333"),
    (123456.7, "123457"),
    (1234567.0, "1.23457e6"),
    (999999.7, "1e6"),                  # rounding carries into the exponent
    (0.00123456789, "0.00123457"),
    (0.00099999999, "0.001"),
    (2.5e-5, "2.5e-5"),
    (-0.25, "-0.25"),
    (100.0, "100"),
    (np.float64(6.283185307179586), "6.28319"),
    (7, "7"), (np.int64(12345678), "12345678"),  # integers whole
])
def test_six_significant_figures(x, text):
    assert fmt(x) == text


def test_the_text_is_the_number_to_six_figures():
    rng = np.random.default_rng(31)
    for x in rng.standard_normal(2000) * 10.0 ** rng.integers(-12, 12, 2000):
        text = fmt(float(x))
        assert significant_figures(text) <= DIGITS, text
        assert float(text) == pytest.approx(x, rel=5e-6), text


@pytest.mark.parametrize("zero", [0.0, -0.0, np.float64(-0.0), np.float32(-0.0)])
def test_never_a_negative_zero(zero):
    assert fmt(zero) == "0" and fmt_err(zero) == "0" and fmt(zero, 2) == "0"
    assert fmt_matrix([[zero]]) == [["0"]]


def test_not_a_number_is_a_dash_and_infinity_a_symbol():
    assert fmt(math.nan) == NO_VALUE == fmt_err(np.nan) == "—"
    assert fmt(math.inf) == "∞" and fmt(-math.inf) == "-∞"


@pytest.mark.parametrize(("x", "text"), [
    (1.234e-13, "1.2e-13"), (8.96e-13, "9e-13"), (0.0456, "0.046"), (0.5, "0.5"),
    (3.3e-12, "3.3e-12"), (0.0, "0"),
])
def test_errors_two_significant_figures(x, text):
    assert fmt_err(x) == text


def test_a_comparison_shows_the_figure_where_value_and_reference_differ():
    # equal to 7 figures, different at the 8th: shown to the 9th
    value, reference = fmt_pair(1.2345678, 1.2345679)
    assert (value, reference) == ("1.2345678", "1.2345679")
    assert fmt(1.2345678) == fmt(1.2345679)  # 6 figures would hide it
    assert fmt(1.2345678, against=1.2345679) == value
    # equal to more figures than a comparison prints: the usual 6 (the table's relative
    # error column tells that agreement), never 15 bare digits
    assert fmt_pair(0.69999999999963, 0.7) == ("0.7", "0.7")
    assert fmt_pair(245408173649620.0, 245408173649620.06) == ("2.45408e14", "2.45408e14")
    assert comparison_digits(1 / 3, 1 / 3 + 2e-12) == DIGITS
    # equal values: the usual 6 figures
    assert fmt_pair(math.pi, math.pi) == ("3.14159", "3.14159")
    assert fmt_pair(1.0, 1.0 + 2.0**-52) == ("1", "1")
    # at least the usual figures when they differ early
    assert fmt_pair(2.0, 3.0) == ("2", "3") and comparison_digits(2.0, 3.0) == DIGITS
    assert COMPARISON_DIGITS == 10


def test_a_matrix_shows_exact_zeros_and_ones():
    c, s = math.cos(math.pi / 2), math.sin(math.pi / 2)   # 6.1e-17, 1.0
    rotation = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 0.9999999999999998]]
    assert fmt_matrix(rotation) == [["0", "-1", "0"], ["1", "0", "0"], ["0", "0", "1"]]
    assert fmt_matrix([-1e-17, 1.0000000000000002, 0.5]) == [["0", "1", "0.5"]]
    # tiny entries are kept where the whole matrix is tiny
    assert fmt_matrix(1e-20 * np.eye(2)) == [["1e-20", "0"], ["0", "1e-20"]]
    # a value that is not round-off of 0 or 1 is printed as such
    assert fmt_matrix([[1e-9, 1 - 1e-9]]) == [["1e-9", "1"]]      # 1 - 1e-9 to 6 figures
    assert fmt_matrix([[1e-9, 1 - 1e-9]], digits=12) == [["1e-9", "0.999999999"]]


# ----------------------------------------------------------------- rendered reports
NUMBER = re.compile(r"(?<![\w.^/])-?\d+(?:\.\d+)?(?:e-?\d+)?(?![\w.])")


def _visible_text(page: str) -> str:
    """The report's text without the scene's TOML, figures, equations and the headline
    checks table (the deliberate value-against-reference comparison)."""
    page = re.sub(r"<pre class=\"config\">.*?</pre>", " ", page, flags=re.S)
    page = re.sub(r"<svg.*?</svg>|<img[^>]*>", " ", page, flags=re.S)
    page = re.sub(r"<tr><th>quantity</th><th>computed</th>.*?</table>", " ", page, flags=re.S)
    page = re.sub(r"<footer>.*?</footer>|<head>.*?</head>", " ", page, flags=re.S)
    return html.unescape(re.sub(r"<[^>]+>", " ", page))


@pytest.mark.parametrize("scene", ["heavy_top_steady_fast", "kepler_e07"])
def test_rendered_reports_follow_the_rule(scene, tmp_path):
    from reportgen.pipeline.stages import run_scene

    outcome = run_scene(str(CONFIGS / f"{scene}.toml"), str(tmp_path), formats=("html",))
    assert outcome.ok, outcome.message
    text = _visible_text((tmp_path / scene / "report.html").read_text(encoding="utf-8"))
    words = set(re.findall(r"[^\s,;:()]+", text))
    assert not words & {"nan", "NaN", "-0", "−0", "inf"}, words & {"nan", "NaN", "-0", "inf"}
    long = [n for n in NUMBER.findall(text) if "." in n and significant_figures(n) > DIGITS]
    assert not long, long[:10]


def test_steady_precession_leaves_out_what_it_cannot_measure(tmp_path):
    """A steady precession has no nutation: no "measured" column of NaN, and the caption
    says so."""
    from reportgen.pipeline.stages import run_scene

    scene = "heavy_top_steady_fast"
    assert run_scene(str(CONFIGS / f"{scene}.toml"), str(tmp_path), formats=("html",)).ok
    page = (tmp_path / scene / "report.html").read_text(encoding="utf-8")
    table = re.search(r"<table[^>]*>\s*<tr><th>quantity</th><th>closed form</th>.*?"
                      r"<p class=\"table-caption\">(.*?)</p>", page, flags=re.S)
    assert table is not None
    assert "<th>measured</th>" not in table.group(0)
    assert "nothing measured: no nutation" in table.group(1)


# ------------------------------------------------------------------ table cells
def _parts(cell) -> list[str]:
    """The whole (nowrap) parts of a rendered cell, and the free words between them."""
    return [p.strip() for p in re.split(r'<span class="nw">|</span>', str(cell)) if p.strip()]


@pytest.mark.parametrize(("text", "parts"), [
    ("rtol 1e-11: 3.9e-10 in 0.0944 ms", ["rtol 1e-11:", "3.9e-10 in 0.0944 ms"]),
    ("ω3 [rad/s]", ["ω3", "[rad/s]"]),
    ("0.540302, 0.459698", ["0.540302,", "0.459698"]),
    ("-0.317 / 0.678", ["-0.317 /", "0.678"]),
    ("(1, 0, -1)", ["(1, 0, -1)"]),                  # no break inside brackets
    ("[0.872665, 1.0472] rad", ["[0.872665, 1.0472] rad"]),
])
def test_a_cell_breaks_between_its_parts_never_inside_a_number(text, parts):
    from reportgen.rendering.report import table_cell

    assert _parts(table_cell(text)) == parts


def test_words_alone_wrap_freely():
    from reportgen.rendering.report import table_cell

    html_cell = str(table_cell("Gauss–Legendre 2-stage (numba, implicit)"))
    assert html_cell == '<span class="nw">Gauss–Legendre 2-stage</span> (numba, implicit)'
    assert str(table_cell("band error: roots / run")) == "band error: roots / run"
