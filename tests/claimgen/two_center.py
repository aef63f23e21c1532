"""Two fixed centres across the orbit classes of notes (7.59): one side (β > 0, either
centre), a ring round both centres (β ≤ 0, q(1) < 0), through the segment between them
(β ≤ 0, q(1) ≥ 0) and escaping (E ≥ 0), at several μ and a, vy given or solved from E.

Constructed in units μ = a = 1 (the classes are scale-free), then scaled: from the x-axis
beyond a centre, (x, 0) with ẏ = v, β = −x²v² + 4x/(x² − 1), so v² < 4/(x(x² − 1)) is one
side and v² > 4x/(x² − 1) escapes; from the y-axis, (0, y) with ẋ = v, β = −v²(1 + y²) ≤ 0
and q(1) = 4 − 4/s − v²y² (s = √(1 + y²)): q(1) < 0 is the ring, E < 0 is v² < 4/s.
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

EXAMPLES = 8

CLASSES = ("one_centre", "both_centres", "through_middle", "escape_axis", "escape_side")


@st.composite
def configs(draw):
    mu = draw(st.floats(0.5, 3.0))
    a = draw(st.floats(0.5, 2.0))
    case = draw(st.sampled_from(CLASSES))
    f = draw(st.floats(0.05, 0.95))
    sign = draw(st.sampled_from((1.0, -1.0)))
    if case in ("one_centre", "escape_side"):
        x = draw(st.floats(1.15, 2.5))
        top = 4.0 / (x * (x * x - 1.0)) if case == "one_centre" else None
        v2 = f * top if top is not None else 4.0 * x / (x * x - 1.0) * (1.0 + f)
        state = (sign * x, 0.0, 0.0, math.sqrt(v2))
    else:
        y = draw(st.floats(0.3, 2.0))
        s = math.sqrt(1.0 + y * y)
        lo, hi = 4.0 * (1.0 - 1.0 / s) / (y * y), 4.0 / s
        v2 = {"both_centres": lo + (0.05 + 0.9 * f) * (hi - lo), "through_middle": f * lo,
              "escape_axis": hi * (1.0 + f)}[case]
        state = (0.0, sign * y, math.sqrt(v2), 0.0)
    speed, time = math.sqrt(mu / a), math.sqrt(a ** 3 / mu)
    x, y, vx, vy = state[0] * a, state[1] * a, state[2] * speed, state[3] * speed
    initial = {"x": x, "y": y, "vx": vx, "vy": vy}
    if vy > 0.0 and draw(st.booleans()):  # vy solved from the energy
        initial.pop("vy")
        initial["energy"] = 0.5 * (vx * vx + vy * vy) - mu / math.hypot(x + a, y) \
            - mu / math.hypot(x - a, y)
    run = {"t_end": draw(st.floats(15.0, 40.0)) * time, "samples": 1501, "study": False}
    if draw(st.integers(0, 4)) == 0:
        run["formulation"] = "regularized"
    return {"kind": "two_center", "params": {"mu": mu, "a": a}, "initial": initial,
            "run": run}
