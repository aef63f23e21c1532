"""Lighter SVG for the PDF engine: the same picture with fewer things for WeasyPrint to walk.

WeasyPrint draws an SVG node by node in Python: every element costs a cascade, a
graphics-state push/pop and attribute parsing, every ``style="..."`` is run through the
CSS tokenizer, every ``<use>`` clones its target, every path coordinate is parsed with a
regular expression and every character of a ``<text>`` gets its own Pango layout.  A
matplotlib SVG is generous with all of these.  :func:`slim_svg` rewrites one matplotlib
SVG into an equivalent, smaller one:

* ``<metadata>``, comments and indentation whitespace are dropped;
* the ``*{stroke-linejoin; stroke-linecap}`` stylesheet becomes attributes of the root
  (both properties inherit) and every ``style="..."`` becomes presentation attributes;
* no-op ``rotate(0 x y)`` transforms are dropped;
* a marker ``<use>`` (tick marks, line markers) becomes the marker's ``<path>`` with a
  ``translate`` (no clone, no second cascade; paint order unchanged);
* a ``clip-path`` is dropped from a path whose every vertex lies inside the clip rectangle
  by more than the stroke width (nothing to clip);
* ``<g>`` wrappers that carry nothing but an unreferenced id are dissolved, unreferenced
  ids are dropped;
* coordinates are rounded to ``decimals`` decimals of a point (0.01 pt = 3.5 µm);
* a long polyline (a data line, a contour) drops every other vertex that lies within
  ``thin`` points of the chord between its neighbours (0.1 pt = 35 µm, under a
  hairline): up to half of a dense curve's vertices.

Text stays text (``svg.fonttype = "none"``), so the PDF's figure text stays selectable.
The result is deterministic (same input, same bytes).  Anything it does not recognise
(another stylesheet, foreign namespaces, relative path commands...) is left as it was;
an SVG it cannot parse is returned unchanged.

:func:`inline_svgs_as_images` is the HTML side: the report's inline ``<svg>`` figures
become ``<img>`` elements of the slim SVG (a file, or a ``data:`` URL), so WeasyPrint's
HTML parser, cascade and box builder never see the figures' thousands of nodes (the
image is drawn by WeasyPrint's SVG code, which is also what draws inline SVG).
"""

from __future__ import annotations

import base64
import hashlib
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from xml.sax.saxutils import escape, quoteattr

from ..support.fsutil import atomic_write

__all__ = ["slim_svg", "slim_cached", "warm_cache", "prune_cache", "inline_svgs_as_images"]

SVG_NS = "http://www.w3.org/2000/svg"
XLINK_NS = "http://www.w3.org/1999/xlink"
_S = "{" + SVG_NS + "}"
_XLINK_HREF = "{" + XLINK_NS + "}href"

#: attributes that hold coordinates or lengths in user units (rounded, as are "d" and the
#: lengths of translate()/rotate() transforms)
_GEOMETRY = ("x", "y", "width", "height", "x1", "y1", "x2", "y2", "cx", "cy", "r", "rx",
             "ry", "points")
_ABS_PATH = re.compile(r"^[MLCQZz0-9eE.,+\-\s]*$")
_PATH_COMMAND = re.compile(r"([MLCQZz])")
_NOOP_ROTATE = re.compile(r"^\s*rotate\(\s*[-+]?0(?:\.0*)?(?:\s+[-+\d.eE]+\s+[-+\d.eE]+)?\s*\)\s*$")
_TRANSLATE_ROTATE = re.compile(r"\b(translate\(|rotate\()([^)]*)\)")
_URL_REF = re.compile(r"url\(\s*#([^)\s]+)\s*\)")
_STAR_RULE = re.compile(r"^\s*\*\s*\{([^{}]*)\}\s*$")


class _Skip(Exception):
    """The SVG has something this module does not rewrite; leave it unchanged."""


# ----------------------------------------------------------------------------- numbers
def _fmt(value: float, decimals: int) -> str:
    text = "%.*f" % (decimals, value)  # noqa: UP031 (the fastest spelling)
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text == "-0" else text


