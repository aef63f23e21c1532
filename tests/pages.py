"""The checks every report of a batch must pass, shared by the page tests of the shipped
pack (``test_shipped_pages.py``) and of the scenes nobody shipped
(``test_unseen_pages.py``): one ``reportgen run`` per module, as a lecturer runs it (study
and PDF on, ``--jobs 2``), then per scene

- the document gate's ``gate.json`` is empty (nothing past the content area, no
  nan/inf/−0, no config key, Python or raw TeX in visible text, typography a textbook
  would not print, provenance in the body, no page under a quarter full; every figure's
  series distinguishable, legends off the data, axes with symbols and units, marked
  points inside the limits: reportgen/rendering/gate.py, each rule's seeded defect in
  test_document_gate.py);
- as an outside reader measures the PDF (``pdftotext``): no word within half an inch of
  the paper's right edge, no fallback title "kind (slug)", no hyphen as a minus sign,
  E-notation or snake_case outside the appended configuration;
- every archive opens in xarray with named dimensions, in every group and as one tree, and
  ``pint-xarray`` quantifies every group: every number has a ``units`` pint reads (or
  says where its units are: a state of mixed units by ``column_units``, a checks column
  by ``units_column``), text has none; every dataset has a CF ``long_name``;
- every citation names its document, and the Sources list holds exactly those cited;
  each citation of the notes or the textbook resolves to a place of their index and the
  words around it are about that place;
- the archive is the whole truth: the report rebuilt from the archive alone, in a process
  where ``reportgen.core`` cannot be imported, gives the same page and byte-identical
  figures.
Each test module calls :func:`page_tests` with its scenes and adds the returned fixtures
and tests to its namespace.
"""

from __future__ import annotations

import html
import json
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import h5py
import pytest

from conftest import study_off_text
from reportgen.rendering.gate import GATE_FILE

WORD = re.compile(r'<word xMin="[\d.]+" yMin="[\d.]+" xMax="([\d.]+)" yMax="[\d.]+">(.*?)</word>')
PAGE = re.compile(r'<page width="([\d.]+)" height="[\d.]+">(.*?)</page>', re.S)
HALF_INCH = 36.0

#: typography a textbook does not print, as an outside reader finds it in the PDF's text
#: (the rules of ../shared/tools/page-check): a hyphen as a minus sign, E-notation, a
#: snake_case identifier, outside the appended configuration
_TYPOGRAPHY = {
    "hyphen as minus": re.compile(r"(?:^|[\s(=\[,;:/±])-(?=\d)"),
    "E-notation": re.compile(r"\b\d+(?:\.\d+)?e[-+\u2212]?\d+\b"),
    "snake_case": re.compile(r"\b[a-z][a-z0-9]*_[a-z0-9_]+\b"),
}
_LABEL = re.compile(r"<li><b>(.*?)</b>")

#: rebuilds reports from their archives alone: reportgen.core cannot be imported; each
#: archive's failure is written beside its rebuilt report, so one does not hide the others
BLOCKED_REBUILD = """
import sys, traceback
sys.modules["reportgen.core"] = None
from pathlib import Path
from reportgen.rendering.report import build_report
out = Path(sys.argv[1])
for archive in map(Path, sys.argv[2:]):
    folder = out / archive.parent.name
    try:
        build_report(archive, formats=("html",), out_dir=folder)
    except Exception:
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "ERROR").write_text(traceback.format_exc())
core = [m for m in sys.modules if m.startswith("reportgen.core.")]
assert not core, f"core was imported: {core}"
"""


def run_batch(scenes: list[Path], source: Path, out: Path, study_off=()) -> Path:
    """One ``reportgen run`` of ``scenes`` (copied into ``source``; those in ``study_off``
    without their study) into ``out``, as a lecturer runs it."""
    for config in scenes:
        assert not (source / config.name).exists(), f"two scenes named {config.stem}"
        if config in study_off:
            (source / config.name).write_text(study_off_text(config), encoding="utf-8")
        else:
            shutil.copy(config, source / config.name)
    proc = subprocess.run([sys.executable, "-m", "reportgen", "run", str(source), "--out",
                           str(out), "--jobs", "2"], capture_output=True, text=True,
                          timeout=1800)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    return out


