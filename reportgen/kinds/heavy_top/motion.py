"""``reportgen animate`` for ``heavy_top``: the heavy top's axis on the unit sphere.

Frame by frame, drawn from the archive alone (``runs``, ``analysis``, the resolved
config); nothing is integrated or solved here.  The report imports this module lazily
(``Report.motion``), so matplotlib loads only to animate.
"""

from __future__ import annotations

import numpy as np

from ...rendering.plots.motion import Motion, _clock, _columns, _cube_axes, _sphere, frame_samples
from ...rendering.plots.style import HIGHLIGHT, REFERENCE, new_figure


def motion(data, frames: int) -> Motion:
    """The symmetry axis on the unit sphere, its trace growing, between the turning
    circles θ1, θ2 when the archive holds them."""
    run = data.runs["main"]
    x, y, z = _columns(run, "axis_x", "axis_y", "axis_z")
    idx = frame_samples(len(run.t), frames)
    fig, ax = new_figure(figsize=(5.2, 5.2), projection="3d")
    _sphere(ax)
    phi = np.linspace(0, 2 * np.pi, 121)
    a = data.analysis
    for key in ("theta1", "theta2"):
        if key in a and np.isfinite(float(a[key])):
            th = float(a[key])
            ax.plot(np.sin(th) * np.cos(phi), np.sin(th) * np.sin(phi),
                    np.full_like(phi, np.cos(th)), "--", color=REFERENCE, lw=1)
    trace, = ax.plot([], [], [], color=HIGHLIGHT, lw=1.4)
    rod, = ax.plot([], [], [], color="black", lw=2.5)
    tip, = ax.plot([], [], [], "o", color=HIGHLIGHT, ms=6)
    _cube_axes(ax)
    ax.view_init(elev=22, azim=-60)
    ax.set_title("symmetry axis of the top on the unit sphere")
    clock = _clock(ax, run.t, idx)

    def update(k):
        j = idx[k]
        trace.set_data_3d(x[:j + 1], y[:j + 1], z[:j + 1])
        rod.set_data_3d([0, x[j]], [0, y[j]], [0, z[j]])
        tip.set_data_3d([x[j]], [y[j]], [z[j]])
        clock(k)

    return Motion(fig, update, "the top's axis on the sphere")