def _round_numbers(text: str, decimals: int) -> str:
    """Every number of ``text`` with more than ``decimals`` decimals, rounded."""
    long_number = _LONG_NUMBER.get(decimals)
    if long_number is None:
        long_number = _LONG_NUMBER[decimals] = re.compile(
            r"[-+]?\d*\.\d{" + str(decimals + 1) + r",}(?:[eE][-+]?\d+)?|[-+]?\d+\.?[eE][-+]?\d+")
    return long_number.sub(lambda m: _fmt(float(m.group()), decimals), text)


_LONG_NUMBER: dict[int, re.Pattern] = {}


def _referenced_ids(root: ET.Element) -> set[str]:
    """Ids something in the SVG points at (href="#id", url(#id))."""
    ids = set()
    for el in root.iter():
        for key, value in el.attrib.items():
            if key == _XLINK_HREF or key == "href":
                if value.startswith("#"):
                    ids.add(value[1:])
            elif "url(" in value:
                ids.update(_URL_REF.findall(value))
    return ids


# ----------------------------------------------------------------------------- paths
_PATH_ARITY = {"M": 2, "L": 2, "C": 6, "Q": 4, "Z": 0, "z": 0}


def _parse_abs_path(d: str) -> list[tuple[str, list[float]]] | None:
    """[(command, [x0, y0, x1, y1, ...]), ...] of a path made of absolute M/L/C/Q/Z only."""
    if not _ABS_PATH.match(d):
        return None
    parts = _PATH_COMMAND.split(d)
    if parts[0].strip():
        return None
    segments: list[tuple[str, list[float]]] = []
    for i in range(1, len(parts), 2):
        command = parts[i]
        try:
            numbers = [float(v) for v in parts[i + 1].replace(",", " ").split()]
        except ValueError:  # "1-2": numbers not separated by blanks
            return None
        n = _PATH_ARITY[command]
        if (n == 0 and numbers) or (n and (not numbers or len(numbers) % n)):
            return None
        segments.append((command, numbers))
    return segments


def _path_text(segments, dx: float, dy: float, decimals: int) -> str:
    out = []
    for command, numbers in segments:
        out.append(command)
        if dx or dy:
            numbers = [v + (dx if i % 2 == 0 else dy) for i, v in enumerate(numbers)]
        out.extend(_fmt(v, decimals) for v in numbers)
    return " ".join(out)


#: polylines shorter than this are left as they are
_THIN_MIN_POINTS = 32


def _thinned(segments, tolerance: float):
    """``segments`` with each long polyline (an M, then L's, perhaps a Z) thinned by
    :func:`_thin_polyline`; None when the path has curves or nothing to thin."""
    if any(command not in "MLZz" for command, _ in segments):
        return None
    runs: list[list[float]] = []  # the vertices of each subpath
    closes: list[str] = []  # its closing command, or ""
    for command, numbers in segments:
        if command == "M":
            runs.append(list(numbers))
            closes.append("")
        elif not runs or closes[-1]:
            return None  # a line after a close, or before any move
        elif command == "L":
            runs[-1].extend(numbers)
        else:
            closes[-1] = command
    if not any(len(run) >= 2 * _THIN_MIN_POINTS for run in runs):
        return None
    out = []
    for run, close in zip(runs, closes, strict=True):
        kept = _thin_polyline(run, tolerance) if len(run) >= 2 * _THIN_MIN_POINTS else None
        points = kept if kept is not None else [run[i:i + 2] for i in range(0, len(run), 2)]
        out.append(("M", points[0]))
        out.extend(("L", point) for point in points[1:])
        if close:
            out.append((close, []))
    return out


