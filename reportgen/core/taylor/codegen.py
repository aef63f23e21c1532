r"""numba source of a system's Taylor coefficients and of the whole adaptive run.

Two forms of one module (the operations from :func:`.decompose.decompose`, constants
as numbers), both with the same two functions:

* ``coefficients(t, x, W, X, order, inv)`` fills ``X[k, i]``, the k-th normalised
  derivative x_i^(k)(t)/k! of state variable i, k = 0..order.  Order by order: the
  operations' k-th coefficients from their operands' first k (the recurrences below:
  Jorba & Zou 2005 §2.2, HNW I §I.8), then x_i^[k+1] = f_i^[k] / (k + 1).
  :func:`unrolled_source` writes it for one order with every loop unrolled: every
  coefficient a local variable, every recurrence weight ((α(k−j) − j)/k, j/k, 1/(k+1))
  a number, every 1/a₀ computed once -- as heyoka's non-compact mode does, and 1.7-2x
  faster than the looped form.  :func:`module_source` writes the looped form, one
  module for every order, its rows in the workspace ``W[row, k]`` (``inv[k]`` = 1/k);
  for systems too big to unroll.
* ``run(t_eval, y0, order, Y, max_steps, info, safety)``: the adaptive Taylor method of
  Jorba & Zou 2005 §3 (order p from the tolerance by the caller, step
  h = safety ρ e⁻² e^(−0.7/(p−1)) with ρ from the last two coefficients -- heyoka's rule
  at safety 1), every output time inside a step evaluated from the step's Taylor
  polynomial (Horner), the steps never shortened to meet an output.  Returns a
  :class:`~reportgen.core.integrators.status.Status` code; ``info`` receives (accepted
  steps, last time reached).

The recurrences for c = op(a, b) in normalised coefficients (a_k = a^(k)/k!), k ≥ 1:

* c = a b:        c_k = Σ_{j=0..k} a_j b_{k−j}
* c = a / b:      c_k = (a_k − Σ_{j=1..k} b_j c_{k−j}) / b_0
* c = a^α:        c_k = Σ_{j=0..k−1} (α (k−j) − j) a_{k−j} c_j / (k a_0)
* c = √a:         c_k = (a_k − Σ_{j=1..k−1} c_j c_{k−j}) / (2 c_0)
* (s, c) = (sin a, cos a):  s_k = Σ_{j=1..k} j a_j c_{k−j} / k,  c_k = −Σ j a_j s_{k−j} / k
* (sinh a, cosh a): the same without the minus sign
* c = exp a:      c_k = Σ_{j=1..k} j a_j c_{k−j} / k
* c = log a:      c_k = (a_k − Σ_{j=1..k−1} j c_j a_{k−j} / k) / a_0
"""

from __future__ import annotations

from .decompose import Decomposition

#: bumped when the generated code's meaning changes without its text changing
CODE_VERSION = "3"


def _num(v: float) -> str:
    text = repr(float(v))
    return f"({text})" if text.startswith("-") else text


def _order_0(op) -> list[str]:
    """Lines computing the order-0 coefficients of ``op``'s rows."""
    a = [f"U[{r}, 0]" for r in op.args]
    o = op.out[0]
    k = op.kind
    if k == "lin":
        k0, *w = op.consts
        terms = [f"{_num(wi)} * {ai}" for wi, ai in zip(w, a, strict=True)]
        return [f"U[{o}, 0] = {_num(k0)} + " + " + ".join(terms)]
    if k == "mul":
        return [f"U[{o}, 0] = {_num(op.consts[0])} * {a[0]} * {a[1]}"]
    if k == "sqr":
        return [f"U[{o}, 0] = {_num(op.consts[0])} * {a[0]} * {a[0]}"]
    if k == "div":
        num = f"{_num(op.consts[0])} * {a[0]}" if len(a) == 2 else _num(op.consts[0])
        return [f"U[{o}, 0] = {num} / {a[-1]}"]
    if k == "pow":
        return [f"U[{o}, 0] = {a[0]} ** {_num(op.consts[0])}"]
    if k == "sqrt":
        return [f"U[{o}, 0] = math.sqrt({a[0]})"]
    if k == "sincos":
        return [f"U[{o}, 0] = math.sin({a[0]})", f"U[{op.out[1]}, 0] = math.cos({a[0]})"]
    if k == "sinhcosh":
        return [f"U[{o}, 0] = math.sinh({a[0]})", f"U[{op.out[1]}, 0] = math.cosh({a[0]})"]
    if k == "exp":
        return [f"U[{o}, 0] = math.exp({a[0]})"]
    if k == "log":
        return [f"U[{o}, 0] = math.log({a[0]})"]
    if k == "abs":
        return [f"U[{o}, 0] = abs({a[0]})"]
    if k == "sign":
        return [f"U[{o}, 0] = 0.0 if {a[0]} == 0.0 else math.copysign(1.0, {a[0]})"]
    raise AssertionError(f"unknown operation {k}")


