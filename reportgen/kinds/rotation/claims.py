"""The ``rotation`` report's claim-carrying sentences (see :mod:`reportgen.scene.claims`).

Each checks table's caption says whether its identities hold ("all 7 axis–angle checks
hold", "2 of 13 Möbius-map checks fail"), chosen by the stored errors against the bound
``TOLERANCE``; the contrasts say whether R(U)ᵀ is the Möbius map and whether the reversed
product is another rotation, chosen by ``transpose_differs`` … against ``CONTRAST``.  The
predicates rebuild the constructions here from the archived inputs (axis, angle, Euler
angles and rates, the SU(2) element, the sample points), with code of their own (the
Rodrigues formula, elementary rotations, the complex step, the trace formula and the
Möbius map written out again), and compare them with the archived results.
"""

from __future__ import annotations

import math
import re

import numpy as np

from ...scene.claims import claim

#: restated (the claims hold the archive to these, not to the kind's own constants)
TOLERANCE = 1e-12
CONTRAST = 1e-9
ORDER_SLACK = 0.1
ORDER_RANGE = 0.5
#: an independent rebuild agrees with the archived construction to rounding; a construction
#: "holds" when it does so within the bound (a few ε of margin for the rebuild's own rounding)
SLACK = 2.0

_SIGMA = np.array([[[0, 1], [1, 0]], [[0, -1j], [1j, 0]], [[1, 0], [0, -1]]], dtype=complex)


def _cross(n):
    n = np.asarray(n, dtype=complex if np.iscomplexobj(n) else float)
    return np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])


def _rodrigues(n, phi) -> np.ndarray:
    n = np.asarray(n, dtype=float) / np.linalg.norm(n)
    return (math.cos(phi) * np.eye(3) + (1 - math.cos(phi)) * np.outer(n, n)
            + math.sin(phi) * _cross(n))


def _elementary(axis: str, a):
    """Active rotations by the angles ``a`` (N,) about a coordinate axis, (N, 3, 3); the
    angles may be complex (the complex step)."""
    a = np.asarray(a)
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(c), np.zeros_like(c)
    m = {"x": [[o, z, z], [z, c, -s], [z, s, c]], "y": [[c, z, s], [z, o, z], [-s, z, c]],
         "z": [[c, -s, z], [s, c, z], [z, z, o]]}[axis]
    return np.moveaxis(np.array(m), (0, 1), (-2, -1))


def _euler(angles, convention: str):
    """R = R_z(φ) R_{x|y}(θ) R_z(ψ) for angles (N, 3), (N, 3, 3)."""
    a = np.atleast_2d(angles)
    middle = "x" if convention == "zxz" else "y"
    return _elementary("z", a[:, 0]) @ _elementary(middle, a[:, 1]) @ _elementary("z", a[:, 2])


def _vee(W):
    return np.stack([W[..., 2, 1], W[..., 0, 2], W[..., 1, 0]], axis=-1)


def _omega(path, rates, convention):
    """(ω space, ω body) along the path by the complex step on R (h = 1e-30)."""
    h = 1e-30
    Rc = _euler(np.asarray(path) + 1j * h * np.asarray(rates), convention)
    R, Rdot = Rc.real, Rc.imag / h
    return (_vee(Rdot @ np.swapaxes(R, -1, -2)), _vee(np.swapaxes(R, -1, -2) @ Rdot))


def _su2(n, phi) -> np.ndarray:
    n = np.asarray(n, dtype=float) / np.linalg.norm(n)
    return (math.cos(phi / 2) * np.eye(2)
            - 1j * math.sin(phi / 2) * np.einsum("k,kab->ab", n, _SIGMA))


def _su2_euler(angles, convention) -> np.ndarray:
    middle = 0 if convention == "zxz" else 1

    def turn(k, a):
        return math.cos(a / 2) * np.eye(2) - 1j * math.sin(a / 2) * _SIGMA[k]

    phi, theta, psi = (float(v) for v in angles)
    return turn(2, phi) @ turn(middle, theta) @ turn(2, psi)


def _so3(U) -> np.ndarray:
    Ud = np.conj(U).T
    return np.array([[0.5 * np.trace(_SIGMA[i] @ U @ _SIGMA[j] @ Ud).real for j in range(3)]
                     for i in range(3)])


def _element(a, b) -> np.ndarray:
    a, b = complex(*np.asarray(a)), complex(*np.asarray(b))
    return np.array([[a, b], [-b.conjugate(), a.conjugate()]])