def _thin_polyline(coordinates: list[float], tolerance: float) -> list[list[float]] | None:
    """The vertices (x, y) of a polyline with every other vertex that lies within
    ``tolerance`` of the segment between its neighbours dropped (never two neighbours, so
    the new line stays within ``tolerance`` of the old), else None when none is dropped.
    One vectorized pass: it halves a dense curve at most, at a cost that does not grow
    with the vertices kept (Ramer-Douglas-Peucker's does)."""
    import numpy as np

    xy = np.array(coordinates, dtype=float).reshape(-1, 2)
    before, point, after = xy[:-2], xy[1:-1], xy[2:]
    chord, rel = after - before, point - before
    # distance to the chord as a segment, not as a line: the tip of a cusp or of a
    # reversal lies on the line through its neighbours but not between them
    length2 = chord[:, 0] ** 2 + chord[:, 1] ** 2
    along = np.clip((rel[:, 0] * chord[:, 0] + rel[:, 1] * chord[:, 1])
                    / np.where(length2 > 0, length2, 1.0), 0.0, 1.0)
    dist = np.hypot(rel[:, 0] - along * chord[:, 0], rel[:, 1] - along * chord[:, 1])
    near = dist < tolerance
    if not near.any():
        return None
    index = np.arange(near.size)
    run_start = np.maximum.accumulate(np.where(near & ~np.r_[False, near[:-1]], index, 0))
    drop = near & ((index - run_start) % 2 == 0)  # every other one of a run of near ones
    keep = np.ones(len(xy), dtype=bool)
    keep[1:-1] = ~drop
    return xy[keep].tolist()


def _path_extent(segments) -> tuple[float, float, float, float] | None:
    xs = [v for _, numbers in segments for v in numbers[0::2]]
    ys = [v for _, numbers in segments for v in numbers[1::2]]
    if not xs:
        return None
    return min(xs), min(ys), max(xs), max(ys)


# ----------------------------------------------------------------------------- styles
def _declarations(text: str) -> list[tuple[str, str]] | None:
    out = []
    for part in text.split(";"):
        if not part.strip():
            continue
        if ":" not in part or "!" in part or "/*" in part:
            return None
        name, value = part.split(":", 1)
        out.append((name.strip(), value.strip()))
    return out


def _float(value: str | None, default: float) -> float:
    if value is None:
        return default
    try:
        return float(value)
    except ValueError:
        return math.nan


# ----------------------------------------------------------------------------- rewrite
def _local(tag: str) -> str:
    if not tag.startswith(_S):
        raise _Skip(tag)
    return tag[len(_S):]


