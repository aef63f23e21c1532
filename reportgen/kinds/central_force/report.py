"""``central_force`` report: the relative orbit, both bodies' tracks, the effective
potential, Kepler's equation and the LRL vector, the apsidal angle, the conserved
quantities and the period across a family."""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from ...scene.report import Report
from .results import SCHEMA

plots = lazy_module("reportgen.rendering.plots.gravitation")
common_plots = lazy_module("reportgen.rendering.plots.common")


class CentralForceReport(Report):
    """The central-force sections, drawn from the archive alone."""

    schema = SCHEMA
    family_sections = (
        Section("kepler_family", "Period against eccentricity across the family",
                description="Each bound member's period, measured from its orbit, against "
                            "Kepler's third law T = 2π √(a³/(k/μ))."),
    )
    sections = (
        Section("orbit", "The relative orbit", integrates=True),
        Section("two_body", "Reduced mass and the centre of mass", integrates=True),
        Section("effective_potential", "Effective potential and turning points"),
        Section("kepler", "Kepler's equation, third law and the Laplace–Runge–Lenz vector",
                integrates=True),
        Section("apsides", "Apsidal angle", integrates=True),
        Section("invariants", "Conserved quantities", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def section_kepler_family(cls, data):
        sweep = data.sweep
        a = sweep.analysis
        need = ("eccentricity", "period", "period_measured")
        if not all(k in a for k in need):
            return SectionContent(notes=["No member has a period measured from its orbit: "
                                         "the potential is not 1/r, no member is bound, or "
                                         "the runs are shorter than two orbits (or resolve "
                                         "a pericentre passage with too few samples)."])
        ok = sweep.ok & np.isfinite(a["period_measured"]) & np.isfinite(a["period"])
        fig = common_plots.family_against_reference(
            a["eccentricity"][ok], a["period_measured"][ok], a["period"][ok],
            xlabel="eccentricity e", ylabel=cls.label("period"),
            measured_label="measured from the orbit",
            exact_label="third law 2π√(a³/(k/μ))")
        rel = np.abs(a["period_measured"][ok] / a["period"][ok] - 1)
        facts = [("bound members with a period", f"{int(ok.sum())} of {sweep.size}")]
        if rel.size:
            facts.append(("max relative difference to the third law", fmt_err(float(rel.max()))))
        return SectionContent(figures=[cls.figure(
            "kepler_family", fig, "Each member's period against its eccentricity: measured "
            "from the orbit and from Kepler's third law with its own semi-major axis; below, "
            "their relative difference.")], facts=facts)


    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        is_kepler = data.config.params.potential == "kepler"
        bound = data.analysis["bound"] == "yes"
        if not (is_kepler and bound):
            names.remove("kepler")
        if is_kepler or not bound:
            names.remove("apsides")
        return names

    @classmethod
    def headline(cls, data):
        p, a = data.config.params, data.analysis
        pot = {"kepler": "V = −k/r", "power": f"V = −k/r^{fmt(p.n)}",
               "kepler_inverse_cube": f"V = −k/r − ε/r², ε = {fmt(p.epsilon)}"}[p.potential]
        out = [("bodies", f"m1 = {fmt(p.m1)} kg, m2 = {fmt(p.m2)} kg, "
                          f"μ = {fmt(a['reduced_mass'])} kg"),
               ("potential", f"{pot}, k = {fmt(p.k)}"),
               ("energy, angular momentum", f"E = {fmt(a['energy'])} J, "
                                            f"L = {fmt(a['angular_momentum'])} kg·m²/s")]
        if "eccentricity" in a:
            out.append(("orbit", f"e = {fmt(a['eccentricity'])}, a = "
                                 f"{fmt(a['semi_major_axis'])} m"
                        + (f", period {fmt(a['period'], 12)} s" if "period" in a else "")))
        if "period_note" in a:
            out.append(("period", a["period_note"]))
        if "kepler_position_error_max" in a:
            out.append(("max |r − r_Kepler|", f"{fmt_err(a['kepler_position_error_max'])} m"))
        return out

    @classmethod
    def section_orbit(cls, data):
        run, a = data.runs["main"], data.analysis
        ref = lrl = peri = None
        if "kepler_orbit" in a:
            ref = (a["kepler_orbit"]["x"], a["kepler_orbit"]["y"])
            lrl = tuple(float(v) for v in a["eccentricity_vector"])
        elif "pericentre_positions" in a:
            peri = (a["pericentre_positions"]["x"], a["pericentre_positions"]["y"])
        fig = plots.relative_orbit(run["x"], run["y"], reference=ref, pericentres=peri, lrl=lrl)
        caption = "The relative orbit r(t) = r1 − r2 (3.21)."
        if lrl is not None:
            caption += (" Dashed: the exact ellipse from Kepler's equation; arrow: the "
                        "direction of the Laplace–Runge–Lenz vector, from the focus to the "
                        "pericentre (its length |A|/μk = e is given in the legend).")
        elif peri is not None:
            caption += " Triangles: pericentre passages, advancing by twice the apsidal angle."
        return SectionContent(figures=[cls.figure("orbit", fig, caption)])

    @classmethod
    def section_two_body(cls, data):
        p, a = data.config.params, data.analysis
        tracks = a["body_tracks"]
        fig = plots.two_body_tracks(tracks["r1"], tracks["r2"], m1=p.m1, m2=p.m2)
        facts = [("reduced mass μ = m1 m2/(m1 + m2) (3.20)", f"{fmt(a['reduced_mass'])} kg"),
                 ("r1 = (m2/M) r, r2 = −(m1/M) r (3.19)",
                  f"m2/M = {fmt(a['mass_fraction_m2'])}, m1/M = {fmt(a['mass_fraction_m1'])}")]
        return SectionContent(figures=[cls.figure(
            "two_body", fig, "Both bodies' tracks in the centre-of-mass frame (R = 0): "
            "similar conics scaled by m2/M and m1/M about the common focus, on opposite sides.")],
            facts=facts)

    @classmethod
    def section_effective_potential(cls, data):
        a = data.analysis
        r_min, r_max = (float(v) for v in np.asarray(a["turning_points"]))
        curve = a["effective_potential_curve"]
        rc = curve["circular_radius"]
        fig = plots.effective_potential(curve["r"], curve["potential"],
                                        curve["effective_potential"], energy=a["energy"],
                                        turning=(r_min, r_max),
                                        circular=(rc, curve["circular_energy"]))
        facts = [("turning points r_min, r_max", f"{fmt(r_min, 12)} m, {fmt(r_max, 12)} m"),
                 ("circular orbit at this L", f"r_c = {fmt(rc, 12)} m")]
        return SectionContent(figures=[cls.figure(
            "effective_potential", fig, "The radial motion in V_eff(r) = V(r) + L²/(2μr²) "
            "(3.28–3.30): the orbit stays where E ≥ V_eff, between the turning points.")],
            facts=facts)

    @classmethod
    def section_kepler(cls, data):
        run, a = data.runs["main"], data.analysis
        fig = common_plots.error_against_time(
            run.t, {"|r − r_Kepler| [m]": a["kepler_position_error"],
                    "| |A|/(μk) − e |": a["lrl_eccentricity_error"]}, ylabel="absolute error")
        rows = [["eccentricity e", fmt(a["eccentricity"], 14), "|A|/(μk) of the initial state"],
                ["semi-major axis a [m]", fmt(a["semi_major_axis"], 14), "−k/(2E)"],
                ["period T [s]", fmt(a["period"], 14), "2π√(a³ μ/k) (third law)"]]
        if "period_measured" in a:
            rows.append(["period measured [s]", fmt(a["period_measured"], 14),
                         f"rel. diff {fmt_err(abs(a['period_measured'] / a['period'] - 1))}"])
        if "semi_major_axis_measured" in a:
            rows.append(["(r_min + r_max)/2 measured [m]", fmt(a["semi_major_axis_measured"], 14),
                         "rel. diff " + fmt_err(abs(a["semi_major_axis_measured"]
                                                    / a["semi_major_axis"] - 1))])
        notes = [a["period_measured_note"]] if "period_measured_note" in a else []
        return SectionContent(
            figures=[cls.figure("kepler_error", fig, "Distance between the stored positions and "
                                "the solution of Kepler's equation at the same times, and the "
                                "change of the LRL vector's length.")],
            tables=[Table(caption="Orbit elements from the initial state and as measured",
                          header=["quantity", "value", "source"], rows=rows)],
            facts=[("max |r − r_Kepler|", f"{fmt_err(a['kepler_position_error_max'])} m"),
                   ("max |v − v_Kepler|", f"{fmt_err(a['kepler_velocity_error_max'])} m/s")],
            notes=notes)

    @classmethod
    def section_apsides(cls, data):
        a = data.analysis
        power = data.config.params.potential == "power"
        family = a["apsidal_angle_family"]
        if power:
            near, label = a["apsidal_angle_near_circular"], "exact quadrature at this L"
        else:
            near = a["apsidal_angle_closed_form"]
            label = "exact quadrature (= π/√(1 − 2με/L²) at every e)"
        measured = ((a["eccentricity"], a["apsidal_angle_measured"])
                    if "apsidal_angle_measured" in a else None)
        fig = plots.apsidal_angle_family(family["eccentricity"], family["angle"],
                                         near_circular=near, measured=measured,
                                         exact_label=label)
        if not power:
            fig.axes[0].get_lines()[1].set_label("closed form π/√(1 − 2με/L²)")
            fig.axes[0].legend(loc="best")
        rows = [["exact, quadrature (Goldstein eq. 3.37)", fmt(a["apsidal_angle_exact"], 13),
                 "—"]]
        if "apsidal_angle_measured" in a:
            rows.append(["measured from the run", fmt(a["apsidal_angle_measured"], 13),
                         fmt_err(abs(a["apsidal_angle_measured"] / a["apsidal_angle_exact"]
                                     - 1))])
        if "apsidal_angle_near_circular" in a:
            rows.append(["near-circular limit π/√(2 − n) (L&L §14)",
                         fmt(a["apsidal_angle_near_circular"], 13),
                         fmt_err(abs(a["apsidal_angle_near_circular"]
                                     / a["apsidal_angle_exact"] - 1))])
        if "apsidal_angle_closed_form" in a:
            rows.append(["closed form π/√(1 − 2με/L²) (L&L §15)",
                         fmt(a["apsidal_angle_closed_form"], 13),
                         fmt_err(abs(a["apsidal_angle_closed_form"]
                                     / a["apsidal_angle_exact"] - 1))])
        notes = [a["apsidal_angle_note"]] if "apsidal_angle_note" in a else []
        return SectionContent(
            figures=[cls.figure("apsidal_angle", fig, "Apsidal angle (pericentre to apocentre) "
                                "against eccentricity at this angular momentum.")],
            tables=[Table(caption="Apsidal angle [rad]", header=["source", "value",
                                                                  "rel. diff to exact"],
                          rows=rows)], notes=notes)

    @classmethod
    def section_invariants(cls, data):
        labels = {"energy": "energy E", "angular_momentum": "angular momentum L",
                  "lrl_x": "LRL A_x", "lrl_y": "LRL A_y"}
        return cls.invariants_section(data, labels=labels,
                                      caption="Drift of the conserved quantities: E and L "
                                              "relative to their size, the LRL components "
                                              "relative to μk.")
