"""Section tables fit the page: a cell may wrap before a parenthesis, never inside a number."""

from __future__ import annotations

import re

from reportgen.rendering.report import table_cell


def test_cell_wraps_only_before_a_parenthesis():
    html = str(table_cell("5.1e-12 (rtol 1e-12)"))
    assert re.findall(r'<span class="nw">([^<]*)</span>', html) == ["5.1e-12", "(rtol 1e-12)"]
    assert str(table_cell("0.0064 s")) == '<span class="nw">0.0064 s</span>'  # unit kept


def test_cell_text_is_escaped():
    assert "&lt;script&gt;" in str(table_cell("<script> (x)"))


def test_the_stylesheet_lets_such_cells_wrap():
    from reportgen.support.layout import template_dir

    css = (template_dir() / "style.css.j2").read_text()
    assert re.search(r"td\.num\.wrap\s*\{\s*white-space:\s*normal", css)
    assert re.search(r"td\.num \.nw\s*\{\s*white-space:\s*nowrap", css)
