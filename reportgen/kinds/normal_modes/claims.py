"""The ``normal_modes`` report's claim-carrying sentences and their predicates (issue 41).

Each predicate measures its claim again from the archive's raw record -- the equilibrium
positions, masses and bonds, the force constants of the archived config, the matrices M
and A, the mode vectors -- with numpy alone, not from the stored classification that chose
the words: a mode called a "C–O stretch" must hold most of its potential energy in the
C–O bonds, recomputed from its vector; a "linear" molecule must have its atoms on one line.
"""

from __future__ import annotations

import math
import re

import numpy as np

from ...scene.claims import claim

#: the share a named class must hold (the declared default, when the archive has none)
_DOMINANT = 0.6
#: tolerance of the recomputed equalities (looser than the simulation's 1e-6: a claim fails
#: only when it is measurably false)
_TOL = 1e-4


# ----------------------------------------------------------------------- measurements
def _molecule(data) -> bool:
    return data.analysis.get("source") == "molecule"


def _vibrations(data) -> tuple[int, np.ndarray, list[str]]:
    """(number of zero modes, vibration vectors (3n, k), their stored names)."""
    a = data.analysis
    z = int(a["n_zero_modes"])
    return z, np.asarray(a["modes"], dtype=float)[:, z:], [str(t) for t in a["mode_type"]][z:]


def _geometry(data) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Positions relative to the centre of mass (n, 3), masses (n,), element symbols."""
    a = data.analysis
    m = np.asarray(a["masses"], dtype=float)
    x = np.asarray(a["positions"], dtype=float)
    return x - m @ x / m.sum(), m, [str(e) for e in a["elements"]]


def _bonds(data) -> list[tuple[int, int, float]]:
    """(i, j, k) of every bond, k from the archived config."""
    return [(int(b.atoms[0]), int(b.atoms[1]), float(b.k)) for b in data.config.bonds]


def _stretch(x: np.ndarray, eta: np.ndarray, i: int, j: int) -> float:
    """First-order change of the length of bond i–j along the displacement ``eta``."""
    e = x[j] - x[i]
    d = eta.reshape(-1, 3)
    return float(e @ (d[j] - d[i]) / np.linalg.norm(e))


def _angle(x: np.ndarray, i: int, j: int, l: int) -> float:
    u, v = x[i] - x[j], x[l] - x[j]
    return math.atan2(float(np.linalg.norm(np.cross(u, v))), float(u @ v))


def _bend(x: np.ndarray, eta: np.ndarray, i: int, j: int, l: int) -> float:
    """First-order change of the angle i–j–l along ``eta`` (central difference)."""
    d = eta.reshape(-1, 3)
    h = 1e-6 * float(np.max(np.ptp(x, axis=0))) / max(float(np.max(np.abs(d))), 1e-300)
    return (_angle(x + h * d, i, j, l) - _angle(x - h * d, i, j, l)) / (2 * h)


def _energy(data, eta: np.ndarray) -> float:
    """ηᵀ A η: twice the vibration's potential energy, from the archived A."""
    return float(eta @ np.asarray(data.analysis["hessian"], dtype=float) @ eta)


def _bond_shares(data, eta: np.ndarray) -> np.ndarray:
    """Each bond's share k (δr)² / ηᵀAη of the vibration's potential energy."""
    x = np.asarray(data.analysis["positions"], dtype=float)
    total = _energy(data, eta)
    return np.array([k * _stretch(x, eta, i, j) ** 2 / total for i, j, k in _bonds(data)])


def _names(data) -> list[str]:
    """Each atom's name as the report uses it: its element, else its 1-based number."""
    return [e if e != "X" else str(a + 1) for a, e in enumerate(_geometry(data)[2])]


def _bonds_named(data, label: str) -> list[int]:
    """The bonds a label like "C–O", "O–H" or "2–1/2–3" names (element pairs or numbers)."""
    names = _names(data)
    wanted = {frozenset(part.split("–")) for part in label.split("/")}
    return [b for b, (i, j, _k) in enumerate(_bonds(data))
            if frozenset((names[i], names[j])) in wanted]


