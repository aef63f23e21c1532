"""A received output folder is untrusted input (issue 48): a fuzzer over a small good
folder.  Random manifests and caches (``.gallery.json``, ``figures/sections.json``,
``.report-stamp.json``), SVGs with handlers and style sheets, links leading out, FIFOs,
oversized and compressed files; then ``run``, ``report``, ``figures``, ``inspect`` and
``reportgen.open(...)._repr_html_()`` over it.  Every command ends, with status 0, 1 or 2
and no traceback; no page holds a script, an event handler or a ``javascript:`` link; no
file outside ``--out`` is written or disclosed; memory stays bounded.

Cheap by design: one good folder is made per module, copied per example, and every
command runs in this process (a watchdog ends the process, with every thread's stack, if
one of them hangs)."""

from __future__ import annotations

import contextlib
import faulthandler
import gzip
import hashlib
import io
import json
import os
import resource
import shutil
import time
from html.parser import HTMLParser
from pathlib import Path

import pytest
from hypothesis import HealthCheck, Phase, example, given, settings
from hypothesis import strategies as st

from conftest import pendulum_text
from reportgen.archive.h5io import ArchiveError
from reportgen.commands.cli import main
from reportgen.errors import ConfigError, ReportError, UsageError

#: the fuzzer's examples (each runs the five commands on its own copy of the folder)
EXAMPLES = int(os.environ.get("REPORTGEN_FUZZ_OUTPUT_EXAMPLES", "25"))
#: a command running longer is hung: the watchdog ends the test process
HANG_S = 60
#: what a file outside --out holds: no page may show it
SECRET = "SECRET-0f3a-OUTSIDE-OUT"
#: how much more memory (peak resident set) the whole fuzz may take
MEMORY_BUDGET = 400 * 2**20
#: larger than every reader's limit (sparse: it costs no disk)
OVERSIZED = 300_000_000

CONFIG = pendulum_text(t_end=2.0, samples=41, title="fuzzed",
                       extra='method = "scipy_dop853"\n[report]\nformats = ["html"]\n')


