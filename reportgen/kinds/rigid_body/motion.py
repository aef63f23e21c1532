"""``reportgen animate`` for ``rigid_body``: the body's attitude in space and its polhode.

Frame by frame, drawn from the archive alone (``runs``, ``analysis``, the resolved
config); nothing is integrated or solved here.  The report imports this module lazily
(``Report.motion``), so matplotlib loads only to animate.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from ...rendering.plots.motion import Motion, _clock, _columns, _cube_axes, frame_samples
from ...rendering.plots.style import CONTEXT, HIGHLIGHT, INK, REFERENCE, SEPARATRIX, SKY


def _rotation(q):
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


_BOX_EDGES = [(0, 1), (1, 3), (3, 2), (2, 0), (4, 5), (5, 7), (7, 6), (6, 4),
              (0, 4), (1, 5), (2, 6), (3, 7)]
_BOX_FACES = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4),
              (1, 3, 7, 5)]


def motion(data, frames: int) -> Motion:
    """Left: the body's attitude in space, a box with the inertia of the body (half-sides
    a_i ∝ √(I_j + I_k − I_i)) and its principal axes.  Right: ω in the body frame tracing
    its polhode on the angular-momentum sphere's intersection."""
    run = data.runs["main"]
    omega = np.column_stack(_columns(run, "omega_1", "omega_2", "omega_3"))
    quat = np.column_stack(_columns(run, "q_w", "q_x", "q_y", "q_z"))
    idx = frame_samples(len(run.t), frames)
    moments = np.asarray(data.analysis["principal_moments"], dtype=float)
    half = np.sqrt(np.maximum([moments[1] + moments[2] - moments[0],
                               moments[0] + moments[2] - moments[1],
                               moments[0] + moments[1] - moments[2]], 1e-12 * moments.max()))
    half = 0.75 * np.maximum(half / half.max(), 0.12)  # a plate keeps some thickness
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
    fig = Figure(figsize=(9.0, 4.6), layout="constrained")
    left = fig.add_subplot(1, 2, 1, projection="3d")
    right = fig.add_subplot(1, 2, 2, projection="3d")
    edges = [left.plot([], [], [], color=INK, lw=1.2)[0] for _ in _BOX_EDGES]
    faces = Poly3DCollection([corners[list(f)] for f in _BOX_FACES], facecolor=SKY,
                             edgecolor="none", alpha=0.35)
    left.add_collection3d(faces)
    colours = (REFERENCE, SEPARATRIX, HIGHLIGHT)
    axes_lines = [left.plot([], [], [], color=c, lw=2.2, label=f"axis {i + 1}")[0]
                  for i, c in enumerate(colours)]
    _cube_axes(left, 1.0)
    left.set_title("attitude in space")
    left.legend(loc="lower left", fontsize=8)
    scale = float(np.max(np.abs(omega))) or 1.0
    w = omega / scale
    right.plot(w[:, 0], w[:, 1], w[:, 2], color=CONTEXT, lw=0.8, alpha=0.6)
    trace, = right.plot([], [], [], color=HIGHLIGHT, lw=1.6)
    arrow, = right.plot([], [], [], color="black", lw=2)
    _cube_axes(right, 1.05)
    right.set_title("ω in the body frame (polhode)\naxes ω1, ω2, ω3 / max|ω|", fontsize=10)
    clock = _clock(left, run.t, idx)

    def update(k):
        j = idx[k]
        rot = _rotation(quat[j])
        pts = corners @ rot.T
        for line, (a, b) in zip(edges, _BOX_EDGES, strict=True):
            line.set_data_3d(*pts[[a, b]].T)
        faces.set_verts([pts[list(f)] for f in _BOX_FACES])
        for i, line in enumerate(axes_lines):
            end = rot[:, i] * 1.0
            line.set_data_3d([0, end[0]], [0, end[1]], [0, end[2]])
        trace.set_data_3d(w[:j + 1, 0], w[:j + 1, 1], w[:j + 1, 2])
        arrow.set_data_3d([0, w[j, 0]], [0, w[j, 1]], [0, w[j, 2]])
        clock(k)

    return Motion(fig, update, "the body's attitude and its polhode")
