r"""``two_center``: Euler's problem of two fixed centres in the plane (notes §7, 7.46–7.61).

A test particle attracted by two equal masses fixed at (±a, 0).  The motion
separates in elliptic coordinates ξ = (r1 + r2)/2a, η = (r1 − r2)/2a; besides the
energy E there is a second constant, the separation constant, notes (7.59).  The report
draws the orbit over the elliptic-coordinate grid with the coordinate lines that
bound the motion, and checks both constants along the run.
"""

from __future__ import annotations

import math

from ...scene.content import fmt as _fmt
from .config import TwoCenterConfig
from .report import TwoCenterReport
from .simulation import TwoCenterSimulation


def fmt(x, digits: int = 10) -> str:
    """A number of a title: :func:`~reportgen.scene.content.fmt` with a true minus sign."""
    return _fmt(x, digits).replace("-", "−")


class TwoCenterScene(TwoCenterSimulation, TwoCenterReport):
    kind = "two_center"
    order = 50
    summary = "Euler's problem of two fixed centres: elliptic coordinates, separation constant"
    Config = TwoCenterConfig
    name_in_words = "Two fixed centres"

    @classmethod
    def default_title(cls, config):
        """``Two fixed centres: a bound orbit at E = −0.5`` (or an escaping one), the
        energy per unit mass given or from the initial state."""
        p, ini = config.params, config.initial
        energy = ini.energy
        if energy is None:
            r1 = math.hypot(ini.x - p.a, ini.y)
            r2 = math.hypot(ini.x + p.a, ini.y)
            energy = 0.5 * (ini.vx ** 2 + ini.vy ** 2) - p.mu / r1 - p.mu / r2
        orbit = "a bound orbit" if energy < 0 else "an unbound (escaping) orbit"
        return (f"Two fixed centres (μ = {fmt(p.mu, 4)}, a = {fmt(p.a, 4)}): {orbit} at "
                f"E = {fmt(energy, 4)}")
