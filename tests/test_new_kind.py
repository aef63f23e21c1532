"""Adding a kind is one module under reportgen/scenes/ plus its template and config.

The package and templates are copied to a temporary folder; one new module
(``scenes/damped_free.py``), its prose template and a config are added there and
nothing else is edited.  ``kinds`` lists the new kind, ``validate`` accepts its config,
``run`` simulates and reports it, and the report rebuilds with ``reportgen.core``
blocked.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

TINY_KIND = '''
"""``free_oscillation``: a tiny kind used by the test suite (q'' = -ω² q)."""

from __future__ import annotations

import numpy as np
from pydantic import Field

from ..config import Positive, Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import Check, Results
from .base import Scene, SceneConfig, Section, SectionContent, fmt

oscillator = lazy_module("reportgen.core.models.oscillator")
style = lazy_module("reportgen.plots.style")


class Params(Strict):
    omega: Positive = Field(description="angular frequency [1/s]")


class Initial(Strict):
    q: Real = Field(description="initial displacement [m]")


class FreeConfig(SceneConfig):
    params: Params
    initial: Initial
    run: RunConfig


class FreeOscillationScene(Scene):
    kind = "free_oscillation"
    summary = "a test kind: q'' = -omega^2 q"
    Config = FreeConfig
    sections = (Section("motion", "Motion", integrates=True),
                Section("error_vs_runtime", "Error against run time", integrates=True))

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
        results.checks.append(Check("q(t_end)", float(run["q"][-1]), float(run.reference["q"][-1]),
                                    "m", "q0 cos(omega t)", scale=abs(q0)))
        return results

    @classmethod
    def headline(cls, data):
        return [("period", f"{fmt(data.analysis['period'])} s")]

    @classmethod
    def section_motion(cls, data):
        run = data.runs["main"]
        fig, ax = style.new_figure()
        ax.plot(run.t, run["q"], label="integrated")
        ax.plot(run.t, run.reference["q"], linestyle="--", label=run.attrs["reference_label"])
        ax.set_xlabel("t [s]")
        ax.set_ylabel("q [m]")
        ax.legend()
        return SectionContent(figures=[cls.figure("q", fig, "q(t) against the exact cosine.")])
'''

TINY_TEMPLATE = """
{% macro summary() %}<p>A free oscillation, added as one module.</p>{% endmacro %}
"""

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


def test_a_kind_is_one_module(tmp_path):
    shutil.copytree(REPO / "reportgen", tmp_path / "reportgen",
                    ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(REPO / "templates", tmp_path / "templates")
    (tmp_path / "reportgen" / "scenes" / "free_oscillation.py").write_text(TINY_KIND)
    (tmp_path / "templates" / "kinds" / "free_oscillation.html.j2").write_text(TINY_TEMPLATE)
    config = tmp_path / "free.toml"
    config.write_text(textwrap.dedent(TINY_CONFIG))
    env = {**os.environ, "PYTHONPATH": str(tmp_path)}

    def reportgen(*args):
        return subprocess.run([sys.executable, "-m", "reportgen", *map(str, args)],
                              capture_output=True, text=True, env=env, cwd=tmp_path, timeout=600)

    kinds = reportgen("kinds")
    assert kinds.returncode == 0, kinds.stderr
    assert "free_oscillation — a test kind" in kinds.stdout
    assert "omega" in kinds.stdout

    valid = reportgen("validate", config)
    assert valid.returncode == 0, valid.stderr
    assert "free_oscillation" in valid.stdout

    run = reportgen("run", config, "--out", tmp_path / "out", "--jobs", "1")
    assert run.returncode == 0, run.stderr
    report = (tmp_path / "out" / "free" / "report.html").read_text(encoding="utf-8")
    assert "A kind added as one module" in report
    assert "A free oscillation, added as one module." in report
    assert (tmp_path / "out" / "free" / "figures" / "motion-q.svg").exists()

    blocked = subprocess.run(
        [sys.executable, "-c", "import sys; sys.modules['reportgen.core'] = None; "
         "from reportgen.cli import main; sys.exit(main(['report', sys.argv[1], "
         "'--format', 'html']))", str(tmp_path / "out" / "free" / "run.h5")],
        capture_output=True, text=True, env=env, cwd=tmp_path, timeout=600)
    assert blocked.returncode == 0, blocked.stderr
