"""Nothing lost: kill -9 at random moments never leaves a broken file under a final name."""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import pendulum_text
from reportgen.archive.store import read_archive, verify_checksums

#: kills of the random-kill test, one in each of KILLS equal slices of a run (a deeper run:
#: REPORTGEN_KILLS=40); stratified, so that a few reach every stage of the run
KILLS = int(os.environ.get("REPORTGEN_KILLS", "8"))


def _start(cfg: Path, out: Path) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "reportgen", "run", str(cfg), "--out", str(out), "--jobs", "1",
         "--force"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)


def _check_folder(folder: Path) -> None:
    for name in ("run.h5", "run.prev.h5"):
        path = folder / name
        if path.exists():
            read_archive(path)
            assert verify_checksums(path) == [], path
    html = folder / "report.html"
    if html.exists():
        assert html.read_text().rstrip().endswith("</html>")
    pdf = folder / "report.pdf"
    if pdf.exists():
        data = pdf.read_bytes()
        assert data.startswith(b"%PDF") and data.rstrip().endswith(b"%%EOF")
    for fig in (folder / "figures").glob("*.svg") if (folder / "figures").is_dir() else []:
        assert fig.read_text().rstrip().endswith("</svg>"), fig


@pytest.mark.slow
def test_random_kills_lose_nothing(tmp_path):
    cfg = tmp_path / "victim.toml"
    cfg.write_text(pendulum_text(theta=2.0, t_end=100.0, samples=10001))
    out = tmp_path / "out"
    start = time.monotonic()
    assert _start(cfg, out).wait(timeout=600) == 0
    full = time.monotonic() - start
    folder = out / "victim"
    good = read_archive(folder / "run.h5")
    rng = random.Random(1234)
    for slice_ in rng.sample(range(KILLS), KILLS):  # every slice once, in random order
        proc = _start(cfg, out)
        time.sleep((slice_ + rng.random()) / KILLS * full)
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
        assert (folder / "run.h5").exists(), "the earlier archive was lost"
        _check_folder(folder)
        # whatever archive is there now holds the same config as the good one
        assert read_archive(folder / "run.h5").config_text == good.config_text
    # a clean run afterwards sweeps the temp files of the killed writers
    assert _start(cfg, out).wait(timeout=600) == 0
    assert not list(folder.rglob(".*.tmp"))
    _check_folder(folder)


def test_two_runs_into_one_folder_do_not_corrupt_each_other(tmp_path):
    cfg = tmp_path / "shared.toml"
    cfg.write_text(pendulum_text(theta=1.0, t_end=20.0, samples=2001))
    out = tmp_path / "out"
    procs = [_start(cfg, out) for _ in range(2)]
    assert [p.wait(timeout=600) for p in procs] == [0, 0]
    folder = out / "shared"
    _check_folder(folder)
    assert read_archive(folder / "run.h5").runs["main"].y.shape == (2001, 2)
    assert not list(folder.rglob(".*.tmp"))
