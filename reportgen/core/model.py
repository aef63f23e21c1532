"""The system, not the solver: what a model of motion exposes to the integrators.

A model is a first-order system ``y' = f(t, y; p)`` whose right-hand side is a
numba-compiled function, plus optional structure that some integrators need:

* ``separable`` -- for a separable Hamiltonian ``H = T(p) + V(q)`` with
  ``y = (q, p)``: the *drift* ``dq/dt = dT/dp`` (depends on p only) and the
  *kick* ``dp/dt = -dV/dq`` (depends on q only).  Symplectic splitting methods
  require it; a method that needs it fails early on a model that lacks it.
* ``jac`` -- the Jacobian ``df/dy``; implicit methods use it for Newton
  iterations (otherwise they fall back to finite differences).

Compiled function signatures (all float64, all write into ``out``)::

    rhs(t, y, params, out)        y: (d,)          out: (d,)
    jac(t, y, params, out)        y: (d,)          out: (d, d)
    drift(p, params, out)         p: (n,)          out: (n,)   dq/dt
    kick(q, params, out)          q: (n,)          out: (n,)   dp/dt

``params`` is a 1-D float64 array packed by the scene; the compiled functions
unpack it by position.  Model functions are defined at module level with
``numba.njit(cache=True)`` so that their compiled code is cached on disk.

The integrators call them as numba C callbacks (:mod:`reportgen.core.integrators.kernels`):
each is compiled once more with exactly the signature above (every array C-contiguous)
and ``error_model="numpy"`` (x/0 gives inf, which the integrators report as
non-finite).  Hence:

* a model function must not raise: an exception cannot leave a C callback (numba
  prints it as "unraisable" and the integrator goes on with a half-written ``out``);
* Helpers: an ``njit`` function that a model function calls with arrays is declared
  ``numba.njit(cache=True, inline="always")``.  Inlined, it compiles with the
  callback's error model, and numba can drop the reference counting of its array
  arguments, which otherwise costs ~50 ns per evaluation (measured: three-body
  kick + drift 76 ns -> 27 ns).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Separable:
    """Split of a separable Hamiltonian system y = (q, p), each of length ``n``."""

    n: int
    drift: Callable  # dq/dt = dT/dp(p)
    kick: Callable  # dp/dt = -dV/dq(q)


@dataclass(frozen=True)
class SurfaceOfSection:
    """A surface of section as a model offers it: the product of ``count`` factors
    g_k(y) vanishes on it, and it is crossed "upward" where the product goes from
    negative to positive along the run.

    A product, not one function, because a regularizing change of variables can fold the
    surface: the x-axis of the plane (y = 0) is p = 0 or sin q = 0 in the Thiele–Burrau
    variables, and an orbit passing near a centre crosses both within one step, so that
    the product would not change sign over it.  Each factor's sign change is found on
    its own (:mod:`reportgen.core.integrators.fictitious_time`).

    Attributes
    ----------
    factors : numba dispatcher
        ``factors(t, y, params, out)`` writes g_k(y) to ``out[k]``, k < count (the
        signature of ``rhs``, with the model's ``params``; like ``rhs``, it must not
        raise).
    count : int
        Number of factors (at least 1).
    """

    factors: Callable
    count: int = 1

    def __post_init__(self):
        if not 1 <= self.count <= MAX_SECTION_FACTORS:
            raise ValueError(f"count: expected 1 to {MAX_SECTION_FACTORS} factors, "
                             f"got {self.count!r}")


#: factors of a surface of section (a product of a few folds, see SurfaceOfSection)
MAX_SECTION_FACTORS = 4


#: a model whose size is set by its scene (a chain of n masses, FPUT's m pairs) runs
#: DOP853 on a driver of its own (``OdeModel.specialize``) up to this many components:
#: measured on small oscillations (ns per evaluation, shared driver -> specialized),
#: 4 components 48 -> 23, 6: 44 -> 31, 12: 69 -> 58; at 18 the shared one, then
#: loop-vectorized, was faster (90 -> 97), and the unrolled driver's compile grows with d
SPECIALIZE_UP_TO = 12


@dataclass(frozen=True)
class OdeModel:
    """A compiled first-order system and what it offers to integrators.

    Attributes
    ----------
    name : str
        Short name used in messages ("pendulum").
    columns : tuple of str
        Names of the state components, length d.
    rhs : numba dispatcher
        ``rhs(t, y, params, out)``.
    params : ndarray, shape (k,)
        Packed parameters passed to every compiled function.
    separable : Separable or None
        Present when H = T(p) + V(q) and y = (q, p).
    jac : numba dispatcher or None
        ``jac(t, y, params, out)`` with ``out`` of shape (d, d).
    stiff_hint : bool
        The scene knows the problem is stiff (widely separated time scales).
    specialize : bool
        DOP853 runs on a driver compiled for this model alone
        (:mod:`reportgen.core.integrators.specialized`): ~2x fewer ns per step on a
        small cheap system, ~4 s more compile once per cache.  ``rhs`` must then be a
        module-level ``njit(error_model="numpy")`` function.  Models whose size the scene
        sets ask for it up to :data:`SPECIALIZE_UP_TO` components.
    """

    name: str
    columns: tuple[str, ...]
    rhs: Callable
    params: np.ndarray
    separable: Separable | None = None
    jac: Callable | None = None
    stiff_hint: bool = False
    specialize: bool = False
    extra: dict = field(default_factory=dict)

    @property
    def dim(self) -> int:
        return len(self.columns)

    def f(self, t: float, y: np.ndarray) -> np.ndarray:
        """Right-hand side as a plain Python callable (for scipy and tests)."""
        out = np.empty(self.dim)
        self.rhs(float(t), np.asarray(y, dtype=np.float64), self.params, out)
        return out

    def jacobian(self, t: float, y: np.ndarray) -> np.ndarray | None:
        if self.jac is None:
            return None
        out = np.empty((self.dim, self.dim))
        self.jac(float(t), np.asarray(y, dtype=np.float64), self.params, out)
        return out
