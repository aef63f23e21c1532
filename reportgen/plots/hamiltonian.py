"""Figures of a formula system: coordinates, configuration path, phase portrait, surface of
section, observables.  Axis labels are the config's own names (no units: a formula system
is in whatever units its author chose)."""

from __future__ import annotations

import numpy as np

from .common import envelope
from .style import CONTEXT, HIGHLIGHT, INK, PALETTE, new_figure, new_figure_grid

#: viridis (perceptually uniform, colour-blind safe) without its last yellows, which
#: vanish as small markers on white
FAMILY_COLOURMAP = ("viridis", 0.0, 0.85)
#: spans of the two plotted columns within this ratio are drawn at equal scales (a
#: section's closed curves then keep their shape)
EQUAL_SCALE_RATIO = 2.5


def coordinates(t, series: dict[str, np.ndarray]):
    """Each coordinate against time, one panel per coordinate (shared time axis)."""
    n = len(series)
    fig, axes = new_figure_grid(n, 1, figsize=(6.8, 1.2 + 1.5 * n), sharex=True)
    axes = axes[:, 0]
    for ax, (name, values), colour in zip(axes, series.items(), PALETTE, strict=False):
        ax.plot(*envelope(t, values), color=colour)
        ax.set_ylabel(name)
    axes[-1].set_xlabel("time t")
    return fig


def configuration(x, y, xname: str, yname: str):
    """The path in the plane of the first two coordinates."""
    fig, ax = new_figure(figsize=(5.6, 5.0))
    ax.plot(x, y, color=HIGHLIGHT, linewidth=0.8)
    ax.plot([x[0]], [y[0]], "o", color="black", markersize=5, label="start")
    ax.set_xlabel(xname)
    ax.set_ylabel(yname)
    ax.legend(loc="upper right")
    return fig


def phase_portrait(q, p, grid_q, grid_p, H, H0: float, qname: str, angle: bool = False):
    """Level curves of H on the grid, the run's level H0 and its orbit (an angle wrapped
    to (−π, π], the orbit broken where it wraps)."""
    fig, ax = new_figure(figsize=(6.4, 4.6))
    Q, P = np.meshgrid(grid_q, grid_p)
    finite = H[np.isfinite(H)]
    if finite.size:
        lo, hi = np.percentile(finite, [2, 90])
        levels = np.unique(np.concatenate([np.linspace(lo, hi, 14), [H0]]))
        ax.contour(Q, P, H, levels=levels, colors=CONTEXT, linewidths=0.7)
    q, p = np.asarray(q), np.asarray(p)
    if angle:
        q = np.pi - np.mod(np.pi - q, 2 * np.pi)
        jumps = np.nonzero(np.abs(np.diff(q)) > np.pi)[0] + 1
        for seg_q, seg_p in zip(np.split(q, jumps), np.split(p, jumps), strict=True):
            ax.plot(seg_q, seg_p, color=HIGHLIGHT, linewidth=2.0)
        ax.set_xlim(-np.pi, np.pi)
    else:
        ax.plot(q, p, color=HIGHLIGHT, linewidth=2.0)
    ax.plot([], [], color=HIGHLIGHT, linewidth=2.0, label=f"this run, H = {H0:.6g}")
    ax.plot([], [], color=CONTEXT, label="other levels of H")
    ax.set_xlabel(qname)
    ax.set_ylabel(f"p_{qname}")
    ax.legend(loc="upper right")
    return fig


def poincare(u, v, uname: str, vname: str):
    """The crossings of the surface of section as points."""
    fig, ax = new_figure(figsize=(5.8, 5.0))
    ax.plot(u, v, ".", color=HIGHLIGHT, markersize=2.5 if len(u) > 400 else 4.0)
    ax.set_xlabel(uname)
    ax.set_ylabel(vname)
    return fig


def poincare_family(u, v, member, colour, uname: str, vname: str, *, colour_label: str,
                    labels: dict[int, str] | None = None, edge=None, edge_label=None):
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
    # marker area [pt²]: dense sets smaller, so that islands stay apart (rasterized: the
    # file's size does not grow with the points)
    size = 6.0 if len(u) < 3000 else 3.0 if len(u) < 30000 else 1.2
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
    spans = np.ptp(u), np.ptp(v)
    if min(spans) > 0 and max(spans) / min(spans) <= EQUAL_SCALE_RATIO:
        ax.set_aspect("equal", adjustable="datalim")
    if labels is not None or edge is not None:
        ax.legend(loc="upper right", fontsize=8, markerscale=2.5)
    return fig


def observables(t, series: dict[str, np.ndarray]):
    """Observables that change, against time."""
    fig, ax = new_figure()
    for (name, values), colour in zip(series.items(), PALETTE, strict=False):
        ax.plot(*envelope(t, values), color=colour, label=name)
    ax.set_xlabel("time t")
    ax.set_ylabel("value")
    ax.legend(loc="best")
    return fig


def new_variables(t, series: dict[str, np.ndarray], integrated=None, first: str = ""):
    """The new canonical variables against time; the first of them also from integrating
    K (dashed), when given."""
    fig, ax = new_figure()
    for (name, values), colour in zip(series.items(), PALETTE, strict=False):
        ax.plot(*envelope(t, values), color=colour, label=name)
    if integrated is not None:
        ax.plot(*envelope(t, integrated), color="black", linestyle=(0, (3, 3)), linewidth=1.0,
                label=f"{first} from K")
    ax.set_xlabel("time t")
    ax.set_ylabel("new variables")
    ax.legend(loc="best")
    return fig
