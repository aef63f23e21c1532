"""Figures of the rigid body: polhodes on the angular-momentum sphere and on the inertia
ellipsoid, Poinsot's construction (the ellipsoid on the invariable plane, the herpolhode),
the inertia ellipsoid of a body, the intermediate-axis flip.

They draw what they are given: every curve (polhode family, separatrices, ellipsoid
surface, herpolhode, growth envelope) is computed in :mod:`reportgen.core` and read from
the archive."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .style import (
    BLUE,
    CONTEXT,
    GREEN,
    HIGHLIGHT,
    PURPLE,
    RC,
    REFERENCE,
    SEPARATRIX,
    SKY,
    new_figure,
    place_legend,
)

AXIS_COLOURS = (BLUE, GREEN, PURPLE)
#: the herpolhode (the curve in space), apart from the polhode (the curve on the body)
HERPOLHODE = SKY
_SUBSCRIPT_DIGITS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def _moment(axis: int | None) -> str:
    """The principal moment of body axis ``axis`` (1, 2 or 3) as printed on a figure,
    "I₂"; without an axis, the intermediate one in words."""
    if axis is None:
        return "the intermediate moment"
    return "I" + str(int(axis)).translate(_SUBSCRIPT_DIGITS)


def polhodes(family, separatrices, track, *, intermediate=None, ax=None):
    """Polhodes on the unit angular-momentum sphere (body frame): a family, the
    separatrices and the scene's own, all given as unit vectors L/|L|.

    family : ndarray, shape (K, n, 3) — curves of a range of energies (grey).
    separatrices : ndarray, shape (S, n, 3) — S = 2, or 0 for a symmetric body.
    track : ndarray, shape (N, 3) — the run's body-frame L/|L|.
    intermediate : the body axis (1, 2 or 3) of the intermediate moment, named in the
    separatrices' legend entry.
    """
    fig, ax = _figure_3d(ax)
    u, v = np.mgrid[0:2 * np.pi:40j, 0:np.pi:20j]
    ax.plot_wireframe(np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v), color=CONTEXT,
                      linewidth=0.3, alpha=0.35, rasterized=True)
    for k, c in enumerate(family):
        ax.plot(c[:, 0], c[:, 1], c[:, 2], color=CONTEXT, linewidth=0.9,
                label="polhodes of other energies (same |L|)" if k == 0 else None)
    for k, c in enumerate(separatrices):
        ax.plot(c[:, 0], c[:, 1], c[:, 2], color=SEPARATRIX, linewidth=1.6,
                label=f"separatrices (2E = L²/{_moment(intermediate)})" if k == 0 else None)
    track = np.asarray(track, dtype=float)
    ax.plot(track[:, 0], track[:, 1], track[:, 2], color=HIGHLIGHT, linewidth=2.4,
            label="this scene's polhode")
    ax.scatter(*track[0], color=HIGHLIGHT, s=30, depthshade=False)
    _principal_axes_3d(ax, np.diag([1.25, 1.25, 1.25]), ("1", "2", "3"))
    ax.set_xlabel("L₁/|L|")
    ax.set_ylabel("L₂/|L|")
    ax.set_zlabel("L₃/|L|")
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=22, azim=35)
    ax.legend(loc="upper left")
    return fig


def _figure_3d(ax=None, figsize=(6.4, 5.6)):
    """(fig, ax): the given 3-D axes, or a new figure with one 3-D axes in a fixed box (a
    layout engine would measure every text twice per save) and no grid lines (the curves
    are the picture; 3-D grid lines cost a quarter of the drawing)."""
    if ax is None:
        fig = Figure(figsize=figsize)
        ax = fig.add_axes((0.04, 0.0, 0.92, 0.92), projection="3d")
    ax.grid(False)
    ax.locator_params(nbins=4)
    return ax.figure, ax


def _principal_axes_3d(ax, half_axes, labels):
    """Dotted lines along the body axes, ±``half_axes[:, k]``, labelled at the + end."""
    for k in range(3):
        d = np.asarray(half_axes)[:, k]
        ax.plot([-d[0], d[0]], [-d[1], d[1]], [-d[2], d[2]], color=AXIS_COLOURS[k],
                linewidth=1.0, linestyle=":")
        ax.text(*(1.08 * d), labels[k], color=AXIS_COLOURS[k])


def polhodes_on_ellipsoid(surface, semi_axes, family, separatrices, track, *,
                          intermediate=None, ax=None):
    """Polhodes on the energy ellipsoid ω·Iω = 2T (body frame, [rad/s]).

    surface : (n_u, n_v, 3) the ellipsoid; semi_axes : (3,) √(2T/I_k);
    family : (K, n, 3) polhodes of a ladder of L² (grey); separatrices : (S, n, 3),
    L² = 2T·I_mid (S = 0 for a symmetric body); track : (N, 3) the run's body-frame ω;
    intermediate : the body axis (1, 2 or 3) of I_mid, named in the legend.
    """
    fig, ax = _figure_3d(ax)
    surface = np.asarray(surface, dtype=float)
    ax.plot_wireframe(surface[..., 0], surface[..., 1], surface[..., 2], color=CONTEXT,
                      linewidth=0.3, alpha=0.45)
    for k, c in enumerate(family):
        ax.plot(c[:, 0], c[:, 1], c[:, 2], color=CONTEXT, linewidth=0.9,
                label="polhodes of other L² (same 2T)" if k == 0 else None)
    for k, c in enumerate(separatrices):
        ax.plot(c[:, 0], c[:, 1], c[:, 2], color=SEPARATRIX, linewidth=1.6,
                label=f"separatrices (L² = 2T·{_moment(intermediate)})" if k == 0 else None)
    track = np.asarray(track, dtype=float)
    ax.plot(track[:, 0], track[:, 1], track[:, 2], color=HIGHLIGHT, linewidth=2.4,
            label="this scene's polhode")
    ax.scatter(*track[0], color=HIGHLIGHT, s=30, depthshade=False)
    semi = np.asarray(semi_axes, dtype=float)
    _principal_axes_3d(ax, np.diag(1.25 * semi), ("1", "2", "3"))
    lim = 1.15 * semi
    ax.set_xlim(-lim[0], lim[0])
    ax.set_ylim(-lim[1], lim[1])
    ax.set_zlim(-lim[2], lim[2])
    # true shape (the same scale on the three axes), shrunk so a tall box keeps its labels
    ax.set_box_aspect(lim, zoom=min(1.0, np.sqrt(max(lim[0], lim[1]) / lim[2])))
    ax.set_xlabel("ω₁ [rad/s]")
    ax.set_ylabel("ω₂ [rad/s]")
    ax.set_zlabel("ω₃ [rad/s]")
    ax.view_init(elev=22, azim=35)
    ax.legend(loc="upper left")
    return fig


def poinsot(surface, half_axes, polhode, herpolhode, plane_height, *, circle_radius=None,
            contact_time=None, figsize=(8.4, 4.6)):
    """Poinsot's construction, in the frame (e1, e2, e3 = −L/|L|) of the invariable plane,
    units of x = ω/√(2T) [1/√(kg m²)]: left, the inertia ellipsoid resting on the plane
    z = ``plane_height`` with the polhode on it and the herpolhode on the plane; right,
    the plane seen along L.

    surface : (n_u, n_v, 3) the ellipsoid at the drawn instant; half_axes : (3, 3) column
    k the semi-axis vector of body axis k; polhode : (N, 3) the body track carried by the
    attitude of that instant; herpolhode : (N, 3) the space-frame tip of x, ending at the
    contact point; circle_radius : closed-form herpolhode radius (symmetric body), drawn
    dashed on the plane view; contact_time : the instant drawn [s], named in the legend.
    """
    # fixed panel boxes: a layout engine would measure every text twice per save
    fig = Figure(figsize=figsize)
    ax3 = fig.add_axes((0.0, 0.13, 0.52, 0.78), projection="3d", computed_zorder=False)
    ax2 = fig.add_axes((0.635, 0.24, 0.345, 0.64))
    surface = np.asarray(surface, dtype=float)
    her = np.asarray(herpolhode, dtype=float)
    pol = np.asarray(polhode, dtype=float)
    reach = max(float(np.max(np.hypot(her[:, 0], her[:, 1]))),
                float(np.max(np.hypot(surface[..., 0], surface[..., 1]))))
    h = 1.1 * reach
    ax3.plot_surface(np.array([[-h, h], [-h, h]]), np.array([[-h, -h], [h, h]]),
                     np.full((2, 2), plane_height), color=REFERENCE, alpha=0.08,
                     edgecolor=REFERENCE, linewidth=0.6, zorder=0)
    ax3.plot_wireframe(surface[..., 0], surface[..., 1], surface[..., 2], color=CONTEXT,
                       linewidth=0.3, alpha=0.6, zorder=1)
    ax3.plot(her[:, 0], her[:, 1], her[:, 2], color=HERPOLHODE, linewidth=1.2, zorder=2,
             label="herpolhode (on the plane)")
    ax3.plot([0.0, 0.0], [0.0, 0.0], [0.0, plane_height], color="k", linewidth=1.0,
             linestyle="--", zorder=3, label="L (normal to the plane)")
    for k in range(3):
        d = np.asarray(half_axes)[:, k]
        ax3.plot([-d[0], d[0]], [-d[1], d[1]], [-d[2], d[2]], color=AXIS_COLOURS[k],
                 linewidth=1.0, linestyle=":", zorder=3)
    ax3.plot(pol[:, 0], pol[:, 1], pol[:, 2], color=HIGHLIGHT, linewidth=1.8, zorder=4,
             label="polhode (on the body)")
    ax3.scatter(*her[-1], color="k", s=18, depthshade=False, zorder=5)
    ax3.set_xlim(-h, h)
    ax3.set_ylim(-h, h)
    top = float(np.max(surface[..., 2]))
    ax3.set_zlim(plane_height, top)
    ax3.set_box_aspect((2 * h, 2 * h, top - plane_height), zoom=1.15)
    ax3.set_axis_off()
    ax3.view_init(elev=16, azim=-55)
    ax2.plot(her[:, 0], her[:, 1], color=HERPOLHODE, linewidth=1.6)
    if circle_radius is not None:  # dashed over the herpolhode: it shows where they part
        phi = np.linspace(0.0, 2 * np.pi, 181)
        ax2.plot(circle_radius * np.cos(phi), circle_radius * np.sin(phi), color=REFERENCE,
                 linestyle=(0, (4, 3)), linewidth=1.0, label="closed-form circle")
    ax2.plot(her[0, 0], her[0, 1], "o", color=HERPOLHODE, markersize=5, label="start")
    contact = ("contact point" if contact_time is None
               else f"contact at t = {contact_time:.4g} s")
    ax2.plot(her[-1, 0], her[-1, 1], "o", color="k", markersize=4, label=contact)
    ax2.plot(0.0, 0.0, "+", color="k", markersize=12, label="foot of L")
    ax2.set_aspect("equal", adjustable="datalim")
    ax2.set_xlabel("x·e₁ [1/√(kg m²)]")
    ax2.set_ylabel("x·e₂ [1/√(kg m²)]")
    for x, title in ((0.26, "inertia ellipsoid on the invariable plane"),
                     (0.8, "herpolhode: the plane seen along L")):
        fig.text(x, 0.93, title, ha="center", fontsize=RC["axes.titlesize"])
    handles, labels = ax3.get_legend_handles_labels()
    more = ax2.get_legend_handles_labels()
    fig.legend(handles + more[0], labels + more[1], loc="lower center", ncol=4,
               fontsize=9, frameon=False)
    return fig


def flips(t, omega, *, envelope=None, ax=None):
    """ω components against time and (optionally) the linear growth envelope δ0 e^{γt} of
    the perturbation about the intermediate axis, shape (N,) like ``t``, drawn while it
    stays below 1.2 max |ω|."""
    fig, ax = new_figure(ax, figsize=(7.0, 4.0))
    for k in range(3):
        ax.plot(t, omega[:, k], color=AXIS_COLOURS[k], label=f"ω{k + 1}")
    if envelope is not None:
        env = np.asarray(envelope)
        keep = env < 1.2 * np.max(np.abs(omega))
        ax.plot(t[keep], env[keep], "--", color=CONTEXT,
                label="perturbation ∝ exp(γt), γ from notes (10.14)")
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("body-frame ω [rad/s]")
    place_legend(ax, loc="upper right", ncols=2)
    return fig


def symmetric_precession(t, omega, axis: int, Omega: float, *, figsize=(8.4, 3.9)):
    """The symmetric body's transverse ω⊥ = ω_b + i ω_c (b, c the axes after the figure
    axis ``axis``, 1-based, in cyclic order) as integrated: left, its tip in the body
    plane with the closed-form circle |ω⊥| = |ω⊥(0)| and the sense it turns; right, its
    unwrapped phase against time over the line φ(0) − Ωt of (10.10).

    t : (N,) [s]; omega : (N, 3) body-frame ω [rad/s]; Omega : Ω [rad/s]."""
    from .style import new_figure_grid

    s = int(axis) - 1
    b, c = (s + 1) % 3, (s + 2) % 3
    t = np.asarray(t, dtype=float)
    omega = np.asarray(omega, dtype=float)
    wb, wc = omega[:, b], omega[:, c]
    fig, axes = new_figure_grid(1, 2, figsize=figsize)
    ax, axp = axes[0, 0], axes[0, 1]
    r = float(np.hypot(wb[0], wc[0]))
    phi = np.linspace(0.0, 2 * np.pi, 181)
    ax.plot(wb, wc, color=HIGHLIGHT, linewidth=2.0, label="integrated")
    ax.plot(r * np.cos(phi), r * np.sin(phi), color=REFERENCE, linestyle=(0, (4, 3)),
            linewidth=1.0, label="|ω⊥| = |ω⊥(0)|")
    ax.plot(wb[0], wc[0], "o", color="k", markersize=5, label="t = 0")
    # the sense of turning: an arrow a tenth of a turn along the closed form from t = 0
    phase0 = float(np.arctan2(wc[0], wb[0]))
    turn = -np.sign(Omega) * 0.6
    ax.annotate("", xy=(r * np.cos(phase0 + turn), r * np.sin(phase0 + turn)),
                xytext=(r * np.cos(phase0), r * np.sin(phase0)),
                arrowprops={"arrowstyle": "->", "color": "k", "linewidth": 1.2,
                            "connectionstyle": f"arc3,rad={0.3 * np.sign(turn)}"})
    ax.set_aspect("equal", adjustable="box")  # its limits are fixed
    lim = 1.25 * r
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_xlabel(f"ω{b + 1} [rad/s]")
    ax.set_ylabel(f"ω{c + 1} [rad/s]")
    angle = np.unwrap(np.arctan2(wc, wb))
    axp.plot(t, angle, color=HIGHLIGHT, linewidth=2.0, label="phase of ω⊥ integrated")
    axp.plot(t, angle[0] - Omega * t, color=REFERENCE, linestyle=(0, (4, 3)),
             linewidth=1.2, label=f"φ(0) − Ωt, Ω = {Omega:.4g} rad/s".replace("-", "−"))
    axp.set_xlabel("time t [s]")
    axp.set_ylabel("phase of ω⊥ [rad]")
    place_legend(ax, loc="center", fontsize=8)  # inside the circle, clear of it
    place_legend(axp)
    return fig


def inertia_ellipsoid(moments, axes, surface, semi_axes, *, points=None, masses=None,
                      ax=None):
    """The inertia ellipsoid Σ I_k x_k² = 1 with its principal axes.

    moments : (3,) principal moments [kg m²] (legend); axes : (3, 3) lab-frame principal
    axes (columns); surface : (n_u, n_v, 3) lab-frame points of the ellipsoid;
    semi_axes : (3,) 1/√I_k; points, masses : a point set drawn scaled into the ellipsoid.
    """
    fig, ax = new_figure(ax, figsize=(6.0, 5.6), projection="3d")
    m = np.asarray(moments, dtype=float)
    semi = np.asarray(semi_axes, dtype=float)
    lab = np.asarray(surface, dtype=float)
    # a shaded body with its mesh: a flat-filled outline of a prolate ellipsoid seen
    # side-on reads as a tilted disc; the curved mesh lines show the third dimension
    ax.plot_surface(lab[..., 0], lab[..., 1], lab[..., 2], color=REFERENCE, alpha=0.22,
                    linewidth=0, shade=True, rasterized=True)
    _rings_about_long_axis(ax, np.asarray(axes, dtype=float), semi)
    for k in range(3):
        d = np.asarray(axes)[:, k] * semi[k] * 1.25
        ax.plot([-d[0], d[0]], [-d[1], d[1]], [-d[2], d[2]], color=AXIS_COLOURS[k],
                linewidth=2.0, label=f"axis {k + 1}: I = {m[k]:.4g} kg m²")
    if points is not None:
        p = np.asarray(points, dtype=float)
        p = p - np.average(p, axis=0, weights=masses)
        scale = semi.max() / max(np.linalg.norm(p, axis=1).max(), 1e-300)
        w = np.asarray(masses, dtype=float)
        ax.scatter(*(scale * p).T, s=40 * w / w.max(), color=HIGHLIGHT, depthshade=False,
                   label=f"masses (scaled ×{scale:.3g})")
    lim = semi.max() * 1.3
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_zlim(-lim, lim)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x [1/√(kg m²)]")
    ax.set_ylabel("y [1/√(kg m²)]")
    ax.set_zlabel("z [1/√(kg m²)]")
    ax.view_init(*ellipsoid_view(axes, semi))
    ax.legend(loc="upper left")
    return fig


def _rings_about_long_axis(ax, axes, semi, n_rings: int = 7, n_meridians: int = 6):
    """Circles of latitude and meridians of the ellipsoid (semi-axes ``semi`` along the
    columns of ``axes``) about its longest axis: a cigar then reads as a cigar, where
    rings about a short axis seen end-on look like a disc."""
    order = np.argsort(semi)
    e_long, e_a, e_b = (axes[:, k] for k in (order[2], order[0], order[1]))
    s_long, s_a, s_b = semi[order[2]], semi[order[0]], semi[order[1]]
    phi = np.linspace(0.0, 2 * np.pi, 121)
    for z in np.linspace(-0.85, 0.85, n_rings):
        r = np.sqrt(1.0 - z * z)
        pts = (z * s_long * e_long[:, None] + r * (s_a * np.cos(phi) * e_a[:, None]
                                                   + s_b * np.sin(phi) * e_b[:, None]))
        ax.plot(*pts, color=CONTEXT, linewidth=0.5, alpha=0.8)
    for ang in np.arange(n_meridians) * np.pi / n_meridians:
        across = s_a * np.cos(ang) * e_a + s_b * np.sin(ang) * e_b
        pts = s_long * np.cos(phi) * e_long[:, None] + np.sin(phi) * across[:, None]
        ax.plot(*pts, color=CONTEXT, linewidth=0.5, alpha=0.8)


def ellipsoid_view(axes, semi_axes) -> tuple[float, float]:
    """(elevation, azimuth) [deg] of a view that shows an ellipsoid's shape: looking
    mostly along its shortest semi-axis, so the longest and the middle one lie across the
    view (looking down the long axis of a prolate body shows a circle), tilted a little
    toward the middle one so it still reads as a solid; from above (z ≥ 0) when the
    direction allows.  ``axes`` (3, 3): the semi-axes' directions as columns."""
    axes = np.asarray(axes, dtype=float)
    semi = np.asarray(semi_axes, dtype=float)
    order = np.argsort(semi)  # shortest, middle, longest
    short, middle = axes[:, order[0]], axes[:, order[1]]
    # two equal short semi-axes (a prolate body): any direction across the long axis is
    # as good, so turn within that plane too; otherwise keep the view mostly along the
    # shortest semi-axis, tilted 15°–40° toward the middle one
    prolate = np.isclose(semi[order[0]], semi[order[1]], rtol=1e-6)
    tilts = np.radians(np.arange(0.0, 360.0, 5.0) if prolate else
                       np.concatenate([np.arange(15.0, 41.0, 5.0),
                                       -np.arange(15.0, 41.0, 5.0)]))
    long_axis = axes[:, order[2]]
    # not prolate: a little of the long axis may come in too, to take the camera off a
    # lab axis (an octahedron's principal axes are the lab axes)
    leans = (0.0,) if prolate else (0.0, 0.25, -0.25, 0.45, -0.45)
    best, best_cost = None, np.inf
    for tilt, lean in ((tilt, lean) for tilt in tilts for lean in leans):
        view = np.cos(tilt) * short + np.sin(tilt) * middle + lean * long_axis
        view /= np.linalg.norm(view)
        if view[2] < 0:
            view = -view
        elevation = float(np.degrees(np.arcsin(np.clip(view[2], -1.0, 1.0))))
        azimuth = float(np.degrees(np.arctan2(view[1], view[0])))
        # a camera from high above or square along a lab axis stacks the tick labels of
        # the axis it looks along: prefer a moderate elevation, an azimuth off the axes
        off_axis = min(abs((azimuth % 90.0) - 0.0), abs((azimuth % 90.0) - 90.0))
        cost = (abs(elevation - 25.0) + 2.0 * max(0.0, 15.0 - off_axis)
                + 0.1 * abs(np.degrees(tilt) - 27.0 * np.sign(np.degrees(tilt) or 1.0))
                + 20.0 * abs(lean))
        if cost < best_cost:
            best, best_cost = (elevation, azimuth), cost
    return best


