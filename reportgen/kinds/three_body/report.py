"""``three_body`` report: the tracks, the light body about its primary (in the lecture
notes' coordinates relative to body 1, notes (3.32)–(3.34), and in Jacobi coordinates, the
standard hierarchical choice not in the notes), the return after one period, pair distances
and the conserved quantities."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from .report_restricted import (
    RESTRICTED_FAMILY,
    RESTRICTED_SECTIONS,
    RestrictedReport,
    is_restricted,
)
from .results import RESTRICTED_SCHEMA, SCHEMA

plots = lazy_module("reportgen.rendering.plots.gravitation")
style = lazy_module("reportgen.rendering.plots.style")


class ThreeBodyReport(RestrictedReport):
    """The three-body sections, drawn from the archive alone (the restricted problem's:
    :class:`.RestrictedReport`)."""

    schema = SCHEMA.merged(RESTRICTED_SCHEMA)
    gallery_name = "Three bodies"
    gallery_figures = ("orbits", "restricted_section", "restricted_orbit")
    config_symbols = {"restricted.x": "x_0", "restricted.y": "y_0",
                      "restricted.vx": r"\dot{x}_0", "restricted.vy": r"\dot{y}_0",
                      "restricted.jacobi": "C", "restricted.mu": r"\mu"}

    @classmethod
    def gallery_headline(cls, data):
        from ...scene import gallery
        if is_restricted(data):
            return cls.restricted_gallery_headline(data)
        a = data.analysis
        energy = gallery.worst_check(data, "energy")
        drift = f"energy drift {gallery.distance(energy.rel_error)}" if energy else ""
        if math.isfinite(a.get("return_position_error", math.nan)):
            return (f"back at its start after one period T = {fmt(a['period'], 6)} within "
                    f"{fmt_err(a['return_position_error'])}; {drift}").strip("; ")
        moon = gallery.worst_check(data, "Moon")
        if moon is not None:
            return (f"Moon {gallery.distance(moon.rel_error)} from an independent tighter "
                    f"run; {drift}").strip("; ")
        if math.isfinite(a.get("min_pair_distance", math.nan)):
            return (f"closest approach {fmt(a['min_pair_distance'], 3)} at t = "
                    f"{fmt(a['min_pair_distance_time'], 4)}; {drift}").strip("; ")
        return drift or super().gallery_headline(data)

    sections = (
        Section("orbits", "Orbits", integrates=True),
        Section("moon", "The light body about its primary; the notes' coordinates and "
                "Jacobi's", integrates=True),
        Section("periodicity", "Return after one period", integrates=True),
        Section("encounters", "Pair distances and close encounters", integrates=True),
        Section("invariants", "Energy, momentum and angular momentum", integrates=True),
        *RestrictedReport.restricted_sections,
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )
    family_sections = RestrictedReport.restricted_family_sections

    @staticmethod
    def _positions(run) -> np.ndarray:
        """The archived positions as (N, 3, 3): time, body, xyz (columns x1 … z3 first)."""
        return np.asarray(run.y)[:, :9].reshape(-1, 3, 3)

    @classmethod
    def default_sections(cls, data):
        if is_restricted(data):
            return list(RESTRICTED_SECTIONS)
        names = [s.name for s in cls.sections if s.name not in RESTRICTED_SECTIONS
                 or s.name == "error_vs_runtime"]
        if not data.analysis.get("hierarchical", False):
            names.remove("moon")
        if data.config.period is None:
            names.remove("periodicity")
        return names

    #: a closest approach below this fraction of the initial size is a close encounter
    CLOSE_FRACTION = 0.05
    #: a return after the configured period within this fraction of the initial size is a
    #: periodic orbit (the figure-eight's initial data, known to 8 digits, return to ~1e-7)
    PERIODIC_FRACTION = 1e-3

    @classmethod
    def held_family_sections(cls, data):
        """The restricted problem's family sections for a restricted sweep only; its
        regions need the members' common Jacobi constant."""
        held = super().held_family_sections(data)
        if not is_restricted(data):
            return [n for n in held if n not in RESTRICTED_FAMILY]
        if "zero_velocity" not in data.analysis:
            held = [n for n in held if n != "restricted_regions"]
        return held

    @classmethod
    def family_words(cls, data):
        if is_restricted(data):
            return cls.restricted_family_words(data)
        return super().family_words(data)

    @classmethod
    def prose_case(cls, data):
        if is_restricted(data):
            return cls.restricted_case(data)
        """Periodic (a period to return after), hierarchical, or neither; the fate the
        behaviour verdict names (bound, escape, collision), chaotic or not; equal masses;
        released at rest; close encounters (closest approach under :attr:`CLOSE_FRACTION`
        of the initial size), from the archive alone."""
        a, cfg = data.analysis, data.config
        masses = [float(m) for m in cfg.params.masses]
        y0 = np.asarray(data.runs["main"].y[0]) if "main" in data.runs else np.zeros(18)
        pos0 = y0[:9].reshape(3, 3)
        size0 = float(max(np.linalg.norm(pos0[i] - pos0[j]) for i in range(3)
                          for j in range(i)))
        closest = float(a.get("min_pair_distance", math.nan))
        behaviour = str(a.get("behaviour", ""))
        ratios = a.get("mass_ratios") or {}
        returned = float(a.get("return_position_error", math.nan))
        # the preset's words only for the preset's physics: the figure-eight with one mass
        # changed is not the figure-eight (its "period" is the preset's, not its own)
        return {"restricted": False, "preset": str(cls.preset_as_given(cfg) or ""),
                "periodic": returned < cls.PERIODIC_FRACTION * size0,
                "returned": math.isfinite(returned),
                "return_error": fmt_err(returned),
                "hierarchical": bool(a.get("hierarchical", False)),
                "fate": behaviour.split(":", 1)[0] if behaviour else "",
                "binary": "form a binary" in behaviour,
                "chaotic": "lyapunov_time" in a,
                "lyapunov_time": fmt(float(a.get("lyapunov_time", math.nan)), 3),
                "study_t_end": (fmt(float(a["study_t_end"]), 3) if "study_t_end" in a
                                else ""),
                "equal_masses": len(set(masses)) == 1,
                "masses": ", ".join(fmt(m, 4) for m in masses),
                "at_rest": bool(np.all(y0[9:18] == 0.0)),
                "close": closest < cls.CLOSE_FRACTION * size0,
                "closest": fmt(closest, 3), "size0": fmt(size0, 3),
                "closest_time": fmt(float(a.get("min_pair_distance_time", math.nan)), 4),
                "period": fmt(float(a.get("period", math.nan)), 6),
                "ratio_2": fmt(float(ratios.get("m2_m1", math.nan)), 2),
                "ratio_3": fmt(float(ratios.get("m3_m1", math.nan)), 2),
                "cross_share": fmt_err(float(a.get("notes_cross_term_share", math.nan))),
                "names": list(cfg.names), "unit": str(cfg.length_unit or "")}

    @classmethod
    def describe(cls, data):
        """``Three equal masses on a periodic orbit, period 6.32591: back at the start
        within 4.1e-8``: the scene's case (periodic, hierarchical, or scattering with its
        fate) with its defining numbers."""
        if is_restricted(data):
            return cls.restricted_describe(data)
        c, a, cfg = cls.prose_case(data), data.analysis, data.config
        t_end = f"{fmt(float(data.runs['main'].t[-1]), 4)} {cfg.time_unit}".strip()
        if c["periodic"]:
            what = "the figure-eight choreography" if c["preset"] == "figure_eight" else \
                "a periodic orbit"
            bodies = "Three equal masses" if c["equal_masses"] else f"Masses {c['masses']}"
            return (f"{bodies} on {what}, period {c['period']}: back at the start within "
                    f"{fmt_err(float(a['return_position_error']))} after one period")
        start = "released at rest" if c["at_rest"] else "started in motion"
        fate = fate_words(c, t_end)
        if c["returned"]:  # a configured period the orbit does not return after
            return (f"Masses {c['masses']} {start}, not periodic: after the configured "
                    f"period T = {c['period']} the bodies are up to {c['return_error']} "
                    f"from their start" + (f"; {fate}" if fate else ""))
        if c["hierarchical"]:
            n = c["names"]
            return (f"A hierarchical triple over {t_end}: {n[2]} about {n[1]} "
                    f"(a = {fmt(float(a['moon_semi_major_axis']), 3)} {cfg.length_unit}), "
                    f"the pair about {n[0]} (mass ratios {c['ratio_2']} and {c['ratio_3']})")
        return (f"Masses {c['masses']} {start}"
                + (f", closest approach {c['closest']} (of an initial size {c['size0']})"
                   if c["close"] else "")
                + (f", {fate}" if fate else "")
                + (f"; chaotic, Lyapunov time ≈ {c['lyapunov_time']}" if c["chaotic"] else ""))

    @classmethod
    def headline(cls, data):
        if is_restricted(data):
            return cls.restricted_headline(data)
        p, a = data.config.params, data.analysis
        names = data.config.names
        out = [("bodies", ", ".join(f"{n}: m = {fmt(x)}" for n, x in zip(names, p.masses,
                                                                          strict=True))
                + f"; G = {fmt(p.G)}"),
               ("energy error", f"max relative |E(t) − E(0)|/|E(0)| = "
                                f"{fmt_err(a['energy_error_max'])} (tolerance "
                                f"{fmt_err(a['energy_tolerance'])})"),
               ("closest approach", f"{fmt(a['min_pair_distance'])} at t ≈ "
                                    f"{fmt(a['min_pair_distance_time'])}")]
        if "return_position_error" in a:
            out.append(("return after one period",
                        f"max |rᵢ(T) − rᵢ(0)| = {fmt_err(a['return_position_error'])}"))
        if "moon_period_measured" in a:
            out.append(("Moon about the Earth", f"period {fmt(a['moon_period_measured'])} "
                        f"{data.config.time_unit} (Kepler two-body "
                        f"{fmt(a['moon_kepler_period'])})"))
        return out

    @classmethod
    def section_orbits(cls, data):
        pos = cls._positions(data.runs["main"])
        names, unit = _plain(data.config.names), _plain(data.config.length_unit)
        fig = plots.three_body_orbits(pos, labels=names, length_unit=unit)
        figures = [cls.figure("orbits", fig, "Tracks of the three bodies projected on the "
                              "x–y plane.")]
        if (np.ptp(pos[:, :, 2]) > 1e-3 * np.ptp(pos[:, :, :2])
                and not data.analysis.get("hierarchical", False)):
            fig2 = plots.three_body_orbits(pos, labels=names, length_unit=unit, plane=(0, 2))
            figures.append(cls.figure("orbits_xz", fig2, "The same tracks in the x–z plane."))
        box = cls._encounter_box(data, pos)
        if box is not None:
            fig3 = plots.encounter_zoom(data.runs["main"].t, pos, box, labels=names,
                                        length_unit=unit,
                                        time_unit=_plain(data.config.time_unit))
            figures.append(cls.figure(
                "encounters_zoom", fig3, "Right: the region of the close encounters, "
                "enlarged, each track coloured by time (dashed box on the left); the bodies "
                "differ in line style."))
        return SectionContent(figures=figures)

    #: the zoom covers the square around the tracks' median point holding this share of
    #: the stored positions (grown by :attr:`ZOOM_MARGIN`) ...
    ZOOM_SHARE = 0.6
    ZOOM_MARGIN = 1.25
    #: ... and is drawn when the whole tracks span this many times its side
    ZOOM_RATIO = 3.0

    @classmethod
    def _encounter_box(cls, data, pos):
        """(x0, x1, y0, y1): the square where the bodies spend most of their time, the
        close encounters (the central "blob" of a scattering problem), or None when it
        would not enlarge the tracks :attr:`ZOOM_RATIO` times (a bound or hierarchical
        system fills its own picture)."""
        if data.analysis.get("hierarchical", False):
            return None
        xy = pos[:, :, :2].reshape(-1, 2)
        xy = xy[np.isfinite(xy).all(axis=1)]
        if len(xy) < 10:
            return None
        centre = np.median(xy, axis=0)
        half = cls.ZOOM_MARGIN * float(np.quantile(np.hypot(*(xy - centre).T), cls.ZOOM_SHARE))
        if half <= 0 or float(np.max(np.ptp(xy, axis=0))) < cls.ZOOM_RATIO * 2 * half:
            return None
        return (centre[0] - half, centre[0] + half, centre[1] - half, centre[1] + half)

    @classmethod
    def section_moon(cls, data):
        """The light body's track about its primary; the notes' coordinates r12, r13
        (notes (3.32)–(3.34)) with their mass matrix and cross-term kinetic energy against
        the Cartesian one; then Jacobi's ρ1, ρ2 with their diagonal kinetic energy."""
        a = data.analysis
        names, unit = data.config.names, data.config.length_unit
        rel = np.asarray(a["moon_relative_position"])
        shown = _plain(names)
        fig = plots.relative_track(rel[:, 0], rel[:, 1], label=f"{shown[2]} − {shown[1]}",
                                   centre_label=shown[1], length_unit=_plain(unit))
        jac = a["jacobi_coordinates"]
        rho1, rho2 = np.asarray(jac["rho1"]), np.asarray(jac["rho2"])
        # lower than the tracks figure, so that it shares a page with the relative track
        _, ax = style.new_figure(figsize=(6.4, 3.5))
        fig2 = plots.three_body_orbits(
            np.stack([rho1, rho2, np.zeros_like(rho1)], axis=1)[:, :2],
            labels=["ρ1 = r2 − r1", "ρ2 = r3 − (m1 r1 + m2 r2)/(m1 + m2)"],
            length_unit=_plain(unit), ax=ax)
        r13 = np.asarray(a["notes_coordinates"]["r13"])
        M, mu1, mu2 = np.asarray(a["jacobi_masses"])
        K = np.asarray(a["notes_mass_matrix"])
        m1, m2, m3 = (float(x) for x in data.config.params.masses)
        ratios = a["mass_ratios"]
        length = f" {unit}" if unit else ""
        facts = [("mass ratios, notes (3.35)", f"m2/m1 = {fmt(ratios['m2_m1'])}, "
                                               f"m3/m1 = {fmt(ratios['m3_m1'])}"),
                 ("the notes' mass matrix K", f"K11 = m2(m1 + m3)/M = {fmt(K[0, 0])}, "
                                              f"K22 = m3(m1 + m2)/M = {fmt(K[1, 1])}"),
                 ("its off-diagonal K12 = K21", f"{_signed(K[0, 1])}, against −m2 m3/M = "
                                                f"{_signed(-m2 * m3 / (m1 + m2 + m3))}"),
                 ("T in the notes' coordinates against Cartesian T",
                  f"max relative difference {fmt_err(a['notes_kinetic_identity_error'])}"),
                 ("its cross term −(m2 m3/M) ṙ12·ṙ13",
                  f"up to {fmt_err(a['notes_cross_term_share'])} of T"),
                 ("Jacobi masses (not in the notes)",
                  f"M = {fmt(M)}, μ1 = {fmt(mu1)}, μ2 = {fmt(mu2)}"),
                 ("T in Jacobi coordinates against Cartesian T",
                  f"max relative difference {fmt_err(a['jacobi_kinetic_identity_error'])}"),
                 (f"{names[2]}'s orbit about {names[1]}",
                  f"a = {fmt(a['moon_semi_major_axis'])}{length}, inclination "
                  f"{fmt(math.degrees(a['moon_inclination']), 5)}°")]
        rows = []
        if "moon_period_measured" in a:
            rows.append(["sidereal period, measured", fmt(a["moon_period_measured"])])
        rows.append(["two-body Kepler period", fmt(a["moon_kepler_period"])])
        # what the two tracks of the Jacobi figure differ by, and what the notes' r13
        # differs from ρ2 by (r13 − ρ2 = m2 r12/(m1 + m2)): a figure of the notes' r12, r13
        # would look the same
        orbit = float(np.max(np.linalg.norm(rho2 - rho1, axis=1)))
        apart = float(np.max(np.linalg.norm(r13 - rho2, axis=1)))
        return SectionContent(
            figures=[cls.figure("moon", fig, f"{names[2]}'s track relative to {names[1]}: a "
                                "near-Keplerian ellipse slowly perturbed by the Sun's tide."),
                     cls.figure("jacobi", fig2, "Jacobi coordinates (the standard "
                                "hierarchical choice; not in the notes): ρ1, the inner pair's "
                                "separation, and ρ2, the third body from the inner pair's "
                                "centre of mass (x–y projection). The two tracks lie within "
                                f"{fmt(orbit, 3)}{length} of each other and overlap at this "
                                "scale; the notes' r12 is ρ1, and the notes' r13 differs from ρ2 by "
                                f"at most {fmt(apart, 3)}{length}.")],
            facts=facts,
            tables=[Table(caption=f"{names[2]}'s period about {names[1]} "
                                  f"[{data.config.time_unit}]", header=["", "value"],
                          rows=rows)])

    @classmethod
    def section_periodicity(cls, data):
        a = data.analysis
        return SectionContent(facts=[
            ("period T", fmt(a["period"])),
            ("max |rᵢ(T) − rᵢ(0)|", fmt_err(a["return_position_error"])),
            ("max |vᵢ(T) − vᵢ(0)|", fmt_err(a["return_velocity_error"]))])

    @classmethod
    def section_encounters(cls, data):
        run, a = data.runs["main"], data.analysis
        d = a["pair_distances"]
        n = _plain(data.config.names)
        fig = plots.closest_approach(run.t, {f"{n[0]}–{n[1]}": d["r12"],
                                             f"{n[0]}–{n[2]}": d["r13"],
                                             f"{n[1]}–{n[2]}": d["r23"]},
                                     time_unit=_plain(data.config.time_unit),
                                     length_unit=_plain(data.config.length_unit))
        return SectionContent(
            figures=[cls.figure("pair_distances", fig, "Distances between the bodies (log "
                                "scale); close encounters are the deep minima, sampled at the "
                                "stored times only.")],
            facts=[("smallest stored pair distance", f"{fmt(a['min_pair_distance'])} at t ≈ "
                                                     f"{fmt(a['min_pair_distance_time'])}")])

    @classmethod
    def section_invariants(cls, data):
        labels = {q.name: q.description for q in cls.schema.invariants}
        return cls.invariants_section(data, labels=labels, time_unit=data.config.time_unit,
                                      caption=(
            "Drift of energy (relative to the initial potential energy), total momentum and "
            "angular momentum (relative to natural momentum scales)."))


def fate_words(case, t_end):
    """The fate of a scattering run in words: ``ending in an escape and a binary``."""
    return {"escape": "ending in an escape" + (" and a binary" if case["binary"] else ""),
            "bound": f"still bound at t = {t_end}",
            "collision": "ending in a collision"}.get(case["fate"], "")


def _signed(x):
    """A number for prose with a typeset minus sign (−1.1e-13)."""
    return f"−{fmt(-x)}" if x < 0 else fmt(x)


def _plain(text):
    """Config text (body names, units) for matplotlib: ``$`` escaped, so that a name is
    drawn as written and never parsed as mathtext (``$\\frac{`` would not parse)."""
    if isinstance(text, str):
        return text.replace("$", r"\$")
    return [_plain(t) for t in text]
