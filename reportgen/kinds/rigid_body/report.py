"""``rigid_body`` report: ω against the exact solution, the polhodes on the L-sphere and
the inertia ellipsoid, Poinsot's construction, the stability table with the flips, the
symmetric precession, the splitting integrator and the invariants."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from ...scene.report import Report
from ...scene.schema import unit_text
from ..inertia.report import stability_table_section
from .results import SCHEMA

common_plots = lazy_module("reportgen.rendering.plots.common")
plots = lazy_module("reportgen.rendering.plots.rigid_body")

#: the invariants as named in tables and the main run's drift figure
INVARIANT_NAMES = {"twice_energy": "2T", "L_squared": "L² (body frame)",
                   "L_x": "Lx (space)", "L_y": "Ly (space)", "L_z": "Lz (space)",
                   "quaternion_norm": "|q|"}


#: relative differences below this are rounding (float64 sums over a few hundred terms)
ROUNDING = 1e-12


def method_name(data, run) -> str:
    """A run's integrator as a reader says it: the study table's label ("DOP853 (numba)"),
    "axis splitting, order 4" for the splitting, else the method's words."""
    from ...scene.report import method_words
    method = str(run.attrs.get("method", ""))
    if method.startswith("splitting") and method[len("splitting"):].isdigit():
        return f"axis splitting, order {method[len('splitting'):]}"
    study = data.study
    if study is not None and len(study) and "label" in (study.dtype.names or ()):
        for m, label in zip(study["method"], study["label"], strict=True):
            if str(m) == method:
                return str(label)
    return method_words(method)


def omega_errors(run, exact) -> tuple[dict, list[int]]:
    """|ω_k − exact| per component, and the components (1-based) whose error is exactly
    zero over the run (ω along a symmetric body's figure axis is constant, integrated to
    the last bit): a log axis cannot show those, the caption names them instead."""
    errors, zero = {}, []
    for k, n in enumerate(["omega_1", "omega_2", "omega_3"]):
        err = run[n] - exact[n]
        if float(np.max(np.abs(err))) == 0.0:
            zero.append(k + 1)
        else:
            errors[f"|ω{k + 1} − exact|"] = err
    return errors, zero


def zero_error_words(zero: list[int]) -> str:
    if not zero:
        return ""
    names = " and ".join(f"ω{k}" for k in zero)
    return (f" The error of {names} is exactly zero over the whole run (constant, integrated "
            "without rounding), so it has no line on the log axis.")


def vector(v) -> str:
    """A vector as report text: (0.1, 0, 0) with true minus signs."""
    return "(" + ", ".join(fmt(float(x)) for x in np.asarray(v, dtype=float)) + ")"


def axes_by_moment(analysis) -> tuple[int, int, int]:
    """The body axes (1, 2, 3) of the smallest, the intermediate and the largest principal
    moment, as configured (ties in axis order)."""
    moments = [float(x) for x in analysis["principal_moments"]]
    order = sorted(range(3), key=lambda k: moments[k])
    return order[0] + 1, order[1] + 1, order[2] + 1


