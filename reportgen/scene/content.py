"""What a report section returns, and how numbers are printed in it.

Shared by every kind's report (and by simulations that word a check's label).  No
numerics, no drawing.

One rule for every number of a report (:func:`fmt`): 6 significant figures, 2 for an
error or a drift (:func:`fmt_err`), never ``nan`` or a negative zero; more figures only in
a deliberate value-against-reference comparison (:func:`fmt_pair`), and exact 0 and 1 in
a matrix (:func:`fmt_matrix`).
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


#: significant figures of a number in prose, facts and tables
DIGITS = 6
#: significant figures of an error, a drift or a relative difference
ERROR_DIGITS = 2
#: most significant figures a comparison shows: float64 holds no more
MAX_DIGITS = 15
#: the most figures a value-against-reference comparison prints (:func:`comparison_digits`)
COMPARISON_DIGITS = 10
#: a matrix entry within this many ulps (of the matrix's largest entry) of 0, or of 1
#: and -1, is printed as 0, 1 or -1: the round-off of an exact entry, not a value
MATRIX_ULPS = 4
#: what a table cell shows where a number is missing or undefined (never "nan")
NO_VALUE = "—"


def fmt(x: Any, digits: int = DIGITS, *, against: float | None = None) -> str:
    """A number as report text: the one rule for every number of a report.

    ``digits`` significant figures (6 by default), no float noise (0.79999999999994 is
    ``0.8``), no trailing zeros, never a negative zero (``-0.0`` is ``0``); scientific
    notation (``1.2e-13``, ``3.4e7``) below 1e-3 and from 1e6 on (from ``10**digits`` for
    fewer figures), so a 15-figure comparison of 1.08e14 is not 15 bare digits.  Integers are
    printed whole.  Not-a-number is :data:`NO_VALUE`; a caller should say why in its caption
    (or leave the cell out) rather than pass one.  Infinity is ``∞``.

    ``against``: a deliberate value-against-reference comparison; ``x`` is printed with as
    many figures as :func:`fmt_pair` gives the pair (enough to see where they differ).
    """
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if not isinstance(x, (float, np.floating)):
        return str(x)
    x = float(x)
    if math.isnan(x):
        return NO_VALUE
    if math.isinf(x):
        return "∞" if x > 0 else "-∞"
    if against is not None:
        digits = comparison_digits(x, float(against), digits)
    if x == 0:
        return "0"
    mantissa, exponent = f"{x:.{digits - 1}e}".split("e")
    exponent = int(exponent)
    if -3 <= exponent < min(digits, DIGITS):
        text = f"{x:.{max(digits - 1 - exponent, 0)}f}"
        text = text.rstrip("0").rstrip(".") if "." in text else text
    else:
        mantissa = mantissa.rstrip("0").rstrip(".") if "." in mantissa else mantissa
        text = f"{mantissa}e{exponent}"
    return "0" if float(text) == 0 else text


def fmt_err(x: Any) -> str:
    """An error, drift or relative difference: two significant figures (``1.2e-13``),
    exactly zero as ``0``; not-a-number as :data:`NO_VALUE`."""
    return fmt(x, ERROR_DIGITS)


def comparison_digits(value: float, reference: float, digits: int = DIGITS) -> int:
    """Significant figures that show where ``value`` and ``reference`` differ: one more
    than the first figure at which their texts differ, at least ``digits``, at most
    :data:`COMPARISON_DIGITS`.  Values equal to more figures than that print at
    ``digits``: a table of them has a relative-error column, which tells such an
    agreement better than fifteen printed figures (a lecturer reads 2.45408e14 against
    2.45408e14 and 5.8e-16, not 245408173649620 against 245408173649620)."""
    if not (math.isfinite(value) and math.isfinite(reference)) or value == reference:
        return digits
    for n in range(1, COMPARISON_DIGITS):
        if f"{value:.{n - 1}e}" != f"{reference:.{n - 1}e}":
            return max(n + 1, digits)
    return digits


def fmt_pair(value: float, reference: float, digits: int = DIGITS) -> tuple[str, str]:
    """A value and its reference as text for a deliberate comparison: both to one figure
    past the first one where they differ (at least ``digits``, at most
    :data:`COMPARISON_DIGITS`), so that ``1.2345678`` against ``1.2345679`` shows the
    difference instead of hiding it in ``1.23457`` twice."""
    n = comparison_digits(float(value), float(reference), digits)
    return fmt(value, n), fmt(reference, n)


def fmt_matrix(matrix: Any, digits: int = DIGITS) -> list[list[str]]:
    """The entries of a matrix (or a vector, as one row) as text: :func:`fmt` each, except
    that an entry within :data:`MATRIX_ULPS` ulps of 1 or -1 is ``1`` or ``-1``, and one
    within as many ulps of the matrix's largest entry of 0 is ``0``: a rotation matrix shows
    ``1`` and ``0``, not ``0.9999999999999998`` and ``-1e-17``, while a matrix whose
    entries are all ~1e-20 keeps them."""
    a = np.atleast_2d(np.asarray(matrix, dtype=float))
    finite = np.abs(a[np.isfinite(a)])
    ulp = MATRIX_ULPS * np.finfo(float).eps
    zero = ulp * float(finite.max(initial=0.0))
    out = []
    for row in a:
        cells = []
        for x in (float(v) for v in row):
            if abs(x) <= zero:
                x = 0.0
            elif abs(abs(x) - 1.0) <= ulp:
                x = math.copysign(1.0, x)
            cells.append(fmt(x, digits))
        out.append(cells)
    return out


def member_text(sweep, i: int, short: bool = False) -> str:
    """A sweep member's swept values as text: ``initial.theta = 0.5`` (``short``: the
    last part of each key at 4 figures, ``theta = 0.5``, for figure labels)."""
    return ", ".join(f"{p.rsplit('.', 1)[-1] if short else p} = "
                     f"{fmt(float(v[i]), 4 if short else DIGITS)}" for p, v in sweep.values.items())

