"""Three bodies across the kind's cases: compact triples (equal and unequal masses, in motion
or released at rest), hierarchical triples (a tight pair among any two of the bodies, at
several mass ratios), a binary with an escaping third body, the figure-eight rescaled and
perturbed (periodic or not), Burrau's configuration rescaled; and the restricted problem at
several mass ratios μ with Jacobi constants on either side of the values at L1, L2, L3 and
L4, the particle starting next to a primary or outside, regularized or Cartesian.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

EXAMPLES = 9

#: the figure-eight's data (Chenciner & Montgomery 2000, Simó's initial conditions)
_X1, _Y1 = 0.97000436, -0.24308753
_V3 = (-0.93240737, -0.86473146)
_PERIOD = 6.32591398

CASES = ("compact", "at_rest", "hierarchical", "escape", "figure_eight", "burrau",
         "restricted")


def _without_drift(masses, velocities):
    m = np.asarray(masses)[:, None]
    v = np.asarray(velocities, dtype=float)
    return (v - (m * v).sum(axis=0) / m.sum()).tolist()


def _circle(draw, radius):
    """Three points on a circle, at least 60° apart, no two arcs between them alike (an
    isosceles triangle released at rest falls into a triple collision)."""
    base = draw(st.floats(0.0, 2 * math.pi))
    g1 = draw(st.floats(math.pi / 3, 0.9 * math.pi))
    g2 = draw(st.floats(math.pi / 3, 0.9 * math.pi))
    g3 = 2 * math.pi - g1 - g2
    if min(abs(g1 - g2), abs(g2 - g3), abs(g1 - g3)) < 0.25 or g3 < math.pi / 3:
        g1, g2 = 0.45 * math.pi, 0.7 * math.pi  # arcs 81°, 126°, 153°
    angles = [base, base + g1, base + g1 + g2]
    return [[radius * math.cos(a), radius * math.sin(a), 0.0] for a in angles]


@st.composite
def _full(draw, case):
    run = {"t_end": 6.0, "samples": 1001, "study": False}
    if case in ("compact", "at_rest"):
        equal = case == "compact" and draw(st.booleans())
        masses = [1.0] * 3 if equal else [draw(st.floats(0.3, 2.0)) for _ in range(3)]
        pos = _circle(draw, draw(st.floats(0.7, 1.5)))
        if case == "at_rest":
            vel = [[0.0] * 3 for _ in range(3)]
        else:
            raw = [[draw(st.floats(-0.6, 0.6)), draw(st.floats(-0.6, 0.6)),
                    draw(st.floats(-0.05, 0.05))] for _ in range(3)]
            vel = _without_drift(masses, raw)
        run.update(rtol=1e-12, atol=1e-14, t_end=draw(st.floats(2.0, 6.0)))
    elif case in ("hierarchical", "escape"):
        inner = draw(st.sampled_from(((0, 1), (1, 2), (0, 2))))
        outer = 3 - sum(inner)
        masses = [0.0] * 3
        masses[inner[0]], masses[inner[1]] = draw(st.floats(0.2, 1.0)), draw(st.floats(0.01, 1.0))
        masses[outer] = draw(st.floats(0.01, 2.0))
        m_in = masses[inner[0]] + masses[inner[1]]
        v_in = math.sqrt(m_in)  # separation 1, circular
        pos, vel = [[0.0] * 3 for _ in range(3)], [[0.0] * 3 for _ in range(3)]
        pos[inner[0]] = [-masses[inner[1]] / m_in, 0.0, 0.0]
        pos[inner[1]] = [masses[inner[0]] / m_in, 0.0, 0.0]
        vel[inner[0]] = [0.0, -v_in * masses[inner[1]] / m_in, 0.0]
        vel[inner[1]] = [0.0, v_in * masses[inner[0]] / m_in, 0.0]
        total = m_in + masses[outer]
        if case == "hierarchical":
            D = draw(st.floats(8.0, 20.0))
            pos[outer] = [0.0, D, 0.0]
            vel[outer] = [-draw(st.floats(0.8, 1.1)) * math.sqrt(total / D), 0.0, 0.0]
            run["t_end"] = draw(st.floats(6.0, 15.0))
        else:
            D = draw(st.floats(4.0, 6.0))
            pos[outer] = [0.0, D, 0.0]
            vel[outer] = [0.1, draw(st.floats(1.4, 2.5)) * math.sqrt(2 * total / D), 0.0]
            run["t_end"] = draw(st.floats(8.0, 15.0))
        vel = _without_drift(masses, vel)
    elif case == "figure_eight":
        L, m = draw(st.floats(0.5, 2.0)), draw(st.floats(0.5, 2.0))
        v = math.sqrt(m / L)
        pos = [[_X1 * L, _Y1 * L, 0.0], [-_X1 * L, -_Y1 * L, 0.0], [0.0, 0.0, 0.0]]
        vel = [[-_V3[0] / 2 * v, -_V3[1] / 2 * v, 0.0]] * 2 + [[_V3[0] * v, _V3[1] * v, 0.0]]
        masses = [m] * 3
        if draw(st.booleans()):  # perturbed: no longer periodic
            masses[2] = m * draw(st.floats(1.02, 1.2))
        period = _PERIOD * L ** 1.5 / math.sqrt(m)
        run.update(t_end=period * draw(st.sampled_from((1.0, 1.3))), samples=1501,
                   rtol=1e-12, atol=1e-14)
        return {"kind": "three_body", "params": {"G": 1.0, "masses": masses},
                "initial": {"positions": pos, "velocities": vel}, "period": period,
                "run": run}
    else:  # Burrau's configuration, rescaled
        L, M = draw(st.floats(0.5, 2.0)), draw(st.floats(0.5, 2.0))
        masses = [3.0 * M, 4.0 * M, 5.0 * M]
        pos = [[1.0 * L, 3.0 * L, 0.0], [-2.0 * L, -1.0 * L, 0.0], [1.0 * L, -1.0 * L, 0.0]]
        vel = [[0.0] * 3 for _ in range(3)]
        run.update(t_end=draw(st.floats(5.0, 20.0)) * math.sqrt(L ** 3 / M), samples=2001,
                   rtol=1e-12, atol=1e-14)
    return {"kind": "three_body", "params": {"G": 1.0, "masses": masses},
            "initial": {"positions": pos, "velocities": vel}, "run": run}


@st.composite
def _restricted(draw):
    from reportgen.core.models.restricted_three_body import lagrange_points

    mu = draw(st.sampled_from((0.001, 0.01215, 0.1, 0.3, 0.5)))
    points = lagrange_points(mu)
    CL = [points[k][2] for k in ("L1", "L2", "L3", "L4")]
    x = draw(st.sampled_from((-mu + 0.3, 1.0 - mu - 0.15, 1.6, -mu - 0.5)))
    two_omega = x * x + 2 * (1 - mu) / abs(x + mu) + 2 * mu / abs(x - 1 + mu)
    level = draw(st.sampled_from(("above_L1", "L1_L2", "L2_L3", "L3_L4", "below_L4")))
    f = draw(st.floats(0.1, 0.9))
    C = {"above_L1": CL[0] + 0.05 + f * 0.3, "L1_L2": CL[1] + f * (CL[0] - CL[1]),
         "L2_L3": CL[2] + f * (CL[1] - CL[2]), "L3_L4": CL[3] + f * (CL[2] - CL[3]),
         "below_L4": CL[3] - 0.05 - f * 0.3}[level]
    C = min(C, two_omega - 1e-3)  # a start the level allows (ẏ² > 0)
    restricted = {"mu": mu, "x": x, "jacobi": C}
    if draw(st.booleans()):  # ẏ given instead of C
        restricted.pop("jacobi")
        restricted["vy"] = math.sqrt(two_omega - C)
    run = {"t_end": draw(st.floats(5.0, 15.0)), "samples": 801, "study": False}
    if draw(st.integers(0, 3)) == 0:
        run["method"] = "rk45"
        run["rtol"], run["atol"] = 1e-10, 1e-12
    return {"kind": "three_body", "restricted": restricted, "run": run}


@st.composite
def configs(draw):
    case = draw(st.sampled_from(CASES))
    if case == "restricted":
        return draw(_restricted())
    return draw(_full(case))
