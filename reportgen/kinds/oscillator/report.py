"""``oscillator`` report: the run against the closed form, the swap transformation
F1 = q Q and the Hamilton–Jacobi solution.  A deliberately short report: no
phase-portrait family, no period study, nothing it does not need."""

from __future__ import annotations

import math

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, fmt, fmt_err
from ...scene.report import Report
from .results import SCHEMA

common_plots = lazy_module("reportgen.rendering.plots.common")
plots = lazy_module("reportgen.kinds.oscillator.plots")


class OscillatorReport(Report):
    """The oscillator's sections, drawn from the archive alone."""

    schema = SCHEMA
    sections = (
        Section("hamilton", "Hamilton's equations against the closed form", integrates=True),
        Section("canonical_swap", "The swap transformation F = q Q", integrates=True),
        Section("hamilton_jacobi", "Hamilton–Jacobi solution", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def headline(cls, data):
        p, ini = data.config.params, data.config.initial
        a = data.analysis
        return [
            ("parameters", f"m = {fmt(p.m)} kg, ω = {fmt(p.omega)} rad/s "
                           f"(period {fmt(a['period'])} s)"),
            ("initial state", f"q0 = {fmt(ini.q)} m, p0 = {fmt(ini.p)} kg·m/s, "
                              f"E = {fmt(a['energy'])} J"),
            ("max |q − q_exact|", f"{fmt_err(a['q_max_error'])} m"),
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
            run.t, {"|q − q_exact| [m]": run["q"] - q_ex,
                    "|p − p_exact| [kg·m/s]": run["p"] - p_ex},
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
                                "Q²/2m + mω²P²/2 integrated from (Q0, P0) = (p0, −q0), over the "
                                "image Q = p, P = −q of the left orbit.")],
            facts=[("generating function",
                    "F1(q, Q) = q Q  ⇒  p = ∂F1/∂q = Q,  P = −∂F1/∂Q = −q"),
                   ("new Hamiltonian", "K(Q, P) = H(−P, Q) = Q²/2m + m ω² P²/2"),
                   ("Poisson bracket {Q, P}", "1 (canonical)"),
                   ("max |(Q, P)_integrated − (p, −q)|", fmt_err(a["swap_max_difference"]))])

    @classmethod
    def section_hamilton_jacobi(cls, data):
        run = data.runs["main"]
        a = data.analysis
        hj = a["hamilton_jacobi"]
        fig = plots.hamilton_jacobi(run.t, run["q"], hj["q"], hj["energy"], hj["beta"])
        return SectionContent(
            figures=[cls.figure("hj", fig, "Top: q(t) = √(2E/mω²) sin ω(t + β) from the "
                                "complete integral S = W(q, E) − E t against the integration. "
                                "Bottom: the new canonical pair (E, β) evaluated along the "
                                "integrated trajectory stays constant.")],
            facts=[("E", f"{fmt(a['hj_energy'], 14)} J"),
                   ("β = ∂S/∂E", f"{fmt(a['hj_beta'], 14)} s"),
                   ("max |β(t) − β(0)| along the integration",
                    fmt_err(a["hj_beta_drift"]) + " s"),
                   ("max |q_HJ − q_integrated|", fmt_err(a["hj_q_max_difference"]) + " m")])