def _slim_tree(root: ET.Element, decimals: int, thin: float) -> None:
    memo: dict[str, list | None] = {}

    def parse(d: str):
        """_parse_abs_path, once per distinct path text."""
        if d not in memo:
            memo[d] = _parse_abs_path(d)
        return memo[d]

    parent_of = {child: parent for parent in root.iter() for child in parent}

    # metadata out; tags we know
    for el in list(root.iter()):
        if el.tag == _S + "metadata":
            parent_of[el].remove(el)
    for el in root.iter():
        _local(el.tag)
        for key in el.attrib:
            if key.startswith("{") and key != _XLINK_HREF:
                raise _Skip(key)

    # the stylesheet: only matplotlib's "*{...}" rule is understood
    star: list[tuple[str, str]] = []
    for el in list(root.iter(_S + "style")):
        match = _STAR_RULE.match(el.text or "")
        decls = _declarations(match.group(1)) if match else None
        if decls is None:
            raise _Skip("stylesheet")
        star.extend(decls)
        parent_of[el].remove(el)
    star_names = {name for name, _ in star}
    for el in root.iter():
        # the rule beat any presentation attribute an element had
        for name, value in star:
            if name in el.attrib and el is not root:
                el.set(name, value)
        style = el.attrib.pop("style", None)
        if style is not None:
            decls = _declarations(style)
            if decls is None:
                raise _Skip("style attribute")
            for name, value in decls:
                el.set(name, value)
    if star_names - {"stroke-linejoin", "stroke-linecap", "fill-rule", "stroke-miterlimit"}:
        raise _Skip("stylesheet property that does not inherit")
    for name, value in star:
        root.set(name, value)
    # the rule set these on every element: where a descendant would now inherit another
    # value from an ancestor that sets it, give the descendant the rule's value
    for el in root.iter():
        if el is root:
            continue
        for name, value in star:
            if name in el.attrib:
                for child in el:
                    child.attrib.setdefault(name, value)

    # marker <use> -> the marker's <path>, translated to the use's place (same paint order)
    defs: dict[str, ET.Element] = {el.get("id"): el for el in root.iter() if el.get("id")}
    for parent in list(root.iter()):
        for i, child in enumerate(list(parent)):
            if child.tag != _S + "use":
                continue
            expanded = _expandable_use(child, defs)
            if expanded is None:
                continue
            segments, attrs = expanded
            x, y = _use_xy(child)
            path = ET.Element(_S + "path", {"d": _path_text(segments, 0.0, 0.0, decimals)})
            if x or y:
                path.set("transform", f"translate({_fmt(x, decimals)} {_fmt(y, decimals)})")
            for k, v in attrs.items():
                path.set(k, v)
            path.tail = child.tail
            parent.remove(child)
            parent.insert(i, path)

    _merge_marker_runs(root, parse, decimals)

    # markers' <defs> that no <use> needs any more
    still_used = _referenced_ids(root)
    parent_of = {child: parent for parent in root.iter() for child in parent}
    for el in list(root.iter(_S + "defs")):
        for child in list(el):
            if child.tag == _S + "path" and child.get("id") not in still_used:
                el.remove(child)
        if len(el) == 0:
            parent_of[el].remove(el)

    # clip rectangles, and clips that clip nothing
    clips: dict[str, tuple[float, float, float, float]] = {}
    for cp in root.iter(_S + "clipPath"):
        kids = list(cp)
        if (len(kids) == 1 and kids[0].tag == _S + "rect" and "transform" not in kids[0].attrib
                and "transform" not in cp.attrib and
                cp.get("clipPathUnits", "userSpaceOnUse") == "userSpaceOnUse"):
            x, y, w, h = (_float(kids[0].get(k), math.nan) for k in ("x", "y", "width", "height"))
            if not any(math.isnan(v) for v in (x, y, w, h)):
                clips[cp.get("id")] = (x, y, x + w, y + h)
    for el in root.iter():
        ref = _URL_REF.fullmatch(el.get("clip-path", "").strip())
        if not ref or ref.group(1) not in clips or "transform" in el.attrib:
            continue
        extent = _element_extent(el, parse)
        if extent is None:
            continue
        margin = _stroke_margin(el, parent_of)
        x0, y0, x1, y1 = clips[ref.group(1)]
        ex0, ey0, ex1, ey1 = extent
        if ex0 - margin > x0 and ey0 - margin > y0 and ex1 + margin < x1 and ey1 + margin < y1:
            del el.attrib["clip-path"]

    # no-op rotations, rounding, thinning (where user units are points), whitespace
    transformed = {el for top in root.iter() if top is not root and "transform" in top.attrib
                   for el in top.iter()}
    has_viewbox_scale = not _user_unit_is_point(root)
    for el in root.iter():
        if el is root:
            continue
        transform = el.get("transform")
        if transform is not None:
            if _NOOP_ROTATE.match(transform):
                del el.attrib["transform"]
            else:
                # lengths only: translate(x y), rotate(a x y); scale/matrix factors stay
                el.set("transform", _TRANSLATE_ROTATE.sub(
                    lambda m: m.group(1) + " ".join(
                        _round_numbers(m.group(2), decimals).split()) + ")", transform))
        d = el.get("d")
        if d is not None:
            segments = parse(d)
            if segments and thin > 0 and el not in transformed and not has_viewbox_scale:
                segments = _thinned(segments, thin) or segments
            el.set("d", _path_text(segments, 0.0, 0.0, decimals) if segments
                   else " ".join(_round_numbers(d, decimals).split()))
        for key in _GEOMETRY:
            value = el.get(key)
            if value is not None:
                el.set(key, " ".join(_round_numbers(value, decimals).split()))

    # drop ids nobody points at, dissolve bare <g>
    used_now = _referenced_ids(root)
    for el in root.iter():
        if el is not root and "id" in el.attrib and el.get("id") not in used_now:
            del el.attrib["id"]
    _dissolve_groups(root)


def _user_unit_is_point(root: ET.Element) -> bool:
    """Whether one user unit of the drawing is one point (matplotlib's width="Wpt" with
    viewBox="0 0 W H"), so that tolerances in points apply to coordinates as they are."""
    width, box = root.get("width", ""), root.get("viewBox", "").replace(",", " ").split()
    if not width.endswith("pt") or len(box) != 4:
        return False
    try:
        return math.isclose(float(width[:-2]), float(box[2]), rel_tol=1e-9)
    except ValueError:
        return False


