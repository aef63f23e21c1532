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

from ...scene.content import fmt as _fmt
from .config import PRESETS, HamiltonianConfig, _PresetFormulas
from .report import HamiltonianReport
from .simulation import HamiltonianSimulation
from .symbols import formula_text, symbol_text


def fmt(x, digits: int = 10) -> str:
    """A number of a title: :func:`~reportgen.scene.content.fmt` with a true minus sign."""
    return _fmt(x, digits).replace("-", "−")

class HamiltonianScene(HamiltonianSimulation, HamiltonianReport):
    kind = "hamiltonian"
    order = 95
    summary = "any system written as H(q, p, t) or L(q, q̇, t): derived, compiled, checked"
    Config = HamiltonianConfig
    presets = PRESETS
    name_in_words = "A system given by its Hamiltonian or Lagrangian"
    PRESET_WORDS = {"central_potential": "Central potential V = −k/r in spherical coordinates",
                    "two_centres": "Two fixed centres in elliptic coordinates"}

    #: longest formula (in characters) a default title spells out; a longer one is said
    #: in words
    TITLE_FORMULA_CHARACTERS = 48

    @classmethod
    def default_title(cls, config):
        """``Lagrangian system in (θ1, θ2): surface of section θ1 = 0``: the preset's
        words or the formula's kind and coordinates, then what the config adds."""
        system = config.system
        words = cls.PRESET_WORDS.get(cls.preset_as_given(config) or "")
        if words is None:
            # the formula itself when it reads as a short line: "Hamiltonian H = p²/2 + q⁴/4"
            given = "H" if system.H else "L"
            formula = formula_text(system.H or system.L, system.coordinates)
            if formula is not None and len(formula) <= cls.TITLE_FORMULA_CHARACTERS:
                words = f"{'Hamiltonian' if system.H else 'Lagrangian'} {given} = {formula}"
            else:
                coordinates = ", ".join(symbol_text(q) for q in system.coordinates)
                words = (f"{'Hamiltonian' if system.H else 'Lagrangian'} system in "
                         f"({coordinates})")
        extra = []
        if config.section is not None:
            extra.append(f"surface of section {symbol_text(config.section.coordinate)} = "
                         f"{fmt(config.section.value, 4)}")
        if config.transform is not None:
            extra.append("a canonical transformation")
        if config.hamilton_jacobi is not None and config.preset is None:
            extra.append("Hamilton–Jacobi separation")
        return words + (": " + ", ".join(extra) if extra else "")


__all__ = ["HamiltonianScene", "_PresetFormulas"]
