r"""Small oscillations from a written potential (textbook §5.1): the equilibrium of U(q)
found from a guess, and the matrices M and A of L ≈ ½ η̇ᵀ M η̇ − ½ ηᵀ A η there.

A system is written as formula text in named coordinates q, through the allow-list
parser of :mod:`reportgen.core.expressions` (never ``sympify``):

* a Lagrangian ``L(q, q̇)``: U(q) = −L(q, 0) and M(q) = ∂²L/∂q̇∂q̇ at q̇ = 0; or
* a potential ``U(q)`` with a kinetic energy ``T(q, q̇)`` (M = ∂²T/∂q̇∂q̇) or a mass
  matrix ``M(q)`` written entry by entry.

The kinetic part must be a quadratic form in the velocities (no part without them, no
part linear in them -- a gyroscopic term would make the equations M q̈ + G q̇ + A q = 0,
not the textbook's -- and none of third order).

:func:`find_equilibrium` solves ∇U(q) = 0 from a starting guess by Newton's method with the
exact Jacobian A(q) = ∂²U/∂q∂q, damped so that |∇U| falls at every step (numpy alone: the
search runs when a config is validated, without scipy), judges the point stationary
against the sizes of the gradient's own parts (:data:`STATIONARY_RTOL`),
and takes A_ij = ∂²U/∂q_i∂q_j there *symbolically*: differentiation of the parsed tree is
exact, so the frequencies carry only the eigensolver's rounding (a central difference of
step h would carry an O(h²) truncation against an O(ε/h²) rounding error, ~1e-8 at
best).  A central difference is still taken, as an independent check of the derivative
(:attr:`Equilibrium.hessian_fd_difference`).

References
----------
.. [1] Textbook ch. 5, §5.1: U(q) expanded about a stable equilibrium, A_ij = ∂²U/∂q_i∂q_j
       there, M evaluated at the equilibrium; M η̈ + A η = 0.
.. [2] Goldstein, Poole & Safko, 3rd ed., §6.1–6.2.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import sympy

from . import mechanics, numeric
from .differences import central_difference_hessian
from .expressions import (
    MAX_CONSTANTS,
    ExpressionError,
    alias_problem,
    name_problem,
    parse_expression,
)
from .formula import FormulaError

#: a point is stationary when every |∂U/∂qᵢ| is below this fraction of the sizes of its
#: parts (each term's |value|, :func:`mechanics.roundoff_scale`) plus the curvature times
#: the distance searched, Σⱼ |Aᵢⱼ| ℓ: the gradient left is rounding, not a slope
STATIONARY_RTOL = 1e-9
#: the step of the central-difference check of A, relative to max(1, |q₀|)
FD_STEP = 1e-4
#: Newton steps at most; a step is halved at most :data:`HALVINGS` times to lower |∇U|
NEWTON_STEPS = 200
HALVINGS = 30
#: a coordinate of the equilibrium at most this share of the search's scale is tried as 0
SNAP_RTOL = 1e-15
#: ω² with |ω²| at most this share of the largest count as zero (as
#: :data:`reportgen.core.normal_modes.ZERO_TOL`, which the eigenproblem uses)
ZERO_TOL = 1e-10
#: the most coordinates a written potential may have
MAX_COORDINATES = 12


class PotentialError(FormulaError):
    """A written potential that cannot give small oscillations; ``key`` is the config key
    at fault (``system.U``, ``system.guess``, ...)."""


@dataclass(frozen=True)
class PotentialSystem:
    """The written system, symbolically: U(q), its gradient and Hessian, M(q).

    ``given`` is how it was written: "L" (a Lagrangian), "T" (U and a kinetic energy) or
    "M" (U and a mass matrix).  Constants stay symbols (``params`` their values)."""

    space: mechanics.PhaseSpace
    params: dict[str, float]
    param_symbols: dict[str, sympy.Symbol]
    given: str
    U: sympy.Expr
    gradient: tuple[sympy.Expr, ...]
    hessian: tuple[tuple[sympy.Expr, ...], ...]
    mass: tuple[tuple[sympy.Expr, ...], ...]
    L: sympy.Expr | None = None
    T: sympy.Expr | None = None

    @property
    def n(self) -> int:
        return len(self.space.q)

    def values(self, q) -> dict[sympy.Symbol, object]:
        """Symbol -> value at the coordinates ``q`` (the constants included)."""
        out: dict[sympy.Symbol, object] = dict(zip(self.space.q, np.asarray(q, dtype=float),
                                                   strict=True))
        out.update({self.param_symbols[k]: v for k, v in self.params.items()})
        return out

    def potential_at(self, q) -> float:
        return float(numeric.evaluate(self.U, self.values(q)))

    def gradient_at(self, q) -> np.ndarray:
        return np.array([float(v) for v in numeric.evaluate_many(self.gradient, self.values(q))])

    def hessian_at(self, q) -> np.ndarray:
        flat = numeric.evaluate_many([e for row in self.hessian for e in row], self.values(q))
        return np.array([float(v) for v in flat]).reshape(self.n, self.n)

    def mass_at(self, q) -> np.ndarray:
        flat = numeric.evaluate_many([e for row in self.mass for e in row], self.values(q))
        return np.array([float(v) for v in flat]).reshape(self.n, self.n)

    def latex(self, expr: sympy.Expr) -> str:
        """``expr`` as TeX, ``theta1`` as θ₁ and ``theta1_dot`` as its dotted symbol."""
        names = {}
        for name, q, v in zip(self.space.names, self.space.q, self.space.qdot, strict=True):
            base = sympy.latex(sympy.Symbol(name))
            names[q] = base
            names[v] = rf"\dot{{{base}}}"
        return sympy.latex(expr, symbol_names=names, ln_notation=False,
                           inv_trig_style="full")

    def coordinate_tex(self) -> list[str]:
        """Each coordinate's symbol as TeX (``theta1`` -> ``\\theta_{1}``)."""
        return [sympy.latex(sympy.Symbol(name)) for name in self.space.names]


