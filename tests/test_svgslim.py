"""reportgen.svgslim: the lighter SVG the PDF engine gets is the same picture."""

from __future__ import annotations

import base64
import io
import re
import xml.etree.ElementTree as ET

import matplotlib
import pytest

from reportgen.plots.style import new_figure
from reportgen.svgslim import inline_svgs_as_images, slim_svg

SVG = "{http://www.w3.org/2000/svg}"


def _matplotlib_svg(markers: bool = True, log: bool = False) -> str:
    fig, ax = new_figure(figsize=(4.0, 3.0))
    x = [0.001 * i for i in range(1, 400)]
    ax.plot(x, [v * v for v in x], label="dense line")
    if markers:
        ax.plot(x[::40], [v for v in x[::40]], "o", label="markers")
    if log:
        ax.set_yscale("log")
    ax.set_xlabel("time t [s]")
    ax.legend()
    buf = io.BytesIO()
    with matplotlib.rc_context({"svg.hashsalt": "test", "svg.id": "test"}):
        fig.savefig(buf, format="svg", metadata={"Date": None})
    text = buf.getvalue().decode("utf-8")
    return text[text.index("<svg"):]


def _texts(svg: str) -> list[str]:
    """The strings of the <text> elements (indentation between <tspan>s ignored)."""
    root = ET.fromstring(svg)
    return ["".join("".join(el.itertext()).split()) for el in root.iter(SVG + "text")]


@pytest.mark.parametrize("log", [False, True])
def test_slim_keeps_text_and_drops_the_heavy_parts(log):
    svg = _matplotlib_svg(log=log)
    slim = slim_svg(svg)
    assert slim != svg and len(slim) < len(svg)
    root = ET.fromstring(slim)  # well-formed, SVG namespace
    assert root.tag == SVG + "svg"
    assert root.get("width") == ET.fromstring(svg).get("width")
    assert root.get("viewBox") == ET.fromstring(svg).get("viewBox")
    # text stays text, same strings in the same order
    assert _texts(slim) == _texts(svg)
    assert "<use" not in slim and "<metadata" not in slim and "style=" not in slim
    assert "<style" not in slim and root.get("stroke-linejoin") == "round"
    # coordinates carry at most two decimals
    for d in re.findall(r' d="([^"]*)"', slim):
        assert not re.search(r"\.\d{3}", d)


def test_slim_is_deterministic_and_idempotent():
    svg = _matplotlib_svg()
    once = slim_svg(svg)
    assert slim_svg(svg) == once
    assert slim_svg(once) == once


def test_markers_become_translated_paths():
    svg = _matplotlib_svg()
    n_uses = svg.count("<use")
    slim = slim_svg(svg)
    assert n_uses and slim.count("translate(") >= n_uses - svg.count("translate(")


def test_unknown_stylesheet_left_alone():
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="10pt" height="10pt">'
           '<style>.a{fill:red}</style><path class="a" d="M 0 0 L 1.23456 1"/></svg>')
    assert slim_svg(svg) == svg
    assert slim_svg("<svg><unclosed></svg>") == "<svg><unclosed></svg>"


def test_style_rule_still_wins_over_an_ancestor():
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="10pt" height="10pt">'
           '<defs><style type="text/css">*{stroke-linecap: butt}</style></defs>'
           '<g style="stroke-linecap: round"><path d="M 0 0 L 1 1" style="stroke: #000"/></g>'
           '</svg>')
    root = ET.fromstring(slim_svg(svg))
    path = next(root.iter(SVG + "path"))
    assert path.get("stroke-linecap") == "butt"  # the * rule applied to it, not the g's


def test_clip_dropped_only_when_nothing_is_clipped():
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="100pt" height="100pt">'
           '<defs><clipPath id="c"><rect x="10" y="10" width="80" height="80"/></clipPath></defs>'
           '<path d="M 20 20 L 80 80" clip-path="url(#c)" style="stroke: #000; stroke-width: 1"/>'
           '<path d="M 10 50 L 90 50" clip-path="url(#c)" style="stroke: #000; stroke-width: 1"/>'
           '</svg>')
    paths = list(ET.fromstring(slim_svg(svg)).iter(SVG + "path"))
    assert paths[0].get("clip-path") is None
    assert paths[1].get("clip-path") == "url(#c)"


def test_inline_svgs_as_images():
    svg = _matplotlib_svg()
    html = f"<html><body><figure>{svg}<figcaption>x</figcaption></figure></body></html>"
    out = inline_svgs_as_images(html)
    assert "<svg" not in out and out.count('<img class="svg-figure"') == 1
    data = re.search(r'src="data:image/svg\+xml;base64,([^"]+)"', out).group(1)
    assert base64.b64decode(data).decode("utf-8") == slim_svg(svg)
    assert inline_svgs_as_images(html, slim=False).count("<img") == 1


def test_images_written_to_a_folder(tmp_path):
    svg = _matplotlib_svg()
    html = f"<figure>{svg}</figure><figure>{svg}</figure>"
    out = inline_svgs_as_images(html, folder=tmp_path)
    files = sorted(tmp_path.glob("figure-*.svg"))
    assert [f.name for f in files] == ["figure-0.svg", "figure-1.svg"]
    assert files[0].read_text(encoding="utf-8") == slim_svg(svg)
    assert out.count('src="file://') == 2


def test_pdf_figure_text_stays_selectable(tmp_path):
    pypdf = pytest.importorskip("pypdf")
    from reportgen.report import write_pdf

    svg = _matplotlib_svg(log=True)
    html = (f"<html><head><style>figure img.svg-figure {{ max-width: 100%; }}</style></head>"
            f"<body><p>before</p><figure>{svg}</figure></body></html>")
    write_pdf(html, tmp_path / "out.pdf", tmp_path)
    text = "".join(page.extract_text() for page in pypdf.PdfReader(tmp_path / "out.pdf").pages)
    assert "before" in text and "dense line" in text and "time t [s]" in text
    assert not list(tmp_path.glob("figure-*.svg"))  # the slim copies were temporary
