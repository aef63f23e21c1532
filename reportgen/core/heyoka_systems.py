r"""Our models of motion as heyoka systems: the same equations for heyoka's Taylor integrator.

heyoka (an optional extra) integrates a system given as (variable, right-hand side) pairs
of its own symbolic expressions.  :func:`system` writes each of our models
(:class:`~reportgen.core.model.OdeModel`) that way, so that heyoka can run as a peer in
the work-precision studies on exactly the equations our integrators run:

* a hand-written model (:mod:`reportgen.core.models`) is recognised by its compiled
  right-hand side ``model.rhs`` and translated by a function of this module that reads
  the same packed ``model.params`` the compiled function unpacks (:data:`_translators`,
  one per right-hand side; each follows the compiled code line by line, branches on the
  parameters taken in Python);
* a formula model (:func:`reportgen.core.formula.compiled_model`) carries its SymPy
  system in ``model.extra["formula_system"]``; its Hamilton equations (or the reduced
  first-order ones) go through ``hy.from_sympy``, with the constants replaced by the
  numbers in ``model.params`` and the time symbol by ``hy.time``.  The few SymPy nodes
  that ``from_sympy`` does not know but our generated code prints (``Abs``, ``sign``,
  ``DiracDelta``, ``sec``, ``csc``, ``cot``, the constant E, rationals whose denominator is
  not a power of 2, floats of more than 53 bits) are translated here to the very values
  the generated code computes.

Parameters are numbers in the expressions, read when :func:`system` is called (heyoka
folds them into the compiled code).  Powers are written as powers, r⁻³ as
``r2 ** -1.5`` where the compiled code has ``1 / (r2 sqrt(r2))``: the same number to a
few ulp, and one Taylor recurrence instead of three.

Nothing here imports heyoka: the caller passes the module in (``system(hy, model)``), and
the model modules are imported only when a translation is looked up, so that importing
this module costs nothing.  The tests check every translation against ``model.f`` at
random states (``tests/test_heyoka_systems.py``).
"""

from __future__ import annotations

from collections.abc import Callable

#: model rhs function -> translator(hy, model) -> list of right-hand sides (built lazily)
_TRANSLATORS: dict[Callable, Callable] | None = None


def system(hy, model) -> list[tuple[object, object]] | None:
    """heyoka's (variable, right-hand side) pairs for ``model``: one variable per state
    component in the order of ``model.columns``, parameters taken from ``model.params`` as
    numbers (read at call time), time as ``hy.time``; None when no translation exists.

    The variables are named after ``model.columns``; for a model in a fictitious time
    (:mod:`~reportgen.core.models.two_center_regularized`, the regularized Kepler and
    three-body models) ``hy.time`` is that independent variable, as in ``model.rhs``.
    """
    if why_not(model):
        return None
    xs = hy.make_vars(*model.columns) if model.dim > 1 else [hy.make_vars(model.columns[0])]
    xs = list(xs)
    formula_system = model.extra.get("formula_system")
    if formula_system is not None:
        rhs = _formula(hy, model, formula_system, xs)
    else:
        rhs = _translators()[model.rhs](hy, model, xs)
    if len(rhs) != model.dim:  # a translator that does not fit its model is a bug
        raise AssertionError(f"{model.name}: {len(rhs)} right-hand sides for "
                             f"{model.dim} components")
    return [(x, hy.expression(float(f)) if isinstance(f, int | float) else f)
            for x, f in zip(xs, rhs, strict=True)]


def why_not(model) -> str:
    """Why :func:`system` gives None for ``model`` ("" when it gives a system)."""
    formula_system = model.extra.get("formula_system")
    if formula_system is not None:
        unknown = _unsupported_nodes(formula_system.hamilton.rhs)
        if unknown:
            return (f"{model.name}: the right-hand side uses {', '.join(sorted(unknown))}, "
                    "which has no heyoka translation")
        return ""
    rhs = getattr(model, "rhs", None)
    if rhs not in _translators():
        where = f"{getattr(rhs, '__module__', '?')}.{getattr(rhs, '__name__', '?')}"
        return f"{model.name}: no heyoka translation of its right-hand side {where}"
    return ""


