"""One figure style for every report: readable at slide size, labelled axes with units."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

from matplotlib.figure import Figure  # noqa: E402 - pyplot is never imported (0.3 s)

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


def new_figure_grid(nrows, ncols, *, figsize=None, sharex=False):
    fig = Figure(figsize=figsize or RC["figure.figsize"], layout="constrained")
    axes = fig.subplots(nrows, ncols, sharex=sharex, squeeze=False)
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
