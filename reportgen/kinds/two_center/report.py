"""``two_center`` report: the orbit over the elliptic-coordinate grid, the two
constants' drift and a family's surface of section y = 0."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from ...scene.report import Report, section_colours, section_point_notes
from .results import SCHEMA

plots = lazy_module("reportgen.rendering.plots.gravitation")
section_plots = lazy_module("reportgen.rendering.plots.sections")

#: the orbit class's name, by its motion (``/analysis`` ``motion``, classified at
#: simulate time from E, β and q(1), notes (7.59)), as the literature names it (Charlier,
#: Die Mechanik des Himmels (1902); Waalkens, Dullin & Richter, Physica D 196 (2004)):
#: a satellite orbit about one centre, a planetary orbit round both (a planet round a
#: binary), a lemniscate orbit through the segment between them
FAMILY_NAME = {"one_centre": "satellite", "both_centres": "planetary",
               "through_middle": "lemniscate", "escape": "unbound"}

#: the orbit family as the headline names it, by its motion; {centre}: the centre a
#: one-side orbit keeps to
MOTION_TEXT = {
    "one_centre": "satellite orbit: stays on one side, about the centre at {centre} (β > 0, "
                  "|η| ≥ η*)",
    "both_centres": "planetary orbit: encircles both centres (β ≤ 0, η free in [−1, 1], ξ "
                    "between two ellipses)",
    "through_middle": "lemniscate orbit: crosses the segment between the centres (β ≤ 0, η "
                      "free in [−1, 1], ξ from 1 up to one ellipse)",
    "escape": "unbound (E ≥ 0)",
}


#: the gallery card's words for the motion
GALLERY_MOTION = {"one_centre": "satellite orbit about one centre",
                  "both_centres": "planetary orbit round both centres",
                  "through_middle": "lemniscate orbit through the segment between the centres",
                  "escape": "unbound orbit"}


def motion_of(a) -> str:
    """The stored motion (``one_centre`` …); an archive from before it was stored: the
    family's, as such archives named it (before the names followed the literature, the
    one-side orbit was "planetary" and every orbit with β ≤ 0 "satellite")."""
    motion = a.get("motion")
    if motion:
        return str(motion)
    return {"planetary": "one_centre", "satellite": "both_centres"}.get(str(a["family"]),
                                                                       "escape")


def centre_words(a, p) -> str:
    """The centre a one-side orbit keeps to, as a point: ``(1, 0)``."""
    side = int(a.get("side", 0) or 0)
    return f"({fmt(side * float(p.a))}, 0)" if side else "one centre"


FORMULATION_TEXT = {
    "cartesian": "Cartesian (x, y, vx, vy) in t",
    "regularized": "regularized: Thiele–Burrau variables z = a cosh(p + iq) in the "
                   "fictitious time dt/ds = r1 r2 (regular at both centres)",
}


class TwoCenterReport(Report):
    """The two-centre sections, drawn from the archive alone."""

    schema = SCHEMA
    config_symbols = {"initial.x": "x_0", "initial.y": "y_0", "initial.vx": r"v_{x,0}",
                      "initial.vy": r"v_{y,0}", "initial.energy": "E"}
    gallery_name = "Two fixed centres (Euler's problem)"
    gallery_figures = ("orbit", "poincare_family")

    @classmethod
    def gallery_headline(cls, data):
        from ...scene import gallery
        if gallery.is_family(data):
            a, c = data.analysis, gallery.worst_check(data)
            members, ok, energy = a["sweep_members"], a.get("sweep_ok", 0), a.get("poincare_energy")
            return (f"{members} orbits on the section"
                    + (f" at E = {fmt(energy, 5)}" if energy is not None else "")
                    + (", all ok" if ok == members else f", {ok} ok")
                    + (f"; separation constant kept to {gallery.distance(c.rel_error)}"
                       if c is not None else ""))
        c = gallery.worst_check(data, "separation constant")
        energy = gallery.worst_check(data, "energy")
        if c is None or energy is None:
            return super().gallery_headline(data)
        motion = GALLERY_MOTION.get(str(data.analysis.get("motion", "")), "")
        return ((f"{motion}: " if motion else "")
                + f"separation constant kept to {gallery.distance(c.rel_error)}, energy to "
                  f"{gallery.distance(energy.rel_error)}")

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
    SWEEP_HIDDEN_RESULTS = ("poincare_*_error", "xi_range_run_*", "eta_abs_range_run_*",
                            "segment_reach", "side")
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
            pts.columns["u"], pts.columns["v"], member, colour, "x [m]", "dx/dt [m/s]",
            colour_label=cls.colour_key_label(data, key), labels=labels,
            edge=None if grid is None else (grid["u"], grid["v"], grid["vy2"], 0.0),
            edge_label=None if grid is None else
            f"ẏ = 0 on E = {fmt(a['poincare_energy'])}",
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
            facts.append(("energy of every orbit", f"E = {fmt(a['poincare_energy'])}"))
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
                   "its own colour " + (f"(colour bar: {cls._colour_key_words(data, key)})"
                                        if labels is None else "(legend)")
                   + ". The problem is integrable: each regular orbit's crossings lie on one "
                   "closed curve" + (", the grey curve C(x, ẋ) = C of the orbit at its energy; "
                                     "dark: ẏ = 0, the edge of the region the energy allows"
                                     if grid is not None else "") + ".")
        return SectionContent(figures=[cls.figure("poincare_family", fig, caption)],
                              facts=facts, notes=notes)

    @classmethod
    def _colour_key_words(cls, data, key: str) -> str:
        """What a family's colour bar shows, in words: "the initial position x"."""
        if key == "member":
            return "the member's number"
        words = cls.config_quantity(data, key).description
        return f"the {words.split(' [')[0].split(',')[0]}" if words else "the swept value"

    #: a sampled approach to a centre closer than this fraction of a is a near collision
    NEAR_FRACTION = 0.05

    @classmethod
    def prose_case(cls, data):
        """The orbit's family (satellite, planetary, lemniscate, unbound) and its motion (one
        side, round both centres, through the segment between them, escaping), its bounds
        from notes (7.59), how close the run came to a centre, and whether it was
        regularized."""
        if data.sweep is not None:
            return {}
        a, p = data.analysis, data.config.params
        xi_b = [float(v) for v in np.asarray(a["xi_bounds"])]
        eta_b = [float(v) for v in np.asarray(a["eta_abs_bounds"])]
        closest = float(a.get("closest_approach_run", math.nan))
        motion = motion_of(a)
        return {"family": FAMILY_NAME[motion], "motion": motion,
                "centre": centre_words(a, p), "energy": fmt(float(a["energy"]), 4),
                "beta": fmt(float(a["beta"]), 4), "xi_min": fmt(xi_b[0], 4),
                "xi_max": fmt(xi_b[1], 4), "eta_min": fmt(eta_b[0], 4),
                "reach": fmt(float(a.get("segment_reach", math.nan)), 4),
                "closest": fmt(closest, 3),
                "near": closest < cls.NEAR_FRACTION * float(p.a),
                "regularized": data.runs["main"].attrs.get("formulation") == "regularized"}

    @classmethod
    def describe(cls, data):
        """``A satellite orbit about the centre at (1, 0) at E = −1.331 (β = 0.4162 > 0):
        |η| ≥ 0.3954, ξ ≤ 1.6``, and how close it comes to a centre."""
        if data.sweep is not None:
            return super().describe(data)
        c = cls.prose_case(data)
        if c["motion"] == "one_centre":
            text = (f"A satellite orbit about the centre at {c['centre']} at E = {c['energy']} "
                    f"(β = {c['beta']} > 0): |η| ≥ {c['eta_min']}, ξ ≤ {c['xi_max']}")
        elif c["motion"] == "both_centres":
            text = (f"A planetary orbit round both centres at E = {c['energy']} (β = "
                    f"{c['beta']} ≤ 0), between the ellipses ξ = {c['xi_min']} and "
                    f"{c['xi_max']}")
        elif c["motion"] == "through_middle":
            text = (f"A lemniscate orbit through the segment between the centres at E = "
                    f"{c['energy']} (β = {c['beta']} ≤ 0), inside the ellipse ξ = "
                    f"{c['xi_max']}")
        else:
            return f"An unbound orbit at E = {c['energy']} ≥ 0: it escapes from both centres"
        if c["near"]:
            text += (f"; it passes within {c['closest']} of a centre"
                     + (", integrated in regularized variables" if c["regularized"] else ""))
        return text

    @classmethod
    def headline(cls, data):
        p, a = data.config.params, data.analysis
        run = data.runs["main"]
        return [("centres", f"μ = {fmt(p.mu)} each at (±{fmt(p.a)}, 0)"),
                ("constants", f"E = {fmt(a['energy'])}, C = "
                              f"{fmt(a['separation_constant'])}, β = {fmt(a['beta'])}"),
                ("orbit family", MOTION_TEXT[motion_of(a)].format(
                    centre=centre_words(a, p))),
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
        # a table, set under the figure: the prose, the figure and its caption fit one page
        rows = [["ξ (dimensionless)", f"{fmt(xi_b[0])} to {fmt(xi_b[1])}",
                 f"{fmt(xr[0])} to {fmt(xr[1])}"],
                ["|η| (dimensionless)", f"{fmt(eta_b[0])} to {fmt(eta_b[1])}",
                 f"{fmt(er[0])} to {fmt(er[1])}"]]
        if "closest_approach_bound" in a:
            rows.append(["distance to the nearer centre [m]",
                         f"at least {fmt(float(a['closest_approach_bound']))}",
                         f"down to {fmt(float(a['closest_approach_run']))}"])
        table = Table(caption=f"The region of motion of this {FAMILY_NAME[motion_of(a)]} "
                              "orbit: the bounds from the separated equations, notes (7.59), "
                              "and what the sampled run reaches.",
                      header=["coordinate", "bounds from notes (7.59)", "sampled run"], rows=rows)
        # the dashed bounds are drawn only where (7.59) has them: none for an unbound orbit,
        # no hyperbola for a planetary or lemniscate orbit (η is free)
        dashed = [w for w, key in (("ξ", "ellipses"), ("η", "hyperbolas")) if key in bound]
        caption = ("The orbit over the elliptic-coordinate grid: confocal ellipses "
                   "ξ = (r1 + r2)/2a = const and hyperbolas η = (r1 − r2)/2a = const with foci "
                   "at the two centres.")
        if dashed:
            caption += (" Dashed: the coordinate lines where the momentum conjugate to "
                        + " or to ".join(dashed) + " vanishes, which bound the motion.")
        elif motion_of(a) == "escape":
            caption += " No coordinate line bounds an unbound orbit: ξ grows without limit."
        return SectionContent(figures=[cls.figure("orbit", fig, caption)], tables=[table])

    @classmethod
    def section_invariants(cls, data):
        return cls.invariants_section(data, labels={"energy": "energy E",
                                                    "separation_constant":
                                                        "separation constant C"},
                                      caption="Drift of E (relative to |V(0)|) and of the "
                                              "separation constant C (relative to "
                                              "max(|L1 L2|, 2aμ) at t = 0).")
