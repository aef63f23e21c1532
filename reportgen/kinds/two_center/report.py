"""``two_center`` report: the orbit over the elliptic-coordinate grid, the two
constants' drift and a family's surface of section y = 0."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, fmt, fmt_err
from ...scene.report import Report, section_colours, section_point_notes
from .results import SCHEMA

plots = lazy_module("reportgen.rendering.plots.gravitation")
section_plots = lazy_module("reportgen.rendering.plots.sections")

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


class TwoCenterReport(Report):
    """The two-centre sections, drawn from the archive alone."""

    schema = SCHEMA
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
    #: members of a sweep told apart by a legend; more get a colour bar
    LEGEND_MEMBERS = 7
    #: marker area of a crossing [pt²]: an integrable family's crossings lie on curves
    #: that do not crowd one another, so they can be larger than in a chaotic sea
    MARKER_SIZE = 9.0

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
