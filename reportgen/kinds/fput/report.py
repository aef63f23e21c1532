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
        return (f"stiff spring {a['first_spring']} hands its energy on in t ≈ "
                f"{fmt(a['exchange_time'], 3)}; total energy kept to "
                f"{gallery.distance(energy.rel_error)}")

    study_horizon_reason = ("the study repeats the integration for every method and "
                            "tolerance, and explicit methods step a fraction of the stiff "
                            "springs' period 2π/ω: over GNI's whole span (t = 200 at ω = 50) "
                            "it took minutes.")
    sections = (
        Section("energy_exchange", "Energy exchange between the stiff springs", integrates=True),
        Section("invariants", "Conservation of energy", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def prose_case(cls, data):
        """Where the oscillatory energy starts (the stiff spring holding most of I(0), or at
        rest), whether and when it is handed on, the other springs' peaks, whether the chain
        has two time scales and the adiabatic invariant's scaled excursion, all from the
        archive's stored classifications."""
        if data.sweep is not None:
            return {"sweep": True}
        a = data.analysis
        energies = np.asarray(a["oscillatory_energies"], dtype=float)
        total0 = float(np.sum(energies[0]))
        first = int(a["first_spring"])
        at_rest = bool(a["stiff_at_rest"])
        share = float(a["first_spring_share"])
        peaks = ([] if at_rest else
                 [f"{cls.percent(float(np.max(energies[:, j])) / total0)} % (spring {j + 1})"
                  for j in range(energies.shape[1]) if j != first - 1])
        excursion = float(a["oscillatory_energy_relative_deviation_times_omega"])
        m = int(data.config.params.m)
        if at_rest:
            start = "at_rest"
        elif m == 1:
            start = "single"
        elif share >= float(a["exchange_share"]):
            start = "concentrated"
        else:
            start = "spread"
        return {"sweep": False, "m": m, "omega": fmt(float(a["omega"]), 4),
                "start": start, "first": first,
                "share": "" if at_rest else fmt(share * 100, 3),
                "exchange_share": fmt(float(a["exchange_share"]) * 100, 2),
                "exchange": "exchange_time" in a,
                "exchange_time": fmt(float(a.get("exchange_time", math.nan)), 4),
                "peaks": " and ".join(peaks),
                "excursion": "" if at_rest else fmt(excursion, 3),
                "order_one": bool(a.get("adiabatic_order_one", False)),
                "order_one_bound": fmt(float(a["order_one_bound"]), 2),
                "two_time_scales": bool(a["two_time_scales"]),
                "stiffness_ratio": fmt(float(a["stiffness_ratio"]), 3),
                "soft_frequency": fmt(float(a["soft_frequency"]), 3),
                "stiff_ratio_bound": fmt(float(a["stiff_ratio_bound"]), 2)}

    @staticmethod
    def percent(share: float) -> str:
        """A share as a percentage to two figures, whole above 100 (I is not conserved: a
        spring may come to hold more than I(0))."""
        value = 100 * share
        return fmt(value, 2) if not value >= 100 or math.isinf(value) else str(round(value))

    @classmethod
    def describe(cls, data):
        """``A stiff–soft chain of 6 masses, ω = 50: the energy put into stiff spring 1 is
        handed on from t ≈ 32.55, ω·|I − I(0)|/I(0) ≤ 0.155``."""
        if data.sweep is not None:
            return super().describe(data)
        c = cls.prose_case(data)
        head = f"A stiff–soft chain of {2 * c['m']} masses, ω = {c['omega']}: "
        if c["start"] == "at_rest":
            return head + "the stiff springs start at rest (no oscillatory energy)"
        if c["start"] == "single":
            where = "one stiff spring, which holds all the oscillatory energy"
        elif c["start"] == "spread":
            where = (f"the oscillatory energy starts spread over the stiff springs (at most "
                     f"{c['share']} %, in spring {c['first']})")
        elif c["exchange"]:
            where = (f"the energy put into stiff spring {c['first']} is handed on from "
                     f"t ≈ {c['exchange_time']}")
        else:
            where = f"the energy put into stiff spring {c['first']} stays there over the run"
        return f"{head}{where}; ω·|I − I(0)|/I(0) ≤ {c['excursion']}"

    @classmethod
    def headline(cls, data):
        prm = data.config.params
        a = data.analysis
        facts = [
            ("parameters", f"m = {prm.m} (2m = {2 * prm.m} masses), ω = {fmt(prm.omega)}"),
            ("energy H", fmt(a["energy"])),
            ("oscillatory energy I(0)", fmt(a["oscillatory_energy_initial"])),
        ]
        if not a["stiff_at_rest"]:
            facts.append(("ω · max |I(t) − I(0)| / I(0)",
                          fmt(a["oscillatory_energy_relative_deviation_times_omega"], 3)))
        if "exchange_time" in a:
            facts.append((f"I{a['first_spring']} first below "
                          f"{fmt(float(a['exchange_share']) * 100, 2)} % of I at t",
                          fmt(a["exchange_time"], 4)))
        return facts

    @classmethod
    def section_energy_exchange(cls, data):
        run = data.runs["main"]
        a = data.analysis
        fig = plots.energy_exchange(run.t, a["oscillatory_energies"],
                                    a["oscillatory_energy_total"],
                                    a["oscillatory_energy_scaled_deviation"],
                                    relative=not a["stiff_at_rest"])
        facts = [("I(0)", fmt(a["oscillatory_energy_initial"])),
                 ("max |I(t) − I(0)|", fmt_err(a["oscillatory_energy_max_deviation"])),
                 ("ω · max |I(t) − I(0)|", fmt(a["oscillatory_energy_deviation_times_omega"], 4))]
        if not a["stiff_at_rest"]:
            facts.append(("ω · max |I(t) − I(0)| / I(0)",
                          fmt(a["oscillatory_energy_relative_deviation_times_omega"], 3)))
        facts.append(("ω over the soft springs' typical frequency √(24⟨Δ²⟩) = "
                      f"{fmt(float(a['soft_frequency']), 3)}",
                      fmt(float(a["stiffness_ratio"]), 3)))
        if "exchange_time" in a:
            facts.append((f"first time I{a['first_spring']} < "
                          f"{fmt(float(a['exchange_share']), 2)} I", fmt(a["exchange_time"], 4)))
        c = cls.prose_case(data)
        if c["start"] == "at_rest":
            bottom = ("Bottom: ω (I(t) − I(0)), since I(0) = 0 here (the stiff springs start "
                      "at rest).")
        elif c["two_time_scales"] and c["order_one"]:
            bottom = ("Bottom: ω (I(t) − I(0)) / I(0); I is an adiabatic invariant, "
                      "I(t) − I(0) = O(1/ω), and this stays of order one here.")
        elif c["two_time_scales"]:
            bottom = ("Bottom: ω (I(t) − I(0)) / I(0); it grows beyond order one here, "
                      f"above {c['order_one_bound']}.")
        else:
            bottom = ("Bottom: ω (I(t) − I(0)) / I(0); ω is not large against the soft "
                      "springs' frequency here, so I is not expected to be an adiabatic "
                      "invariant.")
        return SectionContent(
            figures=[cls.figure("energy_exchange", fig,
                                "Top: oscillatory energies Iⱼ = ½(y₁ⱼ² + ω² x₁ⱼ²) of the stiff "
                                "springs and their sum I (GNI eq. I.5.3, Fig. I.5.2). "
                                + bottom)],
            facts=facts)

    @classmethod
    def section_invariants(cls, data):
        return cls.invariants_section(data, labels={"energy": "energy H"},
                                      caption="Relative drift of the total energy H (GNI eq. "
                                              "I.5.1).")
