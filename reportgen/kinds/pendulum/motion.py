"""``reportgen animate`` for ``pendulum``: the swinging pendulum and its phase point.

Frame by frame, drawn from the archive alone (``runs``, ``analysis``, the resolved
config); nothing is integrated or solved here.  The report imports this module lazily
(``Report.motion``), so matplotlib loads only to animate.
"""

from __future__ import annotations

import math

import numpy as np

from ...rendering.plots.motion import Motion, _clock, _columns, _phase_plane, frame_samples
from ...rendering.plots.style import CONTEXT, HIGHLIGHT, INK, new_figure_grid


def motion(data, frames: int) -> Motion:
    run = data.runs["main"]
    theta, theta_dot = _columns(run, "theta", "theta_dot")
    idx = frame_samples(len(run.t), frames)
    fig, axes = new_figure_grid(1, 2, figsize=(8.4, 4.0))
    swing, phase = axes[0]
    swing.set_xlim(-1.2, 1.2)
    swing.set_ylim(-1.2, 1.2)
    swing.set_aspect("equal")
    swing.axis("off")
    ring = np.linspace(0, 2 * np.pi, 121)
    swing.plot(np.cos(ring), np.sin(ring), color=CONTEXT, lw=0.6, alpha=0.5)
    swing.plot([0], [0], "s", color="black", ms=5)
    rod, = swing.plot([], [], color=INK, lw=2)
    bob, = swing.plot([], [], "o", color=HIGHLIGHT, ms=14)
    swing.set_title("the pendulum")
    point = _phase_plane(phase, theta, theta_dot, "θ [rad]", "dθ/dt [rad/s]")
    clock = _clock(swing, run.t, idx)

    def update(k):
        j = idx[k]
        bx, by = math.sin(theta[j]), -math.cos(theta[j])
        rod.set_data([0, bx], [0, by])
        bob.set_data([bx], [by])
        point.set_data([theta[j]], [theta_dot[j]])
        clock(k)

    return Motion(fig, update, "the swinging pendulum and its phase point")
