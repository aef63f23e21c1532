"""The pendulum's claim-carrying sentences and what makes each true (issue 41; see
:mod:`reportgen.scene.claims`).

The words are chosen at simulate time by the sign of 1 − k² and its size against the
separatrix thresholds (:func:`reportgen.core.pendulum_theory.motion_case`), by T/T0 − 1
against ``SMALL_ANGLE_CLOSE``, by the reference used and by ⌊ω0 T/π⌋.  Each predicate here
measures again from what the archive holds besides those facts: 1 − k² from the archived
energy E(0) and the configured m, g, l (E − m g l = −2 m g l (1 − k²)); libration or
rotation from the sign changes of the archived θ̇ and whether θ passes the upright; the
period from the archived θ(t)'s crossings; the time spent near the upright from the
archived samples; the reference from the Jacobi-sn solution evaluated again; the conjugate
points from the signs of the numerically differentiated action.
"""

from __future__ import annotations

import math

import numpy as np

from ...core import pendulum_theory as theory
from ...scene.claims import claim
from .simulation import PendulumSimulation

#: the upright's neighbourhood the "near the separatrix" words speak of: beyond ±135°
NEAR_UPRIGHT = 0.75 * math.pi


# ------------------------------------------------------------------ measurements
def _omega0(data) -> float:
    p = data.config.params
    return math.sqrt(p.g / p.l)


def _gap(data) -> float:
    """1 − k² from the archived energy E(0) of the run and the configured m, g, l:
    E − m g l = −2 m g l (1 − k²), E = ½ m l² θ̇² − m g l cos θ."""
    p = data.config.params
    scale = p.m * p.g * p.l
    energy = float(np.asarray(data.runs["main"].invariants["energy"])[0])
    return -(energy - scale) / (2.0 * scale)


def _centre(theta: np.ndarray) -> float:
    return 2.0 * math.pi * round(float(theta[0]) / (2.0 * math.pi))


def _turns_sign(run) -> int:
    """+1 or −1 when the archived θ̇ keeps that sign over the run, 0 when it changes sign."""
    v = np.asarray(run["theta_dot"], dtype=float)
    scale = float(np.max(np.abs(v))) or 1.0
    if np.all(v > 1e-12 * scale):
        return 1
    if np.all(v < -1e-12 * scale):
        return -1
    return 0


def _passes_upright(run) -> bool:
    theta = np.asarray(run["theta"], dtype=float)
    return bool(np.any(np.abs(theta - _centre(theta)) >= math.pi))


def _exact_period(data, m1: float) -> float:
    """The period [s] of a libration (m1 = 1 − k² > 0) or the time per turn of a rotation,
    from scipy's K (DLMF 19.2.8, 22.19.4, 22.19.7), not the archived one."""
    from scipy.special import ellipk, ellipkm1

    w = _omega0(data)
    if m1 > 0:
        return 4.0 * float(ellipkm1(m1) if m1 < 0.5 else ellipk(1.0 - m1)) / w
    k2 = 1.0 - m1
    inv = 1.0 / k2  # K(1/k²) with 1 − 1/k² = −m1/k²
    km = -m1 / k2
    return 2.0 * float(ellipkm1(km) if km < 0.5 else ellipk(inv)) / (math.sqrt(k2) * w)


def _measured_period(data) -> float:
    """The mean spacing of upward crossings of the archived θ through its centre (linear
    interpolation between samples); the period from scipy's K when there are fewer than
    two crossings."""
    run = data.runs["main"]
    t, theta = np.asarray(run.t, dtype=float), np.asarray(run["theta"], dtype=float)
    x = theta - _centre(theta)
    up = np.nonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))[0]
    if up.size >= 2:
        crossings = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
        return float(np.mean(np.diff(crossings)))
    return _exact_period(data, _gap(data))


def _excess(data) -> float:
    """T/T0 − 1 measured, T0 = 2π√(l/g) from the config."""
    return _measured_period(data) * _omega0(data) / (2.0 * math.pi) - 1.0


