"""What a report says, without how long things took: the structure of a scene's HTML
(sections, headings, figures, fact labels, table headers and the first cell of each
row) and a sample of its archive arrays.  Used by test_report_content.py and to write
its stored reference (``python tests/report_content.py ARCHIVE_FOLDER OUT.json``)."""

from __future__ import annotations

import json
import sys
from html.parser import HTMLParser
from pathlib import Path

import h5py
import numpy as np

#: sections whose rows depend on timing (the study's ladders stop on a time budget)
TIMED_SECTIONS = {"error_vs_runtime"}


class _Structure(HTMLParser):
    def __init__(self):
        super().__init__()
        self.items: list[list[str]] = []
        self.section = ""
        self._capture: str | None = None
        self._text = ""
        self._row_cells = 0
        self._script: str | None = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "section":
            self.section = a.get("id", "")
            self.items.append(["section", self.section])
        elif tag == "figure" and "id" in a:
            self.items.append(["figure", a["id"]])
        elif tag in ("h2", "th", "dt", "td"):
            if tag == "td":
                self._row_cells += 1
                if self._row_cells > 1 or self.section in TIMED_SECTIONS:
                    return
            self._capture, self._text = tag, ""
        elif tag == "tr":
            self._row_cells = 0
        elif tag in ("sub", "sup"):
            self._script = tag

    def handle_endtag(self, tag):
        if tag in ("sub", "sup"):
            self._script = None
        if tag == self._capture:
            text = " ".join(self._text.split())
            self.items.append([{"td": "row"}.get(tag, tag), text])
            self._capture = None

    def handle_data(self, data):
        if self._capture:
            self._text += _script(data, self._script) if self._script else data


_SCRIPTS = {"sub": str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉"),
            "sup": str.maketrans("0123456789−", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")}


def _script(text: str, tag: str) -> str:
    """A sub- or superscript as it reads: Unicode's small digits, else ``_{…}``/``^{…}``."""
    small = text.translate(_SCRIPTS[tag])
    if all(not c.isascii() or c in " ." for c in small):
        return small
    return ("_" if tag == "sub" else "^") + "{" + text + "}"


def html_structure(html: str) -> list[list[str]]:
    parser = _Structure()
    parser.feed(html)
    return parser.items


def archive_sample(path: Path, every: int = 100) -> dict[str, list[float]]:
    """Every ``every``-th row of each run's state and invariants."""
    out = {}
    with h5py.File(path, "r") as f:
        for run in sorted(f["runs"]):
            g = f["runs"][run]
            out[f"{run}/t"] = g["t"][::every].tolist()
            out[f"{run}/y"] = np.asarray(g["y"][::every]).ravel().tolist()
            for name in sorted(g.get("invariants", {})):
                out[f"{run}/invariants/{name}"] = g["invariants"][name][::every].tolist()
    return out


def content(folder: Path) -> dict:
    html = (folder / "report.html").read_text(encoding="utf-8")
    return {"html": html_structure(html), "arrays": archive_sample(folder / "run.h5")}


if __name__ == "__main__":
    Path(sys.argv[2]).write_text(json.dumps(content(Path(sys.argv[1])), indent=0) + "\n")
