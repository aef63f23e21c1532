"""One figure style for every report: readable at slide size, labelled axes with units."""

from __future__ import annotations

import matplotlib

# No ``matplotlib.use``: figures are ``Figure`` objects that pyplot never sees, saved by
# the canvas of their format (Agg for PNG), so no backend is chosen here; choosing one
# switched a notebook's pyplot away from its inline backend, and switching back did not
# bring back its PNG display (issue 43)
from matplotlib.figure import Figure  # pyplot is never imported (0.3 s)

RC = {
    "figure.figsize": (6.4, 4.0),
    "figure.dpi": 100,
    "savefig.dpi": 150,
    "font.size": 11,
    "axes.titlesize": 12,
    "axes.labelsize": 11,
    "legend.fontsize": 9,
    "legend.framealpha": 0.85,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "lines.linewidth": 1.5,
    "axes.spines.top": False,
    "axes.spines.right": False,
    # one family with the mathematics (issue 41): STIX, which matplotlib ships, for the
    # words, the numbers and the mathtext of every figure, as for the report's body text
    # and its typeset equations (reportgen.rendering.equations)
    "font.family": "STIXGeneral",
    "mathtext.fontset": "stix",
    "svg.fonttype": "none",
    "pdf.fonttype": 42,
    "axes.prop_cycle": matplotlib.cycler(color=[]),  # set below: PALETTE
}

#: Okabe & Ito's colour-blind-safe palette ("Color Universal Design", 2008): the line
#: colours of every figure, in cycle order.  Under simulated deuteranopia, protanopia and
#: tritanopia (Machado et al. 2009) every pair stays at least 16 CIELAB units apart
#: (tests/test_style.py); the palette it replaced had a red and a green 3.5 apart.
BLUE, VERMILLION, GREEN, PURPLE = "#0072B2", "#D55E00", "#009E73", "#CC79A7"
ORANGE, SKY, BLACK = "#E69F00", "#56B4E9", "#000000"
PALETTE = (BLUE, VERMILLION, GREEN, PURPLE, ORANGE, SKY, BLACK)
RC["axes.prop_cycle"] = matplotlib.cycler(color=list(PALETTE))
matplotlib.rcParams.update(RC)

#: colours past the palette's seven, for a figure of many series that must each have its
#: own (the work-precision diagram's dozen methods): Paul Tol's wine, indigo, sand and
#: olive and a mid grey.  With the palette, every pair stays at least 22 CIELAB units apart
#: in normal vision and 9 under simulated colour-vision deficiency (tests/test_style.py);
#: the markers and line styles differ too.
WINE, INDIGO, SAND, OLIVE, MID_GREY = "#882255", "#332288", "#DDCC77", "#999933", "#7F7F7F"
MANY_SERIES = (*PALETTE, WINE, INDIGO, SAND, OLIVE, MID_GREY)


def _share_text_to_path() -> None:
    """Let every renderer use matplotlib's one module-level TextToPath.

    Each renderer (one per savefig) builds its own ``TextToPath`` in
    ``RendererBase.__init__``, and that instance's ``MathTextParser`` is part of the key
    of matplotlib's mathtext cache: so every save re-parses every mathtext string
    (log-axis tick labels ``10^{-4}``, offset texts) with pyparsing, several ms each --
    half the SVG save time of a figure with log axes.  The parse depends only on the
    string and the font properties, so sharing the instance changes no output byte.
    Skipped if matplotlib's internals are not what this expects.
    """
    import matplotlib.text as mtext
    import matplotlib.textpath as mtextpath

    if (getattr(mtext, "TextToPath", None) is not mtextpath.TextToPath
            or not isinstance(getattr(mtextpath, "text_to_path", None), mtextpath.TextToPath)):
        return

    shared = mtextpath.text_to_path

    class SharedTextToPath(mtextpath.TextToPath):
        """``TextToPath()`` returning the shared instance (it holds no per-figure state)."""

        def __new__(cls):
            return shared

    mtext.TextToPath = SharedTextToPath


