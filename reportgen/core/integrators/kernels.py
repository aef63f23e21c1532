"""A model's functions as numba C callbacks, and the compiled drivers bound to them.

Why C callbacks
---------------
The drivers (:mod:`.compiled`) take the model's functions as arguments.  Passed as
they are -- numba dispatchers -- they would be typed as ``types.Dispatcher(<that
object>)``, keyed by object identity: every fresh process misses numba's on-disk
cache and recompiles (measured with numba 0.68.1).  The previous design worked around
this by generating one module per model with the functions bound as globals, which
cached well but compiled every driver again for every model (~5-6 s per model cold,
~60 CPU-s for the lecture pack).

Here each model function is compiled once more as a C callback, ``numba.cfunc`` with
the fixed signature of :mod:`reportgen.core.model`.  numba types a cfunc argument as
``FunctionType[<signature>]``, the same for every model, so each driver is compiled
once (and loaded from disk in later processes) for all models; a model adds only its
own small callbacks.  The indirect call costs ~1 ns per evaluation.

Caching and errors
------------------
* A callback is cached on disk exactly when the model's dispatcher is (``njit(cache=
  True)``, as the model modules do); it shares the function's numba cache index, under
  its own key.  Functions numba cannot cache (made by ``exec``, say) compile in memory.
* Callbacks are built on first use and memoized per process, so a method pays only for
  what it calls (an explicit Runge-Kutta never builds ``jac``, ``drift`` or ``kick``).
* They compile with ``error_model="numpy"``: an exception cannot leave a C callback
  (numba would print it as "unraisable" and go on with a half-written ``out``), so a
  division by zero gives inf/nan instead, which the drivers report as NONFINITE.
* numba types a plain cfunc argument by building a new ``FunctionType`` at every call
  of a driver: 5 µs of the ~19 µs a short ``integrate`` costs (measured).  Ours are
  :class:`_TypedCFunc`, whose type is built once.
* They compile without numba's reference counting (``_nrt=False``).  A callback only
  borrows its arrays for the call, yet numba's refcount pruning leaves an atomic
  ``NRT_incref``/``NRT_decref`` pair per array whenever a branch or an array view
  defeats it: the Kepler right-hand side (``if params[2] != 0.0``) spent 35 of its
  42 ns per call on them, the linear chain's (``reshape`` views) most of its time.  A
  function that allocates cannot compile so and keeps the counting (:func:`as_cfunc`).
  The choice is part of the on-disk cache key (:class:`_FlaggedCache`), so callbacks
  cached before it are not loaded for it.
"""

from __future__ import annotations

import contextlib
import threading
from functools import cached_property

import numba
from numba import types
from numba.core import sigutils
from numba.core.caching import FunctionCache, NullCache
from numba.core.ccallback import CFunc
from numba.core.typing.typeof import typeof_impl

from . import _dop853_unrolled, compiled

_VEC = types.float64[::1]
#: rhs(t, y, params, out) and jac(t, y, params, out): see reportgen.core.model
RHS_SIG = types.void(types.float64, _VEC, _VEC, _VEC)
JAC_SIG = types.void(types.float64, _VEC, _VEC, types.float64[:, ::1])
#: drift(p, params, out) and kick(q, params, out)
SPLIT_SIG = types.void(_VEC, _VEC, _VEC)

_LOCK = threading.RLock()
#: (id(dispatcher), signature) -> (dispatcher, cfunc); the dispatcher is kept so its id stays
_CFUNCS: dict[tuple[int, str], tuple[object, object]] = {}
_KERNELS: dict[tuple[int, ...], ModelKernels] = {}


#: id(dispatcher) -> (dispatcher, body): callbacks compiled from a thin body
_BODIES: dict[int, tuple[object, object]] = {}


def wrap_for_callback(func, body) -> None:
    """Let :func:`as_cfunc` compile ``body`` -- a module-level function that only calls
    ``func`` with its own arguments -- instead of ``func``'s source a second time.

    The callback then links the machine code of ``func`` that numba compiled (or loaded)
    for calls from Python (scipy's peers call it so) instead of compiling the whole body
    again: for the generated double-pendulum module, 1.8 -> 1.2 s on an empty cache, the
    same ns per evaluation and bitwise the same trajectory (measured).  ``func`` must be
    ``njit(error_model="numpy")``, the callbacks' error model."""
    if getattr(func, "targetoptions", {}).get("error_model") != "numpy":
        raise ValueError(f"{func!r}: a wrapped callback needs njit(error_model='numpy')")
    with _LOCK:
        _BODIES[id(func)] = (func, body)


