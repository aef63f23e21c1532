"""Pure numerics on ndarrays: models, integrators, exact references.

No plotting, no HDF5, no archive.  The I/O core does, precisely:

* generated code (:mod:`.codegen`): when compiled code is generated at run time (a
  formula's right-hand side, a DOP853 driver specialized for one model), its text goes
  through the registered code store, :func:`.codegen.load_module`.  The default store,
  :class:`.codegen.FileCodeStore`, writes it once to ``$XDG_CACHE_HOME/reportgen/<kind>``
  and imports it from there, because numba caches machine code only for functions
  defined in files; ``codegen.set_store`` replaces it.  Nothing else in core opens a file.
* numba's own on-disk cache (``njit(cache=True)``) of core's compiled functions, written
  by numba beside their modules (or under ``NUMBA_CACHE_DIR``) when they are compiled.

(``python -m reportgen.core.integrators._gen_dop853`` rewrites a module of the package: a
developer's command, never run by the library.)
"""