def _upright_fraction(data, m1: float) -> float:
    """The fraction of the time beyond ±135° over the whole periods the archived run
    covers; for a run shorter than one, the fraction of one period in closed form."""
    from scipy.special import ellipkinc

    run = data.runs["main"]
    t, theta = np.asarray(run.t, dtype=float), np.asarray(run["theta"], dtype=float)
    period = _exact_period(data, m1)
    whole = math.floor((t[-1] - t[0]) / period)
    if whole >= 1:
        inside = t - t[0] <= whole * period
        wrapped = np.abs(np.mod(theta[inside] + math.pi, 2.0 * math.pi) - math.pi)
        return float(np.mean(wrapped > NEAR_UPRIGHT))
    # by the incomplete integral of the first kind, DLMF 22.19.2: a libration has
    # t = F(φ | k²)/ω0 with sin(θ/2) = k sin φ; a rotation t = F(θ/2 | 1/k²)/(k ω0)
    k2 = 1.0 - m1
    if m1 > 0:
        phi = math.asin(min(1.0, math.sin(0.5 * NEAR_UPRIGHT) / math.sqrt(k2)))
        return 1.0 - float(ellipkinc(phi, k2)) / _complete(k2, m1)
    return 1.0 - float(ellipkinc(0.5 * NEAR_UPRIGHT, 1.0 / k2)) / _complete(1.0 / k2, -m1 / k2)


def _complete(m: float, one_minus_m: float) -> float:
    """K(m), from 1 − m where m is near 1 (it keeps the digits m rounds away)."""
    from scipy.special import ellipk, ellipkm1

    return float(ellipkm1(one_minus_m) if m > 0.5 else ellipk(m))


# ----------------------------------------------------------- libration / rotation
@claim("pendulum librates",
       r"\bpendulum librating\b|This orbit lies (?:just )?inside it|\blibration(?: just inside "
       r"the separatrix \([^)]*\))?: swings between|\bmotion libration\b")
def librates(data) -> bool | str:
    """the archived θ never passes the upright, and θ̇ changes sign (or, over a run too short
    for a swing, the archived energy is below the separatrix's)"""
    run = data.runs["main"]
    if _passes_upright(run):
        return "the archived θ passes the upright θ = ±π: not a libration"
    if _turns_sign(run) == 0:
        return True
    m1 = _gap(data)
    return True if m1 > 0 else (f"θ̇ keeps its sign and the archived energy gives "
                                f"1 − k² = {m1:.3g} < 0: a rotation")


@claim("pendulum rotates",
       r"\bpendulum rotating\b|This orbit lies (?:just )?above it|\brotation(?: just above the "
       r"separatrix \([^)]*\))?: goes over the top|\bmotion rotation\b|This pendulum goes over "
       r"the top|This scene rotates")
def rotates(data) -> bool | str:
    """the archived θ̇ keeps its sign over the run and the archived energy is above the
    separatrix's (1 − k² < 0)"""
    run = data.runs["main"]
    if _turns_sign(run) == 0:
        return "the archived θ̇ changes sign: the pendulum turns back, not a rotation"
    m1 = _gap(data)
    return True if m1 < 0 else f"the archived energy gives 1 − k² = {m1:.3g} > 0: a libration"


@claim("pendulum period measured as a libration's", r"mean spacing of upward crossings of θ")
def measured_as_libration(data) -> bool | str:
    """the method (crossings of the centre) is a libration's: 1 − k² from the archived energy
    is positive, or too small for its sign to be measured (below SEPARATRIX_ON)"""
    m1 = _gap(data)
    return True if m1 > -theory.SEPARATRIX_ON else (
        f"the archived energy gives 1 − k² = {m1:.3g}: a rotation's period is per turn")


@claim("pendulum period measured as a rotation's", r"the mean time per full turn")
def measured_as_rotation(data) -> bool | str:
    """the method (time per turn) is a rotation's: 1 − k² from the archived energy is
    negative, or too small for its sign to be measured"""
    m1 = _gap(data)
    return True if m1 < theory.SEPARATRIX_ON else (
        f"the archived energy gives 1 − k² = {m1:.3g}: a libration's period is between "
        "crossings")


@claim("pendulum rotation sense increasing", r"θ increasing(?: by 2π)?")
def rotation_increasing(data) -> bool | str:
    """the archived θ̇ is positive throughout (θ increases)"""
    sign = _turns_sign(data.runs["main"])
    return True if sign > 0 else "the archived θ̇ is not positive throughout"


@claim("pendulum rotation sense decreasing", r"θ decreasing(?: by 2π)?")
def rotation_decreasing(data) -> bool | str:
    """the archived θ̇ is negative throughout (θ decreases)"""
    sign = _turns_sign(data.runs["main"])
    return True if sign < 0 else "the archived θ̇ is not negative throughout"


@claim("pendulum libration about the bottom θ = 0", r"between ±[\d.]+ rad")
def about_zero(data) -> bool | str:
    """the archived θ stays within (−π, π)"""
    theta = np.asarray(data.runs["main"]["theta"], dtype=float)
    return True if np.all(np.abs(theta) < math.pi) else (
        f"the archived θ reaches {float(np.max(np.abs(theta))):.4g} rad, beyond ±π")


@claim("pendulum libration about another bottom",
       r"between −?2π ± [\d.]+ rad|taken about the bottom the pendulum swings about")
