r"""``oscillator``: the harmonic oscillator three ways (lecture notes §4, §6, §7).

Hamilton's equations integrated and compared with the closed form; the swap
canonical transformation F1 = q Q (6.6–6.11) applied to the trajectory and
checked against integrating the transformed Hamiltonian; the Hamilton–Jacobi
solution (7.33–7.38) compared with the integration.  A deliberately short
report: no phase-portrait family, no period study, nothing it does not need.
"""

from __future__ import annotations

import math

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import AuditCase, Check, Results
from .base import Scene, SceneConfig, Section, SectionContent, fmt, fmt_err

common_plots = lazy_module("reportgen.plots.common")
plots = lazy_module("reportgen.plots.oscillator")
core = lazy_module("reportgen.core.models.oscillator")


class Params(Strict):
    m: Positive = Field(description="mass [kg]")
    omega: Positive = Field(description="angular frequency ω [rad/s]")


class Initial(Strict):
    q: Real = Field(description="initial coordinate [m]")
    p: Real = Field(description="initial momentum [kg·m/s]")


class OscillatorConfig(SceneConfig):
    params: Params
    initial: Initial
    run: RunConfig

    @model_validator(mode="after")
    def _not_at_rest(self):
        if self.initial.q == 0.0 and self.initial.p == 0.0:
            raise ValueError("initial.q / initial.p: both zero, the oscillator rests at E = 0 "
                             "and the Hamilton–Jacobi constants are undefined")
        return self


