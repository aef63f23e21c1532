r"""The report of a first-order Lagrangian L = a(q, t)·q̇ − V(q, t) (notes (3.36–3.38)).

Its "first_order" section takes the place of the equations section: L split as a·q̇ − V,
the matrix ω, the reduced equations q̇ = ω⁻¹(∇V + ∂a/∂t), the bracket of the reduced phase
space, and the checks of the run (det ω, Lagrange's equations, V, a closed form).  The
coordinates are the whole state: n coordinates are n/2 degrees of freedom.

:class:`FirstOrderReport` comes before :class:`HamiltonianReport` in the scene's bases and
hands every other archive on to it.
"""

from __future__ import annotations

import numpy as np

from ...scene.base import Section
from ...scene.content import SectionContent, fmt, fmt_err
from .report import HamiltonianReport
from .symbols import symbol_text


def _is_first_order(data) -> bool:
    return data.sweep is None and bool(data.analysis.get("first_order", False))


def closed_form_error_figure(t, error, labels: list[str]):
    """|q − exp(tA) q(0)| of each coordinate against time, on a log scale (exact zeros,
    at t = 0, left out)."""
    from ...rendering.plots.common import time_label
    from ...rendering.plots.style import PALETTE, new_figure, place_legend
    from .plots import UNITS

    fig, ax = new_figure()
    for values, label, colour in zip(error.T, labels, PALETTE, strict=False):
        keep = values > 0
        ax.semilogy(t[keep], values[keep], color=colour, label=label, linewidth=1.0)
    ax.set_xlabel(time_label(UNITS))
    ax.set_ylabel(f"difference [{UNITS}]")
    place_legend(ax)
    return fig


