"""The one typesetter: numbers and symbols as a textbook prints them (issue 41).

Every text a reader sees -- prose, tables, captions, headlines, gallery cards, figure
labels, in the HTML and the PDF alike -- passes through :func:`segments` once, at the
boundary where it becomes a page or a figure:

- the minus sign is U+2212, never the ASCII hyphen (``-0.34`` -> ``−0.34``, ``(-k/r)``
  -> ``(−k/r)``);
- a number in E-notation is ``a × 10ⁿ`` (``4.2e-15`` -> 4.2 × 10⁻¹⁵, ``1e-12`` ->
  10⁻¹²);
- a symbol with a plain-digit subscript has a real one (``I1`` -> I₁, ``θ0`` -> θ₀,
  ``r12`` -> r₁₂), as do Unicode sub- and superscript characters (the body font, STIX,
  has no glyphs for most of them: they are set as sub- and superscripts of its own
  digits).

The numbers themselves are chosen by :func:`reportgen.scene.content.fmt` (6 significant
figures, 2 for an error); this module only sets their type.  :func:`html_text` gives the
HTML (``<sup>``/``<sub>``), :func:`plain_text` Unicode text (a page title, a terminal),
:func:`figure_text` matplotlib mathtext, and :func:`typeset_html` runs over a whole page,
leaving alone what is not prose (``<svg>``, ``<style>``, ``<pre>``, ``<code>``).

What is not text is left alone: a hyphen between words or digits ("well-known",
"2026-12-07", "pp. 119-131"), a symbol glued to a word ("RK45", "DOP853", "H2O").
"""

from __future__ import annotations

import html
import re
from functools import lru_cache

from markupsafe import Markup, escape

__all__ = ["MINUS", "segments", "html_text", "plain_text", "figure_text", "typeset_html",
           "visible_text", "exponent_text"]

MINUS = "\u2212"
#: the spaces around the × of a × 10ⁿ: no line break inside a number
_TIMES = "\u00a0×\u00a0"

_SUPERSCRIPTS = "⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺"
#: superscript letters (the transpose ᵀ, an index ᵏ): set as superscripts of the font's
#: own letters, which it has
_SUPER_LETTERS = "ᵀᵏᵐᶜⁿⁱᵃᵇᵈᵉᵍʰʲˡᵒᵖʳˢᵗᵘᵛʷˣʸᶻ"
_SUBSCRIPTS = "₀₁₂₃₄₅₆₇₈₉₋₊ₐₑₒₓₕₖₗₘₙₚₛₜᵢᵣᵤᵥⱼ"
_FROM_SUP = str.maketrans(_SUPERSCRIPTS + _SUPER_LETTERS,
                          "0123456789" + MINUS + "+" + "Tkmcniabdeghjlopr" + "stuvwxyz")
_FROM_SUB = str.maketrans(_SUBSCRIPTS, "0123456789" + MINUS + "+" + "aeoxhklmnpstiruvj")
_TO_SUP = str.maketrans("0123456789" + MINUS + "-+", _SUPERSCRIPTS[:11] + "⁻⁺")
_TO_SUB = str.maketrans("0123456789" + MINUS + "+" + "aeoxhklmnpstiruvj", _SUBSCRIPTS)

#: a letter that can name a quantity: Latin, Greek, and a few letter-like symbols
_LETTER = "A-Za-zα-ωΑ-Ωϑϕϵϱℓ℘ħ"
#: characters after which a hyphen before a number or a symbol is a minus sign
_BEFORE_MINUS = r"\s(\[{=,;:/±<>≤≥≈~×·∓"

_NUMBER_E = (r"(?P<esign>[+\-−]?)(?P<mant>\d+(?:\.\d*)?|\.\d+)[eE](?P<xsign>[+\-−]?)"
             r"(?P<exp>\d+)")
