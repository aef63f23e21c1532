"""``central_force`` simulation: the relative orbit in V(r), its conserved quantities,
the Kepler checks (Kepler's equation, third law, LRL vector) or the apsidal angle."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.content import fmt, fmt_err
from ...scene.integration import IntegratingSimulation
from ...scene.results import AccuracyScale, AuditCase, Check, Results
from . import apsides as exact_apsides
from . import cases
from .config import CentralForceConfig
from .results import SCHEMA

core = lazy_module("reportgen.core.models.kepler")
hamilton_jacobi = lazy_module("reportgen.kinds.central_force.hamilton_jacobi")


class CentralForceSimulation(IntegratingSimulation):
    """The relative coordinate r = r1 − r2 integrated as one body of reduced mass μ."""

    schema = SCHEMA
    config: CentralForceConfig

    @classmethod
    def audit_cases(cls):
        def kepler(e, orbits):
            # μ = 1, k = 1: GM = 1, a = 1, period 2π; start at pericentre a(1 − e)
            return AuditCase(
                name=f"Kepler orbit, e = {e}", methods=("dop853", "yoshida8", "gauss6"),
                what=f"pericentre speed √((1 + e)/(1 − e)) = {math.sqrt((1 + e) / (1 - e)):.3g}: "
                     f"time scales {(1 - e) ** 1.5:.1e} of the period at pericentre",
                config={"kind": "central_force", "title": f"Kepler e = {e}",
                        "params": {"m1": 2.0, "m2": 2.0, "k": 1.0},
                        "initial": {"x": 1.0 - e, "y": 0.0, "vx": 0.0,
                                    "vy": math.sqrt((1 + e) / (1 - e))},
                        "run": {"t_end": orbits * 2 * math.pi, "samples": 20001}})

        return [kepler(0.99, 3), kepler(0.999, 2)]

    # ------------------------------------------------------------------ helpers
    @property
    def mu(self) -> float:
        return core.reduced_mass(self.config.params.m1, self.config.params.m2)

    @property
    def n(self) -> float:
        return self.config.params.n if self.config.params.potential == "power" else 1.0

    @property
    def epsilon(self) -> float:
        return self.config.params.epsilon or 0.0

    @property
    def is_kepler(self) -> bool:
        return self.config.params.potential == "kepler"

    @property
    def pot(self) -> tuple[float, float, float]:
        """(k, n, ε) of V = −k/rⁿ − ε/r²."""
        return self.config.params.k, self.n, self.epsilon

    def _state0(self):
        i = self.config.initial
        return np.array([i.x, i.y, i.vx, i.vy])

    @property
    def energy0(self) -> float:
        return float(core.energy(*self._state0(), self.mu, *self.pot))

    @property
    def L0(self) -> float:
        return float(core.angular_momentum(*self._state0(), self.mu))

    @property
    def bound(self) -> bool:
        return self.energy0 < 0.0

    @property
    def elements(self) -> dict:
        return core.orbital_elements(*self._state0(), self.config.params.k / self.mu)


    # --------------------------------------------------------------- simulation
    def _invariants(self, t, y):
        x, yy, vx, vy = y.T
        inv = {"energy": core.energy(x, yy, vx, vy, self.mu, *self.pot),
               "angular_momentum": core.angular_momentum(x, yy, vx, vy, self.mu)}
        if self.is_kepler:
            inv["lrl_x"], inv["lrl_y"] = core.lrl_vector(x, yy, vx, vy, self.mu,
                                                         self.config.params.k)
        return inv

    def _invariant_scales(self):
        k, mu = self.config.params.k, self.mu
        r0 = math.hypot(self.config.initial.x, self.config.initial.y)
        e_scale = max(abs(self.energy0), abs(float(core.potential(r0, *self.pot))))
        return {"energy": e_scale, "angular_momentum": abs(self.L0),
                "lrl_x": mu * k, "lrl_y": mu * k}

    def radial_scales(self) -> dict:
        """Eccentricity, semi-major axis, period: Kepler elements; or from the turning
        points, with the radial period (pericentre to pericentre), or a circle's period of
        revolution 2πμr²/|L|."""
        if self.is_kepler:
            el = self.elements
            out = {"eccentricity": el["eccentricity"], "semi_major_axis": el["semi_major_axis"],
                   "pericentre": el["pericentre"]}
            if el["bound"]:
                out.update(period=el["period"], apocentre=el["apocentre"])
            return out
        r_min, r_max = core.turning_points(self.energy0, self.L0, self.mu, *self.pot)
        out = {"pericentre": r_min}
        if math.isfinite(r_max):
            e = (r_max - r_min) / (r_max + r_min)
            out.update(apocentre=r_max, eccentricity=e, semi_major_axis=0.5 * (r_max + r_min),
                       period=self._radial_period(r_min, r_max, e))
        return out

    def _radial_period(self, r_min: float, r_max: float, e: float) -> float:
        if e < cases.CIRCULAR_E:  # no radial motion: the period of revolution
            return 2.0 * math.pi * self.mu * (0.5 * (r_min + r_max)) ** 2 / abs(self.L0)
        if self.config.params.potential == "power":
            return exact_apsides.radial_period_power(r_min, r_max, self.n, self.L0, self.mu)
        return exact_apsides.radial_period_inverse_cube(self.energy0, self.mu,
                                                        self.config.params.k)

    def apsidal_angle(self) -> float:
        """ψ, pericentre to apocentre, of this bound orbit: π/√(1 − 2με/L²) for V = −k/r
        (ε = 0) and −k/r − ε/r²; the power law's by quadrature (:mod:`.apsides`)."""
        if self.config.params.potential == "power":
            r_min, r_max = core.turning_points(self.energy0, self.L0, self.mu, *self.pot)
            return exact_apsides.apsidal_angle_power(r_min, r_max, self.n)
        return exact_apsides.apsidal_angle_inverse_cube(self.L0, self.mu, self.epsilon)

    def orbit_facts(self, scales: dict) -> dict:
        """The stored cases the report's words follow (:mod:`.cases`): the orbit's shape,
        how its apsides move (2ψ − 2π per radial period, bound non-circular orbits) and
        which body is heavier, with the thresholds they were decided by."""
        p = self.config.params
        e = float(scales.get("eccentricity", math.nan))
        facts = {"heavier_body": cases.heavier_body(p.m1, p.m2),
                 "circular_threshold": cases.CIRCULAR_E,
                 "apsidal_shift_threshold": cases.APSIDAL_SHIFT_NONE}
        shift = math.nan
        if self.bound and e >= cases.CIRCULAR_E:
            shift = 2.0 * self.apsidal_angle() - 2.0 * math.pi
            facts.update(apsidal_shift=shift, apsides=cases.apsides(shift))
        facts["orbit_shape"] = cases.orbit_shape(kepler=self.is_kepler, bound=self.bound,
                                                 eccentricity=e, shift=shift)
        return facts

    def models(self) -> list:
        return [core.model(self.config.params.k, self.mu, self.n, self.epsilon)]

    def accuracy_scale(self, reference_size: float) -> AccuracyScale:
        """A bound orbit's semi-major axis a: an error of 1e-3 a is the limit of "ok"; an
        unbound orbit's, the reference's size."""
        a = self.radial_scales().get("semi_major_axis") if self.bound else None
        if a is not None and math.isfinite(a) and a > 0:
            return AccuracyScale(float(a), "the orbit's semi-major axis a", "m")
        return super().accuracy_scale(reference_size)

    def simulate(self, progress=None) -> Results:
        run, p = self.config.run, self.config.params
        (model,) = self.models()
        y0 = self._state0()
        t = np.linspace(0.0, run.t_end, run.samples)
        scales = self.radial_scales()
        period = scales.get("period")
        results = Results()
        main = self.integrate(model, y0, t, invariants=self._invariants,
                              invariant_scales=self._invariant_scales(), progress=progress,
                              n_periods=run.t_end / period if period else None)
        results.runs["main"] = main
        a = results.analysis
        a.update(scales)
        a.update({"reduced_mass": self.mu, "total_mass": p.m1 + p.m2, "energy": self.energy0,
                  "angular_momentum": self.L0, "potential": p.potential,
                  "bound": "yes" if self.bound else "no"})
        a.update(self.orbit_facts(scales))
        if not self.bound:
            a["period_note"] = ("unbound orbit (E ≥ 0): no period; the apocentre is at "
                                "infinity")
        r_min, r_max = core.turning_points(self.energy0, self.L0, self.mu, *self.pot)
        a["turning_points"] = np.array([r_min, r_max])
        M = p.m1 + p.m2
        a["mass_fraction_m1"], a["mass_fraction_m2"] = p.m1 / M, p.m2 / M
        r1, r2 = core.body_positions(main["x"], main["y"], p.m1, p.m2)
        a["body_tracks"] = {"r1": r1, "r2": r2}
        a["effective_potential_curve"] = self._effective_potential_curve(r_min, r_max)
        if self.is_kepler and self.bound:
            self._kepler_checks(results, main)
        elif a["orbit_shape"] in ("closed", "rosette"):
            self._apsides(results, main)
        if self.bound and hamilton_jacobi.applies(r_min, r_max):
            self._hamilton_jacobi(results, main)
        e_inv = main.invariants["energy"]
        results.checks.append(Check("energy E(t_end)", float(e_inv[-1]), float(e_inv[0]), "J",
                                    "E(0), conserved", scale=self._invariant_scales()["energy"]))
        L_inv = main.invariants["angular_momentum"]
        results.checks.append(Check("angular momentum L(t_end)", float(L_inv[-1]),
                                    float(L_inv[0]), "kg·m²/s",
                                    "L(0), Noether charge of rotations, notes (3.23)–(3.25)"))
        ref, ref_kind = None, "exact"
        if self.is_kepler and self.bound:
            el = self.elements
            ref_kind = "the solution of Kepler's equation E − e sin E = M at every time"

            def ref(ts):
                return np.column_stack(core.kepler_state(ts, el))
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201), reference=ref,
                   reference_kind=ref_kind)
        return results

    def _hamilton_jacobi(self, results: Results, main) -> None:
        """The Hamilton–Jacobi equations along the run, W = W_r(r) + α_θ θ (notes (7.16),
        (7.32), (7.42)–(7.45)): :mod:`reportgen.kinds.central_force.hamilton_jacobi`."""
        k, n, eps = self.pot
        analysis, checks = hamilton_jacobi.residuals(
            main.t, (main["x"], main["y"], main["vx"], main["vy"]), mu=self.mu, k=k, n=n,
            epsilon=eps, energy=self.energy0, angular_momentum=self.L0,
            potential_name=self.config.params.potential)
        results.analysis.update(analysis)
        results.checks.extend(checks)

    def _effective_potential_curve(self, r_min: float, r_max: float) -> dict:
        """V(r) and V_eff(r) on the plotted range, and the circular orbit at this L."""
        top = 2.2 * r_max if math.isfinite(r_max) else 6.0 * r_min
        r = np.linspace(0.15 * r_min, top, 800)
        L, mu = self.L0, self.mu
        rc = core.circular_radius(L, mu, *self.pot)
        return {"r": r, "potential": core.potential(r, *self.pot),
                "effective_potential": core.effective_potential(r, L, mu, *self.pot),
                "circular_radius": rc,
                "circular_energy": float(core.effective_potential(rc, L, mu, *self.pot))}

    #: a pericentre passage must span this many stored samples to be located reliably
    MIN_SAMPLES_PER_PASSAGE = 4

    #: below this eccentricity the orbit is a circle to the samples: r has no minimum to
    #: time (round-off picks "passages" anywhere)
    MIN_ECCENTRICITY_FOR_PASSAGES = 1e-6

    def _passages_resolved(self, e: float, period: float) -> bool:
        run = self.config.run
        per_period = (run.samples - 1) * period / run.t_end
        # the pericentre passage lasts ~ (1 − e)^{3/2} T (time spent within ~2 r_min)
        return per_period * (1.0 - e) ** 1.5 >= self.MIN_SAMPLES_PER_PASSAGE * 2 * math.pi \
            and run.t_end >= 2.2 * period and e >= self.MIN_ECCENTRICITY_FOR_PASSAGES

    def _unresolved_reason(self, el) -> str:
        """Why :meth:`_passages_resolved` is false for this orbit, in words."""
        run, e, period = self.config.run, el["eccentricity"], el["period"]
        if e < self.MIN_ECCENTRICITY_FOR_PASSAGES:
            return "the orbit is (nearly) a circle, with no pericentre to time"
        if run.t_end < 2.2 * period:
            return "the run is shorter than two orbits"
        return (f"a pericentre passage spans fewer than {self.MIN_SAMPLES_PER_PASSAGE} "
                f"samples (e = {fmt(e, 3)}: the body sweeps through pericentre in about "
                f"{fmt_err((1.0 - e) ** 1.5 / (2 * math.pi))} of a period)")

    def _kepler_checks(self, results: Results, main) -> None:
        el, a = self.elements, results.analysis
        x, y, vx, vy = core.kepler_state(main.t, el)
        main.reference = {"x": x, "y": y, "vx": vx, "vy": vy}
        main.attrs["reference_label"] = "Kepler's equation E − e sin E = M (Danby §6.6)"
        # one closed orbit of the exact ellipse, and the eccentricity vector A/(μk)
        xo, yo, _, _ = core.kepler_state(np.linspace(0.0, el["period"], 721), el)
        a["kepler_orbit"] = {"x": xo, "y": yo}
        a["eccentricity_vector"] = el["eccentricity"] * np.array([math.cos(el["omega"]),
                                                                  math.sin(el["omega"])])
        err = np.hypot(main["x"] - x, main["y"] - y)
        scale = el["semi_major_axis"]
        a["kepler_position_error"] = err
        a["kepler_position_error_max"] = float(np.max(err))
        a["kepler_velocity_error_max"] = float(np.max(np.hypot(main["vx"] - vx,
                                                               main["vy"] - vy)))
        results.checks.append(Check("max position error |Δr| over the run", float(np.max(err)), 0.0,
                                    "m", "Kepler's equation E − e sin E = M (Danby §6.6)",
                                    scale=scale))
        mu, k = self.mu, self.config.params.k
        ax, ay = main.invariants["lrl_x"], main.invariants["lrl_y"]
        e_lrl = np.hypot(ax, ay) / (mu * k)
        a["lrl_eccentricity_error"] = e_lrl - el["eccentricity"]
        a["lrl_eccentricity_drift"] = float(np.max(np.abs(e_lrl - el["eccentricity"])))
        results.checks.append(Check("|A|/(μk) at t_end (LRL vector)", float(e_lrl[-1]),
                                    el["eccentricity"], "", "e of the initial state, |A| = μke, "
                                    "Goldstein (3.83)", scale=1.0))
        period = el["period"]
        if self._passages_resolved(el["eccentricity"], period):
            tp, rp, _ = core.apsides_from_samples(main.t, main["x"], main["y"], main["vx"],
                                                  main["vy"], mu, k)
            _, ra, _ = core.apsides_from_samples(main.t, main["x"], main["y"], main["vx"],
                                                 main["vy"], mu, k, which="apocentre")
            if tp.size >= 2 and ra.size >= 1:
                t_meas = (tp[-1] - tp[0]) / (tp.size - 1)
                a["period_measured"] = t_meas
                results.checks.append(Check("period from pericentre passages", t_meas, period,
                                            "s", "third law T = 2π√(a³/(k/μ)), Goldstein (3.71)"))
                a_meas = 0.5 * (float(np.mean(rp)) + float(np.mean(ra)))
                a["semi_major_axis_measured"] = a_meas
                results.checks.append(Check("semi-major axis (rₘᵢₙ + rₘₐₓ)/2 measured", a_meas,
                                            el["semi_major_axis"], "m",
                                            "a = −k/(2E), Goldstein (3.61)"))
        else:
            a["period_measured_note"] = (
                f"period not measured from the samples: {self._unresolved_reason(el)}; the "
                "orbit is checked against Kepler's equation at every sample instead")

    def _apsides(self, results: Results, main) -> None:
        a, mu = results.analysis, self.mu
        k, n, eps = self.pot
        method = "quadrature"
        if self.config.params.potential == "power":
            exact = self.apsidal_angle()
            a["apsidal_angle_near_circular"] = core.apsidal_angle_near_circular(n)
        else:  # the closed form, checked by the quadrature where E − V_eff keeps figures
            closed = core.apsidal_angle_inverse_cube(self.L0, mu, eps)
            a["apsidal_angle_closed_form"] = closed
            if a["eccentricity"] >= self.FAMILY_MIN_E_QUADRATURE:
                exact = core.apsidal_angle(self.energy0, self.L0, mu, k, n, eps)
                results.checks.append(Check("apsidal angle by quadrature", exact, closed,
                                            "rad", "π/√(1 − 2με/L²) (Landau & Lifshitz §15, "
                                                   "problem 3)"))
            else:
                exact, method = closed, "closed form"
        a["apsidal_angle_exact"] = exact
        a["apsidal_angle_exact_method"] = method
        a["apsidal_angle_family"] = self._apsidal_angle_family(a["eccentricity"])
        period = a["period"]
        if not self._passages_resolved(a["eccentricity"], period):
            a["apsidal_angle_note"] = ("fewer than two resolved pericentre passages: "
                                       "the apsidal angle was not measured from the run")
            return
        tp, _rp, phi = core.apsides_from_samples(main.t, main["x"], main["y"], main["vx"],
                                                 main["vy"], mu, k, n, eps)
        if tp.size < 2:
            return
        sweep = abs(phi[-1] - phi[0]) / (tp.size - 1)  # angle between pericentres = 2 × apsidal
        a["apsidal_angle_measured"] = 0.5 * sweep
        a["pericentre_times"] = tp
        a["pericentre_positions"] = {"x": np.interp(tp, main.t, main["x"]),
                                     "y": np.interp(tp, main.t, main["y"])}
        results.checks.append(Check("apsidal angle measured (pericentre to pericentre / 2)",
                                    0.5 * sweep, exact, "rad",
                                    "∫ (L/μr²) dr/ṙ from rₘᵢₙ to rₘₐₓ, Goldstein (3.37)"))
        t_meas = (tp[-1] - tp[0]) / (tp.size - 1)
        a["period_measured"] = t_meas
        results.checks.append(Check("radial period from pericentre passages", t_meas, period,
                                    "s", "2 ∫ dr/ṙ from rₘᵢₙ to rₘₐₓ, Goldstein (3.17)"))

    #: the apsidal-angle family spans e from the circle (the power law; the 1/r³ term's
    #: quadrature from FAMILY_MIN_E_QUADRATURE, where E − V_eff still has figures to lose)
    #: to this orbit's e × FAMILY_REACH, at least FAMILY_MIN_SPAN
    FAMILY_REACH, FAMILY_MIN_SPAN, FAMILY_MIN_E_QUADRATURE = 1.15, 0.1, 0.02

    def _apsidal_angle_family(self, e0: float) -> dict:
        """Exact apsidal angle against eccentricity at this L, from near-circular orbits up
        to a little beyond this orbit's (bound orbits only)."""
        top = min(max(self.FAMILY_REACH * e0, self.FAMILY_MIN_SPAN), max(0.98, e0))
        if self.config.params.potential == "power":
            ecc = np.unique(np.append(np.linspace(0.0, top, 40), e0))
            return {"eccentricity": ecc,
                    "angle": exact_apsides.apsidal_angle_family_power(ecc, self.n)}
        # V = −k/r − ε/r²: Kepler's radial motion with L² → C = L² − 2με; r_min = p/(1 + e),
        # E = −μk²(1 − e²)/(2C) (p = C/(μk)); the quadrature at each
        mu, L = self.mu, self.L0
        k, n, eps = self.pot
        C = L * L - 2.0 * mu * eps
        ecc = np.linspace(self.FAMILY_MIN_E_QUADRATURE, top, 40)
        if e0 >= self.FAMILY_MIN_E_QUADRATURE:
            ecc = np.unique(np.append(ecc, e0))
        ang = [core.apsidal_angle(-mu * k * k * (1.0 - e * e) / (2.0 * C), L, mu, k, n, eps)
               for e in ecc]
        return {"eccentricity": ecc, "angle": np.array(ang)}
