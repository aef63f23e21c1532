"""``three_body`` report with ``[restricted]``: the orbit over the zero-velocity curves, the
Jacobi constant, and a family's surface of section y = 0 (ẏ > 0) with the regions its
Jacobi constant allows (Murray & Dermott ch. 3 and §9.4).  Drawn from the archive alone."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from ...scene.report import Report, section_colours, section_point_notes
from ...scene.schema import Quantity

section_plots = lazy_module("reportgen.rendering.plots.sections")
restricted_plots = lazy_module("reportgen.kinds.three_body.plots")

#: the single run's sections, and the family's
RESTRICTED_SECTIONS = ("restricted_orbit", "jacobi", "error_vs_runtime")
RESTRICTED_FAMILY = ("restricted_section", "restricted_regions")
#: axis labels of the rotating frame's units: lengths in the separation a of the
#: primaries, velocities in a n (n their mean motion)
X_LABEL, XDOT_LABEL = "$x$ [a]", r"$\mathrm{d}x/\mathrm{d}t$ [a n]"
LAGRANGE = ("L1", "L2", "L3", "L4", "L5")


def is_restricted(data) -> bool:
    """Whether the archive is of the restricted problem (its config has ``[restricted]``)."""
    return getattr(data.config, "restricted", None) is not None


def minus(text: str) -> str:
    """A number's text with a typeset minus sign."""
    return text.replace("-", "−") if "e-" not in text else text


