r"""``oscillator``: the harmonic oscillator three ways (lecture notes §4, §6, §7).

Hamilton's equations integrated and compared with the closed form; the swap
canonical transformation F1 = q Q, notes (6.6–6.11), applied to the trajectory and
checked against integrating the transformed Hamiltonian, its Poisson bracket {Q, P}
derived by SymPy and evaluated along the orbit by central differences; the
Hamilton–Jacobi solution, notes (7.33–7.38), compared with the integration, and the
residuals of the Hamilton–Jacobi equations, notes (7.16) and (7.32)–(7.33), along the run with
∂W/∂q from the integrand and from W by quadrature.
"""

from __future__ import annotations

from ...scene.content import fmt as _fmt
from .config import PRESETS, OscillatorConfig
from .report import OscillatorReport
from .simulation import OscillatorSimulation


def fmt(x, digits: int = 10) -> str:
    """A number of a title: :func:`~reportgen.scene.content.fmt` with a true minus sign."""
    return _fmt(x, digits).replace("-", "−")


class OscillatorScene(OscillatorSimulation, OscillatorReport):
    kind = "oscillator"
    order = 20
    summary = "harmonic oscillator H = p²/2m + m ω² q²/2: Hamilton, canonical swap, Hamilton–Jacobi"
    Config = OscillatorConfig
    presets = PRESETS
    name_in_words = "Harmonic oscillator"

    @classmethod
    def default_title(cls, config):
        """``Harmonic oscillator, ω = 1 rad/s, from q0 = 1 m, p0 = 0``."""
        p, ini = config.params, config.initial
        return (f"Harmonic oscillator, ω = {fmt(p.omega, 4)} rad/s, from q0 = "
                f"{fmt(ini.q, 4)} m, p0 = {fmt(ini.p, 4)} kg m/s")
