"""``inertia`` report: the tensor and its principal axes with the inertia ellipsoid, the
parallel-axis shift and the stability table (:func:`stability_table_section`, shared with
``rigid_body``'s report)."""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err, fmt_matrix
from ...scene.report import Report
from .results import SCHEMA

plots = lazy_module("reportgen.rendering.plots.rigid_body")


class InertiaReport(Report):
    """The inertia kind's sections, drawn from the archive alone."""

    schema = SCHEMA
    gallery_figures = ("inertia_ellipsoid",)

    @classmethod
    def gallery_headline(cls, data):
        import numpy as np

        from ...scene import gallery
        moments = np.asarray(data.analysis.get("principal_moments", ()), dtype=float)
        if moments.size != 3 or not np.all(np.isfinite(moments)):
            return super().gallery_headline(data)
        check = gallery.worst_check(data, "principal moment")
        text = f"principal moments {', '.join(fmt(float(m), 5) for m in moments)} kg m²"
        return text + (f", {gallery.from_reference(check.rel_error, 'the closed form')}"
                       if check is not None else "")

    sections = (
        Section("quadrature", "Volume, centre of mass and moments by quadrature"),
        Section("tensor", "Inertia tensor and principal axes"),
        Section("parallel_axis", "Parallel-axis shift"),
        Section("stability", "Stability of free spin about each principal axis"),
    )

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        if "parallel_axis" not in data.analysis:
            names.remove("parallel_axis")
        if "quadrature" not in data.analysis:
            names.remove("quadrature")
        return names

    @classmethod
    def headline(cls, data):
        a = data.analysis
        m = a["principal_moments"]
        st = [a["axis_stability"][f"axis_{k + 1}"] for k in range(3)]
        stability = ("every axis marginal (three equal moments)"
                     if top_of(a) == "spherical" else ", ".join(
                         f"I{k + 1}" + (f" (about {s['shape_axis'].split(',')[0]})"
                                        if "shape_axis" in s else "") + f": {s['verdict']}"
                         for k, s in enumerate(st)))
        facts = [("body", a["shape"]),
                 ("principal moments", ", ".join(f"{fmt(x)}" for x in m) + " kg m²"),
                 ("spin stability", stability)]
        q = a.get("quadrature")
        if q is not None and "apex_distance" in q:
            facts.insert(1, ("centre of mass below the apex",
                             f"{fmt(q['apex_distance'])} m by quadrature; 3h/4 = "
                             f"{fmt(q['apex_distance_closed'])} m (textbook ex. 4.6)"))
        return facts

    @classmethod
    def prose_case(cls, data):
        """Spherical (three equal moments), symmetric (two) or asymmetric, by the stored
        classification of the moments (:func:`top_of`)."""
        verdicts = [data.analysis["axis_stability"][f"axis_{k + 1}"]["verdict"]
                    for k in range(3)]
        top = top_of(data.analysis)
        stability = data.analysis["axis_stability"]
        words = [stability[f"axis_{k + 1}"].get("shape_axis") for k in range(3)]
        q = data.analysis.get("quadrature")
        shape = data.config.get("shape") or {}
        return {"spherical": top == "spherical", "symmetric": top == "symmetric",
                "asymmetric": top == "asymmetric",
                "intermediate": verdicts.index("unstable") + 1 if "unstable" in verdicts
                else None,
                "gap": close_gap(data.analysis["principal_moments"]),
                "equal_rtol": fmt_err(float(data.analysis.get("equal_moments_rtol", 1e-12))),
                "axis_words": words if all(words) else None,
                "quadrature": q is not None,
                "nodes": int(q["nodes"]) if q is not None else 0,
                "cone": q is not None and "apex_distance" in q,
                "tilted": shape.get("euler_angles") is not None,
                "revolution": shape.get("type") in ("cone", "cylinder", "ellipsoid"),
                "rectangle": shape.get("type") == "octahedron"
                and shape.get("equator") == "rectangle"}

    @classmethod
    def section_quadrature(cls, data):
        q = data.analysis["quadrature"]

        def diff(value, closed):
            return fmt_err(abs(float(value) - float(closed)))

        rows = [["volume [m³]", fmt(q["volume"]), fmt(q["volume_closed"]),
                 diff(q["volume"], q["volume_closed"])]]
        if "apex_distance" in q:
            rows.append(["centre of mass below the apex [m]", fmt(q["apex_distance"]),
                         fmt(q["apex_distance_closed"]) + " (3h/4)",
                         diff(q["apex_distance"], q["apex_distance_closed"])])
        else:
            cm = float(np.linalg.norm(q["centre_of_mass"]))
            rows.append(["centre of mass: distance from the centre [m]", fmt_err(cm), "0",
                         fmt_err(cm)])
        for k, axis in enumerate("xyz"):
            rows.append([f"moment about the shape's {axis} axis [kg m²]",
                         fmt(q["moments"][k]), fmt(q["moments_closed"][k]),
                         diff(q["moments"][k], q["moments_closed"][k])])
        rows.append(["largest product of inertia [kg m²]", fmt_err(q["products_max"]), "0",
                     fmt_err(q["products_max"])])
        source = data.analysis.get("closed_form", {}).get("source", "")
        return SectionContent(tables=[Table(
            caption=f"The body as {int(q['nodes'])} point masses at quadrature nodes, in "
                    "its own frame (before any tilt), against the closed forms"
                    + (f": {source}" if source else "") + ".",
            header=["quantity", "quadrature", "closed form", "difference"], rows=rows)])

    @classmethod
    def section_tensor(cls, data):
        a = data.analysis
        T, m, ax = a["tensor"], a["principal_moments"], a["principal_axes"]
        tensor = Table(caption="Inertia tensor about the centre of mass, lab frame [kg m²]",
                       header=["", "x", "y", "z"],
                       rows=[[c] + fmt_matrix(T)[i] for i, c in enumerate("xyz")])
        principal = Table(caption="Principal moments (ascending) and axes (lab-frame unit "
                                  "vectors) from diagonalization",
                          header=["axis", "moment [kg m²]", "direction"],
                          rows=[[f"{k + 1}", fmt(float(m[k])),
                                 "(" + ", ".join(fmt_matrix(ax[:, k])[0]) + ")"]
                                for k in range(3)])
        ell = a["inertia_ellipsoid"]
        pts = a.get("points")
        fig = plots.inertia_ellipsoid(m, ax, ell["surface"], ell["semi_axes"],
                                      points=pts["positions"] if pts else None,
                                      masses=pts["masses"] if pts else None)
        notes = []
        if "closed_form" in a:
            cf = a["closed_form"]
            notes.append(f"Closed form: {cf['source']}; largest relative difference of the "
                         f"diagonalized moments: {fmt_err(cf['max_relative_difference'])}.")
        return SectionContent(
            figures=[cls.figure("inertia_ellipsoid", fig,
                                "Inertia ellipsoid Σ Iₖ xₖ² = 1 (semi-axes 1/√Iₖ) with the "
                                "principal axes; points shown where the body is a point set.")],
            tables=[tensor, principal], notes=notes)

    @classmethod
    def section_parallel_axis(cls, data):
        p = data.analysis["parallel_axis"]
        T = p["tensor"]
        return SectionContent(tables=[
            Table(caption=f"Tensor about ({', '.join(fmt(float(x)) for x in p['about'])}) by "
                          "notes (8.49), I = Iᶜᵐ + M(d² 1 − d dᵀ) with Iᶜᵐ the tensor about the centre "
                          "of mass [kg m²]",
                  header=["", "x", "y", "z"],
                  rows=[[c] + fmt_matrix(T)[i] for i, c in enumerate("xyz")]),
            Table(caption="Principal moments and axes about that point.",
                  header=["axis", "moment [kg m²]", "direction"],
                  rows=[[f"{k + 1}", fmt(float(p["principal_moments"][k])),
                         "(" + ", ".join(fmt_matrix(p["principal_axes"][:, k])[0]) + ")"]
                        for k in range(3)])])

    @classmethod
    def section_stability(cls, data):
        return stability_table_section(data.analysis)


