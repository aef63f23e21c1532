"""``central_force``: the claim-carrying sentences of its reports and what makes each true
(:mod:`reportgen.scene.claims`).

Every predicate measures its claim again from the archive's trajectory and config, not
from the stored case that chose the words (``orbit_shape``, ``apsides``,
``heavier_body``): the energy and angular momentum from the first archived state, the
Laplace–Runge–Lenz vector along the archived run, the turning points by root finding, the
pericentre's turn per radial period from the run's own pericentre passages and from the
closed form (V = −k/r − ε/r²) or a quadrature of its own (the power law).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import integrate, optimize

from ...scene.claims import claim

#: the thresholds the simulation decides by (cases.py), with a margin for the predicates'
#: own measurement: a word chosen within MARGIN × the threshold of it is not contradicted
CIRCULAR_E, PARABOLIC_E, APSIDAL_SHIFT_NONE, EQUAL_MASSES = 1e-6, 1e-9, 1e-8, 1e-12
MARGIN = 2.0
#: |A(t) − A(0)|/(μk) along the run below this: the LRL vector is conserved (V = −k/r)
LRL_CONSERVED = 1e-6
#: error of the power law's apsidal shift by :func:`_quadrature_shift` [rad]
QUADRATURE_ERROR = 1e-9
#: the polar angle turning by more than this between stored samples [rad]: the run's
#: samples do not follow it through a pericentre, and the angle unwrapped may miss turns
MAX_SAMPLE_TURN = 1.0


# ----------------------------------------------------------------- the archived physics
def _potential_params(data) -> tuple[float, float, float]:
    """(k, n, ε) of V = −k/rⁿ − ε/r², from the archived config."""
    p = data.config.params
    n = float(p.n) if p.potential == "power" else 1.0
    eps = float(p.epsilon) if p.potential == "kepler_inverse_cube" else 0.0
    return float(p.k), n, eps


def _mu(data) -> float:
    p = data.config.params
    return float(p.m1) * float(p.m2) / (float(p.m1) + float(p.m2))


def _V(r, k, n, eps):
    return -k / r**n - eps / r**2


def _state(data):
    run = data.runs["main"]
    return run["x"], run["y"], run["vx"], run["vy"]


def _energy_and_L(data, i: int = 0) -> tuple[float, float]:
    """E and L of the archived state number ``i``."""
    x, y, vx, vy = (float(c[i]) for c in _state(data))
    mu = _mu(data)
    E = 0.5 * mu * (vx * vx + vy * vy) + _V(math.hypot(x, y), *_potential_params(data))
    return E, mu * (x * vy - y * vx)


def _lrl(data) -> np.ndarray:
    """A(t)/(μk) = (p × L)/(μk) − r̂ along the run, shape (N, 2), with this scene's k."""
    x, y, vx, vy = _state(data)
    mu, k = _mu(data), _potential_params(data)[0]
    h = x * vy - y * vx
    r = np.hypot(x, y)
    return np.column_stack((vy * h * mu / k - x / r, -vx * h * mu / k - y / r))


def _lrl_conserved(data) -> bool | str:
    """Whether the LRL vector is conserved along the archived run: V = −k/r."""
    A = _lrl(data)
    drift = float(np.max(np.hypot(*(A - A[0]).T)))
    return True if drift < LRL_CONSERVED else (
        f"the Laplace–Runge–Lenz vector measured along the run changes by {drift:.3g} μk: "
        "the potential is not −k/r")


def _eccentricity_lrl(data) -> float:
    return float(np.hypot(*_lrl(data)[0]))


def _turning_points(data) -> tuple[float, float]:
    """r_min, r_max (∞ for E ≥ 0) of the archived initial state, by root finding."""
    E, L = _energy_and_L(data)
    mu, (k, n, eps) = _mu(data), _potential_params(data)

    def veff(r):
        return L * L / (2 * mu * r * r) + _V(r, k, n, eps)

    def slope(r):
        return -L * L / (mu * r**3) + k * n / r ** (n + 1) + 2 * eps / r**3

    r0 = float(np.hypot(*(c[0] for c in _state(data)[:2])))
    lo, hi = r0, r0
    while slope(lo) > 0:
        lo /= 2
    while slope(hi) < 0:
        hi *= 2
    rc = optimize.brentq(slope, lo, hi, xtol=1e-15 * hi, rtol=1e-15)
    if E <= veff(rc):
        return rc, rc
    lo = rc
    while veff(lo) < E:
        lo /= 2
    r_min = optimize.brentq(lambda r: veff(r) - E, lo, rc, xtol=1e-15 * rc, rtol=1e-15)
    if E >= 0:
        return r_min, math.inf
    hi = rc
    while veff(hi) < E:
        hi *= 2
    return r_min, optimize.brentq(lambda r: veff(r) - E, rc, hi, xtol=1e-15 * hi, rtol=1e-15)


