"""Symbolic mechanics of a written L or H (notes §2–§6), with SymPy.

The expressions come from :mod:`reportgen.core.expressions` (never from ``sympify``).
Momenta are named ``p_<q>``, velocities ``<q>_dot``; the state is the coordinates then
the momenta, for L as well as for H.

* :func:`hamiltonian_system` -- Hamilton's equations q̇ = ∂H/∂p, ṗ = −∂H/∂q;
* :func:`legendre` -- from L(q, q̇, t): p = ∂L/∂q̇ solved for q̇ (L quadratic in the
  velocities, so the system is linear) and H = p·q̇ − L;
* :func:`first_order` -- L = a(q, t)·q̇ − V(q, t), linear in the velocities (notes
  (3.36–3.38)): no Legendre transform, but first-order equations ω q̇ = ∇V + ∂a/∂t;
* :func:`poisson_bracket`, :func:`cyclic_coordinates`;
* :func:`roundoff_scale` -- the size of an expression's parts, against which a value
  that should vanish (a Jacobi sum, a bracket) is judged: zero, or rounding.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy

from . import numeric


@dataclass(frozen=True)
class PhaseSpace:
    """Symbols of a system with coordinates ``names``: q, p, q̇ and t."""

    names: tuple[str, ...]
    q: tuple[sympy.Symbol, ...]
    p: tuple[sympy.Symbol, ...]
    qdot: tuple[sympy.Symbol, ...]
    t: sympy.Symbol

    @classmethod
    def of(cls, names) -> PhaseSpace:
        names = tuple(names)
        if len(set(names)) != len(names) or not names:
            raise ValueError(f"coordinates {list(names)}: expected distinct names")
        return cls(names,
                   tuple(sympy.Symbol(n, real=True) for n in names),
                   tuple(sympy.Symbol(f"p_{n}", real=True) for n in names),
                   tuple(sympy.Symbol(f"{n}_dot", real=True) for n in names),
                   sympy.Symbol("t", real=True))

    def symbols_for_h(self) -> dict[str, sympy.Symbol]:
        return {**{s.name: s for s in self.q + self.p}, "t": self.t}

    def symbols_for_l(self) -> dict[str, sympy.Symbol]:
        return {**{s.name: s for s in self.q + self.qdot}, "t": self.t}


@dataclass(frozen=True)
class HamiltonianSystem:
    space: PhaseSpace
    H: sympy.Expr
    qdot: tuple[sympy.Expr, ...]  # ∂H/∂p
    pdot: tuple[sympy.Expr, ...]  # −∂H/∂q

    @property
    def rhs(self) -> tuple[sympy.Expr, ...]:
        """d/dt of the state (q, p)."""
        return self.qdot + self.pdot


def hamiltonian_system(space: PhaseSpace, H: sympy.Expr,
                       constants=()) -> HamiltonianSystem:
    """Hamilton's equations of ``H(q, p, t)`` (notes (5.x); Goldstein 8.18).  ``constants``:
    further symbols H may hold (named constants that stay symbolic)."""
    stray = H.free_symbols - set(space.q + space.p + (space.t,)) - set(constants)
    if stray:
        raise ValueError(f"H depends on {', '.join(sorted(map(str, stray)))}, which are "
                         "neither coordinates, momenta nor t")
    return HamiltonianSystem(space, H,
                             tuple(sympy.diff(H, p) for p in space.p),
                             tuple(-sympy.diff(H, q) for q in space.q))


@dataclass(frozen=True)
class Legendre:
    """The Legendre transform of L: p(q, q̇), q̇(q, p) and H(q, p)."""

    momenta: tuple[sympy.Expr, ...]  # p_i = ∂L/∂q̇_i as functions of q, q̇, t
    velocities: tuple[sympy.Expr, ...]  # q̇_i as functions of q, p, t
    H: sympy.Expr


def legendre(space: PhaseSpace, L: sympy.Expr, constants=()) -> Legendre:
    """p = ∂L/∂q̇ solved for q̇ and H = p·q̇ − L (Goldstein 8.15).

    The velocities must enter L at most quadratically with a nonsingular Hessian
    ∂²L/∂q̇∂q̇ (a regular Lagrangian); otherwise ValueError says which condition fails.
    ``constants``: further symbols L may hold.
    """
    stray = L.free_symbols - set(space.q + space.qdot + (space.t,)) - set(constants)
    if stray:
        raise ValueError(f"L depends on {', '.join(sorted(map(str, stray)))}, which are "
                         "neither coordinates, velocities nor t")
    momenta = tuple(sympy.diff(L, v) for v in space.qdot)
    hessian = sympy.Matrix([[sympy.diff(m, v) for v in space.qdot] for m in momenta])
    if any(sympy.diff(h, v) != 0 for h in hessian for v in space.qdot):
        raise ValueError("L is not quadratic in the velocities: p = ∂L/∂q̇ cannot be "
                         "solved for q̇ in closed form")
    # factor(trigsimp(det)) finds sin² + cos² = 1 at a fraction of simplify's cost
    det = sympy.factor(sympy.trigsimp(sympy.expand(hessian.det())))
    if det == 0:
        raise ValueError("∂²L/∂q̇∂q̇ is singular (and not zero: L is not linear in the "
                         "velocities either): L is not regular, there is no Legendre "
                         "transform")
    # L = ½ q̇ᵀA q̇ + bᵀq̇ + L0 with A the Hessian; p = A q̇ + b, so
    # q̇ = A⁻¹(p − b) and H = p·q̇ − L = ½ (p − b)ᵀ A⁻¹ (p − b) − L0, with A⁻¹ = adj A / det A
    at_rest = {v: 0 for v in space.qdot}
    b = sympy.Matrix([m.subs(at_rest) for m in momenta])
    excess = sympy.Matrix(space.p) - b
    adjugate = hessian.adjugate()
    velocities = tuple(sympy.factor(v / det) for v in adjugate * excess)
    # term by term, cancelled: p_θ²/(2ml²) + p_φ²/(2ml² sin²θ), not one fraction whose
    # derivatives cancel numerically
    kinetic = sympy.Add(*(sympy.cancel(term) for term in sympy.Add.make_args(
        sympy.expand((excess.T * adjugate * excess)[0] / (2 * det)))))
    H = kinetic - L.subs(at_rest)
    return Legendre(momenta, velocities, H)


def linear_in_velocities(space: PhaseSpace, L: sympy.Expr) -> bool:
    """Whether ∂²L/∂q̇∂q̇ vanishes identically: L = a(q, t)·q̇ − V(q, t), a first-order
    Lagrangian (notes (3.36–3.38))."""
    return all(sympy.simplify(sympy.diff(L, v, w)) == 0
               for i, v in enumerate(space.qdot) for w in space.qdot[i:])


@dataclass(frozen=True)
class FirstOrder:
    """L = Σ aᵢ(q, t) q̇ᵢ − V(q, t) reduced to first-order equations (notes (3.36–3.38)).

    With ∂L/∂q̇ᵢ = aᵢ and ∂L/∂qᵢ = Σⱼ ∂ᵢaⱼ q̇ⱼ − ∂ᵢV, Lagrange's equations
    d/dt ∂L/∂q̇ᵢ − ∂L/∂qᵢ = Σⱼ ∂ⱼaᵢ q̇ⱼ + ∂ₜaᵢ − Σⱼ ∂ᵢaⱼ q̇ⱼ + ∂ᵢV = 0 read

        Σⱼ ωᵢⱼ q̇ⱼ = ∂ᵢV + ∂ₜaᵢ,   ωᵢⱼ = ∂ᵢaⱼ − ∂ⱼaᵢ,

    first order: the velocities follow from the coordinates when ω is invertible.  ``a``,
    ``V``; ``omega`` ω; ``det`` det ω; ``inverse`` ω⁻¹; ``force`` ∇V + ∂ₜa; ``qdot``
    ω⁻¹(∇V + ∂ₜa).  The energy function q̇·∂L/∂q̇ − L = a·q̇ − L is V, conserved when L does
    not depend on t (ω antisymmetric: ∇V·ω⁻¹∇V = 0); the bracket of the reduced phase space
    :meth:`bracket` makes ḟ = {f, V} + ∂f/∂t.
    """

    a: tuple[sympy.Expr, ...]
    V: sympy.Expr
    omega: sympy.Matrix
    det: sympy.Expr
    inverse: sympy.Matrix
    force: tuple[sympy.Expr, ...]
    qdot: tuple[sympy.Expr, ...]

    def bracket(self, space: PhaseSpace, f: sympy.Expr, g: sympy.Expr) -> sympy.Expr:
        """{f, g} = Σᵢⱼ ∂ᵢf (ω⁻¹)ᵢⱼ ∂ⱼg, as derived (not simplified): for g = V (t-independent
        L) it is ∇f·q̇ = ḟ."""
        n = len(space.q)
        return sympy.Add(*(sympy.diff(f, space.q[i]) * self.inverse[i, j]
                           * sympy.diff(g, space.q[j])
                           for i in range(n) for j in range(n)))


def first_order(space: PhaseSpace, L: sympy.Expr, constants=()) -> FirstOrder:
    """The reduction of a Lagrangian linear in the velocities (notes (3.36–3.38); see
    :class:`FirstOrder`).  ValueError says why it fails: L not linear in the velocities, an
    odd number of coordinates (an antisymmetric ω of odd size is singular) or det ω = 0
    identically."""
    stray = L.free_symbols - set(space.q + space.qdot + (space.t,)) - set(constants)
    if stray:
        raise ValueError(f"L depends on {', '.join(sorted(map(str, stray)))}, which are "
                         "neither coordinates, velocities nor t")
    if not linear_in_velocities(space, L):
        raise ValueError("L is not linear in the velocities")
    n = len(space.q)
    at_rest = {v: 0 for v in space.qdot}
    a = tuple(sympy.diff(L, v).subs(at_rest) for v in space.qdot)
    V = -L.subs(at_rest)
    words = "L is linear in the velocities (a first-order Lagrangian, notes (3.36–3.38)) but"
    if n % 2:
        raise ValueError(f"{words} its {n} coordinates are an odd number: ω = ∂ᵢaⱼ − ∂ⱼaᵢ "
                         "is antisymmetric of odd size, so det ω = 0 and the equations do not "
                         "determine the velocities")
    omega = sympy.Matrix(n, n, lambda i, j: sympy.diff(a[j], space.q[i])
                         - sympy.diff(a[i], space.q[j]))
    det = sympy.factor(sympy.trigsimp(sympy.expand(omega.det())))
    if det == 0:
        raise ValueError(f"{words} ω = ∂ᵢaⱼ − ∂ⱼaᵢ is singular (det ω = 0 for every q): the "
                         "equations do not determine the velocities")
    inverse = (omega.adjugate() / det).applyfunc(sympy.cancel)
    force = tuple(sympy.diff(V, q) + sympy.diff(ai, space.t)
                  for q, ai in zip(space.q, a, strict=True))
    qdot = tuple(sympy.cancel(e) for e in inverse * sympy.Matrix(force))
    return FirstOrder(a, V, omega, det, inverse, force, qdot)


def poisson_bracket(space: PhaseSpace, f: sympy.Expr, g: sympy.Expr) -> sympy.Expr:
    """{f, g} = Σ ∂f/∂q ∂g/∂p − ∂f/∂p ∂g/∂q (Goldstein 9.67), simplified."""
    return sympy.simplify(sum(sympy.diff(f, q) * sympy.diff(g, p)
                              - sympy.diff(f, p) * sympy.diff(g, q)
                              for q, p in zip(space.q, space.p, strict=True)))


def cyclic_coordinates(space: PhaseSpace, H: sympy.Expr) -> list[str]:
    """The coordinates H does not depend on: their momenta are conserved."""
    return [name for name, q in zip(space.names, space.q, strict=True)
            if sympy.diff(H, q) == 0]


def bracket(space: PhaseSpace, f: sympy.Expr, g: sympy.Expr) -> sympy.Expr:
    """{f, g} = Σ ∂f/∂q ∂g/∂p − ∂f/∂p ∂g/∂q as derived, not simplified (to evaluate, and to
    measure with :func:`roundoff_scale`: simplifying would hide the cancellation)."""
    return sympy.Add(*(sympy.diff(f, q) * sympy.diff(g, p) - sympy.diff(f, p) * sympy.diff(g, q)
                       for q, p in zip(space.q, space.p, strict=True)))


def roundoff_scale(expr: sympy.Expr, values) -> np.ndarray:
    """Σ of the sizes of ``expr``'s parts at ``values``: a sum's terms add in absolute
    value, a product's factors (and a positive integer power's base) multiply in absolute
    value, any other node counts by its own |value|.

    Evaluating ``expr`` in floating point leaves an error of a few eps times this (each
    addition rounds relative to its larger part): a value below ~1e-12 of it is rounding,
    indistinguishable from zero, whatever the size of the variables.  For
    x·y − y·x it is 2|x y|, where the value is 0.
    """
    if not isinstance(expr, sympy.Basic):  # a plain number (a sum that collapsed to 0)
        return np.asarray(abs(float(expr)))
    arrays = {s: np.asarray(v, dtype=np.float64) for s, v in values.items()}
    memo: dict = {}

    def size(node):
        hit = memo.get(node)
        if hit is not None:
            return hit
        if node.is_Add:
            out = sum(size(a) for a in node.args)
        elif node.is_Mul:
            out = 1.0
            for a in node.args:
                out = out * size(a)
        elif node.is_Pow and node.args[1].is_Integer and node.args[1] > 0:
            out = size(node.args[0]) ** int(node.args[1])
        else:
            out = np.abs(numeric.evaluate(node, arrays))
        memo[node] = out
        return out

    with np.errstate(all="ignore"):
        return np.asarray(size(expr), dtype=np.float64)


@dataclass(frozen=True)
class NoetherCharge:
    """The conserved charge of a declared symmetry of L (notes (3.9–3.16)).

    ``delta`` δq_i(q, t) (the generator), ``delta_velocity`` δq̇_i = d(δq_i)/dt,
    ``delta_L`` δL = Σ ∂L/∂q δq + ∂L/∂q̇ δq̇ as derived, ``residual`` δL − dF/dt
    simplified (0: a symmetry), ``charge`` Q = Σ ∂L/∂q̇ δq − F in (q, q̇, t).
    """

    delta: tuple[sympy.Expr, ...]
    delta_velocity: tuple[sympy.Expr, ...]
    F: sympy.Expr
    delta_L: sympy.Expr
    residual: sympy.Expr

    charge: sympy.Expr

    @property
    def symmetry(self) -> bool:
        """δL is zero or the total derivative dF/dt: Q is conserved on every solution."""
        return self.residual == 0


def total_derivative(space: PhaseSpace, f: sympy.Expr) -> sympy.Expr:
    """df/dt = Σ ∂f/∂q q̇ + ∂f/∂t of a function of (q, t) along any motion."""
    return sum((sympy.diff(f, q) * v for q, v in zip(space.q, space.qdot, strict=True)),
               sympy.S.Zero) + sympy.diff(f, space.t)


def noether(space: PhaseSpace, L: sympy.Expr, delta, F: sympy.Expr | None = None,
            constants=()) -> NoetherCharge:
    """The charge of the point transformation q → q + ε δq(q, t) (Noether's theorem,
    notes (3.9–3.16)).

    If δL = Σ ∂L/∂q δq + ∂L/∂q̇ δq̇ (δq̇ = d δq/dt) is the total derivative dF/dt of some
    F(q, t) (F = 0: L invariant), then Q = Σ ∂L/∂q̇ δq − F is conserved, since by Lagrange's
    equations dQ/dt = Σ (∂L/∂q δq + ∂L/∂q̇ δq̇) − dF/dt = δL − dF/dt.  ``delta``: δq per
    coordinate (a sequence, one per coordinate); ValueError when δq or F depends on a
    velocity or momentum (a point transformation moves q by a function of q and t only).
    """
    delta = tuple(sympy.S(d) if not isinstance(d, sympy.Basic) else d for d in delta)
    F = sympy.S.Zero if F is None else F
    if len(delta) != len(space.q):
        raise ValueError(f"delta: expected one δq per coordinate ({len(space.q)}), "
                         f"got {len(delta)}")
    allowed = set(space.q) | {space.t} | set(constants)
    for name, expr in [*((f"δ{n}", d) for n, d in zip(space.names, delta, strict=True)),
                       ("F", F)]:
        stray = expr.free_symbols - allowed
        if stray:
            raise ValueError(f"{name} depends on {', '.join(sorted(map(str, stray)))}: a point "
                             "transformation is a function of the coordinates and t only")
    delta_velocity = tuple(total_derivative(space, d) for d in delta)
    delta_L = sum((sympy.diff(L, q) * d + sympy.diff(L, v) * dv
                   for q, v, d, dv in zip(space.q, space.qdot, delta, delta_velocity,
                                          strict=True)), sympy.S.Zero)
    residual = sympy.simplify(delta_L - total_derivative(space, F))
    charge = sum((sympy.diff(L, v) * d for v, d in zip(space.qdot, delta, strict=True)),
                 sympy.S.Zero) - F
    return NoetherCharge(delta, delta_velocity, F, delta_L, residual, charge)


def accelerations(space: PhaseSpace) -> tuple[sympy.Symbol, ...]:
    """The symbols q̈ (``<q>_ddot``) of the Euler–Lagrange expressions."""
    return tuple(sympy.Symbol(f"{n}_ddot", real=True) for n in space.names)


def euler_lagrange(space: PhaseSpace, L: sympy.Expr) -> tuple[sympy.Expr, ...]:
    """E_i = d/dt ∂L/∂q̇_i − ∂L/∂q_i in (q, q̇, q̈, t): the equations of motion are E = 0
    (notes §3; Goldstein (1.57)).  d/dt of f(q, q̇, t) is Σ ∂f/∂q q̇ + ∂f/∂q̇ q̈ + ∂f/∂t."""
    qddot = accelerations(space)

    def d_dt(f):
        return (sum((sympy.diff(f, q) * v + sympy.diff(f, v) * a
                     for q, v, a in zip(space.q, space.qdot, qddot, strict=True)), sympy.S.Zero)
                + sympy.diff(f, space.t))

    return tuple(d_dt(sympy.diff(L, v)) - sympy.diff(L, q)
                 for q, v in zip(space.q, space.qdot, strict=True))


@dataclass(frozen=True)
class TotalDerivative:
    """L' = L + dF/dt for F(q, t) (notes (3.48–3.49)): the same equations of motion, the
    momenta shifted by ∂F/∂q and H by −∂F/∂t.

    ``L_new`` L + dF/dt; ``difference`` E(L') − E(L) per coordinate, simplified (zero);
    ``momenta_shift`` ∂F/∂q; ``H_new`` the Legendre transform of L'; ``H_difference``
    H'(q, p) − (H(q, p − ∂F/∂q) − ∂F/∂t), simplified (zero).
    """

    F: sympy.Expr
    L_new: sympy.Expr
    difference: tuple[sympy.Expr, ...]
    momenta_shift: tuple[sympy.Expr, ...]
    H_new: sympy.Expr
    H_difference: sympy.Expr

    @property
    def same_equations(self) -> bool:
        return all(d == 0 for d in self.difference)


def add_total_derivative(space: PhaseSpace, L: sympy.Expr, H: sympy.Expr, F: sympy.Expr,
                         constants=()) -> TotalDerivative:
    """L and L + dF/dt compared symbolically (notes (3.48–3.49)): their Euler–Lagrange
    expressions, and their Hamiltonians (L' is transformed by :func:`legendre` on its own,
    an independent derivation of H' = H(q, p − ∂F/∂q) − ∂F/∂t)."""
    stray = F.free_symbols - set(space.q) - {space.t} - set(constants)
    if stray:
        raise ValueError(f"F depends on {', '.join(sorted(map(str, stray)))}: F is a "
                         "function of the coordinates and t only")
    L_new = L + total_derivative(space, F)
    difference = tuple(sympy.simplify(sympy.expand(e1 - e0)) for e0, e1 in
                       zip(euler_lagrange(space, L), euler_lagrange(space, L_new), strict=True))
    shift = tuple(sympy.diff(F, q) for q in space.q)
    H_new = legendre(space, L_new, constants).H
    expected = H.xreplace({p: p - s for p, s in zip(space.p, shift, strict=True)}) \
        - sympy.diff(F, space.t)
    return TotalDerivative(F, L_new, difference, shift, H_new,
                           sympy.simplify(H_new - expected))
