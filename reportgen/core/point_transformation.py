r"""Point transformations of a Lagrangian, q = q(q′) (notes (3.39)–(3.47)), with SymPy.

A change of coordinates q → q′ with a nowhere-singular Jacobian (notes (3.39)–(3.40))
carries the velocities linearly, q̇ = J q̇′ with J = ∂q/∂q′ (notes (3.41)), so that
∂q̇/∂q̇′ = ∂q/∂q′ (3.42) and ∂q̇ᵢ/∂q′ⱼ = Σₖ ∂²qᵢ/∂q′ₖ∂q′ⱼ q̇′ₖ (3.43).  The chain rule
(3.44)–(3.46) then gives the Euler–Lagrange expressions of L′(q′, q̇′) = L(q(q′), J q̇′)
as those of L contracted with the Jacobian (3.47):

    E_{q′}(L′) = Jᵀ E_q(L),   E = d/dt ∂L/∂q̇ − ∂L/∂q,

so that, J being invertible, the solutions of one set of equations are the solutions of
the other.  The notes write the map from old to new; the config writes the old
coordinates as formulas of the new (the direction in which L′ is a substitution), and the
identities above are the notes' with the roles of q and q′ exchanged.

The expressions come from :mod:`reportgen.core.expressions` (never from ``sympify``).

References
----------
Lecture notes (3.39)–(3.47); Goldstein, Poole & Safko, Classical Mechanics, 3rd ed., §1.4.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy

from .mechanics import PhaseSpace, accelerations, euler_lagrange


@dataclass(frozen=True)
class PointTransformation:
    """L′(q′, q̇′) = L(q(q′), J q̇′) and the checks of notes (3.42), (3.43) and (3.47).

    ``old`` qᵢ(q′) per old coordinate; ``jacobian`` J = ∂q/∂q′ (n, n); ``det`` det J,
    simplified; ``velocities`` q̇ᵢ = Σₖ Jᵢₖ q̇′ₖ; ``L_new`` L′, simplified;
    ``velocity_residual`` ∂q̇ᵢ/∂q̇′ⱼ − Jᵢⱼ (3.42), ``second_residual`` ∂q̇ᵢ/∂q′ⱼ −
    Σₖ ∂²qᵢ/∂q′ₖ∂q′ⱼ q̇′ₖ (3.43), each simplified, row by row; ``covariance_residual``
    E_{q′ⱼ}(L′) − Σᵢ Jᵢⱼ E_{qᵢ}(L) per new coordinate, simplified (3.47).
    """

    new: PhaseSpace
    old: tuple[sympy.Expr, ...]
    jacobian: sympy.Matrix
    det: sympy.Expr
    velocities: tuple[sympy.Expr, ...]
    L_new: sympy.Expr
    velocity_residual: tuple[sympy.Expr, ...]
    second_residual: tuple[sympy.Expr, ...]
    covariance_residual: tuple[sympy.Expr, ...]

    @property
    def velocity_identity(self) -> bool:
        """∂q̇/∂q̇′ = ∂q/∂q′ (notes (3.42)) simplified to an identity."""
        return all(r == 0 for r in self.velocity_residual)

    @property
    def second_identity(self) -> bool:
        """∂q̇/∂q′ through the second derivatives (notes (3.43)) simplified."""
        return all(r == 0 for r in self.second_residual)

    @property
    def covariant(self) -> bool:
        """E_{q′}(L′) = Jᵀ E_q(L) (notes (3.47)) simplified to an identity."""
        return all(r == 0 for r in self.covariance_residual)


def _simplified(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` expanded and trigsimp'd (sin² + cos² = 1 at a fraction of simplify's cost),
    sign(r) written r/|r| (the derivative of |r|: simplify alone makes a Piecewise of
    sign(r)/r − 1/|r|, undefined at r = 0), then simplified if not zero."""
    expr = sympy.trigsimp(sympy.expand(expr))
    if expr != 0:
        expr = sympy.simplify(expr.replace(sympy.sign, lambda a: a / sympy.Abs(a)))
    return expr


def point_transformation(space: PhaseSpace, L: sympy.Expr, old, new: PhaseSpace,
                         constants=()) -> PointTransformation:
    """Carry ``L(q, q̇, t)`` of ``space`` to the coordinates of ``new`` by q = ``old``(q′).

    Parameters
    ----------
    space : PhaseSpace
        The old coordinates q.
    L : sympy.Expr
        The Lagrangian in q, q̇, t (and ``constants``).
    old : sequence of sympy.Expr, length n
        qᵢ as functions of the new coordinates q′ and the constants only (a point
        transformation, notes (3.39)); ValueError otherwise.
    new : PhaseSpace
        The new coordinates q′, as many as the old.
    constants : iterable of sympy.Symbol
        Named constants the formulas may hold.

    Returns
    -------
    PointTransformation
        L′ and the residuals of notes (3.42), (3.43) and (3.47), each simplified.
    """
    old = tuple(old)
    n = len(space.q)
    if len(old) != n or len(new.q) != n:
        raise ValueError(f"a point transformation maps {n} coordinates to {n}: got "
                         f"{len(old)} formulas and {len(new.q)} new coordinates")
    allowed = set(new.q) | set(constants)
    for name, expr in zip(space.names, old, strict=True):
        stray = expr.free_symbols - allowed
        if stray:
            raise ValueError(f"{name} depends on {', '.join(sorted(map(str, stray)))}: a "
                             "point transformation writes the old coordinates as functions "
                             "of the new coordinates alone")
    J = sympy.Matrix([[sympy.diff(q, s) for s in new.q] for q in old])
    velocities = tuple(sum((J[i, k] * new.qdot[k] for k in range(n)), sympy.S.Zero)
                       for i in range(n))
    # (3.42) and (3.43), in the direction q(q′)
    velocity_residual = tuple(_simplified(sympy.diff(velocities[i], new.qdot[j]) - J[i, j])
                              for i in range(n) for j in range(n))
    second_residual = tuple(_simplified(
        sympy.diff(velocities[i], new.q[j])
        - sum((sympy.diff(old[i], new.q[k], new.q[j]) * new.qdot[k] for k in range(n)),
              sympy.S.Zero)) for i in range(n) for j in range(n))
    to_new = {**dict(zip(space.q, old, strict=True)),
              **dict(zip(space.qdot, velocities, strict=True)), space.t: new.t}
    L_new = sympy.trigsimp(sympy.expand(L.xreplace(to_new)))
    # q̈ = d/dt (J q̇′) = J q̈′ + Σ ∂J/∂q′ q̇′ q̇′, so that E(L) reads in (q′, q̇′, q̈′)
    new_acc = accelerations(new)
    old_acc = accelerations(space)
    to_new.update({a: sum((sympy.diff(v, s) * sd + sympy.diff(v, sd) * sa
                           for s, sd, sa in zip(new.q, new.qdot, new_acc, strict=True)),
                          sympy.S.Zero) for a, v in zip(old_acc, velocities, strict=True)})
    E_old = [e.xreplace(to_new) for e in euler_lagrange(space, L)]
    E_new = euler_lagrange(new, L_new)
    covariance_residual = tuple(
        _simplified(E_new[j] - sum((J[i, j] * E_old[i] for i in range(n)), sympy.S.Zero))
        for j in range(n))
    det = sympy.factor(sympy.trigsimp(sympy.expand(J.det())))
    return PointTransformation(new, old, J, det, velocities, L_new, velocity_residual,
                               second_residual, covariance_residual)
