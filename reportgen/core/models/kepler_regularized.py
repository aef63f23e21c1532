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
state variable.  Used by ``reportgen bench`` against REBOUND and, through
:func:`at_physical_times`, by the ``levi_civita`` method
(:mod:`reportgen.core.integrators.regularized`).

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

from ..crossings import _quintic_hermite
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


def specific_energy(x, y, vx, vy, gm: float) -> float:
    """h = v²/2 − GM/r, the energy per unit reduced mass that (LC) is written at."""
    return 0.5 * (vx * vx + vy * vy) - gm / math.hypot(x, y)


@numba.njit(cache=True)
def node_derivatives(Y, params):
    """y' = f(y) and y'' = (∂f/∂y) f at each stored state of (LC), from :func:`rhs` and
    :func:`jac`: the slopes and curvatures of the quintic Hermite interpolant.

    Y : ndarray, shape (K, 5)  ->  F, G : ndarray, shape (K, 5)
    """
    n, d = Y.shape
    F = np.empty((n, d))
    G = np.empty((n, d))
    J = np.empty((d, d))
    for i in range(n):
        rhs(0.0, Y[i], params, F[i])
        jac(0.0, Y[i], params, J)
        for a in range(d):
            acc = 0.0
            for b in range(d):
                acc += J[a, b] * F[i, b]
            G[i, a] = acc
    return F, G


#: Newton iterations on t(s) = t_out; quadratic convergence from the linear guess within
#: one step reaches round-off in 3–4 (t' = |w|² = r varies little across a step)
_NEWTON_ITERATIONS = 8


def fictitious_times(ds: float, Y: np.ndarray, t_out: np.ndarray, h: float) -> np.ndarray:
    """Fictitious times s at which (LC) stored every ``ds`` reaches the physical times ``t_out``.

    Between two stored states t(s) is its quintic Hermite interpolant (t, t' = |w|² and
    t'' = 2 w·w' at both ends, from :func:`node_derivatives`; error O(ds⁶), the order of
    ``gauss6``), and t(s) = t_out is solved by Newton's method from the linear guess.

    Parameters
    ----------
    ds : float
        Fictitious-time spacing of the stored states.
    Y : ndarray, shape (K, 5)
        (LC) states at s = 0, ds, …, (K − 1) ds; their t (column 4) increasing.
    t_out : ndarray, shape (N,)
        Times within [Y[0, 4], Y[-1, 4]].
    h : float
        The Kepler energy (LC) is written at.

    Returns
    -------
    ndarray, shape (N,), s measured from the first stored state.
    """
    F, G = node_derivatives(np.ascontiguousarray(Y), np.array([h]))
    T = Y[:, 4]
    i = np.clip(np.searchsorted(T, t_out, side="right") - 1, 0, T.size - 2)
    j = i + 1
    c = _quintic_hermite(ds, T[i], F[i, 4], G[i, 4], T[j], F[j, 4], G[j, 4])
    sigma = (t_out - T[i]) / (T[j] - T[i])
    for _ in range(_NEWTON_ITERATIONS):
        value = ((((c[5] * sigma + c[4]) * sigma + c[3]) * sigma + c[2]) * sigma
                 + c[1]) * sigma + c[0]
        slope = (((5 * c[5] * sigma + 4 * c[4]) * sigma + 3 * c[3]) * sigma
                 + 2 * c[2]) * sigma + c[1]
        step = (value - t_out) / slope
        sigma = sigma - step
        if np.all(np.abs(step) <= 4 * np.finfo(float).eps):
            break
    return (i + sigma) * ds


def shift_to_times(Y: np.ndarray, t_out: np.ndarray, h: float) -> np.ndarray:
    """(LC) states ``Y`` (N, 5) moved along the flow to t = ``t_out`` exactly.

    For states whose t is already within a tiny δt of ``t_out``: the second-order Taylor
    step y + Δs y' + Δs² y''/2 with Δs = δt/t'.  Its change of the quadratic invariant
    is O(Δs³): round-off for Δs ~ 1e-11.
    """
    F, G = node_derivatives(np.ascontiguousarray(Y), np.array([h]))
    delta = ((t_out - Y[:, 4]) / F[:, 4])[:, None]
    out = Y + delta * F + 0.5 * delta * delta * G
    out[:, 4] = t_out
    return out


class LeviCivitaTransform:
    """The Levi-Civita regularization of one Kepler problem (GM = ``gm``): what the
    regularized methods (:mod:`reportgen.core.integrators.regularized`) need, carried by
    the model that offers it (``OdeModel.extra["levi_civita"]``,
    :func:`reportgen.core.models.kepler.model`), so the integrators name no model module.
    ``elements(x, y, vx, vy, gm)`` gives the orbit's elements (the Kepler model's own
    :func:`~reportgen.core.models.kepler.orbital_elements`, passed in so that this module
    does not import the Cartesian model that imports it).
    """

    def __init__(self, gm: float, elements):
        self.gm = float(gm)
        self._elements = elements

    def __repr__(self) -> str:
        return f"LeviCivitaTransform(gm={self.gm!r})"

    def specific_energy(self, y0) -> float:
        """h of the orbit through the Cartesian state ``y0`` = (x, y, ẋ, ẏ)."""
        return specific_energy(*y0, self.gm)

    def orbital_elements(self, y0) -> dict:
        """:func:`reportgen.core.models.kepler.orbital_elements` of the orbit through ``y0``."""
        return self._elements(*(float(v) for v in y0), self.gm)

    #: (LC) at energy h; its fictitious period; the transformation both ways; the s of
    #: physical times on stored states; the final shift of states to their times
    model = staticmethod(model)
    fictitious_period = staticmethod(orbit_fictitious_period)
    to_regularized = staticmethod(to_regularized)
    from_regularized = staticmethod(from_regularized)
    fictitious_times = staticmethod(fictitious_times)
    shift_to_times = staticmethod(shift_to_times)