def _eccentricity(data) -> float:
    """(r_max − r_min)/(r_max + r_min) of the turning points (bound orbits)."""
    r_min, r_max = _turning_points(data)
    return (r_max - r_min) / (r_max + r_min)


# ---------------------------------------------------------------- the apsides, measured
def _quadrature_shift(data) -> float:
    """2ψ − 2π from the archived E and L: the closed form π/√(1 − 2με/L²) of
    V = −k/r − ε/r² (ε = 0: Kepler); for V = −k/rⁿ, ψ = ∫ du/√f(u) in u = 1/r by adaptive
    quadrature with the (u − u₁)^(−1/2) (u₂ − u)^(−1/2) weight."""
    E, L = _energy_and_L(data)
    mu, (k, n, eps) = _mu(data), _potential_params(data)
    if data.config.params.potential != "power":
        return 2 * math.pi / math.sqrt(1 - 2 * mu * eps / (L * L)) - 2 * math.pi
    r_min, r_max = _turning_points(data)
    u1, u2 = 1 / r_max, 1 / r_min
    c = 2 * mu / (L * L)

    def power_difference(u, v):  # (uⁿ − vⁿ)/(u − v), without cancellation
        if u == v:
            return n * v ** (n - 1)
        return v**n * math.expm1(n * math.log1p((u - v) / v)) / (u - v)

    def g(u):  # f(u)/((u − u₁)(u₂ − u)), f = c (E + k uⁿ) − u², f(u₁) = f(u₂) = 0, divided
        # by the factor of the nearer root exactly (the other is at least (u₂ − u₁)/2 away)
        if u - u1 <= u2 - u:
            return (c * k * power_difference(u, u1) - (u + u1)) / (u2 - u)
        return -(c * k * power_difference(u, u2) - (u + u2)) / (u - u1)

    psi, _ = integrate.quad(lambda u: 1 / math.sqrt(abs(g(u))), u1, u2, weight="alg",
                            wvar=(-0.5, -0.5), epsabs=1e-13, epsrel=1e-13, limit=200)
    return 2 * psi - 2 * math.pi


def _measured_shift(data) -> tuple[float, float] | None:
    """2ψ − 2π and its uncertainty from the archived run's pericentre passages (ṙ from
    − to +; φ at ṙ = 0 by cubic inverse interpolation over four samples, its uncertainty the
    difference from the linear one), or None with fewer than two."""
    x, y, vx, vy = _state(data)
    r = np.hypot(x, y)
    rdot = (x * vx + y * vy) / r
    phi = np.unwrap(np.arctan2(y, x)) * np.sign(x[0] * vy[0] - y[0] * vx[0])
    if np.max(np.abs(np.diff(phi))) > MAX_SAMPLE_TURN:  # the angle is not followed
        return None
    found = np.flatnonzero((rdot[:-1] < 0) & (rdot[1:] >= 0))
    found = found[(found >= 1) & (found <= r.size - 3)]
    if found.size < 2:
        return None
    angles, errors = [], []
    for i in (found[0], found[-1]):
        window = slice(i - 1, i + 3)
        cubic = np.polyval(np.polyfit(rdot[window], phi[window], 3), 0.0)
        s = -rdot[i] / (rdot[i + 1] - rdot[i])
        linear = phi[i] + s * (phi[i + 1] - phi[i])
        angles.append(cubic)
        errors.append(abs(cubic - linear))
    turns = found.size - 1
    return (angles[1] - angles[0]) / turns - 2 * math.pi, sum(errors) / turns