def _inversion(data) -> list[int] | None:
    """The atom each atom goes to under x − x_cm → −(x − x_cm), when an atom of equal mass
    is there for every atom and every bond (and angle) goes to one of equal force constant;
    else None."""
    x, m, _ = _geometry(data)
    size = max(float(np.max(np.abs(x))), 1e-300)
    image = []
    for a in range(len(m)):
        d = np.linalg.norm(x + x[a], axis=1)
        b = int(np.argmin(d))
        if d[b] > 1e-6 * size or abs(m[b] - m[a]) > 1e-6 * m[a]:
            return None
        image.append(b)
    bonds = {frozenset((i, j)): k for i, j, k in _bonds(data)}
    for pair, k in bonds.items():
        i, j = tuple(pair)
        other = bonds.get(frozenset((image[i], image[j])))
        if other is None or abs(other - k) > 1e-6 * k:
            return None
    angles = {(int(g.atoms[1]), frozenset((int(g.atoms[0]), int(g.atoms[2])))): float(g.k)
              for g in data.config.angles}
    for (j, ends), k in angles.items():
        i, l = tuple(ends)
        other = angles.get((image[j], frozenset((image[i], image[l]))))
        if other is None or abs(other - k) > 1e-6 * k:
            return None
    return image


def _parity(image: list[int], eta: np.ndarray) -> float:
    """⟨η, S η⟩/⟨η, η⟩ under the inversion S (atom a's displacement goes to −d at image[a])."""
    d = eta.reshape(-1, 3)
    s = np.zeros_like(d)
    for a, b in enumerate(image):
        s[b] = -d[a]
    return float(np.sum(d * s) / np.sum(d * d))


def _axis(data) -> np.ndarray | None:
    """The line the atoms lie on (unit vector), from the two farthest atoms; None when some
    atom lies off it by more than 1e-6 of the size."""
    x, _, _ = _geometry(data)
    far = np.linalg.norm(x[:, None] - x[None], axis=2)
    i, j = np.unravel_index(np.argmax(far), far.shape)
    e = (x[j] - x[i]) / far[i, j]
    off = np.linalg.norm(np.cross(x - x[i], e), axis=1)
    return e if float(off.max()) <= 1e-6 * float(far[i, j]) else None


def _omega2(data) -> np.ndarray:
    """ω² of the archived (M, A), recomputed with numpy (Cholesky of M), ascending."""
    a = data.analysis
    M = np.asarray(a["mass_matrix"], dtype=float)
    A = np.asarray(a["hessian"], dtype=float)
    L = np.linalg.cholesky(M)
    Li = np.linalg.inv(L)
    return np.sort(np.linalg.eigvalsh(Li @ A @ Li.T))


def _zero_count(data) -> int:
    w2 = _omega2(data)
    return int(np.sum(np.abs(w2) <= 1e-9 * float(np.max(np.abs(w2)))))


def _along(data, eta: np.ndarray, axis: np.ndarray) -> float:
    """Share of the vibration's kinetic weight Σ m |η_a|² along ``axis``."""
    _, m, _ = _geometry(data)
    d = eta.reshape(-1, 3)
    return float(np.sum(m * (d @ axis) ** 2) / np.sum(m * np.sum(d * d, axis=1)))


def _each(data, pick, check) -> bool | str:
    """``check(eta, name)`` for every vibration whose stored name ``pick`` selects: True, or
    the first failure's words."""
    z, modes, names = _vibrations(data)
    for k, name in enumerate(names):
        if pick(name):
            verdict = check(modes[:, k], name)
            if verdict is not True:
                return f"mode {z + k + 1} ({name}): {verdict}"
    return True


def _threshold(data) -> float:
    return float(data.analysis.get("dominant_share", _DOMINANT))


# --------------------------------------------------------------------------- molecules
@claim("normal modes: a linear molecule",
       r"(?<![\w-])linear (?:(?:mon|di|tri)atomic |four-atom |\d+-atom )?molecule\b"
       r"|\b2 \(linear\)|\bThis molecule is linear\b")
def linear_molecule(data) -> bool | str:
    """the atoms lie on one line (recomputed from the archived positions)"""
    return _axis(data) is not None or "an atom lies off the line through the farthest two"


@claim("normal modes: a non-linear molecule",
       r"\b(?:non-linear|bent) (?:(?:mon|di|tri)atomic |four-atom |\d+-atom )?molecule\b")
