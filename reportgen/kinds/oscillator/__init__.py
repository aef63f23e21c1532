r"""``oscillator``: the harmonic oscillator three ways (lecture notes §4, §6, §7).

Hamilton's equations integrated and compared with the closed form; the swap
canonical transformation F1 = q Q (6.6–6.11) applied to the trajectory and
checked against integrating the transformed Hamiltonian; the Hamilton–Jacobi
solution (7.33–7.38) compared with the integration.
"""

from __future__ import annotations

from .config import PRESETS, OscillatorConfig
from .report import OscillatorReport
from .simulation import OscillatorSimulation


class OscillatorScene(OscillatorSimulation, OscillatorReport):
    kind = "oscillator"
    order = 20
    summary = "harmonic oscillator H = p²/2m + m ω² q²/2: Hamilton, canonical swap, Hamilton–Jacobi"
    Config = OscillatorConfig
    presets = PRESETS
