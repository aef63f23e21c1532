"""Symbolic mechanics of a written L or H (notes §2–§6), with SymPy.

The expressions come from :mod:`reportgen.core.expressions` (never from ``sympify``).
Momenta are named ``p_<q>``, velocities ``<q>_dot``; the state is the coordinates then
the momenta, for L as well as for H.

* :func:`hamiltonian_system` -- Hamilton's equations q̇ = ∂H/∂p, ṗ = −∂H/∂q;
* :func:`legendre` -- from L(q, q̇, t): p = ∂L/∂q̇ solved for q̇ (L quadratic in the
  velocities, so the system is linear) and H = p·q̇ − L;
* :func:`poisson_bracket`, :func:`cyclic_coordinates`.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy


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
        raise ValueError("∂²L/∂q̇∂q̇ is singular: L is not regular, there is no Legendre "
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


def poisson_bracket(space: PhaseSpace, f: sympy.Expr, g: sympy.Expr) -> sympy.Expr:
    """{f, g} = Σ ∂f/∂q ∂g/∂p − ∂f/∂p ∂g/∂q (Goldstein 9.67), simplified."""
    return sympy.simplify(sum(sympy.diff(f, q) * sympy.diff(g, p)
                              - sympy.diff(f, p) * sympy.diff(g, q)
                              for q, p in zip(space.q, space.p, strict=True)))


def cyclic_coordinates(space: PhaseSpace, H: sympy.Expr) -> list[str]:
    """The coordinates H does not depend on: their momenta are conserved."""
    return [name for name, q in zip(space.names, space.q, strict=True)
            if sympy.diff(H, q) == 0]
