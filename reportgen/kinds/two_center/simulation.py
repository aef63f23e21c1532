"""``two_center`` simulation: the orbit (Cartesian or regularized), its two constants
and the coordinate lines that bound it; a sweep member's crossings of y = 0 and the
family's predicted curves on that surface of section."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.config import ConfigError
from ...scene.content import fmt, member_text
from ...scene.integration import IntegratingSimulation
from ...scene.results import Check, Results
from ...scene.sweep import PointSet
from .config import CLOSE_APPROACH, TwoCenterConfig
from .results import SCHEMA

core = lazy_module("reportgen.core.models.two_center")
regularized = lazy_module("reportgen.core.models.two_center_regularized")
integrators = lazy_module("reportgen.core.integrators")


#: the orbit's motion in the plane, notes (7.59), from E, β and the ξ quadratic at the
#: segment between the centres (:func:`motion_class`), in words for the behaviour line;
#: the classes are named as in the literature (Charlier 1902; Waalkens, Dullin & Richter,
#: Physica D 196 (2004)): satellite about one centre, planetary round both, lemniscate
#: through the segment between them
BEHAVIOUR = {
    "one_centre": "bound: a satellite orbit on one side of the mid-line, about the centre "
                  "at {centre}",
    "both_centres": "bound: a planetary orbit around both centres, between two confocal "
                    "ellipses",
    "through_middle": "bound: a lemniscate orbit through the segment between the centres, "
                      "turning about them in alternating senses",
    "escape": "escape: unbound (E ≥ 0), the particle leaves the centres",
}


def motion_class(E: float, beta: float, mu: float, a: float, x0: float) -> dict:
    """How the orbit moves in the plane, from its constants (notes (7.59)).

    (1 − η²) p_η² = −β − 2a²E η² and (ξ² − 1) p_ξ² = 2a²E ξ² + 4aμ ξ + β =: q(ξ):

    * E ≥ 0: ``"escape"`` (q has no upper root; ξ grows without bound);
    * β > 0: ``"one_centre"`` (a satellite orbit): |η| ≥ η* > 0 keeps η, and so x = a ξ η,
      of one sign: the orbit stays on the side of its start, about the centre there
      (``side`` = ±1);
    * β ≤ 0, q(1) < 0: ``"both_centres"`` (a planetary orbit): η free, ξ between two roots
      > 1: a ring between two confocal ellipses, round both centres, never on the segment
      ξ = 1 between them;
    * β ≤ 0, q(1) ≥ 0: ``"through_middle"`` (a lemniscate orbit): ξ reaches 1, the
      segment between the centres, which the orbit crosses (each crossing reverses its
      sense of turning).

    The same cases as the ``family`` of
    :func:`reportgen.core.models.two_center.coordinate_bounds`.

    The thresholds are E = 0, β = 0 and q(1) = 2a²E + 4aμ + β = 0 (stored as
    ``segment_reach``)."""
    q1 = 2.0 * a * a * E + 4.0 * a * mu + beta
    if E >= 0.0:
        motion = "escape"
    elif beta > 0.0:
        motion = "one_centre"
    elif q1 < 0.0:
        motion = "both_centres"
    else:
        motion = "through_middle"
    side = (1 if x0 > 0 else -1) if motion == "one_centre" else 0
    return {"motion": motion, "segment_reach": float(q1), "side": side}


class TwoCenterSimulation(IntegratingSimulation):
    """A test particle in the field of two fixed centres, checked against E and C (notes (7.59))."""

    schema = SCHEMA
    config: TwoCenterConfig

    #: the surface of section: the line through the centres, crossed with ẏ > 0, drawn in
    #: (x, ẋ); as archived in ``/sweep/points/poincare`` attrs (column, value, direction)
    SURFACE = ("y", "0.0", "up")
    AXES = ("x", "vx")
    #: grid points per axis of C(x, ẋ) on the section (the predicted curves)
    SECTION_GRID = 301
    #: margin of that grid around the crossings, as a fraction of their span
    SECTION_MARGIN = 0.08

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
        where = (f"the region of the motion, notes (7.59), comes within {reach:.3g} of a centre"
                 if reach > 0 else "the region of the motion, notes (7.59), holds a centre")
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
        a.update(motion_class(E, bounds["beta"], p.mu, p.a, float(y0[0])))
        if not self.family_member:  # physical behaviour, not a status
            a["behaviour"] = BEHAVIOUR[a["motion"]].format(
                centre=f"({fmt(a['side'] * p.a)}, 0)".replace("-", "−"))
            if a["closest_approach_bound"] <= 0.0:
                a["behaviour"] += "; its region reaches a centre (collision orbit)"
        if crossings is not None:
            a.update(self._section_analysis(*crossings))
        scales = self._scales()
        for name, label in (("energy", "energy E(t_end)"),
                            ("separation_constant", "separation constant C(t_end)")):
            v = main.invariants[name]
            results.checks.append(Check(label, float(v[-1]), float(v[0]), "",
                                        "value at t = 0, conserved, notes (7.59); error "
                                        "relative to max(|L₁L₂|, 2aμ)"
                                        if name != "energy" else "E(0), conserved",
                                        scale=scales[name]))
        if bounds["family"] != "unbound":
            results.checks.append(Check("largest ξ reached by the run (sampled)",
                                        float(np.max(xi)), bounds["xi_max"], "",
                                        "largest root of 2a²Eξ² + 4aμξ + β, notes (7.59)"))
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
        return PointSet.section_crossings(results, core.COLUMNS, cls.SURFACE, cls.AXES)

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
                "C(0) of the orbit, conserved, notes (7.59)", scale=scale))
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

    def _coordinate_lines(self, xi, eta, bounds) -> dict:
        """The elliptic-coordinate grid drawn under the orbit, and the coordinate lines
        that bound the motion (p_ξ = 0 or p_η = 0), as (x, y) curves.

        ``elliptic_grid``: ellipses ξ = const out to a little beyond the orbit and
        hyperbolas η = const (both branches, y ≥ 0 then y ≤ 0) out to the largest
        ellipse.  ``motion_bounds``: the ξ bounds > 1 and, for a satellite orbit, the
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
