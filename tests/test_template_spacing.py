"""Words glued to an equation: the report's Jinja environment has ``trim_blocks``, which
eats the newline after a block tag.  A tag that ends a line of text (``… {% endfilter %}``)
with the next line starting a word then prints the two with no space between them
("∂a/∂twith SymPy" was on the first-order oscillator's first page, "h²/10and the moments"
on the octahedron's).  ``+%}`` keeps the newline; this test finds every tag that needs it."""

from __future__ import annotations

import re
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
TEMPLATES = sorted([*(REPO / "reportgen" / "kinds").glob("*/*.j2"),
                    *(REPO / "templates").rglob("*.j2")])
_TRAILING_TAG = re.compile(r"\{%-?[^%]*?[^+]%\}$")


def glued(text: str) -> list[int]:
    """The lines (1-based) of ``text`` whose trailing block tag follows text on its line and
    is followed by a line that starts with a word: the two are printed without a space."""
    lines = text.split("\n")
    found = []
    for number, (line, following) in enumerate(zip(lines, lines[1:], strict=False), start=1):
        tag = _TRAILING_TAG.search(line)
        if tag and line[:tag.start()].strip() and re.match(r"[\w(]", following):
            found.append(number)
    return found


def test_the_rule_finds_a_glued_word_and_passes_a_kept_newline():
    assert glued("the equations {% filter eq %}x{% endfilter %}\nwith SymPy") == [1]
    assert glued("the equations {% filter eq %}x{% endfilter +%}\nwith SymPy") == []
    assert glued("{% if a %}\nwords") == []  # a tag alone on its line: nothing precedes it
    assert glued("text {% endif %}\n, and more") == []  # punctuation needs no space


def test_no_template_glues_a_word_to_what_a_block_tag_ends():
    found = [f"{path.relative_to(REPO)}:{n}" for path in TEMPLATES
             for n in glued(path.read_text(encoding="utf-8"))]
    assert found == [], "a block tag ends a line of text and the next line starts a word " \
                        "(use +%} to keep the newline):\n" + "\n".join(found)
