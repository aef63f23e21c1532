"""``rotation`` report: the rotation formula, the Euler-angle constructions, ω from the
rates and the stereographic projection with its Möbius maps, each with its checks."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err, fmt_matrix
from ...scene.report import Report
from .results import SCHEMA, SECTION_DATA, TOLERANCE

plots = lazy_module("reportgen.kinds.rotation.plots")


def _vec(v) -> str:
    return "(" + ", ".join(fmt_matrix(v)[0]) + ")"


def _matrix_rows(M) -> list[list[str]]:
    return fmt_matrix(M)


def _complex(pair) -> str:
    re_, im = fmt_matrix(pair)[0]
    return f"{re_} {'−' if im.startswith('-') else '+'} {im.lstrip('-')} i"


class RotationReport(Report):
    """The rotation kind's sections, drawn from the archive alone."""

    schema = SCHEMA
    gallery_figures = ("rotation_formula", "line_of_nodes")

    @classmethod
    def gallery_headline(cls, data):
        from ...scene import gallery
        checks = [c for c in data.checks if math.isfinite(c.rel_error)]
        if not checks:
            return super().gallery_headline(data)
        worst = max(c.rel_error for c in checks)
        # only what this scene turns (the configured exercises; the gallery reads the
        # archive light, without /analysis groups): rotation_euler has no SU(2)
        topics = [words for key, words in (("axis_angle", "axis–angle"),
                                           ("euler", "Euler angles and ω"),
                                           ("su2", "SU(2)"))
                  if data.config.get(key) is not None]
        return (f"{len(checks)} identities"
                + (f" ({', '.join(topics)})" if topics else "")
                + f" checked: the largest discrepancy {gallery.distance(worst)}")

    sections = (
        Section("axis_angle", "Axis and angle ↔ rotation matrix (exercise 4.5)"),
        Section("euler_angles", "Euler angles: z-x-z and z-y-z (exercises 4.7, 4.8)"),
        Section("angular_velocity", "Angular velocity from Euler-angle rates "
                                    "(exercises 4.7, 4.8)"),
        Section("stereographic", "Stereographic projection, Möbius maps and SU(2) → SO(3) "
                                 "(exercise 4.11)"),
    )

    @classmethod
    def default_sections(cls, data):
        return [s.name for s in cls.sections if SECTION_DATA[s.name] in data.analysis]

    @classmethod
    def describe(cls, data):
        """``A rotation by 120° about n = (0.5774, 0.5774, 0.5774); z-y-z Euler angles along
        a path; an SU(2) matrix of angle 73.74° as a Möbius map``: what this scene turns."""
        a, parts = data.analysis, []
        if "axis_angle" in a:
            n = ", ".join(fmt(float(x), 4) for x in np.asarray(a["axis_angle"]["axis"]))
            parts.append(f"a rotation by {math.degrees(float(a['axis_angle']['angle'])):.4g}° "
                         f"about n = ({n})")
        if "euler" in a:
            c = str(a["euler"]["convention"])
            parts.append(f"{c[0]}-{c[1]}-{c[2]} Euler angles and ω along a path")
        if "stereographic" in a:
            parts.append(f"an SU(2) matrix turning by "
                         f"{math.degrees(float(a['stereographic']['su2_angle'])):.4g}° as a "
                         "Möbius map of the Riemann sphere")
        if not parts:
            return super().describe(data)
        text = "; ".join(parts)
        return text[:1].upper() + text[1:]

    @classmethod
    def headline(cls, data):
        a = data.analysis
        facts = []
        if "axis_angle" in a:
            e = a["axis_angle"]["errors"]
            facts.append(("ex. 4.5 axis–angle ↔ matrix",
                          f"max error {fmt_err(max(e.values()))} (Φ = "
                          f"{fmt(a['axis_angle']['angle'])} rad about "
                          f"{_vec(a['axis_angle']['axis'])})"))
        if "euler" in a:
            e = a["euler"]["errors"]
            facts.append(("ex. 4.7, 4.8 Euler matrices and ω",
                          f"max error {fmt_err(max(e.values()))} (z-x-z vs z-y-z, formulas vs "
                          "dR/dt)"))
        if "stereographic" in a:
            s = a["stereographic"]
            facts.append(("ex. 4.11 Möbius map vs R(U)",
                          f"max error {fmt_err(s['errors']['mobius_vs_rotation'])} over "
                          f"{len(s['points'])} points; R(U)ᵀ would be off by "
                          f"{fmt(s['errors']['transpose_mismatch'], 3)}"))
        facts.append(("computed in", f"{1e3 * float(data.attrs.get('wall_time_s', 0.0)):.0f} ms"
                                     " (nothing integrated)"))
        return facts

    @classmethod
    def section_axis_angle(cls, data):
        a = data.analysis["axis_angle"]
        e = a["errors"]
        fig = plots.axis_angle(a["axis"], a["angle"], a["vector"], a["rotated_vector"], a["arc"],
                               a["circle"], a["centre"], a["turned_axes"])
        facts = [("axis n (normalized)", _vec(a["axis"])),
                 ("angle Φ", f"{fmt(a['angle'], against=a['recovered_angle'])} rad = "
                             f"{fmt(math.degrees(a['angle']))}°"),
                 ("r", _vec(a["vector"])),
                 ("r′ by (4.62)", _vec(a["rotated_vector"])),
                 ("recovered from the matrix",
                  f"Φ = {fmt(a['recovered_angle'], against=a['angle'])} rad, "
                  f"n = {_vec(a['recovered_axis'])}"),
                 ("det A", fmt(a["determinant"], against=1.0))]
        matrix = Table(caption="A(n, Φ) from Goldstein (4.62), column j = the formula applied to "
                               "the j-th axis unit vector (passive: components in the turned "
                               "axes); the active rotation reportgen uses elsewhere is R = Aᵀ",
                       header=["", "x", "y", "z"],
                       rows=[[c] + row for c, row in zip("xyz", _matrix_rows(a["matrix_formula"]),
                                                          strict=True)])
        checks = Table(caption=f"Each check's error (bound {TOLERANCE:g}). A small turn fixes "
                               "its axis only to ε/Φ, so the axis error is weighed by min(1, Φ); "
                               "near Φ = π the axis comes from the symmetric part.",
                       header=["check", "max error"],
                       rows=[["A(4.62) vs exp(−Φ[n]×) by eigenvectors",
                              fmt_err(e["formula_vs_expm"])],
                             ["A(4.62) vs R(q)ᵀ, quaternion",
                              fmt_err(e["formula_vs_quaternion"])],
                             ["r′ by (4.62) vs A r, / |r|",
                              fmt_err(e["vector_formula_vs_matrix"])],
                             ["A Aᵀ − 1", fmt_err(e["orthogonality"])],
                             ["Φ from tr R and ½(R − Rᵀ)",
                              fmt_err(e["recovered_angle"])],
                             ["n recovered, × min(1, Φ)",
                              fmt_err(e["recovered_axis"])]])
        return SectionContent(
            figures=[cls.figure("rotation_formula", fig,
                                "The rotation formula (4.62) applied to r for angles 0 … Φ: r′ "
                                "are the components of r in axes turned by +Φ about n (thin "
                                "dashed: the turned axes), so drawn in the old axes r′ is r "
                                "turned by −Φ.")],
            facts=facts, tables=[matrix, checks])

    @classmethod
    def section_euler_angles(cls, data):
        a = data.analysis["euler"]
        e = a["errors"]
        given, other = a["convention"], a["other_convention"]
        fig = plots.euler_constructions(a["construction"], (given, other))
        names = {"zxz": "z-x-z", "zyz": "z-y-z"}

        def angles(v):
            return ", ".join(fmt(float(x)) for x in v)

        facts = [(f"{names[given]} angles (given) φ, θ, ψ", angles(a["path"][0]) + " rad"),
                 (f"{names[other]} angles of the same rotation", angles(a["path_other"][0])
                  + " rad")]
        matrix = Table(caption=f"R = Aᵀ at t = 0 ({names[given]} product of elementary "
                               "rotations; Goldstein's A of (4.46) is its transpose)",
                       header=["", "x′", "y′", "z′"],
                       rows=[[c] + row for c, row in zip("xyz", _matrix_rows(a["matrix"]),
                                                          strict=True)])
        checks = Table(caption=f"Each check's error (bound {TOLERANCE:g})",
                       header=["check", "max error"],
                       rows=[["R by elementary rotations vs (4.46) elements",
                              fmt_err(e["matrix_product_vs_elements"])],
                             [f"R by {names[given]} angles vs by {names[other]} angles "
                              "(converted), whole path",
                              fmt_err(e["matrix_conventions"])]])
        return SectionContent(
            figures=[cls.figure("line_of_nodes", fig,
                                "One rotation, two constructions: the body axes x′, y′, z′ "
                                "are the same; the line of nodes (the intermediate x axis for "
                                "z-x-z, y axis for z-y-z) and φ, ψ differ by π/2.")],
            facts=facts, tables=[matrix, checks])

    @classmethod
    def section_angular_velocity(cls, data):
        a = data.analysis["euler"]
        e = a["errors"]
        names = {"zxz": "z-x-z", "zyz": "z-y-z"}
        given, other = names[a["convention"]], names[a["other_convention"]]
        t = a["t"]
        picks = np.unique(np.linspace(0, len(t) - 1, 5).round().astype(int))
        path = Table(caption=f"ω along the path by the {given} rate formulas (the {other} "
                             "formulas and Ṙ give the same to the errors below) [rad/s]",
                     header=["t [s]", "ω space axes", "ω body axes"],
                     rows=[[fmt(float(t[i])), _vec(a["omega_space"][i]),
                            _vec(a["omega_body"][i])] for i in picks])
        rows = [[f"ω space: {given} vs {other} formulas", fmt_err(e["omega_space_conventions"])],
                [f"ω body: {given} vs {other} formulas", fmt_err(e["omega_body_conventions"])],
                ["ω space: formula vs vee(Ṙ Rᵀ)", fmt_err(e["omega_space_derivative"])],
                ["ω body: formula vs vee(Rᵀ Ṙ)", fmt_err(e["omega_body_derivative"])],
                ["ω space vs R ω body", fmt_err(e["body_is_space_rotated"])],
                ["Ṙ Rᵀ + (Ṙ Rᵀ)ᵀ, zero as R Rᵀ = 1", fmt_err(e["antisymmetry"])]]
        facts = [("rates φ̇, θ̇, ψ̇", ", ".join(fmt(float(x)) for x in a["rates"])
                  + " rad/s"),
                 ("sample path", f"(φ, θ, ψ)(t) = (φ, θ, ψ)(0) + (φ̇, θ̇, ψ̇) t, {len(t)} "
                                 f"points, t = 0 … {fmt(float(t[-1]))} s")]
        return SectionContent(
            facts=facts,
            tables=[path, Table(caption=f"Each check's error relative to max |ω| = "
                                        f"{fmt(a['omega_scale'])} rad/s over the path (bound "
                                        f"{TOLERANCE:g})",
                                header=["check", "max error"], rows=rows)])

    @classmethod
    def section_stereographic(cls, data):
        s = data.analysis["stereographic"]
        e = s["errors"]
        fig = plots.stereographic(s)
        facts = [("U = [[a, b], [−b̄, ā]]", f"a = {_complex(s['a'])}, b = {_complex(s['b'])}"),
                 ("U = exp(−i α n·σ/2)", f"α = {fmt(s['su2_angle'])} rad about "
                                          f"{_vec(s['su2_axis'])}; −U: α + 2π"),
                 ("sample points", f"{len(s['points'])} (golden-angle spiral, no pole)")]
        matrix = Table(caption="R(U)ᵢⱼ = ½ tr(σᵢ U σⱼ U†), the same for −U",
                       header=["", "x", "y", "z"],
                       rows=[[c] + row for c, row in zip("xyz", _matrix_rows(s["rotation"]),
                                                          strict=True)])
        checks = Table(
            caption=f"Each check's error (bound {TOLERANCE:g}; distances on the unit sphere, "
                    "which stay finite where ζ → ∞)",
            header=["check", "max error"],
            rows=[["Möbius map of U vs R(U), ζ = (x − iy)/(1 − z)",
                   fmt_err(e["mobius_vs_rotation"])],
                  ["Möbius map of U vs R(Ū), ζ = (x + iy)/(1 − z)",
                   fmt_err(e["mobius_vs_rotation_standard_orientation"])],
                  ["R from the Möbius map of the axis unit vectors vs ½ tr",
                   fmt_err(e["rotation_from_mobius"])],
                  ["½ tr(σᵢ U σⱼ U†) vs quaternion formula",
                   fmt_err(e["rotation_trace_vs_quaternion"])],
                  ["R(−U) vs R(U)", fmt_err(e["double_cover_rotation"])],
                  ["Möbius map of −U vs that of U", fmt_err(e["double_cover_mobius"])],
                  ["U U† − 1, det U − 1", fmt_err(e["unitarity"])],
                  ["π⁻¹(π(x)) − x", fmt_err(e["round_trip"])]])
        contrast = Table(
            caption="Not checks: the transpose is not the Möbius map (for a half turn, or an "
                    "axis in the x–z plane with the usual orientation, it would be)",
            header=["candidate", "max distance"],
            rows=[["R(U)ᵀ, ζ = (x − iy)/(1 − z)", fmt(e["transpose_mismatch"], 4)],
                  ["R(U)ᵀ, ζ = (x + iy)/(1 − z)",
                   fmt(e["transpose_mismatch_standard_orientation"], 4)]])
        return SectionContent(
            figures=[cls.figure("mobius", fig,
                                "Left: sample points x on the sphere and their images R(U) x; "
                                "a circle of latitude and its image. Right: the projections "
                                "ζ = (x − iy)/(1 − z) (plane seen from below) and their Möbius "
                                "images (aζ + b)/(−b̄ζ + ā), which fall on the projections of "
                                "R(U) x (dots in rings); circles go to circles.")],
            facts=facts, tables=[matrix, checks, contrast])
