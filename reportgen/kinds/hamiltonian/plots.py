"""Figures of a formula system: coordinates, configuration path, phase portrait, surface of
section, observables.  Axis labels are given by the report: the symbols of the config's
names with their unit, [rad] for an angle, else the config's own units (:data:`UNITS`: a
formula system declares none)."""

from __future__ import annotations

import numpy as np

from ...rendering.plots.common import envelope, time_label
from ...rendering.plots.style import (
    CONTEXT,
    HIGHLIGHT,
    PALETTE,
    dots,
    legend_below,
    new_figure,
    new_figure_grid,
    place_legend,
)
from ...scene.content import fmt
from .symbols import symbol_tex

#: the unit of a formula system's quantities (but its angles): the config's own
UNITS = "config units"


def _math(name: str) -> str:
    """A config name (``p_x2``, ``P_phi``) as mathtext for a legend."""
    return f"${symbol_tex(name)}$"


def coordinates(t, series: dict[str, np.ndarray], *, labels: dict[str, str] | None = None):
    """Each coordinate against time, one panel per coordinate (shared time axis);
    ``labels``: each panel's axis label, with its unit, by coordinate (default the name's
    symbol in :data:`UNITS`)."""
    n = len(series)
    fig, axes = new_figure_grid(n, 1, figsize=(6.8, 1.2 + 1.5 * n), sharex=True)
    axes = axes[:, 0]
    for ax, (name, values), colour in zip(axes, series.items(), PALETTE, strict=False):
        ax.plot(*envelope(t, values), color=colour)
        ax.set_ylabel((labels or {}).get(name, f"{_math(name)} [{UNITS}]"))
    axes[-1].set_xlabel(time_label(UNITS))
    return fig


def configuration(x, y, xname: str, yname: str):
    """The path in the plane of the first two coordinates (``xname``, ``yname``: the axis
    labels, with their units)."""
    fig, ax = new_figure(figsize=(5.6, 5.0))
    ax.plot(x, y, color=HIGHLIGHT, linewidth=0.8)
    ax.plot([x[0]], [y[0]], "o", color="black", markersize=5, label="start")
    ax.set_xlabel(xname)
    ax.set_ylabel(yname)
    place_legend(ax, loc="upper right", outside="right")
    return fig


def phase_portrait(q, p, grid_q, grid_p, H, H0: float, qname: str, angle: bool = False, *,
                   labels: tuple[str, str] | None = None):
    """Level curves of H on the grid, the run's level H0 and its orbit (an angle wrapped
    to (−π, π], the orbit broken where it wraps); ``labels``: the axes' labels, with their
    units (default the symbols of ``qname`` and ``p_<qname>`` in :data:`UNITS`)."""
    fig, ax = new_figure(figsize=(6.4, 4.6))
    Q, P = np.meshgrid(grid_q, grid_p)
    finite = H[np.isfinite(H)]
    if finite.size:
        lo, hi = np.percentile(finite, [2, 90])
        levels = np.unique(np.concatenate([np.linspace(lo, hi, 14), [H0]]))
        ax.contour(Q, P, H, levels=levels, colors=CONTEXT, linewidths=0.7)
    q, p = np.asarray(q), np.asarray(p)
    if angle:
        q = np.pi - np.mod(np.pi - q, 2 * np.pi)
        jumps = np.nonzero(np.abs(np.diff(q)) > np.pi)[0] + 1
        for seg_q, seg_p in zip(np.split(q, jumps), np.split(p, jumps), strict=True):
            ax.plot(seg_q, seg_p, color=HIGHLIGHT, linewidth=2.0)
        ax.set_xlim(-np.pi, np.pi)
    else:
        ax.plot(q, p, color=HIGHLIGHT, linewidth=2.0)
    ax.plot([], [], color=HIGHLIGHT, linewidth=2.0, label=f"this run, H = {fmt(H0, 6)}")
    ax.plot([], [], color=CONTEXT, label="other levels of H")
    xlabel, ylabel = labels or (f"{_math(qname)} [{UNITS}]", f"{_math('p_' + qname)} [{UNITS}]")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    place_legend(ax, loc="upper right", outside="right")
    return fig


def poincare(u, v, uname: str, vname: str):
    """The crossings of the surface of section as points (``uname``, ``vname``: the axis
    labels, with their units)."""
    fig, ax = new_figure(figsize=(5.8, 5.0))
    ax.plot(u, v, color=HIGHLIGHT,
            **(dots() if len(u) > 400 else {"marker": ".", "markersize": 4.0, "ls": "none"}))
    ax.set_xlabel(uname)
    ax.set_ylabel(vname)
    return fig


def observables(t, series: dict[str, np.ndarray]):
    """Observables that change, against time (``series`` by their legend labels)."""
    fig, ax = new_figure()
    for (label, values), colour in zip(series.items(), PALETTE, strict=False):
        ax.plot(*envelope(t, values), color=colour, label=label)
    ax.set_xlabel(time_label(UNITS))
    ax.set_ylabel(f"value [{UNITS}]")
    place_legend(ax)
    return fig


def new_variables(t, series: dict[str, np.ndarray], integrated=None, first: str = ""):
    """The new canonical variables against time; the first of them also from integrating
    K (dashed), when given."""
    fig, ax = new_figure()
    for (name, values), colour in zip(series.items(), PALETTE, strict=False):
        ax.plot(*envelope(t, values), color=colour, label=_math(name))
    if integrated is not None:
        ax.plot(*envelope(t, integrated), color="black", linestyle=(0, (3, 3)), linewidth=1.0,
                label=f"{_math(first)} from K")
    ax.set_xlabel(time_label(UNITS))
    ax.set_ylabel(f"new variables [{UNITS}]")
    place_legend(ax)
    return fig


