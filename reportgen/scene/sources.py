"""The documents reports cite, each named once, and the list a report ends with.

A report cites a document in its text as ``<short name> <place>``: "notes (10.25)",
"notes §7", "textbook Fig. 4.3", "textbook ex. 4.5", "Goldstein (4.62)", "DLMF 22.19.4".
A bare "(10.25)" or "Fig. 4.3" names no document and is refused by the citation test
(``tests/test_citations.py``).  :func:`sources_section` lists, at the end of a report,
every document its text cites, in the order of :data:`SOURCES`.

The course's two documents are the lecture notes (§1–§10: Lagrangian and Hamiltonian
mechanics, canonical transformations, Hamilton–Jacobi, rigid bodies, the heavy top) and
the textbook (chapter 4: rigid-body kinematics and dynamics; chapter 5: small
oscillations).  Their full titles live here and nowhere else.

The citation rule (:func:`bare_citations`)
    A *place* is a token only a citation has: ``§5.1`` (``§I.5.1``), an equation number
    in parentheses ``(3.32)``, ``(3.32–3.34)``, ``(3.32a)``, ``Fig. 4.3``, ``ex. 4.5``,
    ``exercise 4.5``, ``problem 3``, ``eq. 3.37``, ``ch. 5``.  Every place must be preceded
    by a document's name (:data:`SOURCES`) within :data:`CLAUSE` characters of the same
    clause of the same block (paragraph, caption, table cell, list item, fact): a sentence
    end or a ``;`` (which, in a list of references, separates works) ends a clause, so in
    "Landau & Lifshitz §32; ex. 4.6" the exercise is refused (it is the textbook's).
    An equation number is told from a number the report prints in parentheses by its
    shape: a chapter 1–19, a point, one to three digits with no leading zero (``(0.25)``,
    ``(25.4)``, ``(1.05)`` are not equation numbers), not glued to a word
    (``f(1.5)`` is a function's value) — so a report never prints a bare dimensionless
    value in parentheses: it writes the unit with it, or names the quantity first.
"""

from __future__ import annotations

import html
import re
from dataclasses import dataclass

from markupsafe import Markup, escape


@dataclass(frozen=True)
class Source:
    """One cited document: the pattern that finds its citations, the name the text cites
    it by (the label its entry starts with) and its entry."""

    pattern: str
    label: str
    entry: str


