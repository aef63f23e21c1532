"""The document gate: what a reader must never meet in a report, checked on the objects the
report stage already has in hand (issue 31).

:func:`figure_findings` reads a matplotlib figure just after it was saved (its layout,
legends and transforms are those of the saved file); :func:`page_findings` reads a
WeasyPrint document after layout, before it is written as PDF.  Each returns findings, one
line each, naming where and which rule; an empty list is a pass.  Both only read: a
report costs a few milliseconds more.  The report stage writes them to ``gate.json``.

Figure rules (per axes, named by its number and title or label)
    ``series``   the entries of a legend (and the labelled series of one axes) differ in
                 colour (RGB distance > 0.06), line style or marker: no two distinct labels
                 look alike.  Unlabelled artists (a family of curves, guides) are not
                 series.
    ``legend``   a legend inside an axes covers no plotted data: no marker centre (of a
                 line or scatter) inside its frame, and at most 1 % (and at most 3 pt) of
                 any line's drawn length.  Guide lines (``axhline``/``axvline``, lines in
                 axes coordinates), fills and images are not data here; a legend outside
                 the axes covers nothing.
    ``label``    every axis that shows numbers carries a label with a quantity and a unit
                 in square brackets, or the word "dimensionless"; a colour bar likewise.
                 Exempt: axes drawn off, polar axes, an axis whose tick labels are hidden
                 (shared axes) or are words (categories), and an unlabelled axis of a grid
                 panel whose column (x) or row (y) has a labelled panel (small multiples).
    ``limits``   an annotated point (``annotate``'s ``xy`` in data coordinates, a text
                 placed in data coordinates, a single-point marker, a scatter of at most
                 3 points) lies within the axes (0.5 pt slack).

Page rules (per page)
    ``overflow`` no box's border edge passes the page's content area by more than 0.5 pt
                 (reported once, for the outermost box, quoting its first words)
    ``number``   no ``nan``, ``inf`` (the word "infinity" is English: "the apocentre is at
                 infinity") or negative zero (``−0``, ``-0.00``,
                 ``−0.0e+00``) as a token
    ``config``   no config key: ``table.key`` for a table of the scene's config (or of
                 every config: ``run``, ``initial``, ``params`` …; ``run.h5`` is a file),
                 ``[table]`` for such a table, any ``[[table]]``, a key of the config or of
                 ``[run]``/``[report]`` (``t_end``, ``study_budget``); in prose any other
                 ``snake_case`` word but a cited routine (``solve_ivp``) or platform
    ``python``   no Python: ``**``, ``a*b``, ``==``, ``!=``, ``np.``/``numpy.``/``math.``,
                 ``None``/``True``/``False``
    ``tex``      no raw TeX: ``\\command``, ``_{``, ``^{``, a caret exponent ``r^2``,
                 ``$…$``, a symbol with an ASCII subscript (``L_z``, ``V_eff``)
    ``type``     typeset as a textbook (issue 41): no ASCII hyphen as a minus sign
                 (``-0.34``), no E-notation (``4.2e-15``: a × 10ⁿ), no symbol with a
                 plain-digit subscript (``I1``, ``θ0``: I₁, θ₀; a ``<sub>`` is read as one)
    ``provenance`` no slug, archive path (``/runs/main``), library call or ``rtol=`` in
                 the body: they belong to the colophon (``snake_case`` is the ``config``
                 rule's, in prose and code spans alike)
    ``fill``     no page after the first filled to less than a quarter of its height

The appended configuration and colophon (``<section id="config">``) and the footer are
exempt from the text rules.  A ``<code>`` span in the body may name a file (``run.h5``) or
a command (``reportgen cache info``); it is held to the other rules like prose.
"""

from __future__ import annotations

import json
import re
from collections import Counter
from collections.abc import Iterable
from pathlib import Path

import numpy as np

__all__ = ["figure_findings", "page_findings", "write_gate", "gate_findings", "GATE_FILE"]

GATE_FILE = "gate.json"

# ------------------------------------------------------------------ figures

#: colours closer than this (RGB distance, 0-1 scale) count as the same colour
_SAME_COLOUR = 0.06
#: how much of a line may pass under a legend: this fraction of its drawn length ...
_LEGEND_LINE_FRACTION = 0.01
#: ... and at least this many points of it (a corner clipped by a frame is not covered)
_LEGEND_LINE_MIN_PT = 3.0
#: a scatter of at most this many points is a highlight (held to the limits rule)
_HIGHLIGHT_POINTS = 3
_UNIT = re.compile(r"\[[^\]]+\]|\bdimensionless\b", re.I)
_NUMBER_TICK = re.compile(r"^[\s\-−+]*[\d.,]+(?:[eE×][\-−+]?\d+)?%?$|^\$.*\$$|^[\-−+]?10")


