r"""``hamiltonian``: any system written as a formula, H(q, p, t) or L(q, q̇, t) (notes §2–§7).

The config names the coordinates and gives H or L as text; named constants come from
``[params]``.  The text is parsed against an allow-list (:mod:`reportgen.core.expressions`),
derived with SymPy (Hamilton's equations; for L the Legendre transform) and compiled with
numba through the same integrators and study as every kind
(:mod:`reportgen.core.formula`).  The report shows the equations, the phase portrait
(one degree of freedom) or a surface of section (two or more), the conserved quantities
with their drift, the Poisson brackets of the observables with H and with each other (the
Jacobi identity checked on the trajectory), cyclic coordinates, and error against run
time.  ``[transform]`` adds a canonical transformation from a generating function and
``[hamilton_jacobi]`` the separated quadrature solution of the shipped presets.
"""

from __future__ import annotations

from .config import PRESETS, HamiltonianConfig, _PresetFormulas
from .report import HamiltonianReport
from .simulation import HamiltonianSimulation


class HamiltonianScene(HamiltonianSimulation, HamiltonianReport):
    kind = "hamiltonian"
    order = 95
    summary = "any system written as H(q, p, t) or L(q, q̇, t): derived, compiled, checked"
    Config = HamiltonianConfig
    presets = PRESETS


__all__ = ["HamiltonianScene", "_PresetFormulas"]