#: where a number whose rows or columns have several units says where they are
UNITS_ELSEWHERE = ("column_units", "units_column", "units_note")


def datasets_without_cf_attrs(archive: Path) -> list[str]:
    """Every dataset of the archive lacking ``long_name`` (CF style) or with an empty one,
    and every numeric one without ``units`` that does not say where its units are
    (:data:`UNITS_ELSEWHERE`)."""
    bad = []

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            attrs = obj.attrs
            numeric = obj.dtype.kind in "iufc" and attrs.get("dtype") != "bool"  # no flag
            unitless = numeric and "units" not in attrs and not any(
                k in attrs for k in UNITS_ELSEWHERE)
            if unitless or "long_name" not in attrs or not str(attrs["long_name"]):
                bad.append(name)

    with h5py.File(archive, "r") as f:
        f.visititems(visit)
    return bad


def unit_problems(ds) -> list[str]:
    """The variables of the xarray dataset ``ds`` whose units are not as the archive
    promises: a number without ``units`` (or :data:`UNITS_ELSEWHERE`), a ``units`` pint
    cannot read, text with ``units``."""
    import pint_xarray  # noqa: F401 - the accessor

    registry = pint_xarray.unit_registry
    bad = []
    for name, var in ds.variables.items():
        units = var.attrs.get("units")
        if var.dtype.kind in "OUSb":
            if units is not None:
                bad.append(f"{name}: text or a flag with units {units!r}")
        elif units is None:
            if not any(k in var.attrs for k in UNITS_ELSEWHERE):
                bad.append(f"{name}: a number without units")
        else:
            try:
                registry.parse_units(units)
            except Exception as exc:  # noqa: BLE001 - pint raises several kinds
                bad.append(f"{name}: units {units!r} ({type(exc).__name__})")
    return bad


def assert_tree_quantifies(archive: Path) -> None:
    """``xr.open_datatree`` opens the archive without a warning, and pint-xarray quantifies
    every group of it."""
    import warnings

    import pint_xarray  # noqa: F401 - the accessor
    import xarray as xr

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tree = xr.open_datatree(archive, engine="h5netcdf")
    with tree:
        for node in tree.subtree:
            ds = node.to_dataset()
            assert not unit_problems(ds), (node.path, unit_problems(ds))
            ds.pint.quantify()


def assert_xarray_reads(archive: Path) -> None:
    """``runs/<name>`` opens in xarray with named dimensions: t a coordinate, the state
    components a string coordinate, invariants variables on t, no phony dimensions."""
    import h5py
    import xarray as xr

    with h5py.File(archive, "r") as f:
        runs = {name: list(g["component"].asstr()[()]) for name, g in f.get("runs", {}).items()}
        invariants = {name: list(g["invariants"]) for name, g in f.get("runs", {}).items()}
    for name, components in runs.items():
        with xr.open_dataset(archive, group=f"runs/{name}", engine="h5netcdf",
                             phony_dims="sort") as ds:
            assert not [d for d in ds.dims if str(d).startswith("phony_dim")], ds.dims
            assert ds.y.dims == ("t", "component")
            assert "t" in ds.coords and list(ds.component.values) == components
            first = components[0]
            assert (ds.y.sel(component=first).values == ds.y.values[:, 0]).all()
            for q in invariants[name]:
                var = q if q in ds else f"invariant_{q}"
                assert ds[var].dims == ("t",), (q, ds)



