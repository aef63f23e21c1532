"""Issue 48 E: bytes, not only elements.  A fixed-width text of 40,000 bytes per element,
90,000 elements, stored chunked and compressed, adds a few hundred bytes to an archive and
cost 3–4 GiB to read: in ``inspect`` and ``report`` (the validating reader counted its
elements, not its bytes) and in every later ``run`` into that folder (the gallery read its
neighbours without that reader)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

from conftest import PEAK, pendulum_text
from reportgen.archive.check import MAX_DATASET_BYTES
from reportgen.archive.h5io import TABLE_ATTR, ArchiveError, read_table
from reportgen.archive.store import gallery_entry, read_archive
from reportgen.commands.cli import main


def _peak_of_gallery_entry(archive: Path, check: str = "") -> int:
    """The peak resident memory [KiB] of a child that reads ``archive``'s gallery card
    (and asserts ``check`` of its ``entry``)."""
    probe = ("import sys; from pathlib import Path; "
             "from reportgen.archive.store import gallery_entry; "
             f"entry = gallery_entry(Path(sys.argv[1])); {check}" + PEAK)
    out = subprocess.run([sys.executable, "-c", probe, str(archive)], capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    return int(out.stdout)


@pytest.fixture(scope="module")
def swollen(tmp_path_factory):
    root = tmp_path_factory.mktemp("bytes")
    (root / "p.toml").write_text(pendulum_text(t_end=2.0, samples=101) +
                                 '\n[report]\nformats = ["html"]\n')
    assert main(["run", str(root / "p.toml"), "--out", str(root / "out")]) == 0
    good = root / "out" / "p" / "run.h5"
    bad = root / "bad.h5"
    shutil.copy(good, bad)
    with h5py.File(bad, "r+") as f:
        f["analysis"].create_dataset("wide", shape=(90_000,), dtype="S40000", chunks=(1,),
                                     compression="gzip")
    return good, bad


def test_the_wide_text_is_small_on_disk_and_large_in_memory(swollen):
    good, bad = swollen
    assert bad.stat().st_size - good.stat().st_size < 2_000_000
    assert 90_000 * 40_000 > MAX_DATASET_BYTES


def test_the_validating_reader_counts_bytes(swollen):
    _, bad = swollen
    with pytest.raises(ArchiveError, match="elements of 40000 bytes, more than the 1024 MiB"):
        read_archive(bad)
    code = main(["inspect", str(bad)])
    assert code == 2


def test_the_gallery_skips_it_without_reading_it(swollen):
    """Read in a child process, whose peak memory is measured: under 500 MB."""
    good, bad = swollen
    assert gallery_entry(good) is not None and gallery_entry(bad) is None
    peak = _peak_of_gallery_entry(bad, "assert entry is None; ")
    assert peak < 500_000, f"peak {peak / 1024:.0f} MiB"  # KiB


@pytest.mark.parametrize("layout", ["compound", "columns"])
def test_the_gallery_reads_no_wide_checks_table(swollen, tmp_path, layout):
    """A checks table of 10,000 rows (the gallery's row limit) whose quantity is 60,000
    bytes wide: 600 MB, read for one card before; now the card has no headline
    from it, and the read stays small.  Stored as a compound dataset (format 2) or as a
    group of columns (format 3)."""
    good, _ = swollen
    wide = tmp_path / "wide.h5"
    shutil.copy(good, wide)
    with h5py.File(wide, "r+") as f:
        rows = read_table(f["checks"])
        table = np.zeros(10_000, dtype=[
            (n, "S60000" if n == "quantity" else "S16" if rows.dtype[n].kind in "OSU"
             else rows.dtype[n]) for n in rows.dtype.names])
        del f["checks"]
        if layout == "compound":
            f.create_dataset("checks", data=table, chunks=(1,), compression="gzip")
        else:
            g = f.create_group("checks")
            g.attrs[TABLE_ATTR] = np.array(table.dtype.names, dtype=h5py.string_dtype())
            for n in table.dtype.names:
                g.create_dataset(n, data=table[n], chunks=(1,), compression="gzip")
    peak = _peak_of_gallery_entry(wide)
    assert peak < 500_000, f"peak {peak / 1024:.0f} MiB"  # KiB


def test_wide_text_is_still_taken_within_the_limit(swollen, tmp_path):
    """A fixed-width status per member of a large sweep stays readable: 10⁷ × 16 bytes."""
    _, bad = swollen
    ok = tmp_path / "ok.h5"
    shutil.copy(swollen[0], ok)
    with h5py.File(ok, "r+") as f:
        f["analysis"].create_dataset("status", data=np.array([b"ok"] * 1000, dtype="S16"))
    read_archive(ok)
