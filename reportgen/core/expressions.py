"""Formulas from configs, parsed safely: Python's ``ast`` against an allow-list, to SymPy.

Config text is data, never code: nothing here calls ``eval``, ``exec``, ``sympify`` or
``parse_expr``.  A formula is parsed by :func:`ast.parse` in ``eval`` mode and its tree is
walked; only these nodes are turned into SymPy expressions:

* numbers (int and float literals, within :data:`MAX_LITERAL`);
* names: the symbols the caller declares (coordinates, momenta, t), named constants
  (``[params]``) and ``pi``, ``E``;
* ``+ - * / **`` and unary ``-`` / ``+``;
* calls of the functions in :data:`FUNCTIONS` with the right number of positional
  arguments.

Anything else -- attributes, subscripts, lambdas, strings, comprehensions, comparisons,
keyword arguments, dunder names, unknown functions, undefined names -- raises
:class:`ExpressionError` naming the offending piece and where it is in the formula.
Limits keep a formula from costing more than it is worth, checked on the tree before
SymPy sees it (so ``validate`` refuses exactly what ``run`` would): its length, its nesting
depth, its node count (:data:`MAX_NODES`), its total degree (:data:`MAX_DEGREE`: the
exponents of nested powers multiply, the degrees of a product's factors add, a sum takes
its largest term's, so ``x**64**64``, ``((x**8)**8)**8`` and ``(x + p_x + 1)**64`` are
refused), and powers of constants (``9**9**9`` is refused before SymPy tries to evaluate
it).  A constant part that is not a finite real number (``sqrt(-1)``, ``log(0)``, ``1e300**2``)
is refused too.  Names are compared as written: a name that NFKC normalization changes
(a full-width ``ｘ``, which Python would silently read as ``x``) is refused; see
:func:`name_problem` for the names a formula's own symbols may take.
"""

from __future__ import annotations

import ast
import keyword
import math
import re
import unicodedata
from collections.abc import Mapping
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import sympy

#: allowed functions: name -> (name of the SymPy function, number of arguments)
FUNCTIONS = {
    "sin": ("sin", 1), "cos": ("cos", 1), "tan": ("tan", 1), "asin": ("asin", 1),
    "acos": ("acos", 1), "atan": ("atan", 1), "atan2": ("atan2", 2), "sinh": ("sinh", 1),
    "cosh": ("cosh", 1), "tanh": ("tanh", 1), "exp": ("exp", 1), "log": ("log", 1),
    "sqrt": ("sqrt", 1), "abs": ("Abs", 1),
}
#: allowed constants: name -> name of the SymPy constant
CONSTANTS = {"pi": "pi", "E": "E"}
#: names a formula's own symbols (coordinates, constants, observables) may not take: time,
#: the functions and constants the parser knows, and SymPy's own one-letter constants and
#: infinities (``I``, ``oo``, ...), which would read as something else in derived formulas
RESERVED = frozenset({"t", *FUNCTIONS, *CONSTANTS, "I", "oo", "zoo", "nan", "inf", "S", "N",
                      "O", "Q"})

MAX_LENGTH = 2000  # characters of one formula
MAX_DEPTH = 60  # nesting of its tree
MAX_NODES = 400  # nodes of its tree (names, numbers, operators, calls)
MAX_DEGREE = 32  # total degree: nested exponents multiply, a product's factors add
MAX_LITERAL = 1e15  # largest number written in a formula
MAX_OBSERVABLES = 16  # observables of one system (each costs a Poisson bracket, simplified)
MAX_CONSTANTS = 32  # named constants of one system
MAX_CONSTANT_EXPONENT = 64  # |n| in c**n when both are constants

_WORD = re.compile(r"\w+")


def alias_problem(coordinates) -> str | None:
    """Why ``coordinates`` cannot name a system's coordinates together (None if they can):
    each coordinate q brings ``p_<q>`` and ``<q>_dot``, and these 3n names must differ
    (``["x", "p_x"]`` would make p_x both a coordinate and x's momentum)."""
    seen: dict[str, str] = {}
    for q in coordinates:
        for name, what in ((q, f"the coordinate {q!r}"), (f"p_{q}", f"the momentum of {q!r}"),
                           (f"{q}_dot", f"the velocity of {q!r}")):
            if name in seen:
                return f"{name!r} would be both {seen[name]} and {what}"
            seen[name] = what
    return None


