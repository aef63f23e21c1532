"""The last step before a figure is saved: its words typeset and its axes' multipliers
folded into their labels (issue 41).

A figure's text goes through the same typesetter as the page's
(:func:`reportgen.scene.typeset.figure_text`): U+2212 for a minus, a × 10ⁿ for
E-notation, real subscripts.  An axis whose ticks matplotlib would print with an offset
or a multiplier above it ("1e−11", "+1.2345") gets full tick values or a scaled label
instead: "x [10⁻¹¹ m]" with ticks 1, 2, 3, as a textbook scales a column.
"""

from __future__ import annotations

import re

from ...scene.typeset import figure_text

__all__ = ["finish_figure", "figure_words"]

#: marks an axis whose multiplier was folded into its label (finishing twice is harmless)
_DONE = "_reportgen_scaled"


def finish_figure(fig) -> None:
    """Typeset every text of ``fig`` and fold each axis's multiplier into its label
    (in place; a second call changes nothing)."""
    for ax in fig.get_axes():
        for axis in _axes_of(ax):
            _fold_multiplier(axis)
            _typeset_formatter(axis)
    from matplotlib.text import Text

    for text in fig.findobj(Text):
        old = text.get_text()
        new = figure_text(old)
        if new != old:
            text.set_text(new)


def figure_words(fig) -> list[str]:
    """Every visible text of ``fig`` (titles, labels, legend entries, annotations), as
    written (mathtext included)."""
    from matplotlib.text import Text

    return [t.get_text() for t in fig.findobj(Text)
            if t.get_visible() and t.get_text().strip()]


def _axes_of(ax):
    axes = [ax.xaxis, ax.yaxis]
    if getattr(ax, "zaxis", None) is not None:
        axes.append(ax.zaxis)
    return axes


def _fold_multiplier(axis) -> None:
    from matplotlib.ticker import ScalarFormatter

    formatter = axis.get_major_formatter()
    if getattr(axis, _DONE, False) or type(formatter) is not ScalarFormatter:
        return
    if not axis.get_visible() or axis.axes.name == "polar":
        return
    locs = [v for v in axis.get_majorticklocs()
            if min(axis.get_view_interval()) <= v <= max(axis.get_view_interval())]
    if not locs:
        return
    formatter.set_locs(locs)
    if formatter.offset:
        formatter.set_useOffset(False)
        formatter.set_locs(locs)
    order = _order_of_magnitude(formatter)
    setattr(axis, _DONE, True)
    if not order:
        return
    label = axis.get_label()
    text = label.get_text()
    scaled = _scaled_label(text, order)
    if scaled is None:
        return  # no label to scale: the multiplier stays above the axis
    formatter.set_powerlimits((order, order))
    axis.get_offset_text().set_visible(False)
    label.set_text(scaled)


def _order_of_magnitude(formatter) -> int:
    """The power of ten a ScalarFormatter divides its ticks by (a private attribute from
    matplotlib 3.11 on, public before)."""
    if "_orderOfMagnitude" in vars(formatter):
        return int(vars(formatter)["_orderOfMagnitude"])
    return int(formatter.orderOfMagnitude)


_BRACKET = re.compile(r"\[([^\[\]]*)\]\s*$")


def _scaled_label(text: str, order: int) -> str | None:
    """``text`` (an axis label) with the scale 10^order in its unit: "x [m]" -> "x [10⁻¹¹
    m]", "drift (dimensionless)" -> "drift [10⁻¹¹]"; None when it has neither."""
    power = f"$10^{{{order}}}$"
    m = _BRACKET.search(text)
    if m is not None:
        inner = m.group(1).strip()
        return text[:m.start()] + f"[{power}{' ' + inner if inner else ''}]"
    for words in ("(dimensionless)", "dimensionless"):
        if text.rstrip().endswith(words):
            return text.rstrip()[: -len(words)].rstrip() + f" [{power}]"
    return None


def _typeset_formatter(axis) -> None:
    """Tick labels given as strings (a fixed or function formatter) typeset like the
    rest; matplotlib's own number formatters already print U+2212."""
    from matplotlib.ticker import FixedFormatter, FuncFormatter

    for formatter in (axis.get_major_formatter(), axis.get_minor_formatter()):
        if isinstance(formatter, FixedFormatter) and not getattr(formatter, _DONE, False):
            formatter.seq = [figure_text(s) for s in formatter.seq]
            setattr(formatter, _DONE, True)
        elif isinstance(formatter, FuncFormatter) and not getattr(formatter, _DONE, False):
            func = formatter.func
            formatter.func = lambda x, pos=None, _f=func: figure_text(_f(x, pos))
            setattr(formatter, _DONE, True)