def close_gap(moments) -> str | None:
    """The relative gap of the two closest of three distinct moments in words, when it is
    too small for the printed six figures to show (below 10⁻⁴ of the largest); else None."""
    m = np.sort(np.asarray(moments, dtype=float))
    gap = float(np.min(np.diff(m))) / float(m[-1])
    return fmt_err(gap) if 0 < gap < 1e-4 else None


def top_of(analysis: dict) -> str:
    """The stored classification of the principal moments, "spherical", "symmetric" or
    "asymmetric" (``top`` of an inertia archive, ``body`` of a rigid-body one); an archive
    written before them: by its stability verdicts (marginal about 3, 2 or no axes)."""
    top = analysis.get("top") or analysis.get("body")
    if top:
        return str(top)
    marginal = [analysis["axis_stability"][f"axis_{k + 1}"]["verdict"]
                for k in range(3)].count("marginal")
    return {3: "spherical", 2: "symmetric"}.get(marginal, "asymmetric")


def stability_table_section(analysis: dict) -> SectionContent:
    """Table of the linear stability of free rotation about each principal axis, from an
    archive's ``analysis`` alone (shared by ``inertia`` and ``rigid_body``).

    Reads ``axis_stability/axis_<k>`` (verdict, growth_rate, oscillation_frequency and,
    from ``rigid_body``, growth_rate_jacobian), ``principal_moments`` and, when the rates
    are for a given spin rather than per unit spin, ``spin`` [rad/s].
    """
    stability = analysis["axis_stability"]
    moments = analysis["principal_moments"]
    spin = analysis.get("spin")
    top = top_of(analysis)
    rows = []
    unit = "1/s" if spin is not None else "× Ω"
    for k in range(3):
        s = stability[f"axis_{k + 1}"]
        rate = s["growth_rate"] if s["verdict"] == "unstable" else s["oscillation_frequency"]
        what = "growth rate" if s["verdict"] == "unstable" else "wobble frequency"
        if s["verdict"] == "marginal":  # equal moments: neither a wobble nor a growth
            cell = f"— (marginal: {top} body)"
        else:
            cell = f"{what}: {fmt(float(rate))} {unit}"
        row = [f"{k + 1}", fmt(float(moments[k]))]
        if "shape_axis" in s:
            row.append(str(s["shape_axis"]))
        row += [s["verdict"], cell]
        if "growth_rate_jacobian" in s:
            row.append(fmt(float(s["growth_rate_jacobian"])))
        rows.append(row)
    named = all("shape_axis" in stability[f"axis_{k + 1}"] for k in range(3))
    header = ["axis", "moment [kg m²]"] + (["the shape's axis"] if named else []) + [
        "verdict", "rate, notes (10.12)–(10.14)"]
    if any("growth_rate_jacobian" in stability[f"axis_{k + 1}"] for k in range(3)):
        header.append("max Re λ of the Jacobian [1/s]")
    verdicts = [stability[f"axis_{k + 1}"]["verdict"] for k in range(3)]
    if "unstable" in verdicts:
        k = verdicts.index("unstable")
        where = (f" (the shape's {stability[f'axis_{k + 1}']['shape_axis']})" if named else "")
        case = (f": unstable about the intermediate axis {k + 1}{where} with "
                "growth Ω√((I2−I1)(I3−I2)/(I1 I3)), stable about the other two")
    elif top == "spherical":
        case = ": all three moments equal, so no axis is unstable (every axis marginal)"
    elif top == "symmetric":
        case = (": two equal moments (a symmetric body), so no axis is unstable: marginal "
                "about the transverse axes, stable about the figure axis")
    else:
        case = ""
    return SectionContent(tables=[Table(
        caption="Free rotation about each principal axis, linearized, notes (10.12)–(10.14)"
                + ("" if spin is None else f" at spin Ω = {fmt(spin)} rad/s") + case + ".",
        header=header, rows=rows)])
