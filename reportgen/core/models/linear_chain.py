r"""Linear small oscillations L = ½ q̇ᵀ M q̇ − ½ qᵀ A q as a compiled Hamiltonian system.

H = ½ pᵀ M⁻¹ p + ½ qᵀ A q with y = (q, p): q̇ = M⁻¹ p (drift), ṗ = −A q (kick).
Separable, so symplectic splitting methods apply; the Jacobian is constant.

params = (n, M⁻¹ row-major (n²), A row-major (n²)).

References
----------
.. [1] Textbook ch. 5, §5.1 (equations of motion M q̈ + A q = 0).
"""

from __future__ import annotations

import numba
import numpy as np

from ..model import SPECIALIZE_UP_TO, OdeModel, Separable


# inlined into its callers: see "Helpers" in reportgen.core.model
@numba.njit(cache=True, inline="always")
def _unpack(params):
    n = int(params[0])
    minv = params[1:1 + n * n].reshape((n, n))
    a = params[1 + n * n:1 + 2 * n * n].reshape((n, n))
    return n, minv, a


# The hot functions index params flat: M⁻¹[i, j] = params[1 + i n + j] and
# A[i, j] = params[1 + n² + i n + j].  Through _unpack's reshaped views the two-pendulum
# right-hand side took 36 ns per call, flat 20 ns (measured as benchmarks/formula_rhs.py).
@numba.njit(cache=True)
def drift(p, params, out):
    n = int(params[0])
    for i in range(n):
        s = 0.0
        for j in range(n):
            s += params[1 + i * n + j] * p[j]
        out[i] = s


@numba.njit(cache=True)
def kick(q, params, out):
    n = int(params[0])
    a0 = 1 + n * n
    for i in range(n):
        s = 0.0
        for j in range(n):
            s -= params[a0 + i * n + j] * q[j]
        out[i] = s


@numba.njit(cache=True, error_model="numpy")
def rhs(t, y, params, out):
    n = int(params[0])
    a0 = 1 + n * n
    for i in range(n):
        sq = 0.0
        sp = 0.0
        for j in range(n):
            sq += params[1 + i * n + j] * y[n + j]
            sp -= params[a0 + i * n + j] * y[j]
        out[i] = sq
        out[n + i] = sp


@numba.njit(cache=True)
def jac(t, y, params, out):
    n, minv, a = _unpack(params)
    for i in range(2 * n):
        for j in range(2 * n):
            out[i, j] = 0.0
    for i in range(n):
        for j in range(n):
            out[i, n + j] = minv[i, j]
            out[n + i, j] = -a[i, j]


def model(M: np.ndarray, A: np.ndarray, names: list[str], stiff_hint: bool = False,
          omega_max: float | None = None) -> OdeModel:
    """The OdeModel of M q̈ + A q = 0; ``names`` are the n coordinate names (columns q…, p_q…).

    ``omega_max`` (the fastest normal-mode frequency) lets the solver policy pick a step
    that resolves the fastest mode when the model is ``stiff_hint``."""
    M = np.asarray(M, dtype=np.float64)
    A = np.asarray(A, dtype=np.float64)
    n = M.shape[0]
    minv = np.linalg.inv(M)
    minv = 0.5 * (minv + minv.T)
    params = np.concatenate([[float(n)], minv.ravel(), A.ravel()])
    columns = tuple(names) + tuple(f"p_{c}" for c in names)
    return OdeModel(name="small oscillations", columns=columns, rhs=rhs, params=params,
                    separable=Separable(n=n, drift=drift, kick=kick), jac=jac,
                    stiff_hint=stiff_hint, specialize=2 * n <= SPECIALIZE_UP_TO,
                    extra={} if omega_max is None else {"omega_max": float(omega_max)})


def energy(y: np.ndarray, M: np.ndarray, A: np.ndarray) -> np.ndarray:
    """H = ½ pᵀ M⁻¹ p + ½ qᵀ A q for every row of y, shape (N, 2n) -> (N,)."""
    n = M.shape[0]
    q, p = y[:, :n], y[:, n:]
    v = np.linalg.solve(M, p.T).T
    return 0.5 * np.einsum("ij,ij->i", p, v) + 0.5 * np.einsum("ij,jk,ik->i", q, A, q)
