"""Figures of the normal-mode scene: spectrum, mode shapes, phase snapshots, evolution."""

from __future__ import annotations

import math

import numpy as np

from ...rendering.plots.common import time_label
from ...rendering.plots.style import (
    ATOM_COLOURS,
    BLUE,
    CONTEXT,
    GREEN,
    HIGHLIGHT,
    INDIGO,
    OLIVE,
    ORANGE,
    OTHER_ATOM,
    PURPLE,
    REFERENCE,
    SKY,
    VERMILLION,
    WINE,
    new_figure,
    new_figure_grid,
    place_legend,
)

#: colours of the named mode types, in the order the types first appear
TYPE_COLOURS = (BLUE, VERMILLION, GREEN, PURPLE, ORANGE, SKY, WINE, INDIGO, OLIVE)
#: atoms dark enough for a white element symbol
DARK_ATOMS = frozenset({"C", "O", "N", "Cl"})


def spectrum(omega, types, groups, *, exact=None, unit="rad/s",
             quantity="angular frequency ω", named=True, ax=None):
    """Stick spectrum of the vibrational frequencies, degenerate sets marked ×g.

    omega : (k,) ascending, types : k labels, groups : (k,) degenerate-set ids;
    exact : (k,) closed-form frequencies drawn as hollow markers, or None;
    ``quantity`` and ``unit`` name the x axis ("wavenumber ν̃", "cm⁻¹"; a unit
    "dimensionless" or "" is printed as "(dimensionless)"); ``named``: the types name the
    modes (a molecule's "C–O stretch": one colour and legend entry each, the
    "(in-plane)"-like qualifier dropped), else every stick is a "normal mode".
    """
    fig, ax = new_figure(ax, figsize=(6.8, 3.2))
    omega = np.asarray(omega, dtype=float)
    colours: dict[str, str] = {}
    for gid in dict.fromkeys(np.asarray(groups).tolist()):
        idx = [i for i, g in enumerate(groups) if g == gid]
        w = omega[idx[0]]
        base = types[idx[0]].split(" (")[0] if named else "normal mode"
        label = base if base not in colours else None
        if base not in colours:
            colours[base] = (TYPE_COLOURS[len(colours) % len(TYPE_COLOURS)] if named
                             else HIGHLIGHT)
        ax.vlines(w, 0, len(idx), color=colours[base], lw=3, label=label)
        if len(idx) > 1:
            ax.annotate(f"×{len(idx)}", (w, len(idx)), textcoords="offset points",
                        xytext=(0, 3), ha="center", fontsize=9)
    if exact is not None:
        ax.plot(exact, np.full(len(exact), 0.5), "o", mfc="none", color=REFERENCE, ms=7,
                label="closed form")
    ax.set_xlabel(f"{quantity} (dimensionless)" if unit in ("", "1", "dimensionless")
                  else f"{quantity} [{unit}]")
    ax.set_ylabel("multiplicity (dimensionless)")
    top = max([int(np.sum(np.asarray(groups) == g)) for g in set(np.asarray(groups).tolist())]
              or [1])
    ax.set_ylim(0, top + 0.6)
    ax.set_yticks(range(0, top + 1))
    positive = omega[omega > 0]
    if positive.size and positive.max() > 30 * positive.min():  # widely separated: log axis
        ax.set_xscale("log")
        ax.set_xlim(positive.min() / 2, positive.max() * 2)
    else:
        ax.set_xlim(0, 1.08 * float(np.max(omega)) if omega.size else 1.0)
    place_legend(ax, loc="upper left", fontsize=8, outside="right")
    return fig


