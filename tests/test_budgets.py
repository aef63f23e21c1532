"""Issue 48 E: memory from small inputs, and limits that agree.

Each input here is small (a 60 kB config, a sparse file, a 3 MB sweep block, two numbers on
a command line, a dict in a notebook) and asked for gigabytes before: each is now refused
up front, in one line naming the file (or option), the rule and the value, and the
commands that read it stay small.  Memory is measured in a child process by its peak
resident size (``VmHWM``: getrusage's ``ru_maxrss`` keeps a forking parent's size across
exec), with an address-space limit so that a regression fails the test, not the machine.
"""

from __future__ import annotations

import contextlib
import io
import os
import resource
import struct
import subprocess
import sys
import textwrap
import zlib
from pathlib import Path

import h5py
import numpy as np
import pytest

from conftest import PEAK, pendulum_text
from reportgen.commands.cli import main

#: address space a child may take (a regression fails with MemoryError, never swaps)
CHILD_ADDRESS_SPACE = 3 << 30
#: what a child reading none of the large inputs peaks at, with room to spare [KiB]
SMALL = 300_000


def _child(code: str, *args, timeout: float = 120) -> tuple[subprocess.CompletedProcess, int]:
    """Run ``code`` in a fresh interpreter (``sys.argv[1:]`` = ``args``); its result and
    its peak resident memory in KiB (0 when it died before saying)."""

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (CHILD_ADDRESS_SPACE, CHILD_ADDRESS_SPACE))

    proc = subprocess.run([sys.executable, "-c", code + "\n" + PEAK, *map(str, args)],
                          capture_output=True, text=True, timeout=timeout, preexec_fn=limit)
    lines = proc.stdout.strip().splitlines()
    peak = int(lines[-1]) if proc.returncode == 0 and lines and lines[-1].isdigit() else 0
    return proc, peak


def _cli(*args) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = main([str(a) for a in args])
    return code, err.getvalue()


def _one_line(err: str) -> str:
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


def _sparse(path: Path, size: int) -> Path:
    """A file of ``size`` zero bytes that takes no room on disk."""
    with open(path, "wb") as fh:
        fh.truncate(size)
    return path


# ------------------------------------------------------------ config text, before parsing
DEEP = 30_000
#: a 60 kB config whose parse cost 3.4 GiB (tomllib is quadratic in a key's parts), and its
#: relatives: a table header, an array-of-tables header, a dotted key in an inline table,
#: quoted parts, and nesting by brackets
DEEP_FORMS = {
    "dotted key": "a" + ".a" * (DEEP - 1) + " = 1\n",
    "table header": "[a" + ".a" * (DEEP - 1) + "]\n",
    "array of tables": "[[a" + ".a" * (DEEP - 1) + "]]\n",
    "inline table": "x = {a" + ".a" * (DEEP - 1) + " = 1}\n",
    "quoted parts": '"a"' + '."a"' * (DEEP - 1) + " = 1\n",
    "spaced parts": "a" + " . a" * (DEEP - 1) + " = 1\n",
    "arrays": "x = " + "[" * DEEP + "]" * DEEP + "\n",
    "inline tables": "x = " + "{a = " * DEEP + "1" + "}" * DEEP + "\n",
}


