"""``rotation`` report: the rotation formula, the Euler-angle constructions, ω from the
rates and the stereographic projection with its Möbius maps, each with its checks."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err, fmt_matrix
from ...scene.report import Report
from .report_proofs import ProofsSection, time_ordered_notes, time_ordered_tables
from .results import IDENTITY_MATRICES, ORDER_RANGE, ORDER_SLACK, SCHEMA, SECTION_DATA, TOLERANCE

plots = lazy_module("reportgen.kinds.rotation.plots")
euler_figure = lazy_module("reportgen.kinds.rotation.euler_figure")


def verdict(errors, what: str) -> str:
    """``all 7 axis–angle checks hold`` or ``2 of 7 axis–angle checks fail``: the shown
    errors against the kind's bound :data:`~.results.TOLERANCE`."""
    failed = sum(1 for e in errors if not float(e) <= TOLERANCE)
    n = len(errors)
    if not failed:
        return f"both {what} hold" if n == 2 else f"all {n} {what} hold"
    return f"{failed} of {n} {what} fail"


def _vec(v) -> str:
    return "(" + ", ".join(fmt_matrix(v)[0]) + ")"


def _matrix_rows(M) -> list[list[str]]:
    return fmt_matrix(M)


def _deg(angle) -> str:
    """An angle [rad] as read in degrees: ``120°``."""
    return f"{fmt(math.degrees(float(angle)))}°"


def _degrees(angles) -> str:
    """Angles [rad] in degrees with the radians beside: ``28.6479°, 45.8366°, 17.1887°
    (0.5, 0.8, 0.3 rad)``."""
    return (", ".join(_deg(x) for x in angles) + " ("
            + ", ".join(fmt(float(x)) for x in angles) + " rad)")


def _complex(pair) -> str:
    """a + b i with the rounding of a unit-size number (below 1e-15) shown as 0."""
    pair = [0.0 if abs(float(v)) < 1e-15 else float(v) for v in np.asarray(pair)]
    re_, im = fmt_matrix(pair)[0]
    return f"{re_} {'−' if im.startswith('-') else '+'} {im.lstrip('-')} i"


def _rounded(x: float, scale: float) -> float:
    """x with its rounding below 1e-12 of ``scale`` removed, for a value shown (its
    deviation from the closed form is in the checks table)."""
    return round(float(x) / scale, 12) * scale if scale else float(x)


def _eigenvalues(pairs, scale: float) -> str:
    """Three eigenvalues, (real, imaginary) pairs, as read, the real ones first:
    ``1, −0.5 ± 0.866025 i`` (a conjugate pair once), ``0, ± 2.0944 i``,
    ``1, −0.5, −0.5``."""
    z = [complex(_rounded(re_, scale), _rounded(im, scale)) for re_, im in np.asarray(pairs)]
    z.sort(key=lambda w: (w.imag != 0, -w.real, w.imag))  # real ones first, largest first
    parts, used = [], set()
    for i, a in enumerate(z):
        if i in used:
            continue
        pair = next((j for j in range(i + 1, len(z)) if j not in used and a.imag != 0
                     and z[j] == a.conjugate()), None)
        if pair is None:
            parts.append(fmt(a.real) if a.imag == 0 else _complex((a.real, a.imag)))
            continue
        used.add(pair)
        imag = f"± {fmt(abs(a.imag))} i"
        parts.append(imag if a.real == 0 else f"{fmt(a.real)} {imag}")
    return ", ".join(parts).replace("-", "−")


#: the matrices A the similarity turns, as the identities tables name them
_MATRIX_NAMES = {"rotation": "R(n, Φ)", "generator": "Φ[n]×", "symmetric": "½(R + Rᵀ)"}
#: their closed-form eigenvalues, as the identities table writes them
_MATRIX_EIGEN = {"rotation": "1, cos Φ ± i sin Φ", "generator": "0, ± iΦ",
                 "symmetric": "1, cos Φ, cos Φ"}
_CONVENTION = {"zxz": "z-x-z", "zyz": "z-y-z"}