def _order_k(op) -> list[str]:
    """Lines computing the k-th coefficients (k ≥ 1, the loop variable) of ``op``'s rows."""
    r = op.args
    o = op.out[0]
    k = op.kind
    if k == "lin":
        return [f"U[{o}, k] = " + " + ".join(f"{_num(w)} * U[{ri}, k]"
                                             for w, ri in zip(op.consts[1:], r, strict=True))]
    if k == "mul":
        return ["acc = 0.0", "for j in range(k + 1):",
                f"    acc += U[{r[0]}, j] * U[{r[1]}, k - j]",
                f"U[{o}, k] = {_num(op.consts[0])} * acc"]
    if k == "sqr":
        return ["acc = 0.0", "for j in range((k + 1) // 2):",
                f"    acc += U[{r[0]}, j] * U[{r[0]}, k - j]",
                "acc *= 2.0", "if k % 2 == 0:",
                f"    acc += U[{r[0]}, k // 2] * U[{r[0]}, k // 2]",
                f"U[{o}, k] = {_num(op.consts[0])} * acc"]
    if k == "div":
        num = f"{_num(op.consts[0])} * U[{r[0]}, k]" if len(r) == 2 else "0.0"
        return [f"acc = {num}", "for j in range(1, k + 1):",
                f"    acc -= U[{r[-1]}, j] * U[{o}, k - j]",
                f"U[{o}, k] = acc / U[{r[-1]}, 0]"]
    if k == "pow":
        alpha = _num(op.consts[0])
        return ["acc = 0.0", "for j in range(k):",
                f"    acc += ({alpha} * (k - j) - j) * U[{r[0]}, k - j] * U[{o}, j]",
                f"U[{o}, k] = acc * inv[k] / U[{r[0]}, 0]"]
    if k == "sqrt":
        return ["acc = 0.0", "for j in range(1, k):",
                f"    acc += U[{o}, j] * U[{o}, k - j]",
                f"U[{o}, k] = (U[{r[0]}, k] - acc) / (2.0 * U[{o}, 0])"]
    if k in ("sincos", "sinhcosh"):
        s, c = op.out
        sign = "-" if k == "sincos" else ""
        return ["acc_s = 0.0", "acc_c = 0.0", "for j in range(1, k + 1):",
                f"    w = j * U[{r[0]}, j]", f"    acc_s += w * U[{c}, k - j]",
                f"    acc_c += w * U[{s}, k - j]",
                f"U[{s}, k] = acc_s * inv[k]", f"U[{c}, k] = {sign}acc_c * inv[k]"]
    if k == "exp":
        return ["acc = 0.0", "for j in range(1, k + 1):",
                f"    acc += j * U[{r[0]}, j] * U[{o}, k - j]", f"U[{o}, k] = acc * inv[k]"]
    if k == "log":
        return ["acc = 0.0", "for j in range(1, k):",
                f"    acc += j * U[{o}, j] * U[{r[0]}, k - j]",
                f"U[{o}, k] = (U[{r[0]}, k] - acc * inv[k]) / U[{r[0]}, 0]"]
    if k == "abs":
        return [f"U[{o}, k] = -U[{r[0]}, k] if U[{r[0]}, 0] < 0.0 else U[{r[0]}, k]"]
    if k == "sign":
        return [f"U[{o}, k] = 0.0"]
    raise AssertionError(f"unknown operation {k}")


def _state_update(dec: Decomposition, order: str) -> list[str]:
    """Lines setting x_i^[order+1] from the right-hand sides' coefficients of ``order``."""
    lines = []
    for i, f in enumerate(dec.outputs):
        if isinstance(f, float):
            value = _num(f) if order == "0" else "0.0"
            lines.append(f"U[{i}, {order} + 1] = {value}")
        else:
            lines.append(f"U[{i}, {order} + 1] = U[{f}, {order}] * inv[{order} + 1]")
    return lines