def figure_findings(fig, dpi: float = 72.0) -> list[str]:
    """The gate's findings on a drawn matplotlib figure.  Call it just after ``savefig``
    with the ``dpi`` that save drew at (72: SVG and PDF are drawn at 72 dpi whatever the
    figure's own): the layout, the labels' places and the legends' are then those of the
    file.  A failure of the gate itself is a finding too: it never stops a report."""
    own_dpi = fig.dpi
    try:
        fig.dpi = dpi
        return _figure_findings(fig)
    except Exception as exc:  # noqa: BLE001 - reported in gate.json, which tests read
        return [f"gate: could not check the figure: {type(exc).__name__}: {exc}"]
    finally:
        fig.dpi = own_dpi


def _figure_findings(fig) -> list[str]:
    renderer = fig._get_renderer()  # Agg's, made without drawing
    findings: list[str] = []
    axes = fig.get_axes()
    names = _axes_names(axes)
    for ax in axes:
        name = names[ax]
        if _is_colorbar(ax):
            findings += _colorbar_label(ax, name)
            continue
        findings += _series_findings(ax, name)
        findings += _label_findings(ax, name)
        findings += _text_of_axes(ax, name, renderer)
        findings += _limit_findings(ax, name, renderer)
        legend = ax.get_legend()
        if legend is not None and legend.get_visible():
            findings += _legend_cover(legend, [ax], name, renderer)
    findings += _labels_overlapping(axes, names, renderer)
    for i, legend in enumerate(fig.legends):
        where = f"figure legend {i + 1}"
        findings += _figure_text_findings([t.get_text() for t in legend.texts], where)
        said = {f.split(": series: ", 1)[-1] for f in findings if ": series: " in f}
        findings += [f for f in _legend_alike(_legend_entries(legend), where)
                     if f.split(": series: ", 1)[-1] not in said]
        if legend.get_visible():
            findings += _legend_cover(legend, axes, where, renderer)
    return findings


def _axis_texts(ax):
    """The axes' own words: title, axis labels (x, y and z) and legend entries."""
    texts = [ax.title, ax._left_title, ax._right_title, ax.xaxis.label, ax.yaxis.label]
    if ax.name == "3d":
        texts.append(ax.zaxis.label)
    legend = ax.get_legend()
    if legend is not None:
        texts += list(legend.texts)
    return [t for t in texts if t.get_visible() and t.get_text().strip()]


def _text_of_axes(ax, name: str, renderer) -> list[str]:
    """``text`` rule: the axes' title and labels lie within the figure; and the words of
    its title, labels and legend are held to the page's number/config/python/tex rules
    (mathtext between ``$`` is typeset, so it is left out)."""
    findings = _figure_text_findings([t.get_text() for t in _axis_texts(ax)], name)
    if ax.name == "3d":
        return findings
    fig_box = ax.figure.bbox
    slack = ax.figure.dpi / 72.0
    for text in (ax.title, ax.xaxis.label, ax.yaxis.label):
        if not (text.get_visible() and text.get_text().strip()):
            continue
        box = text.get_window_extent(renderer)
        if (box.x0 < fig_box.x0 - slack or box.x1 > fig_box.x1 + slack
                or box.y0 < fig_box.y0 - slack or box.y1 > fig_box.y1 + slack):
            findings.append(f"{name}: text: '{_short(text.get_text())}' passes the "
                            "figure's edge")
    return findings


def _labels_overlapping(axes, names, renderer) -> list[str]:
    """``text`` rule: the x labels (and the y labels) of two axes do not overlap."""
    boxes = []
    for ax in axes:
        if ax.name == "3d" or _is_colorbar(ax):
            continue
        for text in (ax.xaxis.label, ax.yaxis.label, ax.title):
            if text.get_visible() and text.get_text().strip():
                boxes.append((ax, text, text.get_window_extent(renderer)))
    findings = []
    for i, (ax, text, box) in enumerate(boxes):
        for other_ax, other, other_box in boxes[i + 1:]:
            if other_ax is not ax and box.overlaps(other_box):
                findings.append(f"{names[ax]}: text: '{_short(text.get_text())}' overlaps "
                                f"'{_short(other.get_text())}' of {names[other_ax]}")
    return findings


_MATHTEXT = re.compile(r"(?<!\\)\$[^$]*(?<!\\)\$")


def _figure_text_findings(texts: list[str], where: str) -> list[str]:
    findings = []
    for text in texts:
        plain = _MATHTEXT.sub(" ", text).replace("`", " ` ")
        found = _text_findings(plain, False, set(_COMMON_TABLES), set(_COMMON_KEYS))
        if "`" in text:
            found.append(f"config: a code quote '`' in '{_short(text, 10)}'")
        findings += [f"{where}: {f}" for f in found if f not in findings]
    return list(dict.fromkeys(findings))


