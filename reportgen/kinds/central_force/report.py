"""``central_force`` report: the relative orbit, both bodies' tracks, the effective
potential, Kepler's equation and the LRL vector, the apsidal angle, the conserved
quantities and the period across a family."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from ...scene.report import Report
from .results import SCHEMA

plots = lazy_module("reportgen.rendering.plots.gravitation")
own_plots = lazy_module("reportgen.kinds.central_force.plots")
common_plots = lazy_module("reportgen.rendering.plots.common")

#: an exponent as printed: "1.2" -> "¹·²"
_EXPONENT = str.maketrans("0123456789.-−", "⁰¹²³⁴⁵⁶⁷⁸⁹·⁻⁻")


def power_potential(n: str) -> str:
    """The power-law potential with its exponent set as one: ``V = −k/r¹·²``."""
    return f"V = −k/r{n.translate(_EXPONENT)}"


class CentralForceReport(Report):
    """The central-force sections, drawn from the archive alone."""

    schema = SCHEMA
    gallery_name = "Central force, two bodies"
    gallery_figures = ("orbit",)

    @classmethod
    def gallery_headline(cls, data):
        import math

        from ...scene import gallery
        a = data.analysis
        energy = gallery.worst_check(data, "energy")
        drift = f", energy drift {gallery.distance(energy.rel_error)}" if energy else ""
        if a.get("potential") == "kepler" and "kepler_position_error_max" in a:
            return (f"e = {fmt(a['eccentricity'], 3)} orbit, r(t) within "
                    f"{fmt_err(a['kepler_position_error_max'])} m of Kepler's equation{drift}")
        if "apsidal_angle_exact" in a and math.isfinite(a.get("apsidal_angle_measured", math.nan)):
            rel = abs(a["apsidal_angle_measured"] / a["apsidal_angle_exact"] - 1)
            return (f"apsidal angle {fmt(math.degrees(a['apsidal_angle_measured']), 5)}°, "
                    f"{gallery.from_reference(rel, 'the exact value')}{drift}")
        return super().gallery_headline(data)

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
        Section("hamilton_jacobi", "Hamilton–Jacobi: the characteristic function along the run",
                integrates=True),
        Section("invariants", "Conserved quantities", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def held_family_sections(cls, data):
        """The period against Kepler's third law only for a family in V = −k/r (any other
        potential's period is not the third law's)."""
        held = super().held_family_sections(data)
        kepler = (data.config.params.potential == "kepler"
                  and "params.potential" not in data.sweep.values)
        return held if kepler else [name for name in held if name != "kepler_family"]

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


    #: the shapes that are conics with the force centre (the centre of mass) at a focus
    CONICS = ("ellipse", "parabola", "hyperbola")

    @classmethod
    def potential_words(cls, data) -> str:
        """The potential as a formula: ``V = −k/r``, ``V = −k/r¹·²``, ``V = −k/r − ε/r² (ε = …)``."""
        p = data.config.params
        if p.potential == "power":
            return power_potential(fmt(float(p.n), 4))
        if p.potential == "kepler_inverse_cube":
            return f"V = −k/r − ε/r² (ε = {fmt(float(p.epsilon), 4)})"
        return "V = −k/r"

    @classmethod
    def prose_case(cls, data):
        """The stored cases the prose follows (``orbit_shape``, ``apsides``,
        ``heavier_body``: decided at simulate time with their thresholds) and the numbers
        it quotes, from the archive."""
        a, p = data.analysis, data.config.params
        if data.sweep is not None:
            return {}
        shape = str(a["orbit_shape"])
        r_min, r_max = (float(v) for v in np.asarray(a["turning_points"]))
        e = float(a.get("eccentricity", math.nan))
        psi = 0.5 * float(a.get("apsidal_shift", math.nan)) + math.pi
        apsides = str(a.get("apsides", ""))
        heavier = str(a["heavier_body"])
        mass = {"body 1": ("m₁", p.m1), "body 2": ("m₂", p.m2)}.get(heavier)
        invariants = data.runs["main"].invariants if "main" in data.runs else {}
        return {
            "potential": str(p.potential), "potential_words": cls.potential_words(data),
            "bound": a.get("bound") == "yes", "shape": shape,
            "conic": shape in cls.CONICS, "lrl": "lrl_x" in invariants,
            "e": fmt(e, 4), "r_min": fmt(r_min, 4),
            "r_max": fmt(r_max, 4) if math.isfinite(r_max) else "∞",
            "apsides": apsides,
            "apsides_verb": {"advance": "advances", "regress": "regresses"}.get(apsides, ""),
            "apsides_sense": {"advance": "with the motion",
                              "regress": "against the motion"}.get(apsides, ""),
            "psi": fmt(psi, 4, against=math.pi) if math.isfinite(psi) else "",
            "psi_against_pi": {"advance": "greater than", "regress": "less than"}.get(apsides,
                                                                                    ""),
            "shift_deg": (f"{fmt(abs(math.degrees(2 * psi - 2 * math.pi)), 4)}°"
                          if math.isfinite(psi) else ""),
            "shift_threshold": fmt(float(a["apsidal_shift_threshold"])),
            "pericentres_drawn": "pericentre_positions" in a,
            "apsides_measured": "apsidal_angle_measured" in a,
            "period_measured": "period_measured" in a,
            "heavier": heavier,
            "heavier_mass": f"{mass[0]} = {fmt(float(mass[1]))} kg" if mass else "",
            "study_reference": str(data.study_attrs.get("reference_kind", "")),
        }

    @classmethod
    def describe(cls, data):
        """``A bound Kepler ellipse, e = 0.7, a = 1 m: it closes every period T = 6.283
        s``; an escape by its conic and closest approach; a rosette by how its pericentre
        turns: each by the archive's stored case."""
        if data.sweep is not None:
            return super().describe(data)
        c, a = cls.prose_case(data), data.analysis
        pot, shape = c["potential_words"], c["shape"]
        period = fmt(float(a.get("period", math.nan)), 4)
        if shape == "ellipse":
            return (f"A bound Kepler ellipse, e = {c['e']}, a = "
                    f"{fmt(float(a['semi_major_axis']), 4)} m: the relative orbit closes every "
                    f"period T = {period} s")
        if shape == "circle":
            radius = fmt(float(a["semi_major_axis"]), 4)
            if c["lrl"]:
                return (f"A bound Kepler circle of radius r = {radius} m: the relative orbit "
                        f"closes every period T = {period} s")
            return (f"A circular orbit in {pot}, r = {radius} m: period of revolution "
                    f"T = {period} s")
        if not c["bound"]:
            return (f"An escaping orbit in {pot}" + (f", a {shape} with e = {c['e']}"
                                                      if c["conic"] else "")
                    + f": the bodies come no closer than {c['r_min']} m and fly apart")
        where = f"A bound orbit in {pot}, r between {c['r_min']} and {c['r_max']} m"
        if shape == "closed":
            return (f"{where}: it closes, the pericentre turning by less than "
                    f"{c['shift_threshold']} rad per radial period")
        return (f"{where}: a rosette whose pericentre {c['apsides_verb']} {c['shift_deg']} "
                "per radial period")

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        if "kepler_position_error" not in data.analysis:  # not a bound Kepler orbit
            names.remove("kepler")
        if "apsidal_angle_exact" not in data.analysis:  # Kepler, unbound, or a circle
            names.remove("apsides")
        if "hj_residual" not in data.analysis:  # unbound, or a circle: no libration in r
            names.remove("hamilton_jacobi")
        return names

    @classmethod
    def headline(cls, data):
        p, a = data.config.params, data.analysis
        pot = {"kepler": "V = −k/r", "power": power_potential(fmt(p.n)),
               "kepler_inverse_cube": f"V = −k/r − ε/r², ε = {fmt(p.epsilon)}"}[p.potential]
        out = [("bodies", f"m1 = {fmt(p.m1)} kg, m2 = {fmt(p.m2)} kg, "
                          f"μ = {fmt(a['reduced_mass'])} kg"),
               ("potential", f"{pot}, k = {fmt(p.k)}"),
               ("energy, angular momentum", f"E = {fmt(a['energy'])} J, "
                                            f"L = {fmt(a['angular_momentum'])} kg·m²/s")]
        out += cls.orbit_rows(data)
        if "period_note" in a:
            out.append(("period", a["period_note"]))
        if "kepler_position_error_max" in a:
            out.append(("max |Δr| to Kepler's orbit",
                        f"{fmt_err(a['kepler_position_error_max'])} m"))
        return out

    @classmethod
    def orbit_rows(cls, data) -> list[tuple[str, str]]:
        """The orbit's scales in the headline, named for what they are by the stored
        shape: Kepler elements of a conic; a circle's radius and period of revolution; the
        turning points and radial period of any other bound orbit."""
        a, shape = data.analysis, str(data.analysis["orbit_shape"])
        if "eccentricity" not in a:
            return []
        if shape == "circle" and "lrl_x" not in data.runs["main"].invariants:
            return [("orbit", f"a circle of radius r = {fmt(a['semi_major_axis'])} m, period "
                              f"of revolution {fmt(a['period'])} s")]
        if shape in ("closed", "rosette"):
            return [("orbit, from its turning points",
                     f"r from {fmt(a['pericentre'])} to {fmt(a['apocentre'])} m, "
                     f"(rₘₐₓ − rₘᵢₙ)/(rₘₐₓ + rₘᵢₙ) = {fmt(a['eccentricity'])}, radial period "
                     f"(pericentre to pericentre) {fmt(a['period'])} s"),
                    ("pericentre per radial period", cls.apsides_words(data))]
        return [("orbit, Kepler elements", f"e = {fmt(a['eccentricity'])}, a = "
                                           f"{fmt(a['semi_major_axis'])} m"
                 + (f", period {fmt(a['period'])} s" if "period" in a else ""))]

    @classmethod
    def apsides_words(cls, data) -> str:
        """How the pericentre turns, by the stored ``apsides``: "advances by 44.31°
        (2ψ − 2π, with the motion)", or "stays put: |2ψ − 2π| < 1e-8 rad"."""
        c = cls.prose_case(data)
        if c["apsides"] == "fixed":
            return f"stays put: |2ψ − 2π| < {c['shift_threshold']} rad"
        return f"{c['apsides_verb']} by {c['shift_deg']} (2ψ − 2π, {c['apsides_sense']})"

    @classmethod
    def section_orbit(cls, data):
        run, a = data.runs["main"], data.analysis
        ref = lrl = peri = None
        circle = a["orbit_shape"] == "circle"
        if "kepler_orbit" in a:
            ref = (a["kepler_orbit"]["x"], a["kepler_orbit"]["y"])
            if not circle:  # a circle's LRL vector vanishes: no pericentre to point to
                lrl = tuple(float(v) for v in a["eccentricity_vector"])
        elif "pericentre_positions" in a:
            peri = (a["pericentre_positions"]["x"], a["pericentre_positions"]["y"])
        e = math.hypot(*lrl) if lrl is not None else math.nan
        fig = plots.relative_orbit(run["x"], run["y"], reference=ref, pericentres=peri, lrl=lrl,
                                   lrl_label=f"LRL direction (|A|/μk = e = {fmt(e, 4)})")
        caption = "The relative orbit r(t) = r1 − r2, notes (3.19)."
        if ref is not None and circle:
            caption += (" Dashed: the exact circle from Kepler's equation (the Laplace–Runge–"
                        "Lenz vector vanishes: a circle has no pericentre).")
        elif ref is not None:
            caption += (" Dashed: the exact ellipse from Kepler's equation; arrow: the "
                        "direction of the Laplace–Runge–Lenz vector, from the focus to the "
                        "pericentre (its length |A|/μk = e is given in the legend).")
        elif peri is not None:
            caption += (" Triangles: the pericentre passages found in the run, each 2ψ from "
                        "the last in the sense of the motion: the pericentre "
                        + cls.apsides_words(data) + " per radial period.")
        return SectionContent(figures=[cls.figure("orbit", fig, caption)])

    @classmethod
    def section_two_body(cls, data):
        p, a = data.config.params, data.analysis
        tracks = a["body_tracks"]
        fig = plots.two_body_tracks(tracks["r1"], tracks["r2"], m1=p.m1, m2=p.m2)
        facts = [("reduced mass μ = m1 m2/(m1 + m2), notes (3.22)", f"{fmt(a['reduced_mass'])} kg"),
                 ("r1 = (m2/M) r, r2 = −(m1/M) r, notes (3.20)–(3.21)",
                  f"m2/M = {fmt(a['mass_fraction_m2'])}, m1/M = {fmt(a['mass_fraction_m1'])}")]
        caption = ("Both bodies' tracks in the centre-of-mass frame (R = 0): similar curves, "
                   "scaled by m2/M and m1/M about the centre of mass and on opposite sides of it"
                   + (", conics with the centre of mass at their common focus."
                      if a["orbit_shape"] in cls.CONICS else "."))
        return SectionContent(figures=[cls.figure("two_body", fig, caption)], facts=facts)

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
        if a["bound"] != "yes":
            turning = [("turning point rₘᵢₙ, the only one (unbound)", f"{fmt(r_min)} m")]
        elif a["orbit_shape"] == "circle":
            turning = [("turning points rₘᵢₙ = rₘₐₓ (a circle)", f"{fmt(r_min)} m")]
        else:
            turning = [("turning points rₘᵢₙ, rₘₐₓ", f"{fmt(r_min)} m, {fmt(r_max)} m")]
        facts = turning + [("radius of the circular orbit at this L", f"{fmt(rc)} m")]
        return SectionContent(figures=[cls.figure(
            "effective_potential", fig, "The radial motion in the effective potential "
            "V(r) + L²/(2μr²), notes (7.40)–(7.41): "
            + ("a circular orbit sits at its minimum, where E equals it."
               if a["orbit_shape"] == "circle" else "the orbit stays where E is above it, "
               + ("between the turning points." if a["bound"] == "yes" else
                  "outside its one turning point, and escapes.")))],
            facts=facts)

    @classmethod
    def section_kepler(cls, data):
        run, a = data.runs["main"], data.analysis
        fig = common_plots.error_against_time(
            run.t, {r"$|r - r_{\mathrm{Kepler}}|$ [m]": a["kepler_position_error"],
                    "| |A|/(μk) − e |": a["lrl_eccentricity_error"]}, ylabel="absolute error")
        rows = [["eccentricity e", fmt(a["eccentricity"]), "|A|/(μk) of the initial state"],
                ["semi-major axis a [m]", fmt(a["semi_major_axis"]), "−k/(2E)"],
                ["period T [s]", fmt(a["period"]), "2π√(a³ μ/k) (third law)"]]
        if "period_measured" in a:
            rows.append(["period measured [s]", fmt(a["period_measured"]),
                         f"rel. diff {fmt_err(abs(a['period_measured'] / a['period'] - 1))}"])
        if "semi_major_axis_measured" in a:
            rows.append(["(rₘᵢₙ + rₘₐₓ)/2 measured [m]", fmt(a["semi_major_axis_measured"]),
                         "rel. diff " + fmt_err(abs(a["semi_major_axis_measured"]
                                                    / a["semi_major_axis"] - 1))])
        notes = [a["period_measured_note"]] if "period_measured_note" in a else []
        return SectionContent(
            figures=[cls.figure("kepler_error", fig, "Distance between the stored positions and "
                                "the solution of Kepler's equation at the same times, and the "
                                "change of the LRL vector's length.")],
            tables=[Table(caption="Orbit elements from the initial state and as measured",
                          header=["quantity", "value", "source"], rows=rows)],
            facts=[("max |Δr| to Kepler's orbit",
                    f"{fmt_err(a['kepler_position_error_max'])} m"),
                   ("max |Δv| to Kepler's orbit",
                    f"{fmt_err(a['kepler_velocity_error_max'])} m/s")],
            notes=notes)

    @classmethod
    def section_apsides(cls, data):
        a = data.analysis
        power = data.config.params.potential == "power"
        family = a["apsidal_angle_family"]
        if power:
            near, label = a["apsidal_angle_near_circular"], "exact quadrature at this L"
            near_label = "near-circular limit π/√(2 − n)"
        else:
            near = a["apsidal_angle_closed_form"]
            label = "exact quadrature (= π/√(1 − 2με/L²) at every e)"
            near_label = "closed form π/√(1 − 2με/L²)"
        measured = ((a["eccentricity"], a["apsidal_angle_measured"])
                    if "apsidal_angle_measured" in a else None)
        fig = plots.apsidal_angle_family(family["eccentricity"], family["angle"],
                                         near_circular=near, measured=measured,
                                         exact_label=label, near_label=near_label)
        how = ("quadrature, Goldstein (3.37)" if a["apsidal_angle_exact_method"] == "quadrature"
               else "the closed form below")
        rows = [[f"exact, {how}", fmt(a["apsidal_angle_exact"]), "—"]]
        if "apsidal_angle_measured" in a:
            rows.append(["measured from the run", fmt(a["apsidal_angle_measured"]),
                         fmt_err(abs(a["apsidal_angle_measured"] / a["apsidal_angle_exact"]
                                     - 1))])
        if "apsidal_angle_near_circular" in a:
            rows.append(["near-circular limit π/√(2 − n) (Landau & Lifshitz §14)",
                         fmt(a["apsidal_angle_near_circular"]),
                         fmt_err(abs(a["apsidal_angle_near_circular"]
                                     / a["apsidal_angle_exact"] - 1))])
        if "apsidal_angle_closed_form" in a:
            rows.append(["closed form π/√(1 − 2με/L²) (Landau & Lifshitz §15, problem 3)",
                         fmt(a["apsidal_angle_closed_form"]),
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
    def section_hamilton_jacobi(cls, data):
        a = data.analysis
        hj = a["hamilton_jacobi"]
        fig = own_plots.radial_momentum(hj["radius"], hj["radial_momentum"], hj["curve_r"],
                                        hj["curve_p_r"], hj["marks_r"], hj["marks_p_r"])
        rows = [
            ["∂S/∂t + H(q, ∂S/∂q) = 0, notes (7.16)", fmt_err(a["hj_residual"]),
             fmt_err(a["hj_residual_quadrature"])],
            ["H(q, ∂W/∂q) = E, notes (7.32)", fmt_err(a["hj_residual"]),
             fmt_err(a["hj_characteristic_residual_quadrature"])],
        ]
        if "hj_half_action_closed_form" in a:
            rows += [
                ["Wᵣ by quadrature against its closed form, relative to πk√(μ/(−2E))", "—",
                 fmt_err(a["hj_characteristic_quadrature_error"])],
                ["∫ pᵣ dr from rₘᵢₙ to rₘₐₓ against its closed form (Goldstein §10.8)", "—",
                 fmt_err(abs(a["hj_half_action"] / a["hj_half_action_closed_form"] - 1))]]
        rows.append(["integrated pᵣ against ±∂W/∂r, and μr²θ̇ against ∂W/∂θ = L",
                     fmt_err(a["hj_momentum_difference"]), "—"])
        facts = [("separation constant ∂W/∂θ = L", f"{fmt(a['angular_momentum'])} kg·m²/s"),
                 ("∫ pᵣ dr from rₘᵢₙ to rₘₐₓ, by quadrature", f"{fmt(a['hj_half_action'])} J·s")]
        return SectionContent(
            figures=[cls.figure("hamilton_jacobi", fig, "The integrated radial momentum "
                                "pᵣ = μṙ against the distance r, over the two branches "
                                "pᵣ = ±∂W/∂r of the characteristic function: the integrand "
                                "√(2μ(E − V) − L²/r²) (line) and central differences of Wᵣ "
                                "computed by quadrature (crosses).")],
            tables=[Table(caption="Largest relative residual or difference along the run, "
                                  "relative to |E| or to the momentum's size. Middle column: "
                                  "∂W/∂r the integrand and ∂S/∂t = −E; right: Wᵣ by "
                                  "Gauss–Legendre quadrature, ∂W/∂r, ∂W/∂θ and ∂S/∂t by "
                                  "central differences",
                          header=["equation or comparison", "∂W/∂r from the integrand",
                                  "W by quadrature"], rows=rows)],
            facts=facts)

    @classmethod
    def section_invariants(cls, data):
        labels = {"energy": "energy E", "angular_momentum": "angular momentum L",
                  "lrl_x": "LRL vector, x component", "lrl_y": "LRL vector, y component"}
        lrl = "lrl_x" in data.runs["main"].invariants
        return cls.invariants_section(data, labels=labels,
                                      caption="Drift of the conserved quantities: E and L "
                                              "relative to their size"
                                              + (", the LRL components relative to μk."
                                                 if lrl else "."))
