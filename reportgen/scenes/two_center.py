r"""``two_center``: Euler's problem of two fixed centres in the plane (notes §7, 7.46–7.61).

A test particle attracted by two equal masses fixed at (±a, 0).  The motion
separates in elliptic coordinates ξ = (r1 + r2)/2a, η = (r1 − r2)/2a; besides the
energy E there is a second constant, the separation constant (7.59).  The report
draws the orbit over the elliptic-coordinate grid with the coordinate lines that
bound the motion, and checks both constants along the run.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import Check, Results
from .base import Scene, SceneConfig, Section, SectionContent, fmt, fmt_err

core = lazy_module("reportgen.core.models.two_center")
regularized = lazy_module("reportgen.core.models.two_center_regularized")
integrators = lazy_module("reportgen.core.integrators")
plots = lazy_module("reportgen.plots.gravitation")

#: ``formulation = "auto"`` regularizes a bound orbit whose region of motion (7.59) comes
#: within CLOSE_APPROACH·a of a centre.  Measured at rtol 1e-12 (μ = a = 1, outputs
#: every 0.01): the shipped planetary orbit (region reaching the centre, sampled closest
#: approach 0.044) has a max state error of 1.1e-6 in Cartesian DOP853 (2142 steps,
#: 1.7 ms) against 1.9e-8 regularized (776 steps, 2.4 ms); a fall from (2, 0) with
#: vy = 0.01 is 0.6 off (energy error 1e-4, 3773 steps) in Cartesian, 4e-9 (4e-10,
#: 321 steps, 0.9 ms) regularized; with vy ≤ 3e-3 the Cartesian step underflows.  Far
#: from the centres (the shipped satellite orbit, ≥ 0.89 a away) both are as accurate and
#: the Cartesian run is ~3x faster (481 vs 201 steps, but the transformed right-hand side
#: and the located outputs cost more per step and per output).
CLOSE_APPROACH = 0.1


class Params(Strict):
    mu: Positive = Field(description="G·M of each fixed centre [m³/s²]")
    a: Positive = Field(description="half the distance between the centres, at (±a, 0) [m]")


class Initial(Strict):
    x: Real = Field(description="initial position x [m]")
    y: Real = Field(description="initial position y [m]")
    vx: Real = Field(description="initial velocity x [m/s]")
    vy: Real = Field(description="initial velocity y [m/s]")


class TwoCenterRun(RunConfig):
    formulation: Literal["auto", "cartesian", "regularized"] = Field(
        "auto", description='"cartesian" (x, y, vx, vy in t), "regularized" (Thiele–Burrau '
                            'variables, dt/ds = r1 r2: regular at both centres; dop853 only) or '
                            '"auto": regularized when the orbit can come within '
                            f'{CLOSE_APPROACH:g}·a of a centre')

    @model_validator(mode="after")
    def _regularized_with_dop853(self):
        if self.formulation == "regularized" and self.method not in ("auto", "dop853"):
            raise ValueError(f'run.method: the regularized formulation integrates with dop853: '
                             f'expected "auto" or "dop853", got {self.method!r}')
        return self


class TwoCenterConfig(SceneConfig):
    params: Params
    initial: Initial
    run: TwoCenterRun

    @model_validator(mode="after")
    def _not_at_a_centre(self):
        ini, a = self.initial, self.params.a
        for sign in (-1, 1):
            if ini.y == 0.0 and ini.x == sign * a:
                raise ValueError(f"initial.x / initial.y: the particle starts at the centre "
                                 f"({sign * a:g}, 0) = (±params.a, 0) (a collision)")
        return self


FAMILY_TEXT = {
    "satellite": "satellite orbit: encircles both centres (β ≤ 0, η free in [−1, 1], "
                 "ξ between two ellipses)",
    "planetary": "planetary orbit: stays on one side, about one centre (β > 0, |η| ≥ η*)",
    "unbound": "unbound (E ≥ 0)",
}


FORMULATION_TEXT = {
    "cartesian": "Cartesian (x, y, vx, vy) in t",
    "regularized": "regularized: Thiele–Burrau variables z = a cosh(p + iq) in the "
                   "fictitious time dt/ds = r1 r2 (regular at both centres)",
}


class TwoCenterScene(Scene):
    kind = "two_center"
    order = 50
    summary = "Euler's problem of two fixed centres: elliptic coordinates, separation constant"
    Config = TwoCenterConfig
    sections = (
        Section("orbit", "Orbit over the elliptic-coordinate grid", integrates=True),
        Section("invariants", "Energy and the separation constant", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    def _y0(self):
        i = self.config.initial
        return np.array([i.x, i.y, i.vx, i.vy])

    def _constants(self):
        p = self.config.params
        y0 = self._y0()
        return (float(core.energy(*y0, p.mu, p.a)),
                float(core.separation_constant(*y0, p.mu, p.a)))

    def _scales(self):
        """Energy: |V| at the start; C: its two terms' size, L1 L2 and 2aμ."""
        p = self.config.params
        x, y, vx, vy = self._y0()
        r1, r2 = core.distances(x, y, p.a)
        L1, L2 = (x + p.a) * vy - y * vx, (x - p.a) * vy - y * vx
        return {"energy": float(p.mu / r1 + p.mu / r2),
                "separation_constant": float(max(abs(L1 * L2), 2 * p.a * p.mu))}

    def _invariants(self, t, y):
        p = self.config.params
        return {"energy": core.energy(*y.T, p.mu, p.a),
                "separation_constant": core.separation_constant(*y.T, p.mu, p.a)}

    def models(self) -> list:
        """The model the run integrates: Cartesian, or regularized (:meth:`formulation`)."""
        p = self.config.params
        if self.formulation()[0] == "regularized":
            return [regularized.initial_state(*self._y0(), p.mu, p.a)[0]]
        return [core.model(p.mu, p.a)]

    def formulation(self) -> tuple[str, str]:
        """("cartesian" or "regularized", why): the config's choice, or auto's (see
        ``CLOSE_APPROACH``): regularized for a bound orbit whose region of motion comes
        close to a centre, when the method is auto or dop853."""
        run, p = self.config.run, self.config.params
        if run.formulation != "auto":
            return run.formulation, f'[run] formulation = "{run.formulation}"'
        E, C = self._constants()
        reach = core.closest_approach_bound(E, C, p.mu, p.a)
        where = (f"the region of the motion (7.59) comes within {reach:.3g} of a centre"
                 if reach > 0 else "the region of the motion (7.59) holds a centre")
        if run.method not in ("auto", "dop853"):
            return "cartesian", f"method '{run.method}' named: Cartesian coordinates"
        if E < 0 and reach < CLOSE_APPROACH * p.a:
            return "regularized", (
                f"{where} (< {CLOSE_APPROACH:g}·a): Thiele–Burrau regularized variables "
                "z = a cosh(p + iq), dt/ds = r1 r2, regular at both centres; DOP853 in s "
                "with each output located at its physical time")
        why = "unbound orbit" if E >= 0 else f"{where} (≥ {CLOSE_APPROACH:g}·a)"
        return "cartesian", f"{why}: Cartesian coordinates"

    def _cartesian(self, states):
        """(N, 5) regularized states -> (N, 4) x, y, vx, vy."""
        return np.column_stack(regularized.from_regularized(states, self.config.params.a)[:4])

    def _regularized_reference(self, t):
        """The orbit at ``t`` from the regularized variables at rtol 1e-14 (the study's
        reference when the Cartesian references would cross a close approach)."""
        p = self.config.params
        model, z0 = regularized.initial_state(*self._y0(), p.mu, p.a)
        sol = integrators.solve_fictitious_time(
            model, z0, t, regularized.T_INDEX,
            integrators.SolverSpec(method="dop853", rtol=1e-14, atol=1e-16), "").solution
        return self._cartesian(sol.y)

    def simulate(self, progress=None) -> Results:
        run, p = self.config.run, self.config.params
        (model,) = self.models()
        y0 = self._y0()
        t = np.linspace(0.0, run.t_end, run.samples)
        results = Results()
        formulation, reason = self.formulation()
        if formulation == "regularized":
            z0 = regularized.to_regularized(*y0, p.a)
            main = self.integrate(model, z0, t, invariants=self._invariants,
                                  invariant_scales=self._scales(), progress=progress,
                                  method=run.method, method_reason=reason,
                                  fictitious_time=(regularized.T_INDEX, core.COLUMNS,
                                                   self._cartesian))
            model = core.model(p.mu, p.a)  # the study compares Cartesian integrators
        else:
            main = self.integrate(model, y0, t, invariants=self._invariants,
                                  invariant_scales=self._scales(), progress=progress)
        main.attrs["formulation"] = formulation
        results.runs["main"] = main
        E, C = self._constants()
        bounds = core.coordinate_bounds(E, C, p.mu, p.a)
        a = results.analysis
        a.update({"energy": E, "separation_constant": C, "beta": bounds["beta"],
                  "family": bounds["family"],
                  "xi_bounds": np.array([bounds["xi_min"], bounds["xi_max"]]),
                  "eta_abs_bounds": np.array([bounds["eta_abs_min"], bounds["eta_abs_max"]])})
        xi, eta = core.elliptic_coordinates(main["x"], main["y"], p.a)
        a["xi_range_run"] = np.array([float(np.min(xi)), float(np.max(xi))])
        a["eta_abs_range_run"] = np.array([float(np.min(np.abs(eta))),
                                           float(np.max(np.abs(eta)))])
        a.update(self._coordinate_lines(xi, eta, bounds))
        a["closest_approach_bound"] = core.closest_approach_bound(E, C, p.mu, p.a)
        a["closest_approach_run"] = float(np.min(p.a * (xi - np.abs(eta))))
        scales = self._scales()
        for name, label in (("energy", "energy E(t_end)"),
                            ("separation_constant", "separation constant C(t_end)")):
            v = main.invariants[name]
            results.checks.append(Check(label, float(v[-1]), float(v[0]), "",
                                        "value at t = 0, conserved (7.59)"
                                        if name != "energy" else "E(0), conserved",
                                        scale=scales[name]))
        if bounds["family"] != "unbound":
            results.checks.append(Check("ξ_max reached by the run (sampled)",
                                        float(np.max(xi)), bounds["xi_max"], "",
                                        "largest root of 2a²Eξ² + 4aμξ + β (7.59)"))
        t_study = np.linspace(0.0, run.t_end, 201)
        if formulation == "regularized":
            self.study(results, model, y0, t_study, reference=self._regularized_reference,
                       reference_kind="run in the regularized variables (Thiele–Burrau), "
                                      "dop853 rtol=1e-14 atol=1e-16")
        else:
            self.study(results, model, y0, t_study)
        return results

    def _coordinate_lines(self, xi, eta, bounds) -> dict:
        """The elliptic-coordinate grid drawn under the orbit, and the coordinate lines
        that bound the motion (p_ξ = 0 or p_η = 0), as (x, y) curves.

        ``elliptic_grid``: ellipses ξ = const out to a little beyond the orbit and
        hyperbolas η = const (both branches, y ≥ 0 then y ≤ 0) out to the largest
        ellipse.  ``motion_bounds``: the ξ bounds > 1 and, for a planetary orbit, the
        hyperbola |η| = η* on the orbit's side; for E > 0 the |η| limit on both sides.
        """
        a = self.config.params.a
        xi_top = max(float(np.max(xi)), 1.5) * 1.05
        xi_levels = np.linspace(1.0, xi_top, 8)[1:]
        eta_levels = np.linspace(-0.9, 0.9, 7)
        xi_bounds = [v for v in (bounds["xi_min"], bounds["xi_max"])
                     if math.isfinite(v) and v > 1.0]
        eta_bounds = []
        if bounds["eta_abs_min"] > 0:
            side = float(np.sign(np.mean(eta)))
            eta_bounds.append(side * bounds["eta_abs_min"])
        if bounds["eta_abs_max"] < 1:
            eta_bounds += [-bounds["eta_abs_max"], bounds["eta_abs_max"]]

        def curves(levels, hyperbolas):
            xs, ys = [], []
            for level in levels:
                if hyperbolas:
                    for sign in (1.0, -1.0):
                        x, y = core.coordinate_hyperbola(level, a, xi_top, sign=sign)
                        xs.append(x)
                        ys.append(y)
                else:
                    x, y = core.coordinate_ellipse(level, a)
                    xs.append(x)
                    ys.append(y)
            return {"x": np.array(xs), "y": np.array(ys)}

        out = {"elliptic_grid": {"xi_levels": xi_levels, "eta_levels": eta_levels,
                                 "ellipses": curves(xi_levels, False),
                                 "hyperbolas": curves(eta_levels, True)}}
        bound_lines = {}
        if xi_bounds:
            bound_lines["xi"] = np.array(xi_bounds)
            bound_lines["ellipses"] = curves(xi_bounds, False)
        if eta_bounds:
            bound_lines["eta"] = np.array(eta_bounds)
            bound_lines["hyperbolas"] = curves(eta_bounds, True)
        if bound_lines:
            out["motion_bounds"] = bound_lines
        return out

    @classmethod
    def headline(cls, data):
        p, a = data.config.params, data.analysis
        run = data.runs["main"]
        return [("centres", f"μ = {fmt(p.mu)} each at (±{fmt(p.a)}, 0)"),
                ("constants", f"E = {fmt(a['energy'], 12)}, C = "
                              f"{fmt(a['separation_constant'], 12)}, β = {fmt(a['beta'], 10)}"),
                ("orbit family", FAMILY_TEXT[a["family"]]),
                ("formulation", FORMULATION_TEXT.get(str(run.attrs.get("formulation")),
                                                     "Cartesian")),
                ("max relative drift", f"E {fmt_err(run.attrs.get('drift_energy', math.nan))}, "
                 f"C {fmt_err(run.attrs.get('drift_separation_constant', math.nan))}")]

    @classmethod
    def section_orbit(cls, data):
        run, a, p = data.runs["main"], data.analysis, data.config.params
        xi_b = [float(v) for v in np.asarray(a["xi_bounds"])]
        eta_b = [float(v) for v in np.asarray(a["eta_abs_bounds"])]

        def curves(group):
            return list(zip(group["x"], group["y"], strict=True))

        grid = a["elliptic_grid"]
        bound = a.get("motion_bounds", {})
        fig = plots.elliptic_grid_orbit(
            run["x"], run["y"], a=p.a,
            grid=curves(grid["ellipses"]) + curves(grid["hyperbolas"]),
            xi_bounds=curves(bound["ellipses"]) if "ellipses" in bound else None,
            eta_bounds=curves(bound["hyperbolas"]) if "hyperbolas" in bound else None)
        xr, er = np.asarray(a["xi_range_run"]), np.asarray(a["eta_abs_range_run"])
        facts = [("family", FAMILY_TEXT[a["family"]]),
                 ("ξ bounds from (7.59)", f"[{fmt(xi_b[0], 10)}, {fmt(xi_b[1], 10)}]; "
                                          f"sampled run: [{fmt(xr[0], 10)}, {fmt(xr[1], 10)}]"),
                 ("|η| bounds from (7.59)", f"[{fmt(eta_b[0], 10)}, {fmt(eta_b[1], 10)}]; "
                                            f"sampled run: [{fmt(er[0], 10)}, {fmt(er[1], 10)}]")]
        if "closest_approach_bound" in a:
            facts.append(("closest approach to a centre",
                          f"≥ {fmt(float(a['closest_approach_bound']), 6)} from (7.59); sampled "
                          f"run: {fmt(float(a['closest_approach_run']), 6)}"))
        return SectionContent(figures=[cls.figure(
            "orbit", fig, "The orbit over the elliptic-coordinate grid: confocal ellipses "
            "ξ = (r1 + r2)/2a = const and hyperbolas η = (r1 − r2)/2a = const with foci at the "
            "two centres. Bold: the coordinate lines where p_ξ = 0 or p_η = 0, which bound the "
            "motion.")], facts=facts)

    @classmethod
    def section_invariants(cls, data):
        return cls.invariants_section(data, labels={"energy": "energy E",
                                                    "separation_constant":
                                                        "separation constant C"},
                                      caption="Drift of E (relative to |V(0)|) and of the "
                                              "separation constant C (relative to "
                                              "max(|L1 L2|, 2aμ) at t = 0).")