def _draw_molecule(ax, xy, elements, bonds, *, alpha=1.0, size=None, labels=False,
                   fontsize=8.0):
    """Bonds and atoms (CPK colours, area by mass); ``labels``: each atom's element
    symbol on it."""
    for i, j in bonds:
        ax.plot([xy[i, 0], xy[j, 0]], [xy[i, 1], xy[j, 1]], color=CONTEXT, lw=3, alpha=alpha,
                zorder=1, solid_capstyle="round")
    for a, (x, y) in enumerate(xy):
        ax.scatter([x], [y], s=size[a], color=ATOM_COLOURS.get(elements[a], OTHER_ATOM),
                   edgecolor="black", lw=0.8, alpha=alpha, zorder=2)
        if labels and elements[a]:
            ax.text(x, y, elements[a], ha="center", va="center", fontsize=fontsize,
                    color="white" if elements[a] in DARK_ATOMS else "black", zorder=7)


def _atom_sizes(masses):
    m = np.asarray(masses, dtype=float)
    return 120 + 260 * np.sqrt(m / m.max())


def _box(points: list[np.ndarray], span: float):
    """(xmin, xmax, ymin, ymax) around every point set, with a margin for the atom discs."""
    allp = np.vstack(points)
    pad = 0.12 * span
    return (allp[:, 0].min() - pad, allp[:, 0].max() + pad,
            allp[:, 1].min() - pad, allp[:, 1].max() + pad)


def _bare(ax, box):
    ax.set_aspect("equal")
    ax.set_xlim(box[0], box[1])
    ax.set_ylim(box[2], box[3])
    ax.set_xticks([])
    ax.set_yticks([])
    ax.grid(False)
    for side in ("left", "bottom"):
        ax.spines[side].set_visible(False)


def _scaled(displacements, span, share, *, pos=None, bonds=(), stretch=None):
    """Each displacement scaled so its largest atom moves ``share`` × span; with ``pos``
    (n, k) and ``bonds``, also so no bond's length changes by more than ``stretch`` of
    itself (CO₂'s stretches otherwise drew an O on top of the C)."""
    out = []
    for d in displacements:
        d = np.asarray(d, dtype=float)
        amp = float(np.max(np.linalg.norm(d, axis=1))) or 1.0
        factor = share * span / amp
        if stretch is not None and pos is not None:
            for i, j in bonds:
                bond = pos[i] - pos[j]
                length = float(np.linalg.norm(bond))
                # the length change to first order: the relative motion along the bond
                change = abs(float((d[i, :pos.shape[1]] - d[j, :pos.shape[1]]) @ bond)) / (
                    length or 1.0)
                if length > 0 and change > 0:
                    factor = min(factor, stretch * length / change)
        out.append(d * factor)
    return out


def molecule_modes(xy, masses, elements, bonds, displacements, titles):
    """One panel per mode: the molecule at equilibrium with displacement arrows.

    xy : (n, 2) equilibrium positions in the drawing plane; displacements: list of
    (n, 3) arrays in the drawing frame (e1, e2 in the plane, e3 toward the viewer),
    drawn as arrows (in-plane part) and ⊙/⊗ (out-of-plane part); faint atoms show
    the extreme phases ωt = 0 and π.
    """
    k = len(displacements)
    ncols = min(2 if k <= 4 else 3, k)
    nrows = math.ceil(k / ncols)
    xy = np.asarray(xy, dtype=float)
    span = float(np.max(np.ptp(xy, axis=0))) if len(xy) > 1 else 1.0
    span = span or 1.0
    ds = _scaled(displacements, span, 0.35)
    box = _box([xy] + [xy + d[:, :2] for d in ds] + [xy - d[:, :2] for d in ds], span)
    box = (box[0], box[1], min(box[2], -0.12 * span), max(box[3], 0.22 * span))
    ratio = (box[3] - box[2]) / (box[1] - box[0])
    width = 3.4
    fig, axes = new_figure_grid(nrows, ncols, figsize=(width * ncols,
                                                        nrows * (width * ratio + 0.45)))
    sizes = _atom_sizes(masses)
    for ax in axes.ravel()[k:]:
        ax.set_visible(False)
    for ax, d, title in zip(axes.ravel(), ds, titles, strict=False):
        for sgn in (1.0, -1.0):
            _draw_molecule(ax, xy + sgn * d[:, :2], elements, bonds, alpha=0.18, size=sizes)
        _draw_molecule(ax, xy, elements, bonds, size=sizes, labels=True)
        for a in range(len(xy)):
            if np.hypot(d[a, 0], d[a, 1]) > 0.02 * span:
                ax.annotate("", xy=(xy[a, 0] + d[a, 0], xy[a, 1] + d[a, 1]), xytext=tuple(xy[a]),
                            arrowprops={"arrowstyle": "-|>,head_width=0.3,head_length=0.6",
                                        "color": HIGHLIGHT, "lw": 2.2, "shrinkA": 0,
                                        "shrinkB": 0}, zorder=5)
            if abs(d[a, 2]) > 0.02 * span:
                mark = "⊙" if d[a, 2] > 0 else "⊗"
                ax.annotate(mark, (xy[a, 0], xy[a, 1]), textcoords="offset points",
                            xytext=(0, 12), ha="center", va="bottom", color=HIGHLIGHT,
                            fontsize=10 + 8 * abs(d[a, 2]) / (0.35 * span), zorder=6)
        ax.set_title(title, fontsize=9)
        _bare(ax, box)
    return fig