def about_two_pi(data) -> bool | str:
    """the archived θ stays within π of ±2π, the multiple of 2π the run started nearest"""
    theta = np.asarray(data.runs["main"]["theta"], dtype=float)
    centre = _centre(theta)
    if centre == 0.0:
        return "the run started nearest θ = 0, not ±2π"
    return True if np.all(np.abs(theta - centre) < math.pi) else (
        "the archived θ leaves (θc − π, θc + π)")


# ------------------------------------------------------------------ the separatrix
@claim("pendulum on the separatrix",
       r"on (?:its|the) separatrix|This orbit lies on it|This pendulum is on the separatrix")
def on_separatrix(data) -> bool | str:
    """|1 − k²| from the archived energy E(0) is below SEPARATRIX_ON"""
    m1 = _gap(data)
    return True if abs(m1) < theory.SEPARATRIX_ON else (
        f"the archived energy gives |1 − k²| = {abs(m1):.3g}, not below "
        f"{theory.SEPARATRIX_ON:g}")


def _near(data, side: int) -> bool | str:
    m1 = _gap(data)
    if not theory.SEPARATRIX_ON <= abs(m1) < theory.SEPARATRIX_NEAR:
        return (f"the archived energy gives |1 − k²| = {abs(m1):.3g}, outside "
                f"[{theory.SEPARATRIX_ON:g}, {theory.SEPARATRIX_NEAR:g})")
    if side * m1 <= 0:
        return f"the archived energy gives 1 − k² = {m1:.3g}: the other side"
    share = _upright_fraction(data, m1)
    return True if share > 0.5 else (
        f"the run spends {share:.2f} of its time beyond ±135°, not most of it")


@claim("pendulum libration just inside the separatrix",
       r"just inside (?:the separatrix|it)|librating just inside")
def near_inside(data) -> bool | str:
    """SEPARATRIX_ON ≤ 1 − k² < SEPARATRIX_NEAR from the archived energy, and the archived
    θ spends more than half of each whole period beyond ±135°"""
    return _near(data, +1)


@claim("pendulum rotation just above the separatrix",
       r"just above (?:the separatrix|it)|rotating just above")
def near_above(data) -> bool | str:
    """SEPARATRIX_ON ≤ k² − 1 < SEPARATRIX_NEAR from the archived energy, and the archived
    θ spends more than half of each whole turn beyond ±135°"""
    return _near(data, -1)


@claim("pendulum far from the separatrix", r"This orbit lies inside it: a libration|"
       r"This orbit lies above it: the pendulum rotates")
def far(data) -> bool | str:
    """|1 − k²| from the archived energy is at least SEPARATRIX_NEAR"""
    m1 = _gap(data)
    return True if abs(m1) >= theory.SEPARATRIX_NEAR else (
        f"the archived energy gives |1 − k²| = {abs(m1):.3g}, below "
        f"{theory.SEPARATRIX_NEAR:g}: near the separatrix")


# --------------------------------------------------------- against the small angle
@claim("pendulum small-angle periods nearly agree", r"the two nearly agree")
def nearly_agree(data) -> bool | str:
    """T/T0 − 1, T measured from the archived θ(t)'s upward crossings (or from scipy's K
    and the archived energy), is below SMALL_ANGLE_CLOSE"""
    excess = _excess(data)
    return True if 0 <= excess < PendulumSimulation.SMALL_ANGLE_CLOSE else (
        f"measured T/T0 − 1 = {excess:.3g}")


@claim("pendulum linear solution runs ahead",
       r"linear solution runs ahead|is shorter than the exact")
def runs_ahead(data) -> bool | str:
    """T measured from the archived θ(t) is at least (1 + SMALL_ANGLE_CLOSE) T0"""
    excess = _excess(data)
    return True if excess >= PendulumSimulation.SMALL_ANGLE_CLOSE else (
        f"measured T/T0 − 1 = {excess:.3g}")


@claim("pendulum period longer than the small-angle one",
       r"% longer than|times the small-angle period|"
       r"times as long\)")
def longer(data) -> bool | str:
    """T measured from the archived θ(t) exceeds T0 = 2π√(l/g)"""
    excess = _excess(data)
    return True if excess > 0 else f"measured T/T0 − 1 = {excess:.3g}"


@claim("pendulum period several small-angle periods",
       r"[\d.]+ times (?:the small-angle period|as long)")
def several_times(data) -> bool | str:
    """T measured from the archived θ(t) is at least 2 T0 (said as "… times")"""
    excess = _excess(data)
    return True if excess >= 1.0 else f"measured T/T0 = {excess + 1:.3g}, less than 2"


