"""``oscillator`` report: the run against the closed form, the swap transformation
F1 = q Q and the Hamilton–Jacobi solution.  A deliberately short report: no
phase-portrait family, no period study, nothing it does not need."""

from __future__ import annotations

import math

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from ...scene.report import Report
from .results import SCHEMA

common_plots = lazy_module("reportgen.rendering.plots.common")
plots = lazy_module("reportgen.kinds.oscillator.plots")


class OscillatorReport(Report):
    """The oscillator's sections, drawn from the archive alone."""

    schema = SCHEMA
    gallery_figures = ("swap", "qp")

    @classmethod
    def gallery_headline(cls, data):
        from ...scene import gallery
        motion = gallery.worst_check(data, "q(t_end)", "p(t_end)")
        others = gallery.worst_check(data, "Q(t_end)", "Hamilton–Jacobi")
        if motion is None:
            return super().gallery_headline(data)
        text = f"q(t), p(t) {gallery.from_reference(motion.rel_error, 'the closed form')}"
        return text + (f"; the canonical swap and Hamilton–Jacobi agree to "
                       f"{gallery.distance(others.rel_error)}" if others is not None else "")

    sections = (
        Section("hamilton", "Hamilton's equations against the closed form", integrates=True),
        Section("canonical_swap", "The swap transformation F = q Q", integrates=True),
        Section("hamilton_jacobi", "Hamilton–Jacobi solution", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def prose_case(cls, data):
        """The stored facts the prose follows: whether the swap is canonical
        (``swap_canonical``, within ``canonical_threshold``) and what the study measured
        against (its ``reference_kind``)."""
        if data.sweep is not None:
            return {}
        return {"canonical": data.analysis["swap_canonical"] == "yes",
                "canonical_threshold": fmt(float(data.analysis["canonical_threshold"])),
                "study_reference": str(data.study_attrs.get("reference_kind", ""))}

    @classmethod
    def describe(cls, data):
        """``An oscillator with ω = 1.5 rad/s (period 4.189 s) at E = 2.312 J: amplitude
        1.434 m``, from the archived analysis."""
        if data.sweep is not None:
            return super().describe(data)
        a, m = data.analysis, float(data.config.params.m)
        omega, energy = float(a["omega"]), float(a["energy"])
        amplitude = (2.0 * energy / (m * omega ** 2)) ** 0.5
        return (f"An oscillator with ω = {fmt(omega, 4)} rad/s (period "
                f"{fmt(float(a['period']), 4)} s) at E = {fmt(energy, 4)} J: amplitude "
                f"{fmt(amplitude, 4)} m")

    @classmethod
    def headline(cls, data):
        p, ini = data.config.params, data.config.initial
        a = data.analysis
        return [
            ("parameters", f"m = {fmt(p.m)} kg, ω = {fmt(p.omega)} rad/s "
                           f"(period {fmt(a['period'])} s)"),
            ("initial state", f"q0 = {fmt(ini.q)} m, p0 = {fmt(ini.p)} kg·m/s, "
                              f"E = {fmt(a['energy'])} J"),
            ("max |q − closed form|", f"{fmt_err(a['q_max_error'])} m"),
        ]

    @classmethod
    def section_hamilton(cls, data):
        run = data.runs["main"]
        q_ex, p_ex = run.reference["q"], run.reference["p"]
        fig = common_plots.timeseries_against_reference(
            run.t, {"q": run["q"], "p": run["p"]}, {"q": q_ex, "p": p_ex},
            ylabels={"q": "q [m]", "p": "p [kg·m/s]"},
            reference_label=run.attrs["reference_label"])
        err = common_plots.error_against_time(
            run.t, {"|q − closed form| [m]": run["q"] - q_ex,
                    "|p − closed form| [kg·m/s]": run["p"] - p_ex},
            ylabel="absolute error")
        return SectionContent(
            figures=[cls.figure("qp", fig, "q̇ = ∂H/∂p = p/m, ṗ = −∂H/∂q = −mω²q integrated, "
                                "against the closed form."),
                     cls.figure("error", err, "Error against the closed form.")],
            facts=[("energy drift", fmt_err(run.attrs.get("drift_energy", math.nan)) +
                    " (relative)")])

    @classmethod
    def section_canonical_swap(cls, data):
        run, swapped = data.runs["main"], data.runs["swapped"]
        Q, P = swapped.reference["Q"], swapped.reference["P"]
        fig = plots.swap_phase_planes(run["q"], run["p"], swapped["Q"], swapped["P"], Q, P)
        a = data.analysis
        return SectionContent(
            figures=[cls.figure("swap", fig, "Left: the orbit in (q, p). Right: K(Q, P) = "
                                "Q²/2m + mω²P²/2 integrated from (Q₀, P₀) = (p₀, −q₀), over the "
                                "image Q = p, P = −q of the left orbit.")],
            facts=[("generating function",
                    "F1(q, Q) = q Q  ⇒  p = ∂F1/∂q = Q,  P = −∂F1/∂Q = −q"),
                   ("new Hamiltonian", "K(Q, P) = H(−P, Q) = Q²/2m + m ω² P²/2"),
                   ("Poisson bracket {Q, P} from F1 by SymPy",
                    f"{fmt(a['poisson_bracket_QP'])} ("
                    + ("canonical" if a["swap_canonical"] == "yes" else "not canonical")
                    + f": |{{Q, P}} − 1| {'<' if a['swap_canonical'] == 'yes' else '≥'} "
                      f"{fmt(float(a['canonical_threshold']))} along the orbit too)"),
                   ("max |{Q, P} − 1| along the orbit, by central differences",
                    fmt_err(a["poisson_bracket_QP_defect"])),
                   ("max distance of the integrated (Q, P) from (p, −q)",
                    fmt_err(a["swap_max_difference"]))])

    @classmethod
    def section_hamilton_jacobi(cls, data):
        run = data.runs["main"]
        a = data.analysis
        hj = a["hamilton_jacobi"]
        fig = plots.hamilton_jacobi(run.t, run["q"], hj["q"], hj["energy"], hj["beta"])
        return SectionContent(
            tables=[cls.residual_table(a)],
            figures=[cls.figure("hj", fig, "Top: q(t) = √(2E/mω²) sin ω(t + β) from the "
                                "complete integral S = W(q, E) − E t against the integration. "
                                "Bottom: the new canonical pair (E, β) evaluated along the "
                                "integrated trajectory " + cls.constancy_words(a))],
            facts=[("E", f"{fmt(a['hj_energy'])} J"),
                   ("β = ∂S/∂E", f"{fmt(a['hj_beta'])} s"),
                   ("max |β(t) − β(0)| along the integration",
                    fmt_err(a["hj_beta_drift"]) + " s"),
                   ("max difference of q, Hamilton–Jacobi against the integration",
                    fmt_err(a["hj_q_max_difference"]) + " m")])

    @staticmethod
    def constancy_words(a) -> str:
        """Whether (E, β) stayed constant along the run, by the stored ``hj_pair_constant``
        and its threshold, with the drifts measured."""
        drifts = (f"E by {fmt_err(a['hj_energy_drift'])} of itself, β by "
                  f"{fmt_err(a['hj_beta_drift'] / a['period'])} of the period")
        if a["hj_pair_constant"] == "yes":
            return (f"stays constant: it drifts by less than "
                    f"{fmt(float(a['hj_constant_threshold']))} ({drifts}).")
        return (f"drifts by more than {fmt(float(a['hj_constant_threshold']))} ({drifts}): "
                "the integration's error, as the true motion keeps both constant.")

    @staticmethod
    def residual_table(a) -> Table:
        """The Hamilton–Jacobi equations along the run, ∂W/∂q from the integrand and from
        W by quadrature; W and ∫ p dq by quadrature against their closed forms; p against
        ∂W/∂q."""
        rows = [
            ["∂S/∂t + H(q, ∂S/∂q) = 0, notes (7.16)", fmt_err(a["hj_residual"]),
             fmt_err(a["hj_residual_quadrature"])],
            ["H(q, ∂W/∂q) = E, notes (7.32)–(7.33)", fmt_err(a["hj_residual"]),
             fmt_err(a["hj_characteristic_residual_quadrature"])],
            ["W by quadrature against its closed form, relative to πE/ω", "—",
             fmt_err(a["hj_characteristic_quadrature_error"])],
            ["∫ p dq between the turning points against πE/ω (Goldstein §10.6)", "—",
             fmt_err(abs(a["hj_half_action"] * a["omega"] / (math.pi * a["energy"]) - 1))],
            ["integrated p against ±∂W/∂q, relative to √(2mE)",
             fmt_err(a["hj_momentum_difference"]), "—"],
        ]
        return Table(caption="Largest relative residual or difference along the run. "
                             "Middle column: ∂W/∂q the integrand √(2m(E − mω²q²/2)) and "
                             "∂S/∂t = −E; right: W by Gauss–Legendre quadrature, ∂W/∂q and "
                             "∂S/∂t by central differences",
                     header=["equation or comparison", "∂W/∂q from the integrand",
                             "W by quadrature"], rows=rows)
