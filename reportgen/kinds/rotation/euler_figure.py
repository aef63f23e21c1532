"""The notes' Figure 2, the Euler angles, drawn from the archive alone.

The fixed axes x, y, z and their xy plane, the body axes x′, y′, z′ after the rotation and
their x′y′ plane, the line of nodes N where the two planes meet, and the arcs of φ (about z,
from the fixed axis to N), θ (about N, from z to z′) and ψ (about z′, from N to the body
axis), each with an arrowhead for its sense: every point is read from ``/analysis/euler``
(``construction/<convention>`` and ``sketch``, :mod:`.euler_sketch`).

The sketch is a 2-D orthographic projection (a clean line drawing, as a textbook prints it)
seen from the first octant, z up: of the views tried, the one that keeps the labelled tips
(the axes, N and the arcs' middles) farthest apart.  Each label is then put beside its tip
where it covers no line and no other label, the axes' limits leaving room for it; the
layout is made for the size drawn (the report's, or that of ``reportgen figures --size``).
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrowPatch

from ...rendering.plots.layout import mark, requested
from ...rendering.plots.rigid_body import AXIS_COLOURS
from ...rendering.plots.style import CONTEXT, HIGHLIGHT, INK, SEPARATRIX
from ...scene.content import FigureSpec, fmt

#: the figure's size at report size [in] and its labels' size [pt]
SIZE = (5.0, 4.3)
FONT = 13.0
#: the views tried [deg]: the camera in the first octant, so that x points to the lower
#: left, y to the right and z up, as the textbook draws its axes
ELEVATIONS = (14.0, 20.0, 26.0, 32.0)
AZIMUTHS = tuple(float(a) for a in range(10, 85, 5))
#: a view scores the distance of its nearest two labelled points, or the drawn fraction of
#: its shortest axis over this, whichever is less: an axis seen nearly end on spoils a view
#: as much as two labels crowded together
FORESHORTENING = 2.0
#: the view preferred when others are no better (elevation, azimuth) [deg]
DEFAULT_VIEW = (20.0, 35.0)
#: lengths drawn: the fixed axes longer than the body axes (a rotation that leaves an
#: axis in place still shows both), the line of nodes between them
FIXED_LENGTH, BODY_LENGTH, NODE_LENGTH = 1.32, 1.0, 1.16
#: radii of the arcs of φ, θ, ψ (φ and ψ both touch N: at different radii)
ARC_RADII = {"arc_phi": 0.42, "arc_theta": 0.56, "arc_psi": 0.7}
#: an angle smaller than this [rad] (1°) has no arc to draw or label
SMALLEST_ARC = math.radians(1.0)
#: room kept around the drawing for the labels [in]
MARGIN = 0.42
#: the gap between a tip and its label [pt]
GAP = 3.0
#: how close a label's box may come to a line before it counts as covering it [pt]
CLEARANCE = 4.0
#: the label placements tried: turns [deg] from the preferred direction, distance factors
TURNS = (0.0, 30.0, -30.0, 60.0, -60.0, 90.0, -90.0, 125.0, -125.0, 180.0)
DISTANCES = (1.0, 1.7, 2.5)

CONVENTION = {"zxz": "z-x-z", "zyz": "z-y-z"}
#: the line of nodes is this intermediate axis of the convention
NODE_AXIS = {"zxz": "x", "zyz": "y"}


def _projection(elevation: float, azimuth: float) -> np.ndarray:
    """(2, 3): the screen's right and up unit vectors for a camera at ``elevation`` and
    ``azimuth`` [deg] (orthographic)."""
    e, a = math.radians(elevation), math.radians(azimuth)
    return np.array([[-math.sin(a), math.cos(a), 0.0],
                     [-math.sin(e) * math.cos(a), -math.sin(e) * math.sin(a), math.cos(e)]])


def _tips(c: dict) -> np.ndarray:
    """(m, 3): the points that carry labels: the fixed and body axes' tips, N's tip and
    the middles of the arcs."""
    body = np.asarray(c["body_axes"], dtype=float)
    arcs = [ARC_RADII[k] * np.asarray(c[k])[len(c[k]) // 2] for k in ARC_RADII]
    return np.vstack([FIXED_LENGTH * np.eye(3), BODY_LENGTH * body.T,
                      NODE_LENGTH * np.asarray(c["node"])[None], np.array(arcs)])


def best_view(c: dict) -> tuple[float, float]:
    """(elevation, azimuth) [deg] of the view that keeps the labelled points of the
    construction ``c`` farthest apart on the screen (the nearest pair's distance) and its
    axes least foreshortened (the shortest axis drawn, over :data:`FORESHORTENING`), the
    default view winning ties."""
    tips = _tips(c)
    axes = tips[:7] / np.linalg.norm(tips[:7], axis=1)[:, None]  # the axes and N, unit
    best, chosen = -math.inf, DEFAULT_VIEW
    for elevation in ELEVATIONS:
        for azimuth in AZIMUTHS:
            M = _projection(elevation, azimuth)
            p = tips @ M.T
            d = np.linalg.norm(p[:, None] - p[None], axis=-1)
            shortest = float(np.min(np.linalg.norm(axes @ M.T, axis=1)))
            score = min(float(np.min(d[np.triu_indices(len(p), 1)])),
                        shortest / FORESHORTENING)
            score -= 1e-4 * math.hypot(elevation - DEFAULT_VIEW[0], azimuth - DEFAULT_VIEW[1])
            if score > best:
                best, chosen = score, (elevation, azimuth)
    return chosen


def _limits(points: np.ndarray, inches: tuple[float, float]) -> tuple[tuple, tuple]:
    """x and y limits holding ``points`` (m, 2) with :data:`MARGIN` inches around, one
    scale for both directions (the axes fill the figure)."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    width, height = inches
    scale = min((width - 2 * MARGIN) / max(hi[0] - lo[0], 1e-9),
                (height - 2 * MARGIN) / max(hi[1] - lo[1], 1e-9))  # inches per unit
    centre = 0.5 * (lo + hi)
    half = 0.5 * np.array([width, height]) / scale
    return (centre[0] - half[0], centre[0] + half[0]), (centre[1] - half[1], centre[1] + half[1])


def _arrow(ax, start, end, colour, *, width, head=11.0, style="-|>", z=3):
    ax.add_patch(FancyArrowPatch(tuple(start), tuple(end), arrowstyle=style, color=colour,
                                 linewidth=width, mutation_scale=head, shrinkA=0, shrinkB=0,
                                 zorder=z))


def _place(ax, labels, lines: np.ndarray, font: float) -> None:
    """Each label (text, anchor (2,), preferred direction (2,), colour) beside its anchor,
    at the first of the placements tried that covers no label placed before, stays within
    the axes and covers the fewest points of ``lines`` (m, 2), all in data coordinates."""
    fig = ax.figure
    renderer = fig._get_renderer()
    to_screen = ax.transData
    frame = ax.bbox
    drawn = to_screen.transform(lines)
    placed = []  # (x0, y0, x1, y1) on the screen
    pad, clear = GAP * fig.dpi / 72.0, CLEARANCE * fig.dpi / 72.0
    for text, anchor, direction, colour in labels:
        t = ax.text(0.0, 0.0, text, ha="center", va="center", fontsize=font, color=colour,
                    zorder=6)
        box = t.get_window_extent(renderer)
        half = np.array([box.width, box.height]) / 2 + pad / 2
        at = to_screen.transform(np.asarray(anchor, dtype=float))
        preferred = np.asarray(direction, dtype=float)
        norm = float(np.linalg.norm(preferred))
        preferred = preferred / norm if norm > 1e-9 else np.array([1.0, 0.0])
        best, chosen = math.inf, at
        for rank, turn in enumerate(TURNS):
            a = math.radians(turn)
            d = np.array([preferred[0] * math.cos(a) - preferred[1] * math.sin(a),
                          preferred[0] * math.sin(a) + preferred[1] * math.cos(a)])
            for factor in DISTANCES:
                centre = at + d * factor * (pad + abs(d[0]) * half[0] + abs(d[1]) * half[1])
                x0, y0 = centre - half
                x1, y1 = centre + half
                cost = rank + 4.0 * (factor - 1.0)
                if x0 < frame.x0 or x1 > frame.x1 or y0 < frame.y0 or y1 > frame.y1:
                    cost += 1e4
                cost += 1e3 * sum(1 for (a0, b0, a1, b1) in placed
                                  if x0 < a1 and a0 < x1 and y0 < b1 and b0 < y1)
                inside = ((drawn[:, 0] > x0 - clear) & (drawn[:, 0] < x1 + clear)
                          & (drawn[:, 1] > y0 - clear) & (drawn[:, 1] < y1 + clear))
                cost += 20.0 * int(np.count_nonzero(inside))
                if cost < best:
                    best, chosen = cost, centre
        t.set_position(tuple(to_screen.inverted().transform(chosen)))
        placed.append((*(chosen - half), *(chosen + half)))


def _dense(points: np.ndarray, per_segment: int = 24) -> np.ndarray:
    """A polyline (m, 2) with points between its vertices (for the labels to avoid)."""
    s = np.linspace(0.0, 1.0, per_segment, endpoint=False)[:, None]
    segments = [points[i] + s * (points[i + 1] - points[i]) for i in range(len(points) - 1)]
    return np.vstack(segments + [points[-1:]])


def draw(construction: dict, sketch: dict, *, ax=None):
    """The notes' Figure 2 for one stored construction (``/analysis/euler/construction/
    <convention>``: ``body_axes`` (3, 3) columns, ``node`` (3,), ``arc_phi``, ``arc_theta``,
    ``arc_psi`` (m, 3) unit arcs) and ``sketch`` (``plane``, ``body_plane`` (k, 3) unit
    circles, ``convention``).  Drawn at :data:`SIZE`, or at the size asked for by
    ``reportgen figures``."""
    size = requested()
    inches = size.inches(SIZE) if size is not None else SIZE
    font = size.font(FONT) if size is not None else FONT
    scale = font / FONT
    if ax is None:
        fig = Figure(figsize=inches)
        ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    fig = ax.figure
    c = construction
    M = _projection(*best_view(c))

    def p(v):
        return np.asarray(v, dtype=float) @ M.T

    body = np.asarray(c["body_axes"], dtype=float).T  # rows: x′, y′, z′
    node = np.asarray(c["node"], dtype=float)
    plane, body_plane = p(sketch["plane"]), p(sketch["body_plane"])
    fixed_tips, body_tips = p(FIXED_LENGTH * np.eye(3)), p(BODY_LENGTH * body)
    node_line = p(np.stack([-NODE_LENGTH * node, NODE_LENGTH * node]))
    arcs = {k: p(ARC_RADII[k] * np.asarray(c[k], dtype=float))
            for k, angle in zip(ARC_RADII, sketch["angles"], strict=True)
            if abs(float(angle)) >= SMALLEST_ARC}
    everything = np.vstack([plane, body_plane, fixed_tips, body_tips, node_line, [[0, 0]]])
    xlim, ylim = _limits(everything, inches)
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_axis_off()

    ax.fill(*plane.T, color=CONTEXT, alpha=0.13, linewidth=0, zorder=0)
    ax.fill(*body_plane.T, color=AXIS_COLOURS[2], alpha=0.09, linewidth=0, zorder=0)
    ax.plot(*plane.T, color=CONTEXT, linewidth=0.9 * scale, zorder=1)
    ax.plot(*body_plane.T, color=AXIS_COLOURS[2], linewidth=0.9 * scale, alpha=0.7, zorder=1)
    ax.plot(*node_line.T, color=SEPARATRIX, linestyle=(0, (5, 3)), linewidth=1.7 * scale,
            zorder=2)
    for tip in fixed_tips:
        _arrow(ax, (0, 0), tip, INK, width=1.0 * scale, head=10 * scale)
    for tip, colour in zip(body_tips, AXIS_COLOURS, strict=True):
        _arrow(ax, (0, 0), tip, colour, width=2.2 * scale, head=13 * scale, z=4)
    lines = [plane, body_plane, node_line, *([np.zeros(2), t] for t in fixed_tips),
             *([np.zeros(2), t] for t in body_tips)]
    for arc in arcs.values():
        ax.plot(*arc.T, color=HIGHLIGHT, linewidth=1.8 * scale, zorder=5)
        if np.sum(np.linalg.norm(np.diff(arc, axis=0), axis=1)) > 0.08:  # room for a head
            _arrow(ax, arc[-3], arc[-1], HIGHLIGHT, width=1.2 * scale, head=11 * scale, z=5)
        lines.append(arc)
    ax.plot([0.0], [0.0], "o", color=INK, markersize=3.0 * scale, zorder=6)

    # (text, anchor, preferred direction: away from the origin, colour)
    labels = [(f"${a}$", tip, tip, INK) for a, tip in zip("xyz", fixed_tips, strict=True)]
    labels += [(f"${a}'$", tip, tip, colour)
               for a, tip, colour in zip("xyz", body_tips, AXIS_COLOURS, strict=True)]
    labels.append(("$N$", node_line[1], node_line[1], SEPARATRIX))
    for k, symbol in (("arc_phi", r"\varphi"), ("arc_theta", r"\theta"), ("arc_psi", r"\psi")):
        if k not in arcs:
            continue
        middle = arcs[k][len(arcs[k]) // 2]
        labels.append((f"${symbol}$", middle, middle, HIGHLIGHT))
    _place(ax, labels, np.vstack([_dense(np.asarray(line)) for line in lines]), font)
    if size is not None:
        mark(fig, size)
    return fig


def caption(sketch: dict, given: str, given_angles) -> str:
    """The figure's caption, every case chosen by the stored facts: the sketch's
    convention (``sketch/convention``), its angles' signs, and whether they are the angles
    given (the ``euler`` group's ``convention``) or converted from them."""
    conv = str(sketch["convention"])
    phi, theta, psi = (float(v) for v in sketch["angles"])
    k = NODE_AXIS[conv]
    named = (f"the {CONVENTION[conv]} convention of notes (9.17), R₃(ψ)R₁(θ)R₃(φ)"
             if conv == "zxz" else
             f"the {CONVENTION[conv]} convention (the Euler angles of notes (9.17) are z-x-z)")
    text = (f"The Euler angles of notes Fig. 2, drawn for this scene's rotation in {named}: "
            f"φ = {_deg(phi)} about z takes the {k} axis to the line of nodes N (dashed), "
            f"θ = {_deg(theta)} about N takes z to z′, and ψ = {_deg(psi)} about z′ takes N "
            f"to {k}′. ")
    text += ("These are the angles as given. " if given == conv else
             f"The scene gives its Euler angles in {CONVENTION.get(given, given)} form, "
             f"({', '.join(_deg(float(a)) for a in given_angles)}); these are the same "
             "rotation's, converted. ")
    text += ("Grey: the fixed axes x, y, z and their xy plane; blue, green, purple: the body "
             "axes x′, y′, z′ and their x′y′ plane, which meets the xy plane along N.")
    angles = tuple(zip("φθψ", (phi, theta, psi), strict=True))
    small = [s for s, v in angles if abs(v) < SMALLEST_ARC]
    negative = [s for s, v in angles if v <= -SMALLEST_ARC]
    if negative:
        text += (f" {' and '.join(negative)} {'is' if len(negative) == 1 else 'are'} negative "
                 "here: the arrowhead shows the turn clockwise, seen from the tip of its axis.")
    if small:
        text += (f" {' and '.join(small)} {'is' if len(small) == 1 else 'are'} below 1°: "
                 "no arc drawn.")
    return text


def _deg(angle: float) -> str:
    return f"{fmt(math.degrees(angle))}°"


def figures(euler: dict) -> list[FigureSpec]:
    """The notes' Figure 2 of the ``/analysis/euler`` group (none for an archive without
    its ``sketch``)."""
    sketch = euler.get("sketch")
    if sketch is None:
        return []
    fig = draw(euler["construction"][str(sketch["convention"])], sketch)
    return [FigureSpec(name="notes_figure_2", figure=fig,
                       caption=caption(sketch, str(euler["convention"]), euler["path"][0]))]
