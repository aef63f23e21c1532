r"""Our adaptive Taylor-series integrator: recurrences generated from SymPy, run in numba.

A Taylor method advances x(t) by its Taylor polynomial of order p, whose coefficients
come from the right-hand side's by automatic differentiation (Jorba & Zou 2005, "A
software package for the numerical integration of ODEs by means of high-order Taylor
methods", Experimental Math. 14; Hairer–Nørsett–Wanner I §I.8).  Here:

1. :mod:`.systems`: the model's right-hand sides as SymPy expressions;
2. :mod:`.decompose`: those as elementary operations (+, ×, ÷, powers, √, sin/cos,
   sinh/cosh, exp, log, |·|), each with its coefficient recurrence, common
   subexpressions shared (SymPy's cse first);
3. :mod:`.codegen`: numba modules (written through
   :func:`reportgen.core.codegen.load_module`, so numba's disk cache serves later
   processes): per order, the coefficients unrolled -- every coefficient a local, every
   recurrence weight a number -- and the whole run (steps, step sizes, dense output) in
   one compiled call; a system too big to unroll (:data:`MAX_UNROLLED_TERMS`) runs one
   looped module for every order instead.

The order and the step follow Jorba & Zou 2005 §3 as heyoka does: one tolerance ``tol``,
absolute where |x|∞ < 1 and relative above; p = ⌈−ln(tol)/2 + 1⌉ (:func:`order_for_tol`)
and h = ρ_m e⁻² e^(−0.7/(p−1)), ρ_m = min over the last two orders of
(max(1, |x|∞)/|x^[k]|∞)^(1/k).

Parameters are numbers in the generated code (read when the model is first built, as
heyoka's translation does): a model with other parameter values is another module.
Compiling costs ~1 s (pendulum) to ~10 s (three bodies at order 16) per order, once:
numba's disk cache serves later processes in milliseconds.

Public: :func:`taylor_run` (one run), :func:`build` (a model's system, cached per model
in this process; its modules compiled per order on first use), :func:`order_for_tol`,
:func:`why_not`, :class:`Unsupported`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from types import ModuleType

import numpy as np

from .decompose import Decomposition, Unsupported, decompose

__all__ = ["MAX_UNROLLED_TERMS", "TaylorSystem", "Unsupported", "build", "order_for_tol",
           "taylor_run", "unrolled_terms", "why_not"]


def order_for_tol(tol: float) -> int:
    """Jorba & Zou 2005 §3.2.1: p = ⌈−ln(tol)/2 + 1⌉ (at least 2)."""
    if not (tol > 0 and math.isfinite(tol)):
        raise ValueError(f"tol: expected a positive finite tolerance, got {tol!r}")
    return max(2, math.ceil(-math.log(tol) / 2.0 + 1.0))


#: the largest unrolled module (estimated products, :func:`unrolled_terms`); bigger
#: systems or orders run the looped module (one for every order; ~1.7x slower per step)
MAX_UNROLLED_TERMS = 6000


def unrolled_terms(dec: Decomposition, order: int) -> int:
    """About how many products the unrolled coefficients of ``dec`` to ``order`` take."""
    conv = {"mul": 1.0, "sqr": 0.5, "div": 1.0, "pow": 1.0, "sqrt": 0.5, "sincos": 2.0,
            "sinhcosh": 2.0, "exp": 1.0, "log": 1.0}
    per_order = sum(conv.get(op.kind, 0.0) for op in dec.ops)
    linear = sum(len(op.args) for op in dec.ops if op.kind == "lin") + dec.n_state
    return int(per_order * order * (order + 1) / 2 + linear * order)


def _codes() -> dict[str, int]:
    from ..integrators.status import Status

    return {"OK": Status.OK.code, "NONFINITE": Status.NONFINITE.code,
            "STEP_UNDERFLOW": Status.STEP_UNDERFLOW.code, "MAX_STEPS": Status.MAX_STEPS.code}


@dataclass
class TaylorSystem:
    """A model's Taylor system: its operations and, per order, its compiled module
    (unrolled for that order, or the looped one, key None, for every order)."""

    decomposition: Decomposition
    modules: dict[int | None, ModuleType] = field(default_factory=dict)

    def module(self, order: int) -> tuple[ModuleType, float]:
        """(the module that runs ``order``, seconds spent generating and compiling it now,
        or loading numba's disk cache: 0 when loaded before in this process)."""
        dec = self.decomposition
        key = order if unrolled_terms(dec, order) <= MAX_UNROLLED_TERMS else None
        hit = self.modules.get(key)
        if hit is not None:
            return hit, 0.0
        from ..codegen import load_module
        from .codegen import CODE_VERSION, module_source, unrolled_source

        start = time.perf_counter()
        source = (unrolled_source(dec, order, _codes()) if key is not None
                  else module_source(dec, _codes()))
        module = load_module(source, "taylor", CODE_VERSION)
        # compile (or load from numba's cache) with the argument types of every run
        module.run(np.zeros(1), np.zeros(dec.n_state), order,
                   np.empty((1, dec.n_state)), 1, np.zeros(2), 1.0)
        self.modules[key] = module
        return module, time.perf_counter() - start


#: built systems per model (id, with the model kept so an id is never reused)
_BUILT: dict[int, tuple[object, TaylorSystem]] = {}
_MAX_BUILT = 64


def why_not(model) -> str:
    """Why :func:`build` cannot compile ``model`` ("" when it can)."""
    try:
        build(model)
    except Unsupported as exc:
        return str(exc)
    return ""


def _decomposition(model) -> Decomposition:
    from .systems import sympy_system

    rhs, states, t = sympy_system(model)
    return decompose(rhs, states, t)


def build(model) -> tuple[TaylorSystem, float]:
    """(``model``'s Taylor system, seconds spent decomposing it now: 0 when built before
    in this process).  Its modules are compiled per order on first use
    (:meth:`TaylorSystem.module`)."""
    hit = _BUILT.get(id(model))
    if hit is not None and hit[0] is model:
        return hit[1], 0.0
    start = time.perf_counter()
    system = TaylorSystem(_decomposition(model))
    if len(_BUILT) >= _MAX_BUILT:
        _BUILT.clear()
    _BUILT[id(model)] = (model, system)
    return system, time.perf_counter() - start


def taylor_run(system: TaylorSystem, y0, t_eval, tol: float, max_steps: int = 10_000_000,
               order: int | None = None, safety: float = 1.0):
    """One run: (Y (N, d) with NaN after a failure, Status code, accepted steps, last
    time reached, wall seconds, compile seconds spent now)."""
    y0 = np.ascontiguousarray(y0, dtype=np.float64)
    t_eval = np.ascontiguousarray(t_eval, dtype=np.float64)
    p = order_for_tol(tol) if order is None else max(2, int(order))
    module, compile_s = system.module(p)
    Y = np.full((t_eval.size, y0.size), np.nan)
    info = np.zeros(2)
    start = time.perf_counter()
    code = module.run(t_eval, y0, p, Y, int(max_steps), info, float(safety))
    wall = time.perf_counter() - start
    return Y, int(code), int(info[0]), float(info[1]), wall, compile_s