def _axes_names(axes) -> dict:
    names = {}
    for i, ax in enumerate(axes):
        title = next((t for t in (ax.get_title(loc) for loc in ("center", "left", "right"))
                      if t.strip()), "")
        label = title or ax.get_ylabel() or ax.get_xlabel()
        names[ax] = f"axes {i + 1}" + (f" ({_short(label)})" if label.strip() else "")
    return names


def _short(text: str, words: int = 6) -> str:
    parts = " ".join(str(text).split()).split(" ")
    return " ".join(parts[:words]) + (" …" if len(parts) > words else "")


def _is_colorbar(ax) -> bool:
    return getattr(ax, "_colorbar", None) is not None


def _colorbar_label(ax, name: str) -> list[str]:
    cb = ax._colorbar
    axis = ax.yaxis if cb.orientation == "vertical" else ax.xaxis
    if not ax.axison or not _ticks_show_numbers(axis):
        return []
    return _label_rule(axis.get_label().get_text(), f"{name}: colour bar")


def _label_rule(text: str, where: str) -> list[str]:
    text = text.strip()
    if not text:
        return [f"{where}: label: no axis label"]
    if not _UNIT.search(text):
        return [f"{where}: label: '{_short(text, 10)}' has no unit in [ ] "
                "nor 'dimensionless'"]
    if _UNIT.sub("", text).strip(" ,;:()") == "":
        return [f"{where}: label: '{text}' names a unit but no quantity"]
    return []


def _ticks_show_numbers(axis) -> bool:
    """Whether an axis shows numbers: some visible tick label, and not all of them words."""
    texts = []
    for tick in axis.get_major_ticks():
        if not tick.get_visible():
            continue
        for label in (tick.label1, tick.label2):
            if label.get_visible() and label.get_text().strip():
                texts.append(label.get_text().strip())
    if not texts:  # no ticks, or hidden tick labels (a shared axis)
        return False
    return any(_NUMBER_TICK.match(t) for t in texts)


def _shows_data(ax) -> bool:
    return bool(ax.lines or ax.collections or ax.images or ax.patches)


def _label_findings(ax, name: str) -> list[str]:
    if not ax.axison or ax.name == "polar" or not _shows_data(ax):
        return []
    findings = []
    axes_of = [("x", ax.xaxis), ("y", ax.yaxis)]
    if ax.name == "3d":
        axes_of.append(("z", ax.zaxis))
    for letter, axis in axes_of:
        if ax.name != "3d" and not _ticks_show_numbers(axis):
            continue
        text = axis.get_label().get_text()
        if not text.strip() and letter in "xy" and _labelled_by_neighbour(ax, letter):
            continue
        findings += _label_rule(text, f"{name}: {letter} axis")
    return findings


def _labelled_by_neighbour(ax, letter: str) -> bool:
    """Whether an unlabelled axis of a grid of small multiples takes its label from a
    panel of the same column (x) or row (y) that has one, as a grid's outer panels do."""
    spec = ax.get_subplotspec() if hasattr(ax, "get_subplotspec") else None
    if spec is None:
        return False
    span = spec.colspan if letter == "x" else spec.rowspan
    for other in ax.figure.get_axes():
        other_spec = other.get_subplotspec() if hasattr(other, "get_subplotspec") else None
        if (other is ax or other_spec is None
                or other_spec.get_gridspec() is not spec.get_gridspec()):
            continue
        other_span = other_spec.colspan if letter == "x" else other_spec.rowspan
        label = (other.get_xlabel() if letter == "x" else other.get_ylabel()).strip()
        if label and set(span) & set(other_span):
            return True
    return False


# ..... series that look alike
def _line_look(line) -> tuple:
    ls = line.get_linestyle() if line.get_linestyle() not in ("None", "none", " ", "") else ""
    marker = line.get_marker() if str(line.get_marker()) not in ("None", "none", " ", "") else ""
    dashes = tuple(np.round(line._dash_pattern[1], 1)) if ls and line._dash_pattern[1] else ()
    colour = line.get_color() if ls else line.get_markerfacecolor()
    return ("line", _rgb(colour), ls and (ls if ls == "-" else dashes or ls), str(marker),
            _rgb(line.get_markerfacecolor()) if marker else None)


def _collection_look(coll) -> tuple:
    face = coll.get_facecolor()
    edge = coll.get_edgecolor()
    paths = coll.get_paths()
    shape = (len(paths[0].vertices), tuple(np.round(paths[0].vertices[:4].ravel(), 2))) \
        if len(paths) == 1 else ()
    return ("collection", _rgb(face[0]) if len(face) else None,
            _rgb(edge[0]) if len(edge) else None, shape,
            getattr(coll, "get_hatch", lambda: None)())


