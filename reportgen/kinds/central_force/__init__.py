r"""``central_force``: two bodies in a central potential and the Kepler problem (notes §3).

The relative coordinate r = r1 − r2 moves like one body of reduced mass
μ = m1 m2/(m1 + m2) in V(r) (3.18–3.22); the angular momentum L = μ r × ṙ is the
Noether charge of rotations (3.23–3.27); the radial motion sees the effective
potential V + L²/(2μr²) (3.28–3.31).  For V = −k/r the integration is checked
against Kepler's equation at every stored time, the third law and the
Laplace–Runge–Lenz vector; for other potentials the apsidal angle against the
exact quadrature and its near-circular limit π/√(2 − n).
"""

from __future__ import annotations

from .config import PRESETS, CentralForceConfig
from .report import CentralForceReport
from .simulation import CentralForceSimulation


class CentralForceScene(CentralForceSimulation, CentralForceReport):
    kind = "central_force"
    order = 30
    summary = "two bodies in a central potential: reduced mass, Noether charge, Kepler checks"
    Config = CentralForceConfig
    presets = PRESETS
