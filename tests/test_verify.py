"""``reportgen verify`` and ``reportgen.verify`` (issue 43): an archive re-simulated from its
own stored config with the installed code, every stored number compared bit for bit; run
times are not compared, a changed trajectory or text is named with its largest
difference, an unreadable archive exits 2, an earlier release's archive gets the table."""

from __future__ import annotations

import shutil
from pathlib import Path

import h5py
import numpy as np
import pytest

import reportgen
from conftest import pendulum_text
from reportgen.archive.h5io import TABLE_ATTR, column_table, read_table, table
from reportgen.commands.cli import main
from reportgen.pipeline.verify import TIMINGS, Difference

REPO = Path(__file__).resolve().parent.parent

#: a sweep's family: its per-member runs and throughput
FAMILY = pendulum_text(t_end=4.0, samples=201, title="a family") + """
[sweep]
initial.theta = { start = 0.2, stop = 2.0, num = 4 }
store = 2
"""


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    """A pendulum with its error-against-run-time study (run times in its table), a sweep,
    and a molecule's modes (no integration), run into one output folder."""
    root = tmp_path_factory.mktemp("verify")
    configs = root / "configs"
    configs.mkdir()
    (configs / "studied.toml").write_text(
        pendulum_text(t_end=6.0, samples=301, study="true", title="studied")
        + '\n[report]\nformats = ["html"]\n')
    (configs / "family.toml").write_text(FAMILY + '\n[report]\nformats = ["html"]\n')
    (configs / "co2.toml").write_text('kind = "normal_modes"\npreset = "co2"\n'
                                      '[report]\nformats = ["html"]\n')
    assert main(["run", str(configs), "--out", str(root / "out"), "--jobs", "1"]) == 0
    return root / "out"


def test_a_fresh_run_verifies_identical_with_its_run_times_left_out(out, cli):
    code, stdout, err = cli("verify", out)
    assert code == 0, stdout + err
    lines = [line for line in stdout.splitlines() if line.startswith("[")]
    assert len(lines) == 3 and all(": identical (" in line for line in lines), stdout
    assert "same reportgen version and simulation code" in stdout
    # the study's table holds run times that differ between runs: they were left out
    with h5py.File(out / "studied" / "run.h5") as f:
        names = set(read_table(f["study/error_vs_runtime"]).dtype.names)
    assert {"wall_time_s", "compile_time_s"} <= names and {"error_final", "nfev"} <= names


def test_every_timing_the_archives_hold_is_declared(out):
    """A name that measures the machine (ends in time_s, _up_s or _per_s, or says when or
    where) is in TIMINGS, or verifying would call every re-run different."""
    found = set()

    def visit(name, obj):
        found.update(obj.attrs)
        found.add(name.rsplit("/", 1)[-1])  # a table's column (format 3) is a dataset
        if isinstance(obj, h5py.Dataset) and obj.dtype.names:
            found.update(obj.dtype.names)

    for archive in out.rglob("run.h5"):
        with h5py.File(archive) as f:
            found.update(f.attrs)
            f.visititems(visit)
    timing = {n for n in found if n.endswith(("time_s", "_up_s", "_per_s"))
              or n in ("created", "measured_at", "machine", "cached")}
    assert timing and timing <= TIMINGS, timing - TIMINGS


def test_an_altered_trajectory_is_named_with_its_difference(out, tmp_path, cli):
    folder = tmp_path / "studied"
    shutil.copytree(out / "studied", folder)
    with h5py.File(folder / "run.h5", "r+") as f:
        y = f["runs/main/y"]
        values = y[()]
        values[100, 0] *= 1 + 3e-9
        y[...] = values
        f["checks"].attrs["wall_time_s"] = 123.0  # a timing: not a difference
        f["runs/main"].attrs["compile_time_s"] = 9.0
    code, stdout, _ = cli("verify", folder / "run.h5")
    assert code == 1, stdout
    assert "different in 1 of" in stdout and "runs/main/y" in stdout, stdout
    result = reportgen.verify(folder / "run.h5")
    assert [d.path for d in result.differences] == ["runs/main/y"]
    d = result.differences[0]
    assert 2e-9 < d.max_rel < 4e-9 and d.passing_rtol == pytest.approx(1e-8)
    assert not result.code_changed


def test_altered_text_and_a_removed_result_are_differences(out, tmp_path):
    folder = tmp_path / "co2"
    shutil.copytree(out / "co2", folder)
    with h5py.File(folder / "run.h5", "r+") as f:
        f.attrs["title"] = "another title"
        name = next(iter(k for k in f["analysis"].attrs if not k.startswith("__")))
        del f["analysis"].attrs[name]
    result = reportgen.verify(folder / "run.h5")
    assert result.verdict == "different"
    whats = {d.path: d.what for d in result.differences}
    assert whats.get("@title") == "text differs", whats
    assert whats.get(f"analysis@{name}") is None  # the re-run has it: only stored ones count
    assert result.added == 1


def test_an_unreadable_archive_exits_2_and_a_folder_is_searched(out, tmp_path, cli):
    broken = tmp_path / "broken" / "run.h5"
    broken.parent.mkdir()
    broken.write_bytes((out / "co2" / "run.h5").read_bytes()[:4000])
    code, stdout, _ = cli("verify", tmp_path / "broken", out / "co2")
    assert code == 2, stdout
    assert "[1/2]" in stdout and "[2/2] co2: identical" in stdout
    code, stdout, _ = cli("verify", tmp_path / "nothing-here")
    assert code == 2 and stdout.count("\n") == 1 and "nothing-here" in stdout, stdout


