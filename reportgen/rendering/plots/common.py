"""Figures every integrating scene can use: invariants, errors, work-precision."""

from __future__ import annotations

import textwrap

import numpy as np

from ...support.peers import is_peer
from .style import (
    CONTEXT,
    HIGHLIGHT,
    MANY_SERIES,
    REFERENCE,
    dots,
    legend_below,
    member_markers,
    new_figure,
    new_figure_grid,
    place_legend,
)

#: a time series longer than this is drawn as its per-bin extremes (see :func:`envelope`)
ENVELOPE_ABOVE = 6000
ENVELOPE_BINS = 2000


def envelope(t, values, bins: int = ENVELOPE_BINS):
    """``(t, values)`` reduced for drawing: in each of ``bins`` equal runs of samples the
    minimum and the maximum, in time order.  A line through them covers the same pixels as
    the full series at any figure width under ``bins`` pixels (a round-off drift of 10⁵
    samples is noise the SVG would otherwise carry point by point); the archive keeps
    every sample.  Short series are returned as they are."""
    t, values = np.asarray(t), np.asarray(values)
    n = values.size
    if n <= ENVELOPE_ABOVE or n < 4 * bins:
        return t, values
    edges = np.linspace(0, n, bins + 1).astype(int)
    out = np.empty(2 * bins, dtype=int)
    for k in range(bins):  # 2000 small argmin/argmax calls: ~5 ms
        lo, hi = edges[k], edges[k + 1]
        a, b = lo + int(np.argmin(values[lo:hi])), lo + int(np.argmax(values[lo:hi]))
        out[2 * k], out[2 * k + 1] = min(a, b), max(a, b)
    keep = np.unique(np.concatenate([[0], out, [n - 1]]))
    return t[keep], values[keep]


def time_label(unit: str = "s") -> str:
    """The time axis's label, "time t [s]"; a scaled time ("1", "dimensionless" or "")
    is "time t (dimensionless)"."""
    if unit in ("", "1", "dimensionless"):
        return "time t (dimensionless)"
    return f"time t [{unit}]"


#: the y label of a relative drift: a ratio of like quantities (the scale is the one the
#: scene declares for each quantity, else the quantity's own largest size)
DRIFT_LABEL = "drift (I(t) − I(0)) / scale (dimensionless)"


def invariant_drift(t, invariants: dict[str, np.ndarray], *, scales=None, time_unit="s",
                    labels=None, ax=None):
    """Relative drift (I(t) - I(0)) / scale of each conserved quantity against time."""
    fig, ax = new_figure(ax)
    scales = scales or {}
    labels = labels or {}
    for name, values in invariants.items():
        values = np.asarray(values)
        scale = scales.get(name) or max(abs(values[0]), np.max(np.abs(values)), 1e-300)
        with np.errstate(invalid="ignore"):  # a failed run's NaN tail is left out
            drift = (values - values[0]) / scale
        ax.plot(*envelope(t, drift), label=labels.get(name, name))
    ax.set_xlabel(time_label(time_unit))
    ax.set_ylabel(DRIFT_LABEL)
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-2, 2))
    place_legend(ax)
    return fig


def error_against_time(t, errors: dict[str, np.ndarray], *, time_unit="s",
                       ylabel="absolute error", unit: str | None = None, ax=None):
    """Absolute error of one or more quantities against time, log scale.

    ``unit``: the errors' common unit for the y label; None when each series names its
    own in its label ("|θ − θ_exact| [rad]"), and the label says so."""
    fig, ax = new_figure(ax)
    exact = []
    for name, err in errors.items():
        err = np.abs(np.asarray(err))
        if not np.any(err > 0):
            exact.append(name)  # nothing to draw on a log scale: said in words instead
            continue
        tt, ee = envelope(t, np.maximum(err, 1e-300))
        # an error of exactly 0 is a gap in the line, not a floor drawn as a solid block
        ax.semilogy(tt, np.where(ee > 1e-300, ee, np.nan), label=name)
    if exact:
        ax.text(0.02, 0.03, "exactly 0 throughout: " + ", ".join(exact),
                transform=ax.transAxes, fontsize=8, color="0.3")
    ax.set_xlabel(time_label(time_unit))
    ax.set_ylabel(f"{ylabel} [{unit if unit is not None else 'unit of each series'}]")
    place_legend(ax)
    return fig


