"""The ``two_center`` report's claim-carrying sentences (see :mod:`reportgen.scene.claims`).

The words are chosen by the stored ``/analysis`` ``motion`` (from E, β and q(1), notes
(7.59)); each predicate here decides the same case again from the archive's own first
state (E and the separation constant recomputed from x, y, vx, vy and the centres), and
where the run can show it, from the archived trajectory: a one-side orbit never crosses
the mid-line, a ring round both centres never reaches the segment between them.

The classes' names are the literature's (Waalkens, Dullin & Richter, Physica D 196
(2004), after Charlier): a *satellite* orbit keeps to one centre, a *planetary* orbit goes
round both, a *lemniscate* orbit through the segment between them.  A name is a claim of
its own case: "This orbit is a planetary orbit" said of a one-side orbit is false.
"""

from __future__ import annotations

import math

import numpy as np

from ...scene.claims import claim

#: a sampled approach closer than this fraction of a is "within ... of a centre"
NEAR_FRACTION = 0.05


def _state(data):
    run = data.runs["main"]
    cols = list(run.columns)
    y = np.asarray(run.y, dtype=float)
    return tuple(y[:, cols.index(c)] for c in ("x", "y", "vx", "vy"))


def _constants(data) -> dict:
    """E, β and q(1) = 2a²E + 4aμ + β from the archived first state (notes (7.59):
    C = L1 L2 + 2aμ (cos θ1 − cos θ2), β = −C − 2a²E), recomputed here."""
    p = data.config.params
    mu, a = float(p.mu), float(p.a)
    x, y, vx, vy = (float(v[0]) for v in _state(data))
    r1, r2 = math.hypot(x + a, y), math.hypot(x - a, y)
    E = 0.5 * (vx * vx + vy * vy) - mu / r1 - mu / r2
    L1, L2 = (x + a) * vy - y * vx, (x - a) * vy - y * vx
    C = L1 * L2 + 2.0 * a * mu * ((x + a) / r1 - (x - a) / r2)
    beta = -C - 2.0 * a * a * E
    return {"E": E, "beta": beta, "q1": 2.0 * a * a * E + 4.0 * a * mu + beta, "a": a,
            "mu": mu}


def _xi(data) -> np.ndarray:
    a = float(data.config.params.a)
    x, y, _, _ = _state(data)
    return (np.hypot(x + a, y) + np.hypot(x - a, y)) / (2.0 * a)


@claim("two_center one side",
       r"it stays on one side|orbit: stays on one side|orbit on one side of the mid-line"
       r"|orbit about one centre")
def one_side(data) -> bool | str:
    """β > 0 and E < 0 from the archived first state, and the archived x never changes
    sign (the orbit keeps to one side of the mid-line)"""
    k = _constants(data)
    if not (k["beta"] > 0.0 and k["E"] < 0.0):
        return f"recomputed β = {k['beta']:.4g}, E = {k['E']:.4g}: not β > 0 with E < 0"
    x = _state(data)[0]
    if np.any(x > 0) and np.any(x < 0):
        return "the archived run crosses the mid-line x = 0"
    return True


def _side(sign: int):
    def holds(data) -> bool | str:
        x = _state(data)[0]
        if not np.all(np.sign(x) == sign):
            return f"the archived x is not of sign {sign:+d} throughout"
        return one_side(data)
    return holds


claim("two_center about the right centre", r"about the centre at \((?!−|-)")(_side(1))
claim("two_center about the left centre", r"about the centre at \((?:−|-)")(_side(-1))


@claim("two_center satellite orbit",
       r"This orbit is (?:a )?satellite|\b[Aa] satellite orbit (?:about|round|around|through|on)"
       r"|satellite orbit: ")
def satellite(data) -> bool | str:
    """the name "satellite orbit" (about one centre): as ``two_center one side``"""
    return one_side(data)


@claim("two_center round both centres",
       r"it encircles both centres|orbit round both centres|orbit around both centres"
       r"|orbit: encircles both centres")
def both_centres(data) -> bool | str:
    """β ≤ 0, q(1) < 0 and E < 0 recomputed (a ring between two ellipses), and the
    archived run never comes to the segment between the centres (ξ > 1 throughout)"""
    k = _constants(data)
    if not (k["E"] < 0.0 and k["beta"] <= 0.0 and k["q1"] < 0.0):
        return (f"recomputed E = {k['E']:.4g}, β = {k['beta']:.4g}, q(1) = {k['q1']:.4g}: "
                "not a ring round both centres")
    if float(np.min(_xi(data))) <= 1.0 + 1e-12:
        return "the archived run reaches the segment between the centres (ξ = 1)"
    return True


