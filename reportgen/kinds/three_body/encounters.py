"""Closest approaches of the three pairs, located on the continuous solution, and the
geometry of a hierarchical triple, at simulate time (from the run's stored states).

A close encounter of the Pythagorean problem lasts far less than the output step (the pair
distance falls from 10⁻² to 4 × 10⁻⁴ and back within 0.005), so the stored samples miss
the minima by an order of magnitude or more.  A pair's distance r has a minimum where
d(r²)/dt = 2 Δr·Δv changes sign from − to +; the stored states carry the velocities, so
each such sign change brackets one minimum between two samples.  The brackets most likely
to hold the deepest minimum (ranked by the osculating two-body pericentre of the pair at
either end, q = h²/(K(1 + e)), which a close encounter follows) are integrated again from
the stored state at their start, DOP853 at the run's tolerances (scipy's, with its
continuous extension), and the minimum is the root of Δr·Δv on that continuous solution
(scipy's event location).  Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.6.
"""

from __future__ import annotations

import math

import numpy as np

#: the three pairs (0-based bodies), in the order of r12, r13, r23
PAIRS = ((0, 1), (0, 2), (1, 2))


def _split(y):
    y = np.atleast_2d(np.asarray(y, dtype=float))
    return y[:, :9].reshape(-1, 3, 3), y[:, 9:18].reshape(-1, 3, 3)


def pericentre_estimate(dr, dv, K):
    """The osculating two-body pericentre distance q = h²/(K (1 + e)) of a pair with
    relative position ``dr`` and velocity ``dv`` (..., 3) and K = G(mᵢ + mⱼ)."""
    r = np.linalg.norm(dr, axis=-1)
    h2 = np.sum(np.cross(dr, dv) ** 2, axis=-1)
    energy = 0.5 * np.sum(dv * dv, axis=-1) - K / r
    e = np.sqrt(np.maximum(1.0 + 2.0 * energy * h2 / (K * K), 0.0))
    return np.minimum(h2 / (K * (1.0 + e)), r)


def closest_approaches(rhs, params, t, y, G, masses, rtol, atol, refine=12) -> dict:
    """Each pair's closest approach over the run, located on the continuous solution.

    Parameters
    ----------
    rhs : callable ``rhs(t, y, params, out)`` (the model's); params its parameters
    t : ndarray, shape (N,); y : ndarray, shape (N, 18), the stored run
    refine : int
        Brackets integrated again, the most promising first (module docstring), besides
        each pair's two most promising.

    Returns
    -------
    dict with ``distance`` (3,), ``time`` (3,): each pair's closest approach (the located
    minimum, or the smallest stored distance where it is smaller, at the run's ends) and
    ``sampled`` (3,): the smallest stored distances.
    """
    from scipy.integrate import solve_ivp

    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    finite = np.all(np.isfinite(y), axis=1)
    if not np.all(finite):  # a failed run: what it reached
        stop = int(np.argmin(finite))
        t, y = t[:stop], y[:stop]
    pos, vel = _split(y)
    distance = np.full(3, math.inf)
    time = np.full(3, math.nan)
    sampled = np.full(3, math.nan)
    candidates = []
    for p, (i, j) in enumerate(PAIRS):
        dr, dv = pos[:, j] - pos[:, i], vel[:, j] - vel[:, i]
        d = np.linalg.norm(dr, axis=1)
        if not d.size:
            continue
        k = int(np.argmin(d))
        distance[p], time[p], sampled[p] = d[k], t[k], d[k]
        g = np.sum(dr * dv, axis=1)
        brackets = np.flatnonzero((g[:-1] < 0.0) & (g[1:] >= 0.0))
        if not brackets.size:
            continue
        q = pericentre_estimate(dr, dv, G * (masses[i] + masses[j]))
        estimate = np.minimum(np.minimum(q[brackets], q[brackets + 1]),
                              np.minimum(d[brackets], d[brackets + 1]))
        candidates += [(float(e), p, int(b)) for e, b in zip(estimate, brackets, strict=True)]
    candidates.sort()
    chosen = candidates[:refine]
    for p in range(3):  # each pair's own deepest brackets too: its dot on the figure
        chosen += [c for c in candidates if c[1] == p][:2]
    out = np.empty(18)

    def f(time_, state):
        rhs(time_, state, params, out)
        return out.copy()

    for _, p, b in sorted(set(chosen)):
        i, j = PAIRS[p]

        def approach(_, s, i=i, j=j):
            return float(np.dot(s[3 * j:3 * j + 3] - s[3 * i:3 * i + 3],
                                s[9 + 3 * j:12 + 3 * j] - s[9 + 3 * i:12 + 3 * i]))

        approach.direction = 1.0
        sol = solve_ivp(f, (t[b], t[b + 1]), y[b], method="DOP853", rtol=rtol, atol=atol,
                        events=approach)
        if not sol.success or not len(sol.t_events[0]):
            continue
        for te, ye in zip(sol.t_events[0], sol.y_events[0], strict=True):
            de = float(np.linalg.norm(ye[3 * j:3 * j + 3] - ye[3 * i:3 * i + 3]))
            if de < distance[p]:
                distance[p], time[p] = de, float(te)
    return {"distance": distance, "time": time, "sampled": sampled}


