"""Adding a kind is one folder under reportgen/kinds/ plus its config; adding a stored
quantity is one declaration.

The package and templates are copied to a temporary folder; one new package
(``kinds/free_oscillation/``: config, declared results, simulation, report, template)
and a config are added there and nothing else is edited.  ``kinds`` lists the new kind,
``validate`` accepts its config, ``run`` simulates and reports it, the archive carries
each declared quantity's unit, xarray shows it, a figure's axis is labelled from the
declaration, and the report rebuilds with ``reportgen.core`` blocked.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import h5py
import xarray as xr

REPO = Path(__file__).resolve().parent.parent

TINY = {
    "__init__.py": '''
"""``free_oscillation``: a tiny kind used by the test suite (q'' = -omega^2 q)."""

from .config import FreeConfig
from .report import FreeReport
from .simulation import FreeSimulation


class FreeOscillationScene(FreeSimulation, FreeReport):
    kind = "free_oscillation"
    summary = "a test kind: q'' = -omega^2 q"
    Config = FreeConfig
''',
    "config.py": '''
from pydantic import Field

from ...scene.config import Positive, Real, RunConfig, Strict
from ...scene.base import SceneConfig


class Params(Strict):
    omega: Positive = Field(description="angular frequency [rad/s]")


class Initial(Strict):
    q: Real = Field(description="initial displacement [m]")


class FreeConfig(SceneConfig):
    params: Params
    initial: Initial
    run: RunConfig
''',
    "results.py": '''
from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

SCHEMA = ResultsSchema(
    columns=(Q("q", "q", "m", "displacement", ("t",)),
             Q("p", "p", "kg m/s", "momentum", ("t",))),
    analysis=(Q("period", "T", "s", "period 2 pi / omega"),
              # DECLARATION
              ),
)
''',
    "simulation.py": '''
import numpy as np

from ...lazy import lazy_module
from ...scene.results import Check, Results
from ...scene.integration import IntegratingSimulation
from .results import SCHEMA

oscillator = lazy_module("reportgen.core.models.oscillator")


class FreeSimulation(IntegratingSimulation):
    schema = SCHEMA

    def simulate(self, progress=None):
        w, q0 = self.config.params.omega, self.config.initial.q
        t = np.linspace(0.0, self.config.run.t_end, self.config.run.samples)
        model = oscillator.hamilton_model(1.0, w)
        results = Results()
        run = self.integrate(model, np.array([q0, 0.0]), t)
        run.reference = {"q": q0 * np.cos(w * t)}
        run.attrs["reference_label"] = "q0 cos(omega t)"
        results.runs["main"] = run
        results.analysis["period"] = 2 * np.pi / w
        # STORE
        results.checks.append(Check("q(t_end)", float(run["q"][-1]),
                                    float(run.reference["q"][-1]), "m", "q0 cos(omega t)",
                                    scale=abs(q0)))
        return results
''',
    "report.py": '''
from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, fmt
from ...scene.report import Report
from .results import SCHEMA

style = lazy_module("reportgen.rendering.plots.style")


class FreeReport(Report):
    schema = SCHEMA
    sections = (Section("motion", "Motion", integrates=True),
                Section("error_vs_runtime", "Error against run time", integrates=True))

    @classmethod
    def headline(cls, data):
        return [("period", f"{fmt(data.analysis['period'])} s")]

    @classmethod
    def section_motion(cls, data):
        run = data.runs["main"]
        fig, ax = style.new_figure()
        ax.plot(run.t, run["q"], label="integrated")
        ax.plot(run.t, run.reference["q"], linestyle="--", label=run.attrs["reference_label"])
        ax.set_xlabel(cls.label("t"))
        ax.set_ylabel(cls.label("q"))
        ax.legend()
        figures = [cls.figure("q", fig, "q(t) against the exact cosine.")]
        if "envelope" in data.analysis:
            fig, ax = style.new_figure()
            ax.plot(run.t, data.analysis["envelope"])
            ax.set_xlabel(cls.label("t"))
            ax.set_ylabel(cls.label("envelope"))
            figures.append(cls.figure("envelope", fig, "The envelope."))
        return SectionContent(figures=figures)
''',
    "template.html.j2": """
{% macro summary() %}<p>A free oscillation, added as one package.</p>{% endmacro %}
""",
}

#: the one declaration that adds a stored quantity (and the line that stores it)
DECLARATION = ('Q("envelope", "A", "mm", "amplitude envelope", ("t",)),',
               'results.analysis["envelope"] = 1e3 * np.hypot(run["q"], run["p"] / w)')

TINY_CONFIG = """
kind = "free_oscillation"
title = "A kind added as one module"

[params]
omega = 2.0

[initial]
q = 0.5

[run]
t_end = 6.0
samples = 301
study = false

