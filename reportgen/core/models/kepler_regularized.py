r"""Planar Kepler motion in Levi-Civita regularized variables.

With z = x + i y = w² (w complex) and the fictitious time s, dt/ds = |w|², the
Kepler problem z̈ = −μ z/|z|³ at energy h becomes the harmonic oscillator

    w'' = (h/2) w,        t' = |w|²,                                   (LC)

regular at collisions and with the *quadratic* invariant 2|w'|² − h|w|² = μ.
Gauss–Legendre collocation conserves quadratic invariants exactly, so integrating
(LC) with ``gauss6`` keeps the energy error at the level of rounding over any
number of orbits; steps uniform in s are uniform in eccentric anomaly, so a
highly eccentric orbit costs no more than a circular one.

This is the unperturbed problem (h fixed); a perturbed one would carry h as a
state variable.  Used by ``reportgen bench`` against REBOUND.

References
----------
.. [1] Levi-Civita, T., Acta Math. 42 (1920) 99-144.
.. [2] Stiefel, E. L. & Scheifele, G., *Linear and Regular Celestial Mechanics*,
       Springer (1971), §4 and §9.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..model import OdeModel

# state (w1, w2, w1', w2', t); params = (h,)


@numba.njit(cache=True)
def rhs(s, y, params, out):
    half_h = 0.5 * params[0]
    out[0] = y[2]
    out[1] = y[3]
    out[2] = half_h * y[0]
    out[3] = half_h * y[1]
    out[4] = y[0] * y[0] + y[1] * y[1]


@numba.njit(cache=True)
def jac(s, y, params, out):
    for i in range(5):
        for j in range(5):
            out[i, j] = 0.0
    out[0, 2] = 1.0
    out[1, 3] = 1.0
    out[2, 0] = 0.5 * params[0]
    out[3, 1] = 0.5 * params[0]
    out[4, 0] = 2.0 * y[0]
    out[4, 1] = 2.0 * y[1]


def model(h: float) -> OdeModel:
    """(LC) at Kepler energy ``h`` < 0."""
    return OdeModel(name="Kepler (Levi-Civita)", columns=("w1", "w2", "w1_s", "w2_s", "t"),
                    rhs=rhs, params=np.array([h]), jac=jac)


def to_regularized(x, y, vx, vy, t=0.0) -> np.ndarray:
    """(x, y, ẋ, ẏ) -> (w, w', t): w = √z, w' = |w|² ẇ = conj(w) ż / 2."""
    w = np.sqrt(complex(x, y))
    w_s = np.conj(w) * complex(vx, vy) / 2.0
    return np.array([w.real, w.imag, w_s.real, w_s.imag, t])


def from_regularized(state: np.ndarray):
    """(N, 5) regularized states -> x, y, vx, vy, t, each (N,): z = w², ż = 2 w w'/|w|²."""
    w = state[:, 0] + 1j * state[:, 1]
    w_s = state[:, 2] + 1j * state[:, 3]
    z = w * w
    z_dot = 2.0 * w * w_s / np.abs(w) ** 2
    return z.real, z.imag, z_dot.real, z_dot.imag, state[:, 4]


def orbit_fictitious_period(h: float) -> float:
    """Fictitious time of one orbit: w oscillates at ω = √(−h/2) and z = w² at 2ω."""
    return math.pi / math.sqrt(-0.5 * h)
