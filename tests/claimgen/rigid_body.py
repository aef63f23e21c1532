"""Rigid-body configs across the kind's case space (see tests/claimgen/__init__.py).

Bodies given by moments -- asymmetric (generic and just off symmetric), symmetric
(oblate and prolate, I1 = I2 or another pair), spherical -- or by a shape (box, cone,
cylinder, ellipsoid, octahedron, points); spun near each principal axis (within and
beyond the near angle), along the figure axis, across it, or in a generic direction;
with and without an impulse (at the apex of a cone, on and off the figure axis).
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

EXAMPLES = 8

_I = st.floats(0.5, 3.0)


@st.composite
def moments(draw):
    """Principal moments [kg m²] in a random order, each case's triangle inequality kept."""
    case = draw(st.sampled_from(["asymmetric", "asymmetric", "just off", "symmetric",
                                 "spherical"]))
    base = draw(_I)
    if case == "spherical":
        return [base, base, base]
    # the odd moment: oblate (up to 1.9 I⊥, below the 2 I⊥ of the triangle) or prolate
    ratio = draw(st.sampled_from([st.floats(1.1, 1.9), st.floats(0.2, 0.9)]).flatmap(
        lambda s: s))
    if case == "symmetric":
        dims = [base, base, base * ratio]
    elif case == "just off":
        dims = [base, base * (1 + 1e-6), base * ratio]
    else:
        lo, hi = sorted([1.0, ratio])
        dims = [base * lo, base * draw(st.floats(lo + 0.05, max(hi, lo + 0.1) + 0.4)),
                base * hi]
        dims.sort()
        dims[2] = min(dims[2], 0.99 * (dims[0] + dims[1]))
        if min(dims[1] - dims[0], dims[2] - dims[1]) < 0.02 * base:
            dims = [base, 2 * base, 2.9 * base]
    return draw(st.permutations(dims))


@st.composite
def spin(draw, n_axes: int = 3):
    """ω near an axis (within the near angle, or a little beyond it) or generic [rad/s]."""
    size = draw(st.floats(1.0, 5.0))
    case = draw(st.sampled_from(["near", "near", "beyond", "generic", "exact"]))
    k = draw(st.integers(0, n_axes - 1))
    if case == "generic":
        w = [draw(st.floats(-1.0, 1.0)) for _ in range(3)]
        if max(abs(x) for x in w) < 0.1:
            w[k] = 1.0
        return [size * x for x in w]
    tilt = {"near": draw(st.floats(0.005, 0.15)), "beyond": draw(st.floats(0.3, 0.6)),
            "exact": 0.0}[case]
    phase = draw(st.floats(0.0, 2 * math.pi))
    w = [0.0, 0.0, 0.0]
    w[k] = size * math.cos(tilt) * draw(st.sampled_from([1.0, -1.0]))
    w[(k + 1) % 3] = size * math.sin(tilt) * math.cos(phase)
    w[(k + 2) % 3] = size * math.sin(tilt) * math.sin(phase)
    return w


@st.composite
def shape(draw):
    kind = draw(st.sampled_from(["box", "cone", "cylinder", "ellipsoid", "octahedron",
                                 "points"]))
    mass = draw(st.floats(0.5, 3.0))
    size = st.floats(0.2, 1.5)
    if kind in ("box", "ellipsoid", "octahedron"):
        a = draw(size)
        b = a if draw(st.booleans()) else draw(size)
        return {"type": kind, "mass": mass, "a": a, "b": b, "c": draw(size)}
    if kind in ("cone", "cylinder"):
        return {"type": kind, "mass": mass, "radius": draw(size), "height": draw(size)}
    n = draw(st.integers(3, 5))
    return {"type": "points", "masses": [draw(st.floats(0.5, 2.0)) for _ in range(n)],
            "positions": [[0.9, 0.1, -0.2], [-0.3, 0.8, 0.4]] + [  # never on one line
                [draw(st.floats(-1.0, 1.0)) for _ in range(3)] for _ in range(n - 2)]}


@st.composite
def configs(draw):
    config = {"kind": "rigid_body"}
    if draw(st.booleans()):
        I = draw(moments())
        config["params"] = {"I1": I[0], "I2": I[1], "I3": I[2]}
    else:
        config["shape"] = draw(shape())
    config["initial"] = {"omega": draw(spin())}
    if draw(st.integers(0, 3)) == 0:  # an impulse
        P = [draw(st.floats(-0.3, 0.3)) for _ in range(3)]
        P[0] = P[0] or 0.1
        cone = config.get("shape", {}).get("type") == "cone"
        at = ("apex" if cone and draw(st.booleans()) else
              [0.0, 0.0, draw(st.floats(0.1, 0.5))] if draw(st.booleans()) else
              [draw(st.floats(-0.3, 0.3)) for _ in range(3)])
        config["impulse"] = {"P": P, "at": at}
    config["run"] = {"t_end": draw(st.floats(5.0, 15.0)), "samples": 801, "study": False}
    return config
