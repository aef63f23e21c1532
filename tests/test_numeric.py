"""reportgen.core.numeric: SymPy trees evaluated over arrays, without lambdify/eval/exec."""

import numpy as np
import pytest
import sympy

from reportgen.core import expressions, numeric

x, y, t = sympy.symbols("x y t", real=True)


def test_matches_hand_written_numpy_including_derivatives():
    expr = expressions.parse_expression(
        "x/sqrt(x**2 + y**2)**3 + atan2(y, x) + abs(x) + tan(x) - log(cosh(y)) + exp(-t)*pi",
        {"x": x, "y": y, "t": t})
    xs, ys, ts = np.linspace(0.1, 1.0, 7), np.linspace(-1.0, 1.0, 7), np.linspace(0, 2, 7)
    want = (xs / np.hypot(xs, ys) ** 3 + np.arctan2(ys, xs) + np.abs(xs) + np.tan(xs)
            - np.log(np.cosh(ys)) + np.exp(-ts) * np.pi)
    got = numeric.evaluate(expr, {x: xs, y: ys, t: ts})
    np.testing.assert_allclose(got, want, rtol=1e-14)
    # SymPy's derivatives bring sign, sec-like powers and atan2's rational form
    for var in (x, y):
        d = sympy.diff(expr, var)
        eps = 1e-6
        vals = {x: xs, y: ys, t: ts}
        plus = dict(vals)
        plus[var] = vals[var] + eps
        minus = dict(vals)
        minus[var] = vals[var] - eps
        fd = (numeric.evaluate(expr, plus) - numeric.evaluate(expr, minus)) / (2 * eps)
        np.testing.assert_allclose(numeric.evaluate(d, vals), fd, rtol=1e-6, atol=1e-6)


def test_constants_broadcast_and_shared_subtrees():
    assert float(numeric.evaluate(sympy.Integer(3) / 2, {})) == 1.5
    a, b = numeric.evaluate_many([sympy.sin(x) ** 2, sympy.sin(x) ** 2 + 1],
                                 {x: np.array([0.3, 0.4])})
    np.testing.assert_allclose(b - a, 1.0)


def test_unknown_nodes_and_missing_values_are_refused():
    with pytest.raises(numeric.UnsupportedExpression, match="gamma"):
        numeric.evaluate(sympy.gamma(x), {x: 1.0})
    with pytest.raises(KeyError, match="y"):
        numeric.evaluate(x + y, {x: 1.0})
