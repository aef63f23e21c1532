"""Pendulum period against amplitude: one compiled ensemble call against a scipy loop.

Run ``python benchmarks/sweep_pendulum.py [repeats]`` (default 3; the scipy loop takes
~10 s per repeat).

2000 members released from rest at theta0 in [0.01, 3.1] (g = 9.81, l = 1); each
period is the time between the first two upward zero crossings of theta, compared with
T = 4 K(k) sqrt(l / g), k = sin(theta0 / 2) (DLMF 19.2.8, 22.19(i); scipy's ellipk
takes m = k^2).

* ours: ``reportgen.kinds.pendulum.ensemble.pendulum_periods`` (one compiled call per block of
  members, a compiled loop on each of numba's threads), after a warm-up call that compiles it or
  loads it from numba's cache;
* scipy: the loop a user would write, ``solve_ivp(f, ..., method="DOP853", rtol=1e-10,
  atol=1e-12, events=upward)`` per member with a plain Python ``f``, the event
  stopping the run at its second occurrence (``terminal = 2``: the least work scipy can
  do), horizon 2.2 T.

Times are medians of ``repeats`` rounds, each running every variant once (the machine
is shared: interleaving lets a change of load hit all variants alike); the ratio is
scipy's median over ours, quoted for our runs whose max error is no worse than scipy's.
"""

from __future__ import annotations

import math
import sys
import time
from functools import partial

import numba
import numpy as np
from scipy.integrate import solve_ivp
from scipy.special import ellipk

from reportgen.core.ensemble import OK
from reportgen.kinds.pendulum.ensemble import pendulum_periods

G, L = 9.81, 1.0
THETA0 = np.linspace(0.01, 3.1, 2000)
EXACT = 4.0 * ellipk(np.sin(0.5 * THETA0) ** 2) * math.sqrt(L / G)


def scipy_periods(theta0, rtol=1e-10, atol=1e-12, t_end=None):
    """The user's script: a Python loop of solve_ivp with an event on theta.  Each run
    stops at its second crossing within 2.2 T (scipy's least work), or, given ``t_end``,
    runs to ``t_end`` as one run per member of a scene would."""
    def f(t, y):
        return [y[1], -G / L * np.sin(y[0])]

    def upward(t, y):
        return y[0]

    upward.direction = 1
    if t_end is None:
        upward.terminal = 2
    periods = np.full(theta0.size, np.nan)
    for i, th in enumerate(theta0):
        end = (2.2 * 4.0 * ellipk(math.sin(0.5 * th) ** 2) * math.sqrt(L / G)
               if t_end is None else t_end)
        sol = solve_ivp(f, (0.0, end), [th, 0.0], method="DOP853", rtol=rtol, atol=atol,
                        events=upward)
        te = sol.t_events[0]
        if te.size >= 2:
            periods[i] = te[1] - te[0]
    return periods


def ours(rtol, threads):
    """Our ensemble at ``rtol`` on ``threads`` threads (the setting is restored)."""
    before = numba.get_num_threads()
    numba.set_num_threads(threads)
    try:
        periods, status = pendulum_periods(THETA0, G, L, rtol=rtol, atol=1e-12)
    finally:
        numba.set_num_threads(before)
    assert np.all(status == OK)
    return periods


def max_error(periods):
    return float(np.max(np.abs(periods / EXACT - 1.0)))


def main(repeats: int = 3) -> None:
    start = time.perf_counter()
    pendulum_periods(THETA0[:2], G, L)
    warm = time.perf_counter() - start
    threads = numba.get_num_threads()
    runs = {"scipy solve_ivp DOP853 loop, rtol=1e-10": partial(scipy_periods, THETA0)}
    for rtol, n in ((1e-10, threads), (1e-12, threads), (1e-12, 1)):
        runs[f"ours, ensemble rtol={rtol:.0e}, {n} thread(s)"] = partial(ours, rtol, n)
    # interleaved, so that a change of the machine's load hits every variant alike
    times = {label: [] for label in runs}
    errors = {}
    for _ in range(repeats):
        for label, run in runs.items():
            t = time.perf_counter()
            periods = run()
            times[label].append(time.perf_counter() - t)
            errors[label] = max_error(periods)
    (label_sp, t_sp), *rows = ((k, float(np.median(v))) for k, v in times.items())
    err_sp = errors[label_sp]
    print(f"pendulum period sweep: {THETA0.size} amplitudes in [0.01, 3.1], "
          f"error = max |T / (4 K(k) sqrt(l/g)) - 1|, median of {repeats}")
    print(f"  warm-up call (compile or cache load, incl. the model's callback): {warm:.2f} s")
    print(f"  {'run':44s} {'wall time':>11s} {'max error':>10s} {'scipy/ours':>11s}")
    print(f"  {label_sp:44s} {t_sp:9.3f} s {err_sp:10.2e} {'1':>11s}")
    for label, t in rows:
        err = errors[label]
        ratio = f"{t_sp / t:.0f}x" if err <= err_sp else "(worse err)"
        print(f"  {label:44s} {t * 1e3:8.1f} ms {err:10.2e} {ratio:>11s}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
