"""The motion of a scene, frame by frame, for ``reportgen animate``: drawn from the archive.

One function per kind, ``motion_<kind>(data, frames)`` -> :class:`Motion`: a figure and
``update(k)``, which moves the figure's artists to frame ``k`` of ``frames``.  Frames are
spread evenly over the archived run (or, for normal modes, over two periods of each
mode).  Everything drawn is read from the archive (``runs``, ``analysis``, the resolved
config); nothing is integrated or solved here.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from ...kinds.normal_modes.plots import _atom_sizes, _scaled
from .style import (
    ATOM_COLOURS,
    CONTEXT,
    GREEN,
    HIGHLIGHT,
    INK,
    OTHER_ATOM,
    REFERENCE,
    SEPARATRIX,
    SKY,
    new_figure,
    new_figure_grid,
)


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


# ------------------------------------------------------------------------------ kinds
def motion_heavy_top(data, frames: int) -> Motion:
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


def _rotation(q):
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


_BOX_EDGES = [(0, 1), (1, 3), (3, 2), (2, 0), (4, 5), (5, 7), (7, 6), (6, 4),
              (0, 4), (1, 5), (2, 6), (3, 7)]
_BOX_FACES = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4),
              (1, 3, 7, 5)]


def motion_rigid_body(data, frames: int) -> Motion:
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


def motion_central_force(data, frames: int) -> Motion:
    run = data.runs["main"]
    x, y = _columns(run, "x", "y")

    def centre(ax):
        ax.plot([0], [0], "*", color="black", ms=10)

    return _trails(data, frames, [(x, y)], ["particle"], "orbit (the force centre ★)", centre)


def motion_two_center(data, frames: int) -> Motion:
    run = data.runs["main"]
    x, y = _columns(run, "x", "y")
    a = float(data.config["params"]["a"])

    def centres(ax):
        ax.plot([-a, a], [0, 0], "*", color="black", ms=10)

    return _trails(data, frames, [(x, y)], ["particle"], "orbit about two fixed centres ★",
                   centres)


def motion_three_body(data, frames: int) -> Motion:
    run = data.runs["main"]
    bodies = [tuple(_columns(run, f"x{i}", f"y{i}")) for i in (1, 2, 3)]
    names = list(data.config.get("names") or ["body 1", "body 2", "body 3"])
    return _trails(data, frames, bodies, names, "three bodies (x–y plane)")


def _phase_plane(ax, x, y, xlabel: str, ylabel: str):
    """The whole orbit in the phase plane, faint; returns the point that moves along it."""
    ax.plot(x, y, color=CONTEXT, lw=0.8)
    point, = ax.plot([], [], "o", color=HIGHLIGHT, ms=7)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title("phase plane")
    return point


def motion_pendulum(data, frames: int) -> Motion:
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


def motion_oscillator(data, frames: int) -> Motion:
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


def motion_fput(data, frames: int) -> Motion:
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


def motion_normal_modes(data, frames: int) -> Motion:
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
            ax.set_title(f"ω{z + j + 1} = {omega[j]:.4g}{side}", fontsize=10)
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
        ax.set_ylabel(f"ω{z + j + 1}\n{omega[j]:.3g}", rotation=0, ha="right", va="center")
        lines.append((modes[:, j] / np.max(np.abs(modes[:, j])),
                      ax.plot([], [], "-o", color=HIGHLIGHT, ms=6)[0]))
    axes[-1, 0].set_xlabel("coordinate index")

    def update(f):
        c = math.cos(phase[f])
        for shape, line in lines:
            line.set_data(s, c * shape)

    return Motion(fig, update, "the normal modes oscillating")


MOTIONS = {
    "heavy_top": motion_heavy_top,
    "rigid_body": motion_rigid_body,
    "central_force": motion_central_force,
    "two_center": motion_two_center,
    "three_body": motion_three_body,
    "pendulum": motion_pendulum,
    "oscillator": motion_oscillator,
    "fput": motion_fput,
    "normal_modes": motion_normal_modes,
}