def test_deep_config_text_is_refused_before_parsing(tmp_path):
    """Every form in one child: each a ConfigError naming the nesting and the line, the
    child small and quick (the dotted key alone took 27 s and 3.6 GB)."""
    for name, text in DEEP_FORMS.items():
        (tmp_path / f"{name.replace(' ', '_')}.toml").write_text(
            'kind = "pendulum"\n' + text, encoding="utf-8")
    probe = textwrap.dedent("""
        import sys, time
        from pathlib import Path
        from reportgen.scene.config import ConfigError, read_config
        for path in sorted(Path(sys.argv[1]).glob("*.toml")):
            t0 = time.process_time()
            try:
                read_config(path)
                print("ACCEPTED", path.name)
            except ConfigError as exc:
                print(f"{time.process_time() - t0:.2f}", *exc.problems)
        """)
    proc, peak = _child(probe, tmp_path, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    lines = proc.stdout.strip().splitlines()[:-1]
    assert len(lines) == len(DEEP_FORMS), lines
    for line in lines:
        seconds, message = line.split(" ", 1)
        assert "config nesting too deep" in message and "line 2" in message, message
        assert f"{DEEP}" in message or "more than 32" in message, message
        assert float(seconds) < 2.0, line
    assert peak < SMALL, f"peak {peak / 1024:.0f} MiB"


def test_deep_dotted_key_is_exit_2_in_one_line(tmp_path):
    cfg = tmp_path / "dotted.toml"
    cfg.write_text('kind = "pendulum"\n' + DEEP_FORMS["dotted key"], encoding="utf-8")
    proc, peak = _child("import sys\nfrom reportgen.commands.cli import main\n"
                        "code = main(['validate', sys.argv[1]])\nprint(code)", cfg)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stdout.split()[0] == "2", proc.stdout
    line = _one_line(proc.stderr)
    assert str(cfg) in line and f"{DEEP} dotted parts" in line and "more than 32" in line, line
    assert peak < SMALL, f"peak {peak / 1024:.0f} MiB"


@pytest.mark.parametrize("text", [
    "x = 1.5\ny = 1979-05-27T07:32:00.999-07:00\n",
    'a.b.c = "x.y.z.' + "w." * 100 + '"\n',
    "s = '''" + "[" * 100 + "'''\nt = \"\"\"" + "{a." * 100 + "\"\"\"\n",
    "# " + "[" * 100 + "a." * 100 + "\n",
    "[a.b]\nc.d = [[1, 2], [3.5, 4.25]]\n",
])
def test_what_only_looks_deep_still_parses(text):
    """Dots and brackets in strings, comments, numbers and dates are not nesting."""
    from reportgen.scene.config import parse_config_text

    parse_config_text(text)


def test_a_config_at_the_nesting_limit_parses():
    from reportgen.scene.config import MAX_CONFIG_NESTING, ConfigError, parse_config_text

    parse_config_text(".".join(["a"] * MAX_CONFIG_NESTING) + " = 1\n")
    with pytest.raises(ConfigError, match=f"{MAX_CONFIG_NESTING + 1} dotted parts"):
        parse_config_text(".".join(["a"] * (MAX_CONFIG_NESTING + 1)) + " = 1\n")


# ---------------------------------------------------- files read back from an output folder
#: larger than any budget of a file read back, small enough to be read (and fail) safely
LARGE = 700 << 20


def test_read_back_takes_regular_files_within_a_size(tmp_path):
    from reportgen.support.fsutil import FileTooLarge, NotRegularFile, read_back

    small = tmp_path / "small.json"
    small.write_bytes(b"{}")
    assert read_back(small, 10) == b"{}"
    small.write_bytes(b"{ }")
    with pytest.raises(FileTooLarge, match="larger than 2 bytes"):
        read_back(small, 2)
    with pytest.raises(FileTooLarge, match=f"larger than {1 << 20} bytes"):
        read_back(_sparse(tmp_path / "large.json", LARGE), 1 << 20)
    fifo = tmp_path / "fifo.json"
    os.mkfifo(fifo)
    with pytest.raises(NotRegularFile, match="a FIFO"):
        read_back(fifo, 10)  # never waits for a writer
    with pytest.raises(NotRegularFile, match="a device"):
        read_back(Path("/dev/zero"), 10)
    outside = tmp_path / "outside.json"
    outside.write_bytes(b"{}")
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "link.json").symlink_to(outside)
    with pytest.raises(OSError):  # a link is not followed unless asked
        read_back(tmp_path / "out" / "link.json", 10)
    assert read_back(tmp_path / "out" / "link.json", 10, follow_links=True) == b"{}"


