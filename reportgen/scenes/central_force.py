r"""``central_force``: two bodies in a central potential and the Kepler problem (notes §3).

The relative coordinate r = r1 − r2 moves like one body of reduced mass
μ = m1 m2/(m1 + m2) in V(r) (3.18–3.22); the angular momentum L = μ r × ṙ is the
Noether charge of rotations (3.23–3.27); the radial motion sees the effective
potential V + L²/(2μr²) (3.28–3.31).  For V = −k/r the integration is checked
against Kepler's equation at every stored time, the third law and the
Laplace–Runge–Lenz vector; for other potentials the apsidal angle against the
exact quadrature and its near-circular limit π/√(2 − n).
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import AuditCase, Check, Results
from .base import Scene, SceneConfig, Section, SectionContent, Table, fmt, fmt_err

core = lazy_module("reportgen.core.models.kepler")
plots = lazy_module("reportgen.plots.gravitation")
common_plots = lazy_module("reportgen.plots.common")
integrators = lazy_module("reportgen.core.integrators")  # its method list imports no numba


class Params(Strict):
    m1: Positive = Field(description="mass of body 1 [kg]")
    m2: Positive = Field(description="mass of body 2 [kg]")
    k: Positive = Field(description="strength of the attraction, V = −k/r (or −k/rⁿ) [J·mⁿ]")
    potential: Literal["kepler", "power", "kepler_inverse_cube"] = Field(
        "kepler", description='"kepler" V = −k/r; "power" V = −k/rⁿ; '
                              '"kepler_inverse_cube" V = −k/r − ε/r²')
    n: Real | None = Field(None, description="exponent of the power law V = −k/rⁿ, 0 < n < 2")
    epsilon: Real | None = Field(None, description="strength ε of the −ε/r² term (a 1/r³ force)"
                                                   " [J·m²]")


class Initial(Strict):
    x: Real = Field(description="relative position r = r1 − r2, x [m]")
    y: Real = Field(description="relative position, y [m]")
    vx: Real = Field(description="relative velocity, x [m/s]")
    vy: Real = Field(description="relative velocity, y [m/s]")


class CentralForceConfig(SceneConfig):
    params: Params
    initial: Initial
    run: RunConfig

    @model_validator(mode="after")
    def _physics(self):
        p, ini = self.params, self.initial
        if p.potential == "power":
            if p.n is None:
                raise ValueError("params.n: required when params.potential = \"power\"")
            if not 0.0 < p.n < 2.0:
                raise ValueError(f"params.n: must satisfy 0 < n < 2 for V = −k/rⁿ (bound "
                                 f"orbits need an attraction weaker than 1/r³; got {p.n})")
        elif p.n is not None:
            raise ValueError(f"params.n: only used with params.potential = \"power\" "
                             f"(potential is {p.potential!r})")
        if p.potential == "kepler_inverse_cube":
            if p.epsilon is None:
                raise ValueError("params.epsilon: required when params.potential = "
                                 "\"kepler_inverse_cube\"")
        elif p.epsilon is not None:
            raise ValueError(f"params.epsilon: only used with params.potential = "
                             f"\"kepler_inverse_cube\" (potential is {p.potential!r})")
        if ini.x == 0.0 and ini.y == 0.0:
            raise ValueError("initial.x / initial.y: the bodies start at the same point "
                             "(r = 0, a collision)")
        mu = p.m1 * p.m2 / (p.m1 + p.m2)  # reduced mass (validation imports no numerics)
        L = mu * (ini.x * ini.vy - ini.y * ini.vx)
        if L == 0.0:
            raise ValueError("initial.x, initial.y, initial.vx, initial.vy: zero angular "
                             "momentum (r ∥ v): a radial orbit that ends in a collision")
        method = integrators.METHODS.get(self.run.method)
        if method is not None and method.needs_kepler:
            # the regularization is of the 1/r potential's bound orbits (core/integrators/
            # regularized.py): refused here, before anything runs, for any other
            name = self.run.method
            if p.potential != "kepler":
                raise ValueError(f"run.method: \"{name}\" integrates only the "
                                 f"inverse-square force, params.potential = \"kepler\" "
                                 f"(got potential {p.potential!r})")
            energy = 0.5 * mu * (ini.vx**2 + ini.vy**2) - p.k / math.hypot(ini.x, ini.y)
            if energy >= 0.0:
                raise ValueError(f"run.method: \"{name}\" needs a bound orbit, E < 0 "
                                 f"(got E = {energy:.6g} J)")
        if p.potential == "kepler_inverse_cube" and L**2 <= 2.0 * mu * p.epsilon:
            raise ValueError(f"params.epsilon: L² ≤ 2 μ ε (L² = {L**2:.6g}, 2με = "
                             f"{2 * mu * p.epsilon:.6g}): the orbit spirals into the centre")
        return self


class CentralForceScene(Scene):
    kind = "central_force"
    order = 30
    summary = "two bodies in a central potential: reduced mass, Noether charge, Kepler checks"
    Config = CentralForceConfig
    presets = {
        "kepler_e07": {"params": {"m1": 1.0, "m2": 1.0, "k": 0.5},
                       "initial": {"x": 0.3, "y": 0.0, "vx": 0.0,
                                   "vy": math.sqrt(1.7 / 0.3)},
                       "run": {"t_end": 10 * 2 * math.pi, "samples": 4001}},
    }
    family_sections = (
        Section("kepler_family", "Period against eccentricity across the family",
                description="Each bound member's period, measured from its orbit, against "
                            "Kepler's third law T = 2π √(a³/(k/μ))."),
    )
    sections = (
        Section("orbit", "The relative orbit", integrates=True),
        Section("two_body", "Reduced mass and the centre of mass", integrates=True),
        Section("effective_potential", "Effective potential and turning points"),
        Section("kepler", "Kepler's equation, third law and the Laplace–Runge–Lenz vector",
                integrates=True),
        Section("apsides", "Apsidal angle", integrates=True),
        Section("invariants", "Conserved quantities", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def section_kepler_family(cls, data):
        sweep = data.sweep
        a = sweep.analysis
        need = ("eccentricity", "period", "period_measured")
        if not all(k in a for k in need):
            return SectionContent(notes=["No member has a period measured from its orbit: "
                                         "the potential is not 1/r, no member is bound, or "
                                         "the runs are shorter than two orbits (or resolve "
                                         "a pericentre passage with too few samples)."])
        ok = sweep.ok & np.isfinite(a["period_measured"]) & np.isfinite(a["period"])
        fig = common_plots.family_against_reference(
            a["eccentricity"][ok], a["period_measured"][ok], a["period"][ok],
            xlabel="eccentricity e", ylabel="period T", measured_label="measured from the orbit",
            exact_label="third law 2π√(a³/(k/μ))")
        rel = np.abs(a["period_measured"][ok] / a["period"][ok] - 1)
        facts = [("bound members with a period", f"{int(ok.sum())} of {sweep.size}")]
        if rel.size:
            facts.append(("max relative difference to the third law", fmt_err(float(rel.max()))))
        return SectionContent(figures=[cls.figure(
            "kepler_family", fig, "Each member's period against its eccentricity: measured "
            "from the orbit and from Kepler's third law with its own semi-major axis; below, "
            "their relative difference.")], facts=facts)

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

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        is_kepler = data.config.params.potential == "kepler"
        bound = data.analysis["bound"] == "yes"
        if not (is_kepler and bound):
            names.remove("kepler")
        if is_kepler or not bound:
            names.remove("apsides")
        return names

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
        """Eccentricity, semi-major axis, period: Kepler elements, or from the turning points."""
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
            out.update(apocentre=r_max, eccentricity=(r_max - r_min) / (r_max + r_min),
                       semi_major_axis=0.5 * (r_max + r_min),
                       period=core.radial_period(self.energy0, self.L0, self.mu, *self.pot))
        return out

    def models(self) -> list:
        return [core.model(self.config.params.k, self.mu, self.n, self.epsilon)]

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
        elif self.bound:
            self._apsides(results, main)
        e_inv = main.invariants["energy"]
        results.checks.append(Check("energy E(t_end)", float(e_inv[-1]), float(e_inv[0]), "J",
                                    "E(0), conserved", scale=self._invariant_scales()["energy"]))
        L_inv = main.invariants["angular_momentum"]
        results.checks.append(Check("angular momentum L(t_end)", float(L_inv[-1]),
                                    float(L_inv[0]), "kg·m²/s", "L(0), Noether charge (3.27)"))
        ref = None
        if self.is_kepler and self.bound:
            el = self.elements

            def ref(ts):
                return np.column_stack(core.kepler_state(ts, el))
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201), reference=ref)
        return results

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
        results.checks.append(Check("max |r − r_Kepler| over the run", float(np.max(err)), 0.0,
                                    "m", "Kepler's equation E − e sin E = M (Danby §6.6)",
                                    scale=scale))
        mu, k = self.mu, self.config.params.k
        ax, ay = main.invariants["lrl_x"], main.invariants["lrl_y"]
        e_lrl = np.hypot(ax, ay) / (mu * k)
        a["lrl_eccentricity_error"] = e_lrl - el["eccentricity"]
        a["lrl_eccentricity_drift"] = float(np.max(np.abs(e_lrl - el["eccentricity"])))
        results.checks.append(Check("|A|/(μk) at t_end (LRL vector)", float(e_lrl[-1]),
                                    el["eccentricity"], "", "e of the initial state, |A| = μke "
                                    "(Goldstein eq. 3.83)", scale=1.0))
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
                                            "s", "third law T = 2π√(a³/(k/μ)) (3.31)"))
                a_meas = 0.5 * (float(np.mean(rp)) + float(np.mean(ra)))
                a["semi_major_axis_measured"] = a_meas
                results.checks.append(Check("semi-major axis (r_min + r_max)/2 measured", a_meas,
                                            el["semi_major_axis"], "m",
                                            "a = −k/(2E) (Goldstein eq. 3.61)"))
        else:
            a["period_measured_note"] = (
                "period not measured from the samples: a pericentre passage spans fewer than "
                f"{self.MIN_SAMPLES_PER_PASSAGE} samples, the run is shorter than two orbits, "
                "or the orbit is a circle (no pericentre to time); the orbit is checked "
                "against Kepler's equation at every sample instead")

    def _apsides(self, results: Results, main) -> None:
        a, mu = results.analysis, self.mu
        k, n, eps = self.pot
        exact = core.apsidal_angle(self.energy0, self.L0, mu, k, n, eps)
        a["apsidal_angle_exact"] = exact
        if self.config.params.potential == "power":
            a["apsidal_angle_near_circular"] = core.apsidal_angle_near_circular(n)
        else:
            closed = core.apsidal_angle_inverse_cube(self.L0, mu, eps)
            a["apsidal_angle_closed_form"] = closed
            results.checks.append(Check("apsidal angle by quadrature", exact, closed, "rad",
                                        "π/√(1 − 2με/L²) (Landau & Lifshitz §15 problem 3)"))
        a["apsidal_angle_family"] = self._apsidal_angle_family()
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
                                    "∫ (L/μr²) dr/ṙ from r_min to r_max (Goldstein eq. 3.37)"))
        t_meas = (tp[-1] - tp[0]) / (tp.size - 1)
        a["period_measured"] = t_meas
        results.checks.append(Check("radial period from pericentre passages", t_meas, period,
                                    "s", "2 ∫ dr/ṙ from r_min to r_max (Goldstein eq. 3.17)"))

    def _apsidal_angle_family(self) -> dict:
        """Exact apsidal angle against eccentricity at this L, from near-circular orbits up
        to a little beyond this orbit's energy (bound orbits only)."""
        mu, L, E0 = self.mu, self.L0, self.energy0
        k, n, eps = self.pot
        rc = core.circular_radius(L, mu, k, n, eps)
        e_circ = float(core.effective_potential(rc, L, mu, k, n, eps))
        e_max = E0 + 0.3 * (E0 - e_circ) if E0 < 0 else E0
        energies = e_circ + (min(e_max, 0.0) - e_circ) * np.linspace(0.02, 0.97, 40) ** 2
        energies = np.unique(np.append(energies[energies < 0], E0))
        ecc, ang = [], []
        for E in energies:
            r1, r2 = core.turning_points(E, L, mu, k, n, eps)
            ecc.append((r2 - r1) / (r2 + r1))
            ang.append(core.apsidal_angle(E, L, mu, k, n, eps))
        return {"eccentricity": np.array(ecc), "angle": np.array(ang)}

    # ------------------------------------------------------------------ report
    @classmethod
    def headline(cls, data):
        p, a = data.config.params, data.analysis
        pot = {"kepler": "V = −k/r", "power": f"V = −k/r^{fmt(p.n)}",
               "kepler_inverse_cube": f"V = −k/r − ε/r², ε = {fmt(p.epsilon)}"}[p.potential]
        out = [("bodies", f"m1 = {fmt(p.m1)} kg, m2 = {fmt(p.m2)} kg, "
                          f"μ = {fmt(a['reduced_mass'])} kg"),
               ("potential", f"{pot}, k = {fmt(p.k)}"),
               ("energy, angular momentum", f"E = {fmt(a['energy'])} J, "
                                            f"L = {fmt(a['angular_momentum'])} kg·m²/s")]
        if "eccentricity" in a:
            out.append(("orbit", f"e = {fmt(a['eccentricity'])}, a = "
                                 f"{fmt(a['semi_major_axis'])} m"
                        + (f", period {fmt(a['period'], 12)} s" if "period" in a else "")))
        if "period_note" in a:
            out.append(("period", a["period_note"]))
        if "kepler_position_error_max" in a:
            out.append(("max |r − r_Kepler|", f"{fmt_err(a['kepler_position_error_max'])} m"))
        return out

    @classmethod
    def section_orbit(cls, data):
        run, a = data.runs["main"], data.analysis
        ref = lrl = peri = None
        if "kepler_orbit" in a:
            ref = (a["kepler_orbit"]["x"], a["kepler_orbit"]["y"])
            lrl = tuple(float(v) for v in a["eccentricity_vector"])
        elif "pericentre_positions" in a:
            peri = (a["pericentre_positions"]["x"], a["pericentre_positions"]["y"])
        fig = plots.relative_orbit(run["x"], run["y"], reference=ref, pericentres=peri, lrl=lrl)
        caption = "The relative orbit r(t) = r1 − r2 (3.21)."
        if lrl is not None:
            caption += (" Dashed: the exact ellipse from Kepler's equation; arrow: the "
                        "direction of the Laplace–Runge–Lenz vector, from the focus to the "
                        "pericentre (its length |A|/μk = e is given in the legend).")
        elif peri is not None:
            caption += " Triangles: pericentre passages, advancing by twice the apsidal angle."
        return SectionContent(figures=[cls.figure("orbit", fig, caption)])

    @classmethod
    def section_two_body(cls, data):
        p, a = data.config.params, data.analysis
        tracks = a["body_tracks"]
        fig = plots.two_body_tracks(tracks["r1"], tracks["r2"], m1=p.m1, m2=p.m2)
        facts = [("reduced mass μ = m1 m2/(m1 + m2) (3.20)", f"{fmt(a['reduced_mass'])} kg"),
                 ("r1 = (m2/M) r, r2 = −(m1/M) r (3.19)",
                  f"m2/M = {fmt(a['mass_fraction_m2'])}, m1/M = {fmt(a['mass_fraction_m1'])}")]
        return SectionContent(figures=[cls.figure(
            "two_body", fig, "Both bodies' tracks in the centre-of-mass frame (R = 0): "
            "similar conics scaled by m2/M and m1/M about the common focus, on opposite sides.")],
            facts=facts)

    @classmethod
    def section_effective_potential(cls, data):
        a = data.analysis
        r_min, r_max = (float(v) for v in np.asarray(a["turning_points"]))
        curve = a["effective_potential_curve"]
        rc = curve["circular_radius"]
        fig = plots.effective_potential(curve["r"], curve["potential"],
                                        curve["effective_potential"], energy=a["energy"],
                                        turning=(r_min, r_max),
                                        circular=(rc, curve["circular_energy"]))
        facts = [("turning points r_min, r_max", f"{fmt(r_min, 12)} m, {fmt(r_max, 12)} m"),
                 ("circular orbit at this L", f"r_c = {fmt(rc, 12)} m")]
        return SectionContent(figures=[cls.figure(
            "effective_potential", fig, "The radial motion in V_eff(r) = V(r) + L²/(2μr²) "
            "(3.28–3.30): the orbit stays where E ≥ V_eff, between the turning points.")],
            facts=facts)

    @classmethod
    def section_kepler(cls, data):
        run, a = data.runs["main"], data.analysis
        fig = common_plots.error_against_time(
            run.t, {"|r − r_Kepler| [m]": a["kepler_position_error"],
                    "| |A|/(μk) − e |": a["lrl_eccentricity_error"]}, ylabel="absolute error")
        rows = [["eccentricity e", fmt(a["eccentricity"], 14), "|A|/(μk) of the initial state"],
                ["semi-major axis a [m]", fmt(a["semi_major_axis"], 14), "−k/(2E)"],
                ["period T [s]", fmt(a["period"], 14), "2π√(a³ μ/k) (third law)"]]
        if "period_measured" in a:
            rows.append(["period measured [s]", fmt(a["period_measured"], 14),
                         f"rel. diff {fmt_err(abs(a['period_measured'] / a['period'] - 1))}"])
        if "semi_major_axis_measured" in a:
            rows.append(["(r_min + r_max)/2 measured [m]", fmt(a["semi_major_axis_measured"], 14),
                         "rel. diff " + fmt_err(abs(a["semi_major_axis_measured"]
                                                    / a["semi_major_axis"] - 1))])
        notes = [a["period_measured_note"]] if "period_measured_note" in a else []
        return SectionContent(
            figures=[cls.figure("kepler_error", fig, "Distance between the stored positions and "
                                "the solution of Kepler's equation at the same times, and the "
                                "change of the LRL vector's length.")],
            tables=[Table(caption="Orbit elements from the initial state and as measured",
                          header=["quantity", "value", "source"], rows=rows)],
            facts=[("max |r − r_Kepler|", f"{fmt_err(a['kepler_position_error_max'])} m"),
                   ("max |v − v_Kepler|", f"{fmt_err(a['kepler_velocity_error_max'])} m/s")],
            notes=notes)

    @classmethod
    def section_apsides(cls, data):
        a = data.analysis
        power = data.config.params.potential == "power"
        family = a["apsidal_angle_family"]
        if power:
            near, label = a["apsidal_angle_near_circular"], "exact quadrature at this L"
        else:
            near = a["apsidal_angle_closed_form"]
            label = "exact quadrature (= π/√(1 − 2με/L²) at every e)"
        measured = ((a["eccentricity"], a["apsidal_angle_measured"])
                    if "apsidal_angle_measured" in a else None)
        fig = plots.apsidal_angle_family(family["eccentricity"], family["angle"],
                                         near_circular=near, measured=measured,
                                         exact_label=label)
        if not power:
            fig.axes[0].get_lines()[1].set_label("closed form π/√(1 − 2με/L²)")
            fig.axes[0].legend(loc="best")
        rows = [["exact, quadrature (Goldstein eq. 3.37)", fmt(a["apsidal_angle_exact"], 13),
                 "—"]]
        if "apsidal_angle_measured" in a:
            rows.append(["measured from the run", fmt(a["apsidal_angle_measured"], 13),
                         fmt_err(abs(a["apsidal_angle_measured"] / a["apsidal_angle_exact"]
                                     - 1))])
        if "apsidal_angle_near_circular" in a:
            rows.append(["near-circular limit π/√(2 − n) (L&L §14)",
                         fmt(a["apsidal_angle_near_circular"], 13),
                         fmt_err(abs(a["apsidal_angle_near_circular"]
                                     / a["apsidal_angle_exact"] - 1))])
        if "apsidal_angle_closed_form" in a:
            rows.append(["closed form π/√(1 − 2με/L²) (L&L §15)",
                         fmt(a["apsidal_angle_closed_form"], 13),
                         fmt_err(abs(a["apsidal_angle_closed_form"]
                                     / a["apsidal_angle_exact"] - 1))])
        notes = [a["apsidal_angle_note"]] if "apsidal_angle_note" in a else []
        return SectionContent(
            figures=[cls.figure("apsidal_angle", fig, "Apsidal angle (pericentre to apocentre) "
                                "against eccentricity at this angular momentum.")],
            tables=[Table(caption="Apsidal angle [rad]", header=["source", "value",
                                                                  "rel. diff to exact"],
                          rows=rows)], notes=notes)

    @classmethod
    def section_invariants(cls, data):
        labels = {"energy": "energy E", "angular_momentum": "angular momentum L",
                  "lrl_x": "LRL A_x", "lrl_y": "LRL A_y"}
        return cls.invariants_section(data, labels=labels,
                                      caption="Drift of the conserved quantities: E and L "
                                              "relative to their size, the LRL components "
                                              "relative to μk.")
