r"""A system's right-hand sides as a list of elementary operations (Jorba & Zou 2005 §2).

The Taylor coefficients of a solution come from the coefficients of the functions in
its right-hand side, and those follow, order by order, from a few recurrences, one per
elementary operation (Jorba & Zou 2005, "A software package for the numerical
integration of ODEs by means of high-order Taylor methods", Experimental Math. 14, §2.2;
Hairer–Nørsett–Wanner I §I.8).  :func:`decompose` writes each SymPy right-hand side as
such operations, each reading rows of earlier ones; a subexpression met twice is one
operation (the rows are keyed by the operation and its operands).

Rows hold series: row ``i < n`` the state variable ``i``, then the time (when the system
uses it), then one row per operation (two for a sine/cosine or sinh/cosh pair, computed
together).  The operations, with c = the row written, a, b the operand rows:

=========  ==========================================================================
``lin``    c = k0 + Σ w_i a_i (the constant k0 enters the order-0 coefficient only)
``mul``    c = s a b;  ``sqr`` c = s a²
``div``    c = s a / b, or c = s / b (no numerator row)
``pow``    c = a^α (α a float that is not a small integer)
``sqrt``   c = √a
``sincos`` (sin a, cos a);  ``sinhcosh`` (sinh a, cosh a)
``exp``    c = exp a;  ``log`` c = log a
``abs``    c = |a| (= sign(a₀) a in the step: the generated code's ``abs``)
``sign``   c = sign a₀ (a constant series)
=========  ==========================================================================

Only SymPy trees built by our own code arrive here (a formula model's Hamilton
equations, the hand-written models' translations): nothing here parses text.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy


class Unsupported(ValueError):
    """A right-hand side uses a function without a recurrence here."""


@dataclass(frozen=True)
class Op:
    """One elementary operation: ``kind`` reads ``args`` (rows), writes ``out`` (rows)."""

    kind: str
    args: tuple[int, ...]
    consts: tuple[float, ...]
    out: tuple[int, ...]


@dataclass
class Decomposition:
    """The operations of a system, in an order where every operand comes first.

    ``outputs[i]`` is the row of the right-hand side of state ``i``, or a float when that
    right-hand side is a constant.  ``time_row`` is the row of t (None when unused).
    """

    n_state: int
    ops: list[Op] = field(default_factory=list)
    outputs: list[int | float] = field(default_factory=list)
    time_row: int | None = None
    n_rows: int = 0


#: the largest positive integer power written as products (beyond: the pow recurrence)
_MAX_PRODUCT_POWER = 8


class _Builder:
    def __init__(self, states, time):
        self.n = len(states)
        self.rows = {s: i for i, s in enumerate(states)}
        self.time = time
        self.dec = Decomposition(n_state=self.n)
        self.n_rows = self.n
        self.memo: dict[tuple, tuple[int, ...]] = {}
        self.expr_memo: dict[sympy.Expr, int | float] = {}

    # ------------------------------------------------------------------ operations
    def op(self, kind: str, args: tuple[int, ...], consts: tuple[float, ...] = (),
           width: int = 1) -> tuple[int, ...]:
        key = (kind, args, consts)
        hit = self.memo.get(key)
        if hit is not None:
            return hit
        out = tuple(range(self.n_rows, self.n_rows + width))
        self.n_rows += width
        self.dec.ops.append(Op(kind, args, consts, out))
        self.memo[key] = out
        return out

    def time_row(self) -> int:
        if self.dec.time_row is None:
            self.dec.time_row = self.n_rows
            self.n_rows += 1
        return self.dec.time_row

    def scale(self, s: float, a: int | float) -> int | float:
        if isinstance(a, float):
            return s * a
        if s == 1.0:
            return a
        if s == 0.0:
            return 0.0
        return self.op("lin", (a,), (0.0, s))[0]

    def product(self, factors: list[int], s: float = 1.0) -> int | None:
        """s Π factors (rows) as a chain of mul/sqr, the factor s in the last operation
        (a ``lin`` when there is none); None for no factor."""
        if not factors:
            return None
        counts: dict[int, int] = {}
        for f in factors:
            counts[f] = counts.get(f, 0) + 1
        items = sorted(counts.items())
        parts = [self.int_power(row, m) for row, m in items[:-1]]
        row, m = items[-1]
        if not parts:
            if m == 1:
                return self.scale(s, row)
            return self.int_power(row, m, s)
        parts.append(self.int_power(row, m))
        out = parts[0]
        for k, p in enumerate(parts[1:], start=2):
            scale = s if k == len(parts) else 1.0
            out = self.op("mul", tuple(sorted((out, p))), (scale,))[0]
        return out

    def int_power(self, row: int, m: int, s: float = 1.0) -> int:
        """s row^m, m ≥ 1, by squarings and products (s in the last one; m = 1 needs
        s = 1)."""
        if m == 1:
            return row
        half = self.int_power(row, m // 2)
        if m % 2:
            sq = self.op("sqr", (half,), (1.0,))[0]
            return self.op("mul", tuple(sorted((sq, row))), (s,))[0]
        return self.op("sqr", (half,), (s,))[0]

    # ------------------------------------------------------------------ expressions
    def expr(self, e) -> int | float:
        """The row of ``e``, or its value when it is a constant."""
        hit = self.expr_memo.get(e)
        if hit is None:
            hit = self._expr(e)
            self.expr_memo[e] = hit
        return hit

    def _expr(self, e) -> int | float:
        if e.is_Number or isinstance(e, sympy.NumberSymbol):
            return float(e)
        if e.is_Symbol:
            if e in self.rows:
                return self.rows[e]
            if e == self.time:
                return self.time_row()
            raise Unsupported(f"the symbol {e} is neither a state variable nor the time")
        if e.is_Add:
            return self.add(e)
        if e.is_Mul:
            return self.mul(e)
        if e.is_Pow:
            return self.pow(e)
        return self.function(e)

    def add(self, e) -> int | float:
        k0 = 0.0
        terms: dict[int, float] = {}
        for arg in e.args:
            coef, rest = arg.as_coeff_Mul()
            v = self.expr(rest)
            if isinstance(v, float):
                k0 += float(coef) * v
            else:
                terms[v] = terms.get(v, 0.0) + float(coef)
        terms = {r: w for r, w in terms.items() if w != 0.0}
        if not terms:
            return k0
        if k0 == 0.0 and len(terms) == 1:
            ((r, w),) = terms.items()
            return self.scale(w, r)
        rows = tuple(sorted(terms))
        return self.op("lin", rows, (k0, *(terms[r] for r in rows)))[0]

    def mul(self, e) -> int | float:
        coef, factors = e.as_coeff_mul()
        s = float(coef)
        num: list[int] = []
        den: list[int] = []
        for f in factors:
            if f.is_Pow and f.exp.is_Number and float(f.exp) < 0 and \
                    float(f.exp) == int(f.exp) and -int(f.exp) <= _MAX_PRODUCT_POWER:
                v = self.expr(f.base)
                if isinstance(v, float):
                    s *= v ** float(f.exp)
                else:
                    den += [v] * (-int(f.exp))
                continue
            v = self.expr(f)
            if isinstance(v, float):
                s *= v
            else:
                num.append(v)
        if s == 0.0:
            return 0.0
        if not den:
            return s if not num else self.product(num, s)
        n_row, d_row = self.product(num), self.product(den)
        if n_row is None:
            return self.op("div", (d_row,), (s,))[0]
        return self.op("div", (n_row, d_row), (s,))[0]

    def pow(self, e) -> int | float:
        base, ex = e.args
        if not ex.is_Number:
            if ex.free_symbols:  # b^g = exp(g log b)
                return self.expr(sympy.exp(ex * sympy.log(base), evaluate=False))
            ex = sympy.Float(float(ex))
        alpha = float(ex)
        b = self.expr(base)
        if isinstance(b, float):
            return b ** alpha
        if alpha == int(alpha) and abs(alpha) <= _MAX_PRODUCT_POWER:
            m = int(alpha)
            if m == 0:
                return 1.0
            if m > 0:
                return self.int_power(b, m)
            return self.op("div", (self.int_power(b, -m),), (1.0,))[0]
        if alpha == 0.5:
            return self.op("sqrt", (b,))[0]
        return self.op("pow", (b,), (alpha,))[0]

    def function(self, e) -> int | float:
        f = e.func
        if f is sympy.DiracDelta:  # the generated code's value: 0 (d sign/dx off x = 0)
            return 0.0
        args = [self.expr(a) for a in e.args]
        if len(args) != 1:
            raise Unsupported(f"no Taylor recurrence for {f.__name__}")
        (a,) = args
        if isinstance(a, float):  # a constant argument: its value, as the code prints it
            return float(e.func(sympy.Float(a)).evalf(17))
        if f in (sympy.sin, sympy.cos, sympy.tan, sympy.sec, sympy.csc, sympy.cot):
            s, c = self.op("sincos", (a,), (), width=2)
            if f is sympy.sin:
                return s
            if f is sympy.cos:
                return c
            num, den = {sympy.tan: ((s,), c), sympy.sec: ((), c), sympy.csc: ((), s),
                        sympy.cot: ((c,), s)}[f]
            return self.op("div", (*num, den), (1.0,))[0]
        if f in (sympy.sinh, sympy.cosh, sympy.tanh):
            s, c = self.op("sinhcosh", (a,), (), width=2)
            if f is sympy.tanh:
                return self.op("div", (s, c), (1.0,))[0]
            return s if f is sympy.sinh else c
        simple = {sympy.exp: "exp", sympy.log: "log", sympy.Abs: "abs", sympy.sign: "sign"}
        if f in simple:
            return self.op(simple[f], (a,))[0]
        raise Unsupported(f"no Taylor recurrence for {f.__name__}")


def decompose(rhs, states, time=None) -> Decomposition:
    """The elementary operations of the right-hand sides ``rhs`` (SymPy expressions in
    the symbols ``states`` and ``time``, every other constant a number).

    Raises :class:`Unsupported` for a function without a recurrence here (atan, erf, ...)
    or a symbol that is neither a state variable nor the time.
    """
    states = list(states)
    if len(rhs) != len(states):
        raise ValueError(f"rhs: expected {len(states)} right-hand sides, got {len(rhs)}")
    b = _Builder(states, time)
    rhs = [f if isinstance(f, sympy.Basic) else sympy.Float(float(f)) for f in rhs]
    # common subexpressions first, products of common factors included (SymPy's cse
    # matches common subsets of Mul and Add arguments, which the flattening of the
    # expressions hides from the memo: (1 − w) φ̇ with φ̇ = (B + a w)/(w (2 − w)) is one
    # product of two series, not a product and a second quotient)
    replacements, reduced = sympy.cse(rhs, symbols=sympy.numbered_symbols("c", cls=sympy.Dummy))
    for sym, expr in replacements:
        v = b.expr(expr)
        if isinstance(v, float):
            b.expr_memo[sym] = v
        else:
            b.rows[sym] = v
    b.dec.outputs = [b.expr(f) for f in reduced]
    b.dec.n_rows = b.n_rows
    return b.dec
