r"""``pendulum``: the nonlinear plane pendulum and its small-angle limit (lecture notes §1–2).

m l^2 θ'' + m g l sin θ = 0.  Exact solution in Jacobi elliptic functions, exact
period 4 K(k) sqrt(l/g) with k = sin(θ0/2), the phase portrait with its
separatrix, and the boundary-value problem θ(0) = θ0, θ(T) = θ1 of the
linearised equation (1.21) with its action (2.4).
"""

from __future__ import annotations

from .config import PRESETS, PendulumConfig
from .report import PendulumReport
from .simulation import PendulumSimulation


class PendulumScene(PendulumSimulation, PendulumReport):
    kind = "pendulum"
    order = 10
    summary = "nonlinear plane pendulum m l² θ'' + m g l sin θ = 0 and its small-angle limit"
    Config = PendulumConfig
    presets = PRESETS
