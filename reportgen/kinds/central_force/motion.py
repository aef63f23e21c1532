"""``reportgen animate`` for ``central_force``: the orbit about the force centre.

Frame by frame, drawn from the archive alone (``runs``, ``analysis``, the resolved
config); nothing is integrated or solved here.  The report imports this module lazily
(``Report.motion``), so matplotlib loads only to animate.
"""

from __future__ import annotations

from ...rendering.plots.motion import Motion, _columns, _trails


def motion(data, frames: int) -> Motion:
    run = data.runs["main"]
    x, y = _columns(run, "x", "y")

    def centre(ax):
        ax.plot([0], [0], "*", color="black", ms=10)

    return _trails(data, frames, [(x, y)], ["particle"], "orbit (the force centre ★)", centre)
