"""The ``rigid_body`` report's claim-carrying sentences and their predicates (issue 41).

Each predicate measures its claim again from the archive's raw record with numpy alone:
the integrated ω(t) and attitude of the main run, the principal moments, the archived
config (the spin, the impulse).  The precession's sense is read off the phase of the
integrated ω⊥, the polhode's axis off the run's own L² and 2T, the flips off the sign
changes of the integrated intermediate component, the stability off the Jacobian of
Euler's equations (:func:`reportgen.kinds.inertia.claims.jacobian_verdicts`).
"""

from __future__ import annotations

import math

import numpy as np

from ...scene.claims import claim
from ..inertia.claims import EQUAL_RTOL, jacobian_verdicts, top_words

#: "near" an axis: the declared angle, when the archive has none [rad]
_NEAR = 0.2


def _moments(data) -> np.ndarray:
    return np.asarray(data.analysis["principal_moments"], dtype=float)


def _omega(data) -> np.ndarray:
    """The integrated body-frame ω(t), shape (N, 3)."""
    run = data.runs["main"]
    return np.column_stack([run["omega_1"], run["omega_2"], run["omega_3"]])


def _rank(data) -> tuple[int, int, int]:
    """0-based axes of the smallest, intermediate and largest moment."""
    order = np.argsort(_moments(data), kind="stable")
    return int(order[0]), int(order[1]), int(order[2])


def _angle(w: np.ndarray, k: int) -> float:
    return math.acos(min(1.0, abs(float(w[k])) / float(np.linalg.norm(w))))


def _near(data) -> float:
    return float((data.analysis.get("spin_axis") or {}).get("near_angle", _NEAR))


def _figure_axis(data) -> int | None:
    """0-based odd axis of a symmetric body (two equal moments), else None."""
    I = _moments(data)
    for s in range(3):
        b, c = (s + 1) % 3, (s + 2) % 3
        if abs(I[b] - I[c]) <= EQUAL_RTOL * I.max() and abs(I[s] - I[b]) > EQUAL_RTOL * I.max():
            return s
    return None


def _constant(data) -> float:
    """Largest change of the integrated ω over the run, relative to |ω(0)|."""
    w = _omega(data)
    return float(np.max(np.abs(w - w[0]))) / max(float(np.linalg.norm(w[0])), 1e-300)


def _sign_changes(v: np.ndarray) -> int:
    v = v[np.abs(v) > 1e-12 * float(np.max(np.abs(v)))]
    return int(np.sum(np.sign(v[1:]) != np.sign(v[:-1])))


# ---------------------------------------------------------------- the body's symmetry
@claim("rigid body: a spherical top", r"spherical top|all three moments equal|All three "
       r"moments are equal|marginal: spherical")
def spherical(data) -> bool | str:
    """the three moments are equal (1e-12) and the integrated ω stays constant (1e-9)"""
    if top_words(_moments(data)) != "spherical":
        return f"moments {_moments(data)}"
    return _constant(data) <= 1e-9 or f"ω changes by {_constant(data):.3g} of |ω|"


@claim("rigid body: a symmetric body", r"(?<!a)symmetric body|two equal moments|"
       r"marginal: symmetric")
def symmetric(data) -> bool | str:
    """exactly two moments are equal, and ω along the odd axis stays constant over the run"""
    s = _figure_axis(data)
    if s is None:
        return f"moments {_moments(data)}"
    w = _omega(data)[:, s]
    drift = float(np.max(np.abs(w - w[0])))
    scale = max(float(np.linalg.norm(_omega(data)[0])), 1e-300)
    return drift <= 1e-8 * scale or f"ω{s + 1} changes by {drift:.3g} rad/s"


@claim("rigid body: an asymmetric body", r"\basymmetric body|three distinct moments")
def asymmetric(data) -> bool | str:
    """the three moments differ by more than 1e-12 of the largest"""
    return top_words(_moments(data)) == "asymmetric" or f"moments {_moments(data)}"


@claim("rigid body: stability of the spin axes", r"\b(?:un)?stable\b|\bmarginal\b")
def verdicts(data) -> bool | str:
    """each axis's verdict is what the Jacobian of Euler's equations at steady spin about
    it gives (the moments from the archive)"""
    stored = [str(data.analysis["axis_stability"][f"axis_{k + 1}"]["verdict"])
              for k in range(3)]
    found = jacobian_verdicts(_moments(data))
    return stored == found or f"the Jacobian gives {found}, the report says {stored}"


# -------------------------------------------------------------------- the spin's axis
_RANK_WORDS = {"smallest-moment": 0, "intermediate": 1, "largest-moment": 2}


@claim("rigid body: spun near an axis",
       r"(?:spun|spinning) near its (?:smallest-moment|intermediate|largest-moment) axis")
