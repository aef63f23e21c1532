"""Finite differences shared by the numerics (numpy only: :mod:`.small_oscillations` runs
in ``validate``, which loads neither scipy nor the molecules' code)."""

from __future__ import annotations

import numpy as np


def central_difference_hessian(f, x0: np.ndarray, h: float) -> np.ndarray:
    """Central second differences of a scalar ``f`` at ``x0`` with step ``h`` (error O(h²)
    from truncation, O(ε|f|/h²) from rounding); shape (n, n)."""
    x0 = np.asarray(x0, dtype=float)
    n = x0.size
    H = np.empty((n, n))

    def at(i, j, si, sj):
        x = x0.copy()
        x[i] += si * h
        x[j] += sj * h
        return f(x)

    for i in range(n):
        for j in range(i, n):
            H[i, j] = H[j, i] = (at(i, j, 1, 1) - at(i, j, 1, -1) - at(i, j, -1, 1)
                                 + at(i, j, -1, -1)) / (4 * h * h)
    return H