def page_tests(scenes: list[Path], study_off=()) -> dict:
    """The fixtures ``reports`` (the batch's output folder) and ``rebuilt`` (each report
    rebuilt from its archive alone) and the per-scene tests, for a test module's
    namespace."""
    ids = [p.stem for p in scenes]
    # the archive-alone rebuild reads every kind's report code: one scene of each kind
    kinds: dict[str, Path] = {}
    for p in scenes:
        kinds.setdefault(tomllib.loads(p.read_text(encoding="utf-8"))["kind"], p)
    per_kind = sorted(kinds.values())

    @pytest.fixture(scope="module")
    def reports(tmp_path_factory) -> Path:
        return run_batch(scenes, tmp_path_factory.mktemp("scenes"),
                         tmp_path_factory.mktemp("out"), study_off)

    @pytest.fixture(scope="module")
    def rebuilt(reports, tmp_path_factory) -> Path:
        out = tmp_path_factory.mktemp("rebuilt")
        archives = [str(reports / p.stem / "run.h5") for p in per_kind]
        proc = subprocess.run([sys.executable, "-c", BLOCKED_REBUILD, str(out), *archives],
                              capture_output=True, text=True, timeout=1800)
        assert proc.returncode == 0, proc.stderr[-3000:]
        return out

    @pytest.mark.parametrize("config", scenes, ids=ids)
    def test_every_page_passes_the_gate(config, reports):
        folder = reports / config.stem
        findings = json.loads((folder / GATE_FILE).read_text(encoding="utf-8"))
        assert findings == [], f"{config.name}: {len(findings)} findings\n" + "\n".join(findings)

    @pytest.mark.skipif(shutil.which("pdftotext") is None, reason="poppler-utils not installed")
    @pytest.mark.parametrize("config", scenes, ids=ids)
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

    @pytest.mark.skipif(shutil.which("pdftotext") is None, reason="poppler-utils not installed")
    @pytest.mark.parametrize("config", scenes, ids=ids)
    def test_the_text_is_typeset_as_a_textbook(config, reports):
        text = subprocess.run(["pdftotext", str(reports / config.stem / "report.pdf"), "-"],
                              capture_output=True, text=True, timeout=120).stdout
        cut = text.rfind("\nConfiguration\n")
        assert cut > 0, "the configuration heading is where an outside reader looks for it"
        found = [f"{rule}: …{text[max(0, m.start() - 25):m.end() + 10]!r}…"
                 for rule, rx in _TYPOGRAPHY.items() for m in rx.finditer(text[:cut])]
        assert found == [], f"{config.stem}:\n" + "\n".join(found)

    @pytest.mark.parametrize("config", scenes, ids=ids)
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
                bare = unit_problems(ds)
                assert not bare, f"{config.stem}:{group}: {bare}"
        assert datasets_without_cf_attrs(path) == []
        assert_xarray_reads(path)
        assert_tree_quantifies(path)


    # ------------------------------------------------------------------- citations
    @pytest.mark.parametrize("config", scenes, ids=ids)
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

    @pytest.mark.parametrize("config", scenes, ids=ids)
    def test_every_citation_resolves_to_its_place(config, reports):
        """Each citation of the notes or the textbook names a place of the documents' index
        (reportgen/data/places_*.toml, checked against the documents by test_places.py)
        and the words around it are about that place (one of its topics): "the reduced
        mass, notes (3.22)", never "(3.20)" (reportgen.scene.citations)."""
        from reportgen.scene.citations import problems

        page = (reports / config.stem / "report.html").read_text(encoding="utf-8")
        found = list(dict.fromkeys(problems(page)))
        assert found == [], f"{config.stem}:\n  " + "\n  ".join(found)

    @pytest.mark.parametrize("config", per_kind, ids=[p.stem for p in per_kind])
    def test_the_report_is_a_function_of_the_archive_alone(config, reports, rebuilt):
        first, second = reports / config.stem, rebuilt / config.stem
        assert not (second / "ERROR").exists(), (second / "ERROR").read_text()
        svgs = sorted(p.name for p in (first / "figures").glob("*.svg"))
        assert svgs, f"no figures in {first}"
        assert svgs == sorted(p.name for p in (second / "figures").glob("*.svg"))
        for name in svgs:
            assert (first / "figures" / name).read_bytes() == \
                (second / "figures" / name).read_bytes(), \
                f"figure {name} differs when drawn from the archive alone"
        assert (second / "report.html").read_text(encoding="utf-8") == \
            (first / "report.html").read_text(encoding="utf-8")
        assert_xarray_reads(first / "run.h5")

    return {name: value for name, value in locals().items()
            if name.startswith("test_") or name in ("reports", "rebuilt")}