def _patch_look(patch) -> tuple:
    return ("patch", _rgb(patch.get_facecolor()), _rgb(patch.get_edgecolor()),
            patch.get_hatch(), str(patch.get_linestyle()), patch.get_fill())


def _look(artist) -> tuple | None:
    from matplotlib.collections import Collection
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    if isinstance(artist, Line2D):
        return _line_look(artist)
    if isinstance(artist, Collection):
        return _collection_look(artist)
    if isinstance(artist, Patch):
        return _patch_look(artist)
    return None


def _rgb(colour) -> tuple | None:
    from matplotlib.colors import to_rgba

    try:
        r, g, b, a = to_rgba(colour)
    except (ValueError, TypeError):
        return None
    return (r, g, b) if a > 0 else None


def _same(a: tuple, b: tuple) -> bool:
    if len(a) != len(b) or a[0] != b[0]:
        return False
    for x, y in zip(a[1:], b[1:], strict=True):
        if isinstance(x, tuple) and isinstance(y, tuple) and len(x) == len(y) == 3 \
                and all(isinstance(v, float) for v in x + y):
            if np.hypot.reduce(np.subtract(x, y)) > _SAME_COLOUR:
                return False
        elif x != y:
            return False
    return True


def _legend_alike(entries: list[tuple[str, tuple]], where: str) -> list[str]:
    """Pairs of distinct labels whose entries look the same."""
    findings = []
    seen: list[tuple[str, tuple]] = []
    for label, look in entries:
        if look is None or any(label == other for other, _ in seen):
            continue
        for other, other_look in seen:
            if _same(look, other_look):
                findings.append(f"{where}: series: '{_short(other)}' and '{_short(label)}' "
                                "have the same colour, line style and marker")
                break
        seen.append((label, look))
    return findings


def _legend_entries(legend) -> list[tuple[str, tuple]]:
    handles = getattr(legend, "legend_handles", None) or getattr(legend, "legendHandles", [])
    return [(text.get_text(), _look(h)) for text, h in zip(legend.texts, handles, strict=False)
            if h is not None]


def _series_findings(ax, name: str) -> list[str]:
    handles, labels = ax.get_legend_handles_labels()
    entries = [(label, _look(h)) for h, label in zip(handles, labels, strict=True)]
    findings = _legend_alike(entries, name)
    legend = ax.get_legend()
    if legend is not None and not findings:  # a legend of proxies: its own entries
        findings = _legend_alike(_legend_entries(legend), f"{name}: legend")
    return findings


# ..... legends over data
def _is_data_line(line, ax) -> bool:
    return (line.get_visible() and line.get_transform() == ax.transData
            and len(line.get_xydata()) >= 2)


def _legend_cover(legend, axes, where: str, renderer) -> list[str]:
    """One finding naming every series of ``axes`` that ``legend`` covers, if any."""
    from matplotlib.collections import LineCollection, PathCollection

    box = legend.get_window_extent(renderer)
    pt = legend.figure.dpi / 72.0
    covered = []
    for ax in axes:
        if _is_colorbar(ax) or ax.name != "rectilinear" or not ax.get_visible():
            continue
        frame = ax.bbox
        if not box.overlaps(frame):
            continue
        for line in ax.lines:
            if _is_data_line(line, ax):
                xy = line.get_transform().transform(line.get_xydata())
                covered += _covered(xy, box, frame, line, pt, _has_marker(line),
                                    _has_line(line))
        for coll in ax.collections:
            if not coll.get_visible():
                continue
            if isinstance(coll, PathCollection) and coll.get_offset_transform() == ax.transData:
                xy = ax.transData.transform(coll.get_offsets())
                covered += _covered(xy, box, frame, coll, pt, markers=True, line=False)
            elif isinstance(coll, LineCollection) and coll.get_transform() == ax.transData:
                for seg in coll.get_segments():
                    found = _covered(ax.transData.transform(seg), box, frame, coll, pt,
                                     markers=False, line=True) if len(seg) >= 2 else []
                    if found:
                        covered += found
                        break
    if not covered:
        return []
    return [f"{where}: legend: covers plotted data: {', '.join(covered)}"]


def _artist_name(artist) -> str:
    label = artist.get_label()
    return label if label and not label.startswith("_") else type(artist).__name__


def _has_marker(line) -> bool:
    return str(line.get_marker()) not in ("None", "none", " ", "")


def _has_line(line) -> bool:
    return line.get_linestyle() not in ("None", "none", " ", "")


