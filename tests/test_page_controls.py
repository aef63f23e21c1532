"""Control characters and bidirectional overrides on pages (issue 48 I): a title that
would reverse the text after it (U+202E) or ring a bell is shown as its escape, on the
report, the gallery and the notebook view alike, as the terminal shows it."""

from __future__ import annotations

import unicodedata

from conftest import pendulum_text
from reportgen.support.layout import printable

#: TOML escapes: a right-to-left override, a bell, a C1 control, a left-to-right isolate
TITLE = r"evil \u202Egnp.exe \u0007 bell \u0085 next \u2066"
SHOWN = "evil \\u202egnp.exe \\x07 bell \\x85 next \\u2066"
BIDI = set("\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")


def _hidden(page: str) -> set[str]:
    """The characters of ``page`` that act rather than show (line feed and tab aside)."""
    return {c for c in page
            if (unicodedata.category(c) == "Cc" and c not in "\n\t") or c in BIDI}


def test_a_title_with_an_override_and_a_control_is_shown_on_every_page(tmp_path, cli):
    import reportgen

    cfg = tmp_path / "evil.toml"
    cfg.write_text(pendulum_text(t_end=2.0, samples=41, title=TITLE,
                                 extra='method = "scipy_dop853"\n[report]\nformats = ["html"]\n'),
               encoding="utf-8")
    code, out, err = cli("run", cfg, "--out", tmp_path / "out", "--jobs", "1")
    assert code == 0, err
    title = "evil \u202egnp.exe \x07 bell \x85 next \u2066"
    assert printable(title) == SHOWN  # the terminal's form, which the pages use too
    pages = {"report": (tmp_path / "out" / "evil" / "report.html").read_text(encoding="utf-8"),
             "gallery": (tmp_path / "out" / "index.html").read_text(encoding="utf-8"),
             "notebook": reportgen.open(tmp_path / "out" / "evil")._repr_html_()}
    for name, page in pages.items():
        assert _hidden(page) == set(), name
        assert SHOWN in page, name
    assert reportgen.open(tmp_path / "out" / "evil").title == title  # the data keeps it