PHASE_LABELS = {0: "0", 1: "π/4", 2: "π/2", 3: "3π/4", 4: "π"}


def molecule_snapshots(pos, masses, elements, bonds, displacements, titles):
    """Rows = modes, columns = phases ωt = 0, π/4, …, π: the displaced molecule.

    pos : (n, 3) equilibrium positions in the drawing frame; displacements (n, 3)
    each.  A mode moving mostly along e3 (out of the drawing plane) is drawn in
    the (e1, e3) plane instead, and its row says so.
    """
    k = len(displacements)
    pos = np.asarray(pos, dtype=float)
    span = float(np.max(np.ptp(pos[:, :2], axis=0))) or 1.0
    ds = _scaled(displacements, span, 0.25, pos=pos, bonds=bonds, stretch=0.3)
    views = []
    for d in ds:
        out_of_plane, in_plane = float(np.sum(d[:, 2] ** 2)), float(np.sum(d[:, 1] ** 2))
        side = out_of_plane > in_plane and out_of_plane > 1e-6 * float(np.sum(d * d))
        views.append((0, 2) if side else (0, 1))
    box = _box([pos[:, v] + s * d[:, v] for d, v in zip(ds, views, strict=True)
                for s in (-1, 1)] + [pos[:, [0, 1]]], span)
    box = (box[0], box[1], min(box[2], -0.1 * span), max(box[3], 0.1 * span))
    ratio = (box[3] - box[2]) / (box[1] - box[0])
    phases = len(PHASE_LABELS)
    width = 1.45
    fig, axes = new_figure_grid(k, phases, figsize=(width * phases + 1.2,
                                                    k * (width * ratio + 0.15) + 0.4))
    sizes = _atom_sizes(masses) * 0.4
    for r, (d, v, title) in enumerate(zip(ds, views, titles, strict=True)):
        base = pos[:, list(v)]
        for c in range(phases):
            ax = axes[r, c]
            _draw_molecule(ax, base, elements, bonds, alpha=0.12, size=sizes)
            _draw_molecule(ax, base + math.cos(math.pi * c / (phases - 1)) * d[:, list(v)],
                           elements, bonds, size=sizes, labels=c == 0, fontsize=6.0)
            _bare(ax, box)
            if r == 0:
                ax.set_title(f"ωt = {PHASE_LABELS[c]}", fontsize=9)
        label = title + ("\n(side view)" if v == (0, 2) else "")
        axes[r, 0].set_ylabel(label, fontsize=8, rotation=0, ha="right", va="center")
    return fig


