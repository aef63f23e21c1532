"""Figures of the gravitation scenes: orbits, effective potentials, apsides, elliptic grids."""

from __future__ import annotations

import numpy as np

from .style import (
    BLUE,
    CONTEXT,
    GREEN,
    GREY,
    HIGHLIGHT,
    INK,
    ORANGE,
    REFERENCE,
    SEPARATRIX,
    legend_below,
    new_figure,
    new_figure_grid,
    place_legend,
)

BODY_COLOURS = (ORANGE, BLUE, GREY)  # Sun, Earth, Moon
#: line styles of the bodies where colour shows time
BODY_STYLES = ("-", (0, (4, 2)), (0, (1, 1.5)))


def length_label(name: str, unit: str) -> str:
    """An axis label of a length: "x [AU]", or "x (dimensionless)" in scaled units."""
    return f"{name} [{unit}]" if unit else f"{name} (dimensionless)"


def _equal_box(ax, length_unit):
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{length_unit}]")
    ax.set_ylabel(f"y [{length_unit}]")


def relative_orbit(x, y, *, reference=None, pericentres=None, lrl=None, length_unit="m",
                   lrl_label="LRL direction", ax=None):
    """The relative orbit r(t) with the force centre, optional exact orbit, pericentres, LRL
    (its legend entry ``lrl_label``, the caller's words with its length)."""
    fig, ax = new_figure(ax, figsize=(6.4, 5.2))
    if reference is not None:
        ax.plot(reference[0], reference[1], color=REFERENCE, linestyle=(0, (4, 3)), lw=1.2,
                label="Kepler's equation (exact)")
    ax.plot(x, y, color=HIGHLIGHT, lw=1.0, label="integrated r = r1 − r2")
    ax.plot([0], [0], marker="+", color="k", ms=10, mew=1.5, ls="none", label="r = 0")
    ax.plot([x[0]], [y[0]], marker="o", color=HIGHLIGHT, ms=5, ls="none", label="start")
    if pericentres is not None and len(pericentres[0]):
        ax.plot(pericentres[0], pericentres[1], marker="v", color=SEPARATRIX, ms=6, ls="none",
                label="pericentre passages")
    if lrl is not None and np.hypot(*lrl) > 0:
        # A points from the focus to the pericentre; its length e is a number, not a
        # distance, so the arrow is drawn to the pericentre and the length is in the label
        e = float(np.hypot(*lrl))
        r_min = float(np.min(np.hypot(x, y)))
        tip = np.asarray(lrl, dtype=float) / e * r_min
        ax.annotate("", xy=tip, xytext=(0.0, 0.0), annotation_clip=False,
                    arrowprops={"arrowstyle": "-|>", "color": SEPARATRIX, "lw": 2.0})
        ax.plot([], [], color=SEPARATRIX, lw=2.0, label=lrl_label)
    _equal_box(ax, length_unit)
    place_legend(ax)
    return fig


def two_body_tracks(r1, r2, *, m1, m2, length_unit="m", mass_unit="kg", ax=None):
    """Both bodies' tracks about their fixed centre of mass (3.19)."""
    fig, ax = new_figure(ax, figsize=(6.4, 5.2))
    for r, m, c, name in ((r1, m1, BODY_COLOURS[0], "body 1"), (r2, m2, BODY_COLOURS[1],
                                                               "body 2")):
        label = f"{name} (m = {m:g} {mass_unit})".replace(" )", ")")
        ax.plot(r[:, 0], r[:, 1], color=c, lw=1.0, label=label)
        ax.plot([r[0, 0]], [r[0, 1]], marker="o", color=c, ms=5, ls="none")
    ax.plot([0], [0], marker="x", color="k", ms=8, ls="none", label="centre of mass")
    _equal_box(ax, length_unit)
    place_legend(ax)
    return fig


def effective_potential(r, v, v_eff, *, energy, turning, circular=None, length_unit="m",
                        energy_unit="J", ax=None):
    """V(r), V_eff(r) = V + L²/2μr² and the energy line between the turning points."""
    fig, ax = new_figure(ax)
    ax.plot(r, v, color=CONTEXT, linestyle="--", label="V(r)")
    ax.plot(r, v_eff, color=REFERENCE, label=r"$V_{\mathrm{eff}}(r) = V + L^2/(2\mu r^2)$")
    r_lo, r_hi = turning
    hi = r_hi if np.isfinite(r_hi) else r[-1]
    ax.plot([r_lo, hi], [energy, energy], color=HIGHLIGHT, lw=2.0, label="E (allowed region)")
    ax.plot([r_lo] + ([r_hi] if np.isfinite(r_hi) else []),
            [energy] * (1 + int(np.isfinite(r_hi))), marker="o", color=HIGHLIGHT, ls="none",
            label="turning points")
    if circular is not None:
        ax.plot([circular[0]], [circular[1]], marker="s", color=SEPARATRIX, ls="none",
                label="circular orbit")
    finite = v_eff[np.isfinite(v_eff)]
    lo = min(float(np.min(finite)), energy)
    span = max(abs(lo), abs(energy), 1e-300)
    ax.set_ylim(lo - 0.15 * span, max(energy, 0.0) + 0.6 * span)
    ax.set_xlim(0.0, r[-1])
    ax.set_xlabel(f"r [{length_unit}]")
    ax.set_ylabel(f"energy [{energy_unit}]")
    place_legend(ax)
    return fig