def name_problem(name) -> str | None:
    """Why ``name`` cannot name a coordinate, constant or observable (None if it can): not
    an identifier, starting with _, a Python keyword, a reserved name, or a spelling that
    NFKC normalization changes (Python reads ``ｘ`` as ``x``)."""
    if not isinstance(name, str) or not name.isidentifier():
        return f"{name!r} is not an identifier"
    normal = unicodedata.normalize("NFKC", name)
    if normal != name:
        return (f"{name!r} is not in Unicode normal form NFKC (it would read as {normal!r}); "
                f"write {normal!r}")
    if name.startswith("_"):
        return f"{name!r} starts with _"
    if keyword.iskeyword(name) or keyword.issoftkeyword(name):
        return f"{name!r} is a Python keyword"
    if name in RESERVED:
        return f"{name!r} is reserved ({', '.join(sorted(RESERVED))})"
    return None


class ExpressionError(ValueError):
    """A formula outside the allow-list; the message names the piece and its column."""


_OPERATORS = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b,
              ast.Mult: lambda a, b: a * b, ast.Div: lambda a, b: a / b,
              ast.Pow: lambda a, b: a**b}
_WHAT = {
    ast.Attribute: "an attribute", ast.Subscript: "a subscript", ast.Lambda: "a lambda",
    ast.ListComp: "a comprehension", ast.SetComp: "a comprehension",
    ast.DictComp: "a comprehension", ast.GeneratorExp: "a comprehension",
    ast.Compare: "a comparison", ast.BoolOp: "a boolean operator", ast.IfExp: "an if",
    ast.List: "a list", ast.Tuple: "a tuple", ast.Dict: "a dict", ast.Set: "a set",
    ast.JoinedStr: "a string", ast.NamedExpr: "an assignment", ast.Starred: "a starred item",
}


def _tree(text: str) -> ast.AST:
    if not isinstance(text, str):
        raise ExpressionError(f"expected a formula as a string, got {type(text).__name__}")
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"formula longer than {MAX_LENGTH} characters ({len(text)})")
    if not text.strip():
        raise ExpressionError("empty formula")
    for match in _WORD.finditer(text):  # Python would NFKC-normalize names silently
        word = match.group()
        normal = unicodedata.normalize("NFKC", word)
        if normal != word:
            raise ExpressionError(f"{word!r} at column {match.start() + 1} is not in Unicode "
                                  f"normal form NFKC (it would read as {normal!r}); write "
                                  f"{normal!r}")
    # a formula may span lines (a TOML multi-line string): whitespace is only a separator
    text = " ".join(text.split())
    try:
        return ast.parse(text, mode="eval").body
    except SyntaxError as exc:
        where = f" at column {exc.offset}" if exc.offset else ""
        raise ExpressionError(f"not a formula{where}: {exc.msg}") from None


def parse_expression(text: str, symbols: Mapping[str, sympy.Symbol],
                     params: Mapping[str, float] | None = None) -> sympy.Expr:
    """The SymPy expression of ``text``.

    ``symbols``: the names that stay symbolic (coordinates, momenta, velocities, t);
    ``params``: named constants, substituted by their values (kept exact when they are
    whole numbers).  Raises :class:`ExpressionError` for anything outside the allow-list.
    """
    import sympy

    tree = _tree(text)
    names = {k: getattr(sympy, v) for k, v in CONSTANTS.items()}
    for name, value in (params or {}).items():
        names[name] = _number(value)
    clash = set(symbols) & set(names)
    if clash:
        raise ExpressionError(f"{', '.join(sorted(clash))}: both a symbol and a constant")
    names.update(symbols)
    _measure(tree)
    return _Builder(text, names).build(tree, 0)


def check_expression(text: str, names) -> set[str]:
    """The names of ``names`` that ``text`` uses; raises :class:`ExpressionError` if it is
    not a formula over ``names`` (and the constants).  The checks of
    :func:`parse_expression` that need no SymPy (so ``validate`` does not import it):
    syntax, the allow-list, names, arity, size and depth limits."""
    tree = _tree(text)
    known = dict.fromkeys(CONSTANTS) | dict.fromkeys(names)
    _measure(tree)
    _Builder(text, known, build=False).build(tree, 0)
    return {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)} & set(names)


