"""Audit figures: what went wrong in a flagged case, and an overview of all cases."""

from __future__ import annotations

import numpy as np

from .style import GREEN, ORANGE, PURPLE, VERMILLION, new_figure

VERDICT_COLOURS = {"ok": GREEN, "inaccurate": ORANGE, "stiff": PURPLE, "unstable": VERMILLION}


def case_drift(runs: list[dict], *, ax=None):
    """Relative drift of every invariant against time, one line per method tried."""
    fig, ax = new_figure(ax, figsize=(6.8, 3.8))
    for run in runs:
        for q, series in run["drift"].items():
            values = np.abs(np.asarray(series, dtype=float))
            values[~np.isfinite(values)] = np.nan
            ax.semilogy(run["t"], np.maximum(values, 1e-17), label=f"{run['used']}: {q}")
    ax.set_xlabel("time t [scene units]")
    ax.set_ylabel("|I(t) − I(0)| / |I|")
    ax.legend(loc="best", fontsize=8)
    return fig


def overview(table, *, ax=None):
    """Drift against reference disagreement for every run, coloured by its case's verdict."""
    fig, ax = new_figure(ax, figsize=(6.8, 4.2))
    for verdict, colour in VERDICT_COLOURS.items():
        rows = table[table["verdict"] == verdict]
        if len(rows) == 0:
            continue
        # failed runs (inf/NaN) are pinned to the top edge so they stay visible
        drift = np.clip(np.nan_to_num(rows["drift"].astype(float), nan=1e3, posinf=1e3), 1e-17, 1e3)
        error = np.clip(np.nan_to_num(rows["error"].astype(float), nan=1e3, posinf=1e3), 1e-17, 1e3)
        ax.loglog(drift, error, "o", color=colour, label=verdict, alpha=0.8)
    ax.set_xlabel("max relative invariant drift")
    ax.set_ylabel("max relative disagreement with the reference")
    ax.legend(loc="best")
    return fig