[report]
formats = ["html"]
"""


def _add_kind(root: Path, with_quantity: bool) -> None:
    folder = root / "reportgen" / "kinds" / "free_oscillation"
    folder.mkdir()
    for name, text in TINY.items():
        if with_quantity:
            text = text.replace("# DECLARATION", DECLARATION[0]).replace("# STORE",
                                                                          DECLARATION[1])
        (folder / name).write_text(text)


def _reportgen(root: Path):
    env = {**os.environ, "PYTHONPATH": str(root)}

    def reportgen(*args):
        return subprocess.run([sys.executable, "-m", "reportgen", *map(str, args)],
                              capture_output=True, text=True, env=env, cwd=root, timeout=600)
    return reportgen, env


def test_a_kind_is_one_package_and_a_quantity_one_declaration(tmp_path):
    shutil.copytree(REPO / "reportgen", tmp_path / "reportgen",
                    ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(REPO / "templates", tmp_path / "templates")
    _add_kind(tmp_path, with_quantity=True)
    config = tmp_path / "free.toml"
    config.write_text(textwrap.dedent(TINY_CONFIG))
    reportgen, env = _reportgen(tmp_path)

    kinds = reportgen("kinds")
    assert kinds.returncode == 0, kinds.stderr
    assert "free_oscillation — a test kind" in kinds.stdout
    assert "omega" in kinds.stdout

    valid = reportgen("validate", config)
    assert valid.returncode == 0, valid.stderr
    assert "free_oscillation" in valid.stdout

    run = reportgen("run", config, "--out", tmp_path / "out", "--jobs", "1")
    assert run.returncode == 0, run.stderr
    folder = tmp_path / "out" / "free"
    report = (folder / "report.html").read_text(encoding="utf-8")
    assert "A kind added as one module" in report
    assert "A free oscillation, added as one package." in report
    assert (folder / "figures" / "motion-q.svg").exists()

    # the added quantity: its unit in the archive, in xarray and on the figure's axis
    with h5py.File(folder / "run.h5", "r") as f:
        envelope = f["analysis/envelope"]
        assert (envelope.attrs["units"], envelope.attrs["long_name"],
                envelope.attrs["symbol"]) == ("mm", "amplitude envelope", "A")
        assert f["runs/main/t"].attrs["units"] == "s"
        assert list(f["runs/main/y"].attrs["column_units"]) == ["m", "kg m/s"]
    ds = xr.open_dataset(folder / "run.h5", group="analysis", engine="h5netcdf",
                         phony_dims="access")
    assert ds["envelope"].attrs["units"] == "mm"
    svg = (folder / "figures" / "motion-envelope.svg").read_text(encoding="utf-8")
    assert "[mm]" in svg

    blocked = subprocess.run(
        [sys.executable, "-c", "import sys; sys.modules['reportgen.core'] = None; "
         "from reportgen.commands.cli import main; sys.exit(main(['report', sys.argv[1], "
         "'--format', 'html']))", str(folder / "run.h5")],
        capture_output=True, text=True, env=env, cwd=tmp_path, timeout=600)
    assert blocked.returncode == 0, blocked.stderr


def test_an_undeclared_result_is_refused_at_write_time(tmp_path):
    """The simulation stores a quantity nobody declared: the archive is not written and
    the error names the result (not a figure that fails to draw later)."""
    from reportgen.archive.store import ResultsError, write_archive
    from reportgen.scene.results import Results
    from reportgen.scene.schema import Quantity, ResultsSchema

    schema = ResultsSchema(analysis=(Quantity("period", "T", "s", "period"),))
    results = Results(analysis={"period": 1.0, "peroid": 1.0})
    try:
        write_archive(tmp_path / "run.h5", kind="x", title="x", scene="x", config_text="",
                      config_sha256="", results=results, schema=schema)
    except ResultsError as exc:
        assert "/analysis/peroid: not a declared result" in str(exc)
        assert "did you mean 'period'" in str(exc)
    else:
        raise AssertionError("an undeclared result was written")
    assert not (tmp_path / "run.h5").exists()
    missing = Results(analysis={})
    try:
        write_archive(tmp_path / "run.h5", kind="x", title="x", scene="x", config_text="",
                      config_sha256="", results=missing, schema=schema)
    except ResultsError as exc:
        assert "/analysis/period: declared result missing" in str(exc)
    else:
        raise AssertionError("a missing result was not noticed")
    wrong = Results(analysis={"period": [1.0, 2.0]})
    try:
        write_archive(tmp_path / "run.h5", kind="x", title="x", scene="x", config_text="",
                      config_sha256="", results=wrong, schema=schema)
    except ResultsError as exc:
        assert "expected 0 dimension(s)" in str(exc)
    else:
        raise AssertionError("a misshapen result was not noticed")
