r"""``heavy_top``: the heavy symmetric top (lecture notes §10.1, eqs. 10.21-10.50).

Integrated as a quaternion with the body angular velocity (no Euler-angle
singularity: θ = 0 is an ordinary point); θ, φ, ψ and the symmetry axis are
derived for output.  Closed form from the cubic f(u) (10.31): its roots, the
Fig. 4.3 case (loops / waves / cusps), nutation period, precession per period,
u(t) in Jacobi sn², steady precession rates (10.45-10.46) and the sleeping-top
threshold (10.49-10.50), each checked against an independent evaluation.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import AuditCase, Check, Results, RunRecord
from .base import Scene, SceneConfig, Section, SectionContent, Table, fmt, fmt_err

plots = lazy_module("reportgen.plots.heavy_top")
model_core = lazy_module("reportgen.core.models.heavy_top")
theory = lazy_module("reportgen.core.heavy_top_theory")
kinematics = lazy_module("reportgen.core.heavy_top_kinematics")
integrators = lazy_module("reportgen.core.integrators")

CASES = ("loops", "waves", "cusps", "steady", "sleeping")
ALL_KEYS = ("params.I1, params.I3, params.Mgl, initial.theta, initial.theta_dot, "
            "initial.phi_dot, initial.omega3")


class Params(Strict):
    I1: Positive = Field(description="moment of inertia about a transverse axis through the "
                                     "fixed point [kg m²]")
    I3: Positive = Field(description="moment of inertia about the symmetry axis [kg m²]")
    Mgl: Positive = Field(description="M g l: weight × distance of the centre of mass from "
                                      "the fixed point [J]")


class Initial(Strict):
    theta: Real = Field(description="tilt of the symmetry axis from the upward vertical, "
                                    "0 ≤ θ < π [rad]")
    theta_dot: Real = Field(0.0, description="θ̇0 [rad/s]")
    phi_dot: Real | None = Field(None, description="precession rate φ̇0 [rad/s] "
                                                   "(or give `steady`)")
    omega3: Real = Field(description="spin ω3 = ψ̇ + φ̇ cos θ [rad/s]")
    steady: Literal["slow", "fast"] | None = Field(
        None, description='"slow"/"fast": φ̇0 = that steady precession rate (10.45), θ̇0 = 0')


class Sleeping(Strict):
    """``[sleeping]``: sweep of ω3 across the sleeping-top threshold (10.50)."""

    tilt: Positive = Field(1e-6, description="initial tilt of every sweep run [rad]")
    omega3_over_threshold: list[Positive] = Field(
        [0.5, 0.8, 0.9, 1.1, 1.25, 2.0], min_length=1, max_length=12,
        description="spins of the sweep, in units of the threshold ω3")
    t_end: Positive | None = Field(None, description="duration of each sweep run [s] "
                                                      "(default: run.t_end)")


class HeavyTopConfig(SceneConfig):
    params: Params
    initial: Initial
    run: RunConfig
    sleeping: Sleeping | None = None
    expect_case: Literal["loops", "waves", "cusps", "steady", "sleeping"] | None = Field(
        None, description="the Fig. 4.3 case the parameters must give (presets set it)")

    @model_validator(mode="after")
    def _physics(self):
        p, ini = self.params, self.initial
        if p.I3 > 2.0 * p.I1:
            raise ValueError(f"params.I3: a symmetric body needs I3 ≤ I1 + I2 = 2 I1 "
                             f"(got I3 = {p.I3}, I1 = {p.I1})")
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
        return self


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
    sections = (
        Section("nutation_locus", "Nutation locus of the symmetry axis", integrates=True),
        Section("cubic", "The cubic f(u), its roots, nutation period and precession"),
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

    #: crossings are located reliably only with this many samples per nutation period
    MIN_SAMPLES_PER_PERIOD = 16

    # ----------------------------------------------------------------- helpers
    @property
    def phi_dot0(self) -> float:
        return _phi_dot(self.config)

    @property
    def constants(self) -> theory.TopConstants:
        p, ini = self.config.params, self.config.initial
        return theory.constants(p.I1, p.I3, p.Mgl, ini.theta, ini.theta_dot, self.phi_dot0,
                                ini.omega3)

    @property
    def roots(self) -> theory.Roots:
        return theory.roots(self.constants)

    @property
    def case(self) -> str:
        return theory.classify(self.roots, self.constants)

    @property
    def threshold(self) -> float:
        p = self.config.params
        return theory.sleeping_threshold_omega3(p.I1, p.I3, p.Mgl)

    def _invariants(self, y):
        p = self.config.params
        return model_core.invariants(y, p.I1, p.I3, p.Mgl)

    @property
    def scales(self) -> dict[str, float]:
        """Natural sizes of the invariants (drift is relative to them)."""
        p, ini = self.config.params, self.config.initial
        return theory.invariant_scales(p.I1, p.I3, p.Mgl, ini.omega3, self.constants)

    # -------------------------------------------------------------- simulation
    def models(self) -> list:
        """The top's model (the sleeping sweep integrates it with DOP853, its own choice)."""
        p = self.config.params
        return [model_core.model(p.I1, p.I3, p.Mgl)]

    def simulate(self, progress=None) -> Results:
        p, ini, run = self.config.params, self.config.initial, self.config.run
        c, r = self.constants, self.roots
        case = theory.classify(r, c)
        period = theory.nutation_period(r, c)
        precession = theory.precession_per_period(r, c)
        (model,) = self.models()
        y0 = model_core.initial_state(ini.theta, ini.theta_dot, self.phi_dot0, ini.omega3)
        t = np.linspace(0.0, run.t_end, run.samples)
        results = Results()
        raw = self.integrate(model, y0, t, invariants=lambda _t, y: self._invariants(y),
                             invariant_scales=self.scales, progress=progress,
                             n_periods=run.t_end / period if math.isfinite(period) else None)
        main, motion = self._derived_run(raw)
        results.runs["main"] = main

        slow, fast = theory.steady_precession_rates(p.I1, p.I3, p.Mgl, ini.theta, ini.omega3)
        w_cf, _u_cf = theory.u_closed_form(t, r, c)
        u_err = np.abs(motion["w"] - w_cf)
        measured_T, measured_dphi = kinematics.measure_nutation(
            t, motion, w1=r.w1, w2=r.w2, period=period,
            min_samples_per_period=self.MIN_SAMPLES_PER_PERIOD)
        a = {
            "a": c.a, "b": c.b, "alpha": c.alpha, "beta": c.beta,
            "b_over_a": c.b / c.a if c.a != 0 else math.nan,
            "u1": r.u1, "u2": r.u2, "u3": r.u3,
            "one_minus_u1": r.w2, "one_minus_u2": r.w1,
            "theta1": theory.theta_of_w(r.w1), "theta2": theory.theta_of_w(r.w2),
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
            "phi_dot0": self.phi_dot0,
            "sleeping_threshold_omega3": self.threshold,
            "sleeping_stable": bool(abs(ini.omega3) > self.threshold),
            "sleeping_growth_rate": theory.sleeping_growth_rate(p.I1, p.I3, p.Mgl, ini.omega3),
            "u_max_error": float(np.max(u_err)),
            "mean_phi_dot": float((main["phi"][-1] - main["phi"][0]) / (t[-1] - t[0])),
        }
        a["period_sensitivity"] = self._period_sensitivity(main, period)
        results.analysis.update(a)
        self._store_closed_form(results, main)
        self._checks(results, main)
        if self.config.sleeping is not None:
            # computed whenever [sleeping] is given: [report] edits re-stamp the archive
            # without simulating again, and the section must then still find it
            results.analysis["sleeping_sweep"] = self._sleeping_sweep()
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201), progress=progress)
        return results

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

    def _store_closed_form(self, results: Results, main: RunRecord) -> None:
        """Everything the report draws from the closed form, sampled here: θ(t) of the
        sn² solution on the run's grid, cos θ − closed form, f(u) near its roots, V'(θ)
        and the steady-rate curves against ω3."""
        p, ini = self.config.params, self.config.initial
        a = results.analysis
        c, r = self.constants, self.roots
        # θ(t) in closed form on the output grid, and the integration's difference in cos θ
        w_cf, _u = theory.u_closed_form(main.t, r, c)
        main.reference = {"theta": theory.theta_of_w(w_cf)}
        main.attrs["reference_label"] = ("closed form cos θ = u1 + (u2 − u1) sn²(λt + τ0 | k²), "
                                         "λ = ½√(β(u3 − u1)) (Goldstein ex. 4.10)")
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
            x = np.linspace(-1.0, hi, 1201)
            a["cubic_curve"] = {"variable": "u", "x": x, "f": theory.f_u(x, c),
                                "root1": a["u1"], "root2": a["u2"], "root3": a["u3"],
                                "ratio": a["b_over_a"], "start": math.cos(ini.theta)}
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
        w_min = theory.steady_precession_min_omega3(p.I1, p.I3, p.Mgl, ini.theta)
        lo = w_min * 1.0001 if math.isfinite(w_min) else 0.1
        om = np.linspace(lo, max(3.0 * abs(ini.omega3), 2 * lo), 400)
        slow, fast = theory.steady_precession_curve(p.I1, p.I3, p.Mgl, ini.theta, om)
        a["steady_rates"] = {"omega3": om, "slow": slow, "fast": fast, "omega3_min": w_min}

    def _period_sensitivity(self, main: RunRecord, period: float) -> float:
        """|ΔT/T| if E' were off by the run's own energy drift (conditioning of T).

        Near the sleeping top the roots close to u = 1 are set by differences of
        order θ² in E' and p_φ: there an energy error of 1e-12 shifts the measured
        period by percents, and only this estimate says how far to trust it.
        """
        p, ini = self.config.params, self.config.initial
        e = main.invariants["energy"]
        drift = max(float(np.max(np.abs(e - e[0]))), np.finfo(float).eps * self.scales["energy"])
        return theory.period_sensitivity(p.I1, p.I3, p.Mgl, ini.theta, ini.theta_dot,
                                         self.phi_dot0, ini.omega3, drift, period)

    def _checks(self, results: Results, main: RunRecord) -> None:
        a = results.analysis
        src_T = "4K(k²)/√(β(u3−u1)) (notes §10.1; Goldstein 5.72), vs ∮du/√f(u) by quadrature"
        if math.isfinite(a["nutation_period_quadrature"]):
            results.checks.append(Check("nutation period (quadrature of dt = du/√f)",
                                        a["nutation_period_quadrature"], a["nutation_period"],
                                        "s", src_T))
            results.checks.append(Check(
                "precession per period (quadrature of φ̇ dt)", a["precession_quadrature"],
                a["precession_per_period"], "rad",
                "Π(n|k²) closed form of ∮(b − a u)/(1 − u²) dt (10.26)",
                scale=max(abs(a["precession_per_period"]), 1e-300)))
        if math.isfinite(a["nutation_period_measured"]):
            results.checks.append(Check("nutation period measured from θ(t)",
                                        a["nutation_period_measured"], a["nutation_period"],
                                        "s", "4K(k²)/√(β(u3−u1))" + self._conditioning(a)))
        if math.isfinite(a["precession_measured"]):
            results.checks.append(Check("precession per period measured from φ(t)",
                                        a["precession_measured"], a["precession_per_period"],
                                        "rad", "Π(n|k²) closed form (10.26)"
                                        + self._conditioning(a),
                                        scale=max(abs(a["precession_per_period"]), 1e-300)))
        r = self.roots
        if r.w2 > r.w1 and not r.sleeping:
            w = 2.0 * (main["q_x"] ** 2 + main["q_y"] ** 2) / (
                main["q_w"] ** 2 + main["q_x"] ** 2 + main["q_y"] ** 2 + main["q_z"] ** 2)
            w_cf, _ = theory.u_closed_form(main.t[-1:], r, self.constants)
            results.checks.append(Check("cos θ(t_end)", 1.0 - float(w[-1]), 1.0 - float(w_cf[0]),
                                        "", "u1 + (u2−u1) sn²(λt + τ0 | k²) (FIELD-NOTES; "
                                        "Goldstein ex. 4.10)", scale=r.w2 - r.w1))
        if self.case == "steady":
            rate = self.phi_dot0
            results.checks.append(Check("mean φ̇ (steady precession)", a["mean_phi_dot"], rate,
                                        "rad/s", f"{self.config.initial.steady} root of (10.45)"))
        e = main.invariants["energy"]
        results.checks.append(Check("energy E(t_end)", float(e[-1]), float(e[0]), "J",
                                    "E(0), conserved", scale=self.scales["energy"]))

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
        model = model_core.model(p.I1, p.I3, p.Mgl)
        thetas, status = [], []
        for ratio in ratios:
            y0 = model_core.initial_state(sl.tilt, 0.0, 0.0, ratio * self.threshold)
            sol = integrators.integrate(model, y0, t, method="dop853", rtol=run.rtol, atol=run.atol)
            thetas.append(kinematics.tilt_angle(sol.y[:, :4]))
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
        if a["case"] != "steady" and data.config.initial.steady is None:
            names.remove("steady_precession")
        if "sleeping_sweep" not in a:
            names.remove("sleeping_sweep")
        if a["case"] == "sleeping":
            names.remove("effective_potential")  # V'(θ) is flat-infinite at θ = 0 with b = a
        return names

    @classmethod
    def headline(cls, data):
        p, ini = data.config.params, data.config.initial
        a = data.analysis
        facts = [
            ("parameters", f"I1 = {fmt(p.I1)} kg m², I3 = {fmt(p.I3)} kg m², "
                           f"M g l = {fmt(p.Mgl)} J"),
            ("initial state", f"θ0 = {fmt(ini.theta)} rad, θ̇0 = {fmt(ini.theta_dot)} rad/s, "
                              f"φ̇0 = {fmt(a['phi_dot0'])} rad/s, ω3 = {fmt(ini.omega3)} rad/s"),
            ("case", f"{a['case']} (a = {fmt(a['a'])}, b = {fmt(a['b'])}, "
                     f"b/a = {fmt(a['b_over_a'])}; u1 = {fmt(a['u1'])}, u2 = {fmt(a['u2'])})"),
        ]
        if math.isfinite(a["nutation_period"]):
            extra = " (small-oscillation limit, k² = 0)" if a["case"] in ("steady",
                                                                          "sleeping") else ""
            facts.append(("nutation period", f"{fmt(a['nutation_period'], 14)} s{extra}"))
        if math.isfinite(a["precession_per_period"]):
            facts.append(("precession per nutation period",
                          f"{fmt(a['precession_per_period'], 14)} rad"))
        facts.append(("sleeping-top threshold", f"ω3 = 2√(I1 M g l)/I3 = "
                      f"{fmt(a['sleeping_threshold_omega3'])} rad/s (10.50)"))
        return facts

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
                                "θ(t) integrated (quaternion attitude) against the closed form "
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
                                 omega3_config=data.config.initial.omega3,
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
            caption="Drift of E, p_φ and p_ψ relative to their natural sizes.")