def work_precision(study: np.ndarray, *, error_field="error_max", ax=None):
    """Log-log work-precision diagram: error against wall time, one line per method.

    Our methods are solid lines with filled markers; peers (scipy, heyoka) dashed, hollow.
    """
    fig, ax = new_figure(ax, figsize=(6.8, 5.6))
    methods = list(dict.fromkeys(study["method"]))
    # every method its own colour (the palette's 7 and five more); past those a method
    # sharing a colour with an earlier one differs from it in marker shape and line
    markers = "osD^v<>PX*hd"
    for i, method in enumerate(methods):
        rows = study[(study["method"] == method)  # an inaccurate run is measured too (issue 31)
                     & np.isin(study["status"], ("ok", "inaccurate"))]
        err = np.asarray(rows[error_field], dtype=float)
        time = np.asarray(rows["wall_time_s"], dtype=float)
        keep = np.isfinite(err) & np.isfinite(time) & (time > 0)
        if not keep.any():
            continue
        order = np.argsort(time[keep])
        peer = is_peer(method)
        ax.loglog(
            time[keep][order], np.maximum(err[keep][order], 1e-17),
            color=MANY_SERIES[i % len(MANY_SERIES)],
            linestyle="--" if peer else ("-" if i < len(MANY_SERIES) else "-."),
            # past the palette's length the markers shift by one, so that a method sharing
            # a colour with an earlier one differs from it in marker too
            marker=markers[(i + i // len(MANY_SERIES)) % len(markers)],
            markerfacecolor="none" if peer else None,
            label=str(rows["label"][0]),
        )
    ax.set_xlabel("wall time per run [s]  (min of repeats, compile time excluded)")
    ax.set_ylabel("max error over the run [units of the state]")
    legend_below(fig)
    return fig


def timeseries_against_reference(t, numeric: dict[str, np.ndarray],
                                 reference: dict[str, np.ndarray], *, ylabels,
                                 time_unit="s", reference_label="exact",
                                 extra: dict[str, np.ndarray] | None = None):
    """One panel per quantity: the integration (solid) over the reference (dashed)."""
    names = list(numeric)
    fig, axes = new_figure_grid(len(names), 1, figsize=(6.8, 2.2 * len(names) + 0.8), sharex=True)
    for ax, name in zip(axes[:len(names), 0], names, strict=True):
        ax.plot(t, numeric[name], color=HIGHLIGHT, label="integrated")
        if name in reference:
            ax.plot(t, reference[name], color=REFERENCE, linestyle=(0, (4, 3)),
                    label=reference_label)
        if extra and name in extra:
            ax.plot(t, extra[name], color=CONTEXT, linestyle=":", label="small-angle, notes (1.19)")
        ax.set_ylabel(ylabels[name])
    place_legend(axes[0, 0], loc="upper right")
    axes[-1, 0].set_xlabel(time_label(time_unit))
    return fig


#: sweep figures: at most this many panels (results) and lines (other keys' values)
SWEEP_MAX_PANELS = 6
SWEEP_MAX_LINES = 6


def key_value_text(key: tuple[str, str], value: float) -> str:
    """A swept key's value for a legend: "$\\theta_0$ = 0.5 rad" from ``key`` = (symbol
    or description, typeset unit)."""
    symbol, unit = key
    unit = "" if unit in ("", "dimensionless") else f" {unit}"
    return f"{symbol} = {value:.4g}{unit}"


def key_axis_label(key: tuple[str, str]) -> str:
    """A swept key as an axis label, "$\\theta_0$ [rad]", from (symbol, typeset unit)."""
    symbol, unit = key
    return f"{symbol} [{unit}]" if unit else f"{symbol} (dimensionless)"


def sweep_results(values: dict[str, np.ndarray], analysis: dict[str, np.ndarray], ok,
                  paired: bool = False, *, keys: dict[str, tuple[str, str]],
                  ylabels: dict[str, str]):
    """One panel per scalar result (at most six) against the first swept key; with more
    keys on a grid, one line per combination of the others' values (at most six, else
    points); ``paired`` keys (zip) vary together: one line.

    ``keys``: each swept config key as (symbol or description, typeset unit), for the x
    label and the legend; ``ylabels``: each result's axis label (from its declaration)."""
    paths = list(values)
    x = np.asarray(values[paths[0]])
    ok = np.asarray(ok, dtype=bool)
    names = list(analysis)[:SWEEP_MAX_PANELS]
    cols = 1 if len(names) <= 3 else 2
    rows = -(-len(names) // cols)
    fig, grid = new_figure_grid(rows, cols, figsize=(6.4, 1.2 + 1.9 * rows), sharex=True)
    axes = grid.reshape(-1, 1)
    for ax in axes[len(names):, 0]:
        ax.set_visible(False)
    others = [] if paired else paths[1:]
    if others:
        keys = np.stack([np.asarray(values[p]) for p in others], axis=1)
        groups, inverse = np.unique(keys, axis=0, return_inverse=True)
        inverse = inverse.ravel()
    else:
        groups, inverse = np.zeros((1, 0)), np.zeros(x.size, dtype=int)
    as_lines = len(groups) <= SWEEP_MAX_LINES
    for ax, name in zip(axes[:len(names), 0], names, strict=True):
        y = np.asarray(analysis[name], dtype=float)
        for g, combo in enumerate(groups if as_lines else groups[:1]):
            pick = ok & np.isfinite(y) & ((inverse == g) if as_lines else True)
            order = np.argsort(x[pick])
            label = ", ".join(key_value_text(keys[p], v) for p, v in zip(others, combo,
                                                                          strict=True))
            style = dict(marker="o", markersize=2.5) if pick.sum() < 60 else {}
            if as_lines:  # a dense family as per-bin extremes: same pixels, bounded size
                ax.plot(*envelope(x[pick][order], y[pick][order]), label=label or None,
                        **style)
            else:
                ax.plot(*envelope(x[pick][order], y[pick][order]), **dots(1.4))
        # a long label (a description, no mathtext) wrapped to the panel's height
        label = ylabels.get(name, name)
        ax.set_ylabel(label if "$" in label else textwrap.fill(label, 26))
        if as_lines and others and name == names[0]:  # one legend serves every panel
            place_legend(ax, fontsize=8)
    for column in grid.T:  # the lowest visible panel of each column (an odd count of
        shown = [ax for ax in column if ax.get_visible()]  # results hides the last one)
        if shown:
            shown[-1].set_xlabel(key_axis_label(keys[paths[0]]))
            shown[-1].tick_params(labelbottom=True)
    return fig


def member_runs(runs: dict, labels: dict[str, str], *, ylabel: str, time_unit: str = "s"):
    """The first coordinate of each kept member of a sweep against time (``ylabel``: its
    declared label), one colour each."""
    fig, ax = new_figure()
    for i, (name, run) in enumerate(runs.items()):
        ax.plot(*envelope(run.t, run.y[:, 0]), color=MANY_SERIES[i % len(MANY_SERIES)],
                linestyle="-" if i < len(MANY_SERIES) else "--", label=labels.get(name, name))
    ax.set_ylabel(ylabel)
    ax.set_xlabel(time_label(time_unit))
    if runs:
        place_legend(ax, fontsize=8, outside="right")
    return fig


def family_lines(x, lines, *, reference=None, xlabel, ylabel, label="", reference_label=""):
    """Several results of every member against the swept value (a spectrum, say): one
    line each, in the palette's order; ``reference`` (same shapes) dashed on top."""
    fig, ax = new_figure()
    x = np.asarray(x)
    order = np.argsort(x)
    for j, y in enumerate(lines):
        line, = ax.plot(*envelope(x[order], np.asarray(y)[order]), "o-" if x.size < 40 else "-",
                        ms=3, label=f"{label}{j + 1}" if label else None)
        if reference is not None:
            ax.plot(*envelope(x[order], np.asarray(reference[j])[order]), "--",
                    color=REFERENCE, lw=1.0,
                    label=reference_label if j == 0 and reference_label else None)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if label or reference_label:
        place_legend(ax, fontsize=8, ncols=2 if len(lines) > 4 else 1)
    return fig


def family_against_reference(x, measured, exact, *, xlabel, ylabel, measured_label,
                             exact_label):
    """A result of every member against a swept (or derived) value, with its closed form
    (per member: open circles, since a derived ``x`` need not order the members into a
    curve), and below the relative difference of each member."""
    fig, (ax, ax_err) = new_figure_grid(2, 1, figsize=(6.4, 5.2), sharex=True)
    ax, ax_err = ax[0], ax_err[0]
    order = np.argsort(x)
    x = np.asarray(x)[order]
    y, ref = np.asarray(measured)[order], np.asarray(exact)[order]
    dense = x.size > 80
    ax.plot(*envelope(x, ref), "o", mfc="none", color=REFERENCE, ms=7, mew=1.5,
            label=exact_label)
    ax.plot(*envelope(x, y), color=HIGHLIGHT, label=f"{measured_label} ({x.size} members)",
            **member_markers(dense))
    ax.set_ylabel(ylabel)
    legend = place_legend(ax)
    if dense:  # the legend's sample of the dots at a size one can see
        legend.legend_handles[1].set_markersize(4.0)
    rel = np.maximum(np.abs(y / ref - 1), 1e-17)
    ax_err.semilogy(*envelope(x, rel), color=HIGHLIGHT, **member_markers(dense))
    ax_err.set_ylabel("relative difference (dimensionless)")
    ax_err.set_xlabel(xlabel)
    return fig
