"""``oscillator`` simulation: Hamilton's equations against the closed form, the swapped
Hamiltonian K(Q, P) = H(−P, Q) integrated, and the Hamilton–Jacobi constants along the
integrated trajectory."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.integration import IntegratingSimulation
from ...scene.results import AuditCase, Check, Results
from .config import OscillatorConfig
from .results import SCHEMA

core = lazy_module("reportgen.core.models.oscillator")
hamilton_jacobi = lazy_module("reportgen.core.hamilton_jacobi")

#: central-difference steps: of the swap's partial derivatives, relative to the orbit's
#: amplitudes (exact for a linear map but for rounding ~ ε/step); of ∂S/∂t, relative to the
#: run's length (S is linear in t: rounding ~ ε t/step alone, however many periods)
BRACKET_STEP = 1e-3
TIME_STEP = 1e-3
#: the words' thresholds (stored with the facts they decide): |{Q, P} − 1| below
#: CANONICAL_DEFECT is a canonical map; the drifts of E (relative to E) and of β (relative
#: to the period) along the run below CONSTANT_DRIFT: the pair "stays constant"
CANONICAL_DEFECT = 1e-9
CONSTANT_DRIFT = 1e-6
#: what the study measures its errors against (the closed form, every run)
STUDY_REFERENCE = "the closed form q₀ cos ωt + p₀/(mω) sin ωt, p₀ cos ωt − mωq₀ sin ωt"


class OscillatorSimulation(IntegratingSimulation):
    """H = p²/2m + m ω² q²/2 integrated, swapped (notes (6.6–6.11)) and solved by
    Hamilton–Jacobi (notes (7.33–7.38))."""

    schema = SCHEMA
    config: OscillatorConfig

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
        """q(t), p(t) in closed form."""
        p, ini = self.config.params, self.config.initial
        return core.exact_solution(t, ini.q, ini.p, p.m, p.omega)

    def models(self) -> list:
        """The Hamilton model of H and the model of K(Q, P) = H(−P, Q) (the swapped run)."""
        prm = self.config.params
        return [core.hamilton_model(prm.m, prm.omega), core.swapped_model(prm.m, prm.omega)]

    def stored_runs(self) -> int:
        """The main run and the swapped one."""
        return 2

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
            # along the integrated trajectory, on the main run's grid: the new canonical pair
            # (E, β) and q(t) of the Hamilton–Jacobi solution (7.38) from their initial values
            "hamilton_jacobi": {"energy": e, "beta": beta, "q": q_hj},
        })
        # errors relative to the amplitudes: q or p itself passes through zero
        q_amp, p_amp = math.sqrt(2 * e0 / (prm.m * prm.omega**2)), math.sqrt(2 * prm.m * e0)
        results.checks.append(Check("q(t_end)", float(main["q"][-1]), float(q_ex[-1]), "m",
                                    "closed form q0 cos ωt + p0/(mω) sin ωt", scale=q_amp))
        results.checks.append(Check("p(t_end)", float(main["p"][-1]), float(p_ex[-1]), "kg·m/s",
                                    "closed form p₀ cos ωt − mωq₀ sin ωt", scale=p_amp))
        results.checks.append(Check("Q(t_end) from integrating K", float(swapped["Q"][-1]),
                                    float(Q[-1]), "kg·m/s", "Q = p, notes (6.7), of the integrated H",
                                    scale=p_amp))
        results.checks.append(Check("q(t_end) Hamilton–Jacobi", float(q_hj[-1]),
                                    float(main["q"][-1]), "m",
                                    "integration of H; value from notes (7.38)",
                                    scale=q_amp))
        self._swap_bracket(results, main)
        self._hamilton_jacobi_residuals(results, main, e0)
        self._constancy(results, e, beta)
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201),
                   reference=lambda ts: np.column_stack(self.closed_form(ts)),
                   reference_kind=STUDY_REFERENCE)
        return results

    def _constancy(self, results: Results, energy, beta) -> None:
        """Whether the new pair (E, β) stays constant along the integrated trajectory: its
        drifts relative to E and to the period against :data:`CONSTANT_DRIFT` (stored with
        the threshold, for the words)."""
        a = results.analysis
        e_drift = float(np.max(np.abs(energy - energy[0]))) / abs(float(energy[0]))
        b_drift = a["hj_beta_drift"] / a["period"]
        a["hj_energy_drift"] = e_drift
        a["hj_constant_threshold"] = CONSTANT_DRIFT
        a["hj_pair_constant"] = "yes" if max(e_drift, b_drift) < CONSTANT_DRIFT else "no"

    def _swap_bracket(self, results: Results, main) -> None:
        """{Q, P} of the swap: by SymPy from F1 = q Q, and by central differences of the map
        (q, p) -> (Q, P) = (p, −q) at every stored point of the orbit (notes (6.6–6.11))."""
        prm = self.config.params
        e0 = results.analysis["energy"]
        dq = BRACKET_STEP * core.amplitude(e0, prm.m, prm.omega)
        dp = BRACKET_STEP * math.sqrt(2 * prm.m * e0)
        symbolic = core.swap_poisson_bracket()
        along = core.map_poisson_bracket(core.swap, main["q"], main["p"], dq, dp)
        worst = int(np.argmax(np.abs(along - symbolic)))
        results.analysis["poisson_bracket_QP"] = symbolic
        results.analysis["poisson_bracket_QP_defect"] = float(abs(along[worst] - symbolic))
        results.analysis["canonical_threshold"] = CANONICAL_DEFECT
        results.analysis["swap_canonical"] = (
            "yes" if abs(symbolic - 1.0) < CANONICAL_DEFECT
            and abs(along[worst] - 1.0) < CANONICAL_DEFECT else "no")
        results.checks.append(Check("{Q, P} by central differences, worst sample",
                                    float(along[worst]), symbolic, "",
                                    "SymPy from F1 = q Q, notes (6.6–6.11)", scale=1.0))

    def _hamilton_jacobi_residuals(self, results: Results, main, e0: float) -> None:
        """The Hamilton–Jacobi equations along the run, for the complete integral
        S(q, E, t) = W(q, E) − E t, W = ∫ √(2m(E − mω²q²/2)) dq (notes (7.33–7.34)).

        ∂W/∂q once from the integrand's closed form and once by central differences of W
        computed by quadrature (:class:`~reportgen.core.hamilton_jacobi.CharacteristicQuadrature`),
        ∂S/∂t then by a central difference in t: the residuals of ∂S/∂t + H(q, ∂S/∂q) = 0
        (notes (7.16)) and H(q, ∂W/∂q) = E (notes (7.32)–(7.33)) relative to E, the quadrature's W
        against its closed form, and the integrated p against ±∂W/∂q (the branch of p's
        sign).  Points of the run a rounding past a turning point are taken at it."""
        prm, a = self.config.params, results.analysis
        m, omega = prm.m, prm.omega
        t, q, p = main.t, main["q"], main["p"]
        A = core.amplitude(e0, m, omega)
        W = hamilton_jacobi.CharacteristicQuadrature.of(
            lambda x: 2 * m * e0 - (m * omega * x) ** 2, -A, A)
        q_in = np.clip(q, -A, A)
        closed = core.energy(q_in, core.characteristic_momentum(q_in, e0, m, omega), m, omega)
        q_at, dW_dq = W.gradient(q)
        tau = TIME_STEP * float(t[-1])
        W_at = W(q_at)
        dS_dt = ((W_at - e0 * (t + tau)) - (W_at - e0 * (t - tau))) / (2 * tau)
        H_quadrature = core.energy(q_at, dW_dq, m, omega)
        half_action = math.pi * e0 / omega  # ∫_{−A}^{A} p dq, Goldstein §10.6
        branch = np.sign(p) * core.characteristic_momentum(q, e0, m, omega)
        a.update({
            "hj_residual": float(np.max(np.abs(closed - e0)) / e0),
            "hj_residual_quadrature": float(np.max(np.abs(dS_dt + H_quadrature)) / e0),
            "hj_characteristic_residual_quadrature":
                float(np.max(np.abs(H_quadrature - e0)) / e0),
            "hj_characteristic_quadrature_error":
                float(np.max(np.abs(W(q) - core.characteristic_function(q, e0, m, omega)))
                      / half_action),
            "hj_half_action": W.half_action,
            "hj_momentum_difference":
                float(np.max(np.abs(p - branch)) / math.sqrt(2 * m * e0)),
        })
        worst = int(np.argmax(np.abs(H_quadrature - e0)))
        results.checks.append(Check("H(q, ∂W/∂q), W by quadrature, worst sample",
                                    float(H_quadrature[worst]), e0, "J",
                                    "E, notes (7.32)–(7.33)"))
        results.checks.append(Check("∫ p dq between the turning points, by quadrature",
                                    W.half_action, half_action, "J·s",
                                    "πE/ω, Goldstein §10.6"))
