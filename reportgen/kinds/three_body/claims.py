"""The ``three_body`` report's claim-carrying sentences (see :mod:`reportgen.scene.claims`).

The words are chosen by the stored classifications of ``/analysis`` (``close_encounters``,
``hierarchical``, ``periodic``, ``choreography``, ``figure_eight``, ``fate``, ``burrau``;
for the restricted problem ``region``, ``behaviour``, ``formulation``).  Each predicate
decides its case again from the archive with code of its own: the closest approach located
anew between the archived samples (a numpy right-hand side and scipy's event location, not
the kind's), the hierarchy and the fate from the archived states, the return after one
period from the archived trajectory (cubic Hermite interpolation on positions and
velocities), the Lagrange points' Jacobi constants by root finding.
"""

from __future__ import annotations

import math

import numpy as np

from ...scene.claims import claim

PAIRS = ((0, 1), (0, 2), (1, 2))
#: the thresholds the kind's words are chosen by (restated: the claims test the archive
#: against these, not against the kind's own constants)
CLOSE_FRACTION = 0.05
HIERARCHY_SEPARATION = 0.2
COINCIDE_RATIO = 0.02
KEPLER_SPREAD = 0.1
PERIODIC_FRACTION = 1e-3
CHOREOGRAPHY_FRACTION = 1e-3
COLLISION_FRACTION = 1e-6
ESCAPE_DISTANCE_RATIO = 3.0
CHAOTIC_GROWTH = 1e6

_CACHE: dict[int, tuple] = {}


def _full(data) -> bool:
    return getattr(data.config, "restricted", None) is None


def _cached(data, key, compute):
    entry = _CACHE.get(id(data))
    if entry is None or entry[0] is not data:
        if len(_CACHE) > 8:
            _CACHE.clear()
        entry = (data, {})
        _CACHE[id(data)] = entry
    if key not in entry[1]:
        entry[1][key] = compute()
    return entry[1][key]


def _run(data):
    run = data.runs["main"]
    y = np.asarray(run.y, dtype=float)
    keep = np.all(np.isfinite(y), axis=1)
    return np.asarray(run.t, dtype=float)[keep], y[keep]


def _masses(data) -> np.ndarray:
    return np.asarray(data.config.params.masses, dtype=float)


def _size0(y) -> float:
    p = y[0, :9].reshape(3, 3)
    return float(max(np.linalg.norm(p[i] - p[j]) for i, j in PAIRS))


# ------------------------------------------------------------------ closest approach
def _accelerations(q, G, m):
    q = q.reshape(3, 3)
    acc = np.zeros((3, 3))
    for i, j in PAIRS:
        d = q[j] - q[i]
        f = G / float(d @ d) ** 1.5
        acc[i] += m[j] * f * d
        acc[j] -= m[i] * f * d
    return acc.ravel()


def _closest(data) -> np.ndarray:
    """Each pair's closest approach, located again: brackets where Δr·Δv of the archived
    states goes from − to +, the 8 with the smallest sampled distance or two-body
    pericentre (and each pair's 2 smallest) integrated from the archived state at their
    start with scipy's DOP853 and a numpy right-hand side, the minimum found as the root
    of Δr·Δv by scipy's event location."""
    from scipy.integrate import solve_ivp

    t, y = _run(data)
    G, m = float(data.config.params.G), _masses(data)
    rtol = float(data.runs["main"].attrs.get("rtol", 1e-10))
    atol = float(data.runs["main"].attrs.get("atol", 1e-12))
    pos, vel = y[:, :9].reshape(-1, 3, 3), y[:, 9:].reshape(-1, 3, 3)
    best = np.full(3, math.inf)
    candidates = []
    for p, (i, j) in enumerate(PAIRS):
        dr, dv = pos[:, j] - pos[:, i], vel[:, j] - vel[:, i]
        d = np.linalg.norm(dr, axis=1)
        best[p] = float(np.min(d))
        g = np.einsum("ij,ij->i", dr, dv)
        K = G * (m[i] + m[j])
        h2 = np.sum(np.cross(dr, dv) ** 2, axis=1)
        e = np.sqrt(np.maximum(1 + 2 * (0.5 * np.sum(dv * dv, axis=1) - K / d) * h2 / K**2, 0))
        q = np.minimum(h2 / (K * (1 + e)), d)
        for b in np.flatnonzero((g[:-1] < 0) & (g[1:] >= 0)):
            candidates.append((min(q[b], q[b + 1]), p, int(b)))
    candidates.sort()
    chosen = set(candidates[:8])
    for p in range(3):
        chosen |= set([c for c in candidates if c[1] == p][:2])
    for _, p, b in chosen:
        i, j = PAIRS[p]

        def event(_, s, i=i, j=j):
            return float((s[3 * j:3 * j + 3] - s[3 * i:3 * i + 3])
                         @ (s[9 + 3 * j:12 + 3 * j] - s[9 + 3 * i:12 + 3 * i]))

        event.direction = 1.0
        sol = solve_ivp(lambda _, s: np.concatenate([s[9:], _accelerations(s[:9], G, m)]),
                        (t[b], t[b + 1]), y[b], method="DOP853", rtol=rtol, atol=atol,
                        events=event)
        for ye in sol.y_events[0] if sol.success else ():
            best[p] = min(best[p], float(np.linalg.norm(ye[3 * j:3 * j + 3]
                                                        - ye[3 * i:3 * i + 3])))
    return best


