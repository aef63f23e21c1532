"""``fput`` configs across the kind's case space (see tests/claimgen/__init__.py).

Both sides of every threshold the report's sentences are chosen by: one to four stiff
springs; ω from comparable with the soft springs' frequency to well above it (two time
scales or not); energy put into one stiff spring (concentrated: handed on within the run or
not), spread over several, or none at all (stiff springs at rest, the soft springs moving);
small and large amplitudes (weak and strong nonlinearity); GNI's own data.
"""

from __future__ import annotations

from hypothesis import strategies as st

EXAMPLES = 6


def _num(draw, lo: float, hi: float) -> float:
    return round(draw(st.floats(lo, hi, allow_nan=False, allow_infinity=False)), 4)


@st.composite
def configs(draw):
    m = draw(st.integers(1, 4))
    omega = draw(st.sampled_from([2.0, 6.0, 15.0, 30.0, 50.0, 80.0]))
    start = draw(st.sampled_from(["gni", "one", "spread", "rest"]))
    amplitude = _num(draw, 0.1, 1.5)
    n = 2 * m
    q, p = [0.0] * n, [0.0] * n
    if start == "one":  # one stiff spring stretched and moving: I starts there
        j = draw(st.integers(0, m - 1))
        q[2 * j], q[2 * j + 1] = amplitude, amplitude / omega
        p[2 * j], p[2 * j + 1] = amplitude, -amplitude
    elif start == "spread":  # every stiff spring stretched alike
        for j in range(m):
            q[2 * j] = round(amplitude * (1 - 0.2 * j), 4)
            q[2 * j + 1] = -q[2 * j]
    elif start == "rest":  # stiff springs unstretched and not moving: only the soft ones
        for j in range(m):
            q[2 * j] = q[2 * j + 1] = round(amplitude * (-1) ** j, 4)
            p[2 * j] = p[2 * j + 1] = round(0.5 * amplitude, 4)
    config = {"kind": "fput", "params": {"m": m, "omega": omega},
              "run": {"t_end": float(draw(st.sampled_from([20.0, 60.0]))), "samples": 1201,
                      "study": False}}
    if start != "gni":
        config["initial"] = {"q": q, "p": p}
    return config
