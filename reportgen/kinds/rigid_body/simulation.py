"""``rigid_body`` simulation: Euler's equations with the attitude quaternion against the
exact solution, the polhodes, Poinsot's construction, the axis stability and the flips,
and the splitting integrator (run and in the study)."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.content import fmt
from ...scene.integration import IntegratingSimulation
from ...scene.results import AuditCase, Check, Results, RunRecord
from ..inertia.config import EQUAL_MOMENTS_RTOL, body_symmetry
from .config import RigidBodyConfig, body_moments
from .energy_split import kinetic_energy_split
from .impulse import impulse_motion, rotation_matrices
from .results import SCHEMA

inertia_core = lazy_module("reportgen.core.inertia")
core = lazy_module("reportgen.core.models.rigid_body")
study_core = lazy_module("reportgen.core.study")
splitting = lazy_module("reportgen.core.models.rigid_body_splitting")
poinsot = lazy_module("reportgen.core.models.rigid_body_poinsot")

#: ω0 within this angle [rad] of a principal axis is "near" it; a polhode passing within it
#: of the intermediate axis makes the scene a Dzhanibekov demonstration
FLIP_ANGLE = 0.2
#: |ω⊥| or |ω_s| below this share of |ω|: a symmetric body spins steadily (no precession)
STEADY_RTOL = 1e-9


def nearest_axis(omega) -> tuple[int, float]:
    """The principal axis (0-based) nearest the direction of ``omega`` and the angle to it
    [rad], either sense of the axis."""
    w = np.asarray(omega, dtype=float)
    norm = float(np.linalg.norm(w))
    if norm == 0:
        return 0, math.pi / 2
    k = int(np.argmax(np.abs(w)))
    return k, math.acos(min(1.0, abs(float(w[k])) / norm))


def intermediate_closest_angle(moments, omega0) -> float:
    """The smallest angle [rad] between the body-frame L and the intermediate axis (either
    end) over the whole polhode of an asymmetric body: where the polhode crosses the plane
    of the intermediate axis and the one it circles.  From Σ L_k² = L² and Σ L_k²/I_k = 2E:
    circling the largest moment (L² > 2E·I_mid), L_mid² = (2E·I_max − L²) I_mid/(I_max − I_mid)
    at L_min = 0; circling the smallest, L_mid² = (L² − 2E·I_min) I_mid/(I_mid − I_min)."""
    I = np.asarray(moments, dtype=float)
    w = np.asarray(omega0, dtype=float)
    lo, mid, hi = np.argsort(I)
    L2, E2 = float(np.sum((I * w) ** 2)), float(np.sum(I * w * w))
    if L2 == 0:
        return math.pi / 2
    if L2 >= E2 * I[mid]:
        top = (E2 * I[hi] - L2) * I[mid] / (I[hi] - I[mid])
    else:
        top = (L2 - E2 * I[lo]) * I[mid] / (I[mid] - I[lo])
    return math.acos(min(1.0, math.sqrt(max(top, 0.0) / L2)))


def precession_sense(moments, omega0, axis: int) -> str:
    """How a symmetric body's ω⊥ turns in the body frame, seen along its spin ω_s:
    "prograde" (with the spin: oblate, I_s > I⊥), "retrograde" (against it: prolate);
    "steady about the figure axis" when ω⊥ vanishes, "steady about a transverse axis" when
    ω_s does (within ``STEADY_RTOL`` of |ω|): no precession."""
    I, w = np.asarray(moments, dtype=float), np.asarray(omega0, dtype=float)
    norm = float(np.linalg.norm(w))
    if float(np.linalg.norm(np.delete(w, axis))) <= STEADY_RTOL * norm:
        return "steady about the figure axis"
    if abs(float(w[axis])) <= STEADY_RTOL * norm:
        return "steady about a transverse axis"
    return "prograde" if I[axis] > I[(axis + 1) % 3] else "retrograde"


class RigidBodySimulation(IntegratingSimulation):
    """The torque-free rigid body integrated and checked against its closed forms."""

    schema = SCHEMA
    config: RigidBodyConfig
    computed_on_request = ("error_vs_runtime", "geometric_integrator", "polhode_ellipsoid",
                           "herpolhode")

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
    def body(self) -> tuple[str, int | None]:
        """("spherical" | "symmetric" | "asymmetric", the figure axis of a symmetric body),
        the moments equal within ``EQUAL_MOMENTS_RTOL`` of the largest."""
        return body_symmetry(self.moments)

    @property
    def symmetric(self) -> tuple[int, float] | None:
        """(figure axis s, 0-based, Ω = (I⊥ − I_s) ω_s / I⊥, notes (10.10)) of a symmetric
        body, else None."""
        kind, s = self.body
        if kind != "symmetric":
            return None
        I, w = self.moments, self.omega0
        perp = I[(s + 1) % 3]
        return s, float((perp - I[s]) * w[s] / perp)

    @property
    def spherical(self) -> bool:
        return self.body[0] == "spherical"

    @property
    def intermediate_axis(self) -> int | None:
        if self.body[0] != "asymmetric":
            return None
        return int(np.argsort(self.moments)[1])

    @property
    def is_flip_demo(self) -> bool:
        """Whether the polhode passes within ``FLIP_ANGLE`` of the intermediate axis: the
        body then lingers there and turns over (the Dzhanibekov flip)."""
        return self.intermediate_axis is not None and (
            intermediate_closest_angle(self.moments, self.omega0) < FLIP_ANGLE)

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

    def stored_runs(self) -> int:
        """The main run, and the splitting integrator's when the report shows it."""
        return 1 + self.wants_splitting()

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
        exact = core.exact_omega(t, w0, I, rtol=EQUAL_MOMENTS_RTOL)
        err = np.abs(main.y[:, :3] - exact)

        stability = inertia_core.axis_stability(I, spin=spin, rtol=EQUAL_MOMENTS_RTOL)
        for k, s in enumerate(stability):
            s["growth_rate_jacobian"] = core.steady_rotation_growth_rate(I, k, spin)
        analysis = {
            "principal_moments": I,
            "axis_stability": {f"axis_{k + 1}": s for k, s in enumerate(stability)},
            "spin": spin,
            "spherical": self.spherical,
            "body": self.body[0],
            "equal_moments_rtol": EQUAL_MOMENTS_RTOL,
            "spin_axis": {"nearest": nearest_axis(w0)[0] + 1, "angle": nearest_axis(w0)[1],
                          "near_angle": FLIP_ANGLE},
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
            analysis["symmetric"]["shape"] = (
                "oblate" if I[axis] > I[(axis + 1) % 3] else "prolate")
            analysis["symmetric"]["sense"] = precession_sense(I, w0, axis)
            ref_source = "symmetric-body solution notes (10.9)–(10.10)"
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
        results.checks.append(Check("|q| at its farthest from 1 over the run (before renormalization)",
                                    1.0 + q_dev, 1.0, "", "unit quaternion"))
        k2 = self.intermediate_axis
        if k2 is not None:  # how close the polhode comes to the intermediate axis
            analysis["spin_axis"]["intermediate_closest_angle"] = intermediate_closest_angle(
                I, w0)
            s = stability[k2]
            results.checks.append(Check(
                f"growth rate about the intermediate axis {k2 + 1} (Jacobian eigenvalue)",
                s["growth_rate_jacobian"], s["growth_rate"], "1/s",
                "Ω√((I2−I1)(I3−I2)/(I1 I3)), notes (10.14)"))
        if self.is_flip_demo:
            elliptic = analysis.get("elliptic")
            analysis["flip"] = core.flip_analysis(
                t, main.y[:, :3], k2, stability[k2]["growth_rate"],
                elliptic["period"] / 2.0 if elliptic else math.nan)
            f = analysis["flip"]
            half = next((v for v in (f["half_period_exact"], f["half_period_measured"])
                         if math.isfinite(v)), math.nan)
            analysis["behaviour"] = (
                f"flip: rotation near the intermediate axis {k2 + 1} is unstable (growth rate "
                f"{fmt(stability[k2]['growth_rate'], 3)} 1/s)"
                + (f"; the body turns over every {fmt(half, 4)} s" if math.isfinite(half)
                   else "") + ".")
            if math.isfinite(f["half_period_measured"]):
                results.checks.append(Check(f"time between flips (zero crossings of ω{k2 + 1})",
                                            f["half_period_measured"], f["half_period_exact"],
                                            "s", "2K(m)/λ of the elliptic solution"))
        if "symmetric" in analysis:
            sym = analysis["symmetric"]
            if math.isfinite(sym["Omega_measured"]) and not sym["sense"].startswith("steady"):
                results.checks.append(Check("body-frame precession rate Ω",
                                            sym["Omega_measured"], sym["Omega"], "rad/s",
                                            f"Ω = (I⊥ − I{sym['axis']}) ω{sym['axis']} / I⊥, "
                                            "notes (10.10)"))
        if self.config.impulse is not None:
            self._impulse(analysis, results, main)
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

    def _impulse(self, analysis, results, main) -> None:
        """The blow at t = 0 (textbook ex. 4.6(c)): Δω, and for a body with a mass the
        centre of mass drifting at P/M and the struck point's path in space, each checked
        (:mod:`.impulse`)."""
        imp = self.config.impulse
        shape = self.config.shape
        point = shape.apex() if imp.at == "apex" else np.asarray(imp.at, dtype=float)
        mass = elements = None
        if shape is not None:
            mass = float(shape.mass)
            m, r, _ = shape.mass_elements()
            if shape.type == "points":  # the body frame is the principal frame
                r = r @ inertia_core.principal_axes(shape.body_tensor())[1]
            elements = (m, r)
        a = impulse_motion(main.t, main.y[:, :3], main.y[:, 3:7], self.moments, P=imp.P,
                           point=point, omega_before=self.config.initial.omega, mass=mass,
                           elements=elements, symmetric=self.symmetric)
        if self.symmetric is not None:  # the struck point on the figure axis or off it
            off = float(np.linalg.norm(np.delete(point, self.symmetric[0])))
            a["point_on_figure_axis"] = bool(off <= 1e-9 * max(float(np.linalg.norm(point)),
                                                                 1e-300))
        analysis["impulse"] = a
        if elements is not None:  # T = ½ M Ṙ² + K from the point masses, notes (8.38)–(8.42)
            self._energy_split(analysis, results, main, mass, a["cm_velocity"], elements)
        where = "apex" if imp.at == "apex" else "struck point"
        if "cm_velocity_run_max_error" in a:
            k = a["cm_velocity_run_worst_component"]
            results.checks.append(Check(
                f"centre-of-mass velocity {'xyz'[k]} from the run (worst sample)",
                a["cm_velocity_run_worst"], float(a["cm_velocity"][k]), "m/s",
                "P/M (impulse theorem; textbook ex. 4.6)",
                scale=float(np.linalg.norm(a["cm_velocity"]))))
        if "point_path_max_error" in a:
            exact = a["point_path_exact"]
            n = int(np.argmax(np.linalg.norm(a["point_path"] - exact, axis=1)))
            d = a["point_path"][n] - exact[n]
            k = int(np.argmax(np.abs(d)))
            results.checks.append(Check(
                f"{where} position {'xyz'[k]} (worst sample)", float(a["point_path"][n, k]),
                float(exact[n, k]), "m", "V t plus uniform precession about L at |L|/I⊥ "
                "(Landau & Lifshitz §33)", scale=float(np.linalg.norm(point))))

    def _energy_split(self, analysis, results, main, mass, cm_velocity, elements) -> None:
        """Σ ½ m_A |ṙ_A|² over the body's point masses against ½ M Ṙ² + ½ ω·I ω at a few
        samples (:mod:`.energy_split`), with the worst sample as a check."""
        e = kinetic_energy_split(main.t, main.y[:, :3], rotation_matrices(main.y[:, 3:7]),
                                 self.moments, mass=mass, cm_velocity=cm_velocity,
                                 masses=elements[0], positions=elements[1])
        analysis["energy_split"] = e
        n = int(np.argmax(e["relative_error"]))
        results.checks.append(Check(
            "kinetic energy summed over the point masses (worst sample)",
            float(e["kinetic_points"][n]), float(e["kinetic_split"][n]), "J",
            "translational plus rotational kinetic energy ½ M Ṙ² + ½ ω·I ω, notes (8.42)"))

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
                             0, 0.0, "ok", len(walls), *stamp, ""))  # message: none
                if best > 0.5 or float(np.max(e)) < 1e-12:
                    break
        extra = np.array([tuple(v.encode() if isinstance(v, str) else v for v in r)
                          for r in rows], dtype=study.dtype)
        return np.concatenate([study, extra])
