"""The SVG sanitizer: a figure file read back from an output folder (untrusted) made into a
plain drawing that a page may inline.

The file is parsed as XML (expat, the standard library's parser) and written out again
from an allow-list: the elements, attributes and style properties a matplotlib figure
uses, references only to the drawing's own elements (``#id``) or to an embedded PNG or
JPEG, style sheets only of SVG paint properties.  Whatever else is there (``<script>``,
``<foreignObject>``, event handlers, links out, ``@import``, animation that rewrites
attributes, entity declarations) is not written; the metadata, comments and the XML
declaration are dropped quietly, as they draw nothing.

Why a parser and an allow-list of our own rather than nh3 (ammonia) or bleach: those parse
the text as an HTML fragment, where SVG is foreign content.  ammonia compares attribute
*local* names, so ``href`` and ``xlink:href`` are one entry and a ``data:`` scheme is
allowed for every data URL or none; a ``<style>`` it keeps passes its CSS unread; and an
HTML parser guesses at XML's case (``viewBox``, ``clipPath``) through a fix-up table.
The files are XML (matplotlib writes them with their namespaces), so an XML parser sees
exactly what an SVG renderer sees, namespaced names included; the standard library needs no
new dependency; and what is written out is only what the allow-list names, escaped, so it
means the same to an XML parser (the PDF engine) and to an HTML parser (a page that inlines
it: no element of the list leaves SVG's foreign content, no text is markup).
"""

from __future__ import annotations

import re
from typing import NamedTuple
from xml.parsers import expat

from .layout import visible_controls

__all__ = ["SvgRefused", "CleanSvg", "clean_svg", "svg_safe"]

SVG_NS = "http://www.w3.org/2000/svg"
XLINK_NS = "http://www.w3.org/1999/xlink"
XML_NS = "http://www.w3.org/XML/1998/namespace"

#: deeper nesting than this is refused (a matplotlib figure nests ~10 deep)
MAX_DEPTH = 100

#: the drawing elements (SVG namespace, or none: an inline ``<svg>`` needs no ``xmlns``)
ELEMENTS = frozenset({
    "svg", "g", "defs", "symbol", "use", "path", "rect", "circle", "ellipse", "line",
    "polyline", "polygon", "text", "tspan", "title", "desc", "clipPath", "mask", "marker",
    "pattern", "linearGradient", "radialGradient", "stop", "filter", "feColorMatrix",
    "feComposite", "feFlood", "feOffset", "feGaussianBlur", "feMerge", "feMergeNode",
    "feBlend", "image", "style",
})
#: elements that draw nothing: left out without counting as removed
QUIET = frozenset({"metadata"})

#: SVG paint properties: what a ``<style>`` sheet may set (it applies to the whole page
#: that inlines it, and none of these applies to an HTML element) and a ``style`` attribute
_PAINT = frozenset({
    "fill", "fill-opacity", "fill-rule", "stroke", "stroke-width", "stroke-opacity",
    "stroke-linecap", "stroke-linejoin", "stroke-miterlimit", "stroke-dasharray",
    "stroke-dashoffset", "clip-rule", "marker-start", "marker-mid", "marker-end",
    "stop-color", "stop-opacity", "vector-effect", "shape-rendering", "text-rendering",
    "image-rendering", "paint-order", "text-anchor", "dominant-baseline",
    "alignment-baseline", "baseline-shift", "color-interpolation-filters",
})
#: what else a ``style`` attribute may set on one element (a figure's text and opacity):
#: no position, size, transform or content, so a drawing cannot leave its own box
PROPERTIES = _PAINT | frozenset({
    "opacity", "clip-path", "mask", "filter", "font", "font-family", "font-size",
    "font-style", "font-weight", "font-variant", "font-stretch", "letter-spacing",
    "word-spacing", "writing-mode", "text-decoration", "visibility", "display", "color",
    "overflow", "vertical-align",
})
#: attributes without a namespace (presentation attributes: the properties above)
ATTRIBUTES = PROPERTIES | frozenset({
    "id", "x", "y", "width", "height", "x1", "y1", "x2", "y2", "cx", "cy", "r", "rx", "ry",
    "fx", "fy", "fr", "d", "points", "transform", "viewBox", "preserveAspectRatio",
    "version", "dx", "dy", "rotate", "textLength", "lengthAdjust", "clipPathUnits",
    "maskUnits", "maskContentUnits", "patternUnits", "patternContentUnits",
    "patternTransform", "gradientUnits", "gradientTransform", "spreadMethod", "offset",
    "filterUnits", "primitiveUnits", "in", "in2", "result", "operator", "k1", "k2", "k3",
    "k4", "type", "values", "stdDeviation", "mode", "flood-color", "flood-opacity",
    "markerWidth", "markerHeight", "markerUnits", "refX", "refY", "orient",
    "aria-hidden", "aria-label", "role", "style",
})
#: the root may not move itself over the page that inlines it
ROOT_EXCLUDED = frozenset({"transform", "x", "y"})
#: the elements whose link may name an element of the drawing (``#id``)
_LINKS_IN = frozenset({"use", "pattern", "linearGradient", "radialGradient", "filter",
                       "mask"})
