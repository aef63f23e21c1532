"""The stretch of a nutation locus that Fig. 4.3 (and the family's loci) draw.

The simulation stores it for the band runs; the report computes it for a family's kept
members from their archived runs.  Plain numpy on the run's ``t`` and ``phi``.
"""

from __future__ import annotations

import math

import numpy as np

#: Fig. 4.3: nutation periods drawn per locus (at most, at least), and how far round
#: the sphere [rad] they may go before fewer are drawn
FIG43_PERIODS = 6
FIG43_MIN_PERIODS = 2
FIG43_SPAN = 1.1 * math.pi
#: and the sphere is seen from this height above the horizon [degrees]
FIG43_ELEVATION_DEG = 28.0


def locus_stretch(record, period: float, precession: float) -> tuple[int, int, float]:
    """(samples, nutation periods, view azimuth) of the stretch of a locus Fig. 4.3
    draws: from the release to at most ``FIG43_PERIODS`` nutation periods, fewer when
    they would go round the sphere more than ``FIG43_SPAN`` [rad]; the view faces
    the middle of the stretch (the axis' azimuth is φ − π/2, (4.46)).

    ``record``: a run with ``t`` and the column ``phi``; ``period`` [s] and
    ``precession`` (per nutation period) [rad]."""
    dphi = abs(precession)
    periods = FIG43_PERIODS
    if dphi > 0.0:
        periods = min(periods, max(FIG43_MIN_PERIODS, math.floor(FIG43_SPAN / dphi)))
    stop = int(np.searchsorted(record.t, periods * period, side="right"))
    stop = min(max(stop, 2), len(record.t))
    phi = record["phi"]
    return stop, periods, float(0.5 * (phi[0] + phi[stop - 1]) - 0.5 * math.pi)
