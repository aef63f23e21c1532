"""The index of the places of the course's two documents (``reportgen/data/places_*.toml``,
read by :mod:`reportgen.scene.places`): resolving a citation's place, the index's own
consistency, and — where the documents' text is on the machine — the index against it."""

from __future__ import annotations

import functools
import os
import re
from pathlib import Path

import pytest

from reportgen.scene.places import DOCUMENTS, KINDS, places, resolve

#: the folder of the documents' text: $REPORTGEN_DOCUMENTS, else /work/shared/documents
#: beside the repository (/work/main)
DOCUMENTS_DIR = Path(os.environ.get("REPORTGEN_DOCUMENTS")
                     or Path(__file__).resolve().parents[2] / "shared" / "documents")
#: how many lines from its recorded line a figure, exercise or part may be found
NEAR = 2
#: places whose number or part letter the textbook's extraction lost: the index keeps
#: them (the textbook sets them) at the line where their text survives
LOST_IN_EXTRACTION = {"ex. 4.2", "ex. 4.2(a)", "ex. 4.2(b)", "ex. 4.2(c)", "ex. 4.10(f)"}


def entries(document: str, *kinds: str):
    """The index's places of ``document``, of the given kinds (all if none)."""
    return [p for p in places(document).values() if not kinds or p.kind in kinds]


@functools.cache
def _read(document: str) -> tuple[str, ...] | None:
    path = DOCUMENTS_DIR / DOCUMENTS[document]
    return tuple(path.read_text(encoding="utf-8").split("\n")) if path.is_file() else None


def text_lines(document: str) -> tuple[str, ...]:
    """The document's text, line by line; the test is skipped where it is absent."""
    lines = _read(document)
    if lines is None:
        pytest.skip(f"the documents' text is not here: {DOCUMENTS_DIR / DOCUMENTS[document]} "
                    "(set REPORTGEN_DOCUMENTS to its folder)")
    return lines


def near(lines: tuple[str, ...], line: int, pattern: str) -> bool:
    """Whether ``pattern`` is found on one of the lines within NEAR of ``line``."""
    window = lines[max(line - 1 - NEAR, 0):line + NEAR]
    return any(re.search(pattern, text) for text in window)


# ------------------------------------------------------------------ resolve


def test_resolve_one_equation():
    (place,) = resolve("notes", "(3.19)")
    assert place is places("notes")["(3.19)"]
    assert (place.kind, place.section, place.document) == ("equation", "3", "notes")
    assert resolve("notes", "eq. 3.19") == [place]


@pytest.mark.parametrize("cited", ["(3.18–3.22)", "(3.18)–(3.22)", "(3.18-3.22)", "(3.18–22)"])
def test_resolve_a_range_of_equations(cited):
    assert [p.place for p in resolve("notes", cited)] == [f"(3.{n})" for n in range(18, 23)]


def test_resolve_a_range_written_as_two_citations():
    found = resolve("notes", "(10.25)–(10.31)")
    assert [p.place for p in found] == [f"(10.{n})" for n in range(25, 32)]
    assert {p.section for p in found} == {"10.1"}


@pytest.mark.parametrize("cited", ["(3.48–4.2)", "(3.22–3.18)", "(3.49–3.50)"])
def test_a_range_across_sections_backwards_or_past_the_end_is_refused(cited):
    with pytest.raises(KeyError, match=re.escape(cited)):
        resolve("notes", cited)


def test_resolve_sections():
    (section,) = resolve("notes", "§7")
    assert (section.kind, section.section) == ("section", "7")
    assert resolve("notes", "§8.1")[0].section == "8.1"
    assert [p.place for p in resolve("notes", "§8–10")] == ["§8", "§8.1", "§8.2", "§9", "§10",
                                                           "§10.1"]
    assert resolve("textbook", "§5.1")[0].kind == "section"


def test_resolve_figures():
    (figure,) = resolve("textbook", "Fig. 4.3")
    assert (figure.kind, figure.section) == ("figure", "4.4")
    assert resolve("textbook", "Fig 4.3b")[0].place == "Fig. 4.3b"
    assert resolve("notes", "Figure 2")[0].section == "9"


def test_resolve_exercises_and_parts():
    (exercise,) = resolve("textbook", "ex. 4.10")
    assert exercise.kind == "exercise"
    (part,) = resolve("textbook", "ex. 4.10(b)")
    assert (part.kind, part.section) == ("exercise-part", "4")
    assert resolve("textbook", "ex. 4.6c") == resolve("textbook", "ex. 4.6(c)")
    assert [p.place for p in resolve("textbook", "ex. 4.1–4.4")] == [
        "ex. 4.1", "ex. 4.2", "ex. 4.3", "ex. 4.4"]