def closest(data) -> np.ndarray:
    return _cached(data, "closest", lambda: _closest(data))


# ------------------------------------------------------------------------ hierarchy
def _hierarchy(data) -> tuple[float, tuple[int, int], np.ndarray]:
    """(ratio, inner pair, inner separations (N,)): the pair bound at every archived state
    whose largest separation over the third body's smallest distance from its centre of
    mass is least (ratio NaN: no pair stays bound)."""
    _, y = _run(data)
    G, m = float(data.config.params.G), _masses(data)
    pos, vel = y[:, :9].reshape(-1, 3, 3), y[:, 9:].reshape(-1, 3, 3)
    out = (math.nan, (1, 2), np.zeros(0))
    for i, j in PAIRS:
        k = 3 - i - j
        s = np.linalg.norm(pos[:, j] - pos[:, i], axis=1)
        dv = vel[:, j] - vel[:, i]
        energy = 0.5 * m[i] * m[j] / (m[i] + m[j]) * np.sum(dv * dv, axis=1) \
            - G * m[i] * m[j] / s
        if not np.all(energy < 0):
            continue
        centre = (m[i] * pos[:, i] + m[j] * pos[:, j]) / (m[i] + m[j])
        with np.errstate(divide="ignore"):
            ratio = float(np.max(s) / np.min(np.linalg.norm(pos[:, k] - centre, axis=1)))
        if not ratio >= out[0]:
            out = (ratio, (i, j), s)
    return out


def hierarchy_of(data):
    return _cached(data, "hierarchy", lambda: _hierarchy(data))


def _hierarchical(data) -> bool:
    return hierarchy_of(data)[0] < HIERARCHY_SEPARATION


def _thresholds(data) -> np.ndarray:
    _, y = _run(data)
    scales = np.full(3, _size0(y))
    ratio, pair, s = hierarchy_of(data)
    if ratio < HIERARCHY_SEPARATION:
        scales[PAIRS.index(pair)] = float(np.median(s))
    return CLOSE_FRACTION * scales


@claim("three_body closest approach",
       r"closest approach,? (?:located between the samples )?[\d.]|closest approach [\d.]"
       r"|down to [\d.]\S*(?: × 10\S+)?, \S.* at t ≈|The closest approach is [\d.]")
def closest_approach(data) -> bool | str:
    """the closest approach printed (stored once) is the one located again between the
    archived samples, to 1 %, and no larger than the smallest sampled distance"""
    if not _full(data):
        return True
    found = float(np.min(closest(data)))
    stored = float(data.analysis.get("closest_approach", math.nan))
    sampled = float(data.analysis.get("min_pair_distance", math.nan))
    if not abs(stored - found) <= 0.01 * found or stored > sampled:
        return (f"stored closest approach {stored:.4g}; located again {found:.4g} "
                f"(sampled minimum {sampled:.4g})")
    return True


@claim("three_body close encounters",
       r"pass through close encounters|the run has close encounters|close encounters, "
       r"coloured by time|the region of the close encounters|close encounters are the deep "
       r"minima|Pair distances and close encounters")
def close_encounters(data) -> bool | str:
    """some pair's closest approach, located again, is below its threshold (0.05 of the
    initial size; of its median separation for the inner pair of a hierarchical triple)"""
    d, limit = closest(data), _thresholds(data)
    return True if np.any(d < limit) else (f"closest approaches {np.round(d, 6).tolist()} "
                                           f"all above {np.round(limit, 6).tolist()}")


