"""Every page fit to hand out: the document gate over every shipped report and over a
varied, untitled config of every kind (tests/data/variants: cases the shipped pack does
not show -- a rotating pendulum, a Kepler hyperbola, a prolate and a stable asymmetric
body, a molecule written from scratch, a one-degree-of-freedom Hamiltonian ...).

The two folders are run once, together, by the command line a lecturer uses
(``reportgen run ... --jobs 2``, study and PDF on), and every report's ``gate.json``
must be empty: nothing past the content area, no nan/inf/−0, no config key, Python or
raw TeX in visible text, no near-empty interior page, and every figure's series
distinguishable, legends off the data, axes with symbols and units, marked points inside
the limits (reportgen/rendering/gate.py; each rule's seeded defect is in
test_document_gate.py).  The words of every PDF are also measured as an outside reader
would (``pdftotext -bbox``): none within half an inch of the paper's right edge, no
fallback title "kind (slug)".  Every archive opens in xarray with named dimensions (no
``phony_dim``, no warning) and ``units`` on every variable, in every group (``/analysis``
and its subgroups included).
"""

from __future__ import annotations

import html
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import pytest

from reportgen.rendering.gate import GATE_FILE

REPO = Path(__file__).resolve().parent.parent
SHIPPED = sorted((REPO / "configs").glob("*.toml"))
VARIANTS = sorted((REPO / "tests" / "data" / "variants").glob("*.toml"))
SCENES = [*SHIPPED, *VARIANTS]

WORD = re.compile(r'<word xMin="[\d.]+" yMin="[\d.]+" xMax="([\d.]+)" yMax="[\d.]+">(.*?)</word>')
PAGE = re.compile(r'<page width="([\d.]+)" height="[\d.]+">(.*?)</page>', re.S)
HALF_INCH = 36.0


@pytest.fixture(scope="module")
def reports(tmp_path_factory) -> Path:
    """The output folder of one ``reportgen run`` over the shipped configs and the
    variants (the variants copied beside them, so one batch runs both)."""
    source = tmp_path_factory.mktemp("scenes")
    for config in SCENES:
        assert not (source / config.name).exists(), f"two scenes named {config.stem}"
        shutil.copy(config, source / config.name)
    out = tmp_path_factory.mktemp("out")
    proc = subprocess.run([sys.executable, "-m", "reportgen", "run", str(source), "--out",
                           str(out), "--jobs", "2"], capture_output=True, text=True,
                          timeout=1800)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    return out


@pytest.mark.parametrize("config", SCENES, ids=[p.stem for p in SCENES])
def test_every_page_passes_the_gate(config, reports):
    folder = reports / config.stem
    findings = json.loads((folder / GATE_FILE).read_text(encoding="utf-8"))
    assert findings == [], f"{config.name}: {len(findings)} findings\n" + "\n".join(findings)


@pytest.mark.skipif(shutil.which("pdftotext") is None, reason="poppler-utils not installed")
@pytest.mark.parametrize("config", SCENES, ids=[p.stem for p in SCENES])
def test_no_word_near_the_paper_edge_and_a_real_title(config, reports):
    pdf = reports / config.stem / "report.pdf"
    text = subprocess.run(["pdftotext", "-bbox", str(pdf), "-"], capture_output=True,
                          text=True, timeout=120).stdout
    near = []
    for number, (width, body) in enumerate(PAGE.findall(text), start=1):
        for right, word in WORD.findall(body):
            if float(right) > float(width) - HALF_INCH:
                near.append(f"p{number}: {html.unescape(word)!r} ends at {float(right):.0f} pt")
            if html.unescape(word).strip(",;:()") in ("nan", "NaN", "-0", "\u22120"):
                near.append(f"p{number}: prints {html.unescape(word)!r}")
    assert near == []
    first = subprocess.run(["pdftotext", "-l", "1", str(pdf), "-"], capture_output=True,
                           text=True, timeout=60).stdout
    title = next(line.strip() for line in first.splitlines() if line.strip())
    assert not re.fullmatch(r"[a-z ]+ \(" + re.escape(config.stem) + r"\)", title), title


@pytest.mark.parametrize("config", SCENES, ids=[p.stem for p in SCENES])
def test_every_archive_opens_in_xarray_with_units(config, reports):
    import warnings

    import xarray as xr

    path = reports / config.stem / "run.h5"
    groups: list[str] = []
    with h5py.File(path, "r") as f:  # every group: runs, /analysis and its subgroups, sweep
        f.visititems(lambda name, obj: groups.append(name) if isinstance(obj, h5py.Group)
                     else None)
    for group in [None, *groups]:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # the phony_dims warning (or any other) fails
            ds = xr.open_dataset(path, group=group, engine="h5netcdf")
        with ds:
            assert not [d for d in ds.dims if str(d).startswith("phony")], (group, ds.dims)
            bare = [n for n, v in ds.variables.items() if "units" not in v.attrs]
            assert not bare, f"{config.stem}:{group}: no units on {bare}"


# ------------------------------------------------------------------- citations
_LABEL = re.compile(r"<li><b>(.*?)</b>")


@pytest.mark.parametrize("config", SCENES, ids=[p.stem for p in SCENES])
def test_every_citation_names_its_document(config, reports):
    """No "(10.25)" or "Fig. 4.3" without the document it is in (reportgen.scene.sources),
    and the Sources list holds exactly the documents the text cites, in their order."""
    from markupsafe import escape

    from reportgen.scene.sources import (
        PLACE,
        SOURCES,
        bare_citations,
        cited,
        citing_document,
        visible_blocks,
    )

    page = (reports / config.stem / "report.html").read_text(encoding="utf-8")
    bare = list(dict.fromkeys(bare_citations(page)))
    assert bare == [], f"{config.stem}: citations naming no document:\n  " + "\n  ".join(bare)
    named = {key for block in visible_blocks(page) for place in PLACE.finditer(block)
             if (key := citing_document(block, place)) is not None}
    section = page.split('<section id="sources">', 1)
    listed = []
    if len(section) == 2:
        by_label = {str(escape(s.label)): k for k, s in SOURCES.items()}
        listed = [by_label[label] for label in
                  _LABEL.findall(section[1].split("</section>", 1)[0])]
    assert named <= set(listed), f"{config.stem}: cited but not listed: {named - set(listed)}"
    assert listed == cited(page) == [k for k in SOURCES if k in listed]



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
