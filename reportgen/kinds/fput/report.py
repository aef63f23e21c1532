"""``fput`` report: the energy exchange between the stiff springs (GNI Fig. I.5.2) and
the conservation of the total energy."""

from __future__ import annotations

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, fmt, fmt_err
from ...scene.report import Report
from .results import SCHEMA

plots = lazy_module("reportgen.kinds.fput.plots")


class FputReport(Report):
    """The FPUT chain's sections, drawn from the archive alone."""

    schema = SCHEMA
    study_horizon_reason = ("explicit methods must resolve the stiff period 2π/ω, and the "
                            "full span made the sweep too slow.")
    sections = (
        Section("energy_exchange", "Energy exchange between the stiff springs", integrates=True),
        Section("invariants", "Conservation of energy", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

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