@claim("two_center planetary orbit",
       r"This orbit is (?:a )?planetary|\b[Aa] planetary orbit (?:about|round|around|through|on)"
       r"|planetary orbit: ")
def planetary(data) -> bool | str:
    """the name "planetary orbit" (round both centres): as ``two_center round both
    centres``"""
    return both_centres(data)


@claim("two_center through the middle",
       r"through the segment between the centres|crosses the segment between the centres"
       r"|orbit crosses between the centres|orbit through the middle")
def through_middle(data) -> bool | str:
    """β ≤ 0, E < 0 and q(1) ≥ 0 recomputed: ξ reaches 1, the segment between the centres;
    and the archived run, where it goes round once (ξ oscillates), does reach it"""
    k = _constants(data)
    if not (k["E"] < 0.0 and k["beta"] <= 0.0 and k["q1"] >= 0.0):
        return (f"recomputed E = {k['E']:.4g}, β = {k['beta']:.4g}, q(1) = {k['q1']:.4g}: "
                "the region does not reach the segment between the centres")
    xi = _xi(data)
    turns = int(np.sum(np.diff(np.sign(np.diff(xi))) > 0))  # minima of ξ
    if turns >= 2 and float(np.min(xi)) > 1.0 + 0.05 * (float(np.max(xi)) - 1.0):
        return f"the archived run stays at ξ ≥ {float(np.min(xi)):.4g} over {turns} minima of ξ"
    return True


@claim("two_center lemniscate orbit",
       r"This orbit is (?:a )?lemniscate|\b[Aa] lemniscate orbit (?:about|round|around|through|on)"
       r"|lemniscate orbit: ")
def lemniscate(data) -> bool | str:
    """the name "lemniscate orbit" (through the segment between the centres): as
    ``two_center through the middle``"""
    return through_middle(data)


@claim("two_center unbound",
       r"An unbound orbit at E|unbound \(E ≥ 0\)|the particle escapes|unbound \(escaping\) "
       r"orbit|No coordinate line bounds an unbound orbit|escape: unbound")
def unbound(data) -> bool | str:
    """E ≥ 0 recomputed from the archived first state"""
    E = _constants(data)["E"]
    return True if E >= 0.0 else f"recomputed E = {E:.6g} < 0"


@claim("two_center bound", r"a bound orbit at E|\bbound: a (?:satellite|planetary|lemniscate) orbit")
def bound(data) -> bool | str:
    """E < 0 recomputed from the archived first state"""
    E = _constants(data)["E"]
    return True if E < 0.0 else f"recomputed E = {E:.6g} ≥ 0"


@claim("two_center collision orbit", r"its region reaches a centre \(collision orbit\)")
def collision_orbit(data) -> bool | str:
    """the region allowed by (7.59), recomputed, holds a centre: ξ = 1 allowed (q(1) ≥ 0)
    and |η| = 1 allowed (E < 0, or −β ≥ 2a²E for E ≥ 0)"""
    k = _constants(data)
    eta_one = k["E"] < 0.0 or -k["beta"] >= 2.0 * k["a"] ** 2 * k["E"]
    if k["q1"] >= 0.0 and eta_one:
        return True
    return f"recomputed q(1) = {k['q1']:.4g}: the region keeps away from both centres"


@claim("two_center near pass",
       r"passes within \S+ of (?:a centre|it)|passing within \S+ of one")
def near_pass(data) -> bool | str:
    """the archived run comes within NEAR_FRACTION·a of a centre"""
    a = float(data.config.params.a)
    x, y, _, _ = _state(data)
    d = float(np.min(np.minimum(np.hypot(x + a, y), np.hypot(x - a, y))))
    return True if d < NEAR_FRACTION * a else f"closest sampled distance {d:.3g} a"


@claim("two_center regularized", r"integrated in (?:the )?regularized variables")
def regularized(data) -> bool | str:
    """the run's own record says it ran in the Thiele–Burrau variables (dt/ds = r1 r2):
    its outputs were located in the fictitious time"""
    attrs = data.runs["main"].attrs
    return (True if attrs.get("formulation") == "regularized"
            else f"the run's formulation is {attrs.get('formulation')!r}")
