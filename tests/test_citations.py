"""Every citation in a report names its document (issue 32).

A reader meeting "(3.32)", "§5.1", "Fig. 4.3" or "ex. 4.5" must be able to tell whose
equation, section, figure or exercise it is: the notes', the textbook's, Goldstein's …
The rule is :func:`reportgen.scene.sources.bare_citations` (its module docstring states
it); here it is first shown to refuse seeded bare citations and to pass their named twins,
then run over the visible text of shipped reports, whose "Sources" list must hold an entry
for every document their text cites, and none other.

False positives, and the choice made.  A number a report prints in parentheses can look
like an equation number.  The rule does not try to tell prose from tables (a table's
"source" column holds citations too: "closed form, notes (2.4)"); it tells them by shape
instead: an equation number is a chapter 1–19, a point and one to three digits without a
leading zero, in parentheses not glued to a word.  So "(0.25)", "(25.4)", "(1.05)", "f(1.5)"
and "(0.4, 1.2)" are not citations, and a report never prints a bare dimensionless value in
parentheses: "(1.67)" would be refused, which is why the study's accuracy scale reads
"0.001 × 1.67 (the reference's largest |value|)".
"""

from __future__ import annotations

import pytest

from reportgen.scene.sources import (
    PLACE,
    SOURCES,
    bare_citations,
    cited,
    citing_document,
    sources_section,
    visible_blocks,
)


def page(text: str) -> str:
    """A minimal report page whose body is ``text``."""
    return f"<html><body><p>{text}</p></body></html>"


# ------------------------------------------------------------------ the rule itself
@pytest.mark.parametrize("text", [
    "the small-angle solution (1.19).",
    "separates (3.18–3.22): R moves freely",
    "linearized (10.12)–(10.14)",
    "the (3.32a) variant",
    "Small oscillations (§5.1) about equilibrium",
    "as printed in Fig. 4.3",
    "the cone of ex. 4.5",
    "exercise 4.10",
    "problem 3 there",
    "the orbit (eq. 3.37)",
    "chapter 5 treats this",
    # a name in another clause does not cover the place: ";" separates works
    "Landau & Lifshitz §32 problem 2; ex. 4.6",
    "as Goldstein shows. The solution (1.21) is",
    # "notes" as an English word is not the lecture notes
    "the runs' status (notes below) and (3.2)",
    # too far back: the name must stand within the clause's last 40 characters
    "Goldstein, who treats it at length in a long and winding chapter, (3.37)",
])
def test_bare_citation_is_refused(text):
    assert bare_citations(page(text)), text


@pytest.mark.parametrize("text, document", [
    ("the small-angle solution, notes (1.19).", "notes"),
    ("the lecture notes ch. 5", "notes"),
    ("notes §5.1; Goldstein §6.4", "goldstein"),
    ("textbook Fig. 5.1", "textbook"),
    ("textbook ex. 4.5", "textbook"),
    ("Goldstein (4.62)", "goldstein"),
    ("exact, quadrature (Goldstein eq. 3.37)", "goldstein"),
    ("linearized, notes (10.12)–(10.14)", "notes"),
    ("(Landau & Lifshitz §15, problem 3)", "landau"),
    ("(GNI §I.5.1, §XIII)", "gni"),
    ("the total energy (GNI eq. I.5.1)", "gni"),
    ("Kepler's equation (Danby §6.6)", "danby"),
])
def test_named_citation_passes(text, document):
    assert bare_citations(page(text)) == []
    places = list(PLACE.finditer(text))
    assert places, f"no place found in {text!r}"
    assert citing_document(text, places[-1]) == document


@pytest.mark.parametrize("text", [
    "the reference's largest |value| (0.25)",   # leading zero: a value
    "largest |value| (25.4)",                    # no chapter 25
    "a drift (1.05)",                            # leading zero after the point
    "the function f(1.5)",                       # glued to a word: an argument
    "tensor about (0.376305, -0.890046, 1.14726)",
    "members (3 ok, 1 failed)",
    "DLMF 22.19.4",                              # cited, but not a parenthesised number
])
def test_numbers_that_are_not_citations(text):
    assert bare_citations(page(text)) == []


def test_a_bare_value_in_parentheses_reads_as_a_citation():
    """The documented limit of the shape rule: a dimensionless value printed bare in
    parentheses is indistinguishable from an equation number, and is refused."""
    assert bare_citations(page("the reference's largest |value| (1.67)"))


def test_blocks_do_not_lend_names():
    """A name in one table cell does not cover a place in the next."""
    html = "<body><table><tr><td>notes</td><td>(3.32)</td></tr></table></body>"
    assert bare_citations(html)
    assert bare_citations("<body><table><tr><td>notes (3.32)</td></tr></table></body>") == []


def test_configuration_and_figures_are_not_read():
    """The configuration listing quotes the user's comments; a figure's words are drawn."""
    html = ('<body><p>text</p><svg><text>(3.32)</text></svg>'
            '<section id="config"><pre># the solution (1.19)</pre></section></body>')
    assert visible_blocks(html) == ["text"]
    assert bare_citations(html) == []