class RigidBodyReport(Report):
    """The rigid body's sections, drawn from the archive alone."""

    schema = SCHEMA
    gallery_figures = ("polhode_ellipsoid", "polhodes")

    @classmethod
    def gallery_headline(cls, data):
        from ...scene import gallery
        flips = gallery.worst_check(data, "time between flips")
        if flips is not None and math.isfinite(flips.value):
            return (f"flips every {fmt(flips.value, 5)} s, "
                    f"{gallery.from_reference(flips.rel_error, 'the exact 2K(m)/λ')}")
        omega = gallery.worst_check(data, "ω1", "ω2", "ω3")
        if omega is None:
            return super().gallery_headline(data)
        exact = "the exact " + gallery.reference_words(omega.source)
        precession = gallery.worst_check(data, "body-frame precession rate Ω")
        if precession is not None and precession.reference != 0:  # the symmetric case
            return (f"ω precesses about the figure axis at Ω = "
                    f"{fmt(precession.reference, 4)} rad/s; ω(t) "
                    f"{gallery.from_reference(omega.rel_error, 'the exact uniform precession')}")
        return f"ω(t) {gallery.from_reference(omega.rel_error, exact)}"

    sections = (
        Section("impulse", "The blow: the centre of mass and the struck point in space",
                integrates=True),
        Section("omega", "Angular velocity against the exact solution", integrates=True),
        Section("polhodes", "Polhodes on the angular-momentum sphere", integrates=True),
        Section("polhode_ellipsoid", "Polhodes on the inertia ellipsoid", integrates=True),
        Section("herpolhode", "Poinsot's construction: the inertia ellipsoid rolls on the "
                              "invariable plane", integrates=True),
        Section("stability", "Stability of rotation about the principal axes", integrates=True),
        Section("symmetric_precession", "Precession of the symmetric body", integrates=True),
        Section("geometric_integrator", "Splitting integrator (free rotations about the axes)",
                integrates=True),
        Section("invariants", "Conserved quantities", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        if "impulse" not in data.analysis:
            names.remove("impulse")
        if "symmetric" not in data.analysis:
            names.remove("symmetric_precession")
        if data.analysis.get("spherical", False):
            # every direction is a principal axis: ω is constant, no polhodes to draw
            for name in ("polhodes", "polhode_ellipsoid", "herpolhode"):
                names.remove(name)
        if "splitting" not in data.runs:
            names.remove("geometric_integrator")
        return names

    @classmethod
    def headline(cls, data):
        a = data.analysis
        I, w = a["principal_moments"], a["omega_initial"]
        st = a["axis_stability"]
        facts = [
            ("principal moments", f"I1 = {fmt(I[0])}, I2 = {fmt(I[1])}, I3 = {fmt(I[2])} kg m²"),
            ("initial ω (body)", "(" + ", ".join(fmt(float(x)) for x in w) + ") rad/s"
             + (" after the impulse" if data.config.get("impulse") is not None else "")),
            ("axis stability", ", ".join(f"{k[-1]}: {v['verdict']}" for k, v in st.items())),
            ("max |ω − exact ω|", f"{fmt_err(a['omega_max_error'])} rad/s ({a['reference']})"),
            ("max ||q| − 1|", f"{fmt_err(a['quaternion_norm_max_deviation'])} (integrator "
                              "output; archived attitude renormalized)"),
        ]
        imp = a.get("impulse")
        if imp is not None and "cm_velocity" in imp:
            facts.insert(2, ("centre of mass after the impulse",
                             f"drifts at V = P/M = {vector(imp['cm_velocity'])} m/s"))
        if "elliptic" in a:
            facts.append(("branch", f"{a['elliptic']['branch']}, m = {fmt(a['elliptic']['m'])}"))
        return facts

    @classmethod
    def prose_case(cls, data):
        """Spherical, symmetric (figure axis, prolate or oblate, the sense of the
        precession) or asymmetric (which configured axis has the smallest, intermediate and
        largest moment, the elliptic branch), the axis the spin starts nearest, whether the
        scene shows the intermediate-axis flip and how many flips the run holds, and what
        the impulse struck: each from the archive's stored classification."""
        a = data.analysis
        moments = [float(x) for x in a["principal_moments"]]
        case = {"spherical": bool(a.get("spherical", False)), "symmetric": "symmetric" in a,
                "asymmetric": "elliptic" in a, "flip": "flip" in a,
                "splitting": data.study is not None and any(
                    "splitting" in str(m) for m in data.study["method"]),
                "unstable_axes": [int(k[-1]) for k, v in a["axis_stability"].items()
                                  if v["verdict"] == "unstable"]}
        spin = a.get("spin_axis")
        if spin is not None:
            case.update(nearest=int(spin["nearest"]), angle=fmt(float(spin["angle"]), 3),
                        near_angle=fmt(float(spin["near_angle"]), 3),
                        closest=fmt(float(spin.get("intermediate_closest_angle", math.nan)),
                                    3))
        if case["flip"]:
            case["flips"] = len(np.atleast_1d(a["flip"]["flip_times"]))
        circled = (a.get("polhode_ellipsoid") or {}).get("circled_axis")
        case["circled"] = int(circled) if circled is not None else None
        if case["symmetric"]:
            s = a["symmetric"]
            axis = int(s["axis"])
            transverse = [k for k in (1, 2, 3) if k != axis]
            shape = s.get("shape") or ("oblate" if moments[axis - 1] > moments[transverse[0] - 1]
                                       else "prolate")
            case.update(axis=axis, transverse=transverse, shape=str(shape),
                        sense=str(s.get("sense", "prograde" if shape == "oblate"
                                        else "retrograde")))
            case["steady"] = case["sense"].startswith("steady")
        if case["asymmetric"]:
            smallest, intermediate, largest = axes_by_moment(a)
            branch = str(a["elliptic"]["branch"])
            case.update(smallest=smallest, intermediate=intermediate, largest=largest,
                        branch=branch,
                        circled_axis=largest if "largest" in branch else smallest,
                        starts_near_intermediate=spin is not None
                        and int(spin["nearest"]) == intermediate
                        and float(spin["angle"]) < float(spin["near_angle"]))
        imp = a.get("impulse")
        if imp is not None:
            case.update(impulse_mass="cm_velocity" in imp,
                        apex=data.config.get("impulse", {}).get("at") == "apex",
                        on_figure_axis=bool(imp.get("point_on_figure_axis", False)))
        e = a.get("energy_split")
        case["energy_split"] = e is not None
        if e is not None:  # the point-mass check of notes (8.38)–(8.42)
            case.update(split_nodes=int(e["nodes"]),
                        split_samples=len(np.atleast_1d(e["times"])),
                        split_error=fmt_err(float(e["max_relative_error"])),
                        split_cross=fmt_err(float(e["max_cross_term_share"])),
                        split_offsets=fmt_err(float(np.max(e["first_moment"]))
                                              / float(e["first_moment_scale"])),
                        split_rounding=max(float(e["max_relative_error"]),
                                           float(e["max_cross_term_share"])) <= ROUNDING)
        return case

    @classmethod
    def section_impulse(cls, data):
        a = data.analysis["impulse"]
        apex = data.config.get("impulse", {}).get("at") == "apex"
        name = "apex" if apex else "struck point"
        facts = [
            ("impulse P (body frame)", f"{vector(a['P'])} kg m/s at p = {vector(a['point'])} m "
                                       f"from the centre of mass" + (" (the apex, 3h/4 up the "
                                                                      "axis)" if apex else "")),
            ("angular impulse p × P", f"{vector(a['angular_impulse'])} kg m²/s"),
            ("ω before → after (body)", f"{vector(a['omega_before'])} → "
                                        f"{vector(np.asarray(a['omega_before']) + a['delta_omega'])}"
                                        " rad/s, Δω = I⁻¹(p × P)")]
        figures = []
        if "cm_velocity" in a:
            V = np.asarray(a["cm_velocity"], dtype=float)
            v = np.asarray(a["point_velocity_initial"], dtype=float)
            speed = float(np.linalg.norm(v))
            facts += [
                ("centre-of-mass velocity V = P/M", f"{vector(V)} m/s (M = {fmt(a['mass'])} kg)"),
                (f"{name} just after the blow",
                 f"moves at {vector(v)} m/s, |v| = {fmt(speed)} m/s = "
                 f"{fmt(speed / float(np.linalg.norm(V)), 4)} |V|")]
            if "cm_velocity_run_max_error" in a:
                facts.append((f"centre of mass from the run ({int(a['nodes'])} point masses)",
                              f"velocity within {fmt_err(a['cm_velocity_run_max_error'])} m/s "
                              f"of P/M, position within {fmt_err(a['cm_path_run_max_error'])} m "
                              "of the line V t, over the whole run"))
            if "point_path_max_error" in a:
                facts.append((f"{name}'s path against the closed form",
                              f"within {fmt_err(a['point_path_max_error'])} m over the run "
                              f"(precession about L at |L|/I⊥ = {fmt(a['precession_rate'])} "
                              "rad/s)"))
            run = data.runs["main"]
            L = np.array([run.invariants[k][0] for k in ("L_x", "L_y", "L_z")])
            fig = plots.impulse_paths(run.t, a["point_path"], a["cm_path"], L,
                                      point_name=name, exact=a.get("point_path_exact"))
            figures.append(cls.figure(
                "impulse_paths", fig,
                f"After the blow at t = 0: the {name} (red) from the integrated attitude, "
                f"r = V t + R(t) p, and the centre of mass on its straight line V t (black), "
                f"t from 0 to {fmt(float(run.t[-1]), 4)} s; grey, the body's line from the "
                f"centre of mass to the {name} at a few instants (each axis to its own "
                "scale). Right: the same seen along "
                "the angular momentum L"
                + (", with the closed form of the symmetric body dashed" if
                   "point_path_exact" in a else "") + "."))
        tables = [cls.energy_split_table(data)] if "energy_split" in data.analysis else []
        return SectionContent(figures=figures, facts=facts, tables=tables)

    @classmethod
    def header(cls, name: str) -> str:
        """A table header from the declared result ``name``: its symbol as page text and
        its unit ("M Ṙ²/2 [J]")."""
        q = cls.schema.result(name)
        unit = unit_text(q.unit)
        return f"{q.text} [{unit}]" if unit and q.unit != "1" else q.text

    @classmethod
    def energy_split_table(cls, data) -> Table:
        """The kinetic energy summed over the body's point masses against the split at
        the centre of mass, notes (8.38)–(8.42), at the stored samples."""
        e = data.analysis["energy_split"]
        names = ("times", "kinetic_points", "kinetic_split", "cross_term", "first_moment")
        rows = [[fmt(float(t)), fmt(float(k), 12), fmt(float(s), 12), fmt_err(float(c)),
                 fmt_err(float(x)), fmt_err(float(r))]
                for t, k, s, c, x, r in zip(*(np.atleast_1d(e[n]) for n in names),
                                            np.atleast_1d(e["relative_error"]), strict=True)]
        return Table(
            caption=f"The kinetic energy of the {int(e['nodes'])} point masses, summed point "
                    "by point, against the translational plus rotational kinetic energy of "
                    "the stored state, and the cross term and the mass-weighted offsets from "
                    "the centre of mass, notes (8.40)–(8.41), at a few stored times "
                    f"(M Ṙ²/2 = {fmt(float(e['translational']))} J throughout).",
            header=[*(cls.header(f"energy_split/{n}") for n in names), "relative difference"],
            rows=rows)

    @classmethod
    def section_omega(cls, data):
        run = data.runs["main"]
        names = ["omega_1", "omega_2", "omega_3"]
        exact = run.reference
        fig = common_plots.timeseries_against_reference(
            run.t, {n: run[n] for n in names}, {n: exact[n] for n in names},
            ylabels={n: f"ω{k + 1} [rad/s]" for k, n in enumerate(names)},
            reference_label=data.analysis["reference"])
        errors, zero = omega_errors(run, exact)
        figures = [cls.figure("omega", fig, "Body-frame angular velocity integrated (Euler's "
                              "equations notes (10.5)) against the exact solution.")]
        if errors:  # every component exact to the last bit (a spherical top): nothing to draw
            err = common_plots.error_against_time(run.t, errors, ylabel="absolute error",
                                                  unit="rad/s")
            figures.append(cls.figure("omega_error", err, "Error of ω against the exact "
                                      "solution." + zero_error_words(zero)))
        facts = [("max |ω − exact ω|", f"{fmt_err(data.analysis['omega_max_error'])} rad/s")]
        if not errors:
            facts.append(("ω1, ω2, ω3 against the exact solution", "equal at every sample: "
                          "the right-hand sides vanish, so the integration changes no bit"))
        return SectionContent(figures=figures, facts=facts)

    @classmethod
    def section_polhodes(cls, data):
        p = data.analysis["polhodes"]
        fig = plots.polhodes(p["family"], p["separatrices"], p["track"],
                             intermediate=axes_by_moment(data.analysis)[1])
        return SectionContent(figures=[cls.figure(
            "polhodes", fig, "Polhodes: the body-frame L on the sphere |L| = const cut by the "
            "energy ellipsoid Σ Lₖ²/Iₖ = 2E. Grey: a family of energies; "
            + ("orange: the separatrices through the intermediate axis; "
               if len(p["separatrices"]) else "")
            + "red: this scene.")])

    @classmethod
    def section_polhode_ellipsoid(cls, data):
        p = data.analysis.get("polhode_ellipsoid")
        if p is None:
            return SectionContent(notes=["The polhodes on the inertia ellipsoid were not "
                                         "computed for this archive (a spherical body, or the "
                                         "section was not asked for when it was simulated)."])
        run = data.runs["main"]
        smallest, mid, largest = axes_by_moment(data.analysis)
        fig = plots.polhodes_on_ellipsoid(p["surface"], p["semi_axes"], p["family"],
                                          p["separatrices"], run.y[:, :3], intermediate=mid)
        side = int(p["circled_axis"])
        facts = [("2T, L²", f"{fmt(float(p['twice_energy']))} J, "
                            f"{fmt(float(p['L_squared']))} (kg m²/s)²")]
        symmetric = data.analysis.get("symmetric")
        if symmetric is not None:  # no intermediate moment, no separatrix to be off
            steady = str(symmetric.get("sense", "")).startswith("steady")
            facts.append(("polhode (symmetric body)",
                          (f"a point (a steady rotation {str(symmetric['sense'])[7:]}), "
                           if steady else
                           f"a circle about the figure axis {int(symmetric['axis'])}, ")
                          + f"|ω⊥| = {fmt(float(symmetric['omega_perp']))} rad/s constant"))
        else:
            facts.append((f"(L² − 2T·I{mid})/(2T·I{mid}), I{mid} the intermediate moment",
                          f"{fmt(float(p['separatrix_offset']), 4)}: "
                          + (f"the polhode circles axis {side}" if side else
                             "on the separatrix")))
        return SectionContent(
            figures=[cls.figure(
                "polhode_ellipsoid", fig,
                "Polhodes on the energy ellipsoid ω·Iω = 2T (the inertia ellipsoid scaled by "
                "√(2T)), body frame: each is its intersection with ω·I²ω = L². Grey: a ladder "
                + (f"of L² between 2T·I{smallest} and 2T·I{largest} (the smallest and the "
                   "largest moment); " if symmetric is None else
                   f"of L² between 2T·I{int(symmetric['axis'])} and 2T·I⊥ (the figure-axis "
                   "and the transverse moment); ")
                + (f"orange: the separatrices L² = 2T·I{mid}; " if len(p["separatrices"])
                   else "")
                + "red: ω of this scene as integrated.")],
            facts=facts)

    @classmethod
    def section_herpolhode(cls, data):
        c = data.analysis.get("poinsot")
        if c is None:
            return SectionContent(notes=["Poinsot's construction was not computed for this "
                                         "archive (a spherical body, or the section was not "
                                         "asked for when it was simulated)."])
        radius = c.get("herpolhode_radius")
        t = data.runs["main"].t
        contact_time = float(t[int(c["contact_index"])])
        fig = plots.poinsot(c["surface"], c["axes"], c["polhode"], c["herpolhode"],
                            float(c["plane_height"]),
                            circle_radius=None if radius is None else float(radius),
                            contact_time=contact_time)
        d = float(c["plane_distance"])
        facts = [("invariable plane at √(2T)/|L|", f"{fmt(d)} 1/√(kg m²)"),
                 ("tip of x off the plane", f"{fmt_err(float(c['plane_distance_max_error']))}"
                                            " 1/√(kg m²) at most over the run")]
        if radius is not None:
            facts.append(("herpolhode radius (symmetric body)",
                          f"{fmt(float(radius))} 1/√(kg m²) closed form; the run deviates by "
                          f"{fmt_err(float(c['herpolhode_radius_max_error']))} at most"))
        caption = ("Poinsot's construction, x = ω/√(2T) [1/√(kg m²)], seen with L pointing "
                   "down: the inertia ellipsoid x·Ix = 1 at t = "
                   f"{fmt(contact_time, 4)} s, resting on the invariable "
                   "plane at the tip of x; red, the polhode on the body; light blue, the herpolhode "
                   "the contact point has traced on the plane since t = 0 (right: the plane "
                   "seen along L).")
        if radius is not None:
            caption += " Dashed: the closed-form circle of the symmetric body."
        return SectionContent(figures=[cls.figure("poinsot", fig, caption)], facts=facts)

    @classmethod
    def section_stability(cls, data):
        a = data.analysis
        content = stability_table_section(a)
        if "flip" in a:
            f = a["flip"]
            run = data.runs["main"]
            k = int(f["axis"]) - 1
            fig = plots.flips(run.t, run.y[:, :3], envelope=f["growth_envelope"])
            count = len(np.atleast_1d(f["flip_times"]))
            flipped = {0: "the run ends before the body's first flip",
                       1: "the body flips over once within the run"}.get(
                count, f"the body flips over {count} times within the run")
            closest = (a.get("spin_axis") or {}).get("intermediate_closest_angle")
            where = (f"the polhode passes within {fmt(float(closest), 3)} rad of the "
                     f"intermediate axis {k + 1}" if closest is not None else
                     f"spin started close to the intermediate axis {k + 1}")
            content.figures.append(cls.figure(
                "flips", fig, f"Dzhanibekov effect: {where}; the perturbation grows at "
                f"γ = {fmt(f['growth_rate'])} 1/s and {flipped}."))
            content.facts += [
                ("flips observed", str(len(f["flip_times"]))),
                ("time between flips", f"{fmt(f['half_period_measured'])} s measured; "
                                       f"2K(m)/λ = {fmt(f['half_period_exact'])} s exact")]
        return content

    @classmethod
    def section_symmetric_precession(cls, data):
        s = data.analysis["symmetric"]
        figures = []
        steady = str(s.get("sense", "")).startswith("steady")
        if math.isfinite(float(s["Omega_measured"])) and not steady:  # no turning to draw
            run = data.runs["main"]
            axis = int(s["axis"])
            b, c = axis % 3 + 1, (axis + 1) % 3 + 1
            sense = {"prograde": "with the spin (prograde)",
                     "retrograde": "against the spin (retrograde)"}[
                cls.prose_case(data)["sense"]]
            fig = plots.symmetric_precession(run.t, run.y[:, :3], axis, float(s["Omega"]))
            figures.append(cls.figure(
                "symmetric_precession", fig,
                f"Left: the tip of ω⊥ = (ω{b}, ω{c}) in the body plane perpendicular to the "
                f"figure axis {axis}, as integrated, on the dashed circle |ω⊥| = "
                f"{fmt(float(s['omega_perp']))} rad/s; the arrow shows it turning "
                f"{sense}. Right: its unwrapped phase against time, a straight line of slope "
                f"−Ω = {fmt(-float(s['Omega']))} rad/s (dashed: notes (10.10))."))
        return SectionContent(figures=figures, facts=[
            ("symmetry axis", str(s["axis"])),
            ("precession rate Ω of the transverse ω, notes (10.10)",
             f"{fmt(s['Omega'], against=s['Omega_measured'])} rad/s"),
            ("Ω measured (minus the slope of the phase of ω⊥)",
             f"{fmt(s['Omega_measured'], against=s['Omega'])} rad/s"),
            ("|ω⊥|", f"{fmt(s['omega_perp'])} rad/s (constant)"),
            ("precession of the figure axis about L, |L|/I⊥",
             "none: the figure axis lies along L" if s.get("sense") ==
             "steady about the figure axis" else f"{fmt(s['space_precession_rate'])} rad/s")])

    @classmethod
    def section_geometric_integrator(cls, data):
        if "splitting" not in data.runs:
            return SectionContent(notes=["The splitting integrator was not run for this "
                                         "archive (the section was not asked for when it "
                                         "was simulated)."])
        split = data.runs["splitting"]
        a = data.analysis
        exact = split.reference
        errors, zero = omega_errors(split, exact)
        fig = common_plots.error_against_time(split.t, errors, ylabel="absolute error",
                                              unit="rad/s")
        scales = {q: split.attrs[f"scale_{q}"] for q in split.invariants}
        # relative drifts: each invariant by its declared symbol, without a unit
        symbols = {q: cls.schema.invariant(q).math for q in split.invariants}
        inv = common_plots.invariant_drift(split.t, split.invariants, scales=scales,
                                           labels=symbols)
        rows = [[INVARIANT_NAMES.get(name, name),
                 fmt_err(float(split.attrs.get(f"drift_{name}", math.nan))),
                 fmt_err(float(data.runs["main"].attrs.get(f"drift_{name}", math.nan)))]
                for name in split.invariants]
        return SectionContent(
            figures=[cls.figure("splitting_error", fig,
                                f"Error of the {method_name(data, split)} (h = "
                                f"{fmt(split.attrs['h'])} s) against the exact solution."
                                + zero_error_words(zero)),
                     cls.figure("splitting_invariants", inv, "Invariants under the splitting: "
                                "L² and the space-frame L are kept to round-off, the energy "
                                "error stays bounded.")],
            tables=[Table(caption="Max relative drift of each invariant.",
                          header=["quantity", "splitting", f"main run "
                                  f"({method_name(data, data.runs['main'])})"], rows=rows)],
            facts=[("max |ω − exact ω| (splitting)", f"{fmt_err(a['splitting_omega_max_error'])}"
                    f" rad/s in {fmt(float(split.attrs['wall_time_s']) * 1e3, 3)} ms, "
                    f"{int(split.attrs['nsteps'])} steps")])

    @classmethod
    def section_invariants(cls, data):
        return cls.invariants_section(
            data,
            labels=INVARIANT_NAMES,
            caption="Drift of 2T, L² and the space-frame L, relative to their natural scales; "
                    "|q| as integrated (the archived attitude is renormalized afterwards).")
