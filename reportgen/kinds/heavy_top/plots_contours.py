"""``heavy_top`` figure of textbook ex. 4.10(a)–(e): the cut u plane and its image in the
t plane (:mod:`.report_contours`), from ``/analysis/contours`` alone."""

from __future__ import annotations

import math

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure
from matplotlib.ticker import NullLocator

from ...rendering.plots.style import CONTEXT, REFERENCE, SEPARATRIX, new_figure_grid


def contour_figure(k) -> Figure:
    """Left: the u plane with its cuts and the grid (solid above the axis, dashed its mirror
    below); right: the grid's images in the t plane, the first sheet in the rectangle
    (0, T/2) × (−τ/2, τ/2), the second sheet beside it."""
    fig, axes = new_figure_grid(1, 2, figsize=(7.4, 3.6))
    ax_u, ax_t = axes[0, 0], axes[0, 1]
    u_X, u_N, u_U = (float(k[n]) for n in ("u_X", "u_N", "u_U"))
    T, tau = float(k["period"]), float(k["imaginary_period"])
    gre, gim = np.asarray(k["grid_re"]), np.asarray(k["grid_im"])
    colours = [tuple(c) for c in colormaps["viridis"](np.linspace(0.1, 0.85, len(gre)))]
    for j, colour in enumerate(colours):
        ax_u.plot(gre[j], gim[j], color=colour, linewidth=1.0)
        ax_u.plot(gre[j], -gim[j], color=colour, linewidth=1.0, linestyle="--")
    lo, hi = float(gre.min()), float(gre.max())
    ax_u.plot([lo, u_X], [0, 0], color=SEPARATRIX, linewidth=3.0, solid_capstyle="butt")
    ax_u.plot([u_N, u_U], [0, 0], color=SEPARATRIX, linewidth=3.0, solid_capstyle="butt")
    ax_u.plot([u_X, u_N, u_U], [0, 0, 0], "o", color="k", markersize=4, zorder=5)
    ax_u.annotate("$u_X$", (u_X, 0), textcoords="offset points", xytext=(-4, -12),
                  ha="right", fontsize=9)
    ax_u.annotate("$u_N$", (u_N, 0), textcoords="offset points", xytext=(3, 6), ha="left",
                  fontsize=9)
    ax_u.annotate("$u_U$", (u_U, 0), textcoords="offset points", xytext=(0, -13),
                  ha="center", fontsize=9)
    # the branch points crowd near u_X: |Im u| on a scale linear within the lowest line's
    # height and logarithmic beyond, Re u over the cuts and a little past them
    top, low = float(gim.max()), float(gim.min())
    ax_u.set_yscale("symlog", linthresh=low)
    ax_u.set_ylim(-1.3 * top, 1.3 * top)
    decades = np.arange(math.ceil(math.log10(low)) + 1, math.floor(math.log10(top)) + 1)
    decades = decades[::max(1, math.ceil(len(decades) / 3))]  # at most three a side
    ax_u.set_yticks([*(-(10.0 ** decades[::-1])), 0.0, *(10.0 ** decades)])
    ax_u.yaxis.set_minor_locator(NullLocator())
    span = u_U - u_X
    ax_u.set_xlim(max(lo, u_X - 0.8 * span), min(hi, u_U + 0.8 * span))
    ax_u.set_xlabel("Re u (dimensionless)")
    ax_u.set_ylabel("Im u (dimensionless)")
    ax_u.set_title("u plane: the grid and its mirror (dashed)")
    # the t plane: each sheet's rectangle, then the images
    for x0, x1, colour, width in ((0.0, 0.5 * T, REFERENCE, 1.4), (-0.5 * T, 0.0, CONTEXT, 1.0),
                                  (0.5 * T, T, CONTEXT, 1.0)):
        ax_t.plot([x0, x1, x1, x0, x0], [-0.5 * tau, -0.5 * tau, 0.5 * tau, 0.5 * tau,
                                         -0.5 * tau], color=colour, linewidth=width)
    ax_t.axhline(0.0, color=CONTEXT, linewidth=0.6, linestyle=":")
    for name, style in (("upper", "-"), ("lower", "--"), ("left", "--"), ("right", "--")):
        re, im = np.asarray(k[f"{name}_re"]), np.asarray(k[f"{name}_im"])
        for j, colour in enumerate(colours):
            ax_t.plot(re[j], im[j], color=colour, linewidth=1.0, linestyle=style,
                      alpha=1.0 if name in ("upper", "lower") else 0.55)
    corners = ((0.0, 0.0, "$u_X$", (4, -11)), (0.5 * T, 0.0, "$u_N$", (4, -11)),
               (0.5 * T, 0.5 * tau, "$u_U$", (4, 5)), (0.0, 0.5 * tau, "∞", (4, 5)))
    for x, y, name, offset in corners:
        ax_t.plot([x], [y], "o", color="k", markersize=4, zorder=5)
        ax_t.annotate(name, (x, y), textcoords="offset points", xytext=offset, fontsize=9)
    for x, words in ((0.25 * T, "sheet 1"), (-0.25 * T, "sheet 2\nvia $(-\\infty, u_X]$"),
                     (0.75 * T, "sheet 2\nvia $[u_N, u_U]$")):
        ax_t.text(x, 0.62 * tau, words, ha="center", va="bottom", fontsize=8, color="0.25")
    ax_t.set_xlim(-0.55 * T, 1.05 * T)
    ax_t.set_ylim(-0.62 * tau, 0.9 * tau)
    ax_t.set_xlabel("Re t [s]")
    ax_t.set_ylabel("Im t [s]")
    ax_t.set_title("t plane: the images")
    return fig