def _nonzero(expr: sympy.Expr) -> bool:
    """Whether ``expr`` is not identically zero (structurally, then after simplify)."""
    return expr != 0 and sympy.simplify(expr) != 0


def _kinetic_mass(key: str, T: sympy.Expr, space: mechanics.PhaseSpace, *,
                  at_rest_allowed: bool) -> tuple[tuple[sympy.Expr, ...], ...]:
    """M(q) = ∂²T/∂q̇∂q̇ of a kinetic part that is a quadratic form in the velocities;
    ``at_rest_allowed``: a part without velocities is allowed (L's −U)."""
    rest = {v: 0 for v in space.qdot}
    if not at_rest_allowed and _nonzero(T.subs(rest)):
        raise PotentialError(key, "T has a part without velocities; T must be a quadratic "
                                  "form in the velocities (put that part in U)")
    for q, v in zip(space.names, space.qdot, strict=True):
        if _nonzero(sympy.diff(T, v).subs(rest)):
            raise PotentialError(key, f"a term linear in the velocity {q}_dot: a gyroscopic "
                                      "or magnetic term gives M q̈ + G q̇ + A q = 0, not "
                                      "the small oscillations M q̈ + A q = 0 of textbook §5.1")
    mass = tuple(tuple(sympy.diff(T, v, w) for w in space.qdot) for v in space.qdot)
    if any(_nonzero(sympy.diff(entry, v)) for row in mass for entry in row for v in space.qdot):
        raise PotentialError(key, "not quadratic in the velocities (a term of third order or "
                                  "more in them): the kinetic energy is ½ q̇ᵀ M(q) q̇")
    return tuple(tuple(entry.subs(rest) for entry in row) for row in mass)