def _covered(xy, box, frame, artist, pt, markers: bool, line: bool) -> list[str]:
    """How ``artist`` (its points ``xy`` in display coordinates) passes under ``box``
    within the axes ``frame``: markers (any centre) or a line (its drawn length)."""
    xy = xy[np.isfinite(xy).all(axis=1)]
    if len(xy) == 0:
        return []
    name = f"'{_short(_artist_name(artist))}'"
    if markers:
        inside = _inside(xy, box) & _inside(xy, frame)
        if inside.any():
            return [f"{name} ({int(inside.sum())} of {len(xy)} points)"]
    if line and len(xy) >= 2:
        under = _clipped_length(xy, box, frame)
        drawn = _clipped_length(xy, frame, frame)
        if drawn > 0 and under > max(_LEGEND_LINE_FRACTION * drawn, _LEGEND_LINE_MIN_PT * pt):
            return [f"{name} ({100 * under / drawn:.0f} % of its line)"]
    return []


def _inside(xy, box) -> np.ndarray:
    return ((xy[:, 0] > box.x0) & (xy[:, 0] < box.x1)
            & (xy[:, 1] > box.y0) & (xy[:, 1] < box.y1))


def _clipped_length(xy, box, frame) -> float:
    """Length of the polyline ``xy`` (display coordinates) within both boxes
    (Liang-Barsky clipping of every segment at once)."""
    x0, x1 = max(box.x0, frame.x0), min(box.x1, frame.x1)
    y0, y1 = max(box.y0, frame.y0), min(box.y1, frame.y1)
    if x0 >= x1 or y0 >= y1:
        return 0.0
    p, q = xy[:-1], xy[1:]
    d = q - p
    lo = np.zeros(len(d))
    hi = np.ones(len(d))
    with np.errstate(divide="ignore", invalid="ignore"):
        for k, (a, b) in enumerate(((x0, x1), (y0, y1))):
            dk, pk = d[:, k], p[:, k]
            t_a = (a - pk) / dk
            t_b = (b - pk) / dk
            t_in = np.where(dk > 0, t_a, t_b)
            t_out = np.where(dk > 0, t_b, t_a)
            still = dk == 0
            outside = still & ((pk < a) | (pk > b))
            lo = np.where(still, lo, np.maximum(lo, t_in))
            hi = np.where(still, hi, np.minimum(hi, t_out))
            hi = np.where(outside, -1.0, hi)
    frac = np.clip(hi - lo, 0.0, None)
    return float(np.sum(frac * np.hypot(d[:, 0], d[:, 1])))


# ..... annotated points
def _limit_findings(ax, name: str, renderer) -> list[str]:
    from matplotlib.text import Annotation

    if ax.name != "rectilinear":
        return []
    frame = ax.bbox
    slack = ax.figure.dpi / 72.0 * 0.5
    points = []
    for text in ax.texts:
        if not text.get_visible():
            continue
        if isinstance(text, Annotation):
            if text.xycoords == "data":
                points.append((f"annotation '{_short(text.get_text())}'", text.xy))
        elif text.get_transform() == ax.transData:
            points.append((f"text '{_short(text.get_text())}'", text.get_position()))
    for line in ax.lines:
        if (line.get_visible() and line.get_transform() == ax.transData
                and len(line.get_xydata()) == 1):
            points.append((f"marker '{_artist_name(line)}'", line.get_xydata()[0]))
    for coll in ax.collections:
        if (coll.get_visible() and hasattr(coll, "get_offsets")
                and coll.get_offset_transform() == ax.transData
                and 0 < len(coll.get_offsets()) <= _HIGHLIGHT_POINTS):
            for xy in coll.get_offsets():
                points.append((f"point of '{_artist_name(coll)}'", xy))
    findings = []
    for what, xy in points:
        x, y = np.asarray(xy, dtype=float)
        if not (np.isfinite(x) and np.isfinite(y)):
            findings.append(f"{name}: limits: {what} at a non-finite point")
            continue
        dx, dy = ax.transData.transform((x, y))
        if not (frame.x0 - slack <= dx <= frame.x1 + slack
                and frame.y0 - slack <= dy <= frame.y1 + slack):
            findings.append(f"{name}: limits: {what} at ({x:.4g}, {y:.4g}) lies outside "
                            f"x {_lims(ax.get_xlim())}, y {_lims(ax.get_ylim())}")
    return findings


def _lims(lims) -> str:
    lo, hi = sorted(lims)
    return f"[{lo:.4g}, {hi:.4g}]"


# ------------------------------------------------------------------- pages

#: how far a box may pass the content area, in CSS px (0.5 pt)
_OVERFLOW_SLACK = 0.5 * 96 / 72
#: an interior page must be filled to at least this fraction of its content height
_MIN_FILL = 0.25