_FRAGMENT = re.compile(r"#[^\s\"'<>()\\]*")
_DATA_IMAGE = re.compile(r"data:image/(?:png|jpeg);base64,[A-Za-z0-9+/=\s]*")
#: a CSS value: functions allowed (a url() only to ``#id``); no escapes, comments, at-rules
_CSS_FUNCTION = re.compile(r"([A-Za-z_-][\w-]*)\s*\(")
_CSS_FUNCTIONS = frozenset({"rgb", "rgba", "hsl", "hsla", "url"})
_CSS_URL = re.compile(r"url\(\s*(['\"]?)#[\w.:-]*\1\s*\)", re.IGNORECASE)
_CSS_FORBIDDEN = re.compile(r"[\\@<>{}]|/\*|expression", re.IGNORECASE)
#: a ``<style>`` sheet: rules for every element (``*``), matplotlib's one selector
_CSS_RULE = re.compile(r"\s*\*\s*\{([^{}]*)\}\s*")


class SvgRefused(ValueError):
    """An SVG that cannot be made safe by leaving things out: not well-formed XML, no
    ``<svg>`` root, a document type with declarations of its own (entities), too deep."""


class CleanSvg(NamedTuple):
    #: the drawing as markup, from ``<svg`` to ``</svg>``, with its namespaces declared
    svg: str
    #: what was left out, one phrase each ("element script", "attribute onload", ...)
    removed: tuple[str, ...]


def svg_safe(data: bytes | str) -> bool:
    """Whether the SVG ``data`` is a plain drawing: the sanitizer (:func:`clean_svg`)
    leaves nothing out but metadata.  What matplotlib writes is; a figure file that is
    not is drawn again rather than reused."""
    try:
        return not clean_svg(data).removed
    except SvgRefused:
        return False


def clean_svg(data: bytes | str) -> CleanSvg:
    """The SVG ``data`` (a file's bytes, or text) written out again from the allow-list
    (module docstring); SvgRefused when it is no SVG document that can be."""
    writer = _Writer()
    parser = expat.ParserCreate(namespace_separator="}")
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    parser.buffer_text = True
    parser.StartDoctypeDeclHandler = _doctype
    parser.EntityDeclHandler = _entity
    parser.SkippedEntityHandler = _skipped
    parser.ExternalEntityRefHandler = _external
    parser.StartElementHandler = writer.start
    parser.EndElementHandler = writer.end
    parser.CharacterDataHandler = writer.text
    try:
        parser.Parse(data, True)
    except expat.ExpatError as exc:
        raise SvgRefused(f"not well-formed XML ({expat.ErrorString(exc.code)}, line "
                         f"{exc.lineno})") from None
    if not writer.out:
        raise SvgRefused("no <svg> root element")
    return CleanSvg("".join(writer.out), tuple(writer.removed))


def _doctype(name, system_id, public_id, has_internal_subset):
    # matplotlib names the SVG 1.1 DTD, which no parser here reads; declarations of the
    # file's own (entities: a billion laughs, a local file) are refused
    if has_internal_subset:
        raise SvgRefused("a document type with declarations of its own")


def _entity(*args):
    raise SvgRefused("an entity declaration")


def _skipped(name, is_parameter_entity):
    raise SvgRefused(f"an undeclared entity &{name};")


def _external(*args):
    raise SvgRefused("an external entity")


def _split(name: str) -> tuple[str, str]:
    """(namespace, local name) of an expat name ``"uri}local"`` or ``"local"``."""
    ns, _, local = name.rpartition("}")
    return ns, local


