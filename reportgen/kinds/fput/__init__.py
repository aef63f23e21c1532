r"""``fput``: the Fermi–Pasta–Ulam–Tsingou stiff–soft chain (Hairer, Lubich & Wanner, GNI §I.5.1).

2m unit masses, stiff linear springs of frequency ω alternating with soft quartic
springs (GNI eq. I.5.1).  The total energy is conserved; the total oscillatory
energy I of the stiff springs (GNI eq. I.5.3) is an adiabatic invariant, within
O(1/ω) of its start, while energy is exchanged between the stiff springs on the
slow time scale ω (GNI Fig. I.5.2).
"""

from __future__ import annotations

from ...scene.content import fmt as _fmt
from .config import PRESETS, FputConfig
from .report import FputReport
from .simulation import FputSimulation


def fmt(x, digits: int = 10) -> str:
    """A number of a title: :func:`~reportgen.scene.content.fmt` with a true minus sign."""
    return _fmt(x, digits).replace("-", "−")


class FputScene(FputSimulation, FputReport):
    kind = "fput"
    order = 85
    summary = ("Fermi–Pasta–Ulam–Tsingou stiff–soft chain: energy exchange between stiff "
               "springs, adiabatic invariant (GNI §I.5.1)")
    Config = FputConfig
    presets = PRESETS
    name_in_words = "Fermi–Pasta–Ulam–Tsingou chain"

    @classmethod
    def default_title(cls, config):
        """``Fermi–Pasta–Ulam–Tsingou chain: 3 stiff springs, ω = 50``."""
        m = config.params.m
        return (f"Fermi–Pasta–Ulam–Tsingou chain: {m} stiff spring{'s' if m != 1 else ''}, "
                f"ω = {fmt(config.params.omega, 4)}")
