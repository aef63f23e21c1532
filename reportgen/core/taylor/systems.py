r"""A model's right-hand sides as SymPy expressions, the input of :mod:`.decompose`.

* A formula model (:func:`reportgen.core.formula.compiled_model`) carries its SymPy
  system in ``model.extra["formula_system"]``: its Hamilton (or reduced first-order)
  equations ``hamilton.rhs`` over ``state_symbols``, the constants replaced by the numbers
  in ``model.params``.
* A hand-written model (:mod:`reportgen.core.models`) goes through its heyoka translator
  (:mod:`reportgen.core.heyoka_systems`, one per compiled right-hand side, each checked
  against ``model.f`` by ``tests/test_heyoka_systems.py``), given :data:`SYMPY` -- a
  namespace with heyoka's few names (``sin``, ``make_vars``, ``time``, ...) spelled in
  SymPy -- instead of heyoka.

Parameters become numbers read now; the variables are :class:`sympy.Dummy` symbols, so
that no column name can meet the time's.
"""

from __future__ import annotations

from types import SimpleNamespace

import sympy

from .decompose import Unsupported


def _make_vars(*names):
    vs = [sympy.Dummy(str(n)) for n in names]
    return vs if len(vs) > 1 else vs[0]


#: heyoka's names used by the translators of :mod:`reportgen.core.heyoka_systems`, in SymPy
SYMPY = SimpleNamespace(
    sin=sympy.sin, cos=sympy.cos, tan=sympy.tan, sinh=sympy.sinh, cosh=sympy.cosh,
    exp=sympy.exp, log=sympy.log, sqrt=sympy.sqrt,
    make_vars=_make_vars, time=sympy.Dummy("t"),
    expression=lambda v: sympy.Float(float(v)),
    sum=lambda terms: sympy.Add(*terms),
)


def sympy_system(model) -> tuple[list[sympy.Expr], list[sympy.Symbol], sympy.Symbol]:
    """(right-hand sides, state symbols in ``model.columns`` order, time symbol).

    Raises :class:`~.decompose.Unsupported` when the model has no SymPy form here."""
    formula_system = model.extra.get("formula_system")
    if formula_system is not None:
        subs = {sym: sympy.Float(float(v)) for sym, v in
                zip(formula_system.param_symbols.values(), model.params, strict=True)}
        rhs = [e.xreplace(subs) if isinstance(e, sympy.Basic) else sympy.Float(float(e))
               for e in formula_system.hamilton.rhs]
        return rhs, list(formula_system.state_symbols), formula_system.space.t
    from .. import heyoka_systems

    reason = heyoka_systems.why_not(model)
    if reason:
        raise Unsupported(reason.replace("heyoka translation", "SymPy form"))
    pairs = heyoka_systems.system(SYMPY, model)
    return [f for _, f in pairs], [x for x, _ in pairs], SYMPY.time
