"""``reportgen figures``: a scene's figures as standalone files for slides and print.

Each figure of the report is drawn again from the archive alone (the scene's report-side
section methods, as the report draws them) at a chosen size and saved as PNG, SVG and
PDF.  Nothing is integrated or evaluated: an archive written today exports next year.

Sizes
-----
``report``  the size the report draws (the default)
``slide``   10 x 5.625 in (a 16:9 slide), text 1.3x larger so that it reads on a projector
``print``   6.5 in wide (a page's text width), the figure's own aspect ratio
``WxH``     W x H inches, e.g. ``8x4.5``

A multi-panel figure whose function lays it out for the size asked for
(:mod:`.plots.layout`: Fig. 4.3 as a row of three on a slide, 2 + 1 in print, text at
least ``SLIDE_MIN_FONT`` on a slide) is saved as drawn, at the asked width and height
(print: its own height); every other figure is stretched to the size and its text scaled.

PNG files record their resolution (``--dpi``, default 200) in the file's pHYs chunk, so
a word processor places them at their size; SVG and PDF keep text as text.
"""

from __future__ import annotations

import fnmatch
import math
import re
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from ..errors import UsageError
from ..support.fsutil import atomic_write
from .plots.layout import Size, drawing_for, laid_out_for

EXPORT_FORMATS = ("png", "svg", "pdf")
DEFAULT_DPI = 200
#: pixels a figure may have as PNG (or an animation's frame): its RGBA canvas is 256 MiB
#: (``--size 40x40 --dpi 1200`` asked for 48000 × 48000 pixels, 9.2 GB)
MAX_FIGURE_PIXELS = 1 << 26

#: the smallest text [pt] a figure laid out again for a slide uses: read from the back
#: of a lecture hall
SLIDE_MIN_FONT = 14.0

SIZES = {
    "report": Size("report"),
    "slide": Size("slide", 10.0, 5.625, 1.3, min_font=SLIDE_MIN_FONT),
    "print": Size("print", 6.5, None),
}
_WXH = re.compile(r"^\s*(\d+(?:\.\d*)?|\.\d+)\s*[x×]\s*(\d+(?:\.\d*)?|\.\d+)\s*$")


def parse_size(text: str) -> Size:
    """``slide``, ``print``, ``report`` or ``WxH`` in inches (each between 1 and 40)."""
    if text in SIZES:
        return SIZES[text]
    match = _WXH.match(text)
    if match:
        width, height = float(match.group(1)), float(match.group(2))
        if 1.0 <= width <= 40.0 and 1.0 <= height <= 40.0:
            return Size(f"{width:g}x{height:g}", width, height)
    raise UsageError(f"--size: expected slide, print, report or WxH in inches with W and H "
                     f"between 1 and 40, e.g. 8x4.5 (got {text!r})")


def pixel_problem(width: float, height: float, dpi: int, what: str) -> str | None:
    """Why ``what`` (a ``--size``, or a figure), ``width`` × ``height`` inches drawn at
    ``dpi``, has too many pixels (:data:`MAX_FIGURE_PIXELS`), naming the largest ``--dpi``
    that fits; None when it fits."""
    w, h = round(width * dpi), round(height * dpi)
    if w * h <= MAX_FIGURE_PIXELS:
        return None
    fits = int(math.sqrt(MAX_FIGURE_PIXELS / (width * height)))
    return (f"{what} at --dpi {dpi} is {w} x {h} pixels ({w * h / 1e6:.0f} megapixels), more "
            f"than the {MAX_FIGURE_PIXELS / 1e6:.0f} a figure may have: --dpi {fits} or less, "
            "or a smaller size")


def parse_formats(text: str) -> tuple[str, ...]:
    items = tuple(dict.fromkeys(f.strip().lower() for f in text.split(",") if f.strip()))
    bad = [f for f in items if f not in EXPORT_FORMATS]
    if bad or not items:
        raise UsageError(f"--format: expected a comma-separated subset of "
                         f"{','.join(EXPORT_FORMATS)} (got {text!r})")
    return items


