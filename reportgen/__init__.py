"""reportgen: config-driven simulator and report generator for classical mechanics."""

import os as _os
from pathlib import Path as _Path

__version__ = "0.2.0"


def cache_root() -> _Path:
    """``$XDG_CACHE_HOME/reportgen``, else ``~/.cache/reportgen``: the folder of every user
    cache of the package (peer rows, generated code, templates, equations).  Here, at the
    root, so that :mod:`reportgen.core` may use it too."""
    base = _os.environ.get("XDG_CACHE_HOME") or _os.path.join(_os.path.expanduser("~"), ".cache")
    return _Path(base) / "reportgen"


# Our drivers loop over states of 2 to ~20 components through LLVM's loop vectorizer,
# which wraps every such loop in runtime alias and trip-count checks that cost more than
# the vector loop saves at these sizes: without it the shared DOP853 driver takes 1.1-1.5x
# fewer ns per evaluation (benchmarks/README.md, "Loop vectorization").  Set before numba
# reads its configuration (numba reloads it when a NUMBA_* variable changes, so this also
# holds if numba was imported first); a value the user set is kept.  DOP853 on a state of
# 10 or more components runs a twin compiled with the vectorizer on
# (reportgen.core.integrators.kernels.WIDE_STATE).
_os.environ.setdefault("NUMBA_LOOP_VECTORIZE", "0")
# numba's on-disk cache does not key its entries on this setting: code compiled with the
# vectorizer on would be loaded later by runs without it (and the other way round).  A
# user who turns it on gets a cache folder of their own, unless they chose one.
if _os.environ["NUMBA_LOOP_VECTORIZE"] != "0" and not _os.environ.get("NUMBA_CACHE_DIR"):
    _os.environ["NUMBA_CACHE_DIR"] = str(
        cache_root() / ("numba-loop-vectorize-" + _os.environ["NUMBA_LOOP_VECTORIZE"]))


#: the Python API (reportgen/api.py: run, open, kinds, Run, verify), imported on first use so that
#: ``import reportgen`` loads no numerics, h5py or xarray.  Imported by a computed name:
#: every module below may import this package's ``__version__`` and the API imports them,
#: and no stage runs the API, so neither the import graph (tests/test_imports.py) nor the
#: stages' code stamps (reportgen.support.codestamp, which follows literal names only)
#: count it.  (``reportgen.kinds`` is also the package of scene kinds, made callable there.)
_API = ("run", "open", "kinds", "Run", "verify")


def __getattr__(name: str):
    if name in _API:
        import importlib

        return getattr(importlib.import_module(f"{__name__}.api"), name)
    raise AttributeError(f"module 'reportgen' has no attribute {name!r}")


def __dir__():
    return sorted([*globals(), *_API])