@pytest.mark.parametrize("text, keys", [
    ("the runs' status (notes below)", []),
    ("the lecture notes and notes §7", ["notes"]),
    ("Thiele–Burrau variables", []),
    ("Burrau's problem (Szebehely & Peters)", ["szebehely"]),
    ("Hairer, Lubich & Wanner's Geometric Numerical Integration", ["gni"]),
    ("dense output (Hairer, Nørsett & Wanner II.6)", ["hairer"]),
    ("the textbook's three steps; Goldstein §6.4", ["textbook", "goldstein"]),
    ("a planetary orbit (Waalkens, Dullin & Richter 2004)", ["waalkens"]),
])
def test_cited_documents(text, keys):
    assert cited(page(text)) == keys


def test_sources_section_lists_cited_documents_in_order():
    html = page("Goldstein (3.37) and notes (3.20)")
    section = str(sources_section(html))
    assert section.count("<li>") == 2
    assert section.index("<b>notes</b>") < section.index("<b>Goldstein</b>")
    assert str(sources_section(page("no citation here"))) == ""
    labels = [s.label for s in SOURCES.values()]
    assert len(set(labels)) == len(labels)  # an entry is found by its label


# Every shipped report and variant is read by tests/test_shipped_pages.py (no bare
# citation; the Sources list holds exactly the documents cited), on the one batch run
# the page tests already make.


# ------------------------------------------------ each citation resolved (issue 42)
@pytest.mark.parametrize("text", [
    "(Goldstein 5.72)", "period 4K(k)·√(l/g), DLMF 22.19.4", "DLMF 22.19(i) gives"])
def test_goldstein_and_dlmf_numbers_are_places_of_their_books(text):
    """"Goldstein 5.72" and "DLMF 22.19.4" cite a place, named by the book before it."""
    block = visible_blocks(page(text))[0]
    found = [citing_document(block, m) for m in PLACE.finditer(block)]
    assert found and set(found) <= {"goldstein", "dlmf"}
    assert bare_citations(page(text)) == []


#: the sentences the shipped reports printed before issue 42, each citing the wrong place
#: (the lecture notes, /work/shared/documents/lecture-notes.txt), with the place they meant
SLIPS = [
    ("The relative orbit r(t) = r₁ − r₂, notes (3.21).", "(3.21)", "(3.19)"),
    ("reduced mass μ = m1 m2/(m1 + m2), notes (3.20)", "(3.20)", "(3.22)"),
    ("r1 = (m2/M) r, r2 = −(m1/M) r, notes (3.19)", "(3.19)", "(3.20)–(3.21)"),
    ("L(0), Noether charge of rotations, notes (3.27)", "(3.27)", "(3.23)–(3.25)"),
    ("the effective potential V + L²/(2μr²), notes (3.28–3.30): the barrier",
     "(3.28–3.30)", "(7.40)–(7.41)"),
    ("Kepler's third law T = 2π√(a³/(k/μ)), notes (3.31)", "(3.31)", None),
    ("W_r solves H(q, ∂W/∂q) = E, notes (7.34).", "(7.34)", "(7.32), (7.42)–(7.45)"),
    ("the energy ellipsoid ω·Iω = 2T, notes (10.17)", "(10.17)", "(10.15)"),
    ("Q = p, notes (6.9), of the integrated H", "(6.9)", "(6.7)"),
]


@pytest.mark.parametrize(("sentence", "wrong", "right"), SLIPS)
def test_a_citation_of_the_wrong_equation_is_found_and_the_right_one_passes(sentence, wrong,
                                                                            right):
    """The topic rule of :func:`reportgen.scene.citations.problems` on the slips issue 42
    listed: each sentence as printed is about none of the places it cites; with the place
    the notes give it (the third law: cited from Goldstein, the notes have none) it
    passes."""
    from reportgen.scene.citations import problems

    found = problems(page(sentence))
    assert len(found) == 1 and found[0].startswith(f"notes {wrong}"), found
    if right is not None:
        assert problems(page(sentence.replace(wrong, right))) == []


def test_a_table_row_reads_as_one_sentence_and_places_cited_together_share_words():
    """A row's citation is about what its first cell names; "notes (7.32), (7.42)–(7.45)"
    is one citation of a list of places; a place the index lacks is named."""
    from reportgen.scene.citations import citations, problems

    row = ("<html><body><table><tr><td>reduced mass μ</td><td>0.5 kg</td>"
           "<td>notes (3.22)</td></tr></table></body></html>")
    assert [c.words for c in citations(row)] == ["reduced mass μ | 0.5 kg | notes (3.22)"]
    assert problems(row) == [] and problems(row.replace("(3.22)", "(3.21)")) != []
    listed = page("W_r solves H(q, ∂W/∂q) = E, notes (7.32), (7.42)–(7.45).")
    assert problems(listed) == []
    assert problems(page("as in textbook ex. 4.12")) == [
        "textbook ex. 4.12: textbook has no place 'ex. 4.12' in its index "
        "(reportgen/data/places_textbook.toml)"]