def apsidal_angle_family(e, angle_exact, *, near_circular, measured=None, exact_label,
                         near_label="near-circular limit π/√(2 − n)", ax=None):
    """Apsidal angle against eccentricity at fixed L: the exact quadrature and, dashed,
    ``near_circular`` (its circular limit, or a closed form) labelled ``near_label``."""
    fig, ax = new_figure(ax)
    ax.plot(e, np.degrees(angle_exact), color=REFERENCE, label=exact_label)
    ax.axhline(np.degrees(near_circular), color=CONTEXT, linestyle="--", label=near_label)
    ax.axhline(180.0, color=CONTEXT, linestyle=":", label="Kepler: 180° (closed orbit)")
    if measured is not None:
        ax.plot([measured[0]], [np.degrees(measured[1])], marker="o", color=HIGHLIGHT,
                ls="none", label="measured from the run")
    ax.set_xlabel(r"eccentricity $e = (r_{\max} - r_{\min})/(r_{\max} + r_{\min})$ "
                  "(dimensionless)")
    ax.set_ylabel("apsidal angle [deg]")
    place_legend(ax)
    return fig


def three_body_orbits(positions, *, labels, length_unit="", ax=None, plane=(0, 1)):
    """Tracks of the bodies in a plane; positions has shape (N, 3, 3) (time, body, xyz)."""
    fig, ax = new_figure(ax, figsize=(6.4, 5.2))
    names = "xyz"
    for b in range(positions.shape[1]):
        c = BODY_COLOURS[b % len(BODY_COLOURS)]
        ax.plot(positions[:, b, plane[0]], positions[:, b, plane[1]], color=c, lw=0.9,
                label=labels[b])
        ax.plot([positions[0, b, plane[0]]], [positions[0, b, plane[1]]], marker="o", color=c,
                ms=5, ls="none")
        ax.plot([positions[-1, b, plane[0]]], [positions[-1, b, plane[1]]], marker="s",
                color=c, ms=5, ls="none", mfc="none")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(length_label(names[plane[0]], length_unit))
    ax.set_ylabel(length_label(names[plane[1]], length_unit))
    place_legend(ax, title="● start, □ end")
    return fig


def encounter_zoom(t, positions, box, *, labels, length_unit="", time_unit="", cmap="viridis",
                   close_encounters=True):
    """Left, the whole tracks with the zoomed box; right, the tracks inside the box with
    time as colour (one colour scale, the bodies told apart by line style), so the order
    of the close encounters reads off the colours.  ``close_encounters``: whether the run
    had any (the archive's classification), which the enlargement's title names.

    positions : (N, 3, 3) time, body, xyz; box : (x0, x1, y0, y1) the zoomed region."""
    from matplotlib.collections import LineCollection
    from matplotlib.colors import Normalize
    from matplotlib.lines import Line2D

    fig, axes = new_figure_grid(1, 2, figsize=(8.6, 4.6))
    full, zoom = axes[0]
    t = np.asarray(t, dtype=float)
    norm = Normalize(float(t[0]), float(t[-1]))
    x0, x1, y0, y1 = box
    styles = []
    for b in range(positions.shape[1]):
        xy = positions[:, b, :2]
        full.plot(xy[:, 0], xy[:, 1], color=BODY_COLOURS[b % len(BODY_COLOURS)], lw=0.7,
                  label=labels[b])
        # polylines a 25th of the box long, each one colour (its mean time): a dash
        # pattern restarts on every piece, so one piece per sample drew every style solid
        pieces, times = _arc_pieces(xy, t, (x1 - x0) / 25.0)
        lines = LineCollection(pieces, cmap=cmap, norm=norm, linewidths=1.3,
                               linestyles=BODY_STYLES[b % len(BODY_STYLES)])
        lines.set_array(times)
        zoom.add_collection(lines)
        styles.append(Line2D([], [], color=INK, lw=1.3,
                             linestyle=BODY_STYLES[b % len(BODY_STYLES)], label=labels[b]))
    full.plot([x0, x1, x1, x0, x0], [y0, y0, y1, y1, y0], color="k", lw=0.9, ls="--",
              label="zoomed region")
    full.set_aspect("equal", adjustable="datalim")
    zoom.set_xlim(x0, x1)
    zoom.set_ylim(y0, y1)
    zoom.set_aspect("equal")
    for ax in (full, zoom):
        ax.set_xlabel(length_label("x", length_unit))
        ax.set_ylabel(length_label("y", length_unit))
    full.set_title("whole tracks", fontsize=10)
    zoom.set_title("close encounters, coloured by time" if close_encounters
                   else "enlarged, coloured by time", fontsize=10)
    place_legend(full, fontsize=9)
    # the bodies' line styles under the figure: inside or above the enlargement they
    # covered its tracks or its title
    fig.legend(handles=styles, loc="outside lower center", ncols=len(styles), fontsize=9,
               frameon=False, title="line style in the enlargement", title_fontsize=9)
    bar = fig.colorbar(lines, ax=zoom, shrink=0.8)
    bar.set_label(f"time t [{time_unit}]" if time_unit else "time t (dimensionless)")
    return fig