def _worst(*pairs) -> float:
    return max(float(np.max(np.abs(np.asarray(x) - np.asarray(y)))) for x, y in pairs)


def _verdicts(what: str, rebuild):
    """Register "all … hold" and "… fail" for one table: ``rebuild(data)`` returns the
    largest distance of the archived constructions from their rebuilds."""
    def holds(data) -> bool | str:
        worst = rebuild(data)
        return True if worst <= SLACK * TOLERANCE else f"rebuilt, off by {worst:.2g}"

    def fails(data) -> bool | str:
        worst = rebuild(data)
        return True if worst > SLACK * TOLERANCE else f"rebuilt, all within {worst:.2g}"

    holds.__doc__ = f"the {what} rebuilt here agree with the archive within the bound"
    fails.__doc__ = f"some of the {what} rebuilt here are off the archive by more than the bound"
    claim(f"rotation {what} hold", rf"(?:all \d+|both) {re.escape(what)} hold")(holds)
    claim(f"rotation {what} fail", rf"\d+ of \d+ {re.escape(what)} fail")(fails)


def _axis_angle(data) -> float:
    a = data.analysis["axis_angle"]
    n = np.asarray(a["axis_given"], dtype=float)
    phi, r = float(a["angle"]), np.asarray(a["vector"], dtype=float)
    R = _rodrigues(n, phi)
    angle = math.acos(max(-1.0, min(1.0, (np.trace(np.asarray(a["matrix_textbook"])) - 1) / 2)))
    return max(_worst((a["matrix_textbook"], R), (a["matrix_expm"], R),
                      (a["matrix_quaternion"], R), (np.asarray(a["matrix_formula"]).T, R),
                      (a["turned_vector"], R @ r), (a["rotated_vector"], R.T @ r)),
               abs(angle - phi) * min(1.0, phi, math.pi - phi + 1e-3) if phi < math.pi else 0)


def _euler_matrices(data) -> float:
    e = data.analysis["euler"]
    given, other = str(e["convention"]), str(e["other_convention"])
    R = _euler(np.asarray(e["path"])[:1], given)[0]
    R2 = _euler(np.asarray(e["path_other"])[:1], other)[0]
    return _worst((e["matrix"], R), (e["matrix_other"], R2), (R, R2),
                  (np.asarray(e["elements"]).T, R))


def _angular_velocity(data) -> float:
    e = data.analysis["euler"]
    path, rates = np.asarray(e["path"]), np.asarray(e["rates"])
    space, body = _omega(path, np.broadcast_to(rates, path.shape), str(e["convention"]))
    scale = float(np.max(np.linalg.norm(space, axis=-1))) or 1.0
    return _worst((e["omega_space"], space), (e["omega_body"], body),
                  (e["omega_space_other"], space), (e["omega_body_other"], body)) / scale


def _identities(data) -> float:
    d, a = data.analysis["identities"], data.analysis.get("axis_angle")
    S = np.asarray(d["second_rotation"])
    worst = _worst((S.T @ S, np.eye(3)))
    if a is not None:
        n = np.asarray(a["axis_given"], float) / np.linalg.norm(a["axis_given"])
        phi = float(a["angle"])
        turned = np.asarray(d["turned"])
        worst = max(worst, _worst((turned[0], _rodrigues(S @ n, phi)),
                                  (turned[1], phi * _cross(S @ n)),
                                  (d["trace_turned"], [1 + 2 * math.cos(phi), 0.0,
                                                       1 + 2 * math.cos(phi)]),
                                  (d["determinant_turned"], [1.0, 0.0, math.cos(phi) ** 2])))
    if "euler" in data.analysis:
        e = data.analysis["euler"]
        worst = max(worst, _worst((S, _euler(np.asarray(e["path"])[:1],
                                              str(e["convention"]))[0])))
    return worst


def _su2_form(data) -> float:
    d = data.analysis["su2_form"]
    U = _su2(d["axis"], float(d["angle"]))
    Ue = _su2_euler(np.asarray(d["euler_angles"]), str(d["convention"]))
    Re = _euler(np.asarray(d["euler_angles"])[None], str(d["convention"]))[0]
    return _worst((_element(d["a"], d["b"]), U), (d["rotation"], _so3(U)),
                  (_element(d["euler_a"], d["euler_b"]), Ue), (d["euler_rotation"], Re),
                  (_so3(Ue), Re), (_rodrigues(d["euler_axis"], float(d["euler_angle"])), Re))