@claim("three_body no close encounters",
       r"there are no close encounters|not close encounters|\(no close encounters\)")
def no_close_encounters(data) -> bool | str:
    """no pair's closest approach, located again, is below its threshold"""
    d, limit = closest(data), _thresholds(data)
    return True if not np.any(d < limit) else (f"closest approaches {np.round(d, 6).tolist()}"
                                               f" below {np.round(limit, 6).tolist()}")


@claim("three_body hierarchical",
       r"The system is hierarchical|A hierarchical triple over|Two scales: the inner pair"
       r"|form a tight pair")
def hierarchical(data) -> bool | str:
    """a pair stays bound at every archived state with its largest separation below 0.2 of
    the third body's smallest distance from its centre of mass, and it is the stored inner
    pair"""
    ratio, pair, _ = hierarchy_of(data)
    if not ratio < HIERARCHY_SEPARATION:
        return f"hierarchy ratio {ratio:.3g} (no pair that tight and bound)"
    stored = tuple(int(k) - 1 for k in data.analysis.get("inner_pair", (0, 0)))
    return True if stored == pair else f"the inner pair is {pair}, the archive says {stored}"


@claim("three_body tracks coincide", r"the pair's two tracks nearly coincide")
def tracks_coincide(data) -> bool | str:
    """the inner pair's largest separation is below 0.02 of the third body's distance"""
    ratio = hierarchy_of(data)[0]
    return True if ratio < COINCIDE_RATIO else f"hierarchy ratio {ratio:.3g}"


def _kepler_spread(data) -> float:
    """The range of the osculating semi-major axis of the inner pair over the run,
    relative to its mean (from the archived states)."""
    _, y = _run(data)
    G, m = float(data.config.params.G), _masses(data)
    _, (i, j), _ = hierarchy_of(data)
    pos, vel = y[:, :9].reshape(-1, 3, 3), y[:, 9:].reshape(-1, 3, 3)
    dr, dv = pos[:, j] - pos[:, i], vel[:, j] - vel[:, i]
    a = 1.0 / (2.0 / np.linalg.norm(dr, axis=1) - np.sum(dv * dv, axis=1)
               / (G * (m[i] + m[j])))
    return float(np.ptp(a) / abs(np.mean(a)))


@claim("three_body near-Keplerian", r"near-Keplerian ellipse|close to a Kepler ellipse")
def near_keplerian(data) -> bool | str:
    """the inner pair's osculating semi-major axis varies by less than 0.1 of its mean"""
    spread = _kepler_spread(data)
    return True if spread < KEPLER_SPREAD else f"it varies by {spread:.3g}"


@claim("three_body not Keplerian", r"far from one Kepler ellipse")
def not_keplerian(data) -> bool | str:
    """the inner pair's osculating semi-major axis varies by at least 0.1 of its mean"""
    spread = _kepler_spread(data)
    return True if spread >= KEPLER_SPREAD else f"it varies by {spread:.3g}"


# ------------------------------------------------------------------------- periodic
def _state_at(t, y, when):
    """The state at ``when`` by cubic Hermite interpolation of the archived positions
    (with the archived velocities as their derivatives); None outside the run."""
    if not t[0] <= when <= t[-1] * (1 + 1e-12):
        return None
    k = min(int(np.searchsorted(t, when, side="right")) - 1, len(t) - 2)
    h = t[k + 1] - t[k]
    s = (when - t[k]) / h
    p0, p1, v0, v1 = y[k, :9], y[k + 1, :9], y[k, 9:], y[k + 1, 9:]
    h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
    h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
    return h00 * p0 + h10 * h * v0 + h01 * p1 + h11 * h * v1


def _return(data) -> float:
    """max |rᵢ(T) − rᵢ(0)| from the archived trajectory (the stored return check when the
    run ends before T)."""
    t, y = _run(data)
    T = float(data.config.period)
    back = _state_at(t, y, T)
    if back is None:
        return float(data.analysis.get("return_position_error", math.nan))
    return float(np.max(np.linalg.norm((back - y[0, :9]).reshape(3, 3), axis=1)))


@claim("three_body periodic",
       r"The orbit is periodic|on (?:the figure-eight choreography|a choreography|a periodic "
       r"orbit), period|back at its start after one period")
def periodic(data) -> bool | str:
    """the archived trajectory is back at its start after the period within 1e-3 of the
    initial size"""
    if data.config.get("period") is None:
        return "no period is configured"
    gap, size = _return(data), _size0(_run(data)[1])
    return True if gap < PERIODIC_FRACTION * size else f"back only within {gap:.3g}"


