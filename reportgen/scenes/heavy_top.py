r"""``heavy_top``: the heavy symmetric top (lecture notes §10.1, eqs. 10.21-10.50).

Integrated as a quaternion with the body angular velocity (no Euler-angle
singularity: θ = 0 is an ordinary point); θ, φ, ψ and the symmetry axis are
derived for output.  Closed form from the cubic f(u) (10.31): its roots, the
Fig. 4.3 case (loops / waves / cusps), nutation period, precession per period,
u(t) in Jacobi sn² and through Weierstrass's ℘ (exercise 4.10), steady precession
rates (10.45-10.46) and the sleeping-top threshold (10.49-10.50), each checked against
an independent evaluation.

Instead of ``[initial]`` a ``[band]`` asks for a nutation band θmin ≤ θ ≤ θmax and a
case; the scene solves for the release on the upper circle that gives it
(:func:`reportgen.core.heavy_top_theory.band_start`).  ``case = "all"`` integrates the
three cases on the same band as runs ``loops``, ``waves`` and ``cusps`` (``/runs/main``
is ``/runs/loops``) and draws them as Fig. 4.3 is printed.
"""

from __future__ import annotations

import math
from typing import Literal, NamedTuple

import numpy as np
from pydantic import Field, model_validator

from ..config import ConfigError, Positive, Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import AuditCase, Check, Results, RunRecord
from .base import (
    Scene,
    SceneConfig,
    Section,
    SectionContent,
    Table,
    fmt,
    fmt_err,
    kept_members,
    member_text,
)

plots = lazy_module("reportgen.plots.heavy_top")
model_core = lazy_module("reportgen.core.models.heavy_top")
theory = lazy_module("reportgen.core.heavy_top_theory")
kinematics = lazy_module("reportgen.core.heavy_top_kinematics")
integrators = lazy_module("reportgen.core.integrators")

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
        None, description='"slow"/"fast": φ̇0 = that steady precession rate (10.45), θ̇0 = 0')


class Band(Strict):
    """Instead of [initial]: a nutation band and a Fig. 4.3 case to solve for.

    The scene releases the top on the upper circle θmin (θ̇0 = 0) with the φ̇0 that
    makes θmax the lower turning circle and gives the case asked for."""

    theta_min: Real = Field(description="upper turning circle θ1, 0 < θmin < θmax [rad]")
    theta_max: Real = Field(description="lower turning circle θ2, θmin < θmax < π [rad]")
    case: Literal["loops", "waves", "cusps", "all"] = Field(
        description='"loops", "waves", "cusps", or "all": the three as runs loops, waves, '
                    'cusps and the Fig. 4.3 figure')
    omega3: Real | None = Field(
        None, description="spin ω3 [rad/s] of loops and waves (cusps have one possible spin "
                          "per band); default: 1.5 × the cusp spin for loops, halfway between "
                          "the smallest wave spin and the cusp spin for waves")


class Sleeping(Strict):
    """``[sleeping]``: sweep of ω3 across the sleeping-top threshold (10.50)."""

    tilt: Positive = Field(1e-6, description="initial tilt of every sweep run [rad]")
    omega3_over_threshold: list[Positive] = Field(
        [0.5, 0.8, 0.9, 1.1, 1.25, 2.0], min_length=1, max_length=12,
        description="spins of the sweep, in units of the threshold ω3")
    t_end: Positive | None = Field(None, description="duration of each sweep run [s] "
                                                      "(default: run.t_end)")


#: ``formulation = "auto"`` integrates Lagrange's reduced equations when the axis stays at
#: least this far from the vertical over the whole motion (sin θ ≥ this for θ1 ≤ θ ≤ θ2),
#: else the spin-free frame, for which the vertical is an ordinary point
REDUCED_MIN_SIN = 0.1

FORMULATION_TEXT = {
    "reduced": "Lagrange's reduction: the nutation w = 1 − cos θ (ẅ = g′(w)/2, a polynomial) "
               "and the quadratures φ, ψ; the body attitude follows from θ, φ, ψ",
    "spin_free": "the frame that follows the axis without spinning (a quaternion and "
                 "its angular velocity ⊥ the axis), turned by ω3 t",
}


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
        None, description="the Fig. 4.3 case the parameters must give (presets set it)")

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
            raise ValueError(f"band.theta_min / band.theta_max: need 0 < θmin < θmax < π "
                             f"(got θmin = {band.theta_min}, θmax = {band.theta_max})")
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
            raise ValueError(f"initial.theta: must satisfy 0 ≤ θ < π (got {ini.theta})")
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
                    f"initial.omega3 / initial.steady: no steady precession: (10.46) needs "
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


def _starts(config: HeavyTopConfig) -> dict[str, Start]:
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


_TOP = {"I1": 1.0, "I3": 0.5, "Mgl": 1.0}


def _preset(initial, t_end, samples, case=None, **extra):
    out = {"params": dict(_TOP), "initial": initial, "run": {"t_end": t_end, "samples": samples}}
    if case is not None:
        out["expect_case"] = case
    return out | extra


