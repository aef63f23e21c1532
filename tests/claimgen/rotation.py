"""Rotations across the kind's inputs: axis and angle (general axes, an axis in the x–z
plane, the y axis; small turns, half turns), Euler angles in both conventions (rates at
rest, slow and fast against the path's step: the order check made or not), SU(2) elements
by Cayley–Klein parameters or by axis and angle (α past 2π: −U), alone (U₂ = U) or with
the other tables; angles in radians or in degrees.
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

EXAMPLES = 7


def _axis(draw):
    kind = draw(st.sampled_from(("general", "xz_plane", "y_axis", "z_axis")))
    if kind == "general":
        v = [draw(st.floats(-1.0, 1.0)) for _ in range(3)]
        return v if math.hypot(*v) > 0.1 else [1.0, 2.0, 2.0]
    if kind == "xz_plane":
        return [draw(st.floats(0.2, 1.0)), 0.0, draw(st.floats(-1.0, 1.0))]
    return [0.0, 1.0, 0.0] if kind == "y_axis" else [0.0, 0.0, 1.0]


def _angle(draw, top=math.pi):
    kind = draw(st.sampled_from(("any", "half_turn", "small")))
    value = {"any": draw(st.floats(0.05, top)), "half_turn": math.pi,
             "small": draw(st.floats(1e-4, 1e-2))}[kind]
    if draw(st.booleans()) and kind != "half_turn":
        return f"{math.degrees(value):.6g} deg"
    return value


@st.composite
def configs(draw):
    tables = draw(st.sampled_from((("axis_angle",), ("euler",), ("su2",),
                                   ("axis_angle", "euler"), ("axis_angle", "su2"),
                                   ("euler", "su2"), ("axis_angle", "euler", "su2"))))
    config = {"kind": "rotation"}
    if "axis_angle" in tables:
        config["axis_angle"] = {"axis": _axis(draw), "angle": _angle(draw),
                                "vector": [draw(st.floats(-1.0, 1.0)), 1.0,
                                           draw(st.floats(-1.0, 1.0))]}
    if "euler" in tables:
        speed = draw(st.sampled_from((0.0, 0.5, 4.0)))
        config["euler"] = {
            "convention": draw(st.sampled_from(("zxz", "zyz"))),
            "angles": [draw(st.floats(-3.0, 3.0)), draw(st.floats(0.0, 3.0)),
                       draw(st.floats(-3.0, 3.0))],
            "rates": [speed * draw(st.floats(-1.0, 1.0)) for _ in range(3)],
            "duration": draw(st.floats(1.0, 5.0)),
            "samples": draw(st.sampled_from((21, 81))),
        }
    if "su2" in tables:
        if draw(st.booleans()):
            config["su2"] = {"axis": _axis(draw), "angle": _angle(draw, top=4 * math.pi),
                             "points": 120}
        else:
            t = draw(st.floats(0.0, 2 * math.pi))
            u = draw(st.floats(0.0, 2 * math.pi))
            c = draw(st.floats(0.0, 1.0))
            s = math.sqrt(1.0 - c * c)
            config["su2"] = {"a": [c * math.cos(t), c * math.sin(t)],
                             "b": [s * math.cos(u), s * math.sin(u)], "points": 120}
    return config