def _direction(data, sign: int) -> bool | str:
    """The pericentre turns with (+1), against (−1) or not at all (0) with the motion."""
    E, _ = _energy_and_L(data)
    if E >= 0:
        return f"E = {E:.6g} J ≥ 0: an unbound orbit has no apsides to turn"
    if _eccentricity(data) < CIRCULAR_E / MARGIN:
        return "the orbit is a circle: it has no pericentre"
    quad = _quadrature_shift(data)
    quad_err = QUADRATURE_ERROR if data.config.params.potential == "power" else 1e-12
    measured = _measured_shift(data)
    limit = APSIDAL_SHIFT_NONE * MARGIN + quad_err
    said = {1: "advances", -1: "regresses", 0: "stays put"}[sign]
    words = f"2ψ − 2π = {quad:.6g} rad from the archived E and L"
    if measured is not None:
        words += f", {measured[0]:.6g} ± {measured[1]:.2g} rad between the run's pericentres"
    if sign == 0:
        ok = abs(quad) < limit and (measured is None
                                    or abs(measured[0]) < limit + 3 * measured[1])
    else:
        ok = sign * quad > quad_err and (measured is None or abs(measured[0]) < 3 * measured[1]
                                         or sign * measured[0] > 0)
    return True if ok else f"said the pericentre {said}; measured {words}"


# ----------------------------------------------------------------------- the claims
@claim("central_force: bound", r"\b[Aa] bound (orbit|Kepler|circle|ellipse)\b|"
                               r"\bis a bound (ellipse|circle)\b")
def bound(data) -> bool | str:
    """the energy of the archived initial and final states is negative"""
    E0, _ = _energy_and_L(data, 0)
    E1, _ = _energy_and_L(data, -1)
    return True if E0 < 0 and E1 < 0 else f"E = {E0:.6g} J at the start, {E1:.6g} J at the end"


@claim("central_force: radial oscillation", r"oscillates between the turning points")
def radial_oscillation(data) -> bool | str:
    """bound, with two distinct turning points (not a circle)"""
    E, _ = _energy_and_L(data)
    if E >= 0:
        return f"E = {E:.6g} J ≥ 0: one turning point"
    e = _eccentricity(data)
    return True if e >= CIRCULAR_E / MARGIN else f"a circle: (r_max − r_min)/(r_max + r_min) = {e:.3g}"


@claim("central_force: escaping", r"[Ee]scaping orbit|fly apart|single turning point|"
                                  r"escapes to r → ∞|orbit is not bound|: escape, e =|"
                                  r"no period; the apocentre is at infinity|unbound \(E ≥ 0\)|"
                                  r"energy is not negative")
def escaping(data) -> bool | str:
    """the energy of the archived initial state is not negative"""
    E, _ = _energy_and_L(data)
    return True if E >= 0 else f"E = {E:.6g} J < 0: the orbit is bound"


@claim("central_force: closest approach", r"come no closer than")
def closest_approach(data) -> bool | str:
    """the archived run never comes closer than the turning point r_min of its E and L"""
    r_min, _ = _turning_points(data)
    closest = float(np.min(np.hypot(*_state(data)[:2])))
    return True if closest >= r_min * (1 - 1e-6) else (
        f"the run comes to r = {closest:.6g} m, inside the turning point {r_min:.6g} m")


@claim("central_force: circle", r"\bcircle of radius|Kepler circle|This orbit is a circle|"
                                r"circular orbit in V|\(a circle\)|exact circle|"
                                r"\(nearly\) a circle")
def circle(data) -> bool | str:
    """bound, with coinciding turning points, and r constant along the archived run"""
    E, _ = _energy_and_L(data)
    r = np.hypot(*_state(data)[:2])
    spread = float((r.max() - r.min()) / (r.max() + r.min()))
    e = _eccentricity(data) if E < 0 else math.inf
    if e < CIRCULAR_E * MARGIN and spread < CIRCULAR_E * MARGIN + 1e-8:
        return True
    return f"(r_max − r_min)/(r_max + r_min) = {e:.3g} from E and L, {spread:.3g} along the run"


def _conic(data, name: str) -> bool | str:
    conserved = _lrl_conserved(data)
    if conserved is not True:
        return conserved
    E, _ = _energy_and_L(data)
    e = _eccentricity_lrl(data)
    ok = {"ellipse": E < 0 and e >= CIRCULAR_E / MARGIN,
          "hyperbola": E > 0 and e > 1 + PARABOLIC_E / MARGIN,
          "parabola": abs(e - 1) < PARABOLIC_E * MARGIN + 1e-13}[name]
    return True if ok else f"|A|/(μk) = {e:.12g} and E = {E:.6g} J: not a {name}"


@claim("central_force: ellipse", r"Kepler ellipse|bound ellipse|exact ellipse")
def ellipse(data) -> bool | str:
    """V = −k/r (the LRL vector conserved along the run), E < 0 and |A|/(μk) > 0"""
    return _conic(data, "ellipse")