class HeavyTopScene(Scene):
    kind = "heavy_top"
    order = 70
    summary = ("heavy symmetric top: nutation loci (loops, waves, cusps), f(u), steady "
               "precession, the sleeping top")
    Config = HeavyTopConfig
    presets = {
        # θ0 = 1 rad, ω3 = 6 rad/s, threshold ω3 = 4 rad/s; steady rates 0.356 and 5.196 rad/s
        "fig4.3a": _preset({"theta": 1.0, "theta_dot": 0.0, "phi_dot": 1.5, "omega3": 6.0},
                           30.0, 3000, "loops"),
        "fig4.3b": _preset({"theta": 1.0, "theta_dot": 0.0, "phi_dot": 0.2, "omega3": 6.0},
                           30.0, 3000, "waves"),
        "fig4.3c": _preset({"theta": 1.0, "theta_dot": 0.0, "phi_dot": 0.0, "omega3": 6.0},
                           30.0, 3000, "cusps"),
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
    family_sections = (
        Section("nutation_family", "Nutation band and case across the family",
                description="Each member's turning circles and case against the swept "
                            "value; dashed: where the case changes between neighbours."),
        Section("loci_family", "Nutation loci of the kept members",
                description="The path of the symmetry axis of each kept member."),
    )
    sections = (
        Section("fig4_3", "Fig. 4.3: loops, waves and cusps on one band", integrates=True),
        Section("nutation_locus", "Nutation locus of the symmetry axis", integrates=True),
        Section("cubic", "The cubic f(u), its roots, nutation period and precession"),
        Section("weierstrass", "u(t) through Weierstrass's ℘ (exercise 4.10)"),
        Section("effective_potential", "Effective potential"),
        Section("time_series", "θ(t) and φ̇(t) against the closed form", integrates=True),
        Section("steady_precession", "Steady precession"),
        Section("sleeping_sweep", "The sleeping top across its threshold"),
        Section("invariants", "Conserved quantities", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def audit_cases(cls):
        def case(name, initial, t_end, samples, what):
            config = {"kind": "heavy_top", "title": name, "params": dict(_TOP),
                      "initial": initial, "run": {"t_end": t_end, "samples": samples}}
            return AuditCase(name=name, config=config, what=what,
                             methods=("dop853", "gauss6", "rk45"))

        return [
            case("sleeping top exactly upright, below its threshold",
                 {"theta": 0.0, "theta_dot": 0.0, "phi_dot": 0.0, "omega3": 2.8}, 50.0, 2001,
                 "θ = 0 is a coordinate singularity of the Euler angles and an unstable "
                 "equilibrium: the quaternion state must stay finite and upright"),
            case("fast top, ω3 = 200 rad/s (50 × the sleeping threshold)",
                 {"theta": 1.0, "theta_dot": 0.0, "phi_dot": 0.0, "omega3": 200.0}, 20.0,
                 40001, "nutation 60 ms and 1e-4 rad against a precession of ~60 s: two "
                        "widely separated time scales over ~300 nutation periods"),
            case("top just above its sleeping threshold, tilted 1e-6",
                 {"theta": 1e-6, "theta_dot": 0.0, "phi_dot": 0.0,
                  "omega3": 1.02 * 2.0 * math.sqrt(_TOP["I1"] * _TOP["Mgl"]) / _TOP["I3"]},
                 100.0, 5001, "2 % above I3²ω3² = 4 I1 Mgl: the tilt must stay small, but the "
                 "nutation is slow and nearly degenerate"),
            case("top just below its sleeping threshold, tilted 1e-6",
                 {"theta": 1e-6, "theta_dot": 0.0, "phi_dot": 0.0,
                  "omega3": 0.98 * 2.0 * math.sqrt(_TOP["I1"] * _TOP["Mgl"]) / _TOP["I3"]},
                 100.0, 5001, "2 % below the threshold: a 1e-6 tilt grows to order one"),
        ]

    #: ℘ (exercise 4.10; /analysis weierstrass_max_difference) is computed for every
    #: nutating top (3 ms), the tilted sleeping tops included; a sleeping-top scene (one
    #: with a [sleeping] sweep, which is about its threshold) shows its section only when
    #: its [report] sections name it
    computed_on_request = ("error_vs_runtime",)

    def computes(self, name: str) -> bool:
        return name == "weierstrass" or super().computes(name)

    #: f(u) is drawn around [u1, u2] alone when u2 − u1 is less than this fraction of the
    #: range [−1, u3] (else the motion's interval is a sliver)
    NARROW_BAND = 0.1

    #: crossings are located reliably only with this many samples per nutation period
    MIN_SAMPLES_PER_PERIOD = 16

    # ----------------------------------------------------------------- helpers
    @property
    def starts(self) -> dict[str, Start]:
        """Run name -> initial state (one run, or the three of ``[band] case = "all"``)."""
        return _starts(self.config)

    @property
    def threshold(self) -> float:
        p = self.config.params
        return theory.sleeping_threshold_omega3(p.I1, p.I3, p.Mgl)

    def _constants(self, start: Start) -> theory.TopConstants:
        p = self.config.params
        return theory.constants(p.I1, p.I3, p.Mgl, *start)

    def _invariants(self, y):
        p = self.config.params
        return model_core.invariants(y, p.I1, p.I3, p.Mgl)

    def _scales(self, start: Start, c: theory.TopConstants) -> dict[str, float]:
        """Natural sizes of the invariants (drift is relative to them)."""
        p = self.config.params
        return theory.invariant_scales(p.I1, p.I3, p.Mgl, start.omega3, c)

    @classmethod
    def from_source(cls, source):
        """A ``[run] formulation`` that cannot integrate one of the starts is refused (exit
        2) before anything runs."""
        scene = super().from_source(source)
        for start in scene.starts.values():
            scene.formulation(start)
        return scene

    # -------------------------------------------------------------- simulation
    def models(self) -> list:
        """The model the first start integrates (:meth:`formulation`; the sleeping sweep
        integrates the spin-free one with DOP853, its own choice)."""
        return [self._model(next(iter(self.starts.values())))]

    def _model(self, start: Start):
        """The model one start integrates (:meth:`formulation`): the spin ω3 is a
        parameter, not a state."""
        return self._integration(start)[0]

    def formulation(self, start: Start, c: theory.TopConstants | None = None
                    ) -> tuple[str, str]:
        """("reduced" or "spin_free", why).  The reduced equations divide by sin²θ, so
        ``auto`` takes them only when the axis keeps away from the vertical (sin θ ≥
        :data:`REDUCED_MIN_SIN` at both turning circles; sin is concave on [0, π], so
        then in between too); a named one that cannot run is refused (exit 2).  ``c``:
        the start's constants, when the caller has them."""
        run = self.config.run
        r = theory.roots(self._constants(start) if c is None else c)
        lowest = min(math.sin(theory.theta_of_w(r.w1)), math.sin(theory.theta_of_w(r.w2)))
        if run.formulation == "spin_free":
            return "spin_free", '[run] formulation = "spin_free"'
        if run.formulation == "reduced":
            if lowest <= 0.0:
                raise ConfigError([
                    f"{self.source.label}: key 'run.formulation': the reduced equations are "
                    f"singular on the vertical, which this top reaches (sin θ = {lowest:.3g} "
                    f'at a turning circle): expected "spin_free" or "auto", got "reduced"'])
            return "reduced", '[run] formulation = "reduced"'
        if lowest >= REDUCED_MIN_SIN:
            return "reduced", f"auto: sin θ ≥ {lowest:.3g} over the motion"
        return "spin_free", (f"auto: the axis comes within sin θ = {lowest:.3g} of the "
                             "vertical")

    def _integration(self, start: Start, c: theory.TopConstants | None = None):
        """(model, y0, body(t, y) -> the body state (q, ω), formulation, why) of one start
        (``c``: its constants, when the caller has them)."""
        p = self.config.params
        c = self._constants(start) if c is None else c
        name, why = self.formulation(start, c)
        if name == "reduced":
            model = model_core.reduced_model(p.I1, p.I3, p.Mgl, start.omega3, c.A, c.B)
            return (model, model_core.reduced_initial_state(start.theta, start.theta_dot),
                    lambda t_, y: model_core.reduced_body_state(y, model.params), name, why)
        model = model_core.spin_free_model(p.I1, p.I3, p.Mgl, start.omega3)
        return (model, model_core.spin_free_initial_state(*start[:3]),
                lambda t_, y: model_core.body_state(t_, y, start.omega3), name, why)

    def simulate(self, progress=None) -> Results:
        run = self.config.run
        starts = self.starts
        results = Results()
        for k, (name, start) in enumerate(starts.items()):
            part = None if progress is None else (
                lambda x, k=k: progress((k + x) / len(starts)))
            record, analysis, checks = self._simulate_start(start, part)
            results.runs[name] = record
            if name in ("main", BAND_CASES[0]):
                results.analysis.update(analysis)
                results.checks.extend(checks)
            else:
                results.checks.extend(Check(f"[{name}] {c.quantity}", c.value, c.reference,
                                            c.unit, c.source, c.scale) for c in checks
                                      if c.quantity in self.BAND_RUN_CHECKS)
            if self.config.band is not None:
                results.analysis.setdefault("band", self._band_info())["runs"][name] = (
                    self._band_run_summary(record, analysis))
        if "main" not in results.runs:
            results.runs["main"] = results.runs[BAND_CASES[0]]  # one HDF5 object, two names
        if self.config.sleeping is not None:
            # computed whenever [sleeping] is given: [report] edits re-stamp the archive
            # without simulating again, and the section must then still find it
            results.analysis["sleeping_sweep"] = self._sleeping_sweep()
        model, y0, *_ = self._integration(next(iter(starts.values())))
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201),
                   progress=progress)
        return results

    def _simulate_start(self, start: Start, progress=None):
        """Integrate one initial state: (run, analysis, checks) for the archive."""
        p, run = self.config.params, self.config.run
        c = self._constants(start)
        r = theory.roots(c)
        case = theory.classify(r, c)
        period = theory.nutation_period(r, c)
        precession = theory.precession_per_period(r, c)
        model, y0, body, formulation, why = self._integration(start, c)
        t = np.linspace(0.0, run.t_end, run.samples)
        scales = self._scales(start, c)
        raw = self.integrate(model, y0, t,
                             invariants=lambda t_, y: self._invariants(body(t_, y)),
                             invariant_scales=scales, progress=progress,
                             n_periods=run.t_end / period if math.isfinite(period) else None)
        raw.y = body(raw.t, raw.y)  # the archived state: body quaternion and ω
        main, motion = self._derived_run(raw)
        main.attrs["formulation"] = formulation
        main.attrs["formulation_reason"] = why

        slow, fast = theory.steady_precession_rates(p.I1, p.I3, p.Mgl, start.theta, start.omega3)
        w_cf, _u_cf = theory.u_closed_form(t, r, c)
        u_err = np.abs(motion["w"] - w_cf)
        measured_T, measured_dphi = kinematics.measure_nutation(
            t, motion, w1=r.w1, w2=r.w2, period=period,
            min_samples_per_period=self.MIN_SAMPLES_PER_PERIOD)
        w_lo, w_hi = kinematics.extreme_values(t, motion["w"], motion["w_dot"], motion["w_ddot"])
        a = {
            "a": c.a, "b": c.b, "alpha": c.alpha, "beta": c.beta,
            "b_over_a": c.b / c.a if c.a != 0 else math.nan,
            "u1": r.u1, "u2": r.u2, "u3": r.u3,
            "one_minus_u1": r.w2, "one_minus_u2": r.w1,
            "theta1": theory.theta_of_w(r.w1), "theta2": theory.theta_of_w(r.w2),
            "theta_min_measured": theory.theta_of_w(w_lo),
            "theta_max_measured": theory.theta_of_w(w_hi),
            "k2": r.m if r.w2 > r.w3 else math.nan,
            "case": case,
            "nutation_period": period,
            "nutation_period_quadrature": theory.nutation_period_quadrature(r, c),
            "nutation_period_measured": measured_T,
            "precession_per_period": precession,
            "precession_quadrature": theory.precession_quadrature(r, c),
            "precession_measured": measured_dphi,
            "reduced_energy": 0.5 * p.I1 * c.alpha,
            "steady_rate_slow": slow, "steady_rate_fast": fast,
            "steady_exists": bool(math.isfinite(slow)),
            "theta0": start.theta, "theta_dot0": start.theta_dot, "phi_dot0": start.phi_dot,
            "omega3": start.omega3,
            "sleeping_threshold_omega3": self.threshold,
            "sleeping_stable": bool(abs(start.omega3) > self.threshold),
            "sleeping_growth_rate": theory.sleeping_growth_rate(p.I1, p.I3, p.Mgl, start.omega3),
            "u_max_error": float(np.max(u_err)),
            "mean_phi_dot": float((main["phi"][-1] - main["phi"][0]) / (t[-1] - t[0])),
        }
        a["period_sensitivity"] = self._period_sensitivity(start, c, main, period, scales)
        self._store_closed_form(a, main, start, c, r)
        if self.computes("weierstrass"):
            self._store_weierstrass(a, main, c, r, w_cf)
        checks = self._checks(a, main, start, c, r, scales)
        return main, a, checks

    def _derived_run(self, raw: RunRecord) -> tuple[RunRecord, dict]:
        """The archived run: Euler angles, axis, rates and the integrated state."""
        p = self.config.params
        m = kinematics.derived_motion(raw.y, p.I1, p.I3, p.Mgl)
        columns = ["theta", "phi", "psi", "axis_x", "axis_y", "axis_z", "theta_dot", "phi_dot",
                   *model_core.COLUMNS]
        data = np.column_stack([m["theta"], m["phi"], m["psi"], m["axis"], m["theta_dot"],
                                m["phi_dot"], raw.y])
        return RunRecord(t=raw.t, y=data, columns=columns, invariants=raw.invariants,
                         attrs=raw.attrs), m

    def _store_closed_form(self, a: dict, main: RunRecord, start: Start,
                           c: theory.TopConstants, r: theory.Roots) -> None:
        """Everything the report draws from the closed form, sampled here: θ(t) of the
        sn² solution on the run's grid, cos θ − closed form, f(u) near its roots, V'(θ)
        and the steady-rate curves against ω3."""
        p = self.config.params
        # θ(t) in closed form on the output grid, and the integration's difference in cos θ
        w_cf, _u = theory.u_closed_form(main.t, r, c)
        main.reference = {"theta": theory.theta_of_w(w_cf)}
        main.attrs["reference_label"] = (
            "closed form cos θ = u1 + (u2 − u1) sn²(λt + τ0 | k²), λ = ½√(β(u3 − u1)): the "
            "Jacobi form of the quadrature t = ∫du/√f(u) (Goldstein 5.72; DLMF §22.15)")
        q = np.column_stack([main["q_w"], main["q_x"], main["q_y"], main["q_z"]])
        w = kinematics.one_minus_cos_theta(q)
        width = a["one_minus_u1"] - a["one_minus_u2"]
        relative = bool(width > 0.0)
        a["cos_theta_error"] = {"difference": (w - w_cf) / width if relative else w - w_cf,
                                "relative_to_width": relative}
        # f(u) (10.31); near the vertical in w = 1 − u, where [u1, u2] would be invisible
        w2 = a["one_minus_u1"]
        if 0.0 < w2 < 1e-3:
            x = np.linspace(0.0, 1.25 * w2, 1201)
            a["cubic_curve"] = {"variable": "w", "x": x, "f": theory.g_w(x, c),
                                "root1": a["one_minus_u2"], "root2": w2, "root3": 1.0 - a["u3"],
                                "ratio": -c.B / c.a if c.a else math.nan, "start": c.w0}
        else:
            hi = min(max(1.05, a["u3"] + 0.1 * (a["u3"] - a["u1"])), 3.0) if math.isfinite(
                a["u3"]) else 1.5
            lo, width = -1.0, a["u2"] - a["u1"]
            if 0.0 < width < self.NARROW_BAND * (hi - lo):  # a sliver on [−1, u3]: zoom in
                lo, hi = max(-1.0, a["u1"] - width), a["u2"] + width
            x = np.linspace(lo, hi, 1201)
            a["cubic_curve"] = {"variable": "u", "x": x, "f": theory.f_u(x, c),
                                "root1": a["u1"], "root2": a["u2"], "root3": a["u3"],
                                "ratio": a["b_over_a"], "start": math.cos(start.theta)}
        # V'(θ) (10.28); on the vertical (the sleeping top) it is not drawn
        if a["case"] != "sleeping":
            if a["theta2"] < 0.05:
                # near the vertical V' − Mgl is of order θ²: evaluated in w = 1 − cos θ
                theta = np.linspace(0.5 * a["theta1"], 1.5 * a["theta2"], 1500)
                V, energy = theory.effective_potential_near_vertical(theta, p.I1, p.Mgl, c)
                shifted = True
            else:
                theta = np.linspace(1e-3, math.pi - 1e-3, 1500)
                V = theory.effective_potential(theta, p.I1, p.Mgl, c)
                energy, shifted = a["reduced_energy"], False
            a["effective_potential"] = {"theta": theta, "V": V, "energy": energy,
                                        "minus_Mgl": shifted}
        # the two steady precession rates (10.45) against the spin, from the bound (10.46)
        w_min = theory.steady_precession_min_omega3(p.I1, p.I3, p.Mgl, start.theta)
        lo = w_min * 1.0001 if math.isfinite(w_min) else 0.1
        om = np.linspace(lo, max(3.0 * abs(start.omega3), 2 * lo), 400)
        slow, fast = theory.steady_precession_curve(p.I1, p.I3, p.Mgl, start.theta, om)
        a["steady_rates"] = {"omega3": om, "slow": slow, "fast": fast, "omega3_min": w_min}

    @staticmethod
    def _store_weierstrass(a: dict, main: RunRecord, c: theory.TopConstants,
                           r: theory.Roots, w_sn: np.ndarray) -> None:
        """u(t) through ℘ on the output grid (exercise 4.10), its lattice, and its largest
        difference from the sn² form; nothing for a top without nutation."""
        form = theory.weierstrass_form(r, c)
        if form is None:
            return
        w_wp = theory.w_weierstrass(main.t, form, r)
        main.reference["cos_theta_weierstrass"] = 1.0 - w_wp
        difference = float(np.max(np.abs(w_wp - w_sn)))
        a["weierstrass_max_difference"] = difference
        a["weierstrass"] = {
            "g2": form.g2, "g3": form.g3, "e1": form.e1, "e2": form.e2, "e3": form.e3,
            "omega": form.omega, "omega_prime": form.omega_prime, "x0": form.x0,
            "scale": form.scale, "shift": form.shift, "t_end": float(main.t[-1]),
            "period": 2.0 * form.omega, "series_terms": form.lattice.terms,
            "nome": math.exp(-math.pi * form.omega_prime / form.omega),
            "max_difference": difference,
        }

    def _period_sensitivity(self, start: Start, c, main: RunRecord, period: float,
                            scales: dict[str, float]) -> float:
        """|ΔT/T| if E' were off by the run's own energy drift (conditioning of T).

        Near the sleeping top the roots close to u = 1 are set by differences of
        order θ² in E' and p_φ: there an energy error of 1e-12 shifts the measured
        period by percents, and only this estimate says how far to trust it.
        """
        p = self.config.params
        e = main.invariants["energy"]
        drift = max(float(np.max(np.abs(e - e[0]))), np.finfo(float).eps * scales["energy"])
        return theory.period_sensitivity(p.I1, p.I3, p.Mgl, *start, drift, period)

    #: the checks repeated for the waves and cusps runs of ``case = "all"``
    BAND_RUN_CHECKS = ("θ2 = arccos u1 (the band's θmax)", "largest θ of the integrated run",
                       "max |u℘(t) − u_sn²(t)| on the output grid")

    def _checks(self, a: dict, main: RunRecord, start: Start, c: theory.TopConstants,
                r: theory.Roots, scales: dict[str, float]) -> list[Check]:
        checks = []
        src_T = "4K(k²)/√(β(u3−u1)) (notes §10.1; Goldstein 5.72), vs ∮du/√f(u) by quadrature"
        band = self.config.band
        if band is not None:
            solved = "[band] of the config; the release solved for on the upper circle"
            measured = ("[band] of the config; extremes of the integrated θ(t), "
                        "Hermite-refined between samples")
            for name, value, ref, source in (
                    ("θ1 = arccos u2 (the band's θmin)", a["theta1"], band.theta_min, solved),
                    ("θ2 = arccos u1 (the band's θmax)", a["theta2"], band.theta_max, solved),
                    ("smallest θ of the integrated run", a["theta_min_measured"],
                     band.theta_min, measured),
                    ("largest θ of the integrated run", a["theta_max_measured"],
                     band.theta_max, measured)):
                checks.append(Check(name, value, ref, "rad", source))
        if math.isfinite(a["nutation_period_quadrature"]):
            checks.append(Check("nutation period (quadrature of dt = du/√f)",
                                a["nutation_period_quadrature"], a["nutation_period"], "s", src_T))
            checks.append(Check(
                "precession per period (quadrature of φ̇ dt)", a["precession_quadrature"],
                a["precession_per_period"], "rad",
                "Π(n|k²) closed form of ∮(b − a u)/(1 − u²) dt (10.26)",
                scale=max(abs(a["precession_per_period"]), 1e-300)))
        if "weierstrass" in a:
            wp = a["weierstrass"]
            checks.append(Check("nutation period 2ω of the ℘ lattice (AGM)", wp["period"],
                                a["nutation_period"], "s",
                                "4K(k²)/√(β(u3−u1)) with K in Carlson's R_F"))
            checks.append(Check("max |u℘(t) − u_sn²(t)| on the output grid",
                                a["weierstrass_max_difference"], 0.0, "",
                                "℘ by theta series (exercise 4.10) against Jacobi sn² by AGM; "
                                "absolute difference in u = cos θ", scale=1.0))
        if math.isfinite(a["nutation_period_measured"]):
            checks.append(Check("nutation period measured from θ(t)",
                                a["nutation_period_measured"], a["nutation_period"],
                                "s", "4K(k²)/√(β(u3−u1))" + self._conditioning(a)))
        if math.isfinite(a["precession_measured"]):
            checks.append(Check("precession per period measured from φ(t)",
                                a["precession_measured"], a["precession_per_period"],
                                "rad", "Π(n|k²) closed form (10.26)" + self._conditioning(a),
                                scale=max(abs(a["precession_per_period"]), 1e-300)))
        if r.w2 > r.w1 and not r.sleeping:
            w = 2.0 * (main["q_x"] ** 2 + main["q_y"] ** 2) / (
                main["q_w"] ** 2 + main["q_x"] ** 2 + main["q_y"] ** 2 + main["q_z"] ** 2)
            w_cf, _ = theory.u_closed_form(main.t[-1:], r, c)
            checks.append(Check("cos θ(t_end)", 1.0 - float(w[-1]), 1.0 - float(w_cf[0]),
                                "", "u1 + (u2−u1) sn²(λt + τ0 | k²) (Jacobi form of "
                                "Goldstein 5.72; FIELD-NOTES)", scale=r.w2 - r.w1))
        if a["case"] == "steady":
            checks.append(Check("mean φ̇ (steady precession)", a["mean_phi_dot"], start.phi_dot,
                                "rad/s", f"{self.config.initial.steady} root of (10.45)"))
        e = main.invariants["energy"]
        checks.append(Check("energy E(t_end)", float(e[-1]), float(e[0]), "J",
                            "E(0), conserved", scale=scales["energy"]))
        return checks

    def _band_info(self) -> dict:
        """The band asked for and which spins it allows (:class:`theory.BandSpins`)."""
        p, band = self.config.params, self.config.band
        spins = theory.band_spins(p.I1, p.I3, p.Mgl, band.theta_min, band.theta_max)
        return {"theta_min": band.theta_min, "theta_max": band.theta_max, "case": band.case,
                "omega3_cusps": spins.omega3_cusps, "omega3_waves_min": spins.omega3_waves_min,
                "sigma": spins.sigma, "possible_spins": spins.possible(), "runs": {}}

    @classmethod
    def _band_run_summary(cls, record: RunRecord, a: dict) -> dict:
        """One band run in a few numbers, and the stretch of it Fig. 4.3 draws: from the
        release to at most ``FIG43_PERIODS`` nutation periods, fewer when they would go
        round the sphere more than ``FIG43_SPAN`` [rad]."""
        keys = ("case", "theta1", "theta2", "theta_min_measured", "theta_max_measured",
                "omega3", "phi_dot0", "b_over_a", "u1", "u2", "u3", "nutation_period",
                "precession_per_period", "u_max_error")
        out = {k: a[k] for k in keys}
        out["weierstrass_max_difference"] = a.get("weierstrass_max_difference", math.nan)
        out["energy_drift"] = float(record.attrs.get("drift_energy", math.nan))
        # φ̇ = (b − a u)/(1 − u²) (10.26) on the two turning circles
        out["phi_dot_upper"] = (a["b"] - a["a"] * a["u2"]) / (1.0 - a["u2"] ** 2)
        out["phi_dot_lower"] = (a["b"] - a["a"] * a["u1"]) / (1.0 - a["u1"] ** 2)
        out["locus_stop"], out["locus_periods"], out["view_azimuth"] = cls._locus_stretch(
            record, a["nutation_period"], a["precession_per_period"])
        return out

    @classmethod
    def _locus_stretch(cls, record: RunRecord, period: float,
                       precession: float) -> tuple[int, int, float]:
        """(samples, nutation periods, view azimuth) of the stretch of a locus Fig. 4.3
        draws: from the release to at most ``FIG43_PERIODS`` nutation periods, fewer when
        they would go round the sphere more than ``FIG43_SPAN`` [rad]; the view faces
        the middle of the stretch (the axis' azimuth is φ − π/2, (4.46))."""
        dphi = abs(precession)
        periods = cls.FIG43_PERIODS
        if dphi > 0.0:
            periods = min(periods, max(cls.FIG43_MIN_PERIODS, math.floor(cls.FIG43_SPAN / dphi)))
        stop = int(np.searchsorted(record.t, periods * period, side="right"))
        stop = min(max(stop, 2), len(record.t))
        phi = record["phi"]
        return stop, periods, float(0.5 * (phi[0] + phi[stop - 1]) - 0.5 * math.pi)

    #: Fig. 4.3: nutation periods drawn per locus (at most, at least), and how far round
    #: the sphere [rad] they may go before fewer are drawn
    FIG43_PERIODS = 6
    FIG43_MIN_PERIODS = 2
    FIG43_SPAN = 1.1 * math.pi
    #: and the sphere is seen from this height above the horizon [degrees]
    FIG43_ELEVATION_DEG = 28.0

    @staticmethod
    def _conditioning(a) -> str:
        sens = a.get("period_sensitivity", math.nan)
        if math.isfinite(sens) and sens > 1e-6:
            return (f"; ill-conditioned: the run's own energy drift alone moves T by "
                    f"{fmt_err(sens)}")
        return ""

    def _sleeping_sweep(self) -> dict:
        """Tops tilted by ``tilt`` at several spins across the threshold (10.50)."""
        p, sl, run = self.config.params, self.config.sleeping, self.config.run
        t_end = sl.t_end or run.t_end
        t = np.linspace(0.0, t_end, 1001)
        ratios = np.array(sorted(sl.omega3_over_threshold), dtype=float)
        thetas, status = [], []
        y0 = model_core.spin_free_initial_state(sl.tilt, 0.0, 0.0)
        for ratio in ratios:
            model = model_core.spin_free_model(p.I1, p.I3, p.Mgl, ratio * self.threshold)
            sol = integrators.integrate(model, y0, t, method="dop853", rtol=run.rtol, atol=run.atol)
            thetas.append(kinematics.tilt_angle(sol.y[:, :4]))  # F' and the body share θ
            status.append(sol.status)
        thetas = np.array(thetas)
        return {
            "t": t, "omega3_over_threshold": ratios, "omega3": ratios * self.threshold,
            "theta": thetas, "theta_max": thetas.max(axis=1), "tilt": sl.tilt,
            "growth_rate": np.array([theory.sleeping_growth_rate(p.I1, p.I3, p.Mgl,
                                                                 x * self.threshold)
                                     for x in ratios]),
            "status": [str(s) for s in status],
        }

    # ------------------------------------------------------ report (archive only)
    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        a = data.analysis
        band = a.get("band")
        if band is None or band["case"] != "all":
            names.remove("fig4_3")
        else:  # Fig. 4.3 shows the three loci; the sections that follow describe loops
            for name in ("nutation_locus", "effective_potential", "time_series"):
                names.remove(name)
        if "weierstrass" not in a or "sleeping_sweep" in a:
            names.remove("weierstrass")  # no nutation, or a scene about the threshold
        initial = data.config.get("initial") or {}
        if a["case"] != "steady" and initial.get("steady") is None:
            names.remove("steady_precession")
        if "sleeping_sweep" not in a:
            names.remove("sleeping_sweep")
        if a["case"] == "sleeping" and "effective_potential" in names:
            names.remove("effective_potential")  # V'(θ) is flat-infinite at θ = 0 with b = a
        return names

    @classmethod
    def headline(cls, data):
        p = data.config.params
        a = data.analysis
        band = a.get("band")
        facts = [("parameters", f"I1 = {fmt(p.I1)} kg m², I3 = {fmt(p.I3)} kg m², "
                                f"M g l = {fmt(p.Mgl)} J")]
        if band is not None:
            facts.append(("band asked for", f"θmin = {fmt(band['theta_min'])} rad, θmax = "
                          f"{fmt(band['theta_max'])} rad, case = {band['case']}"))
            for name in [n for n in (*BAND_CASES, "main") if n in band["runs"]]:
                run = band["runs"][name]
                label = "released on θmin" if name == "main" else f"{name}: released on θmin"
                facts.append((label, f"θ̇0 = 0, φ̇0 = {fmt(run['phi_dot0'])} rad/s, ω3 = "
                                     f"{fmt(run['omega3'])} rad/s → {run['case']}, θ1 − θmin = "
                              f"{fmt_err(run['theta1'] - band['theta_min'])}, θ2 − θmax = "
                              f"{fmt_err(run['theta2'] - band['theta_max'])}"))
            if band["case"] == "all":
                facts.append(("sections below Fig. 4.3", "the loops run (/runs/main is "
                                                         "/runs/loops)"))
        else:
            facts.append(("initial state", f"θ0 = {fmt(a['theta0'])} rad, θ̇0 = "
                          f"{fmt(a['theta_dot0'])} rad/s, φ̇0 = {fmt(a['phi_dot0'])} rad/s, "
                          f"ω3 = {fmt(a['omega3'])} rad/s"))
        facts.append(("case", f"{a['case']} (a = {fmt(a['a'])}, b = {fmt(a['b'])}, "
                              f"b/a = {fmt(a['b_over_a'])}; u1 = {fmt(a['u1'])}, "
                              f"u2 = {fmt(a['u2'])})"))
        if math.isfinite(a["nutation_period"]):
            extra = " (small-oscillation limit, k² = 0)" if a["case"] in ("steady",
                                                                          "sleeping") else ""
            facts.append(("nutation period", f"{fmt(a['nutation_period'], 14)} s{extra}"))
        if math.isfinite(a["precession_per_period"]):
            facts.append(("precession per nutation period",
                          f"{fmt(a['precession_per_period'], 14)} rad"))
        if "weierstrass_max_difference" in a:
            facts.append(("℘ form against sn² form", "max |u℘ − u_sn²| = "
                          f"{fmt_err(a['weierstrass_max_difference'])} on the output grid"))
        facts.append(("sleeping-top threshold", f"ω3 = 2√(I1 M g l)/I3 = "
                      f"{fmt(a['sleeping_threshold_omega3'])} rad/s (10.50)"))
        formulation = data.runs["main"].attrs.get("formulation")
        if formulation in FORMULATION_TEXT:  # archives before it was stored: spin-free
            facts.append(("integrated", f"{FORMULATION_TEXT[formulation]} "
                                        f"({data.runs['main'].attrs.get('formulation_reason')})"))
        return facts

    @classmethod
    def section_fig4_3(cls, data):
        """The three band runs as Fig. 4.3 is printed, and a table of what each achieved."""
        band = data.analysis["band"]
        loci, labels, azimuths = [], [], []
        for letter, name in zip("abc", BAND_CASES, strict=True):
            run, summary = data.runs[name], band["runs"][name]
            stop = int(summary["locus_stop"])
            loci.append(np.column_stack([run["axis_x"], run["axis_y"], run["axis_z"]])[:stop])
            labels.append((f"({letter}) {summary['case']}",
                           f"ω3 = {summary['omega3']:.4g} rad/s, dφ/dt(0) = "
                           f"{summary['phi_dot0']:.3g} rad/s"))
            azimuths.append(summary["view_azimuth"])
        fig = plots.fig43(loci, theta1=band["theta_min"], theta2=band["theta_max"],
                          labels=labels, azimuths=azimuths,
                          elevation=math.radians(cls.FIG43_ELEVATION_DEG))
        rows = []
        for name in BAND_CASES:
            r = band["runs"][name]
            roots = max(abs(r["theta1"] - band["theta_min"]), abs(r["theta2"] - band["theta_max"]))
            span = max(abs(r["theta_min_measured"] - band["theta_min"]),
                       abs(r["theta_max_measured"] - band["theta_max"]))
            rows.append([f"{name} ({r['case']})", fmt(r["omega3"], 5), fmt(r["phi_dot0"], 5),
                         f"{fmt(r['phi_dot_upper'], 3)} / {fmt(r['phi_dot_lower'], 3)}",
                         f"{fmt_err(roots)} / {fmt_err(span)}", fmt(r["nutation_period"], 5),
                         fmt(r["precession_per_period"], 5),
                         fmt_err(r["weierstrass_max_difference"])])
        table = Table(
            caption=f"The three runs on θ ∈ [{fmt(band['theta_min'])}, {fmt(band['theta_max'])}] "
                    f"rad: the case the solved release gives (classified from b/a and u1, u2), "
                    f"φ̇ = (b − a cos θ)/sin²θ on the "
                    f"two circles, how far the roots of f(u) and the extremes of the integrated "
                    f"θ(t) are from the band (rad), and the ℘ form against the sn² form. "
                    f"{band['possible_spins'][0].upper()}{band['possible_spins'][1:]}.",
            header=["run (case)", "ω3 [rad/s]", "φ̇0 [rad/s]", "φ̇ on θ1 / θ2 [rad/s]",
                    "band error: roots / run", "T [s]", "Δφ [rad]", "max |u℘ − u_sn²|"],
            rows=rows)
        periods = ", ".join(f"{band['runs'][n]['locus_periods']}" for n in BAND_CASES)
        return SectionContent(
            figures=[cls.figure("fig4_3", fig,
                                f"The symmetry axis on the unit sphere between the turning "
                                f"circles θ1 = {fmt(band['theta_min'])} rad and θ2 = "
                                f"{fmt(band['theta_max'])} rad, seen from "
                                f"{cls.FIG43_ELEVATION_DEG:g}° above the horizon; dashed: "
                                f"behind the sphere. Each locus starts on the "
                                f"upper circle (dot) and runs {periods} nutation periods "
                                f"(loops, waves, cusps).")],
            tables=[table])

    @classmethod
    def section_nutation_family(cls, data):
        sweep = data.sweep
        a, ok = sweep.analysis, sweep.ok
        path, x = next(iter(sweep.values.items()))
        case = np.asarray(sweep.labels.get("case", np.full(sweep.size, "")), dtype=str)
        threshold = a.get("sleeping_threshold_omega3")
        swept_omega3 = path == "initial.omega3"
        fig = plots.nutation_family(
            x[ok], theta1=a["theta1"][ok], theta2=a["theta2"][ok], case=case[ok], xlabel=path,
            precession=a["precession_per_period"][ok] if "precession_per_period" in a else None,
            growth=a["sleeping_growth_rate"][ok] if "sleeping_growth_rate" in a else None,
            threshold=float(np.nanmedian(threshold[ok])) if threshold is not None
            and swept_omega3 else None)
        names, counts = np.unique(case[ok], return_counts=True)
        boundaries = plots._case_boundaries(x[ok], case[ok])
        facts = [("cases", ", ".join(f"{n} {c}" for n, c in zip(names, counts, strict=True)))]
        if boundaries:
            facts.append(("case changes", "; ".join(f"{left} → {right} near {path} = "
                                                   f"{fmt(at, 5)}" for at, left, right
                                                   in boundaries)))
        return SectionContent(figures=[cls.figure(
            "nutation_family", fig, f"Turning circles θ1 (▼) and θ2 (▲) of each member against "
            f"{path}, by case; the band between them shaded.")], facts=facts)

    @classmethod
    def section_loci_family(cls, data):
        sweep = data.sweep
        members = kept_members(data)
        loci, theta1, theta2, labels, azimuths = [], [], [], [], []
        a = sweep.analysis
        case = sweep.labels.get("case", np.full(sweep.size, ""))
        for i, name in members:
            run = data.runs[name]
            period = a["nutation_period"][i]
            if not (np.isfinite(period) and period > 0):  # no nutation: the whole run
                period = math.inf
            stop, _, azimuth = cls._locus_stretch(run, period, a["precession_per_period"][i])
            loci.append(np.column_stack([run["axis_x"], run["axis_y"], run["axis_z"]])[:stop])
            theta1.append(a["theta1"][i])
            theta2.append(a["theta2"][i])
            azimuths.append(azimuth)
            labels.append((str(case[i]) or f"member {i}", member_text(sweep, i, short=True)))
        fig = plots.loci_family(loci, theta1=theta1, theta2=theta2, labels=labels,
                                azimuths=azimuths,
                                elevation=math.radians(cls.FIG43_ELEVATION_DEG))
        return SectionContent(figures=[cls.figure(
            "loci_family", fig, "The symmetry axis of each kept member on the unit sphere, "
            "with its own turning circles θ1, θ2 (a few nutation periods from the release; "
            "dashed: behind the sphere).")])

    @classmethod
    def section_nutation_locus(cls, data):
        run = data.runs["main"]
        a = data.analysis
        axis = np.column_stack([run["axis_x"], run["axis_y"], run["axis_z"]])
        fig = plots.nutation_locus(axis, run["theta"], theta1=a["theta1"], theta2=a["theta2"])
        label = {"loops": "b/a inside (u1, u2): φ̇ changes sign, the axis loops (Fig. 4.3a)",
                 "waves": "b/a outside [u1, u2]: φ̇ keeps its sign, the axis waves (Fig. 4.3b)",
                 "cusps": "b/a = u2: φ̇ = 0 on the upper circle, cusps (Fig. 4.3c)",
                 "steady": "u1 = u2: no nutation, steady precession on one circle",
                 "sleeping": "the sleeping top: the axis stays vertical"}[a["case"]]
        return SectionContent(
            figures=[cls.figure("nutation_locus", fig,
                                f"Path of the symmetry axis; dashed: the turning circles "
                                f"θ1 = arccos u2 and θ2 = arccos u1. Case: {label}.")],
            facts=[("case", a["case"]), ("θ1, θ2", f"{fmt(a['theta1'])} rad, "
                                                   f"{fmt(a['theta2'])} rad")])

    @classmethod
    def section_cubic(cls, data):
        a = data.analysis
        cc = a["cubic_curve"]
        if cc["variable"] == "w":
            # near the vertical the interval is invisible on [−1, 1]: drawn against w = 1 − u
            fig = plots.cubic(cc["x"], cc["f"], u1=cc["root1"], u2=cc["root2"], u3=cc["root3"],
                              b_over_a=cc["ratio"], u0=cc["start"],
                              xlabel="1 − u = 1 − cos θ  (near the vertical)",
                              names=("1 − u2", "1 − u1", "1 − u3"), ratio_label="1 − b/a")
        else:
            fig = plots.cubic(cc["x"], cc["f"], u1=cc["root1"], u2=cc["root2"], u3=cc["root3"],
                              b_over_a=cc["ratio"], u0=cc["start"])
        rows = [
            ["a = I3 ω3/I1 (10.25)", fmt(a["a"], 14), "1/s"],
            ["b = p_φ/I1 (10.25)", fmt(a["b"], 14), "1/s"],
            ["α = 2E'/I1 (10.30)", fmt(a["alpha"], 14), "1/s²"],
            ["β = 2Mgl/I1 (10.30)", fmt(a["beta"], 14), "1/s²"],
            ["u1, 1 − u1", f"{fmt(a['u1'], 14)}, {fmt(a['one_minus_u1'], 14)}", ""],
            ["u2, 1 − u2", f"{fmt(a['u2'], 14)}, {fmt(a['one_minus_u2'], 14)}", ""],
            ["u3", fmt(a["u3"], 14), ""],
            ["k² = (u2 − u1)/(u3 − u1)", fmt(a["k2"], 14), ""],
        ]
        table = Table(caption="Constants of the motion and the roots of f(u)",
                      header=["quantity", "value", "unit"], rows=rows)
        per = []
        for name, closed, quad, meas, unit in (
                ("nutation period T", "nutation_period", "nutation_period_quadrature",
                 "nutation_period_measured", "s"),
                ("precession per period Δφ", "precession_per_period", "precession_quadrature",
                 "precession_measured", "rad")):
            ref = a[closed]
            per.append([name + f" [{unit}]", fmt(ref, 14), fmt(a[quad], 14),
                        fmt_err(abs(a[quad] / ref - 1)) if ref else "—", fmt(a[meas], 14),
                        fmt_err(abs(a[meas] / ref - 1)) if ref else "—"])
        table2 = Table(caption="Closed form (Carlson R_F, R_J) against quadrature of "
                               "∮du/√f(u) and against the integrated trajectory",
                       header=["quantity", "closed form", "quadrature", "rel. diff.",
                               "measured", "rel. diff."], rows=per)
        notes = []
        if a["case"] in ("steady", "sleeping"):
            notes.append("u1 = u2: f(u) has a double root, there is no nutation. The period "
                         "shown is the small-oscillation limit k² → 0, 2π/√(β(u3 − u1)); "
                         "nothing is measured.")
        if a["case"] == "sleeping" and not a["sleeping_stable"]:
            notes.append("Unstable sleeping top (u3 ≤ 1): no small-oscillation period (NaN).")
        sens = a.get("period_sensitivity", math.nan)
        if math.isfinite(sens) and sens > 1e-6:
            notes.append(f"Ill-conditioned: an energy error as small as this run's own drift "
                         f"changes the nutation period by {fmt_err(sens)} (relative). The "
                         f"axis passes close to the vertical, where the roots near u = 1 are "
                         f"set by differences of order θ² in E′ and p_φ; the measured values "
                         f"can agree with the closed form only to about this level.")
        if (not math.isfinite(a["nutation_period_measured"])
                and a["case"] not in ("steady", "sleeping")):
            notes.append(f"No measured period: the run covers fewer than two nutation periods "
                         f"or stores fewer than {cls.MIN_SAMPLES_PER_PERIOD} samples per "
                         f"period.")
        facts = [("sensitivity of T to an energy error of the run's drift",
                  fmt_err(sens))] if math.isfinite(sens) else []
        return SectionContent(
            facts=facts,
            figures=[cls.figure("f_of_u", fig, "f(u) = (1 − u²)(α − βu) − (b − au)² (10.31): "
                                "the motion is confined to u1 ≤ u ≤ u2 where f ≥ 0; "
                                "u3 > 1 is unphysical. Dashed: b/a, where φ̇ = 0.")],
            tables=[table, table2], notes=notes)

    @classmethod
    def section_weierstrass(cls, data):
        a = data.analysis
        wp = a.get("weierstrass")
        if wp is None:
            return SectionContent(notes=["No nutation (u1 = u2): the cubic has a double root "
                                         "and ℘ degenerates; nothing to show."])
        fig = plots.weierstrass_rectangle(wp["omega"], wp["omega_prime"], wp["x0"], wp["t_end"])
        rows = [
            ["u = λ℘ + μ: λ = 4/β", fmt(wp["scale"], 14), ""],
            ["μ = (u1 + u2 + u3)/3", fmt(wp["shift"], 14), ""],
            ["g2 = 2(e1² + e2² + e3²)", fmt(wp["g2"], 14), "1/s⁴"],
            ["g3 = 4 e1 e2 e3", fmt(wp["g3"], 14), "1/s⁶"],
            ["e1 = ℘(ω) = β(u3 − μ)/4", fmt(wp["e1"], 14), "1/s²"],
            ["e2 = ℘(ω + ω′) = β(u2 − μ)/4", fmt(wp["e2"], 14), "1/s²"],
            ["e3 = ℘(ω′) = β(u1 − μ)/4", fmt(wp["e3"], 14), "1/s²"],
            ["ω (real half-period)", fmt(wp["omega"], 14), "s"],
            ["ω′/i (imaginary half-period)", fmt(wp["omega_prime"], 14), "s"],
            ["x0: z(0) = x0 + ω′", fmt(wp["x0"], 14), "s"],
            ["nome q = exp(iπω′/ω)", fmt(wp["nome"], 6), ""],
        ]
        table = Table(caption="Invariants, roots and half-periods of ℘ for this top",
                      header=["quantity", "value", "unit"], rows=rows)
        return SectionContent(
            facts=[("max |u℘(t) − u_sn²(t)| on the output grid", fmt_err(wp["max_difference"])),
                   ("2ω against 4K(k²)/√(β(u3 − u1))",
                    fmt_err(abs(wp["period"] / a["nutation_period"] - 1.0)))],
            figures=[cls.figure(
                "weierstrass", fig,
                "The period rectangle of ℘ with corners 0, 2ω, 2ω + 2ω′, 2ω′ (double poles of "
                "℘ at the corners); ℘ is real on its edges and middle lines. The motion is the "
                "line z = x0 + t + ω′, along which ℘ runs between e3 (u = u1, lower circle) and "
                "e2 (u = u2, upper circle), one nutation period per 2ω. u℘(t) is stored on the "
                "output grid as /runs/main/reference/cos_theta_weierstrass.")],
            tables=[table])

    @classmethod
    def section_effective_potential(cls, data):
        a = data.analysis
        ep = a.get("effective_potential")
        if ep is None:
            return SectionContent(notes=["The sleeping top stays on the vertical, where "
                                         "V'(θ) is not defined: nothing to draw."])
        if ep["minus_Mgl"]:
            fig = plots.effective_potential(ep["theta"], ep["V"], energy=ep["energy"],
                                            theta1=a["theta1"], theta2=a["theta2"],
                                            ylabel="V'(θ) − Mgl [J]")
        else:
            fig = plots.effective_potential(ep["theta"], ep["V"], energy=ep["energy"],
                                            theta1=a["theta1"], theta2=a["theta2"])
        return SectionContent(figures=[cls.figure(
            "effective_potential", fig,
            "V'(θ) = Mgl cos θ + I1 (b − a cos θ)²/(2 sin²θ) (10.28) and the energy E' = "
            "E − I3ω3²/2: θ oscillates between the turning angles θ1 and θ2 where E' = V'.")])

    @classmethod
    def section_time_series(cls, data):
        run = data.runs["main"]
        a = data.analysis
        err = a["cos_theta_error"]
        relative = err["relative_to_width"]
        fig = plots.time_series(run.t, run["theta"], run.reference["theta"], run["phi_dot"],
                                err["difference"], theta1=a["theta1"], theta2=a["theta2"],
                                error_label="|Δcos θ| / (u2 − u1)" if relative
                                else "|cos θ − closed form|")
        return SectionContent(
            figures=[cls.figure("time_series", fig,
                                "θ(t) of the integrated attitude against the closed form "
                                "cos θ = u1 + (u2 − u1) sn²(λt + τ0 | k²), λ = ½√(β(u3 − u1)); "
                                "φ̇(t) = (b − a cos θ)/sin²θ (10.26); and the difference in "
                                "cos θ.")],
            facts=[("max |cos θ − closed form|", fmt_err(a["u_max_error"]))])

    @classmethod
    def section_steady_precession(cls, data):
        a = data.analysis
        sr = a["steady_rates"]
        fig = plots.steady_rates(sr["omega3"], sr["slow"], sr["fast"],
                                 omega3_min=sr["omega3_min"],
                                 omega3_config=data.analysis["omega3"],
                                 rate_config=a["phi_dot0"], rate_measured=a["mean_phi_dot"])
        table = Table(caption="Steady precession at θ0 (10.45)",
                      header=["root", "φ̇ [rad/s]"],
                      rows=[["slow  2Mgl/(I3ω3 + √D)", fmt(a["steady_rate_slow"], 14)],
                            ["fast  (I3ω3 + √D)/(2 I1 cos θ0)", fmt(a["steady_rate_fast"], 14)],
                            ["mean φ̇ of the integration", fmt(a["mean_phi_dot"], 14)]])
        return SectionContent(
            figures=[cls.figure("steady_rates", fig,
                                "The two steady precession rates φ̇ = [I3ω3 ± √(I3²ω3² − "
                                "4I1Mgl cos θ0)]/(2I1 cos θ0) (10.45) against the spin; they "
                                "exist only for I3²ω3² ≥ 4I1Mgl cos θ0 (10.46).")],
            tables=[table])

    @classmethod
    def section_sleeping_sweep(cls, data):
        sw = data.analysis.get("sleeping_sweep")
        if sw is None:
            return SectionContent(notes=["No sweep: the config has no [sleeping] table."])
        fig = plots.sleeping_sweep(sw["t"], sw["theta"], sw["omega3_over_threshold"],
                                   theta_max=sw["theta_max"])
        rows = [[fmt(float(x)), fmt(float(w)),
                 "stable" if x > 1 else ("marginal" if x == 1 else "unstable"),
                 fmt(float(g)), fmt_err(float(m))]
                for x, w, g, m in zip(sw["omega3_over_threshold"], sw["omega3"],
                                      sw["growth_rate"], sw["theta_max"], strict=True)]
        table = Table(caption=f"Tops started at a tilt of {fmt(sw['tilt'])} rad at rest "
                              f"(threshold ω3 = {fmt(data.analysis['sleeping_threshold_omega3'])}"
                              f" rad/s)",
                      header=["ω3 / threshold", "ω3 [rad/s]", "(10.50)",
                              "linear growth rate ½√(2β − a²) [1/s]", "largest tilt [rad]"],
                      rows=rows)
        return SectionContent(
            figures=[cls.figure("sleeping_sweep", fig,
                                "Below ω3² = 4I1Mgl/I3² (10.50) a small tilt grows "
                                "exponentially to order one; above it the tilt stays of the "
                                "order of its initial value.")],
            tables=[table])

    @classmethod
    def section_invariants(cls, data):
        return cls.invariants_section(
            data, labels={"energy": "energy E", "p_phi": "p_φ = L·ẑ", "p_psi": "p_ψ = I3 ω3"},
            caption="Drift of E, p_φ and p_ψ relative to their natural sizes." + (
                " The reduced equations hold p_φ and p_ψ constant by construction (only "
                "round-off shows): here the energy's drift measures the integration error."
                if data.runs["main"].attrs.get("formulation") == "reduced" else ""))
