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

References
----------
.. [1] NIST DLMF §20.2 (theta functions), §23.2-23.6 (℘, invariants, lattice cases,
       theta-function and Jacobi-function forms), §19.8(i) (AGM).
.. [2] Whittaker & Watson, *A Course of Modern Analysis*, ch. XX-XXI.
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
