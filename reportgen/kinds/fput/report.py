"""``fput`` report: the energy exchange between the stiff springs (GNI Fig. I.5.2) and
the conservation of the total energy."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, fmt, fmt_err
from ...scene.report import Report
from .results import SCHEMA

plots = lazy_module("reportgen.kinds.fput.plots")


class FputReport(Report):
    """The FPUT chain's sections, drawn from the archive alone."""

    schema = SCHEMA
    gallery_figures = ("energy_exchange",)

    @classmethod
    def gallery_headline(cls, data):
        import math

        from ...scene import gallery
        a = data.analysis
        energy = gallery.worst_check(data, "energy")
        if energy is None or not math.isfinite(a.get("exchange_time", math.nan)):
            return super().gallery_headline(data)
        return (f"the stiff springs hand their energy on in t ≈ {fmt(a['exchange_time'], 3)}; "
                f"total energy kept to {gallery.distance(energy.rel_error)}")

    study_horizon_reason = ("explicit methods must resolve the stiff period 2π/ω, and the "
                            "full span made the sweep too slow.")
    sections = (
        Section("energy_exchange", "Energy exchange between the stiff springs", integrates=True),
        Section("invariants", "Conservation of energy", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def prose_case(cls, data):
        """Where the oscillatory energy starts (the stiff spring holding most of I(0)),
        whether and when it is handed on, the other springs' peaks, and the adiabatic
        invariant's scaled excursion, from the archive."""
        if data.sweep is not None:
            return {}
        a = data.analysis
        energies = np.asarray(a["oscillatory_energies"], dtype=float)
        total0 = float(np.sum(energies[0])) or 1.0
        first = int(np.argmax(energies[0]))
        peaks = [f"{fmt(float(np.max(energies[:, j])) / total0 * 100, 2)} % (spring {j + 1})"
                 for j in range(energies.shape[1]) if j != first]
        return {"m": int(data.config.params.m), "omega": fmt(float(a["omega"]), 4),
                "first": first + 1, "share": fmt(energies[0, first] / total0 * 100, 3),
                "exchange": "exchange_time" in a,
                "exchange_time": fmt(float(a.get("exchange_time", math.nan)), 4),
                "peaks": " and ".join(peaks),
                "excursion": fmt(float(a["oscillatory_energy_relative_deviation_times_omega"]), 3),
                "order_one": float(a["oscillatory_energy_relative_deviation_times_omega"]) < 10}

    @classmethod
    def describe(cls, data):
        """``A stiff–soft chain of 6 masses, ω = 50: the energy put into stiff spring 1 is
        handed on from t ≈ 32.55, ω·|I − I(0)|/I(0) ≤ 0.155``."""
        if data.sweep is not None:
            return super().describe(data)
        c = cls.prose_case(data)
        handed = (f"is handed on from t ≈ {c['exchange_time']}" if c["exchange"]
                  else "stays there over the run")
        return (f"A stiff–soft chain of {2 * c['m']} masses, ω = {c['omega']}: the energy put "
                f"into stiff spring {c['first']} {handed}; ω·|I − I(0)|/I(0) ≤ "
                f"{c['excursion']}")

    @classmethod
    def headline(cls, data):
        prm = data.config.params
        a = data.analysis
        facts = [
            ("parameters", f"m = {prm.m} (2m = {2 * prm.m} masses), ω = {fmt(prm.omega)}"),
            ("energy H", fmt(a["energy"])),
            ("oscillatory energy I(0)", fmt(a["oscillatory_energy_initial"])),
            ("ω · max |I(t) − I(0)| / I(0)",
             fmt(a["oscillatory_energy_relative_deviation_times_omega"], 3)),
        ]
        if "exchange_time" in a:
            facts.append(("I₁ first below 0.7 I at t", fmt(a["exchange_time"], 4)))
        return facts

    @classmethod
    def section_energy_exchange(cls, data):
        run = data.runs["main"]
        a = data.analysis
        fig = plots.energy_exchange(run.t, a["oscillatory_energies"],
                                    a["oscillatory_energy_total"],
                                    a["oscillatory_energy_scaled_deviation"])
        facts = [("I(0)", fmt(a["oscillatory_energy_initial"])),
                 ("max |I(t) − I(0)|", fmt_err(a["oscillatory_energy_max_deviation"])),
                 ("ω · max |I(t) − I(0)|", fmt(a["oscillatory_energy_deviation_times_omega"], 4)),
                 ("ω · max |I(t) − I(0)| / I(0)",
                  fmt(a["oscillatory_energy_relative_deviation_times_omega"], 3))]
        if "exchange_time" in a:
            facts.append(("first time I₁ < 0.7 I", fmt(a["exchange_time"], 4)))
        return SectionContent(
            figures=[cls.figure("energy_exchange", fig,
                                "Top: oscillatory energies Iⱼ = ½(y₁ⱼ² + ω² x₁ⱼ²) of the stiff "
                                "springs and their sum I (GNI eq. I.5.3, Fig. I.5.2). Bottom: "
                                "ω (I(t) − I(0)) / I(0); I is an adiabatic invariant, "
                                "I(t) − I(0) = O(1/ω), so this stays of order one.")],
            facts=facts)

    @classmethod
    def section_invariants(cls, data):
        return cls.invariants_section(data, labels={"energy": "energy H"},
                                      caption="Relative drift of the total energy H (GNI eq. "
                                              "I.5.1).")
