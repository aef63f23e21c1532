"""Figures of a formula system: coordinates, configuration path, phase portrait, surface of
section, observables.  Axis labels are the symbols of the config's names, as SymPy typesets
them (no units: a formula system is in whatever units its author chose)."""

from __future__ import annotations

import numpy as np

from ...rendering.plots.common import envelope
from ...rendering.plots.style import CONTEXT, HIGHLIGHT, PALETTE, dots, new_figure, new_figure_grid


def coordinates(t, series: dict[str, np.ndarray], *, labels: dict[str, str] | None = None):
    """Each coordinate against time, one panel per coordinate (shared time axis);
    ``labels``: each panel's axis label by coordinate (default its name)."""
    n = len(series)
    fig, axes = new_figure_grid(n, 1, figsize=(6.8, 1.2 + 1.5 * n), sharex=True)
    axes = axes[:, 0]
    for ax, (name, values), colour in zip(axes, series.items(), PALETTE, strict=False):
        ax.plot(*envelope(t, values), color=colour)
        ax.set_ylabel((labels or {}).get(name, name))
    axes[-1].set_xlabel("time t")
    return fig


def configuration(x, y, xname: str, yname: str):
    """The path in the plane of the first two coordinates."""
    fig, ax = new_figure(figsize=(5.6, 5.0))
    ax.plot(x, y, color=HIGHLIGHT, linewidth=0.8)
    ax.plot([x[0]], [y[0]], "o", color="black", markersize=5, label="start")
    ax.set_xlabel(xname)
    ax.set_ylabel(yname)
    ax.legend(loc="upper right")
    return fig


def phase_portrait(q, p, grid_q, grid_p, H, H0: float, qname: str, angle: bool = False, *,
                   labels: tuple[str, str] | None = None):
    """Level curves of H on the grid, the run's level H0 and its orbit (an angle wrapped
    to (−π, π], the orbit broken where it wraps); ``labels``: the axes' labels (default
    ``qname`` and ``p_<qname>``)."""
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
    ax.plot([], [], color=HIGHLIGHT, linewidth=2.0, label=f"this run, H = {H0:.6g}")
    ax.plot([], [], color=CONTEXT, label="other levels of H")
    xlabel, ylabel = labels or (qname, f"p_{qname}")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.legend(loc="upper right")
    return fig


def poincare(u, v, uname: str, vname: str):
    """The crossings of the surface of section as points."""
    fig, ax = new_figure(figsize=(5.8, 5.0))
    ax.plot(u, v, color=HIGHLIGHT,
            **(dots() if len(u) > 400 else {"marker": ".", "markersize": 4.0, "ls": "none"}))
    ax.set_xlabel(uname)
    ax.set_ylabel(vname)
    return fig


def observables(t, series: dict[str, np.ndarray]):
    """Observables that change, against time."""
    fig, ax = new_figure()
    for (name, values), colour in zip(series.items(), PALETTE, strict=False):
        ax.plot(*envelope(t, values), color=colour, label=name)
    ax.set_xlabel("time t")
    ax.set_ylabel("value")
    ax.legend(loc="best")
    return fig


def new_variables(t, series: dict[str, np.ndarray], integrated=None, first: str = ""):
    """The new canonical variables against time; the first of them also from integrating
    K (dashed), when given."""
    fig, ax = new_figure()
    for (name, values), colour in zip(series.items(), PALETTE, strict=False):
        ax.plot(*envelope(t, values), color=colour, label=name)
    if integrated is not None:
        ax.plot(*envelope(t, integrated), color="black", linestyle=(0, (3, 3)), linewidth=1.0,
                label=f"{first} from K")
    ax.set_xlabel("time t")
    ax.set_ylabel("new variables")
    ax.legend(loc="best")
    return fig