class RestrictedReport(Report):
    """The ``[restricted]`` sections (see the module docstring)."""

    restricted_sections = (
        Section("restricted_orbit", "Orbit in the rotating frame and the zero-velocity curves",
                integrates=True),
        Section("jacobi", "The Jacobi constant", integrates=True),
    )
    restricted_family_sections = (
        Section("restricted_section", "Surface of section y = 0 from many orbits",
                description="Every member's crossings of the line through the primaries "
                            "(y = 0, ẏ > 0) in (x, ẋ), each orbit coloured by its starting "
                            "point, inside the edge its Jacobi constant allows.",
                points="poincare"),
        Section("restricted_regions", "Zero-velocity curves and the Lagrange points",
                description="The regions of the plane the family's Jacobi constant allows, "
                            "the Lagrange points and where the orbits start."),
    )
    #: a restricted family's results figure leaves out the Jacobi constant's absolute error
    #: (its error relative to 2Ω, the one judged, is drawn; the section's table gives both)
    SWEEP_HIDDEN_RESULTS = ("jacobi_error_max",)
    #: members told apart by a legend; more get a colour bar
    LEGEND_MEMBERS = 7
    #: the section's view holds the crossings at least NEAR (in a) from both primaries,
    #: grown by VIEW_MARGIN: the crossings next to a primary, where ẋ grows as 1/√r,
    #: would squeeze the islands into a line (they lie in a narrow band above and below it)
    NEAR = 0.1
    VIEW_MARGIN = 1.1

    # ------------------------------------------------------------------ units
    #: the rotating frame's units of the config keys and results that have one: lengths
    #: in the separation a, velocities in a n
    UNITS = {"restricted.x": "a", "restricted.y": "a", "restricted.vx": "a n",
             "restricted.vy": "a n", "closest_approach_1": "a", "closest_approach_2": "a"}

    @classmethod
    def swept_keys(cls, data):
        keys = super().swept_keys(data)
        if is_restricted(data):
            keys = {p: (sym, cls.UNITS.get(p, unit)) for p, (sym, unit) in keys.items()}
        return keys

    @classmethod
    def colour_key_label(cls, data, key):
        if is_restricted(data) and key in cls.UNITS:
            return f"{cls.config_quantity(data, key).math} [{cls.UNITS[key]}]"
        return super().colour_key_label(data, key)

    @classmethod
    def result_quantity(cls, data, name):
        q = super().result_quantity(data, name)
        if is_restricted(data) and name in cls.UNITS:
            return Quantity(q.name, q.symbol, cls.UNITS[name], q.description, q.dims, q.kind,
                            q.optional)
        return q

    # ------------------------------------------------------------------ words
    @staticmethod
    def primary_names(data) -> tuple[str, str, str]:
        """(larger primary, smaller primary, particle) as the page names them: the
        config's ``names`` when given, else "primary 1", "primary 2", "particle"."""
        names = list(data.config.names)
        if names == ["body 1", "body 2", "body 3"]:
            return "primary 1", "primary 2", "particle"
        return names[0], names[1], names[2]

    @classmethod
    def restricted_case(cls, data) -> dict:
        """What the restricted prose branches on, from the archive alone."""
        a, r = data.analysis, data.config.restricted
        C = a.get("poincare_jacobi", a.get("jacobi_constant"))
        lag = a.get("lagrange_points") or {}
        CL = [float(c) for c in np.asarray(lag.get("jacobi", [math.nan] * 5))]
        big, small, particle = cls.primary_names(data)
        return {"restricted": True, "mu": fmt(float(r.mu)), "jacobi": fmt(float(C), 6)
                if C is not None else "", "region": str(a.get("region", "")),
                "big": big, "small": small, "particle": particle,
                "C_L": [fmt(c, 6) for c in CL],
                "between_L1_L2": C is not None and CL[1] < float(C) < CL[0],
                "sweep": data.sweep is not None,
                "chaotic": "lyapunov_time" in a,
                "study_t_end": (fmt(float(a["study_t_end"]), 3) if "study_t_end" in a
                                else ""),
                "lyapunov_time": fmt(float(a.get("lyapunov_time", math.nan)), 3),
                "regularized": str(a.get("formulation", "regularized")) == "regularized"}

    @classmethod
    def restricted_title(cls, config) -> str:
        r = config.restricted
        C = r.jacobi_constant()
        return (f"Restricted three-body problem (μ = {minus(fmt(r.mu, 4))}): an orbit from "
                f"x = {minus(fmt(r.x, 4))} at C = {minus(fmt(C, 6))}")

    @classmethod
    def restricted_describe(cls, data) -> str:
        a = data.analysis
        return (f"A test particle in the rotating frame of two primaries with μ = "
                f"{fmt(float(data.config.restricted.mu))}, Jacobi constant C = "
                f"{fmt(float(a['jacobi_constant']), 6)}; " + str(a.get("behaviour", "")))

    @classmethod
    def restricted_family_words(cls, data) -> str:
        sweep, a = data.sweep, data.analysis
        words = [f"{sweep.size} orbits of the restricted three-body problem (μ = "
                 f"{fmt(float(data.config.restricted.mu))})"]
        if "poincare_jacobi" in a:
            words.append(f"at one Jacobi constant C = {fmt(float(a['poincare_jacobi']), 6)}")
        for path, values in sweep.values.items():
            lo, hi = (minus(fmt(float(f(values)), 4)) for f in (np.min, np.max))
            words.append(f"{cls.config_words(data, path)} from {lo} to {hi}")
        return ", ".join(words)

    @classmethod
    def restricted_headline(cls, data) -> list[tuple[str, str]]:
        a, run = data.analysis, data.runs["main"]
        big, small, _ = cls.primary_names(data)
        return [("primaries", f"{big}: 1 − μ, {small}: μ = {fmt(float(a['mu']))}"),
                ("Jacobi constant", f"C = {fmt(float(a['jacobi_constant']))}; gates open: "
                                    f"{a['region']}"),
                ("Jacobi constant error", f"max |C − C(0)| = {fmt_err(a['jacobi_error_max'])}; "
                                          f"relative to 2Ω {fmt_err(a['jacobi_error_relative'])}"
                                          f" (tolerance {fmt_err(a['jacobi_tolerance'])})"),
                ("closest sampled approach", f"{fmt(a['closest_approach_1'], 4)} a to {big}, "
                                             f"{fmt(a['closest_approach_2'], 4)} a to {small}"),
                ("formulation", "Thiele–Burrau regularized (DOP853 in fictitious time)"
                 if run.attrs.get("formulation") == "regularized" else "Cartesian")]

    @classmethod
    def restricted_gallery_headline(cls, data) -> str:
        from ...scene import gallery
        a = data.analysis
        if gallery.is_family(data):
            c = gallery.worst_check(data, "Jacobi")
            members, ok = a["sweep_members"], a.get("sweep_ok", 0)
            return (f"{members} orbits on the section"
                    + (f" at C = {fmt(a['poincare_jacobi'], 6)}" if "poincare_jacobi" in a
                       else "") + (", all ok" if ok == members else f", {ok} ok")
                    + (f"; Jacobi constant kept to {gallery.distance(c.rel_error)}"
                       if c is not None else ""))
        c = gallery.worst_check(data, "Jacobi")
        return (f"Jacobi constant kept to {gallery.distance(c.rel_error)}" if c is not None
                else super().gallery_headline(data))

    # ---------------------------------------------------------------- figures
    @classmethod
    def _regions_figure(cls, data, C, track=None, starts=None):
        a = data.analysis
        grid, lag = a["zero_velocity"], a["lagrange_points"]
        mu = float(data.config.restricted.mu)
        big, small, _ = cls.primary_names(data)
        return restricted_plots.hill_regions(
            grid["x"], grid["y"], grid["level"], primaries=((-mu, 0.0), (1.0 - mu, 0.0)),
            names=(f"{big} (mass 1 − μ)", f"{small} (mass μ)"),
            lagrange=(lag["x"], lag["y"]), track=track, starts=starts)

    @classmethod
    def _lagrange_table(cls, data, C: float) -> Table:
        lag = data.analysis["lagrange_points"]
        rows = []
        for k, name in enumerate(LAGRANGE):
            CL = float(lag["jacobi"][k])
            rows.append([name, minus(fmt(float(lag["x"][k]))), minus(fmt(float(lag["y"][k]))),
                         fmt(CL), "open" if C < CL else "closed"])
        return Table(caption=f"The Lagrange points, the Jacobi constant at each, and whether "
                             f"the level C = {fmt(C, 6)} opens the region there (C below "
                             "the point's; Murray & Dermott §3.5–3.6, §3.10). Lengths in "
                             "units of the separation a.",
                     header=["point", "x [a]", "y [a]", "C there", f"at C = {fmt(C, 6)}"],
                     rows=rows)

    # ------------------------------------------------------- single-run sections
    @classmethod
    def section_restricted_orbit(cls, data):
        run, a = data.runs["main"], data.analysis
        C = float(a["jacobi_constant"])
        fig = cls._regions_figure(data, C, track=(run["x"], run["y"]))
        caption = (f"The orbit in the frame rotating with the primaries, over the region the "
                   f"level C = {fmt(C, 6)} forbids (shaded, 2Ω < C), bounded by the "
                   "zero-velocity curves 2Ω = C; crosses: the Lagrange points. Lengths in "
                   "units of the primaries' separation a.")
        return SectionContent(figures=[cls.figure("restricted_orbit", fig, caption)],
                              tables=[cls._lagrange_table(data, C)])

    @classmethod
    def section_jacobi(cls, data):
        return cls.invariants_section(
            data, labels={"jacobi_constant": "Jacobi constant C"},
            caption="Drift of the Jacobi constant C = 2Ω − v², relative to the largest term "
                    "2Ω of the run (next to a primary both terms grow as 2/r).")

    # ---------------------------------------------------------- family sections
    @classmethod
    def section_restricted_section(cls, data):
        sweep, a = data.sweep, data.analysis
        mu = float(data.config.restricted.mu)
        big, small, _ = cls.primary_names(data)
        pts = sweep.points["poincare"]
        u, v = np.asarray(pts.columns["u"]), np.asarray(pts.columns["v"])
        member = np.asarray(pts.member)
        kept = pts.counts(sweep.size)
        crossing, key, colour, labels = section_colours(sweep, pts, cls.LEGEND_MEMBERS)
        grid = a.get("poincare_grid")
        C = a.get("poincare_jacobi")
        fig = section_plots.poincare_family(
            u, v, member, colour, X_LABEL, XDOT_LABEL,
            colour_label=cls.colour_key_label(data, key), labels=labels,
            edge=None if grid is None else (grid["u"], grid["v"], grid["vy2"], 0.0),
            edge_label=None if grid is None else f"ẏ = 0 at C = {fmt(float(C), 6)}",
            lines=[(-mu, f"a primary ({big}, {small})"), (1.0 - mu,
                                                          f"a primary ({big}, {small})")],
            legend_below=True)
        far = (np.abs(u + mu) > cls.NEAR) & (np.abs(u - 1.0 + mu) > cls.NEAR)
        limit = cls.VIEW_MARGIN * float(np.max(np.abs(v[far]))) if np.any(far) else math.inf
        outside = int(np.sum(np.abs(v) > limit))
        if outside:
            fig.axes[0].set_ylim(-limit, limit)
        notes = section_point_notes(sweep, "poincare", kept, "cross y = 0 upward")
        if outside:
            notes.append(f"{outside} of the {len(v)} crossings lie beyond |ẋ| = "
                         f"{fmt(limit, 3)} a n, above and below the view: all within "
                         f"{fmt(cls.NEAR, 2)} a of a primary, where ẋ grows as 1/√r (the "
                         "view holds every crossing farther from both); the archive keeps "
                         "them all.")
        caption = ("Surface of section y = 0 crossed with ẏ > 0 (the line through the "
                   f"primaries): (x, ẋ) at the crossings of {len(crossing)} orbits, each in "
                   "its own colour " + (f"(colour bar: {cls._colour_words(data, key)})"
                                        if labels is None else "(legend)")
                   + ". Regular orbits lie on closed curves (islands about stable periodic "
                   "orbits), chaotic ones scatter over the area between them"
                   + ("; dark: ẏ = 0, the edge of the region the Jacobi constant allows"
                      if grid is not None else "")
                   + ". Lengths in units of the separation a, velocities in a n.")
        return SectionContent(figures=[cls.figure("restricted_section", fig, caption)],
                              notes=notes)

    @classmethod
    def sweep_headline(cls, data):
        """The family's facts, and for a restricted one its section's: orbits and
        crossings, the common C, the Jacobi constant's worst error against the tolerance,
        the closest approaches to the primaries, the formulation."""
        facts = super().sweep_headline(data)
        pts = data.sweep.points.get("poincare")
        if not is_restricted(data) or pts is None or not len(pts.member):
            return facts
        return facts + cls._family_facts(data)

    @classmethod
    def _family_facts(cls, data) -> list[tuple[str, str]]:
        sweep, a = data.sweep, data.analysis
        big, small, _ = cls.primary_names(data)
        pts = sweep.points["poincare"]
        kept = pts.counts(sweep.size)
        crossing = np.flatnonzero(kept)
        facts = [("orbits on the section", f"{len(crossing)} of {sweep.size} cross y = 0 "
                                           f"upward; {len(pts.member)} crossings "
                                           f"({int(kept[crossing].min())} to "
                                           f"{int(kept[crossing].max())} per orbit)")]
        C = a.get("poincare_jacobi")
        if C is not None:
            facts.append(("Jacobi constant of every orbit", f"C = {fmt(float(C))}; gates "
                                                           f"open: {a.get('region', '')}"))
        facts += cls._jacobi_facts(sweep, a)
        approach = []
        for name, who in (("closest_approach_1", big), ("closest_approach_2", small)):
            d = np.asarray(sweep.analysis.get(name, []), dtype=float)
            if d.size and np.any(np.isfinite(d)):
                approach.append(f"{fmt(float(np.nanmin(d)), 3)} a to {who}")
        if approach:
            facts.append(("closest sampled approach", ", ".join(approach)
                          + " (over all orbits; regularized, so no orbit is stopped)"))
        formulation = sweep.labels.get("formulation")
        if formulation is not None:
            n = int(np.sum(np.asarray(formulation) == "regularized"))
            facts.append(("formulation", f"{n} of {len(formulation)} orbits in the "
                                         "Thiele–Burrau regularized variables"))
        return facts

    @classmethod
    def _jacobi_facts(cls, sweep, a) -> list[tuple[str, str]]:
        """The worst member's Jacobi constant error, absolute and relative to 2Ω, against
        the tolerance: "ok" only when every member is within it."""
        err = np.asarray(sweep.analysis.get("jacobi_error_max", []), dtype=float)
        rel = np.asarray(sweep.analysis.get("jacobi_error_relative", []), dtype=float)
        tol = np.asarray(sweep.analysis.get("jacobi_tolerance", []), dtype=float)
        if not err.size or not np.any(np.isfinite(err)):
            return []
        worst = float(np.nanmax(rel))
        limit = float(np.nanmin(tol)) if tol.size and np.any(np.isfinite(tol)) else math.nan
        verdict = ("ok: within the tolerance" if worst <= limit
                   else "above the tolerance: those members are flagged unstable")
        return [("Jacobi constant error over every orbit",
                 f"max |C − C(0)| = {fmt_err(float(np.nanmax(err)))} over the samples and "
                 f"crossings; relative to 2Ω at the same point {fmt_err(worst)} (tolerance "
                 f"{fmt_err(limit)}): {verdict}")]

    @classmethod
    def _colour_words(cls, data, key: str) -> str:
        if key == "member":
            return "the member's number"
        return f"the starting point {cls.config_words(data, key)}" \
            if key == "restricted.x" else f"the swept {cls.config_words(data, key)}"

    @classmethod
    def section_restricted_regions(cls, data):
        sweep, a = data.sweep, data.analysis
        C = float(a["poincare_jacobi"])
        starts = None
        if "restricted.x" in sweep.values:
            x0 = np.asarray(sweep.values["restricted.x"], dtype=float)
            starts = (float(np.min(x0)), float(np.max(x0)))
        fig = cls._regions_figure(data, C, starts=starts)
        caption = (f"The plane of the rotating frame at C = {fmt(C, 6)}: shaded, the region "
                   "the level forbids (2Ω < C), bounded by the zero-velocity curves 2Ω = C; "
                   "crosses: the Lagrange points"
                   + ("; blue: the segment of y = 0 where the orbits start" if starts else "")
                   + ". Lengths in units of the separation a.")
        return SectionContent(figures=[cls.figure("restricted_regions", fig, caption)],
                              tables=[cls._lagrange_table(data, C)])