def _arc_pieces(xy, t, length):
    """The track ``xy`` cut into polylines about ``length`` long (sharing end points),
    with each piece's mean time."""
    step = np.hypot(*np.diff(xy, axis=0).T)
    arc = np.concatenate([[0.0], np.cumsum(np.where(np.isfinite(step), step, 0.0))])
    cut = np.searchsorted(arc, np.arange(0.0, arc[-1], max(length, 1e-300)))
    cut = np.unique(np.concatenate([cut, [len(xy) - 1]]))
    pieces, times = [], []
    for i, j in zip(cut[:-1], cut[1:], strict=True):
        if j > i:
            pieces.append(xy[i:j + 1])
            times.append(float(np.mean(t[i:j + 1])))
    return pieces, np.asarray(times)


def relative_track(dx, dy, *, label, centre_label, length_unit="", ax=None):
    """One body's track relative to another (e.g. the Moon about the Earth)."""
    fig, ax = new_figure(ax, figsize=(6.0, 5.2))
    ax.plot(dx, dy, color=HIGHLIGHT, lw=0.8, label=label)
    ax.plot([0], [0], marker="o", color=BODY_COLOURS[1], ms=7, ls="none", label=centre_label)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(length_label("Δx", length_unit))
    ax.set_ylabel(length_label("Δy", length_unit))
    place_legend(ax, loc="upper right")
    return fig


def closest_approach(t, distances: dict[str, np.ndarray], *, time_unit="", length_unit="",
                     minima=None, ax=None):
    """Pairwise distances against time on a log scale (close encounters); an empty unit
    is a scaled (dimensionless) one.  ``minima``: (times, distances), one per pair in the
    order of ``distances``, each pair's closest approach located between the samples,
    drawn as a dot in the pair's colour."""
    fig, ax = new_figure(ax)
    dots = 0
    for k, (name, d) in enumerate(distances.items()):
        (line,) = ax.semilogy(t, d, lw=0.9, label=name)
        if minima is not None and np.isfinite(minima[1][k]) and minima[1][k] > 0:
            ax.plot([minima[0][k]], [minima[1][k]], "o", color=line.get_color(), ms=5,
                    label="closest approach (continuous solution)" if not dots else None)
            dots += 1
    ax.set_xlabel(f"time t [{time_unit}]" if time_unit else "time t (dimensionless)")
    ax.set_ylabel(length_label("pair distance r", length_unit))
    place_legend(ax)
    return fig


def elliptic_grid_orbit(x, y, *, a, grid, xi_bounds=None, eta_bounds=None, length_unit="m",
                        ax=None):
    """The orbit over the elliptic-coordinate grid of two centres at (±a, 0).

    ``grid``: the coordinate lines as (x, y) curves, drawn thin: confocal ellipses
    ξ = (r1 + r2)/2a = const and hyperbola branches η = (r1 − r2)/2a = const.
    ``xi_bounds`` (ellipses) and ``eta_bounds`` (hyperbola branches): the coordinate
    lines bounding the separated motion, as (x, y) curves, drawn dashed when given (the
    orbit runs along them).
    """
    fig, ax = new_figure(ax, figsize=(6.4, 4.6))
    for gx, gy in grid:
        ax.plot(gx, gy, color=CONTEXT, lw=0.5)
    for i, (bx, by) in enumerate(xi_bounds or ()):
        ax.plot(bx, by, color=GREEN, lw=1.5, linestyle=(0, (4, 2)), zorder=3,
                label="ξ bounds of the motion" if i == 0 else None)
    for i, (bx, by) in enumerate(eta_bounds or ()):
        ax.plot(bx, by, color=REFERENCE, lw=1.5, linestyle=(0, (4, 2)), zorder=3,
                label="η bounds of the motion" if i == 0 else None)
    ax.plot(x, y, color=HIGHLIGHT, lw=0.7, label="orbit", zorder=4)  # above the bounds
    ax.plot([-a, a], [0, 0], marker="o", color="k", ms=6, ls="none", label="fixed centres")
    ax.plot([x[0]], [y[0]], marker="o", color=HIGHLIGHT, ms=5, ls="none")
    lim = 1.05 * max(np.max(np.abs(x)), np.max(np.abs(y)), 1.2 * a)
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.set_xlabel(f"x [{length_unit}]")
    ax.set_ylabel(f"y [{length_unit}]")
    # under the axes, as the figure's: the orbit fills the square box, and a legend
    # anchored beside or above an equal-aspect axes was cut at the figure's edge
    legend_below(fig, fontsize=8, max_columns=4)
    return fig
