"""A mechanical system written as a formula, derived with SymPy and compiled with numba.

:func:`build_system` turns the text of ``[system]`` (coordinates and H or L),
``[observables]`` and ``[params]`` into SymPy expressions -- through the allow-list parser
of :mod:`reportgen.core.expressions`, never ``sympify`` -- and derives what the report
shows: Hamilton's equations, for L the Legendre transform (:mod:`.mechanics`), whether H
is separable, its cyclic coordinates.  Named constants stay symbols (``k``, ``m``), so the
derived formulas read as written and the compiled code does not change when a value does.

:func:`compiled_model` makes the right-hand side an :class:`~reportgen.core.model.OdeModel`
like every hand-written kind's:

* the derivatives are reduced with SymPy's common-subexpression elimination and printed
  by :class:`_Printer` into the source of a small module of ``numba.njit(cache=True)``
  functions (``rhs``, ``jac``, and ``drift``/``kick`` for a separable H);
* the printer knows only the node types the allow-list and differentiation produce, and
  every name it writes is its own: ``y[i]`` for the state, ``params[j]`` for the named
  constants, ``t``, temporaries ``x<n>``, ``math.<function>`` -- no text from the config
  reaches the module, only numbers (as ``repr`` of floats) and structure.  A test
  tokenizes generated modules and checks this;
* the module is written once per content into ``$XDG_CACHE_HOME/reportgen/formula``
  and imported from there, so numba caches its machine code on disk like any other model
  (a second run of the same system compiles nothing, and a changed constant only changes
  ``params``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
import sympy

from . import codegen, mechanics
from .expressions import (
    MAX_CONSTANTS,
    MAX_OBSERVABLES,
    ExpressionError,
    alias_problem,
    name_problem,
    parse_expression,
)

#: bump when the generated code changes
CODE_VERSION = "2"


class FormulaError(ValueError):
    """A formula system that cannot be built; ``key`` is the config key at fault."""

    def __init__(self, key: str, message: str):
        super().__init__(f"{key}: {message}")
        self.key = key
        self.detail = message


@dataclass(frozen=True)
class FormulaSystem:
    """Everything derived from the written system, symbolically."""

    space: mechanics.PhaseSpace
    params: dict[str, float]
    param_symbols: dict[str, sympy.Symbol]
    H: sympy.Expr  # in q, p, t (and the constants)
    L: sympy.Expr | None  # as written, in q, q_dot, t
    legendre: mechanics.Legendre | None
    hamilton: mechanics.HamiltonianSystem
    observables: dict[str, sympy.Expr] = field(default_factory=dict)  # in q, p, t
    #: L linear in the velocities, reduced (notes (3.36–3.38)): the state is q alone, H is
    #: the energy function V and ``hamilton.rhs`` the reduced q̇ = ω⁻¹(∇V + ∂a/∂t)
    first_order: mechanics.FirstOrder | None = None

    @property
    def n(self) -> int:
        return len(self.space.names)

    @property
    def columns(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.state_symbols)

    @property
    def state_symbols(self) -> tuple[sympy.Symbol, ...]:
        return self.space.q if self.first_order is not None else self.space.q + self.space.p

    @property
    def time_dependent(self) -> bool:
        if self.first_order is not None:  # a(q, t) moving makes V change too
            return self.space.t in self.L.free_symbols
        return self.space.t in self.H.free_symbols

    @property
    def separable(self) -> bool:
        """H = T(p) + V(q), with neither depending on t."""
        if self.time_dependent or self.first_order is not None:
            return False
        q, p = set(self.space.q), set(self.space.p)
        return (all(not (e.free_symbols & q) for e in self.hamilton.qdot)
                and all(not (e.free_symbols & p) for e in self.hamilton.pdot))

    def values(self, y: np.ndarray, t) -> dict[sympy.Symbol, object]:
        """Symbol -> values for :func:`reportgen.core.numeric.evaluate`: the state
        columns of ``y`` (N, 2n; N, n for a first-order L), ``t`` and the constants."""
        y = np.asarray(y, dtype=np.float64)
        out: dict[sympy.Symbol, object] = {s: y[..., i]
                                           for i, s in enumerate(self.state_symbols)}
        out[self.space.t] = t
        out.update({self.param_symbols[k]: v for k, v in self.params.items()})
        return out

    def param_array(self) -> np.ndarray:
        return np.array([self.params[k] for k in self.param_symbols], dtype=np.float64)

    def latex(self, expr: sympy.Expr) -> str:
        """``expr`` as mathtext-friendly LaTeX: ``x_dot`` as ẋ, ``p_x`` as p_x."""
        names = {}
        for name, q, p, v in zip(self.space.names, self.space.q, self.space.p,
                                 self.space.qdot, strict=True):
            base = sympy.latex(sympy.Symbol(name))
            names[q] = base
            names[p] = f"p_{{{base}}}"
            names[v] = rf"\dot{{{base}}}"
        return sympy.latex(expr, symbol_names=names, ln_notation=False,
                           inv_trig_style="full")


def _check_name(key: str, name: str) -> None:
    problem = name_problem(name)
    if problem is not None:
        raise FormulaError(key, f"not a usable name: {problem}")


def _check_real(key: str, expr: sympy.Expr) -> None:
    """A derived formula with a non-real or infinite constant in it (``log(0*x)``) would print
    ``inf`` or a complex number into the generated code: refused."""
    if expr.has(sympy.I, sympy.zoo, sympy.oo, sympy.nan):
        raise FormulaError(key, "has a part that is not a finite real number (such as "
                                "sqrt(-1), log(0) or 1/0)")


def build_system(coordinates, *, H: str | None = None, L: str | None = None,
                 observables: Mapping[str, str] | None = None,
                 params: Mapping[str, float] | None = None) -> FormulaSystem:
    """Parse and derive a system; :class:`FormulaError` names the config key at fault.

    Exactly one of ``H`` (in q, ``p_<q>``, t) and ``L`` (in q, ``<q>_dot``, t).  Observables
    may use q, ``p_<q>``, ``<q>_dot`` and t; velocities are replaced by q̇(q, p).
    """
    params = dict(params or {})
    coordinates = list(coordinates)
    for c in coordinates:
        _check_name("system.coordinates", c)
    problem = alias_problem(coordinates)
    if problem is not None:
        raise FormulaError("system.coordinates", problem)
    if len(params) > MAX_CONSTANTS:
        raise FormulaError("params", f"at most {MAX_CONSTANTS} named constants "
                                     f"(got {len(params)})")
    if len(observables or {}) > MAX_OBSERVABLES:
        raise FormulaError("observables", f"at most {MAX_OBSERVABLES} observables "
                                          f"(got {len(observables)})")
    try:
        space = mechanics.PhaseSpace.of(coordinates)
    except ValueError as exc:
        raise FormulaError("system.coordinates", str(exc)) from None
    state_names = {s.name for s in space.q + space.p + space.qdot}
    for name, value in params.items():
        _check_name(f"params.{name}", name)
        if name in state_names:
            raise FormulaError(f"params.{name}", "a constant may not share the name of a "
                                                 "coordinate, momentum or velocity")
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise FormulaError(f"params.{name}", f"expected a number, got {value!r}")
        if not np.isfinite(value):
            raise FormulaError(f"params.{name}", f"expected a finite number, got {value!r}")
    # constants stay symbols; positive ones are declared so (simpler square roots)
    param_symbols = {k: sympy.Symbol(k, real=True, positive=True) if v > 0
                     else sympy.Symbol(k, real=True) for k, v in params.items()}
    if (H is None) == (L is None):
        raise FormulaError("system", "give exactly one of H and L")

    def parse(key: str, text: str, symbols: Mapping[str, sympy.Symbol]) -> sympy.Expr:
        try:
            return parse_expression(text, {**symbols, **param_symbols})
        except ExpressionError as exc:
            raise FormulaError(key, str(exc)) from None

    legendre_result = reduced = None
    L_expr = None
    if H is not None:
        H_expr = parse("system.H", H, space.symbols_for_h())
        if H_expr.free_symbols & set(space.qdot):
            raise FormulaError("system.H", "H is a function of q and p: velocities "
                                           "(<q>_dot) belong in L")
    else:
        L_expr = parse("system.L", L, space.symbols_for_l())
        try:
            if mechanics.linear_in_velocities(space, L_expr):  # notes (3.36–3.38)
                reduced = mechanics.first_order(space, L_expr, param_symbols.values())
            else:
                legendre_result = mechanics.legendre(space, L_expr, param_symbols.values())
        except ValueError as exc:
            raise FormulaError("system.L", str(exc)) from None
        H_expr = legendre_result.H if reduced is None else reduced.V
    _check_real("system.H" if H is not None else "system.L", H_expr)
    if reduced is not None:
        for e in (*reduced.qdot, reduced.det):
            _check_real("system.L", e)
        # the reduced equations in place of Hamilton's: rhs = q̇ (no momenta in the state)
        hamilton = mechanics.HamiltonianSystem(space, H_expr, reduced.qdot, ())
    else:
        try:
            hamilton = mechanics.hamiltonian_system(space, H_expr, param_symbols.values())
        except ValueError as exc:
            raise FormulaError("system.H" if H is not None else "system.L", str(exc)) \
                from None
    velocities = (reduced.qdot if reduced is not None else hamilton.qdot
                  if legendre_result is None else legendre_result.velocities)
    to_qp = dict(zip(space.qdot, velocities, strict=True))
    if reduced is not None:  # p = ∂L/∂q̇ = a(q, t)
        to_qp.update(zip(space.p, reduced.a, strict=True))
    obs = {}
    for name, text in (observables or {}).items():
        key = f"observables.{name}"
        _check_name(key, name)
        if name in state_names or name in params or name == "H":
            raise FormulaError(key, "an observable may not share the name of a coordinate, "
                                    "momentum, velocity, constant or H")
        symbols = {**space.symbols_for_h(), **{v.name: v for v in space.qdot}}
        obs[name] = parse(key, text, symbols).subs(to_qp)
        _check_real(key, obs[name])
    return FormulaSystem(space, params, param_symbols, H_expr, L_expr, legendre_result,
                         hamilton, obs, reduced)


# ------------------------------------------------------------------ code generation
class _Printer:
    """SymPy expression -> Python source over ``math``, with our own names only."""

    _FUNCTIONS = {
        sympy.sin: "math.sin", sympy.cos: "math.cos", sympy.tan: "math.tan",
        sympy.asin: "math.asin", sympy.acos: "math.acos", sympy.atan: "math.atan",
        sympy.atan2: "math.atan2", sympy.sinh: "math.sinh", sympy.cosh: "math.cosh",
        sympy.tanh: "math.tanh", sympy.exp: "math.exp", sympy.log: "math.log",
        sympy.Abs: "abs", sympy.asinh: "math.asinh", sympy.acosh: "math.acosh",
        sympy.atanh: "math.atanh",
    }

    def __init__(self, names: Mapping[sympy.Symbol, str]):
        self.names = names

    def __call__(self, node) -> str:
        if node.is_Symbol:
            return self.names[node]
        if node.is_Number or node in (sympy.pi, sympy.E):
            value = float(node)
            return repr(value) if value >= 0 else f"({value!r})"
        args = node.args
        if node.is_Add:
            return "(" + " + ".join(self(a) for a in args) + ")"
        if node.is_Mul:
            return "(" + " * ".join(self(a) for a in args) + ")"
        if node.is_Pow:
            base, e = self(args[0]), args[1]
            if e == sympy.S.Half:
                return f"math.sqrt({base})"
            if e == -sympy.S.Half:
                return f"(1.0 / math.sqrt({base}))"
            if e.is_Integer:
                n = int(e)
                if n < 0:
                    return f"(1.0 / {base} ** {-n})" if n != -1 else f"(1.0 / {base})"
                return f"({base} ** {n})"
            if e.is_Rational and e.q == 2:  # x**(3/2) = x * sqrt(x)
                n = int(e.p)
                root = f"math.sqrt({base})"
                if n > 0:
                    return f"({root} ** {n})"
                return f"(1.0 / {root} ** {-n})"
            return f"({base} ** {self(e)})"
        if node.func == sympy.sign:
            x = self(args[0])
            return f"(0.0 if {x} == 0.0 else math.copysign(1.0, {x}))"
        if node.func == sympy.DiracDelta:  # d sign(x)/dx: zero but at x = 0
            return "0.0"
        if node.func == sympy.sec:
            return f"(1.0 / math.cos({self(args[0])}))"
        if node.func == sympy.csc:
            return f"(1.0 / math.sin({self(args[0])}))"
        if node.func == sympy.cot:
            return f"(1.0 / math.tan({self(args[0])}))"
        func = self._FUNCTIONS.get(node.func)
        if func is None:
            raise ValueError(f"cannot compile {node.func.__name__} (in {node})")
        return f"{func}(" + ", ".join(self(a) for a in args) + ")"


def _function_source(name: str, signature: str, outputs: list[tuple[str, sympy.Expr]],
                     names: Mapping[sympy.Symbol, str], optimizations="basic") -> str:
    """``def name(signature)`` assigning each output (target text, expression) after CSE."""
    exprs = [e for _, e in outputs]
    temps = sympy.numbered_symbols("x")
    replacements, reduced = sympy.cse(exprs, symbols=temps, optimizations=optimizations)
    local = dict(names)
    lines = ['@numba.njit(cache=True, error_model="numpy")', f"def {name}({signature}):"]
    printer = _Printer(local)
    for sym, expr in replacements:
        text = printer(expr)
        local[sym] = sym.name
        lines.append(f"    {sym.name} = {text}")
    for (target, _), expr in zip(outputs, reduced, strict=True):
        lines.append(f"    {target} = {printer(expr)}")
    if len(lines) == 2:
        lines.append("    pass")
    # the C callback's body: only a call, so the callback links the code compiled above
    # instead of compiling the whole body again (kernels.wrap_for_callback)
    lines += ["", "", f"def {name}_callback({signature}):", f"    {name}({signature})"]
    return "\n".join(lines) + "\n"


def module_source(system: FormulaSystem) -> str:
    """The generated module of ``system``'s compiled functions."""
    space = system.space
    params = {s: f"params[{j}]" for j, s in enumerate(system.param_symbols.values())}
    state = {s: f"y[{i}]" for i, s in enumerate(system.state_symbols)}
    base = {**state, **params, space.t: "t"}
    rhs = system.hamilton.rhs
    parts = ['"""Generated by reportgen.core.formula; do not edit."""', "import math", "",
             "import numba", "", ""]
    parts.append(_function_source("rhs", "t, y, params, out",
                                  [(f"out[{i}]", e) for i, e in enumerate(rhs)], base))
    jac = [(f"out[{i}, {j}]", sympy.diff(e, s)) for i, e in enumerate(rhs)
           for j, s in enumerate(system.state_symbols)]
    # the Jacobian without CSE's "basic" optimizations: 20x cheaper to reduce, rarely used
    parts += ["", _function_source("jac", "t, y, params, out", jac, base, optimizations=None)]
    if system.separable:
        drift_names = {**params, **{s: f"p[{i}]" for i, s in enumerate(space.p)}}
        kick_names = {**params, **{s: f"q[{i}]" for i, s in enumerate(space.q)}}
        parts += ["", _function_source("drift", "p, params, out",
                                       [(f"out[{i}]", e) for i, e in
                                        enumerate(system.hamilton.qdot)], drift_names)]
        parts += ["", _function_source("kick", "q, params, out",
                                       [(f"out[{i}]", e) for i, e in
                                        enumerate(system.hamilton.pdot)], kick_names)]
    return "\n".join(parts)


