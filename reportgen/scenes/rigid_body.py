r"""``rigid_body``: the torque-free rigid body (lecture notes §8–10; textbook ch. 4).

Euler's equations (10.5) with the attitude quaternion, checked against the exact
solution in Jacobi elliptic functions (both branches L² ≷ 2E·I2) or, for a symmetric
body, the precession (10.9)–(10.10); polhodes on the angular-momentum sphere and on
the inertia ellipsoid (10.17) with the separatrices, Poinsot's construction (the
ellipsoid rolling on the invariable plane, the herpolhode), the stability of rotation
about each principal axis (10.12)–(10.14) with the Dzhanibekov flip, and a geometric
splitting integrator next to the general-purpose ones.

The body frame is the principal frame: with ``[params]`` the moments I1, I2, I3 are
given in any order; with a solid ``[shape]`` the shape's own x, y, z axes; with
``type = "points"`` the principal axes by diagonalization (ascending moments).
``initial.omega`` (and an ``[impulse]``) are components in that frame.

Tolerance: the shared default rtol = 1e-12 (atol 1e-14) keeps ω(t) within ~2e-10 of
the elliptic solution even for the Dzhanibekov preset, whose polhode passes close to the
separatrix; that is why this kind does not loosen it.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import AuditCase, Check, Results, RunRecord
from .base import Scene, SceneConfig, Section, SectionContent, Table, fmt, fmt_err
from .inertia import Shape, stability_table_section

inertia_core = lazy_module("reportgen.core.inertia")
core = lazy_module("reportgen.core.models.rigid_body")
study_core = lazy_module("reportgen.core.study")
splitting = lazy_module("reportgen.core.models.rigid_body_splitting")
poinsot = lazy_module("reportgen.core.models.rigid_body_poinsot")
common_plots = lazy_module("reportgen.plots.common")
plots = lazy_module("reportgen.plots.rigid_body")

#: ω0 within this angle of the intermediate axis: the scene is a Dzhanibekov demonstration
FLIP_ANGLE = 0.2


class Params(Strict):
    I1: Positive = Field(description="principal moment about body axis 1 [kg m²]")
    I2: Positive = Field(description="principal moment about body axis 2 [kg m²]")
    I3: Positive = Field(description="principal moment about body axis 3 [kg m²]")

    @model_validator(mode="after")
    def _triangle(self):
        # checked on the table itself, so it is reported together with problems elsewhere
        k = inertia_core.triangle_violation((self.I1, self.I2, self.I3))
        if k is not None:
            names = ["I1", "I2", "I3"]
            others = " + ".join(n for i, n in enumerate(names) if i != k)
            raise ValueError(f"params.{names[k]}: violates the triangle inequality "
                             f"{names[k]} ≤ {others} that every real body satisfies "
                             f"(got I1 = {self.I1}, I2 = {self.I2}, I3 = {self.I3})")
        return self


class Initial(Strict):
    omega: list[Real] = Field(description="[ω1, ω2, ω3] body-frame angular velocity [rad/s]")
    attitude: list[Real] = Field([1.0, 0.0, 0.0, 0.0],
                                 description="[w, x, y, z] unit quaternion body -> space")

    @model_validator(mode="after")
    def _lengths(self):
        if len(self.omega) != 3:
            raise ValueError(f"initial.omega: expected [ω1, ω2, ω3] (got {self.omega})")
        if len(self.attitude) != 4:
            raise ValueError(f"initial.attitude: expected [w, x, y, z] (got {self.attitude})")
        n = math.sqrt(sum(x * x for x in self.attitude))
        if abs(n - 1.0) > 1e-6:
            raise ValueError(f"initial.attitude: must be a unit quaternion, |q| = 1 within 1e-6 "
                             f"(got |q| = {n:.9g})")
        return self


class Impulse(Strict):
    """``[impulse]``: an impulse P applied at a point r of the body at t = 0 (exercise 4.6c)."""

    P: list[Real] = Field(description="[Px, Py, Pz] impulse, body frame [kg m/s]")
    at: list[Real] | Literal["apex"] = Field(
        description='[x, y, z] point of application relative to the CM, body frame [m], '
                    'or "apex" for a cone')


class Splitting(Strict):
    """``[splitting]``: the geometric integrator (free rotations about the principal axes)."""

    order: Literal[2, 4] = Field(4, description="2 (Strang) or 4 (Yoshida triple jump)")
    h: Positive | None = Field(None, description="step [s] (default: 1/200 of 2π/|ω0|)")


class RigidBodyConfig(SceneConfig):
    params: Params | None = None
    shape: Shape | None = None
    initial: Initial
    impulse: Impulse | None = None
    splitting: Splitting = Splitting()
    run: RunConfig

    @model_validator(mode="after")
    def _physics(self):
        if (self.params is None) == (self.shape is None):
            raise ValueError("params / shape: give either [params] I1, I2, I3 or a [shape] "
                             "table, not both and not neither")
        if self.shape is not None:
            for key in ("euler_angles", "about"):
                if getattr(self.shape, key) is not None:
                    raise ValueError(f"shape.{key}: not used by rigid_body (the body frame is "
                                     "the principal frame; set initial.attitude instead)")
        if self.impulse is not None:
            if len(self.impulse.P) != 3:
                raise ValueError(f"impulse.P: expected [Px, Py, Pz] (got {self.impulse.P})")
            at = self.impulse.at
            if at == "apex" and (self.shape is None or self.shape.type != "cone"):
                raise ValueError('impulse.at: "apex" needs a [shape] of type "cone"')
            if at != "apex" and len(at) != 3:
                raise ValueError(f"impulse.at: expected [x, y, z] (got {at})")
        return self


def body_moments(config: RigidBodyConfig) -> np.ndarray:
    """Principal moments along the body axes 1, 2, 3 (the configured order)."""
    if config.params is not None:
        p = config.params
        return np.array([p.I1, p.I2, p.I3])
    shape = config.shape
    if shape.type == "points":
        return inertia_core.principal_axes(shape.body_tensor())[0]
    return np.diag(shape.body_tensor()).copy()


class RigidBodyScene(Scene):
    kind = "rigid_body"
    order = 60
    computed_on_request = ("error_vs_runtime", "geometric_integrator", "polhode_ellipsoid",
                           "herpolhode")
    summary = "torque-free rigid body: Euler's equations, attitude, polhodes, axis stability"
    Config = RigidBodyConfig
    presets = {
        "dzhanibekov": {"title": "Dzhanibekov effect: flips about the intermediate axis",
                        "params": {"I1": 1.0, "I2": 2.0, "I3": 3.0},
                        "initial": {"omega": [0.01, 2.0, 0.01]},
                        "run": {"t_end": 40.0, "samples": 4001}},
        "symmetric_precession": {"title": "Symmetric body: precession of ω about the figure axis",
                                 "params": {"I1": 1.0, "I2": 1.0, "I3": 1.5},
                                 "initial": {"omega": [0.3, 0.0, 2.0]},
                                 "run": {"t_end": 30.0, "samples": 3001}},
        "cone_impulse": {"title": "Spinning cone struck at its apex (exercise 4.6c)",
                         "shape": {"type": "cone", "mass": 1.0, "radius": 0.5, "height": 2.0},
                         "initial": {"omega": [0.0, 0.0, 20.0]},
                         "impulse": {"P": [0.1, 0.0, 0.0], "at": "apex"},
                         "run": {"t_end": 5.0, "samples": 3001}},
        "octahedron_spin": {"title": "Octahedron spinning near its smallest-moment axis "
                                     "(exercise 4.9)",
                            "shape": {"type": "octahedron", "mass": 1.0, "a": 1.0, "b": 0.8,
                                      "c": 0.6},
                            "initial": {"omega": [4.0, 0.5, 0.5]},
                            "run": {"t_end": 20.0, "samples": 4001}},
    }
    sections = (
        Section("omega", "Angular velocity against the exact solution", integrates=True),
        Section("polhodes", "Polhodes on the angular-momentum sphere", integrates=True),
        Section("polhode_ellipsoid", "Polhodes on the inertia ellipsoid", integrates=True),
        Section("herpolhode", "Poinsot's construction: the inertia ellipsoid rolls on the "
                              "invariable plane", integrates=True),
        Section("stability", "Stability of rotation about the principal axes", integrates=True),
        Section("symmetric_precession", "Precession of the symmetric body", integrates=True),
        Section("geometric_integrator", "Splitting integrator (free rotations about the axes)",
                integrates=True),
        Section("invariants", "Conserved quantities", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def audit_cases(cls):
        # I = (1, 2, 3): L² = 2E·I2 when I1ω1²(I1 − I2) + I3ω3²(I3 − I2) = 0, i.e. ω1 = √3 ω3
        return [AuditCase(
            name="rigid body on the intermediate-axis separatrix",
            what="L² = 2E·I2 (to rounding): the elliptic parameter is 1, the motion creeps "
                 "towards the unstable intermediate axis and the exact solution degenerates",
            methods=("dop853", "gauss6"),
            config={"kind": "rigid_body", "title": "separatrix",
                    "params": {"I1": 1.0, "I2": 2.0, "I3": 3.0},
                    "initial": {"omega": [math.sqrt(3.0), 0.0, 1.0]},
                    "run": {"t_end": 30.0, "samples": 3001}})]

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        if "symmetric" not in data.analysis:
            names.remove("symmetric_precession")
        if data.analysis.get("spherical", False):
            # every direction is a principal axis: ω is constant, no polhodes to draw
            for name in ("polhodes", "polhode_ellipsoid", "herpolhode"):
                names.remove(name)
        if "splitting" not in data.runs:
            names.remove("geometric_integrator")
        return names

    # ----------------------------------------------------------------- helpers
    @property
    def moments(self) -> np.ndarray:
        return body_moments(self.config)

    @property
    def omega0(self) -> np.ndarray:
        """Initial body-frame ω after the impulse: ω + I⁻¹ (r × P)."""
        w = np.array(self.config.initial.omega, dtype=float)
        imp = self.config.impulse
        if imp is None:
            return w
        r = self.config.shape.apex() if imp.at == "apex" else np.asarray(imp.at, dtype=float)
        return core.omega_after_impulse(w, self.moments, r, imp.P)

    @property
    def symmetric(self):
        return core.symmetric_precession_rate(self.moments, self.omega0)

    @property
    def spherical(self) -> bool:
        I = self.moments
        return bool(np.ptp(I) <= 1e-13 * I.max())

    @property
    def intermediate_axis(self) -> int | None:
        I = self.moments
        order = np.argsort(I)
        if len(set(np.round(I / I.max(), 13))) < 3:
            return None
        return int(order[1])

    @property
    def is_flip_demo(self) -> bool:
        k = self.intermediate_axis
        if k is None:
            return False
        w = self.omega0
        return math.acos(min(1.0, abs(w[k]) / np.linalg.norm(w))) < FLIP_ANGLE

    def _invariants(self, t, y):
        return core.invariants(y, self.moments)

    def _scales(self, y0):
        I = self.moments
        L = float(np.linalg.norm(I * y0[:3]))
        return {"twice_energy": float(np.sum(I * y0[:3] ** 2)), "L_squared": L * L,
                "L_x": L, "L_y": L, "L_z": L, "quaternion_norm": 1.0}

    @property
    def splitting_step(self) -> float:
        h = self.config.splitting.h
        return h if h is not None else 2 * math.pi / float(np.linalg.norm(self.omega0)) / 200

    # -------------------------------------------------------------- simulation
    def wants_splitting(self) -> bool:
        """Whether the report will show the splitting integrator (only then is it run)."""
        return self.wants_section("geometric_integrator")

    def models(self) -> list:
        """The Euler–quaternion model (the splitting run is the scene's own method)."""
        return [core.model(*self.moments)]

    def simulate(self, progress=None) -> Results:
        run = self.config.run
        I, w0 = self.moments, self.omega0
        q0 = np.array(self.config.initial.attitude, dtype=float)
        q0 /= np.linalg.norm(q0)
        y0 = np.concatenate([w0, q0])
        spin = float(np.linalg.norm(w0))
        (model,) = self.models()
        t = np.linspace(0.0, run.t_end, run.samples)
        results = Results()
        scales = self._scales(y0)
        main = self.integrate(model, y0, t, invariants=self._invariants,
                              invariant_scales=scales, progress=progress)
        q_dev = float(np.max(np.abs(np.linalg.norm(main.y[:, 3:7], axis=1) - 1.0)))
        # the archived attitude is renormalized; the raw deviation is reported
        main.y[:, 3:7] /= np.linalg.norm(main.y[:, 3:7], axis=1, keepdims=True)
        results.runs["main"] = main
        exact = core.exact_omega(t, w0, I)
        err = np.abs(main.y[:, :3] - exact)

        stability = inertia_core.axis_stability(I, spin=spin)
        for k, s in enumerate(stability):
            s["growth_rate_jacobian"] = core.steady_rotation_growth_rate(I, k, spin)
        analysis = {
            "principal_moments": I,
            "axis_stability": {f"axis_{k + 1}": s for k, s in enumerate(stability)},
            "spin": spin,
            "spherical": self.spherical,
            "omega_initial": w0,
            "omega_max_error": float(np.max(err)),
            "quaternion_norm_max_deviation": q_dev,
            "twice_energy": scales["twice_energy"],
            "L_squared": scales["L_squared"],
        }
        if self.spherical:
            ref_source = "constant ω (spherical top)"
        elif self.symmetric is None:
            ell = core.elliptic_parameters(w0, I)
            analysis["elliptic"] = {k: ell[k] for k in ("branch", "lambda", "m", "period")}
            ref_source = "Jacobi elliptic solution (Landau & Lifshitz §37)"
        else:
            axis, Omega = self.symmetric
            analysis["symmetric"] = core.symmetric_precession_analysis(t, main.y[:, :3], I, axis,
                                                                       Omega)
            ref_source = "symmetric-body solution (10.9)–(10.10)"
        analysis["reference"] = ref_source
        main.reference = {c: exact[:, k] for k, c in enumerate(core.COLUMNS[:3])}
        main.attrs["reference_label"] = ref_source
        # polhodes on the L-sphere
        analysis["polhodes"] = {"family": core.polhode_family(I),
                                "separatrices": core.polhode_separatrices(I),
                                "track": core.polhode_track(main.y[:, :3], I)}
        for k in range(3):
            results.checks.append(Check(f"ω{k + 1}(t_end)", float(main.y[-1, k]),
                                        float(exact[-1, k]), "rad/s", ref_source, scale=spin))
        results.checks.append(Check("max |q| − 1 over the run (before renormalization)",
                                    1.0 + q_dev, 1.0, "", "unit quaternion"))
        k2 = self.intermediate_axis
        if k2 is not None:
            s = stability[k2]
            results.checks.append(Check(
                f"growth rate about the intermediate axis {k2 + 1} (Jacobian eigenvalue)",
                s["growth_rate_jacobian"], s["growth_rate"], "1/s",
                "Ω√((I2−I1)(I3−I2)/(I1 I3)), (10.14)"))
        if self.is_flip_demo:
            elliptic = analysis.get("elliptic")
            analysis["flip"] = core.flip_analysis(
                t, main.y[:, :3], k2, stability[k2]["growth_rate"],
                elliptic["period"] / 2.0 if elliptic else math.nan)
            f = analysis["flip"]
            if math.isfinite(f["half_period_measured"]):
                results.checks.append(Check("time between flips (zero crossings of ω_b)",
                                            f["half_period_measured"], f["half_period_exact"],
                                            "s", "2K(m)/λ of the elliptic solution"))
        if "symmetric" in analysis:
            sym = analysis["symmetric"]
            if math.isfinite(sym["Omega_measured"]):
                results.checks.append(Check("body-frame precession rate Ω",
                                            sym["Omega_measured"], sym["Omega"], "rad/s",
                                            "Ω = (I1 − I3) ω3 / I1, (10.10)"))
        self._poinsot_geometry(analysis, results, main)
        if self.wants_splitting():
            split = self._splitting_run(y0, t, scales)
            split.reference = dict(main.reference)
            split.attrs["reference_label"] = ref_source
            results.runs["splitting"] = split
            analysis["splitting_omega_max_error"] = float(
                np.max(np.abs(split.y[:, :3] - exact)))
        results.analysis.update(analysis)
        t_study = np.linspace(0.0, run.t_end, 201)
        self.study(results, model, y0, t_study, progress=progress)
        if results.study is not None and len(results.study):
            results.study = self._splitting_study(results.study, model, y0, t_study)
        return results

    def _poinsot_geometry(self, analysis, results, main) -> None:
        """Polhodes on the inertia ellipsoid and Poinsot's construction, each only if its
        section is shown (not for a spherical body, whose ω is constant)."""
        if self.spherical:
            return
        I = self.moments
        if self.wants_section("polhode_ellipsoid"):
            analysis["polhode_ellipsoid"] = poinsot.polhodes_on_ellipsoid(I, main.y[0, :3])
        if not self.wants_section("herpolhode"):
            return
        c = poinsot.poinsot_construction(main.y[:, :3], main.y[:, 3:7], I)
        height = c["herpolhode"][:, 2]
        c["plane_distance"] = -c["plane_height"]
        c["plane_distance_max_error"] = float(np.max(np.abs(height - c["plane_height"])))
        if self.symmetric is not None:
            axis, _ = self.symmetric
            r = poinsot.symmetric_herpolhode_radius(main.y[0, :3], I, axis)
            measured = np.hypot(c["herpolhode"][:, 0], c["herpolhode"][:, 1])
            worst = float(measured[np.argmax(np.abs(measured - r))])
            c["herpolhode_radius"] = r
            c["herpolhode_radius_max_error"] = abs(worst - r)
            results.checks.append(Check(
                "herpolhode radius (symmetric body), worst sample", worst, r, "1/√(kg m²)",
                "|I3 − I⊥| |ω3| ω⊥ / (|L| √(2T)) (Landau & Lifshitz §33)",
                scale=c["plane_distance"]))
        analysis["poinsot"] = c

    def _splitting_run(self, y0, t, scales) -> RunRecord:
        I = self.moments
        order, h = self.config.splitting.order, self.splitting_step
        _, _, compile_s = splitting.integrate_splitting(I, y0, t[:2], h, order)  # compile
        Y, nsteps, wall = splitting.integrate_splitting(I, y0, t, h, order)
        inv = core.invariants(Y, I)
        drift = {f"drift_{k}": float(np.max(np.abs(v - v[0])) / scales[k])
                 for k, v in inv.items()}
        ok = bool(np.all(np.isfinite(Y)))
        return RunRecord(t=t, y=Y, columns=list(core.COLUMNS), invariants=inv, attrs={
            "method": f"splitting{order}", "rtol": float("nan"), "atol": float("nan"),
            "h": float(h), "nfev": 0, "nsteps": nsteps, "nreject": 0, "wall_time_s": wall,
            "compile_time_s": compile_s,
            "method_reason": "explicit Lie–Poisson splitting into free rotations about the "
                             "principal axes (no function evaluations)",
            "status": "ok" if ok else "failed", "message": "" if ok else "non-finite state",
            **drift, **{f"scale_{k}": float(v) for k, v in scales.items()}})

    def _splitting_study(self, study, model, y0, t_eval):
        """Append rows for the splitting integrator (orders 2 and 4) to the study table.

        They share the study's budget like two more methods: each order's step ladder
        stops before a rung whose predicted cost (growth between the last two rungs)
        would overrun its part, as the study's own ladders do; a run slower than
        ``REPEAT_BELOW_S`` is timed once."""
        ref = self.reference_run(model, y0, t_eval)
        h0 = 2 * math.pi / float(np.linalg.norm(y0[:3])) / 10
        rows = []
        I = self.moments
        stamp = tuple(study_core.measurement_stamp().values())  # measured_at, machine, cached
        methods = len({bytes(m) for m in study["method"]}) + 2
        share = float(self.config.run.study_budget) / methods  # inf: unbudgeted
        for order in (2, 4):
            splitting.integrate_splitting(I, y0, t_eval[:2], h0, order)
            costs, spent = [], 0.0
            for k in range(12):
                if costs and spent + study_core.predicted_cost(costs) > share:
                    break
                h = h0 * 2.0 ** (-k / 1.0)
                walls = []
                while len(walls) < 3 and (not walls or walls[0] < study_core.REPEAT_BELOW_S):
                    Y, nsteps, wall = splitting.integrate_splitting(I, y0, t_eval, h, order)
                    walls.append(wall)
                best = min(walls)
                costs.append(best)
                spent += sum(walls)
                e = np.abs(Y - ref)
                rows.append((f"splitting{order}", f"axis splitting, order {order}", "fixed",
                             math.nan, h, float(np.max(e[-1])), float(np.max(e)), best,
                             0, 0.0, "ok", len(walls), *stamp))
                if best > 0.5 or float(np.max(e)) < 1e-12:
                    break
        extra = np.array([tuple(v.encode() if isinstance(v, str) else v for v in r)
                          for r in rows], dtype=study.dtype)
        return np.concatenate([study, extra])

    # ------------------------------------------------- report (archive only)
    @classmethod
    def headline(cls, data):
        a = data.analysis
        I, w = a["principal_moments"], a["omega_initial"]
        st = a["axis_stability"]
        facts = [
            ("principal moments", f"I1 = {fmt(I[0])}, I2 = {fmt(I[1])}, I3 = {fmt(I[2])} kg m²"),
            ("initial ω (body)", "(" + ", ".join(fmt(float(x)) for x in w) + ") rad/s"
             + (" after the impulse" if data.config.get("impulse") is not None else "")),
            ("axis stability", ", ".join(f"{k[-1]}: {v['verdict']}" for k, v in st.items())),
            ("max |ω − ω_exact|", f"{fmt_err(a['omega_max_error'])} rad/s ({a['reference']})"),
            ("max ||q| − 1|", f"{fmt_err(a['quaternion_norm_max_deviation'])} (integrator "
                              "output; archived attitude renormalized)"),
        ]
        if "elliptic" in a:
            facts.append(("branch", f"{a['elliptic']['branch']}, m = {fmt(a['elliptic']['m'])}"))
        return facts

    @classmethod
    def section_omega(cls, data):
        run = data.runs["main"]
        names = ["omega_1", "omega_2", "omega_3"]
        exact = run.reference
        fig = common_plots.timeseries_against_reference(
            run.t, {n: run[n] for n in names}, {n: exact[n] for n in names},
            ylabels={n: f"ω{k + 1} [rad/s]" for k, n in enumerate(names)},
            reference_label=data.analysis["reference"])
        err = common_plots.error_against_time(
            run.t, {f"|ω{k + 1} − exact|": run[n] - exact[n] for k, n in enumerate(names)},
            ylabel="absolute error [rad/s]")
        return SectionContent(figures=[
            cls.figure("omega", fig, "Body-frame angular velocity integrated (Euler's equations "
                       "(10.5)) against the exact solution."),
            cls.figure("omega_error", err, "Error of ω against the exact solution.")],
            facts=[("max |ω − ω_exact|", f"{fmt_err(data.analysis['omega_max_error'])} rad/s")])

    @classmethod
    def section_polhodes(cls, data):
        p = data.analysis["polhodes"]
        fig = plots.polhodes(p["family"], p["separatrices"], p["track"])
        return SectionContent(figures=[cls.figure(
            "polhodes", fig, "Polhodes: the body-frame L on the sphere |L| = const cut by the "
            "energy ellipsoid Σ L_k²/I_k = 2E. Grey: a family of energies; orange: the "
            "separatrices through the intermediate axis; red: this scene.")])

    @classmethod
    def section_polhode_ellipsoid(cls, data):
        p = data.analysis.get("polhode_ellipsoid")
        if p is None:
            return SectionContent(notes=["The polhodes on the inertia ellipsoid were not "
                                         "computed for this archive (a spherical body, or the "
                                         "section was not asked for when it was simulated)."])
        run = data.runs["main"]
        fig = plots.polhodes_on_ellipsoid(p["surface"], p["semi_axes"], p["family"],
                                          p["separatrices"], run.y[:, :3])
        side = int(p["circled_axis"])
        facts = [("2T, L²", f"{fmt(float(p['twice_energy']))} J, "
                            f"{fmt(float(p['L_squared']))} (kg m²/s)²"),
                 ("(L² − 2T·I_mid)/(2T·I_mid)",
                  f"{fmt(float(p['separatrix_offset']), 4)}: "
                  + (f"the polhode circles axis {side}" if side else "on the separatrix"))]
        return SectionContent(
            figures=[cls.figure(
                "polhode_ellipsoid", fig,
                "Polhodes on the energy ellipsoid ω·Iω = 2T (the inertia ellipsoid scaled by "
                "√(2T)), body frame: each is its intersection with ω·I²ω = L². Grey: a ladder "
                "of L² between 2T·I_min and 2T·I_max; orange: the separatrices L² = 2T·I_mid; "
                "red: ω of this scene as integrated.")],
            facts=facts)

    @classmethod
    def section_herpolhode(cls, data):
        c = data.analysis.get("poinsot")
        if c is None:
            return SectionContent(notes=["Poinsot's construction was not computed for this "
                                         "archive (a spherical body, or the section was not "
                                         "asked for when it was simulated)."])
        radius = c.get("herpolhode_radius")
        fig = plots.poinsot(c["surface"], c["axes"], c["polhode"], c["herpolhode"],
                            float(c["plane_height"]),
                            circle_radius=None if radius is None else float(radius))
        d = float(c["plane_distance"])
        facts = [("invariable plane at √(2T)/|L|", f"{fmt(d)} 1/√(kg m²)"),
                 ("tip of x off the plane", f"{fmt_err(float(c['plane_distance_max_error']))}"
                                            " 1/√(kg m²) at most over the run")]
        if radius is not None:
            facts.append(("herpolhode radius (symmetric body)",
                          f"{fmt(float(radius))} 1/√(kg m²) closed form; the run deviates by "
                          f"{fmt_err(float(c['herpolhode_radius_max_error']))} at most"))
        t = data.runs["main"].t
        caption = ("Poinsot's construction, x = ω/√(2T) [1/√(kg m²)], seen with L pointing "
                   "down: the inertia ellipsoid x·Ix = 1 at t = "
                   f"{fmt(float(t[int(c['contact_index'])]), 4)} s, resting on the invariable "
                   "plane at the tip of x; red, the polhode on the body; light blue, the herpolhode "
                   "the contact point has traced on the plane since t = 0 (right: the plane "
                   "seen along L).")
        if radius is not None:
            caption += " Dashed: the closed-form circle of the symmetric body."
        return SectionContent(figures=[cls.figure("poinsot", fig, caption)], facts=facts)

    @classmethod
    def section_stability(cls, data):
        a = data.analysis
        content = stability_table_section(a)
        if "flip" in a:
            f = a["flip"]
            run = data.runs["main"]
            k = int(f["axis"]) - 1
            fig = plots.flips(run.t, run.y[:, :3], envelope=f["growth_envelope"])
            content.figures.append(cls.figure(
                "flips", fig, f"Dzhanibekov effect: spin started close to the intermediate axis "
                f"{k + 1}; the perturbation grows at γ = {fmt(f['growth_rate'])} 1/s and the "
                "body flips over, again and again."))
            content.facts += [
                ("flips observed", str(len(f["flip_times"]))),
                ("time between flips", f"{fmt(f['half_period_measured'])} s measured; "
                                       f"2K(m)/λ = {fmt(f['half_period_exact'])} s exact")]
        return content

    @classmethod
    def section_symmetric_precession(cls, data):
        s = data.analysis["symmetric"]
        return SectionContent(facts=[
            ("symmetry axis", str(s["axis"])),
            ("Ω (10.10)", f"{fmt(s['Omega'], 12)} rad/s"),
            ("Ω measured (slope of the phase of ω⊥)", f"{fmt(s['Omega_measured'], 12)} rad/s"),
            ("|ω⊥|", f"{fmt(s['omega_perp'])} rad/s (constant)"),
            ("precession of the figure axis about L, |L|/I⊥", f"{fmt(s['space_precession_rate'])}"
                                                                " rad/s")])

    @classmethod
    def section_geometric_integrator(cls, data):
        if "splitting" not in data.runs:
            return SectionContent(notes=["The splitting integrator was not run for this "
                                         "archive (the section was not asked for when it "
                                         "was simulated)."])
        split = data.runs["splitting"]
        a = data.analysis
        exact = split.reference
        names = ["omega_1", "omega_2", "omega_3"]
        fig = common_plots.error_against_time(
            split.t, {f"|ω{k + 1} − exact|": split[n] - exact[n] for k, n in enumerate(names)},
            ylabel="absolute error [rad/s]")
        scales = {q: split.attrs[f"scale_{q}"] for q in split.invariants}
        inv = common_plots.invariant_drift(split.t, split.invariants, scales=scales)
        rows = [[name, fmt_err(float(split.attrs.get(f"drift_{name}", math.nan))),
                 fmt_err(float(data.runs["main"].attrs.get(f"drift_{name}", math.nan)))]
                for name in split.invariants]
        return SectionContent(
            figures=[cls.figure("splitting_error", fig,
                                f"Error of the {split.attrs['method']} axis splitting "
                                f"(h = {fmt(split.attrs['h'])} s) against the exact solution."),
                     cls.figure("splitting_invariants", inv, "Invariants under the splitting: "
                                "L² and the space-frame L are kept to round-off, the energy "
                                "error stays bounded.")],
            tables=[Table(caption="Max relative drift of each invariant",
                          header=["quantity", "splitting", f"main run "
                                  f"({data.runs['main'].attrs['method']})"], rows=rows)],
            facts=[("max |ω − ω_exact| (splitting)", f"{fmt_err(a['splitting_omega_max_error'])}"
                    f" rad/s in {float(split.attrs['wall_time_s']) * 1e3:.3g} ms, "
                    f"{int(split.attrs['nsteps'])} steps")])

    @classmethod
    def section_invariants(cls, data):
        return cls.invariants_section(
            data,
            labels={"twice_energy": "2T", "L_squared": "L² (body frame)",
                    "L_x": "L_x (space)", "L_y": "L_y (space)", "L_z": "L_z (space)",
                    "quaternion_norm": "|q|"},
            caption="Drift of 2T, L² and the space-frame L, relative to their natural scales; "
                    "|q| as integrated (the archived attitude is renormalized afterwards).")
