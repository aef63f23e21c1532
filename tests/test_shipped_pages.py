"""Every page of the shipped lecture pack fit to hand out (the checks of
``tests/pages.py``: the document gate, the PDF as an outside reader measures it, xarray,
citations, the report rebuilt from its archive alone), and the coverage map of the two
documents true of the pack's archives.  The scenes nobody shipped are checked the same way
in ``test_unseen_pages.py``."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import h5py

from conftest import study_off_text
from pages import page_tests

REPO = Path(__file__).resolve().parent.parent
SHIPPED = sorted((REPO / "configs").glob("*.toml"))


def _study_off(configs: list[Path]) -> list[Path]:
    """All but one config of each kind: the error-against-run-time study is most of a
    scene's cost, and its pages are the same section for every scene of a kind, so the
    suite checks them on one scene per kind (``make run`` runs every study)."""
    first: dict[str, Path] = {}
    for path in configs:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        if study_off_text(path) != path.read_text(encoding="utf-8"):  # it has a study
            first.setdefault(data["kind"], path)
    return [p for p in configs if p not in first.values()]


globals().update(page_tests(SHIPPED, study_off=_study_off(SHIPPED)))


# ------------------------------------------------------------------- coverage map
COVERAGE = REPO / "docs" / "coverage.md"
_COVERAGE_ROW = re.compile(r"^\| *(?:notes|textbook)[^|]*\|")
#: the kinds of index entries the map must have a row for (every equation is not a row:
#: the map groups them under their section)
_MAPPED = ("section", "example", "figure", "exercise", "exercise-part")


def _coverage_rows() -> list[list[str]]:
    rows = []
    for line in COVERAGE.read_text(encoding="utf-8").splitlines():
        if _COVERAGE_ROW.match(line):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            assert len(cells) == 6, line
            rows.append(cells)
    return rows


def test_the_coverage_map_has_a_row_for_every_place_of_the_index():
    """One row per section, worked example, figure and exercise part of both documents
    (an exercise without parts is its own row); every row names a place of the index."""
    from reportgen.scene.places import places, resolve

    rows = _coverage_rows()
    covered = set()
    for place, _, shown, *_ in rows:
        document, _, where = place.partition(" ")
        assert shown in ("yes", "partly", "no"), place
        covered |= {(document, p.place) for p in resolve(document, where)}
    missing = []
    for document in ("notes", "textbook"):
        index = places(document)
        with_parts = {p.place.split("(")[0] for p in index.values() if p.kind == "exercise-part"}
        for key, p in index.items():
            if p.kind not in _MAPPED or (p.kind == "exercise" and key in with_parts):
                continue
            if (document, key) not in covered:
                missing.append(f"{document} {key} ({p.label})")
    assert missing == [], "no row in docs/coverage.md for:\n  " + "\n  ".join(missing)


def test_the_coverage_map_is_true(reports):
    """Every row of docs/coverage.md shown (yes or partly) names a shipped config whose
    report has the section and whose archive has each result (a group, dataset or
    attribute of /analysis); a row not shown says why."""
    rows = _coverage_rows()
    assert len(rows) >= 100 and {r[0].split()[0] for r in rows} == {"notes", "textbook"}
    wrong = []
    for place, _, shown, config, section, result in rows:
        if shown == "no":
            assert config == section == "—" and result.startswith("— not shown: "), place
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