_share_text_to_path()

#: colours with a meaning, used the same way in every figure
HIGHLIGHT = VERMILLION  # the scene's own orbit / numerical result
REFERENCE = BLUE  # exact or reference solution
CONTEXT = "#9a9a9a"  # families of curves for context
SEPARATRIX = ORANGE
INK = "#404040"  # drawn objects: rods, springs, box edges
GREY = "#7f7f7f"
#: atoms by element, after the CPK convention chemists read at a glance
ATOM_COLOURS = {"H": "#d9d9d9", "C": "#404040", "O": "#d62728", "N": "#1f77b4",
                "S": "#e6c229", "Cl": "#2ca02c"}
OTHER_ATOM = PURPLE


def dots(size: float = 1.6) -> dict:
    """Line style of a dense cloud of points (hundreds to thousands): small filled squares
    without an edge, ``size`` points wide.  At print size they read as dots; in the PDF
    each is 4 path vertices instead of a circle's 13 Bézier points, which WeasyPrint
    parses one by one (2000 circles were 0.3 s of a sweep report's PDF)."""
    return {"marker": "s", "markersize": size, "markeredgewidth": 0.0, "linestyle": "none"}


def member_markers(dense: bool) -> dict:
    """Line style of a family's members, one point each: :func:`dots` when ``dense``,
    else 3.5-point circles."""
    return dots() if dense else {"marker": "o", "markersize": 3.5, "linestyle": "none"}


def new_figure(ax=None, *, figsize=None, projection=None):
    """(fig, ax): the given axes and its figure, or a new Figure (not registered with pyplot)."""
    if ax is not None:
        return ax.figure, ax
    fig = Figure(figsize=figsize or RC["figure.figsize"], layout="constrained")
    ax = fig.add_subplot(projection=projection)
    return fig, ax


def new_figure_grid(nrows, ncols, *, figsize=None, sharex=False, sharey=False):
    fig = Figure(figsize=figsize or RC["figure.figsize"], layout="constrained")
    axes = fig.subplots(nrows, ncols, sharex=sharex, sharey=sharey, squeeze=False)
    return fig, axes


def legend_below(fig, *, fontsize: float = 8, max_columns: int = 3):
    """The figure's legend under its axes, in as many columns (at most ``max_columns``) as
    fit the figure's width: long labels (``Gauss–Legendre 3-stage (numba, implicit)``) in
    three columns ran past both edges of a 6.8-inch work-precision diagram."""
    for ncols in range(max_columns, 0, -1):
        legend = fig.legend(loc="outside lower center", ncols=ncols, fontsize=fontsize,
                            frameon=False)
        if ncols == 1 or legend.get_window_extent().width <= 0.98 * fig.bbox.width:
            return legend
        legend.remove()


#: where :func:`place_legend` tries a legend inside the axes, in order
INSIDE_LOCATIONS = ("upper right", "upper left", "lower left", "lower right", "center right",
                    "center left", "upper center", "lower center")