_RUN = '''

@numba.njit(cache=True, error_model="numpy", fastmath=FASTMATH)
def run(t_eval, y0, order, Y, max_steps, info, safety):
    """The adaptive Taylor run (see reportgen.core.taylor.codegen)."""
    n = N_STATE
    W = np.zeros((N_ROWS, order + 1))
    X = np.zeros((order + 1, n))
    acc = np.empty(n)
    x = y0.copy()
    t = t_eval[0]
    n_out = t_eval.size
    for r in range(n):
        Y[0, r] = x[r]
    i = 1
    steps = 0
    status = OK
    inv = np.zeros(order + 2)
    for k in range(1, order + 2):
        inv[k] = 1.0 / k
    rhofac = safety * math.exp(-2.0) * math.exp(-0.7 / (order - 1))
    inv_o = 1.0 / order
    inv_om1 = 1.0 / (order - 1)
    while i < n_out:
        if steps >= max_steps:
            status = MAX_STEPS
            break
        coefficients(t, x, W, X, order, inv)
        max_x = 0.0
        d_o = 0.0
        d_om1 = 0.0
        check = 0.0
        for r in range(n):
            max_x = max(max_x, abs(x[r]))
            d_o = max(d_o, abs(X[order, r]))
            d_om1 = max(d_om1, abs(X[order - 1, r]))
            check += X[order, r] + X[order - 1, r]
        if not math.isfinite(check):
            status = NONFINITE
            break
        # absolute tolerance below |x| = 1, relative above (Jorba & Zou 2005 §3.2)
        num = 1.0 if max_x < 1.0 else max_x
        rho_o = (num / d_o) ** inv_o if d_o > 0.0 else math.inf
        rho_om1 = (num / d_om1) ** inv_om1 if d_om1 > 0.0 else math.inf
        h = min(rho_o, rho_om1) * rhofac
        if math.isnan(h):
            status = NONFINITE
            break
        t_new = t + h
        if h < 10.0 * EPS * abs(t) or t_new == t:
            status = STEP_UNDERFLOW
            break
        while i < n_out and t_eval[i] <= t_new:
            dt = t_eval[i] - t
            for r in range(n):
                acc[r] = X[order, r]
            for m in range(order - 1, -1, -1):
                for r in range(n):
                    acc[r] = acc[r] * dt + X[m, r]
            for r in range(n):
                Y[i, r] = acc[r]
            i += 1
        steps += 1
        if i >= n_out:
            break
        for r in range(n):
            acc[r] = X[order, r]
        for m in range(order - 1, -1, -1):
            for r in range(n):
                acc[r] = acc[r] * h + X[m, r]
        ok = True
        for r in range(n):
            x[r] = acc[r]
            if not math.isfinite(acc[r]):
                ok = False
        if not ok:
            status = NONFINITE
            break
        t = t_new
    info[0] = steps
    info[1] = t
    return status
'''

#: numba's fast-math flags for the generated code: contraction to FMA, reassociation,
#: reciprocals, no signed zeros -- not ``nnan``/``ninf``, so the finiteness checks hold
FASTMATH = '{"contract", "reassoc", "nsz", "arcp"}'


def _header(dec: Decomposition, codes: dict[str, int], title: str) -> list[str]:
    lines = [f'"""Generated by reportgen.core.taylor ({title}); do not edit."""',
             "import math", "", "import numba", "import numpy as np", "",
             f"N_STATE = {dec.n_state}", f"N_ROWS = {max(dec.n_rows, 1)}",
             "EPS = 2.220446049250313e-16", f"FASTMATH = {FASTMATH}"]
    return lines + [f"{name} = {int(code)}" for name, code in codes.items()]