def potential_system(coordinates: Sequence[str], *, U: str | None = None,
                     T: str | None = None, M: Sequence[Sequence[str | float]] | None = None,
                     L: str | None = None,
                     params: Mapping[str, float] | None = None) -> PotentialSystem:
    """Parse and derive a written system; :class:`PotentialError` names the key at fault.

    Either ``L`` (in q, ``<q>_dot`` and the constants) alone, or ``U`` (in q) with one of
    ``T`` (in q, ``<q>_dot``) and ``M`` (n × n entries, each a number or a formula in q).
    """
    params = dict(params or {})
    names = list(coordinates)
    if not 1 <= len(names) <= MAX_COORDINATES:
        raise PotentialError("system.coordinates", f"1 to {MAX_COORDINATES} coordinates "
                                                   f"(got {len(names)})")
    for name in names:
        problem = name_problem(name)
        if problem is not None:
            raise PotentialError("system.coordinates", f"not a usable name: {problem}")
    problem = alias_problem(names)
    if problem is not None:
        raise PotentialError("system.coordinates", problem)
    if len(params) > MAX_CONSTANTS:
        raise PotentialError("params", f"at most {MAX_CONSTANTS} named constants "
                                       f"(got {len(params)})")
    try:
        space = mechanics.PhaseSpace.of(names)
    except ValueError as exc:
        raise PotentialError("system.coordinates", str(exc)) from None
    taken = {s.name for s in space.q + space.qdot}
    for name, value in params.items():
        problem = name_problem(name)
        if problem is not None or name in taken:
            raise PotentialError(f"params.{name}", f"not a usable name: {problem}" if problem
                                 else "a constant may not share the name of a coordinate "
                                      "or velocity")
        if isinstance(value, bool) or not isinstance(value, int | float) \
                or not np.isfinite(value):
            raise PotentialError(f"params.{name}", f"expected a finite number, got {value!r}")
    param_symbols = {k: sympy.Symbol(k, real=True, positive=True) if v > 0
                     else sympy.Symbol(k, real=True) for k, v in params.items()}
    q_symbols = {s.name: s for s in space.q}
    qv_symbols = {**q_symbols, **{s.name: s for s in space.qdot}}

    def parse(key: str, text: str | float, symbols) -> sympy.Expr:
        if isinstance(text, int | float) and not isinstance(text, bool):
            return sympy.Float(text) if not float(text).is_integer() else sympy.Integer(int(text))
        try:
            expr = parse_expression(text, {**symbols, **param_symbols})
        except ExpressionError as exc:
            raise PotentialError(key, str(exc)) from None
        if expr.has(sympy.I, sympy.zoo, sympy.oo, sympy.nan):
            raise PotentialError(key, "has a part that is not a finite real number (such as "
                                      "sqrt(-1), log(0) or 1/0)")
        return expr

    if L is not None:
        if U is not None or T is not None or M is not None:
            raise PotentialError("system", "give L alone, or U with T or M")
        L_expr = parse("system.L", L, qv_symbols)
        mass = _kinetic_mass("system.L", L_expr, space, at_rest_allowed=True)
        U_expr = -L_expr.subs({v: 0 for v in space.qdot})
        given, T_expr = "L", None
    else:
        if U is None or (T is None) == (M is None):
            raise PotentialError("system", "give L alone, or U with one of T and M")
        U_expr = parse("system.U", U, q_symbols)
        L_expr = None
        if T is not None:
            T_expr = parse("system.T", T, qv_symbols)
            mass = _kinetic_mass("system.T", T_expr, space, at_rest_allowed=False)
            given = "T"
        else:
            T_expr = None
            rows = list(M)
            if len(rows) != len(names) or any(len(r) != len(names) for r in rows):
                raise PotentialError("system.M", f"must be {len(names)} × {len(names)}, one "
                                                 "row per coordinate")
            mass = tuple(tuple(parse(f"system.M.{i}.{j}", e, q_symbols)
                               for j, e in enumerate(r)) for i, r in enumerate(rows))
            given = "M"
    gradient = tuple(sympy.diff(U_expr, q) for q in space.q)
    hessian = tuple(tuple(sympy.diff(g, q) for q in space.q) for g in gradient)
    return PotentialSystem(space, params, param_symbols, given, U_expr, gradient, hessian,
                           mass, L_expr, T_expr)


@dataclass(frozen=True)
class Equilibrium:
    """A stationary point q₀ of U and the small-oscillation matrices there.

    ``gradient`` ∇U(q₀), ``gradient_norm`` its Euclidean norm, ``residual`` the largest
    |∂U/∂qᵢ| relative to the sizes of its parts plus Σⱼ |Aᵢⱼ| ℓ (ℓ the distance searched),
    ``M`` and ``A`` at q₀, ``omega2`` the eigenvalues of A a = ω² M a (ascending),
    ``stability`` :func:`stability` of them, ``hessian_fd_difference`` max |A_fd − A| /
    max |A| of a central difference of U with step ``fd_step``, ``evaluations`` the
    solver's calls of ∇U."""

    q: np.ndarray
    guess: np.ndarray
    potential: float
    gradient: np.ndarray
    gradient_norm: float
    residual: float
    M: np.ndarray
    A: np.ndarray
    omega2: np.ndarray
    stability: str
    hessian_fd_difference: float
    fd_step: float
    evaluations: int