def non_linear_molecule(data) -> bool | str:
    """some atom lies off the line through the others (archived positions)"""
    return _axis(data) is None or "the atoms lie on one line"


@claim("normal modes: the count of zero modes", r"\(\d+ zero modes?\)|zero modes found \d+")
def zero_modes(data) -> bool | str:
    """the stored count of zero modes is the number of ω² of the archived (M, A) below
    1e-9 of the largest, recomputed"""
    found, stored = _zero_count(data), int(data.analysis["n_zero_modes"])
    return found == stored or f"{found} eigenvalues of (M, A) are zero, the report says {stored}"


@claim("normal modes: 3n − 5 or 3n − 6 vibrations", r"3n − [56] \((?:non-)?linear molecule")
def vibration_count(data) -> bool | str:
    """a linear molecule (atoms on one line) has 5 rigid zero modes, another 6, and the
    zero modes recomputed from (M, A) are that many"""
    expected = 5 if _axis(data) is not None else 6
    stored = int(data.analysis["expected_zero_modes"])
    if stored != expected:
        return f"the geometry gives 3n − {expected}, the report says 3n − {stored}"
    return True


@claim("normal modes: floppy internal modes", r"internal mode\(s\) have ω = 0")
def floppy(data) -> bool | str:
    """more zero modes than the rigid body's 5 (linear) or 6, recomputed"""
    rigid = 5 if _axis(data) is not None else 6
    return _zero_count(data) > rigid or "no zero mode beyond the rigid-body ones"


@claim("normal modes: a centre of inversion",
       r"have a centre of symmetry|has a centre of inversion")
def centre_of_inversion(data) -> bool | str:
    """every atom has an atom of equal mass opposite it through the centre of mass, and the
    bonds and angles go to ones of equal force constant (archived geometry and config)"""
    return _inversion(data) is not None or "no inversion maps the molecule onto itself"


@claim("normal modes: no centre of inversion", r"has no centre of inversion")
def no_centre_of_inversion(data) -> bool | str:
    """no inversion through the centre of mass maps the molecule and its bonds onto
    themselves (archived geometry and config)"""
    return _inversion(data) is None or "the inversion maps the molecule onto itself"


@claim("normal modes: parity under the inversion", r"\beven \(g\)|\bodd \(u\)")
def parity(data) -> bool | str:
    """each mode called even (odd) is mapped onto itself (its negative) by the inversion,
    recomputed from the mode vector"""
    image = _inversion(data)
    if image is None:
        return "the molecule has no centre of inversion"
    z, modes, _ = _vibrations(data)
    stored = [str(p) for p in data.analysis.get("mode_parity", ())][z:]
    for k, p in enumerate(stored):
        c = _parity(image, modes[:, k])
        if (p == "g" and c < 1 - _TOL) or (p == "u" and c > -1 + _TOL):
            return f"mode {z + k + 1} is called {p}; ⟨η, Sη⟩/⟨η, η⟩ = {c:.6f}"
    return True


def _named_class(name: str) -> tuple[str, str] | None:
    """(label, family) of a named vibration: ("C–O", "stretch"), ("", "bend"); None for a
    mixed or transverse one."""
    name = name.split(", ")[-1]
    if name.startswith(("mixed", "transverse", "normal mode")):
        return None
    m = re.fullmatch(r"(?:(?:anti)?symmetric )?(?:(\S+) )?(stretch|bend)", name)
    return (m.group(1) or "", m.group(2)) if m else None


@claim("normal modes: a stretch or bend",
       r"(?<![\w–])(?:(?:anti)?symmetric )?(?:stretch|bend)\b(?! constant)")
def family(data) -> bool | str:
    """a vibration named a stretch holds at least the naming share of its potential energy
    in the bonds (k δr² recomputed over ηᵀAη), one named a bend in the angles (the rest)"""
    if not _molecule(data):
        return "not a molecule"
    threshold = _threshold(data)

    def check(eta, name):
        label, fam = _named_class(name)
        stretch = float(np.sum(_bond_shares(data, eta)))
        share = stretch if fam == "stretch" else 1.0 - stretch
        return share >= threshold - _TOL or f"{fam} share {share:.3f} < {threshold:g}"

    return _each(data, lambda n: _named_class(n) is not None, check)


