"""Markdown pieces the page generators share: table cells that survive any text, tables."""

from __future__ import annotations

import html
import re

#: a code span in text that is already Markdown (a description quoting `reportgen kinds`)
_CODE_SPAN = re.compile(r"(`+)(.+?)\1")


def text(value: str) -> str:
    """Plain text as one table cell: HTML escaped (``p_<q>`` is not a tag), pipes and
    emphasis markers escaped, code spans kept; one line."""
    out, at = [], 0
    value = " ".join(str(value).split())
    for m in _CODE_SPAN.finditer(value):
        out.append(_plain(value[at:m.start()]))
        out.append(code(m.group(2)))
        at = m.end()
    out.append(_plain(value[at:]))
    return "".join(out)


def _plain(value: str) -> str:
    value = html.escape(value, quote=False)
    return re.sub(r"([|*_\[\]\\])", r"\\\1", value)


def code(value: str) -> str:
    """``value`` as an inline code span (safe in a table cell: the table extension does
    not split a row at a pipe inside a code span)."""
    value = " ".join(str(value).split())
    fence = "``" if "`" in value else "`"
    pad = " " if value.startswith("`") or value.endswith("`") else ""
    return f"{fence}{pad}{value}{pad}{fence}"


def table(headers: list[str], rows: list[list[str]]) -> str:
    """A Markdown table; cells are given as Markdown already (see :func:`text`)."""
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)
