"""The space a figure is drawn for, and how a multi-panel figure fills it.

A report draws each figure at its own size.  ``reportgen figures --size slide|print|WxH``
asks for another :class:`Size`; a figure function that can lay its panels out again for
that shape (a row on a 16:9 slide, two rows on a printed page) reads it with
:func:`requested` while the export draws, marks the figure with :func:`mark`, and the
export then saves it as drawn instead of stretching it and scaling its text.  Every
other figure is stretched to the size and its text scaled (:mod:`..export`).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass


@dataclass(frozen=True)
class Size:
    """What a figure is drawn for: a width and height in inches (None: the figure's own,
    or the own aspect ratio when only the height is None), a text scale, and the smallest
    text [pt] a figure laid out for it uses (None: no floor)."""

    label: str
    width: float | None = None
    height: float | None = None
    text_scale: float = 1.0
    min_font: float | None = None

    def inches(self, own: tuple[float, float]) -> tuple[float, float]:
        if self.width is None:
            return own
        if self.height is None:
            return self.width, self.width * own[1] / own[0]
        return self.width, self.height

    def font(self, base: float) -> float:
        """A text of ``base`` points at report size, as drawn for this size."""
        return max(base * self.text_scale, self.min_font or 0.0)


_REQUESTED: ContextVar[Size | None] = ContextVar("requested_figure_size", default=None)


def requested() -> Size | None:
    """The size the figures being drawn are for (None: the report's own)."""
    size = _REQUESTED.get()
    return None if size is None or size.width is None else size


@contextmanager
def drawing_for(size: Size) -> Iterator[None]:
    """Figures drawn inside are for ``size`` (:func:`requested`)."""
    token = _REQUESTED.set(size)
    try:
        yield
    finally:
        _REQUESTED.reset(token)


def mark(fig, size: Size | None) -> None:
    """Record that ``fig`` was laid out for ``size`` (and needs no stretching)."""
    fig.reportgen_laid_out_for = size


def laid_out_for(fig) -> Size | None:
    return getattr(fig, "reportgen_laid_out_for", None)


@dataclass(frozen=True)
class Grid:
    """Panels in rows: ``rows`` × ``cols`` slots, each panel ``panel`` inches wide."""

    rows: int
    cols: int
    panel: float

    def slots(self, n: int) -> list[tuple[int, float]]:
        """(row, column) of each of ``n`` panels, the columns of a short last row
        fractional so that it is centred (2 + 1: the third under the middle)."""
        out = []
        for k in range(n):
            row, col = divmod(k, self.cols)
            in_row = min(self.cols, n - row * self.cols)
            out.append((row, col + 0.5 * (self.cols - in_row)))
        return out


#: a figure keeps fewer rows (a row of three, as the textbook prints them side by side)
#: unless more rows make each panel this much larger
MORE_ROWS_GAIN = 1.25


def panel_grid(n: int, aspect: float, width: float, height: float, *, head: float,
               gap: float = 0.15) -> Grid:
    """The arrangement of ``n`` panels of width/height ``aspect``, each with ``head``
    inches of text above it, within ``width`` × ``height`` inches (``gap`` between
    columns): the fewest rows whose panels are within ``MORE_ROWS_GAIN`` of the largest
    any arrangement allows."""
    grids = []
    for rows in range(1, n + 1):
        cols = math.ceil(n / rows)
        if (rows - 1) * cols >= n:
            continue  # an empty row
        panel = min((width - gap * (cols - 1)) / cols, (height / rows - head) * aspect)
        grids.append(Grid(rows, cols, panel))
    largest = max(g.panel for g in grids)
    return next(g for g in grids if g.panel * MORE_ROWS_GAIN >= largest)
