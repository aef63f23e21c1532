"""What a report section returns, and how numbers are printed in it.

Shared by every kind's report (and by simulations that word a check's label).  No
numerics, no drawing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from matplotlib.figure import Figure


@dataclass
class FigureSpec:
    """A figure of a section: saved as its own files and shown inline."""

    name: str
    figure: Figure
    caption: str


@dataclass
class Table:
    caption: str
    header: list[str]
    rows: list[list[str]]


@dataclass
class SectionContent:
    figures: list[FigureSpec] = field(default_factory=list)
    tables: list[Table] = field(default_factory=list)
    facts: list[tuple[str, str]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    #: displayed equations: (what it is, TeX), typeset by the report (reportgen.rendering.equations)
    equations: list[tuple[str, str]] = field(default_factory=list)


def fmt(x: Any, digits: int = 10) -> str:
    """A number as lecture-table text."""
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, (float, np.floating)):
        x = float(x)
        if not math.isfinite(x):
            return str(x)
        if x != 0 and (abs(x) < 1e-3 or abs(x) >= 1e6):
            return f"{x:.{min(digits, 4)}e}"
        return f"{x:.{digits}g}"
    return str(x)


def fmt_err(x: float) -> str:
    return f"{x:.1e}" if math.isfinite(x) else str(x)



def member_text(sweep, i: int, short: bool = False) -> str:
    """A sweep member's swept values as text: ``initial.theta = 0.5`` (``short``: the
    last part of each key at 4 digits, ``theta = 0.5``, for figure labels)."""
    return ", ".join(f"{p.rsplit('.', 1)[-1] if short else p} = "
                     f"{fmt(float(v[i]), 4 if short else 8)}" for p, v in sweep.values.items())