_PATTERN = re.compile(
    # a number in E-notation, not inside a word or a longer number
    rf"(?<![\w.]){_NUMBER_E}(?!\w|\.\d)"
    # an ASCII hyphen used as a minus sign: before a number, infinity or a one-letter symbol
    rf"|(?P<minus>(?<![^{_BEFORE_MINUS}])-(?=\.?\d|∞|[{_LETTER}][\u0300-\u036f]?(?![A-Za-z])))"
    # a symbol (one letter, maybe accented) with a plain-digit subscript
    # (also right after another symbol's subscript or a superscript: "I3ω3", "sin²θ2")
    rf"|(?:(?<![\w.\\'’])|(?<=[{_LETTER}]\d)|(?<=[{_SUPERSCRIPTS}]))"
    rf"(?P<sym>[{_LETTER}][\u0300-\u036f]*)(?P<index>\d{{1,2}})"
    rf"(?!(?![{_SUPERSCRIPTS}])[\w\u0300-\u036f]|\.\d)"
    # a symbol with a TeX-style subscript word ("θ_exact", "V_eff", "t_end")
    rf"|(?<![\w.\-−\\'’/])(?P<tsym>[{_LETTER}][\u0300-\u036f]*)_(?P<tindex>[A-Za-z0-9]{{1,8}})"
    r"(?![\w\u0300-\u036f])"
    # a tolerance written as code ("rtol=1e-12"): the word and the number
    r"|(?P<tol>\b[ar]tol)\s?=\s?(?=[\d.])"
    # a caret exponent left from TeX ("r^0.4", "r^{-2}")
    r"|(?<=[\w)])\^(?:\{(?P<brace>[^{}]*)\}|(?P<caret>[+\-−]?\d+(?:\.\d+)?))"
    # Unicode superscripts and subscripts (with a point between digits: "r¹·²")
    rf"|(?P<sup>[{_SUPERSCRIPTS}](?:·?[{_SUPERSCRIPTS}])*|[{_SUPER_LETTERS}]+)"
    rf"|(?P<sub>[{_SUBSCRIPTS}]+)"
)


def exponent_text(sign: str, digits: str) -> str:
    """An exponent as it is printed: ``−15``, ``7`` (no leading zeros, no plus)."""
    digits = digits.lstrip("0") or "0"
    return (MINUS if sign in ("-", MINUS) and digits != "0" else "") + digits


@lru_cache(maxsize=4096)
def segments(text: str) -> tuple[tuple[str, str], ...]:
    """``text`` as typeset runs: ``("text", s)``, ``("sup", s)``, ``("sub", s)``.

    Adjacent text runs are merged; a sup or sub run holds digits, signs, points and
    letters as they are printed (U+2212 for a minus)."""
    out: list[list[str]] = []

    def put(kind: str, value: str) -> None:
        if not value:
            return
        if out and out[-1][0] == kind == "text":
            out[-1][1] += value
        else:
            out.append([kind, value])

    text = str(text)
    start = 0
    for m in _PATTERN.finditer(text):
        put("text", text[start:m.start()])
        start = m.end()
        if m.group("mant") is not None:
            sign = MINUS if m.group("esign") in ("-", MINUS) else m.group("esign")
            mant = m.group("mant").rstrip(".")
            exp = exponent_text(m.group("xsign"), m.group("exp"))
            if exp == "0":
                put("text", sign + mant)
            elif float(mant) == 1.0:
                put("text", sign + "10")
                put("sup", exp)
            else:
                put("text", f"{sign}{mant}{_TIMES}10")
                put("sup", exp)
        elif m.group("minus") is not None:
            put("text", MINUS)
        elif m.group("sym") is not None:
            put("text", m.group("sym"))
            put("sub", m.group("index"))
        elif m.group("tsym") is not None:
            put("text", m.group("tsym"))
            put("sub", m.group("tindex"))
        elif m.group("tol") is not None:
            put("text", m.group("tol") + " ")
        elif m.group("brace") is not None or m.group("caret") is not None:
            put("sup", (m.group("brace") or m.group("caret")).replace("-", MINUS))
        elif m.group("sup") is not None:
            put("sup", m.group("sup").translate(_FROM_SUP))
        else:
            put("sub", m.group("sub").translate(_FROM_SUB))
    put("text", text[start:])
    return tuple((k, v) for k, v in out)


#: characters the body font has in its regular face only (STIX's bold lacks ‖): set in
#: the regular weight wherever they stand, a bold label included
_REGULAR_ONLY = re.compile("([‖]+)")


def html_text(text: str) -> Markup:
    """``text`` (plain, unescaped) as HTML: escaped, with ``<sup>``/``<sub>`` runs."""
    parts = []
    for kind, value in segments(str(text)):
        if kind == "text":
            parts.append(_REGULAR_ONLY.sub(r'<span class="regular">\1</span>',
                                           str(escape(value))))
        else:
            parts.append(f"<{kind}>{escape(value)}</{kind}>")
    return Markup("".join(parts))


