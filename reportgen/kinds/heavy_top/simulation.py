"""``heavy_top`` simulation: each initial state integrated (Lagrange's reduction or the
spin-free frame), its Euler angles and axis derived, and checked against the closed forms
of the cubic f(u) notes (10.31): roots, case, nutation period and precession, u(t) in sn² and
through ℘; the band runs of ``[band]`` and the ``[sleeping]`` sweep across the threshold."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.config import ConfigError
from ...scene.content import fmt_err
from ...scene.integration import IntegratingSimulation
from ...scene.results import AuditCase, Check, Results, RunRecord
from .config import (
    BAND_CASES,
    MIN_SAMPLES_PER_PERIOD,
    REDUCED_MIN_SIN,
    TOP,
    HeavyTopConfig,
    Start,
    starts,
)
from .locus import locus_stretch
from .results import SCHEMA
from .sleeping import SleepingTop

model_core = lazy_module("reportgen.core.models.heavy_top")
theory = lazy_module("reportgen.core.heavy_top_theory")
top_contours = lazy_module("reportgen.core.top_contours")
kinematics = lazy_module("reportgen.core.heavy_top_kinematics")
integrators = lazy_module("reportgen.core.integrators")


#: β² = 4 within this (relative): β℘ and (4/β)℘ are the same numbers
TEXTBOOK_SCALE_RTOL = 1e-6


class HeavyTopSimulation(SleepingTop, IntegratingSimulation):
    """The heavy symmetric top integrated and checked against its closed forms."""

    schema = SCHEMA
    config: HeavyTopConfig

    @classmethod
    def audit_cases(cls):
        def case(name, initial, t_end, samples, what):
            config = {"kind": "heavy_top", "title": name, "params": dict(TOP),
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
                  "omega3": 1.02 * 2.0 * math.sqrt(TOP["I1"] * TOP["Mgl"]) / TOP["I3"]},
                 100.0, 5001, "2 % above I3²ω3² = 4 I1 Mgl: the tilt must stay small, but the "
                 "nutation is slow and nearly degenerate"),
            case("top just below its sleeping threshold, tilted 1e-6",
                 {"theta": 1e-6, "theta_dot": 0.0, "phi_dot": 0.0,
                  "omega3": 0.98 * 2.0 * math.sqrt(TOP["I1"] * TOP["Mgl"]) / TOP["I3"]},
                 100.0, 5001, "2 % below the threshold: a 1e-6 tilt grows to order one"),
        ]

    #: ℘ (textbook exercise 4.10; /analysis weierstrass_max_difference) is computed for every
    #: nutating top (3 ms), the tilted sleeping tops included; a sleeping-top scene (one
    #: with a [sleeping] sweep, which is about its threshold) shows its section only when
    #: its [report] sections name it
    computed_on_request = ("error_vs_runtime", "contour_map")

    def computes(self, name: str) -> bool:
        if name == "contour_map":  # ex. 4.10(a)–(e): only a scene that names the section
            asked = self.config.report.sections
            return asked is not None and name in asked
        return name == "weierstrass" or super().computes(name)

    #: f(u) is drawn around [u1, u2] alone when u2 − u1 is less than this fraction of the
    #: range [−1, u3] (else the motion's interval is a sliver)
    NARROW_BAND = 0.1

    # ----------------------------------------------------------------- helpers
    @property
    def starts(self) -> dict[str, Start]:
        """Run name -> initial state (one run, or the three of ``[band] case = "all"``)."""
        return starts(self.config)

    def stored_runs(self) -> int:
        """One run of each start (``main`` names the first of a band's)."""
        return len(self.starts)

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
            return "spin_free", "as the configuration asks"
        if run.formulation == "reduced":
            if lowest <= 0.0:
                raise ConfigError([
                    f"{self.source.label}: key 'run.formulation': the reduced equations are "
                    f"singular on the vertical, which this top reaches (sin θ = {lowest:.3g} "
                    f'at a turning circle): expected "spin_free" or "auto", got "reduced"'])
            return "reduced", "as the configuration asks"
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
        if results.analysis.get("theta0", math.inf) < self.SLEEPING_TILT:
            results.analysis.update(self._sleeping_facts(results))
            results.analysis["behaviour"] = self._sleeping_behaviour(results)
        if self.config.sleeping is not None:
            # computed whenever [sleeping] is given: [report] edits re-stamp the archive
            # without simulating again, and the section must then still find it
            results.analysis["sleeping_sweep"] = self._sleeping_sweep()
        model, y0, *_ = self._integration(next(iter(starts.values())))
        t_study = min(run.t_end, self.accuracy_horizon(results))  # up to a return upright
        if t_study < run.t_end and self.wants_study():
            results.analysis["study_t_end"] = t_study
        self.study(results, model, y0, np.linspace(0.0, t_study, 201),
                   progress=progress)
        return results

    def accuracy_horizon(self, results: Results) -> float:
        """An unstable sleeping top is compared with its closed form over one nutation
        period only: at its return to the vertical (θ ≈ θ0) it passes the unstable
        equilibrium again, where an error (of the run, and of the closed form's roots,
        u2 within round-off of 1) grows by ~θmax/θ0 = 1e6."""
        a = results.analysis
        period = float(a.get("nutation_period", math.nan))
        if ("behaviour" in a and not a.get("sleeping_stable", True)
                and math.isfinite(period) and period > 0):
            return period
        return super().accuracy_horizon(results)

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
            min_samples_per_period=MIN_SAMPLES_PER_PERIOD)
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
        a.update(self._case_facts(start, c, r, a))
        self._store_closed_form(a, main, start, c, r)
        if self.computes("weierstrass"):
            self._store_weierstrass(a, main, c, r, w_cf)
        if self.computes("contour_map") and "weierstrass" in a:  # a nutating top
            a["contours"] = self._contours(c, r)
        checks = self._checks(a, main, start, c, r, scales)
        return main, a, checks

    def _case_facts(self, start: Start, c: theory.TopConstants, r: theory.Roots,
                    a: dict) -> dict:
        """The facts the words follow, with their thresholds: φ̇ on the two turning circles
        (whose signs make the case: loops, waves, cusps), the classification's tolerances,
        whether the top is released at rest, which steady root it precesses at, and how
        many whole nutation periods the run spans."""
        period = a["nutation_period"]
        out = {"phi_dot_upper": self._phi_dot_at(r.w1, c), "phi_dot_lower": self._phi_dot_at(r.w2, c),
               "case_cusp_tolerance": theory.CUSP_RTOL,
               "case_steady_tolerance": theory.STEADY_RTOL,
               "released_at_rest": bool(start.theta_dot == 0.0 and start.phi_dot == 0.0),
               "periods_in_run": int(self.config.run.t_end // period)
               if math.isfinite(period) and period > 0 else 0,
               "steady_root": ""}
        if a["case"] == "steady" and math.isfinite(a["steady_rate_slow"]):
            slow, fast = a["steady_rate_slow"], a["steady_rate_fast"]
            near_fast = math.isfinite(fast) and abs(start.phi_dot - fast) < abs(
                start.phi_dot - slow)
            out["steady_root"] = "fast" if near_fast else "slow"
        return out

    @staticmethod
    def _phi_dot_at(w: float, c: theory.TopConstants) -> float:
        """φ̇ = (b − a u)/(1 − u²), notes (10.26), at u = 1 − w, in w: (B + a w)/(w (2 − w)),
        B = b − a (no cancellation near the vertical); NaN on the vertical itself."""
        if w <= 0.0 or w >= 2.0:
            return math.nan
        return (c.B + c.a * w) / (w * (2.0 - w))

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
            "Jacobi form of the quadrature t = ∫du/√f(u), notes (10.31) (Goldstein §5.7; "
            "DLMF §22.15)")
        q = np.column_stack([main["q_w"], main["q_x"], main["q_y"], main["q_z"]])
        w = kinematics.one_minus_cos_theta(q)
        width = a["one_minus_u1"] - a["one_minus_u2"]
        relative = bool(width > 0.0)
        a["cos_theta_error"] = {"difference": (w - w_cf) / width if relative else w - w_cf,
                                "relative_to_width": relative}
        # f(u) notes (10.31); near the vertical in w = 1 − u, where [u1, u2] would be invisible
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
        # V'(θ) notes (10.28); on the vertical (the sleeping top) it is not drawn
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
        # the two steady precession rates notes (10.45) against the spin, from the bound notes (10.46)
        w_min = theory.steady_precession_min_omega3(p.I1, p.I3, p.Mgl, start.theta)
        lo = w_min * 1.0001 if math.isfinite(w_min) else 0.1
        om = np.linspace(lo, max(3.0 * abs(start.omega3), 2 * lo), 400)
        slow, fast = theory.steady_precession_curve(p.I1, p.I3, p.Mgl, start.theta, om)
        a["steady_rates"] = {"omega3": om, "slow": slow, "fast": fast, "omega3_min": w_min}

    @staticmethod
    def _store_weierstrass(a: dict, main: RunRecord, c: theory.TopConstants,
                           r: theory.Roots, w_sn: np.ndarray) -> None:
        """u(t) through ℘ on the output grid (textbook exercise 4.10), its lattice, and its largest
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
            "ode_residual": theory.weierstrass_ode_residual(main.t, form, r, c),
            # the textbook's u = β℘ + c gives the same numbers as u = (4/β)℘ + μ only when
            # β² = 4 (to TEXTBOOK_SCALE_RTOL): then the report says so
            "textbook_scale_agrees": bool(abs(0.25 * c.beta * c.beta - 1.0)
                                          <= TEXTBOOK_SCALE_RTOL),
        }
        loops = theory.period_loops(r, c)  # the period round the cut (textbook ex. 4.10)

        def settled(value, integral):  # a sum that did not settle within its budget: none
            return value if integral.converged else math.nan

        a["weierstrass"].update({
            "period_loop": settled(loops.loop.value, loops.loop),
            "period_loop_imag": settled(loops.loop.imag, loops.loop),
            "period_loop_nodes": loops.loop.nodes, "period_loop_rho": loops.loop.rho,
            "period_loop_strip": loops.loop.strip,
            "period_sine_squared": settled(loops.sine_squared.value, loops.sine_squared),
            "period_sine_squared_nodes": loops.sine_squared.nodes,
            "omega_loop": settled(0.5 * loops.wp_loop.value, loops.wp_loop),
            "omega_loop_nodes": loops.wp_loop.nodes,
        })

    @staticmethod
    def _contours(c: theory.TopConstants, r: theory.Roots) -> dict:
        """Textbook ex. 4.10(a)–(e): t(u) = ∫du/√f(u) continued over the cut plane and onto
        the second sheet by contour integration (:mod:`reportgen.core.top_contours`)."""
        m = top_contours.contour_map(top_contours.TopCubic(c.beta, r.u1, r.w2 - r.w1,
                                                           r.w2 - r.w3))
        out = {"u_X": r.u1, "u_N": r.u2, "u_U": r.u3, "period": m.cubic.period,
               "imaginary_period": m.cubic.imaginary_period,
               "grid_re": m.grid_v.real + r.u1, "grid_im": m.grid_v.imag,
               "defects": dict(m.defects), "sides": dict(m.sides)}
        for name, t in (*m.corners.items(), ("loop", m.loop)):
            out[f"t_{name}_re"], out[f"t_{name}_im"] = t.real, t.imag
        for name, t in m.images.items():
            out[f"{name}_re"], out[f"{name}_im"] = t.real, t.imag
        return out

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
                       "max |Δu(t)|, ℘ form against sn² form, on the output grid")

    def _checks(self, a: dict, main: RunRecord, start: Start, c: theory.TopConstants,
                r: theory.Roots, scales: dict[str, float]) -> list[Check]:
        checks = []
        src_T = ("4K(k²)/√(β(u3−u1)), the period of t = ∫du/√f(u), notes (10.31) (Goldstein "
                 "§5.7), vs ∮du/√f(u) by quadrature")
        band = self.config.band
        if band is not None:
            solved = "the configured band; the release solved for on the upper circle"
            measured = ("the configured band; extremes of the integrated θ(t), "
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
                "Π(n|k²) closed form of ∮(b − a u)/(1 − u²) dt notes (10.26)",
                scale=max(abs(a["precession_per_period"]), 1e-300)))
        if "weierstrass" in a:
            wp = a["weierstrass"]
            checks.append(Check("nutation period 2ω of the ℘ lattice (AGM)", wp["period"],
                                a["nutation_period"], "s",
                                "4K(k²)/√(β(u3−u1)) with K from Carlson's symmetric "
                                "integral of the first kind"))
            checks.append(Check("max |Δu(t)|, ℘ form against sn² form, on the output grid",
                                a["weierstrass_max_difference"], 0.0, "",
                                "℘ by theta series (textbook exercise 4.10) against Jacobi sn² by AGM; "
                                "absolute difference in u = cos θ", scale=1.0))
        if "contours" in a:
            checks += self._contour_checks(a["contours"])
        if math.isfinite(a["nutation_period_measured"]):
            checks.append(Check("nutation period measured from θ(t)",
                                a["nutation_period_measured"], a["nutation_period"],
                                "s", "4K(k²)/√(β(u3−u1))" + self._conditioning(a)))
        if math.isfinite(a["precession_measured"]):
            checks.append(Check("precession per period measured from φ(t)",
                                a["precession_measured"], a["precession_per_period"],
                                "rad", "Π(n|k²) closed form notes (10.26)" + self._conditioning(a),
                                scale=max(abs(a["precession_per_period"]), 1e-300)))
        if r.w2 > r.w1 and not r.sleeping:
            w = 2.0 * (main["q_x"] ** 2 + main["q_y"] ** 2) / (
                main["q_w"] ** 2 + main["q_x"] ** 2 + main["q_y"] ** 2 + main["q_z"] ** 2)
            w_cf, _ = theory.u_closed_form(main.t[-1:], r, c)
            checks.append(Check("cos θ(t_end)", 1.0 - float(w[-1]), 1.0 - float(w_cf[0]),
                                "", "u1 + (u2−u1) sn²(λt + τ0 | k²), the Jacobi form of "
                                "t = ∫du/√f(u), notes (10.31) (Goldstein §5.7; DLMF §22.15)",
                                scale=r.w2 - r.w1))
        if a["case"] == "steady":
            checks.append(Check("mean φ̇ (steady precession)", a["mean_phi_dot"], start.phi_dot,
                                "rad/s", f"{self.config.initial.steady} root of notes (10.45)"))
        e = main.invariants["energy"]
        checks.append(Check("energy E(t_end)", float(e[-1]), float(e[0]), "J",
                            "E(0), conserved", scale=scales["energy"]))
        return checks

    @staticmethod
    def _contour_checks(k: dict) -> list[Check]:
        """Ex. 4.10(a)–(e) by contour integration against the closed forms T = 2K(k²)/λ and
        τ = 2K(1 − k²)/λ, λ = ½√(β(u3 − u1)) (each error relative to T)."""
        T, tau = k["period"], k["imaginary_period"]
        src = ("the periods of t = ∫du/√f(u) for the cubic f(u), notes (10.31): "
               "T = 4K(k²)/√(β(u3 − u1)), τ = 4K(1 − k²)/√(β(u3 − u1))")
        rows = (("Re t(u_N) = T/2, a corner of the rectangle (textbook ex. 4.10(a))",
                 k["t_u_N_re"], 0.5 * T),
                ("Im t(u_U) = τ/2, a corner of the rectangle (textbook ex. 4.10(a))",
                 k["t_u_U_im"], 0.5 * tau),
                ("Im t(∞) = τ/2, a corner of the rectangle (textbook ex. 4.10(a))",
                 k["t_infinity_im"], 0.5 * tau),
                ("the loop clockwise round the cut [u_N, u_U]: Im ∮ = τ (textbook ex. "
                 "4.10(e))", k["t_loop_im"], tau),
                ("the loop round [u_X, u_N] through both cuts: Re ∮ = T", k["t_loop_real_re"],
                 T))
        checks = [Check(name, value, ref, "s", src, scale=T) for name, value, ref in rows]
        for name, words in (
                ("sides", "the real axis onto the rectangle's sides (textbook ex. 4.10(a))"),
                ("lower_reflection", "t(ū) = conj t(u) in the lower half-plane (textbook ex. "
                 "4.10(b))"),
                ("second_sheet_left", "t₁ = −t₀ on the second sheet through (−∞, u_X] "
                 "(textbook ex. 4.10(c))"),
                ("second_sheet_right", "t₂ = t₁ + T on the second sheet through [u_N, u_U] "
                 "(textbook ex. 4.10(d))")):
            checks.append(Check(f"largest defect of {words}", k["defects"][name], 0.0, "s",
                                "contour integration on the cut plane, against the same "
                                "closed forms", scale=T))
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
        out["period_loop"] = a.get("weierstrass", {}).get("period_loop", math.nan)
        out["energy_drift"] = float(record.attrs.get("drift_energy", math.nan))
        # φ̇ = (b − a u)/(1 − u²) notes (10.26) on the two turning circles
        out["phi_dot_upper"] = (a["b"] - a["a"] * a["u2"]) / (1.0 - a["u2"] ** 2)
        out["phi_dot_lower"] = (a["b"] - a["a"] * a["u1"]) / (1.0 - a["u1"] ** 2)
        out["locus_stop"], out["locus_periods"], out["view_azimuth"] = locus_stretch(
            record, a["nutation_period"], a["precession_per_period"])
        # whether the stretch drawn goes once round the band (Δφ ≥ 2π), or is cut short by
        # the run or by FIG43_MAX_PERIODS
        out["locus_full_turn"] = bool(abs(out["locus_periods"] * a["precession_per_period"])
                                      >= 2.0 * math.pi)
        return out


    @staticmethod
    def _conditioning(a) -> str:
        sens = a.get("period_sensitivity", math.nan)
        if math.isfinite(sens) and sens > 1e-6:
            return (f"; ill-conditioned: the run's own energy drift alone moves T by "
                    f"{fmt_err(sens)} (relative)")
        return ""
