"""``heavy_top`` config: parameters, the initial state or a nutation band to solve for,
the ``[sleeping]`` sweep, the formulation, presets, and the initial states they give."""

from __future__ import annotations

import math
from typing import Literal, NamedTuple

from pydantic import Field, model_validator

from ...lazy import lazy_module
from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, RunConfig, Strict
from ...scene.units import angle_hint

theory = lazy_module("reportgen.core.heavy_top_theory")  # validation solves for the band

CASES = ("loops", "waves", "cusps", "steady", "sleeping")
#: the runs of ``[band] case = "all"``, in the order of Fig. 4.3 (a), (b), (c)
BAND_CASES = ("loops", "waves", "cusps")
ALL_KEYS = ("params.I1, params.I3, params.Mgl, initial.theta, initial.theta_dot, "
            "initial.phi_dot, initial.omega3")


class Params(Strict):
    I1: Positive = Field(description="moment of inertia about a transverse axis through the "
                                     "fixed point [kg m²]")
    I3: Positive = Field(description="moment of inertia about the symmetry axis [kg m²]")
    Mgl: Positive = Field(description="M g l: weight × distance of the centre of mass from "
                                      "the fixed point [J]")


class Initial(Strict):
    """The initial state (one of [initial] and [band] is required)."""

    theta: Real = Field(description="tilt of the symmetry axis from the upward vertical, "
                                    "0 ≤ θ < π [rad]")
    theta_dot: Real = Field(0.0, description="θ̇0 [rad/s]")
    phi_dot: Real | None = Field(None, description="precession rate φ̇0 [rad/s] "
                                                   "(or give `steady`)")
    omega3: Real = Field(description="spin ω3 = ψ̇ + φ̇ cos θ [rad/s]")
    steady: Literal["slow", "fast"] | None = Field(
        None, description='"slow"/"fast": φ̇0 = that steady precession rate (notes (10.45)), '
                          'θ̇0 = 0')


class Band(Strict):
    """Instead of [initial]: a nutation band and a textbook Fig. 4.3 case to solve for.

    The scene releases the top on the upper circle θmin (θ̇0 = 0) with the φ̇0 that
    makes θmax the lower turning circle and gives the case asked for."""

    theta_min: Real = Field(description="upper turning circle θ1, 0 < θmin < θmax [rad]")
    theta_max: Real = Field(description="lower turning circle θ2, θmin < θmax < π [rad]")
    case: Literal["loops", "waves", "cusps", "all"] = Field(
        description='"loops", "waves", "cusps", or "all": the three as runs loops, waves, '
                    'cusps and the textbook Fig. 4.3 figure')
    omega3: Real | None = Field(
        None, description="spin ω3 [rad/s] of loops and waves (cusps have one possible spin "
                          "per band); default: 1.5 × the cusp spin for loops, halfway between "
                          "the smallest wave spin and the cusp spin for waves")


class Sleeping(Strict):
    """``[sleeping]``: sweep of ω3 across the sleeping-top threshold (notes (10.50))."""

    tilt: Positive = Field(1e-6, description="initial tilt of every sweep run, 0 < tilt < π "
                                             "[rad]")
    omega3_over_threshold: list[Positive] = Field(
        [0.5, 0.8, 0.9, 1.1, 1.25, 2.0], min_length=1, max_length=12,
        description="spins of the sweep as multiples of the threshold ω3 [dimensionless]")
    t_end: Positive | None = Field(None, description="duration of each sweep run [s] "
                                                      "(default: run.t_end)")

    @model_validator(mode="after")
    def _tilt(self):
        if not self.tilt < math.pi:
            raise ValueError(f"sleeping.tilt: must satisfy 0 < tilt < π (got {self.tilt})"
                             + angle_hint(self.tilt, valid=lambda a: 0.0 < a < math.pi))
        return self


#: ``formulation = "auto"`` integrates Lagrange's reduced equations when the axis stays at
#: least this far from the vertical over the whole motion (sin θ ≥ this for θ1 ≤ θ ≤ θ2),
#: else the spin-free frame, for which the vertical is an ordinary point
REDUCED_MIN_SIN = 0.1

#: crossings are located reliably only with this many samples per nutation period
MIN_SAMPLES_PER_PERIOD = 16


class HeavyTopRun(RunConfig):
    formulation: Literal["auto", "reduced", "spin_free"] = Field(
        "auto", description='"reduced" (Lagrange\'s reduction in w = 1 − cos θ, with φ and ψ '
                            'as quadratures: cheapest, singular on the vertical), "spin_free" '
                            '(the non-spinning frame of the axis: regular everywhere) or '
                            '"auto": reduced when sin θ ≥ '
                            f'{REDUCED_MIN_SIN:g} over the whole motion')


