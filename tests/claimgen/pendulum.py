"""Pendulum configs across the whole case space of its words (see tests/claimgen/__init__.py).

The report's words follow the sign of 1 − k² = cos²(θ0/2) − (θ̇0/2ω0)² (libration or
rotation), its size against SEPARATRIX_ON = 1e-12 and SEPARATRIX_NEAR = 1e-2 (on, near or far
from the separatrix), T/T0 − 1 against 1 % (the small-angle comparison), whether the exact
solution resolves the motion (|1 − k²| ≥ 1e-8), the bottom a libration swings about, the
sense of a rotation and, with a [boundary], ω0 T against π.  So the draws take each side
of each: small and large amplitudes, starts just below the upright and exactly on it,
rotations slow (just above the separatrix) and fast, either sign of θ0 and θ̇0, starts
beyond ±π (a libration about ±2π), angles in degrees or radians, and boundary-value
problems before and after the first conjugate point.  Runs span 1.5–5 periods of small
oscillation with 40 samples per period: each simulates in well under a second (a boundary
problem adds about one).
"""

from __future__ import annotations

import math

from hypothesis import assume
from hypothesis import strategies as st

EXAMPLES = 10

#: ω0 T and the end angles [rad] of the boundary-value problems drawn
BOUNDARY_OMEGA_T = (0.8, 1.7, 2.5, 4.0, 4.8, 5.5, 7.3, 8.2)
BOUNDARY_ENDS = (-0.25, -0.15, -0.08, 0.08, 0.15, 0.25)

#: the regions of the case space
REGIONS = ("small", "large", "near_below", "on", "near_above", "rotation", "beyond_pi")


def _angle(draw, theta: float):
    """θ in radians, or (sometimes) as a lecturer writes it, in degrees."""
    if draw(st.booleans()):
        return theta
    return f"{math.degrees(theta):.12g} deg"


@st.composite
def configs(draw):
    g = draw(st.sampled_from([9.81, 1.0, 1.62, 24.8]))
    l = draw(st.floats(0.2, 3.0))
    w0 = math.sqrt(g / l)
    sign = draw(st.sampled_from([1.0, -1.0]))
    region = draw(st.sampled_from(REGIONS))
    theta_dot = 0.0
    if region == "small":  # T/T0 − 1 ≈ θ0²/16 < 1 % up to θ0 ≈ 0.4
        theta = sign * draw(st.floats(0.01, 0.35))
        theta_dot = draw(st.sampled_from([0.0, 0.0, 0.05 * w0]))
    elif region == "large":
        theta = sign * draw(st.floats(0.5, 2.9))
    elif region == "near_below":  # 1 − k² = sin²(δ/2) from 1e-11 to 2.5e-3
        theta = sign * (math.pi - 10.0 ** draw(st.floats(-5.0, -1.0)))
    elif region == "on":  # released at the upright: 1 − k² = cos²(π/2) ~ 4e-33
        theta = sign * math.pi
    elif region == "near_above":  # k² − 1 from 1e-10 to 1e-2, from the bottom
        theta = 0.0
        theta_dot = sign * 2.0 * w0 * math.sqrt(1.0 + 10.0 ** draw(st.floats(-10.0, -2.0)))
    elif region == "rotation":
        theta = draw(st.floats(-math.pi, math.pi))
        theta_dot = sign * w0 * draw(st.floats(2.3, 6.0))
    else:  # beyond ±π: a libration about ±2π
        theta = sign * draw(st.floats(3.6, 6.0))
        theta_dot = draw(st.sampled_from([0.0, 0.3 * w0]))
    m1 = math.cos(0.5 * theta) ** 2 - (theta_dot / (2.0 * w0)) ** 2
    assume(m1 != 0.0)  # exactly on the separatrix the config is refused (infinite period)
    periods = draw(st.floats(1.5, 5.0))
    t_end = round(periods * 2.0 * math.pi / w0, 6)
    config = {"kind": "pendulum",
              "params": {"g": g, "l": l, "m": draw(st.sampled_from([1.0, 0.25, 3.0]))},
              "initial": {"theta": _angle(draw, theta), "theta_dot": theta_dot},
              "run": {"t_end": t_end, "samples": int(40 * periods) + 1, "study": False}}
    if draw(st.integers(0, 5)) == 0:
        # ω0 T before the first conjugate point π, between π and 2π, past 2π; ends of either
        # sign, none zero (S = 0 has no relative error to show).  A grid: every one of its
        # problems converges in ~0.3 s, where some drawn at random (ω0 T = 3.73 with ends
        # 0.1, 0.3) leave the nonlinear collocation unconverged after ~20 s
        x = draw(st.sampled_from(BOUNDARY_OMEGA_T))
        ends = st.sampled_from(BOUNDARY_ENDS)
        config["boundary"] = {"theta0": draw(ends), "theta1": draw(ends), "T": x / w0}
    return config
