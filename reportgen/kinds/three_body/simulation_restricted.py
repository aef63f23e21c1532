"""``three_body`` with ``[restricted]``: the planar circular restricted problem in the
rotating frame (Murray & Dermott ch. 3).

A run integrates the test particle in the Thiele–Burrau variables, regular at both
primaries (:mod:`reportgen.core.models.restricted_three_body`): DOP853 in the fictitious
time s, dt/ds = r1 r2, its outputs located at the physical times.  So a close approach to
a primary -- frequent on the chaotic orbits of a surface of section -- costs neither a
collapsing step nor accuracy, and no member has to be stopped.  A named method other than
DOP853 integrates the Cartesian equations instead (a single run only: a sweep's members
locate their crossings of y = 0 on DOP853's steps).

The Jacobi constant C = 2Ω − v² is the run's invariant.  Its error is judged relative to
its term 2Ω at the same point (next to a primary both terms grow as 2/r, and the C of a
state loses digits in proportion): a run whose worst error exceeds ``energy_tolerance`` is
flagged unstable.
"""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from ...scene.config import ConfigError
from ...scene.content import fmt, member_text
from ...scene.integration import IntegratingSimulation
from ...scene.results import Check, Results
from ...scene.sweep import PointSet

core = lazy_module("reportgen.core.models.restricted_three_body")
integrators = lazy_module("reportgen.core.integrators")

#: the family's section is computed by the members of a restricted sweep
SECTION = "restricted_section"


