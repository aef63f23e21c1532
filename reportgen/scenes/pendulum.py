r"""``pendulum``: the nonlinear plane pendulum and its small-angle limit (lecture notes §1–2).

m l^2 θ'' + m g l sin θ = 0.  Exact solution in Jacobi elliptic functions, exact
period 4 K(k) sqrt(l/g) with k = sin(θ0/2), the phase portrait with its
separatrix, and the boundary-value problem θ(0) = θ0, θ(T) = θ1 of the
linearised equation (1.21) with its action (2.4).
"""

from __future__ import annotations

import math

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import AuditCase, Check, Results
from .base import (
    Scene,
    SceneConfig,
    Section,
    SectionContent,
    Table,
    fmt,
    fmt_err,
    member_text,
)

common_plots = lazy_module("reportgen.plots.common")
plots = lazy_module("reportgen.plots.pendulum")
core = lazy_module("reportgen.core.models.pendulum")
theory = lazy_module("reportgen.core.pendulum_theory")  # no numerics: validation uses it


class Params(Strict):
    g: Positive = Field(description="gravitational acceleration [m/s^2]")
    l: Positive = Field(description="length of the pendulum [m]")
    m: Positive = Field(1.0, description="bob mass [kg]")


class Initial(Strict):
    theta: Real = Field(description="initial angle from the downward vertical [rad]")
    theta_dot: Real = Field(0.0, description="initial angular velocity [rad/s]")


class Boundary(Strict):
    """``[boundary]``: the linearised boundary-value problem (1.21)."""

    theta0: Real = Field(description="θ(0) [rad]")
    theta1: Real = Field(description="θ(T) [rad]")
    T: Positive = Field(description="end time of the boundary-value problem [s]")


class PendulumConfig(SceneConfig):
    params: Params
    initial: Initial
    run: RunConfig
    boundary: Boundary | None = None

    @model_validator(mode="after")
    def _physics(self):
        omega0 = math.sqrt(self.params.g / self.params.l)
        m1 = theory.complementary_parameter(self.initial.theta, self.initial.theta_dot, omega0)
        if m1 == 0.0:
            raise ValueError(
                "initial.theta / initial.theta_dot: the state lies exactly on the separatrix "
                "(k = 1, infinite period)"
            )
        if self.boundary is not None:
            s = math.sin(omega0 * self.boundary.T)
            if abs(s) < 1e-8:
                raise ValueError(
                    f"boundary.T: T = {self.boundary.T} is a multiple of π/ω0 = "
                    f"{math.pi / omega0:.6g} s (a conjugate point: the linear boundary-value "
                    "problem has no unique solution)"
                )
        return self