def module_source(dec: Decomposition, codes: dict[str, int]) -> str:
    """The generated module of ``dec`` for every order: ``coefficients`` (loops over the
    orders, the workspace ``W[row, k]``) and ``run``.  ``codes``: the status codes the run
    returns (OK, NONFINITE, STEP_UNDERFLOW, MAX_STEPS)."""
    lines = _header(dec, codes, "any order")
    lines += ["", "", '@numba.njit(cache=True, error_model="numpy", fastmath=FASTMATH)',
              "def coefficients(t, x, U, X, order, inv):",
              '    """X[k, i] = x_i^(k)(t) / k!, k = 0..order; U the rows\' workspace; '
              'inv[k] = 1/k."""']
    body = [f"U[{i}, 0] = x[{i}]" for i in range(dec.n_state)]
    if dec.time_row is not None:
        tr = dec.time_row
        body += [f"U[{tr}, 0] = t", f"U[{tr}, 1] = 1.0", "for k in range(2, order + 1):",
                 f"    U[{tr}, k] = 0.0"]
    for op in dec.ops:
        body += _order_0(op)
    body += _state_update(dec, "0")
    body += ["for k in range(1, order):"]
    inner = []
    for op in dec.ops:
        inner += _order_k(op)
    inner += _state_update(dec, "k")
    body += ["    " + line for line in inner]
    body += ["for k in range(order + 1):", f"    for i in range({dec.n_state}):",
             "        X[k, i] = U[i, k]"]
    lines += ["    " + line for line in body]
    return "\n".join(lines) + "\n" + _RUN


# ------------------------------------------------------------- one order, unrolled
def _c(r: int, k: int) -> str:
    return f"c{r}_{k}"


def _sum(terms: list[str]) -> str:
    return " + ".join(terms) if terms else "0.0"


