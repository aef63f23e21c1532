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
Limits keep a formula from costing more than it is worth: its length, its nesting depth,
and powers of constants (``9**9**9`` is refused before SymPy tries to evaluate it).
"""

from __future__ import annotations

import ast
import math
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
#: names a formula's own symbols (coordinates, constants, observables) may not take
RESERVED = frozenset({"t", *FUNCTIONS, *CONSTANTS})

MAX_LENGTH = 2000  # characters of one formula
MAX_DEPTH = 60  # nesting of its tree
MAX_LITERAL = 1e15  # largest number written in a formula
MAX_CONSTANT_EXPONENT = 64  # |n| in c**n when both are constants


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
    return _Builder(text, names).build(tree, 0)


def check_expression(text: str, names) -> set[str]:
    """The names of ``names`` that ``text`` uses; raises :class:`ExpressionError` if it is
    not a formula over ``names`` (and the constants).  The checks of
    :func:`parse_expression` that need no SymPy (so ``validate`` does not import it):
    syntax, the allow-list, names, arity, size and depth limits."""
    tree = _tree(text)
    known = dict.fromkeys(CONSTANTS) | dict.fromkeys(names)
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
            return None
        return value if isinstance(value, float) and math.isfinite(value) else None

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
            return _OPERATORS[type(node.op)](left, right)
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
                return None
            import sympy

            return getattr(sympy, function)(*args)
        what = _WHAT.get(type(node), f"a {type(node).__name__}")
        if isinstance(node, ast.BinOp):
            what = f"the operator {type(node.op).__name__}"
        if isinstance(node, ast.UnaryOp):
            what = f"the operator {type(node.op).__name__}"
        raise self.fail(node, what)
