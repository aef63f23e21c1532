"""How a molecule's vibrations are named (issue 41): by the internal coordinates that hold
their potential energy and by the molecule's symmetry, never by the preset.

The potential-energy distribution (Wilson, Decius & Cross, *Molecular Vibrations* (1955),
ch. 7) splits each vibration's ½ ηᵀ A η = ½ Σ k (b·η)² over classes of like coordinates
(the stretches of bonds joining the same two kinds of atom, the bends of angles with the
same three); the class holding at least :data:`DOMINANT_SHARE` names it ("C–O stretch",
"bend"), else it is "mixed".  A centre of inversion makes a named vibration symmetric (g)
or antisymmetric (u); without one, like coordinates changing by equal amounts make it
symmetric, changes summing to zero antisymmetric (H₂O's two O–H stretches).  The names,
the classes and the shares are stored in the archive (``mode_type``,
``coordinate_classes``, ``coordinate_shares``, ``dominant_share``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...lazy import lazy_module

core = lazy_module("reportgen.core.normal_modes")

#: a class of internal coordinates names a vibration when it holds at least this share of
#: the vibration's potential energy ½ ηᵀ A η; below it the vibration is "mixed"
DOMINANT_SHARE = 0.6
#: a class's amplitudes are equal (symmetric) or sum to zero (antisymmetric) within this
#: share of their largest
PHASE_TOL = 1e-6


@dataclass(frozen=True)
class CoordinateClass:
    """Internal coordinates of one kind: the stretches of the bonds joining the same two
    species, or the bends with the same vertex and end species (Wilson, Decius & Cross
    ch. 2: a mode is named by the coordinates that hold its potential energy).

    Attributes
    ----------
    label : str
        "C–O stretch", "H–O–H bend"; "stretch" ("bend") when the molecule has one class of
        that family; atoms without an element are named by their (1-based) numbers.
    family : {"stretch", "bend"}
    members : tuple of int
        Indices into :attr:`Molecule.bonds` (stretches) or :attr:`Molecule.angles` (bends).
    """

    label: str
    family: str
    members: tuple[int, ...]


def _species(mol: core.Molecule, elements) -> list[tuple]:
    """Per atom, what makes two atoms alike: the element, else the mass (relative 1e-9)."""
    m = np.asarray(mol.masses, dtype=float)
    return [("element", e) if e else ("mass", float(f"{m[a]:.9e}"))
            for a, e in enumerate(elements)]


def coordinate_classes(mol: core.Molecule, elements) -> list[CoordinateClass]:
    """The molecule's internal coordinates grouped into classes of like coordinates.

    Parameters
    ----------
    mol : Molecule
    elements : sequence of str or None, length n
        Each atom's chemical symbol (None or "" for an atom given by its mass alone).

    Returns
    -------
    list of CoordinateClass, the stretches first, each family in the order of first
    appearance.
    """
    elements = [e if e and e != "X" else None for e in elements]
    species = _species(mol, elements)
    degree = np.bincount([a for i, j, _k in mol.bonds for a in (i, j)],
                         minlength=mol.n_atoms)

    def name(a: int) -> str:
        return elements[a] or str(a + 1)

    def stretch_key(i, j):
        return ("stretch", tuple(sorted((species[i], species[j]))))

    def bend_key(i, j, l):
        return ("bend", species[j], tuple(sorted((species[i], species[l]))))

    def stretch_words(i, j):  # the more bonded atom first: "C–O", "O–H"
        i, j = sorted((i, j), key=lambda a: (-degree[a], name(a)))
        return f"{name(i)}–{name(j)}"

    def bend_words(i, j, l):
        i, l = sorted((i, l), key=name)
        return f"{name(i)}–{name(j)}–{name(l)}"

    groups: dict[tuple, list[int]] = {}
    for b, (i, j, _k) in enumerate(mol.bonds):
        groups.setdefault(stretch_key(i, j), []).append(b)
    for g, (i, j, l, _k) in enumerate(mol.angles):
        groups.setdefault(bend_key(i, j, l), []).append(g)
    families = [key[0] for key in groups]
    out = []
    for key, members in groups.items():
        family = key[0]
        if families.count(family) == 1:
            label = family
        else:
            words = ([stretch_words(*mol.bonds[b][:2]) for b in members] if family == "stretch"
                     else [bend_words(*mol.angles[g][:3]) for g in members])
            named = all(elements[a] for b in members for a in (
                mol.bonds[b][:2] if family == "stretch" else mol.angles[b][:3]))
            label = f"{words[0] if named else '/'.join(words)} {family}"
        out.append(CoordinateClass(label, family, tuple(members)))
    return out


def coordinate_amplitudes(mol: core.Molecule, mode: np.ndarray) -> tuple[np.ndarray, list]:
    """First-order change of each bond length (b·η) and of each angle along ``mode``.

    Returns
    -------
    stretches : ndarray, shape (n_bonds,)
    bends : list, length n_angles: the angle's change, or None for a linear angle (two
        perpendicular bend coordinates, no one sign)
    """
    x = np.asarray(mol.positions, dtype=float)
    stretches = np.array([float(core.stretch_bvector(x, i, j) @ mode) for i, j, _k in mol.bonds])
    bends = []
    for i, j, l, _k in mol.angles:
        bs = core.bend_bvectors(x, i, j, l)
        bends.append(float(bs[0] @ mode) if len(bs) == 1 else None)
    return stretches, bends


def coordinate_shares(mol: core.Molecule, classes: list[CoordinateClass],
                      modes: np.ndarray) -> np.ndarray:
    """The potential-energy distribution: each class's share of ½ ηᵀ A η = ½ Σ k (b·η)²
    for every column η of ``modes`` (Wilson, Decius & Cross ch. 7).

    Parameters
    ----------
    mol : Molecule
    classes : list of CoordinateClass (:func:`coordinate_classes`)
    modes : ndarray, shape (3n, k), vibrations (ω > 0)

    Returns
    -------
    ndarray, shape (k, len(classes)); each row sums to 1 (0 for a mode with no energy)
    """
    x = np.asarray(mol.positions, dtype=float)
    energy = np.zeros((modes.shape[1], len(classes)))
    for c, cls in enumerate(classes):
        for member in cls.members:
            if cls.family == "stretch":
                i, j, k = mol.bonds[member]
                vectors = [core.stretch_bvector(x, i, j)]
            else:
                i, j, l, k = mol.angles[member]
                vectors = core.bend_bvectors(x, i, j, l)
            for b in vectors:
                energy[:, c] += k * (b @ modes) ** 2
    total = energy.sum(axis=1, keepdims=True)
    return np.divide(energy, total, out=np.zeros_like(energy), where=total > 0)


def _phase(values: list[float | None]) -> str:
    """"symmetric" when the amplitudes are equal, "antisymmetric" when they sum to zero
    (both within :data:`PHASE_TOL`), else ""; "" for fewer than two."""
    if len(values) < 2 or any(v is None for v in values):
        return ""
    v = np.asarray(values, dtype=float)
    top = float(np.max(np.abs(v)))
    if top == 0:
        return ""
    if float(np.ptp(v)) <= PHASE_TOL * top:
        return "symmetric"
    if abs(float(v.sum())) <= PHASE_TOL * top:
        return "antisymmetric"
    return ""


def vibration_name(shares: np.ndarray, classes: list[CoordinateClass], stretches: np.ndarray,
                   bends: list, parity: str = "") -> str:
    """A vibration's name from its potential-energy shares (:func:`coordinate_shares`).

    The class holding at least :data:`DOMINANT_SHARE` of the energy names it ("C–O
    stretch", "bend"); none does: "mixed <first> and <second>".  A named vibration of a
    molecule with a centre of inversion is "symmetric" when even under it and
    "antisymmetric" when odd (``parity`` "g"/"u", :func:`mode_parity`); without one, a
    class of two or more like coordinates moving with equal amplitudes is "symmetric",
    with amplitudes summing to zero "antisymmetric" (H₂O's two O–H stretches).
    """
    order = np.argsort(-shares, kind="stable")
    top = classes[order[0]]
    if shares[order[0]] < DOMINANT_SHARE and len(classes) > 1:
        return f"mixed {top.label} and {classes[order[1]].label}"
    if parity in ("g", "u"):
        phase = "symmetric" if parity == "g" else "antisymmetric"
    else:
        values = (stretches if top.family == "stretch" else bends)
        phase = _phase([values[m] for m in top.members])
    return f"{phase} {top.label}".strip()


def mode_names(modes: core.ModeSet, mol: core.Molecule, elements, parity: list[str]
               ) -> tuple[list[str], list[CoordinateClass], np.ndarray]:
    """Every vibration's name (:func:`vibration_name`), the coordinate classes and the
    shares, shape (n_vibrations, n_classes)."""
    classes = coordinate_classes(mol, elements)
    vib = modes.modes[:, modes.n_zero:]
    if not classes:
        return ["normal mode"] * vib.shape[1], classes, np.zeros((vib.shape[1], 0))
    shares = coordinate_shares(mol, classes, vib)
    names = []
    for k in range(vib.shape[1]):
        stretches, bends = coordinate_amplitudes(mol, vib[:, k])
        names.append(vibration_name(shares[k], classes, stretches, bends,
                                    parity[modes.n_zero + k]))
    return names, classes, shares