def _inverse(zeta):
    """The point of the unit sphere projected to ζ = (x − iy)/(1 − z), (N, 3)."""
    w = np.abs(zeta) ** 2
    return np.stack([2 * zeta.real, -2 * zeta.imag, w - 1], axis=-1) / (w + 1)[:, None]


def _rotation_of(s) -> np.ndarray:
    return _so3(_element(s["a"], s["b"]))


def _mobius(data) -> float:
    s = data.analysis["stereographic"]
    U = _element(s["a"], s["b"])
    (a, b), (c, d) = U
    x = np.asarray(s["points"], dtype=float)
    zeta = (x[:, 0] - 1j * x[:, 1]) / (1 - x[:, 2])
    moved = _inverse((a * zeta + b) / (c * zeta + d))
    R = _so3(U)
    U2 = _element(s["second_a"], s["second_b"])
    return _worst((moved, x @ R.T), (s["rotation"], R), (s["rotation_minus_u"], R),
                  (s["images"], x @ R.T), (_so3(U @ U2), R @ _so3(U2)),
                  (s["second_rotation"], _so3(U2)))


_verdicts("axis–angle checks", _axis_angle)
_verdicts("Euler-matrix checks", _euler_matrices)
_verdicts("angular-velocity checks", _angular_velocity)
_verdicts("identities limited by rounding", _identities)
_verdicts("SU(2) checks", _su2_form)
_verdicts("Möbius-map checks", _mobius)


# ----------------------------------------------------------------- the contrasts
def _asymmetry(data) -> float:
    R = _rotation_of(data.analysis["stereographic"])
    return float(np.max(np.abs(R - R.T)))


def _conjugate_gap(data) -> float:
    s = data.analysis["stereographic"]
    R, Rbar = _rotation_of(s), _so3(np.conj(_element(s["a"], s["b"])))
    return float(np.max(np.abs(Rbar - R.T)))


def _commutator(data) -> float:
    s = data.analysis["stereographic"]
    R, R2 = _rotation_of(s), _so3(_element(s["second_a"], s["second_b"]))
    return float(np.max(np.abs(R @ R2 - R2 @ R)))


@claim("rotation transpose differs",
       r"R\(U\)[ᵀT] is not the Möbius map|R\(U\)[ᵀT] would be off by"
       r"|the Möbius map matches R, not R[ᵀT]")
def transpose_differs(data) -> bool | str:
    """R(U), rebuilt from the archived a, b, is not symmetric (so Rᵀ is another map)"""
    gap = _asymmetry(data)
    return True if gap > CONTRAST else f"|R − Rᵀ| = {gap:.2g}: R is symmetric"


@claim("rotation transpose is the map",
       r"R\(U\)[ᵀT] is the Möbius map too|R\(U\)[ᵀT] is the same map|and here R[ᵀT] as well")
def transpose_same(data) -> bool | str:
    """R(U), rebuilt, is symmetric (a half turn): Rᵀ is the Möbius map too"""
    gap = _asymmetry(data)
    return True if gap <= CONTRAST else f"|R − Rᵀ| = {gap:.2g}"


@claim("rotation usual orientation differs", r"nor is it with the usual orientation")
def usual_differs(data) -> bool | str:
    """R(Ū), rebuilt, is not R(U)ᵀ"""
    gap = _conjugate_gap(data)
    return True if gap > CONTRAST else f"|R(Ū) − Rᵀ| = {gap:.2g}"


@claim("rotation usual orientation is the transpose",
       r"with the usual orientation R\(U\)[ᵀT] is that Möbius map|for a half turn about the y "
       r"axis, as here")
def usual_same(data) -> bool | str:
    """R(Ū), rebuilt, is R(U)ᵀ (an axis in the x–z plane, or a half turn about y)"""
    gap = _conjugate_gap(data)
    return True if gap <= CONTRAST else f"|R(Ū) − Rᵀ| = {gap:.2g}"


@claim("rotation reversed order differs", r"the reversed order is another rotation")
def reversed_differs(data) -> bool | str:
    """R(U) and R(U₂), rebuilt, do not commute"""
    gap = _commutator(data)
    return True if gap > CONTRAST else f"|[R, R₂]| = {gap:.2g}: they commute"


