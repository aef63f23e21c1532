"""Hashes of reportgen's own code, part of the stage keys.

The package is installed editable (``make run``), so after a ``git pull`` the same
version number may run different code.  A stage's cached output must then not be
reused: the simulate key holds :func:`physics_code`, the figures key and the report
stamp :func:`drawing_code`.  Standard library only, and each hash is computed once per
process (~1.3 MB of source: a few ms).
"""

from __future__ import annotations

import functools
import hashlib
from collections.abc import Iterable
from pathlib import Path

from .layout import TEMPLATE_DIRS

PACKAGE = Path(__file__).resolve().parent

#: what draws figures and renders reports from an archive (and never simulates)
DRAWING = ("plots", "report.py", "svgslim.py", "pdf.py", "layout.py", "export.py",
           "animate.py")
#: neither simulates nor draws: commands around the stages, benchmarks, this module
NEITHER = ("cli.py", "watch.py", "bench.py", "bench_nbody.py", "bench_pipeline.py",
           "codestamp.py", "__main__.py")


def _hash(files: Iterable[Path], root: Path) -> str:
    """Hash of the files' names (relative to their ``root`` folder: the same in every
    checkout) and contents."""
    h = hashlib.sha256()
    for path in sorted(set(files)):
        h.update(path.relative_to(root).as_posix().encode() + b"\0")
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


def _sources(names: Iterable[str], package: Path) -> list[Path]:
    files = []
    for name in names:
        path = package / name
        files.extend(path.rglob("*.py") if path.is_dir() else [path] if path.exists() else [])
    return files


@functools.cache
def physics_code(package: Path = PACKAGE) -> str:
    """Hash of the code a simulation runs: the whole package but what only draws or only
    drives (:data:`DRAWING`, :data:`NEITHER`).  A scene kind's module holds both its physics
    and its sections, so editing a kind's drawing simulates that kind's scenes again."""
    skip = set(_sources(DRAWING + NEITHER, package))
    return _hash((p for p in package.rglob("*.py") if p not in skip), package)


@functools.cache
def drawing_code(package: Path = PACKAGE, template_dirs: tuple[Path, ...] = TEMPLATE_DIRS
                 ) -> str:
    """Hash of the code and templates that turn an archive into figures and reports: the
    drawing modules, the scene kinds (their sections) and the jinja2 templates."""
    code = _hash(_sources(DRAWING + ("scenes",), package), package)
    templates = next((d for d in template_dirs if d.is_dir()), None)
    if templates is None:
        return code
    return code + _hash((p for p in templates.rglob("*") if p.is_file()), templates)