def load_module(source: str):
    """Import the generated ``source`` (:func:`reportgen.core.codegen.load_module`: the
    code store's, by default a file under ``$XDG_CACHE_HOME/reportgen/formula``)."""
    return codegen.load_module(source, "formula", CODE_VERSION)


#: the directions a surface of section may be crossed in (see :func:`section_factors`)
SECTION_DIRECTIONS = ("up", "down", "both")


def section_factors(system: FormulaSystem, column: int, value: float,
                    direction: str) -> list[sympy.Expr]:
    """The factors g_k of the surface of section ``y[column] = value`` as
    :class:`~reportgen.core.model.SurfaceOfSection` takes them: their product crosses zero
    upward along the run exactly at the crossings counted.

    * ``"up"``: g = y − value; ``"down"``: g = value − y;
    * ``"both"``: (y − value, ẏ) with ẏ from Hamilton's equations.  At a crossing of the
      surface ẏ has the sign of the crossing, so the product rises through zero whichever
      way y crosses; a turning point of y (ẏ = 0) with y above the surface at a minimum, or
      below it at a maximum, rises through zero too: those rows have y ≠ value and are
      told apart by the caller (:func:`section_rows`).
    """
    if direction not in SECTION_DIRECTIONS:
        raise ValueError(f"direction {direction!r}: expected one of "
                         f"{', '.join(SECTION_DIRECTIONS)}")
    if not 0 <= column < len(system.columns):
        raise ValueError(f"column {column!r}: expected 0 to {len(system.columns) - 1}")
    if not np.isfinite(value):
        raise ValueError(f"value {value!r}: expected a finite number")
    y = system.state_symbols[column]
    # the value as the float it is (53 bits), printed back by repr: no config text
    level = sympy.Float(float(value), precision=53)
    g = y - level if direction != "down" else level - y
    return [g] if direction != "both" else [g, system.hamilton.rhs[column]]


