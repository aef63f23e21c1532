r"""``three_body``: three gravitating bodies (lecture notes §3, eqs. 3.32–3.35).

Arbitrary masses and states, and presets: the Sun–Earth–Moon system with the
notes' mass ratios m2/m1 ~ 1e-6, m3/m1 ~ 1e-8 (3.35) and its Jacobi coordinates
(3.32–3.34); the Chenciner–Montgomery figure-eight; Burrau's Pythagorean problem
with its close encounters.  Energy, total momentum and angular momentum are the
conserved quantities; a run whose energy error exceeds ``energy_tolerance`` is
flagged unstable, never drawn silently.

Archive columns: x1, y1, z1, x2, y2, z2, x3, y3, z3 (positions body by body), then
vx1, vy1, vz1, …, vz3 in the same order.
"""

from __future__ import annotations

from .config import PRESETS, ThreeBodyConfig
from .report import ThreeBodyReport
from .simulation import ThreeBodySimulation


class ThreeBodyScene(ThreeBodySimulation, ThreeBodyReport):
    kind = "three_body"
    order = 40
    summary = "three gravitating bodies: Sun–Earth–Moon (Jacobi coordinates), figure-eight, " \
              "Pythagorean problem"
    Config = ThreeBodyConfig
    presets = PRESETS
