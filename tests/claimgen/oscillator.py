"""``oscillator`` configs across its case space (see ``tests/claimgen/__init__.py``).

Masses and frequencies over three decades each, starts on either axis of the phase plane
(q₀ = 0 or p₀ = 0) and anywhere else, either sign; runs of one to a dozen periods, and
now and then a loose tolerance over many periods, where the integration's error makes the
Hamilton–Jacobi pair (E, β) drift past its threshold and the words must say so.
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

EXAMPLES = 6


@st.composite
def configs(draw):
    m = 10 ** draw(st.floats(-1.3, 1.3))
    omega = 10 ** draw(st.floats(-1.0, 1.5))
    start = draw(st.sampled_from(["both", "q only", "p only"]))
    q = 0.0 if start == "p only" else draw(st.floats(0.05, 3.0)) * draw(
        st.sampled_from([1.0, -1.0]))
    p = 0.0 if start == "q only" else draw(st.floats(0.05, 3.0)) * draw(
        st.sampled_from([1.0, -1.0]))
    period = 2 * math.pi / omega
    loose = draw(st.sampled_from([False, False, True]))
    if loose:  # drifts past the threshold: a loose tolerance over many periods
        run = {"t_end": draw(st.floats(20.0, 40.0)) * period, "samples": 1201,
               "rtol": 1e-5, "atol": 1e-7, "method": "rk45"}
    else:
        periods = draw(st.floats(1.0, 12.0))
        run = {"t_end": periods * period,
               "samples": int(min(1200, max(200, 60 * periods))) + 1}
    return {"kind": "oscillator", "params": {"m": m, "omega": omega},
            "initial": {"q": q, "p": p}, "run": {**run, "study": False}}
