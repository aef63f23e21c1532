"""``pendulum`` simulation: the run against the Jacobi-sn solution, the measured period,
the phase portrait's level sets, the boundary-value problem and the compiled ensemble of
a sweep."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.content import fmt, fmt_err, member_text
from ...scene.integration import IntegratingSimulation
from ...scene.results import AuditCase, Check, Results
from .config import MIN_SAMPLES_PER_PERIOD, PendulumConfig
from .results import SCHEMA

core = lazy_module("reportgen.core.models.pendulum")
theory = lazy_module("reportgen.core.pendulum_theory")
action = lazy_module("reportgen.core.pendulum_action")


class PendulumSimulation(IntegratingSimulation):
    """m l² θ'' + m g l sin θ = 0 integrated and checked against its closed forms."""

    schema = SCHEMA
    config: PendulumConfig

    #: swept keys the compiled ensemble covers (members released from rest)
    ENSEMBLE_KEYS = frozenset({"initial.theta", "params.g", "params.l", "params.m"})
    #: phase-portrait grid: points per axis
    PHASE_GRID = 400
    #: period-curve samples over 0 < θ0 < π
    PERIOD_CURVE_POINTS = 500

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
    def regime(self) -> str:
        return "libration" if self.m1 > 0.0 else "rotation"

    @property
    def proximity(self) -> str:
        """"on", "near" or "far" from the separatrix (:func:`theory.separatrix_proximity`)."""
        return theory.separatrix_proximity(self.m1)

    #: |T/T0 − 1| below this: the exact and the small-angle periods "nearly agree"
    SMALL_ANGLE_CLOSE = 0.01

    @property
    def centre(self) -> float:
        """The bottom a libration swings about: the multiple of 2π nearest θ0 [rad]."""
        return 2.0 * math.pi * round(self.config.initial.theta / (2.0 * math.pi))

    def _behaviour(self, a: dict) -> str:
        """The motion in words, chosen by :func:`theory.motion_case` (|1 − k²| against
        SEPARATRIX_ON and SEPARATRIX_NEAR, and the sign of 1 − k²)."""
        case = theory.motion_case(self.m1)
        period = fmt(a["period"], 5)
        if case == "separatrix":
            return (f"on the separatrix: the energy is the upright's, 2 m g l above the bottom, "
                    f"to within |1 − k²| = {fmt_err(abs(self.m1))} of it (below "
                    f"{fmt(theory.SEPARATRIX_ON)}); the pendulum lingers at the upright "
                    f"θ = ±π, which it approaches or leaves only asymptotically, and its exact "
                    f"period, {period} s, is set by that residue alone")
        if case == "rotation":
            sense = "increasing" if self.config.initial.theta_dot > 0 else "decreasing"
            return f"rotation: goes over the top, θ {sense} by 2π every {period} s"
        if case == "rotation near the separatrix":
            return (f"rotation just above the separatrix (k² − 1 = {fmt_err(-self.m1)}, below "
                    f"{fmt(theory.SEPARATRIX_NEAR)}): goes over the top once every {period} s, "
                    "spending most of each turn beyond ±135°, slow near the upright")
        amplitude = self._swing(a)
        if case == "libration near the separatrix":
            return (f"libration just inside the separatrix (1 − k² = {fmt_err(self.m1)}, below "
                    f"{fmt(theory.SEPARATRIX_NEAR)}): swings between {amplitude} with the "
                    f"finite period {period} s, spending most of each period beyond ±135°, "
                    "near the upright")
        return f"libration: swings between {amplitude}, never over the top"

    @staticmethod
    def _swing(a: dict) -> str:
        """``±2.5 rad``, or ``2π ± 2.28 rad`` when the bottom swung about is not θ = 0."""
        centre, amplitude = float(a.get("libration_centre", 0.0)), fmt(a["amplitude"], 6)
        return f"{fmt(centre / math.pi)}π ± {amplitude} rad" if centre else f"±{amplitude} rad"

    @property
    def has_exact_solution(self) -> bool:
        return abs(self.m1) >= theory.EXACT_SOLUTION_MIN_M1

    @property
    def reference_label(self) -> str:
        if self.has_exact_solution:  # sn for a libration, am for a rotation
            return "exact (Jacobi sn)" if self.m1 > 0 else "exact (Jacobi am)"
        return "reference run (DOP853, rtol 1e-14)"

    def reference_solution(self, t):
        """θ(t), θ̇(t): the elliptic-function solution, or — closer to the separatrix than
        double precision resolves it — the reference run at rtol 1e-14 (said so in the report)."""
        p, ini = self.config.params, self.config.initial
        if self.has_exact_solution:
            # taken about the bottom the libration swings about: core's phase of a start near
            # ±2π is off by a half-period (sin(θ0/2) changes sign with each turn)
            centre = self.centre if self.m1 > 0 else 0.0
            theta, theta_dot = core.exact_solution(t, ini.theta - centre, ini.theta_dot, p.g,
                                                   p.l)
            return theta + centre, theta_dot
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
                                        min_samples_per_period=MIN_SAMPLES_PER_PERIOD)
        results.analysis.update({
            "period": period,
            "period_measured": measured,
            "period_small_angle": 2 * math.pi / self.omega0,
            "omega0": self.omega0,
            "k": math.sqrt(self.k2),
            "motion": self.regime,
            "complementary_parameter": self.m1,
            "separatrix_proximity": self.proximity,
            "separatrix_on_below": theory.SEPARATRIX_ON,
            "separatrix_near_below": theory.SEPARATRIX_NEAR,
            "reference": self.reference_label,
            "reference_is_exact": self.has_exact_solution,
            "theta_max_error": float(np.max(err)),
            "theta_dot_max_error": float(np.max(np.abs(theta_dot - exact_theta_dot))),
        })
        if self.m1 > 0:
            results.analysis["amplitude"] = core.libration_amplitude(ini.theta, ini.theta_dot,
                                                                     self.omega0)
            results.analysis["libration_centre"] = self.centre
        if self.m1 > 0 and self.proximity != "on":
            # the linearised solution (1.19) about the bottom the pendulum swings about, drawn
            # against the run; meaningless for a rotation or on the separatrix
            th_lin, thd_lin = core.small_angle_solution(t, ini.theta - self.centre,
                                                        ini.theta_dot, p.g, p.l)
            results.analysis["small_angle_solution"] = {"theta": th_lin + self.centre,
                                                        "theta_dot": thd_lin}
            results.analysis["period_excess"] = period * self.omega0 / (2 * math.pi) - 1.0
            results.analysis["small_angle_close_below"] = self.SMALL_ANGLE_CLOSE
        elif self.m1 < 0:
            results.analysis["rotation_sense"] = "increasing" if ini.theta_dot > 0 else (
                "decreasing")
        results.analysis["phase_portrait"] = self._phase_portrait(theta_dot)
        if not self.family_member:  # physical behaviour, not a status (a sweep: per member)
            results.analysis["behaviour"] = self._behaviour(results.analysis)
        amp = np.linspace(1e-3, math.pi - 1e-3, self.PERIOD_CURVE_POINTS)
        results.analysis["period_curve"] = {"amplitude": amp,
                                            "period": core.libration_period(amp, self.omega0)}
        if math.isfinite(measured):
            results.checks.append(Check("period (measured from θ(t))", measured, period, "s",
                                        "4K(k)·√(l/g), DLMF 22.19.4" if self.m1 > 0
                                        else "2K(1/k²)/(k ω0), DLMF 22.19.7"))
        exact_name = ("Jacobi sn solution, DLMF 22.19.2" if self.m1 > 0 else
                      "Jacobi amplitude solution θ/2 = am(u | 1/k²), DLMF §22.19")
        results.checks.append(Check("θ(t_end)", float(theta[-1]), float(exact_theta[-1]), "rad",
                                    exact_name if self.has_exact_solution
                                    else self.reference_label, scale=math.pi))
        e = main.invariants["energy"]
        results.checks.append(Check("energy E(t_end)", float(e[-1]), float(e[0]), "J",
                                    "E(0), conserved", scale=self.energy_scale))
        b = self.config.boundary
        if b is not None:
            bvp = core.boundary_value_problem(b.theta0, b.theta1, b.T, p.g, p.l, p.m)
            # the Lagrangian action's second variation along sin(kπt/T) is negative for each
            # k < ω0 T/π: the conjugate points ω0 T = π, 2π, … passed
            bvp["conjugate_points"] = int(self.omega0 * b.T // math.pi)
            results.analysis["boundary_value"] = bvp
            results.checks.append(Check("action S of the linear BVP (numerical quadrature)",
                                        bvp["action_numeric"], bvp["action_exact"], "J·s",
                                        "notes (2.4) on the solution (1.21), closed form"))
            self._action_analysis(results)
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201),
                   reference=(lambda ts: np.column_stack(self.reference_solution(ts)))
                   if self.has_exact_solution else None)
        return results

    def _action_analysis(self, results: Results) -> None:
        """The action of the linear boundary-value problem as a function of its ends,
        notes (7.1–7.15), in phase space, notes §5, and as g → 0, notes (1.22) and (2.5):
        ``end_variation``, ``phase_space_action``, ``free_particle_limit``."""
        p, b, w = self.config.params, self.config.boundary, self.omega0
        inertia = p.m * p.l**2

        def computed_action(theta0, theta1, T):  # what the first table's quadrature gives
            return core.boundary_value_problem(theta0, theta1, T, p.g, p.l, p.m)["action_numeric"]

        ends = action.end_variation(computed_action, b.theta0, b.theta1, b.T, w)
        p0, p1 = theory.linear_end_momenta(b.theta0, b.theta1, b.T, w, inertia)
        ends.update(momentum_start=p0, momentum_end=p1,
                    energy=theory.linear_energy(b.theta0, b.theta1, b.T, w, inertia))
        phase = action.action_variations(b.theta0, b.theta1, b.T, w, inertia)
        results.analysis.update({
            "end_variation": ends, "phase_space_action": phase,
            "free_particle_limit": action.free_particle_limit(b.theta0, b.theta1, b.T, w,
                                                              inertia)})
        exact = theory.linear_action(b.theta0, b.theta1, b.T, w, inertia)
        source = "notes (7.1–7.15): δS = p δq − H δt"
        # relative to the largest |p| on the solution, √(2 m l² E): p(T) itself may be 0
        momentum_scale = math.sqrt(2.0 * inertia * ends["energy"])
        results.checks.extend([
            Check("∂S/∂θ1 by differences of the computed S", ends["dS_dtheta1"], p1, "J·s",
                  f"m l² θ̇(T), {source}", scale=momentum_scale or None),
            Check("∂S/∂T by differences of the computed S", ends["dS_dT"], -ends["energy"],
                  "J", f"−E, {source}"),
            Check("∫ (p θ̇ − H) dt on the solution, Simpson", phase["action_hamiltonian"],
                  exact, "J·s", "notes §5; closed form notes (2.4)"),
        ])

    # ------------------------------------------------------------------ sweeps
    def sweep_block(self, lo, hi, values):
        """Members released from rest run as one compiled ensemble
        (:func:`.ensemble.pendulum_periods`): each member's period is the
        time between its first two upward crossings of θ = 0, against the exact
        4K(k)√(l/g).  Other sweeps run member by member."""
        p, ini, run = self.config.params, self.config.initial, self.config.run
        if not self._ensemble_sweep():
            return super().sweep_block(lo, hi, values)
        from ...scene.sweep import SweepBlock
        from . import ensemble

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
            from . import ensemble

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