def _paint_order_free(attrs: dict[str, str], segments) -> bool:
    """Whether drawing copies of this path as one path (all fills, then all strokes) looks
    the same as drawing them one by one: opaque paint, and no fill showing through
    another copy's stroke (no fill, no stroke, the same colour for both, or only
    two-point lines, whose fill paints nothing)."""
    if any(attrs.get(k, "1") not in ("1", "1.0") for k in ("opacity", "fill-opacity",
                                                           "stroke-opacity")):
        return False
    fill, stroke = attrs.get("fill"), attrs.get("stroke", "none")
    if fill == "none" or stroke == "none" or (fill is not None and fill == stroke):
        return True
    return all(command in "ML" for command, _ in segments) and sum(
        len(numbers) for _, numbers in segments) == 4 and segments[0][0] == "M"


def _merge_marker_runs(root: ET.Element, parse, decimals: int) -> None:
    """Consecutive sibling paths that differ only by a translation (a line's markers, an
    axis's tick marks) become one path of translated subpaths, where that looks the same
    (:func:`_paint_order_free`): one node for WeasyPrint instead of dozens."""
    for parent in list(root.iter()):
        children = list(parent)
        i = 0
        while i < len(children):
            first = children[i]
            key = _marker_key(first, parse)
            j = i + 1
            while j < len(children) and key is not None and _marker_key(children[j], parse) == key:
                j += 1
            if j - i > 1:
                parts = []
                for el in children[i:j]:
                    dx, dy = _shift(el) or (0.0, 0.0)
                    parts.append(_path_text(parse(el.get("d")), dx, dy, decimals))
                first.set("d", " ".join(parts))
                first.attrib.pop("transform", None)
                first.tail = children[j - 1].tail
                for el in children[i + 1:j]:
                    parent.remove(el)
            i = j


def _marker_key(el: ET.Element, parse):
    """What must agree for ``el`` to join a run of translated copies, else None."""
    if el.tag != _S + "path" or "id" in el.attrib:
        return None
    if "transform" in el.attrib and _shift(el) is None:
        return None
    segments = parse(el.get("d", ""))
    if not segments:
        return None
    attrs = {k: v for k, v in el.attrib.items() if k not in ("d", "transform")}
    if not _paint_order_free(attrs, segments):
        return None
    return tuple(sorted(attrs.items())), el.get("d")


def _use_xy(el: ET.Element) -> tuple[float, float]:
    return _float(el.get("x"), 0.0), _float(el.get("y"), 0.0)


def _expandable_use(use: ET.Element, defs: dict[str, ET.Element]):
    """(segments, attributes) for a <use> of a plain absolute path, else None."""
    href = use.get(_XLINK_HREF, use.get("href"))
    if not href or not href.startswith("#"):
        return None
    target = defs.get(href[1:])
    if target is None or target.tag != _S + "path" or len(target):
        return None
    if set(use.attrib) - {_XLINK_HREF, "href", "x", "y", "fill", "stroke", "stroke-width",
                          "fill-opacity", "stroke-opacity", "stroke-linecap",
                          "stroke-linejoin"}:
        return None
    if set(target.attrib) - {"id", "d", "fill", "stroke", "stroke-width", "fill-opacity",
                             "stroke-opacity", "stroke-linecap", "stroke-linejoin"}:
        return None
    x, y = _use_xy(use)
    if math.isnan(x) or math.isnan(y):
        return None
    segments = _parse_abs_path(target.get("d", ""))
    if not segments:
        return None
    # the clone inherits the use's properties; the target's own ones win
    attrs = {k: v for k, v in use.attrib.items() if k not in (_XLINK_HREF, "href", "x", "y")}
    attrs.update({k: v for k, v in target.attrib.items() if k not in ("id", "d")})
    return segments, attrs


_TRANSLATE_ONLY = re.compile(r"^\s*translate\(\s*([-+\d.eE]+)(?:[\s,]+([-+\d.eE]+))?\s*\)\s*$")