def test_an_earlier_release_gets_the_comparison_table(cli):
    """The 0.2.0 CO₂ archive: its stored numbers compared with today's (the modes' units
    changed since: the table says by how much, and which columns' text differs)."""
    code, stdout, _ = cli("verify", REPO / "tests" / "data" / "archive_0.2.0_normal_modes_co2.h5")
    assert code == 1
    assert "max |Δ|" in stdout and "passes at rtol" in stdout
    assert "items more (not compared)" in stdout and "physics key differs" in stdout


def test_difference_rtol_is_the_next_power_of_ten():
    assert Difference("x", 1.0, 3e-9).passing_rtol == pytest.approx(1e-8)
    assert Difference("x", 1.0, 1e-9).passing_rtol == pytest.approx(1e-9)
    assert Difference("x", np.inf, np.inf).passing_rtol == np.inf


def test_the_study_is_compared_on_the_rows_both_runs_timed(out, tmp_path):
    """The study times as many tolerances as its time budget allows, so a re-run on a busy
    machine may time fewer rows: rows are matched by method and tolerance, a row one run
    lacks is no difference, a changed error in a shared row is."""
    folder = tmp_path / "studied"
    shutil.copytree(out / "studied", folder)
    with h5py.File(folder / "run.h5", "r+") as f:
        g = f["study/error_vs_runtime"]
        table = read_table(g)
        attrs = dict(g.attrs)
        columns = {n: dict(g[n].attrs) for n in table.dtype.names}
        del f["study/error_vs_runtime"]
        column_table(f["study"], "error_vs_runtime", table[:-1], "row", "row",  # one row fewer
                     describe=lambda n: {k: v for k, v in columns[n].items()
                                         if k not in ("DIMENSION_LIST", "REFERENCE_LIST")})
        f["study/error_vs_runtime"].attrs.update(attrs)
    assert reportgen.verify(folder / "run.h5").identical
    with h5py.File(folder / "run.h5", "r+") as f:
        error = f["study/error_vs_runtime/error_final"]
        values = error[()]
        values[0] *= 2
        error[...] = values
    result = reportgen.verify(folder / "run.h5")
    assert [d.path for d in result.differences] == ["study/error_vs_runtime:error_final"]


def test_an_archive_of_format_2_compares_with_its_re_run_of_format_3(out, tmp_path):
    """The tables written as compound datasets, the row numbers beside them (format 2)
    compare with today's groups of columns: the same run verifies identical."""
    folder = tmp_path / "studied"
    shutil.copytree(out / "studied", folder)
    with h5py.File(folder / "run.h5", "r+") as f:
        for path, row in (("checks", "check"), ("study/error_vs_runtime", "row")):
            g = f[path]
            records, attrs = read_table(g), dict(g.attrs)
            attrs.pop(TABLE_ATTR)
            parent = g.parent
            del f[path]
            stored = table(parent, path.rsplit("/", 1)[-1], records)
            stored.attrs.update(attrs)
            scale = parent.create_dataset(row, data=np.arange(len(records)))
            scale.make_scale(row)
            stored.dims[0].attach_scale(scale)
        f.attrs["format_version"] = 2
    result = reportgen.verify(folder / "run.h5")
    assert result.identical, result.differences[:5]


def test_provenance_names_the_processor_the_source_and_the_simulation_code(out, tmp_path, cli):
    """Issue 43: the archive says which processor ran it, which revision of reportgen's
    source (a git commit from a checkout, "release" from a wheel) and which simulation
    code (the hash the physics key holds); verify says when these differ from the re-run's,
    item by item, and the report's colophon names only the software."""
    from reportgen.archive.h5io import LIBRARIES
    from reportgen.kinds import get_kind

    with h5py.File(out / "studied" / "run.h5") as f:
        stored = {k: (v.decode() if isinstance(v, bytes) else str(v))
                  for k, v in f["provenance"].attrs.items()}
    assert stored["cpu"] and stored["cpu"] != "unknown"
    assert stored["source"] == "release" or stored["source"].startswith("git ")
    assert stored["simulation code"] == get_kind("pendulum").simulation_code()
    page = (out / "studied" / "report.html").read_text(encoding="utf-8")
    colophon = page[page.index("<b>Software</b>"):]
    colophon = colophon[:colophon.index("</p>")]
    assert all(f" {k} <code>" in colophon for k in LIBRARIES if k in stored)
    assert "cpu" not in colophon and "simulation code" not in colophon

    folder = tmp_path / "studied"
    shutil.copytree(out / "studied", folder)
    with h5py.File(folder / "run.h5", "r+") as f:
        f["provenance"].attrs["simulation code"] = "0123456789abcdef"
        f["provenance"].attrs["source"] = "git " + "0" * 40
    code, stdout, _ = cli("verify", folder / "run.h5")
    assert code == 0, stdout  # the numbers are the same: said, not a difference
    assert "simulation code: 0123456789abcdef then, " in stdout
    assert f"source: git {'0' * 40} then, " in stdout
