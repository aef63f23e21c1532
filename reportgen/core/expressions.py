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

import sympy

#: allowed functions: name -> (SymPy function, number of arguments)
FUNCTIONS = {
    "sin": (sympy.sin, 1), "cos": (sympy.cos, 1), "tan": (sympy.tan, 1),
    "asin": (sympy.asin, 1), "acos": (sympy.acos, 1), "atan": (sympy.atan, 1),
    "atan2": (sympy.atan2, 2), "sinh": (sympy.sinh, 1), "cosh": (sympy.cosh, 1),
    "tanh": (sympy.tanh, 1), "exp": (sympy.exp, 1), "log": (sympy.log, 1),
    "sqrt": (sympy.sqrt, 1), "abs": (sympy.Abs, 1),
}
CONSTANTS = {"pi": sympy.pi, "E": sympy.E}

MAX_LENGTH = 2000  # characters of one formula
MAX_DEPTH = 60  # nesting of its tree
MAX_LITERAL = 1e15  # largest number written in a formula
MAX_CONSTANT_EXPONENT = 64  # |n| in c**n when both are constants


class ExpressionError(ValueError):
    """A formula outside the allow-list; the message names the piece and its column."""


_OPERATORS = {ast.Add: sympy.Add, ast.Sub: lambda a, b: a - b, ast.Mult: sympy.Mul,
              ast.Div: lambda a, b: a / b, ast.Pow: sympy.Pow}
_WHAT = {
    ast.Attribute: "an attribute", ast.Subscript: "a subscript", ast.Lambda: "a lambda",
    ast.ListComp: "a comprehension", ast.SetComp: "a comprehension",
    ast.DictComp: "a comprehension", ast.GeneratorExp: "a comprehension",
    ast.Compare: "a comparison", ast.BoolOp: "a boolean operator", ast.IfExp: "an if",
    ast.List: "a list", ast.Tuple: "a tuple", ast.Dict: "a dict", ast.Set: "a set",
    ast.JoinedStr: "a string", ast.NamedExpr: "an assignment", ast.Starred: "a starred item",
}


def parse_expression(text: str, symbols: Mapping[str, sympy.Symbol],
                     params: Mapping[str, float] | None = None) -> sympy.Expr:
    """The SymPy expression of ``text``.

    ``symbols``: the names that stay symbolic (coordinates, momenta, velocities, t);
    ``params``: named constants, substituted by their values (kept exact when they are
    whole numbers).  Raises :class:`ExpressionError` for anything outside the allow-list.
    """
    if not isinstance(text, str):
        raise ExpressionError(f"expected a formula as a string, got {type(text).__name__}")
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"formula longer than {MAX_LENGTH} characters ({len(text)})")
    if not text.strip():
        raise ExpressionError("empty formula")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        where = f" at column {exc.offset}" if exc.offset else ""
        raise ExpressionError(f"not a formula{where}: {exc.msg}") from None
    names = {**{k: v for k, v in CONSTANTS.items()}}
    for name, value in (params or {}).items():
        names[name] = _number(value)
    clash = set(symbols) & set(names)
    if clash:
        raise ExpressionError(f"{', '.join(sorted(clash))}: both a symbol and a constant")
    names.update(symbols)
    return _Builder(text, names).build(tree.body, 0)


def _number(value) -> sympy.Expr:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ExpressionError(f"constant {value!r} is not a number")
    if not math.isfinite(value):
        raise ExpressionError(f"constant {value!r} is not finite")
    if isinstance(value, int) or float(value).is_integer() and abs(value) < 2**53:
        return sympy.Integer(int(value))
    return sympy.Float(value)


class _Builder:
    def __init__(self, text: str, names: Mapping[str, sympy.Expr]):
        self.text = text
        self.names = names

    def fail(self, node: ast.AST, what: str) -> ExpressionError:
        col = getattr(node, "col_offset", None)
        piece = ast.get_source_segment(self.text.strip(), node) if col is not None else None
        at = f" at column {col + 1}" if col is not None else ""
        shown = f" {piece!r}" if piece else ""
        return ExpressionError(f"{what}{shown}{at} is not allowed in a formula")

    def build(self, node: ast.AST, depth: int) -> sympy.Expr:
        if depth > MAX_DEPTH:
            raise ExpressionError(f"formula nested deeper than {MAX_DEPTH}")
        if isinstance(node, ast.Constant):
            value = node.value
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise self.fail(node, "a string" if isinstance(value, str) else "a constant")
            if abs(value) > MAX_LITERAL:
                raise self.fail(node, f"a number above {MAX_LITERAL:g}")
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
            return -inner if isinstance(node.op, ast.USub) else inner
        if isinstance(node, ast.BinOp) and type(node.op) in _OPERATORS:
            left = self.build(node.left, depth + 1)
            right = self.build(node.right, depth + 1)
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
            return function(*(self.build(arg, depth + 1) for arg in node.args))
        what = _WHAT.get(type(node), f"a {type(node).__name__}")
        if isinstance(node, ast.BinOp):
            what = f"the operator {type(node.op).__name__}"
        if isinstance(node, ast.UnaryOp):
            what = f"the operator {type(node.op).__name__}"
        raise self.fail(node, what)
