r"""``normal_modes``: small oscillations about a stable equilibrium (textbook ch. 5, §5.1).

The generalized eigenproblem A η = ω² M η for a system given as matrices, as a
molecule (atoms, bond stretches, angle bends; textbook Fig. 5.1), as a chain of masses
and springs, as coupled pendula, or as formulas: a potential U(q) (with a kinetic energy or
a mass matrix) or a Lagrangian L, whose equilibrium is found from a guess and A = ∂²U/∂q∂q
taken there.  Rigid-body zero modes are identified and
projected out, vibrations counted (3n − 6 or 3n − 5) and classified, mode
shapes drawn.  Nothing is integrated unless ``[evolve]`` asks for a time
evolution, which is then done two ways: modal superposition (exact) and direct
integration of M q̈ + A q = 0.

Atom indices in ``[[bonds]]`` and ``[[angles]]`` are zero-based.
"""

from __future__ import annotations

from .config import PRESETS, NormalModesConfig, name_as_symbol
from .report import NormalModesReport, counted, formula
from .simulation import NormalModesSimulation


class NormalModesScene(NormalModesSimulation, NormalModesReport):
    kind = "normal_modes"
    order = 80
    summary = ("small oscillations A η = ω² M η of [[atoms]] with [[bonds]] and [[angles]] "
               "(zero-based atom indices), or top-level M and A matrices, a [chain], "
               "[pendula], or a [system] of formulas (U with T or M, or L; the equilibrium "
               "found from a guess); rigid-body zero modes, 3n−6/3n−5 vibrations, mode shapes; "
               "[evolve] (displacement, t_end) adds a time evolution")
    Config = NormalModesConfig
    presets = PRESETS
    name_in_words = "Normal modes"

    @classmethod
    def default_title(cls, config):
        """``Normal modes of CO₂ (3 atoms, 2 bonds, 1 bending angle)``, of a chain, of
        coupled pendula or of given matrices."""
        if config.chain is not None:
            c = config.chain
            return (f"Normal modes of a chain of {c.n} equal masses "
                    + ("between fixed walls" if c.ends == "fixed" else "with free ends"))
        if config.pendula is not None:
            return f"Normal modes of {config.pendula.n} pendula coupled by springs"
        if config.system is not None:
            s = config.system
            given = "a Lagrangian" if s.L is not None else (
                "a potential and kinetic energy" if s.T is not None
                else "a potential and mass matrix")
            return (f"Small oscillations from {given} in "
                    f"{', '.join(name_as_symbol(c) for c in s.coordinates)}")
        if config.atoms:
            atoms = list(config.atoms)
            name = formula([atom.element for atom in atoms]) or "a molecule"
            return (f"Normal modes of {name} ({counted(len(atoms), 'atom')}, "
                    f"{counted(len(config.bonds), 'bond')}, "
                    f"{counted(len(config.angles), 'bending angle')})")
        return f"Normal modes of a system of {len(config.M)} coordinates (M and A given)"
