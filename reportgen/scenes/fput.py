r"""``fput``: the Fermi–Pasta–Ulam–Tsingou stiff–soft chain (Hairer, Lubich & Wanner, GNI §I.5.1).

2m unit masses, stiff linear springs of frequency ω alternating with soft quartic
springs (GNI eq. I.5.1).  The total energy is conserved; the total oscillatory
energy I of the stiff springs (GNI eq. I.5.3) is an adiabatic invariant, within
O(1/ω) of its start, while energy is exchanged between the stiff springs on the
slow time scale ω (GNI Fig. I.5.2).  I is archived as analysis, not as a run
invariant: it is not exactly conserved, so it must not enter the stability check.
"""

from __future__ import annotations

import math

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import AuditCase, Check, Results
from .base import Scene, SceneConfig, Section, SectionContent, fmt, fmt_err

plots = lazy_module("reportgen.plots.fput")
core = lazy_module("reportgen.core.models.fput")

GNI = "Hairer, Lubich & Wanner, Geometric Numerical Integration, 2nd ed."
#: the error-against-run-time study integrates at most this span (the full t = 200 of GNI's
#: data made the default study take minutes: explicit methods must resolve the period 2π/ω)
STUDY_SPAN = 20.0


class Params(Strict):
    m: int = Field(3, ge=1, le=50, description="number of stiff springs (2m masses)")
    omega: Positive = Field(50.0, description="frequency ω of the stiff springs (dimensionless)")


class Initial(Strict):
    q: list[Real] | None = Field(None, description="initial positions q_1 … q_2m (default: "
                                                   "GNI §I.5.1 data)")
    p: list[Real] | None = Field(None, description="initial momenta p_1 … p_2m (default: "
                                                   "GNI §I.5.1 data)")


class FputConfig(SceneConfig):
    params: Params = Params()
    initial: Initial = Initial()
    run: RunConfig

    @model_validator(mode="after")
    def _lengths(self):
        n = 2 * self.params.m
        for key in ("q", "p"):
            values = getattr(self.initial, key)
            if values is not None and len(values) != n:
                raise ValueError(f"initial.{key}: must have 2m = {n} entries for params.m = "
                                 f"{self.params.m} (got {len(values)})")
        return self


class FputScene(Scene):
    kind = "fput"
    order = 85
    summary = ("Fermi–Pasta–Ulam–Tsingou stiff–soft chain: energy exchange between stiff "
               "springs, adiabatic invariant (GNI §I.5.1)")
    Config = FputConfig
    study_horizon_reason = ("explicit methods must resolve the stiff period 2π/ω, and the "
                            "full span made the sweep too slow.")
    presets = {
        "gni": {"params": {"m": 3, "omega": 50.0},
                "run": {"t_end": 200.0, "samples": 4001}},
    }
    sections = (
        Section("energy_exchange", "Energy exchange between the stiff springs", integrates=True),
        Section("invariants", "Conservation of energy", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

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
        osc = core.oscillatory_energies(main.y[:, :n], main.y[:, n:], prm.omega)
        total = osc.sum(axis=1)
        dev = np.abs(total - total[0])
        energy = main.invariants["energy"]
        results.analysis.update({
            "m": prm.m,
            "omega": prm.omega,
            "energy": e0,
            "oscillatory_energies": osc,
            "oscillatory_energy_total": total,
            "oscillatory_energy_scaled_deviation": core.scaled_adiabatic_deviation(total,
                                                                                   prm.omega),
            "oscillatory_energy_initial": float(total[0]),
            # GNI §I.5.1: I(t) = I(0) + O(1/ω); ω max|I − I(0)| stays of order one
            "oscillatory_energy_max_deviation": float(np.max(dev)),
            "oscillatory_energy_deviation_times_omega": float(prm.omega * np.max(dev)),
            "oscillatory_energy_relative_deviation_times_omega":
                float(prm.omega * np.max(dev) / abs(total[0])) if total[0] else math.nan,
        })
        if prm.m >= 2 and total[0] > 0:
            below = osc[:, 0] < 0.7 * total
            if np.any(below):
                results.analysis["exchange_time"] = float(t[int(np.argmax(below))])
        # H is conserved exactly by the flow (GNI eq. I.5.1)
        results.checks.append(Check("energy H(t_end)", float(energy[-1]), e0, "",
                                    f"H(0), conserved ({GNI}, eq. I.5.1)", scale=abs(e0) or None))
        t_study = t if run.t_end <= STUDY_SPAN else np.linspace(0.0, STUDY_SPAN, 401)
        self.study(results, model, y0, t_study, reference=None)
        if results.study is not None:
            results.analysis["study_t_end"] = float(t_study[-1])
        return results

    @classmethod
    def headline(cls, data):
        prm = data.config.params
        a = data.analysis
        facts = [
            ("parameters", f"m = {prm.m} (2m = {2 * prm.m} masses), ω = {fmt(prm.omega)}"),
            ("energy H", fmt(a["energy"], 12)),
            ("oscillatory energy I(0)", fmt(a["oscillatory_energy_initial"], 12)),
            ("ω · max |I(t) − I(0)| / I(0)",
             fmt(a["oscillatory_energy_relative_deviation_times_omega"], 3)),
        ]
        if "exchange_time" in a:
            facts.append(("I_1 first below 0.7 I at t", fmt(a["exchange_time"], 4)))
        return facts

    @classmethod
    def section_energy_exchange(cls, data):
        run = data.runs["main"]
        a = data.analysis
        fig = plots.energy_exchange(run.t, a["oscillatory_energies"],
                                    a["oscillatory_energy_total"],
                                    a["oscillatory_energy_scaled_deviation"])
        facts = [("I(0)", fmt(a["oscillatory_energy_initial"], 12)),
                 ("max |I(t) − I(0)|", fmt_err(a["oscillatory_energy_max_deviation"])),
                 ("ω · max |I(t) − I(0)|", fmt(a["oscillatory_energy_deviation_times_omega"], 4)),
                 ("ω · max |I(t) − I(0)| / I(0)",
                  fmt(a["oscillatory_energy_relative_deviation_times_omega"], 3))]
        if "exchange_time" in a:
            facts.append(("first time I_1 < 0.7 I", fmt(a["exchange_time"], 4)))
        return SectionContent(
            figures=[cls.figure("energy_exchange", fig,
                                 "Top: oscillatory energies I_j = ½(y₁ⱼ² + ω² x₁ⱼ²) of the stiff "
                                 "springs and their sum I (GNI eq. I.5.3, Fig. I.5.2). Bottom: "
                                 "ω (I(t) − I(0)) / I(0); I is an adiabatic invariant, "
                                 "I(t) − I(0) = O(1/ω), so this stays of order one.")],
            facts=facts)

    @classmethod
    def section_invariants(cls, data):
        return cls.invariants_section(data, labels={"energy": "energy H"},
                                      caption="Relative drift of the total energy H (GNI eq. "
                                              "I.5.1).")