class OscillatorScene(Scene):
    kind = "oscillator"
    order = 20
    summary = "harmonic oscillator H = p²/2m + m ω² q²/2: Hamilton, canonical swap, Hamilton–Jacobi"
    Config = OscillatorConfig
    presets = {
        "unit": {"params": {"m": 1.0, "omega": 1.0}, "initial": {"q": 1.0, "p": 0.0},
                 "run": {"t_end": 20.0}},
    }
    sections = (
        Section("hamilton", "Hamilton's equations against the closed form", integrates=True),
        Section("canonical_swap", "The swap transformation F = q Q", integrates=True),
        Section("hamilton_jacobi", "Hamilton–Jacobi solution", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def audit_cases(cls):
        def case(name, m, omega, t_end, what, samples=2001):
            return AuditCase(name=name, what=what, methods=("dop853", "yoshida8", "gauss6"),
                             config={"kind": "oscillator", "title": name,
                                     "params": {"m": m, "omega": omega},
                                     "initial": {"q": 1.0, "p": 0.0},
                                     "run": {"t_end": t_end, "samples": samples}})

        return [
            case("oscillator, 10⁴ periods at ω = 10⁴", 1.0, 1e4, 2 * math.pi,
                 "fast oscillation sampled far below its period; long run", samples=20001),
            case("oscillator with m = 1e-20 kg", 1e-20, 1.0, 50.0,
                 "momentum scale 1e-20: absolute tolerances must not swamp it"),
        ]

    def closed_form(self, t):
        """q(t), p(t) in closed form (simulate side)."""
        p, ini = self.config.params, self.config.initial
        return core.exact_solution(t, ini.q, ini.p, p.m, p.omega)

    def models(self) -> list:
        """The Hamilton model of H and the model of K(Q, P) = H(−P, Q) (the swapped run)."""
        prm = self.config.params
        return [core.hamilton_model(prm.m, prm.omega), core.swapped_model(prm.m, prm.omega)]

    def simulate(self, progress=None) -> Results:
        prm, ini, run = self.config.params, self.config.initial, self.config.run
        t = np.linspace(0.0, run.t_end, run.samples)
        n_periods = run.t_end * prm.omega / (2 * math.pi)
        y0 = np.array([ini.q, ini.p])
        e0 = float(core.energy(ini.q, ini.p, prm.m, prm.omega))

        def invariants(_t, y):
            return {"energy": core.energy(y[:, 0], y[:, 1], prm.m, prm.omega)}

        def swapped_invariants(_t, y):  # K(Q, P) = H(q, p)
            return {"energy": core.energy(-y[:, 1], y[:, 0], prm.m, prm.omega)}

        results = Results()
        model, swapped_model = self.models()
        main = self.integrate(model, y0, t, invariants=invariants, progress=progress,
                              n_periods=n_periods, invariant_scales={"energy": e0})
        results.runs["main"] = main
        q_ex, p_ex = self.closed_form(t)
        main.reference = {"q": q_ex, "p": p_ex}
        main.attrs["reference_label"] = "closed form"
        Q0, P0 = core.swap(ini.q, ini.p)
        swapped = self.integrate(swapped_model, np.array([Q0, P0]), t,
                                 invariants=swapped_invariants, n_periods=n_periods,
                                 invariant_scales={"energy": e0})
        results.runs["swapped"] = swapped

        # the image (Q, P) = (p, −q) of the integrated H orbit: what integrating K must give
        Q, P = core.swap(main["q"], main["p"])
        swapped.reference = {"Q": Q, "P": P}
        swapped.attrs["reference_label"] = "(p, −q) of the integrated H orbit"
        e, beta = core.hamilton_jacobi_constants(main["q"], main["p"], t, prm.m, prm.omega)
        q_hj, p_hj = core.hamilton_jacobi_solution(t, e[0], beta[0], prm.m, prm.omega)
        results.analysis.update({
            "omega": prm.omega,
            "period": 2 * math.pi / prm.omega,
            "energy": e0,
            "q_max_error": float(np.max(np.abs(main["q"] - q_ex))),
            "p_max_error": float(np.max(np.abs(main["p"] - p_ex))),
            "swap_max_difference": float(max(np.max(np.abs(swapped["Q"] - Q)),
                                             np.max(np.abs(swapped["P"] - P)))),
            "hj_energy": float(e[0]),
            "hj_beta": float(beta[0]),
            "hj_beta_drift": float(np.max(np.abs(beta - beta[0]))),
            "hj_q_max_difference": float(np.max(np.abs(main["q"] - q_hj))),
            "poisson_bracket_QP": 1.0,  # {Q, P}_(q,p) = ∂Q/∂q ∂P/∂p − ∂Q/∂p ∂P/∂q = 0 − (1)(−1)
            # along the integrated trajectory, on the main run's grid: the new canonical pair
            # (E, β) and q(t) of the Hamilton–Jacobi solution (7.38) from their initial values
            "hamilton_jacobi": {"energy": e, "beta": beta, "q": q_hj},
        })
        # errors relative to the amplitudes: q or p itself passes through zero
        q_amp, p_amp = math.sqrt(2 * e0 / (prm.m * prm.omega**2)), math.sqrt(2 * prm.m * e0)
        results.checks.append(Check("q(t_end)", float(main["q"][-1]), float(q_ex[-1]), "m",
                                    "closed form q0 cos ωt + p0/(mω) sin ωt", scale=q_amp))
        results.checks.append(Check("p(t_end)", float(main["p"][-1]), float(p_ex[-1]), "kg·m/s",
                                    "closed form p0 cos ωt − mωq0 sin ωt", scale=p_amp))
        results.checks.append(Check("Q(t_end) from integrating K", float(swapped["Q"][-1]),
                                    float(Q[-1]), "kg·m/s", "Q = p of the integrated H (6.9)",
                                    scale=p_amp))
        results.checks.append(Check("q(t_end) Hamilton–Jacobi", float(q_hj[-1]),
                                    float(main["q"][-1]), "m", "integration of H (7.38)",
                                    scale=q_amp))
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201),
                   reference=lambda ts: np.column_stack(self.closed_form(ts)))
        return results

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
            run.t, {"|q − q_exact| [m]": run["q"] - q_ex, "|p − p_exact| [kg·m/s]": run["p"] - p_ex},
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
            facts=[("generating function", "F1(q, Q) = q Q  ⇒  p = ∂F1/∂q = Q,  P = −∂F1/∂Q = −q"),
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
            figures=[cls.figure("hj", fig, "Top: q(t) = √(2E/mω²) sin ω(t + β) from the complete "
                                "integral S = W(q, E) − E t against the integration. Bottom: the "
                                "new canonical pair (E, β) evaluated along the integrated "
                                "trajectory stays constant.")],
            facts=[("E", f"{fmt(a['hj_energy'], 14)} J"), ("β = ∂S/∂E", f"{fmt(a['hj_beta'], 14)} s"),
                   ("max |β(t) − β(0)| along the integration", fmt_err(a["hj_beta_drift"]) + " s"),
                   ("max |q_HJ − q_integrated|", fmt_err(a["hj_q_max_difference"]) + " m")])