def _translators() -> dict[Callable, Callable]:
    """{compiled rhs: translator}; the model modules (numba) are imported on first use."""
    global _TRANSLATORS
    if _TRANSLATORS is None:
        from .models import (
            fput,
            heavy_top,
            kepler,
            kepler_regularized,
            linear_chain,
            nbody,
            oscillator,
            pendulum,
            restricted_three_body,
            rigid_body,
            three_body_ks,
            two_center,
            two_center_regularized,
        )

        _TRANSLATORS = {
            pendulum.rhs: _pendulum,
            oscillator.rhs: _oscillator,
            kepler.rhs: _kepler,
            kepler_regularized.rhs: _kepler_levi_civita,
            heavy_top.rhs: _heavy_top,
            heavy_top.spin_free_rhs: _heavy_top_spin_free,
            heavy_top.reduced_rhs: _heavy_top_reduced,
            linear_chain.rhs: _linear_chain,
            fput.rhs: _fput,
            rigid_body.rhs: _rigid_body,
            nbody.rhs: _three_body,
            two_center.rhs: _two_center,
            two_center_regularized.rhs: _two_center_regularized,
            restricted_three_body.rhs: _restricted,
            restricted_three_body.regularized_rhs: _restricted_regularized,
            three_body_ks.rhs: _three_body_ks,
            three_body_ks.rhs_physical: _three_body_ks_physical,
        }
    return _TRANSLATORS


def _p(model) -> list[float]:
    return [float(v) for v in model.params]


def _sum(hy, terms):
    """Σ terms as a heyoka expression (0 for none)."""
    terms = list(terms)
    if not terms:
        return hy.expression(0.0)
    return terms[0] if len(terms) == 1 else hy.sum(terms)


# ------------------------------------------------------------------- hand-written models
def _pendulum(hy, model, xs):
    """pendulum.rhs: θ' = θ̇, θ̇' = −ω0² sin θ; params (ω0²,)."""
    (w2,) = _p(model)
    th, thd = xs
    return [thd, -w2 * hy.sin(th)]


def _oscillator(hy, model, xs):
    """oscillator.rhs: q' = a p, p' = −b q; params (a, b) (the Hamilton and the swapped
    model alike)."""
    a, b = _p(model)
    q, p = xs
    return [a * p, -b * q]


def _kepler(hy, model, xs):
    """kepler.rhs: r̈ = −f r with f = c_n r^(−n−2) (+ c_3 r⁻⁴ when c_3 ≠ 0);
    params (c_n, n, c_3), the branches of ``_accel_factor`` taken here."""
    cn, n, c3 = _p(model)
    x, y, vx, vy = xs
    r2 = x * x + y * y
    f = cn * r2 ** (-1.5 if n == 1.0 else -0.5 * (n + 2.0))
    if c3 != 0.0:
        f = f + c3 * r2 ** -2.0
    return [vx, vy, -f * x, -f * y]


def _kepler_levi_civita(hy, model, xs):
    """kepler_regularized.rhs in the fictitious time s: w'' = (h/2) w, t' = |w|²;
    params (h,)."""
    (h,) = _p(model)
    w1, w2, w1s, w2s, _t = xs
    return [w1s, w2s, 0.5 * h * w1, 0.5 * h * w2, w1 * w1 + w2 * w2]


def _quaternion_rate(q, w):
    """½ q ⊗ (0, ω) for q = (w, x, y, z) and ω = (ω1, ω2, ω3) (ω3 may be 0)."""
    qw, qx, qy, qz = q
    w1, w2, w3 = w
    return [-0.5 * (qx * w1 + qy * w2 + qz * w3), 0.5 * (qw * w1 + qy * w3 - qz * w2),
            0.5 * (qw * w2 + qz * w1 - qx * w3), 0.5 * (qw * w3 + qx * w2 - qy * w1)]


def _heavy_top(hy, model, xs):
    """heavy_top.rhs: the quaternion and Euler's equations with the gravity torque;
    params (I1, I3, Mgl)."""
    i1, i3, mgl = _p(model)
    qw, qx, qy, qz, w1, w2, w3 = xs
    n2 = qw * qw + qx * qx + qy * qy + qz * qz
    g1 = 2.0 * (qx * qz - qw * qy) / n2
    g2 = 2.0 * (qy * qz + qw * qx) / n2
    return [*_quaternion_rate((qw, qx, qy, qz), (w1, w2, w3)),
            ((i1 - i3) * w2 * w3 + mgl * g2) / i1,
            ((i3 - i1) * w3 * w1 - mgl * g1) / i1, 0.0]