def stability(omega2: np.ndarray, zero_tol: float = ZERO_TOL) -> str:
    """"stable" (every ω² > 0: A positive definite, a minimum of U), "neutral" (none
    negative, some zero within ``zero_tol`` of the largest |ω²|: the stability is decided
    by higher orders) or "unstable" (some ω² < 0: a maximum or saddle of U)."""
    omega2 = np.asarray(omega2, dtype=float)
    scale = float(np.max(np.abs(omega2))) if omega2.size else 0.0
    if scale == 0.0:
        return "neutral"
    if np.any(omega2 < -zero_tol * scale):
        return "unstable"
    return "neutral" if np.any(np.abs(omega2) <= zero_tol * scale) else "stable"


def where_text(system: PotentialSystem, q) -> str:
    """``theta1 = 0.3, theta2 = -0.2``: a point named by the config's coordinates."""
    return ", ".join(f"{n} = {float(v):.6g}" for n, v in zip(system.space.names, q, strict=True))


def _residual(system: PotentialSystem, q: np.ndarray, gradient: np.ndarray, A: np.ndarray,
              reach: float) -> float:
    """max |∂U/∂qᵢ| / (size of its parts + Σⱼ |Aᵢⱼ| ℓ); 0 where the gradient is exactly 0."""
    values = system.values(q)
    worst = 0.0
    for i, expr in enumerate(system.gradient):
        if gradient[i] == 0.0:
            continue
        scale = float(mechanics.roundoff_scale(expr, values)) + float(np.sum(np.abs(A[i]))) * reach
        worst = max(worst, abs(gradient[i]) / scale if scale > 0 else np.inf)
    return worst


