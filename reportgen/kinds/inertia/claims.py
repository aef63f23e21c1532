"""The ``inertia`` report's claim-carrying sentences and their predicates (issue 41).

Each predicate measures its claim again from the archive's raw record with numpy alone:
the principal moments as the eigenvalues of the archived tensor, the stability of spin
about each axis from the Jacobian of Euler's equations written out here, the shape's own
axes by turning the archived principal axes back with the configured Euler angles, the
closed forms of the configured shape.  The helpers are shared with ``rigid_body``'s
claims, whose bodies are the same shapes.
"""

from __future__ import annotations

import math

import numpy as np

from ...scene.claims import claim

#: moments equal within this share of the largest (the declared threshold, when the
#: archive has none)
EQUAL_RTOL = 1e-12


# ----------------------------------------------------------------------- measurements
def equal_pairs(moments, rtol: float = EQUAL_RTOL) -> int:
    """How many of the three pairs of moments are equal within ``rtol`` of the largest."""
    I = np.sort(np.asarray(moments, dtype=float))
    tol = rtol * float(I[-1])
    return sum(abs(float(I[j] - I[i])) <= tol for i, j in ((0, 1), (1, 2), (0, 2)))


def top_words(moments, rtol: float = EQUAL_RTOL) -> str:
    """"spherical", "symmetric" or "asymmetric" from the moments themselves."""
    return {0: "asymmetric", 1: "symmetric"}.get(equal_pairs(moments, rtol), "spherical")


def jacobian_verdicts(moments, rtol: float = EQUAL_RTOL) -> list[str]:
    """Per axis, free spin about it as the eigenvalues of the Jacobian of Euler's
    equations I₁ω̇₁ = (I₂ − I₃)ω₂ω₃ (cyclic) at ω = e_k say: "unstable" (an eigenvalue with
    a positive real part), "marginal" (the moment equals another: the Jacobian is
    nilpotent) or "stable" (purely imaginary)."""
    I = np.asarray(moments, dtype=float)
    out = []
    for k in range(3):
        others = [j for j in range(3) if j != k]
        if any(abs(float(I[j] - I[k])) <= rtol * float(I.max()) for j in others):
            out.append("marginal")
            continue
        w = np.zeros(3)
        w[k] = 1.0
        J = np.zeros((3, 3))
        for i in range(3):  # ∂/∂ω of (I_j − I_l) ω_j ω_l / I_i, (i, j, l) cyclic
            j, l = (i + 1) % 3, (i + 2) % 3
            c = (I[j] - I[l]) / I[i]
            J[i, j] += c * w[l]
            J[i, l] += c * w[j]
        growth = float(np.max(np.linalg.eigvals(J).real))
        out.append("unstable" if growth > 1e-9 else "stable")
    return out


def euler_rotation(angles) -> np.ndarray:
    """R = R_z(φ) R_x(θ) R_z(ψ), body -> lab (z-x-z), or the identity for None."""
    if angles is None:
        return np.eye(3)

    def rz(a):
        c, s = math.cos(a), math.sin(a)
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    def rx(a):
        c, s = math.cos(a), math.sin(a)
        return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])

    phi, theta, psi = (float(x) for x in angles)
    return rz(phi) @ rx(theta) @ rz(psi)


def closed_moments(shape) -> np.ndarray | None:
    """The moments of the configured solid about its own x, y, z (Landau & Lifshitz §32
    Problem 2; textbook ex. 4.6, 4.9), or None for a point set."""
    t, M = shape.get("type"), float(shape.get("mass", 0.0) or 0.0)
    if t == "box":
        a, b, c = (float(shape[k]) for k in "abc")
        return M / 12 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
    if t == "ellipsoid":
        a, b, c = (float(shape[k]) for k in "abc")
        return M / 5 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
    if t == "cylinder":
        R, h = float(shape["radius"]), float(shape["height"])
        return np.array([M * (R * R / 4 + h * h / 12)] * 2 + [M * R * R / 2])
    if t == "cone":
        R, h = float(shape["radius"]), float(shape["height"])
        return np.array([3 * M * (R * R + h * h / 4) / 20] * 2 + [3 * M * R * R / 10])
    if t == "octahedron":
        a, b = float(shape["a"]), float(shape["b"])
        if shape.get("equator") == "rectangle":
            h = float(shape["h"])
            return M / 20 * np.array([b * b + 2 * h * h, a * a + 2 * h * h, a * a + b * b])
        c = float(shape["c"])
        return M / 10 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
    return None


def eigen_moments(data) -> np.ndarray:
    """The principal moments as the eigenvalues of the archived tensor, ascending."""
    return np.linalg.eigvalsh(np.asarray(data.analysis["tensor"], dtype=float))


def _verdicts_hold(data, moments) -> bool | str:
    stored = [str(data.analysis["axis_stability"][f"axis_{k + 1}"]["verdict"])
              for k in range(3)]
    found = jacobian_verdicts(moments)
    return stored == found or f"the Jacobian gives {found}, the report says {stored}"


# -------------------------------------------------------------------------- the claims
@claim("inertia: a spherical top",
       r"All three principal moments are equal|all three moments equal|marginal: spherical")
def spherical(data) -> bool | str:
    """the archived tensor's eigenvalues are all equal (within 1e-12 of the largest)"""
    I = eigen_moments(data)
    return top_words(I) == "spherical" or f"the tensor's eigenvalues are {I}"


@claim("inertia: a symmetric top",
       r"Two principal moments are equal|two equal moments|marginal: symmetric")
