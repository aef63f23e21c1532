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

from ..config import ConfigError, Positive, Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import Check, Results
from ..sweep import PointSet
from .base import (
    Scene,
    SceneConfig,
    Section,
    SectionContent,
    fmt,
    fmt_err,
    member_text,
    section_colours,
    section_point_notes,
)

core = lazy_module("reportgen.core.models.two_center")
regularized = lazy_module("reportgen.core.models.two_center_regularized")
integrators = lazy_module("reportgen.core.integrators")
plots = lazy_module("reportgen.plots.gravitation")
section_plots = lazy_module("reportgen.plots.sections")

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
    vy: Real | None = Field(None, description="initial velocity y [m/s]; leave it out and give "
                                              "energy to have it solved for (vy ≥ 0)")
    energy: Real | None = Field(None, description="energy per unit mass E [m²/s²], instead of "
                                                  "vy: vy = +√(2(E − V(x, y)) − vx²), so that "
                                                  "a sweep's members share one energy")


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
        if (ini.vy is None) == (ini.energy is None):
            raise ValueError("initial.vy / initial.energy: give exactly one of them (got "
                             + ("both" if ini.vy is not None else "neither") + ")")
        if ini.energy is not None:
            floor = potential(ini.x, ini.y, self.params.mu, a) + 0.5 * ini.vx**2
            if ini.energy < floor:
                raise ValueError(f"initial.energy: must be at least V(x, y) + vx²/2 = "
                                 f"{floor:.12g} at the start, where vy would be imaginary "
                                 f"(got {ini.energy!r})")
        return self

    def initial_state(self) -> tuple[float, float, float, float]:
        """(x, y, vx, vy), vy solved for when ``initial.energy`` is given (vy ≥ 0)."""
        ini, p = self.initial, self.params
        if ini.vy is not None:
            return ini.x, ini.y, ini.vx, ini.vy
        vy2 = 2.0 * (ini.energy - potential(ini.x, ini.y, p.mu, p.a)) - ini.vx**2
        return ini.x, ini.y, ini.vx, math.sqrt(max(vy2, 0.0))


