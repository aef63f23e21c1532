r"""The pendulum's periods over a family of amplitudes, as one compiled ensemble.

Core's generic ensemble (:func:`reportgen.core.ensemble.run_ensemble`: DOP853 members, the
first zero crossings of one component located on the dense output) run on the pendulum
(:func:`reportgen.core.models.pendulum.model`); what is pendulum-specific lives here:
which members librate, the horizon that holds two periods, and reading a period off two
crossings.

References
----------
.. [1] NIST DLMF 19.2.8 and 22.19(i): the pendulum's period 4 K(k) / omega0,
       k = sin(theta0 / 2).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ...core.ensemble import OK, STATUS_NAMES, run_ensemble
from ...core.integrators.status import Status
from ...core.models import pendulum

#: theta0 outside (0, pi), or g / l not positive, or not finite
NOT_LIBRATING = Status.NOT_LIBRATING.code
#: fewer than two upward crossings before the horizon
NO_PERIOD = Status.NO_PERIOD.code

__all__ = ["NOT_LIBRATING", "NO_PERIOD", "OK", "STATUS_NAMES", "pendulum_periods"]


def pendulum_periods(theta0, g, l, rtol: float = 1e-12, atol: float = 1e-12,
                     block: int = 1024, progress: Callable[[float], None] | None = None,
                     max_steps: int = 1_000_000) -> tuple[np.ndarray, np.ndarray]:
    """Periods of pendulums released from rest at amplitudes ``theta0``, integrated.

    Each member starts at (theta0, 0) with omega0^2 = g / l; its period is the time
    between its first two upward zero crossings of theta (at 3T/4 and 7T/4), located on
    DOP853's dense output.  To compare with 4 K(k) sqrt(l / g), k = sin(theta0 / 2)
    (DLMF 19.2.8, 22.19(i)).

    Parameters
    ----------
    theta0, g, l : array_like, broadcast together
        Amplitude [rad] in (0, pi), gravity [m/s^2], length [m].

    rtol, atol : float
        Near the separatrix the period is ill-conditioned: dT / T ~ (dE / omega0^2) /
        (4 k'^2 K(k)), k' = cos(theta0 / 2), for an energy error dE (from dK/dk, DLMF
        19.4.1), ~110 dE / omega0^2 at theta0 = 3.1.  There rtol = 1e-10 gives 1e-8
        relative error in T, the default 1e-12 gives 1.5e-10.

    Returns
    -------
    periods : ndarray
        [s]; NaN where ``status`` is not ``OK``.
    status : ndarray of int
        ``OK``; ``NOT_LIBRATING`` for theta0 outside (0, pi) (rotation or separatrix),
        g / l not positive, or anything not finite; else the integration's status
        (:class:`reportgen.core.ensemble.Ensemble`), or ``NO_PERIOD``.

    Notes
    -----
    The members run until their second crossing (terminal events) within the horizon
    t_end = 2 max T_bound, where T <= T_bound = 2 pi / (omega0 cos(theta0 / 2)) because
    K(k) <= (pi / 2) / sqrt(1 - k^2) (bound the integrand of DLMF 19.2.8).
    """
    theta0, g, l = np.broadcast_arrays(np.asarray(theta0, dtype=np.float64),
                                       np.asarray(g, dtype=np.float64),
                                       np.asarray(l, dtype=np.float64))
    shape = theta0.shape
    theta0, g, l = theta0.ravel(), g.ravel(), l.ravel()
    with np.errstate(divide="ignore", invalid="ignore"):
        omega2 = g / l
        valid = (np.isfinite(theta0) & (theta0 > 0.0) & (theta0 < math.pi)
                 & np.isfinite(omega2) & (omega2 > 0.0))
    periods = np.full(theta0.size, np.nan)
    status = np.full(theta0.size, NOT_LIBRATING, dtype=np.int64)
    idx = np.nonzero(valid)[0]
    if idx.size:
        bound = 2.0 * math.pi / (np.sqrt(omega2[idx]) * np.cos(0.5 * theta0[idx]))
        Y0 = np.column_stack([theta0[idx], np.zeros(idx.size)])
        ens = run_ensemble(pendulum.model(1.0, 1.0), Y0, omega2[idx, None],
                           t_end=2.0 * float(bound.max()), rtol=rtol, atol=atol, event=0,
                           direction=1, max_events=2, terminal=True, max_steps=max_steps,
                           block=block, progress=progress)
        found = (ens.status == OK) & (ens.n_events == 2)
        periods[idx[found]] = ens.events[found, 1] - ens.events[found, 0]
        status[idx] = np.where(found, OK, np.where(ens.status == OK, NO_PERIOD, ens.status))
    return periods.reshape(shape), status.reshape(shape)