@claim("normal modes: a stretch named by its bonds",
       r"(?<![\w–])(?:[A-Z][a-z]?|\d+)–(?:[A-Z][a-z]?|\d+)(?:/\S+)? stretch\b")
def named_stretch(data) -> bool | str:
    """a vibration named "X–Y stretch" holds at least the naming share of its potential
    energy in the X–Y bonds, recomputed from its vector"""
    threshold = _threshold(data)

    def check(eta, name):
        label, _ = _named_class(name)
        bonds = _bonds_named(data, label)
        if not bonds:
            return f"no bond is {label}"
        share = float(np.sum(_bond_shares(data, eta)[bonds]))
        return share >= threshold - _TOL or f"{label} share {share:.3f} < {threshold:g}"

    return _each(data, lambda n: (c := _named_class(n)) is not None and c[1] == "stretch"
                 and c[0] != "", check)


@claim("normal modes: an unlabelled stretch names every bond alike",
       r"(?<![\w–])(?:(?:anti)?symmetric )?stretch\b(?! constant)")
def one_kind_of_bond(data) -> bool | str:
    """a stretch named without its bonds is in a molecule whose bonds all join the same two
    kinds of atom (element, else mass)"""
    names = _names(data)
    _, m, elements = _geometry(data)
    kind = [e if e != "X" else f"{m[a]:.9e}" for a, e in enumerate(elements)]
    pairs = {frozenset((kind[i], kind[j])) for i, j, _k in _bonds(data)}

    def check(_eta, _name):
        return len(pairs) == 1 or ("its bonds are of several kinds: "
                                   + ", ".join(sorted("–".join(sorted(names[a] for a in (i, j)))
                                                      for i, j, _k in _bonds(data))))

    return _each(data, lambda n: (c := _named_class(n)) is not None and c == ("", "stretch"),
                 check)


def _amplitudes(data, eta: np.ndarray, label: str, fam: str) -> list[float]:
    """The named coordinates' first-order changes along ``eta``: the bonds (or angles) the
    label names, every one of the family when it names none."""
    x = np.asarray(data.analysis["positions"], dtype=float)
    if fam == "stretch":
        bonds = _bonds(data)
        idx = _bonds_named(data, label) if label else range(len(bonds))
        return [_stretch(x, eta, bonds[b][0], bonds[b][1]) for b in idx]
    names = _names(data)
    out = []
    for g in data.config.angles:
        i, j, l = (int(v) for v in g.atoms)
        words = f"{names[i]}–{names[j]}–{names[l]}", f"{names[l]}–{names[j]}–{names[i]}"
        if not label or label in words or any(part in words for part in label.split("/")):
            out.append(_bend(x, eta, i, j, l))
    return out


def _phase_holds(data, eta, name: str, symmetric: bool) -> bool | str:
    image = _inversion(data)
    if image is not None:
        c = _parity(image, eta)
        ok = c > 1 - _TOL if symmetric else c < -1 + _TOL
        return ok or f"⟨η, Sη⟩/⟨η, η⟩ = {c:.6f} under the inversion"
    label, fam = _named_class(name)
    v = np.asarray(_amplitudes(data, eta, label, fam))
    if v.size < 2:
        return "no centre of inversion and fewer than two like coordinates"
    top = float(np.max(np.abs(v)))
    if symmetric:
        return float(np.ptp(v)) <= _TOL * top or f"the coordinates change by {np.round(v, 6)}"
    return abs(float(v.sum())) <= _TOL * top or f"the changes {np.round(v, 6)} do not cancel"


@claim("normal modes: a symmetric stretch or bend",
       r"(?<![\w-])symmetric (?:\S+ )?(?:stretch|bend)")
def symmetric(data) -> bool | str:
    """a "symmetric" vibration is even under the centre of inversion when there is one,
    else its like coordinates change by equal amounts (recomputed from the vector)"""
    return _each(data, lambda n: n.split(", ")[-1].startswith("symmetric"),
                 lambda eta, name: _phase_holds(data, eta, name, True))


@claim("normal modes: an antisymmetric stretch or bend",
       r"\bantisymmetric (?:\S+ )?(?:stretch|bend)")
def antisymmetric(data) -> bool | str:
    """an "antisymmetric" vibration is odd under the centre of inversion when there is one,
    else its like coordinates' changes sum to zero (recomputed from the vector)"""
    return _each(data, lambda n: n.split(", ")[-1].startswith("antisymmetric"),
                 lambda eta, name: _phase_holds(data, eta, name, False))