@pytest.mark.parametrize(("document", "cited"), [
    ("notes", "(3.50)"), ("notes", "§11"), ("notes", "Fig. 3"), ("notes", "ex. 4.1"),
    ("textbook", "(5.1)"), ("textbook", "ex. 4.12"), ("textbook", "ex. 4.6(d)"),
    ("textbook", "Fig. 4.4"), ("textbook", "ex. 4.1–4.14"),
])
def test_a_place_not_in_the_index_is_a_key_error(document, cited):
    with pytest.raises(KeyError, match=re.escape(cited)):
        resolve(document, cited)


def test_an_unknown_document_is_a_key_error():
    with pytest.raises(KeyError, match="goldstein"):
        places("goldstein")


# ------------------------------------------------------------------ the index itself


@pytest.mark.parametrize("document", DOCUMENTS)
def test_every_place_has_a_kind_a_label_and_lowercase_topics(document):
    for place in entries(document):
        assert place.kind in KINDS, place
        assert place.label and len(place.label.split()) <= 13, place
        assert place.topics, place
        assert all(topic and topic == topic.lower() for topic in place.topics), place


@pytest.mark.parametrize("document", DOCUMENTS)
def test_every_place_sits_in_its_section(document):
    """An entry's section is a section of the index, and where the section has a "§"
    heading, the entry is between that heading and the next one."""
    sections = {p.section for p in entries(document, "section")}
    headings = sorted((p.line, p.section) for p in entries(document, "section")
                      if p.place.startswith("§"))
    for place in entries(document):
        assert place.section in sections, place
        if place.kind != "section" and f"§{place.section}" in places(document):
            assert [s for line, s in headings if line <= place.line][-1] == place.section, place


@pytest.mark.parametrize(("document", "kinds"), [
    ("notes", ("equation",)), ("textbook", ("exercise", "exercise-part"))])
def test_numbered_places_are_listed_in_the_document_order(document, kinds):
    lines = [p.line for p in entries(document, *kinds)]
    assert lines == sorted(lines)


def test_each_worked_example_of_the_notes_names_the_equations_it_opens():
    equations = entries("notes", "equation")
    for example in entries("notes", "example"):
        cited = example.place.removeprefix("example ")
        opened = resolve("notes", cited)
        following = next(p for p in equations if p.line > example.line)
        assert opened[0] is following, example


# ------------------------------------------------------------------ the index against the text

EQUATION_AT_LINE_END = re.compile(r"\((\d+\.\d+[a-z]?)\)\s*$")


@pytest.mark.parametrize("document", DOCUMENTS)
def test_each_equation_number_ends_its_recorded_line(document):
    lines = text_lines(document)
    for place in entries(document, "equation"):
        assert re.search(re.escape(place.place) + r"\s*$", lines[place.line - 1]), place


@pytest.mark.parametrize("document", DOCUMENTS)
def test_every_equation_number_of_the_text_is_indexed(document):
    lines = text_lines(document)
    in_text = {(f"({m[1]})", n) for n, text in enumerate(lines, 1)
               if (m := EQUATION_AT_LINE_END.search(text))}
    indexed = {(p.place, p.line) for p in entries(document, "equation")}
    assert in_text == indexed


@pytest.mark.parametrize("document", DOCUMENTS)
def test_each_section_heading_is_at_its_line(document):
    lines = text_lines(document)
    for place in entries(document, "section"):
        text = lines[place.line - 1]
        if place.place.startswith("§"):
            # the notes' headings; the textbook's running heads ("orthog-5.1 SMALL ...")
            pattern = rf"(?:^|[\s-]){re.escape(place.section)}\s+[A-Z]"
            assert re.search(pattern, text) and len(text) < 100, place
        elif place.place.endswith("exercises"):
            assert text.strip() == "Exercises", place
        else:
            assert f"CHAPTER {place.section} " in text, place


@pytest.mark.parametrize("document", DOCUMENTS)
def test_figures_exercises_and_parts_are_at_their_lines(document):
    lines = text_lines(document)
    for place in entries(document, "figure", "exercise", "exercise-part"):
        if place.kind == "figure":
            number = place.place.removeprefix("Fig. ")
            pattern = rf"Fig(?:ure)?\.?\s*{re.escape(number)}\b"
        elif place.kind == "exercise":
            pattern = rf"^\s*{re.escape(place.place.removeprefix('ex. '))}\s"
        else:
            letter = place.place[-2]
            pattern = rf"(?:^|[\s(]){letter}\)"
        found = near(lines, place.line, pattern)
        if place.place in LOST_IN_EXTRACTION:
            assert not found, f"{place.place} is found in the text: drop it from the lost ones"
        else:
            assert found, place


@pytest.mark.parametrize("document", DOCUMENTS)
def test_labels_quote_no_run_of_six_words(document):
    words = re.findall(r"\w+", "\n".join(text_lines(document)).lower())
    runs = {tuple(words[i:i + 6]) for i in range(len(words) - 5)}
    for place in entries(document):
        label = re.findall(r"\w+", place.label.lower())
        copied = [" ".join(label[i:i + 6]) for i in range(len(label) - 5)
                  if tuple(label[i:i + 6]) in runs]
        assert not copied, f"{document} {place.place}: label copies {copied}"
