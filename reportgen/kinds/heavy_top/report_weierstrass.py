"""``heavy_top`` report, the ℘ section (textbook ex. 4.10): u(t) through Weierstrass's ℘,
the scaling u = (4/β)℘ + μ against the textbook's u = β℘ + c, and the nutation period as the
loop integral ∮du/√f(u) round the cut [u1, u2] against 2ω and 4K(k²)/√(β(u3 − u1))."""

from __future__ import annotations

import math

from ...lazy import lazy_module
from ...scene.content import SectionContent, Table, fmt, fmt_err
from .config import BAND_CASES

plots = lazy_module("reportgen.kinds.heavy_top.plots")

#: the band runs in the order textbook Fig. 4.3 draws them
_RUN_ORDER = {name: i for i, name in enumerate(BAND_CASES)}


def scaling_note(beta: float, agrees: bool | None = None) -> str:
    """Why ℘ is multiplied by 4/β, not by β as textbook ex. 4.10 writes, for this top's
    β = 2Mgl/I1 [1/s²]; ``agrees``: the stored fact that β and 4/β coincide in number (β²
    = 4 to 1e-6), which decides the last sentence (by default, whether they print alike)."""
    text = ("Scale of ℘: textbook ex. 4.10 writes u = β℘ + c. The factor is fixed by the "
            "leading coefficients: with u = λ℘(t) + μ, u̇² = f(u) = βu³ + … becomes "
            "λ²℘′² = βλ³℘³ + …, i.e. ℘′² = βλ℘³ + …, and ℘′² = 4℘³ − g2℘ − g3 needs βλ = 4: "
            f"λ = 4/β = {fmt(4.0 / beta)} s² here (β = {fmt(beta)} 1/s²). With λ = β the "
            "leading coefficient would be β², Weierstrass's equation only when β² = 4 "
            "(or with ℘ taken at βt/2 instead of t); nor is β℘ a number: ℘(t) ≈ 1/t² near "
            "its pole carries 1/s², so β℘ carries 1/s⁴, while (4/β)℘ is dimensionless.")
    if agrees if agrees is not None else fmt(beta) == fmt(4.0 / beta):
        text += (f" For this top β = {fmt(beta)} 1/s², so β and 4/β share the number "
                 f"{fmt(beta)} and the textbook's form happens to give the same u(t): only "
                 "the units tell the two apart; another I1 or Mgl separates them.")
    return text