def _class_shares(data, eta: np.ndarray) -> dict[str, float]:
    """The vibration's potential energy per kind of coordinate: bonds by their two atoms'
    names, bent angles by theirs (k δθ², δθ by central differences), linear angles together
    as the rest of ηᵀAη."""
    names = _names(data)
    x = np.asarray(data.analysis["positions"], dtype=float)
    total = _energy(data, eta)
    out: dict[str, float] = {}
    for (i, j, _k), s in zip(_bonds(data), _bond_shares(data, eta), strict=True):
        key = "–".join(sorted((names[i], names[j])))
        out[key] = out.get(key, 0.0) + float(s)
    rest = 1.0 - sum(out.values())
    for g in data.config.angles:
        i, j, l = (int(v) for v in g.atoms)
        if math.pi - _angle(x, i, j, l) < 1e-6:
            continue
        key = "–".join([min(names[i], names[l]), names[j], max(names[i], names[l])])
        share = float(g.k) * _bend(x, eta, i, j, l) ** 2 / total
        out[key] = out.get(key, 0.0) + share
        rest -= share
    if rest > 1e-9:
        out["linear bends"] = rest
    return out


@claim("normal modes: a mixed vibration", r"\bmixed \S+ (?:stretch|bend)")
def mixed(data) -> bool | str:
    """a "mixed" vibration has no kind of coordinate (the bonds between two kinds of atom,
    the angles with the same three) holding the naming share of its potential energy,
    recomputed from its vector"""
    threshold = _threshold(data)

    def check(eta, _name):
        shares = _class_shares(data, eta)
        kind, best = max(shares.items(), key=lambda kv: kv[1])
        return best < threshold + _TOL or f"{kind} holds {best:.3f} ≥ {threshold:g}"

    return _each(data, lambda n: n.split(", ")[-1].startswith("mixed"), check)


@claim("normal modes: longitudinal and transverse vibrations",
       r"\b(?:longitudinal|transverse)\b")
def along_and_across(data) -> bool | str:
    """a vibration called longitudinal moves the atoms along their line, a transverse one
    across it (kinetic weight along the recomputed axis > 1 − 1e-6, < 1e-6), and the
    stored counts are those of the recomputed vibrations"""
    axis = _axis(data)
    if axis is None:
        return "the atoms are not on one line"
    counts = {"longitudinal": 0, "transverse": 0}

    def check(eta, name):
        along = _along(data, eta, axis)
        if name.startswith("longitudinal"):
            counts["longitudinal"] += 1
            return along > 1 - 1e-6 or f"only {along:.6f} of its motion is along the axis"
        counts["transverse"] += 1
        return along < 1e-6 or f"{along:.6f} of its motion is along the axis"

    verdict = _each(data, lambda n: n.startswith(("longitudinal", "transverse")), check)
    if verdict is not True:
        return verdict
    a = data.analysis
    for kind in counts:
        if f"n_{kind}" in a and int(a[f"n_{kind}"]) != counts[kind]:
            return f"{counts[kind]} {kind} vibrations, the report counts {int(a[f'n_{kind}'])}"
    return True


@claim("normal modes: in-plane and out-of-plane bends", r"\((?:in-plane|out-of-plane)\)")
def plane_of_bend(data) -> bool | str:
    """a transverse vibration called in-plane moves the atoms in the drawing plane (none
    along its normal), an out-of-plane one along the normal only"""
    frame = np.asarray(data.analysis["frame"], dtype=float)

    def check(eta, name):
        d = eta.reshape(-1, 3)
        out = float(np.sum((d @ frame[2]) ** 2) / np.sum(d * d))
        if "(in-plane)" in name:
            return out < 1e-6 or f"{out:.6f} of its motion is out of the plane"
        return out > 1 - 1e-6 or f"only {out:.6f} of its motion is out of the plane"

    return _each(data, lambda n: "plane)" in n, check)


