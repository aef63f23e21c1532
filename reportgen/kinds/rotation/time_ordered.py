"""R(t) rebuilt from ω(t) alone, notes (8.36)–(8.37): Ṙ R⁻¹ = [ω]× (space axes) is solved by
the time-ordered exponential R(t) = T exp(∫₀ᵗ[ω]× dt′) R(0), here two ways, each against the
Euler-angle path's own R(t):

* the notes' series (8.37) term by term, Iₖ(t) = ∫₀ᵗ [ω(t′)]× Iₖ₋₁(t′) dt′ with I₀ = 1, each
  integral spectral (Chebyshev interpolation on the whole run, integrated exactly): the
  partial sums S_K = I₀ + … + I_K converge like (|ω|t)^(K+1)/(K+1)!, but their terms grow to
  about e^(|ω|t)/√(2π|ω|t) first, and the cancellation costs that many digits;
* Magnus's fourth-order method (Blanes, Casas, Oteo & Ros 2009, eq. (253)), steps of h:
  Ω = h(A₁ + A₂)/2 + (√3/12)h²[A₂, A₁] with A at the two Gauss points, R ← exp(Ω)R, an
  exact rotation at every step; its error falls as h⁴.

ω(t) is the Euler rates' formula (notes (10.20)) on the sample path of ``[euler]``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.polynomial import chebyshev as C

from ...lazy import lazy_module

rotations = lazy_module("reportgen.core.rotations")  # the report never imports core

#: Chebyshev points on the whole run for the series (ω is a trigonometric polynomial in
#: t: enough for its coefficients to fall to rounding at the configured lengths)
NODES = 96
#: the series is summed to this order at most
MAX_ORDER = 80
#: Magnus steps per run, halving
MAGNUS_STEPS = (8, 16, 32, 64, 128)


def _expm_skew(W) -> np.ndarray:
    """exp of an antisymmetric 3 × 3 matrix [w]×: the rotation by |w| about w/|w|
    (Rodrigues' formula, core's passive A(n, Φ) transposed)."""
    w = rotations.vee(W)
    a = float(np.linalg.norm(w))
    return np.eye(3) if a == 0.0 else rotations.rotation_formula_matrix(w / a, a).T


def rebuild(angles0, rates, convention: str, duration: float) -> dict:
    """The series and Magnus rebuilds of R(duration) from ω(t) (module docstring), each
    against the Euler matrix there: a dict for ``/analysis/euler/time_ordered``."""
    angles0, rates = np.asarray(angles0, dtype=float), np.asarray(rates, dtype=float)

    def omega(t):
        a = angles0 + np.asarray(t)[..., None] * rates
        return rotations.omega_from_euler_rates(*np.moveaxis(a, -1, 0), *rates, frame="space",
                                                convention=convention)

    R0 = rotations.euler_matrix(*angles0, convention)
    R_end = rotations.euler_matrix(*(angles0 + duration * rates), convention)
    # the series (8.37) on Chebyshev points x ∈ [−1, 1], t = (x + 1) T/2
    x = np.cos(np.pi * np.arange(NODES) / (NODES - 1))[::-1]
    t = 0.5 * (x + 1.0) * duration
    omega_nodes = omega(t)
    W = rotations.skew(omega_nodes)  # (NODES, 3, 3)
    term = np.broadcast_to(np.eye(3), (NODES, 3, 3)).copy()
    total = term[-1].copy()  # S at t = T (x = 1 is the last node)
    errors, sizes = [], []
    for _ in range(MAX_ORDER):
        f = W @ term  # (NODES, 3, 3): the integrand of the next term
        coef = C.chebfit(x, f.reshape(NODES, 9), NODES - 1)
        integral = C.chebint(coef, lbnd=-1.0) * (0.5 * duration)
        term = C.chebval(x, integral).T.reshape(NODES, 3, 3)
        total = total + term[-1]
        sizes.append(float(np.max(np.abs(term))))
        errors.append(float(np.max(np.abs(total @ R0 - R_end))))
    omega_max = float(np.max(np.linalg.norm(omega_nodes, axis=-1)))
    orders = np.arange(1, MAX_ORDER + 1)
    bound = np.array([math.exp(k * math.log(omega_max * duration) - math.lgamma(k + 1.0))
                      if omega_max * duration > 0 else 0.0 for k in orders + 1])
    # Magnus, fourth order
    c1, c2 = 0.5 - math.sqrt(3.0) / 6.0, 0.5 + math.sqrt(3.0) / 6.0
    magnus = []
    for n in MAGNUS_STEPS:
        h = duration / n
        R = R0.copy()
        for i in range(n):
            A1, A2 = rotations.skew(omega(i * h + c1 * h)), rotations.skew(omega(i * h + c2 * h))
            Om = 0.5 * h * (A1 + A2) + (math.sqrt(3.0) / 12.0) * h * h * (A2 @ A1 - A1 @ A2)
            R = _expm_skew(Om) @ R
        magnus.append(float(np.max(np.abs(R - R_end))))
    magnus = np.asarray(magnus)
    usable = magnus > 1e3 * np.finfo(float).eps
    pairs = np.nonzero(usable[:-1] & usable[1:])[0]
    order = (float(np.median(np.log2(magnus[pairs] / magnus[pairs + 1])))
             if pairs.size else math.nan)
    return {"orders": orders, "series_error": np.asarray(errors),
            "series_term": np.asarray(sizes), "series_bound": bound,
            "omega_t": omega_max * duration, "series_best": float(np.min(errors)),
            "series_largest_term": float(np.max(sizes)),
            "magnus_steps": np.asarray(MAGNUS_STEPS, dtype=np.int64),
            "magnus_error": magnus, "magnus_order": order}
