"""``reportgen animate`` for ``fput``: the chain's displacements.

Frame by frame, drawn from the archive alone (``runs``, ``analysis``, the resolved
config); nothing is integrated or solved here.  The report imports this module lazily
(``Report.motion``), so matplotlib loads only to animate.
"""

from __future__ import annotations

import numpy as np

from ...rendering.plots.motion import Motion, _clock, frame_samples
from ...rendering.plots.style import CONTEXT, HIGHLIGHT, new_figure


def motion(data, frames: int) -> Motion:
    run = data.runs["main"]
    n = sum(1 for c in run.columns if c.startswith("q"))
    q = run.y[:, :n]
    idx = frame_samples(len(run.t), frames)
    fig, ax = new_figure(figsize=(7.2, 3.6))
    amp = float(np.max(np.abs(q))) or 1.0
    s = np.arange(0, n + 2)
    ax.set_xlim(-0.5, n + 1.5)
    ax.set_ylim(-1.25 * amp, 1.25 * amp)
    ax.axhline(0, color=CONTEXT, lw=0.8)
    line, = ax.plot([], [], "-o", color=HIGHLIGHT, ms=8, lw=1.2)
    ax.plot([0, n + 1], [0, 0], "s", color="black", ms=8)
    ax.set_xlabel("mass index (ends fixed)")
    ax.set_ylabel("displacement q")
    ax.set_title("Fermi–Pasta–Ulam–Tsingou chain")
    clock = _clock(ax, run.t, idx)

    def update(k):
        j = idx[k]
        line.set_data(s, np.r_[0.0, q[j], 0.0])
        clock(k)

    return Motion(fig, update, "the chain's displacements")