def _heavy_top_spin_free(hy, model, xs):
    """heavy_top.spin_free_rhs: the frame F' (quaternion p) and Ω = (Ω1, Ω2, 0);
    params (I1, I3, Mgl, ω3, Mgl/I1, I3 ω3/I1), the last two used."""
    torque, spin = _p(model)[4:6]
    pw, px, py, pz, o1, o2 = xs
    two_over_n2 = 2.0 / (pw * pw + px * px + py * py + pz * pz)
    g1 = (px * pz - pw * py) * two_over_n2
    g2 = (py * pz + pw * px) * two_over_n2
    return [-0.5 * (px * o1 + py * o2), 0.5 * (pw * o1 - pz * o2),
            0.5 * (pw * o2 + pz * o1), 0.5 * (px * o2 - py * o1),
            torque * g2 - spin * o2, spin * o1 - torque * g1]


def _heavy_top_reduced(hy, model, xs):
    """heavy_top.reduced_rhs: ẅ = k0 + (k1 − k2 w) w, φ̇ = (B + a w)/(w (2 − w)),
    ψ̇ = ω3 − (1 − w) φ̇; params (I1, I3, Mgl, ω3, k0, k1, k2, B, a)."""
    omega3, k0, k1, k2, b_, a = _p(model)[3:9]
    w, w_dot, _phi, _psi = xs
    phi_dot = (b_ + a * w) / (w * (2.0 - w))
    return [w_dot, k0 + (k1 - k2 * w) * w, phi_dot, omega3 - (1.0 - w) * phi_dot]


def _linear_chain(hy, model, xs):
    """linear_chain.rhs: q̇ = M⁻¹ p, ṗ = −A q; params (n, M⁻¹ row-major, A row-major).
    Zero entries are left out (adding 0·x changes no finite value)."""
    p = _p(model)
    n = int(p[0])
    minv = [p[1 + i * n:1 + (i + 1) * n] for i in range(n)]
    a = [p[1 + n * n + i * n:1 + n * n + (i + 1) * n] for i in range(n)]
    q, mom = xs[:n], xs[n:]
    qdot = [_sum(hy, (minv[i][j] * mom[j] for j in range(n) if minv[i][j] != 0.0))
            for i in range(n)]
    pdot = [_sum(hy, (-a[i][j] * q[j] for j in range(n) if a[i][j] != 0.0))
            for i in range(n)]
    return qdot + pdot


def _fput(hy, model, xs):
    """fput.rhs: q' = p, p' = −∇V(q) with the stiff springs (ω²/4)(q_{2i} − q_{2i−1})² and
    the soft ones (q_{2i+1} − q_{2i})⁴, ends held at 0; params (ω,), m from the size."""
    (omega,) = _p(model)
    n = len(xs) // 2
    m = n // 2
    q, p = xs[:n], xs[n:]
    half_w2 = 0.5 * omega * omega
    grad: list[list] = [[] for _ in range(n)]  # terms of ∂V/∂q_k
    for j in range(m):
        s = q[2 * j + 1] - q[2 * j]
        grad[2 * j + 1].append(half_w2 * s)
        grad[2 * j].append(-half_w2 * s)
    for i in range(m + 1):
        right = q[2 * i] if i < m else None
        left = q[2 * i - 1] if i > 0 else None
        d = right - left if right is not None and left is not None else (
            right if right is not None else -left)
        f = 4.0 * (d * d * d)  # heyoka differentiates d**3 as a real power: NaN at d = 0
        if i < m:
            grad[2 * i].append(f)
        if i > 0:
            grad[2 * i - 1].append(-f)
    return list(p) + [-_sum(hy, terms) for terms in grad]


def _rigid_body(hy, model, xs):
    """rigid_body.rhs: Euler's equations and q̇ = ½ q ⊗ (0, ω) + κ (1 − |q|²) q;
    params (I1, I2, I3, κ), the κ term left out when κ = 0."""
    I1, I2, I3, kappa = _p(model)
    w1, w2, w3, qw, qx, qy, qz = xs
    rate = _quaternion_rate((qw, qx, qy, qz), (w1, w2, w3))
    if kappa != 0.0:
        c = kappa * (1.0 - (qw * qw + qx * qx + qy * qy + qz * qz))
        rate = [r + c * v for r, v in zip(rate, (qw, qx, qy, qz), strict=True)]
    return [(I2 - I3) * w2 * w3 / I1, (I3 - I1) * w3 * w1 / I2,
            (I1 - I2) * w1 * w2 / I3, *rate]


def _three_body(hy, model, xs):
    """nbody.rhs: q̇ = v, v̇_i = Σ_j G m_j (q_j − q_i)/r_ij³ (no softening);
    params (G, m1, m2, m3)."""
    G, *masses = _p(model)
    q, v = xs[:9], xs[9:]
    acc: list[list] = [[] for _ in range(9)]
    for i in range(3):
        for j in range(i + 1, 3):
            d = [q[3 * j + k] - q[3 * i + k] for k in range(3)]
            inv3 = G * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) ** -1.5
            for k in range(3):
                acc[3 * i + k].append(masses[j] * inv3 * d[k])
                acc[3 * j + k].append(-masses[i] * inv3 * d[k])
    return list(v) + [_sum(hy, terms) for terms in acc]


