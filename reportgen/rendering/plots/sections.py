"""A surface of section built from many orbits (the family figure of a sweep whose members
cross a section: ``hamiltonian`` and ``two_center``)."""

from __future__ import annotations

import numpy as np

from .style import CONTEXT, INK, PALETTE, new_figure

#: viridis (perceptually uniform, colour-blind safe) without its last yellows, which
#: vanish as small markers on white
FAMILY_COLOURMAP = ("viridis", 0.0, 0.85)
#: spans of the two plotted columns within this ratio are drawn at equal scales (a
#: section's closed curves then keep their shape)
EQUAL_SCALE_RATIO = 2.5
#: most predicted curves drawn (evenly picked among the orbits); more would fill the plane
MAX_CURVES = 60


def poincare_family(u, v, member, colour, uname: str, vname: str, *, colour_label: str,
                    labels: dict[int, str] | None = None, edge=None, edge_label=None,
                    curves=None, curves_label=None, lines=None, marker_size=None,
                    legend_below=False):
    """The crossings of many orbits on one surface of section, each orbit in its own colour.

    Parameters
    ----------
    u, v : ndarray, shape (P,)
        The crossings' two plotted columns.
    member : ndarray of int, shape (P,)
        The orbit (sweep member) of each crossing.
    colour : ndarray, shape (M,)
        The value each member's colour is keyed to (its swept value).
    labels : dict of member -> str, optional
        Few orbits: a legend with these labels instead of a colour bar.
    edge : (u grid, v grid, H on the grid, E), optional
        The level H = E drawn as the edge of the allowed region.
    curves : (u grid, v grid, G on the grid, levels), optional
        The curves G = level, one per orbit (at most ``MAX_CURVES``), drawn thin under
        the points: where an integral of the motion puts each orbit's crossings.
    lines : list of (u value, label), optional
        Lines u = value drawn dotted (where the section is singular, say), if in view.
    marker_size : float, optional
        Marker area [pt²]; default: smaller for denser sets.
    legend_below : bool
        The legend under the axes (where curves fill the plane up to its corners) instead
        of in their upper right corner.
    """
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import ListedColormap, Normalize

    fig, ax = new_figure(figsize=(6.4, 5.4))
    u, v, member = np.asarray(u), np.asarray(v), np.asarray(member, dtype=np.int64)
    colour = np.asarray(colour, dtype=float)
    name, start, stop = FAMILY_COLOURMAP
    cmap = ListedColormap(colormaps[name](np.linspace(start, stop, 256)))
    drawn = np.unique(member)
    lo, hi = float(np.min(colour[drawn])), float(np.max(colour[drawn]))
    norm = Normalize(lo, hi if hi > lo else lo + 1.0)
    if curves is not None:
        gu, gv, G, levels = curves
        levels = np.unique(np.asarray(levels, dtype=float))
        if len(levels) > MAX_CURVES:
            levels = levels[np.linspace(0, len(levels) - 1, MAX_CURVES).round().astype(int)]
        ax.contour(gu, gv, G, levels=levels, colors=CONTEXT, linewidths=0.4, alpha=0.8,
                   zorder=0.9)  # under the points (collections: 1)
        ax.plot([], [], color=CONTEXT, linewidth=0.8, label=curves_label)
    # marker area [pt²]: dense sets smaller, so that islands stay apart (rasterized: the
    # file's size does not grow with the points)
    size = marker_size or (6.0 if len(u) < 3000 else 3.0 if len(u) < 30000 else 1.2)
    if labels is not None:
        for i, colour_i in zip(drawn, PALETTE, strict=False):
            pick = member == i
            ax.scatter(u[pick], v[pick], s=2 * size, color=colour_i, marker=".",
                       linewidths=0, rasterized=True, label=labels.get(int(i), str(i)))
    else:
        ax.scatter(u, v, c=colour[member], cmap=cmap, norm=norm, s=size, marker=".",
                   linewidths=0, rasterized=True)
        fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=ax, label=colour_label,
                     shrink=0.85)
    if edge is not None:
        gu, gv, H, energy = edge
        ax.contour(gu, gv, H, levels=[energy], colors=INK, linewidths=0.8)
        ax.plot([], [], color=INK, linewidth=0.8, label=edge_label)
    ax.set_xlabel(uname)
    ax.set_ylabel(vname)
    shown = False
    low, high = float(np.min(u)), float(np.max(u))
    margin = 0.05 * (high - low)
    for value, label in lines or []:
        if low - margin < value < high + margin:
            ax.axvline(value, color=INK, linewidth=0.8, linestyle=":",
                       label=None if shown else label)
            shown = True
    spans = np.ptp(u), np.ptp(v)
    if min(spans) > 0 and max(spans) / min(spans) <= EQUAL_SCALE_RATIO:
        ax.set_aspect("equal", adjustable="box")  # the limits fit the data at any size
    if legend_below and (labels is not None or edge is not None or curves is not None
                         or shown):
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, fontsize=8,
                  markerscale=2.5, frameon=False)
    elif labels is not None or edge is not None or curves is not None or shown:
        ax.legend(loc="upper right", fontsize=8, markerscale=2.5)
    return fig
