"""Every page of the shipped lecture pack fit to hand out (the checks of
``tests/pages.py``: the document gate, the PDF as an outside reader measures it, xarray,
citations, the report rebuilt from its archive alone), and the coverage map of the two
documents true of the pack's archives.  The scenes nobody shipped are checked the same way
in ``test_unseen_pages.py``."""

from __future__ import annotations

import re
from pathlib import Path

import h5py

from pages import page_tests

REPO = Path(__file__).resolve().parent.parent
SHIPPED = sorted((REPO / "configs").glob("*.toml"))

globals().update(page_tests(SHIPPED))


# ------------------------------------------------------------------- coverage map
COVERAGE = REPO / "docs" / "coverage.md"
_COVERAGE_ROW = re.compile(r"^\| *(?:notes|textbook)[^|]*\|")


def _coverage_rows() -> list[list[str]]:
    rows = []
    for line in COVERAGE.read_text(encoding="utf-8").splitlines():
        if _COVERAGE_ROW.match(line):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            assert len(cells) == 5, line
            rows.append(cells)
    return rows


def test_the_coverage_map_is_true(reports):
    """Every row of docs/coverage.md names a shipped config whose report has the section
    and whose archive has each result (a group, dataset or attribute of /analysis); a
    row shown by no config says why."""
    rows = _coverage_rows()
    assert len(rows) >= 50 and {r[0].split()[0] for r in rows} == {"notes", "textbook"}
    wrong = []
    for place, _, config, section, result in rows:
        if config == "—":
            assert result.startswith("— not shown"), place
            continue
        if not (REPO / "configs" / f"{config}.toml").exists():
            wrong.append(f"{place}: no config {config}")
            continue
        page = (reports / config / "report.html").read_text(encoding="utf-8")
        if f'<section id="{section}">' not in page:
            wrong.append(f"{place}: {config} has no section {section}")
        with h5py.File(reports / config / "run.h5", "r") as f:
            for key in (k.strip() for k in result.split(",")):
                group, _, name = key.rpartition("/")
                where = f["analysis"][group] if group else f["analysis"]
                if name not in where and name not in where.attrs:
                    wrong.append(f"{place}: {config} stores no {key}")
    assert wrong == [], "\n".join(wrong)
