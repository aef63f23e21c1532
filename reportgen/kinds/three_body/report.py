"""``three_body`` report: the tracks, the light body about its primary (in the lecture
notes' coordinates relative to body 1, notes (3.32)–(3.34), and in Jacobi coordinates, the
standard hierarchical choice not in the notes), the return after one period, pair distances
and the conserved quantities."""

from __future__ import annotations

import math
from dataclasses import replace

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
        if "moon_pair" in a:
            primary, moon = (data.config.names[int(k) - 1] for k in a["moon_pair"])
            check = gallery.worst_check(data, f"{moon} about {primary}")
            if check is not None:
                return (f"{moon} {gallery.distance(check.rel_error)} from an independent "
                        f"tighter run; {drift}").strip("; ")
        closest = a.get("closest_approach", a.get("min_pair_distance", math.nan))
        if math.isfinite(closest):
            when = a.get("closest_approach_time", a.get("min_pair_distance_time"))
            return (f"closest approach {fmt(closest, 3)} at t = {fmt(when, 4)}; "
                    f"{drift}").strip("; ")
        return drift or super().gallery_headline(data)

    sections = (
        Section("orbits", "Orbits", integrates=True),
        Section("moon", "The inner pair; the notes' coordinates and Jacobi's",
                integrates=True),
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

    @classmethod
    def chosen_sections(cls, data):
        """The sections, the pair distances' titled by whether close encounters happened
        (``/analysis`` ``close_encounters``)."""
        chosen = super().chosen_sections(data)
        if data.sweep is not None or data.analysis.get("close_encounters", True):
            return chosen
        return [replace(s, title="Pair distances") if s.name == "encounters" else s
                for s in chosen]

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
        """Periodic (a choreography, a figure-eight), hierarchical, or neither; the fate
        (bound, unbound, escape, collision), chaotic or not; equal masses; released at rest;
        close encounters; Burrau's configuration: each from its stored classification."""
        if is_restricted(data):
            return cls.restricted_case(data)
        a, cfg = data.analysis, data.config
        names = list(cfg.names)
        masses = [float(m) for m in cfg.params.masses]
        y0 = np.asarray(data.runs["main"].y[0]) if "main" in data.runs else np.zeros(18)
        pos0 = y0[:9].reshape(3, 3)
        size0 = float(max(np.linalg.norm(pos0[i] - pos0[j]) for i in range(3)
                          for j in range(i)))
        closest = float(a.get("closest_approach", a.get("min_pair_distance", math.nan)))
        pair = [int(k) for k in a.get("closest_approach_pair", [1, 2])]
        behaviour = str(a.get("behaviour", ""))
        ratios = a.get("mass_ratios") or {}
        returned = float(a.get("return_position_error", math.nan))
        inner = [int(k) - 1 for k in a.get("inner_pair", [2, 3])]
        outer = 3 - sum(inner)
        moon = [int(k) - 1 for k in a.get("moon_pair", inner)]
        inner_sep = [float(v) for v in np.asarray(a.get("inner_separation", [math.nan] * 3))]
        outer_d = [float(v) for v in np.asarray(a.get("outer_distance", [math.nan] * 3))]
        unit = str(cfg.length_unit or "")
        spread = float(a.get("moon_semi_major_axis_spread", math.nan))
        return {"restricted": False,
                "periodic": bool(a.get("periodic", False)),
                "choreography": bool(a.get("choreography", False)),
                "figure_eight": bool(a.get("figure_eight", False)),
                "returned": math.isfinite(returned),
                "return_error": fmt_err(returned),
                "hierarchical": bool(a.get("hierarchical", False)),
                "fate": str(a.get("fate", behaviour.split(":", 1)[0] if behaviour else "")),
                "binary": "form a binary" in behaviour,
                "chaotic": "lyapunov_time" in a,
                "lyapunov_time": fmt(float(a.get("lyapunov_time", math.nan)), 3),
                "study_t_end": (fmt(float(a["study_t_end"]), 3) if "study_t_end" in a
                                else ""),
                "equal_masses": len(set(masses)) == 1,
                "masses": ", ".join(fmt(m, 4) for m in masses),
                "at_rest": bool(np.all(y0[9:18] == 0.0)),
                "close": bool(a.get("close_encounters", False)),
                "burrau": bool(a.get("burrau", False)),
                "closest": fmt(closest, 3), "size0": fmt(size0, 3),
                "closest_time": fmt(float(a.get("closest_approach_time",
                                                a.get("min_pair_distance_time", math.nan))), 4),
                "closest_pair": f"{names[pair[0] - 1]} and {names[pair[1] - 1]}",
                "sampled": fmt(float(a.get("min_pair_distance", math.nan)), 3),
                "period": fmt(float(a.get("period", math.nan)), 6),
                "ratio_2": fmt(float(ratios.get("m2_m1", math.nan)), 2),
                "ratio_3": fmt(float(ratios.get("m3_m1", math.nan)), 2),
                "cross_share": fmt_err(float(a.get("notes_cross_term_share", math.nan))),
                "inner": [names[inner[0]], names[inner[1]]], "outer": names[outer],
                "inner_first": inner == [0, 1],
                "primary": names[moon[0]], "moon": names[moon[1]],
                "outer_heaviest": masses[outer] > max(masses[inner[0]], masses[inner[1]]),
                "inner_range": _range(inner_sep[0], inner_sep[2]),
                "outer_range": _range(outer_d[0], outer_d[2]),
                "coincide": float(a.get("hierarchy_ratio", math.nan)) < cls.COINCIDE_RATIO,
                "keplerian": spread < float(a.get("kepler_spread_threshold", 0.1)),
                "spread": fmt(spread, 2),
                "moon_shown": ("moon_relative_position" in a
                               and "moon" in (cfg.report.sections or ("moon",))),
                "names": names, "unit": unit}

    #: a hierarchical triple whose inner pair's largest separation is below this fraction of
    #: the third body's smallest distance draws the pair's two tracks on top of each other
    COINCIDE_RATIO = 0.02

    @classmethod
    def describe(cls, data):
        """``Three equal masses on the figure-eight choreography, period 6.32591: back at
        the start within 4.1e-8``: the scene's case (periodic, hierarchical, or scattering
        with its fate) with its defining numbers."""
        if is_restricted(data):
            return cls.restricted_describe(data)
        c, a, cfg = cls.prose_case(data), data.analysis, data.config
        t_end = f"{fmt(float(data.runs['main'].t[-1]), 4)} {cfg.time_unit}".strip()
        if c["periodic"]:
            what = ("the figure-eight choreography" if c["figure_eight"] else
                    "a choreography" if c["choreography"] else "a periodic orbit")
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
            unit = f" {cfg.length_unit}" if cfg.length_unit else ""
            return (f"A hierarchical triple over {t_end}: {c['moon']} about {c['primary']} "
                    f"(a = {fmt(float(a['moon_semi_major_axis']), 3)}{unit}), the pair "
                    f"{c['outer_range']}{unit} from {c['outer']} (masses {c['masses']})")
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
        c = cls.prose_case(data)
        out = [("bodies", ", ".join(f"{n}: m = {fmt(x)}" for n, x in zip(names, p.masses,
                                                                          strict=True))
                + f"; G = {fmt(p.G)}"),
               ("energy error", f"max relative |E(t) − E(0)|/|E(0)| = "
                                f"{fmt_err(a['energy_error_max'])} (tolerance "
                                f"{fmt_err(a['energy_tolerance'])})")]
        if "closest_approach" in a:
            out.append(("closest approach", f"{fmt(a['closest_approach'])} ({c['closest_pair']}) "
                                            f"at t ≈ {fmt(a['closest_approach_time'])}, "
                                            "located between the samples"))
        else:
            out.append(("smallest sampled pair distance", f"{fmt(a['min_pair_distance'])} at "
                                                          f"t ≈ {fmt(a['min_pair_distance_time'])}"))
        if "return_position_error" in a:
            out.append(("return after one period",
                        f"max |rᵢ(T) − rᵢ(0)| = {fmt_err(a['return_position_error'])}"))
        if "moon_period_measured" in a:
            out.append((f"{c['moon']} about {c['primary']}", f"period "
                        f"{fmt(a['moon_period_measured'])} {data.config.time_unit} (Kepler "
                        f"two-body {fmt(a['moon_kepler_period'])})".replace("  ", " ")))
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
            close = bool(data.analysis.get("close_encounters", False))
            fig3 = plots.encounter_zoom(data.runs["main"].t, pos, box, labels=names,
                                        length_unit=unit,
                                        time_unit=_plain(data.config.time_unit),
                                        close_encounters=close)
            where = ("the region of the close encounters" if close
                     else "the region where the bodies spend most of their time (no close "
                          "encounters)")
            figures.append(cls.figure(
                "encounters_zoom", fig3, f"Right: {where}, enlarged, each track coloured by "
                "time (dashed box on the left); the bodies differ in line style."))
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
        c = cls.prose_case(data)
        unit = data.config.length_unit
        rel = np.asarray(a["moon_relative_position"])
        primary, moon = _plain(c["primary"]), _plain(c["moon"])
        fig = plots.relative_track(rel[:, 0], rel[:, 1], label=f"{moon} − {primary}",
                                   centre_label=primary, length_unit=_plain(unit))
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
                 ("its off-diagonal K12 = K21", f"{_signed(K[0, 1])}, against −m₂ m₃/M = "
                                                f"{_signed(-m2 * m3 / (m1 + m2 + m3))}"),
                 ("T in the notes' coordinates against Cartesian T",
                  f"max relative difference {fmt_err(a['notes_kinetic_identity_error'])}"),
                 ("its cross term −(m2 m3/M) ṙ12·ṙ13",
                  f"up to {fmt_err(a['notes_cross_term_share'])} of T"),
                 ("Jacobi masses (not in the notes)",
                  f"M = {fmt(M)}, μ1 = {fmt(mu1)}, μ2 = {fmt(mu2)}"),
                 ("T in Jacobi coordinates against Cartesian T",
                  f"max relative difference {fmt_err(a['jacobi_kinetic_identity_error'])}"),
                 (f"{c['moon']}'s orbit about {c['primary']}",
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
        shape = (f"a near-Keplerian ellipse perturbed by the tide of {c['outer']} (its "
                 f"osculating semi-major axis varies by {c['spread']} of its mean)"
                 if c["keplerian"] else
                 f"far from one Kepler ellipse: under the tide of {c['outer']} its osculating "
                 f"semi-major axis varies by {c['spread']} of its mean")
        pair = ("ρ1, the inner pair's separation, and ρ2, the third body from the inner "
                "pair's centre of mass" if c["inner_first"] else
                "ρ1, the separation of the first two bodies, and ρ2, the third body from "
                "their centre of mass")
        time_unit = f" [{data.config.time_unit}]" if data.config.time_unit else ""
        return SectionContent(
            figures=[cls.figure("moon", fig, f"{c['moon']}'s track relative to "
                                             f"{c['primary']}: {shape}."),
                     cls.figure("jacobi", fig2, "Jacobi coordinates (the standard "
                                f"hierarchical choice; not in the notes): {pair} (x–y "
                                "projection). The two tracks lie within "
                                f"{fmt(orbit, 3)}{length} of each other; the notes' r12 is ρ1, "
                                "and the notes' r13 differs from ρ2 by "
                                f"at most {fmt(apart, 3)}{length}.")],
            facts=facts,
            tables=[Table(caption=f"{c['moon']}'s period about {c['primary']}{time_unit}",
                          header=["", "value"], rows=rows)])

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
        c = cls.prose_case(data)
        minima = None
        if "pair_closest" in a:
            minima = (np.asarray(a["pair_closest_time"]), np.asarray(a["pair_closest"]))
        fig = plots.closest_approach(run.t, {f"{n[0]}–{n[1]}": d["r12"],
                                             f"{n[0]}–{n[2]}": d["r13"],
                                             f"{n[1]}–{n[2]}": d["r23"]},
                                     time_unit=_plain(data.config.time_unit),
                                     length_unit=_plain(data.config.length_unit),
                                     minima=minima)
        caption = ("Distances between the bodies (log scale) at the stored times"
                   + ("; dots: each pair's closest approach, located between the samples on "
                      "the integrator's continuous solution" if minima is not None else "")
                   + ("; the close encounters are the deep minima." if c["close"] else "."))
        facts = [("smallest sampled pair distance", f"{fmt(a['min_pair_distance'])} at t ≈ "
                                                    f"{fmt(a['min_pair_distance_time'])}")]
        if "closest_approach" in a:
            facts.insert(0, ("closest approach, located between the samples",
                             f"{fmt(a['closest_approach'])} ({c['closest_pair']}) at t ≈ "
                             f"{fmt(a['closest_approach_time'])}"))
        return SectionContent(figures=[cls.figure("pair_distances", fig, caption)],
                              facts=facts)

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
            "unbound": f"unbound but with no escape yet at t = {t_end}",
            "collision": "ending in a collision"}.get(case["fate"], "")


def _range(lo: float, hi: float) -> str:
    """``0.999 to 1.01``, or ``about 1`` when the two read the same to 4 figures."""
    a, b = fmt(lo, 4), fmt(hi, 4)
    return f"about {a}" if a == b else f"{a} to {b}"


def _signed(x):
    """A number for prose with a typeset minus sign (−1.1e-13)."""
    return f"−{fmt(-x)}" if x < 0 else fmt(x)


def _plain(text):
    """Config text (body names, units) for matplotlib: ``$`` escaped, so that a name is
    drawn as written and never parsed as mathtext (``$\\frac{`` would not parse)."""
    if isinstance(text, str):
        return text.replace("$", r"\$")
    return [_plain(t) for t in text]
