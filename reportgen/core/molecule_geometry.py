"""Molecule geometry that validation needs: atomic weights and bond angles (numpy only).

Kept apart from :mod:`reportgen.core.normal_modes` so that checking a config imports
no scipy."""

from __future__ import annotations

import math

import numpy as np

#: standard atomic weights [u] (IUPAC 2021, abridged) for ``atoms[i].element``
ELEMENT_MASSES = {
    "H": 1.008, "D": 2.014, "He": 4.0026, "Li": 6.94, "B": 10.81, "C": 12.011,
    "N": 14.007, "O": 15.999, "F": 18.998, "Ne": 20.180, "Na": 22.990, "Si": 28.085,
    "P": 30.974, "S": 32.06, "Cl": 35.45, "Ar": 39.95, "Br": 79.904, "I": 126.90,
}


def bond_angle(x: np.ndarray, i: int, j: int, l: int) -> float:
    """θ at vertex j between bonds j→i and j→l (atan2 form: accurate near 0 and π)."""
    u, v = x[i] - x[j], x[l] - x[j]
    return math.atan2(float(np.linalg.norm(np.cross(u, v))), float(u @ v))
