"""reportgen.rendering.svgslim: the lighter SVG the PDF engine gets is the same picture."""

from __future__ import annotations

import base64
import io
import math
import re
import xml.etree.ElementTree as ET

import matplotlib
import pytest

from reportgen.rendering.plots.style import new_figure
from reportgen.rendering.svgslim import (
    inline_svgs_as_images,
    prune_cache,
    slim_cached,
    slim_svg,
    warm_cache,
)

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


def test_markers_become_one_path_of_translated_copies():
    svg = _matplotlib_svg()
    assert svg.count("<use") >= 10
    slim = slim_svg(svg)
    assert "<use" not in slim
    # the ten "o" markers (fill and edge of one opaque colour): one path, ten subpaths
    marker_runs = [d for d in re.findall(r' d="([^"]*)"', slim) if d.count("M") == 10]
    assert len(marker_runs) == 1 and marker_runs[0].count("z") == 10


def test_translucent_markers_stay_apart():
    """Merged, the fills of overlapping translucent markers would not darken each other:
    those are left one path per marker."""
    fig, ax = new_figure(figsize=(3.0, 2.0))
    ax.plot([0, 1, 2, 3], [0, 1, 0, 1], "o", alpha=0.5)
    buf = io.BytesIO()
    with matplotlib.rc_context({"svg.hashsalt": "test", "svg.id": "test"}):
        fig.savefig(buf, format="svg", metadata={"Date": None})
    slim = slim_svg(buf.getvalue().decode("utf-8"))
    assert len([d for d in re.findall(r' d="([^"]*)"', slim) if "C" in d and "z" in d]) == 4


def _polyline_svg(points) -> str:
    d = "M " + " L ".join(f"{x:.4f} {y:.4f}" for x, y in points)
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="400pt" height="300pt" '
            f'viewBox="0 0 400 300"><path d="{d}" fill="none" stroke="#000"/></svg>')


def _distance_to_polyline(p, vertices) -> float:
    best = math.inf
    for (ax, ay), (bx, by) in zip(vertices, vertices[1:], strict=False):
        dx, dy = bx - ax, by - ay
        t = 0.0 if dx == dy == 0 else max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy)
                                                    / (dx * dx + dy * dy)))
        best = min(best, math.hypot(p[0] - ax - t * dx, p[1] - ay - t * dy))
    return best


def test_dense_polyline_thinned_within_tolerance():
    points = [(10 + 0.38 * i, 290 - 280 * (i / 1000) ** 2) for i in range(1001)]
    slim = slim_svg(_polyline_svg(points), thin=0.1)
    d = re.search(r' d="([^"]*)"', slim).group(1)
    kept = [(float(x), float(y)) for x, y in re.findall(r"([-\d.]+) ([-\d.]+)", d)]
    assert len(kept) <= len(points) // 2 + 1  # every other vertex of a smooth dense curve
    assert kept[0] == (10.0, 290.0) and kept[-1] == pytest.approx(points[-1], abs=0.006)
    # every dropped vertex within the tolerance (plus the 0.005 pt rounding) of the line
    assert max(_distance_to_polyline(p, kept) for p in points[::7]) <= 0.1 + 0.01
    unthinned = slim_svg(_polyline_svg(points), thin=0)
    assert unthinned.count(" L ") + unthinned.count("L ") >= 1000


def test_tips_of_cusps_and_reversals_kept():
    # a trace that runs out and back along one line (a cusp seen edge-on, a reversal):
    # each tip lies on the line through its neighbours but 1 pt beyond them
    out = [(10.0 + i, 100.0) for i in range(40)]  # out to x = 49 in steps of 1 pt
    back = [(49.0 - 0.7 * (i + 1), 100.0) for i in range(55)]  # back in steps of 0.7 pt
    points = out + back + out[1:] + back
    slim = slim_svg(_polyline_svg(points), thin=0.1)
    d = re.search(r' d="([^"]*)"', slim).group(1)
    kept = [(float(x), float(y)) for x, y in re.findall(r"([-\d.]+) ([-\d.]+)", d)]
    assert len(kept) < len(points)  # the straight stretches are thinned ...
    assert max(x for x, _ in kept) == 49.0 and min(x for x, _ in kept) < 10.6  # ... the tips kept
    assert max(_distance_to_polyline(p, kept) for p in points) <= 0.1 + 0.01


def test_thinning_only_where_a_user_unit_is_a_point():
    points = [(0.04 * i, 0.001 * i * i) for i in range(300)]
    svg = _polyline_svg(points).replace('viewBox="0 0 400 300"', 'viewBox="0 0 40 30"')
    assert slim_svg(svg, thin=0.1).count("L") == 299


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
    from reportgen.rendering.report import write_pdf

    svg = _matplotlib_svg(log=True)
    html = (f"<html><head><style>figure img.svg-figure {{ max-width: 100%; }}</style></head>"
            f"<body><p>before</p><figure>{svg}</figure></body></html>")
    write_pdf(html, tmp_path / "out.pdf", tmp_path)
    text = "".join(page.extract_text() for page in pypdf.PdfReader(tmp_path / "out.pdf").pages)
    assert "before" in text and "dense line" in text and "time t [s]" in text
    assert not list(tmp_path.glob("figure-*.svg"))  # the slim copies were temporary


def test_slim_copies_cached_by_content(tmp_path):
    svg = _matplotlib_svg()
    cache = tmp_path / "slim"
    warm_cache(f"<figure>{svg}</figure>", cache)
    (made,) = cache.glob("*.svg")
    assert made.read_text(encoding="utf-8") == slim_svg(svg)
    stamp = made.stat().st_mtime_ns
    used: set = set()
    out = inline_svgs_as_images(f"<p>a</p>{svg}", cache=cache, used=used)
    assert used == {made} and made.resolve().as_uri() in out
    assert made.stat().st_mtime_ns == stamp  # found, not made again
    other = slim_cached(_matplotlib_svg(markers=False), cache)
    assert other != made and slim_cached(svg, cache, thin=0) not in (made, other)
    prune_cache(cache, {made})
    assert sorted(cache.glob("*.svg")) == [made]


def test_a_dense_family_costs_the_pdf_four_vertices_per_member():
    # The period-against-amplitude figure of a 2000-member sweep: its error panel's dots
    # are edgeless squares (style.dots), 4 vertices each in the slim SVG, where circles
    # were 13 Bézier points each (50,000 numbers for WeasyPrint to parse in Python).
    import numpy as np
    from scipy import special

    from reportgen.kinds.pendulum.plots import period_family
    from reportgen.rendering.report import figure_bytes

    amplitude = np.linspace(0.01, 3.1, 2000)
    exact = 4 * special.ellipk(np.sin(amplitude / 2) ** 2) / math.sqrt(9.81)
    noise = np.random.default_rng(1).standard_normal(amplitude.size) * 1e-12
    fig = period_family(amplitude, exact * (1 + noise), exact)
    slim = slim_svg(figure_bytes(fig, "family", "svg").decode())
    vertices = sum(len(re.findall(r"-?[\d.]+[ ,]-?[\d.]+", d))
                   for d in re.findall(r' d="([^"]*)"', slim))
    assert 2000 * 4 <= vertices < 2000 * 4 + 6000