class RestrictedSimulation(IntegratingSimulation):
    """The ``[restricted]`` face of the three-body simulation (see the module docstring)."""

    #: grid points per axis of ẏ² on the section (its edge) and of 2Ω − C in the plane
    SECTION_GRID = 301
    PLANE_GRID = 401
    #: margin of the section's grid around the crossings, as a fraction of their span
    SECTION_MARGIN = 0.08
    #: half-widths of the plane drawn at least (every Lagrange point inside for μ ≤ 1/2)
    PLANE_HALF = (1.55, 1.55)

    # ----------------------------------------------------------------- config
    def build_models(self) -> None:
        """A restricted sweep's members locate their crossings of y = 0 on DOP853's steps:
        another named method is refused (exit 2) before anything runs (after the model's
        own check, which names what that method cannot integrate)."""
        super().build_models()
        if self.config.restricted is not None and self.wants_section(SECTION):
            method = self.config.run.method
            if method not in ("auto", "dop853"):
                raise ConfigError([
                    f"{self.source.label}: key 'run.method': a restricted [sweep] locates each "
                    f"member's crossings of y = 0 on the continuous extension of DOP853's "
                    f'steps in the regularized variables: expected "auto" or "dop853", got '
                    f"{method!r}"])

    def wants_section(self, name: str) -> bool:
        """The family's surface of section is wanted by a restricted sweep (and its
        members) whose config does not narrow ``[report] sections`` to leave it out."""
        if name == SECTION:
            asked = self.config.report.sections
            return (self.config.restricted is not None
                    and (self.sweep is not None or self.family_member)
                    and (asked is None or name in asked))
        return super().wants_section(name)

    def restricted_state(self) -> np.ndarray:
        return np.array(self.config.restricted.initial_state(), dtype=float)

    def restricted_formulation(self) -> tuple[str, str]:
        """("regularized" or "cartesian", why): DOP853 (auto) runs in the Thiele–Burrau
        variables; another named method in the Cartesian ones."""
        method = self.config.run.method
        if method in ("auto", "dop853"):
            return "regularized", (
                "Thiele–Burrau regularized variables z − d = (a/2) cosh(p + iq), dt/ds = r1 r2, "
                "regular at both primaries: DOP853 in s with each output located at its "
                "physical time")
        return "cartesian", f"method '{method}' named: the Cartesian equations of the " \
                            "rotating frame"

    # ------------------------------------------------------------- simulation
    def simulate_restricted(self, progress=None) -> Results:
        cfg, run = self.config, self.config.run
        mu, C = cfg.restricted.mu, cfg.restricted.jacobi_constant()
        y0 = self.restricted_state()
        t = np.linspace(0.0, run.t_end, run.samples)
        formulation, reason = self.restricted_formulation()
        wanted = self.family_member and self.wants_section(SECTION)
        results = Results()
        crossings = (np.zeros(0), np.zeros((0, 4)))
        if wanted:
            main, crossings = self._run_with_section(mu, C, y0, t, reason, progress)
        else:
            scales: dict[str, float] = {}
            fictitious = None
            start = y0
            if formulation == "regularized":
                start = core.to_regularized(*y0, mu)
                fictitious = (core.T_INDEX, core.COLUMNS,
                              lambda states: core.from_regularized(states, mu))
            main = self.integrate(self.restricted_model(), start, t, progress=progress,
                                  invariants=self._jacobi_with_scale(mu, scales),
                                  invariant_scales=scales, method=run.method,
                                  method_reason=reason, fictitious_time=fictitious)
        main.attrs["formulation"] = formulation
        results.runs["main"] = main
        a = results.analysis
        a.update(self._jacobi_errors(main.y, crossings[1], mu, C))
        a["jacobi_tolerance"] = cfg.energy_tolerance
        a["mu"], a["jacobi_constant"], a["formulation"] = mu, C, formulation
        both = np.vstack([main.y[np.all(np.isfinite(main.y), axis=1)], crossings[1]])
        r1, r2 = core.distances(both[:, 0], both[:, 1], mu)
        a["closest_approach_1"], a["closest_approach_2"] = float(np.min(r1)), float(np.min(r2))
        points = core.lagrange_points(mu)
        a["region"] = gates_open(C, points)
        if wanted:
            a["poincare"] = {"t": crossings[0], "u": crossings[1][:, 0],
                             "v": crossings[1][:, 2], "state": crossings[1]}
        else:
            a["lagrange_points"] = _lagrange_arrays(points)
            a["zero_velocity"] = self._plane(mu, C, main.y)
            a["behaviour"] = self._confinement(mu, C, y0, a["zero_velocity"], a["region"])
            v = main.invariants["jacobi_constant"]
            results.checks.append(Check("Jacobi constant C(t_end)", float(v[-1]), float(v[0]),
                                        "", "C(0), conserved (Murray & Dermott §3.3)",
                                        scale=float(main.attrs["scale_jacobi_constant"])))
        tol = cfg.energy_tolerance
        if not (a["jacobi_error_relative"] <= tol):
            results.flag("unstable", f"Jacobi constant error {a['jacobi_error_relative']:.2e} "
                                     f"(relative to 2Ω) exceeds energy_tolerance = {tol:.0e}; "
                                     "tighten run.rtol")
        if not self.family_member:
            self._restricted_study(results, mu, C, y0, t)
        return results


    def restricted_model(self):
        """The model a run integrates: (R) in the Thiele–Burrau variables on the level of
        its Jacobi constant, or the Cartesian equations for another named method."""
        restricted = self.config.restricted
        if self.restricted_formulation()[0] == "regularized":
            return core.regularized_model(restricted.mu, restricted.jacobi_constant())
        return core.model(restricted.mu)

    def _run_with_section(self, mu, C, y0, t, reason, progress):
        """A sweep member's run in the Thiele–Burrau variables, stepped so that its
        crossings of y = 0 upward are located on each DOP853 step's continuous extension
        (there the line is p = 0 or sin q = 0).  Returns (the run in x, y, ẋ, ẏ, (times,
        (K, 4) states at the crossings))."""
        run = self.config.run
        reason += ("; stepped so that the crossings of y = 0 (the family's surface of section) "
                   "are located on each step's continuous extension")
        spec = integrators.SolverSpec(method="dop853", rtol=run.rtol, atol=run.atol,
                                      reason=reason)
        res = integrators.solve_fictitious_time(
            core.regularized_model(mu, C), core.to_regularized(*y0, mu), t, core.T_INDEX,
            spec, reason, progress=progress, section=core.REGULARIZED_AXIS_SECTION)
        scales: dict[str, float] = {}
        main = self.run_record(res, core.COLUMNS, y=core.from_regularized(res.solution.y, mu),
                               invariants=self._jacobi_with_scale(mu, scales),
                               invariant_scales=scales)
        found = res.solution.crossings
        if found is None or not len(found):
            return main, (np.zeros(0), np.zeros((0, 4)))
        return main, (found[:, 0], core.from_regularized(found[:, 1:], mu))

    @classmethod
    def _jacobi_with_scale(cls, mu, scales: dict):
        """The run's invariants callable: C along the stored states.  It also puts the scale
        of C's drift in ``scales`` (the largest term 2Ω of the run, known only from the
        states): the run's record computes the invariants first and reads the scales after,
        so the one dict serves as its ``invariant_scales``."""
        def jacobi(_, y):
            scales["jacobi_constant"] = cls._term_scale(y, mu)
            return cls._jacobi(y, mu)

        return jacobi

    @staticmethod
    def _jacobi(y, mu) -> dict[str, np.ndarray]:
        return {"jacobi_constant": core.jacobi_constant(*np.asarray(y).T, mu)}

    @staticmethod
    def _term_scale(y, mu) -> float:
        """The drift's scale: the largest term 2Ω of C over the finite samples (≥ |C|)."""
        y = np.asarray(y)
        y = y[np.all(np.isfinite(y), axis=1)]
        return float(np.max(2.0 * core.effective_potential(y[:, 0], y[:, 1], mu)))

    @staticmethod
    def _jacobi_errors(samples, crossings, mu, C) -> dict[str, float]:
        """The largest |C − C(0)| over the samples and crossings, and relative to 2Ω at the
        same point (NaN rows of a failed run left out)."""
        states = np.vstack([samples, crossings])
        states = states[np.all(np.isfinite(states), axis=1)]
        err = np.abs(core.jacobi_constant(*states.T, mu) - C)
        terms = np.maximum(2.0 * core.effective_potential(states[:, 0], states[:, 1], mu),
                           abs(C))
        return {"jacobi_error_max": float(np.max(err)),
                "jacobi_error_relative": float(np.max(err / terms))}

    def _plane(self, mu, C, y) -> dict[str, np.ndarray]:
        """2Ω − C on a grid of the plane holding the Lagrange points, the outer
        zero-velocity curve and the orbit."""
        outer = 1.1 * core.outer_zero_velocity_radius(mu, C)
        hx, hy = (max(h, outer) for h in self.PLANE_HALF)
        if y is not None and len(y):
            finite = y[np.all(np.isfinite(y), axis=1)]
            hx = max(hx, 1.05 * float(np.max(np.abs(finite[:, 0]))))
            hy = max(hy, 1.05 * float(np.max(np.abs(finite[:, 1]))))
        return core.zero_velocity_grid(mu, C, (-hx, hx, -hy, hy), self.PLANE_GRID)

    @staticmethod
    def _confinement(mu, C, y0, grid, region: str) -> str:
        """The behaviour in words: confined by the zero-velocity curve to the region of its
        start (the allowed cells connected to the start's do not reach the grid's edge),
        or free to reach the outside."""
        from scipy import ndimage

        allowed = np.asarray(grid["level"]) >= 0.0
        labels, _ = ndimage.label(allowed)
        # the allowed cell nearest the start (a start next to its zero-velocity curve may
        # fall in a cell whose centre the level forbids)
        gx, gy = np.meshgrid(grid["x"], grid["y"])
        gap = np.where(allowed, np.hypot(gx - y0[0], gy - y0[1]), np.inf)
        i, j = np.unravel_index(int(np.argmin(gap)), gap.shape)
        own = labels[i, j]
        edge = np.concatenate([labels[0], labels[-1], labels[:, 0], labels[:, -1]])
        gates = {"closed": "", "everywhere": "; the level forbids no region"}.get(
            region, f"; the zero-velocity curves open at {region}")
        if own and own not in edge:
            return (f"bound: the zero-velocity curve at C = {fmt(C, 6)} encloses the region "
                    f"of its start{gates}")
        return f"not confined: the region of its start at C = {fmt(C, 6)} reaches the " \
               f"outside{gates}"

    def _restricted_study(self, results, mu, C, y0, t):
        """Chaos (two Cartesian reference runs 1e-10 apart) and the error-against-run-time
        study of the Cartesian integrators against the regularized run at rtol 1e-14."""
        model = core.model(mu)
        horizon = self.divergence(results, model, y0, t)
        if horizon < t[-1]:
            results.analysis["study_t_end"] = horizon
        reference_model = core.regularized_model(mu, C)

        def reference(times):
            sol = integrators.solve_fictitious_time(
                reference_model, core.to_regularized(*y0, mu), times, core.T_INDEX,
                integrators.SolverSpec(method="dop853", rtol=1e-14, atol=1e-16), "").solution
            return core.from_regularized(sol.y, mu)

        self.study(results, model, y0, np.linspace(0.0, horizon, 201), reference=reference,
                   reference_kind="run in the regularized variables (Thiele–Burrau), "
                                  "dop853 rtol=1e-14 atol=1e-16")

    # ------------------------------------------------------------------ sweeps
    @staticmethod
    def restricted_points(results) -> dict[str, PointSet]:
        """A member's crossings of y = 0 (ẏ > 0): time, x, ẋ and the whole state there."""
        return PointSet.section_crossings(results, core.COLUMNS, ("y", "0.0", "up"),
                                          ("x", "vx"))

    def restricted_extras(self, sweep) -> dict:
        """The family's figures' data: the Lagrange points and 2Ω − C in the plane at the
        members' common C, and ẏ² on the section around the crossings (its zero is the
        section's edge).  Without a common C (C swept), only the Lagrange points."""
        mu = self.config.restricted.mu
        points = core.lagrange_points(mu)
        out = {"mu": mu, "lagrange_points": _lagrange_arrays(points)}
        C = _common(sweep.analysis.get("jacobi_constant"), sweep.ok)
        pts = sweep.points.get("poincare")
        if C is None or any(not p.startswith("restricted.") or p == "restricted.mu"
                            for p in sweep.values):
            return out
        out.update({"poincare_jacobi": C, "region": gates_open(C, points),
                    "zero_velocity": self._plane(mu, C, None)})
        if pts is None or not len(pts.member):
            return out

        def span(x):
            lo, hi = float(np.min(x)), float(np.max(x))
            pad = self.SECTION_MARGIN * max(hi - lo, 1e-9)
            return np.linspace(lo - pad, hi + pad, self.SECTION_GRID)

        u = np.asarray(pts.columns["u"])
        gu, gv = span(u), span(pts.columns["v"])
        U, V = np.meshgrid(gu, gv)
        with np.errstate(divide="ignore"):
            vy2 = np.minimum(core.section_vy2(U, V, C, mu), 4.0 * abs(C))
            # the edge of the crossings' own interval of y = 0 only: past the forbidden
            # gaps on either side lies another region's (the exterior's), never reached
            axis = core.section_vy2(gu, 0.0, C, mu) < 0.0
        gap_left = np.flatnonzero(axis & (gu < np.min(u)))
        gap_right = np.flatnonzero(axis & (gu > np.max(u)))
        if gap_left.size:
            vy2[:, :gap_left[-1]] = np.nan
        if gap_right.size:
            vy2[:, gap_right[0] + 1:] = np.nan
        out["poincare_grid"] = {"u": gu, "v": gv, "vy2": vy2}
        return out

    def restricted_checks(self, sweep) -> list[Check]:
        """The Jacobi constant at the stored crossings: the crossing furthest from its
        orbit's C(0) relative to 2Ω there, over all members; and, with ``jacobi`` given,
        the member whose C(0) is furthest from it."""
        checks = []
        pts = sweep.points.get("poincare")
        C0 = np.asarray(sweep.analysis.get("jacobi_constant", []), dtype=float)
        mu = self.config.restricted.mu
        if pts is not None and len(pts.member) and C0.size:
            state = np.asarray(pts.columns["state"])
            member = np.asarray(pts.member)
            C = core.jacobi_constant(*state.T, mu)
            terms = np.maximum(2.0 * core.effective_potential(state[:, 0], state[:, 1], mu),
                               np.abs(C0[member]))
            gap = np.where(np.isfinite(C), np.abs(C - C0[member]) / terms, np.inf)
            k = int(np.argmax(gap))
            i = int(member[k])
            checks.append(Check(
                f"Jacobi constant C at the crossings of y = 0, the furthest from its orbit's "
                f"C(0) relative to 2Ω there ({member_text(sweep, i)}, t = "
                f"{fmt(float(pts.columns['t'][k]), 6)})", float(C[k]), float(C0[i]), "",
                "C(0) of the orbit, conserved (Murray & Dermott §3.3)", scale=float(terms[k])))
        given = self.config.restricted.jacobi
        if given is not None and C0.size and "restricted.jacobi" not in sweep.values:
            gap = np.where(sweep.ok, np.abs(C0 - given), np.nan)
            if np.any(np.isfinite(gap)):
                i = int(np.nanargmax(gap))
                checks.append(Check(
                    f"C(0) of the member furthest from the configured C ({member_text(sweep, i)})",
                    float(C0[i]), float(given), "", "the configured Jacobi constant (ẏ solved "
                    "from it)", scale=abs(float(given))))
        return checks


