"""The stretch of a nutation locus that Fig. 4.3 (and the family's loci) draw.

The simulation stores it for the band runs; the report computes it for a family's kept
members from their archived runs.  Plain numpy on the run's ``t`` and ``phi``.
"""

from __future__ import annotations

import math

import numpy as np

#: Fig. 4.3: each locus is drawn over a full turn in azimuth, Δφ ≥ 2π (the same span in
#: every panel: the loops, waves and cusps go once round the band), a whole number of
#: nutation periods, so that it ends on the upper circle where it started; at least this
#: many periods, at most this many (a top that hardly precesses would fill the band)
FIG43_MIN_PERIODS = 2
FIG43_MAX_PERIODS = 40
#: a family's loci: at most this many periods, fewer when they would go round the sphere
#: more than ``FAMILY_SPAN`` [rad] (small panels, one per member)
FAMILY_PERIODS = 6
FAMILY_SPAN = 1.1 * math.pi
#: and the sphere is seen from this height above the horizon [degrees]
FIG43_ELEVATION_DEG = 28.0


def full_turn_periods(precession: float) -> int:
    """Nutation periods whose precession covers a full turn, |Δφ| n ≥ 2π (Fig. 4.3);
    ``precession``: Δφ per nutation period [rad] (0 or NaN: ``FIG43_MAX_PERIODS``)."""
    dphi = abs(precession)
    if not (math.isfinite(dphi) and dphi > 0.0):
        return FIG43_MAX_PERIODS
    return min(FIG43_MAX_PERIODS, max(FIG43_MIN_PERIODS, math.ceil(2.0 * math.pi / dphi)))


def locus_stretch(record, period: float, precession: float, *, full_turn: bool = True
                  ) -> tuple[int, int, float]:
    """(samples, nutation periods, view azimuth) of the stretch of a locus to draw, from
    the release on: a full turn, :func:`full_turn_periods` (Fig. 4.3), or with
    ``full_turn=False`` at most ``FAMILY_PERIODS``, fewer when they would go round the
    sphere more than ``FAMILY_SPAN``.  Never more than the run holds.  The view faces the
    middle of the stretch (the axis' azimuth is φ − π/2, (4.46)); a full turn is seen
    with the release on the limb, so that the locus crosses the front from there and
    its two ends meet at the side, foreshortened.

    ``record``: a run with ``t`` and the column ``phi``; ``period`` [s] and
    ``precession`` (per nutation period) [rad]."""
    if full_turn:
        periods = full_turn_periods(precession)
    else:
        dphi = abs(precession)
        periods = FAMILY_PERIODS
        if dphi > 0.0:
            periods = min(periods, max(FIG43_MIN_PERIODS, math.floor(FAMILY_SPAN / dphi)))
    t = np.asarray(record.t)
    if math.isfinite(period) and period > 0.0 and t[-1] < periods * period:
        periods = max(1, math.floor(t[-1] / period))  # what the run holds
    # up to the first sample at or past the last period's end, so the drawn Δφ is not
    # a sample short of it
    stop = int(np.searchsorted(t, periods * period, side="left")) + 1
    stop = min(max(stop, 2), len(t))
    phi = record["phi"]
    if full_turn:  # the release on the limb, a quarter turn before the view's centre
        ahead = math.copysign(0.5 * math.pi, phi[stop - 1] - phi[0])
        return stop, periods, float(phi[0] - 0.5 * math.pi + ahead)
    return stop, periods, float(0.5 * (phi[0] + phi[stop - 1]) - 0.5 * math.pi)
