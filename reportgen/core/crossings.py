"""Event times from stored samples: level crossings refined by Hermite interpolation."""

from __future__ import annotations

import numpy as np


def _quintic_hermite(h, x0, v0, a0, x1, v1, a1):
    """Coefficients c[0..5] of p(s), s in [0, 1], matching value, slope, curvature at both ends."""
    v0, v1 = v0 * h, v1 * h
    a0, a1 = a0 * h * h, a1 * h * h
    c0, c1, c2 = x0, v0, 0.5 * a0
    # remaining cubic part solves the three end conditions at s = 1
    r0 = x1 - (c0 + c1 + c2)
    r1 = v1 - (c1 + 2 * c2)
    r2 = a1 - 2 * c2
    c3 = 10 * r0 - 4 * r1 + 0.5 * r2
    c4 = -15 * r0 + 7 * r1 - r2
    c5 = 6 * r0 - 3 * r1 + 0.5 * r2
    return c0, c1, c2, c3, c4, c5


def upward_crossings(t, x, xdot, xddot, level=0.0):
    """Times where x(t) crosses ``level`` going up, to interpolation accuracy O(h^6).

    Between stored samples x is replaced by the quintic Hermite interpolant built
    from x, x' and x'' at both ends (all three known exactly from the ODE), and
    its root is found by Newton's method started from the linear guess.

    Parameters
    ----------
    t, x, xdot, xddot : ndarray, shape (N,)

    Returns
    -------
    ndarray, shape (K,)
    """
    t, x = np.asarray(t), np.asarray(x) - level
    idx = np.nonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))[0]
    times = np.empty(idx.size)
    for n, i in enumerate(idx):
        h = t[i + 1] - t[i]
        c = _quintic_hermite(h, x[i], xdot[i], xddot[i], x[i + 1], xdot[i + 1], xddot[i + 1])
        s = -x[i] / (x[i + 1] - x[i])
        for _ in range(50):
            p = ((((c[5] * s + c[4]) * s + c[3]) * s + c[2]) * s + c[1]) * s + c[0]
            dp = (((5 * c[5] * s + 4 * c[4]) * s + 3 * c[3]) * s + 2 * c[2]) * s + c[1]
            step = p / dp
            s -= step
            if abs(step) < 1e-16:
                break
        times[n] = t[i] + s * h
    return times


def mean_period(crossings: np.ndarray) -> float:
    """Mean spacing of successive crossings (first to last over their count); NaN if < 2."""
    if crossings.size < 2:
        return float("nan")
    return float((crossings[-1] - crossings[0]) / (crossings.size - 1))
