"""Typeset equations without TeX: matplotlib's mathtext drawn as inline SVG.

A report template writes an equation as ``{% filter eq %}\\dot u^2 = f(u){% endfilter %}``
(mathtext, a TeX subset: ``\\frac``, ``\\sqrt``, ``\\dot``, Greek, sub/superscripts …).
:func:`equation_html` gives ``<span class="eq" role="math" aria-label="TeX">`` holding an
``<svg>`` of the glyphs as paths (STIX, the body text's family), sized in points
and lowered by its depth so that its baseline sits on the line's; the same element serves
the HTML and the PDF, and no font has to be installed to show it.

Cost: about 30-40 ms per equation to lay out and draw.  Equations are template constants,
so each is drawn once per machine: kept by content in ``$XDG_CACHE_HOME/reportgen/
equations`` (and in memory), which makes a report's equations a few file reads.
"""

from __future__ import annotations

import functools
import hashlib
import html
import io
import os
import re
from pathlib import Path

from markupsafe import Markup

#: text size of the equations in points (the body's is 11 pt; math reads better larger)
EQUATION_POINTS = 12.0
FONTSET = "stix"
#: bump when the drawing changes, so that no cached drawing survives
_VERSION = "2"
_SUPERSAMPLE = 8  # layout measured at 8 x 72 dpi: sizes to 1/8 pt


def _cache_dir() -> Path | None:
    if os.environ.get("REPORTGEN_NO_EQUATION_CACHE"):
        return None
    from ..support.cache import cache_root

    return cache_root() / "equations"


@functools.cache
def _matplotlib_version() -> str:
    """matplotlib's version without importing it (a report of cached equations never
    needs matplotlib itself; importing it costs a few tenths of a second)."""
    from importlib.metadata import version

    return version("matplotlib")


def _key(tex: str, points: float) -> str:
    blob = f"{_VERSION}|{_matplotlib_version()}|{FONTSET}|{points}|{tex}"
    return hashlib.sha256(blob.encode("utf-8")).hexdigest()[:32]


@functools.lru_cache(maxsize=1024)
def equation_svg(tex: str, points: float = EQUATION_POINTS) -> str:
    """The ``<svg>`` element of ``tex`` (mathtext without the ``$``): glyphs as paths,
    ``width``/``height`` in points and a ``vertical-align`` that puts its baseline on the
    surrounding text's.  Raises ValueError naming the equation when mathtext cannot parse it."""
    folder = _cache_dir()
    name = _key(tex, points) + ".svg"
    if folder is not None:
        try:
            return (folder / name).read_text(encoding="utf-8")
        except OSError:
            pass
    svg = _draw(tex, points)
    if folder is not None:
        from ..support.fsutil import atomic_write

        try:
            folder.mkdir(parents=True, exist_ok=True)
            atomic_write(folder / name, svg.encode("utf-8"))
        except OSError:
            pass  # a read-only cache costs time, not correctness
    return svg


def _draw(tex: str, points: float) -> str:
    import matplotlib
    from matplotlib.figure import Figure
    from matplotlib.font_manager import FontProperties
    from matplotlib.mathtext import MathTextParser

    math = f"${tex}$"
    key = _key(tex, points)
    with matplotlib.rc_context({"mathtext.fontset": FONTSET, "svg.fonttype": "path",
                                "svg.hashsalt": key, "svg.id": "eq"}):
        prop = FontProperties(size=points)
        try:
            width, height, depth, _, _ = MathTextParser("path").parse(
                math, dpi=72 * _SUPERSAMPLE, prop=prop)
        except ValueError as exc:
            raise ValueError(f"equation {tex!r}: {exc}") from None
        except RecursionError:  # mathtext's parser recurses per level (~15 nested calls)
            raise ValueError(f"equation {tex[:60]!r}…: nested too deeply for mathtext") \
                from None
        width, height, depth = (v / _SUPERSAMPLE for v in (width, height, depth))
        pad = 0.5  # points around the ink, so antialiased edges are not clipped
        fig = Figure(figsize=((width + 2 * pad) / 72, (height + 2 * pad) / 72))
        fig.text(pad / (width + 2 * pad), (depth + pad) / (height + 2 * pad), math,
                 fontproperties=prop)
        buf = io.BytesIO()
        fig.savefig(buf, format="svg", transparent=True, metadata={"Date": None})
    text = buf.getvalue().decode("utf-8")
    svg = text[text.index("<svg"):]
    svg = re.sub(r"\s*<metadata>.*?</metadata>", "", svg, flags=re.S)
    svg = re.sub(r">\s+<", "><", svg).strip()
    # ids (the figure's, the glyphs') made unique to this equation on a page of many
    prefix = "eq" + key[:8] + "-"
    svg = re.sub(r'\s+id="eq"', "", svg, count=1)
    svg = re.sub(r'\bid="([^"]+)"', rf'id="{prefix}\1"', svg)
    svg = re.sub(r'href="#([^"]+)"', rf'href="#{prefix}\1"', svg)
    svg = re.sub(r"url\(#([^)]+)\)", rf"url(#{prefix}\1)", svg)
    style = f'style="vertical-align: {-(depth + pad):.3f}pt"'
    return svg.replace("<svg", f"<svg {style} aria-hidden=\"true\"", 1)


def equation_html(tex: str) -> Markup:
    """The report's element for one equation: ``<span class="eq" role="math">`` holding
    the drawing, with the TeX source as its accessible name (and what a reader copies)."""
    tex = html.unescape(str(tex)).strip()
    return Markup(f'<span class="eq" role="math" aria-label="{html.escape(tex)}">'
                  f"{equation_svg(tex)}</span>")
