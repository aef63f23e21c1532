"""Figures of the rotation kind: a vector turned about an axis (textbook ex. 4.5), Euler
angles with the line of nodes, the stereographic projection and Möbius maps.

They draw what they are given: every point, arc and curve is computed in
:mod:`reportgen.core.rotations` and read from the archive."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ...rendering.plots.rigid_body import AXIS_COLOURS
from ...rendering.plots.style import (
    CONTEXT,
    HIGHLIGHT,
    REFERENCE,
    SEPARATRIX,
    legend_below,
    new_figure,
    place_legend,
)
from ...scene.content import fmt

#: Euler-angle convention names as printed
CONVENTION = {"zxz": "z-x-z", "zyz": "z-y-z"}
#: the half-width of the ζ-plane window [1]: |Re ζ|, |Im ζ| ≤ this
PLANE_WINDOW = 3.0
#: at most this many sample points carry markers (more would hide the circles)
PLANE_MARKERS = 32


def _axes_lines(ax, axes, labels, *, colours, length=1.0, style="-", width=1.0, alpha=1.0):
    """Unit vectors (columns of ``axes``) from the origin, each with its label."""
    for k in range(3):
        v = length * np.asarray(axes)[:, k]
        ax.plot([0, v[0]], [0, v[1]], [0, v[2]], color=colours[k], linestyle=style,
                linewidth=width, alpha=alpha)
        ax.text(*(1.1 * v), labels[k], color=colours[k], fontsize=12)


def _frame_3d(ax, lim, *, elev=22, azim=35, centre=(0.0, 0.0, 0.0), zoom=1.2):
    """A schematic 3-D view: equal scales about ``centre``, no panes or ticks (the axes are
    drawn as lines)."""
    for set_lim, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre, strict=True):
        set_lim(c - lim, c + lim)
    ax.set_box_aspect((1, 1, 1), zoom=zoom)
    ax.view_init(elev=elev, azim=azim)
    ax.set_axis_off()


def _fit(points) -> tuple[np.ndarray, float]:
    """Centre and half-width of the cube around everything drawn, (m, 3) points."""
    p = np.asarray(points, dtype=float)
    lo, hi = p.min(axis=0), p.max(axis=0)
    return 0.5 * (lo + hi), 0.5 * float(np.max(hi - lo))


def _oblique_azimuth(normals, *, elev=20.0, band=(35.0, 72.0), start=-60.0) -> float:
    """The azimuth [deg], nearest to ``start`` (matplotlib's usual view), from which every
    unit vector of ``normals`` (m, 3) is seen between ``band`` degrees from the line of
    sight: an axis foreshortened but not end-on, circles about it open ellipses rather
    than lines.  ``start`` if there is none."""
    steps = np.arange(0.0, 180.0, 5.0)
    az = np.radians(start + np.stack([steps, -steps], axis=-1).ravel())
    e = np.radians(elev)
    sight = np.stack([np.cos(e) * np.cos(az), np.cos(e) * np.sin(az),
                      np.full_like(az, np.sin(e))], axis=-1)
    cosines = np.abs(sight @ np.atleast_2d(np.asarray(normals, dtype=float)).T)
    angle = np.degrees(np.arccos(np.clip(cosines, 0.0, 1.0)))
    fits = np.all((angle >= band[0]) & (angle <= band[1]), axis=1)
    return float(np.degrees(az[np.argmax(fits)])) if fits.any() else start


def axis_angle(axis, angle, vector, turned, goldstein, arc, circle, centre, turned_axes, *,
               ax=None):
    """The textbook's rotation R(n, Φ) (textbook ex. 4.5) on one vector, with Goldstein's
    passive A r (Goldstein (4.62)) beside it.

    axis : (3,) unit n; angle : Φ [rad]; vector, turned, goldstein : (3,) r, R r and A r;
    arc : (m, 3) r turned by 0 … Φ; circle : (k, 3) by 0 … 2π; centre : (3,) n (n·r);
    turned_axes : (3, 3) rows e′_i = R e_i, the axes turned by +Φ.  Drawn in units of |r|.
    """
    fig, ax = new_figure(ax, figsize=(5.6, 4.4), projection="3d")
    size = float(np.linalg.norm(vector))
    n = np.asarray(axis, dtype=float)
    _axes_lines(ax, size * np.eye(3), ("x", "y", "z"), colours=(CONTEXT,) * 3, width=1.0)
    _axes_lines(ax, 1.2 * size * np.asarray(turned_axes).T, ("x′", "y′", "z′"),
                colours=AXIS_COLOURS, style="--", width=0.9)
    ax.plot(*np.stack([-0.5 * size * n, 1.4 * size * n]).T, color="black", linewidth=1.6,
            label="axis n")
    ax.text(*(1.5 * size * n), "n", color="black", fontsize=12)
    ax.plot(*np.asarray(circle).T, color=CONTEXT, linestyle=":", linewidth=1.0)
    ax.plot(*np.asarray(arc).T, color=HIGHLIGHT, linewidth=2.2,
            label=f"r turned by 0 … Φ = {fmt(np.degrees(angle), 4)}°")
    c = np.asarray(centre)
    for tip in (vector, turned):
        ax.plot(*np.stack([c, tip]).T, color=CONTEXT, linewidth=0.8)
    # Rᵀ in mathtext: the figure font has no superscript T
    goldstein_label = r"$A\,r = R^{\mathrm{T}} r$ (Goldstein (4.62))"
    for tip, colour, name, width in ((vector, REFERENCE, "r", 2.2),
                                     (turned, HIGHLIGHT, "R r (textbook ex. 4.5)", 2.2),
                                     (goldstein, SEPARATRIX, goldstein_label, 1.2)):
        ax.quiver(0, 0, 0, *tip, color=colour, arrow_length_ratio=0.1, linewidth=width,
                  label=name)
    ax.scatter(*c, color="black", s=12, depthshade=False)
    ax.plot([], [], color=AXIS_COLOURS[0], linestyle="--", linewidth=0.9,
            label="axes turned by +Φ")
    drawn = np.concatenate([np.zeros((1, 3)), size * np.eye(3), 1.2 * size * np.asarray(
        turned_axes), size * np.stack([-0.5 * n, 1.5 * n]), np.asarray(circle)])
    centre, half = _fit(drawn)
    _frame_3d(ax, 0.8 * half, azim=_oblique_azimuth(n), centre=centre, zoom=1.0)
    legend_below(fig)
    return fig


def euler_constructions(constructions: dict, order):
    """One panel per convention: space axes, the line of nodes, body axes and the arcs of
    φ, θ, ψ (from :func:`reportgen.core.rotations.euler_construction`)."""
    fig = Figure(figsize=(8.6, 4.4), layout="constrained")
    t = np.linspace(0.0, 2 * np.pi, 121)
    for i, conv in enumerate(order):
        ax = fig.add_subplot(1, len(order), i + 1, projection="3d")
        c = constructions[conv]
        body = np.asarray(c["body_axes"])
        _axes_lines(ax, np.eye(3), ("x", "y", "z"), colours=(CONTEXT,) * 3, width=0.9)
        _axes_lines(ax, body, ("x′", "y′", "z′"), colours=AXIS_COLOURS, width=2.0)
        ax.plot(np.cos(t), np.sin(t), 0 * t, color=CONTEXT, linewidth=0.6, alpha=0.7)
        plane = np.cos(t)[:, None] * body[:, 0] + np.sin(t)[:, None] * body[:, 1]
        ax.plot(*plane.T, color=AXIS_COLOURS[2], linewidth=0.6, alpha=0.7)
        node = np.asarray(c["node"])
        ax.plot(*np.stack([-1.05 * node, 1.05 * node]).T, color=SEPARATRIX, linestyle="--",
                linewidth=1.6, label="line of nodes")
        ax.text(*(1.1 * node), "N", color=SEPARATRIX, fontsize=12)
        # each arc at its own radius, its label at its own place along it, so that φ and ψ
        # (both ending or starting at the node) stay apart
        for name, label, radius, where in (("arc_phi", "φ", 0.62, 0.3),
                                           ("arc_theta", "θ", 0.5, 0.5),
                                           ("arc_psi", "ψ", 0.4, 0.8)):
            arc = radius * np.asarray(c[name])
            ax.plot(*arc.T, color=HIGHLIGHT, linewidth=1.6)
            ax.text(*(1.25 * arc[int(where * (len(arc) - 1))]), label, color=HIGHLIGHT,
                    fontsize=12, bbox={"facecolor": "white", "edgecolor": "none", "pad": 0.3,
                                       "alpha": 0.8})
        ax.set_title(f"{CONVENTION[conv]}" + (" (given)" if i == 0 else " (same rotation)"))
        _frame_3d(ax, 0.85, elev=20, azim=40)
        if i == 0:
            ax.legend(loc="upper left", fontsize=9)
    return fig


def _globe(ax, *, n_meridians=8, latitudes=(-0.75, -0.4, 0.0, 0.4, 0.75)):
    """A light globe: a few meridians and circles of latitude (vector lines, cheap)."""
    t = np.linspace(0.0, 2 * np.pi, 73)
    for lon in np.linspace(0.0, np.pi, n_meridians // 2, endpoint=False):
        ax.plot(np.cos(lon) * np.sin(t), np.sin(lon) * np.sin(t), np.cos(t), color=CONTEXT,
                linewidth=0.4, alpha=0.6)
    for z in latitudes:
        r = np.sqrt(1 - z * z)
        ax.plot(r * np.cos(t), r * np.sin(t), np.full_like(t, z), color=CONTEXT,
                linewidth=0.4, alpha=0.6)


def stereographic(s: dict, *, markers: int = PLANE_MARKERS):
    """Left: the sphere with sample points, their images R(U) x, a circle of latitude and
    its image, the rotation axis, the pole N and its image.  Right: the ζ plane with the
    projected points, their Möbius images and the projections of the rotated points; the
    circle and its image; M_U(∞), the image of the pole.

    ``s`` holds the arrays of ``/analysis/stereographic`` (points, images, plane,
    plane_mobius, plane_rotated, circle, circle_image, circle_plane, circle_plane_mobius,
    su2_axis, pole, pole_image, pole_image_plane).  Every k-th sample point is drawn, at
    most ``markers`` of them.
    """
    fig = Figure(figsize=(9.0, 4.6), layout="constrained")
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    _globe(ax)
    x, images = np.asarray(s["points"]), np.asarray(s["images"])
    every = max(1, -(-len(x) // markers))
    ax.plot(*x[::every].T, ".", color=REFERENCE, markersize=4, label="points x")
    ax.plot(*images[::every].T, ".", color=HIGHLIGHT, markersize=4, label="R(U) x")
    ax.plot(*np.asarray(s["circle"]).T, color=REFERENCE, linewidth=2.0)
    ax.plot(*np.asarray(s["circle_image"]).T, color=HIGHLIGHT, linewidth=2.0)
    n = np.asarray(s["su2_axis"])
    ax.plot(*np.stack([-1.3 * n, 1.3 * n]).T, color="black", linewidth=1.4,
            label="axis of R(U)")
    pole, pole_image = np.asarray(s["pole"]), np.asarray(s["pole_image"])
    ax.scatter(*pole, color="black", marker="^", s=36, depthshade=False)
    ax.text(*(1.12 * pole), "N", fontsize=11)
    ax.scatter(*pole_image, color=HIGHLIGHT, marker="*", s=90, depthshade=False,
               label="R(U) N")
    normals = [[0.0, 0.0, 1.0], pole_image]  # of the circle and of its image
    _frame_3d(ax, 0.9, elev=18, azim=_oblique_azimuth(normals, elev=18.0), zoom=1.1)
    ax.legend(loc="upper left", fontsize=9)

    ax = fig.add_subplot(1, 2, 2)
    w = PLANE_WINDOW
    t = np.linspace(0.0, 2 * np.pi, 121)
    ax.plot(np.cos(t), np.sin(t), color=CONTEXT, linestyle="--", linewidth=0.8,
            label="equator, |ζ| = 1")
    plane, mob, rot = (np.asarray(s[k])[::every] for k in ("plane", "plane_mobius",
                                                          "plane_rotated"))
    ax.plot(*plane.T, "o", color=REFERENCE, markersize=3.0, label="ζ = π(x)")
    ax.plot(*mob.T, "o", color=HIGHLIGHT, markersize=7.0, markerfacecolor="none",
            markeredgewidth=0.9, label=r"$M_U(\zeta) = (a\zeta + b)/(\bar a - \bar b\zeta)$")
    ax.plot(*rot.T, ".", color=HIGHLIGHT, markersize=3.5, label="π(R(U) x)")
    ax.plot(*np.asarray(s["circle_plane"]).T, color=REFERENCE, linewidth=2.0)
    ax.plot(*np.asarray(s["circle_plane_mobius"]).T, color=HIGHLIGHT, linewidth=2.0)
    ax.plot(*np.asarray(s["pole_image_plane"]), "*", color=HIGHLIGHT, markersize=12,
            label=r"$M_U(\infty)$ = π(R(U) N)")
    ax.set_xlim(-w, w)
    ax.set_ylim(-w, w)
    ax.set_aspect("equal")
    ax.set_xlabel("Re ζ (dimensionless)")
    ax.set_ylabel("Im ζ (dimensionless)")
    place_legend(ax, loc="lower left", outside="right", fontsize=8, framealpha=0.95)
    return fig