@claim("normal modes: bends in pairs of equal frequency", r"in pairs of equal frequency")
def bend_pairs(data) -> bool | str:
    """the transverse vibrations' frequencies, recomputed from (M, A), come in equal pairs"""
    axis = _axis(data)
    if axis is None:
        return "the atoms are not on one line"
    z, modes, _ = _vibrations(data)
    M, A = (np.asarray(data.analysis[k], dtype=float) for k in ("mass_matrix", "hessian"))
    w2 = [float(eta @ A @ eta / (eta @ M @ eta)) for eta in modes.T
          if _along(data, eta, axis) < 1e-6]
    w2.sort()
    top = max(w2, default=1.0)
    if len(w2) % 2 or any(abs(w2[i] - w2[i + 1]) > 1e-6 * top for i in range(0, len(w2), 2)):
        return f"transverse ω² {np.round(w2, 6)} are not in equal pairs"
    return True


@claim("normal modes: degenerate sets", r"\(×\d+\)|\bdegeneracy\b")
def degeneracy(data) -> bool | str:
    """modes share a degenerate set only when their ω, recomputed from (M, A), agree to
    1e-6 of the largest, and ω equal to 1e-10 share one (the simulation groups at 1e-8)"""
    w = np.sqrt(np.clip(_omega2(data), 0.0, None))
    groups = np.asarray(data.analysis["degenerate_group"])
    top = float(np.max(w))
    for i in range(len(w) - 1):
        same, gap = groups[i] == groups[i + 1], abs(w[i + 1] - w[i])
        if (same and gap > 1e-6 * top) or (not same and gap <= 1e-10 * top):
            return f"modes {i + 1} and {i + 2}: ω {w[i]:.9g} and {w[i + 1]:.9g}"
    return True


# ------------------------------------------------------------------ chains and pendula
def _sign_changes(v: np.ndarray) -> int:
    v = v[np.abs(v) > 1e-6 * np.max(np.abs(v))]
    return int(np.sum(np.sign(v[1:]) != np.sign(v[:-1])))


@claim("normal modes: nodes of a chain's modes", r"\b\d+ nodes?\b")
def nodes(data) -> bool | str:
    """a mode said to have N nodes changes sign N times along the chain (archived vector)"""
    def check(eta, name):
        n = _sign_changes(eta)
        return n == int(name.split()[0]) or f"{n} sign changes"

    return _each(data, lambda n: re.fullmatch(r"\d+ nodes?", n) is not None, check)


@claim("normal modes: two pendula in or out of phase",
       r"(?<!coordinate )\b(?:in|out of) phase\b(?! with)")
def pendula_phase(data) -> bool | str:
    """the mode called in phase moves both pendula the same way, out of phase opposite
    (archived vector)"""
    def check(eta, name):
        same = bool(eta[0] * eta[-1] > 0)
        return same == (name == "in phase") or f"components {np.round(eta, 6)}"

    return _each(data, lambda n: n in ("in phase", "out of phase"), check)


@claim("normal modes: a chain between fixed walls", r"between fixed walls")
def fixed_walls(data) -> bool | str:
    """A holds every mass to the walls: no zero mode (archived A)"""
    return _zero_count(data) == 0 or "the archived A has a zero mode: the ends are free"


@claim("normal modes: a chain with free ends", r"with free ends")
def free_ends(data) -> bool | str:
    """A moves nothing under a uniform shift: its rows sum to zero (archived A)"""
    A = np.asarray(data.analysis["hessian"], dtype=float)
    return (float(np.max(np.abs(A.sum(axis=1)))) <= 1e-9 * float(np.max(np.abs(A)))
            or "a uniform shift stretches the archived springs: an end is held")


# -------------------------------------------------------------------------- evolution
def _ratio(data) -> float:
    w2 = _omega2(data)
    w = np.sqrt(w2[w2 > 1e-9 * float(np.max(w2))])
    return float(w.max() / w.min())


@claim("normal modes: a stiff evolution", r"This scene is stiff|≥ 1000: an explicit")
def stiff(data) -> bool | str:
    """ω_max/ω_min of the archived (M, A), recomputed, is at least 10³"""
    r = _ratio(data)
    return r >= 1e3 or f"ω_max/ω_min = {r:.3g}"


@claim("normal modes: a non-stiff evolution", r"< 1000: not stiff")
def not_stiff(data) -> bool | str:
    """ω_max/ω_min of the archived (M, A), recomputed, is below 10³"""
    r = _ratio(data)
    return r < 1e3 or f"ω_max/ω_min = {r:.3g}"
