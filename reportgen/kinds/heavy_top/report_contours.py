"""``heavy_top`` report, the contour section (textbook ex. 4.10(a)–(e)): t(u) = ∫du/√f(u)
continued off the real axis by contour integration, the image of the cut plane a rectangle
T/2 × τ/2, the lower half-plane below it, the second sheet beside it, and the loop round a
cut one imaginary period.  Drawn from ``/analysis/contours`` alone."""

from __future__ import annotations

from ...lazy import lazy_module
from ...scene.content import SectionContent, Table, fmt, fmt_err

plots_contours = lazy_module("reportgen.kinds.heavy_top.plots_contours")


def _complex(k, name: str) -> complex:
    return complex(float(k[f"t_{name}_re"]), float(k[f"t_{name}_im"]))


def _t_text(t: complex) -> str:
    """t = x + iy as the page prints it."""
    x, y = t.real, t.imag
    if abs(y) < 1e-300:
        return fmt(x)
    sign = "−" if y < 0 else "+"
    return f"{fmt(x)} {sign} {fmt(abs(y))} i"


class ContourSection:
    """The contour section (mixed into :class:`.report.HeavyTopReport`)."""

    @classmethod
    def section_contour_map(cls, data):
        k = data.analysis["contours"]
        T, tau = float(k["period"]), float(k["imaginary_period"])
        d, sides = k["defects"], k["sides"]
        rows = [
            ["t(u_N)", _t_text(_complex(k, "u_N")), "T/2 = " + fmt(0.5 * T),
             fmt_err(float(d["corner_u_N"]))],
            ["t(u_U)", _t_text(_complex(k, "u_U")),
             f"(T + iτ)/2 = {_t_text(complex(0.5 * T, 0.5 * tau))}",
             fmt_err(float(d["corner_u_U"]))],
            ["t(∞) along (u_U, ∞)", _t_text(_complex(k, "infinity")),
             f"iτ/2 = {_t_text(complex(0.0, 0.5 * tau))}", fmt_err(float(d["corner_infinity"]))],
            ["t(−∞) along (−∞, u_X)", _t_text(_complex(k, "infinity_left")),
             "t(∞) the other way", fmt_err(float(d["infinity_both_ways"]))],
            ["∮ clockwise round [u_N, u_U]", _t_text(_complex(k, "loop")),
             f"iτ = {_t_text(complex(0.0, tau))}", fmt_err(float(d["loop"]))],
            ["∮ round [u_X, u_N], through both cuts", _t_text(_complex(k, "loop_real")),
             f"T = {fmt(T)}", fmt_err(float(d["loop_real"]))],
        ]
        corner_table = Table(
            caption="Corners of the rectangle and the loop round the cut, by contour "
                    "integration, against T = 4K(k²)/√(β(u3 − u1)) and τ = "
                    "4K(1 − k²)/√(β(u3 − u1)) (t in s; defect = |computed − closed form| "
                    "in s)",
            header=["integral", "computed [s]", "closed form [s]", "defect [s]"], rows=rows)
        claims = [
            ["(a) (u_X, u_N) ↦ bottom side, Im t = 0", fmt_err(float(sides["bottom"]))],
            ["(a) (u_N, u_U) ↦ right side, Re t = T/2", fmt_err(float(sides["right"]))],
            ["(a) (u_U, ∞) ↦ top side, Im t = τ/2", fmt_err(float(sides["top"]))],
            ["(a) (−∞, u_X) ↦ left side, Re t = 0", fmt_err(float(sides["left"]))],
            ["(a) grid above the axis outside (0, T/2) × (0, τ/2) by",
             fmt_err(float(d["upper_in_rectangle"]))],
            ["(b) below the axis through (u_X, u_N): t(ū) = conj t(u)",
             fmt_err(float(d["lower_reflection"]))],
            ["(b) … outside (0, T/2) × (−τ/2, 0) by", fmt_err(float(d["lower_in_rectangle"]))],
            ["(c) second sheet through (−∞, u_X]: t₁(u) = −t₀(u)",
             fmt_err(float(d["second_sheet_left"]))],
            ["(d) second sheet through [u_N, u_U]: t₂(u) = t₁(u) + T",
             fmt_err(float(d["second_sheet_right"]))],
        ]
        claims_table = Table(
            caption="Each part of the exercise on this top: the largest defect over the "
                    "sampled points (in s)",
            header=["claim", "largest defect [s]"], rows=claims)
        caption = (
            "Left: the u plane cut along (−∞, u_X] and [u_N, u_U] (thick), with horizontal "
            "lines above the axis (solid; heights on a scale logarithmic away from the axis) "
            "and their mirror images below it (dashed). "
            "Right: their images t(u) = ∫du/√f(u) from u_X. The lines above the axis fill "
            f"the rectangle (0, T/2) × (0, τ/2), T = {fmt(T)} s and τ = {fmt(tau)} s, with "
            "u_X, u_N, u_U and ∞ at its corners; their mirror images, reached through "
            "(u_X, u_N), fill the rectangle below; reached through a cut onto the second "
            "sheet (pale), they land at −t₀ on the left and T − t₀ on the right.")
        return SectionContent(
            facts=[("t(u_N) against T/2, relative to T", fmt_err(float(d["corner_u_N"]) / T)),
                   ("the loop round [u_N, u_U] against iτ, relative to T",
                    fmt_err(float(d["loop"]) / T))],
            figures=[cls.figure("contour_map", plots_contours.contour_figure(k), caption)],
            tables=[corner_table, claims_table])
