"""Typeset equations: mathtext drawn as inline SVG (no TeX installation), one element with
class="eq" per equation, in the HTML and (as images on the baseline) in the PDF."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from reportgen.rendering import equations
from reportgen.rendering.pdf import prepare_html

KINDS = Path(__file__).resolve().parent.parent / "reportgen" / "kinds"
FILTER = re.compile(r"\{% filter eq %\}(.*?)\{% endfilter", re.S)


def _template_equations() -> list[tuple[str, str]]:
    out = []
    for path in sorted(KINDS.glob("*/template.html.j2")):
        out.extend((path.parent.name, tex) for tex in FILTER.findall(path.read_text()))
    return out


def test_no_equation_left_as_plain_text():
    """Every displayed equation of the kinds' prose goes through the eq filter."""
    for path in sorted(KINDS.glob("*/template.html.j2")):
        assert '<span class="eq">' not in path.read_text(), f"{path.parent.name}: untypeset equation"
    assert len(_template_equations()) >= 45


@pytest.mark.parametrize("kind, tex", _template_equations())
def test_every_template_equation_draws(kind, tex, monkeypatch):
    monkeypatch.setenv("REPORTGEN_NO_EQUATION_CACHE", "1")
    svg = equations._draw(tex, equations.EQUATION_POINTS)
    assert svg.startswith("<svg") and svg.endswith("</svg>")
    assert "<text" not in svg  # glyphs as paths: no font needed to show it
    assert re.search(r'width="[\d.]+pt" height="[\d.]+pt"', svg)


def test_baseline_size_and_determinism(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    equations.equation_svg.cache_clear()
    low = equations._draw(r"x", 12.0)
    deep = equations._draw(r"\frac{a}{b}", 12.0)
    drop = [float(re.search(r"vertical-align: (-[\d.]+)pt", s).group(1)) for s in (low, deep)]
    height = [float(re.search(r'height="([\d.]+)pt"', s).group(1)) for s in (low, deep)]
    assert drop[1] < drop[0] < 0  # a fraction reaches further below the baseline
    assert height[1] > height[0] > 5  # and is taller; 12 pt 'x' is some 5-8 pt of ink + pad
    assert equations._draw(r"\frac{a}{b}", 12.0) == deep  # same bytes every time
    # ids are unique to the equation, so many on one page do not collide
    ids = re.findall(r'id="([^"]+)"', deep)
    assert ids and all(i.startswith("eq") for i in ids)
    assert set(ids).isdisjoint(re.findall(r'id="([^"]+)"', low))


def test_cached_on_disk_by_content(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    monkeypatch.delenv("REPORTGEN_NO_EQUATION_CACHE", raising=False)
    equations.equation_svg.cache_clear()
    first = equations.equation_svg(r"E = mc^2")
    files = list((tmp_path / "reportgen" / "equations").glob("*.svg"))
    assert len(files) == 1 and files[0].read_text() == first
    equations.equation_svg.cache_clear()
    files[0].write_text(first.replace("<svg", "<svg data-from-cache=\"1\"", 1))
    assert "data-from-cache" in equations.equation_svg(r"E = mc^2")
    equations.equation_svg.cache_clear()


def test_bad_tex_names_the_equation(monkeypatch):
    monkeypatch.setenv("REPORTGEN_NO_EQUATION_CACHE", "1")
    with pytest.raises(ValueError, match=r"\\frac\{a"):
        equations._draw(r"\frac{a", 12.0)


def test_html_element_and_pdf_image_on_the_baseline():
    html = str(equations.equation_html(r"\dot{u}^2 = f(u)"))
    assert html.startswith('<span class="eq" role="math" aria-label="\\dot{u}^2 = f(u)">')
    assert html.count("<svg") == 1
    prepared = prepare_html(f"<p>so {html} holds</p>", Path("/tmp"))
    img = re.search(r"<img [^>]*>", prepared).group(0)
    assert 'class="svg-eq"' in img and re.search(r'style="vertical-align: -[\d.]+pt"', img)


def test_pendulum_report_typesets_its_equations(tmp_path, write_config, cli):
    from conftest import pendulum_text

    config = write_config("p", pendulum_text(t_end=3.0, samples=301,
                                             extra='[report]\nformats = ["html"]\n'))
    code, _, err = cli("run", config, "--out", tmp_path / "out")
    assert code == 0, err
    page = (tmp_path / "out" / "p" / "report.html").read_text()
    spans = re.findall(r'<span class="eq" role="math" aria-label="[^"]*"><svg', page)
    assert len(spans) >= 3
