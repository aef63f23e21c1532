"""``reportgen animate`` for ``three_body``: the three bodies' orbits in the x–y plane.

Frame by frame, drawn from the archive alone (``runs``, ``analysis``, the resolved
config); nothing is integrated or solved here.  The report imports this module lazily
(``Report.motion``), so matplotlib loads only to animate.
"""

from __future__ import annotations

from ...rendering.plots.motion import Motion, _columns, _trails


def motion(data, frames: int) -> Motion:
    run = data.runs["main"]
    restricted = getattr(data.config, "restricted", None)
    if restricted is not None:  # the particle in the rotating frame, the primaries at rest
        mu = float(restricted.mu)

        def primaries(ax):
            ax.plot([-mu, 1.0 - mu], [0.0, 0.0], "o", color="0.4", ms=6, ls="none")

        return _trails(data, frames, [tuple(_columns(run, "x", "y"))], ["particle"],
                       "restricted three-body problem (rotating frame)", extra=primaries)
    bodies = [tuple(_columns(run, f"x{i}", f"y{i}")) for i in (1, 2, 3)]
    names = list(data.config.get("names") or ["body 1", "body 2", "body 3"])
    return _trails(data, frames, bodies, names, "three bodies (x–y plane)")