def _escape(text: str) -> str:
    """Text content as markup, its control characters shown (as a page shows them)."""
    return visible_controls(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _quote(value: str) -> str:
    """An attribute value (one without control characters) for double quotes."""
    return (value.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace('"', "&quot;").replace("\n", "&#10;").replace("\r", "&#13;")
            .replace("\t", "&#9;"))


def _css_ok(value: str) -> bool:
    """Whether a CSS value calls no function but colours and ``url(#id)`` and holds no
    escape, comment, at-rule, markup or control character."""
    if _CSS_FORBIDDEN.search(value) or visible_controls(value) != value:
        return False
    for m in _CSS_FUNCTION.finditer(value):
        name = m.group(1).lower()
        if name not in _CSS_FUNCTIONS or (name == "url" and not _CSS_URL.match(value, m.start())):
            return False
    return True


def _declarations(text: str, allowed: frozenset[str]) -> list[str] | None:
    """The CSS declarations ``text`` (``a: b; c: d``) if every property is in ``allowed``
    and every value passes :func:`_css_ok`, else None."""
    out = []
    for part in text.split(";"):
        if not part.strip():
            continue
        prop, colon, value = part.partition(":")
        prop = prop.strip()
        if not colon or prop.lower() not in allowed or prop != prop.lower() or not _css_ok(value):
            return None
        out.append(part.strip())
    return out


class _Writer:
    """The expat handlers: each allowed element written as it is parsed, a removed one
    with everything inside it left out."""

    def __init__(self):
        self.out: list[str] = []
        self.removed: list[str] = []
        self.stack: list[str | None] = []  # the written name of each open element, or None
        self.skipping = 0  # depth inside a left-out element
        self.pending = False  # a start tag written without its ">" (it may close as "/>")
        self.style: list[str] | None = None  # the text of an open <style>, checked at its end
        self.style_bad = False  # markup inside the open <style>
        self.style_attrs = ""
        self.done = False

    def _remove(self, what: str) -> None:
        if len(self.removed) < 50:
            self.removed.append(what[:120])

    def _close_pending(self) -> None:
        if self.pending:
            self.out.append(">")
            self.pending = False

    def start(self, name: str, attrs: dict[str, str]) -> None:
        if len(self.stack) >= MAX_DEPTH:
            raise SvgRefused(f"elements nested deeper than {MAX_DEPTH}")
        ns, local = _split(name)
        if not self.stack and (self.done or local != "svg" or ns not in ("", SVG_NS)):
            raise SvgRefused(f"the root element is <{local}>, not <svg>")
        if self.skipping or self.style is not None:  # inside a left-out element or a sheet
            self.style_bad = self.style_bad or not self.skipping  # a sheet is text only
            self.skipping += 1
            self.stack.append(None)
            return
        if ns not in ("", SVG_NS) or local not in ELEMENTS:
            if local not in QUIET or ns not in ("", SVG_NS):
                self._remove(f"element {local}")
            self.skipping = 1
            self.stack.append(None)
            return
        written = self._attributes(local, attrs, root=not self.stack)
        self._close_pending()
        if local == "style":
            self.style, self.style_bad, self.style_attrs = [], False, written
            self.stack.append(local)
            return
        if not self.stack:
            written = (f' xmlns="{SVG_NS}" xmlns:xlink="{XLINK_NS}"') + written
        self.out.append(f"<{local}{written}")
        self.pending = True
        self.stack.append(local)

    def _attributes(self, element: str, attrs: dict[str, str], root: bool) -> str:
        parts, seen = [], set()
        for name, value in attrs.items():
            ns, local = _split(name)
            label = f"{'xlink:' if ns == XLINK_NS else ''}{local}"
            if visible_controls(value) != value:  # no figure of ours has one in a value
                self._remove(f"attribute {label} with control characters on <{element}>")
                continue
            if local == "href" and ns in ("", XLINK_NS):
                if not ((element in _LINKS_IN and _FRAGMENT.fullmatch(value.strip()))
                        or (element == "image" and _DATA_IMAGE.fullmatch(value.strip()))):
                    self._remove(f"attribute {label}={value[:40]!r} on <{element}>")
                    continue
                written = "xlink:href"
            elif ns == XML_NS and local in ("space", "lang"):
                written = f"xml:{local}"
            elif ns or local not in ATTRIBUTES or (root and local in ROOT_EXCLUDED):
                self._remove(f"attribute {label} on <{element}>")
                continue
            elif local == "style":
                decls = _declarations(value, PROPERTIES)
                if decls is None:
                    self._remove(f"attribute style={value[:40]!r} on <{element}>")
                    continue
                value = "; ".join(decls)
                written = local
            elif local in PROPERTIES and not _css_ok(value):  # fill="url(...)", clip-path=...
                self._remove(f"attribute {local}={value[:40]!r} on <{element}>")
                continue
            else:
                written = local
            if written in seen:  # href beside xlink:href: the first is kept, as HTML does
                self._remove(f"attribute {label} repeated on <{element}>")
                continue
            seen.add(written)
            parts.append(f' {written}="{_quote(value)}"')
        return "".join(parts)

    def end(self, name: str) -> None:
        written = self.stack.pop()
        if self.skipping:
            self.skipping -= 1
        elif written == "style":
            self._end_style()
        elif self.pending:
            self.out.append("/>")
            self.pending = False
        else:
            self.out.append(f"</{written}>")
        if not self.stack:
            self.done = True

    def _end_style(self) -> None:
        sheet, self.style = "".join(self.style), None
        rules = []
        rest = _CSS_RULE.sub(lambda m: rules.append(m.group(1)) or "", sheet)
        checked = [_declarations(rule, _PAINT) for rule in rules]
        if self.style_bad or rest.strip() or any(d is None for d in checked):
            self._remove(f"style sheet {sheet[:40]!r}")
            return
        body = "".join("*{" + "; ".join(d) + "}" for d in checked)
        self.out.append(f"<style{self.style_attrs}>{_escape(body)}</style>")

    def text(self, data: str) -> None:
        if self.skipping or not self.stack:
            return
        if self.style is not None:
            self.style.append(data)
            return
        self._close_pending()
        self.out.append(_escape(data))