def _scale_text(fig, scale: float) -> None:
    """Every text of ``fig`` ``scale`` times larger, the tick labels drawn later too
    (figures set some sizes explicitly, so the rc defaults alone would miss them)."""
    from matplotlib.text import Text

    if scale == 1.0:
        return
    tick_labels = set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis, getattr(ax, "zaxis", None)):
            if axis is None:
                continue
            for which, ticks in (("major", axis.get_major_ticks()),
                                 ("minor", axis.get_minor_ticks())):
                if ticks:
                    size = ticks[0].label1.get_fontsize()
                    axis.set_tick_params(which=which, labelsize=size * scale)
                    tick_labels.update(id(t) for tick in ticks for t in (tick.label1, tick.label2))
    for text in fig.findobj(Text):
        if id(text) not in tick_labels:
            text.set_fontsize(text.get_fontsize() * scale)


def sized_figures(data, size: Size, only: tuple[str, ...] = ()) -> Iterator[tuple[str, Any]]:
    """(figure id, figure drawn for ``size``) of each figure of the report of the archive
    ``data``, in the report's order; the figure is None when ``only`` (shell patterns)
    leaves it out.  A figure its function laid out for ``size`` comes as drawn; any other
    is stretched to the size and its text scaled.  The caller may clear each figure once
    it is done with it."""
    from .plots import style  # noqa: F401 - the figure style, before anything draws
    from .plots.finish import finish_figure
    from .report import kind_of_archive

    scene = kind_of_archive(data)
    for section in scene.chosen_sections(data):
        with drawing_for(size):
            content = getattr(scene, f"section_{section.name}")(data)
        for spec in content.figures:
            fig_id = f"{section.name}-{spec.name}"
            fig = spec.figure
            if only and not any(fnmatch.fnmatch(fig_id, p) for p in only):
                fig.clear()
                yield fig_id, None
                continue
            if laid_out_for(fig) != size:  # not drawn for it: stretched, text scaled
                fig.set_size_inches(*size.inches(tuple(fig.get_size_inches())))
                _scale_text(fig, size.text_scale)
            finish_figure(fig)
            yield fig_id, fig


def export_figures(archive: Path, out_dir: Path, *, size: Size = SIZES["report"],
                   dpi: int = DEFAULT_DPI, formats: tuple[str, ...] = EXPORT_FORMATS,
                   only: tuple[str, ...] = (),
                   progress: Callable[[Path], None] | None = None) -> list[Path]:
    """Write each figure of ``archive``'s report into ``out_dir`` as ``<id>.<format>``.

    ``only``: shell patterns (``nutation*``) a figure id must match, if any are given.
    Returns the files written, in the report's order.  Each file is written atomically.
    """
    from ..archive.store import read_archive
    from .report import figure_bytes

    data = read_archive(Path(archive))
    written: list[Path] = []
    seen: list[str] = []
    out_dir = Path(out_dir)
    for fig_id, fig in sized_figures(data, size, only):
        seen.append(fig_id)
        if fig is None:
            continue
        if "png" in formats:  # the canvas is allocated when drawn: refused before
            problem = pixel_problem(*fig.get_size_inches(), dpi, f"figure {fig_id}")
            if problem is not None:
                fig.clear()
                raise UsageError(problem)
        out_dir.mkdir(parents=True, exist_ok=True)
        for fmt in formats:
            target = out_dir / f"{fig_id}.{fmt}"
            atomic_write(target, figure_bytes(fig, fig_id, fmt,
                                                dpi if fmt == "png" else "figure"))
            written.append(target)
            if progress is not None:
                progress(target)
        fig.clear()
    if only and not written:
        raise UsageError(f"--only {' '.join(only)}: no figure of {archive} matches; its "
                         f"figures are: {', '.join(seen) or 'none'}")
    return written