@claim("rotation reversed order same", r"the reversed order gives the same rotation here")
def reversed_same(data) -> bool | str:
    """R(U) and R(U₂), rebuilt, commute"""
    gap = _commutator(data)
    return True if gap <= CONTRAST else f"|[R, R₂]| = {gap:.2g}"


@claim("rotation difference quotient order", r"tends to the scale factor as δ²")
def quotient_order(data) -> bool | str:
    """the difference quotient |Δζ|/|Δx| along each point's circle of latitude, rebuilt at
    the archived arcs δ, departs from 1/(1 − z) in proportion to δ² (ratio within a factor
    2 of the steps' squared ratio)"""
    s = data.analysis["stereographic"]
    x = np.asarray(s["points"], dtype=float)
    steps = [float(v) for v in np.asarray(s["contrasts"]["steps"])]
    rho = np.hypot(x[:, 0], x[:, 1])
    east = np.stack([-x[:, 1], x[:, 0], np.zeros(len(x))], axis=-1) / rho[:, None]
    devs = []
    for d in steps:
        plus, minus = x * math.cos(d) + east * math.sin(d), x * math.cos(d) - east * math.sin(d)

        def proj(p):
            return (p[:, 0] - 1j * p[:, 1]) / (1 - p[:, 2])

        q = np.abs(proj(plus) - proj(minus)) / np.linalg.norm(plus - minus, axis=1)
        devs.append(float(np.max(np.abs(q * (1 - x[:, 2]) - 1))))
    expected = (steps[0] / steps[1]) ** 2
    ratio = devs[0] / devs[1]
    return True if expected / 2 <= ratio <= 2 * expected else f"ratio {ratio:.3g}"


@claim("rotation minus U angle", r"−U turns by 360° − α about −m")
def minus_u(data) -> bool | str:
    """the Euler-angle U at t = 0, rebuilt, has ½ tr U < 0: its angle α exceeds 180°"""
    d = data.analysis["su2_form"]
    U = _su2_euler(np.asarray(d["euler_angles"]), str(d["convention"]))
    half_trace = float(np.trace(U).real) / 2
    return True if half_trace < 0 else f"½ tr U = {half_trace:.3g} ≥ 0: α ≤ 180°"


def _order(data):
    """(order of the central differences, h max|ω|) rebuilt from the archived path."""
    e = data.analysis["euler"]
    t, path = np.asarray(e["t"], dtype=float), np.asarray(e["path"], dtype=float)
    rates = np.asarray(e["rates"], dtype=float)
    conv = str(e["convention"])
    R = _euler(path, conv)
    space, _ = _omega(path, np.broadcast_to(rates, path.shape), conv)
    scale = float(np.max(np.linalg.norm(space, axis=-1))) or 1.0
    h = float(t[1] - t[0])
    Om = _cross_many(space)[2:-2]
    inv = np.swapaxes(R[2:-2], -1, -2)
    e1 = float(np.max(np.abs((R[3:-1] - R[1:-3]) / (2 * h) @ inv - Om))) / scale
    e2 = float(np.max(np.abs((R[4:] - R[:-4]) / (4 * h) @ inv - Om))) / scale
    return math.log2(e2 / e1), h * scale


def _cross_many(w):
    out = np.zeros(w.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2], out[..., 1, 2] = -w[..., 2], w[..., 1], -w[..., 0]
    return out - np.swapaxes(out, -1, -2)


@claim("rotation order within", r"checked: within 2 ± ")
def order_within(data) -> bool | str:
    """the central differences of the archived path, rebuilt, show order 2 ± 0.1 where
    h max|ω| ≤ 0.5"""
    order, turn = _order(data)
    return True if turn <= ORDER_RANGE and abs(order - 2) <= ORDER_SLACK else \
        f"order {order:.4g} at h max|ω| = {turn:.3g}"


@claim("rotation order outside", r"checked: outside 2 ± ")
def order_outside(data) -> bool | str:
    """the rebuilt order misses 2 by more than 0.1 where h max|ω| ≤ 0.5"""
    order, turn = _order(data)
    return True if turn <= ORDER_RANGE and abs(order - 2) > ORDER_SLACK else \
        f"order {order:.4g} at h max|ω| = {turn:.3g}"


@claim("rotation order not checked", r"not checked, as h max \|ω\| is above")
def order_not_checked(data) -> bool | str:
    """the archived path's step turns it by more than 0.5: h max|ω| > 0.5"""
    _, turn = _order(data)
    return True if turn > ORDER_RANGE else f"h max|ω| = {turn:.3g}"
