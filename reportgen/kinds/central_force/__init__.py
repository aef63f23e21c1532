r"""``central_force``: two bodies in a central potential and the Kepler problem (notes §3).

The relative coordinate r = r1 − r2 moves like one body of reduced mass
μ = m1 m2/(m1 + m2) in V(r) (notes (3.18–3.22)); the angular momentum L = μ r × ṙ is the
Noether charge of rotations (notes (3.23–3.27)); the radial motion sees the effective
potential V + L²/(2μr²) (notes (7.40)–(7.41)).  For V = −k/r the integration is checked
against Kepler's equation at every stored time, the third law and the
Laplace–Runge–Lenz vector; for other potentials the apsidal angle against the
exact quadrature and its near-circular limit π/√(2 − n).  A bound orbit's
Hamilton–Jacobi equations, notes (7.16), (7.32) and (7.42)–(7.45), are evaluated along the run with
W = W_r(r) + α_θ θ (:mod:`.hamilton_jacobi`).
"""

from __future__ import annotations

import math

from ...scene.content import fmt as _fmt
from . import cases
from .config import PRESETS, CentralForceConfig
from .report import CentralForceReport, power_potential
from .simulation import CentralForceSimulation


def fmt(x, digits: int = 10) -> str:
    """A number of a title: :func:`~reportgen.scene.content.fmt` with a true minus sign."""
    return _fmt(x, digits).replace("-", "−")


class CentralForceScene(CentralForceSimulation, CentralForceReport):
    kind = "central_force"
    order = 30
    summary = "two bodies in a central potential: reduced mass, Noether charge, Kepler checks"
    Config = CentralForceConfig
    presets = PRESETS
    name_in_words = "Two bodies in a central potential"

    @classmethod
    def default_title(cls, config):
        """``Kepler orbit, e = 0.95`` (bound), ``Kepler hyperbola: escape, e = 1.3``
        (escaping; the conic by :func:`.cases.conic`); the power law and the 1/r³ term named
        with their numbers, and bound or escaping by the sign of E."""
        p, ini = config.params, config.initial
        if p.potential == "power":
            return (f"Central potential {power_potential(fmt(p.n, 4))}: two bodies started at "
                    f"r = {fmt(math.hypot(ini.x, ini.y), 4)} m")
        mu = p.m1 * p.m2 / (p.m1 + p.m2)
        r = math.hypot(ini.x, ini.y)
        energy = 0.5 * mu * (ini.vx ** 2 + ini.vy ** 2) - p.k / r
        ell = mu * (ini.x * ini.vy - ini.y * ini.vx)
        e = math.sqrt(max(0.0, 1.0 + 2.0 * energy * ell ** 2 / (mu * p.k ** 2)))
        if p.potential == "kepler_inverse_cube":
            energy -= p.epsilon / r**2
            return (f"Kepler potential with a 1/r³ force (ε = {fmt(p.epsilon, 4)}): "
                    + ("a bound orbit" if energy < 0 else "an escaping orbit"))
        if energy < 0:
            return f"Kepler orbit, e = {fmt(e, 4)}"
        return f"Kepler {cases.conic(e, bound=False)}: escape, e = {fmt(e, 4)}"