def _two_center(hy, model, xs):
    """two_center.rhs: r̈ = −μ (r − C1)/r1³ − μ (r − C2)/r2³, C1,2 = (∓a, 0);
    params (μ, a)."""
    mu, a = _p(model)
    x, y, vx, vy = xs
    d1x, d2x = x + a, x - a
    c1 = mu * (d1x * d1x + y * y) ** -1.5
    c2 = mu * (d2x * d2x + y * y) ** -1.5
    return [vx, vy, -c1 * d1x - c2 * d2x, -(c1 + c2) * y]


def _two_center_regularized(hy, model, xs):
    """two_center_regularized.rhs (Thiele–Burrau) in the fictitious time s:
    P_p' = 2aμ sinh p + a²E sinh 2p, P_q' = a²E sin 2q, t' = a² (sinh² p + sin² q);
    params (μ, a, E)."""
    mu, a, E = _p(model)
    p, q, Pp, Pq, _t = xs
    sp, sq = hy.sinh(p), hy.sin(q)
    return [Pp, Pq, 2.0 * a * mu * sp + a * a * E * hy.sinh(2.0 * p),
            a * a * E * hy.sin(2.0 * q), a * a * (sp * sp + sq * sq)]


def _restricted(hy, model, xs):
    """restricted_three_body.rhs: ẍ = 2ẏ + x − (1 − μ)(x + μ)/r1³ − μ(x − 1 + μ)/r2³,
    ÿ = −2ẋ + y − ((1 − μ)/r1³ + μ/r2³) y; params (μ,)."""
    (mu,) = _p(model)
    x, y, vx, vy = xs
    d1, d2 = x + mu, x - 1.0 + mu
    c1 = (1.0 - mu) * (d1 * d1 + y * y) ** -1.5
    c2 = mu * (d2 * d2 + y * y) ** -1.5
    return [vx, vy, 2.0 * vy + x - c1 * d1 - c2 * d2, -2.0 * vx + y - (c1 + c2) * y]


def _restricted_regularized(hy, model, xs):
    """restricted_three_body.regularized_rhs (Thiele–Burrau in the rotating frame, a = 1/2,
    in s); params (μ, E = −C/2)."""
    mu, E = _p(model)
    a, d = 0.5, 0.5 - mu
    p, q, Pp, Pq, _t = xs
    sh, ch, sq, cq = hy.sinh(p), hy.cosh(p), hy.sin(q), hy.cos(q)
    X, Y = a * ch * cq + d, a * sh * sq
    A, B = a * sh * cq, a * ch * sq
    Ap, Bp = a * ch * cq, a * sh * sq
    g = A * A + B * B
    return [Pp - (X * B - Y * A), Pq - (X * A + Y * B),
            (X * Bp - Y * Ap) * Pp + (g + X * Ap + Y * Bp) * Pq + a * sh
            + 2.0 * E * a * a * sh * ch,
            (X * Ap + Y * Bp - g) * Pp + (Y * Ap - X * Bp) * Pq + (1.0 - 2.0 * mu) * a * sq
            + 2.0 * E * a * a * sq * cq,
            a * a * (sh * sh + sq * sq)]


