"""Pendulum benchmark: speed at matched error against scipy DOP853, and long-time energy.

Run ``python benchmarks/bench_pendulum.py``; ``reportgen bench`` calls
:func:`run_pendulum_bench`.

1. theta0 = 1 rad, 10 periods, 1001 outputs; error = max over the run of
   |y - y_exact| (exact: Jacobi elliptic functions, DLMF 22.19.2).  Baseline: scipy
   DOP853 at rtol = 1e-10 (atol = 1e-12); ours: the fastest run of any of our methods
   (work-precision sweep, min of 3 timings) whose error is <= the baseline's.
2. 1e6 periods with Yoshida 4 at 100 steps per period (|dE/E| ~ 1.5e-6); relative energy error at 2000
   outputs spaced 500.123 periods apart (so samples see all phases of the bounded
   energy oscillation); plot to ``benchmarks/out/longtime_energy.png``.
"""

from __future__ import annotations

import builtins
from pathlib import Path

import numpy as np

from reportgen.commands.bench import long_time_energy
from reportgen.core.integrators import integrate
from reportgen.core.models import pendulum
from reportgen.core.study import matched_error_speedup, work_precision

G, L, THETA0 = 9.81, 1.0, 1.0
OUT_DIR = Path(__file__).resolve().parent / "out"
OURS = ["dop853", "rk45", "yoshida6", "yoshida8", "gauss6"]


def _exact(t):
    return np.column_stack(pendulum.exact_solution(t, THETA0, 0.0, G, L))


def matched_error(print=builtins.print) -> dict:
    model = pendulum.model(G, L)
    T = pendulum.exact_period(THETA0, 0.0, G, L)
    t_eval = np.linspace(0.0, 10 * T, 1001)
    y0 = np.array([THETA0, 0.0])
    # compile / cache-load time of our default method, measured on its own
    first = integrate(model, y0, t_eval[:3], method="dop853")
    res = work_precision(model, y0, t_eval, reference=_exact, methods=OURS + ["scipy_dop853"],
                         tolerances=[1e-8, 1e-9, 1e-10, 5e-11, 2e-11, 1e-11, 1e-12],
                         steps=T * np.array([1 / 50, 1 / 100, 1 / 150, 1 / 200, 1 / 300]),
                         repeats=3)
    m = matched_error_speedup(res, baseline="scipy_dop853", baseline_rtol=1e-10)
    b, best = m["baseline"], m["matches"][0]
    print(f"pendulum theta0=1 rad, 10 periods, {t_eval.size} outputs, error = max |y - exact|")
    print(f"  scipy DOP853 rtol=1e-10: error {b['error_max']:.2e}  time {b['wall_time_s']*1e3:.2f} ms")
    knob = (f"rtol={best['tolerance']:.0e}" if np.isfinite(best["tolerance"])
            else f"h={best['h']:.4g}")
    print(f"  ours, fastest at <= that error: {best['label']} {knob}: error "
          f"{best['error_max']:.2e}  time {best['wall_time_s']*1e3:.3f} ms")
    print(f"  speed-up at matched error: {best['speedup']:.0f}x")
    for other in m["matches"][1:]:
        print(f"    {other['label']:44s} {other['wall_time_s']*1e3:8.3f} ms  "
              f"{other['speedup']:6.1f}x")
    print(f"  compile (or cache load) time of dop853 in this process: "
          f"{first.compile_time_s:.2f} s")
    return {"baseline": b, "best": best, "matches": m["matches"],
            "compile_time_s": first.compile_time_s, "rows": res.rows}


def run_pendulum_bench(print=builtins.print) -> dict:
    """Both parts; returns the numbers (and the plot path) as a dict."""
    return {"matched_error": matched_error(print=print),
            "long_time": long_time_energy(out_dir=OUT_DIR, print=print)}


if __name__ == "__main__":
    run_pendulum_bench()
