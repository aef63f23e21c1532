"""Pages quoted from the source when the site is built: the archive layout (the module
docstrings of the archive writer, the sweep and the validating reader) and the shipped
notebook ``docs/example.ipynb`` (shown without running it, and offered for download)."""

from __future__ import annotations

import ast
import json
from pathlib import Path

from rst import to_markdown

REPO = Path(__file__).resolve().parents[2]

#: (heading, module file) quoted on the archive layout page, in this order
ARCHIVE_SOURCES = (
    ("The layout", "reportgen/archive/store.py"),
    ("Units and coordinates", "reportgen/archive/cf.py"),
    ("A family of runs: `/sweep`", "reportgen/scene/sweep.py"),
    ("What every reader checks first", "reportgen/archive/check.py"),
)


def module_docstring(relative: str) -> str:
    """The docstring of a module of the repository, read without importing it."""
    tree = ast.parse((REPO / relative).read_text(encoding="utf-8"))
    return ast.get_docstring(tree) or ""


def archive_layout() -> str:
    out = ["# Archive layout", "",
           "*Quoted from the docstrings of the modules that write and check archives when "
           "the site is built; the product contract (SPEC.md, \"Archive\") fixes the part "
           "other programs may rely on. [The archive](../archive.md) says how to read one.*",
           ""]
    for heading, relative in ARCHIVE_SOURCES:
        out += [f"## {heading}", "", f"From `{relative}`:", "",
                to_markdown(module_docstring(relative)), ""]
    return "\n".join(out)


def _fence(source: str, language: str) -> str:
    ticks = "````" if "```" in source else "```"
    return f"{ticks}{language}\n{source.rstrip()}\n{ticks}"


def notebook() -> str:
    """``docs/example.ipynb`` as a page: its Markdown cells as they are, its code cells as
    Python blocks, any stored text output below them (the shipped notebook stores none)."""
    cells = json.loads((REPO / "docs" / "example.ipynb").read_text(encoding="utf-8"))["cells"]
    out = ["*The shipped notebook `docs/example.ipynb`, shown here without running it: "
           "[download it](example.ipynb) and open it in Jupyter "
           "([Getting started](getting-started.md#a-first-notebook)), where every cell "
           "draws its output.*", ""]
    for cell in cells:
        source = "".join(cell.get("source", ""))
        if cell.get("cell_type") == "markdown":
            out += [source, ""]
        elif cell.get("cell_type") == "code":
            out += [_fence(source, "python"), ""]
            for output in cell.get("outputs", []):
                shown = output.get("text") or output.get("data", {}).get("text/plain")
                if shown:
                    out += [_fence("".join(shown), "text"), ""]
    # the notebook's own title (its first Markdown heading) heads the page
    first = next((i for i, line in enumerate(out) if line.startswith("# ")), None)
    if first is not None:
        out.insert(0, out.pop(first))
        out.insert(1, "")
    return "\n".join(out)


def pages() -> dict[str, str]:
    return {"reference/archive-layout.md": archive_layout(), "notebook.md": notebook()}