def _shift(el: ET.Element) -> tuple[float, float] | None:
    """The element's transform as (dx, dy) when it is none or a translation, else None."""
    transform = el.get("transform")
    if transform is None:
        return 0.0, 0.0
    match = _TRANSLATE_ONLY.match(transform)
    if not match:
        return None
    return float(match.group(1)), float(match.group(2) or 0.0)


def _path_box(el: ET.Element, parse):
    if el.tag != _S + "path" or len(el) or "clip-path" in el.attrib:
        return None
    shift = _shift(el)
    segments = parse(el.get("d", ""))
    box = _path_extent(segments) if segments and shift else None
    if box is None:
        return None
    dx, dy = shift
    return box[0] + dx, box[1] + dy, box[2] + dx, box[3] + dy


def _element_extent(el: ET.Element, parse):
    """Bounding box of the vertices of a path, or of a group of paths, in the parent's
    user space (None when it is anything else)."""
    if el.tag == _S + "path":
        segments = parse(el.get("d", ""))
        return _path_extent(segments) if segments else None
    if el.tag == _S + "g" and len(el) and "transform" not in el.attrib:
        boxes = [_path_box(child, parse) for child in el]
        if any(box is None for box in boxes):
            return None
        return (min(b[0] for b in boxes), min(b[1] for b in boxes),
                max(b[2] for b in boxes), max(b[3] for b in boxes))
    return None


def _inherited(el: ET.Element, name: str, parent_of) -> str | None:
    node = el
    while node is not None:
        if name in node.attrib:
            return node.get(name)
        node = parent_of.get(node)
    return None


def _stroke_margin(el: ET.Element, parent_of) -> float:
    """How far past its vertices a path (or a group of paths) may paint."""
    widths = [1.0]
    for node in [el, *list(el)]:
        stroke = _inherited(node, "stroke", parent_of)
        if stroke in (None, "none"):
            continue
        width = _float(_inherited(node, "stroke-width", parent_of), 1.0)
        if math.isnan(width):
            return math.inf
        # round joins/caps reach width / 2 past a vertex, square caps width / sqrt(2),
        # miter joins up to stroke-miterlimit * width / 2
        join = _inherited(node, "stroke-linejoin", parent_of) or "miter"
        limit = _float(_inherited(node, "stroke-miterlimit", parent_of), 4.0)
        factor = limit / 2 if join == "miter" else 1.0
        widths.append(width * max(factor, 1.0))
    return max(widths)


def _dissolve_groups(node: ET.Element) -> None:
    changed = True
    while changed:
        changed = False
        new_children = []
        for child in list(node):
            if child.tag == _S + "g" and not child.attrib and not (child.text or "").strip():
                new_children.extend(list(child))
                changed = True
            else:
                new_children.append(child)
        if changed:
            for child in list(node):
                node.remove(child)
            node.extend(new_children)
    for child in node:
        if child.tag != _S + "text":
            _dissolve_groups(child)


# ----------------------------------------------------------------------------- output
def _serialize(el: ET.Element, out: list[str], in_text: bool = False, root: bool = False) -> None:
    tag = el.tag[len(_S):]
    out.append("<" + tag)
    if root:
        out.append(f' xmlns="{SVG_NS}" xmlns:xlink="{XLINK_NS}"')
    for key, value in el.attrib.items():
        name = "xlink:href" if key == _XLINK_HREF else key
        out.append(f" {name}={quoteattr(value)}")
    inside_text = in_text or tag in ("text", "tspan", "textPath")
    text = el.text or ""
    if not text.strip() and (not inside_text or "\n" in text):
        text = ""  # indentation
    if len(el) == 0 and not text:
        out.append("/>")
    else:
        out.append(">")
        out.append(escape(text))
        for child in el:
            _serialize(child, out, inside_text)
            tail = child.tail or ""
            if inside_text and tail and (tail.strip() or "\n" not in tail):
                out.append(escape(tail))
        out.append(f"</{tag}>")