def _unrolled_op(op, k: int) -> list[str]:
    """Lines computing the k-th coefficient of ``op``'s rows, every index and every
    recurrence weight a number (the recurrences of the module docstring)."""
    r = op.args
    o = op.out[0]
    kind = op.kind
    if kind == "lin":
        k0, *w = op.consts
        terms = [f"{_num(wi)} * {_c(ri, k)}" for wi, ri in zip(w, r, strict=True)]
        if k == 0 and k0 != 0.0:
            terms.insert(0, _num(k0))
        return [f"{_c(o, k)} = {_sum(terms)}"]
    if kind == "mul":
        s = op.consts[0]
        terms = [f"{_c(r[0], j)} * {_c(r[1], k - j)}" for j in range(k + 1)]
        pre = "" if s == 1.0 else f"{_num(s)} * "
        return [f"{_c(o, k)} = {pre}({_sum(terms)})"]
    if kind == "sqr":
        s = op.consts[0]
        a = r[0]
        terms = [f"{_c(a, j)} * {_c(a, k - j)}" for j in range((k + 1) // 2)]
        expr = f"2.0 * ({_sum(terms)})" if terms else ""
        if k % 2 == 0:
            mid = f"{_c(a, k // 2)} * {_c(a, k // 2)}"
            expr = f"{expr} + {mid}" if expr else mid
        pre = "" if s == 1.0 else f"{_num(s)} * "
        return [f"{_c(o, k)} = {pre}({expr})"]
    if kind == "div":
        s = op.consts[0]
        b = r[-1]
        if k == 0:
            num = f"{_num(s)} * {_c(r[0], 0)}" if len(r) == 2 else _num(s)
            return [f"r{o} = 1.0 / {_c(b, 0)}", f"{_c(o, 0)} = {num} * r{o}"]
        terms = [f"{_num(s)} * {_c(r[0], k)}"] if len(r) == 2 else []
        terms += [f"- {_c(b, j)} * {_c(o, k - j)}" for j in range(1, k + 1)]
        return [f"{_c(o, k)} = ({_signed(terms)}) * r{o}"]
    if kind == "pow":
        alpha = op.consts[0]
        a = r[0]
        if k == 0:
            return [f"r{o} = 1.0 / {_c(a, 0)}", f"{_c(o, 0)} = {_c(a, 0)} ** {_num(alpha)}"]
        terms = [f"{_num((alpha * (k - j) - j) / k)} * {_c(a, k - j)} * {_c(o, j)}"
                 for j in range(k)]
        return [f"{_c(o, k)} = ({_sum(terms)}) * r{o}"]
    if kind == "sqrt":
        a = r[0]
        if k == 0:
            return [f"{_c(o, 0)} = math.sqrt({_c(a, 0)})", f"r{o} = 0.5 / {_c(o, 0)}"]
        terms = [f"{_c(o, j)} * {_c(o, k - j)}" for j in range(1, (k + 1) // 2)]
        parts = [f"2.0 * ({_sum(terms)})"] if terms else []
        if k % 2 == 0 and k >= 2:
            parts.append(f"{_c(o, k // 2)} * {_c(o, k // 2)}")
        sub = f" - ({' + '.join(parts)})" if parts else ""
        return [f"{_c(o, k)} = ({_c(a, k)}{sub}) * r{o}"]
    if kind in ("sincos", "sinhcosh"):
        s_, c_ = op.out
        a = r[0]
        if k == 0:
            f1, f2 = ("sin", "cos") if kind == "sincos" else ("sinh", "cosh")
            return [f"{_c(s_, 0)} = math.{f1}({_c(a, 0)})", f"{_c(c_, 0)} = math.{f2}({_c(a, 0)})"]
        ts = [f"{_num(j / k)} * {_c(a, j)} * {_c(c_, k - j)}" for j in range(1, k + 1)]
        tc = [f"{_num(j / k)} * {_c(a, j)} * {_c(s_, k - j)}" for j in range(1, k + 1)]
        sign = "-" if kind == "sincos" else ""
        return [f"{_c(s_, k)} = {_sum(ts)}", f"{_c(c_, k)} = {sign}({_sum(tc)})"]
    if kind == "exp":
        a = r[0]
        if k == 0:
            return [f"{_c(o, 0)} = math.exp({_c(a, 0)})"]
        terms = [f"{_num(j / k)} * {_c(a, j)} * {_c(o, k - j)}" for j in range(1, k + 1)]
        return [f"{_c(o, k)} = {_sum(terms)}"]
    if kind == "log":
        a = r[0]
        if k == 0:
            return [f"{_c(o, 0)} = math.log({_c(a, 0)})", f"r{o} = 1.0 / {_c(a, 0)}"]
        terms = [f"{_num(j / k)} * {_c(o, j)} * {_c(a, k - j)}" for j in range(1, k)]
        sub = f" - ({_sum(terms)})" if terms else ""
        return [f"{_c(o, k)} = ({_c(a, k)}{sub}) * r{o}"]
    if kind == "abs":
        a = r[0]
        if k == 0:
            return [f"r{o} = -1.0 if {_c(a, 0)} < 0.0 else 1.0",
                    f"{_c(o, 0)} = abs({_c(a, 0)})"]
        return [f"{_c(o, k)} = r{o} * {_c(a, k)}"]
    if kind == "sign":
        a = r[0]
        if k == 0:
            return [f"{_c(o, 0)} = 0.0 if {_c(a, 0)} == 0.0 else math.copysign(1.0, {_c(a, 0)})"]
        return [f"{_c(o, k)} = 0.0"]
    raise AssertionError(f"unknown operation {kind}")


def _signed(terms: list[str]) -> str:
    """Join terms some of which start with '- ' into one expression."""
    out = ""
    for t in terms:
        if t.startswith("- "):
            out += f" - {t[2:]}" if out else f"-{t[2:]}"
        else:
            out += f" + {t}" if out else t
    return out or "0.0"


def unrolled_source(dec: Decomposition, order: int, codes: dict[str, int]) -> str:
    """The generated module of ``dec`` for one ``order``: ``coefficients`` with every
    loop unrolled (every coefficient a local, every recurrence weight a number) and the
    same ``run`` as :func:`module_source`'s (``order`` must be passed as this one)."""
    n = dec.n_state
    lines = _header(dec, codes, f"order {order}, unrolled") + [f"ORDER = {order}"]
    lines += ["", "", '@numba.njit(cache=True, error_model="numpy", fastmath=FASTMATH)',
              "def coefficients(t, x, U, X, order, inv):",
              '    """X[k, i] = x_i^(k)(t) / k!, k = 0..ORDER (U, order, inv unused)."""']
    body = [f"{_c(i, 0)} = x[{i}]" for i in range(n)]
    tr = dec.time_row
    for k in range(order):
        if tr is not None:
            body.append(f"{_c(tr, k)} = " + ("t" if k == 0 else "1.0" if k == 1 else "0.0"))
        for op in dec.ops:
            body += _unrolled_op(op, k)
        for i, f in enumerate(dec.outputs):
            if isinstance(f, float):
                body.append(f"{_c(i, k + 1)} = {_num(f) if k == 0 else '0.0'}")
            elif k == 0:
                body.append(f"{_c(i, 1)} = {_c(f, 0)}")
            else:
                body.append(f"{_c(i, k + 1)} = {_c(f, k)} * {_num(1.0 / (k + 1))}")
    body += [f"X[{k}, {i}] = {_c(i, k)}" for k in range(order + 1) for i in range(n)]
    lines += ["    " + line for line in body]
    return "\n".join(lines) + "\n" + _RUN