def spun_near(data) -> bool | str:
    """the integrated ω(0) lies within the near angle of the axis of the moment the title
    names (read from the archived title: the title is the claim)"""
    title = str(data.title)
    words = next((w for w in _RANK_WORDS if f"near its {w} axis" in title), None)
    if words is None:
        return True  # the title does not say it: another sentence did, checked elsewhere
    k = _rank(data)[_RANK_WORDS[words]]
    angle = _angle(_omega(data)[0], k)
    return angle < _near(data) or f"ω(0) is {angle:.3g} rad from axis {k + 1}"


def _closest_to_intermediate(data) -> float:
    """The smallest angle between L and the intermediate axis over the polhode through the
    integrated ω(0): the largest |L_mid| for which the other two components can still meet
    Σ L_k² = L² and Σ L_k²/I_k = 2E (both squares ≥ 0), found by bisection."""
    I = _moments(data)
    L = I * _omega(data)[0]
    L2, E2 = float(L @ L), float(np.sum(L * L / I))
    _small, mid, _large = _rank(data)
    a, b = (k for k in range(3) if k != mid)
    system = np.array([[1.0, 1.0], [1.0 / I[a], 1.0 / I[b]]])

    def feasible(m2: float) -> bool:
        sa, sb = np.linalg.solve(system, [L2 - m2, E2 - m2 / I[mid]])
        return min(sa, sb) >= -1e-12 * L2

    lo, hi = float(L[mid] ** 2), L2  # the start is on the polhode
    if feasible(hi):
        return 0.0
    for _ in range(200):
        m = 0.5 * (lo + hi)
        lo, hi = (m, hi) if feasible(m) else (lo, m)
    return math.acos(min(1.0, math.sqrt(lo / L2)))


@claim("rigid body: the polhode passes near the intermediate axis",
       r"passes within \S+ rad of (?:that crossing|the\s+intermediate axis)|passing within "
       r"\S+ rad of the intermediate axis|rotation near the intermediate axis \d is unstable"
       r"|flips about the intermediate axis")
def near_intermediate(data) -> bool | str:
    """the polhode through the integrated ω(0) comes within the near angle of the
    intermediate axis (its closest point, where it crosses the plane of the intermediate
    axis and the axis it circles, from the conservation of L² and 2E)"""
    angle = _closest_to_intermediate(data)
    return angle < _near(data) or f"the polhode keeps {angle:.3g} rad from the axis"


@claim("rigid body: the polhode keeps off the intermediate axis",
       r"polhode keeps \S+ rad or more from the intermediate axis")
def not_near_intermediate(data) -> bool | str:
    """the polhode through the integrated ω(0) keeps at least the near angle from the
    intermediate axis"""
    angle = _closest_to_intermediate(data)
    if angle < _near(data):
        return f"the polhode comes within {angle:.3g} rad of the intermediate axis"
    return True


@claim("rigid body: does not start near the intermediate axis",
       r"does not start near the intermediate axis")
def not_started_near_intermediate(data) -> bool | str:
    """the integrated ω(0) is at least the near angle from the intermediate axis"""
    _, mid, _ = _rank(data)
    angle = _angle(_omega(data)[0], mid)
    return angle >= _near(data) or f"ω(0) is {angle:.3g} rad from the intermediate axis"


@claim("rigid body: the circled axis keeps its sense", r"circling axis \d, which keeps its "
       r"sense along L")
def circled_keeps_sense(data) -> bool | str:
    """the axis the polhode circles (L² against 2T·I_mid from ω(0)) is the one whose
    body-frame L component never changes sign over the integrated run"""
    I = _moments(data)
    w = _omega(data)
    small, mid, large = _rank(data)
    L2, T2 = float(np.sum((I * w[0]) ** 2)), float(np.sum(I * w[0] ** 2))
    circled = large if L2 > T2 * I[mid] else small
    n = _sign_changes(w[:, circled])
    return n == 0 or f"ω{circled + 1} changes sign {n} times"


@claim("rigid body: starts nearest an axis", r"starts nearest axis \d")
def nearest(data) -> bool | str:
    """the axis the report names as nearest the spin is the one with the largest |ω_k(0)|
    of the integrated ω"""
    k = int(np.argmax(np.abs(_omega(data)[0]))) + 1
    said = int((data.analysis.get("spin_axis") or {}).get("nearest", 0))
    return said == k or f"ω(0) is nearest axis {k}"


@claim("rigid body: the number of flips",
       r"flips over once within the run|flips over \d+ times within the run|"
       r"ends before the body's first flip")