@claim("three_body not periodic", r"not periodic|This orbit does not return")
def not_periodic(data) -> bool | str:
    """the archived trajectory is not back at its start after the period"""
    gap, size = _return(data), _size0(_run(data)[1])
    return True if not gap < PERIODIC_FRACTION * size else f"back within {gap:.3g}"


def _on_one_track(data) -> bool | str:
    m = _masses(data)
    if not np.all(m == m[0]):
        return f"masses {m.tolist()} are not equal"
    t, y = _run(data)
    one = t <= float(data.config.period) * (1 + 1e-9)
    pos = y[one, :9].reshape(-1, 3, 3)
    track = pos[:, 0]
    gap = 0.0
    for b in (1, 2):
        p = pos[0, b]
        seg = track[1:] - track[:-1]
        s = np.clip(np.einsum("ij,ij->i", p - track[:-1], seg)
                    / np.maximum(np.einsum("ij,ij->i", seg, seg), 1e-300), 0, 1)
        gap = max(gap, float(np.min(np.linalg.norm(track[:-1] + s[:, None] * seg - p,
                                                   axis=1))))
    size = _size0(y)
    return True if gap < CHOREOGRAPHY_FRACTION * size else f"body off body 1's track by {gap:.3g}"


@claim("three_body choreography", r"chasing each other round one|choreography")
def choreography(data) -> bool | str:
    """equal masses, periodic, and bodies 2 and 3 start on body 1's archived track"""
    found = periodic(data)
    return _on_one_track(data) if found is True else found


@claim("three_body figure-eight", r"[Ff]igure-eight")
def figure_eight(data) -> bool | str:
    """a planar choreography whose tangent turns by less than π over one period (the
    archived velocities of body 1)"""
    found = choreography(data)
    if found is not True:
        return found
    t, y = _run(data)
    one = t <= float(data.config.period) * (1 + 1e-9)
    angle = np.unwrap(np.arctan2(y[one, 10], y[one, 9]))
    turn = float(angle[-1] - angle[0])
    planar = float(np.ptp(y[:, 2:9:3])) <= 1e-9 * max(float(np.ptp(y[:, :9])), 1e-300)
    return True if planar and abs(turn) < math.pi else f"tangent turns by {turn:.3g} rad"


# --------------------------------------------------------------------------- fate
def _final(data):
    _, y = _run(data)
    return y[-1, :9].reshape(3, 3), y[-1, 9:].reshape(3, 3)


def _energies(data):
    """For each body i: (its energy relative to the other two's centre of mass, r·v
    there, its distance over theirs, the other two's pair energy) at the run's end."""
    G, m = float(data.config.params.G), _masses(data)
    pos, vel = _final(data)
    out = []
    for i in range(3):
        j, k = (n for n in range(3) if n != i)
        mjk = m[j] + m[k]
        r = pos[i] - (m[j] * pos[j] + m[k] * pos[k]) / mjk
        v = vel[i] - (m[j] * vel[j] + m[k] * vel[k]) / mjk
        e = 0.5 * m[i] * mjk / (m[i] + mjk) * float(v @ v) - G * m[i] * mjk / np.linalg.norm(r)
        pair = float(np.linalg.norm(pos[j] - pos[k]))
        dv = vel[j] - vel[k]
        pair_e = 0.5 * m[j] * m[k] / mjk * float(dv @ dv) - G * m[j] * m[k] / pair
        out.append((e, float(r @ v), float(np.linalg.norm(r)) / pair, pair_e))
    return out


def _collided(data) -> bool:
    return float(np.min(closest(data))) < COLLISION_FRACTION * _size0(_run(data)[1])


def _escaper(data):
    for i, (e, rv, far, pair_e) in enumerate(_energies(data)):
        if e > 0 and rv > 0 and far > ESCAPE_DISTANCE_RATIO:
            return i, pair_e
    return None


@claim("three_body escape",
       r"leaves on a hyperbolic orbit|ending in an escape|until one body is thrown out")
def escape(data) -> bool | str:
    """no collision, and at the run's end a body has positive energy relative to the other
    two's centre of mass, moves away from it and is over 3 times farther from it than they
    are apart"""
    if _collided(data):
        return "a collision comes first"
    return True if _escaper(data) is not None else "no body meets the escape criterion"


