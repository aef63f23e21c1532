"""reStructuredText of our docstrings as Markdown, for the documentation site.

The package's docstrings are written for Sphinx-style readers: roles
(``:func:`~reportgen.api.run```), doctest sessions and literal blocks after ``::``.  The
site renders Markdown, so these few constructs are rewritten before a docstring reaches a
page: by the griffe extension :mod:`griffe_rst` for the API reference, and by the page
generators for the module docstrings they quote (the archive layout).  Nothing else of
reStructuredText is used in the package.
"""

from __future__ import annotations

import re

#: ``:func:`~reportgen.api.run``` and the like; ``~`` keeps only the last name
_ROLE = re.compile(r":(?:py:)?(?:func|class|meth|mod|data|attr|exc|obj|const)"
                   r":`(~?)([^`<]+?)(?:\s*<([^`>]+)>)?`")


def _role(match: re.Match) -> str:
    short, text, target = match.groups()
    name = (target or text).strip()
    if short:
        name = name.rsplit(".", 1)[-1]
    return f"`{name}`" if not target else f"{text.strip()} (`{name}`)"


def roles_to_code(text: str) -> str:
    """Sphinx cross-reference roles as inline code (no link: the site does not document
    every target, and a dangling link would fail the strict build)."""
    return _ROLE.sub(_role, text)


def _is_prompt(line: str) -> bool:
    return line.lstrip().startswith(">>>")


def _fence_doctests(lines: list[str]) -> list[str]:
    """Doctest sessions (``>>>`` lines, ``...`` continuations and their output, up to a
    blank line) as ```pycon fenced blocks."""
    out: list[str] = []
    i = 0
    while i < len(lines):
        if not _is_prompt(lines[i]):
            out.append(lines[i])
            i += 1
            continue
        indent = len(lines[i]) - len(lines[i].lstrip())
        out.append(" " * indent + "```pycon")
        while i < len(lines) and lines[i].strip():
            out.append(lines[i])
            i += 1
        out.append(" " * indent + "```")
    return out


def _fence_literal_blocks(lines: list[str]) -> list[str]:
    """A paragraph ending in ``::`` followed by an indented block: the block as a fenced
    ```text block, the paragraph ending in one colon (rst's own rule)."""
    out: list[str] = []
    i = 0
    while i < len(lines):
        line = lines[i]
        if not line.rstrip().endswith("::"):
            out.append(line)
            i += 1
            continue
        head = line.rstrip()[:-1]
        out.append(head.rstrip() if head.rstrip().endswith(":") else head)
        base = len(line) - len(line.lstrip())
        j = i + 1
        while j < len(lines) and not lines[j].strip():
            j += 1
        block: list[str] = []
        while j < len(lines) and (not lines[j].strip()
                                  or len(lines[j]) - len(lines[j].lstrip()) > base):
            block.append(lines[j])
            j += 1
        while block and not block[-1].strip():
            block.pop()
        if not block:  # a "::" with nothing indented after it: leave the text alone
            i += 1
            continue
        cut = min(len(b) - len(b.lstrip()) for b in block if b.strip())
        out += ["", " " * base + "```text", *[" " * base + b[cut:] for b in block],
                " " * base + "```", ""]
        i = j
    return out


def to_markdown(text: str) -> str:
    """A docstring's reStructuredText (the constructs above) as Markdown."""
    lines = _fence_literal_blocks(roles_to_code(text).splitlines())
    return "\n".join(_fence_doctests(lines))