class FirstOrderReport:
    """Sections of a first-order L; every other archive is the parent's."""

    sections = (*HamiltonianReport.sections[:1],
                Section("first_order", "A first-order Lagrangian: the reduced equations",
                        integrates=True),
                *HamiltonianReport.sections[1:])

    #: the sections of a first-order L, in order (the others need momenta)
    FIRST_ORDER_SECTIONS = ("first_order", "trajectory", "invariants", "error_vs_runtime")

    @classmethod
    def default_sections(cls, data):
        if not _is_first_order(data):
            return [n for n in super().default_sections(data) if n != "first_order"]
        return list(cls.FIRST_ORDER_SECTIONS)

    @classmethod
    def prose_case(cls, data):
        """The parent's, and whether the L is first order (the summary's words)."""
        return {**super().prose_case(data), "first_order": _is_first_order(data)}

    @classmethod
    def symbols(cls, data) -> dict[str, str]:
        """The coordinates' symbols: the whole state of a first-order L."""
        if not _is_first_order(data):
            return super().symbols(data)
        a = data.analysis
        return {n: f"${t}$" for n, t in zip(a["coordinates"], a["latex"]["q"], strict=True)}

    @classmethod
    def symbols_of_columns(cls, data) -> list[str]:
        if not _is_first_order(data):
            return super().symbols_of_columns(data)
        return cls.coordinates(data)

    @classmethod
    def _freedom(cls, data) -> str:
        n = len(cls.coordinates(data))
        dof = n // 2
        return (f"{n} coordinates, the whole state: {dof} degree{'s' if dof > 1 else ''} of "
                "freedom")

    @classmethod
    def describe(cls, data):
        if not _is_first_order(data):
            return super().describe(data)
        a = data.analysis
        coords = ", ".join(symbol_text(str(q)) for q in a["coordinates"])
        text = f"First-order Lagrangian in ({coords}), {cls._freedom(data)}"
        if not a.get("time_dependent", False):
            text += f", at V = {fmt(float(a['H0']), 4)}"
        return text

    @classmethod
    def headline(cls, data):
        if not _is_first_order(data):
            return super().headline(data)
        a, run = data.analysis, data.runs.get("main")
        facts = [("system", f"L linear in the velocities, in "
                            f"{', '.join(map(symbol_text, cls.coordinates(data)))} "
                            f"({cls._freedom(data)})"),
                 ("energy V(0)", fmt(a["H0"]))]
        if run is not None and "drift_H" in run.attrs:
            facts.append(("drift of V, relative to its scale", fmt_err(run.attrs["drift_H"])))
        return facts

    @classmethod
    def name_tex(cls, data, name: str) -> str:
        """The energy function of a first-order L is V (stored as the invariant H)."""
        if str(name) == "H" and _is_first_order(data):
            return "V"
        return super().name_tex(data, name)

    @classmethod
    def section_first_order(cls, data):
        a = data.analysis
        tex = a["first_order_latex"]
        q = list(a["latex"]["q"])
        eqs = [("Lagrangian", f"L = {a['latex']['L']}")]
        eqs += [("a = ∂L/∂q̇" if i == 0 else "", f"a_{{{qi}}} = {ai}")
                for i, (qi, ai) in enumerate(zip(q, tex["a"], strict=True))]
        eqs.append(("V = a·q̇ − L, the energy function", f"V = {tex['V']}"))
        names = cls.coordinates(data)
        omega = [str(r).split(" & ") for r in tex["omega"]]
        inverse = [str(r).split(" & ") for r in tex["inverse"]]
        pairs = [(i, j) for i in range(len(q)) for j in range(i + 1, len(q))]
        # mathtext has no matrices: ω and ω⁻¹ are antisymmetric, their entries above the
        # diagonal say everything
        eqs += [("ωᵢⱼ = ∂aⱼ/∂qᵢ − ∂aᵢ/∂qⱼ (antisymmetric: ωⱼᵢ = −ωᵢⱼ, ωᵢᵢ = 0)"
                 if k == 0 else "", rf"\omega_{{{q[i]}{q[j]}}} = {omega[i][j]}")
                for k, (i, j) in enumerate(pairs)]
        eqs.append(("", rf"\det\omega = {tex['det']}"))
        eqs += [("reduced equations q̇ = ω⁻¹(∇V + ∂a/∂t)" if i == 0 else "",
                 rf"\dot{{{qi}}} = {e}") for i, (qi, e) in enumerate(zip(q, tex["qdot"],
                                                                            strict=True))]
        eqs += [("brackets of the reduced phase space {qᵢ, qⱼ} = (ω⁻¹)ᵢⱼ" if k == 0 else "",
                 rf"\{{{q[i]}, {q[j]}\}} = {inverse[i][j]}") for k, (i, j) in enumerate(pairs)]
        facts = [
            ("det ω at the initial point; smallest |det ω| along the run",
             f"{fmt(a['first_order_det0'])}; {fmt(a['first_order_det_min'])} ("
             + ("sign kept: ω invertible on the whole run)" if a["first_order_det_sign_kept"]
                else "the sign changes: ω is singular on the run)")),
            ("largest Lagrange expression d/dt ∂L/∂q̇ − ∂L/∂q at the velocities of the "
             "compiled reduced equations",
             f"{fmt_err(a['first_order_el_residual'])} (its terms ≤ "
             f"{fmt(a['first_order_el_scale'], 4)})"),
            ("{qᵢ, V} = q̇ᵢ for every coordinate (SymPy)",
             "yes: the reduced bracket generates the motion, ḟ = {f, V}"
             if a["first_order_bracket_generates"] else
             "no (L depends on t)" if a["time_dependent"] else "no"),
            ("dV/dt = ∇V·q̇ + ∂V/∂t simplifies to 0",
             "yes: V is conserved (ω antisymmetric)" if a["first_order_energy_rate_zero"]
             else "no: V changes along the run")]
        facts[:0] = cls.no_transform_facts(a)  # first: why L is reduced, not transformed
        run = data.runs["main"]
        if "drift_H" in run.attrs:
            facts.append(("largest drift of V along the run, relative to its scale",
                          fmt_err(run.attrs["drift_H"])))
        figures, notes = [], cls.no_transform_words(a)
        if a["first_order_linear"]:
            A = np.asarray(a["first_order_A"], dtype=float)
            facts.append(("linear reduced equations q̇ = A q: closed form q(t) = exp(tA) q(0); "
                          "the rows of A (" + ", ".join(map(symbol_text, names)) + ")",
                          "; ".join("(" + ", ".join(fmt(x) for x in row) + ")" for row in A)))
            facts.append(("largest |q − exp(tA) q(0)| along the run",
                          f"{fmt_err(a['first_order_closed_form_error'])} (|q| ≤ "
                          f"{fmt(a['first_order_closed_form_scale'], 4)})"))
            eig = np.linalg.eigvals(A)
            if np.all(np.abs(eig.real) <= 1e-12 * max(np.max(np.abs(eig)), 1e-300)):
                omegas = np.unique(np.round(np.abs(eig.imag[np.abs(eig.imag) > 0]), 12))
                if len(omegas):
                    facts.append(("angular frequencies of the closed form (A has eigenvalues "
                                  "±iΩ)", ", ".join(f"Ω = {fmt(w)}" for w in omegas)))
            error = np.abs(run.y - np.asarray(a["first_order_closed_form"], dtype=float))
            symbol = cls.symbols(data)
            figures.append(cls.figure(
                "first_order_closed_form",
                closed_form_error_figure(run.t, error, [symbol[n] for n in
                                                        cls.coordinates(data)]),
                "Difference of each integrated coordinate from the closed form "
                "exp(tA) q(0) of the linear reduced equations, against time."))
        else:
            notes.append("The reduced equations are not linear with constant coefficients: "
                         "no closed form is compared.")
        return SectionContent(equations=eqs, facts=facts, figures=figures, notes=notes)

    @staticmethod
    def no_transform_facts(a) -> list[tuple[str, str]]:
        """∂²L/∂q̇ᵢ∂q̇ⱼ (its rank, its largest entry at the initial point) and the momenta
        at the initial point over the sampled velocities."""
        if "first_order_velocity_hessian_rank" not in a:
            return []
        hessian = np.asarray(a["first_order_velocity_hessian"], dtype=float)
        return [
            ("rank of ∂²L/∂q̇ᵢ∂q̇ⱼ (SymPy); its largest |entry| at the initial point",
             f"{int(a['first_order_velocity_hessian_rank'])}; "
             f"{fmt(float(np.max(np.abs(hessian))))}"),
            (f"p = ∂L/∂q̇ at the initial point for {int(a['first_order_velocity_samples'])} "
             "velocities drawn at random from [−v, v], v = "
             f"{fmt(float(a['first_order_velocity_range']))}: largest spread of a momentum",
             f"{fmt_err(a['first_order_momentum_spread'])} (|p| ≤ "
             f"{fmt(a['first_order_momentum_scale'], 4)})")]

    @staticmethod
    def no_transform_words(a) -> list[str]:
        """Why the Legendre transform fails, as for the linear function of notes
        (4.13)–(4.14): said only when the stored facts show it (rank 0, no velocity in the
        momenta; their spread over the sampled velocities is quoted)."""
        if "first_order_velocity_hessian_rank" not in a:
            return []
        spread = float(a["first_order_momentum_spread"])
        if (int(a["first_order_velocity_hessian_rank"]) != 0
                or bool(a["first_order_momenta_contain_velocities"])):
            return []
        return [f"∂²L/∂q̇ᵢ∂q̇ⱼ has rank 0 and p = ∂L/∂q̇ = a(q, t) contains no velocity: at "
                f"the initial point the {int(a['first_order_velocity_samples'])} sampled "
                f"velocities all give the same momenta (spread {fmt_err(spread)}). This is the "
                "linear function of notes (4.13)–(4.14), whose derivatives y = ∂f/∂x = C are "
                "constants: q̇ cannot be solved for p, so the Legendre transform fails, and "
                "the reduction above takes its place."]

    @classmethod
    def section_invariants(cls, data):
        if not _is_first_order(data):
            return super().section_invariants(data)
        content = cls.invariants_section(
            data, labels={n: f"${cls.name_tex(data, n)}$" for n in data.runs["main"].invariants},
            time_unit=cls.UNITS,
            caption="Drift of the energy function V = a·q̇ − L and of every observable whose "
                    "rate ∇f·q̇ + ∂f/∂t simplifies to zero, each relative to its scale.")
        content.tables = []  # the kind's template typesets it (symbol_tables: its names)
        cls.relabel_drift(content)
        moving = data.analysis.get("observables")
        if moving:
            from . import plots

            content.figures.append(cls.figure(
                "observables", plots.observables(
                    data.runs["main"].t,
                    {f"${cls.name_tex(data, f)}$": v for f, v in moving.items()}),
                "Observables that are not conserved, against time."))
        return content
