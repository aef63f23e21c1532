r"""Weierstrass's elliptic function ℘ from Jacobi theta series (no Jacobi sn, cn, dn).

℘(z) = ℘(z; g2, g3) is the doubly periodic solution of ℘'² = 4℘³ − g2 ℘ − g3 with a
double pole at the lattice points 2mω1 + 2nω3.  Here it is evaluated through the
theta-function quotients of DLMF §23.6(i),

    ℘(z) = e3 + [(π/2ω1) θ2(0) θ3(0) θ4(v)/θ1(v)]²,   v = πz/(2ω1),

with the theta functions summed as q-series in the nome q = exp(iπτ), τ = ω3/ω1
(DLMF 20.2.1-20.2.4), after reducing z into the period parallelogram centred on 0.
For a cubic with three real roots e1 > e2 > e3 (a rectangular lattice, as for the
heavy top) the half-periods come from the arithmetic-geometric mean,

    ω1 = π / (2 M(√(e1 − e3), √(e1 − e2))),   ω3 = iπ / (2 M(√(e1 − e3), √(e2 − e3))),

(ω1 = K(k)/√(e1 − e3), ω3 = iK′(k)/√(e1 − e3), DLMF §23.6(iv) with K = π/(2M(1, k′)),
DLMF 19.8.5).  Nothing here goes through the Jacobi elliptic functions, so that ℘ is an
independent check of the sn² closed forms in :mod:`reportgen.core.heavy_top_theory`.

The real period itself is also a loop integral: for P(x) = c(x − x1)(x2 − x)(x3 − x),
T = ∮ dx/√P(x) once round the cut [x1, x2] (:func:`loop_period`, the trapezoidal rule on
an ellipse about the cut; :func:`sine_squared_period`, the same on the cut itself), and
for ℘'s cubic 4℘³ − g2℘ − g3 round [e3, e2] it is 2ω1: with ℘ = e3 + (e2 − e3) sin²s,
∫_{e3}^{e2} d℘/√|4Π(℘ − e_j)| = K(k)/√(e1 − e3) = ω1 (DLMF §23.6(iv)).

References
----------
.. [1] NIST DLMF §20.2 (theta functions), §23.2-23.6 (℘, invariants, lattice cases,
       theta-function and Jacobi-function forms), §19.8(i) (AGM).
.. [2] Whittaker & Watson, *A Course of Modern Analysis*, ch. XX-XXI.
.. [3] L. N. Trefethen, J. A. C. Weideman, "The exponentially convergent trapezoidal
       rule", SIAM Review 56 (2014) 385-458, §3 (periodic analytic integrands).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

#: terms of a theta q-series are dropped below this size (relative to the leading one)
_SERIES_EPS = 1e-18
#: |q| above this makes the series too long (a degenerate lattice, e2 → e1)
_MAX_NOME = 0.99


def agm(a: float, b: float) -> float:
    """Arithmetic-geometric mean M(a, b) of two positive numbers (DLMF 19.8.1)."""
    if not (a > 0.0 and b > 0.0):
        raise ValueError(f"agm needs positive arguments (got {a}, {b})")
    for _ in range(64):
        if abs(a - b) <= 4e-16 * a:
            break
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return 0.5 * (a + b)


def invariants(e1, e2, e3) -> tuple[float, float]:
    """g2 = −4(e1e2 + e1e3 + e2e3) = 2(e1² + e2² + e3²), g3 = 4 e1 e2 e3 (DLMF 23.3.4-5),
    for roots with e1 + e2 + e3 = 0."""
    return 2.0 * (e1 * e1 + e2 * e2 + e3 * e3), 4.0 * e1 * e2 * e3


def half_periods(e1: float, e2: float, e3: float) -> tuple[float, float]:
    """Real half-period ω and |ω′| of the rectangular lattice of real roots e1 > e2 > e3.

    ω1 = π/(2M(√(e1 − e3), √(e1 − e2))) and ω3 = i π/(2M(√(e1 − e3), √(e2 − e3)))
    (DLMF §23.6(iv), 19.8.5); returned as (ω1, |ω3|).
    """
    return half_periods_from_gaps(e1 - e3, e1 - e2, e2 - e3)


def half_periods_from_gaps(d13: float, d12: float, d23: float) -> tuple[float, float]:
    """:func:`half_periods` from the root differences e1 − e3, e1 − e2, e2 − e3 (all > 0),
    for callers that know them without cancellation."""
    if not (d13 > 0.0 and d12 > 0.0 and d23 > 0.0):
        raise ValueError(f"half-periods need real roots e1 > e2 > e3 (got differences "
                         f"e1 − e3 = {d13}, e1 − e2 = {d12}, e2 − e3 = {d23})")
    r13 = math.sqrt(d13)
    return (0.5 * math.pi / agm(r13, math.sqrt(d12)),
            0.5 * math.pi / agm(r13, math.sqrt(d23)))


def _series_terms(tau: complex) -> int:
    """Terms of the theta series for |q^{n² − n}| ≤ _SERIES_EPS on the reduced cell."""
    log_q = math.pi * tau.imag  # −ln|q|
    if math.exp(-log_q) > _MAX_NOME:
        raise ValueError(f"nome |q| = {math.exp(-log_q):.6g} > {_MAX_NOME}: degenerate lattice")
    need = -math.log(_SERIES_EPS) / log_q  # n² − n ≥ need
    return int(math.ceil(0.5 + math.sqrt(0.25 + need))) + 1


def theta_functions(v, tau: complex, terms: int | None = None):
    """Jacobi theta functions θ1..θ4(v | τ) as q-series, q = exp(iπτ) (DLMF 20.2.1-20.2.4).

    Parameters
    ----------
    v : array_like, shape (N,)
        Complex arguments (kept within |Im v| ≤ π Im τ / 2 for full accuracy).
    tau : complex
        Lattice ratio, Im τ > 0.

    Returns
    -------
    tuple of 4 ndarrays, shape (N,), complex
    """
    n_terms = terms or _series_terms(complex(tau))
    v = np.asarray(v, dtype=np.complex128)[..., None]
    n = np.arange(n_terms)
    # q^{(n+½)²} and q^{n²} as exponentials: no branch of q^{1/4} to choose
    q_half = np.exp(1j * math.pi * tau * (n + 0.5) ** 2)
    q_int = np.exp(1j * math.pi * tau * n[1:] ** 2.0)
    sign = np.where(n % 2 == 0, 1.0, -1.0)
    odd = (2 * n + 1) * v
    even = 2 * n[1:] * v
    t1 = 2.0 * np.sum(sign * q_half * np.sin(odd), axis=-1)
    t2 = 2.0 * np.sum(q_half * np.cos(odd), axis=-1)
    t3 = 1.0 + 2.0 * np.sum(q_int * np.cos(even), axis=-1)
    t4 = 1.0 + 2.0 * np.sum(sign[1:] * q_int * np.cos(even), axis=-1)
    return t1, t2, t3, t4


@dataclass(frozen=True)
class Lattice:
    """The period lattice 2mω1 + 2nω3 of ℘ and its theta constants.

    Attributes
    ----------
    omega1, omega3 : complex
        Half-periods with Im(ω3/ω1) > 0 (for real roots: ω1 real, ω3 imaginary).
    """

    omega1: complex
    omega3: complex
    tau: complex = field(init=False)
    terms: int = field(init=False)
    theta0: tuple[complex, complex, complex] = field(init=False)  # θ2(0), θ3(0), θ4(0)

    def __post_init__(self):
        tau = complex(self.omega3) / complex(self.omega1)
        if tau.imag <= 0.0:
            raise ValueError(f"half-periods need Im(ω3/ω1) > 0 (got τ = {tau})")
        object.__setattr__(self, "tau", tau)
        object.__setattr__(self, "terms", _series_terms(tau))
        _t1, t2, t3, t4 = theta_functions(np.zeros(1), tau, self.terms)
        object.__setattr__(self, "theta0", (complex(t2[0]), complex(t3[0]), complex(t4[0])))

    @classmethod
    def from_roots(cls, e1: float, e2: float, e3: float) -> Lattice:
        """The rectangular lattice of three real roots e1 > e2 > e3 (:func:`half_periods`)."""
        return cls.rectangular(*half_periods(e1, e2, e3))

    @classmethod
    def rectangular(cls, omega: float, omega_prime: float) -> Lattice:
        """The lattice of half-periods ω1 = ω (real) and ω3 = iω′."""
        return cls(complex(omega), complex(0.0, omega_prime))

    @property
    def scale(self) -> complex:
        """(π/2ω1)², the factor of every theta quotient."""
        return (math.pi / (2.0 * self.omega1)) ** 2

    @property
    def roots(self) -> tuple[complex, complex, complex]:
        """e1, e2, e3 = ℘(ω1), ℘(ω1 + ω3), ℘(ω3) from the theta constants (DLMF §23.6(i)):
        e1 = (π²/12ω1²)(θ2⁴ + 2θ4⁴), e2 = (π²/12ω1²)(θ2⁴ − θ4⁴), e3 = −(π²/12ω1²)(2θ2⁴ + θ4⁴)."""
        t2, _t3, t4 = (x**4 for x in self.theta0)
        c = self.scale / 3.0
        return c * (t2 + 2.0 * t4), c * (t2 - t4), -c * (2.0 * t2 + t4)

    @property
    def invariants(self) -> tuple[complex, complex]:
        """g2, g3 of this lattice (from :attr:`roots`, DLMF 23.3.4-5)."""
        return invariants(*self.roots)

    def reduce(self, z) -> np.ndarray:
        """z moved by a period into the parallelogram {2ω1 s + 2ω3 r : |s|, |r| ≤ ½}."""
        z = np.asarray(z, dtype=np.complex128)
        a, b = 2.0 * complex(self.omega1), 2.0 * complex(self.omega3)
        det = a.real * b.imag - a.imag * b.real
        s = (z.real * b.imag - z.imag * b.real) / det
        r = (a.real * z.imag - a.imag * z.real) / det
        return z - a * np.round(s) - b * np.round(r)

    def _thetas(self, z):
        v = math.pi * self.reduce(z) / (2.0 * complex(self.omega1))
        return theta_functions(v, self.tau, self.terms)


def wp_minus_e3(z, lattice: Lattice) -> np.ndarray:
    """℘(z) − e3 = [(π/2ω1) θ2(0) θ3(0) θ4(v)/θ1(v)]², v = πz/(2ω1) (DLMF §23.6(i)).

    Evaluated as one square, without the cancellation of ℘ − e3 near z = ω3 where ℘ → e3.

    Parameters
    ----------
    z : array_like, shape (N,)
        Complex (or real) arguments, any size: reduced by the periods first.

    Returns
    -------
    ndarray, shape (N,), complex
    """
    t1, _t2, _t3, t4 = lattice._thetas(z)
    a2, a3, _a4 = lattice.theta0
    return lattice.scale * (a2 * a3 * t4 / t1) ** 2


def wp(z, lattice: Lattice) -> np.ndarray:
    """Weierstrass ℘(z) on ``lattice``: e3 + (℘ − e3) (:func:`wp_minus_e3`)."""
    return lattice.roots[2] + wp_minus_e3(z, lattice)


def wp_prime(z, lattice: Lattice) -> np.ndarray:
    """℘′(z) = −2 (π/2ω1)³ [θ2θ3θ4(0)]² θ2(v) θ3(v) θ4(v)/θ1(v)³, v = πz/(2ω1).

    From ℘ − e_j = [(π/2ω1) c_j θ_{j+1}(v)/θ1(v)]² and ℘′² = 4Π(℘ − e_j); the sign is the
    one of the pole, ℘′ ≈ −2/z³ (DLMF 23.2.4 with 23.6(i)).
    """
    t1, t2, t3, t4 = lattice._thetas(z)
    a2, a3, a4 = lattice.theta0
    k = math.pi / (2.0 * complex(lattice.omega1))
    return -2.0 * k**3 * (a2 * a3 * a4) ** 2 * t2 * t3 * t4 / t1**3


# ------------------------------------------------ periods as integrals round the cut
@dataclass(frozen=True)
class PeriodIntegral:
    """A period ∮ dx/√P(x) of a cubic with real roots, by the trapezoidal rule.

    Attributes
    ----------
    value : float
        The period (the real part of the sum; P's variable per unit of √P).
    imag : float
        Imaginary part the sum leaves (zero in exact arithmetic), same unit as ``value``.
    nodes : int
        Nodes of the converged rule.
    rho : float
        The contour: the ellipse x − m = r cos(φ − iρ) round the cut (ρ = 0: the cut itself,
        the sin² substitution).
    strip : float
        a = arccosh(d/r): the third root's conformal distance from the cut; the rule's error
        falls as exp(−N(a − ρ)).
    change : float
        |T_N − T_{N/2}|/|T_N| at the last doubling (the error of T_{N/2}).
    converged : bool
        Whether two sums agreed within the node budget: the doubling stops near
        N ≈ 60/(a − ρ), more than the budget for a third root within ~1e-7 (x2 − x1) of
        the cut (k² → 1, a → 0).
    """

    value: float
    imag: float
    nodes: int
    rho: float
    strip: float
    change: float
    converged: bool = True


#: the doubling stops once T_{N/2} agrees with T_N to this; T_N is then far better (the
#: error falls geometrically, so squares at each doubling)
_PERIOD_RTOL = 1e-13
#: the node budget (some 30 ms a sum): enough for a ≳ 5e-4, i.e. x3 − x2 ≳ 6e-8 (x2 − x1)
PERIOD_MAX_NODES = 2**18


def _cut_geometry(width: float, gap: float) -> tuple[float, float]:
    """(r, a): half the cut's width and a = arccosh(d/r), d = r + gap the third root's
    distance from the cut's middle; arccosh(1 + g/r) formed without cancellation."""
    if not (width > 0.0 and gap > 0.0):
        raise ValueError(f"a period round the cut needs x1 < x2 < x3 (got x2 − x1 = {width}, "
                         f"x3 − x2 = {gap})")
    r = 0.5 * width
    t = gap / r
    return r, math.log1p(t + math.sqrt(t * (t + 2.0)))


def _trapezoid_doubling(rule, rate: float, nodes: int | None = None
                        ) -> tuple[complex, int, float, bool]:
    """Periodic trapezoidal sums (2π/N) Σ g(φ_k), N = 16, 32, …, until two agree.

    ``rule(phi)`` gives g on an array of angles; each doubling evaluates only the new
    (odd) nodes.  Returns (sum, N, relative change at the last doubling, converged); at
    the budget :data:`PERIOD_MAX_NODES` the last sum is returned, not converged — and
    none is summed (NaN, N the nodes needed) when the error's rate exp(−N·``rate``) says
    beforehand that the budget cannot do.  ``nodes``: one sum with exactly that many
    nodes instead (change NaN), to watch the convergence.
    """
    if nodes is None and rate * PERIOD_MAX_NODES < 2.0 * math.log(1.0 / _PERIOD_RTOL):
        return complex(math.nan, math.nan), int(2.0 * math.log(1.0 / _PERIOD_RTOL) / rate), \
            math.nan, False
    if nodes is not None:
        if nodes < 1:
            raise ValueError(f"nodes: expected a positive number of nodes, got {nodes}")
        total = np.sum(rule(2.0 * math.pi * np.arange(nodes) / nodes))
        return 2.0 * math.pi * total / nodes, int(nodes), math.nan, True
    n = 16
    total = np.sum(rule(2.0 * math.pi * np.arange(n) / n))
    value, change = 2.0 * math.pi * total / n, math.inf
    while n < PERIOD_MAX_NODES:
        odd = 2.0 * math.pi * (np.arange(n) + 0.5) / n
        total = total + np.sum(rule(odd))
        n *= 2
        new = 2.0 * math.pi * total / n
        change = float(abs(new - value) / abs(new))
        value = new
        if change <= _PERIOD_RTOL:
            return value, n, change, True
    return value, n, change, False


def loop_period(lead: float, width: float, gap: float, *, rho: float | None = None,
                nodes: int | None = None) -> PeriodIntegral:
    r"""T = ∮ dx/√P(x) once round the cut [x1, x2], by the trapezoidal rule on an ellipse.

    P(x) = lead·(x − x1)(x2 − x)(x3 − x) with lead > 0 and x1 < x2 < x3 is positive on
    [x1, x2], where a particle with ẋ² = P(x) oscillates; T = 2∫_{x1}^{x2} dx/√P(x) is its
    period.  Off the real axis √P(x) = i √(lead (x3 − x)) √((x − x1)(x − x2)) is one
    analytic function outside the cuts [x1, x2] and [x3, ∞) (principal square roots;
    √((x − x1)(x − x2)) = v√(1 − r²/v²) ~ v at infinity, v = x − m, m = (x1 + x2)/2,
    r = (x2 − x1)/2), and the integral counter-clockwise round any closed curve that
    encloses the cut but not x3 is, by Cauchy's theorem, the two sides of the cut: T.

    The curve is the ellipse v = r cos(φ − iρ), 0 ≤ φ < 2π (foci x1, x2), with
    0 < ρ < a = arccosh((x3 − m)/r); the integrand is then an analytic periodic function of
    φ, and the trapezoidal rule converges geometrically, as exp(−N(a − ρ)) (Trefethen &
    Weideman, SIAM Rev. 56 (2014) 385, §3).  Default ρ = a/2: halfway, conformally, from
    the cut to x3.  Nothing here uses elliptic functions.

    Parameters
    ----------
    lead : float
        Leading coefficient of P (β for the heavy top's f(u); 4 for ℘'s cubic).
    width, gap : float
        x2 − x1 and x3 − x2, both > 0 (passed as differences: no cancellation).
    rho : float, optional
        The ellipse, 0 < ρ < a.
    nodes : int, optional
        A fixed number of nodes N (default: doubled from 16 until two sums agree to
        1e-13, the error of the last one then far smaller; at most 2¹⁸, see
        :attr:`PeriodIntegral.converged`).

    Returns
    -------
    PeriodIntegral
        T in units of x/√P (seconds for the top).
    """
    r, a = _cut_geometry(width, gap)
    rho = 0.5 * a if rho is None else float(rho)
    if not 0.0 < rho < a:
        raise ValueError(f"the ellipse must enclose the cut and not x3: expected "
                         f"0 < ρ < {a:.6g}, got ρ = {rho}")

    def integrand(phi):
        theta = phi - 1j * rho
        v = r * np.cos(theta)
        dv = -r * np.sin(theta)  # dv/dφ
        # (v − r)(v + r) and x3 − x = gap + (r − v) from half angles: exact near the ends
        v_minus_r = -2.0 * r * np.sin(0.5 * theta) ** 2
        v_plus_r = 2.0 * r * np.cos(0.5 * theta) ** 2
        # √((x − x1)(x − x2)) on the branch ~ v at infinity (cut [x1, x2]), principal roots
        pair_root = v * np.sqrt(v_minus_r * v_plus_r / (v * v))
        sqrt_p = 1j * np.sqrt(lead * (gap - v_minus_r)) * pair_root
        return dv / sqrt_p

    value, n, change, converged = _trapezoid_doubling(integrand, a - rho, nodes)
    return PeriodIntegral(value=float(value.real), imag=float(value.imag), nodes=n,
                          rho=rho, strip=a, change=change, converged=converged)


def sine_squared_period(lead: float, width: float, gap: float, *, nodes: int | None = None
                        ) -> PeriodIntegral:
    """T = 2∫_{x1}^{x2} dx/√P(x) on the real axis, with x = x1 + (x2 − x1) sin²s.

    The substitution removes both endpoint singularities: dx/√P = 2 ds/√(lead (x3 − x)),
    x3 − x = gap + width cos²s, so T = 4∫_0^{π/2} ds/√(lead (gap + width cos²s)) =
    ∫_0^{2π} dφ/√(lead (gap + width cos²(φ/2))), the integrand analytic and periodic: the
    trapezoidal rule converges geometrically (as exp(−N a), a = arccosh((x3 − m)/r)).
    The limit ρ → 0 of :func:`loop_period`, with the square root of the pair of roots
    cancelled by hand.  Parameters as for :func:`loop_period`.
    """
    _r, a = _cut_geometry(width, gap)

    def integrand(phi):
        return 1.0 / np.sqrt(lead * (gap + width * np.cos(0.5 * phi) ** 2))

    value, n, change, converged = _trapezoid_doubling(integrand, a, nodes)
    return PeriodIntegral(value=float(np.real(value)), imag=0.0, nodes=n, rho=0.0,
                          strip=a, change=change, converged=converged)
