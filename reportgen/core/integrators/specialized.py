"""DOP853 compiled for one model: its right-hand side inlined, its dimension a constant.

The shared drivers (:mod:`.kernels`) call a model through a C callback, so one compiled
driver serves every model.  The price is an opaque call per evaluation and loops over
the state whose length LLVM does not know.  For a small, cheap system that is most of
the step: on the reduced heavy top (4 states, a polynomial and one division per
evaluation) this driver takes the same steps, bit for bit, in 75 instead of 135 µs
(measured, 274 steps).  The price is its own compile, ~4 s once per numba cache, so a
model asks for it (``OdeModel.specialize``); the lecture pack's heavy tops share one.

The driver is the generic one's text (:mod:`._gen_dop853`) with ``rhs`` imported by
name, loaded through core's code store (:func:`reportgen.core.codegen.load_module`; by
default a file under ``$XDG_CACHE_HOME/reportgen/drivers``) so numba caches it. numba
does not notice when an inlined function changes, so the text carries a hash of the
model's module and of :mod:`.compiled`: an edited model writes a new driver instead of
loading a stale one.
"""

from __future__ import annotations

import functools
import hashlib
import importlib
import inspect
import sys

from .. import codegen
from . import _gen_dop853, compiled

#: bump when what a generated driver means changes without its text changing
VERSION = "1"


@functools.cache
def _stamp(module_name: str) -> str:
    h = hashlib.sha256()
    for module in (importlib.import_module(module_name), compiled):
        h.update(inspect.getsource(module).encode())
    return h.hexdigest()[:16]


def dop853_driver(rhs, dim: int):
    """The DOP853 driver compiled for ``rhs`` (a module-level ``njit(error_model="numpy")``
    function) and state dimension ``dim``: :func:`._dop853_unrolled.dop853_adaptive`'s
    arguments without the leading ``rhs``."""
    py = getattr(rhs, "py_func", None)
    if py is None:
        raise TypeError(f"a specialized driver needs a numba.njit right-hand side, got {rhs!r}")
    module_name, name = py.__module__, py.__name__
    if getattr(sys.modules.get(module_name), name, None) is not rhs:
        raise ValueError(f"{module_name}.{name}: a specialized driver imports its right-hand "
                         "side by name; it must be a module-level function")
    if rhs.targetoptions.get("error_model") != "numpy":
        # inlined, a division by zero would raise inside the driver instead of giving the
        # inf/nan the driver reports as NONFINITE (the C callbacks' error model)
        raise ValueError(f"{module_name}.{name}: a specialized driver needs "
                         "njit(error_model='numpy')")
    source = _gen_dop853.source((module_name, name), int(dim), _stamp(module_name))
    return codegen.load_module(source, "drivers", VERSION).dop853_adaptive