#: the stereographic section's checks, in the order of its table
MOBIUS_CHECKS = ("mobius_vs_rotation", "mobius_vs_rotation_standard_orientation",
                 "rotation_from_mobius", "rotation_trace_vs_quaternion",
                 "double_cover_rotation", "double_cover_mobius", "unitarity", "round_trip",
                 "scale_factor", "conformal_angle", "difference_quotient_chordal",
                 "composition_mobius", "composition_rotation")


def contrast_words(s) -> list[str]:
    """What the contrasts show, each chosen by its stored fact (``transpose_differs``,
    ``transpose_differs_standard``, ``reversed_differs``: a distance above ``CONTRAST``)."""
    words = ["R(U)ᵀ is not the Möbius map" if s["transpose_differs"] else
             "here R(U)ᵀ is the Möbius map too: R(U) is symmetric (a half turn)"]
    words.append("nor is it with the usual orientation" if s["transpose_differs_standard"]
                 else "with the usual orientation R(U)ᵀ is that Möbius map, R(Ū), here")
    words.append("the difference quotient tends to the scale factor as δ² (relative "
                 "distance)")
    words.append("the reversed order is another rotation" if s["reversed_differs"] else
                 "the reversed order gives the same rotation here (U and U₂ commute)")
    return words


class RotationReport(ProofsSection, Report):
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
        Section("axis_angle", "Axis and angle ↔ rotation matrix (textbook exercise 4.5)"),
        Section("euler_angles", "Euler angles: z-x-z and z-y-z (textbook exercises 4.7, 4.8)"),
        Section("angular_velocity", "Angular velocity from Euler-angle rates "
                                    "(textbook exercises 4.7, 4.8)"),
        Section("matrix_identities", "Matrix identities (textbook ex. 4.1–4.4)"),
        Section("matrix_proofs", "Textbook ex. 4.1–4.4 for every matrix: SymPy's proofs"),
        Section("su2_euler", "Euler's theorem and Euler angles in SU(2) (notes (9.17)–(9.18))"),
        Section("stereographic", "Stereographic projection, Möbius maps and SU(2) → SO(3) "
                                 "(textbook exercise 4.11)"),
    )

    @classmethod
    def default_sections(cls, data):
        return [s.name for s in cls.sections if SECTION_DATA[s.name] in data.analysis]

    @classmethod
    def prose_case(cls, data):
        """What the template's sentences branch on: the stereographic contrasts."""
        s = data.analysis.get("stereographic") or {}
        return {"transpose_differs": bool(s.get("transpose_differs", True)),
                "transpose_differs_standard": bool(s.get("transpose_differs_standard", True))}

    @classmethod
    def describe(cls, data):
        """``A rotation by 120° about n = (0.5774, 0.5774, 0.5774); z-y-z Euler angles along
        a path; an SU(2) matrix of angle 73.74° as a Möbius map``: what this scene turns."""
        a, parts = data.analysis, []
        if "axis_angle" in a:
            n = ", ".join(fmt(float(x), 4) for x in np.asarray(a["axis_angle"]["axis"]))
            parts.append(f"a rotation by {fmt(math.degrees(float(a['axis_angle']['angle'])), 4)}° "
                         f"about n = ({n})")
        if "euler" in a:
            c = str(a["euler"]["convention"])
            parts.append(f"{c[0]}-{c[1]}-{c[2]} Euler angles and ω along a path")
        if "stereographic" in a:
            parts.append(f"an SU(2) matrix turning by "
                         f"{fmt(math.degrees(float(a['stereographic']['su2_angle'])), 4)}° as a "
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
            facts.append(("textbook ex. 4.5: axis–angle ↔ matrix",
                          f"max error {fmt_err(max(e.values()))} (Φ = "
                          f"{_deg(a['axis_angle']['angle'])} about "
                          f"{_vec(a['axis_angle']['axis'])}; Goldstein's A = Rᵀ)"))
        if "euler" in a:
            e = a["euler"]["errors"]
            facts.append(("textbook ex. 4.7, 4.8: Euler matrices and ω",
                          f"max error {fmt_err(max(e.values()))} (z-x-z vs z-y-z, formulas vs "
                          "dR/dt)"))
        if "identities" in a:
            d = a["identities"]
            order = d.get("central_differences", {}).get("order")
            facts.append(("textbook ex. 4.1–4.4: matrix identities",
                          f"max error {fmt_err(max(d['errors'].values()))} (RᵀR = 1, det R = 1, "
                          "S A S⁻¹ keeps tr, det, eigenvalues; Ṙ R⁻¹ = [ω]×)"
                          + (f"; central differences of order {fmt(order, 4)}"
                             if order is not None else "")))
        if "su2_form" in a:
            facts.append(("notes (9.17)–(9.18): rotations in SU(2)",
                          f"max error {fmt_err(max(a['su2_form']['errors'].values()))} "
                          "(R(U) of U(n, Φ) and of the Euler-angle U vs the matrices)"))
        if "stereographic" in a:
            s = a["stereographic"]
            e = s["errors"]
            facts.append(("textbook ex. 4.11: Möbius map vs R(U)",
                          f"max error {fmt_err(e['mobius_vs_rotation'])} over "
                          f"{len(s['points'])} points; "
                          + (f"R(U)ᵀ would be off by {fmt(e['transpose_mismatch'], 3)}"
                             if s.get("transpose_differs", True) else
                             "R(U)ᵀ is the same map (R(U) is symmetric: a half turn)")
                          + "; scale factor 1/(1 − z) and "
                          "composition to "
                          + fmt_err(max(e[k] for k in ("scale_factor", "conformal_angle",
                                                       "difference_quotient_chordal",
                                                       "composition_mobius",
                                                       "composition_rotation")))))
        facts.append(("computed in", f"{1e3 * float(data.attrs.get('wall_time_s', 0.0)):.0f} ms"
                                     " (nothing integrated)"))
        return facts

    @classmethod
    def section_axis_angle(cls, data):
        a = data.analysis["axis_angle"]
        e = a["errors"]
        fig = plots.axis_angle(a["axis"], a["angle"], a["vector"], a["turned_vector"],
                               a["rotated_vector"], a["arc_turned"], a["circle"], a["centre"],
                               a["turned_axes"])
        facts = [("axis n (normalized)", _vec(a["axis"])),
                 ("angle Φ", f"{_deg(a['angle'])} "
                             f"({fmt(a['angle'], against=a['recovered_angle'])} rad)"),
                 ("r", _vec(a["vector"])),
                 ("R r (textbook ex. 4.5)", f"{_vec(a['turned_vector'])}: r turned by Φ "
                                            "about n"),
                 ("A r (Goldstein (4.62))", f"{_vec(a['rotated_vector'])}: r in the turned "
                                            "axes, A r = Rᵀ r"),
                 ("Goldstein's A", "A = Rᵀ = R(n, −Φ): max |R − Aᵀ| = "
                                   f"{fmt_err(e['textbook_vs_goldstein'])}"),
                 ("recovered from R",
                  f"Φ = {fmt(a['recovered_angle'], against=a['angle'])} rad, "
                  f"n = {_vec(a['recovered_axis'])}"),
                 ("det R", fmt(a["determinant"], against=1.0))]
        matrix = Table(caption="The textbook's R(n, Φ) (textbook ex. 4.5), active: column j "
                               "is the j-th axis unit vector turned by Φ about n. Goldstein's "
                               "passive A(n, Φ) of Goldstein (4.62) is its transpose.",
                       header=["", "x", "y", "z"],
                       rows=[[c] + row for c, row in zip("xyz", _matrix_rows(a["matrix_textbook"]),
                                                          strict=True)])
        shown = [e["textbook_vs_goldstein"], e["formula_vs_expm"], e["formula_vs_quaternion"],
                 max(e["turned_vector_vs_matrix"], e["vector_formula_vs_matrix"]),
                 e["orthogonality"], e["recovered_angle"], e["recovered_axis"]]
        checks = Table(caption=f"Each check's error against the bound {fmt(TOLERANCE)}: "
                               f"{verdict(shown, 'axis–angle checks')}. A small turn fixes "
                               "its axis only to ε/Φ, so the axis error is weighed by min(1, Φ); "
                               "near Φ = π the axis comes from the symmetric part.",
                       header=["check", "max error"],
                       rows=[["R vs Aᵀ, A column by column from Goldstein (4.62)",
                              fmt_err(e["textbook_vs_goldstein"])],
                             ["R vs exp(Φ[n]×) by eigenvectors",
                              fmt_err(e["formula_vs_expm"])],
                             ["R vs R(q), quaternion q = (cos Φ/2, n sin Φ/2)",
                              fmt_err(e["formula_vs_quaternion"])],
                             ["R r, A r vs their vector forms above, / |r|",
                              fmt_err(max(e["turned_vector_vs_matrix"],
                                          e["vector_formula_vs_matrix"]))],
                             ["R Rᵀ − 1", fmt_err(e["orthogonality"])],
                             ["Φ from tr R and ½(R − Rᵀ)",
                              fmt_err(e["recovered_angle"])],
                             ["n recovered, × min(1, Φ)",
                              fmt_err(e["recovered_axis"])]])
        return SectionContent(
            figures=[cls.figure("rotation_formula", fig,
                                "The textbook's rotation (textbook ex. 4.5) applied to r for "
                                "angles 0 … Φ: r turns by +Φ about n to R r, on the circle "
                                "about n through r (dotted); thin dashed: the axes x′, y′, "
                                "z′ turned with it (the columns of R). Goldstein's A r (Goldstein "
                                "(4.62)) gives the components of the fixed r in those turned "
                                "axes; drawn in the old axes it is r turned by −Φ.")],
            facts=facts, tables=[matrix, checks])

    @classmethod
    def section_euler_angles(cls, data):
        a = data.analysis["euler"]
        e = a["errors"]
        given, other = a["convention"], a["other_convention"]
        fig = plots.euler_constructions(a["construction"], (given, other))
        names = {"zxz": "z-x-z", "zyz": "z-y-z"}
        facts = [(f"{names[given]} angles (given) φ, θ, ψ", _degrees(a["path"][0])),
                 (f"{names[other]} angles of the same rotation", _degrees(a["path_other"][0]))]
        matrix = Table(caption=f"R = Aᵀ at t = 0 ({names[given]} product of elementary "
                               "rotations; Goldstein's A, Goldstein (4.46), is its transpose)",
                       header=["", "x′", "y′", "z′"],
                       rows=[[c] + row for c, row in zip("xyz", _matrix_rows(a["matrix"]),
                                                          strict=True)])
        shown = [e["matrix_product_vs_elements"], e["matrix_conventions"]]
        checks = Table(caption=f"Each check's error against the bound {fmt(TOLERANCE)}: "
                               f"{verdict(shown, 'Euler-matrix checks')}",
                       header=["check", "max error"],
                       rows=[["R by elementary rotations vs Goldstein (4.46) elements",
                              fmt_err(e["matrix_product_vs_elements"])],
                             [f"R by {names[given]} angles vs by {names[other]} angles "
                              "(converted), whole path",
                              fmt_err(e["matrix_conventions"])]])
        return SectionContent(
            figures=[*euler_figure.figures(a), cls.figure("line_of_nodes", fig,
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
        shown = [e[k] for k in ("omega_space_conventions", "omega_body_conventions",
                                "omega_space_derivative", "omega_body_derivative",
                                "body_is_space_rotated", "antisymmetry")]
        facts = [("rates φ̇, θ̇, ψ̇", ", ".join(fmt(float(x)) for x in a["rates"])
                  + " rad/s"),
                 ("sample path", f"(φ, θ, ψ)(t) = (φ, θ, ψ)(0) + (φ̇, θ̇, ψ̇) t, {len(t)} "
                                 f"points, t = 0 … {fmt(float(t[-1]))} s")]
        return SectionContent(
            facts=facts,
            tables=[path, Table(caption=f"Each check's error relative to max |ω| = "
                                        f"{fmt(a['omega_scale'])} rad/s over the path, against "
                                        f"the bound {fmt(TOLERANCE)}: "
                                        f"{verdict(shown, 'angular-velocity checks')}",
                                header=["check", "max error"], rows=rows),
                    *time_ordered_tables(a)], notes=time_ordered_notes(a))

    @classmethod
    def section_matrix_identities(cls, data):
        d = data.analysis["identities"]
        e = d["errors"]
        facts = [("turned axis S n", _vec(d["turned_axis"]))]
        rows = []
        for i, name in enumerate(IDENTITY_MATRICES):
            scale = max(1.0, float(np.max(np.abs(d["turned"][i]))))
            rows.append([_MATRIX_NAMES[name], fmt(_rounded(d["trace_turned"][i], scale)),
                         fmt(_rounded(d["determinant_turned"][i], scale)),
                         _eigenvalues(d["eigenvalues_turned"][i], scale), _MATRIX_EIGEN[name]])
        invariants = Table(caption="What A′ = S A S⁻¹ keeps, computed; "
                                   "A gives the same to the deviations below",
                           header=["A", "tr A′", "det A′", "eigenvalues of A′", "closed form"],
                           rows=rows)
        rows = [["RᵀR = 1 (orthogonality, notes (9.19)), det R = 1: R(n, Φ), S R(n, Φ), R(t), "
                 "R(t) R(n, Φ); S⁻¹ = Sᵀ",
                 fmt_err(max(e["orthogonality"], e["determinant"],
                             e["inverse_is_transpose"])), "rounding"],
                ["S A S⁻¹ = A built on S n; antisymmetry, symmetry kept",
                 fmt_err(max(e["similarity_closed_form"], e["symmetry_kept"])), "rounding"],
                ["tr A′ = tr A = closed form", fmt_err(e["trace_invariant"]), "rounding"],
                ["det A′ = det A = closed form", fmt_err(e["determinant_invariant"]),
                 "rounding"],
                ["eigenvalues of A′ = of A = closed form", fmt_err(e["eigenvalue_invariant"]),
                 "rounding"],
                ["Ṙ R⁻¹ + (Ṙ R⁻¹)ᵀ = 0, Ṙ exact (complex step)",
                 fmt_err(e["rdot_antisymmetric"]), "rounding"],
                ["Ṙ R⁻¹ = [ω]×, ω in space axes from the Euler-angle rates",
                 fmt_err(e["rdot_is_omega"]), "rounding"],
                ["Ȧ A⁻¹ = −[ω′]× for Goldstein's A = Rᵀ, ω′ in body axes",
                 fmt_err(e["adot_is_omega_body"]), "rounding"]]
        shown = [e[k] for k in ("orthogonality", "determinant", "inverse_is_transpose",
                                "similarity_closed_form", "symmetry_kept", "trace_invariant",
                                "determinant_invariant", "eigenvalue_invariant",
                                "rdot_antisymmetric", "rdot_is_omega", "adot_is_omega_body")]
        caption = (f"Bound {fmt(TOLERANCE)} where rounding limits: "
                   f"{verdict(shown, 'identities limited by rounding')}; the rows with Ṙ "
                   + (f"relative to max |ω| = {fmt(d['omega_scale'])} rad/s."
                      if d["omega_scale"] > 0 else "absolute [rad/s], as ω = 0 on this path."))
        cd = d.get("central_differences")
        if cd is not None:
            rows += [["D(h) R⁻¹ + (D(h) R⁻¹)ᵀ = 0", fmt_err(cd["antisymmetry"]), "h²"],
                     ["D(h) R⁻¹ = [ω]×: e(h)", fmt_err(cd["omega"]), "h²"],
                     ["D(2h) R⁻¹ = [ω]×: e(2h)", fmt_err(cd["omega_double_step"]), "h²"],
                     ["(4 D(h) − D(2h))/3 R⁻¹ = [ω]× (Richardson)",
                      fmt_err(cd["omega_richardson"]), "h⁴"]]
            caption += (f" D(h): the central difference above on the stored path, "
                        f"h = {fmt(cd['step'])} s")
            if "order" in cd:
                if cd["step"] * d["omega_scale"] > ORDER_RANGE:
                    checked = f"not checked, as h max |ω| is above {fmt(ORDER_RANGE)}"
                elif abs(cd["order"] - 2.0) <= ORDER_SLACK:
                    checked = f"checked: within 2 ± {fmt(ORDER_SLACK)}"
                else:
                    checked = f"checked: outside 2 ± {fmt(ORDER_SLACK)}, the check fails"
                caption += f"; order log₂(e(2h)/e(h)) = {fmt(cd['order'], 4)} ({checked})"
            caption += "."
        checks = Table(caption=caption, header=["identity", "largest deviation", "limited by"],
                       rows=rows)
        return SectionContent(facts=facts, tables=[invariants, checks])

    @classmethod
    def section_su2_euler(cls, data):
        d = data.analysis["su2_form"]
        e = d["errors"]
        given = str(d["convention"])
        other = "zxz" if given == "zyz" else "zyz"
        shift = ("(φ + π/2, θ, ψ − π/2)" if given == "zyz" else "(φ − π/2, θ, ψ + π/2)")
        alpha = float(d["euler_angle"])
        facts = [("U(n, Φ) of the turn R(n, Φ), textbook ex. 4.5",
                  f"a = {_complex(d['a'])}, b = {_complex(d['b'])} (Φ = {_deg(d['angle'])} "
                  f"about {_vec(d['axis'])})"),
                 (f"{_CONVENTION[given]} angles at t = 0", _degrees(d["euler_angles"])),
                 ("U(φ, θ, ψ) at t = 0",
                  f"a = {_complex(d['euler_a'])}, b = {_complex(d['euler_b'])}"),
                 ("one turn (Euler's theorem)",
                  f"α = {_deg(alpha)} about m = {_vec(d['euler_axis'])}"
                  + ("; −U turns by 360° − α about −m" if alpha > math.pi else ""))]
        checks = Table(
            caption=f"Each check's error against the bound {fmt(TOLERANCE)}: "
                    f"{verdict(list(e.values()), 'SU(2) checks')}; the Euler-angle rows over the "
                    "whole path of the Euler-angle section",
            header=["check", "max error"],
            rows=[["cos(Φ/2) 1 − i sin(Φ/2) n·σ vs exp(−iΦ n·σ/2) by eigenvectors",
                   fmt_err(e["closed_form_vs_exp"])],
                  ["R(U(n, Φ)) vs the textbook's R(n, Φ) (textbook ex. 4.5)",
                   fmt_err(e["rotation_vs_textbook"])],
                  ["U U† − 1, det U − 1", fmt_err(e["unitarity"])],
                  [f"R(U) of the {_CONVENTION[given]} product U vs the Euler matrix",
                   fmt_err(e["euler_rotation_vs_matrix"])],
                  ["the product U vs its a, b multiplied out",
                   fmt_err(e["euler_product_vs_cayley_klein"])],
                  [f"U by {_CONVENTION[given]} angles vs by {_CONVENTION[other]} angles "
                   f"{shift}", fmt_err(e["euler_conventions"])],
                  ["R(m, α) of the one turn vs the Euler matrix at t = 0",
                   fmt_err(e["euler_theorem"])],
                  ["U(φ + 2π, θ, ψ) + U(φ, θ, ψ): the sign flips", fmt_err(e["two_pi_flip"])],
                  ["R(U(φ + 2π, θ, ψ)) vs R(U(φ, θ, ψ)): R does not",
                   fmt_err(e["double_cover"])]])
        tables = [checks]
        if "notes" in d:
            tables.append(cls._notes_su2_table(d["notes"], e))
        return SectionContent(facts=facts, tables=tables)

    @classmethod
    def _notes_su2_table(cls, n, e) -> Table:
        """The notes' own form of SU(2) → SO(3), notes (9.4)–(9.16), at the scene's U."""
        alpha, beta, gamma = (float(n[k]) for k in ("alpha", "beta", "gamma"))
        trace = float(n["case_9_12_trace"])
        half_turn = abs(trace + 1.0) < 1e-9
        what = (f"a half-turn (tr R = {fmt(trace, 3)}) about {_vec(n['case_9_12_axis'])}"
                if half_turn else f"a turn with tr R = {fmt(trace, 6)}")
        errors = [e[k] for k in e if str(k).startswith("notes_")]
        return Table(
            caption="The notes' own parametrization at the scene's U: u(α, β, γ) of notes "
                    f"(9.4) with α = {_deg(alpha)}, β = {_deg(beta)}, γ = {_deg(gamma)}, and "
                    "M = 1 + xσ₁ + yσ₂ + zσ₃ of notes (9.5) at 12 points of lengths 0.25 to "
                    f"1.75; {verdict(errors, 'checks')}. The special cases turn by twice the "
                    "angle in u.",
            header=["check", "max error"],
            rows=[["u(α, β, γ), notes (9.4), vs U", fmt_err(e["notes_parametrization"])],
                  ["det M vs 1 − r², notes (9.6)", fmt_err(e["notes_determinant"])],
                  ["det uMu† vs det M, notes (9.7)", fmt_err(e["notes_determinant_kept"])],
                  ["r′ read off uMu† vs R(U) r, notes (9.8)",
                   fmt_err(e["notes_map_vs_rotation"])],
                  ["β = γ = 0: R(u) vs R₂(2α), notes (9.10)", fmt_err(e["notes_second_axis"])],
                  ["α = 0: R(u) vs R₃(2β), notes (9.11)", fmt_err(e["notes_third_axis"])],
                  ["β = 0, γ = π/2: R(u) vs R₁(2α), notes (9.16)",
                   fmt_err(e["notes_first_axis"])],
                  ["notes (9.10) as printed ends in sin 2α; the map gives cos 2α: they differ by",
                   fmt(float(n["printed_9_10_entry"]), 3)],
                  [f"α = π/2, β = 0, notes (9.12), at γ = {_deg(gamma)}: R(u) is {what}; "
                   "its distance from the R₃(2γ) the notes state",
                   fmt(float(n["case_9_12_vs_third_axis"]), 3)],
                  *cls._notes_euler_rows(n, e)])

    @staticmethod
    def _notes_euler_rows(n, e) -> list[list[str]]:
        """Euler's angles in the notes' SU(2), notes (9.17)–(9.18) (archives written before
        these were stored have none)."""
        if "notes_euler_half_angles" not in e or "euler_angles" not in n:
            return []
        angles = ", ".join(_deg(float(a)) for a in n["euler_angles"])
        return [[f"(φ, θ, ψ) = ({angles}): U₃(ψ)U₁(θ)U₃(φ) of notes (9.18) vs "
                 "u(θ/2, φ + ψ, ψ − φ + π/2) of notes (9.4)",
                 fmt_err(e["notes_euler_identification"])],
                ["with ψ/2 and φ/2: its R vs R₃(ψ)R₁(θ)R₃(φ) of notes (9.17)",
                 fmt_err(e["notes_euler_half_angles"])],
                ["with the full angles as notes (9.18) prints them, its R is R₃(2ψ)R₁(θ)R₃(2φ): "
                 "its distance from R₃(ψ)R₁(θ)R₃(φ) of notes (9.17) (not a check)",
                 fmt(float(n["printed_9_18_full_angles"]), 3)]]

    @staticmethod
    def _second_text(data, s) -> str:
        """Where U₂ of the composition check comes from, in words."""
        source = str(s["second_source"])
        if source == "axis_angle" and "axis_angle" in data.analysis:
            a = data.analysis["axis_angle"]
            return (f"the turn of textbook ex. 4.5, {_deg(a['angle'])} about "
                    f"{_vec(a['axis'])}")
        if source == "euler":
            return "the Euler angles' U at t = 0"
        if source == "su2":
            return "U itself (U₂ = U)"
        return f"a = {_complex(s['second_a'])}, b = {_complex(s['second_b'])}"

    @classmethod
    def section_stereographic(cls, data):
        s = data.analysis["stereographic"]
        e, c = s["errors"], s["contrasts"]
        steps = [float(x) for x in c["steps"]]
        fig = plots.stereographic(s)
        facts = [("U = [[a, b], [−b̄, ā]]", f"a = {_complex(s['a'])}, b = {_complex(s['b'])}"),
                 ("U = exp(−i α n·σ/2)", f"α = {_deg(s['su2_angle'])} ({fmt(s['su2_angle'])} rad) about "
                                          f"{_vec(s['su2_axis'])}; −U: α + 2π"),
                 ("sample points", f"{len(s['points'])} (golden-angle spiral, no pole)"),
                 ("scale factor 1/(1 − z)", f"{fmt(float(np.min(s['conformal_factor'])))} to "
                                            f"{fmt(float(np.max(s['conformal_factor'])))} "
                                            "at the sample points"),
                 ("U₂ (composition)", cls._second_text(data, s))]
        matrix = Table(caption="R(U)ᵢⱼ = ½ tr(σᵢ U σⱼ U†), the same for −U",
                       header=["", "x", "y", "z"],
                       rows=[[c] + row for c, row in zip("xyz", _matrix_rows(s["rotation"]),
                                                          strict=True)])
        checks = Table(
            caption=f"Each check's error against the bound {fmt(TOLERANCE)} (distances on the "
                    "unit sphere, which stay finite where ζ → ∞): "
                    f"{verdict([e[k] for k in MOBIUS_CHECKS], 'Möbius-map checks')}. "
                    "Near the pole 1 − z keeps the points' rounding only to ε/(1 − z): the "
                    "relative errors of the scale factor are weighed by min(1, 1 − z).",
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
                  ["π⁻¹(π(x)) − x", fmt_err(e["round_trip"])],
                  *([["|f′(ζ)| (1 + |ζ|²)/(1 + |f(ζ)|²) − 1 for the Möbius map f of U: "
                      "distances kept (textbook ex. 4.11(d))", fmt_err(e["isometry"])],
                     ["the same for U diag(2, ½), det 1 but not unitary: distances change by "
                      "up to (not a check)", fmt(float(s["isometry_non_unitary"]), 3)]]
                    if "isometry" in e and "isometry_non_unitary" in s else []),
                  ["|dζ/ds| (1 − z) − 1 east and south, dζ/ds by the complex step",
                   fmt_err(e["scale_factor"])],
                  ["Re(dζ(east) dζ̄(south)) (1 − z)²: right angles stay right",
                   fmt_err(e["conformal_angle"])],
                  [f"|Δζ|/|Δx| vs 1/√((1 − z₊)(1 − z₋)), arc δ = {fmt(steps[0])}",
                   fmt_err(e["difference_quotient_chordal"])],
                  ["Möbius map of U U₂ vs that of U after that of U₂",
                   fmt_err(e["composition_mobius"])],
                  ["R(U U₂) vs R(U) R(U₂)", fmt_err(e["composition_rotation"])]])
        quotient = [[f"|Δζ|/|Δx| vs 1/(1 − z), arc δ = {fmt(step)}",
                     fmt(float(dev), 3)] for step, dev in zip(steps, c["quotient_vs_factor"],
                                                              strict=True)]
        contrast = Table(
            caption="Not checks: " + "; ".join(contrast_words(s)),
            header=["candidate", "max distance"],
            rows=[["R(U)ᵀ, ζ = (x − iy)/(1 − z)", fmt(e["transpose_mismatch"], 4)],
                  ["R(U)ᵀ, ζ = (x + iy)/(1 − z)",
                   fmt(e["transpose_mismatch_standard_orientation"], 4)],
                  *quotient,
                  ["Möbius map of U after that of U₂ (reversed)",
                   fmt(c["reversed_mobius"], 4)],
                  ["R(U₂) R(U) (reversed)", fmt(c["reversed_rotation"], 4)]])
        return SectionContent(
            figures=[cls.figure("mobius", fig,
                                "Left: sample points x on the sphere and their images R(U) x; "
                                "a circle of latitude and its image. Right: the projections "
                                "ζ = (x − iy)/(1 − z) (plane seen from below) and their Möbius "
                                "images (aζ + b)/(−b̄ζ + ā), which fall on the projections of "
                                "R(U) x (dots in rings); circles go to circles.")],
            facts=facts, tables=[matrix, checks, contrast])
