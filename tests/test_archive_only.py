"""The archive is the whole truth: a report is a function of the archive alone.

Every shipped scene is simulated, then its report is rebuilt in a fresh process in
which ``reportgen.core`` cannot be imported (``sys.modules["reportgen.core"] = None``,
so any import of core or of a module below it raises).  The rebuilt report must
succeed and give byte-identical SVG figures.  The study is switched off here to keep
the suite fast; ``test_study_section_from_archive_alone`` covers the
error-against-run-time section with one scene.
"""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from conftest import without_study
from reportgen.pipeline.stages import run_scene
from reportgen.scene.config import to_toml

REPO = Path(__file__).resolve().parent.parent
SHIPPED = sorted((REPO / "configs").glob("*.toml"))

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


def _datasets_without_cf_attrs(archive: Path) -> list[str]:
    """Every dataset of the archive lacking ``units`` or ``long_name`` (CF style), and
    every numeric one whose ``long_name`` is empty."""
    import h5py

    bad = []

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            attrs = obj.attrs
            if "units" not in attrs or "long_name" not in attrs or not str(attrs["long_name"]):
                bad.append(name)

    with h5py.File(archive, "r") as f:
        f.visititems(visit)
    return bad


@pytest.mark.parametrize("config", SHIPPED, ids=[p.stem for p in SHIPPED])
def test_report_from_archive_alone(config, tmp_path):
    source = without_study(config, tmp_path / config.name)
    outcome = run_scene(str(source), str(tmp_path / "out"), force=True, formats=("html",))
    assert outcome.status in ("ok", "unstable"), outcome.message
    folder = tmp_path / "out" / config.stem
    assert _datasets_without_cf_attrs(folder / "run.h5") == []
    rebuilt = tmp_path / "rebuilt"
    proc = _report_from_archive_alone(folder / "run.h5", rebuilt)
    assert proc.returncode == 0, proc.stderr[-3000:]
    _assert_same_figures(folder, rebuilt)
    assert (rebuilt / "report.html").read_text(encoding="utf-8") == \
        (folder / "report.html").read_text(encoding="utf-8")
    _assert_xarray_reads(folder / "run.h5")


def _assert_xarray_reads(archive: Path) -> None:
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
