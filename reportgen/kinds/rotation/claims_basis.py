"""The claim-carrying sentences of textbook ex. 4.2(a)–(c) on a random basis that is not
orthonormal and of the notes' Figure 2 (see :mod:`reportgen.scene.claims`).

The predicates rebuild from the archived inputs alone, with code of their own: the Gram
matrix and the components of V from the stored basis vectors, the relations' residuals,
the Euler matrices of the sketch's angles (by :func:`.claims._euler`, elementary rotations
written out again) and the sense of each stored angle arc from its points.
"""

from __future__ import annotations

import math

import numpy as np

from ...scene.claims import claim
from .claims import CONTRAST, SLACK, TOLERANCE, _euler


def _sizes(data) -> list[int]:
    g = data.analysis["proofs"]
    return [int(n) for n in g["sizes"] if f"prime_{int(n)}" in g.get("basis", {})]


def _gram_distances(data) -> list[float]:
    b = data.analysis["proofs"]["basis"]
    out = []
    for n in _sizes(data):
        P = np.asarray(b[f"prime_{n}"], dtype=float)
        out.append(float(np.max(np.abs(P.T @ P - np.eye(n)))))
    return out


def _projection_gaps(data) -> list[float]:
    """Per size: how far the projections e′ᵢ · V are from the components V′ that rebuild
    V (least squares on the stored basis), relative to the largest."""
    b = data.analysis["proofs"]["basis"]
    out = []
    for n in _sizes(data):
        P, V = np.asarray(b[f"prime_{n}"], dtype=float), np.asarray(b[f"vector_{n}"], dtype=float)
        components = np.linalg.lstsq(P, V, rcond=None)[0]
        out.append(float(np.max(np.abs(P.T @ V - components))
                         / max(np.max(np.abs(components)), np.max(np.abs(P.T @ V)))))
    return out


def _residual(data) -> float:
    """The largest relative residual of ex. 4.2(a)–(c) rebuilt from the stored ê, A, e′ and
    V of every size: êᵢ = Σⱼ Aⱼᵢ e′ⱼ, e′ⱼ = Σᵢ (A⁻¹)ᵢⱼ êᵢ, V′ = AV and V = A⁻¹V′ with V′
    the least-squares components of V in e′ and Vᵢ = êᵢ · V."""
    b = data.analysis["proofs"]["basis"]
    worst = 0.0

    def rel(x, y):
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        return float(np.max(np.abs(x - y)) / max(np.max(np.abs(x)), np.max(np.abs(y))))

    for n in _sizes(data):
        H, A, P = (np.asarray(b[f"{k}_{n}"], dtype=float) for k in ("hat", "matrix", "prime"))
        V = np.asarray(b[f"vector_{n}"], dtype=float)
        A_inv = np.linalg.inv(A)
        hat_components = H.T @ V
        components = np.linalg.lstsq(P, V, rcond=None)[0]
        worst = max(worst, rel(P @ A, H), rel(P, H @ A_inv), rel(components, A @ hat_components),
                    rel(hat_components, A_inv @ components))
    return worst


@claim("rotation basis checks hold",
       r"(?:all \d+|both) checks of textbook ex\. 4\.2\(a\)–\(c\) on the basis e′ hold")
def basis_checks_hold(data) -> bool | str:
    """ex. 4.2(a)–(c), rebuilt from the stored bases, A and V, hold within the bound"""
    worst = _residual(data)
    return True if worst <= SLACK * TOLERANCE else f"rebuilt, off by {worst:.2g}"


@claim("rotation basis checks fail",
       r"\d+ of \d+ checks of textbook ex\. 4\.2\(a\)–\(c\) on the basis e′ fail")
def basis_checks_fail(data) -> bool | str:
    """some of ex. 4.2(a)–(c), rebuilt, is off by more than the bound"""
    worst = _residual(data)
    return True if worst > SLACK * TOLERANCE else f"rebuilt, all within {worst:.2g}"


@claim("rotation basis not orthonormal", r"e′ is not orthonormal")
def basis_not_orthonormal(data) -> bool | str:
    """the stored e′ of every size has a Gram matrix farther than 10⁻⁹ from 1"""
    gram = _gram_distances(data)
    return True if min(gram) > CONTRAST else f"max |G − 1| = {min(gram):.2g}"


@claim("rotation basis orthonormal", r"e′ is orthonormal here to 10⁻⁹(?! for some)")
def basis_orthonormal(data) -> bool | str:
    """the stored e′ of every size has a Gram matrix within 10⁻⁹ of 1"""
    gram = _gram_distances(data)
    return True if max(gram) <= CONTRAST else f"max |G − 1| = {max(gram):.2g}"