class _TypedCFunc(CFunc):
    """A cfunc whose numba type (``FunctionType`` of its signature) is made once."""

    def __init__(self, pyfunc, sig, options):
        super().__init__(pyfunc, sigutils.normalize_signature(sig), locals={},
                         options=options)
        self.numba_type = types.FunctionType(self._sig)
        self._address_once = None

    def __wrapper_address__(self, *_):
        # numba's wrapper-address protocol, asked at every driver call: without it numba
        # checks the signature's equality again each time
        if self._address_once is None:
            self._address_once = self.address
        return self._address_once


@typeof_impl.register(_TypedCFunc)
def _typeof_typed_cfunc(val, c):
    return val.numba_type


class _FlaggedCache(FunctionCache):
    """numba's cache of a function, with ``flag`` (how it was compiled) in the index key:
    numba's own key holds the signature and the bytecode, not the compile options, so a
    function compiled two ways would otherwise load whichever was saved first."""

    def __init__(self, py_func, flag: str):
        super().__init__(py_func)
        self._flag = flag

    def _index_key(self, sig, codegen):
        return (*super()._index_key(sig, codegen), self._flag)


@contextlib.contextmanager
def loop_vectorizer():
    """Compile with LLVM's loop vectorizer on, whatever NUMBA_LOOP_VECTORIZE says (the
    package turns it off by default, see ``reportgen/__init__.py``; the model callbacks
    take the same ns per call either way, measured on the three-body, FPUT, coupled
    pendula, rigid body and double pendulum right-hand sides).  numba reads the
    setting when it optimizes a module, so this holds for what compiles inside; numba's
    compiler lock is held throughout, so no other thread compiles under the switch."""
    from numba.core import config
    from numba.core.compiler_lock import global_compiler_lock

    with global_compiler_lock:
        config.reload_config()  # apply a changed NUMBA_* variable now, not mid-compile
        before, config.LOOP_VECTORIZE = config.LOOP_VECTORIZE, 1
        try:
            yield
        finally:
            config.LOOP_VECTORIZE = before


class _VectorizedTwin:
    """``dispatcher``'s function compiled once more with the loop vectorizer on
    (:func:`loop_vectorizer`), cached under its own key; called like the dispatcher."""

    def __init__(self, dispatcher):
        options = {k: v for k, v in dispatcher.targetoptions.items() if k != "nopython"}
        self._twin = numba.njit(**options)(dispatcher.py_func)
        self._twin._cache = _FlaggedCache(dispatcher.py_func, "loop_vectorize=1")
        self._ready = False

    def __call__(self, *args):
        if self._ready:
            return self._twin(*args)
        with loop_vectorizer():  # compiles or loads from the cache
            out = self._twin(*args)
        self._ready = True
        return out


def _compile_cfunc(py, sig, options, cache: bool) -> _TypedCFunc:
    """What ``numba.cfunc(sig, cache=cache, **options)(py)`` does, as a :class:`_TypedCFunc`."""
    cf = _TypedCFunc(py, sig, options)
    if cache:
        if options.get("_nrt", True):
            cf.enable_caching()
        else:
            cf._cache = _FlaggedCache(py, "nrt=False")
    cf.compile()
    return cf


def _compile_uncounted(py, sig, options, cache: bool) -> _TypedCFunc:
    """The callback without reference counting if ``py`` compiles so (it does not when it
    allocates an array), else with it."""
    try:
        return _compile_cfunc(py, sig, {**options, "_nrt": False}, cache)
    except numba.core.errors.NumbaError:
        return _compile_cfunc(py, sig, options, cache)