class WeierstrassSection:
    """The ℘ section (mixed into :class:`.report.HeavyTopReport`)."""

    @classmethod
    def section_weierstrass(cls, data):
        a = data.analysis
        wp = a.get("weierstrass")
        if wp is None:
            return SectionContent(notes=["No nutation (u1 = u2): the cubic has a double root "
                                         "and ℘ degenerates; nothing to show."])
        fig = plots.weierstrass_rectangle(wp["omega"], wp["omega_prime"], wp["x0"], wp["t_end"])
        rows = [
            ["u = λ℘ + μ: λ = 4/β", fmt(wp["scale"]), "s²"],
            ["μ = (u1 + u2 + u3)/3", fmt(wp["shift"]), ""],
            ["g2 = 2(e1² + e2² + e3²)", fmt(wp["g2"]), "1/s⁴"],
            ["g3 = 4 e1 e2 e3", fmt(wp["g3"]), "1/s⁶"],
            ["e1 = ℘(ω) = β(u3 − μ)/4", fmt(wp["e1"]), "1/s²"],
            ["e2 = ℘(ω + ω′) = β(u2 − μ)/4", fmt(wp["e2"]), "1/s²"],
            ["e3 = ℘(ω′) = β(u1 − μ)/4", fmt(wp["e3"]), "1/s²"],
            ["ω (real half-period)", fmt(wp["omega"]), "s"],
            ["ω′/i (imaginary half-period)", fmt(wp["omega_prime"]), "s"],
            ["x0: z(0) = x0 + ω′", fmt(wp["x0"]), "s"],
            ["nome q = exp(iπω′/ω)", fmt(wp["nome"], 6), ""],
        ]
        table = Table(caption="Invariants, roots and half-periods of ℘ for this top"
                              + cls._of_run(data),
                      header=["quantity", "value", "unit"], rows=rows)
        facts = [("max |Δu(t)|, ℘ form against sn² form, on the output grid",
                  fmt_err(wp["max_difference"])),
                 ("2ω against 4K(k²)/√(β(u3 − u1))",
                  fmt_err(abs(wp["period"] / a["nutation_period"] - 1.0)))]
        if "ode_residual" in wp:
            facts.append(("max |λ²℘′² − f(u)| / max f(u) on the output grid, λ = 4/β",
                          fmt_err(wp["ode_residual"])))
        tables, notes = [table], [scaling_note(float(a["beta"]),
                                               wp.get("textbook_scale_agrees"))]
        if "period_loop" in wp:
            tables += cls._period_tables(a, wp)
            if math.isfinite(wp["period_loop_imag"]):
                facts.append(("imaginary part left by the loop sum (zero in exact "
                              "arithmetic)", f"{fmt_err(wp['period_loop_imag'])} s"))
            if not math.isfinite(wp["period_loop"]):
                notes.append(
                    f"No loop sum here: u3 lies so close to the cut (a = "
                    f"{fmt(wp['period_loop_strip'], 3)}) that the trapezoidal rule would need "
                    f"some 60/(a − ρ) = {fmt(float(wp['period_loop_nodes']), 2)} nodes, beyond "
                    "its node budget; the period is then 2ω and 4K(k²)/√(β(u3 − u1)) alone.")
        return SectionContent(
            facts=facts,
            figures=[cls.figure(
                "weierstrass", fig,
                "The period rectangle of ℘ with corners 0, 2ω, 2ω + 2ω′, 2ω′ (double poles of "
                "℘ at the corners); ℘ is real on its edges and middle lines. The motion is the "
                "line z = x0 + t + ω′, along which ℘ runs between e3 (u = u1, lower circle) and "
                "e2 (u = u2, upper circle), one nutation period per 2ω. u℘(t) is stored on the "
                "output grid beside the run" + cls._of_run(data) + ".")],
            tables=tables, notes=notes)

    @staticmethod
    def _period_tables(a, wp) -> list[Table]:
        """The nutation period as loop integrals against its closed forms; and, for the
        three runs of a band, the loop integral of each."""
        T = float(a["nutation_period"])

        def row(way, value, nodes=None):
            if not math.isfinite(value):  # not summed: the note says why
                return [way, fmt(value), fmt(value), "—"]
            return [way, fmt(value, against=T), fmt_err(abs(value / T - 1.0)),
                    "—" if nodes is None else str(int(nodes))]

        rows = [
            row(f"∮du/√f(u) round [u1, u2], on the ellipse ρ = "
                f"{fmt(wp['period_loop_rho'], 4)} (a = {fmt(wp['period_loop_strip'], 4)})",
                wp["period_loop"], wp["period_loop_nodes"]),
            row("2∫du/√f(u) from u1 to u2, u = u1 + (u2 − u1) sin²s",
                wp["period_sine_squared"], wp["period_sine_squared_nodes"]),
            row("∮d℘/√(4℘³ − g2℘ − g3) round [e3, e2]", 2.0 * wp["omega_loop"],
                wp["omega_loop_nodes"]),
            row("2ω, ω by the arithmetic–geometric mean", wp["period"]),
        ]
        measured = float(a.get("nutation_period_measured", math.nan))
        if math.isfinite(measured):
            rows.append(row("measured from the integrated θ(t)", measured))
        rows.append(["4K(k²)/√(β(u3 − u1)), K by Carlson's symmetric integral", fmt(T),
                     "reference", "—"])
        tables = [Table(
            caption="The nutation period as a loop integral round the cut (textbook ex. 4.10; "
                    "trapezoidal rule with N nodes), against 2ω and the closed form of notes "
                    "§10.1",
            header=["T computed as", "value [s]", "relative difference", "N"], rows=rows)]
        runs = (a.get("band") or {}).get("runs") or {}
        if len(runs) > 1:
            tables.append(Table(
                caption="The loop integral ∮du/√f(u) on each run of the band",
                header=["run", "∮du/√f(u) [s]", "4K(k²)/√(β(u3 − u1)) [s]", "relative"],
                rows=[[name, fmt(r["period_loop"], against=r["nutation_period"]),
                       fmt(r["nutation_period"], against=r["period_loop"]),
                       fmt_err(abs(r["period_loop"] / r["nutation_period"] - 1.0))]
                      for name, r in sorted(runs.items(), key=lambda item: _RUN_ORDER.get(
                          item[0], len(_RUN_ORDER)))]))
        return tables