def plain_text(text: str) -> str:
    """``text`` typeset in Unicode alone (a page's ``<title>``, a terminal line):
    superscripts and subscripts as Unicode characters."""
    parts = []
    for kind, value in segments(str(text)):
        if kind == "sup":
            parts.append(value.translate(_TO_SUP))
        elif kind == "sub" and all(c in _TO_SUB for c in map(ord, value)):
            parts.append(value.translate(_TO_SUB))
        elif kind == "sub":
            parts.append("_" + value)
        else:
            parts.append(value)
    return "".join(parts)


_MATH = re.compile(r"(?<!\\)\$[^$]*(?<!\\)\$")


def figure_text(text: str) -> str:
    """A figure's text (a label, title, legend entry or annotation) typeset for
    matplotlib: its mathtext (between ``$``) kept, the rest as :func:`segments` with the
    sub- and superscripts in mathtext (``4.2 × $10^{−15}$``, ``I$_1$``)."""
    text = str(text)
    if not text or not _needs_figure_typesetting(text):
        return text
    out, start = [], 0
    for m in _MATH.finditer(text):
        out.append(_figure_plain(text[start:m.start()]))
        out.append(m.group(0))
        start = m.end()
    out.append(_figure_plain(text[start:]))
    return "".join(out)


def _needs_figure_typesetting(text: str) -> bool:
    return bool(re.search(rf"[-eE\d{_SUPERSCRIPTS}{_SUBSCRIPTS}]", text))


def _figure_plain(text: str) -> str:
    if not text:
        return text
    runs = segments(text)
    if all(kind == "text" for kind, _ in runs):
        return "".join(value for _, value in runs)
    parts = []
    for kind, value in runs:
        if kind == "text":
            parts.append(value.replace("$", r"\$"))  # text beside the mathtext added here
        else:
            body = value.replace(MINUS, "-")
            script = f"^{{{body}}}" if kind == "sup" else f"_{{{body}}}"
            if parts and parts[-1].endswith("}$") and parts[-1].startswith("$"):
                parts[-1] = parts[-1][:-1] + script + "$"  # a subscript and its power stacked
            else:
                parts.append(f"${script}$")
    return "".join(parts)


# ------------------------------------------------------------------ a whole page
#: elements whose text is not prose: kept as they are (an inline figure or equation, the
#: style sheet, code and the configuration listing)
_RAW = ("svg", "style", "script", "pre", "code", "textarea", "math")
_TOKENS = re.compile(
    r"<(?P<raw>" + "|".join(_RAW) + r")\b[^>]*>.*?</(?P=raw)\s*>"
    r"|<!--.*?-->"
    r"|<title\b[^>]*>(?P<title>.*?)</title\s*>"
    r"|<[^>]*>",
    re.S | re.I,
)


def typeset_html(page: str) -> str:
    """A rendered HTML page with the text of every element typeset (:func:`html_text`);
    tags, attributes and the content of :data:`_RAW` elements are kept byte for byte, the
    ``<title>`` typeset as Unicode text (:func:`plain_text`)."""
    out, start = [], 0
    for m in _TOKENS.finditer(page):
        if m.start() > start:
            out.append(_typeset_data(page[start:m.start()]))
        if m.group("title") is not None:
            inner = m.group("title")
            head = m.group(0)[:m.start("title") - m.start()]
            tail = m.group(0)[m.end("title") - m.start():]
            out.append(head + str(escape(plain_text(html.unescape(inner)))) + tail)
        else:
            out.append(m.group(0))
        start = m.end()
    if start < len(page):
        out.append(_typeset_data(page[start:]))
    return "".join(out)


def _typeset_data(data: str) -> str:
    if not data.strip():
        return data
    return str(html_text(html.unescape(data)))


_HIDDEN = re.compile(r'<section id="config">.*?</section>|<footer\b.*?</footer>'
                     r"|<(svg|style|script|pre|head)\b.*?</\1\s*>", re.S | re.I)
_SUPSUB = re.compile(r"<(sup|sub)>(.*?)</\1>", re.S)


def visible_text(page: str) -> str:
    """The text a reader of ``page`` (HTML) sees outside the appended configuration and
    the footer, one line: tags dropped, sub- and superscripts as Unicode characters where
    Unicode has them."""
    page = _HIDDEN.sub(" ", page)

    def script(m: re.Match) -> str:
        inner = re.sub(r"<[^>]+>", "", m.group(2))
        inner = html.unescape(inner)
        table = _TO_SUP if m.group(1) == "sup" else _TO_SUB
        return inner.translate(table)

    page = _SUPSUB.sub(script, page)
    text = html.unescape(re.sub(r"<[^>]+>", " ", page))
    return " ".join(text.split())