class HeavyTopConfig(SceneConfig):
    params: Params
    initial: Initial | None = None
    band: Band | None = None
    run: HeavyTopRun
    sleeping: Sleeping | None = None
    expect_case: Literal["loops", "waves", "cusps", "steady", "sleeping"] | None = Field(
        None, description="the textbook Fig. 4.3 case the parameters must give (presets set "
                          "it)")

    @model_validator(mode="after")
    def _physics(self):
        p = self.params
        if p.I3 > 2.0 * p.I1:
            raise ValueError(f"params.I3: a symmetric body needs I3 ≤ I1 + I2 = 2 I1 "
                             f"(got I3 = {p.I3}, I1 = {p.I1})")
        if self.initial is not None and self.band is not None:
            raise ValueError("initial / band: give one of [initial] (an initial state) and "
                             "[band] (a nutation band to solve for), not both")
        if self.band is not None:
            self._check_band()
        elif self.initial is None:
            raise ValueError("initial: required table is missing (or give [band] with "
                             "theta_min, theta_max and case)")
        else:
            self._check_initial()
        return self

    def _check_band(self) -> None:
        p, band = self.params, self.band
        if not 0.0 < band.theta_min < band.theta_max < math.pi:
            raise ValueError(f"band.theta_min / band.theta_max: must satisfy 0 < θmin < θmax < π "
                             f"(got θmin = {band.theta_min}, θmax = {band.theta_max})"
                             + angle_hint(band.theta_min, band.theta_max,
                                          valid=lambda a: 0.0 < a < math.pi))
        if self.expect_case is not None:
            raise ValueError(f"expect_case: not with [band], whose case says it "
                             f"(got expect_case = {self.expect_case!r})")
        key = "band.omega3" if band.omega3 is not None else "band.theta_min / band.theta_max"
        for case in _band_cases(band):
            try:
                theory.band_start(p.I1, p.I3, p.Mgl, band.theta_min, band.theta_max, case,
                                  _band_omega3(band, case))
            except theory.ImpossibleBand as exc:
                raise ValueError(f"{key}: {exc}") from None

    def _check_initial(self) -> None:
        p, ini = self.params, self.initial
        if not 0.0 <= ini.theta < math.pi:
            raise ValueError(f"initial.theta: must satisfy 0 ≤ θ < π (got {ini.theta})"
                             + angle_hint(ini.theta, valid=lambda a: 0.0 <= a < math.pi))
        if ini.steady is not None:
            if ini.phi_dot is not None:
                raise ValueError("initial.phi_dot / initial.steady: give one of them "
                                 f"(got phi_dot = {ini.phi_dot}, steady = {ini.steady!r})")
            if ini.theta_dot != 0.0:
                raise ValueError(f"initial.theta_dot: steady precession needs θ̇0 = 0 "
                                 f"(got {ini.theta_dot})")
            if ini.theta == 0.0:
                raise ValueError("initial.theta / initial.steady: steady precession needs a "
                                 "tilted axis (θ > 0); θ = 0 is the sleeping top")
            slow, fast = theory.steady_precession_rates(p.I1, p.I3, p.Mgl, ini.theta, ini.omega3)
            rate = slow if ini.steady == "slow" else fast
            if math.isnan(slow):
                bound = 4 * p.I1 * p.Mgl * math.cos(ini.theta)
                raise ValueError(
                    f"initial.omega3 / initial.steady: no steady precession: notes (10.46) "
                    f"needs "
                    f"I3² ω3² ≥ 4 I1 M g l cos θ = {bound:.6g} "
                    f"(got I3² ω3² = {(p.I3 * ini.omega3) ** 2:.6g})")
            if not math.isfinite(rate):
                raise ValueError("initial.steady: at θ = π/2 only the slow rate exists "
                                 f"(got steady = {ini.steady!r})")
        elif ini.theta == 0.0 and ini.phi_dot != 0.0:
            raise ValueError(f"initial.phi_dot: on the vertical (θ = 0) φ is undefined and "
                             f"a precession rate means nothing; give 0 (got {ini.phi_dot})")
        elif ini.phi_dot is None:
            raise ValueError("initial.phi_dot: required key is missing (or give "
                             "initial.steady = \"slow\" / \"fast\")")
        phi_dot = _phi_dot(self)
        if ini.omega3 == 0.0 and phi_dot * math.sin(ini.theta) == 0.0:
            raise ValueError("initial.omega3 / initial.phi_dot: a = b = 0 is a plane pendulum "
                             "swinging through the vertical, not a top (use kind = "
                             "\"pendulum\")")
        c = theory.constants(p.I1, p.I3, p.Mgl, ini.theta, ini.theta_dot, phi_dot, ini.omega3)
        r = theory.roots(c)
        try:
            theory.check_admissible(r, c)
        except theory.NoAdmissibleInterval as exc:
            raise ValueError(f"{ALL_KEYS}: {exc}") from None
        if self.expect_case is not None:
            case = theory.classify(r, c)
            if case != self.expect_case:
                ratio = c.b / c.a if c.a != 0 else math.inf
                raise ValueError(
                    f"expect_case: the parameters give '{case}', not '{self.expect_case}' "
                    f"(a = {c.a:.6g}, b = {c.b:.6g}, b/a = {ratio:.10g}, u1 = {r.u1:.10g}, "
                    f"u2 = {r.u2:.10g}; loops need u1 < b/a < u2, cusps b/a = u2 (released "
                    f"at rest: θ̇0 = φ̇0 = 0), waves b/a outside [u1, u2]); change "
                    f"initial.phi_dot / initial.theta_dot / initial.omega3 or expect_case")


