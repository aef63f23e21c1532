"""The SVG sanitizer (issue 48 A): what matplotlib draws passes unchanged in meaning;
script, handlers, links out, style sheets that load or restyle the page and entity
declarations are left out or refused, however they are spelled."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from reportgen.support.layout import visible_controls
from reportgen.support.svgsafe import (
    ATTRIBUTES,
    ELEMENTS,
    PROPERTIES,
    ROOT_EXCLUDED,
    SVG_NS,
    XLINK_NS,
    SvgRefused,
    clean_svg,
    svg_safe,
)

SECRET = "SECRET-51c2-NOT-FOR-PAGES"


def _tree(el: ET.Element):
    """An element as comparable data: name, attributes, text, children (no metadata)."""
    return (el.tag, sorted(el.attrib.items()), (el.text or "").strip(), (el.tail or "").strip(),
            [_tree(c) for c in el if not c.tag.endswith("metadata")])


def _drawings():
    """Figures using what matplotlib's SVG backend writes: paths, markers (<use>), text,
    clip paths, an embedded PNG (imshow), a hatch (<pattern>), a Gouraud triangle
    (<linearGradient>, <filter>), dashes and transparency."""
    import matplotlib.pyplot as plt

    from reportgen.rendering.plots import style  # noqa: F401 - the reports' rcParams
    from reportgen.rendering.report import figure_bytes

    x = np.linspace(0, 6, 50)
    fig, axes = plt.subplots(2, 2)
    axes[0, 0].plot(x, np.sin(x), "o--", alpha=0.6, label=r"$\sin\theta$ & <x>")
    axes[0, 0].legend()
    axes[0, 0].set_title("θ̇ über — \"quoted\"")
    axes[0, 1].imshow(np.arange(12.0).reshape(3, 4))
    axes[1, 0].bar([1, 2], [3, 4], hatch="//", fill=False)
    axes[1, 0].fill_between(x, 0, np.cos(x), alpha=0.3)
    axes[1, 1].tripcolor([0, 1, 0], [0, 0, 1], [[0, 1, 2]], [0.0, 1.0, 2.0],
                         shading="gouraud")
    axes[1, 1].contourf(*np.meshgrid(x, x), np.outer(np.sin(x), np.cos(x)))
    yield figure_bytes(fig, "mixed", "svg")
    plt.close(fig)


def test_matplotlib_figures_pass_unchanged_in_meaning():
    for data in _drawings():
        cleaned = clean_svg(data)
        assert cleaned.removed == ()
        assert svg_safe(data)
        assert _tree(ET.fromstring(cleaned.svg)) == _tree(ET.fromstring(data))
        assert clean_svg(cleaned.svg).svg == cleaned.svg  # a fixed point
        for element in ("<use", "<text", "<clipPath", "<image", "<pattern", "<linearGradient",
                        "<filter", "<style"):
            assert element in cleaned.svg, element  # the drawing used what it was to test


def _svg(inner: str, head: str = "") -> str:
    return (f'{head}<svg xmlns="{SVG_NS}" xmlns:xlink="{XLINK_NS}" width="10" height="10">'
            f"{inner}</svg>")


#: each is left out (the rest of the drawing kept) or refused whole
HOSTILE = {
    "script": _svg(f"<script>alert('{SECRET}')</script><path d='M0 0'/>"),
    "script in CDATA": _svg(f"<script><![CDATA[alert('{SECRET}')]]></script>"),
    "xhtml script": _svg(f"<h:script xmlns:h='http://www.w3.org/1999/xhtml'>{SECRET}"
                         "</h:script>"),
    "onload": _svg("<g onload='alert(1)' ONCLICK='x' onMouseOver='x'/>"),
    "slash handler": f"<svg/onload=alert('{SECRET}') width='1'></svg>",
    "img onerror": f"<svg><img src=\"x\"/onerror=alert('{SECRET}')></svg>",
    "newline handler": _svg("<g\nonload\n=\n'alert(1)'/>"),
    "foreignObject": _svg("<foreignObject><body xmlns='http://www.w3.org/1999/xhtml'>"
                          f"<img src='x' onerror='{SECRET}'/></body></foreignObject>"),
    "javascript link": _svg(f"<a xlink:href='javascript:alert(\"{SECRET}\")'><text>x</text></a>"),
    "use from afar": _svg(f"<use xlink:href='https://example.org/{SECRET}.svg#a'/>"),
    "use a file": _svg(f"<use href='file:///etc/{SECRET}#a'/>"),
    "image svg": _svg(f"<image xlink:href='data:image/svg+xml;base64,{SECRET}'/>"),
    "image http": _svg(f"<image href='http://example.org/{SECRET}.png'/>"),
    "set href": _svg(f"<a><set attributeName='href' to='javascript:{SECRET}'/></a>"),
    "animate": _svg(f"<animate attributeName='onbegin' values='{SECRET}'/>"),
    "style import": _svg(f"<style>@import 'file:///{SECRET}';</style>"),
    "style url": _svg(f"<style>*{{fill: url(https://example.org/{SECRET})}}</style>"),
    "style escape": _svg(f"<style>*{{fill: u\\72l(https://{SECRET})}}</style>"),
    "style restyles the page": _svg(f"<style>body{{display:none}} /* {SECRET} */</style>"),
    "style opacity": _svg(f"<style>*{{opacity: 0}} #{SECRET}{{}}</style>"),
    "style with markup": _svg(f"<style><![CDATA[</style><script>{SECRET}</script>]]></style>"),
    "style attribute url": _svg(f"<path style='fill: url(http://{SECRET})'/>"),
    "style attribute position": f"<svg style='position:fixed;top:0;--x:{SECRET}'/>",
    "fill url": _svg(f"<path fill='url(http://example.org/{SECRET})'/>"),
    "root moved": f"<svg xmlns='{SVG_NS}' transform='translate(0 -900)' x='-9{SECRET}'/>",
    "entity": _svg("<text>&x;</text>",
                   f"<!DOCTYPE svg [<!ENTITY x SYSTEM 'file:///etc/{SECRET}'>]>"),
    "billion laughs": _svg("<text>&b;</text>",
                           "<!DOCTYPE svg [<!ENTITY a 'aaaaaaaa'><!ENTITY b '&a;&a;&a;&a;'>]>"),
    "undeclared entity": _svg("<text>&xxe;</text>",
                              '<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" '
                              '"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd">'),
    "stylesheet instruction": _svg("", f"<?xml-stylesheet href='http://{SECRET}'?>"),
    "html root": f"<html><script>{SECRET}</script></html>",
    "nested deep": "<svg>" + "<g>" * 500 + "</g>" * 500 + "</svg>",
}


#: what draws nothing is dropped without counting as removed: the file is still "safe"
QUIETLY_DROPPED = {"stylesheet instruction"}


@pytest.mark.parametrize("name", sorted(HOSTILE))
def test_hostile_svg_is_cleaned_or_refused(name):
    text = HOSTILE[name]
    assert svg_safe(text) == (name in QUIETLY_DROPPED)  # a report draws such a figure again
    try:
        cleaned = clean_svg(text)
    except SvgRefused:
        return
    _assert_plain(cleaned.svg)


def _assert_plain(svg: str) -> None:
    """What a page may inline: only allowed elements and attributes, links inside the
    drawing or to an embedded PNG/JPEG, no secret."""
    assert SECRET not in svg
    root = ET.fromstring(svg)
    assert not set(root.attrib) & ROOT_EXCLUDED  # the drawing stays in its own box
    for el in root.iter():
        ns, _, local = el.tag[1:].partition("}")
        assert ns == SVG_NS and local in ELEMENTS, el.tag
        if local == "style":
            assert el.text is None or el.text.startswith("*{"), el.text
        for key, value in el.attrib.items():
            if key.startswith("{"):
                assert key in (f"{{{XLINK_NS}}}href", "{http://www.w3.org/XML/1998/namespace}space")
                assert value.startswith(("#", "data:image/png;base64,", "data:image/jpeg;base64,"))
            else:
                assert key in ATTRIBUTES and not key.lower().startswith("on"), key
            if key in PROPERTIES or key == "style" or local == "style":
                css = (el.text or "") if local == "style" else value
                assert "url(" not in css.replace("url(#", "") and "@" not in css, css
                assert "position" not in css and "\\" not in css, css
    assert "<script" not in svg.lower()


def test_an_escaped_tag_stays_text():
    svg = clean_svg(_svg("<text>&lt;script&gt;alert(1)&lt;/script&gt;</text>"
                         "<title>&lt;img src=x onerror=alert(1)&gt;</title>")).svg
    assert "<script" not in svg and "<img" not in svg
    assert "&lt;script&gt;" in svg


def test_bidirectional_overrides_in_figure_text_are_shown():
    svg = clean_svg(_svg("<text>abc\u202edef</text>")).svg
    assert "\u202e" not in svg and "abc\\u202edef" in svg


#: names the generator draws elements and attributes from: allowed ones and hostile ones
_NAMES = sorted(ELEMENTS)[:12] + ["script", "foreignObject", "a", "animate", "set", "iframe"]
_ATTRS = ["d", "x", "fill", "style", "id", "href", "xlink:href", "onload", "onclick",
          "ONLOAD", "src", "transform", "clip-path", "values", "to"]
_VALUES = ["#a", "0 0", "url(#a)", "url(http://x/)", "javascript:alert(1)", "red",
           "fill: red", "fill: url(//x)", "data:image/png;base64,AAAA",
           "data:text/html,<script>", "expression(alert(1))", "@import 'x'", "\u202e", ""]


@st.composite
def _elements(draw, depth=0):
    name = draw(st.sampled_from(_NAMES))
    attrs = draw(st.dictionaries(st.sampled_from(_ATTRS), st.sampled_from(_VALUES),
                                 max_size=4))
    children = (draw(st.lists(_elements(depth + 1), max_size=3)) if depth < 3 else [])
    text = draw(st.sampled_from(["", "x", "&lt;script&gt;", "*{fill: red}", "*{fill: \u202e}",
                                 "<![CDATA[</x>]]>", "\u2066"]))
    quoted = "".join(f' {k}="{v.replace("&", "&amp;").replace("<", "&lt;")}"'
                     for k, v in attrs.items())
    return f"<{name}{quoted}>{text}{''.join(children)}</{name}>"


@settings(max_examples=60, deadline=None, derandomize=True, database=None)
@given(st.lists(_elements(), max_size=4))
def test_random_svgs_come_out_plain_and_stay_so(children):
    """Whatever the tree, what comes out is plain (only allowed names, links inside) and
    a fixed point: cleaning it again removes nothing and changes nothing."""
    try:
        cleaned = clean_svg(_svg("".join(children)))
    except SvgRefused:
        return
    _assert_plain(cleaned.svg)
    again = clean_svg(cleaned.svg)
    assert again.removed == () and again.svg == cleaned.svg


def test_visible_controls_shows_what_the_terminal_shows():
    from reportgen.support.layout import printable

    text = "a\u202eb\u2066c\x07d\x85e\tf\ng\r\nh\ri\x1b[31m"
    assert visible_controls(text) == "a\\u202eb\\u2066c\\x07d\\x85e\tf\ng\r\nh\\x0di\\x1b[31m"
    plain = "a\u202eb\x07\x85\x1b"
    assert visible_controls(plain) == printable(plain)