def _cli(*args) -> tuple[int, str]:
    """``reportgen args`` in this process: (status, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in args])
    return code, err.getvalue()


@pytest.fixture(scope="module")
def good(tmp_path_factory) -> Path:
    """A small good output folder (one pendulum scene, ``tiny``), made once."""
    root = tmp_path_factory.mktemp("good")
    cfg = root / "tiny.toml"
    cfg.write_text(CONFIG, encoding="utf-8")
    code, err = _cli("run", cfg, "--out", root / "out", "--jobs", "1")
    assert code == 0, err
    return root / "out"


# ------------------------------------------------------------------ damage
HOSTILE_SVGS = [
    "<svg/onload=alert(1) width='1'></svg>",
    "<svg xmlns='http://www.w3.org/2000/svg'><script>alert(1)</script></svg>",
    "<svg xmlns='http://www.w3.org/2000/svg'><g\nonclick\n=\n'alert(1)'/></svg>",
    "<svg xmlns='http://www.w3.org/2000/svg'><style>@import 'file:///etc/hostname';</style></svg>",
    "<svg xmlns='http://www.w3.org/2000/svg'><style>*{fill:url(http://x/)}</style></svg>",
    "<svg xmlns='http://www.w3.org/2000/svg' style='position:fixed'><foreignObject>"
    "<img xmlns='http://www.w3.org/1999/xhtml' src='x' onerror='alert(1)'/></foreignObject></svg>",
    "<svg xmlns='http://www.w3.org/2000/svg' xmlns:xlink='http://www.w3.org/1999/xlink'>"
    "<a xlink:href='javascript:alert(1)'><text>x</text></a><use href='../outside/secret.svg#a'/></svg>",
    "<!DOCTYPE svg [<!ENTITY x SYSTEM 'file:///etc/hostname'>]><svg>&x;</svg>",
    "<svg><img src=\"x\"/onerror=alert(1)></svg>",
]

#: the files and folders of the output folder that commands read back or write into
TARGETS = [".gallery.json", "tiny/figures/sections.json", "tiny/.report-stamp.json",
           "svg", "tiny/figures", "tiny/figures-svg", "tiny/run.h5", "other/run.h5", ".lock",
           "tiny/report.html", "tiny/.pdf-figures"]
DAMAGES = ["json", "twist", "svg", "link-file", "link-dir", "link-zero", "fifo", "oversized",
           "gzip", "deep", "empty"]

_json = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats()
    | st.sampled_from(["<script>alert(1)</script>", "javascript:alert(1)", "\u202e", "../x",
                       "figures/../../outside/secret.svg", "/etc/hostname"]),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(
        st.sampled_from(["key", "sections", "figures", "files", "svg", "title", "stamp",
                         "entry", "tiny", "archive", "formats"]), inner, max_size=3),
    max_leaves=8)


#: the examples every run tries first: each damage where it matters most
_READ_BACK = (".gallery.json", "tiny/figures/sections.json", "tiny/.report-stamp.json", "svg")
_KEPT_FIGURE = "figures/time_series-timeseries.svg"  # a twisted manifest still valid
EXPLICIT = [
    [(target, "fifo", None, "") for target in _READ_BACK],
    [(target, "oversized", None, "") for target in _READ_BACK],
    [("tiny/figures", "link-dir", None, ""), ("tiny/figures-svg", "link-dir", None, ""),
     ("tiny/.pdf-figures", "link-dir", None, ""), (".gallery.json", "link-file", None, "")],
    [(".gallery.json", "twist", "\u202e", ""),
     ("tiny/figures/sections.json", "twist", _KEPT_FIGURE, "")],  # reused: text escaped
    [("svg", "svg", None, HOSTILE_SVGS[2]), ("tiny/.report-stamp.json", "twist", None, "")],
    [("svg", "svg", None, HOSTILE_SVGS[0]), ("tiny/run.h5", "fifo", None, "")],
]


def _outside(example: Path) -> Path:
    """The sibling of ``--out`` that links lead to: a secret file, an SVG, a folder."""
    outside = example / "outside"
    (outside / "dir").mkdir(parents=True)
    (outside / "secret.json").write_text(json.dumps({"key": SECRET}))
    (outside / "secret.svg").write_text(f"<svg xmlns='http://www.w3.org/2000/svg'><text>"
                                        f"{SECRET}</text></svg>")
    (outside / "dir" / "sections.json").write_text(json.dumps({"key": SECRET}))
    return outside


def _twist(path: Path, data, out: Path) -> bytes:
    """The file ``path`` as this reportgen wrote it, one field changed to ``data``: what
    passes the readers' shape checks as far as it can (the manifest keeps its key, the
    gallery cache its stamp)."""
    rel = path.relative_to(out).as_posix()
    if rel == "tiny/figures/sections.json":
        stored = json.loads(path.read_text())
        fig = stored["sections"][0]["figures"][0]
        fig["files"]["svg"] = data if isinstance(data, str) else "figures/../../outside/secret.svg"
        stored["sections"][0]["title"] = "<script>alert(1)</script>\u202e"
        fig["caption"] = "<img src=x onerror=alert(1)>"
        return json.dumps(stored).encode()
    if rel == ".gallery.json":
        stored = json.loads(path.read_text())
        st_ = (out / "tiny" / "run.h5").stat()
        entry = stored["tiny"]
        entry["stamp"][:3] = [st_.st_mtime_ns, st_.st_size, st_.st_ino]  # current: reused
        entry["entry"].update(title="<script>alert(1)</script>", kind="javascript:alert(1)",
                              message="<svg/onload=alert(1)>", headline=str(data))
        return json.dumps(stored).encode()
    return json.dumps(data).encode()


def _damage(out: Path, outside: Path, target: str, damage: str, data, svg: str) -> None:
    paths = (sorted((out / "tiny" / "figures").glob("*.svg")) if target == "svg"
             else [out / target])
    for path in paths:
        content = None
        if damage in ("json", "twist"):
            try:
                content = _twist(path, data, out) if damage == "twist" else json.dumps(data).encode()
            except (OSError, ValueError, KeyError, IndexError, TypeError):
                content = json.dumps(data).encode()
        elif damage == "svg":
            content = svg.encode()
        elif damage == "gzip":
            content = gzip.compress(b"[" * 20_000_000)
        elif damage == "deep":
            content = b"[" * 200_000 + b"]" * 200_000
        elif damage == "empty":
            content = b""
        path.parent.mkdir(parents=True, exist_ok=True)
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        else:
            path.unlink(missing_ok=True)
        if content is not None:
            path.write_bytes(content)
        elif damage == "link-file":
            path.symlink_to(outside / ("secret.svg" if path.suffix == ".svg" else "secret.json"))
        elif damage == "link-dir":
            path.symlink_to(outside / "dir", target_is_directory=True)
        elif damage == "link-zero":
            path.symlink_to("/dev/zero")
        elif damage == "fifo":
            os.mkfifo(path)
        elif damage == "oversized":
            with open(path, "wb") as f:
                f.truncate(OVERSIZED)


# ------------------------------------------------------------------ checks
def _snapshot(folder: Path) -> dict[str, tuple]:
    """Every entry below ``folder`` (links not followed): its kind, size, time of change
    and, for a small file, its content's hash."""
    seen = {}
    for top, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = os.path.join(top, name)
            st_ = os.lstat(path)
            digest = ""
            if os.path.isfile(path) and not os.path.islink(path) and st_.st_size < 2**20:
                digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()
            seen[os.path.relpath(path, folder)] = (st_.st_mode, st_.st_size, st_.st_mtime_ns,
                                                   digest)
    return seen


