"""The places of the course's two documents, kept as data: what a citation may name.

A report cites the lecture notes and the textbook as ``<document> <place>`` ("notes (3.19)",
"notes §8.1", "textbook Fig. 4.3", "textbook ex. 4.10(b)": see :mod:`.sources`).  Every
place either document has — section headings, numbered equations, figures, worked
examples, exercises and their parts — is listed once in ``reportgen/data/places_notes.toml``
and ``reportgen/data/places_textbook.toml``, with the line of the document's text where it
is, a short label in this project's words and the topics a sentence citing it would
mention.  :func:`places` reads one document's index; :func:`resolve` turns a place as a
report writes it, single or a range, into the entries it names.

Place forms :func:`resolve` reads
    ``(3.19)`` (or ``eq. 3.19``) an equation; ``(3.18–3.22)`` or ``(10.25)–(10.31)`` every
    equation of the range (one section's numbering); ``§7``, ``§8.1`` a section, ``§8–10``
    or ``§2–§7`` consecutive sections with their subsections; ``Fig. 4.3`` (``Fig 4.3``,
    ``Figure 4.3``) a figure; ``ex. 4.10`` an exercise, ``ex. 4.10(b)`` (``ex. 4.10b``) one
    of its parts, ``ex. 4.1–4.4`` consecutive exercises; any other text is looked up as
    written (``ch. 5``, ``example (1.10–1.22)``).  A hyphen may stand for the en dash of a
    range.

The documents themselves (:data:`DOCUMENTS`) live outside the project, in the folder
``tests/test_places.py`` checks the index against.
"""

from __future__ import annotations

import functools
import re
import tomllib
from collections.abc import Callable
from dataclasses import dataclass
from importlib import resources

#: each document's short name and the file of its extracted text
DOCUMENTS = {"notes": "lecture-notes.txt", "textbook": "textbook-pp119-131.txt"}

#: what a place may be
KINDS = ("section", "equation", "figure", "example", "exercise", "exercise-part")

_EQUATION_RANGE = re.compile(r"\((\d+)\.(\d+)\)?–\(?(?:(\d+)\.)?(\d+)\)")
_SECTION_RANGE = re.compile(r"§(\d+)–§?(\d+)")
_EXERCISE_RANGE = re.compile(r"ex\. (\d+)\.(\d+)–(?:(\d+)\.)?(\d+)")


@dataclass(frozen=True)
class Place:
    """One place of a document.

    Attributes
    ----------
    document : str
        The document's short name, a key of :data:`DOCUMENTS`.
    place : str
        How a report cites it after the document's name: "(3.19)", "§8.1", "Fig. 4.3",
        "ex. 4.10(b)".
    kind : str
        One of :data:`KINDS`.
    section : str
        The section (or subsection) it sits in: "3", "8.1".
    line : int
        The 1-based line of the document's text where it is.
    label : str
        A short description, in this project's words.
    topics : tuple of str
        Lowercase phrases a sentence citing the place would contain.
    """

    document: str
    place: str
    kind: str
    section: str
    line: int
    label: str
    topics: tuple[str, ...]


@functools.cache
def places(document: str) -> dict[str, Place]:
    """Every place of a document, by its place text, in the order of the index.

    Parameters
    ----------
    document : str
        "notes" or "textbook".

    Returns
    -------
    dict of str to Place
        ``{"(3.19)": Place(...), ...}``.

    Raises
    ------
    KeyError
        If ``document`` is not a key of :data:`DOCUMENTS`.
    ValueError
        If the index names a place twice or gives an unknown kind.
    """
    if document not in DOCUMENTS:
        raise KeyError(f"no document {document!r}: the documents are {', '.join(DOCUMENTS)}")
    text = resources.files("reportgen").joinpath("data", f"places_{document}.toml").read_text(
        encoding="utf-8")
    index: dict[str, Place] = {}
    for row in tomllib.loads(text)["place"]:
        place = Place(document=document, place=row["place"], kind=row["kind"],
                      section=row["section"], line=row["line"], label=row["label"],
                      topics=tuple(row["topics"]))
        if place.kind not in KINDS:
            raise ValueError(f"{document} {place.place}: unknown kind {place.kind!r}")
        if place.place in index:
            raise ValueError(f"{document} {place.place}: listed twice")
        index[place.place] = place
    return index


