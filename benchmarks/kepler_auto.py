"""What ``method = "auto"`` should pick for a Kepler orbit: max |ΔE/E| over the outputs and
wall time of Cartesian DOP853, Levi-Civita + DOP853 and Levi-Civita + Gauss–Legendre 6
(``levi_civita``) at the scene's tolerances (atol = rtol/100), 10 outputs per orbit.

``python benchmarks/kepler_auto.py [e,e,...] [orbits,...] [rtol,...]``; earlier numbers behind
the Kepler choice in reportgen/core/integrators/policy.py.  Not a test: wall times
depend on the machine (best of 3 after a warm-up, compile excluded).

``python benchmarks/kepler_auto.py policy``: the grid behind ``auto``'s choice for a bound
Kepler orbit (e = 0.1 … 0.95, 1 … 1000 orbits, rtol 1e-8 … 1e-13, 100 outputs per orbit):
Cartesian DOP853 and ``levi_civita`` at the asked rtol, and whether each meets it on the
energy.

Without arguments: issue 34's case instead, Kepler e = 0.9 over 1000 orbits at 10,001
outputs, ``levi_civita`` at 16, 24 and 48 steps per orbit and at rtol 1e-13 (what auto
takes) against heyoka (Taylor, LLVM JIT) at tol 1e-15 and 1e-13 when it is installed, in
the same run: best and median of 5 after a warm-up (compile and JIT excluded), max |ΔE/E|
over the outputs, |Δr| at the end against Kepler's equation, and per heyoka row our
fastest row at or below its max |ΔE/E| with the ratio of the times (< 1: ours faster).
"""

from __future__ import annotations

import math
import statistics
import sys
import time

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


def against_heyoka(e=0.9, orbits=1000, outputs=10_001, repeats=5):
    """Issue 34's comparison (module docstring); the rows printed, also returned."""
    from reportgen.core.integrators.regularized import SAFETY, STEP_CONSTANT

    y0 = np.array([1 - e, 0.0, 0.0, math.sqrt((1 + e) / (1 - e))])
    t = np.linspace(0.0, orbits * 2 * math.pi, outputs)
    e0 = kepler.energy(*y0, 1.0, 1.0)
    end = np.array(kepler.kepler_state(t[-1:], kepler.orbital_elements(*y0, 1.0)))[:2, 0]

    def timed(fn):
        fn()  # compile / JIT / warm-up outside the timing
        times, out = [], None
        for _ in range(repeats):
            start = time.perf_counter()
            out = fn()
            times.append(time.perf_counter() - start)
        return min(times), statistics.median(times), out

    def row(label, ours, fn):
        best, median, y = timed(fn)
        de = np.abs(kepler.energy(*y.T, 1.0, 1.0) / e0 - 1)
        return {"label": label, "ours": ours, "best": best, "median": median,
                "error": float(de.max()), "position_end": float(np.hypot(*(y[-1, :2] - end)))}

    speed = math.sqrt((1 + e) / (1 - e))
    rows = []
    # rtol for N grid steps per orbit (regularized.grid_steps_per_orbit inverted)
    for n, rtol in [(n, STEP_CONSTANT * speed / (SAFETY * (n - 0.5) ** 6)) for n in (16, 24, 48)
                    ] + [(None, 1e-13)]:
        label = (f"levi_civita {n}/orbit" if n else f"levi_civita rtol {rtol:.0e} (auto)")
        rows.append(row(label, True, lambda rtol=rtol: integrate(
            MODEL, y0, t, method="levi_civita", rtol=rtol, atol=rtol * 1e-2).y))
    try:
        import heyoka as hy
    except ImportError:
        hy = None
        print("heyoka not installed: no same-run comparison")
    if hy is not None:
        x, y, vx, vy = hy.make_vars("x", "y", "vx", "vy")
        r3 = (x**2 + y**2) ** -1.5
        system = [(x, vx), (y, vy), (vx, -x * r3), (vy, -y * r3)]
        for tol in (1e-15, 1e-13):
            ta = hy.taylor_adaptive(system, list(y0), tol=tol)

            def run(ta=ta):
                ta.time = 0.0
                ta.state[:] = y0
                return ta.propagate_grid(t)[-1]

            rows.append(row(f"heyoka tol {tol:.0e}", False, run))
    print(f"Kepler e = {e}, {orbits} orbits, {outputs} outputs; best (median) of {repeats}")
    for r in rows:
        print(f"  {r['label']:<30} max |ΔE/E| {r['error']:.1e}  |Δr| end "
              f"{r['position_end']:.1e}  {r['best'] * 1e3:7.2f} ms ({r['median'] * 1e3:.2f})")
    for peer in (r for r in rows if not r["ours"]):
        for measure, keys in (("|ΔE/E|", ("error",)),
                              ("|ΔE/E| and |Δr|", ("error", "position_end"))):
            match = [r for r in rows if r["ours"] and all(r[k] <= peer[k] for k in keys)]
            if not match:
                print(f"  vs {peer['label']} on {measure}: none of ours reaches it")
                continue
            ours = min(match, key=lambda r: r["best"])
            print(f"  vs {peer['label']} on {measure}: {ours['label']}, ours/heyoka "
                  f"{ours['best'] / peer['best']:.2f} best, "
                  f"{ours['median'] / peer['median']:.2f} median")
    return rows


def policy_grid(es=(0.1, 0.3, 0.5, 0.7, 0.9, 0.95), orbits=(1, 10, 100, 1000),
                rtols=(1e-8, 1e-10, 1e-12, 1e-13), outputs_per_orbit=100):
    """The measurement behind ``auto``'s Kepler choice (``KEPLER_ENERGY_MEASURED`` in
    policy.py): Cartesian DOP853 and ``levi_civita`` at the asked rtol, max |ΔE/E| over the
    outputs and whether it meets the rtol; returns the rows."""
    rows = []
    for e in es:
        for n in orbits:
            for rtol in rtols:
                line = f"e = {e:<4} {n:5d} orbits rtol {rtol:.0e}:"
                for method in ("dop853", "levi_civita"):
                    wall, worst, _end = run(e, n, rtol, method, outputs_per_orbit, repeats=5)
                    rows.append({"e": e, "orbits": n, "rtol": rtol, "method": method,
                                 "error": worst, "wall_time_s": wall})
                    line += (f"  {method:<11} |ΔE/E| {worst:.1e} "
                             f"({'meets' if worst <= rtol else f'{worst / rtol:.0f}x'}) "
                             f"{wall * 1e3:8.3f} ms")
                print(line, flush=True)
    missed = [r for r in rows if r["method"] == "dop853" and r["error"] > r["rtol"]]
    met = [r for r in rows if r["method"] == "levi_civita" and r["error"] <= r["rtol"]]
    print(f"DOP853 missed the rtol on the energy in {len(missed)} of {len(rows) // 2} cases "
          f"(by {min(r['error'] / r['rtol'] for r in missed):.0f}x to "
          f"{max(r['error'] / r['rtol'] for r in missed):.0f}x); levi_civita met it in "
          f"{len(met)}" if missed else "DOP853 met every rtol")
    return rows


def main(argv):
    if not argv:
        against_heyoka()
        return
    if argv[0] == "policy":
        policy_grid()
        return
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