#: every document a report may cite, in the order the sources list gives them
SOURCES: dict[str, Source] = {
    # "notes" is also an English word ("the runs' status (notes below)"): the notes are
    # cited as "lecture notes" or as "notes" followed by a place
    "notes": Source(r"\b[Ll]ecture notes\b|\b[Nn]otes(?=\s*(?:§|\(\d|Fig\.|ex\.|eqs?\.|ch\.))",
                    "notes",
                    "the course's lecture notes on analytical mechanics (§1–§10), with their "
                    "own section and equation numbers."),
    "textbook": Source(r"\b[Tt]extbook\b", "textbook",
                       "the course textbook: chapter 4, the kinematics and dynamics of rigid "
                       "bodies; chapter 5, small oscillations."),
    "goldstein": Source(r"\bGoldstein\b", "Goldstein",
                        "H. Goldstein, C. Poole, J. Safko, Classical Mechanics, 3rd ed., "
                        "Addison-Wesley (2002)."),
    "landau": Source(r"\bLandau\b", "Landau & Lifshitz",
                     "L. D. Landau, E. M. Lifshitz, Mechanics, 3rd ed., Pergamon (1976)."),
    "whittaker": Source(r"\bWhittaker\b", "Whittaker & Watson",
                        "E. T. Whittaker, G. N. Watson, A Course of Modern Analysis, 4th ed., "
                        "Cambridge (1927)."),
    "dlmf": Source(r"\bDLMF\b", "DLMF",
                   "NIST Digital Library of Mathematical Functions, https://dlmf.nist.gov "
                   "(elliptic integrals ch. 19, Jacobi functions ch. 22, Weierstrass "
                   "functions ch. 23)."),
    # "Hairer, Lubich & Wanner's Geometric Numerical Integration (GNI §I.5.1)" cites GNI
    "gni": Source(r"\bGNI\b|\bHairer, Lubich\b", "GNI",
                  "E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration, 2nd ed., "
                  "Springer (2006)."),
    "hairer": Source(r"\bN[øo]rsett\b", "Hairer, Nørsett & Wanner",
                     "E. Hairer, S. P. Nørsett, G. Wanner, Solving Ordinary Differential "
                     "Equations I, 2nd ed., Springer (1993)."),
    "danby": Source(r"\bDanby\b", "Danby",
                    "J. M. A. Danby, Fundamentals of Celestial Mechanics, 2nd ed., "
                    "Willmann-Bell (1988)."),
    # the names of the two-fixed-centres orbit classes (satellite, planetary, lemniscate)
    "waalkens": Source(r"\bWaalkens\b", "Waalkens, Dullin & Richter",
                       "H. Waalkens, H. R. Dullin, P. H. Richter, The problem of two fixed "
                       "centers: bifurcations, actions, monodromy, Physica D 196, 265 (2004) "
                       "(the orbit classes of Euler's problem as C. V. L. Charlier named them "
                       "in Die Mechanik des Himmels (1902): satellite, planetary and "
                       "lemniscate orbits)."),
    "yoshida": Source(r"\bYoshida\b", "Yoshida",
                      "H. Yoshida, Construction of higher order symplectic integrators, "
                      "Phys. Lett. A 150, 262 (1990)."),
    # "Thiele–Burrau variables" (two_center) name a regularization, not this paper
    "szebehely": Source(r"\bSzebehely\b|\bBurrau(?:'s)? (?:Pythagorean )?problem\b",
                        "Szebehely & Peters",
                        "V. Szebehely, C. F. Peters, Complete solution of a general problem "
                        "of three bodies, Astron. J. 72, 876 (1967) (Burrau's problem)."),
    "murray": Source(r"\bMurray (?:&|and) Dermott\b", "Murray & Dermott",
                     "C. D. Murray, S. F. Dermott, Solar System Dynamics, Cambridge University "
                     "Press (1999) (ch. 3, the restricted three-body problem; §9.4, chaos in "
                     "the circular restricted problem)."),
    # "Hénon–Heiles" names the system; "Hénon & Heiles" cites the paper
    "henon": Source(r"\bH[ée]non & Heiles\b", "Hénon & Heiles",
                    "M. Hénon, C. Heiles, The applicability of the third integral of motion: "
                    "some numerical experiments, Astron. J. 69, 73 (1964)."),
    "chenciner": Source(r"\b(?:Chenciner|Montgomery)\b", "Chenciner & Montgomery",
                        "A. Chenciner, R. Montgomery, A remarkable periodic solution of the "
                        "three-body problem in the case of equal masses, Ann. Math. 152, "
                        "881 (2000)."),
}

#: how far before a place its document's name may stand (same clause, same block)
CLAUSE = 40

#: the places a citation has (see the module's docstring)
PLACE = re.compile(
    r"§\s*(?:\d|[IVX]+\b)"
    r"|(?<![\w)\]′'])\((?:1\d|[1-9])\.[1-9]\d{0,2}[a-z]?"
    r"(?:\s*[–-]\s*(?:1\d|[1-9])\.[1-9]\d{0,2}[a-z]?)?\)"
    r"|\bFigs?\.\s*(?:\d|[IVX]+\.\d)|\bFigures?\s+\d+\.\d"
    r"|\b[Ee]x\.\s*(?:\d|[IVX]+\.\d)|\b[Ee]xercises?\s+\d|\b[Pp]roblems?\s+\d"
    r"|\b[Ee]qs?\.\s*\(?(?:\d|[IVX]+\.\d)|\b[Ee]quations?\s+\d"
    r"|\b[Cc]h\.\s*\d|\b[Cc]hapters?\s+\d"
    # a bare equation number right after the book's name: "Goldstein 5.72", "DLMF 22.19.4",
    # "DLMF 22.19(i)"
    r"|(?<=\bGoldstein )\d+\.\d+\b"
    r"|(?<=\bDLMF )\d+\.\d+(?:\.\d+)?(?:\([ivx]+\))?")