def gates_open(C: float, points: dict) -> str:
    """Which gates of the zero-velocity curves the level C opens, in words for a label
    (≤ 40 characters): "closed" (C above every collinear point's), "L1", "L1 and L2",
    "L1, L2 and L3", or "everywhere" (below the triangular points' C, nothing forbidden)."""
    if C <= points["L4"][2]:
        return "everywhere"
    open_ = [k for k in ("L1", "L2", "L3") if C < points[k][2]]
    if not open_:
        return "closed"
    return open_[0] if len(open_) == 1 else ", ".join(open_[:-1]) + " and " + open_[-1]


def _lagrange_arrays(points: dict) -> dict[str, np.ndarray]:
    names = ("L1", "L2", "L3", "L4", "L5")
    return {"x": np.array([points[k][0] for k in names]),
            "y": np.array([points[k][1] for k in names]),
            "jacobi": np.array([points[k][2] for k in names])}


def _common(values, ok) -> float | None:
    """The members' common value (within rounding), or None if they differ."""
    v = np.asarray(values if values is not None else [], dtype=float)
    v = v[np.asarray(ok) & np.isfinite(v)] if v.size else v
    if v.size == 0 or np.ptp(v) > 1e-12 * max(float(np.max(np.abs(v))), 1.0):
        return None
    return float(np.median(v))


__all__ = ["SECTION", "RestrictedSimulation", "gates_open"]