class PendulumScene(Scene):
    kind = "pendulum"
    order = 10
    summary = "nonlinear plane pendulum m l² θ'' + m g l sin θ = 0 and its small-angle limit"
    Config = PendulumConfig
    presets = {
        "small_angle": {"params": {"g": 9.81, "l": 1.0}, "initial": {"theta": 0.1},
                        "run": {"t_end": 20.0}},
        "large_amplitude": {"params": {"g": 9.81, "l": 1.0}, "initial": {"theta": 2.5},
                            "run": {"t_end": 30.0}},
        "near_separatrix": {"params": {"g": 9.81, "l": 1.0},
                            "initial": {"theta": math.pi - 1e-3}, "run": {"t_end": 40.0}},
        "rotation": {"params": {"g": 9.81, "l": 1.0},
                     "initial": {"theta": 0.0, "theta_dot": 7.0}, "run": {"t_end": 10.0}},
    }
    sections = (
        Section("time_series", "Angle against time", integrates=True),
        Section("phase_portrait", "Phase portrait", integrates=True),
        Section("period", "Period against amplitude"),
        Section("boundary_value", "Boundary-value problem and its action"),
        Section("energy", "Energy conservation", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    family_sections = (
        Section("period_family", "Period against amplitude across the family",
                description="Each member's period, integrated, against the exact period."),
    )
    #: swept keys the compiled ensemble covers (members released from rest)
    ENSEMBLE_KEYS = frozenset({"initial.theta", "params.g", "params.l", "params.m"})

    #: crossings are located reliably only with this many samples per period
    MIN_SAMPLES_PER_PERIOD = 16
    #: phase-portrait grid: points per axis
    PHASE_GRID = 400
    #: period-curve samples over 0 < θ0 < π
    PERIOD_CURVE_POINTS = 500

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        if "boundary_value" not in data.analysis:
            names.remove("boundary_value")
        return names

    @classmethod
    def audit_cases(cls):
        w0 = math.sqrt(9.81)
        base = {"kind": "pendulum", "params": {"g": 9.81, "l": 1.0}}

        def case(name, initial, t_end, what, methods=("dop853", "yoshida6", "gauss6")):
            config = {**base, "title": name, "initial": initial,
                      "run": {"t_end": t_end, "samples": 2001}}
            return AuditCase(name=name, config=config, what=what, methods=methods)

        return [
            case("pendulum released at π − 1e-8", {"theta": math.pi - 1e-8}, 60.0,
                 "lingers ~20 s at the unstable equilibrium; errors grow like e^(ω0 t) there"),
            case("pendulum just below the separatrix",
                 {"theta": 0.0, "theta_dot": 2 * w0 * math.sqrt(1 - 1e-10)}, 40.0,
                 "k² = 1 − 1e-10: libration with a period of ~15 s"),
            case("pendulum just above the separatrix",
                 {"theta": 0.0, "theta_dot": 2 * w0 * math.sqrt(1 + 1e-10)}, 40.0,
                 "k² = 1 + 1e-10: a slow rotation"),
            AuditCase(name="pendulum over 10⁴ periods", what="long run: a non-symplectic "
                      "energy error grows linearly, a phase error in any method",
                      methods=("dop853", "yoshida6"),
                      config={**base, "title": "pendulum over 10⁴ periods",
                              "initial": {"theta": 1.0},
                              "run": {"t_end": 2.1e4, "samples": 200001}}),
        ]

    # ----------------------------------------------------------------- helpers
    @property
    def omega0(self) -> float:
        return math.sqrt(self.config.params.g / self.config.params.l)

    @property
    def k2(self) -> float:
        ini = self.config.initial
        return theory.modulus_squared(ini.theta, ini.theta_dot, self.omega0)

    @property
    def m1(self) -> float:
        """1 − k², accurate near the separatrix."""
        ini = self.config.initial
        return theory.complementary_parameter(ini.theta, ini.theta_dot, self.omega0)

    @property
    def motion(self) -> str:
        return "libration" if self.m1 > 0.0 else "rotation"

    @property
    def has_exact_solution(self) -> bool:
        return abs(self.m1) >= theory.EXACT_SOLUTION_MIN_M1

    @property
    def reference_label(self) -> str:
        if self.has_exact_solution:
            return "exact (Jacobi sn)"
        return "reference run (DOP853, rtol 1e-14)"

    def reference_solution(self, t):
        """θ(t), θ̇(t): the elliptic-function solution, or — closer to the separatrix than
        double precision resolves it — the reference run at rtol 1e-14 (said so in the report)."""
        p, ini = self.config.params, self.config.initial
        if self.has_exact_solution:
            return core.exact_solution(t, ini.theta, ini.theta_dot, p.g, p.l)
        y = self.reference_run(core.model(p.g, p.l), np.array([ini.theta, ini.theta_dot]),
                               np.asarray(t, dtype=np.float64))
        return y[:, 0], y[:, 1]

    def energy(self, theta, theta_dot):
        p = self.config.params
        return core.energy(theta, theta_dot, p.g, p.l, p.m)

    @property
    def energy_scale(self) -> float:
        p = self.config.params
        return p.m * p.g * p.l

    # -------------------------------------------------------------- simulation
    def models(self) -> list:
        return [core.model(self.config.params.g, self.config.params.l)]

    def simulate(self, progress=None) -> Results:
        p, ini, run = self.config.params, self.config.initial, self.config.run
        (model,) = self.models()
        y0 = np.array([ini.theta, ini.theta_dot])
        t = np.linspace(0.0, run.t_end, run.samples)
        period = core.exact_period(ini.theta, ini.theta_dot, p.g, p.l)
        results = Results()
        main = self.integrate(
            model, y0, t,
            invariants=lambda t, y: {"energy": self.energy(y[:, 0], y[:, 1])},
            invariant_scales={"energy": self.energy_scale},
            progress=progress, n_periods=run.t_end / period,
        )
        results.runs["main"] = main
        theta, theta_dot = main.y[:, 0], main.y[:, 1]
        exact_theta, exact_theta_dot = self.reference_solution(t)
        main.reference = {"theta": exact_theta, "theta_dot": exact_theta_dot}
        main.attrs["reference_label"] = self.reference_label
        err = np.abs(theta - exact_theta)

        measured = core.measured_period(t, theta, theta_dot, ini.theta, ini.theta_dot, p.g, p.l,
                                        min_samples_per_period=self.MIN_SAMPLES_PER_PERIOD)
        results.analysis.update({
            "period": period,
            "period_measured": measured,
            "period_small_angle": 2 * math.pi / self.omega0,
            "omega0": self.omega0,
            "k": math.sqrt(self.k2),
            "motion": self.motion,
            "complementary_parameter": self.m1,
            "reference": self.reference_label,
            "theta_max_error": float(np.max(err)),
            "theta_dot_max_error": float(np.max(np.abs(theta_dot - exact_theta_dot))),
        })
        if self.m1 > 0:
            # the linearised solution (1.19), drawn against the run; meaningless for rotation
            th_lin, thd_lin = core.small_angle_solution(t, ini.theta, ini.theta_dot, p.g, p.l)
            results.analysis["small_angle_solution"] = {"theta": th_lin, "theta_dot": thd_lin}
            results.analysis["amplitude"] = core.libration_amplitude(ini.theta, ini.theta_dot,
                                                                     self.omega0)
        results.analysis["phase_portrait"] = self._phase_portrait(theta_dot)
        amp = np.linspace(1e-3, math.pi - 1e-3, self.PERIOD_CURVE_POINTS)
        results.analysis["period_curve"] = {"amplitude": amp,
                                            "period": core.libration_period(amp, self.omega0)}
        if math.isfinite(measured):
            results.checks.append(Check("period (measured from θ(t))", measured, period, "s",
                                        "4K(k)·√(l/g), DLMF 22.19.4" if self.m1 > 0
                                        else "2K(1/k²)/(k ω0), DLMF 22.19.7"))
        results.checks.append(Check("θ(t_end)", float(theta[-1]), float(exact_theta[-1]), "rad",
                                    "Jacobi sn solution, DLMF 22.19.2" if self.has_exact_solution
                                    else self.reference_label, scale=math.pi))
        e = main.invariants["energy"]
        results.checks.append(Check("energy E(t_end)", float(e[-1]), float(e[0]), "J",
                                    "E(0), conserved", scale=self.energy_scale))
        b = self.config.boundary
        if b is not None:
            bvp = core.boundary_value_problem(b.theta0, b.theta1, b.T, p.g, p.l, p.m)
            results.analysis["boundary_value"] = bvp
            results.checks.append(Check("action S of the linear BVP (numerical quadrature)",
                                        bvp["action_numeric"], bvp["action_exact"], "J·s",
                                        "closed form (2.4) on solution (1.21)"))
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201),
                   reference=(lambda ts: np.column_stack(self.reference_solution(ts)))
                   if self.has_exact_solution else None)
        return results

    # ------------------------------------------------------------------ sweeps
    def sweep_block(self, lo, hi, values):
        """Members released from rest run as one compiled ensemble
        (:func:`reportgen.core.ensemble.pendulum_periods`): each member's period is the
        time between its first two upward crossings of θ = 0, against the exact
        4K(k)√(l/g).  Other sweeps run member by member."""
        p, ini, run = self.config.params, self.config.initial, self.config.run
        if not self._ensemble_sweep():
            return super().sweep_block(lo, hi, values)
        from ..core import ensemble
        from ..sweep import SweepBlock

        n = hi - lo
        theta = values.get("initial.theta", np.full(n, ini.theta))
        g = values.get("params.g", np.full(n, p.g))
        l = values.get("params.l", np.full(n, p.l))
        amplitude = np.abs(theta)
        measured, codes = ensemble.pendulum_periods(amplitude, g, l, rtol=run.rtol,
                                                    atol=run.atol)
        omega0 = np.sqrt(g / l)
        with np.errstate(invalid="ignore"):  # amplitudes >= π (no libration): NaN
            exact = np.where(amplitude < math.pi, core.libration_period(
                np.minimum(amplitude, math.pi), omega0), np.nan)
        status = np.array([ensemble.STATUS_NAMES.get(int(c), f"status {int(c)}")
                           for c in codes], dtype=object)
        return SweepBlock(analysis={
            "period_measured": measured, "period": exact,
            "period_relative_error": np.abs(measured - exact) / exact,
            "period_small_angle": 2 * math.pi / omega0}, status=status)

    def sweep_warm_up(self) -> None:
        """One member through the compiled ensemble (compiles it on an empty cache)."""
        if self._ensemble_sweep():
            from ..core import ensemble

            ensemble.pendulum_periods(np.array([0.5]), 1.0, 1.0, rtol=self.config.run.rtol,
                                      atol=self.config.run.atol)

    def _ensemble_sweep(self) -> bool:
        """Whether this sweep's members run as one compiled ensemble."""
        return (self.sweep is not None and set(self.sweep.paths) <= self.ENSEMBLE_KEYS
                and self.config.initial.theta_dot == 0.0)

    def sweep_min_block(self) -> int:
        return 1024 if self._ensemble_sweep() else 1

    def sweep_extras(self, sweep) -> dict:
        """The exact period curve over the swept amplitudes (g and l not swept)."""
        theta = sweep.values.get("initial.theta")
        if theta is None or {"params.g", "params.l"} & set(sweep.values):
            return {}
        amp = np.abs(theta[np.abs(theta) < math.pi])
        if amp.size == 0:
            return {}
        grid = np.linspace(amp.min(), amp.max(), self.PERIOD_CURVE_POINTS)
        return {"period_curve": {"amplitude": grid,
                                 "period": core.libration_period(grid, self.omega0)}}

    def sweep_checks(self, sweep) -> list[Check]:
        """The member whose integrated period is furthest from 4K(k)√(l/g)."""
        a = sweep.analysis
        if "period_measured" not in a:
            return []
        rel = np.where(sweep.ok, np.abs(a["period_measured"] / a["period"] - 1), np.nan)
        if not np.any(np.isfinite(rel)):
            return []
        i = int(np.nanargmax(rel))
        return [Check(f"period of the worst member ({member_text(sweep, i)})",
                      float(a["period_measured"][i]),
                      float(a["period"][i]), "s", "4K(k)·√(l/g), DLMF 22.19.4")]

    def _phase_portrait(self, theta_dot) -> dict:
        """Level sets of E/(m l²) over θ ∈ [−π, π] and |θ̇| ≤ vmax (wide enough for the orbit):
        librations below the separatrix, rotations above it."""
        w = self.omega0
        vmax = max(2.6 * w, 1.15 * float(np.max(np.abs(theta_dot))))
        th = np.linspace(-math.pi, math.pi, self.PHASE_GRID)
        thd = np.linspace(-vmax, vmax, self.PHASE_GRID)
        TH, THD = np.meshgrid(th, thd)
        sep = core.separatrix_level(w)
        levels = np.concatenate([np.linspace(-0.95 * sep, 0.9 * sep, 7),
                                 np.linspace(1.15 * sep, 0.5 * vmax**2, 4)])
        return {"theta": th, "theta_dot": thd, "energy": core.reduced_energy(TH, THD, w),
                "levels": levels, "separatrix": float(sep)}

    # ----------------------------------------------------------------- report
    @classmethod
    def headline(cls, data):
        p, ini = data.config.params, data.config.initial
        a = data.analysis
        return [
            ("parameters", f"g = {fmt(p.g)} m/s², l = {fmt(p.l)} m, m = {fmt(p.m)} kg"),
            ("initial state", f"θ0 = {fmt(ini.theta)} rad, θ̇0 = {fmt(ini.theta_dot)} rad/s"),
            ("motion", f"{a['motion']}, k = {fmt(a['k'])}"),
            ("period", f"{fmt(a['period'], 14)} s exact; small-angle 2π/ω0 = "
                       f"{fmt(a['period_small_angle'])} s"),
            ("max |θ − θ_exact|", f"{fmt_err(a['theta_max_error'])} rad over the run"),
        ]

    @classmethod
    def section_time_series(cls, data):
        run = data.runs["main"]
        th_ex, thd_ex = run.reference["theta"], run.reference["theta_dot"]
        small = data.analysis.get("small_angle_solution")
        fig = common_plots.timeseries_against_reference(
            run.t, {"theta": run["theta"], "theta_dot": run["theta_dot"]},
            {"theta": th_ex, "theta_dot": thd_ex},
            ylabels={"theta": "θ [rad]", "theta_dot": "θ̇ [rad/s]"},
            reference_label=run.attrs["reference_label"],
            extra={"theta": small["theta"], "theta_dot": small["theta_dot"]}
            if small is not None else None,
        )
        err = common_plots.error_against_time(
            run.t, {"|θ − θ_exact| [rad]": run["theta"] - th_ex,
                    "|θ̇ − θ̇_exact| [rad/s]": run["theta_dot"] - thd_ex},
            ylabel="absolute error")
        return SectionContent(figures=[
            cls.figure("timeseries", fig, "θ(t) and θ̇(t) integrated, against the exact "
                       "elliptic-function solution and the small-angle solution (1.19)."),
            cls.figure("error", err, "Error of the integration against the exact solution."),
        ])

    @classmethod
    def section_phase_portrait(cls, data):
        run = data.runs["main"]
        grid = data.analysis["phase_portrait"]
        fig = plots.phase_portrait(run["theta"], run["theta_dot"], grid_theta=grid["theta"],
                                   grid_theta_dot=grid["theta_dot"], energy=grid["energy"],
                                   levels=grid["levels"], separatrix=grid["separatrix"])
        return SectionContent(figures=[cls.figure(
            "phase", fig, "Phase portrait: librations (closed curves), the separatrix "
            "E = m g l through (±π, 0), and rotations; this scene's orbit highlighted.")])

    @classmethod
    def section_period(cls, data):
        a = data.analysis
        libration = a["motion"] == "libration"
        curve = a["period_curve"]
        fig = plots.period_against_amplitude(
            curve_amplitude=curve["amplitude"], curve_period=curve["period"],
            small_angle_period=a["period_small_angle"],
            amplitude=a["amplitude"] if libration else None, period=a["period"],
            period_measured=a["period_measured"] if libration else None)
        facts = [("exact period", f"{fmt(a['period'], 14)} s"),
                 ("measured from θ(t)", f"{fmt(a['period_measured'], 14)} s"),
                 ("relative difference", fmt_err(abs(a['period_measured'] / a['period'] - 1)))]
        notes = [] if libration else [
            "This scene rotates; its period is the time of one full turn, 2K(1/k²)/(k ω0)."]
        if not math.isfinite(a["period_measured"]):
            notes.append(f"No measured period: the run covers fewer than two periods or stores "
                         f"fewer than {cls.MIN_SAMPLES_PER_PERIOD} samples per period.")
        return SectionContent(figures=[cls.figure(
            "period", fig, "Period against amplitude: exact 4K(k)√(l/g), k = sin(θ0/2), "
            "against the small-angle period 2π√(l/g).")], facts=facts, notes=notes)

    @classmethod
    def section_period_family(cls, data):
        sweep = data.sweep
        a = sweep.analysis
        theta = sweep.values.get("initial.theta")
        x = np.abs(theta) if theta is not None else np.full(sweep.size, data.config.initial.theta)
        ok = sweep.ok & np.isfinite(a.get("period_measured", np.full(sweep.size, np.nan)))
        curve = data.analysis.get("period_curve")
        fig = plots.period_family(x[ok], a["period_measured"][ok], a["period"][ok],
                                  curve=curve, small_angle=a["period_small_angle"][ok])
        rel = np.abs(a["period_measured"][ok] / a["period"][ok] - 1)
        facts = [("members with a period", f"{int(ok.sum())} of {sweep.size}"),
                 ("max relative error of the period", fmt_err(float(np.max(rel)))
                  if rel.size else "—"),
                 ("tolerance of the runs", f"rtol {data.config.run.rtol:g}, "
                                           f"atol {data.config.run.atol:g}")]
        return SectionContent(figures=[cls.figure(
            "period_family", fig, "Each member's period, the time between its first two upward "
            "crossings of θ = 0 on the integrator's dense output, against the exact "
            "4K(k)√(l/g), k = sin(θ0/2) (DLMF 19.2.8, 22.19.4), and the small-angle period "
            "2π√(l/g); below, the relative error.")], facts=facts)

    @classmethod
    def section_boundary_value(cls, data):
        bvp = data.analysis["boundary_value"]
        fig = plots.boundary_value(bvp["t"], bvp["theta_exact"], bvp["theta_numeric"],
                                   bvp["theta_nonlinear"])
        b = data.config.boundary
        table = Table(
            caption="Action S = ∫ L dt (2.4) along the boundary-value solution",
            header=["solution", "action [J·s]", "rel. error vs closed form"],
            rows=[["linear, closed form (2.4)", fmt(bvp["action_exact"], 14), "—"],
                  ["linear, solve_bvp + Simpson quadrature", fmt(bvp["action_numeric"], 14),
                   fmt_err(abs(bvp["action_numeric"] / bvp["action_exact"] - 1))],
                  ["nonlinear pendulum, solve_bvp", fmt(bvp["action_nonlinear"], 14),
                   "(different problem)"]])
        return SectionContent(
            figures=[cls.figure("bvp", fig, f"θ(0) = {fmt(b.theta0)} rad, θ(T) = "
                                f"{fmt(b.theta1)} rad, T = {fmt(b.T)} s: the linearised "
                                "solution (1.21) in closed form and numerically, and the "
                                "nonlinear pendulum's solution with the same ends.")],
            tables=[table])

    @classmethod
    def section_energy(cls, data):
        return cls.invariants_section(data, labels={"energy": "energy E"},
                                      caption="Energy drift relative to m g l.")