def chain_modes(modes, titles, *, coordinate="q", exact_shapes=None, ncols=2):
    """One panel per mode: amplitude of every mass (stems) against its index.

    modes : (n, k) columns to draw; exact_shapes : None or (s, waves) with s (m,) the
    mass index over 0..N+1 and waves (m, k) the closed-form standing waves
    sin(j s π/(N+1)) (scaled and signed like the columns), drawn dashed.
    """
    n, k = modes.shape
    ncols = min(ncols, k)
    nrows = math.ceil(k / ncols)
    # shared axes: the inner panels' tick labels (and so their axis labels) are left out
    fig, axes = new_figure_grid(nrows, ncols, figsize=(3.5 * ncols, 1.9 * nrows + 0.4),
                                sharex=True, sharey=True)
    s = np.arange(1, n + 1)
    for ax in axes.ravel()[k:]:
        ax.set_visible(False)
    for j, ax in enumerate(axes.ravel()[:k]):
        v = modes[:, j] / np.max(np.abs(modes[:, j]))
        ax.axhline(0, color=CONTEXT, lw=0.8)
        ax.vlines(s, 0, v, color=HIGHLIGHT, lw=2)
        ax.plot(s, v, "o", color=HIGHLIGHT, ms=6)
        if exact_shapes is not None:
            fine, waves = exact_shapes
            ax.plot(fine, waves[:, j], "--", color=REFERENCE, lw=1)
        ax.set_title(titles[j], fontsize=9)
        ax.set_ylim(-1.25, 1.25)
        ax.set_xlim(0, n + 1)
        if j % ncols == 0:
            ax.set_ylabel(f"{coordinate}/max|{coordinate}| (dimensionless)", fontsize=9)
    for ax in axes[-1, :]:
        ax.set_xlabel("mass index s (dimensionless)")
    return fig


def matrix_modes(modes, titles, names):
    """Bar chart of the components of each mode (a system given as matrices M and A)."""
    n, k = modes.shape
    fig, axes = new_figure_grid(k, 1, figsize=(6.4, 1.5 * k + 0.6), sharex=True)
    for j in range(k):
        ax = axes[j, 0]
        v = modes[:, j] / np.max(np.abs(modes[:, j]))
        ax.bar(np.arange(n), v, color=HIGHLIGHT)
        ax.axhline(0, color=CONTEXT, lw=0.8)
        ax.set_ylim(-1.2, 1.2)
        ax.set_ylabel("η/max|η| (dimensionless)", fontsize=8)
        ax.set_title(titles[j], fontsize=9)
    axes[-1, 0].set_xticks(np.arange(n))
    axes[-1, 0].set_xticklabels(names)
    axes[-1, 0].set_xlabel("coordinate")
    return fig


def evolution(t, direct, modal, names, *, time_unit="s", unit=""):
    """Direct integration (solid) over the modal superposition (dashed), and their
    difference; ``names``: the coordinates' axis labels, ``unit`` their common unit."""
    k = len(names)
    fig, axes = new_figure_grid(k + 1, 1, figsize=(6.8, 1.7 * (k + 1) + 0.6), sharex=True)
    for i, name in enumerate(names):
        ax = axes[i, 0]
        ax.plot(t, direct[:, i], color=HIGHLIGHT, label="direct integration")
        ax.plot(t, modal[:, i], color=REFERENCE, ls=(0, (4, 3)), label="modal superposition")
        ax.set_ylabel(name)
    place_legend(axes[0, 0], loc="upper right", fontsize=8)
    ax = axes[-1, 0]
    err = np.max(np.abs(direct - modal), axis=1)
    ax.semilogy(t, np.maximum(err, 1e-18), color=HIGHLIGHT)
    what = r"max $|q - q_\mathrm{modal}|$"
    ax.set_ylabel(f"{what} (dimensionless)" if unit in ("", "1", "dimensionless")
                  else f"{what} [{unit}]")
    ax.set_xlabel(time_label(time_unit))
    return fig
