"""``hamiltonian`` report, the sections on structure: the Poisson brackets and the Jacobi
identity, Noether charges of a declared symmetry, the total-derivative invariance of L, a
canonical transformation (finite or infinitesimal) and the Hamilton–Jacobi comparison."""

from __future__ import annotations

import numpy as np
from markupsafe import Markup

from ...lazy import lazy_module
from ...rendering.equations import equation_html
from ...scene.content import SectionContent, fmt, fmt_err
from .config import (
    JACOBI_ROUNDOFF,
    JACOBI_RTOL,
)
from .symbols import symbol_tex, symbol_text

common_plots = lazy_module("reportgen.rendering.plots.common")
plots = lazy_module("reportgen.kinds.hamiltonian.plots")


class CanonicalSections:
    """Mixed into :class:`.report.HamiltonianReport`."""

    @classmethod
    def section_brackets(cls, data):
        """The cyclic coordinates and the Jacobi identity on the run; the brackets' tables
        are typeset by the kind's template (:meth:`symbol_tables`)."""
        a = data.analysis
        cyclic = [symbol_text(str(c)) for c in a["cyclic"]]
        facts = []
        observables = [k[len("conserved_"):] for k in a if k.startswith("conserved_")]
        kept = [f for f in observables if a[f"conserved_{f}"]]
        moving = [f for f in observables if not a[f"conserved_{f}"]]
        if kept:  # typeset: A_xy has no spelling in text
            facts.append(("observables conserved ({f, H} + ∂f/∂t simplifies to 0)",
                          cls.names_html(data, kept)))
        if moving:
            facts.append(("observables not conserved ({f, H} + ∂f/∂t ≠ 0)",
                          cls.names_html(data, moving)))
        facts += [("cyclic coordinates (H does not contain them)", ", ".join(cyclic) + (
                      " (its conjugate momentum is conserved)" if len(cyclic) == 1 else
                      " (their conjugate momenta are conserved)") if cyclic else
                   "none: H depends on every coordinate"),
                  ("Jacobi identity {f,{g,h}} + {g,{h,f}} + {h,{f,g}}",
                   cls.jacobi_words(a))]
        if "brackets_leibniz" in a:
            said = {True: "holds", False: "not shown by SymPy's expansion"}
            facts.append(("the brackets' other properties, notes (4.38), expanded by SymPy "
                          "for cubics f, g, h in (q, p)",
                          "; ".join(f"{rule} {said[bool(a[key])]}" for rule, key in (
                              ("{qᵢ, pⱼ} = δᵢⱼ", "brackets_canonical"),
                              ("{f, g} = −{g, f}", "brackets_antisymmetric"),
                              ("{Cf, h} = C{f, h}", "brackets_homogeneous"),
                              ("{fg, h} = f{g, h} + {f, h}g", "brackets_leibniz")))))
        triple = a.get("jacobi_triple_latex")
        equations = [] if triple is None else [
            ("the Jacobi identity is checked for", r",\quad ".join(
                f"{n} = {t}" for n, t in zip("fgh", triple, strict=True)))]
        return SectionContent(facts=facts, equations=equations)

    @classmethod
    def names_html(cls, data, names: list[str]):
        """Names typeset, comma-separated (a symbol such as A_xy has no spelling in text)."""
        return Markup(", ").join(equation_html(cls.name_tex(data, f)) for f in names)

    @classmethod
    def jacobi_words(cls, a) -> str:
        """The Jacobi identity's verdict, relative to the size of its terms; "not tested"
        when every term is rounding (each below JACOBI_ROUNDOFF of its parts' size)."""
        terms = ", ".join(fmt_err(float(x)) for x in np.asarray(a.get("jacobi_terms", [])))
        if not bool(a.get("jacobi_tested", True)):
            return (f"not tested: every term is round-off (largest |values| {terms}, each below "
                    f"{fmt_err(JACOBI_ROUNDOFF)} of the size of its parts)")
        relative = float(a.get("jacobi_relative", a["jacobi_max"] / a["jacobi_scale"]))
        verdict = "holds" if relative <= JACOBI_RTOL else "FAILS"
        return (f"{verdict}: largest sum {fmt_err(a['jacobi_max'])} on {cls.JACOBI_SAMPLES} "
                f"samples of the run, {fmt_err(relative)} of the size of its terms (largest "
                f"|values| {terms}; passes below {fmt_err(JACOBI_RTOL)})")

    @classmethod
    def section_noether(cls, data):
        """The declared symmetry: δq, δL (zero or dF/dt), the charge derived from L and in
        phase space, its bracket with H, and its drift along the run."""
        a = data.analysis
        run = data.runs["main"]
        tex = a["latex"]
        eqs = []
        for i, (q, d) in enumerate(zip(tex["q"], a["noether_delta_latex"], strict=True)):
            eqs.append(("the declared generator, notes (3.9–3.16)" if i == 0 else "",
                        rf"\delta {q} = {d}"))
        has_F = str(a["noether_F_latex"]) != "0"
        eqs.append(("change of L, δL = Σ ∂L/∂q δq + ∂L/∂q̇ δq̇",
                    rf"\delta L = {a['noether_delta_L_latex']}"))
        if has_F:
            eqs.append(("δL = dF/dt with, notes (3.48–3.49)", f"F = {a['noether_F_latex']}"))
        eqs.append(("the charge", (r"Q_{\mathrm{N}} = \sum_i \frac{\partial L}"
                     r"{\partial \dot q_i}\,\delta q_i" + (" - F" if has_F else "")
                     + f" = {a['noether_charge_latex']}")))
        eqs.append(("in phase space", rf"Q_{{\mathrm{{N}}}} = {a['noether_charge_qp_latex']}"))
        verdict = ("zero: a symmetry, so the charge is conserved" if a["noether_symmetry"]
                   else "not zero: not a symmetry, the charge is not conserved")
        facts = [("δL − dF/dt, simplified" if has_F else "δL, simplified",
                  verdict),
                 ("{Q, H} + ∂Q/∂t, simplified (the bracket test of the observables)",
                  "zero: found conserved by the bracket too" if a["noether_bracket_zero"]
                  else "not zero")]
        facts.append(("charge at t = 0", fmt(a["noether_charge0"])))
        drift = run.attrs.get("drift_noether_charge")
        facts.append(("max |Q(t) − Q(0)| along the run, relative to the size of its parts "
                      f"({fmt(a['noether_scale'], 4)})",
                      fmt_err(a["noether_drift"]) + ("" if drift is None else
                                                     " (the invariants' drift, above)")))
        if not a["noether_symmetry"]:
            eqs.append(("δL − dF/dt" if has_F else "δL", str(a["noether_residual_latex"])))
        return SectionContent(equations=eqs, facts=facts)

    @classmethod
    def section_total_derivative(cls, data):
        """L' = L + dF/dt: the same Euler–Lagrange equations, shifted momenta and H
        (notes (3.48–3.49))."""
        a = data.analysis
        tex = a["latex"]
        eqs = [("F(q, t)", f"F = {a['total_derivative_F_latex']}"),
               ("L' = L + dF/dt", f"L' = {a['total_derivative_L_latex']}")]
        for i, (q, d) in enumerate(zip(tex["q"], a["total_derivative_difference_latex"],
                                       strict=True)):
            eqs.append(("Euler–Lagrange expressions, E(L') − E(L), simplified" if i == 0
                        else "", rf"E_{{{q}}}(L') - E_{{{q}}}(L) = {d}"))
        for i, (p, s) in enumerate(zip(tex["p"], a["total_derivative_shift_latex"],
                                       strict=True)):
            eqs.append(("momenta of L': shifted by ∂F/∂q" if i == 0 else "",
                        rf"{p}' - {p} = {s}"))
        if len(str(a["total_derivative_H_latex"])) <= cls.LONGEST_EQUATION:
            eqs.append(("the Legendre transform of L'", f"H' = {a['total_derivative_H_latex']}"))
        facts = [("same equations of motion",
                  "yes: every E(L') − E(L) simplifies to 0" if a["total_derivative_same_equations"]
                  else "no (SymPy did not simplify the difference to 0)"),
                 ("H'(q, p) = H(q, p − ∂F/∂q) − ∂F/∂t",
                  "yes, simplified by SymPy" if a["total_derivative_H_same"] else
                  "not shown by SymPy's simplification"),
                 ("max |H' − (H − ∂F/∂t)| along the run, at p' = p + ∂F/∂q",
                  f"{fmt_err(a['total_derivative_H_error'])} (|H − ∂F/∂t| ≤ "
                  f"{fmt(a['total_derivative_H_scale'], 4)})")]
        return SectionContent(equations=eqs, facts=facts)

    #: where each kind of transformation is defined: the notes treat F(q, Q) at (6.4)–(6.5)
    #: and F(p, Q) at (6.12)–(6.14); F(q, P) and F(p, P) only Goldstein's Table 9.1 has
    TRANSFORM_NOTES = {"F1": "notes (6.4)–(6.5)", "F2": "Goldstein §9.1, Table 9.1",
                       "F3": "notes (6.12)–(6.14)", "F4": "Goldstein §9.1, Table 9.1",
                       "G": "notes (6.16)–(6.18)"}

    @classmethod
    def section_transform(cls, data):
        a = data.analysis
        if str(a.get("transform_kind", "")) == "G":
            return cls.infinitesimal_content(data)
        tr = a["transform"]
        new = list(a["transform_new"])
        n = len(new) // 2
        run = data.runs.get("transformed")
        series = {new[i]: tr["Q"][:, i] for i in range(n)}
        series.update({new[n + i]: tr["P"][:, i] for i in range(n)})
        fig = plots.new_variables(data.runs["main"].t, series,
                                  run[new[0]] if run is not None else None, new[0])
        kind = str(a.get("transform_kind", "F1"))
        eqs = [(f"generating function of type {kind}, {cls.TRANSFORM_NOTES.get(kind, 'notes §6')}, "
                "and its relations" if i == 0 else "", line)
               for i, line in enumerate(a["transform_latex"])]
        if a["transform_K_latex"]:
            eqs.append(("K in the new variables", f"K = {a['transform_K_latex']}"))
        facts = [("max |MᵀJM − J| along the run (M = ∂(Q, P)/∂(q, p))",
                  fmt_err(a["transform_defect_max"])),
                 ("max |{Qᵢ, Pⱼ} − δᵢⱼ|, |{Qᵢ, Qⱼ}|, |{Pᵢ, Pⱼ}|",
                  fmt_err(a["transform_bracket_max"]))]
        if "transform_bracket_relative" in a:
            facts.append(("the same, relative to the size of each bracket's terms",
                          fmt_err(a["transform_bracket_relative"])))
        notes = []
        if float(a.get("transform_identity_defect", 1.0)) <= cls.IDENTITY_RTOL:
            defect = float(a["transform_identity_defect"])
            notes.append("(Q, P) = (q, p) along the whole run, " + (
                "exactly" if defect == 0.0 else f"to {fmt_err(defect)} of their size") +
                         ": this F is the identity transformation" + (
                             ", the generating function F = −Σ pᵢQᵢ of notes (6.15)."
                             if kind == "F3" else "."))
        if run is not None:
            facts.append(("max |(Q, P) from integrating K − (Q, P) of the H orbit|",
                          fmt_err(a["transform_run_difference"])))
            if "transform_K_other_sign_difference" in a:
                facts.append(("the same for H − ∂F/∂t, the other sign",
                              fmt_err(a["transform_K_other_sign_difference"])))
                notes.append(cls.sign_note(kind, float(a["transform_run_difference"]),
                                           float(a["transform_K_other_sign_difference"])))
        elif not a["transform_K_latex"]:
            facts.append(("K as a formula in (Q, P)", "not found: SymPy solves only relations "
                          "linear in the old variables; K = H + ∂F/∂t is evaluated along the "
                          "run instead"))
        else:
            facts.append(("K as a formula in (Q, P)", "found (above), but it still holds old "
                          "variables or other names: not integrated on its own"))
        caption = ("The new variables along the integrated orbit" +
                   (f"; dashed: {symbol_text(new[0])} from integrating K's own Hamilton "
                    "equations from (Q₀, P₀)." if run is not None else "."))
        figures = [cls.figure("new_variables", fig, caption)]
        if n == 2 and float(a.get("transform_identity_defect", 1.0)) > cls.IDENTITY_RTOL:
            names = (new[0], new[1])
            figures.append(cls.figure("new_orbit", plots.new_orbit(
                tr["Q"][:, 0], tr["Q"][:, 1], names,
                (run[new[0]], run[new[1]]) if run is not None else None),
                f"The orbit in the new coordinates, {symbol_text(new[1])} against "
                f"{symbol_text(new[0])}" + ("; dashed: from integrating K's own Hamilton "
                                            "equations." if run is not None else ".")))
        return SectionContent(figures=figures, equations=eqs, facts=facts, notes=notes)

    #: (Q, P) this close to (q, p), relative to their size, is the identity transformation
    IDENTITY_RTOL = 1e-12
    #: a sign of ∂F/∂t is shown wrong when integrating K with it leaves the H orbit's image
    #: by more than this many times the distance K = H + ∂F/∂t keeps from it
    SIGN_CONTRAST = 1e3

    @classmethod
    def sign_note(cls, kind: str, plus: float, minus: float) -> str:
        """Which sign of ∂F/∂t in K the two integrations show, in words chosen by their
        distances from the image of the H orbit (``plus``: K = H + ∂F/∂t)."""
        measured = (f"integrated from the same (Q₀, P₀), K = H + ∂F/∂t stays within "
                    f"{fmt_err(plus)} of the image of the H orbit and K = H − ∂F/∂t within "
                    f"{fmt_err(minus)}")
        if not minus > cls.SIGN_CONTRAST * plus:
            return (f"F depends on t, yet the sign of ∂F/∂t in K is not told apart here: "
                    f"{measured}.")
        text = f"F depends on t, and the sign of ∂F/∂t in K matters: {measured}."
        if kind == "F3":
            text += (" For a generating function F(p, Q) of type 3, notes (6.14) prints "
                     "K = H − ∂F/∂t: a misprint. The differential of the generating function "
                     "in notes (6.12) leaves out its term ∂F/∂t dt; kept, the coefficients of "
                     "dt give K = H + ∂F/∂t, as for a generating function of type 1 in notes "
                     "(6.5).")
        return text

    @classmethod
    def infinitesimal_content(cls, data):
        """An infinitesimal canonical transformation (notes (6.16–6.18)): its relations,
        its brackets against their closed form, and the change of H against ε{H, G}."""
        a = data.analysis
        tr = a["transform"]
        t = data.runs["main"].t
        eps = float(a["transform_epsilon"])
        fig = plots.change_of_energy(t, np.asarray(tr["dH"]), np.asarray(tr["first_order"]),
                                     np.asarray(tr["second_order"]))
        eqs = [("generator and relations, notes (6.16–6.17)" if i == 0 else "", line)
               for i, line in enumerate(a["transform_latex"])]
        HG = str(a["transform_HG_latex"])
        eqs.append(("first-order change of H, notes (6.18)",
                    r"\delta H = \epsilon\,\{H, G\} = "
                    + ("0" if HG == "0" else rf"\epsilon\,\left({HG}\right)")))
        symbolic = ("holds exactly in SymPy's algebra" if a["transform_bracket_symbolic"]
                    else "not shown by SymPy's expansion")
        facts = [("ε", fmt(eps)),
                 ("{zᵢ, zⱼ} = Jᵢⱼ + ε²{wᵢ, wⱼ}, w = (∂G/∂p, −∂G/∂q)",
                  f"{symbolic}; along the run the computed brackets agree with it to "
                  f"{fmt_err(a['transform_bracket_agreement'])} of the size of their terms"),
                 ("max |{zᵢ, zⱼ} − Jᵢⱼ| along the run (second order in ε)",
                  f"{fmt_err(a['transform_bracket_max'])} (closed form ε²|{{wᵢ, wⱼ}}|: "
                  f"{fmt_err(a['transform_bracket_closed_max'])})"),
                 ("max |H(Q, P) − H(q, p)|", fmt_err(a["transform_dH_max"])),
                 ("max |ε{H, G}|", fmt_err(a["transform_first_order_max"])),
                 ("max |ΔH − ε{H, G} − ε²wᵀ∇²H w/2| (third order in ε)",
                  f"{fmt_err(a['transform_second_order_residual'])} (|H| ≤ "
                  f"{fmt(a['transform_H_scale'], 4)})")]
        caption = ("Above: the change of H under the transformation at each point of the run "
                   "and its first-order part ε{H, G}"
                   + (", zero: G generates a symmetry" if a["transform_first_order_max"] == 0
                      else "") + ". Below: what is left, against the second-order term "
                   "ε²wᵀ∇²H w/2 (dashed).")
        return SectionContent(figures=[cls.figure("change_of_energy", fig, caption)],
                              equations=eqs, facts=facts)

    @classmethod
    def section_hamilton_jacobi(cls, data):
        a = data.analysis
        hj = a["hamilton_jacobi"]
        run = data.runs["main"]
        fig = common_plots.error_against_time(
            run.t, {f"$|{symbol_tex(c)}^{{\\mathrm{{HJ}}}} - {symbol_tex(c)}|$": d
                    for c, d in hj["difference"].items()},
            time_unit=cls.UNITS, ylabel="quadrature − integration", unit=cls.UNITS)
        which = ("Kepler's equation for t(r) (∂W/∂E), the argument of latitude (∂W/∂L) and the "
                 "node (W differentiated by the z-component of L)"
                 if a["hj_separation"] == "central" else
                 "Charlier's quadratures, notes (7.60–7.61), in the fictitious time "
                 "dt = m a²(cosh²ξ − cos²η) dτ, "
                 "each coordinate through its turning points")
        return SectionContent(
            figures=[cls.figure("hj_difference", fig,
                                f"The quadrature solution ({which}) minus the integration.")],
            facts=[("max |quadrature − integration|", fmt_err(a["hj_max_difference"]))])