def _band_cases(band: Band) -> tuple[str, ...]:
    return BAND_CASES if band.case == "all" else (band.case,)


def _band_omega3(band: Band, case: str) -> float | None:
    """The configured spin of one band run: cusps of ``case = "all"`` take their own."""
    return None if (band.case == "all" and case == "cusps") else band.omega3


class Start(NamedTuple):
    """The initial state of one run: θ0, θ̇0, φ̇0 [rad, rad/s] and the spin ω3 [rad/s]."""

    theta: float
    theta_dot: float
    phi_dot: float
    omega3: float


def starts(config: HeavyTopConfig) -> dict[str, Start]:
    """Run name -> initial state: ``main`` from ``[initial]`` or a one-case ``[band]``;
    ``loops``, ``waves``, ``cusps`` for ``case = "all"``."""
    if config.band is None:
        ini = config.initial
        return {"main": Start(ini.theta, ini.theta_dot, _phi_dot(config), ini.omega3)}
    p, band = config.params, config.band
    starts = {case: Start(*theory.band_start(p.I1, p.I3, p.Mgl, band.theta_min, band.theta_max,
                                             case, _band_omega3(band, case)))
              for case in _band_cases(band)}
    return starts if band.case == "all" else {"main": starts[band.case]}


def _phi_dot(config: HeavyTopConfig) -> float:
    ini, p = config.initial, config.params
    if ini.steady is None:
        return float(ini.phi_dot)
    slow, fast = theory.steady_precession_rates(p.I1, p.I3, p.Mgl, ini.theta, ini.omega3)
    return slow if ini.steady == "slow" else fast


#: the top of the presets and the audit cases
TOP = {"I1": 1.0, "I3": 0.5, "Mgl": 1.0}


def _preset(initial, t_end, samples, case=None, **extra):
    out = {"params": dict(TOP), "initial": initial, "run": {"t_end": t_end, "samples": samples}}
    if case is not None:
        out["expect_case"] = case
    return out | extra


#: Fig. 4.3's band: the upper and lower turning circles θ1 = 50°, θ2 = 60° [rad]
FIG43_BAND = (math.radians(50.0), math.radians(60.0))

#: the cases of Fig. 4.3 and the sleeping top (explicit keys override).  Fig. 4.3 a/b/c
#: are the three runs of configs/heavy_top_fig4.3.toml: released at rest in θ on the
#: upper circle θ1 = 50° with the φ̇0, ω3 that band_start solves for so that θ2 = 60°
#: (cusps: the one spin of the band; loops 1.5 times it; waves halfway between the
#: smallest wave spin and it); each run goes a full turn round the band (Δφ ≥ 2π)
PRESETS = {
    # T = 1.35342 s, Δφ = 0.283264 rad per period: 23 periods are 31.13 s
    "fig4.3a": _preset({"theta": FIG43_BAND[0], "theta_dot": 0.0,
                        "phi_dot": -0.3168071689827444, "omega3": 9.723477700446692},
                       32.0, 3201, "loops"),
    # T = 3.33752 s, Δφ = 1.572850 rad: 4 periods are 13.35 s
    "fig4.3b": _preset({"theta": FIG43_BAND[0], "theta_dot": 0.0,
                        "phi_dot": 0.26563611133989, "omega3": 4.752971132950242},
                       14.0, 1401, "waves"),
    # T = 2.17290 s, Δφ = 0.705923 rad: 9 periods are 19.56 s
    "fig4.3c": _preset({"theta": FIG43_BAND[0], "theta_dot": 0.0, "phi_dot": 0.0,
                        "omega3": 6.482318466964461}, 20.0, 2001, "cusps"),
    "sleeping_stable": _preset({"theta": 1e-6, "theta_dot": 0.0, "phi_dot": 0.0,
                                "omega3": 6.0}, 40.0, 4001,
                               sleeping={"tilt": 1e-6, "t_end": 60.0}),
    "sleeping_unstable": _preset({"theta": 1e-6, "theta_dot": 0.0, "phi_dot": 0.0,
                                  "omega3": 2.8}, 100.0, 10001,
                                 sleeping={"tilt": 1e-6, "t_end": 60.0}),
    "steady_slow": _preset({"theta": 1.0, "theta_dot": 0.0, "steady": "slow",
                            "omega3": 6.0}, 30.0, 3000, "steady"),
    "steady_fast": _preset({"theta": 1.0, "theta_dot": 0.0, "steady": "fast",
                            "omega3": 6.0}, 10.0, 3000, "steady"),
}
