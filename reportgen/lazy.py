"""Modules imported on first use.

Scene kinds are one module each, holding both their simulate stage (which needs
``reportgen.core``: models, integrators, closed forms) and their report stage (which
reads the archive and nothing else).  A kind names its core modules with
:func:`lazy_module`, so importing the kind - as the report, ``kinds`` and
``validate`` do - imports no numerics; a report section that reached into
``reportgen.core`` would fail loudly when core is unavailable (tested in
``tests/test_archive_only.py``).  This is layering, not a cycle dodge: core never
imports scenes.
"""

from __future__ import annotations

import importlib
import types


class LazyModule(types.ModuleType):
    """A stand-in for the module ``name``, imported on the first attribute access."""

    def __init__(self, name: str):
        super().__init__(name)
        self.__dict__["_lazy_target"] = name

    def _load(self) -> types.ModuleType:
        return importlib.import_module(self.__dict__["_lazy_target"])

    def __getattr__(self, attr: str):
        return getattr(self._load(), attr)

    def __dir__(self):
        return dir(self._load())


def lazy_module(name: str) -> types.ModuleType:
    """``name`` (absolute, e.g. ``"reportgen.core.models.pendulum"``) imported on first use."""
    return LazyModule(name)