def _ks_derivatives(hy, model, xs):
    """three_body_ks._derivatives: d/ds of the 16 components, and r = |x| = dt/ds."""
    G, mi, mj, mk = _p(model)
    mij = mi + mj
    y = xs
    u0, u1, u2, u3 = y[0], y[1], y[2], y[3]
    r = u0 * u0 + u1 * u1 + u2 * u2 + u3 * u3
    x0 = u0 * u0 - u1 * u1 - u2 * u2 + u3 * u3
    x1 = 2.0 * (u0 * u1 - u2 * u3)
    x2 = 2.0 * (u0 * u2 + u1 * u3)
    ci, cj = mj / mij, mi / mij
    dik = [y[9] + ci * x0, y[10] + ci * x1, y[11] + ci * x2]
    djk = [y[9] - cj * x0, y[10] - cj * x1, y[11] - cj * x2]
    fik = G * (dik[0] * dik[0] + dik[1] * dik[1] + dik[2] * dik[2]) ** -1.5
    fjk = G * (djk[0] * djk[0] + djk[1] * djk[1] + djk[2] * djk[2]) ** -1.5
    p0, p1, p2 = (mk * (fjk * djk[k] - fik * dik[k]) for k in range(3))
    ltp = [u0 * p0 + u1 * p1 + u2 * p2, -u1 * p0 + u0 * p1 + u3 * p2,
           -u2 * p0 - u3 * p1 + u0 * p2, u3 * p0 - u2 * p1 + u1 * p2]
    half_h, half_r = 0.5 * y[8], 0.5 * r
    c = -(mi + mj + mk) / mij * r
    out = [y[4], y[5], y[6], y[7]]
    out += [half_h * u + half_r * lt for u, lt in zip((u0, u1, u2, u3), ltp, strict=True)]
    out.append(2.0 * (y[4] * ltp[0] + y[5] * ltp[1] + y[6] * ltp[2] + y[7] * ltp[3]))
    out += [r * y[12], r * y[13], r * y[14]]
    out += [c * (mi * fik * dik[k] + mj * fjk * djk[k]) for k in range(3)]
    out.append(r)
    return out, r


def _three_body_ks(hy, model, xs):
    """three_body_ks.rhs: the KS-regularized pair and the third body in the fictitious
    time s; params (G, m_i, m_j, m_k)."""
    return _ks_derivatives(hy, model, xs)[0]


def _three_body_ks_physical(hy, model, xs):
    """three_body_ks.rhs_physical: the same in the physical time (d/dt = (1/r) d/ds)."""
    out, r = _ks_derivatives(hy, model, xs)
    inv_r = 1.0 / r
    return [f * inv_r for f in out[:15]] + [1.0]


# ----------------------------------------------------------------------- formula models
def _formula_handlers():
    """{SymPy node type: (hy, translated args) -> heyoka expression} for the nodes the
    generated code prints (formula._Printer) and ``hy.from_sympy`` does not know, each
    the value the generated code computes."""
    import sympy

    def sign(hy, x):  # generated: 0.0 if x == 0.0 else copysign(1.0, x)
        return hy.relup(x) - hy.relup(-x)

    return {
        sympy.Abs: lambda hy, x: hy.relu(x) + hy.relu(-x),
        sympy.sign: sign,
        sympy.DiracDelta: lambda hy, *_: hy.expression(0.0),
        sympy.sec: lambda hy, x: 1.0 / hy.cos(x),
        sympy.csc: lambda hy, x: 1.0 / hy.sin(x),
        sympy.cot: lambda hy, x: 1.0 / hy.tan(x),
    }


#: SymPy functions ``hy.from_sympy`` translates itself (its own table, by name)
_FROM_SYMPY = frozenset({"Add", "Mul", "Pow", "acos", "acosh", "asin", "asinh", "atan",
                         "atan2", "atanh", "cos", "cosh", "erf", "erfc", "exp", "log", "sin",
                         "sinh", "tan", "tanh"})


def _unsupported_nodes(exprs) -> set[str]:
    """Names of the function nodes in ``exprs`` that neither ``hy.from_sympy`` nor this
    module translates."""
    import sympy

    handled = {f.__name__ for f in _formula_handlers()}
    out = set()
    for expr in exprs:
        for node in sympy.preorder_traversal(expr):
            if node.is_Atom:
                continue
            name = type(node).__name__
            if name not in _FROM_SYMPY and name not in handled:
                out.add(name)
    return out


def _formula(hy, model, formula_system, xs):
    """The SymPy right-hand sides of a formula model (``formula_system.hamilton.rhs``, in
    ``formula_system.state_symbols``), constants as the numbers in ``model.params``."""
    import sympy

    handlers = _formula_handlers()
    s_dict: dict = dict(zip(formula_system.state_symbols, xs, strict=True))
    s_dict[formula_system.space.t] = hy.time
    for sym, value in zip(formula_system.param_symbols.values(), model.params, strict=True):
        s_dict[sym] = hy.expression(float(value))
    out = []
    for expr in formula_system.hamilton.rhs:
        # bottom-up: numbers as the floats the generated code prints, then the nodes
        # from_sympy does not know, each from its arguments' translations
        for node in sympy.postorder_traversal(expr):
            if node in s_dict:
                continue
            if node.is_Number or isinstance(node, sympy.NumberSymbol):
                s_dict[node] = hy.expression(float(node))
            elif type(node) in handlers:
                args = [hy.from_sympy(a, s_dict) for a in node.args]
                s_dict[node] = handlers[type(node)](hy, *args)
        out.append(hy.from_sympy(expr, s_dict))
    return out
