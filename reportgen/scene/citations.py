"""Every citation of the course's two documents, resolved against their index.

:mod:`.sources` makes sure a citation names its document; this module checks that the
place it names exists and is about what the sentence says.  For each citation of the
lecture notes or the textbook in a report's visible text (:func:`.sources.visible_blocks`)
:func:`citations` gives the document, the place as written ("(3.18–3.22)", "§8.1",
"Fig. 4.3", "ex. 4.10(b)") and the words around it: from the previous citation or the
sentence's start to the next citation or the sentence's end.  :func:`problems` resolves
each place in the index of the documents' places (:mod:`.places`) and asks that the
words around it contain one of the topics of a place it names: "the reduced mass,
notes (3.22)" passes, "the reduced mass, notes (3.20)" does not ((3.20) gives r₁ and r₂).

The topics are matched on text with subscripts and dashes folded (``r₁ − r₂`` and
"r1 − r2" are one text, as are "Euler–Lagrange" and "Euler-Lagrange").
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .places import resolve
from .sources import PLACE, citing_document, visible_blocks

#: the documents whose places are indexed (reportgen/data/places_<key>.toml)
INDEXED = ("notes", "textbook")

#: a whole place as written, from where :data:`.sources.PLACE` found it: a section or a
#: range of sections, an equation or a range (one or two pairs of parentheses), a figure
#: with its panel, an exercise with its part or a range of exercises, a chapter
_WHOLE = re.compile(
    r"§\s*\d+(?:\.\d+)*(?:\s*[–-]\s*§?\d+(?:\.\d+)*)?"
    r"|\(\d+\.\d+[a-z]?(?:\s*[–-]\s*(?:\d+\.)?\d+[a-z]?)?\)(?:\s*[–-]\s*\(\d+\.\d+[a-z]?\))?"
    r"|Figs?\.\s*\d+\.\d+[a-c]?|Figures?\s+\d+\.\d+[a-c]?"
    r"|(?:[Ee]x\.|[Ee]xercises?)\s*\d+\.\d+(?:\s*\([a-f]\)|[a-f]\b)?(?:\s*[–-]\s*(?:\d+\.)?\d+)?"
    r"|[Ee]qs?\.\s*\(?\d+\.\d+\)?"
    r"|[Cc]h\.\s*\d+|[Cc]hapters?\s+\d+")
#: where a sentence ends (not after an abbreviation's point)
_SENTENCE_END = re.compile(r"(?<!\bFig)(?<!\bFigs)(?<!\b[Ee]x)(?<!\b[Ee]q)(?<!\b[Ee]qs)"
                           r"(?<!\b[Cc]h)(?<!\bcf)(?<!\bvs)(?<!\be\.g)(?<!\bi\.e)[.!?](?=\s|$)")
#: a typeset equation's opening tag, with its TeX
_EQUATION = re.compile(r'<span class="eq"[^>]*\baria-label="([^"]*)"[^>]*>')
#: between two places cited together: a comma, a semicolon, "and", "or", and maybe the
#: second one's document ("Landau & Lifshitz §32 Problem 2; textbook ex. 4.6")
_TOGETHER = re.compile(r"\s*(?:[,;]|and|or|,\s*and)?\s*(?:(?:the\s+)?(?:notes|textbook|Goldstein|"
                       r"Landau\s*&\s*Lifshitz|DLMF)\s*)?")
#: between two cells of a table row, or a fact and its value
_CELL_JOIN = re.compile(r"</t[dh]>\s*<t[dh]\b[^>]*>|</dt>\s*<dd\b[^>]*>", re.I)
_FOLD = str.maketrans("₀₁₂₃₄₅₆₇₈₉⁰¹²³⁴⁵⁶⁷⁸⁹‐‑‒–—−’",
                      "01234567890123456789-----−'")


@dataclass(frozen=True)
class Citation:
    """One citation of an indexed document in a report.

    Attributes
    ----------
    document : str
        A key of :data:`INDEXED`.
    place : str
        The place as the report writes it: "(3.18–3.22)", "§8.1", "ex. 4.10(b)".
    words : str
        The text around it: from the previous citation (or the sentence's start) to the
        next (or the sentence's end).
    """

    document: str
    place: str
    words: str


def fold(text: str) -> str:
    """``text`` lowercased, with subscript and superscript digits as plain digits and
    every dash as a hyphen (the minus sign kept), for matching topics."""
    return text.translate(_FOLD).lower()


def citations(html_text: str) -> list[Citation]:
    """Every citation of the notes and the textbook in a report's visible text, in order;
    a typeset equation reads as its TeX (its ``aria-label``), so "the effective potential
    V_eff = …, notes (7.41)" is read with its formula."""
    found = []
    html_text = _EQUATION.sub(lambda m: f"{m.group(0)} {m.group(1)} ", html_text)
    # a table row, or a fact with its value, is read as one block: "reduced mass μ | 0.5 kg
    # | notes (3.22)" is about what its first cell names
    html_text = _CELL_JOIN.sub(" | ", html_text)
    for block in visible_blocks(html_text):
        spans = []  # (start, end, document, place) of each citation in the block
        for match in PLACE.finditer(block):
            if spans and match.start() < spans[-1][1]:
                continue  # the second half of a range already read
            document = citing_document(block, match)
            whole = _WHOLE.match(block, match.start())
            end = whole.end() if whole else match.end()
            spans.append((match.start(), end, document, block[match.start():end]))
        windows = []
        for i, (start, end, _, _) in enumerate(spans):
            left = spans[i - 1][1] if i else 0
            right = spans[i + 1][0] if i + 1 < len(spans) else len(block)
            ends = [m.end() for m in _SENTENCE_END.finditer(block, left, start)]
            left = ends[-1] if ends else left
            after = _SENTENCE_END.search(block, end, right)
            windows.append([left, after.end() if after else right])
        # a list of places cited together ("notes (7.32), (7.42)–(7.45)") shares its words
        for i in range(1, len(spans)):
            if _TOGETHER.fullmatch(block, spans[i - 1][1], spans[i][0]):
                windows[i][0] = windows[i - 1][0]
        for i in range(len(spans) - 2, -1, -1):
            if _TOGETHER.fullmatch(block, spans[i][1], spans[i + 1][0]):
                windows[i][1] = windows[i + 1][1]
        for (_, _, document, place), (left, right) in zip(spans, windows, strict=True):
            if document in INDEXED:
                found.append(Citation(document, _as_indexed(place), block[left:right].strip()))
    return found


def _as_indexed(place: str) -> str:
    """A place in the spelling :func:`.places.resolve` reads: "chapter 5" → "ch. 5",
    "eq. (3.37)" → "eq. 3.37"."""
    place = " ".join(place.split())
    place = re.sub(r"^[Cc]h(?:apters?|\.)\s*(\d+)$", r"ch. \1", place)
    place = re.sub(r"^[Ee]x(?:ercises?|\.)\s*", "ex. ", place)
    return re.sub(r"^([Ee]qs?\.)\s*\((\d+\.\d+)\)$", r"\1 \2", place)


def problems(html_text: str) -> list[str]:
    """Every citation of the notes or the textbook in a report that names no place of the
    documents' index, or whose words mention none of the topics of the places it names,
    each as one line: ``notes (3.20): 'the reduced mass μ …' is about none of: r1 …``."""
    out = []
    for citation in citations(html_text):
        try:
            named = resolve(citation.document, citation.place)
        except KeyError as error:
            out.append(f"{citation.document} {citation.place}: {error.args[0]}")
            continue
        words = fold(citation.words)
        topics = [topic for place in named for topic in place.topics]
        if not any(fold(topic) in words for topic in topics):
            labels = "; ".join(f"{p.place} {p.label}" for p in named[:4])
            out.append(f"{citation.document} {citation.place}: {citation.words!r} is about "
                       f"none of its places ({labels}{' …' if len(named) > 4 else ''})")
    return out
