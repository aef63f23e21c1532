"""Generated Python modules, imported through a pluggable code store.

Numba caches a function's machine code next to its source file, so compiled code that
is generated at run time (a formula's right-hand side, a driver compiled for one model)
must come from a file for numba's on-disk cache to serve later processes (a measured
speed feature: seconds of compiling per model, once per cache).  Core only asks for a
module from its source text, :func:`load_module`; *where* the text goes is a
:class:`CodeStore`'s business:

* the default, :class:`FileCodeStore`, writes each text once under
  ``$XDG_CACHE_HOME/reportgen/<kind>`` and imports it from there.  It is the only code
  in :mod:`reportgen.core` that touches files, and is created on first use only;
* :func:`set_store` puts another in its place (a test's temporary folder, an in-memory
  store without numba's disk cache, a store the application layer owns).

A file's name is the hash of its text (and of ``version``): a changed generator or input
writes a new file, never a stale one under an old name.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
import threading
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Protocol

__all__ = ["CodeStore", "FileCodeStore", "get_store", "load_module", "module_name",
           "set_store"]


class CodeStore(Protocol):
    """Where generated code lives: turns a module's source text into the module."""

    def load(self, source: str, kind: str, version: str) -> ModuleType:
        """The module whose text is ``source``.  ``kind`` groups the modules of one
        generator ("formula", "drivers"); ``version`` joins the identity of the text:
        bumped when what the code means changes without its text changing."""
        ...


def module_name(source: str, kind: str, version: str) -> str:
    """The module's name: ``reportgen_<kind>_<hash of version and text>``."""
    digest = hashlib.sha256(f"{version}\n{source}".encode()).hexdigest()[:24]
    return f"reportgen_{kind}_{digest}"


class FileCodeStore:
    """Each module a file ``<root>/<kind>/<module_name>.py`` (written once per content,
    atomically: whole under a temporary name, then renamed), imported from there and
    memoized per process.

    ``root`` : a folder, or a function giving one (read at each load, so a changed
    ``$XDG_CACHE_HOME`` is followed); default :func:`reportgen.cache_root`.
    """

    def __init__(self, root: Path | str | Callable[[], Path] | None = None):
        self._root = root
        self._lock = threading.Lock()
        self._modules: dict[str, ModuleType] = {}

    def folder(self, kind: str) -> Path:
        root = self._root
        if root is None:
            from .. import cache_root

            root = cache_root
        return Path(root() if callable(root) else root) / kind

    def load(self, source: str, kind: str, version: str = "") -> ModuleType:
        name = module_name(source, kind, version)
        with self._lock:
            module = self._modules.get(name)
            if module is not None:
                return module
            folder = self.folder(kind)
            folder.mkdir(parents=True, exist_ok=True)
            path = folder / f"{name}.py"
            try:
                current = path.read_text(encoding="utf-8")
            except OSError:
                current = None
            if current != source:
                tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
                tmp.write_text(source, encoding="utf-8")
                os.replace(tmp, path)
            spec = importlib.util.spec_from_file_location(name, path)
            module = importlib.util.module_from_spec(spec)
            sys.modules[name] = module
            spec.loader.exec_module(module)
            self._modules[name] = module
            return module


_LOCK = threading.Lock()
_STORE: CodeStore | None = None


def get_store() -> CodeStore:
    """The registered store; a :class:`FileCodeStore` on the user cache unless
    :func:`set_store` gave another (created on first use)."""
    global _STORE
    with _LOCK:
        if _STORE is None:
            _STORE = FileCodeStore()
        return _STORE


def set_store(store: CodeStore | None) -> CodeStore | None:
    """Register ``store`` for every later :func:`load_module` (None: the default again,
    created on next use); returns the store it replaces (None if none was made yet)."""
    global _STORE
    if store is not None and not callable(getattr(store, "load", None)):
        raise TypeError(f"store: expected an object with load(source, kind, version), "
                        f"got {store!r}")
    with _LOCK:
        previous, _STORE = _STORE, store
        return previous


def load_module(source: str, kind: str, version: str = "") -> ModuleType:
    """The module whose text is ``source``, from the registered :class:`CodeStore`
    (:func:`get_store`).  ``version`` joins the text's identity: bump it when what the
    code means changes without its text changing."""
    return get_store().load(source, kind, version)