def as_cfunc(func, sig):
    """``func`` (a numba dispatcher) compiled as a C callback of signature ``sig``, memoized."""
    key = (id(func), str(sig))
    with _LOCK:
        hit = _CFUNCS.get(key)
        if hit is not None:
            return hit[1]
        py = getattr(func, "py_func", None)
        if py is None:
            raise TypeError(f"model functions must be numba.njit dispatchers, got {func!r}")
        wrapped = _BODIES.get(id(func))
        if wrapped is not None and wrapped[0] is func:
            py = wrapped[1]
        options = {**getattr(func, "targetoptions", {}), "error_model": "numpy"}
        cache = not isinstance(getattr(func, "_cache", None), NullCache)
        try:
            cf = _compile_uncounted(py, sig, options, cache)
        except RuntimeError:  # numba cannot locate a cache for this function
            cf = _compile_uncounted(py, sig, options, False)
        _CFUNCS[key] = (func, cf)
        return cf


@numba.njit(cache=True)
def _no_jac(t, y, params, out):
    """Stands in for a missing Jacobian; never called (the driver uses finite differences)."""


class ModelKernels:
    """The drivers of :mod:`.compiled` with one model's callbacks as leading arguments.

    The methods take the drivers' remaining arguments unchanged, so a Run calls
    ``kern.erk_fixed(A, b, c, ...)`` without knowing how the model is bound.
    """

    def __init__(self, model):
        sep = model.separable
        self._funcs = (model.rhs, model.jac, sep and sep.drift, sep and sep.kick)
        self.has_jac = model.jac is not None
        self.dim = model.dim if model.specialize else None
        self.wide = model.dim >= WIDE_STATE

    @cached_property
    def rhs(self):
        return as_cfunc(self._funcs[0], RHS_SIG)

    @cached_property
    def jac(self):
        return as_cfunc(self._funcs[1] if self.has_jac else _no_jac, JAC_SIG)

    @cached_property
    def drift(self):
        return as_cfunc(self._funcs[2], SPLIT_SIG)

    @cached_property
    def kick(self):
        return as_cfunc(self._funcs[3], SPLIT_SIG)

    def erk_adaptive(self, *args):
        return compiled.erk_adaptive(self.rhs, *args)

    @cached_property
    def dop853_specialized(self):
        from .specialized import dop853_driver

        return dop853_driver(self._funcs[0], self.dim)

    def dop853_adaptive(self, *args):
        """DOP853 with its tableau written out (:mod:`._dop853_unrolled`): erk_adaptive's
        steps; on a driver compiled for this model when it asks (``model.specialize``),
        on the loop-vectorized twin for a state of ``WIDE_STATE`` or more components."""
        if self.dim is not None:
            return self.dop853_specialized(*args)
        if self.wide:
            return _DOP853_WIDE(self.rhs, *args)
        return _dop853_unrolled.dop853_adaptive(self.rhs, *args)

    def erk_fixed(self, *args):
        return compiled.erk_fixed(self.rhs, *args)

    def splitting_fixed(self, *args):
        return compiled.splitting_fixed(self.drift, self.kick, *args)

    def collocation_fixed(self, *args):
        """Gauss collocation with the model's Jacobian, or finite differences without one."""
        return compiled.collocation_fixed(self.rhs, self.jac, not self.has_jac, *args)


#: States of this many components or more run DOP853 on its loop-vectorized twin.  The
#: vectorized loops pay runtime alias and length checks at every entry, ~30 per step; from
#: ~10 components their 8-wide arithmetic wins (measured per evaluation, same steps: 7
#: components 31 -> 26 ns without the vectorizer, 12 components 42 -> 54 ns, 18: 62 -> 77 ns)
WIDE_STATE = 10
_DOP853_WIDE = _VectorizedTwin(_dop853_unrolled.dop853_adaptive)


def kernels_for(model) -> ModelKernels:
    """The compiled drivers bound to ``model``'s functions (one object per process and set
    of functions; the callbacks are compiled or loaded when a driver first needs them)."""
    sep = model.separable
    funcs = (model.rhs, model.jac, sep and sep.drift, sep and sep.kick)
    key = (*(id(f) for f in funcs), model.dim if model.specialize else None,
           model.dim >= WIDE_STATE)
    with _LOCK:
        kern = _KERNELS.get(key)
        if kern is None:
            kern = _KERNELS[key] = ModelKernels(model)
        return kern