def section_source(system: FormulaSystem, column: int, value: float, direction: str) -> str:
    """The generated module of the section's factors: ``section(t, y, params, out)``."""
    space = system.space
    params = {s: f"params[{j}]" for j, s in enumerate(system.param_symbols.values())}
    state = {s: f"y[{i}]" for i, s in enumerate(system.state_symbols)}
    factors = section_factors(system, column, value, direction)
    return "\n".join(['"""Generated by reportgen.core.formula; do not edit."""', "import math",
                      "", "import numba", "", "",
                      _function_source("section", "t, y, params, out",
                                       [(f"out[{k}]", g) for k, g in enumerate(factors)],
                                       {**state, **params, space.t: "t"})])


def compiled_section(system: FormulaSystem, column: int, value: float, direction: str):
    """The :class:`~reportgen.core.model.SurfaceOfSection` ``y[column] = value`` crossed in
    ``direction`` (:func:`section_factors`), compiled like the model's right-hand side, for
    :func:`reportgen.core.integrators.solve_fictitious_time` to locate on the steps."""
    from .integrators.kernels import wrap_for_callback
    from .model import SurfaceOfSection

    module = load_module(section_source(system, column, value, direction))
    wrap_for_callback(module.section, module.section_callback)
    return SurfaceOfSection(factors=module.section, count=2 if direction == "both" else 1)


