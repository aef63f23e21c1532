"""``fput`` simulation: the stiff–soft chain integrated, its total energy conserved and
the oscillatory energies of the stiff springs (an adiabatic invariant) along the run.

I is archived as analysis, not as a run invariant: it is not exactly conserved, so it
must not enter the stability check.
"""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.integration import IntegratingSimulation
from ...scene.results import AuditCase, Check, Results
from .config import AT_REST, EXCHANGE_SHARE, ORDER_ONE, STIFF_RATIO, FputConfig
from .results import SCHEMA

core = lazy_module("reportgen.core.models.fput")

#: the error-against-run-time study integrates at most this span (the full t = 200 of GNI's
#: data made the default study take minutes: explicit methods must resolve the period 2π/ω)
STUDY_SPAN = 20.0


class FputSimulation(IntegratingSimulation):
    """2m unit masses, stiff linear springs alternating with soft quartic ones (GNI I.5.1)."""

    schema = SCHEMA
    config: FputConfig

    @classmethod
    def audit_cases(cls):
        name = "FPUT stiff–soft chain, ω = 50"
        return [AuditCase(
            name=name,
            what="stiff springs ω = 50 against soft nonlinear ones: two time scales, energy "
                 "exchange on the slow one",
            methods=("dop853", "yoshida6", "gauss6"),
            config={"kind": "fput", "title": name, "params": {"m": 3, "omega": 50.0},
                    "run": {"t_end": 200.0, "samples": 4001}})]

    # ----------------------------------------------------------------- helpers
    def initial_state(self) -> tuple[np.ndarray, np.ndarray]:
        prm, ini = self.config.params, self.config.initial
        q_gni, p_gni = core.gni_initial(prm.m, prm.omega)
        q = np.array(ini.q if ini.q is not None else q_gni, dtype=np.float64)
        p = np.array(ini.p if ini.p is not None else p_gni, dtype=np.float64)
        return q, p

    def models(self) -> list:
        return [core.model(self.config.params.m, self.config.params.omega)]

    def _largest_m(self) -> int:
        """m, or the largest m of a sweep over ``params.m``."""
        m = self.config.params.m
        for axis in self.sweep.axes if self.sweep is not None else ():
            if axis.path == "params.m":
                m = max(m, int(max(axis.array())))
        return m

    def stored_columns(self) -> int:
        """q and p of the 2m masses (the schema declares them for the largest m)."""
        return 4 * self._largest_m()

    def dimension_size(self, name: str) -> int | None:
        return self._largest_m() if name == "stiff_spring" else None

    def exchange(self, q, p, t, e0: float) -> dict:
        """The oscillatory energies Iⱼ of the stiff springs along the run (GNI eq. I.5.3),
        where I starts (the spring holding most of I(0), and its share), when that spring
        first holds less than EXCHANGE_SHARE of I (only when it starts with at least that
        share, m ≥ 2), and the adiabatic invariant's excursion ω·max|I − I(0)|/I(0) (not
        defined when the stiff springs start at rest: I(0) ≤ AT_REST × |H|)."""
        omega = self.config.params.omega
        osc = core.oscillatory_energies(q, p, omega)
        total = osc.sum(axis=1)
        dev = np.abs(total - total[0])
        at_rest = bool(total[0] <= AT_REST * max(abs(e0), 1e-300))
        first = int(np.argmax(osc[0]))
        share = float(osc[0, first] / total[0]) if not at_rest else math.nan
        out = {
            "m": self.config.params.m,
            "omega": omega,
            "energy": e0,
            "oscillatory_energies": osc,
            "oscillatory_energy_total": total,
            "oscillatory_energy_scaled_deviation": core.scaled_adiabatic_deviation(total,
                                                                                   omega),
            "oscillatory_energy_initial": float(total[0]),
            # GNI §I.5.1: I(t) = I(0) + O(1/ω); ω max|I − I(0)| stays of order one
            "oscillatory_energy_max_deviation": float(np.max(dev)),
            "oscillatory_energy_deviation_times_omega": float(omega * np.max(dev)),
            "oscillatory_energy_relative_deviation_times_omega":
                math.nan if at_rest else float(omega * np.max(dev) / abs(total[0])),
            "stiff_at_rest": at_rest,
            "first_spring": first + 1,
            "first_spring_share": share,
            "exchange_share": EXCHANGE_SHARE,
            "order_one_bound": ORDER_ONE,
        }
        if not at_rest:
            out["adiabatic_order_one"] = bool(
                out["oscillatory_energy_relative_deviation_times_omega"] < ORDER_ONE)
        if self.config.params.m >= 2 and not at_rest and share >= EXCHANGE_SHARE:
            below = osc[:, first] < EXCHANGE_SHARE * total
            if np.any(below):
                out["exchange_time"] = float(t[int(np.argmax(below))])
        return out

    def time_scales(self, q) -> dict:
        """ω against the soft springs' typical frequency √(24⟨Δ²⟩) along the run (Δ their
        elongations q₂ᵢ₊₁ − q₂ᵢ, ends fixed: V = Δ⁴ between two unit masses has
        V″/μ = 24Δ²): two time scales when ω is STIFF_RATIO times it or more."""
        omega = self.config.params.omega
        padded = np.pad(np.asarray(q, dtype=float), ((0, 0), (1, 1)))
        soft = padded[:, 1::2] - padded[:, 0::2]
        frequency = float(np.sqrt(24.0 * np.mean(soft**2)))
        ratio = omega / frequency if frequency > 0 else math.inf
        return {"soft_frequency": frequency, "stiffness_ratio": ratio,
                "stiff_ratio_bound": STIFF_RATIO, "two_time_scales": bool(ratio >= STIFF_RATIO)}

    def simulate(self, progress=None) -> Results:
        prm, run = self.config.params, self.config.run
        n = 2 * prm.m
        q0, p0 = self.initial_state()
        y0 = np.concatenate([q0, p0])
        t = np.linspace(0.0, run.t_end, run.samples)
        e0 = float(core.energy(q0, p0, prm.omega)[0])
        (model,) = self.models()

        def invariants(_t, y):
            return {"energy": core.energy(y[:, :n], y[:, n:], prm.omega)}

        results = Results()
        main = self.integrate(model, y0, t, invariants=invariants, progress=progress,
                              n_periods=run.t_end * prm.omega / (2 * math.pi),
                              invariant_scales={"energy": abs(e0)} if e0 else None)
        results.runs["main"] = main
        energy = main.invariants["energy"]
        results.analysis.update(self.exchange(main.y[:, :n], main.y[:, n:], main.t, e0))
        results.analysis.update(self.time_scales(main.y[:, :n]))
        # H is conserved exactly by the flow (GNI eq. I.5.1)
        results.checks.append(Check("energy H(t_end)", float(energy[-1]), e0, "",
                                    "H(0), conserved (GNI eq. I.5.1)", scale=abs(e0) or None))
        t_study = t if run.t_end <= STUDY_SPAN else np.linspace(0.0, STUDY_SPAN, 401)
        self.study(results, model, y0, t_study, reference=None)
        if results.study is not None:
            results.analysis["study_t_end"] = float(t_study[-1])
        return results