_NAN_INF = re.compile(r"(?<![\w.])[+\-−]?(?:nan|inf)(?![\w(])", re.I)
_NEG_ZERO = re.compile(r"(?<![\w.^])[\-−]0(?:\.0*)?(?:[eE][+\-−]?\d+)?(?![\d.])"
                       r"|(?<![\w.^])[\-−]0\.0+(?![\d])")
_FILE_EXT = ("h5", "toml", "svg", "pdf", "png", "html", "json", "csv", "txt", "log", "py",
             "npz", "gif", "mp4", "webm", "prev")
_DOTTED = re.compile(r"(?<![\w.])([A-Za-z_]\w*)\.([A-Za-z_]\w*)(?![\w(])")
_BRACKET_TABLE = re.compile(r"\[\[\s*([\w.]+)\s*\]\]|\[\s*([A-Za-z_][\w.]*)\s*\]")
_SNAKE = re.compile(r"(?<![\w/.])([A-Za-z][A-Za-z0-9]*_[A-Za-z0-9_]*[A-Za-z0-9])(?![\w(])")
#: a symbol with an ASCII subscript (``L_z``, ``V_eff``, ``r_Kepler``): TeX notation
_SUBSCRIPTED = re.compile(r"[A-Za-z]\d?_[A-Za-z0-9]{1,7}")
#: typography a textbook never prints (issue 41): a hyphen as a minus sign, E-notation, a
#: symbol with a plain-digit subscript
_HYPHEN_MINUS = re.compile(r"(?<![^\s(\[{=,;:/±<>≤≥≈~×·])-(?=\.?\d)")
_E_NOTATION = re.compile(r"(?<![\w.])\d+(?:\.\d+)?[eE][+\-−]?\d+(?!\w|\.\d)")
_DIGIT_SUBSCRIPT = re.compile(r"(?<![\w.\\'’])[A-Za-zα-ωΑ-Ωϑϕϵℓ][\u0300-\u036f]*\d{1,2}"
                              r"(?!(?![⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺])[\w\u0300-\u036f]|\.\d)"
                              # a product of subscripted symbols: "I3ω3", "4I1Mgl"
                              r"|[A-Za-zα-ω][\u0300-\u036f]*\d{1,2}(?=[A-Za-zα-ωΑ-Ω][\u0300-\u036f]*\d)"
                              r"|(?<=[A-Za-zα-ω]\d)[A-Za-zα-ωΑ-Ω][\u0300-\u036f]*\d{1,2}(?!\w)"
                              r"|(?<=\d)[A-Z]\d(?=[A-Z][a-z])")
#: provenance that belongs to the colophon: an archive path, a tolerance as code
_ARCHIVE_PATH = re.compile(r"(?<![\w/.])/(?:study|runs|analysis|sweep|config|provenance|checks)"
                           r"(?![\w])")
_RTOL_CODE = re.compile(r"\b[ar]tol\s?=")
_PYTHON = [
    (re.compile(r"\*\*"), "'**'"),
    (re.compile(r"[\w)]\s?\*\s?[\w(]"), "'*' as a product"),
    (re.compile(r"==|!="), "a comparison operator"),
    (re.compile(r"\b(?:np|numpy|math)\.\w+"), "a module prefix"),
    (re.compile(r"\b(?:None|True|False)\b"), "a Python constant"),
]
_TEX = [
    (re.compile(r"\\[A-Za-z]+"), "a backslash command"),
    (re.compile(r"[_^]\{"), "a TeX sub/superscript"),
    (re.compile(r"\w\^[\w\-−(]"), "a caret exponent"),
    (re.compile(r"\$[^$\s][^$]*\$"), "TeX math between $"),
]
#: the tables every scene config may have (the generic fallback when the document holds no
#: parsable config)
_COMMON_TABLES = {"params", "initial", "run", "report", "sweep", "boundary", "study",
                  "atoms", "bodies", "springs", "model", "section"}


#: keys every scene config may set ([run], [report]) though this one leaves them default
_COMMON_KEYS = {"t_end", "samples", "method", "rtol", "atol", "study", "study_budget",
                "sections", "formats", "figure_formats"}


def page_findings(document, html_text: str | None = None) -> list[str]:
    """The gate's findings on a laid-out WeasyPrint document (``HTML(...).render()``).

    ``html_text`` is accepted for symmetry with the renderer and not needed: the text
    rules read the laid-out boxes, so they see exactly what is printed.  A failure of the
    gate itself is a finding too: it never stops a report."""
    try:
        return _page_findings(document)
    except Exception as exc:  # noqa: BLE001 - reported in gate.json, which tests read
        return [f"gate: could not check the pages: {type(exc).__name__}: {exc}"]