def _newton(system: PotentialSystem, x0: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """Newton's method on ∇U(q) = 0 from ``x0`` with the exact Jacobian A(q) (least squares
    where A is singular), each step halved until |∇U| falls; it stops where no step lowers
    |∇U| (rounding reached, or no stationary point ahead) or after :data:`NEWTON_STEPS`.
    Returns (q, ∇U(q), evaluations of ∇U)."""
    q, g = x0.copy(), system.gradient_at(x0)
    evaluations = 1
    for _ in range(NEWTON_STEPS):
        if not np.any(g):
            break
        step = np.linalg.lstsq(system.hessian_at(q), g, rcond=None)[0]
        size = float(np.linalg.norm(g))
        for _ in range(HALVINGS):
            trial = q - step
            g_trial = system.gradient_at(trial)
            evaluations += 1
            if np.all(np.isfinite(g_trial)) and float(np.linalg.norm(g_trial)) < size:
                break
            step = step / 2
        else:
            break  # no step along Newton's direction lowers |∇U|
        q, g = trial, g_trial
    # a coordinate within rounding of zero on the search's scale is zero, where U's gradient
    # is no larger (a pendulum hanging straight down at 0, not at 10⁻¹⁶⁵ rad)
    scale = max(float(np.max(np.abs(q))), float(np.max(np.abs(q - x0))))
    snapped = np.where(np.abs(q) <= SNAP_RTOL * scale, 0.0, q)
    if np.any(snapped != q):
        g_snapped = system.gradient_at(snapped)
        evaluations += 1
        if np.all(np.isfinite(g_snapped)) and np.linalg.norm(g_snapped) <= np.linalg.norm(g):
            q, g = snapped, g_snapped
    return q, g, evaluations


def generalized_omega2(M: np.ndarray, A: np.ndarray) -> np.ndarray:
    """The eigenvalues ω² of A a = ω² M a, ascending (M = L Lᵀ by Cholesky, then the
    symmetric L⁻¹ A L⁻ᵀ; numpy alone)."""
    L = np.linalg.cholesky(M)
    Li = np.linalg.inv(L)
    B = Li @ A @ Li.T
    return np.linalg.eigvalsh(0.5 * (B + B.T))


def find_equilibrium(system: PotentialSystem, guess: Sequence[float]) -> Equilibrium:
    """The stationary point of U reached from ``guess``, with M and A there.

    Raises :class:`PotentialError` (key ``system.guess``) when U or its gradient is not
    finite at the guess, the search ends at no stationary point, or M(q₀) is not positive
    definite (key of the kinetic part).  An unstable point is returned (``stability``): the
    caller decides whether small oscillations about it mean anything.
    """
    x0 = np.asarray(guess, dtype=float)
    shown = where_text(system, x0)
    if not (np.isfinite(system.potential_at(x0)) and np.all(np.isfinite(system.gradient_at(x0)))):
        raise PotentialError("system.guess", f"U or its gradient is not finite at the guess "
                                             f"({shown})")
    q, g, evaluations = _newton(system, x0)
    A = system.hessian_at(q)
    reach = max(float(np.max(np.abs(q))), float(np.max(np.abs(q - x0))))
    finite = bool(np.all(np.isfinite(q)) and np.all(np.isfinite(g)) and np.all(np.isfinite(A)))
    residual = _residual(system, q, g, A, reach) if finite else np.inf
    if not residual <= STATIONARY_RTOL:
        raise PotentialError("system.guess", (
            f"no stationary point of U found from the guess ({shown}): the search ended at "
            f"{where_text(system, q)} with |∇U| = {float(np.linalg.norm(g)):.3g}, not rounding "
            f"(relative {residual:.3g} > {STATIONARY_RTOL:g}); start nearer an equilibrium"))
    M = system.mass_at(q)
    key = {"L": "system.L", "T": "system.T", "M": "system.M"}[system.given]
    if not np.all(np.isfinite(M)):
        raise PotentialError(key, "the mass matrix M is not finite at the equilibrium")
    if not np.allclose(M, M.T, rtol=1e-12, atol=1e-12 * float(np.max(np.abs(M)))):
        raise PotentialError(key, "the mass matrix M is not symmetric at the equilibrium")
    M = 0.5 * (M + M.T)
    lowest = float(np.linalg.eigvalsh(M).min())
    if lowest <= 0.0:
        raise PotentialError(key, f"the mass matrix M is not positive definite at the "
                                  f"equilibrium (smallest eigenvalue {lowest:.6g}): the "
                                  "kinetic energy must be positive")
    A = 0.5 * (A + A.T)
    at_guess = system.hessian_at(x0)
    size = float(np.max(np.abs(A)))
    if size <= ZERO_TOL * max(size, float(np.max(np.abs(np.nan_to_num(at_guess))))):
        raise PotentialError("system.U", "A = ∂²U/∂q∂q vanishes at the stationary point found "
                                         f"({where_text(system, q)}): U is flat to second order "
                                         "there, so there are no small oscillations about it")
    omega2 = generalized_omega2(M, A)
    h = FD_STEP * max(1.0, float(np.max(np.abs(q))))
    A_fd = central_difference_hessian(system.potential_at, q, h)
    diff = float(np.max(np.abs(A_fd - A)))
    return Equilibrium(q=q, guess=x0, potential=system.potential_at(q), gradient=g,
                       gradient_norm=float(np.linalg.norm(g)), residual=float(residual),
                       M=M, A=A, omega2=np.asarray(omega2, dtype=float),
                       stability=stability(omega2), evaluations=evaluations, fd_step=h,
                       hessian_fd_difference=diff / size if size > 0 else diff)


def secular_omega2(M: np.ndarray, A: np.ndarray) -> np.ndarray:
    """ω² of two coordinates in closed form: det(A − ω² M) = 0 is the quadratic
    a ω⁴ − b ω² + c = 0 with a = det M, b = M₁₁A₂₂ + M₂₂A₁₁ − 2M₁₂A₁₂, c = det A;
    ascending.  Written in the cancellation-free form (the smaller root as 2c/(b + √Δ))."""
    M, A = np.asarray(M, dtype=float), np.asarray(A, dtype=float)
    if M.shape != (2, 2) or A.shape != (2, 2):
        raise ValueError(f"two coordinates only (got M {M.shape}, A {A.shape})")
    a = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
    b = M[0, 0] * A[1, 1] + M[1, 1] * A[0, 0] - M[0, 1] * A[1, 0] - M[1, 0] * A[0, 1]
    c = A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]
    root = np.sqrt(max(b * b - 4 * a * c, 0.0))
    high = (b + root) / (2 * a)
    low = 2 * c / (b + root) if b + root != 0 else 0.0
    return np.array(sorted((low, high)))
