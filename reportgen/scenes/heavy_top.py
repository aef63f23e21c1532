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
from ..core.crossings import mean_period, upward_crossings
from ..core.models import heavy_top as core
from ..plots import heavy_top as plots
from ..results import Check, Results, RunRecord
from .base import Scene, SceneConfig, Section, SectionContent, Table, fmt, fmt_err
from .shared import error_vs_runtime_section, invariants_section

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
            slow, fast = core.steady_precession_rates(p.I1, p.I3, p.Mgl, ini.theta, ini.omega3)
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
        c = core.constants(p.I1, p.I3, p.Mgl, ini.theta, ini.theta_dot, phi_dot, ini.omega3)
        r = core.roots(c)
        try:
            core.check_admissible(r, c)
        except core.NoAdmissibleInterval as exc:
            raise ValueError(f"{ALL_KEYS}: {exc}") from None
        if self.expect_case is not None:
            case = core.classify(r, c)
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
    slow, fast = core.steady_precession_rates(p.I1, p.I3, p.Mgl, ini.theta, ini.omega3)
    return slow if ini.steady == "slow" else fast


_TOP = {"I1": 1.0, "I3": 0.5, "Mgl": 1.0}


def _preset(initial, t_end, samples, case=None, **extra):
    out = {"params": dict(_TOP), "initial": initial, "run": {"t_end": t_end, "samples": samples}}
    if case is not None:
        out["expect_case"] = case
    return out | extra