def _page_findings(document) -> list[str]:
    pages = [_read_page(page._page_box) for page in document.pages]
    tables, keys = _config_names("\n".join(t for p in pages for t in p["config_text"]))
    findings: list[str] = []
    for i, page in enumerate(pages):
        where = f"page {i + 1}"
        for right, text in page["overflow"]:
            findings.append(f"{where}: overflow: '{_short(text, 8)}' passes the content "
                            f"area by {right * 72 / 96:.1f} pt")
        texts = [f for text, in_code in page["texts"]
                 for f in _text_findings(text, in_code, tables, keys)]
        for text, count in Counter(texts).items():  # one line for a repeated cell
            findings.append(f"{where}: {text}" + (f" ({count} times)" if count > 1 else ""))
        if i > 0 and page["fill"] < _MIN_FILL:
            findings.append(f"{where}: fill: the page is {100 * page['fill']:.0f} % full "
                            "(a page needs a quarter)")
    return findings


def _read_page(page_box) -> dict:
    from weasyprint.formatting_structure import boxes

    content_x0 = page_box.content_box_x()
    content_x1 = content_x0 + page_box.width
    content_y0 = page_box.content_box_y()
    page = {"overflow": [], "texts": [], "config_text": [], "fill": 0.0}
    bottom = content_y0

    def walk(box, in_config: bool, in_code: bool, in_footer: bool, reported: bool):
        nonlocal bottom
        element = getattr(box, "element", None)
        tag = getattr(box, "element_tag", None)
        if element is not None and not isinstance(box, boxes.TextBox):
            in_config = in_config or element.get("id") == "config"
            in_code = in_code or tag in ("code", "pre", "kbd", "samp")
            in_footer = in_footer or tag == "footer"
        left = box.border_box_x()
        right = left + box.border_width()
        if isinstance(box, (boxes.LineBox, boxes.ReplacedBox, boxes.TableCellBox)):
            bottom = max(bottom, box.border_box_y() + box.border_height())
        if not reported and not isinstance(box, (boxes.LineBox, boxes.PageBox)) and (
                right > content_x1 + _OVERFLOW_SLACK or left < content_x0 - _OVERFLOW_SLACK):
            text = _box_text(box)
            if text.strip() or isinstance(box, boxes.ReplacedBox):
                over = max(right - content_x1, content_x0 - left)
                page["overflow"].append((over, text.strip() or f"<{tag}>"))
                reported = True  # its children overflow with it: one finding per box
        if isinstance(box, boxes.BlockContainerBox) and any(
                isinstance(c, boxes.LineBox) for c in box.children):
            if in_config and tag == "pre":
                page["config_text"].append(_box_text(box, lines="\n"))
            elif not (in_config or in_footer):
                prose, code = _line_texts(box, in_code)
                page["texts"] += [(t, False) for t in prose] + [(t, True) for t in code]
        for child in getattr(box, "children", ()):
            if isinstance(child, boxes.MarginBox):
                continue
            walk(child, in_config, in_code, in_footer, reported)

    walk(page_box, False, False, False, False)
    page["fill"] = (bottom - content_y0) / page_box.height if page_box.height else 1.0
    return page


def _box_text(box, lines: str = " ") -> str:
    from weasyprint.formatting_structure import boxes

    if isinstance(box, boxes.TextBox):
        return box.text
    parts = []
    for child in getattr(box, "children", ()):
        text = _box_text(child, lines)
        if text:
            parts.append(text)
    return (lines if isinstance(box, boxes.BlockContainerBox) else "").join(parts)


def _line_texts(block, in_code: bool) -> tuple[list[str], list[str]]:
    """The prose text of a block's lines (code spans replaced by a space) and the text of
    each code span; lines are joined with a space."""
    from weasyprint.formatting_structure import boxes

    prose: list[str] = []
    code: list[str] = []

    def collect(box, coding: bool, script: str | None = None):
        if isinstance(box, boxes.TextBox):
            text = box.text.translate(_SCRIPTS[script]) if script else box.text
            if coding:
                if code and code[-1] is not None:
                    code[-1] += text
                else:
                    code.append(text)
                prose.append(" ")
            else:
                if code and code[-1] is not None:
                    code.append(None)
                prose.append(text)
            return
        if isinstance(box, boxes.BlockContainerBox) and box is not block:
            return  # a nested block reports its own lines
        tag = getattr(box, "element_tag", None)
        coding = coding or tag in ("code", "kbd", "samp")
        script = tag if tag in ("sub", "sup") else script
        for child in getattr(box, "children", ()):
            collect(child, coding, script)
        if isinstance(box, boxes.LineBox):
            prose.append(" ")
            if code and code[-1] is not None:
                code.append(None)

    if in_code:  # the whole block is code (a <pre> outside the configuration)
        return [], [_box_text(block, lines="\n")]
    collect(block, False)
    return ["".join(prose)], [c for c in code if c]


