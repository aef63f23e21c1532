"""``heavy_top`` report: textbook Fig. 4.3 and the nutation locus, f(u) and its roots, ℘, the
effective potential, θ(t) against the closed form, steady precession, the sleeping-top
sweep, the conserved quantities, and a family's bands and loci."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from ...scene.report import Report, no_period_reason
from .config import BAND_CASES, MIN_SAMPLES_PER_PERIOD
from .locus import FIG43_ELEVATION_DEG
from .report_contours import ContourSection
from .report_family import FamilySections
from .report_weierstrass import WeierstrassSection
from .results import SCHEMA

plots = lazy_module("reportgen.kinds.heavy_top.plots")


def _deg(angle, digits: int | None = None) -> str:
    """An angle [rad] as a lecturer reads it, in degrees: ``50°``."""
    value = math.degrees(float(angle))
    return f"{fmt(value) if digits is None else fmt(value, digits)}°"


def _deg_rad(angle) -> str:
    """An angle [rad] in degrees with the radians beside, for a number that also enters a
    formula: ``50° (0.872665 rad)``."""
    return f"{_deg(angle)} ({fmt(float(angle))} rad)"


def _band_words(theta1, theta2, *, radians: bool = False) -> str:
    """The turning circles θ1 = arccos u2, θ2 = arccos u1 [rad] in degrees (with radians
    beside if asked): ``θ1 = 50°, θ2 = 60°``, or one circle where they print alike."""
    show = _deg_rad if radians else _deg
    if fmt(float(theta1)) == fmt(float(theta2)):
        return f"θ1 = θ2 = {show(theta1)} (no nutation)"
    return f"θ1 = arccos u2 = {show(theta1)}, θ2 = arccos u1 = {show(theta2)}"

FORMULATION_TEXT = {
    "reduced": "Lagrange's reduction: the nutation w = 1 − cos θ (ẅ = g′(w)/2, a polynomial) "
               "and the quadratures φ, ψ; the body attitude follows from θ, φ, ψ",
    "spin_free": "the frame that follows the axis without spinning (a quaternion and "
                 "its angular velocity ⊥ the axis), turned by ω3 t",
}


class HeavyTopReport(FamilySections, WeierstrassSection, ContourSection, Report):
    """The heavy top's sections, drawn from the archive alone."""

    schema = SCHEMA
    #: only an unstable sleeping top's study is cut short (its accuracy_horizon)
    study_horizon_reason = ("one nutation period, up to the top's first return to the "
                            "vertical: there it passes the unstable equilibrium again, where "
                            "any error (of a run, and of the reference) grows by about "
                            "θmax/θ0, so later differences measure that instability, not the "
                            "method. The run is compared with its closed form over the same "
                            "period.")
    gallery_figures = ("fig4_3", "loci_family", "nutation_locus")

    @classmethod
    def gallery_headline(cls, data):
        from ...scene import gallery
        if gallery.is_family(data):
            return gallery.family_headline(data, "spin rates")
        a = data.analysis
        steady = gallery.worst_check(data, "steady precession")
        if steady is not None:
            exact = "the exact " + gallery.reference_words(steady.source)
            return (f"steady precession φ̇ = {fmt(steady.value, 5)} rad/s, "
                    f"{gallery.from_reference(steady.rel_error, exact)}")
        if a.get("sleeping_top"):  # a sleeping top: started next to the vertical
            stable = bool(a.get("sleeping_stable"))
            return (f"ω3 = {fmt(a['omega3'], 4)} rad/s, {'above' if stable else 'below'} the "
                    f"sleeping threshold {fmt(a['sleeping_threshold_omega3'], 4)} rad/s: "
                    + ("a small tilt stays small" if stable else
                       f"a small tilt grows at {fmt(a['sleeping_growth_rate'], 3)}/s"))
        rel = abs(a["nutation_period_measured"] / a["nutation_period"] - 1)
        if not math.isfinite(rel):
            return super().gallery_headline(data)
        return (f"{a['case']}, nutation period {fmt(a['nutation_period'], 5)} s: measured "
                f"{gallery.from_reference(rel, 'the exact 4K(k²)/√(β(u3−u1))')}")

    family_sections = (
        Section("nutation_family", "Nutation band and case across the family",
                description="Each member's turning circles and case against the swept "
                            "value; dashed: where the case changes between neighbours."),
        Section("loci_family", "Nutation loci of the kept members",
                description="The path of the symmetry axis of each kept member."),
    )
    sections = (
        Section("fig4_3", "Loops, waves and cusps on one band (textbook Fig. 4.3)",
                integrates=True),
        Section("nutation_locus", "Nutation locus of the symmetry axis", integrates=True),
        Section("cubic", "The cubic f(u), its roots, nutation period and precession"),
        Section("weierstrass", "u(t) through Weierstrass's ℘ (textbook exercise 4.10)"),
        Section("contour_map", "t(u) on its Riemann surface (textbook exercise 4.10(a)–(e))"),
        Section("effective_potential", "Effective potential"),
        Section("time_series", "θ(t) and φ̇(t) against the closed form", integrates=True),
        Section("steady_precession", "Steady precession"),
        Section("sleeping_sweep", "The sleeping top across its threshold"),
        Section("invariants", "Conserved quantities", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        a = data.analysis
        band = a.get("band")
        if band is None or band["case"] != "all":
            names.remove("fig4_3")
        else:  # Fig. 4.3 shows the three loci; the sections that follow describe loops
            for name in ("nutation_locus", "effective_potential", "time_series"):
                names.remove(name)
        if "weierstrass" not in a or "sleeping_sweep" in a:
            names.remove("weierstrass")  # no nutation, or a scene about the threshold
        if "contours" not in a:  # computed only when a scene's [report] sections name it
            names.remove("contour_map")
        initial = data.config.get("initial") or {}
        if a["case"] != "steady" and initial.get("steady") is None:
            names.remove("steady_precession")
        if "sleeping_sweep" not in a:
            names.remove("sleeping_sweep")
        if a["case"] == "sleeping" and "effective_potential" in names:
            names.remove("effective_potential")  # V'(θ) is flat-infinite at θ = 0 with b = a
        return names

    #: the nutation cases in words
    CASE_ADJECTIVES = {"loops": "looping", "waves": "wavy", "cusps": "cusped"}

    @staticmethod
    def _all_runs(data) -> list[str]:
        """The runs of a ``[band] case = "all"`` archive, in the order of Fig. 4.3 (empty
        for any other archive)."""
        band = data.analysis.get("band")
        if band is None or band["case"] != "all":
            return []
        return [name for name in BAND_CASES if name in band["runs"]]

    @classmethod
    def _of_run(cls, data) -> str:
        """`` (the loops run)`` where the sections after Fig. 4.3 speak of one of three runs."""
        return f" (the {BAND_CASES[0]} run)" if cls._all_runs(data) else ""

    @classmethod
    def prose_case(cls, data):
        """The stored facts the words follow: the nutation case (from b/a against u1, u2 with
        their tolerances), whether the top sleeps (started within the stored sleeping tilt of
        the vertical) and what the stored thresholds say of it, which steady root it
        precesses at, whether it is released at rest, and the band's angles, as printed."""
        a = data.analysis
        if data.sweep is not None:
            return {}
        w3, threshold = float(a["omega3"]), float(a["sleeping_threshold_omega3"])
        case = {"case": str(a["case"]), "band": a.get("band") is not None,
                "all": bool(cls._all_runs(data)), "of_run": cls._of_run(data),
                "sleeping": bool(a.get("sleeping_top", False)),
                "upright": str(a["case"]) == "sleeping",
                "stable": bool(a.get("sleeping_stable", True)),
                "stays_upright": bool(a.get("stays_upright", False)),
                "of_the_order": bool(a.get("tilt_of_the_order", False)),
                "tilted_away": bool(a.get("tilted_away", False)),
                "at_rest": bool(a.get("released_at_rest", False)),
                "periods": int(a.get("periods_in_run", 0)),
                "tilt_reached": fmt(float(a.get("tilt_reached", math.nan)), 3),
                "omega3": fmt(w3, 4), "abs_omega3": fmt(abs(w3), 4),
                "threshold": fmt(threshold, 4),
                "ratio": fmt(abs(w3) / threshold, 3) if threshold > 0 else "—",
                "growth": fmt(float(a.get("sleeping_growth_rate", math.nan)), 3),
                "theta0": fmt(float(a["theta0"]), 3), "theta1": fmt(float(a["theta1"]), 3),
                "theta2": fmt(float(a["theta2"]), 3),
                "theta1_deg": _deg(a["theta1"], 3), "theta2_deg": _deg(a["theta2"], 3),
                "half_period": fmt(0.5 * float(a["nutation_period"]), 4),
                "phi_dot0": fmt(float(a["phi_dot0"]), 4),
                "theta_dot0": fmt(float(a["theta_dot0"]), 4),
                "root": str(a.get("steady_root", "")), "other": ""}
        if case["root"]:
            other = a["steady_rate_slow"] if case["root"] == "fast" else a["steady_rate_fast"]
            case["other"] = fmt(float(other), 4)
        return case

    @classmethod
    def describe(cls, data):
        """``A heavy top spun at ω3 = 6 rad/s in steady precession at θ0 = 57.3°, φ̇ =
        5.196 rad/s (the fast root of notes (10.45))``: the scene's case with its numbers."""
        if data.sweep is not None:
            return super().describe(data)
        c, a = cls.prose_case(data), data.analysis
        runs = cls._all_runs(data)
        if runs:
            band = a["band"]
            words = [cls.CASE_ADJECTIVES.get(str(band["runs"][n]["case"]),
                                             str(band["runs"][n]["case"])) for n in runs]
            listed = ", ".join(words[:-1]) + f" and {words[-1]}" if len(words) > 1 else words[0]
            count = {2: "Two", 3: "Three"}.get(len(runs), str(len(runs)))
            return (f"{count} heavy tops released on the same band, θ from "
                    f"{_deg(band['theta_min'], 3)} to {_deg(band['theta_max'], 3)}: {listed} "
                    "nutation (textbook Fig. 4.3)")
        if c["sleeping"]:
            side = "above" if c["stable"] else "below"
            where = ("standing exactly upright" if c["upright"] else
                     f"released at rest {c['theta0']} rad from the vertical" if c["at_rest"]
                     else f"started {c['theta0']} rad from the vertical with θ̇0 = "
                          f"{c['theta_dot0']} rad/s, φ̇0 = {c['phi_dot0']} rad/s")
            return (f"A top spun at ω3 = {c['omega3']} rad/s, {side} its sleeping threshold "
                    f"{c['threshold']} rad/s, {where}")
        if c["case"] == "steady":
            return (f"A heavy top spun at ω3 = {c['omega3']} rad/s in steady precession at "
                    f"θ0 = {c['theta1_deg']}, φ̇ = {c['phi_dot0']} rad/s"
                    + (f" (the {c['root']} root of notes (10.45))" if c["root"] else ""))
        words = cls.CASE_ADJECTIVES.get(c["case"], "")
        period = float(a["nutation_period"])
        return (f"A heavy top spun at ω3 = {c['omega3']} rad/s, its axis in {words} nutation "
                f"between θ1 = {c['theta1_deg']} and θ2 = {c['theta2_deg']}"
                + (f", nutation period {fmt(period, 4)} s" if math.isfinite(period) else ""))

    @classmethod
    def headline(cls, data):
        p = data.config.params
        a = data.analysis
        band = a.get("band")
        runs = cls._all_runs(data)
        facts = [("parameters", f"I1 = {fmt(p.I1)} kg m², I3 = {fmt(p.I3)} kg m², "
                                f"M g l = {fmt(p.Mgl)} J")]
        if band is not None:
            facts.append(("band asked for", f"θmin = {_deg_rad(band['theta_min'])}, θmax = "
                          f"{_deg_rad(band['theta_max'])}, case = {band['case']}"))
            for name in [n for n in (*BAND_CASES, "main") if n in band["runs"]]:
                run = band["runs"][name]
                label = "released on θmin" if name == "main" else f"{name}: released on θmin"
                facts.append((label, f"θ̇0 = 0, φ̇0 = {fmt(run['phi_dot0'])} rad/s, ω3 = "
                                     f"{fmt(run['omega3'])} rad/s → {run['case']}, θ1 − θmin = "
                              f"{fmt_err(run['theta1'] - band['theta_min'])} rad, θ2 − θmax = "
                              f"{fmt_err(run['theta2'] - band['theta_max'])} rad"))
        else:
            facts.append(("initial state", f"θ0 = {_deg_rad(a['theta0'])}, θ̇0 = "
                          f"{fmt(a['theta_dot0'])} rad/s, φ̇0 = {fmt(a['phi_dot0'])} rad/s, "
                          f"ω3 = {fmt(a['omega3'])} rad/s"))
        if runs:
            facts += cls._all_runs_headline(data, runs)
        else:
            facts += cls._one_run_headline(data)
        facts.append(("sleeping-top threshold", f"ω3 = 2√(I1 M g l)/I3 = "
                      f"{fmt(a['sleeping_threshold_omega3'])} rad/s (notes (10.50))"))
        formulation = data.runs["main"].attrs.get("formulation")
        if formulation in FORMULATION_TEXT:  # archives before it was stored: spin-free
            facts.append(("integrated" + cls._of_run(data),
                          f"{FORMULATION_TEXT[formulation]} "
                          f"({data.runs['main'].attrs.get('formulation_reason')})"))
        return facts

    @classmethod
    def _all_runs_headline(cls, data, runs) -> list[tuple[str, str]]:
        """The three runs of a band, each by its own case, nutation period and precession
        (from the archived band summary of each run)."""
        band = data.analysis["band"]
        out = []
        for name in runs:
            r = band["runs"][name]
            out.append((f"{name} run", f"{r['case']}, nutation period "
                                       f"{fmt(r['nutation_period'])} s, precession per period "
                                       f"{fmt(r['precession_per_period'])} rad"))
        worst = max(float(band["runs"][n]["weierstrass_max_difference"]) for n in runs)
        if math.isfinite(worst):
            out.append(("℘ form against sn² form", f"max |Δu| = {fmt_err(worst)} over the "
                                                   f"{len(runs)} runs' output grids"))
        out.append(("sections below textbook Fig. 4.3", f"the {BAND_CASES[0]} run"))
        return out

    @classmethod
    def _one_run_headline(cls, data) -> list[tuple[str, str]]:
        a = data.analysis
        facts = [("case", f"{a['case']} (a = {fmt(a['a'])}, b = {fmt(a['b'])}, "
                          f"b/a = {fmt(a['b_over_a'])}; u1 = {fmt(a['u1'])}, "
                          f"u2 = {fmt(a['u2'])})")]
        if a.get("band") is None and math.isfinite(a["theta1"]) and math.isfinite(a["theta2"]):
            facts.append(("nutation band", _band_words(a["theta1"], a["theta2"])))
        if math.isfinite(a["nutation_period"]):
            extra = " (small-oscillation limit, k² = 0)" if a["case"] in ("steady",
                                                                          "sleeping") else ""
            facts.append(("nutation period", f"{fmt(a['nutation_period'])} s{extra}"))
        if math.isfinite(a["precession_per_period"]):
            facts.append(("precession per nutation period",
                          f"{fmt(a['precession_per_period'])} rad"))
        if "weierstrass_max_difference" in a:
            facts.append(("℘ form against sn² form", "max |Δu| = "
                          f"{fmt_err(a['weierstrass_max_difference'])} on the output grid"))
        return facts

    @classmethod
    def section_fig4_3(cls, data):
        """The three band runs as Fig. 4.3 is printed, and a table of what each achieved."""
        band = data.analysis["band"]
        loci, labels, azimuths = [], [], []
        for letter, name in zip("abc", BAND_CASES, strict=True):
            run, summary = data.runs[name], band["runs"][name]
            stop = int(summary["locus_stop"])
            loci.append(np.column_stack([run["axis_x"], run["axis_y"], run["axis_z"]])[:stop])
            labels.append((f"({letter}) {summary['case']}",
                           f"ω3 = {fmt(summary['omega3'], 4)} rad/s\ndφ/dt(0) = "
                           f"{fmt(summary['phi_dot0'], 3)} rad/s"))
            azimuths.append(summary["view_azimuth"])
        fig = plots.fig43(loci, theta1=band["theta_min"], theta2=band["theta_max"],
                          labels=labels, azimuths=azimuths,
                          elevation=math.radians(FIG43_ELEVATION_DEG))
        rows = []
        for name in BAND_CASES:
            r = band["runs"][name]
            roots = max(abs(r["theta1"] - band["theta_min"]), abs(r["theta2"] - band["theta_max"]))
            span = max(abs(r["theta_min_measured"] - band["theta_min"]),
                       abs(r["theta_max_measured"] - band["theta_max"]))
            rows.append([f"{name} ({r['case']})", fmt(r["omega3"], 5), fmt(r["phi_dot0"], 5),
                         f"{fmt(r['phi_dot_upper'], 3)} / {fmt(r['phi_dot_lower'], 3)}",
                         f"{fmt_err(roots)} / {fmt_err(span)}", fmt(r["nutation_period"], 5),
                         fmt(r["precession_per_period"], 5),
                         fmt_err(r["weierstrass_max_difference"])])
        spins = _spins_in_words(band)
        table = Table(
            caption=f"The three runs on θ ∈ [{_deg(band['theta_min'])}, "
                    f"{_deg(band['theta_max'])}]: the case the solved release gives (classified "
                    f"from b/a and u1, u2), "
                    f"φ̇ = (b − a cos θ)/sin²θ on the "
                    f"two circles, how far the roots of f(u) and the extremes of the integrated "
                    f"θ(t) are from the band (rad), and the ℘ form against the sn² form. "
                    f"{spins[0].upper()}{spins[1:]}.",
            header=["run (case)", "ω3 [rad/s]", "φ̇0 [rad/s]", "φ̇ on θ1 / θ2 [rad/s]",
                    "band error: roots / run", "T [s]", "Δφ [rad]", "max |Δu|, ℘ against sn²"],
            rows=rows)
        periods = ", ".join(f"{band['runs'][n]['locus_periods']}" for n in BAND_CASES)
        turns = ", ".join(fmt(abs(band["runs"][n]["locus_periods"]
                                  * band["runs"][n]["precession_per_period"]), 4)
                          for n in BAND_CASES)
        short = [n for n in BAND_CASES if not band["runs"][n].get("locus_full_turn", True)]
        extent = ("the whole number that takes it once round the band" if not short else
                  "the fewest whole number that takes it once round the band, or as many as "
                  "the run holds, short of a turn for "
                  + (f"{', '.join(short[:-1])} and {short[-1]}" if len(short) > 1 else short[0]))
        return SectionContent(
            figures=[cls.figure("fig4_3", fig,
                                f"The symmetry axis on the unit sphere, as in textbook "
                                f"Fig. 4.3, between the turning circles θ1 = "
                                f"{_deg(band['theta_min'])} and θ2 = "
                                f"{_deg(band['theta_max'])}, seen from "
                                f"{FIG43_ELEVATION_DEG:g}° above the horizon; dashed: "
                                f"behind the sphere. Each locus starts on the upper circle "
                                f"(dot) and runs {periods} "
                                f"nutation periods (loops, waves, cusps), {extent}: "
                                f"Δφ = {turns} rad.")],
            tables=[table])

    @classmethod
    def section_nutation_locus(cls, data):
        run = data.runs["main"]
        a = data.analysis
        axis = np.column_stack([run["axis_x"], run["axis_y"], run["axis_z"]])
        fig = plots.nutation_locus(axis, run["theta"], theta1=a["theta1"], theta2=a["theta2"])
        label = {"loops": "b/a inside (u1, u2): φ̇ changes sign, the axis loops (textbook "
                          "Fig. 4.3a)",
                 "waves": "b/a outside [u1, u2]: φ̇ never changes sign, the axis waves "
                          "(textbook Fig. 4.3b)",
                 "cusps": "b/a = u2: φ̇ = 0 on the upper circle, cusps (textbook Fig. 4.3c)",
                 "steady": "u1 = u2: no nutation, steady precession on one circle",
                 "sleeping": "the sleeping top: the axis stays vertical"}[a["case"]]
        # the figure draws one circle where θ1 and θ2 print alike (no nutation)
        circles = (f"; dashed: the turning circle θ1 = θ2 = {_deg(a['theta1'])}"
                   if fmt(a["theta1"]) == fmt(a["theta2"])
                   else f"; dashed: the upper turning circle θ1 = arccos u2 = "
                        f"{_deg(a['theta1'])}, dash-dotted: the lower one θ2 = arccos u1 = "
                        f"{_deg(a['theta2'])}")
        if not (math.isfinite(a["theta1"]) and math.isfinite(a["theta2"])):
            circles = ""
        return SectionContent(
            figures=[cls.figure("nutation_locus", fig,
                                f"Path of the symmetry axis{circles}. Case: {label}.")],
            facts=[("case", a["case"]), ("θ1, θ2", _band_words(a["theta1"], a["theta2"],
                                                               radians=True))])

    @classmethod
    def _no_period_reason(cls, data) -> str:
        """Which reason for a missing measured nutation period applies."""
        period = float(data.analysis["nutation_period"])
        if not math.isfinite(period) or period <= 0:
            return "the closed-form nutation period is not finite"
        return no_period_reason(data, period, noun="nutation periods",
                                min_samples=MIN_SAMPLES_PER_PERIOD,
                                fallback="θ(t) has fewer than two turning points to measure "
                                         "between")

    @classmethod
    def section_cubic(cls, data):
        a = data.analysis
        cc = a["cubic_curve"]
        if cc["variable"] == "w":
            # near the vertical the interval is invisible on [−1, 1]: drawn against w = 1 − u
            fig = plots.cubic(cc["x"], cc["f"], u1=cc["root1"], u2=cc["root2"], u3=cc["root3"],
                              b_over_a=cc["ratio"], u0=cc["start"],
                              xlabel="1 − u = 1 − cos θ, near the vertical (dimensionless)",
                              names=("1 − u2", "1 − u1", "1 − u3"), ratio_label="1 − b/a")
        else:
            fig = plots.cubic(cc["x"], cc["f"], u1=cc["root1"], u2=cc["root2"], u3=cc["root3"],
                              b_over_a=cc["ratio"], u0=cc["start"])
        rows = [
            ["a = I3 ω3/I1, notes (10.25)", fmt(a["a"]), "1/s"],
            ["b = p_φ/I1, notes (10.25)", fmt(a["b"]), "1/s"],
            ["α = 2E'/I1, notes (10.30)", fmt(a["alpha"]), "1/s²"],
            ["β = 2Mgl/I1, notes (10.30)", fmt(a["beta"]), "1/s²"],
            ["u1, 1 − u1", f"{fmt(a['u1'])}, {fmt(a['one_minus_u1'])}", ""],
            ["u2, 1 − u2", f"{fmt(a['u2'])}, {fmt(a['one_minus_u2'])}", ""],
            ["u3", fmt(a["u3"]), ""],
            ["k² = (u2 − u1)/(u3 − u1)", fmt(a["k2"]), ""],
        ]
        table = Table(caption="Constants of the motion and the roots of f(u)" + cls._of_run(data),
                      header=["quantity", "value", "unit"], rows=rows)
        per = []
        compared = (("nutation period T", "nutation_period", "nutation_period_quadrature",
                     "nutation_period_measured", "s"),
                    ("precession per period Δφ", "precession_per_period",
                     "precession_quadrature", "precession_measured", "rad"))
        # a steady or sleeping top has no nutation to measure: no "measured" columns then
        measured = any(math.isfinite(a[meas]) for _, _, _, meas, _ in compared)
        for name, closed, quad, meas, unit in compared:
            ref = a[closed]
            row = [name + f" [{unit}]", fmt(ref), fmt(a[quad]),
                   fmt_err(abs(a[quad] / ref - 1)) if ref else "—"]
            if measured:
                row += [fmt(a[meas]), fmt_err(abs(a[meas] / ref - 1)) if ref else "—"]
            per.append(row)
        table2 = Table(caption=f"Closed form{cls._of_run(data)} (Carlson's symmetric integrals "
                               "of the first and third kind) against quadrature of "
                               "∮du/√f(u)" + (" and against the integrated trajectory" if measured
                                              else "; nothing measured: no nutation")
                               + (" (—: not defined or not measured)"
                                  if any("—" in c for r in per for c in r) else ""),
                       header=["quantity", "closed form", "quadrature", "rel. diff."]
                       + (["measured", "rel. diff."] if measured else []), rows=per)
        notes = []
        if a["case"] in ("steady", "sleeping"):
            notes.append("u1 = u2: f(u) has a double root, there is no nutation. The period "
                         "shown is the small-oscillation limit k² → 0, 2π/√(β(u3 − u1)); "
                         "nothing is measured.")
        if a["case"] == "sleeping" and not a["sleeping_stable"]:
            notes.append("Unstable sleeping top (u3 ≤ 1): no small-oscillation period (—).")
        sens = a.get("period_sensitivity", math.nan)
        if math.isfinite(sens) and sens > 1e-6:
            notes.append(f"Ill-conditioned: an energy error as small as this run's own drift "
                         f"changes the nutation period by {fmt_err(sens)} (relative). The "
                         f"axis passes close to the vertical, where the roots near u = 1 are "
                         f"set by differences of order θ² in E′ and p_φ; the measured values "
                         f"can agree with the closed form only to about this level.")
        if (not math.isfinite(a["nutation_period_measured"])
                and a["case"] not in ("steady", "sleeping")):
            notes.append("No measured period: " + cls._no_period_reason(data) + ".")
        facts = [("sensitivity of T to an energy error of the run's drift",
                  fmt_err(sens))] if math.isfinite(sens) else []
        return SectionContent(
            facts=facts,
            figures=[cls.figure("f_of_u", fig, f"f(u){cls._of_run(data)} = (1 − u²)(α − βu) − "
                                "(b − au)², notes (10.31): "
                                "the motion is confined to u1 ≤ u ≤ u2 where f ≥ 0; "
                                "u3 ≥ 1 lies outside it. Dashed: b/a, where φ̇ = 0.")],
            tables=[table, table2], notes=notes)

    @classmethod
    def section_effective_potential(cls, data):
        a = data.analysis
        ep = a.get("effective_potential")
        if ep is None:
            return SectionContent(notes=["The sleeping top stays on the vertical, where "
                                         "V'(θ) is not defined: nothing to draw."])
        if ep["minus_Mgl"]:
            fig = plots.effective_potential(ep["theta"], ep["V"], energy=ep["energy"],
                                            theta1=a["theta1"], theta2=a["theta2"],
                                            ylabel="V'(θ) − Mgl [J]")
        else:
            fig = plots.effective_potential(ep["theta"], ep["V"], energy=ep["energy"],
                                            theta1=a["theta1"], theta2=a["theta2"])
        return SectionContent(figures=[cls.figure(
            "effective_potential", fig,
            "V'(θ) = Mgl cos θ + I1 (b − a cos θ)²/(2 sin²θ), notes (10.28), and the energy "
            "E' = "
            "E − I₃ω₃²/2: "
            + ("E' sits at the minimum of V', so θ stays at θ0: steady precession, no "
               "nutation." if a["case"] == "steady" else
               "θ oscillates between the turning angles θ1 and θ2 where E' = V'."))])

    @classmethod
    def section_time_series(cls, data):
        run = data.runs["main"]
        a = data.analysis
        err = a["cos_theta_error"]
        relative = err["relative_to_width"]
        fig = plots.time_series(run.t, run["theta"], run.reference["theta"], run["phi_dot"],
                                err["difference"], theta1=a["theta1"], theta2=a["theta2"],
                                error_label="|Δcos θ| / (u2 − u1)\n(dimensionless)" if relative
                                else "|cos θ − closed form|\n(dimensionless)")
        return SectionContent(
            figures=[cls.figure("time_series", fig,
                                "θ(t) of the integrated attitude against the closed form "
                                "cos θ = u1 + (u2 − u1) sn²(λt + τ0 | k²), λ = ½√(β(u3 − u1)); "
                                "φ̇(t) = (b − a cos θ)/sin²θ, notes (10.26); and the "
                                "difference in "
                                "cos θ.")],
            facts=[("max |cos θ − closed form|", fmt_err(a["u_max_error"]))])

    @classmethod
    def section_steady_precession(cls, data):
        a = data.analysis
        sr = a["steady_rates"]
        fig = plots.steady_rates(sr["omega3"], sr["slow"], sr["fast"],
                                 omega3_min=sr["omega3_min"],
                                 omega3_config=data.analysis["omega3"],
                                 rate_config=a["phi_dot0"], rate_measured=a["mean_phi_dot"])
        table = Table(caption=f"Steady precession at θ0 = {_deg(a['theta0'])}, notes (10.45)",
                      header=["root", "φ̇ [rad/s]"],
                      rows=[["slow  2Mgl/(I₃ω₃ + √D)", fmt(a["steady_rate_slow"])],
                            ["fast  (I₃ω₃ + √D)/(2 I1 cos θ0)", fmt(a["steady_rate_fast"])],
                            ["mean φ̇ of the integration", fmt(a["mean_phi_dot"])]])
        return SectionContent(
            figures=[cls.figure("steady_rates", fig,
                                "The two steady precession rates φ̇ = [I₃ω₃ ± √(I3²ω3² − "
                                "4I₁Mgl cos θ0)]/(2I1 cos θ0), notes (10.45), against the "
                                "spin; they exist only for I3²ω3² ≥ 4I₁Mgl cos θ0, notes "
                                "(10.46).")],
            tables=[table])

    @classmethod
    def section_sleeping_sweep(cls, data):
        sw = data.analysis.get("sleeping_sweep")
        if sw is None:
            return SectionContent(notes=["No sweep: the config has no [sleeping] table."])
        fig = plots.sleeping_sweep(sw["t"], sw["theta"], sw["omega3_over_threshold"],
                                   theta_max=sw["theta_max"])
        rows = [[fmt(float(x)), fmt(float(w)),
                 "stable" if x > 1 else ("marginal" if x == 1 else "unstable"),
                 fmt(float(g)), fmt(math.degrees(float(m)), 3)]
                for x, w, g, m in zip(sw["omega3_over_threshold"], sw["omega3"],
                                      sw["growth_rate"], sw["theta_max"], strict=True)]
        table = Table(caption=f"Tops started at a tilt of {_deg_rad(sw['tilt'])} at rest "
                              f"(threshold ω3 = {fmt(data.analysis['sleeping_threshold_omega3'])}"
                              f" rad/s)",
                      header=["ω3 / threshold", "ω3 [rad/s]", "stability, notes (10.50)",
                              "linear growth rate ½√(2β − a²) [1/s]", "largest tilt [°]"],
                      rows=rows)
        return SectionContent(
            figures=[cls.figure("sleeping_sweep", fig,
                                "Below ω3² = 4I₁Mgl/I3², notes (10.50), a small tilt grows "
                                "exponentially to order one; above it the tilt stays of the "
                                "order of its initial value.")],
            tables=[table])

    @classmethod
    def section_invariants(cls, data):
        return cls.invariants_section(
            data, labels={"energy": "energy E", "p_phi": "p_φ = L·ẑ", "p_psi": "p_ψ = I3 ω3"},
            caption=f"Drift of E, p_φ and p_ψ{cls._of_run(data)} relative to their natural "
                    "sizes." + (
                " The reduced equations hold p_φ and p_ψ constant by construction (only "
                "round-off shows): here the energy's drift measures the integration error."
                if data.runs["main"].attrs.get("formulation") == "reduced" else ""))


def _spins_in_words(band) -> str:
    """Which spins give which case on the archived band, in words at the report's
    6 figures (the config's error messages give 10: core.heavy_top_theory.BandSpins)."""
    wc = fmt(band["omega3_cusps"])
    sigma = band["sigma"]
    if sigma > 0.0:
        waves = f"|ω3| ≥ {fmt(band['omega3_waves_min'])} rad/s"
    elif sigma < 0.0:
        waves = "any ω3"
    else:
        waves = f"0 < |ω3| < {wc} rad/s"
    return (f"on the band [{_deg(band['theta_min'])}, {_deg(band['theta_max'])}] cusps "
            f"need |ω3| = {wc} rad/s, loops |ω3| > {wc} rad/s, waves {waves}")