def place_legend(ax, *, loc: str | None = None, outside: str = "above", margin: float = 0.02,
                 **kwargs):
    """The axes' legend where it covers no plotted data: ``loc`` if that is clear, else the
    first clear corner or edge of :data:`INSIDE_LOCATIONS`, else outside the axes
    (``outside`` = "above" the frame, in as many columns as fit its width, or to the
    "right").  "Clear": no vertex, marker or point of a line drawn between two vertices
    (lines in data coordinates and scatters) falls within the legend's frame grown by
    ``margin`` (a fraction of the axes).  The axes' limits must be final; the layout engine
    may still resize the axes (it only grows them here, so a clear place stays clear).
    ``kwargs`` go to ``ax.legend``.  Returns the legend (None if nothing is labelled)."""
    handles, labels = ax.get_legend_handles_labels()
    if not handles and "handles" not in kwargs:
        return None
    legend = ax.legend(loc=loc or INSIDE_LOCATIONS[0], **kwargs)
    renderer = ax.figure._get_renderer()
    points = _data_points_in_axes(ax)
    to_axes = ax.transAxes.inverted()
    for where in dict.fromkeys([loc, *INSIDE_LOCATIONS] if loc else INSIDE_LOCATIONS):
        legend.set_loc(where)
        box = legend.get_window_extent(renderer).transformed(to_axes)
        inside = ((points[:, 0] > box.x0 - margin) & (points[:, 0] < box.x1 + margin)
                  & (points[:, 1] > box.y0 - margin) & (points[:, 1] < box.y1 + margin))
        if not inside.any():
            return legend
    legend.remove()
    if outside == "right":
        return ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                         **kwargs)
    n = len(labels) if "handles" not in kwargs else len(kwargs["handles"])
    kwargs.pop("ncols", None)
    kwargs.pop("ncol", None)
    # above a linear y axis, clear of its offset text ("1e−11") at the top left
    pad = 1.3 if ax.get_yscale() == "linear" else 0.0
    if ax.get_aspect() != "auto" and ax.get_adjustable() == "box":
        ax.apply_aspect()  # an equal-aspect axes' frame is only final once applied
    for ncols in range(min(n, 4), 0, -1):
        # measured at its natural width: "expand" stretches any legend to the axes' width,
        # so four long entries squeezed into one row would pass as fitting and overprint
        legend = ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0, 1.0, 0.1),
                           borderaxespad=pad, ncols=ncols, **kwargs)
        fits = legend.get_window_extent(renderer).width <= ax.bbox.width * 1.001
        legend.remove()
        if ncols == 1 or fits:
            return ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0, 1.0, 0.1),
                             mode="expand" if ncols > 1 else None, borderaxespad=pad,
                             ncols=ncols, **kwargs)
    return legend


def _data_points_in_axes(ax, step: float = 0.01):
    """Every plotted point of ``ax`` in axes fractions, shape (n, 2): the vertices of its
    lines in data coordinates with points every ``step`` between them, and the offsets of
    its scatters."""
    import numpy as np

    ax.get_xlim(), ax.get_ylim()  # brings the autoscaled limits up to date
    if ax.get_aspect() != "auto":
        ax.apply_aspect()
    to_axes = ax.transAxes.inverted()
    parts = [np.zeros((0, 2))]
    for line in ax.get_lines():
        if not line.get_visible() or line.get_transform() != ax.transData:
            continue
        xy = np.asarray(line.get_xydata(), dtype=float)
        xy = to_axes.transform(ax.transData.transform(xy[np.isfinite(xy).all(axis=1)]))
        if len(xy) > 1 and str(line.get_linestyle()) not in ("None", "none", "", " "):
            gap = np.hypot(*np.diff(xy, axis=0).T)
            count = np.minimum(np.ceil(gap / step), 200).astype(int)
            seg = np.repeat(np.arange(len(gap)), count)
            frac = (np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)) \
                / np.repeat(np.maximum(count, 1), count)
            xy = np.concatenate([xy, xy[seg] + frac[:, None] * (xy[seg + 1] - xy[seg])])
        parts.append(xy)
    for coll in ax.collections:
        offsets = getattr(coll, "get_offsets", lambda: [])()
        if not coll.get_visible():
            continue
        if coll.get_transform() == ax.transData:  # contour lines, line collections
            parts += [to_axes.transform(ax.transData.transform(path.vertices))
                      for path in coll.get_paths() if len(path.vertices)]
        elif len(offsets) and coll.get_offset_transform() == ax.transData:  # scatters
            parts.append(to_axes.transform(ax.transData.transform(np.asarray(offsets))))
    points = np.concatenate(parts)
    inside = (points > -0.01).all(axis=1) & (points < 1.01).all(axis=1)
    return points[inside]