def flips(data) -> bool | str:
    """the count of flips said is the number of sign changes of the integrated
    intermediate component ω₂(t)"""
    _, mid, _ = _rank(data)
    n = _sign_changes(_omega(data)[:, mid])
    said = len(np.atleast_1d(data.analysis["flip"]["flip_times"]))
    return n == said or f"ω{mid + 1} changes sign {n} times"


@claim("rigid body: the polhode's axis", r"polhode circles axis \d|closed polhode about\s+"
       r"axis \d|polhode about the (?:largest|smallest)-moment axis")
def polhode_axis(data) -> bool | str:
    """the polhode circles the largest-moment axis when L² > 2T·I_mid, else the smallest,
    with L² and 2T from the integrated ω(0)"""
    I = _moments(data)
    w = _omega(data)[0]
    small, mid, large = _rank(data)
    L2, T2 = float(np.sum((I * w) ** 2)), float(np.sum(I * w * w))
    circled = large if L2 > T2 * I[mid] else small
    said = (data.analysis.get("polhode_ellipsoid") or {}).get("circled_axis")
    if said is not None and int(said) != circled + 1:
        return f"L² − 2T·I_mid = {L2 - T2 * I[mid]:.3g}: it circles axis {circled + 1}"
    branch = str((data.analysis.get("elliptic") or {}).get("branch", ""))
    if branch and ("largest" in branch) != (circled == large):
        return f"L² − 2T·I_mid = {L2 - T2 * I[mid]:.3g}: it circles axis {circled + 1}"
    return True


# ------------------------------------------------------------------ symmetric precession
def _phase_rate(data, s: int) -> float:
    """Slope of the unwrapped phase of ω⊥ = ω_b + i ω_c (b, c after s, cyclic) [rad/s]."""
    w = _omega(data)
    b, c = (s + 1) % 3, (s + 2) % 3
    phase = np.unwrap(np.arctan2(w[:, c], w[:, b]))
    t = np.asarray(data.runs["main"].t, dtype=float)
    return float(np.polyfit(t, phase, 1)[0])


@claim("rigid body: precession with or against the spin", r"\b(?:prograde|retrograde)\b")
def precession_sense(data) -> bool | str:
    """ω⊥ turns about the figure axis in the sense of ω_s (prograde) or against it
    (retrograde), from the slope of the integrated ω⊥'s phase"""
    s = _figure_axis(data)
    if s is None:
        return "not a symmetric body"
    sense = str(data.analysis["symmetric"].get("sense", ""))
    rate = _phase_rate(data, s) * float(np.sign(_omega(data)[0, s]))
    if sense == "prograde":
        return rate > 0 or f"the phase of ω⊥ turns at {rate:.3g} rad/s along the spin"
    if sense == "retrograde":
        return rate < 0 or f"the phase of ω⊥ turns at {rate:.3g} rad/s along the spin"
    return "the report calls it steady"


@claim("rigid body: oblate or prolate", r"\b(?:oblate|prolate)\b")
def shape(data) -> bool | str:
    """oblate: the figure-axis moment exceeds the two equal ones; prolate: it is less"""
    s = _figure_axis(data)
    if s is None:
        return "not a symmetric body"
    I = _moments(data)
    found = "oblate" if I[s] > I[(s + 1) % 3] else "prolate"
    return str(data.analysis["symmetric"].get("shape", found)) == found or f"it is {found}"


@claim("rigid body: ω precesses about the figure axis",
       r"precession of ω about the figure axis|ω precesses about the figure axis")
def precesses(data) -> bool | str:
    """a symmetric body whose integrated ω⊥ turns: neither ω⊥ nor ω_s is zero, and the
    phase of ω⊥ advances over the run"""
    s = _figure_axis(data)
    if s is None:
        return "not a symmetric body"
    rate = _phase_rate(data, s)
    return abs(rate) > 1e-9 or "ω⊥ does not turn (a steady rotation)"


@claim("rigid body: a steady rotation", r"a steady rotation|ω stays constant|ω stays\s+constant")
def steady(data) -> bool | str:
    """the integrated ω stays constant over the run (1e-9 of |ω|)"""
    return _constant(data) <= 1e-9 or f"ω changes by {_constant(data):.3g} of |ω|"


# ------------------------------------------------------------------------------ impulse
def _struck_point(data) -> np.ndarray:
    imp = data.config["impulse"]
    if imp["at"] == "apex":
        return np.array([0.0, 0.0, 0.75 * float(data.config["shape"]["height"])])
    return np.asarray(imp["at"], dtype=float)