@claim("three_body binary", r"form a binary|leave as a binary|an escape and a binary")
def binary(data) -> bool | str:
    """the two bodies left behind by the escape have negative pair energy"""
    found = _escaper(data)
    if found is None:
        return "no escape"
    return True if found[1] < 0 else f"their pair energy is {found[1]:.3g}"


@claim("three_body bound", r"\bbound: at t = |still bound at t =")
def bound(data) -> bool | str:
    """no collision or escape, and at the run's end some pair is bound and the third body
    bound to it (negative energy relative to the pair's centre of mass)"""
    if _collided(data) or _escaper(data) is not None:
        return "a collision or an escape"
    ok = any(e < 0 and pair_e < 0 for e, _, _, pair_e in _energies(data))
    return True if ok else "no body is bound to a bound pair"


@claim("three_body unbound", r"no escape yet|unbound but with no escape yet")
def unbound(data) -> bool | str:
    """no collision, escape or bound configuration at the run's end"""
    if _collided(data) or _escaper(data) is not None:
        return "a collision or an escape"
    ok = not any(e < 0 and pair_e < 0 for e, _, _, pair_e in _energies(data))
    return True if ok else "a body is bound to a bound pair"


@claim("three_body collision", r"collision: two bodies come within|ending in a collision")
def collision(data) -> bool | str:
    """the closest approach, located again, is below 1e-6 of the initial size"""
    return True if _collided(data) else f"closest approach {float(np.min(closest(data))):.3g}"


# ------------------------------------------------------------------ start and masses
@claim("three_body at rest", r"released at rest|start at rest and fall together")
def at_rest(data) -> bool | str:
    """every archived velocity at t = 0 is zero"""
    _, y = _run(data)
    return True if np.all(y[0, 9:] == 0.0) else "the bodies start in motion"


@claim("three_body in motion", r"started in motion")
def in_motion(data) -> bool | str:
    """some archived velocity at t = 0 is not zero"""
    _, y = _run(data)
    return True if np.any(y[0, 9:] != 0.0) else "the bodies start at rest"


@claim("three_body equal masses", r"[Tt]hree equal masses|the three equal masses")
def equal_masses(data) -> bool | str:
    """the configured masses are equal"""
    m = _masses(data) if _full(data) else np.zeros(2)
    return True if _full(data) and np.all(m == m[0]) else f"masses {m.tolist()}"


@claim("three_body unequal masses", r"are not equal\)")
def unequal_masses(data) -> bool | str:
    """the configured masses are not all equal"""
    m = _masses(data)
    return True if not np.all(m == m[0]) else "the masses are equal"


@claim("three_body Burrau", r"this is Burrau's problem")
def burrau(data) -> bool | str:
    """at rest, masses 3 : 4 : 5, each body opposite the side of its own length (from the
    archived first state)"""
    _, y = _run(data)
    m = _masses(data)
    p = y[0, :9].reshape(3, 3)
    opposite = np.array([np.linalg.norm(p[1] - p[2]), np.linalg.norm(p[0] - p[2]),
                         np.linalg.norm(p[0] - p[1])]) / m
    ok = (np.all(y[0, 9:] == 0) and np.allclose(np.sort(m) / m.min(), [1, 4 / 3, 5 / 3])
          and np.ptp(opposite) <= 1e-9 * opposite.max())
    return True if ok else "not Burrau's configuration"


# ------------------------------------------------------------------------- chaos
@claim("three_body chaotic",
       r"chaotic: nearby orbits separate|; chaotic, Lyapunov time|The motion is chaotic"
       r"|The orbit is chaotic")
def chaotic(data) -> bool | str:
    """two orbits 1e-10 apart separated by at least 1e6 within the run (the stored
    measurement), and the Lyapunov time is positive and shorter than the run"""
    a = data.analysis
    growth = float(a.get("separation_growth", math.nan))
    T = float(a.get("lyapunov_time", math.nan))
    t_end = float(data.runs["main"].t[-1])
    if growth >= CHAOTIC_GROWTH and 0 < T < t_end:
        return True
    return f"separation growth {growth:.3g}, Lyapunov time {T:.3g}"


@claim("three_body study horizon",
       r"shorter than the estimated Lyapunov time|over the first half of the estimated Lyapunov")
def study_horizon(data) -> bool | str:
    """the study's horizon is at most half the Lyapunov time"""
    a = data.analysis
    T, end = float(a.get("lyapunov_time", math.nan)), float(a.get("study_t_end", math.nan))
    return True if end <= 0.5 * T * (1 + 1e-9) else f"study to {end:.3g}, Lyapunov time {T:.3g}"