def change_of_energy(t, change, first_order, second_order):
    """The change of H under an infinitesimal transformation against time: above,
    H(Q, P) − H(q, p) with its first-order part ε{H, G}; below, what is left after the first
    order with the second-order term ε²/2 wᵀ∇²H w (dashed), too small to see above."""
    fig, axes = new_figure_grid(2, 1, figsize=(6.8, 5.6), sharex=True)
    top, bottom = axes[:, 0]
    top.plot(*envelope(t, change), color=PALETTE[0], linewidth=2.4,
             label=r"$H(Q, P) - H(q, p)$")
    top.plot(*envelope(t, first_order), color=PALETTE[1], label=r"$\epsilon\{H, G\}$")
    top.set_ylabel(f"change of H [{UNITS}]")
    place_legend(top)
    bottom.plot(*envelope(t, change - first_order), color=PALETTE[0], linewidth=2.4,
                label=r"$H(Q, P) - H(q, p) - \epsilon\{H, G\}$")
    bottom.plot(*envelope(t, second_order), color="black", linestyle=(0, (3, 3)),
                linewidth=1.0, label=r"$\frac{\epsilon^2}{2} w^T \nabla^2 H\, w$")
    # from zero: a constant remainder (ε²H for a quadratic H) reads as its size, not as
    # rounding noise about an offset
    rest = np.concatenate([np.ravel(change - first_order), np.ravel(second_order)])
    rest = rest[np.isfinite(rest)]
    if rest.size:
        lo, hi = min(0.0, float(rest.min())), max(0.0, float(rest.max()))
        if hi > lo:
            bottom.set_ylim(lo - 0.1 * (hi - lo), hi + 0.1 * (hi - lo))
    bottom.ticklabel_format(axis="y", useOffset=False)
    bottom.set_ylabel(f"beyond first order [{UNITS}]")
    bottom.set_xlabel(time_label(UNITS))
    place_legend(bottom)
    return fig


def new_orbit(first, second, names: tuple[str, str], integrated=None):
    """The orbit in the two new coordinates, the second against the first (a frame turning
    with the transformation shows another curve than the old one); K's own integration
    dashed, when given."""
    fig, ax = new_figure()
    ax.plot(first, second, color=PALETTE[0], label="image of the H orbit")
    if integrated is not None:
        ax.plot(*integrated, color="black", linestyle=(0, (3, 3)), linewidth=1.0,
                label="integrating K")
    ax.plot([first[0]], [second[0]], "o", color="black", markersize=4, label="start")
    ax.set_xlabel(f"{_math(names[0])} [{UNITS}]")
    ax.set_ylabel(f"{_math(names[1])} [{UNITS}]")
    place_legend(ax)
    return fig


def tangent_planes(curve, points, dual, labels: dict[str, str]):
    """The Legendre transform as geometry, notes (4.19)–(4.25), on the unit sphere's cut
    y = 0: left, the curve ``curve`` = (x, z) with the tangent lines z = ω − ξx at
    ``points`` = (x₀, z₀, ξ, ω) (each point and its intercept ω on the z axis in the
    line's colour); right, the dual curve ``dual`` = (ξ, ω) with the same planes as
    points (ξ, ω); one legend under both.  ``labels``: the axes' labels by "x", "z", "xi",
    "omega"."""
    fig, axes = new_figure_grid(1, 2, figsize=(8.4, 4.6))
    left, right = axes[0]
    (x, z), (x0, z0, xi, omega) = curve, (np.asarray(v, dtype=float) for v in points)
    reach = 1.3
    left.axvline(0.0, color=CONTEXT, linewidth=0.6)
    left.plot(x, z, color="black", linewidth=2.0, label="surface, cut y = 0")
    right.plot(*dual, color="black", linewidth=1.6, linestyle=(0, (5, 3)),
               label=r"dual curve, closed form $\omega = \sqrt{1 + \xi^2}$")
    ends = np.array([-reach, reach])
    colours = [c for c in PALETTE if c != PALETTE[-1]]
    for k, (a, b, s, w) in enumerate(zip(x0, z0, xi, omega, strict=True)):
        colour = colours[k % len(colours)]
        left.plot(ends, w - s * ends, color=colour, linewidth=1.0)
        left.plot([a], [b], "o", color=colour, markersize=5)
        left.plot([0.0], [w], "s", color=colour, markersize=5, markerfacecolor="white")
        right.plot([s], [w], "D", color=colour, markersize=6)
    left.plot([], [], color=CONTEXT, linewidth=1.0,
              label=r"tangent lines $z = \omega - \xi x$, one colour per point")
    left.plot([], [], "o", color=CONTEXT, label="tangent point")
    left.plot([], [], "s", color=CONTEXT, markerfacecolor="white", label=r"intercept $\omega$")
    right.plot([], [], "D", color=CONTEXT, label=r"$(\xi, \omega)$ of each tangent plane")
    top = 1.15 * float(max(np.max(omega), 1.0))
    left.set_xlim(-reach, reach)
    left.set_ylim(0.0, top)
    left.set_aspect("equal", adjustable="box")
    right.set_ylim(0.0, max(top, 1.05 * float(np.max(dual[1]))))
    left.set_xlabel(labels["x"])
    left.set_ylabel(labels["z"])
    right.set_xlabel(labels["xi"])
    right.set_ylabel(labels["omega"])
    legend_below(fig, fontsize=9, max_columns=3)
    return fig
