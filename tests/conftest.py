"""Shared fixtures: write configs into a temp folder and run the CLI in-process."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

# one BLAS thread in the test processes and every process they start, as the `reportgen`
# command has (reportgen.support.threads): set before anything loads numpy
from reportgen.support.threads import one_blas_thread_by_default  # noqa: I001 - loads no numpy

one_blas_thread_by_default()

import pytest  # noqa: E402

from reportgen.commands.cli import main  # noqa: E402

REPO = Path(__file__).resolve().parent.parent

# The user caches of the test session (peer measurements, generated and compiled code,
# equations, templates) live in a temporary folder, never in the user's ~/.cache.  One
# folder for the whole session: made by the first process that imports this file (pytest's
# controller), inherited by the xdist workers it starts and by every subprocess a test
# starts, so each model's code is compiled once per session, not once per worker and
# again in every batch's pool (~40 CPU-s for the lecture pack each time).  Its entries
# are written atomically, so processes sharing it is safe.
_SESSION_CACHE = "REPORTGEN_TEST_SESSION_CACHE"
if not os.path.isdir(os.environ.get(_SESSION_CACHE, "")):
    os.environ[_SESSION_CACHE] = tempfile.mkdtemp(prefix="reportgen-test-cache-")
os.environ["XDG_CACHE_HOME"] = os.environ[_SESSION_CACHE]
os.environ.pop("REPORTGEN_NO_CACHE", None)


@pytest.fixture
def write_config(tmp_path):
    """write_config(name, text) -> Path of tmp_path/name.toml with dedented text."""

    def write(name: str, text: str) -> Path:
        path = tmp_path / f"{name}.toml"
        path.write_text(textwrap.dedent(text).lstrip())
        return path

    return write


@pytest.fixture
def cli(capsys):
    """cli(*args) -> (exit status, stdout, stderr) of `reportgen args` run in-process."""

    def run(*args):
        code = main([str(a) for a in args])
        out, err = capsys.readouterr()
        return code, out, err

    return run


def study_off_text(config: Path) -> str:
    """The text of ``config`` with its error-against-run-time study off: ``[run] study =
    false``, added to a preset's run too; a scene whose kind has no run (inertia, rotation,
    a molecule's modes) has no study and is returned as it is."""
    import tomllib

    from reportgen.kinds import load_scene
    from reportgen.scene.config import parse_config_text, to_toml

    text = config.read_text(encoding="utf-8")
    data = tomllib.loads(text)
    data.setdefault("run", {})["study"] = False
    try:
        load_scene(parse_config_text(to_toml(data), config))
    except Exception:  # no run to turn the study off in
        return text
    return to_toml(data)


def without_study(path: Path, target: Path) -> Path:
    """``target``: the config ``path`` with its study off (:func:`study_off_text`) and HTML
    only (what a test of the report's drawing needs, at a fraction of the cost)."""
    import tomllib

    from reportgen.scene.config import to_toml

    data = tomllib.loads(study_off_text(path))
    data.setdefault("report", {})["formats"] = ["html"]
    target.write_text(to_toml(data), encoding="utf-8")
    return target


@pytest.fixture(scope="module")
def shipped_archives(tmp_path_factory):
    """archive(name) -> the archive of ``configs/<name>.toml``, simulated without its study
    once per test module, on first request."""
    from reportgen.archive.store import read_archive
    from reportgen.pipeline.stages import run_scene

    folder = tmp_path_factory.mktemp("shipped-archives")
    made = {}

    def archive(name: str):
        if name not in made:
            source = without_study(REPO / "configs" / f"{name}.toml", folder / f"{name}.toml")
            outcome = run_scene(str(source), str(folder / "out"), force=True,
                                formats=("html",))
            assert outcome.status in ("ok", "unstable"), outcome.message
            made[name] = read_archive(folder / "out" / name / "run.h5")
        return made[name]

    return archive


#: a line of Python that prints its process's peak resident memory in KiB since its exec,
#: for a test to append to a child's code: VmHWM (getrusage's ru_maxrss keeps the forking
#: parent's size across exec: a pytest worker's 900 MiB)
PEAK = ("print(next(int(line.split()[1]) for line in open('/proc/self/status') "
        "if line.startswith('VmHWM:')))")


def cli_without_core(*args) -> subprocess.CompletedProcess:
    """`reportgen args` in a fresh process in which ``reportgen.core`` cannot be imported:
    whatever it does, it does from an archive alone."""
    code = ("import sys; sys.modules['reportgen.core'] = None\n"
            "from reportgen.commands.cli import main\n"
            f"raise SystemExit(main({[str(a) for a in args]!r}))")
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=300)


PENDULUM = """
kind = "pendulum"
title = "{title}"

[params]
g = 9.81
l = 1.0

[initial]
theta = {theta}

[run]
t_end = {t_end}
samples = {samples}
study = {study}
"""


def pendulum_text(theta=1.0, t_end=10.0, samples=1001, study="false", title="test pendulum",
                  extra=""):
    return PENDULUM.format(theta=theta, t_end=t_end, samples=samples, study=study,
                           title=title) + textwrap.dedent(extra)


#: the test modules whose fixtures run a whole batch of scenes (minutes, in a pool of their
#: own): collected first, so that xdist (``--dist loadfile`` hands out modules in
#: collection order) starts them at once and the short tests fill the other worker around
#: them, rather than two long batches starting last and running alone at the end
_LONG_MODULES = ("test_shipped_pages.py", "test_unseen_pages.py")


def pytest_collection_modifyitems(config, items):
    def rank(item):
        name = item.path.name
        return _LONG_MODULES.index(name) if name in _LONG_MODULES else len(_LONG_MODULES)

    items.sort(key=rank)  # stable: every other module keeps its order
