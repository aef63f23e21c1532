"""What ``method = "auto"`` should pick for a Kepler orbit: max |ΔE/E| over the outputs and
wall time of Cartesian DOP853, Levi-Civita + DOP853 and Levi-Civita + Gauss–Legendre 6
(``levi_civita``) at the scene's tolerances (atol = rtol/100), 10 outputs per orbit.

``python benchmarks/kepler_auto.py [e,e,...] [orbits,...] [rtol,...]``; the numbers behind
``KEPLER_MANY_ORBITS`` in reportgen/core/integrators/policy.py.  Not a test: wall times
depend on the machine (best of 3 after a warm-up, compile excluded).
"""

from __future__ import annotations

import math
import sys

import numpy as np

from reportgen.core.integrators import integrate
from reportgen.core.models import kepler
from reportgen.support.timing import best_time

MODEL = kepler.model(1.0, 1.0)  # GM = 1, a = 1: period 2π


def run(e, orbits, rtol, method, outputs_per_orbit=10, repeats=3):
    """(best wall time, max |ΔE/E| over the outputs, |ΔE/E| at the end)."""
    y0 = np.array([1 - e, 0.0, 0.0, math.sqrt((1 + e) / (1 - e))])
    t = np.linspace(0.0, orbits * 2 * math.pi, orbits * outputs_per_orbit + 1)
    integrate(MODEL, y0, t[:3], method=method, rtol=rtol, atol=rtol * 1e-2)
    wall, sol = best_time(lambda: integrate(MODEL, y0, t, method=method, rtol=rtol,
                                            atol=rtol * 1e-2), repeats)
    de = np.abs(kepler.energy(*sol.y.T, 1.0, 1.0) / kepler.energy(*y0, 1.0, 1.0) - 1)
    return wall, float(de.max()), float(de[-1])


def main(argv):
    es = [float(v) for v in (argv[0] if argv else "0,0.5,0.7,0.9").split(",")]
    orbits = [int(v) for v in (argv[1] if len(argv) > 1 else "10,100,1000").split(",")]
    rtols = [float(v) for v in (argv[2] if len(argv) > 2 else "1e-10,1e-12,1e-13").split(",")]
    for e in es:
        for n in orbits:
            for rtol in rtols:
                for method in ("dop853", "levi_civita_dop853", "levi_civita"):
                    wall, worst, end = run(e, n, rtol, method)
                    print(f"e = {e:<4} {n:5d} orbits rtol {rtol:.0e} {method:<19} "
                          f"max |ΔE/E| {worst:.1e} end {end:.1e} {wall * 1e3:8.2f} ms",
                          flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