def hierarchy(y, G, masses) -> dict:
    """The tightest bound pair and how far the third body keeps from it over the run.

    For each pair (i, j) bound throughout (two-body energy < 0 at every stored state), the
    ratio of its largest separation to the third body's smallest distance from the pair's
    centre of mass; the pair with the smallest ratio is the inner pair.  Returns
    ``ratio`` (NaN when no pair stays bound), ``pair`` (i, j) 0-based, and the inner
    pair's separation and the third body's distance, each as (min, median, max)."""
    pos, vel = _split(y)
    finite = np.all(np.isfinite(pos.reshape(len(pos), -1)), axis=1)
    pos, vel = pos[finite], vel[finite]
    m = np.asarray(masses, dtype=float)
    best = {"ratio": math.inf, "pair": (1, 2), "inner": (math.nan,) * 3,
            "outer": (math.nan,) * 3}
    for i, j in PAIRS:
        k = 3 - i - j
        dr, dv = pos[:, j] - pos[:, i], vel[:, j] - vel[:, i]
        s = np.linalg.norm(dr, axis=1)
        reduced = m[i] * m[j] / (m[i] + m[j])
        energy = 0.5 * reduced * np.sum(dv * dv, axis=1) - G * m[i] * m[j] / s
        if not s.size or not np.all(energy < 0.0):
            continue
        centre = (m[i] * pos[:, i] + m[j] * pos[:, j]) / (m[i] + m[j])
        D = np.linalg.norm(pos[:, k] - centre, axis=1)
        with np.errstate(divide="ignore"):  # the third body at the pair's centre of mass
            ratio = float(np.max(s) / np.min(D))
        if ratio < best["ratio"]:
            best = {"ratio": ratio, "pair": (i, j),
                    "inner": (float(np.min(s)), float(np.median(s)), float(np.max(s))),
                    "outer": (float(np.min(D)), float(np.median(D)), float(np.max(D)))}
    if not math.isfinite(best["ratio"]):
        best["ratio"] = math.nan
    return best


def turning(vx, vy) -> float:
    """Total turning of the direction of (vx, vy) along the samples [rad] (0 for a
    figure-eight traced once, ±2π for a simple loop)."""
    angle = np.unwrap(np.arctan2(np.asarray(vy, dtype=float), np.asarray(vx, dtype=float)))
    return float(angle[-1] - angle[0])


def distance_to_track(points, track) -> np.ndarray:
    """Each point's (P, 3) distance to the polyline ``track`` (N, 3)."""
    a, b = track[:-1], track[1:]
    ab = b - a
    length2 = np.maximum(np.sum(ab * ab, axis=1), 1e-300)
    out = []
    for p in np.atleast_2d(points):
        s = np.clip(np.sum((p - a) * ab, axis=1) / length2, 0.0, 1.0)
        out.append(float(np.min(np.linalg.norm(a + s[:, None] * ab - p, axis=1))))
    return np.asarray(out)
