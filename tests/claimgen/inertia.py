"""Inertia configs across the kind's case space (see tests/claimgen/__init__.py).

Every shape type -- box, cylinder, cone, ellipsoid, octahedron (rhombus and rectangle),
point sets -- with dimensions on both sides of the symmetric cases: all equal (a
spherical top: cube, sphere, regular octahedron, regular tetrahedron of points), two
equal (symmetric), just off equal (asymmetric by 10⁻⁶) and generic; some turned by Euler
angles, some with a parallel-axis shift.
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

EXAMPLES = 8

_SIZE = st.floats(0.2, 2.0)


@st.composite
def _three(draw):
    """Three dimensions: all equal, two equal, two just off equal, or generic."""
    case = draw(st.sampled_from(["equal", "two equal", "just off", "generic"]))
    a = draw(_SIZE)
    if case == "equal":
        return [a, a, a]
    b = draw(_SIZE.filter(lambda x: abs(x - a) > 0.05))
    if case == "two equal":
        dims = [a, a, b]
    elif case == "just off":
        dims = [a, a * (1 + 1e-6), b]
    else:
        dims = [a, b, draw(_SIZE.filter(lambda x: min(abs(x - a), abs(x - b)) > 0.05))]
    return draw(st.permutations(dims))


@st.composite
def solid(draw):
    kind = draw(st.sampled_from(["box", "ellipsoid", "octahedron", "rectangle", "cone",
                                 "cylinder"]))
    mass = draw(st.floats(0.5, 5.0))
    if kind in ("box", "ellipsoid", "octahedron"):
        a, b, c = draw(_three())
        return {"type": kind, "mass": mass, "a": a, "b": b, "c": c}
    if kind == "rectangle":
        a, b, c = draw(_three())
        if draw(st.booleans()):  # the regular octahedron: a = b = s, h = s/√2
            a = b = draw(_SIZE)
            c = a / math.sqrt(2)
        return {"type": "octahedron", "equator": "rectangle", "mass": mass, "a": a, "b": b,
                "h": c}
    radius, height = draw(_SIZE), draw(_SIZE)
    if draw(st.booleans()):  # the spherical cone (h = 2R) or cylinder (h = √3 R)
        height = 2 * radius if kind == "cone" else math.sqrt(3) * radius
    return {"type": kind, "mass": mass, "radius": radius, "height": height}


@st.composite
def points(draw):
    case = draw(st.sampled_from(["tetrahedron", "square", "random"]))
    if case == "tetrahedron":  # equal masses at the corners: a spherical top
        positions = [[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]]
    elif case == "square":  # a symmetric top
        positions = [[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]]
    else:
        n = draw(st.integers(3, 6))
        # two fixed points off any line through the origin: never all on one line (refused)
        positions = [[0.9, 0.1, -0.2], [-0.3, 0.8, 0.4]] + [
            [draw(st.floats(-1.5, 1.5)) for _ in range(3)] for _ in range(n - 2)]
    scale = draw(_SIZE)
    positions = [[scale * float(x) for x in p] for p in positions]
    masses = ([1.0] * len(positions) if case != "random"
              else [draw(st.floats(0.2, 3.0)) for _ in positions])
    return {"type": "points", "masses": masses, "positions": positions}


@st.composite
def configs(draw):
    shape = draw(st.one_of(solid(), solid(), points()))
    if draw(st.booleans()):
        shape["euler_angles"] = [draw(st.floats(-3.0, 3.0)), draw(st.floats(0.0, 3.0)),
                                 draw(st.floats(-3.0, 3.0))]
    if draw(st.booleans()):
        shape["about"] = [draw(st.floats(-1.0, 1.0)) for _ in range(3)]
    return {"kind": "inertia", "shape": shape}