#: sub- and superscript text as the gate reads it: Unicode's small digits and signs, so
#: that I<sub>1</sub> reads "I₁", not the plain-digit "I1"
_SCRIPTS = {
    "sub": str.maketrans("0123456789+−-=()aeoxhklmnpstiruvj",
                         "₀₁₂₃₄₅₆₇₈₉₊₋₋₌₍₎ₐₑₒₓₕₖₗₘₙₚₛₜᵢᵣᵤᵥⱼ"),
    "sup": str.maketrans("0123456789+−-=()n", "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁻⁼⁽⁾ⁿ"),
}


def _config_names(config_text: str) -> tuple[set[str], set[str]]:
    """(table names, key names) of the configuration shown at the end of the report."""
    import tomllib

    tables, keys = set(_COMMON_TABLES), set(_COMMON_KEYS)
    try:
        data = tomllib.loads(config_text)
    except (tomllib.TOMLDecodeError, ValueError):
        data = None
    if data is not None:
        def visit(value, path=()):
            if isinstance(value, dict):
                if path:
                    tables.add(".".join(path))
                    tables.add(path[-1])
                for k, v in value.items():
                    if isinstance(v, (dict, list)) and (
                            isinstance(v, dict) or (v and isinstance(v[0], dict))):
                        visit(v, (*path, k))
                    else:
                        keys.add(k)
            elif isinstance(value, list):
                for item in value:
                    visit(item, path)
        visit(data)
    else:
        tables |= set(re.findall(r"^\s*\[\[?\s*([\w.]+)\s*\]\]?", config_text, re.M))
        keys |= set(re.findall(r"^\s*([A-Za-z_]\w*)\s*=", config_text, re.M))
    return tables, keys


def _text_findings(text: str, in_code: bool, tables: set[str], keys: set[str]) -> list[str]:
    """The text rules on one block's text (or one code span's): each offending token
    once, quoted in its context."""
    text = " ".join(text.split())
    if not text:
        return []
    found: dict[str, str] = {}

    def add(rule: str, what: str, m: re.Match) -> None:
        key = f"{rule}: {what} '{m.group(0).strip()}'"
        if key not in found:
            found[key] = f"{key} in {_context(text, m)}"

    for m in _NAN_INF.finditer(text):
        add("number", "not a number", m)
    for m in _NEG_ZERO.finditer(text):
        add("number", "negative zero", m)
    for m in _DOTTED.finditer(text):
        head, tail = m.groups()
        if head in tables and tail.lower() not in _FILE_EXT:
            add("config", "key", m)
    for m in _BRACKET_TABLE.finditer(text):
        if m.group(1) or m.group(2) in tables:
            add("config", "table", m)
    for m in _SNAKE.finditer(text):
        word = m.group(1)
        if word in keys or word in tables:
            add("config", "key", m)
        elif _SUBSCRIPTED.fullmatch(word):
            add("tex", "an underscore subscript", m)
        else:
            add("config", "identifier", m)
    for m in _HYPHEN_MINUS.finditer(text):
        add("type", "an ASCII hyphen as a minus sign", m)
    for m in _E_NOTATION.finditer(text):
        add("type", "E-notation", m)
    for m in _DIGIT_SUBSCRIPT.finditer(text):
        add("type", "a plain-digit subscript", m)
    for m in _ARCHIVE_PATH.finditer(text):
        add("provenance", "an archive path", m)
    for m in _RTOL_CODE.finditer(text):
        add("provenance", "a tolerance as code", m)
    for pattern, what in _PYTHON:
        for m in pattern.finditer(text):
            add("python", what, m)
    for pattern, what in _TEX:
        for m in pattern.finditer(text):
            add("tex", what, m)
    return list(found.values())


def _context(text: str, m: re.Match, width: int = 30) -> str:
    lo, hi = max(0, m.start() - width), min(len(text), m.end() + width)
    return f"'{'…' if lo else ''}{text[lo:hi]}{'…' if hi < len(text) else ''}'"


# ------------------------------------------------------------------- the record

def gate_findings(sections: Iterable[dict], pages: Iterable[str] = ()) -> list[str]:
    """A report's findings: each figure's (kept with it in the figures manifest, under
    ``gate``), prefixed with the figure's id, then the pages'."""
    out = [f"figure {fig['id']}: {f}" for section in sections
           for fig in section.get("figures", ()) for f in fig.get("gate", ())]
    return out + list(pages)


def write_gate(folder: Path, findings: list[str]) -> Path:
    """``folder/gate.json``: the report's findings (a JSON list; empty is a pass)."""
    from ..support.fsutil import atomic_write

    path = Path(folder) / GATE_FILE
    atomic_write(path, json.dumps(findings, ensure_ascii=False, indent=1).encode("utf-8"))
    return path
