"""``reportgen animate`` for ``oscillator``: the mass on its spring and its phase point.

Frame by frame, drawn from the archive alone (``runs``, ``analysis``, the resolved
config); nothing is integrated or solved here.  The report imports this module lazily
(``Report.motion``), so matplotlib loads only to animate.
"""

from __future__ import annotations

import numpy as np

from ...rendering.plots.motion import Motion, _clock, _columns, _phase_plane, frame_samples
from ...rendering.plots.style import HIGHLIGHT, INK, new_figure_grid


def motion(data, frames: int) -> Motion:
    run = data.runs["main"]
    q, p = _columns(run, "q", "p")
    idx = frame_samples(len(run.t), frames)
    fig, axes = new_figure_grid(1, 2, figsize=(8.4, 4.0))
    mass, phase = axes[0]
    amp = float(np.max(np.abs(q))) or 1.0
    mass.set_xlim(-2.2 * amp, 1.6 * amp)
    mass.set_ylim(-1, 1)
    mass.set_yticks([])
    mass.plot([-2.0 * amp, -2.0 * amp], [-0.5, 0.5], color="black", lw=3)  # the wall
    spring, = mass.plot([], [], color=INK, lw=1.2)
    block, = mass.plot([], [], "s", color=HIGHLIGHT, ms=22)
    mass.set_xlabel("q")
    mass.set_title("mass on a spring")
    point = _phase_plane(phase, q, p, "q", "p")
    phase.set_aspect("equal", adjustable="datalim")
    clock = _clock(mass, run.t, idx)
    coils = np.linspace(0, 1, 61)

    def update(k):
        j = idx[k]
        start, end = -2.0 * amp, q[j]
        xs = start + coils * (end - start)
        ys = 0.25 * np.sin(coils * 16 * np.pi)
        spring.set_data(xs, ys)
        block.set_data([end], [0])
        point.set_data([q[j]], [p[j]])
        clock(k)

    return Motion(fig, update, "the oscillator and its phase point")
