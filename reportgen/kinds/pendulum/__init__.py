r"""``pendulum``: the nonlinear plane pendulum and its small-angle limit (lecture notes §1–2).

m l^2 θ'' + m g l sin θ = 0.  Exact solution in Jacobi elliptic functions, exact
period 4 K(k) sqrt(l/g) with k = sin(θmax/2), the phase portrait with its
separatrix, and the boundary-value problem θ(0) = θ0, θ(T) = θ1 of the
linearised equation, notes (1.21), with its action, notes (2.4).
"""

from __future__ import annotations

import math

from ...scene.content import fmt as _fmt
from .config import PRESETS, PendulumConfig, theory
from .report import PendulumReport
from .simulation import PendulumSimulation


def fmt(x, digits: int = 10) -> str:
    """A number of a title: :func:`~reportgen.scene.content.fmt` with a true minus sign."""
    return _fmt(x, digits).replace("-", "−")


class PendulumScene(PendulumSimulation, PendulumReport):
    kind = "pendulum"
    order = 10
    summary = "nonlinear plane pendulum m l² θ'' + m g l sin θ = 0 and its small-angle limit"
    Config = PendulumConfig
    presets = PRESETS
    name_in_words = "Plane pendulum"

    @classmethod
    def default_title(cls, config):
        """``Plane pendulum librating from θ0 = 2.5 rad`` (or rotating over the top, or on or
        near the separatrix), by :func:`~reportgen.core.pendulum_theory.motion_case`: the sign
        of 1 − k² and its size against the separatrix thresholds."""
        p, ini = config.params, config.initial
        m1 = theory.complementary_parameter(ini.theta, ini.theta_dot, math.sqrt(p.g / p.l))
        start = f"θ0 = {fmt(ini.theta, 6)} rad" + (
            f", θ̇0 = {fmt(ini.theta_dot, 4)} rad/s" if ini.theta_dot else "")
        case = theory.motion_case(m1)
        if case == "separatrix":
            return f"Plane pendulum on the separatrix ({start})"
        if case == "rotation":
            return f"Plane pendulum rotating over the top ({start})"
        if case == "rotation near the separatrix":
            return f"Plane pendulum rotating just above the separatrix ({start})"
        if case == "libration near the separatrix":
            return f"Plane pendulum librating just inside the separatrix ({start})"
        return f"Plane pendulum librating from {start}" if not ini.theta_dot else (
            f"Plane pendulum librating ({start})")
