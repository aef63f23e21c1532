"""The motion of a scene, frame by frame, for ``reportgen animate``: the shared pieces.

A kind that animates overrides ``Report.motion(data, frames)`` with its own
``kinds/<kind>/motion.py``, which returns a :class:`Motion`: a figure and ``update(k)``,
which moves the figure's artists to frame ``k`` of ``frames``.  Here are the pieces
several kinds share: frames spread evenly over the archived run (:func:`frame_samples`),
the clock, the unit sphere, cubic 3D axes, planar trails and the phase plane.  Everything
drawn is read from the archive; nothing is integrated or solved here.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .style import CONTEXT, GREEN, HIGHLIGHT, REFERENCE, new_figure


@dataclass
class Motion:
    figure: object
    update: Callable[[int], None]
    label: str  # what the animation shows, for the command's output


def frame_samples(n_samples: int, frames: int) -> np.ndarray:
    """The run's sample index shown at each frame: spread evenly from first to last."""
    return np.rint(np.linspace(0, n_samples - 1, frames)).astype(int)


def _columns(run, *names):
    return [run.y[:, run.columns.index(n)] for n in names]


def _clock(ax, t, idx, unit="s"):
    write = getattr(ax, "text2D", ax.text)  # 3D axes place screen text with text2D
    text = write(0.02, 0.97, "", transform=ax.transAxes, va="top", ha="left", fontsize=10)

    def update(k):
        text.set_text(f"t = {t[idx[k]]:.3g} {unit}")

    return update


def _sphere(ax, alpha=0.25):
    u = np.linspace(0, 2 * np.pi, 25)
    v = np.linspace(0, np.pi, 13)
    ax.plot_wireframe(np.outer(np.cos(u), np.sin(v)), np.outer(np.sin(u), np.sin(v)),
                      np.outer(np.ones_like(u), np.cos(v)), color=CONTEXT, lw=0.4, alpha=alpha)


def _cube_axes(ax, r=1.05):
    ax.set_xlim(-r, r)
    ax.set_ylim(-r, r)
    ax.set_zlim(-r, r)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_zticks([])


def _trails(data, frames, bodies, names, title, extra=None) -> Motion:
    """Planar orbits drawn as they are traced: each body a dot with its trail."""
    run = data.runs["main"]
    idx = frame_samples(len(run.t), frames)
    fig, ax = new_figure(figsize=(5.6, 5.2))
    allx = np.concatenate([b[0] for b in bodies])
    ally = np.concatenate([b[1] for b in bodies])
    span = max(np.ptp(allx), np.ptp(ally)) or 1.0
    cx, cy = 0.5 * (allx.max() + allx.min()), 0.5 * (ally.max() + ally.min())
    ax.set_xlim(cx - 0.58 * span, cx + 0.58 * span)
    ax.set_ylim(cy - 0.58 * span, cy + 0.58 * span)
    ax.set_aspect("equal")
    if extra is not None:
        extra(ax)
    palette = (HIGHLIGHT, REFERENCE, GREEN)
    trails, dots = [], []
    for i, name in enumerate(names):
        colour = palette[i % len(palette)]
        trails.append(ax.plot([], [], color=colour, lw=1.2)[0])
        dots.append(ax.plot([], [], "o", color=colour, ms=7, label=name)[0])
    if len(names) > 1:
        ax.legend(loc="upper right", fontsize=8)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_title(title)
    clock = _clock(ax, run.t, idx)

    def update(k):
        j = idx[k]
        for (bx, by), trail, dot in zip(bodies, trails, dots, strict=True):
            trail.set_data(bx[:j + 1], by[:j + 1])
            dot.set_data([bx[j]], [by[j]])
        clock(k)

    return Motion(fig, update, "the orbit being traced")


def _phase_plane(ax, x, y, xlabel: str, ylabel: str):
    """The whole orbit in the phase plane, faint; returns the point that moves along it."""
    ax.plot(x, y, color=CONTEXT, lw=0.8)
    point, = ax.plot([], [], "o", color=HIGHLIGHT, ms=7)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title("phase plane")
    return point
