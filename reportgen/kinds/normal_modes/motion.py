"""``reportgen animate`` for ``normal_modes``: each vibrational mode oscillating.

Frame by frame, drawn from the archive alone (``runs``, ``analysis``, the resolved
config); nothing is integrated or solved here.  The report imports this module lazily
(``Report.motion``), so matplotlib loads only to animate.
"""

from __future__ import annotations

import math

import numpy as np

from ...rendering.plots.motion import Motion
from ...rendering.plots.style import ATOM_COLOURS, CONTEXT, HIGHLIGHT, OTHER_ATOM, new_figure_grid
from ...scene.content import fmt
from .plots import _atom_sizes, _scaled


def motion(data, frames: int) -> Motion:
    """Each vibrational mode oscillating, x(t) = x₀ + η cos ωt, over two periods of each
    mode (the modes' own frequencies are in the panel titles)."""
    a = data.analysis
    z = int(a["n_zero_modes"])
    omega = np.asarray(a["frequencies"], dtype=float)[z:]
    phase = np.linspace(0, 4 * np.pi, frames, endpoint=False)  # loops without a seam
    if a["source"] == "molecule":
        pos = np.asarray(a["drawing"]["positions"], dtype=float)
        disps = list(np.asarray(a["drawing"]["displacements"], dtype=float))[:6]
        span = float(np.max(np.ptp(pos[:, :2], axis=0))) or 1.0
        ds = _scaled(disps, span, 0.25)
        k = len(ds)
        ncols = 2 if k == 4 else min(k, 3)
        views = []  # a mode mostly out of the drawing plane is seen from the side
        for d in ds:
            out_of_plane, in_plane = float(np.sum(d[:, 2] ** 2)), float(np.sum(d[:, 1] ** 2))
            side = out_of_plane > in_plane and out_of_plane > 1e-6 * float(np.sum(d * d))
            views.append([0, 2] if side else [0, 1])
        nrows = math.ceil(k / ncols)
        fig, axes = new_figure_grid(nrows, ncols, figsize=(3.0 * ncols, 2.6 * nrows + 0.3))
        elements = list(a["elements"])
        bonds = [tuple(b) for b in np.asarray(a["bonds"]).tolist()]
        sizes = _atom_sizes(a["masses"]) * 0.5
        pad = 0.45 * span
        movers = []
        for j, ax in enumerate(axes.ravel()):
            if j >= k:
                ax.set_visible(False)
                continue
            v = views[j]
            ax.set_xlim(pos[:, 0].min() - pad, pos[:, 0].max() + pad)
            ax.set_ylim(pos[:, v[1]].min() - pad, pos[:, v[1]].max() + pad)
            ax.set_aspect("equal")
            ax.axis("off")
            side = " (side view)" if v[1] == 2 else ""
            ax.set_title(f"ω{z + j + 1} = {fmt(float(omega[j]), 4)}{side}", fontsize=10)
            bond_lines = [ax.plot([], [], color=CONTEXT, lw=3, zorder=1)[0] for _ in bonds]
            atoms = ax.scatter(pos[:, 0], pos[:, v[1]], s=sizes, zorder=2, edgecolor="black",
                               color=[ATOM_COLOURS.get(e, OTHER_ATOM) for e in elements])
            movers.append((pos[:, v], ds[j][:, v], bond_lines, atoms))

        def update(f):
            c = math.cos(phase[f])
            for base, d, bond_lines, atoms in movers:
                xy = base + c * d
                atoms.set_offsets(xy)
                for line, (i, m) in zip(bond_lines, bonds, strict=True):
                    line.set_data([xy[i, 0], xy[m, 0]], [xy[i, 1], xy[m, 1]])

        return Motion(fig, update, "the molecule's vibrations")
    modes = np.asarray(a["modes"], dtype=float)[:, z:]
    shown = min(modes.shape[1], 4)
    fig, axes = new_figure_grid(shown, 1, figsize=(6.4, 1.5 * shown + 0.6), sharex=True)
    n = modes.shape[0]
    s = np.arange(1, n + 1)
    lines = []
    for j in range(shown):
        ax = axes[j, 0]
        ax.axhline(0, color=CONTEXT, lw=0.8)
        ax.set_ylim(-1.3, 1.3)
        ax.set_xlim(0, n + 1)
        ax.set_ylabel(f"ω{z + j + 1}\n{fmt(float(omega[j]), 3)}", rotation=0, ha="right",
                      va="center")
        lines.append((modes[:, j] / np.max(np.abs(modes[:, j])),
                      ax.plot([], [], "-o", color=HIGHLIGHT, ms=6)[0]))
    axes[-1, 0].set_xlabel("coordinate index")

    def update(f):
        c = math.cos(phase[f])
        for shape, line in lines:
            line.set_data(s, c * shape)

    return Motion(fig, update, "the normal modes oscillating")