@claim("rotation projections are not components", r"V are not the components V′")
def projections_differ(data) -> bool | str:
    """the projections e′ᵢ · V, rebuilt, differ from the components of V in e′ (every size)"""
    gaps = _projection_gaps(data)
    return True if min(gaps) > CONTRAST else f"relative distance {min(gaps):.2g}"


@claim("rotation projections are components", r"V are the components V′\S* here(?! for some)")
def projections_same(data) -> bool | str:
    """the projections e′ᵢ · V, rebuilt, are the components of V in e′ (every size)"""
    gaps = _projection_gaps(data)
    return True if max(gaps) <= CONTRAST else f"relative distance {max(gaps):.2g}"


# ----------------------------------------------------------------- the notes' Figure 2
def _sketch_rotation(data) -> tuple[float, str]:
    """(distance of the Euler matrix of the sketch's angles in its convention from that of
    the scene's angles at t = 0 in theirs and from the stored body axes, the convention)."""
    e = data.analysis["euler"]
    s = e["sketch"]
    conv = str(s["convention"])
    R = _euler(np.asarray(s["angles"], dtype=float)[None], conv)[0]
    scene = _euler(np.asarray(e["path"], dtype=float)[:1], str(e["convention"]))[0]
    body = np.asarray(e["construction"][conv]["body_axes"], dtype=float)
    return max(float(np.max(np.abs(R - scene))), float(np.max(np.abs(R - body)))), conv


def _drawn_in(convention: str):
    def holds(data) -> bool | str:
        gap, conv = _sketch_rotation(data)
        if conv != convention:
            return f"the sketch's angles are {conv}"
        return True if gap <= SLACK * TOLERANCE else f"its rotation is off by {gap:.2g}"

    holds.__doc__ = (f"the sketch's angles, as {convention} angles rebuilt, give the scene's "
                     "rotation and the drawn body axes")
    return holds


for _convention, _words in (("zxz", "z-x-z"), ("zyz", "z-y-z")):
    claim(f"rotation sketch {_words}",
          rf"drawn for this scene's rotation in the {_words} convention")(_drawn_in(_convention))


@claim("rotation sketch angles as given", r"These are the angles as given")
def sketch_as_given(data) -> bool | str:
    """the sketch's angles are the scene's at t = 0, in the scene's own convention"""
    e = data.analysis["euler"]
    s = e["sketch"]
    same = (str(s["convention"]) == str(e["convention"])
            and np.array_equal(np.asarray(s["angles"]), np.asarray(e["path"])[0]))
    return True if same else "converted from another convention"


@claim("rotation sketch angles converted", r"these are the same rotation's, converted")
def sketch_converted(data) -> bool | str:
    """the sketch's convention is not the scene's, and its angles give the same rotation"""
    e = data.analysis["euler"]
    gap, conv = _sketch_rotation(data)
    if conv == str(e["convention"]):
        return "the sketch's convention is the scene's own"
    return True if gap <= SLACK * TOLERANCE else f"another rotation: off by {gap:.2g}"


def _arc_turns(data) -> list[float]:
    """The turn [rad] of each stored arc of the sketch (φ about z, θ about the line of
    nodes, ψ about z′) from its end points, its sign from the sense of its first step."""
    e = data.analysis["euler"]
    c = e["construction"][str(e["sketch"]["convention"])]
    axes = (np.array([0.0, 0.0, 1.0]), np.asarray(c["node"], dtype=float),
            np.asarray(c["body_axes"], dtype=float)[:, 2])
    turns = []
    for key, axis in zip(("arc_phi", "arc_theta", "arc_psi"), axes, strict=True):
        arc = np.asarray(c[key], dtype=float)
        step = float(np.dot(axis, np.cross(arc[0], arc[1])))
        total = sum(math.acos(max(-1.0, min(1.0, float(np.dot(a, b)))))
                    for a, b in zip(arc[:-1], arc[1:], strict=True))
        turns.append(math.copysign(total, step) if step else 0.0)
    return turns


@claim("rotation sketch negative angle", r"(?:is|are) negative here: the arrowhead")
def sketch_negative(data) -> bool | str:
    """some arc of the sketch, rebuilt from its points, turns clockwise about its axis by
    at least 1°"""
    turns = _arc_turns(data)
    return True if min(turns) <= -math.radians(1.0) else f"turns {turns}"


@claim("rotation sketch small angle", r"below 1°: no arc drawn")
def sketch_small(data) -> bool | str:
    """some arc of the sketch, rebuilt from its points, turns by less than 1°"""
    turns = _arc_turns(data)
    return True if min(abs(t) for t in turns) < math.radians(1.0) else f"turns {turns}"
