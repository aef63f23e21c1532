"""Generated Python modules, imported from files so that numba caches them on disk.

Numba caches a function's machine code next to its source file, so compiled code that
is generated at run time (a formula's right-hand side, a driver compiled for one model)
is written to a file under ``$XDG_CACHE_HOME/reportgen/<kind>`` and imported from there.
A file's name is the hash of its text: a changed generator or input writes a new file,
never a stale one under an old name.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
import threading
from pathlib import Path

from .. import cache_root

_LOCK = threading.Lock()
_MODULES: dict[str, object] = {}


def code_folder(kind: str) -> Path:
    """``$XDG_CACHE_HOME/reportgen/<kind>`` (:func:`reportgen.cache_root`)."""
    return cache_root() / kind


def load_module(source: str, kind: str, version: str = ""):
    """Import ``source`` from its file under :func:`code_folder` ``(kind)`` (written once
    per content, atomically), memoized per process.  ``version`` joins the hash: bump it
    when what the code means changes without its text changing."""
    digest = hashlib.sha256(f"{version}\n{source}".encode()).hexdigest()[:24]
    name = f"reportgen_{kind}_{digest}"
    with _LOCK:
        module = _MODULES.get(name)
        if module is not None:
            return module
        folder = code_folder(kind)
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f"{name}.py"
        try:
            current = path.read_text(encoding="utf-8")
        except OSError:
            current = None
        if current != source:  # written whole under a temporary name, then renamed
            tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
            tmp.write_text(source, encoding="utf-8")
            os.replace(tmp, path)
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
        _MODULES[name] = module
        return module
