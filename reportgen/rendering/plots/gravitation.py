"""Figures of the gravitation scenes: orbits, effective potentials, apsides, elliptic grids."""

from __future__ import annotations

import numpy as np

from .style import BLUE, CONTEXT, GREY, HIGHLIGHT, ORANGE, REFERENCE, SEPARATRIX, new_figure

BODY_COLOURS = (ORANGE, BLUE, GREY)  # Sun, Earth, Moon


def _equal_box(ax, length_unit):
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{length_unit}]")
    ax.set_ylabel(f"y [{length_unit}]")


def relative_orbit(x, y, *, reference=None, pericentres=None, lrl=None, length_unit="m",
                   ax=None):
    """The relative orbit r(t) with the force centre, optional exact orbit, pericentres, LRL."""
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
        ax.plot([], [], color=SEPARATRIX, lw=2.0,
                label=f"LRL direction (|A|/μk = e = {e:.4g})")
    _equal_box(ax, length_unit)
    ax.legend(loc="best")
    return fig


def two_body_tracks(r1, r2, *, m1, m2, length_unit="m", ax=None):
    """Both bodies' tracks about their fixed centre of mass (3.19)."""
    fig, ax = new_figure(ax, figsize=(6.4, 5.2))
    for r, m, c, name in ((r1, m1, BODY_COLOURS[0], "body 1"), (r2, m2, BODY_COLOURS[1],
                                                               "body 2")):
        ax.plot(r[:, 0], r[:, 1], color=c, lw=1.0, label=f"{name} (m = {m:g})")
        ax.plot([r[0, 0]], [r[0, 1]], marker="o", color=c, ms=5, ls="none")
    ax.plot([0], [0], marker="x", color="k", ms=8, ls="none", label="centre of mass")
    _equal_box(ax, length_unit)
    ax.legend(loc="best")
    return fig


def effective_potential(r, v, v_eff, *, energy, turning, circular=None, length_unit="m",
                        energy_unit="J", ax=None):
    """V(r), V_eff(r) = V + L²/2μr² and the energy line between the turning points."""
    fig, ax = new_figure(ax)
    ax.plot(r, v, color=CONTEXT, linestyle="--", label="V(r)")
    ax.plot(r, v_eff, color=REFERENCE, label="V_eff(r) = V + L²/(2μr²)")
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
    ax.legend(loc="best")
    return fig


def apsidal_angle_family(e, angle_exact, *, near_circular, measured=None, exact_label,
                         ax=None):
    """Apsidal angle against eccentricity at fixed L: exact quadrature and its circular limit."""
    fig, ax = new_figure(ax)
    ax.plot(e, np.degrees(angle_exact), color=REFERENCE, label=exact_label)
    ax.axhline(np.degrees(near_circular), color=CONTEXT, linestyle="--",
               label="near-circular limit π/√(2 − n)")
    ax.axhline(180.0, color=CONTEXT, linestyle=":", label="Kepler: 180° (closed orbit)")
    if measured is not None:
        ax.plot([measured[0]], [np.degrees(measured[1])], marker="o", color=HIGHLIGHT,
                ls="none", label="measured from the run")
    ax.set_xlabel("eccentricity e = (r_max − r_min)/(r_max + r_min)")
    ax.set_ylabel("apsidal angle [deg]")
    ax.legend(loc="best")
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
    unit = f" [{length_unit}]" if length_unit else ""
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"{names[plane[0]]}{unit}")
    ax.set_ylabel(f"{names[plane[1]]}{unit}")
    ax.legend(loc="best", title="● start, □ end")
    return fig


def relative_track(dx, dy, *, label, centre_label, length_unit="", ax=None):
    """One body's track relative to another (e.g. the Moon about the Earth)."""
    fig, ax = new_figure(ax, figsize=(6.0, 5.2))
    ax.plot(dx, dy, color=HIGHLIGHT, lw=0.8, label=label)
    ax.plot([0], [0], marker="o", color=BODY_COLOURS[1], ms=7, ls="none", label=centre_label)
    unit = f" [{length_unit}]" if length_unit else ""
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"Δx{unit}")
    ax.set_ylabel(f"Δy{unit}")
    ax.legend(loc="upper right")
    return fig


def closest_approach(t, distances: dict[str, np.ndarray], *, time_unit="", ax=None):
    """Pairwise distances against time on a log scale (close encounters)."""
    fig, ax = new_figure(ax)
    for name, d in distances.items():
        ax.semilogy(t, d, lw=0.9, label=name)
    unit = f" [{time_unit}]" if time_unit else ""
    ax.set_xlabel(f"time t{unit}")
    ax.set_ylabel("pair distance")
    ax.legend(loc="best")
    return fig


def elliptic_grid_orbit(x, y, *, a, grid, xi_bounds=None, eta_bounds=None, length_unit="m",
                        ax=None):
    """The orbit over the elliptic-coordinate grid of two centres at (±a, 0).

    ``grid``: the coordinate lines as (x, y) curves, drawn thin: confocal ellipses
    ξ = (r1 + r2)/2a = const and hyperbola branches η = (r1 − r2)/2a = const.
    ``xi_bounds`` (ellipses) and ``eta_bounds`` (hyperbola branches): the coordinate
    lines bounding the separated motion, as (x, y) curves, drawn bold when given.
    """
    fig, ax = new_figure(ax, figsize=(6.8, 5.2))
    for gx, gy in grid:
        ax.plot(gx, gy, color=CONTEXT, lw=0.5)
    for i, (bx, by) in enumerate(xi_bounds or ()):
        ax.plot(bx, by, color=SEPARATRIX, lw=1.5,
                label="ξ bounds of the motion" if i == 0 else None)
    for i, (bx, by) in enumerate(eta_bounds or ()):
        ax.plot(bx, by, color=REFERENCE, lw=1.5,
                label="η bounds of the motion" if i == 0 else None)
    ax.plot(x, y, color=HIGHLIGHT, lw=0.7, label="orbit")
    ax.plot([-a, a], [0, 0], marker="o", color="k", ms=6, ls="none", label="fixed centres")
    ax.plot([x[0]], [y[0]], marker="o", color=HIGHLIGHT, ms=5, ls="none")
    lim = 1.05 * max(np.max(np.abs(x)), np.max(np.abs(y)), 1.2 * a)
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.set_xlabel(f"x [{length_unit}]")
    ax.set_ylabel(f"y [{length_unit}]")
    ax.legend(loc="upper right", fontsize=8)
    return fig
