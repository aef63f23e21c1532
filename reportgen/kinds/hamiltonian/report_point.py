"""``hamiltonian`` report, a point transformation q = q(q′) of L (notes (3.39)–(3.47)): L′
and its Hamiltonian, the notes' identities as SymPy simplified them, and the run of L′
carried back to the old coordinates against the main run, from the archive alone."""

from __future__ import annotations

from ...scene.content import SectionContent, Table, fmt, fmt_err
from .symbols import symbol_text


class PointTransformSections:
    """Mixed into :class:`.report.HamiltonianReport` (its ``LONGEST_EQUATION``)."""

    #: what a simplified identity's verdict says, by the stored flag
    SIMPLIFIED = {True: "yes, simplified to 0 by SymPy",
                  False: "not shown by SymPy's simplification"}

    @classmethod
    def section_point_transform(cls, data):
        """L′(q′, q̇′) = L(q(q′), J q̇′): the same Euler–Lagrange equations contracted with
        the Jacobian (notes (3.47)), and the same orbit."""
        a = data.analysis
        old_tex, new_tex = list(a["latex"]["q"]), list(a["point_transform_coordinates_latex"])
        new_words = ", ".join(symbol_text(str(q)) for q in a["point_transform_coordinates"])
        eqs = [("the old coordinates as functions of the new", r",\quad ".join(
                    f"{q} = {f}" for q, f in zip(old_tex, a["point_transform_old_latex"],
                                                 strict=True))),
               ("the determinant of the Jacobian J = ∂q/∂q′, nonzero where the map is "
                "invertible (notes (3.40))",
                rf"\det J = {a['point_transform_det_latex']}")]
        if len(str(a["point_transform_L_latex"])) <= cls.LONGEST_EQUATION:
            eqs.append(("L′(q′, q̇′) = L(q(q′), J q̇′)", f"L' = {a['point_transform_L_latex']}"))
        if len(str(a["point_transform_H_latex"])) <= cls.LONGEST_EQUATION:
            eqs.append(("the Legendre transform of L′", f"H' = {a['point_transform_H_latex']}"))
        eqs.append(("the velocities follow with the Jacobian, notes (3.41)–(3.42)",
                    r"\dot q = J\,\dot q',\qquad \frac{\partial\dot q}{\partial\dot q'} = "
                    r"\frac{\partial q}{\partial q'} = J"))
        for i, (q, r) in enumerate(zip(new_tex, a["point_transform_residual_latex"],
                                       strict=True)):
            eqs.append(("Euler–Lagrange expressions, E(L′) − JᵀE(L) simplified, "
                        "notes (3.47)" if i == 0 else "",
                        rf"E_{{{q}}}(L') - (J^{{T}}E(L))_{{{q}}} = {r}"))
        agree = bool(a["point_transform_agree"])
        tolerance = fmt_err(a["point_transform_tolerance"])
        difference = fmt_err(a["point_transform_q_difference"])
        facts = [("∂q̇/∂q̇′ = ∂q/∂q′, the Jacobian (notes (3.42))",
                  cls.SIMPLIFIED[bool(a["point_transform_velocity_identity"])]),
                 ("∂q̇/∂q′ through the second derivatives of q(q′) (notes (3.43))",
                  cls.SIMPLIFIED[bool(a["point_transform_second_identity"])]),
                 ("the Euler–Lagrange expressions transform with the Jacobian, "
                  "E(L′) = JᵀE(L) (notes (3.47))",
                  "yes: every component of the difference simplifies to 0"
                  if a["point_transform_covariant"] else
                  "not shown by SymPy's simplification"),
                 (f"the same orbit from L′ in ({new_words}), carried back",
                  f"yes: {difference} of the coordinates' size at most over the whole run "
                  f"(agreement below {tolerance})"
                  if agree else
                  f"no: the runs differ by {difference} of the coordinates' size, more than "
                  f"{tolerance}")]
        initial = ", ".join(f"{symbol_text(str(q))} = {fmt(float(v))}" for q, v in zip(
            a["point_transform_coordinates"], a["point_transform_initial"], strict=False))
        table = Table(
            caption="The run of L′, integrated with the main run's method and tolerances from "
                    "the transformed initial state, against the main run: its coordinates "
                    "carried back by q(q′), its momenta against p′ = Jᵀp (momenta transform "
                    "with the transposed Jacobian), each relative to the largest value of the "
                    "run. |det J| is measured against the product of the lengths of J's "
                    f"columns (1 for orthogonal columns); below "
                    f"{fmt_err(a['point_transform_singular_threshold'])} J is called "
                    "singular.",
            header=["quantity", "value"],
            rows=[["new initial coordinates (Newton's method on q(q′) = q(0))", initial],
                  ["relative |det J| at t = 0", fmt(a["point_transform_det0"], 4)],
                  ["smallest relative |det J| along the run",
                   fmt(a["point_transform_det_min"], 4)],
                  ["max |q(q′) − q| / max |q|", fmt_err(a["point_transform_q_difference"])],
                  ["max |q| of the main run", fmt(a["point_transform_q_scale"], 4)],
                  ["max |p′ − Jᵀp| / max |p′|", fmt_err(a["point_transform_p_difference"])],
                  ["agreement threshold (10⁴ × the larger of the relative tolerance and the "
                   "energy drift)", tolerance],
                  ["samples compared", str(int(a["point_transform_samples"]))],
                  ["right-hand-side evaluations of the run of L′",
                   str(int(a["point_transform_nfev"]))]])
        return SectionContent(equations=eqs, facts=facts, tables=[table])