def slim_svg(svg_text: str, decimals: int = 2, thin: float = 0.1) -> str:
    """The SVG rewritten lighter for WeasyPrint (see the module docstring); unchanged when
    it holds something this module does not rewrite.  ``thin``: the polyline tolerance in
    points (0: keep every vertex)."""
    start = svg_text.find("<svg")
    if start < 0:
        return svg_text
    try:
        root = ET.fromstring(svg_text[start:])
        if root.tag != _S + "svg":
            return svg_text
        _slim_tree(root, decimals, thin)
    except (ET.ParseError, _Skip, ValueError):
        return svg_text
    out: list[str] = []
    _serialize(root, out, root=True)
    return "".join(out)


_INLINE_SVG = re.compile(r"<svg\b.*?</svg>", re.S)

#: a slim copy's file name changes with this module's output
_SLIM_VERSION = "3"


def slim_cached(svg: str, cache: Path, decimals: int = 2, thin: float = 0.1) -> Path:
    """The file in ``cache`` holding the slim copy of ``svg`` (an inline ``<svg>`` as the
    report's HTML carries it), made now unless an earlier call made it.  Named by the
    content and the settings, so a stale copy is never used."""
    key = hashlib.sha256(f"{_SLIM_VERSION}:{decimals}:{thin}:{svg}".encode()).hexdigest()
    path = Path(cache) / f"{key[:32]}.svg"
    if not path.exists():
        text = slim_svg(svg, decimals, thin)
        if "xmlns=" not in text[:text.find(">")]:
            text = text.replace("<svg", f'<svg xmlns="{SVG_NS}"', 1)
        Path(cache).mkdir(parents=True, exist_ok=True)
        atomic_write(path, text.encode("utf-8"))
    return path


def warm_cache(text: str, cache: Path, decimals: int = 2) -> None:
    """Make the slim copies of the ``<svg>`` elements in ``text`` (the figures stage does
    this while it draws, so the PDF stage finds them made)."""
    for match in _INLINE_SVG.finditer(text):
        slim_cached(match.group(0), cache, decimals)


def prune_cache(cache: Path, keep: set[Path]) -> None:
    """Delete the slim copies in ``cache`` other than ``keep`` (those of older figures)."""
    keep = {Path(p).resolve() for p in keep}
    for path in Path(cache).glob("*.svg"):
        if path.resolve() not in keep:
            path.unlink(missing_ok=True)


def inline_svgs_as_images(html_text: str, slim: bool = True, decimals: int = 2,
                          folder: Path | None = None, cache: Path | None = None,
                          used: set[Path] | None = None) -> str:
    """The HTML with every inline ``<svg>...</svg>`` replaced by an ``<img>`` of it (the
    SVG's own width/height give the image's size).

    The image is the slimmed SVG: the copy in ``cache`` (see :func:`slim_cached`; the
    files used are added to ``used``) when one is given, else written to ``folder``
    (``figure-<n>.svg``, referenced by a ``file:`` URL), else inlined as a ``data:`` URL
    -- whose long attribute value costs the HTML parser some 5 ms per 100 kB.
    """
    count = 0

    def image(match: re.Match) -> str:
        nonlocal count
        svg = match.group(0)
        head = svg[:svg.find(">")]
        # an inline equation (reportgen.rendering.equations) keeps its baseline: its vertical-align
        lowered = _VERTICAL_ALIGN.search(head)
        tag = (f'<img class="svg-eq" alt="" style="{lowered.group(0)}"' if lowered
               else '<img class="svg-figure" alt=""')
        if slim and cache is not None:
            path = slim_cached(svg, cache, decimals)
            if used is not None:
                used.add(path)
            return f'{tag} src="{path.resolve().as_uri()}">'
        if slim:
            svg = slim_svg(svg, decimals)
        if "xmlns=" not in svg[:svg.find(">")]:
            svg = svg.replace("<svg", f'<svg xmlns="{SVG_NS}"', 1)
        if folder is not None:
            path = Path(folder) / f"figure-{count}.svg"
            count += 1
            atomic_write(path, svg.encode("utf-8"))  # renamed over a link, never through
            src = path.resolve().as_uri()
        else:
            src = "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode("ascii")
        return f'{tag} src="{src}">'

    return _INLINE_SVG.sub(image, html_text)


_VERTICAL_ALIGN = re.compile(r"vertical-align:\s*-?[\d.]+pt")