@claim("central_force: hyperbola", r"\bhyperbola\b")
def hyperbola(data) -> bool | str:
    """V = −k/r (the LRL vector conserved along the run), E > 0 and |A|/(μk) > 1"""
    return _conic(data, "hyperbola")


@claim("central_force: parabola", r"\bparabola\b")
def parabola(data) -> bool | str:
    """V = −k/r (the LRL vector conserved along the run) and |A|/(μk) = 1"""
    return _conic(data, "parabola")


@claim("central_force: Kepler orbit closes", r"closes (on itself )?every period|"
                                             r"^Kepler orbit, e = ")
def kepler_closes(data) -> bool | str:
    """bound, with the LRL vector (pericentre direction and e) constant along the run"""
    E, _ = _energy_and_L(data)
    if E >= 0:
        return f"E = {E:.6g} J ≥ 0: the orbit does not return"
    return _lrl_conserved(data)


@claim("central_force: Laplace–Runge–Lenz vector", r"Laplace–Runge–Lenz|\bLRL\b|"
                                                   r"Kepler elements|conics with the centre")
def lrl_vector(data) -> bool | str:
    """the LRL vector computed from the archived run is conserved (V = −k/r): it, the
    Kepler elements and the conic sections it defines mean something here"""
    return _lrl_conserved(data)


@claim("central_force: Kepler's equation", r"Kepler's equation")
def kepler_equation(data) -> bool | str:
    """a bound orbit of V = −k/r (LRL conserved along the run, E < 0): the only case with a
    solution of Kepler's equation to compare with"""
    E, _ = _energy_and_L(data)
    if E >= 0:
        return f"E = {E:.6g} J ≥ 0: Kepler's equation E − e sin E = M is for bound orbits"
    return _lrl_conserved(data)


@claim("central_force: apsides advance", r"pericentre advances|rad is greater than π|"
                                         r"2ψ − 2π, with the motion")
def apsides_advance(data) -> bool | str:
    """2ψ − 2π > 0: from the archived E and L, and between the run's pericentre passages"""
    return _direction(data, 1)


@claim("central_force: apsides regress", r"pericentre regresses|rad is less than π|"
                                         r"2ψ − 2π, against the motion")
def apsides_regress(data) -> bool | str:
    """2ψ − 2π < 0: from the archived E and L, and between the run's pericentre passages"""
    return _direction(data, -1)


@claim("central_force: apsides fixed", r"pericentre stays put|"
                                       r"the pericentre turning by less than")
def apsides_fixed(data) -> bool | str:
    """|2ψ − 2π| below the threshold: from the archived E and L, and between the run's
    pericentre passages"""
    return _direction(data, 0)


@claim("central_force: rosette", r"\brosette\b")
def rosette(data) -> bool | str:
    """bound, not a circle, and the pericentre turns measurably"""
    verdict = _direction(data, 0)
    if verdict is True:
        return "the pericentre stays put: the orbit closes"
    return True if verdict.startswith("said") else verdict


def _track_sizes(data) -> tuple[float, float]:
    tracks = data.analysis["body_tracks"]
    return tuple(float(np.max(np.hypot(*np.asarray(tracks[b]).T))) for b in ("r1", "r2"))


@claim("central_force: equal masses", r"[Ww]ith equal masses")
def equal_masses(data) -> bool | str:
    """m1 = m2 in the config, and the two drawn tracks are the same size"""
    p = data.config.params
    m1, m2 = float(p.m1), float(p.m2)
    s1, s2 = _track_sizes(data)
    if abs(m1 - m2) <= EQUAL_MASSES * MARGIN * (m1 + m2) and abs(s1 - s2) <= 1e-9 * (s1 + s2):
        return True
    return f"m1 = {m1:.6g} kg, m2 = {m2:.6g} kg; tracks of size {s1:.6g} m and {s2:.6g} m"


@claim("central_force: heavier body", r"heavier body")
def heavier_body(data) -> bool | str:
    """the body named heavier in the config draws the smaller track"""
    p = data.config.params
    m1, m2 = float(p.m1), float(p.m2)
    s1, s2 = _track_sizes(data)
    if abs(m1 - m2) > EQUAL_MASSES * (m1 + m2) and (m1 > m2) == (s1 < s2):
        return True
    return f"m1 = {m1:.6g} kg, m2 = {m2:.6g} kg; tracks of size {s1:.6g} m and {s2:.6g} m"
