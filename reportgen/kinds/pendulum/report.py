"""``pendulum`` report: angle against time, the phase portrait, the period against
amplitude (and across a family), the boundary-value problem and the energy."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err, fmt_pair
from ...scene.report import Report, no_period_reason
from .config import MIN_SAMPLES_PER_PERIOD
from .results import SCHEMA

common_plots = lazy_module("reportgen.rendering.plots.common")
plots = lazy_module("reportgen.kinds.pendulum.plots")


class PendulumReport(Report):
    """The pendulum's sections, drawn from the archive alone."""

    schema = SCHEMA
    gallery_figures = ("phase", "period_family", "period")

    @classmethod
    def gallery_headline(cls, data):
        from ...scene import gallery
        if gallery.is_family(data):
            return gallery.family_headline(data, "amplitudes", "period")
        a = data.analysis
        rel = abs(a["period_measured"] / a["period"] - 1)
        if not math.isfinite(rel):
            return super().gallery_headline(data)
        exact = "4K(k)√(l/g)" if a["motion"] == "libration" else "2K(1/k²)/(k ω0)"
        motion = {"on": "on the separatrix", "near": f"{a['motion']} near the separatrix"}.get(
            str(a.get("separatrix_proximity", "far")), str(a["motion"]))
        return (f"{motion}, period {fmt(a['period'], 5)} s: measured "
                f"{gallery.from_reference(rel, 'the exact ' + exact)}")

    config_symbols = {"initial.theta": r"\theta_0", "initial.theta_dot": r"\dot{\theta}_0",
                      "params.g": "g", "params.l": "l", "params.m": "m"}
    sections = (
        Section("time_series", "Angle against time", integrates=True),
        Section("phase_portrait", "Phase portrait", integrates=True),
        Section("period", "Period against amplitude"),
        Section("boundary_value", "Boundary-value problem and its action"),
        Section("energy", "Energy conservation", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    family_sections = (
        Section("period_family", "Period against amplitude across the family",
                description="Each member's period, integrated, against the exact period."),
    )

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        if "boundary_value" not in data.analysis:
            names.remove("boundary_value")
        return names

    @classmethod
    def prose_case(cls, data):
        """The stored facts the words follow: the motion (libration or rotation, by the sign
        of 1 − k²), how close to the separatrix (|1 − k²| against the stored thresholds),
        how much longer the exact period is than the small-angle one (against its stored
        threshold), the reference, and the boundary-value problem's conjugate points."""
        if data.sweep is not None:
            return {}
        a = data.analysis
        m1 = float(a["complementary_parameter"])
        proximity = str(a.get("separatrix_proximity", "far"))
        motion = str(a["motion"])
        case = {}
        bvp = a.get("boundary_value")
        if bvp is not None and "conjugate_points" in bvp:
            # the Lagrangian action's k = 1 second variation changes sign at ω0 T = π
            points = int(bvp["conjugate_points"])
            case = {"omega_T": fmt(float(a["omega0"]) * data.config.boundary.T),
                    "conjugate": points > 0, "conjugate_points": points}
        excess = a.get("period_excess")
        excess = None if excess is None else float(excess)
        centre = float(a.get("libration_centre", 0.0))
        amplitude = fmt(float(a.get("amplitude", math.nan)), 6)
        return case | {
            "motion": motion, "proximity": proximity,
            "separatrix": proximity == "on",
            "near_separatrix": proximity == "near",
            "on_below": fmt(float(a.get("separatrix_on_below", math.nan))),
            "near_below": fmt(float(a.get("separatrix_near_below", math.nan))),
            "k": fmt(float(a["k"]), 6),
            # near the separatrix k prints as 1: its distance says which side
            "gap": fmt_err(abs(m1)),
            "amplitude": amplitude,
            "swing": (f"{fmt(centre / math.pi)}π ± {amplitude} rad" if centre
                      else f"±{amplitude} rad"),
            "period": fmt(float(a["period"]), 5),
            "period_small": fmt(float(a["period_small_angle"]), 5),
            "has_small_angle": "small_angle_solution" in a,
            "excess": "" if excess is None else (
                f"{fmt(excess * 100, 2)} %" if excess < 1 else f"{fmt(excess + 1, 3)} times"),
            "small": excess is not None and excess < float(a["small_angle_close_below"]),
            "exact_reference": bool(a.get("reference_is_exact", True)),
            "sense": str(a.get("rotation_sense", "")),
        }

    @classmethod
    def _longer(cls, c) -> str:
        """``0.25 % longer than the small-angle 2π√(l/g)`` or ``5.72 times the small-angle
        period``."""
        if c["excess"].endswith("times"):
            return f"{c['excess']} the small-angle period"
        return f"{c['excess']} longer than the small-angle 2π√(l/g)"

    @classmethod
    def describe(cls, data):
        """``A pendulum librating with amplitude 0.2 rad (k = 0.0998), period 2.0116 s:
        0.25 % longer than the small-angle 2π√(l/g)``; a rotation, or a motion on or near
        the separatrix, in its own words."""
        if data.sweep is not None:
            return super().describe(data)
        c = cls.prose_case(data)
        if c["separatrix"]:
            return (f"A pendulum on its separatrix: its energy is the upright's to within "
                    f"|1 − k²| = {c['gap']} (below {c['on_below']}), so it lingers at the "
                    "upright θ = ±π")
        if c["motion"] == "rotation":
            if c["near_separatrix"]:
                return (f"A pendulum rotating just above the separatrix (k² − 1 = {c['gap']}): "
                        f"one turn takes {c['period']} s, most of it near the upright")
            return (f"A pendulum rotating over the top (k = {c['k']}): one turn takes "
                    f"{c['period']} s")
        if c["near_separatrix"]:
            return (f"A pendulum librating just inside the separatrix with amplitude "
                    f"{c['swing']} (1 − k² = {c['gap']}), period {c['period']} s: "
                    f"{cls._longer(c)}")
        return (f"A pendulum librating with amplitude {c['swing']} (k = {c['k']}), period "
                f"{c['period']} s: {cls._longer(c)}")

    @classmethod
    def _motion_words(cls, c) -> str:
        """The motion row of the summary, from :meth:`prose_case`."""
        if c["separatrix"]:
            return f"on the separatrix, |1 − k²| = {c['gap']} (below {c['on_below']})"
        if c["near_separatrix"]:
            side = "1 − k²" if c["motion"] == "libration" else "k² − 1"
            where = "inside" if c["motion"] == "libration" else "above"
            return f"{c['motion']} just {where} the separatrix, {side} = {c['gap']}"
        return f"{c['motion']}, k = {c['k']}"

    @classmethod
    def headline(cls, data):
        p, ini = data.config.params, data.config.initial
        a = data.analysis
        c = cls.prose_case(data)
        reference = "exact" if c["exact_reference"] else "reference run"
        per = "per turn, exact" if c["motion"] == "rotation" else "exact"
        return [
            ("parameters", f"g = {fmt(p.g)} m/s², l = {fmt(p.l)} m, m = {fmt(p.m)} kg"),
            ("initial state", f"θ0 = {fmt(ini.theta)} rad, θ̇0 = {fmt(ini.theta_dot)} rad/s"),
            ("motion", cls._motion_words(c)),
            ("period", f"{fmt(a['period'])} s {per}; small-angle 2π/ω0 = "
                       f"{fmt(a['period_small_angle'])} s"),
            (f"max |θ − θ_{'exact' if c['exact_reference'] else 'ref'}|",
             f"{fmt_err(a['theta_max_error'])} rad over the run ({reference})"),
        ]

    @classmethod
    def section_time_series(cls, data):
        run = data.runs["main"]
        th_ex, thd_ex = run.reference["theta"], run.reference["theta_dot"]
        small = data.analysis.get("small_angle_solution")
        fig = common_plots.timeseries_against_reference(
            run.t, {"theta": run["theta"], "theta_dot": run["theta_dot"]},
            {"theta": th_ex, "theta_dot": thd_ex},
            ylabels={"theta": cls.label("theta"), "theta_dot": cls.label("theta_dot")},
            reference_label=run.attrs["reference_label"],
            extra={"theta": small["theta"], "theta_dot": small["theta_dot"]}
            if small is not None else None,
        )
        c = cls.prose_case(data)
        ref = "exact" if c["exact_reference"] else "ref"
        err = common_plots.error_against_time(
            run.t, {f"|θ − θ_{ref}| [rad]": run["theta"] - th_ex,
                    f"|dθ/dt − (dθ/dt)_{ref}| [rad/s]": run["theta_dot"] - thd_ex},
            ylabel="absolute error")
        reference = ("the exact elliptic-function solution" if c["exact_reference"] else
                     "a reference run of scipy's DOP853 at rtol 1e-14")
        small = (" and the small-angle solution, notes (1.19)" if c["has_small_angle"]
                 else "")
        return SectionContent(figures=[
            cls.figure("timeseries", fig, f"θ(t) and θ̇(t) integrated, against {reference}"
                                          f"{small}."),
            cls.figure("error", err, f"Error of the integration against {reference}."),
        ])

    @classmethod
    def section_phase_portrait(cls, data):
        run = data.runs["main"]
        grid = data.analysis["phase_portrait"]
        fig = plots.phase_portrait(run["theta"], run["theta_dot"], grid_theta=grid["theta"],
                                   grid_theta_dot=grid["theta_dot"], energy=grid["energy"],
                                   levels=grid["levels"], separatrix=grid["separatrix"])
        return SectionContent(figures=[cls.figure(
            "phase", fig, "Phase portrait: librations (closed curves), the separatrix "
            "E = m g l through (±π, 0), and rotations; this scene's orbit highlighted.")])

    @classmethod
    def section_period(cls, data):
        a = data.analysis
        libration = a["motion"] == "libration"
        curve = a["period_curve"]
        fig = plots.period_against_amplitude(
            curve_amplitude=curve["amplitude"], curve_period=curve["period"],
            small_angle_period=a["period_small_angle"],
            amplitude=a["amplitude"] if libration else None, period=a["period"],
            period_measured=a["period_measured"] if libration else None)
        facts = [("exact period", f"{fmt(a['period'])} s"),
                 ("measured from θ(t)", f"{fmt(a['period_measured'])} s"),
                 ("relative difference", fmt_err(abs(a['period_measured'] / a['period'] - 1)))]
        notes = [] if libration else [
            f"This scene rotates: its period is the time of one full turn, 2K(1/k²)/(k ω0) = "
            f"{fmt(a['period'])} s."]
        if not math.isfinite(a["period_measured"]):
            notes.append("No measured period: " + cls._no_period_reason(data) + ".")
        return SectionContent(figures=[cls.figure(
            "period", fig, "Period against amplitude: exact 4K(k)√(l/g), k = sin(θmax/2) for "
            "the amplitude θmax, against the small-angle period 2π√(l/g).")], facts=facts,
            notes=notes)

    @classmethod
    def _no_period_reason(cls, data) -> str:
        """Which reason for a missing measured period applies."""
        period = float(data.analysis["period"])
        if not math.isfinite(period):
            return "the exact period is infinite"
        return no_period_reason(data, period, noun="periods",
                                min_samples=MIN_SAMPLES_PER_PERIOD,
                                fallback="θ(t) crosses its centre upward fewer than twice")

    @classmethod
    def section_period_family(cls, data):
        sweep = data.sweep
        a = sweep.analysis
        theta = sweep.values.get("initial.theta")
        x = np.abs(theta) if theta is not None else np.full(sweep.size, data.config.initial.theta)
        ok = sweep.ok & np.isfinite(a.get("period_measured", np.full(sweep.size, np.nan)))
        every = bool(ok.all())  # a family of 10⁷: no copies of its arrays when all have one

        def having(v):
            return v if every else v[ok]

        curve = data.analysis.get("period_curve")
        measured, exact = having(a["period_measured"]), having(a["period"])
        fig = plots.period_family(having(x), measured, exact, curve=curve,
                                  small_angle=having(a["period_small_angle"]))
        worst = float(np.max(np.abs(np.divide(measured, exact) - 1))) if measured.size \
            else math.nan
        facts = [("members with a period", f"{int(ok.sum())} of {sweep.size}"),
                 ("max relative error of the period", fmt_err(worst)
                  if measured.size else "—"),
                 ("tolerance of the runs", f"rtol {fmt(data.config.run.rtol)}, "
                                           f"atol {fmt(data.config.run.atol)}")]
        return SectionContent(figures=[cls.figure(
            "period_family", fig, "Each member's period, the time between its first two upward "
            "crossings of θ = 0 on the integrator's dense output, against the exact "
            "4K(k)√(l/g), k = sin(θ0/2) (DLMF 19.2.8, 22.19.4), and the small-angle period "
            "2π√(l/g); below, the relative error.")], facts=facts)

    @classmethod
    def section_boundary_value(cls, data):
        bvp = data.analysis["boundary_value"]
        fig = plots.boundary_value(bvp["t"], bvp["theta_exact"], bvp["theta_numeric"],
                                   bvp["theta_nonlinear"])
        b = data.config.boundary
        exact = bvp["action_exact"]
        rows = [["linear, closed form, notes (2.4)", fmt(exact), "—"],
                ["linear, scipy's collocation solver + Simpson quadrature",
                 fmt(bvp["action_numeric"]),
                 _relative(bvp["action_numeric"], exact)]]
        phase = data.analysis.get("phase_space_action")
        if phase is not None:
            rows += [[f"linear, closed form, Simpson quadrature of {what}",
                      fmt(phase[key]), _relative(phase[key], exact)]
                     for what, key in (("L", "action_lagrangian"),
                                       ("p θ̇ − H, notes §5", "action_hamiltonian"))]
        rows.append(["nonlinear pendulum, scipy's collocation solver",
                     fmt(bvp["action_nonlinear"]),
                     "(different problem)"])
        tables = [Table(caption="Action S = ∫ L dt, notes (2.4), along the boundary-value "
                        "solution; on the solution p = m l² θ̇, so ∫ (p θ̇ − H) dt is the same "
                        "number.", header=["solution", "action [J·s]", "rel. error vs closed form"],
                        rows=rows)]
        if "end_variation" in data.analysis:
            tables.append(cls._end_variation_table(data))
        if phase is not None:
            tables.append(cls._variations_table(data))
        if "free_particle_limit" in data.analysis:
            tables.append(cls._free_particle_table(data))
        return SectionContent(
            figures=[cls.figure("bvp", fig, f"θ(0) = {fmt(b.theta0)} rad, θ(T) = "
                                f"{fmt(b.theta1)} rad, T = {fmt(b.T)} s: the linearised "
                                "solution, notes (1.21), in closed form and numerically, and the "
                                "nonlinear pendulum's solution with the same ends.")],
            tables=tables)

    @classmethod
    def _end_variation_table(cls, data) -> Table:
        """∂S/∂θ0, ∂S/∂θ1, ∂S/∂T by differences against −p(0), p(T), −E, notes (7.1–7.15)."""
        e = data.analysis["end_variation"]
        momentum_scale = math.sqrt(2.0 * data.config.params.m * data.config.params.l**2
                                   * e["energy"])
        rows = []
        for name, unit, key, what, reference, scale in (
                ("∂S/∂θ0", "J·s", "dS_dtheta0", "−p(0) = −m l² θ̇(0)", -e["momentum_start"],
                 momentum_scale),
                ("∂S/∂θ1", "J·s", "dS_dtheta1", "p(T) = m l² θ̇(T)", e["momentum_end"],
                 momentum_scale),
                ("∂S/∂T", "J", "dS_dT", "−E", -e["energy"], e["energy"])):
            value, ref = fmt_pair(e[key], reference)
            rows.append([f"{name} [{unit}]", value, f"{what} = {ref}",
                         fmt_err(abs(e[key] - reference) / scale) if scale else "—"])
        return Table(
            caption=f"δS = p δq − H δt, notes (7.1–7.15): the action of the first table "
                    f"(collocation + Simpson) differentiated by central differences of "
                    f"neighbouring boundary-value solutions, Richardson-extrapolated from "
                    f"steps h and 2h (h = {fmt(e['step_theta'], 2)} rad in θ0 and θ1, "
                    f"{fmt(e['step_T'], 2)} s in T), against the momentum and energy of the "
                    f"closed-form solution, notes (1.21). Relative to √(2 m l² E), the "
                    f"largest |p| on the solution, for the momenta; to E for the energy.",
            header=["derivative", "differences of S", "closed form", "rel. difference"],
            rows=rows)

    #: the perturbations of :func:`reportgen.core.pendulum_action.action_variations`
    VARIATIONS = (("q", "δθ = ε sin(kπt/T)"), ("p", "δp = ε m l² (kπ/T) cos(kπt/T)"),
                  ("qp", "both, δp = m l² δθ̇"))

    @classmethod
    def _variations_table(cls, data) -> Table:
        """First and second variations of the phase-space action, notes §5."""
        v = data.analysis["phase_space_action"]
        rows = [[what if i == 0 else "", str(int(k)), fmt_err(v[f"first_variation_{name}"][i]),
                 fmt(v[f"second_variation_{name}"][i]),
                 fmt(v[f"second_variation_{name}_exact"][i])]
                for name, what in cls.VARIATIONS for i, k in enumerate(v["mode"])]
        return Table(
            caption=f"Variations of the phase-space action S = ∫ (p θ̇ − H) dt, notes §5, "
                    f"about the closed-form solution: Simpson on {v['samples']} points, "
                    f"central differences at ε = ±{fmt(v['epsilon'])} rad (S is quadratic "
                    f"in ε, so they are exact). Closed forms: δθ alone −m l² ω0² T/2; δp "
                    f"alone −m l² (kπ/T)² T/2; both m l² T [(kπ/T)² − ω0²]/2. "
                    + cls._free_path_text(v),
            header=["perturbation", "k", "dS/dε [J·s]", "d²S/dε² [J·s]",
                    "closed form [J·s]"], rows=rows)

    @staticmethod
    def _free_path_text(v) -> str:
        """The control: the same δθ about the free path, which is not a solution."""
        i = int(np.argmax(np.abs(v["first_variation_free_path_exact"])))
        value, ref = fmt_pair(v["first_variation_free_path"][i],
                              v["first_variation_free_path_exact"][i])
        return (f"The first variation vanishes only on the solution: about the free path "
                f"θ0 + (θ1 − θ0) t/T, which has the same ends, δθ with k = "
                f"{int(v['mode'][i])} gives dS/dε = {value} J·s (closed form "
                f"−m l² ω0² (T/kπ) [θ0 − (−1)ᵏ θ1] = {ref} J·s).")

    @classmethod
    def _free_particle_table(cls, data) -> Table:
        """S and θ as g → 0 against the free rotor, notes (1.22) and (2.5)."""
        f = data.analysis["free_particle_limit"]
        l = data.config.params.l
        rows = [[fmt(w * w * l), fmt(s), fmt(excess), fmt(leading), fmt_err(dev)]
                for w, s, excess, leading, dev in zip(
                    f["omega"], f["action"], f["action_excess"], f["action_excess_leading"],
                    f["path_excess"], strict=True)]
        return Table(
            caption=f"The same ends as g → 0: S tends to the free rotor's S(g = 0) = "
                    f"m l² (θ1 − θ0)²/(2T) = {fmt(f['action_free'])} J·s, notes (2.5), "
                    f"and θ(t) to θ0 + (θ1 − θ0) t/T, notes (1.22). S − S(g = 0) is "
                    f"evaluated directly (series of x cot x − 1 for small x = ωT), and "
                    f"approaches −∫ V dt along the free path, −m l² ω² T (θ0² + θ0 θ1 + "
                    f"θ1²)/6, ω = √(g/l). The first row is this scene's g.",
            header=["g [m/s²]", "S [J·s]", "S − S(g = 0) [J·s]", "−∫ V dt, free path [J·s]",
                    "max |θ − θ(g = 0)| [rad]"], rows=rows)

    @classmethod
    def section_energy(cls, data):
        return cls.invariants_section(data, labels={"energy": "energy E"},
                                      caption="Energy drift relative to m g l.")


def _relative(value: float, exact: float) -> str:
    """|value/exact − 1| as an error, or "—" where the closed form is 0 (θ0 = θ1 = 0)."""
    return fmt_err(abs(value / exact - 1)) if exact else "—"