def _number(value) -> sympy.Expr:
    import sympy

    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ExpressionError(f"constant {value!r} is not a number")
    if not math.isfinite(value):
        raise ExpressionError(f"constant {value!r} is not finite")
    if isinstance(value, int) or float(value).is_integer() and abs(value) < 2**53:
        return sympy.Integer(int(value))
    return sympy.Float(value)


_MATH = {"abs": abs, "atan2": math.atan2}


def _measure(tree: ast.AST) -> None:
    """Refuse a formula whose tree is too deep, has too many nodes or too high a total
    degree -- before SymPy sees it, in ``validate`` and ``run`` alike.

    Degree, counting every name but ``pi`` and ``E`` as degree 1: a number 0; a sum (or
    difference) its largest term's; a product or quotient the sum of its factors'; a power
    with a constant exponent n the base's times ceil(|n|), with any other exponent the sum
    of both; a function call its largest argument's.
    """
    nodes = 0

    def walk(node: ast.AST, depth: int) -> tuple[float, float | None]:
        """(degree, value if a constant)"""
        nonlocal nodes
        nodes += 1
        if depth > MAX_DEPTH:
            raise ExpressionError(f"formula nested deeper than {MAX_DEPTH}")
        if nodes > MAX_NODES:
            raise ExpressionError(f"formula larger than {MAX_NODES} nodes (names, numbers, "
                                  "operators and calls)")
        if isinstance(node, ast.Constant):
            value = node.value
            ok = isinstance(value, int | float) and not isinstance(value, bool)
            return 0.0, float(value) if ok and abs(value) <= MAX_LITERAL else None
        if isinstance(node, ast.Name):
            return (0.0, None) if node.id in CONSTANTS else (1.0, None)
        if isinstance(node, ast.UnaryOp):
            degree, value = walk(node.operand, depth + 1)
            return degree, (-value if value is not None and isinstance(node.op, ast.USub)
                            else value)
        if isinstance(node, ast.BinOp):
            (dl, vl), (dr, vr) = walk(node.left, depth + 1), walk(node.right, depth + 1)
            value = None
            if vl is not None and vr is not None and type(node.op) in _OPERATORS:
                try:
                    value = float(_OPERATORS[type(node.op)](vl, vr))
                except (ArithmeticError, ValueError, TypeError):
                    value = None
                if value is not None and not math.isfinite(value):
                    value = None
            if isinstance(node.op, ast.Add | ast.Sub):
                return max(dl, dr), value
            if isinstance(node.op, ast.Pow):
                degree = dl * max(1.0, math.ceil(abs(vr))) if vr is not None else dl + dr
            else:
                degree = dl + dr
            if degree > MAX_DEGREE:
                raise ExpressionError(
                    f"formula of total degree above {MAX_DEGREE} ({_degree_text(degree)}; "
                    f"nested exponents multiply, a product's factors add) at column "
                    f"{node.col_offset + 1}")
            return degree, value
        if isinstance(node, ast.Call):
            degrees = [walk(arg, depth + 1)[0] for arg in node.args]
            for keyword_ in node.keywords:
                walk(keyword_.value, depth + 1)
            return max(degrees, default=0.0), None
        for child in ast.iter_child_nodes(node):  # refused by the builder, with its reason
            walk(child, depth + 1)
        return 0.0, None

    walk(tree, 0)


def _degree_text(degree: float) -> str:
    return f"{degree:.0f}" if degree < 1e15 else f"{degree:.3g}"


def _not_real(sympy, value) -> bool:
    """Whether a SymPy number is not a finite real number (``I``, ``zoo``, ``oo``, nan)."""
    return bool(value.has(sympy.I, sympy.zoo, sympy.oo, sympy.nan)
                or value.is_extended_real is False or value.is_finite is False)


