r"""The harmonic oscillator H = p²/2m + m ω² q²/2 (lecture notes §4, §6, §7).

The compiled model is the general linear separable system q' = a p, p' = −b q,
so the same code integrates the original Hamiltonian (a = 1/m, b = m ω²) and the
one after the swap transformation F1 = q Q (6.6–6.11), K(Q, P) = Q²/2m + m ω² P²/2
(a = m ω², b = 1/m).

References
----------
.. [1] Lecture notes §6, eqs. (6.6)-(6.11); §7, eqs. (7.33)-(7.38).
.. [2] Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., §9.1 and §10.2.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..model import OdeModel, Separable

# params = (a, b): q' = a p, p' = -b q


@numba.njit(cache=True, error_model="numpy")
def rhs(t, y, params, out):
    out[0] = params[0] * y[1]
    out[1] = -params[1] * y[0]


@numba.njit(cache=True)
def jac(t, y, params, out):
    out[0, 0] = 0.0
    out[0, 1] = params[0]
    out[1, 0] = -params[1]
    out[1, 1] = 0.0


@numba.njit(cache=True)
def drift(p, params, out):
    out[0] = params[0] * p[0]


@numba.njit(cache=True)
def kick(q, params, out):
    out[0] = -params[1] * q[0]


def model(a: float, b: float, columns=("q", "p"), name="oscillator") -> OdeModel:
    # DOP853 on a driver with rhs inlined and d = 2 (see reportgen.core.model.OdeModel)
    return OdeModel(name=name, columns=columns, rhs=rhs, params=np.array([a, b]),
                    separable=Separable(n=1, drift=drift, kick=kick), jac=jac,
                    specialize=True)


def hamilton_model(m: float, omega: float) -> OdeModel:
    """Hamilton's equations of H: q' = p/m, p' = −m ω² q."""
    return model(1.0 / m, m * omega**2)


def swapped_model(m: float, omega: float) -> OdeModel:
    """Hamilton's equations of K(Q, P) = Q²/2m + m ω² P²/2 after Q = p, P = −q (6.11)."""
    return model(m * omega**2, 1.0 / m, columns=("Q", "P"), name="oscillator (swapped)")


def swap(q, p):
    """The canonical map of F1 = q Q: p = ∂F/∂q = Q, P = −∂F/∂Q = −q (6.8-6.9)."""
    return np.asarray(p), -np.asarray(q)


def exact_solution(t, q0, p0, m, omega):
    """q(t) = q0 cos ωt + p0/(mω) sin ωt,  p(t) = p0 cos ωt − m ω q0 sin ωt."""
    t = np.asarray(t, dtype=np.float64)
    c, s = np.cos(omega * t), np.sin(omega * t)
    return q0 * c + p0 / (m * omega) * s, p0 * c - m * omega * q0 * s


def energy(q, p, m, omega):
    return 0.5 * np.asarray(p) ** 2 / m + 0.5 * m * omega**2 * np.asarray(q) ** 2


def hamilton_jacobi_constants(q, p, t, m, omega):
    """The new momentum E and coordinate β = ∂S/∂E of the complete integral (7.33-7.38).

    With W(q, E) = ∫ √(2m E − m² ω² q²) dq and S = W − E t, the conjugate
    coordinate β obeys q = √(2E/(mω²)) sin(ω(t + β)), p = √(2mE) cos(ω(t + β)),
    so β = atan2(m ω q, p)/ω − t.  Both are constant along any true trajectory.
    """
    q, p, t = np.asarray(q), np.asarray(p), np.asarray(t)
    e = energy(q, p, m, omega)
    beta = np.arctan2(m * omega * q, p) / omega - t
    period = 2 * math.pi / omega
    if beta.ndim:  # atan2 wraps once per period: unwrap about the first value
        beta = beta[0] + np.mod(beta - beta[0] + period / 2, period) - period / 2
    return e, beta


def hamilton_jacobi_solution(t, e, beta, m, omega):
    """q(t), p(t) from the Hamilton–Jacobi constants (7.38)."""
    t = np.asarray(t, dtype=np.float64)
    phase = omega * (t + beta)
    return math.sqrt(2 * e / (m * omega**2)) * np.sin(phase), math.sqrt(2 * m * e) * np.cos(phase)