READ_BACK_PROBES = {
    "gallery cache": ("from reportgen.pipeline.stages import GALLERY_CACHE, _gallery_entries\n"
                      "assert _gallery_entries(root) == {}", ".gallery.json"),
    "report stamp": ("from reportgen.pipeline.stages import _report_current\n"
                     "assert _report_current(root / 'scene', None, ('html',), None) is False",
                     "scene/.report-stamp.json"),
    "figure manifest": ("from reportgen.support.layout import figure_manifest\n"
                        "assert figure_manifest(root / 'scene') is None",
                        "scene/figures/sections.json"),
}


@pytest.mark.parametrize("what", sorted(READ_BACK_PROBES))
@pytest.mark.parametrize("how", ["large", "/dev/zero"])
def test_files_read_back_stay_small(tmp_path, what, how):
    """A gallery cache, report stamp or figure manifest that is a 700 MB (sparse) file or
    a link to /dev/zero is not read (``.gallery.json`` → /dev/zero cost 5.4 GiB)."""
    code, rel = READ_BACK_PROBES[what]
    target = tmp_path / rel
    (tmp_path / "scene" / "figures").mkdir(parents=True)
    if how == "large":
        _sparse(target, LARGE)
    else:
        target.symlink_to("/dev/zero")
    proc, peak = _child("import sys\nfrom pathlib import Path\nroot = Path(sys.argv[1])\n"
                        + code, tmp_path, timeout=60)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert peak < SMALL, f"peak {peak / 1024:.0f} MiB"


# ------------------------------------------------------------------------- sweep blocks
def _zip(path: Path, entries: dict[str, tuple[bytes, int, int, bool]]) -> None:
    """A zip file of ``entries``: name -> (payload, CRC-32, size, deflated?), written by hand
    so that a payload may be deflated once and its size declared freely."""
    local, central = [], []
    offset = 0
    for name, (payload, crc, size, deflated) in entries.items():
        raw = name.encode()
        method = 8 if deflated else 0
        head = struct.pack("<IHHHHHIIIHH", 0x04034B50, 20, 0, method, 0, 0x21, crc,
                           len(payload), size, len(raw), 0) + raw
        central.append(struct.pack("<IHHHHHHIIIHHHHHII", 0x02014B50, 20, 20, 0, method, 0,
                                   0x21, crc, len(payload), size, len(raw), 0, 0, 0, 0, 0,
                                   offset) + raw)
        local.append(head + payload)
        offset += len(head) + len(payload)
    directory = b"".join(central)
    end = struct.pack("<IHHHHIIH", 0x06054B50, 0, 0, len(central), len(central),
                      len(directory), offset, 0)
    path.write_bytes(b"".join(local) + directory + end)


def _npy(value: np.ndarray) -> tuple[bytes, int, int, bool]:
    buf = io.BytesIO()
    np.lib.format.write_array(buf, value, allow_pickle=False)
    data = buf.getvalue()
    return data, zlib.crc32(data), len(data), False