def potential(x: float, y: float, mu: float, a: float) -> float:
    """V = −μ/r1 − μ/r2 per unit mass at (x, y) (the config's check of initial.energy;
    the numerics use :mod:`reportgen.core.models.two_center`)."""
    return -mu / math.hypot(x + a, y) - mu / math.hypot(x - a, y)


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

    family_sections = (
        Section("poincare_family", "Surface of section y = 0 from many orbits",
                description="Every member's crossings of the line through the centres "
                            "(y = 0, ẏ > 0) in (x, ẋ), each orbit coloured by its swept "
                            "value, on the curves its energy and separation constant "
                            "predict.",
                points="poincare"),
    )

    #: self-checks of the members (shown in the family section instead) and the sampled
    #: ranges of ξ and |η| (the bounds from 7.59 up to sampling: noise against the swept
    #: value where a bound is 0 or 1)
    SWEEP_HIDDEN_RESULTS = ("poincare_*_error", "xi_range_run_*", "eta_abs_range_run_*")
    #: the surface of section: the line through the centres, crossed with ẏ > 0, drawn in
    #: (x, ẋ); as archived in ``/sweep/points/poincare`` attrs (column, value, direction)
    SURFACE = ("y", "0.0", "up")
    AXES = ("x", "vx")
    #: grid points per axis of C(x, ẋ) on the section (the predicted curves)
    SECTION_GRID = 301
    #: margin of that grid around the crossings, as a fraction of their span
    SECTION_MARGIN = 0.08
    #: members of a sweep told apart by a legend; more get a colour bar
    LEGEND_MEMBERS = 7
    #: marker area of a crossing [pt²]: an integrable family's crossings lie on curves
    #: that do not crowd one another, so they can be larger than in a chaotic sea
    MARKER_SIZE = 9.0

    #: the members compute their crossings only for the family's surface of section
    computed_on_request = ("error_vs_runtime", "poincare_family")

    def wants_section(self, name: str) -> bool:
        """The family's surface of section is wanted by a sweep (and its members) whose
        config does not narrow ``[report] sections`` to leave it out."""
        if name == "poincare_family":
            asked = self.config.report.sections
            return ((self.sweep is not None or self.family_member)
                    and (asked is None or name in asked))
        return super().wants_section(name)

    @classmethod
    def from_source(cls, source):
        """A sweep's members locate their crossings of y = 0 on DOP853's steps: a sweep
        that shows its surface of section with another named method is refused (exit 2)
        before anything runs."""
        scene = super().from_source(source)
        method = scene.config.run.method
        if scene.wants_section("poincare_family") and method not in ("auto", "dop853"):
            raise ConfigError([
                f"{source.label}: key 'run.method': a two_center [sweep] locates each member's "
                f"crossings of y = 0 (its surface of section) on the continuous extension of "
                f'DOP853\'s steps: expected "auto" or "dop853", got {method!r} (or leave '
                f"poincare_family out of [report] sections)"])
        return scene

    def _y0(self):
        return np.array(self.config.initial_state())

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
        crossings = None
        if self.family_member and self.wants_section("poincare_family"):
            main, crossings = self._run_with_section(model, formulation, reason, t, progress)
            if formulation == "regularized":
                model = core.model(p.mu, p.a)
        elif formulation == "regularized":
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
        if crossings is not None:
            a.update(self._section_analysis(*crossings))
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

    def _run_with_section(self, model, formulation: str, reason: str, t, progress):
        """A sweep member's run, stepped so that its crossings of y = 0 with ẏ > 0 are
        located on each DOP853 step's continuous extension (in t, or in s when
        regularized, where the line is p = 0 or sin q = 0).  Returns (the run, (times,
        (K, 4) states x, y, vx, vy at the crossings))."""
        run, p = self.config.run, self.config.params
        y0 = self._y0()
        if formulation == "regularized":
            start, index, section = (regularized.to_regularized(*y0, p.a), regularized.T_INDEX,
                                     regularized.AXIS_SECTION)
            convert = self._cartesian
        else:
            start, index, section, convert = y0, None, core.AXIS_SECTION, np.asarray
        reason = (f"{reason}; stepped so that the crossings of y = 0 (the family's surface of "
                  "section) are located on each step's continuous extension")
        spec = integrators.SolverSpec(method=run.method, rtol=run.rtol, atol=run.atol,
                                      reason=reason)
        res = integrators.solve_fictitious_time(model, start, t, index, spec, reason,
                                                progress=progress, section=section)
        main = self.run_record(res, core.COLUMNS, y=convert(res.solution.y),
                               invariants=self._invariants, invariant_scales=self._scales())
        found = res.solution.crossings
        return main, (found[:, 0], np.reshape(convert(found[:, 1:]), (-1, 4)))

    def _section_analysis(self, times, states) -> dict:
        """The crossings as the family's point set, and how far E and C at them are from
        their values at t = 0 (relative to the invariants' scales)."""
        p = self.config.params
        E, C = self._constants()
        scales = self._scales()
        out = {"poincare": {"t": times, "u": states[:, 0], "v": states[:, 2], "state": states},
               "formulation": self.formulation()[0]}
        if len(times):
            out["poincare_E_error"] = float(np.max(np.abs(
                core.energy(*states.T, p.mu, p.a) - E))) / scales["energy"]
            out["poincare_C_error"] = float(np.max(np.abs(
                core.separation_constant(*states.T, p.mu, p.a) - C))) / \
                scales["separation_constant"]
        return out

    # ------------------------------------------------------------------ sweeps
    @classmethod
    def member_points(cls, results) -> dict[str, PointSet]:
        """A member's crossings of y = 0 (ẏ > 0): time, x, ẋ and the whole state there."""
        pts = results.analysis.get("poincare")
        if pts is None:
            return {}
        return {"poincare": PointSet(
            columns={"t": pts["t"], "u": pts["u"], "v": pts["v"], "state": pts["state"]},
            components=tuple(core.COLUMNS),
            attrs={"surface": list(cls.SURFACE), "axes": list(cls.AXES)})}

    def sweep_extras(self, sweep) -> dict:
        """When every member has one energy E (and the centres are not swept): C(x, ẋ) on
        the section at that energy, on a grid around the crossings, for the curves
        C = C(member) each member's crossings must lie on, and ẏ² there (its zero is the
        edge of the region E allows).  NaN outside that region and next to the centres'
        lines x = ±a, where C jumps by 4aμ (so no contour is drawn along the jump)."""
        pts = sweep.points.get("poincare")
        energy = self._family_energy(sweep)
        if pts is None or not len(pts.member) or energy is None \
                or any(not path.startswith("initial.") for path in sweep.values):
            return {}
        p = self.config.params

        def span(x):
            lo, hi = float(np.min(x)), float(np.max(x))
            pad = self.SECTION_MARGIN * max(hi - lo, 1e-9)
            return np.linspace(lo - pad, hi + pad, self.SECTION_GRID)

        gu, gv = span(pts.columns["u"]), span(pts.columns["v"])
        U, V = np.meshgrid(gu, gv)
        C, vy2 = core.separation_constant_on_axis(U, V, energy, p.mu, p.a)
        step = gu[1] - gu[0]
        C = np.where((vy2 >= 0) & (np.abs(np.abs(U) - p.a) > 1.5 * step), C, np.nan)
        return {"poincare_grid": {"u": gu, "v": gv, "C": C, "vy2": vy2},
                "poincare_energy": energy}

    @staticmethod
    def _family_energy(sweep) -> float | None:
        """The members' common energy E, or None if they differ (beyond rounding)."""
        energy = np.asarray(sweep.analysis.get("energy", []), dtype=float)
        energy = energy[sweep.ok & np.isfinite(energy)] if energy.size else energy
        if energy.size == 0 or np.ptp(energy) > 1e-12 * max(float(np.max(np.abs(energy))),
                                                             1.0):
            return None
        return float(np.median(energy))

    def sweep_checks(self, sweep) -> list[Check]:
        """The second integral at the stored crossings: the crossing whose C is furthest
        from its orbit's C(0), over all members; and, with ``initial.energy``, the member
        whose E(0) is furthest from it (vy is solved for so that E = energy)."""
        checks = []
        pts = sweep.points.get("poincare")
        C0 = np.asarray(sweep.analysis.get("separation_constant", []), dtype=float)
        if pts is not None and len(pts.member) and C0.size:
            p = self.config.params
            state = np.asarray(pts.columns["state"])
            member = np.asarray(pts.member)
            C = core.separation_constant(*state.T, p.mu, p.a)
            gap = np.where(np.isfinite(C), np.abs(C - C0[member]), np.inf)
            k = int(np.argmax(gap))
            i = int(member[k])
            scale = self.member({path: float(v[i]) for path, v in sweep.values.items()}
                                )._scales()["separation_constant"]
            checks.append(Check(
                f"separation constant C at the crossings of y = 0, the furthest from its "
                f"orbit's C(0) ({member_text(sweep, i)}, t = {fmt(float(pts.columns['t'][k]), 6)})",
                float(C[k]), float(C0[i]), "",
                "C(0) of the orbit, conserved (7.59)", scale=scale))
        given = self.config.initial.energy
        energy = sweep.values.get("initial.energy")
        E0 = sweep.analysis.get("energy")
        if E0 is not None and (given is not None or energy is not None):
            energy = energy if energy is not None else np.full(sweep.size, float(given))
            gap = np.where(sweep.ok, np.abs(E0 - energy), np.nan)
            if np.any(np.isfinite(gap)):
                i = int(np.nanargmax(gap))
                checks.append(Check(
                    f"E(0) of the member furthest from its energy ({member_text(sweep, i)})",
                    float(E0[i]), float(energy[i]), "",
                    "initial.energy (vy solved so that E = energy)",
                    scale=max(abs(float(energy[i])), 1e-300)))
        return checks

    @classmethod
    def section_poincare_family(cls, data):
        sweep, a, p = data.sweep, data.analysis, data.config.params
        pts = sweep.points["poincare"]
        member = np.asarray(pts.member)
        kept = pts.counts(sweep.size)
        crossing, key, colour, labels = section_colours(sweep, pts, cls.LEGEND_MEMBERS)
        grid = a.get("poincare_grid")
        C0 = np.asarray(sweep.analysis["separation_constant"], dtype=float)
        levels = C0[crossing[sweep.ok[crossing]]]
        fig = section_plots.poincare_family(
            pts.columns["u"], pts.columns["v"], member, colour, "x [m]", "ẋ [m/s]",
            colour_label=key, labels=labels,
            edge=None if grid is None else (grid["u"], grid["v"], grid["vy2"], 0.0),
            edge_label=None if grid is None else
            f"ẏ = 0 on E = {fmt(a['poincare_energy'], 6)}",
            curves=None if grid is None else (grid["u"], grid["v"], grid["C"], levels),
            marker_size=cls.MARKER_SIZE, legend_below=True,
            curves_label=None if grid is None else "C(x, ẋ) = C of each orbit",
            lines=[(-p.a, "a centre, x = ±a"), (p.a, "a centre, x = ±a")])
        facts = [("orbits", f"{len(crossing)} of {sweep.size} members cross y = 0 upward"),
                 ("crossings drawn", f"{len(member)} ({int(kept[crossing].min())} to "
                                     f"{int(kept[crossing].max())} per orbit)")]
        for name, label in (("poincare_C_error", "separation constant C at the crossings"),
                            ("poincare_E_error", "energy E at the crossings")):
            error = sweep.analysis.get(name)
            if error is not None and np.any(np.isfinite(error)):
                facts.append((label, f"within {fmt_err(float(np.nanmax(error)))} of its value "
                                     "at t = 0, relative, on every orbit"))
        if "poincare_energy" in a:
            facts.append(("energy of every orbit", f"E = {fmt(a['poincare_energy'], 12)}"))
        formulation = sweep.labels.get("formulation")
        if formulation is not None:
            regularized_members = int(np.sum(np.asarray(formulation) == "regularized"))
            facts.append(("formulation", f"{len(formulation) - regularized_members} Cartesian, "
                                         f"{regularized_members} regularized (Thiele–Burrau)"))
        notes = section_point_notes(sweep, "poincare", kept, "cross y = 0 upward")
        if grid is None:
            notes.append("The members do not share one energy, so no predicted curves are "
                         "drawn: C(x, ẋ) on the section depends on E.")
        caption = ("Surface of section y = 0 crossed with ẏ > 0 (the line through the "
                   f"centres): (x, ẋ) at the crossings of {len(crossing)} orbits, each orbit in "
                   "its own colour " + (f"(keyed to {key})" if labels is None else "(legend)")
                   + ". The problem is integrable: each regular orbit's crossings lie on one "
                   "closed curve" + (", the grey curve C(x, ẋ) = C of the orbit at its energy; "
                                     "dark: ẏ = 0, the edge of the region the energy allows"
                                     if grid is not None else "") + ".")
        return SectionContent(figures=[cls.figure("poincare_family", fig, caption)],
                              facts=facts, notes=notes)

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