class _Active(HTMLParser):
    """What in a page could act: script-like elements, event handlers, script links."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.found: list[str] = []

    def handle_starttag(self, tag, attrs):
        if (tag in ("script", "iframe", "object", "embed", "foreignobject", "base")
                or (tag == "meta" and "http-equiv" in dict(attrs))):  # a refresh to a URL
            self.found.append(f"<{tag}>")
        for name, value in attrs:
            if name.startswith("on"):
                self.found.append(f"<{tag} {name}=…>")
            if (name in ("href", "src", "xlink:href", "action", "formaction")
                    and (value or "").strip().lower().startswith(("javascript:", "data:text",
                                                                  "vbscript:"))):
                self.found.append(f"<{tag} {name}={value[:30]}>")

    def handle_data(self, data):
        if "@import" in data:
            self.found.append("@import")


def _assert_inert(page: str, where: str) -> None:
    parser = _Active()
    parser.feed(page)
    parser.close()
    assert parser.found == [], (where, parser.found)
    assert SECRET not in page, where


def _stat(path: Path) -> tuple | None:
    try:
        st_ = os.lstat(path)
    except OSError:
        return None
    return st_.st_ino, st_.st_mtime_ns, st_.st_size


def _page(path: Path, planted: tuple | None) -> str | None:
    """The page at ``path`` if a command wrote it (a regular file, not the one the
    damage left there: what a browser would open), else None."""
    if _stat(path) == planted or not path.is_file() or path.is_symlink():
        return None
    return path.read_text(encoding="utf-8", errors="replace")


# ------------------------------------------------------------------ the fuzzer
def test_hostile_output_folders(good, tmp_path_factory):
    import reportgen

    root = tmp_path_factory.mktemp("fuzz")
    cfg = root / "config" / "tiny.toml"
    cfg.parent.mkdir()
    cfg.write_text(CONFIG, encoding="utf-8")
    peak_before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    stats = {"examples": 0, "codes": {}, "slowest": 0.0}

    @settings(max_examples=EXAMPLES - len(EXPLICIT), deadline=None, derandomize=True,
              database=None, suppress_health_check=list(HealthCheck),
              phases=(Phase.explicit, Phase.generate))  # no shrinking: each example costs
    @given(changes=st.lists(st.tuples(st.sampled_from(TARGETS), st.sampled_from(DAMAGES),
                                      _json, st.sampled_from(HOSTILE_SVGS)),
                            min_size=1, max_size=4, unique_by=lambda change: change[0]))
    def check(changes):
        example = root / f"ex{stats['examples']}"
        stats["examples"] += 1
        out = example / "out"
        shutil.copytree(good, out, symlinks=True)
        (out / "other").mkdir(exist_ok=True)
        outside = _outside(example)
        for change in changes:
            _damage(out, outside, *change)
        before = _snapshot(outside), _snapshot(cfg.parent)
        pages = {"report": out / "tiny" / "report.html", "gallery": out / "index.html"}
        planted = {name: _stat(path) for name, path in pages.items()}
        archive = out / "tiny" / "run.h5"
        commands = [("run", cfg, "--out", out, "--jobs", "1"),
                    ("report", archive, "--format", "html"),
                    ("figures", archive, "--format", "svg", "--only", "energy*",
                     "--out", out / "exported"),
                    ("inspect", archive)]
        for args in commands:
            start = time.monotonic()
            faulthandler.dump_traceback_later(HANG_S, exit=True)  # a hang ends the process
            try:
                code, err = _cli(*args)
            finally:
                faulthandler.cancel_dump_traceback_later()
            stats["slowest"] = max(stats["slowest"], time.monotonic() - start)
            assert code in (0, 1, 2) and "Traceback" not in err, (args[0], changes, err)
            assert SECRET not in err, (args[0], err)
            stats["codes"].setdefault(args[0], set()).add(code)
        faulthandler.dump_traceback_later(HANG_S, exit=True)
        try:
            view = reportgen.open(out / "tiny")._repr_html_()
        except (ArchiveError, ConfigError, ReportError, UsageError):
            view = None  # the view of no archive: refused, in words
        finally:
            faulthandler.cancel_dump_traceback_later()
        for where, page in [*((name, _page(path, planted[name])) for name, path in pages.items()),
                            ("notebook", view)]:
            if page is not None:
                _assert_inert(page, f"{where} after {changes}")
        assert (_snapshot(outside), _snapshot(cfg.parent)) == before, changes
        shutil.rmtree(example)

    for changes in EXPLICIT:
        check = example(changes=changes)(check)
    check()
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024 - peak_before
    assert grown < MEMORY_BUDGET, f"peak memory grew by {grown / 2**20:.0f} MiB"
    assert stats["slowest"] < HANG_S
    assert {0, 2} <= set().union(*stats["codes"].values()), stats  # good and refused both seen


def test_the_fuzzers_checks_see_what_they_look_for():
    """The page check finds each thing it looks for (else the fuzzer proves nothing)."""
    for page in ("<svg/onload=alert(1)>", "<p><script>x</script>", "<a href=' javascript:x'>",
                 "<svg><style>@import 'x';</style></svg>", f"<p>{SECRET}</p>",
                 "<img src=x onerror=y>", "<meta http-equiv='refresh' content='0;url=x'>"):
        with pytest.raises(AssertionError):
            _assert_inert(page, "probe")
    _assert_inert("<meta charset='utf-8'><p>fine &lt;script&gt;</p><svg><path d='M0 0'/></svg>",
                  "probe")