@claim("rigid body: the impulse's jump of ω", r"jumps by p × P")
def impulse_jump(data) -> bool | str:
    """the integrated ω(0) is the configured ω plus I⁻¹(p × P), p and P from the config"""
    imp = data.config.get("impulse")
    if imp is None:
        return "no impulse"
    w_before = np.asarray(data.config["initial"]["omega"], dtype=float)
    expect = w_before + np.cross(_struck_point(data), np.asarray(imp["P"], dtype=float)) / (
        _moments(data))
    err = float(np.max(np.abs(_omega(data)[0] - expect)))
    return err <= 1e-9 * max(float(np.linalg.norm(expect)), 1e-300) or (
        f"ω(0) differs from ω + I⁻¹(p × P) by {err:.3g} rad/s")


@claim("rigid body: the centre of mass drifts at P/M", r"V = P/M")
def drift(data) -> bool | str:
    """the body has a mass (a shape) and its archived centre of mass moves on a straight
    line at |P|/M (P and M from the config)"""
    shape = data.config.get("shape")
    imp = data.analysis.get("impulse") or {}
    if shape is None or "cm_path" not in imp:
        return "the body has no mass"
    path = np.asarray(imp["cm_path"], dtype=float)
    t = np.asarray(data.runs["main"].t, dtype=float)
    mass = float(shape["mass"]) if "mass" in shape else float(np.sum(shape["masses"]))
    speed = float(np.linalg.norm(np.asarray(data.config["impulse"]["P"], dtype=float))) / mass
    v = np.gradient(path, t, axis=0)
    err = float(np.max(np.abs(np.linalg.norm(v, axis=1) - speed)))
    return err <= 1e-9 * max(speed, 1e-300) or f"its speed departs from |P|/M by {err:.3g}"


@claim("rigid body: the struck point on the figure axis", r"which lies on it, circles")
def on_figure_axis(data) -> bool | str:
    """the configured struck point lies on the figure axis (off it by < 1e-9 of its
    distance)"""
    s = _figure_axis(data)
    if s is None or data.config.get("impulse") is None:
        return "not a symmetric body struck by an impulse"
    p = _struck_point(data)
    off = float(np.linalg.norm(np.delete(p, s)))
    return off <= 1e-9 * float(np.linalg.norm(p)) or f"it is {off:.3g} m off the axis"


@claim("rigid body: the struck point off the figure axis", r"off the figure axis, combines")
def off_figure_axis(data) -> bool | str:
    """the configured struck point lies off the figure axis"""
    s = _figure_axis(data)
    if s is None or data.config.get("impulse") is None:
        return "not a symmetric body struck by an impulse"
    p = _struck_point(data)
    off = float(np.linalg.norm(np.delete(p, s)))
    return off > 1e-9 * float(np.linalg.norm(p)) or "it is on the figure axis"


@claim("rigid body: a body without a mass", r"by its principal moments alone, without a mass")
def massless(data) -> bool | str:
    """the config gives the moments, not a shape"""
    return data.config.get("params") is not None or "a shape with a mass is given"


# -------------------------------------------------------------------------- splitting
@claim("rigid body: the splitting keeps L to round-off",
       r"L² and the space-frame L are kept to round-off")
def splitting_keeps_L(data) -> bool | str:
    """L² and the space-frame L of the splitting run, recomputed from its ω and attitude,
    stay within 1e-10 of |L|"""
    if "splitting" not in data.runs:
        return "no splitting run"
    run = data.runs["splitting"]
    I = _moments(data)
    w = np.column_stack([run["omega_1"], run["omega_2"], run["omega_3"]])
    q = np.column_stack([run["q_w"], run["q_x"], run["q_y"], run["q_z"]])
    q = q / np.linalg.norm(q, axis=1, keepdims=True)
    L = I * w
    qw, qv = q[:, :1], q[:, 1:]
    Ls = L + 2 * qw * np.cross(qv, L) + 2 * np.cross(qv, np.cross(qv, L))  # q L q*
    scale = float(np.linalg.norm(L[0]))
    err = max(float(np.max(np.abs(np.linalg.norm(L, axis=1) - scale))),
              float(np.max(np.abs(Ls - Ls[0]))))
    return err <= 1e-10 * scale or f"|L| or the space-frame L drifts by {err / scale:.3g}"


@claim("rigid body: ω circles the figure axis", r"ω circles the\s+figure axis|a circle about "
       r"the figure axis")
def circles_figure_axis(data) -> bool | str:
    """the integrated ω⊥ is not zero and keeps its length, ω along the figure axis constant"""
    s = _figure_axis(data)
    if s is None:
        return "not a symmetric body"
    w = _omega(data)
    perp = np.linalg.norm(np.delete(w, s, axis=1), axis=1)
    scale = float(np.linalg.norm(w[0]))
    if float(perp[0]) <= 1e-9 * scale:
        return "ω⊥ = 0: ω lies on the figure axis"
    return float(np.ptp(perp)) <= 1e-8 * scale or f"|ω⊥| varies by {float(np.ptp(perp)):.3g}"
