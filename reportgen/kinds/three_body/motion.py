"""``reportgen animate`` for ``three_body``: the three bodies' orbits in the x–y plane.

Frame by frame, drawn from the archive alone (``runs``, ``analysis``, the resolved
config); nothing is integrated or solved here.  The report imports this module lazily
(``Report.motion``), so matplotlib loads only to animate.
"""

from __future__ import annotations

from ...rendering.plots.motion import Motion, _columns, _trails


def motion(data, frames: int) -> Motion:
    run = data.runs["main"]
    bodies = [tuple(_columns(run, f"x{i}", f"y{i}")) for i in (1, 2, 3)]
    names = list(data.config.get("names") or ["body 1", "body 2", "body 3"])
    return _trails(data, frames, bodies, names, "three bodies (x–y plane)")