def resolve(document: str, cited: str) -> list[Place]:
    """The places a citation names, as a report writes them after the document's name.

    Parameters
    ----------
    document : str
        "notes" or "textbook".
    cited : str
        The place text: "(3.19)", "(3.18–3.22)", "(10.25)–(10.31)", "§7", "§8.1",
        "Fig. 4.3", "ex. 4.10", "ex. 4.10(b)", "ex. 4.1–4.4" (see the module's docstring).

    Returns
    -------
    list of Place
        One place, or every place of a range in the document's order.

    Raises
    ------
    KeyError
        If the text names no place of the index, or a range runs across sections or
        backwards.
    """
    index = places(document)
    text = _normalized(cited)
    if text in index:
        return [index[text]]
    if match := _EQUATION_RANGE.fullmatch(text):
        first_section, first, last_section, last = match.groups()
        if last_section not in (None, first_section):
            raise KeyError(f"{document} {cited}: a range of equations stays in one section")
        return _numbered_range(document, cited, "equation", first_section, int(first),
                               int(last), lambda s, n: f"({s}.{n})")
    if match := _EXERCISE_RANGE.fullmatch(text):
        first_chapter, first, last_chapter, last = match.groups()
        if last_chapter not in (None, first_chapter):
            raise KeyError(f"{document} {cited}: a range of exercises stays in one chapter")
        return _numbered_range(document, cited, "exercise", first_chapter, int(first),
                               int(last), lambda c, n: f"ex. {c}.{n}")
    if match := _SECTION_RANGE.fullmatch(text):
        first, last = (int(n) for n in match.groups())
        if first > last or f"§{first}" not in index or f"§{last}" not in index:
            raise KeyError(f"{document} {cited}: not a range of sections of the index "
                           f"(reportgen/data/places_{document}.toml)")
        return [place for place in index.values() if place.kind == "section"
                and place.place.startswith("§")
                and first <= int(place.section.split(".")[0]) <= last]
    raise KeyError(f"{document} has no place {cited!r} in its index "
                   f"(reportgen/data/places_{document}.toml)")


def _normalized(cited: str) -> str:
    """The place text in the index's spelling: one space, an en dash for a range,
    "Fig. 4.3", "ex. 4.10(b)", "(3.37)" for "eq. 3.37"; no trailing punctuation."""
    text = " ".join(cited.split()).rstrip(",;:")
    text = re.sub(r"(?<=[\d)])\.$", "", text)
    text = re.sub(r"\s*[-‒–—]\s*", "–", text)
    text = re.sub(r"^(?:Fig(?:ure)?\.?|fig\.)\s*", "Fig. ", text)
    text = re.sub(r"^(?:ex\.|exercise|Ex\.|Exercise)\s*", "ex. ", text)
    text = re.sub(r"^(ex\. \d+\.\d+)\s*\(?([a-z])\)?$", r"\1(\2)", text)
    text = re.sub(r"^eqs?\.\s*(\d+\.\d+)$", r"(\1)", text)
    return re.sub(r"^§\s+", "§", text)


def _numbered_range(document: str, cited: str, kind: str, prefix: str, first: int, last: int,
                    place_of: Callable[[str, int], str]) -> list[Place]:
    """The places ``place_of(prefix, n)`` for n = first … last, each of ``kind``; the two
    ends must be in the index, the numbers between are those the index has."""
    index = places(document)
    ends = [index.get(place_of(prefix, first)), index.get(place_of(prefix, last))]
    if first > last or any(end is None or end.kind != kind for end in ends):
        raise KeyError(f"{document} {cited}: not a range of {kind}s of the index "
                       f"(reportgen/data/places_{document}.toml)")
    found = [index[place_of(prefix, n)] for n in range(first, last + 1)
             if place_of(prefix, n) in index]
    return [place for place in found if place.kind == kind]
