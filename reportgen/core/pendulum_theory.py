"""Pendulum constants of the motion that need no numerics library: the elliptic parameter
k^2 and its complement 1 - k^2 (config validation uses them without importing numba or
scipy).  The solutions and the compiled model are in :mod:`reportgen.core.models.pendulum`.
"""

from __future__ import annotations

import math


def modulus_squared(theta0, theta_dot0, omega0):
    """Elliptic parameter m = k^2 of the motion, k^2 = sin^2(theta0/2) + (theta_dot0 / 2 omega0)^2.

    m < 1: libration with amplitude 2 asin(k); m > 1: rotation; m = 1: separatrix.
    """
    return math.sin(0.5 * theta0) ** 2 + (theta_dot0 / (2.0 * omega0)) ** 2


def complementary_parameter(theta0, theta_dot0, omega0):
    """1 - k^2 = cos^2(theta0/2) - (theta_dot0 / 2 omega0)^2, computed without cancellation.

    Near the separatrix k^2 rounds to 1 long before 1 - k^2 loses its digits
    (theta0 = pi - 1e-8 gives 1 - k^2 = 2.5e-17).
    """
    return math.cos(0.5 * theta0) ** 2 - (theta_dot0 / (2.0 * omega0)) ** 2


#: below this |1 - k^2| scipy's double-precision ellipj no longer resolves the motion
#: (measured against 40-digit mpmath: 4e-9 error at 1 - k^2 = 2.5e-7 over 12 periods)
EXACT_SOLUTION_MIN_M1 = 1e-8
