"""The archive is the whole truth: a report is a function of the archive alone.

A report is rebuilt in a fresh process in which ``reportgen.core`` cannot be imported
(``sys.modules["reportgen.core"] = None``, so any import of core or of a module below it
raises); the rebuilt report must succeed and give byte-identical SVG figures.  Every
report of the shipped pack and of the unseen scenes is rebuilt so, from the archives of
their page tests' batch (``tests/pages.py``); here the error-against-run-time section on
its own.
"""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

from reportgen.pipeline.stages import run_scene
from reportgen.scene.config import to_toml

REPO = Path(__file__).resolve().parent.parent

BLOCKED_REPORT = """
import sys
sys.modules["reportgen.core"] = None
from pathlib import Path
from reportgen.rendering.report import build_report
build_report(Path(sys.argv[1]), formats=("html",), out_dir=Path(sys.argv[2]))
assert not [m for m in sys.modules if m.startswith("reportgen.core.")], "core was imported"
"""


def _report_from_archive_alone(archive: Path, out_dir: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", BLOCKED_REPORT, str(archive), str(out_dir)],
                          capture_output=True, text=True, timeout=600)


def _assert_same_figures(first: Path, second: Path) -> None:
    svgs = sorted(p.name for p in (first / "figures").glob("*.svg"))
    assert svgs, f"no figures in {first}"
    assert svgs == sorted(p.name for p in (second / "figures").glob("*.svg"))
    for name in svgs:
        assert (first / "figures" / name).read_bytes() == (second / "figures" / name).read_bytes(), \
            f"figure {name} differs when drawn from the archive alone"


def test_study_section_from_archive_alone(tmp_path):
    config = REPO / "configs" / "pendulum_small.toml"
    data = tomllib.loads(config.read_text(encoding="utf-8"))
    data["report"] = {"sections": ["time_series", "error_vs_runtime"], "formats": ["html"]}
    source = tmp_path / "pendulum_small.toml"
    source.write_text(to_toml(data), encoding="utf-8")
    outcome = run_scene(str(source), str(tmp_path / "out"), force=True, formats=("html",))
    assert outcome.ok, outcome.message
    folder = tmp_path / "out" / "pendulum_small"
    assert (folder / "figures" / "error_vs_runtime-work_precision.svg").exists()
    rebuilt = tmp_path / "rebuilt"
    proc = _report_from_archive_alone(folder / "run.h5", rebuilt)
    assert proc.returncode == 0, proc.stderr[-3000:]
    _assert_same_figures(folder, rebuilt)