def section_rows(crossings: np.ndarray, column: int, value: float, direction: str,
                 slope: np.ndarray | None = None, sizes: tuple[float, float] = (1.0, 1.0)
                 ) -> np.ndarray:
    """The rows (t, state) of ``crossings`` located with :func:`compiled_section` that are
    crossings of the surface: all of them but for ``"both"``, where a turning point of
    y = ``state[:, column]`` (a root of the second factor ẏ; ``slope`` is ẏ at the rows) is
    dropped.  ``sizes`` = (the largest |y − value|, the largest |ẏ|) along the run: a row is
    a crossing when |y − value| is the smaller of the two factors, each relative to its
    size (a crossing leaves |y − value| at rounding level, a turning point |ẏ|)."""
    crossings = np.asarray(crossings, dtype=np.float64)
    if direction != "both" or not len(crossings):
        return crossings
    if slope is None:
        raise ValueError("slope: the factor ẏ at the rows is needed for direction 'both'")
    tiny = np.finfo(float).tiny
    gap = np.abs(crossings[:, 1 + column] - value) / max(float(sizes[0]), tiny)
    rate = np.abs(np.asarray(slope, dtype=np.float64)) / max(float(sizes[1]), tiny)
    return crossings[gap <= rate]


def compiled_model(system: FormulaSystem, name: str = "formula"):
    """The :class:`~reportgen.core.model.OdeModel` of ``system`` (state: q then p).

    ``extra["formula_system"]`` is ``system`` itself: the symbolic right-hand side, for what
    needs the equations rather than compiled code (:mod:`reportgen.core.heyoka_systems`)."""
    from .integrators.kernels import wrap_for_callback
    from .model import OdeModel, Separable

    module = load_module(module_source(system))
    for fname in ("rhs", "jac", "drift", "kick"):
        if hasattr(module, fname):
            wrap_for_callback(getattr(module, fname), getattr(module, f"{fname}_callback"))
    separable = (Separable(n=system.n, drift=module.drift, kick=module.kick)
                 if system.separable else None)
    return OdeModel(name=name, columns=system.columns, rhs=module.rhs,
                    params=system.param_array(), separable=separable, jac=module.jac,
                    extra={"formula_system": system})
