"""Pendulum figures: phase portrait, period against amplitude, boundary-value solution."""

from __future__ import annotations

import math

import numpy as np

from ...rendering.plots.common import envelope
from ...rendering.plots.style import (
    CONTEXT,
    HIGHLIGHT,
    REFERENCE,
    SEPARATRIX,
    member_markers,
    new_figure,
    new_figure_grid,
    place_legend,
)


def phase_portrait(theta, theta_dot, *, grid_theta, grid_theta_dot, energy, levels,
                   separatrix, ax=None):
    """Given level sets of the phase-plane energy, with the separatrix and the scene's orbit.

    ``energy`` (shape (len(grid_theta_dot), len(grid_theta))) is drawn at ``levels``
    and at ``separatrix``; the orbit (``theta``, ``theta_dot``, wrapped to (−π, π]) on top.
    """
    fig, ax = new_figure(ax, figsize=(6.8, 4.4))
    wrapped = np.mod(np.asarray(theta) + math.pi, 2 * math.pi) - math.pi
    TH, THD = np.meshgrid(grid_theta, grid_theta_dot)
    # solid: a one-colour contour draws negative levels dashed, which nothing explains
    ax.contour(TH, THD, energy, levels=np.sort(levels), colors=CONTEXT, linewidths=0.8,
               linestyles="solid")
    ax.contour(TH, THD, energy, levels=[separatrix], colors=SEPARATRIX, linewidths=1.6)
    # break the orbit where it wraps so no line crosses the plot
    jumps = np.nonzero(np.abs(np.diff(wrapped)) > math.pi)[0] + 1
    for seg_t, seg_v in zip(np.split(wrapped, jumps), np.split(theta_dot, jumps), strict=True):
        ax.plot(seg_t, seg_v, color=HIGHLIGHT, linewidth=2.0)
    ax.plot([], [], color=SEPARATRIX, label="separatrix E = m g l")
    ax.plot([], [], color=CONTEXT, label="librations / rotations")
    ax.plot([], [], color=HIGHLIGHT, linewidth=2.0, label="this scene")
    ax.set_xlim(-math.pi, math.pi)
    ax.set_xticks([-math.pi, -math.pi / 2, 0, math.pi / 2, math.pi],
                  ["−π", "−π/2", "0", "π/2", "π"])
    ax.set_xlabel("θ [rad]")
    ax.set_ylabel(r"$\mathrm{d}\theta/\mathrm{d}t$ [rad/s]")  # no combining dot (see Quantity.math)
    place_legend(ax, loc="upper right", fontsize=8, outside="right")
    return fig


def period_against_amplitude(*, curve_amplitude, curve_period, small_angle_period,
                             amplitude=None, period=None, period_measured=None, ax=None):
    """The given period curve T(θ0) (the exact 4 K(sin²(θ0/2)) / ω0 over 0 < θ0 < π), with
    the small-angle period and this scene's point."""
    fig, ax = new_figure(ax)
    ax.plot(curve_amplitude, curve_period, color=REFERENCE, label="exact 4K(k)√(l/g)")
    ax.axhline(small_angle_period, color=CONTEXT, linestyle="--", label="small angle 2π√(l/g)")
    if amplitude is not None and period is not None:
        ax.plot([amplitude], [period], "o", color=REFERENCE, markersize=9,
                markerfacecolor="none", label="this scene, exact")
    if amplitude is not None and period_measured is not None and np.isfinite(period_measured):
        ax.plot([amplitude], [period_measured], "x", color=HIGHLIGHT, markersize=9,
                label="this scene, measured")
    ax.set_xlim(0, 1.02 * math.pi)  # a point at θ0 → π keeps its whole marker
    # the curve up to four small-angle periods, or up to this scene's point (inside the
    # frame, with room for its marker): near the separatrix it lies far above
    top = min(float(np.max(curve_period)), 4 * small_angle_period)
    shown = [v for v in (period, period_measured) if v is not None and np.isfinite(v)]
    ax.set_ylim(0, max([top, *(1.08 * v for v in shown)]))
    ax.set_xticks([0, math.pi / 4, math.pi / 2, 3 * math.pi / 4, math.pi],
                  ["0", "π/4", "π/2", "3π/4", "π"])
    ax.set_xlabel("amplitude θ₀ [rad]")
    ax.set_ylabel("period T [s]")
    place_legend(ax, loc="upper left")
    return fig


def boundary_value(t, theta_exact, theta_numeric, theta_nonlinear, *, ax=None):
    fig, ax = new_figure(ax)
    ax.plot(t, theta_exact, color=REFERENCE, label="linear, closed form, notes (1.21)")
    ax.plot(t, theta_numeric, color=HIGHLIGHT, linestyle=(0, (4, 3)), label="linear, numerical")
    if np.all(np.isfinite(theta_nonlinear)):
        ax.plot(t, theta_nonlinear, color=CONTEXT, linestyle=":", label="nonlinear, numerical")
    ax.plot([t[0], t[-1]], [theta_exact[0], theta_exact[-1]], "o", color="black",
            label="boundary values")
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("θ [rad]")
    place_legend(ax)
    return fig


def period_family(amplitude, measured, exact, *, curve=None, small_angle=None):
    """A sweep's periods against amplitude: members (markers, or a line when dense), the
    exact curve and the small-angle period; below, the relative error of each member.

    A dense family is drawn as per-bin extremes (:func:`envelope`: the same pixels, a
    bounded size whatever the members); for 10⁷ members the arrays are used in place
    where they are already in amplitude order (a range sweep's are), and the error is
    computed in one buffer, so the figure costs two member arrays of memory."""
    fig, (ax, ax_err) = new_figure_grid(2, 1, figsize=(6.4, 5.6), sharex=True)
    ax, ax_err = ax[0], ax_err[0]
    x = np.asarray(amplitude, dtype=float)
    ordered = x.size < 2 or bool(np.all(x[1:] >= x[:-1]))
    order = None if ordered else np.argsort(x, kind="stable")

    def sort(v):
        v = np.asarray(v, dtype=float)
        return v if order is None else v[order]

    x, y = sort(x), sort(measured)
    if curve is not None:
        ax.plot(curve["amplitude"], curve["period"], color=REFERENCE, lw=2.5,
                label="exact 4K(k)√(l/g)")
    else:
        ax.plot(*envelope(x, sort(exact)), color=REFERENCE, lw=2.5, label="exact 4K(k)√(l/g)")
    dense = x.size > 80
    ax.plot(*envelope(x, y), "-" if dense else "o", color=HIGHLIGHT, ms=3.5, lw=1.2,
            label=f"integrated ({x.size} members)")
    if small_angle is not None and np.size(small_angle):
        ax.plot(*envelope(x, sort(np.broadcast_to(small_angle, x.shape))), "--",
                color=CONTEXT, label="small-angle 2π√(l/g)")
    ax.set_ylabel("period T [s]")
    place_legend(ax, loc="upper left")
    rel = np.divide(y, sort(exact))  # |T/T_exact - 1| in one buffer
    rel -= 1.0
    np.abs(rel, out=rel)
    np.maximum(rel, 1e-17, out=rel)
    ax_err.semilogy(*envelope(x, rel), color=HIGHLIGHT, **member_markers(dense))
    ax_err.set_ylabel(r"$|T - T_\mathrm{exact}|/T_\mathrm{exact}$ (dimensionless)")
    ax_err.set_xlabel("amplitude θ₀ [rad]")
    return fig
