r"""``two_center``: Euler's problem of two fixed centres in the plane (notes §7, 7.46–7.61).

A test particle attracted by two equal masses fixed at (±a, 0).  The motion
separates in elliptic coordinates ξ = (r1 + r2)/2a, η = (r1 − r2)/2a; besides the
energy E there is a second constant, the separation constant (7.59).  The report
draws the orbit over the elliptic-coordinate grid with the coordinate lines that
bound the motion, and checks both constants along the run.
"""

from __future__ import annotations

from .config import TwoCenterConfig
from .report import TwoCenterReport
from .simulation import TwoCenterSimulation


class TwoCenterScene(TwoCenterSimulation, TwoCenterReport):
    kind = "two_center"
    order = 50
    summary = "Euler's problem of two fixed centres: elliptic coordinates, separation constant"
    Config = TwoCenterConfig
