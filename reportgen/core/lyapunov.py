"""Whether an orbit is chaotic, and how fast nearby orbits separate.

Two reference runs (DOP853, rtol 1e-14) start :data:`PERTURBATION` × the state's size
apart.  On a regular (quasi-periodic) orbit their separation d(t) grows at most like a
power of t (shear: the frequencies depend on the actions); on a chaotic one it grows like
e^{λt} until it reaches the orbit's size.  An orbit is called chaotic when d grows by
:data:`CHAOTIC_GROWTH` within the run; λ is then the mean rate of that growth,
ln(d(t₂)/d(t₁)) / (t₂ − t₁), between t₁ (d = 10 d₀: the separation has turned towards the
unstable direction) and t₂ (d = :data:`CHAOTIC_GROWTH` d₀, far below the orbit's size), and
the Lyapunov time is 1/λ (Benettin et al., *Meccanica* 15, 9 (1980), the two-orbit
method; without renormalisation, which the 1e6 range of the growth does not need).

Measured on the shipped scenes: the Hénon–Heiles orbit at E = 1/6 and the double pendulum
grow by > 1e7, the Pythagorean three-body problem by > 1e8; the regular scenes (the
figure-eight, Sun–Earth–Moon, the regular Hénon–Heiles orbit, Kepler, two centres) by
1.6–2300 over their runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .integrators import integrate

#: the second run starts this far from the first, relative to the state's largest |value|
PERTURBATION = 1e-10
#: a separation grown by this factor within the run is exponential (chaos), not shear
CHAOTIC_GROWTH = 1e6


@dataclass(frozen=True)
class Divergence:
    """How two orbits :data:`PERTURBATION` apart separate (module docstring)."""

    #: largest separation over the run / initial separation
    growth: float
    #: the mean exponential rate λ (NaN for a regular orbit) [1/time]
    exponent: float

    @property
    def chaotic(self) -> bool:
        return math.isfinite(self.exponent)

    @property
    def lyapunov_time(self) -> float:
        """1/λ: the time over which a small error grows by e (inf when regular)."""
        return 1.0 / self.exponent if self.chaotic and self.exponent > 0 else math.inf


def divergence(model, y0: np.ndarray, t_eval: np.ndarray,
               perturbation: float = PERTURBATION) -> Divergence:
    """Separation of the orbit from ``y0`` and one started ``perturbation`` × max|y0|
    away (along (1, −1, 1, …)/√d), sampled on ``t_eval``, shape (N,)."""
    y0 = np.asarray(y0, dtype=np.float64)
    direction = np.where(np.arange(y0.size) % 2 == 0, 1.0, -1.0) / math.sqrt(y0.size)
    d0 = perturbation * max(float(np.max(np.abs(y0))), 1e-300)
    a = integrate(model, y0, t_eval, method="dop853", rtol=1e-14, atol=1e-16)
    b = integrate(model, y0 + d0 * direction, t_eval, method="dop853", rtol=1e-14,
                  atol=1e-16)
    d = np.linalg.norm(a.y - b.y, axis=1)
    finite = np.isfinite(d)
    if not np.all(finite):  # one run failed: keep what both reached
        d = d[: int(np.argmin(finite))]
    d0 = float(d[0]) if d.size and d[0] > 0 else d0
    growth = float(np.max(d) / d0) if d.size else math.nan
    if not growth >= CHAOTIC_GROWTH:
        return Divergence(growth=growth, exponent=math.nan)
    t = np.asarray(t_eval, dtype=np.float64)[: d.size]
    i1 = int(np.argmax(d >= 10.0 * d0))
    i2 = int(np.argmax(d >= CHAOTIC_GROWTH * d0))
    rate = math.log(d[i2] / d[i1]) / (t[i2] - t[i1]) if t[i2] > t[i1] else math.inf
    return Divergence(growth=growth, exponent=rate)
