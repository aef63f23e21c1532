"""Formulas from configs: the allow-list parser (issue 14's groundwork).  Never eval."""

from __future__ import annotations

import math

import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from reportgen.core.expressions import ExpressionError, parse_expression

x, y, px, py, t = sympy.symbols("x y p_x p_y t", real=True)
SYMBOLS = {"x": x, "y": y, "p_x": px, "p_y": py, "t": t}


def parse(text, params=None):
    return parse_expression(text, SYMBOLS, params)


def test_kepler_hamiltonian_from_the_issue():
    H = parse("(p_x**2 + p_y**2)/2 - k/sqrt(x**2 + y**2)", {"k": 1.0})
    expected = (px**2 + py**2) / 2 - 1 / sympy.sqrt(x**2 + y**2)
    assert sympy.simplify(H - expected) == 0
    # Hamilton's equations come out of it symbolically: dx/dt = ∂H/∂p_x = p_x
    assert sympy.diff(H, px) == px


def test_numbers_functions_and_constants():
    expr = parse("2*pi*sin(x)**2 + atan2(y, x) - E**t + abs(-3) + 1.5e-3")
    value = float(expr.subs({x: 0.3, y: 0.4, t: 0.1}))
    assert value == pytest.approx(2 * math.pi * math.sin(0.3) ** 2 + math.atan2(0.4, 0.3)
                                  - math.e ** 0.1 + 3 + 1.5e-3, rel=1e-14)


def test_whole_number_params_stay_exact():
    assert parse("m*x**2/2", {"m": 2.0}) == x**2
    assert parse("g*x", {"g": 9.81}).coeff(x) == sympy.Float(9.81)


@pytest.mark.parametrize("text, named", [
    ("x.__class__", "an attribute"),
    ("().__class__.__bases__[0]", "a subscript"),
    ("x[0]", "a subscript"),
    ("lambda: 1", "a lambda"),
    ("'abc'", "a string"),
    ("[x for x in (1, 2)]", "a comprehension"),
    ("x < y", "a comparison"),
    ("x and y", "a boolean operator"),
    ("x if y else t", "an if"),
    ("(x, y)", "a tuple"),
    ("x // y", "the operator FloorDiv"),
    ("x % y", "the operator Mod"),
    ("~x", "the operator Invert"),
    ("sin(x=1)", "a keyword argument"),
    ("__import__('os')", "unknown function"),
    ("eval('1')", "unknown function"),
    ("sympify('x')", "unknown function"),
    ("open('f')", "unknown function"),
    ("f(x)", "unknown function 'f'"),
    ("(lambda: 1)()", "a call of something other than a function name"),
    ("_secret", "a name starting with _"),
    ("z + 1", "undefined name 'z'"),
    ("sin(x, y)", "sin takes 1 argument, got 2"),
    ("9**9**9", "a power of constants"),
    ("1e300", "a number above"),
    ("x/0", "a division by zero"),
    ("True + x", "a constant"),
    ("x +", "not a formula"),
    ("", "empty formula"),
    ("x" + "+x" * 1200, "longer than"),
    ("(" * 100 + "x" + ")" * 100 + "+" + "-" * 100 + "x", "nested deeper"),
])
def test_everything_else_is_refused_naming_the_piece(text, named):
    with pytest.raises(ExpressionError, match=None) as exc:
        parse(text)
    assert named in str(exc.value)


def test_a_param_may_not_shadow_a_symbol():
    with pytest.raises(ExpressionError, match="both a symbol and a constant"):
        parse("x", {"x": 1.0})


def test_non_numeric_params_refused():
    with pytest.raises(ExpressionError, match="not a number"):
        parse("k*x", {"k": "1"})
    with pytest.raises(ExpressionError, match="not finite"):
        parse("k*x", {"k": math.inf})


def test_the_parser_never_evaluates_python(monkeypatch):
    import builtins

    def refuse(*args, **kwargs):  # pragma: no cover - reaching it is the failure
        raise AssertionError("eval/exec called")

    monkeypatch.setattr(builtins, "eval", refuse)
    monkeypatch.setattr(builtins, "exec", refuse)
    monkeypatch.setattr(sympy, "sympify", refuse)
    assert parse("x**2 + sin(y)") == x**2 + sympy.sin(y)


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet="xy+-*/()0123456789.sinco_[]'\"lambda :=,<>", max_size=40))
def test_fuzz_only_expressions_or_expression_errors(text):
    """Whatever the text, the parser returns a SymPy expression or an ExpressionError."""
    try:
        result = parse(text)
    except ExpressionError:
        return
    assert isinstance(result, sympy.Basic)