@claim("pendulum period a percentage longer", r"[\d.]+ % longer than")
def percent_longer(data) -> bool | str:
    """T measured from the archived θ(t) is less than 2 T0 (said as "… % longer")"""
    excess = _excess(data)
    return True if 0 < excess < 1.0 else f"measured T/T0 = {excess + 1:.3g}"


# -------------------------------------------------------------------- the reference
@claim("pendulum reference is the exact solution",
       r"compared with its exact solution in Jacobi|against the exact elliptic-function "
       r"solution")
def exact_reference(data) -> bool | str:
    """the archived reference starts at the archived state, keeps the archived energy E(0)
    at every sample, and is the Jacobi-sn solution evaluated again from the configured
    state (about the bottom it swings about)"""
    from ...core.models import pendulum

    p, ini = data.config.params, data.config.initial
    run = data.runs["main"]
    ref, ref_dot = (np.asarray(run.reference[c], dtype=float) for c in ("theta", "theta_dot"))
    y0 = np.asarray(run.y[0], dtype=float)
    if abs(ref[0] - y0[run.columns.index("theta")]) > 1e-9 * max(1.0, abs(ref[0])):
        return f"the archived reference starts at θ = {ref[0]:.6g}, not at the run's θ(0)"
    energy = pendulum.energy(ref, ref_dot, p.g, p.l, p.m)
    e0 = float(np.asarray(run.invariants["energy"])[0])
    drift = float(np.max(np.abs(energy - e0))) / (p.m * p.g * p.l)
    if drift > 1e-8:
        return f"the archived reference's energy departs from E(0) by {drift:.2g} of m g l"
    t = np.asarray(run.t, dtype=float)
    pick = np.unique(np.linspace(0, t.size - 1, 25).astype(int))
    centre = 2.0 * math.pi * round(ini.theta / (2.0 * math.pi)) if _gap(data) > 0 else 0.0
    theta, _ = pendulum.exact_solution(t[pick], ini.theta - centre, ini.theta_dot, p.g, p.l)
    worst = float(np.max(np.abs(theta + centre - ref[pick])))
    return True if worst < 1e-6 else (
        f"the archived reference differs from the Jacobi-sn solution by {worst:.2g} rad")


@claim("pendulum reference is a reference run", r"a reference run of scipy's DOP853")
def run_reference(data) -> bool | str:
    """|1 − k²| from the archived energy is below EXACT_SOLUTION_MIN_M1, where double
    precision no longer resolves the elliptic functions"""
    m1 = _gap(data)
    return True if abs(m1) < theory.EXACT_SOLUTION_MIN_M1 else (
        f"|1 − k²| = {abs(m1):.3g}: the elliptic functions resolve this motion")


# --------------------------------------------------------------- conjugate points
def _lagrangian_second_variations(data) -> dict[int, float]:
    v = data.analysis["phase_space_action"]
    return {int(k): float(x) for k, x in zip(v["mode"], v["second_variation_qp"],
                                              strict=True)}


@claim("pendulum action past a conjugate point",
       r"is past (?:the first conjugate point|\d+ conjugate points)")
def past_conjugate(data) -> bool | str:
    """the numerically differentiated Lagrangian action lowers under sin(πt/T) (negative
    second variation for k = 1), and for each mode k the sign matches k < ω0 T/π"""
    second = _lagrangian_second_variations(data)
    if second.get(1, 0.0) >= 0:
        return f"d²S/dε² = {second.get(1, math.nan):.3g} ≥ 0 for k = 1: a minimum"
    wT = _omega0(data) * data.config.boundary.T
    wrong = [k for k, s in second.items() if (s < 0) != (k * math.pi < wT)]
    return True if not wrong else f"the second variation's sign is off for k = {wrong}"


@claim("pendulum action a minimum", r"is short of the first conjugate point")
def before_conjugate(data) -> bool | str:
    """every numerically differentiated second variation of the Lagrangian action is
    positive"""
    second = _lagrangian_second_variations(data)
    negative = [k for k, s in second.items() if s <= 0]
    return True if not negative else f"d²S/dε² ≤ 0 for k = {negative}"


@claim("pendulum action lowered by θ or p alone", r"varying θ alone or p alone lowers S")
def saddle(data) -> bool | str:
    """the numerical second variations under δθ alone and under δp alone are negative"""
    v = data.analysis.get("phase_space_action")
    if v is None:
        return True  # the sentence is the section's general statement; nothing computed
    bad = [name for name in ("q", "p")
           if not np.all(np.asarray(v[f"second_variation_{name}"], dtype=float) < 0)]
    return True if not bad else f"a second variation under δ{bad} is not negative"
