"""Harmonic-oscillator figures: the swap transformation and the Hamilton–Jacobi constants."""

from __future__ import annotations

import numpy as np

from ...rendering.plots.style import CONTEXT, HIGHLIGHT, REFERENCE, new_figure_grid


def swap_phase_planes(q, p, Q_int, P_int, Q_map, P_map):
    fig, axes = new_figure_grid(1, 2, figsize=(8.0, 3.9))
    left, right = axes[0]
    left.plot(q, p, color=REFERENCE)
    left.plot(q[:1], p[:1], "o", color=REFERENCE, label="start")
    left.set_xlabel("q [m]")
    left.set_ylabel("p [kg·m/s]")
    left.set_title("H(q, p)")
    left.legend(loc="upper right")
    right.plot(Q_map, P_map, color=CONTEXT, linewidth=4, alpha=0.6, label="(p, −q) of left orbit")
    right.plot(Q_int, P_int, color=HIGHLIGHT, linestyle=(0, (4, 3)), label="K integrated")
    right.plot(Q_int[:1], P_int[:1], "o", color=HIGHLIGHT)
    right.set_xlabel("Q = p [kg·m/s]")
    right.set_ylabel("P = −q [m]")
    right.set_title("K(Q, P)")
    # under the panels: the orbits fill the right one up to its corners
    fig.legend(*right.get_legend_handles_labels(), loc="outside lower center", ncols=2,
               fontsize=8, frameon=False)
    for ax in (left, right):
        ax.set_aspect("auto")
    return fig


def hamilton_jacobi(t, q_int, q_hj, energy, beta):
    # short enough to share the page with the section's prose and facts
    fig, axes = new_figure_grid(3, 1, figsize=(6.8, 4.6), sharex=True)
    ax_q, ax_e, ax_b = axes[:, 0]
    ax_q.plot(t, q_int, color=HIGHLIGHT, label="integrated")
    ax_q.plot(t, q_hj, color=REFERENCE, linestyle=(0, (4, 3)), label="Hamilton–Jacobi, notes (7.38)")
    ax_q.set_ylabel("q [m]")
    # above the panels: q(t) peaks in every corner of its axes
    fig.legend(*ax_q.get_legend_handles_labels(), loc="outside upper center", ncols=2,
               frameon=False)
    ax_e.plot(t, np.asarray(energy) - energy[0], color=REFERENCE)
    ax_e.set_ylabel("E(t) − E(0) [J]")
    ax_e.ticklabel_format(axis="y", style="sci", scilimits=(-2, 2))
    ax_b.plot(t, np.asarray(beta) - beta[0], color=REFERENCE)
    ax_b.set_ylabel("β(t) − β(0) [s]")
    ax_b.ticklabel_format(axis="y", style="sci", scilimits=(-2, 2))
    ax_b.set_xlabel("time t [s]")
    return fig