def _deflated_zeros(header: bytes, size: int) -> tuple[bytes, int, int, bool]:
    """``header`` then ``size`` zero bytes, deflated (1000:1) from one chunk compressed
    once and repeated: a 1.5 GB entry costs a second to make."""
    chunk = 16 << 20
    assert size % chunk == 0
    zeros = bytes(chunk)
    z = zlib.compressobj(9, zlib.DEFLATED, -15)
    head = z.compress(header) + z.flush(zlib.Z_FULL_FLUSH)
    body = z.compress(zeros) + z.flush(zlib.Z_FULL_FLUSH)
    crc = zlib.crc32(header)
    for _ in range(size // chunk):
        crc = zlib.crc32(zeros, crc)
    payload = head + body * (size // chunk) + z.flush()
    return payload, crc, len(header) + size, True


def _inflating_block(path: Path, members: int, inflated: int) -> None:
    """A sweep block of ``members`` members whose extra result ``analysis/bomb`` is a few
    MB in the file and ``inflated`` bytes read back."""
    header = io.BytesIO()
    np.lib.format.write_array_header_1_0(header, {"descr": "<f8", "fortran_order": False,
                                                  "shape": (inflated // 8,)})
    entries = {f"{key}.npy": _npy(value) for key, value in {
        "status/codes": np.zeros(members, np.uint8), "status/names": np.asarray(["ok"]),
        "message/codes": np.zeros(members, np.uint8), "message/names": np.asarray([""]),
        "analysis/x": np.zeros(members)}.items()}
    entries["analysis/bomb.npy"] = _deflated_zeros(header.getvalue(), inflated)
    _zip(path, entries)


SWEEP_PROBE = textwrap.dedent("""
    import sys
    from pathlib import Path
    import numpy as np
    from reportgen.scene import sweep
    spec = sweep.SweepSpec(axes=(sweep.Axis("initial.theta", values=(0.1, 0.2, 0.3, 0.4)),),
                           block=4)
    ran = []

    def run_block(lo, hi, values):
        ran.append((lo, hi))
        n = hi - lo
        return sweep.SweepBlock(analysis={"x": np.arange(lo, hi, dtype=float)},
                                status=np.full(n, "ok", dtype=object),
                                message=np.full(n, "", dtype=object))

    data, resumed = sweep.run_sweep(spec, run_block, Path(sys.argv[1]), sys.argv[2])
    assert resumed == 0 and ran == [(0, 4)], (resumed, ran)
    assert sorted(data.analysis) == ["x"] and list(data.analysis["x"]) == [0, 1, 2, 3]
    """)


def test_an_inflating_sweep_block_is_run_again_not_read(tmp_path):
    """A 3 MB block that inflates to 1.5 GB, left where a killed sweep resumes: before, the
    family was assembled from it (3 GB from a 2.9 MB block); now it is not taken (its
    members run again), and the run stays small."""
    from reportgen.scene.sweep import partial_folder

    key = "k" * 64
    partial = partial_folder(tmp_path, key)
    partial.mkdir()
    (partial / "key").write_text(key)
    block = partial / "block-000000.npz"
    _inflating_block(block, 4, 1536 << 20)
    assert block.stat().st_size < 4 << 20
    proc, peak = _child(SWEEP_PROBE, tmp_path, key, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert peak < SMALL, f"peak {peak / 1024:.0f} MiB"


def test_a_block_of_another_shape_is_run_again(tmp_path):
    """A block whose per-member arrays do not have its members' length, or whose extra
    arrays would make the family larger than an archive holds, is not taken."""
    from reportgen.scene.sweep import block_fits

    ok = {"status/codes": np.zeros(4, np.uint8), "status/names": np.asarray(["ok"]),
          "analysis/x": np.zeros(4)}
    wrong = {**ok, "analysis/y": np.zeros(5)}
    for name, arrays in {"ok": ok, "wrong": wrong}.items():
        np.savez(tmp_path / f"{name}.npz", **arrays)
    assert block_fits(tmp_path / "ok.npz", 4, size=4, max_points=10)
    assert not block_fits(tmp_path / "ok.npz", 5, size=5, max_points=10)
    assert not block_fits(tmp_path / "wrong.npz", 4, size=4, max_points=10)
    # 10⁷ members: 11 results of 10⁷ would be more numbers than an archive takes
    many = {**ok, **{f"analysis/r{i}": np.zeros(4) for i in range(11)}}
    np.savez(tmp_path / "many.npz", **many)
    assert block_fits(tmp_path / "many.npz", 4, size=4, max_points=10)
    assert not block_fits(tmp_path / "many.npz", 4, size=10_000_000, max_points=10)


# ------------------------------------------------------------ the archive a config asks for
SWEEP = pendulum_text(t_end=2.0, samples="{samples}") + textwrap.dedent("""
    [sweep]
    initial.theta = {{ start = 0.1, stop = 2.0, num = {num} }}
    store = {store}
    """)


@pytest.mark.parametrize(("store", "samples", "num"), [(50, 1_000_000, 100),
                                                        (20, 2_000_000, 50)])
def test_a_sweep_whose_archive_the_reader_refuses_is_a_config_error(tmp_path, store, samples,
                                                                     num):
    """``store = 50`` with ``samples = 1000000`` wrote a 1.1 GB archive that its own
    reader refused (3e8 numbers, more than the 1e8 it takes): now validation says so."""
    cfg = tmp_path / "family.toml"
    cfg.write_text(SWEEP.format(samples=samples, num=num, store=store))
    code, err = _cli("validate", cfg)
    assert code == 2, err
    line = _one_line(err)
    assert str(cfg) in line and "key 'sweep.store'" in line, line
    assert f"{store} stored runs × {samples} samples" in line and "1e+08" in line, line


def test_a_wide_single_run_whose_archive_the_reader_refuses_is_a_config_error(tmp_path):
    """50 stiff springs (200 columns) at 2e6 samples: one dataset of 4e8 numbers."""
    cfg = tmp_path / "chain.toml"
    cfg.write_text(textwrap.dedent("""
        kind = "fput"
        [params]
        m = 50
        [run]
        t_end = 10.0
        samples = 2000000
        study = false
        """))
    code, err = _cli("validate", cfg)
    assert code == 2, err
    line = _one_line(err)
    assert str(cfg) in line and "key 'run.samples'" in line and "4e+07" in line, line


def test_configs_within_the_budget_are_taken(tmp_path):
    """The largest runs the limits are sized for: a pendulum at 2e6 samples, a family
    keeping 5 members of 1e6 samples, 4 stiff springs at 2e6 samples."""
    from reportgen.kinds import load_scene
    from reportgen.scene.config import parse_config_text

    load_scene(parse_config_text(pendulum_text(samples=2_000_000)))
    load_scene(parse_config_text(SWEEP.format(samples=1_000_000, num=100, store=5)))
    load_scene(parse_config_text('kind = "fput"\n[params]\nm = 4\n[run]\nt_end = 10.0\n'
                                 'samples = 2000000\n'))


def test_the_budget_reads_the_config_alone():
    """The budget is checked when a config is loaded, before a scene's time limit starts
    (the API loads a dict before running it): it does no symbolic work, so a Lagrangian of
    degree 32, whose analysis takes minutes, loads at once."""
    import time

    from reportgen.kinds import load_scene
    from reportgen.scene.config import parse_config_text

    t0 = time.process_time()
    load_scene(parse_config_text(textwrap.dedent("""
        kind = "hamiltonian"
        [system]
        coordinates = ["x", "y"]
        L = "(x_dot**2 + y_dot**2)*(1 + x**2 + y**2)**15/2 - x**2"
        [initial]
        x = 0.1
        y = 0.0
        x_dot = 0.0
        y_dot = 0.1
        [run]
        t_end = 1.0
        samples = 11
        """)))
    assert time.process_time() - t0 < 5.0


@pytest.fixture(scope="module")
def small_runs(tmp_path_factory):
    """A single run and a family, small, as written: (scene, archive) of each."""
    from reportgen.kinds import load_scene
    from reportgen.scene.config import read_config

    root = tmp_path_factory.mktemp("budget")
    texts = {"single": pendulum_text(t_end=2.0, samples=301),
             "family": SWEEP.format(samples=201, num=6, store=3)}
    made = {}
    for name, text in texts.items():
        cfg = root / f"{name}.toml"
        cfg.write_text(text + '\n[report]\nformats = ["html"]\n' if name == "single" else text)
        assert main(["run", str(cfg), "--out", str(root / "out"), "--format", "html"]) == 0
        made[name] = (load_scene(read_config(cfg)), root / "out" / name / "run.h5")
    return made


@pytest.mark.parametrize("name", ["single", "family"])
def test_the_estimate_bounds_what_is_written(small_runs, name):
    """The budget's estimate of a config's runs is at least what its archive holds in
    them (so a config it takes writes an archive the reader takes)."""
    from reportgen.scene.budget import archive_estimate

    scene, archive = small_runs[name]
    estimate = archive_estimate(scene)
    with h5py.File(archive, "r") as f:
        held = sum(ds.size for ds in _datasets(f["runs"]))
        largest = max(ds.size for ds in _datasets(f["runs"]))
    assert estimate.runs >= held, (estimate, held)
    assert estimate.largest >= largest, (estimate, largest)


def _datasets(group: h5py.Group) -> list[h5py.Dataset]:
    """Every dataset below ``group`` once (a dataset with two names is one)."""
    found: dict[int, h5py.Dataset] = {}

    def visit(_name, obj):
        if isinstance(obj, h5py.Dataset):
            found.setdefault(h5py.h5o.get_info(obj.id).addr, obj)

    group.visititems(visit)
    return list(found.values())


# ------------------------------------------------------------------------ figure pixels
def test_figures_at_9_gb_are_refused_up_front(small_runs):
    """``--size 40x40 --dpi 1200`` is 48000 × 48000 pixels (9.2 GB as RGBA): exit 2 and
    one line naming both options and the largest --dpi that fits, nothing drawn."""
    _, archive = small_runs["single"]
    proc, peak = _child("import sys\nfrom reportgen.commands.cli import main\n"
                        "print(main(['figures', sys.argv[1], '--size', '40x40', '--dpi', "
                        "'1200', '--format', 'png']))", archive, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stdout.split()[0] == "2", proc.stdout
    line = _one_line(proc.stderr)
    assert "--size 40x40" in line and "--dpi 1200" in line and "48000 x 48000" in line, line
    assert "--dpi 204" in line, line  # the largest that fits 40x40
    assert peak < SMALL, f"peak {peak / 1024:.0f} MiB"


def test_figures_within_the_pixel_budget_are_drawn(small_runs, tmp_path):
    _, archive = small_runs["single"]
    code, err = _cli("figures", archive, "--size", "slide", "--dpi", "50", "--format", "png",
                     "--only", "phase*", "--folder", tmp_path / "f")
    assert code == 0, err
    assert list((tmp_path / "f").glob("*.png"))


# ------------------------------------------------------------------------ the API's dicts
def test_a_huge_dict_writes_nothing(tmp_path):
    """A list of 5 million values in a dict made an 89 MB TOML (written, then refused as
    larger than 1 MB): now a ConfigError before anything is written, in a second."""
    import time

    import reportgen
    from reportgen.errors import ConfigError

    config = {"kind": "pendulum", "title": "huge", "params": {"g": 9.81, "l": 1.0},
              "initial": {"theta": 1.0}, "run": {"t_end": 1.0, "study": False},
              "sweep": {"initial.theta": [0.5] * 5_000_000}}
    t0 = time.process_time()
    with pytest.raises(ConfigError, match="larger than 1000 kB") as info:
        reportgen.run(config, out=tmp_path / "out")
    assert time.process_time() - t0 < 2.0
    assert len(info.value.problems) == 1 and "'huge'" in info.value.problems[0]
    assert not list(tmp_path.rglob("*.toml"))


def test_an_animation_held_in_memory_is_bounded(small_runs, tmp_path):
    """A GIF's frames are held until it is written: 90 frames at --dpi 1200 would be
    4 gigapixels; exit 2 and one line before the first frame is drawn."""
    _, archive = small_runs["single"]
    code, err = _cli("animate", archive, "--dpi", "1200", "--format", "gif",
                     "--folder", tmp_path / "a")
    assert code == 2, err
    line = [x for x in err.splitlines() if x.strip()][-1]
    assert "a GIF of 90 frames at --dpi 1200" in line and "--format mp4" in line, err
    assert "Traceback" not in err and not (tmp_path / "a" / "animation.gif").exists()