class HeavyTopScene(Scene):
    kind = "heavy_top"
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
        from ..audit import AuditCase

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

    def default_sections(self):
        names = [s.name for s in self.sections]
        if self.case != "steady" and self.config.initial.steady is None:
            names.remove("steady_precession")
        if self.config.sleeping is None:
            names.remove("sleeping_sweep")
        if self.case == "sleeping":
            names.remove("effective_potential")  # V'(θ) is flat-infinite at θ = 0 with b = a
        return names

    # ----------------------------------------------------------------- helpers
    @property
    def phi_dot0(self) -> float:
        return _phi_dot(self.config)

    @property
    def constants(self) -> core.TopConstants:
        p, ini = self.config.params, self.config.initial
        return core.constants(p.I1, p.I3, p.Mgl, ini.theta, ini.theta_dot, self.phi_dot0,
                              ini.omega3)

    @property
    def roots(self) -> core.Roots:
        return core.roots(self.constants)

    @property
    def case(self) -> str:
        return core.classify(self.roots, self.constants)

    @property
    def threshold(self) -> float:
        p = self.config.params
        return core.sleeping_threshold_omega3(p.I1, p.I3, p.Mgl)

    def _invariants(self, y):
        p = self.config.params
        return core.invariants(y, p.I1, p.I3, p.Mgl)

    @property
    def scales(self) -> dict[str, float]:
        """Natural sizes of the invariants (drift is relative to them)."""
        p, ini = self.config.params, self.config.initial
        spin = 0.5 * p.I3 * ini.omega3**2
        c = self.constants
        energy = max(abs(0.5 * p.I1 * c.alpha) + spin, p.Mgl)
        momentum = max(abs(p.I3 * ini.omega3), abs(p.I1 * c.b), math.sqrt(p.I1 * p.Mgl))
        return {"energy": energy, "p_phi": momentum, "p_psi": momentum}

    # -------------------------------------------------------------- simulation
    def simulate(self, progress=None) -> Results:
        p, ini, run = self.config.params, self.config.initial, self.config.run
        c, r = self.constants, self.roots
        case = core.classify(r, c)
        period = core.nutation_period(r, c)
        precession = core.precession_per_period(r, c)
        model = core.model(p.I1, p.I3, p.Mgl)
        y0 = core.initial_state(ini.theta, ini.theta_dot, self.phi_dot0, ini.omega3)
        t = np.linspace(0.0, run.t_end, run.samples)
        results = Results()
        raw = self.integrate(model, y0, t, invariants=lambda _t, y: self._invariants(y),
                             invariant_scales=self.scales, progress=progress,
                             n_periods=run.t_end / period if math.isfinite(period) else None)
        main, kin = self._derived_run(raw)
        results.runs["main"] = main

        slow, fast = core.steady_precession_rates(p.I1, p.I3, p.Mgl, ini.theta, ini.omega3)
        w_cf, _u_cf = core.u_closed_form(t, r, c)
        u_err = np.abs(kin["w"] - w_cf)
        measured_T, measured_dphi = self._measured(t, kin, r)
        a = {
            "a": c.a, "b": c.b, "alpha": c.alpha, "beta": c.beta,
            "b_over_a": c.b / c.a if c.a != 0 else math.nan,
            "u1": r.u1, "u2": r.u2, "u3": r.u3,
            "one_minus_u1": r.w2, "one_minus_u2": r.w1,
            "theta1": _theta_of_w(r.w1), "theta2": _theta_of_w(r.w2),
            "k2": r.m if r.w2 > r.w3 else math.nan,
            "case": case,
            "nutation_period": period,
            "nutation_period_quadrature": core.nutation_period_quadrature(r, c),
            "nutation_period_measured": measured_T,
            "precession_per_period": precession,
            "precession_quadrature": core.precession_quadrature(r, c),
            "precession_measured": measured_dphi,
            "reduced_energy": 0.5 * p.I1 * c.alpha,
            "steady_rate_slow": slow, "steady_rate_fast": fast,
            "steady_exists": bool(math.isfinite(slow)),
            "phi_dot0": self.phi_dot0,
            "sleeping_threshold_omega3": self.threshold,
            "sleeping_stable": bool(abs(ini.omega3) > self.threshold),
            "sleeping_growth_rate": core.sleeping_growth_rate(p.I1, p.I3, p.Mgl, ini.omega3),
            "u_max_error": float(np.max(u_err)),
            "mean_phi_dot": float((main["phi"][-1] - main["phi"][0]) / (t[-1] - t[0])),
        }
        a["period_sensitivity"] = self._period_sensitivity(main, period)
        results.analysis.update(a)
        self._checks(results, main)
        if self.config.sleeping is not None and "sleeping_sweep" in [
                s.name for s in self.chosen_sections()]:
            results.analysis["sleeping_sweep"] = self._sleeping_sweep()
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201), progress=progress)
        return results

    def _derived_run(self, raw: RunRecord) -> tuple[RunRecord, dict]:
        """The archived run: Euler angles, axis, rates and the integrated state."""
        p = self.config.params
        y = raw.y
        q = y[:, :4] / np.linalg.norm(y[:, :4], axis=1)[:, None]
        theta, phi, psi = core.euler_angles(q)
        e3, e3_dot, e3_ddot = core.axis_kinematics(y, p.I1, p.I3, p.Mgl)
        rho = np.hypot(e3[:, 0], e3[:, 1])
        on_axis = rho == 0.0  # exactly vertical: φ undefined, rates stored as 0
        safe = np.where(on_axis, 1.0, rho)
        rho_dot = np.where(on_axis, 0.0, (e3[:, 0] * e3_dot[:, 0] + e3[:, 1] * e3_dot[:, 1]) / safe)
        theta_dot = rho_dot * e3[:, 2] - e3_dot[:, 2] * rho
        phi_dot = np.where(on_axis, 0.0,
                           (e3[:, 0] * e3_dot[:, 1] - e3[:, 1] * e3_dot[:, 0]) / safe**2)
        columns = ["theta", "phi", "psi", "axis_x", "axis_y", "axis_z", "theta_dot", "phi_dot",
                   *core.COLUMNS]
        data = np.column_stack([theta, phi, psi, e3, theta_dot, phi_dot, y])
        w = 2.0 * (q[:, 1] ** 2 + q[:, 2] ** 2)  # 1 − cos θ without cancellation
        kin = {"w": w, "w_dot": -e3_dot[:, 2], "w_ddot": -e3_ddot[:, 2], "phi": phi,
               "phi_dot": phi_dot}
        return RunRecord(t=raw.t, y=data, columns=columns, invariants=raw.invariants,
                         attrs=raw.attrs), kin

    def _period_sensitivity(self, main: RunRecord, period: float) -> float:
        """|ΔT/T| if E' were off by the run's own energy drift (conditioning of T).

        Near the sleeping top the roots close to u = 1 are set by differences of
        order θ² in E' and p_φ: there an energy error of 1e-12 shifts the measured
        period by percents, and only this estimate says how far to trust it.
        """
        p, ini = self.config.params, self.config.initial
        e = main.invariants["energy"]
        drift = max(float(np.max(np.abs(e - e[0]))), np.finfo(float).eps * self.scales["energy"])
        theta_dot = math.sqrt(ini.theta_dot**2 + 2.0 * drift / p.I1)
        c = core.constants(p.I1, p.I3, p.Mgl, ini.theta, theta_dot, self.phi_dot0, ini.omega3)
        try:
            perturbed = core.nutation_period(core.roots(c), c)
        except (ValueError, ArithmeticError):
            return math.nan
        return abs(perturbed / period - 1.0) if math.isfinite(period) else math.nan

    #: crossings are located reliably only with this many samples per nutation period
    MIN_SAMPLES_PER_PERIOD = 16

    def _measured(self, t, kin, r: core.Roots) -> tuple[float, float]:
        """Nutation period and precession per period measured from the trajectory.

        Upward crossings of w = 1 − cos θ through the middle of [w1, w2] (quintic
        Hermite, ``core/crossings.py``); φ at those times by cubic Hermite
        interpolation of the stored φ, φ̇.  NaN without nutation or with too few samples.
        """
        if r.sleeping or r.w2 - r.w1 <= core.STEADY_RTOL * r.w2:
            return math.nan, math.nan
        period = core.nutation_period(r, core.constants(  # for the sampling check only
            self.config.params.I1, self.config.params.I3, self.config.params.Mgl,
            self.config.initial.theta, self.config.initial.theta_dot, self.phi_dot0,
            self.config.initial.omega3))
        if not math.isfinite(period) or (t[-1] / period) * self.MIN_SAMPLES_PER_PERIOD > len(t):
            return math.nan, math.nan
        level = 0.5 * (r.w1 + r.w2)
        times = upward_crossings(t, kin["w"], kin["w_dot"], kin["w_ddot"], level=level)
        T = mean_period(times)
        if times.size < 2:
            return T, math.nan
        phis = _hermite(t, kin["phi"], kin["phi_dot"], times)
        return T, float((phis[-1] - phis[0]) / (times.size - 1))

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
            w_cf, _ = core.u_closed_form(main.t[-1:], r, self.constants)
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
        from ..core.integrators import integrate

        p, sl, run = self.config.params, self.config.sleeping, self.config.run
        t_end = sl.t_end or run.t_end
        t = np.linspace(0.0, t_end, 1001)
        ratios = np.array(sorted(sl.omega3_over_threshold), dtype=float)
        model = core.model(p.I1, p.I3, p.Mgl)
        thetas, status = [], []
        for ratio in ratios:
            y0 = core.initial_state(sl.tilt, 0.0, 0.0, ratio * self.threshold)
            sol = integrate(model, y0, t, method="dop853", rtol=run.rtol, atol=run.atol)
            q = sol.y[:, :4]
            thetas.append(2.0 * np.arctan2(np.hypot(q[:, 1], q[:, 2]), np.hypot(q[:, 0], q[:, 3])))
            status.append(sol.status)
        thetas = np.array(thetas)
        return {
            "t": t, "omega3_over_threshold": ratios, "omega3": ratios * self.threshold,
            "theta": thetas, "theta_max": thetas.max(axis=1), "tilt": sl.tilt,
            "growth_rate": np.array([core.sleeping_growth_rate(p.I1, p.I3, p.Mgl,
                                                               x * self.threshold)
                                     for x in ratios]),
            "status": [str(s) for s in status],
        }

    # ----------------------------------------------------------------- report
    def headline(self, data):
        p, ini = self.config.params, self.config.initial
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

    def section_nutation_locus(self, data):
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
            figures=[self.figure("nutation_locus", fig,
                                 f"Path of the symmetry axis; dashed: the turning circles "
                                 f"θ1 = arccos u2 and θ2 = arccos u1. Case: {label}.")],
            facts=[("case", a["case"]), ("θ1, θ2", f"{fmt(a['theta1'])} rad, "
                                                   f"{fmt(a['theta2'])} rad")])

    def section_cubic(self, data):
        a = data.analysis
        c = self.constants
        w1, w2 = a["one_minus_u2"], a["one_minus_u1"]
        if 0.0 < w2 < 1e-3:
            # near the vertical the interval is invisible on [−1, 1]: plot against w = 1 − u
            w = np.linspace(0.0, 1.25 * w2, 1201)
            w3 = 1.0 - a["u3"]
            fig = plots.cubic(w, core.g_w(w, c), u1=w1, u2=w2, u3=w3,
                              b_over_a=-c.B / c.a if c.a else math.nan, u0=c.w0,
                              xlabel="1 − u = 1 − cos θ  (near the vertical)",
                              names=("1 − u2", "1 − u1", "1 − u3"), ratio_label="1 − b/a")
        else:
            hi = min(max(1.05, a["u3"] + 0.1 * (a["u3"] - a["u1"])), 3.0) if math.isfinite(
                a["u3"]) else 1.5
            u = np.linspace(-1.0, hi, 1201)
            fig = plots.cubic(u, core.f_u(u, c), u1=a["u1"], u2=a["u2"], u3=a["u3"],
                              b_over_a=a["b_over_a"], u0=math.cos(self.config.initial.theta))
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
                         f"or stores fewer than {self.MIN_SAMPLES_PER_PERIOD} samples per "
                         f"period.")
        facts = [("sensitivity of T to an energy error of the run's drift",
                  fmt_err(sens))] if math.isfinite(sens) else []
        return SectionContent(
            facts=facts,
            figures=[self.figure("f_of_u", fig, "f(u) = (1 − u²)(α − βu) − (b − au)² (10.31): "
                                 "the motion is confined to u1 ≤ u ≤ u2 where f ≥ 0; "
                                 "u3 > 1 is unphysical. Dashed: b/a, where φ̇ = 0.")],
            tables=[table, table2], notes=notes)

    def section_effective_potential(self, data):
        a = data.analysis
        p = self.config.params
        c = self.constants
        if a["theta2"] < 0.05:
            # near the vertical V' − Mgl is of order θ²: evaluate it in w = 1 − cos θ
            theta = np.linspace(0.5 * a["theta1"], 1.5 * a["theta2"], 1500)
            w = 2.0 * np.sin(0.5 * theta) ** 2
            V = -p.Mgl * w + 0.5 * p.I1 * (c.B + c.a * w) ** 2 / (w * (2.0 - w))
            fig = plots.effective_potential(theta, V, energy=0.5 * p.I1 * c.A,
                                            theta1=a["theta1"], theta2=a["theta2"],
                                            ylabel="V'(θ) − Mgl [J]")
        else:
            theta = np.linspace(1e-3, math.pi - 1e-3, 1500)
            V = core.effective_potential(theta, p.I1, p.Mgl, c)
            fig = plots.effective_potential(theta, V, energy=a["reduced_energy"],
                                            theta1=a["theta1"], theta2=a["theta2"])
        return SectionContent(figures=[self.figure(
            "effective_potential", fig,
            "V'(θ) = Mgl cos θ + I1 (b − a cos θ)²/(2 sin²θ) (10.28) and the energy E' = "
            "E − I3ω3²/2: θ oscillates between the turning angles θ1 and θ2 where E' = V'.")])

    def section_time_series(self, data):
        run = data.runs["main"]
        a = data.analysis
        w_cf, _u = core.u_closed_form(run.t, self.roots, self.constants)
        theta_cf = 2.0 * np.arcsin(np.sqrt(np.clip(0.5 * w_cf, 0.0, 1.0)))
        q = np.column_stack([run["q_w"], run["q_x"], run["q_y"], run["q_z"]])
        w = 2.0 * (q[:, 1] ** 2 + q[:, 2] ** 2) / np.sum(q**2, axis=1)
        width = a["one_minus_u1"] - a["one_minus_u2"]
        relative = width > 0.0
        fig = plots.time_series(run.t, run["theta"], theta_cf, run["phi_dot"],
                                (w - w_cf) / width if relative else w - w_cf,
                                theta1=a["theta1"], theta2=a["theta2"],
                                error_label="|Δcos θ| / (u2 − u1)" if relative
                                else "|cos θ − closed form|")
        return SectionContent(
            figures=[self.figure("time_series", fig,
                                 "θ(t) integrated (quaternion attitude) against the closed form "
                                 "cos θ = u1 + (u2 − u1) sn²(λt + τ0 | k²), λ = ½√(β(u3 − u1)); "
                                 "φ̇(t) = (b − a cos θ)/sin²θ (10.26); and the difference in "
                                 "cos θ.")],
            facts=[("max |cos θ − closed form|", fmt_err(a["u_max_error"]))])

    def section_steady_precession(self, data):
        a = data.analysis
        p, ini = self.config.params, self.config.initial
        cos = math.cos(ini.theta)
        w_min = 2.0 * math.sqrt(p.I1 * p.Mgl * cos) / p.I3 if cos > 0 else math.nan
        lo = w_min * 1.0001 if math.isfinite(w_min) else 0.1
        om = np.linspace(lo, max(3.0 * abs(ini.omega3), 2 * lo), 400)
        rates = np.array([core.steady_precession_rates(p.I1, p.I3, p.Mgl, ini.theta, x)
                          for x in om])
        fig = plots.steady_rates(om, rates[:, 0], rates[:, 1], omega3_min=w_min,
                                 omega3_config=ini.omega3, rate_config=a["phi_dot0"],
                                 rate_measured=a["mean_phi_dot"])
        table = Table(caption="Steady precession at θ0 (10.45)",
                      header=["root", "φ̇ [rad/s]"],
                      rows=[["slow  2Mgl/(I3ω3 + √D)", fmt(a["steady_rate_slow"], 14)],
                            ["fast  (I3ω3 + √D)/(2 I1 cos θ0)", fmt(a["steady_rate_fast"], 14)],
                            ["mean φ̇ of the integration", fmt(a["mean_phi_dot"], 14)]])
        return SectionContent(
            figures=[self.figure("steady_rates", fig,
                                 "The two steady precession rates φ̇ = [I3ω3 ± √(I3²ω3² − "
                                 "4I1Mgl cos θ0)]/(2I1 cos θ0) (10.45) against the spin; they "
                                 "exist only for I3²ω3² ≥ 4I1Mgl cos θ0 (10.46).")],
            tables=[table])

    def section_sleeping_sweep(self, data):
        sw = data.analysis["sleeping_sweep"]
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
            figures=[self.figure("sleeping_sweep", fig,
                                 "Below ω3² = 4I1Mgl/I3² (10.50) a small tilt grows "
                                 "exponentially to order one; above it the tilt stays of the "
                                 "order of its initial value.")],
            tables=[table])

    def section_invariants(self, data):
        return invariants_section(
            self, data, scales=self.scales,
            labels={"energy": "energy E", "p_phi": "p_φ = L·ẑ", "p_psi": "p_ψ = I3 ω3"},
            caption="Drift of E, p_φ and p_ψ relative to their natural sizes.")

    def section_error_vs_runtime(self, data):
        return error_vs_runtime_section(self, data)


def _theta_of_w(w: float) -> float:
    """θ = 2 arcsin √(w/2) for w = 1 − cos θ (accurate near the vertical)."""
    return 2.0 * math.asin(math.sqrt(min(1.0, max(0.0, 0.5 * w))))


def _hermite(t, x, xdot, times):
    """Cubic Hermite interpolation of x(t) with slopes xdot at ``times``."""
    idx = np.clip(np.searchsorted(t, times) - 1, 0, len(t) - 2)
    h = t[idx + 1] - t[idx]
    s = (times - t[idx]) / h
    h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
    h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
    return h00 * x[idx] + h10 * h * xdot[idx] + h01 * x[idx + 1] + h11 * h * xdot[idx + 1]

