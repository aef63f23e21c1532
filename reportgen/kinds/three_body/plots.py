"""Figures of the restricted three-body problem (this kind alone): the zero-velocity curves
with the forbidden region, the primaries and the Lagrange points, in the rotating frame."""

from __future__ import annotations

import numpy as np

from ...rendering.plots.style import (
    BLUE,
    CONTEXT,
    HIGHLIGHT,
    INK,
    ORANGE,
    new_figure,
    place_legend,
)

#: shade of the region the level C forbids
FORBIDDEN = "#d9d9d9"
#: stored samples of a track drawn at most (a long run is thinned evenly)
MAX_TRACK = 20000


def hill_regions(gx, gy, level, *, primaries, names, lagrange, track=None, starts=None,
                 length_unit="a", ax=None):
    """The plane of the rotating frame at one Jacobi constant C.

    Parameters
    ----------
    gx, gy : ndarray, shapes (nx,), (ny,)
        The grid; ``level`` (ny, nx) is 2Ω − C on it: negative where the level forbids
        the particle (shaded), zero on the zero-velocity curves (drawn).
    primaries : ((x1, y1), (x2, y2))
        The primaries' positions, drawn as discs named by ``names`` (larger first).
    lagrange : (x (5,), y (5,))
        L1 … L5, drawn as crosses with their names.
    track : (x, y), optional
        An orbit drawn over the regions.
    starts : (x0 min, x0 max), optional
        The segment of y = 0 where a family's orbits start.
    """
    from matplotlib.patches import Patch

    fig, ax = new_figure(ax, figsize=(6.4, 5.4))
    gx, gy, level = np.asarray(gx), np.asarray(gy), np.asarray(level)
    ax.contourf(gx, gy, level, levels=[float(np.min(level)) - 1.0, 0.0], colors=[FORBIDDEN])
    ax.contour(gx, gy, level, levels=[0.0], colors=INK, linewidths=0.9)
    handles = [Patch(facecolor=FORBIDDEN, edgecolor=INK, linewidth=0.9,
                     label="forbidden: 2Ω < C (edge: zero-velocity curve)")]
    if track is not None:
        x, y = (np.asarray(v) for v in track)
        step = max(1, len(x) // MAX_TRACK)
        handles += ax.plot(x[::step], y[::step], color=HIGHLIGHT, lw=0.5, label="the orbit")
    if starts is not None:
        handles += ax.plot(list(starts), [0.0, 0.0], color=BLUE, lw=3.0, solid_capstyle="butt",
                           label="where the orbits start (y = 0)")
    for (x, y), name, size, colour in zip(primaries, names, (9, 6), (ORANGE, CONTEXT),
                                          strict=True):
        handles += ax.plot([x], [y], "o", color=colour, mec=INK, ms=size, ls="none",
                           label=name)
    lx, ly = (np.asarray(v) for v in lagrange)
    handles += ax.plot(lx, ly, "x", color=INK, ms=6, mew=1.4, ls="none",
                       label="Lagrange points")
    for k, (x, y) in enumerate(zip(lx, ly, strict=True)):
        ax.annotate(f"L{k + 1}", (x, y), xytext=(4, 4 if y >= 0 else -11),
                    textcoords="offset points", fontsize=8, color=INK)
    ax.set_xlim(float(gx[0]), float(gx[-1]))
    ax.set_ylim(float(gy[0]), float(gy[-1]))
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel(f"x [{length_unit}]")
    ax.set_ylabel(f"y [{length_unit}]")
    place_legend(ax, handles=handles, fontsize=8, outside="above")
    return fig
