"""The heavy top's claim-carrying sentences and what makes each true (issue 41; see
:mod:`reportgen.scene.claims`).

The words are chosen at simulate time: the case by b/a against the roots u1, u2 with the
tolerances CUSP_RTOL and STEADY_RTOL (:func:`reportgen.core.heavy_top_theory.classify`), the
sleeping top's side by |ω3| against 2√(I1 Mgl)/I3, its words by the stored thresholds on θ2 and
on the run's largest tilt, the steady root by the nearer of the two rates.  Each predicate
here measures again from what the archive holds besides those facts:

- the constants a, b, α, β of a run from its archived initial state (θ, θ̇, φ̇ and the body
  spin ω3 at t = 0, derived from the integrated attitude) and the configured I1, I3, Mgl,
  written in w = 1 − cos θ so a nearly upright top keeps its digits; the turning circles as
  roots of g(w) = f(1 − w) by numpy's companion matrix polished with Newton; the sign of φ̇
  = (b − a u)/(1 − u²) on each (notes (10.26), (10.31));
- the sign changes of the archived φ̇ column, the archived θ's range, returns to the vertical
  and largest tilt;
- I3² ω3² against 4 I1 Mgl with ω3 from the archived p_ψ = I3 ω3;
- the mean precession rate from the archived φ(t), against both roots of notes (10.45).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...scene.claims import claim
from .config import BAND_CASES, REDUCED_MIN_SIN
from .simulation import HeavyTopSimulation as Sim

#: |φ̇| on the upper circle against |φ̇| on the lower: at most CUSP_SURE, a cusp; above
#: CUSP_NOT, none; in between either reading is accepted (the roots' own rounding)
CUSP_SURE, CUSP_NOT = 1e-12, 1e-6
#: u2 − u1 below this fraction of 1 − u1: no nutation (steady precession)
STEADY_TOLERANCE = 1e-8


# ------------------------------------------------------------------ measurements
@dataclass(frozen=True)
class Turning:
    """A run's turning circles w1 ≤ w2 (w = 1 − cos θ) and φ̇ = (B + a w)/(w (2 − w)) on them,
    notes (10.26)."""

    a: float
    w1: float
    w2: float
    upper: float  # φ̇ on the upper circle
    lower: float  # φ̇ on the lower circle
    #: |g(w0)| and |g'(w0)| at the start, each over the sum of its terms' sizes: both vanish
    #: when the start is a double root, notes (10.37) (a companion matrix splits a double
    #: root by ~√eps, so coinciding circles are found here rather than from the roots)
    double_root: float

    @property
    def width(self) -> float:
        return self.w2 - self.w1

    @property
    def steady(self) -> bool:
        return (self.double_root <= STEADY_TOLERANCE
                or self.width <= STEADY_TOLERANCE * max(self.w2, 1e-300))

    def cases(self) -> set[str]:
        """The cases the measurement allows (two near the cusp tolerance)."""
        if self.steady:
            return {"steady"}
        ratio = abs(self.upper) / abs(self.lower) if self.lower else math.inf
        if not math.isfinite(self.upper) or ratio <= CUSP_SURE:
            return {"cusps"}
        signed = {"loops" if self.upper * self.lower < 0 else "waves"}
        return signed | {"cusps"} if ratio <= CUSP_NOT else signed

    def case(self) -> str:
        return "/".join(sorted(self.cases()))


def _start(data, name: str = "main") -> tuple[float, float, float, float]:
    """θ, θ̇, φ̇, ω3 of the archived run at t = 0."""
    run = data.runs[name]
    return (float(run["theta"][0]), float(run["theta_dot"][0]), float(run["phi_dot"][0]),
            float(run["omega_3"][0]))


def turning(data, name: str = "main") -> Turning:
    """The turning circles of the archived run ``name`` from its initial state and the
    configured top: g(w) = f(1 − w) = −βw³ + (2β − c − a²)w² + 2(c − aB)w − B², with
    c = α − β = θ̇² + φ̇² sin²θ − 2β sin²(θ/2) and B = b − a = φ̇ sin²θ − 2a sin²(θ/2).  The
    roots are found in v = w/w0 (w0 = 1 − cos θ0), so that a nearly upright top's circles,
    w ~ θ0², are of order one, and polished with Newton."""
    p = data.config.params
    theta, theta_dot, phi_dot, omega3 = _start(data, name)
    a, beta = p.I3 * omega3 / p.I1, 2.0 * p.Mgl / p.I1
    s2, h2 = math.sin(theta) ** 2, math.sin(0.5 * theta) ** 2
    B = phi_dot * s2 - 2.0 * a * h2
    c = theta_dot**2 + phi_dot**2 * s2 - 2.0 * beta * h2
    coeffs = np.array([-beta, 2.0 * beta - c - a * a, 2.0 * (c - a * B), -B * B])
    w0 = 2.0 * h2
    scale = w0 if w0 > 0 else 1.0
    scaled = coeffs * scale ** np.arange(3, -1, -1)  # g(scale v) in v

    def polished(v):
        d = np.polyder(scaled)
        for _ in range(8):
            slope = np.polyval(d, v)
            if slope == 0:
                break
            v = v - np.polyval(scaled, v) / slope
        return float(v)

    roots = np.sort(np.real(np.roots(scaled / np.max(np.abs(scaled)))))
    v1, v2 = roots[-2], roots[-1]
    if v2 - v1 > 1e-6 * max(abs(v2), 1e-300):
        v1, v2 = sorted((polished(v1), polished(v2)))
    w1, w2 = scale * v1, scale * v2

    def phi_dot_at(w):
        return (B + a * w) / (w * (2.0 - w)) if 0.0 < w < 2.0 else math.nan

    powers = w0 ** np.arange(3, -1, -1)
    terms = np.abs(coeffs * powers)
    slope_terms = np.abs(np.polyder(coeffs) * powers[1:])
    double = max(abs(np.polyval(coeffs, w0)) / (terms.sum() or 1.0),
                 abs(np.polyval(np.polyder(coeffs), w0)) / (slope_terms.sum() or 1.0))
    return Turning(a, float(w1), float(w2), phi_dot_at(w1), phi_dot_at(w2), float(double))


def _phi_dot_sign_changes(data, name: str = "main") -> bool:
    """Whether the archived φ̇ takes both signs, beyond 1e-6 of its largest size."""
    v = np.asarray(data.runs[name]["phi_dot"], dtype=float)
    scale = float(np.max(np.abs(v))) or 1.0
    return bool(np.min(v) < -1e-6 * scale and np.max(v) > 1e-6 * scale)


def _case_holds(data, case: str, name: str = "main") -> bool | str:
    """The case of run ``name`` measured again (:func:`turning`), cross-checked with the sign
    changes of its archived φ̇."""
    run = data.runs[name]
    theta = np.asarray(run["theta"], dtype=float)
    if float(np.max(np.abs(theta))) == 0.0:
        return True if case == "sleeping" else "the archived axis stays exactly upright"
    found = turning(data, name)
    if case not in found.cases():
        return (f"run {name!r}: the turning circles from its archived start give "
                f"{found.case()} (φ̇ = {found.upper:.3g} rad/s on the upper circle, "
                f"{found.lower:.3g} rad/s on the lower)")
    if case == "waves" and _phi_dot_sign_changes(data, name):
        return f"run {name!r}: the archived φ̇ changes sign"
    return True


def _spin_squared_ratio(data) -> float:
    """I3² ω3² / (4 I1 Mgl), ω3 from the archived p_ψ = I3 ω3 at t = 0."""
    p = data.config.params
    p_psi = float(np.asarray(data.runs["main"].invariants["p_psi"])[0])
    return p_psi**2 / (4.0 * p.I1 * p.Mgl)


def _theta(data, name: str = "main") -> np.ndarray:
    return np.asarray(data.runs[name]["theta"], dtype=float)


def _returns(data) -> int:
    """Returns of the archived axis towards the vertical after its first fall: local
    minima of θ below a tenth of its largest value, after the first maximum."""
    theta = _theta(data)
    top = float(np.max(theta))
    first = int(np.argmax(theta > 0.5 * top))
    x = theta[first:]
    minima = np.nonzero((x[1:-1] < x[:-2]) & (x[1:-1] <= x[2:]) & (x[1:-1] < 0.1 * top))[0]
    return int(minima.size)


# ------------------------------------------------------------------ the cases
@claim("heavy top loops",
       r"the axis loops between|in looping nutation|Heavy top: looping nutation|"
       r"this top's changes sign|\bcase loops (?:\(a =|θ₁, θ₂)|the axis loops \(textbook|"
       r"(?<!s: )released on θmin[^→]{0,120}→ loops\b")
def loops(data) -> bool | str:
    """φ̇ on the two turning circles, measured again from the archived start, has opposite
    signs (and does not vanish on the upper one)"""
    return _case_holds(data, "loops")


@claim("heavy top waves",
       r"the axis waves between|in wavy nutation|Heavy top: wavy nutation|"
       r"this top's keeps its sign|\bcase waves (?:\(a =|θ₁, θ₂)|the axis waves \(textbook|"
       r"(?<!s: )released on θmin[^→]{0,120}→ waves\b")
def waves(data) -> bool | str:
    """φ̇ on the two turning circles, measured again, has one sign, and the archived φ̇
    never changes sign"""
    return _case_holds(data, "waves")


@claim("heavy top cusps",
       r"Here b/a = u₂[:,]|in cusped nutation|Heavy top: cusped nutation|"
       r"this top's touches zero|\bcase cusps (?:\(a =|θ₁, θ₂)|, cusps \(textbook|"
       r"so the (?:tiny )?path has cusps|each return is a cusp|"
       r"(?<!s: )released on θmin[^→]{0,120}→ cusps\b")
def cusps(data) -> bool | str:
    """φ̇ on the upper turning circle, measured again from the archived start, vanishes
    against φ̇ on the lower one"""
    return _case_holds(data, "cusps")


@claim("heavy top steady precession",
       r"in steady precession at|steady precession on one circle|\bcase steady (?:\(a =|θ₁, θ₂)|"
       r"of f\(u\) coincide: there is no nutation band|E' sits at the minimum of V'|"
       r"Heavy top: (?:fast |slow )?steady precession")
def steady(data) -> bool | str:
    """the archived θ stays within 1e-6 rad of its start over the run, and the turning
    circles measured again coincide"""
    theta = _theta(data)
    spread = float(np.max(theta) - np.min(theta))
    if spread > 1e-6:
        return f"the archived θ ranges over {spread:.3g} rad: it nutates"
    found = turning(data)
    return True if found.steady else (
        f"the turning circles from the archived start are {found.width:.3g} apart in 1 − cos θ")


@claim("heavy top without nutation",
       r"f\(u\) has a double root, there is no nutation|small-oscillation limit, k² = 0|"
       r"No nutation \(u₁ = u₂\)")
def no_nutation(data) -> bool | str:
    """the archived θ stays within 1e-6 rad of its start over the run"""
    theta = _theta(data)
    spread = float(np.max(theta) - np.min(theta))
    return True if spread <= 1e-6 else f"the archived θ ranges over {spread:.3g} rad"


@claim("heavy top nutates",
       r"θ oscillates between the turning angles")
def nutates(data) -> bool | str:
    """the turning circles measured again from the archived start are apart (not steady)"""
    found = turning(data)
    return True if not found.steady else "the turning circles coincide: no nutation"


def _nearer_root(data) -> str | None:
    """"slow" or "fast": which root of I1 cos θ0 φ̇² − I3 ω3 φ̇ + Mgl = 0, notes (10.45), the
    archived mean φ̇ (from φ(t)) is nearer; "fast" is the larger in size."""
    p = data.config.params
    run = data.runs["main"]
    t, phi = np.asarray(run.t, dtype=float), np.asarray(run["phi"], dtype=float)
    mean = (phi[-1] - phi[0]) / (t[-1] - t[0])
    theta0, _, _, omega3 = _start(data)
    roots = np.roots([p.I1 * math.cos(theta0), -p.I3 * omega3, p.Mgl])
    roots = np.real(roots[np.abs(np.imag(roots)) <= 1e-9 * np.abs(roots)])
    if roots.size == 0:
        return None
    if roots.size == 1:
        return "slow"
    slow, fast = sorted(roots, key=abs)
    return "fast" if abs(mean - fast) < abs(mean - slow) else "slow"


@claim("heavy top fast steady root",
       r"the fast root of notes \(10\.45\)|started at the fast rate|Heavy top: fast steady")
def fast_root(data) -> bool | str:
    """the archived mean φ̇ is nearer the larger root of notes (10.45), both solved again"""
    root = _nearer_root(data)
    return True if root == "fast" else f"the archived mean φ̇ is nearer the {root} root"


@claim("heavy top slow steady root",
       r"the slow root of notes \(10\.45\)|started at the slow rate|Heavy top: slow steady")
def slow_root(data) -> bool | str:
    """the archived mean φ̇ is nearer the smaller root of notes (10.45), both solved again"""
    root = _nearer_root(data)
    return True if root == "slow" else f"the archived mean φ̇ is nearer the {root} root"


@claim("heavy top released at rest",
       r"released at rest [^,.;]* from the vertical|the top is released at rest,")
def at_rest(data) -> bool | str:
    """the archived θ̇ and φ̇ at t = 0 vanish (below 1e-9 of the run's largest rates)"""
    _, theta_dot, phi_dot, _ = _start(data)
    run = data.runs["main"]
    scale = float(np.max(np.abs(run["theta_dot"])) + np.max(np.abs(run["phi_dot"]))) or 1.0
    worst = max(abs(theta_dot), abs(phi_dot))
    return True if worst <= 1e-9 * scale else (
        f"the archived start has θ̇ = {theta_dot:.3g}, φ̇ = {phi_dot:.3g} rad/s")


# ------------------------------------------------------------------ the sleeping top
@claim("heavy top above its sleeping threshold",
       r"above its sleeping threshold|Sleeping top above its threshold|(?<!un)stable: |"
       r"(?<!un)stable equilibrium: the top|faster than its sleeping threshold|above it, so ")
def above_threshold(data) -> bool | str:
    """I3² ω3² > 4 I1 Mgl, ω3 from the archived p_ψ and the configured top"""
    ratio = _spin_squared_ratio(data)
    return True if ratio > 1.0 else f"I3² ω3²/(4 I1 Mgl) = {ratio:.4g} from the archived p_ψ"


@claim("heavy top below its sleeping threshold",
       r"below its sleeping threshold|Sleeping top below its threshold|unstable: |"
       r"unstable equilibrium: the top|slower than its sleeping threshold|below it, so |"
       r"Unstable sleeping top \(u₃ ≤ 1\)")
def below_threshold(data) -> bool | str:
    """I3² ω3² < 4 I1 Mgl, ω3 from the archived p_ψ and the configured top"""
    ratio = _spin_squared_ratio(data)
    return True if ratio < 1.0 else f"I3² ω3²/(4 I1 Mgl) = {ratio:.4g} from the archived p_ψ"


@claim("heavy top stays upright", r"the sleeping top stays upright|; the top sleeps")
def stays_upright(data) -> bool | str:
    """the archived θ stays below STAYS_UPRIGHT throughout"""
    reached = float(np.max(_theta(data)))
    return True if reached <= Sim.STAYS_UPRIGHT else f"the archived θ reaches {reached:.3g} rad"


@claim("heavy top tilt of the order of the initial",
       r"tilt stays of the order of the initial|a band of the order of the initial tilt")
def of_the_order(data) -> bool | str:
    """the archived largest tilt is less than OF_THE_ORDER times the initial one"""
    theta = _theta(data)
    growth = float(np.max(theta)) / float(theta[0]) if theta[0] > 0 else math.inf
    return True if growth < Sim.OF_THE_ORDER else (
        f"the archived tilt grows {growth:.3g}-fold")


@claim("heavy top tilts away", r"the sleeping top tilts away")
def tilts_away(data) -> bool | str:
    """the archived largest tilt is at least TILTS_AWAY times the initial one"""
    theta = _theta(data)
    growth = float(np.max(theta)) / float(theta[0]) if theta[0] > 0 else 0.0
    return True if growth >= Sim.TILTS_AWAY else f"the archived tilt grows only {growth:.3g}-fold"


@claim("heavy top exactly upright",
       r"starts exactly upright|stands exactly upright|standing exactly upright|"
       r"the top stays upright, and on the vertical|the axis stays vertical|"
       r"\bcase sleeping (?:\(a =|θ₁, θ₂)|The sleeping top stays on the vertical")
def exactly_upright(data) -> bool | str:
    """the archived θ is 0 at the start and stays below 1e-9 rad"""
    theta = _theta(data)
    return True if theta[0] == 0.0 and float(np.max(theta)) < 1e-9 else (
        f"the archived θ starts at {theta[0]:.3g} and reaches {float(np.max(theta)):.3g} rad")


@claim("heavy top returns to the vertical",
       r"then rises back to\s+the vertical|each return is a cusp at the top")
def returns(data) -> bool | str:
    """the archived θ comes back near the vertical at least once after its fall"""
    n = _returns(data)
    return True if n >= 1 else "the archived θ never comes back towards the vertical"


@claim("heavy top later returns", r"the later returns miss the upper circle")
def later_returns(data) -> bool | str:
    """the archived θ comes back near the vertical at least twice"""
    n = _returns(data)
    return True if n >= 2 else f"the archived θ comes back {n} time(s)"


@claim("heavy top run ends before a return", r"this run ends before it returns")
def no_return(data) -> bool | str:
    """the archived θ never comes back near the vertical"""
    n = _returns(data)
    return True if n == 0 else f"the archived θ comes back {n} time(s)"


# ------------------------------------------------------------------ the band's runs
def _band_run_holds(data, name: str) -> bool | str:
    """Run ``name`` of a band is the case of its name, measured again; and, over two
    nutation periods or more, the spacing of its archived θ maxima is its stored period."""
    if name not in data.runs:
        return f"the archive holds no run {name!r}"
    verdict = _case_holds(data, name, name)
    if verdict is not True:
        return verdict
    run = data.runs[name]
    t, theta = np.asarray(run.t, dtype=float), np.asarray(run["theta"], dtype=float)
    peaks = np.nonzero((theta[1:-1] > theta[:-2]) & (theta[1:-1] >= theta[2:]))[0] + 1
    period = float(data.analysis["band"]["runs"][name]["nutation_period"])
    if peaks.size >= 3:
        spacing = float(np.mean(np.diff(t[peaks])))
        if abs(spacing / period - 1.0) > 0.02:
            return f"run {name!r}: θ maxima {spacing:.4g} s apart, not {period:.4g} s"
    return True


@claim("heavy top band run loops", r"loops run loops,|loops \(loops\)|\(a\) loops")
def band_loops(data) -> bool | str:
    """the band's loops run loops (measured again), with its stored nutation period"""
    return _band_run_holds(data, "loops")


@claim("heavy top band run waves", r"waves run waves,|waves \(waves\)|\(b\) waves")
def band_waves(data) -> bool | str:
    """the band's waves run waves (measured again), with its stored nutation period"""
    return _band_run_holds(data, "waves")


@claim("heavy top band run cusps", r"cusps run cusps,|cusps \(cusps\)|\(c\) cusps")
def band_cusps(data) -> bool | str:
    """the band's cusps run has cusps (measured again), with its stored nutation period"""
    return _band_run_holds(data, "cusps")


@claim("heavy top band of three cases", r"looping, wavy and cusped nutation \(textbook")
def band_all(data) -> bool | str:
    """the archive holds the three runs, each the case of its name (measured again)"""
    for name in BAND_CASES:
        verdict = _band_run_holds(data, name)
        if verdict is not True:
            return verdict
    return True


@claim("heavy top loops against the spin on the upper circle",
       r"φ̇ against the spin on the upper circle and with it on the lower one")
def loops_signs(data) -> bool | str:
    """every looping run in the archive has φ̇ against the spin on its upper circle and with
    it on its lower one (measured again)"""
    names = [n for n in data.runs if n != "main" or len(data.runs) == 1]
    for name in names:
        found = turning(data, name)
        if found.cases() != {"loops"}:
            continue
        if not (found.upper * found.a < 0 < found.lower * found.a):
            return (f"run {name!r}: φ̇ = {found.upper:.3g} rad/s on the upper circle, "
                    f"{found.lower:.3g} on the lower, a = {found.a:.3g}")
    return True


@claim("heavy top loci once round the band", r"the whole number that takes it once round "
       r"the band: Δφ")
def once_round(data) -> bool | str:
    """each band run's archived φ turns by at least 2π over the stretch Fig. 4.3 draws"""
    band = data.analysis["band"]
    for name in BAND_CASES:
        run = data.runs[name]
        stop = int(band["runs"][name]["locus_stop"])
        turn = abs(float(run["phi"][stop - 1] - run["phi"][0]))
        if turn < 2.0 * math.pi * (1.0 - 1e-3):
            return f"run {name!r}: the archived φ turns by {turn:.4g} rad over the stretch drawn"
    return True


@claim("heavy top sleeping sweep stability", r"stability, notes \(10\.50\)")
def sweep_stability(data) -> bool | str:
    """each sweep row's side of I3² ω3² = 4 I1 Mgl, from its spin and the configured top,
    is the side its ratio to the threshold says; an unstable row's archived tilt grows ten-fold
    wherever its run spans five e-foldings, a stable row's stays below 100 times the start"""
    p = data.config.params
    sw = data.analysis["sleeping_sweep"]
    t_end = float(sw["t"][-1])
    for ratio, w3, growth, top in zip(sw["omega3_over_threshold"], sw["omega3"],
                                      sw["growth_rate"], sw["theta_max"], strict=True):
        stable = (p.I3 * w3) ** 2 > 4.0 * p.I1 * p.Mgl
        if stable != (ratio > 1):
            return f"ω3 = {w3:.4g} rad/s: I3² ω3² against 4 I1 Mgl disagrees with the row"
        if stable and top > 100.0 * sw["tilt"]:
            return f"the stable row at ω3 = {w3:.4g} rad/s tilts to {top:.3g} rad"
        if not stable and growth * t_end > 5.0 and top < 10.0 * sw["tilt"]:
            return f"the unstable row at ω3 = {w3:.4g} rad/s stays at {top:.3g} rad"
    return True


# ------------------------------------------------------------------ method and names
def _closest_sin(data) -> float:
    """The least sin θ over the motion: over the turning circles measured again, and over
    the archived θ."""
    found = turning(data)
    on_circles = min(math.sin(2.0 * math.asin(math.sqrt(max(0.0, min(w, 2.0)) / 2.0)))
                     for w in (found.w1, found.w2))
    return min(on_circles, float(np.min(np.sin(_theta(data)))))


@claim("heavy top integrated reduced", r"\(auto: sin θ ≥ [\d.]+ over the motion\)")
def reduced_auto(data) -> bool | str:
    """the axis keeps sin θ ≥ REDUCED_MIN_SIN over the motion (turning circles measured
    again, and the archived θ)"""
    least = _closest_sin(data)
    return True if least >= REDUCED_MIN_SIN * (1.0 - 1e-9) else (
        f"sin θ comes down to {least:.3g}")


@claim("heavy top integrated spin-free", r"\(auto: the axis comes within sin θ =")
def spin_free_auto(data) -> bool | str:
    """the axis comes within sin θ < REDUCED_MIN_SIN of the vertical over the motion"""
    least = _closest_sin(data)
    return True if least < REDUCED_MIN_SIN * (1.0 + 1e-9) else (
        f"sin θ stays at or above {least:.3g}")


@claim("heavy top textbook ℘ scale agrees", r"the textbook's form happens to give the same")
def textbook_scale(data) -> bool | str:
    """β = 2 Mgl/I1 from the configured top has β² = 4 (β℘ and (4/β)℘ coincide in number)"""
    p = data.config.params
    beta = 2.0 * p.Mgl / p.I1
    return True if abs(beta * beta - 4.0) <= 1e-5 * 4.0 else f"β = {beta:.6g}: β² ≠ 4"