#: a document's name, as a citation gives it
_NAME = re.compile("|".join(f"(?P<{key}>{s.pattern})" for key, s in SOURCES.items()))
#: where a clause ends: a sentence's end (not an abbreviation's point) or a ";"
_CLAUSE_END = re.compile(r";|(?<!\bFig)(?<!\bFigs)(?<!\b[Ee]x)(?<!\b[Ee]q)(?<!\b[Ee]qs)"
                         r"(?<!\b[Cc]h)(?<!\bcf)(?<!\bed)(?<!\bvol)(?<!\bpp)(?<!\b[a-z]\.[a-z])"
                         r"[.!?](?=\s)")
_HIDDEN = re.compile(r"<(style|script|svg|head)\b.*?</\1\s*>", re.S | re.I)
_BLOCK = re.compile(r"</?(?:p|li|ul|ol|td|th|tr|table|caption|figcaption|figure|dt|dd|dl|"
                    r"h[1-6]|div|section|nav|header|footer|pre|br)\b[^>]*>", re.I)
_TAGS = re.compile(r"<[^>]+>")


def visible_blocks(html_text: str) -> list[str]:
    """The visible text of a report, one string per block (paragraph, caption, table cell,
    list item, fact, heading): the body before the sources list and the configuration
    listing (which quotes the user's own comments), without figures (their words are drawn
    as paths) and styles."""
    head, _, body = html_text.partition("<body")
    body = body.partition(">")[2] if body else head
    for section in ('<section id="sources">', '<section id="config">'):
        body = body.split(section, 1)[0]
    body = _HIDDEN.sub(" ", body)
    blocks = (" ".join(html.unescape(_TAGS.sub("", b)).split()) for b in _BLOCK.split(body))
    return [b for b in blocks if b]


def citing_document(block: str, place: re.Match) -> str | None:
    """The key of the document named before ``place`` (a match of :data:`PLACE` in
    ``block``) in its clause, within :data:`CLAUSE` characters; ``None`` for a bare
    citation."""
    start = max(0, place.start() - CLAUSE)
    before = block[start:place.start()]
    ends = list(_CLAUSE_END.finditer(before))
    if ends:
        start += ends[-1].end()
    text = block[start:place.end()]  # to the place's end: "notes" is told by what follows
    names = [m for m in _NAME.finditer(text) if m.start() < place.start() - start]
    return names[-1].lastgroup if names else None


def bare_citations(html_text: str) -> list[str]:
    """Every citation of a report's visible text that names no document, quoted with the
    words before it ("… the small-angle solution (1.19)")."""
    found = []
    for block in visible_blocks(html_text):
        for place in PLACE.finditer(block):
            if citing_document(block, place) is None:
                rest = re.match(r"[\w.]*(?<!\.)", block[place.end():]).group(0)
                found.append("…" + block[max(0, place.start() - CLAUSE):place.end()] + rest)
    return found


def cited(html_text: str) -> list[str]:
    """The keys of :data:`SOURCES` whose citations occur in the visible text of a report
    (:func:`visible_blocks`), in the order of :data:`SOURCES`."""
    text = "\n".join(visible_blocks(html_text))
    return [key for key, source in SOURCES.items() if re.search(source.pattern, text)]


def sources_section(html_text: str) -> Markup:
    """The "Sources" section a report ends with: every document its text cites, or
    nothing when it cites none."""
    keys = cited(html_text)
    if not keys:
        return Markup("")
    items = "".join(f"<li><b>{escape(SOURCES[k].label)}</b> – {escape(SOURCES[k].entry)}</li>"
                    for k in keys)
    return Markup('<section id="sources">\n<h2>Sources</h2>\n'
                  f'<ul class="sources">{items}</ul>\n</section>\n')


#: where the scene template leaves room for :func:`sources_section`
PLACEHOLDER = "<!-- sources -->"


def with_sources(html_text: str) -> str:
    """``html_text`` with its sources section in place of :data:`PLACEHOLDER`."""
    return html_text.replace(PLACEHOLDER, str(sources_section(html_text)), 1)
