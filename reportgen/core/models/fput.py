r"""The Fermi–Pasta–Ulam–Tsingou stiff–soft chain (Hairer, Lubich & Wanner, GNI §I.5.1).

2m unit masses; stiff linear springs of frequency ω join q_{2i−1} and q_{2i};
soft quartic springs join q_{2i} and q_{2i+1}, the ends held by soft springs to
q_0 = q_{2m+1} = 0.  The Hamiltonian (GNI eq. I.5.1)

    H(p, q) = ½ Σ_{i=1}^{2m} p_i² + (ω²/4) Σ_{i=1}^{m} (q_{2i} − q_{2i−1})²
              + Σ_{i=0}^{m} (q_{2i+1} − q_{2i})⁴

is separable: q' = p, p' = −∇V(q).  The state is y = (q_1 … q_{2m}, p_1 … p_{2m}),
and ``params = (ω,)``; m is read from the length of y.

The oscillatory energies (GNI eq. I.5.3), with x_{1,j} = (q_{2j} − q_{2j−1})/√2 and
y_{1,j} = (p_{2j} − p_{2j−1})/√2, are I_j = ½(y_{1,j}² + ω² x_{1,j}²); their sum
I is an adiabatic invariant, I(t) = I(0) + O(1/ω) over long times (GNI §XIII).

References
----------
.. [1] E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed.,
   Springer 2006, §I.5.1, eqs. (5.1)–(5.3) and Fig. 5.2.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..model import SPECIALIZE_UP_TO, OdeModel, Separable


# inlined into its callers: see "Helpers" in reportgen.core.model
@numba.njit(cache=True, inline="always")
def _grad_v(q, omega, out):
    """∇V(q) of GNI eq. (I.5.1), written into ``out``; q has length 2m (0-based)."""
    n = q.shape[0]
    m = n // 2
    half_w2 = 0.5 * omega * omega
    for k in range(n):
        out[k] = 0.0
    for j in range(m):  # stiff spring between q[2j] and q[2j+1]: (ω²/4) s²
        s = q[2 * j + 1] - q[2 * j]
        out[2 * j + 1] += half_w2 * s
        out[2 * j] -= half_w2 * s
    for i in range(m + 1):  # soft spring q_{2i+1} − q_{2i} (1-based), with q_0 = q_{2m+1} = 0
        right = q[2 * i] if i < m else 0.0
        left = q[2 * i - 1] if i > 0 else 0.0
        d = right - left
        f = 4.0 * d * d * d
        if i < m:
            out[2 * i] += f
        if i > 0:
            out[2 * i - 1] -= f


@numba.njit(cache=True, error_model="numpy")
def rhs(t, y, params, out):
    n = y.shape[0] // 2
    for k in range(n):
        out[k] = y[n + k]
    _grad_v(y[:n], params[0], out[n:])
    for k in range(n):
        out[n + k] = -out[n + k]


@numba.njit(cache=True)
def jac(t, y, params, out):
    """[[0, I], [−∇²V(q), 0]]."""
    d = y.shape[0]
    n = d // 2
    m = n // 2
    omega = params[0]
    for a in range(d):
        for b in range(d):
            out[a, b] = 0.0
    for k in range(n):
        out[k, n + k] = 1.0
    c = 0.5 * omega * omega
    for j in range(m):  # stiff: (ω²/2) [[1, −1], [−1, 1]] in ∇²V
        a, b = n + 2 * j, 2 * j
        out[a, b] -= c
        out[a, b + 1] += c
        out[a + 1, b] += c
        out[a + 1, b + 1] -= c
    for i in range(m + 1):  # soft: 12 d² [[1, −1], [−1, 1]] on (left, right)
        right = y[2 * i] if i < m else 0.0
        left = y[2 * i - 1] if i > 0 else 0.0
        dd = right - left
        h = 12.0 * dd * dd
        if i < m:
            out[n + 2 * i, 2 * i] -= h
        if i > 0:
            out[n + 2 * i - 1, 2 * i - 1] -= h
        if 0 < i < m:
            out[n + 2 * i, 2 * i - 1] += h
            out[n + 2 * i - 1, 2 * i] += h


@numba.njit(cache=True)
def drift(p, params, out):
    for k in range(p.shape[0]):
        out[k] = p[k]


@numba.njit(cache=True)
def kick(q, params, out):
    _grad_v(q, params[0], out)
    for k in range(q.shape[0]):
        out[k] = -out[k]


def columns(m: int) -> tuple[str, ...]:
    return tuple(f"q{i}" for i in range(1, 2 * m + 1)) + tuple(f"p{i}" for i in range(1, 2 * m + 1))


def model(m: int, omega: float) -> OdeModel:
    return OdeModel(name="fput", columns=columns(m), rhs=rhs, params=np.array([float(omega)]),
                    separable=Separable(n=2 * m, drift=drift, kick=kick), jac=jac,
                    specialize=4 * m <= SPECIALIZE_UP_TO)


def gni_initial(m: int, omega: float) -> tuple[list[float], list[float]]:
    """GNI §I.5.1: q_1 = 1, p_1 = 1, q_2 = ω⁻¹, p_2 = 1, all others zero."""
    q, p = [0.0] * (2 * m), [0.0] * (2 * m)
    q[0], p[0] = 1.0, 1.0
    if m >= 1:
        q[1], p[1] = 1.0 / omega, 1.0
    return q, p


def potential(q, omega):
    """V(q) of GNI eq. (I.5.1); q of shape (N, 2m) or (2m,)."""
    q = np.atleast_2d(np.asarray(q, dtype=np.float64))
    stiff = q[:, 1::2] - q[:, 0::2]
    z = np.zeros((q.shape[0], 1))
    padded = np.hstack([z, q, z])  # q_0 … q_{2m+1}
    soft = padded[:, 1::2] - padded[:, 0::2]  # q_{2i+1} − q_{2i}, i = 0 … m
    return 0.25 * omega**2 * np.sum(stiff**2, axis=1) + np.sum(soft**4, axis=1)


def energy(q, p, omega):
    """H(p, q) of GNI eq. (I.5.1); q, p of shape (N, 2m) → (N,), or (2m,) → scalar-like (1,)."""
    p = np.atleast_2d(np.asarray(p, dtype=np.float64))
    return 0.5 * np.sum(p**2, axis=1) + potential(q, omega)


def oscillatory_energies(q, p, omega):
    """I_j = ½(y_{1,j}² + ω² x_{1,j}²), j = 1 … m (GNI eq. I.5.3); shape (N, m)."""
    q = np.atleast_2d(np.asarray(q, dtype=np.float64))
    p = np.atleast_2d(np.asarray(p, dtype=np.float64))
    x1 = (q[:, 1::2] - q[:, 0::2]) / math.sqrt(2.0)
    y1 = (p[:, 1::2] - p[:, 0::2]) / math.sqrt(2.0)
    return 0.5 * (y1**2 + omega**2 * x1**2)


def scaled_adiabatic_deviation(total, omega):
    """ω (I(t) − I(0)) / I(0), the adiabatic-invariant wobble scaled by ω.

    Parameters
    ----------
    total : array_like, shape (N,)
        The total oscillatory energy I = Σ_j I_j (GNI eq. I.5.3) on the output grid.
    omega : float
        Frequency ω of the stiff springs.

    Returns
    -------
    ndarray, shape (N,)
        Of order one over long times, since I(t) = I(0) + O(1/ω) (GNI §I.5.1, §XIII).
        Divides by 1 instead of I(0) when I(0) = 0.
    """
    total = np.asarray(total, dtype=np.float64)
    scale = abs(float(total[0])) or 1.0
    return omega * (total - total[0]) / scale