def symmetric(data) -> bool | str:
    """exactly two eigenvalues of the archived tensor are equal (within 1e-12)"""
    I = eigen_moments(data)
    return top_words(I) == "symmetric" or f"the tensor's eigenvalues are {I}"


@claim("inertia: an asymmetric top", r"The three moments differ|unstable about the "
       r"intermediate axis")
def asymmetric(data) -> bool | str:
    """the archived tensor's three eigenvalues differ (by more than 1e-12 of the largest)"""
    I = eigen_moments(data)
    return top_words(I) == "asymmetric" or f"the tensor's eigenvalues are {I}"


@claim("inertia: which spin axes are stable", r"\b(?:un)?stable\b|\bmarginal\b")
def verdicts(data) -> bool | str:
    """each axis's verdict is what the Jacobian of Euler's equations at steady spin about
    it gives, with the moments recomputed from the archived tensor"""
    return _verdicts_hold(data, eigen_moments(data))


@claim("inertia: the shape's axis of each principal axis",
       r"\b[xyz], (?:along the|transverse|the symmetry axis|through the apexes)"
       r"|any axis ⊥ [xyz]\b")
def shape_axes(data) -> bool | str:
    """each principal axis, turned back into the shape's frame by the configured Euler
    angles, lies along the shape's axis it is named by; "any axis ⊥ z": its moment equals
    another's and the odd axis is z"""
    shape = data.config.get("shape") or {}
    R = euler_rotation(shape.get("euler_angles"))
    axes = np.asarray(data.analysis["principal_axes"], dtype=float)
    I = np.asarray(data.analysis["principal_moments"], dtype=float)
    for k in range(3):
        words = str(data.analysis["axis_stability"][f"axis_{k + 1}"].get("shape_axis", ""))
        if not words:
            continue
        if words.startswith("any axis ⊥"):
            others = [j for j in range(3) if j != k]
            twin = [j for j in others if abs(I[j] - I[k]) <= EQUAL_RTOL * I.max()]
            if len(twin) != 1:
                return f"axis {k + 1} is called '{words}' with moments {I}"
            odd = ({0, 1, 2} - {k, twin[0]}).pop()
            own = R.T @ axes[:, odd]
            if "xyz"[int(np.argmax(np.abs(own)))] != words[-1]:
                return f"the odd axis lies along {own} in the shape's frame"
        elif words.startswith("any axis"):
            if top_words(I) != "spherical":
                return f"axis {k + 1} is called '{words}' with moments {I}"
        else:
            own = R.T @ axes[:, k]
            if abs(float(own["xyz".index(words[0])])) < 1 - 1e-9:
                return f"axis {k + 1} is {own} in the shape's frame, not along {words[0]}"
    return True


@claim("inertia: the body is the configured solid",
       r"\bsolid (?:cone|box|cylinder|ellipsoid|octahedron)\b|\bbox, M =")
def configured_solid(data) -> bool | str:
    """the archived principal moments are the closed form of the configured solid with its
    dimensions (recomputed here), in some order"""
    shape = data.config.get("shape") or {}
    closed = closed_moments(shape)
    if closed is None:
        return "the body is a point set"
    found = np.sort(np.asarray(data.analysis["principal_moments"], dtype=float))
    return bool(np.allclose(np.sort(closed), found, rtol=1e-9, atol=0.0)) or (
        f"moments {found}, the closed form of a {shape.get('type')} gives {np.sort(closed)}")


@claim("inertia: the cone's centre of mass 3h/4 below the apex", r"3h/4 below the apex")
def cone_centre(data) -> bool | str:
    """the quadrature's centre of mass lies 3h/4 below the apex (h from the config)"""
    shape = data.config.get("shape") or {}
    q = data.analysis.get("quadrature") or {}
    if shape.get("type") != "cone" or "apex_distance" not in q:
        return "not a cone with its quadrature"
    h = float(shape["height"])
    d = float(q["apex_distance"])
    return abs(d - 0.75 * h) <= 1e-9 * h or f"the quadrature puts it {d:.9g} below, h = {h}"


@claim("inertia: quadrature agrees with the closed forms",
       r"agree with the closed forms to\s+round-off")
def quadrature(data) -> bool | str:
    """the quadrature's moments about the shape's axes equal the closed forms recomputed
    here from the config, to 1e-10 of the largest"""
    shape = data.config.get("shape") or {}
    closed = closed_moments(shape)
    q = data.analysis.get("quadrature") or {}
    if closed is None or "moments" not in q:
        return "no quadrature of a solid"
    diff = float(np.max(np.abs(np.asarray(q["moments"], dtype=float) - closed)))
    return diff <= 1e-10 * float(closed.max()) or f"they differ by {diff:.3g} kg m²"


@claim("inertia: the parallel-axis shift", r"by notes \(8\.49\)")
def parallel_axis(data) -> bool | str:
    """the tensor about the shifted point is I_cm + M(d² 1 − d dᵀ), d from the archived
    centre of mass to the point, recomputed"""
    p = data.analysis.get("parallel_axis")
    if p is None:
        return "no shifted point"
    a = data.analysis
    d = np.asarray(p["about"], dtype=float) - np.asarray(a["centre_of_mass"], dtype=float)
    expect = (np.asarray(a["tensor"], dtype=float)
              + float(a["mass"]) * (float(d @ d) * np.eye(3) - np.outer(d, d)))
    found = np.asarray(p["tensor"], dtype=float)
    err = float(np.max(np.abs(found - expect)))
    return err <= 1e-12 * float(np.max(np.abs(expect))) or f"it differs by {err:.3g} kg m²"