class _Builder:
    """Walks the tree; builds the SymPy expression, or with ``build=False`` only checks."""

    def __init__(self, text: str, names: Mapping[str, sympy.Expr], build: bool = True):
        self.text = text
        self.names = names
        self.building = build

    def fail(self, node: ast.AST, what: str) -> ExpressionError:
        col = getattr(node, "col_offset", None)
        piece = ast.get_source_segment(" ".join(self.text.split()), node) if col is not None else None
        at = f" at column {col + 1}" if col is not None else ""
        shown = f" {piece!r}" if piece else ""
        return ExpressionError(f"{what}{shown}{at} is not allowed in a formula")

    def _fold(self, node: ast.BinOp, left, right):
        """Check mode: a binary operation of two constants as a float (None otherwise),
        with the limits :meth:`build` applies to SymPy constants."""
        if left is None or right is None:
            return None
        if isinstance(node.op, ast.Pow) and abs(right) > MAX_CONSTANT_EXPONENT:
            raise self.fail(node, f"a power of constants with an exponent above "
                                  f"{MAX_CONSTANT_EXPONENT}")
        if isinstance(node.op, ast.Div) and right == 0:
            raise self.fail(node, "a division by zero")
        try:
            value = _OPERATORS[type(node.op)](left, right)
        except (OverflowError, ZeroDivisionError, ValueError):
            value = None
        if not (isinstance(value, float | int) and math.isfinite(value)):
            raise self.fail(node, "a constant that is not a finite real number")
        return float(value)

    def build(self, node: ast.AST, depth: int) -> sympy.Expr:
        if depth > MAX_DEPTH:
            raise ExpressionError(f"formula nested deeper than {MAX_DEPTH}")
        if isinstance(node, ast.Constant):
            value = node.value
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise self.fail(node, "a string" if isinstance(value, str) else "a constant")
            if abs(value) > MAX_LITERAL:
                raise self.fail(node, f"a number above {MAX_LITERAL:g}")
            if not self.building:
                return float(value)  # constants are folded, so that the limits apply
            import sympy

            return sympy.Integer(value) if isinstance(value, int) else sympy.Float(value)
        if isinstance(node, ast.Name):
            if node.id.startswith("_"):
                raise self.fail(node, "a name starting with _")
            if node.id not in self.names:
                known = ", ".join(sorted(self.names)) or "none"
                raise ExpressionError(f"undefined name {node.id!r} at column "
                                      f"{node.col_offset + 1} (known: {known})")
            return self.names[node.id]
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
            inner = self.build(node.operand, depth + 1)
            if not self.building:
                return None if inner is None else (-inner if isinstance(node.op, ast.USub)
                                                   else inner)
            return -inner if isinstance(node.op, ast.USub) else inner
        if isinstance(node, ast.BinOp) and type(node.op) in _OPERATORS:
            left = self.build(node.left, depth + 1)
            right = self.build(node.right, depth + 1)
            if not self.building:
                return self._fold(node, left, right)
            if isinstance(node.op, ast.Pow) and left.is_number and right.is_number:
                if not right.is_real or abs(float(right)) > MAX_CONSTANT_EXPONENT:
                    raise self.fail(node, f"a power of constants with an exponent above "
                                          f"{MAX_CONSTANT_EXPONENT}")
            if isinstance(node.op, ast.Div) and right.is_zero:
                raise self.fail(node, "a division by zero")
            value = _OPERATORS[type(node.op)](left, right)
            if left.is_number and right.is_number:
                import sympy

                if _not_real(sympy, value):
                    raise self.fail(node, "a constant that is not a finite real number")
            return value
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name):
                raise self.fail(node.func, "a call of something other than a function name")
            name = node.func.id
            if name not in FUNCTIONS:
                raise ExpressionError(
                    f"unknown function {name!r} at column {node.col_offset + 1} (allowed: "
                    f"{', '.join(sorted(FUNCTIONS))})")
            function, arity = FUNCTIONS[name]
            if node.keywords:
                raise self.fail(node.keywords[0].value, "a keyword argument")
            if len(node.args) != arity:
                raise ExpressionError(f"{name} takes {arity} argument"
                                      f"{'s' if arity > 1 else ''}, got {len(node.args)} at "
                                      f"column {node.col_offset + 1}")
            args = [self.build(arg, depth + 1) for arg in node.args]
            if not self.building:
                if any(a is None for a in args):
                    return None
                try:
                    value = _MATH.get(name, getattr(math, name))(*args)
                except (ArithmeticError, ValueError):
                    value = None
                if not (isinstance(value, float | int) and math.isfinite(value)):
                    raise self.fail(node, "a constant that is not a finite real number")
                return float(value)
            import sympy

            value = getattr(sympy, function)(*args)
            if value.is_number and _not_real(sympy, value):
                raise self.fail(node, "a constant that is not a finite real number")
            return value
        what = _WHAT.get(type(node), f"a {type(node).__name__}")
        if isinstance(node, ast.BinOp):
            what = f"the operator {type(node.op).__name__}"
        if isinstance(node, ast.UnaryOp):
            what = f"the operator {type(node.op).__name__}"
        raise self.fail(node, what)