def impulse_paths(t, point_path, cm_path, L_space, *, point_name="apex", exact=None,
                  snapshots: int = 7, figsize=(8.6, 4.4)):
    """The struck point's path in space after the blow and the centre of mass's straight
    line [m]: left, in 3-D with the body's line from the centre of mass to the point at a
    few instants; right, both seen along L (projected on the plane ⊥ L through the start
    of the centre of mass), first axis along the drift V.

    t : (N,) [s]; point_path, cm_path : (N, 3) space frame [m]; L_space : (3,) the
    space-frame angular momentum (any length); exact : (N, 3) the closed-form path,
    drawn dashed, or None."""
    point_path = np.asarray(point_path, dtype=float)
    cm_path = np.asarray(cm_path, dtype=float)
    fig = Figure(figsize=figsize)
    ax3 = fig.add_axes((0.0, 0.12, 0.5, 0.8), projection="3d")
    ax2 = fig.add_axes((0.6, 0.25, 0.37, 0.62))
    ax3.grid(False)
    ax3.locator_params(nbins=4)
    ax3.plot(*point_path.T, color=HIGHLIGHT, linewidth=1.1, label=f"{point_name}")
    ax3.plot(*cm_path.T, color="k", linewidth=1.6, label="centre of mass")
    for k, n in enumerate(np.linspace(0, len(t) - 1, snapshots).astype(int)):
        seg = np.array([cm_path[n], point_path[n]])
        ax3.plot(*seg.T, color=CONTEXT, linewidth=1.0,
                 label=f"centre of mass to {point_name}" if k == 0 else None)
    ax3.scatter(*point_path[0], color=HIGHLIGHT, s=16, depthshade=False)
    ax3.scatter(*cm_path[0], color="k", s=16, depthshade=False)
    lo = np.minimum(point_path.min(axis=0), cm_path.min(axis=0))
    hi = np.maximum(point_path.max(axis=0), cm_path.max(axis=0))
    span = np.maximum(hi - lo, 0.05 * float(np.max(hi - lo)))
    mid = 0.5 * (hi + lo)
    for set_lim, c, s in zip((ax3.set_xlim, ax3.set_ylim, ax3.set_zlim), mid, span,
                             strict=True):
        set_lim(c - 0.55 * s, c + 0.55 * s)
    # each axis stretched to its data (the caption says so): a drift of a few tenths
    # under a body of metres would be a sliver at equal scales
    ax3.set_box_aspect((1.4, 1.0, 1.0), zoom=0.85)
    ax3.set_xlabel("x [m]")
    ax3.set_ylabel("y [m]")
    ax3.set_zlabel("z [m]")
    ax3.view_init(elev=20, azim=-60)
    # the plane ⊥ L: e1 along the drift's part in it, e2 = L̂ × e1
    n = np.asarray(L_space, dtype=float)
    n = n / np.linalg.norm(n)
    drift = cm_path[-1] - cm_path[0]
    e1 = drift - (drift @ n) * n
    if np.linalg.norm(e1) < 1e-12 * max(1.0, float(np.linalg.norm(drift))):
        e1 = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 = e1 / np.linalg.norm(e1)
    e2 = np.cross(n, e1)

    def plane(r):
        d = np.asarray(r) - cm_path[0]
        return d @ e1, d @ e2

    ax2.plot(*plane(point_path), color=HIGHLIGHT, linewidth=1.8, label=point_name)
    if exact is not None:
        ax2.plot(*plane(exact), color=REFERENCE, linestyle=(0, (4, 3)), linewidth=0.9,
                 label="closed form")
    ax2.plot(*plane(cm_path), color="k", linewidth=1.6, label="centre of mass, V t")
    x0, y0 = plane(point_path[:1])
    ax2.plot(x0, y0, "o", color=HIGHLIGHT, markersize=4)
    ax2.plot(0.0, 0.0, "o", color="k", markersize=4)
    ax2.set_aspect("equal", adjustable="datalim")
    ax2.set_xlabel("along the drift [m]")
    ax2.set_ylabel("across the drift [m]")
    for x, title in ((0.25, "in space"), (0.785, "seen along L")):
        fig.text(x, 0.93, title, ha="center", fontsize=RC["axes.titlesize"])
    handles, labels = ax3.get_legend_handles_labels()
    more = ax2.get_legend_handles_labels()
    seen = set(labels)
    for h, lab in zip(*more, strict=True):
        if lab not in seen and lab != point_name and not lab.startswith("centre of mass"):
            handles.append(h)
            labels.append(lab)
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=9, frameon=False)
    return fig
