"""``reportgen bench``: error against run time for each scene, against peer solvers.

For every integrating scene the work-precision study is run (ours and scipy's
solve_ivp methods on the same problem, same error measure) and the speed ratio
at matched error is printed: the fastest of our runs whose max error is ≤ what
scipy DOP853 reaches at rtol = 1e-10, against that DOP853 run.  Compile time is
reported beside it, never mixed in.  Then a long run: the pendulum over 10⁶
periods with a symplectic method, whose energy error must stay bounded.

This is a benchmark, not a test: the numbers depend on the machine.
"""

from __future__ import annotations

import builtins
import math
import time
from pathlib import Path

import numpy as np

from ..scene.config import ConfigError
from ..support.peers import against_peer, compared_range, study_rows
from ..support.timing import best_time
from . import default_paths

BASELINE, BASELINE_RTOL = "scipy_dop853", 1e-10


def bench_tolerances() -> tuple[float, ...]:
    """Our adaptive methods' ladder in ``reportgen bench``: the study's fine ladder, then on
    in quarter decades to 1e-14, where heyoka's tight runs are matched."""
    from ..core.study import FINE_TOLERANCES

    return tuple(sorted({*FINE_TOLERANCES, *(10.0 ** (-k / 4) for k in range(49, 57))},
                        reverse=True))


def scene_bench(scene, print=builtins.print) -> dict | None:
    """Run one scene with its study on and print the matched-error speed ratio."""
    from ..core.study import matched_error_speedup

    if scene.config.run is None:
        print(f"{scene.source.name}: integrates nothing; skipped")
        return None
    if not scene.config.run.study:
        print(f"{scene.source.name}: its config turns the study off ([run] study = false); "
              "skipped")
        return None
    config = scene.config.model_copy(update={"run": scene.config.run.model_copy(
        update={"study": True, "study_budget": math.inf}), "report": scene.config.report.model_copy(
        update={"sections": None})})
    scene = type(scene)(config, scene.source)
    scene.study_tolerances = bench_tolerances()
    scene.study_extra_methods = ("taylor",)
    start = time.perf_counter()
    results = scene.simulate()
    elapsed = time.perf_counter() - start
    if results.study is None:
        print(f"{scene.source.name}: this scene has no error-against-run-time study")
        return None
    rows = study_rows(results.study)
    compile_s = sum(r["compile_time_s"] for r in rows if not math.isnan(r["compile_time_s"]))
    try:
        matched = matched_error_speedup(rows, baseline=BASELINE, baseline_rtol=BASELINE_RTOL)
    except ValueError as exc:
        print(f"{scene.source.name}: no matched-error comparison ({exc})")
        return {"scene": scene.source.name, "rows": rows}
    base = matched["baseline"]
    line = (f"{scene.source.name:<30} scipy DOP853 rtol 1e-10: error {base['error_max']:.1e} "
            f"in {base['wall_time_s'] * 1e3:8.2f} ms")
    if matched["matches"]:
        best = matched["matches"][0]
        line += (f" | ours: {_setting(best)}: {best['error_max']:.1e} in "
                 f"{best['wall_time_s'] * 1e3:7.3f} ms → {best['speedup']:6.0f}×")
    else:
        line += " | none of our runs reached that error"
    print(line + f" | compile {compile_s:.2f} s | study {elapsed:.1f} s "
                 f"({results.study_attrs.get('reference_kind', '')})")
    out = {"scene": scene.source.name, "baseline": base, "matches": matched["matches"],
           "compile_time_s": compile_s, "kind": scene.kind, "rows": rows}
    if any(r["method"] == "heyoka" for r in rows):
        out["range"] = compared_range(results.study_attrs.get("reference_agreement", math.nan))
        out["heyoka"] = against_peer(rows, error_range=out["range"])
        for m in out["heyoka"]:
            ours = m["ours"]
            text = (f"  vs heyoka tol {m['tolerance']:.0e}: {m['error_max']:.1e} in "
                    f"{m['wall_time_s'] * 1e3:8.3f} ms (JIT {m['compile_time_s']:.2f} s)")
            if ours is None:
                print(text + " | none of ours as accurate: BEHIND")
            else:
                print(text + f" | ours {_setting(ours)}: {ours['error_max']:.1e} in "
                             f"{ours['wall_time_s'] * 1e3:8.3f} ms → heyoka/ours "
                             f"{m['ratio']:.2f} ({'ahead' if m['ratio'] >= 1 else 'BEHIND'})")
    if scene.kind == "heavy_top" and scene.config.band is None:
        out["textbook"] = heavy_top_textbook(scene, print=print)
    return out


TARGET_SPEEDUP = 300.0


def _setting(row) -> str:
    """"dop853 rtol 1e-09" or "gauss6 h 0.0123": a study row's method and knob."""
    knob = (f"rtol {row['tolerance']:.0e}" if math.isfinite(row["tolerance"])
            else f"h {row['h']:.3g}")
    return f"{row['method']} {knob}"


def error_over_tolerance(rows, method: str) -> float:
    """The median over a method's measured adaptive rows of (max error over the run) / its
    tolerance: how far past its tolerance a method's global error lands on this scene."""
    ratios = [r["error_max"] / r["tolerance"] for r in rows
              if r["method"] == method and r["status"] in ("ok", "inaccurate")
              and math.isfinite(r["tolerance"]) and r["error_max"] > 0]
    return float(np.median(ratios)) if ratios else math.nan


def behind_reason(rows, worst: dict) -> str:
    """Why we are behind heyoka at its run ``worst`` (one of
    :func:`~reportgen.support.peers.against_peer`'s), from the scene's study ``rows``:
    where our Taylor integrator's errors stop (its floor) against heyoka's error, or, when
    a Taylor run matched it, how their times compare; and how far past its tolerance
    DOP853's global error lands here."""
    def measured(name):
        return [r for r in rows if r["method"] == name and r["status"] in ("ok", "inaccurate")]

    taylor, dop = measured("taylor"), measured("dop853")
    dop_ratio = error_over_tolerance(rows, "dop853")
    tail = (f"; DOP853's global error lands {dop_ratio:.2g}x past its rtol here, so it needs "
            "rtol far below heyoka's tol" if dop and math.isfinite(dop_ratio) else "")
    ours = worst["ours"]
    if ours is not None and ours["method"] == "taylor":
        return (f"our Taylor run ({_setting(ours)}) takes {1 / worst['ratio']:.2f}x heyoka's "
                f"time (tol {worst['tolerance']:.0e}) for this error: at one tolerance the two "
                "take the same steps (both choose order and step as Jorba & Zou), and here "
                "ours needs a tighter one for the same error" + tail)
    if taylor:
        floor = min(r["error_max"] for r in taylor)
        if floor > worst["error_max"]:
            return (f"our Taylor integrator's errors stop at {floor:.1e} here (tighter "
                    "tolerances, to 1e-14 or until a decade gains less than 2x, give none "
                    "smaller: rounding, not the tolerance, sets it), where heyoka's reach "
                    f"{worst['error_max']:.1e}; "
                    + ("none of ours is as accurate" if ours is None
                       else f"ours then needs {_setting(ours)}") + tail)
    return ("no Taylor run of ours in this study" if not taylor else
            f"ours needs {_setting(ours)} there" if ours else "none of ours as accurate") + tail


def heyoka_table(results: list[dict], print=builtins.print) -> list[dict]:
    """One row per integrating scene: across heyoka's runs whose max error lies in
    1e-13..1e-6 (:data:`~reportgen.support.peers.PEER_ERROR_RANGE`; its low end raised to
    what the scene's reference runs resolve, :func:`~reportgen.support.peers.compared_range`),
    the one where we do
    worst, our fastest run at least as accurate, both times, and heyoka's time over ours
    (≥ 1: we are at least as fast); with how many of heyoka's errors we are ahead at.
    A row below 1 carries its reason."""
    rows = []
    compared = [r for r in results if r.get("heyoka") is not None]
    if not compared:
        return rows
    print("\nAgainst heyoka at matched error (max error over the run, same reference, same "
          "outputs; best of repeats, compile/JIT excluded). ratio = heyoka's time / ours "
          "(≥ 1: ours at least as fast), at the error where ours does worst")
    print(f"  {'scene':<40} {'heyoka error':>12} {'heyoka ms':>10} {'ours ms':>10} "
          f"{'ratio':>6}  ahead at")
    for r in compared:
        matched = r["heyoka"]
        if not matched:
            lo, hi = r["range"]
            print(f"  {r['scene']:<40} no heyoka run with an error in {lo:.1e}..{hi:.0e}")
            rows.append({"scene": r["scene"], "ratio": math.nan, "reason": "no run in range"})
            continue
        worst = min(matched, key=lambda m: m["ratio"])
        ahead = sum(m["ratio"] >= 1.0 for m in matched)
        ours = worst["ours"]
        ours_ms = f"{ours['wall_time_s'] * 1e3:10.3f}" if ours else f"{'—':>10}"
        line = (f"  {r['scene']:<40} {worst['error_max']:12.1e} "
                f"{worst['wall_time_s'] * 1e3:10.3f} {ours_ms} {worst['ratio']:6.2f}  "
                f"{ahead} of {len(matched)}")
        reason = ""
        if worst["ratio"] < 1.0:
            reason = behind_reason(r.get("rows", []), worst)
            line += f"\n      behind: {reason}"
        print(line)
        rows.append({"scene": r["scene"], "ratio": worst["ratio"], "ahead": ahead,
                     "compared": len(matched), "reason": reason, "worst": worst})
    behind = [x for x in rows if x["ratio"] < 1.0]
    print(f"  {len(rows) - len(behind)} of {len(rows)} scenes at or ahead of heyoka at every "
          "matched error")
    return rows


def summarize(results: list[dict], print=builtins.print) -> None:
    """One line per scene: the speed-up at matched error on our formulation and (heavy top)
    on the textbook one, against the ≥ 300× target, with why a scene is below it: the cost
    of one right-hand-side evaluation in scipy (Python) and in ours (compiled, including the
    step's linear algebra), and how many evaluations each needed for that error."""
    print(f"\nSummary: target ≥ {TARGET_SPEEDUP:.0f}× scipy DOP853 at matched error")
    for r in results:
        if "baseline" not in r:
            print(f"  {r['scene']:<40} no matched-error comparison")
            continue
        base, best = r["baseline"], (r["matches"] or [None])[0]
        if best is None:
            print(f"  {r['scene']:<40} none of our runs reached scipy's error")
            continue
        text = f"  {r['scene']:<40} {best['speedup']:6.0f}×"
        book = (r.get("textbook") or {}).get("ours")
        if book:
            text += f"  textbook {book['speedup']:5.0f}×"
        worst = min([best["speedup"]] + ([book["speedup"]] if book else []))
        if worst >= TARGET_SPEEDUP:
            print(text + "  meets the target")
            continue
        peer_us = base["wall_time_s"] / max(base["nfev"], 1) * 1e6
        ours_ns = best["wall_time_s"] / max(best["nfev"], 1) * 1e9
        evals = best["nfev"] / max(base["nfev"], 1)
        print(text + f"  below: scipy {peer_us:4.1f} µs per evaluation, ours {ours_ns:4.0f} ns "
                     f"(all the step's work), with {evals:.2f}× scipy's evaluations; "
                     f"{TARGET_SPEEDUP:.0f}× needs ≤ {peer_us * 1e3 / TARGET_SPEEDUP / evals:.0f} "
                     "ns")


def heavy_top_textbook(scene, print=builtins.print, samples: int = 201) -> dict:
    """The heavy top against the script a user would write: scipy DOP853 (rtol 1e-10,
    atol 1e-12) on the Euler-angle Lagrange equations
    (:func:`~reportgen.core.models.heavy_top.euler_angle_rhs`), and our run (compiled
    DOP853 on the equations the scene integrates: the reduced ones, or spin-free near the
    vertical) at the loosest rtol, in quarter decades, that reaches the same max error of
    θ(t) at ``samples`` times, both against the elliptic-function θ(t)
    (:func:`~reportgen.core.heavy_top_theory.theta_closed_form`).  Both timed as whole
    calls (ours includes the Python around the compiled driver and the conversion to θ):
    min of repeats after a warm-up."""
    from scipy.integrate import solve_ivp

    from ..core import heavy_top_kinematics as kinematics
    from ..core import heavy_top_theory as theory
    from ..core.integrators import integrate
    from ..core.models import heavy_top as model_core

    p, t_end = scene.config.params, scene.config.run.t_end
    start = next(iter(scene.starts.values()))
    theta0, theta_dot0, phi_dot0, omega3 = start
    t = np.linspace(0.0, t_end, samples)
    c = theory.constants(p.I1, p.I3, p.Mgl, *start)
    exact = theory.theta_closed_form(t, theory.roots(c), c)
    name = scene.source.name
    if math.sin(theta0) == 0.0:
        print(f"  {name}: textbook peer skipped (the Euler-angle equations are singular at "
              "θ0 = 0)")
        return {}
    f = model_core.euler_angle_rhs(p.I1, p.I3, p.Mgl)
    y0 = [theta0, 0.0, 0.0, theta_dot0, phi_dot0, omega3 - phi_dot0 * math.cos(theta0)]
    peer_s, sol = best_time(lambda: solve_ivp(f, (0.0, t_end), y0, method="DOP853",
                                               rtol=1e-10, atol=1e-12, t_eval=t), 3)
    peer_err = (float(np.max(np.abs(sol.y[0] - exact))) if sol.success else math.inf)
    # what the scene integrates (reduced, or spin-free near the vertical), up to θ(t)
    model, s0, _body, formulation, _why = scene._integration(start)
    if formulation == "reduced":  # the state's first component is w = 1 − cos θ
        def theta_of(y):
            return theory.theta_of_w(y[:, 0])
    else:
        def theta_of(y):
            return kinematics.tilt_angle(y[:, :4])

    def run(rtol):
        sol = integrate(model, s0, t, rtol=rtol, atol=rtol * 1e-2)
        return sol, theta_of(sol.y)

    ours = None
    for rtol in 10.0 ** -np.arange(6.0, 14.25, 0.25):
        run(rtol)  # warm-up (and compile)
        wall, (sol_ours, theta) = best_time(lambda rtol=rtol: run(rtol), 20)
        err = float(np.max(np.abs(theta - exact)))
        if err <= peer_err:
            ours = {"rtol": float(rtol), "error": err, "wall_time_s": wall,
                    "steps": sol_ours.nsteps, "nfev": sol_ours.nfev,
                    "formulation": formulation}
            break
    line = (f"  {name:<28} textbook: scipy DOP853 on Euler angles, rtol 1e-10: θ error "
            f"{peer_err:.1e} in {peer_s * 1e3:7.2f} ms ({sol.nfev} evaluations)")
    if ours is None:
        print(line + " | none of our runs reached that θ error")
    else:
        ratio = peer_s / ours["wall_time_s"]
        print(line + f" | ours: {formulation} dop853 rtol {ours['rtol']:.1e}: {ours['error']:.1e} "
                     f"in {ours['wall_time_s'] * 1e3:6.3f} ms ({ours['steps']} steps) → "
                     f"{ratio:5.0f}×")
        ours["speedup"] = ratio
    out = {"peer_error": peer_err, "peer_wall_time_s": peer_s, "peer_nfev": int(sol.nfev),
           "ours": ours}

    def ours_at(rtol):
        run(rtol)
        wall, (_sol, theta) = best_time(lambda: run(rtol), 5)
        return wall, float(np.max(np.abs(theta - exact)))

    out["heyoka"] = heavy_top_heyoka(p.I1, p.I3, p.Mgl, y0, t, exact, ours_at, name,
                                     print=print)
    return out


def heavy_top_heyoka(I1, I3, Mgl, y0, t, exact, ours_at, name="", print=builtins.print,
                     tolerances=(1e-9, 1e-11, 1e-13, 1e-15), repeats=5) -> list[dict]:
    """heyoka (Taylor, LLVM JIT) on the same Euler-angle equations as the textbook script,
    at ``tolerances``: max θ error at the times ``t`` against ``exact``, its run time (one
    warm-up, best and median of ``repeats``) and its JIT time; beside each, ours at the
    loosest rtol reaching the same θ error (``ours_at(rtol)`` → (best wall time, θ error))
    and our time over heyoka's.  Empty (and one line saying so) when heyoka is absent."""
    hy = _heyoka(print, f"  {name}: heavy top")
    if hy is None:
        return []
    th, ph, ps, thd, phd, psd = hy.make_vars("th", "ph", "ps", "thd", "phd", "psd")
    s, c = hy.sin(th), hy.cos(th)
    omega3 = psd + phd * c
    th_dd = (I1 * phd**2 * s * c - I3 * omega3 * phd * s + Mgl * s) / I1
    ph_dd = (I3 * omega3 * thd - 2.0 * I1 * phd * thd * c) / (I1 * s)
    system = [(th, thd), (ph, phd), (ps, psd), (thd, th_dd), (phd, ph_dd),
              (psd, phd * thd * s - ph_dd * c)]
    ours = [(rtol, *ours_at(rtol)) for rtol in 10.0 ** -np.arange(6.0, 14.25, 0.25)]
    rows = []
    for tol in tolerances:
        row = _heyoka_rows(hy, system, y0, t, tol, repeats)
        row["error"] = float(np.max(np.abs(row.pop("y")[:, 0] - exact)))
        line = (f"  {name:<28} heyoka tol {tol:.0e}: θ error {row['error']:.1e} in "
                f"{row['wall_time_s'] * 1e3:7.3f} ms (JIT {row['jit_s']:.2f} s)")
        match = next(((rtol, wall, err) for rtol, wall, err in ours if err <= row["error"]),
                      None)
        if match is None:
            line += " | ours: no rtol ≥ 1e-14 reaches it (behind)"
        else:
            rtol, wall, err = match
            row.update(ours_rtol=rtol, ours_error=err, ours_wall_time_s=wall,
                       ratio=wall / row["wall_time_s"])
            line += (f" | ours rtol {rtol:.1e}: {err:.1e} in {wall * 1e3:7.3f} ms → "
                     f"ours/heyoka {row['ratio']:.2f} "
                     f"({'behind' if row['ratio'] > 1 else 'ahead'})")
        rows.append(row)
        print(line)
    return rows


def _heyoka(print, what: str):
    """The heyoka module, or None with one line saying it is not installed."""
    try:
        import heyoka
    except ImportError:
        print(f"{what}: heyoka not installed (pip install 'reportgen[heyoka]'): no heyoka "
              "peer")
        return None
    return heyoka


def _heyoka_rows(hy, system, y0, t, tol, repeats) -> dict:
    """One heyoka run of ``system`` from ``y0`` over the grid ``t`` at ``tol``: its JIT time
    (building the integrator), then one warm-up and ``repeats`` timed ``propagate_grid``
    calls (state and time reset before each, inside the timing)."""
    start = time.perf_counter()
    ta = hy.taylor_adaptive(system, list(y0), tol=tol)
    jit = time.perf_counter() - start

    def run():
        ta.time = float(t[0])
        ta.state[:] = y0
        return ta.propagate_grid(t)

    run()
    times, out = _times(run, repeats)
    return {"method": f"heyoka tol {tol:.0e}", "tol": tol, "jit_s": jit,
            "wall_time_s": min(times), "median_s": float(np.median(times)),
            "outcome": str(out[0]).rsplit(".", 1)[-1], "steps": int(out[3]), "y": out[-1]}


def _times(fn, repeats):
    """(wall times of ``repeats`` calls of ``fn``, the last result)."""
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - start)
    return times, result


def long_time_energy(n_periods=1_000_000, steps_per_period=100, n_out=2000, method="yoshida4",
                     out_dir: Path | None = None, print=builtins.print) -> dict:
    """Pendulum θ0 = 1 rad over ``n_periods`` with a symplectic method: bounded energy error.

    Output points are spaced a non-integer number of periods apart so they see
    every phase of the bounded energy oscillation.
    """
    from ..core.integrators import integrate
    from ..core.models import pendulum

    g, l, theta0 = 9.81, 1.0, 1.0
    model = pendulum.model(g, l)
    period = pendulum.exact_period(theta0, 0.0, g, l)
    spacing = (n_periods / n_out + 0.123) * period
    t_eval = spacing * np.arange(n_out + 1)
    start = time.perf_counter()
    sol = integrate(model, np.array([theta0, 0.0]), t_eval, method=method,
                    h=period / steps_per_period, max_steps=10**10)
    wall = time.perf_counter() - start
    e0 = pendulum.energy(theta0, 0.0, g, l)
    de = np.abs(pendulum.energy(sol.y[:, 0], sol.y[:, 1], g, l) / e0 - 1.0)
    decile = max(1, de.size // 10)
    first, last = float(de[1:decile].max()), float(de[-decile:].max())
    print(f"long run: pendulum θ0 = 1 rad, {t_eval[-1] / period:.3g} periods, {method}, "
          f"h = T/{steps_per_period}: {sol.nsteps} steps in {wall:.2f} s ({sol.status})")
    print(f"  max |ΔE/E| first decile {first:.2e}, last decile {last:.2e} "
          f"(ratio {last / first:.2f}: {'bounded' if last < 2 * first else 'DRIFTING'})")
    result = {"method": method, "n_periods": float(t_eval[-1] / period), "wall_time_s": wall,
              "first_decile": first, "last_decile": last, "status": sol.status}
    if out_dir is not None:
        result["figure"] = str(_plot_long_run(t_eval[1:] / period, de[1:], method, out_dir))
        print(f"  figure: {result['figure']}")
    return result


def kepler_against_rebound(e=0.9, orbits=1000, outputs=1001, target=1e-13,
                           print=builtins.print) -> dict:
    """Kepler orbit of eccentricity ``e`` over ``orbits`` periods: energy error and wall time
    of our integrators against REBOUND's IAS15 and WHFast (when installed), same run.

    GM = 1, a = 1, started at pericentre; the energy is checked at ``outputs`` times.
    """
    from ..core.integrators import integrate
    from ..core.models import kepler

    period = 2 * math.pi
    y0 = np.array([1 - e, 0.0, 0.0, math.sqrt((1 + e) / (1 - e))])
    t = np.linspace(0.0, orbits * period, outputs)
    model = kepler.model(1.0, 1.0)
    e0 = kepler.energy(*y0, 1.0, 1.0)
    integrate(model, y0, t[:3], method="dop853")  # compile / load outside the timing
    print(f"Kepler e = {e}, {orbits} orbits, max |ΔE/E| over {outputs} outputs "
          f"(target ≤ {target:.0e}); wall time = min of 3")
    rows = []
    for method, rtol in (("dop853", 1e-13), ("dop853", 1e-14)):
        best, sol = math.inf, None
        for _ in range(3):
            start = time.perf_counter()
            sol = integrate(model, y0, t, method=method, rtol=rtol, atol=rtol * 1e-3)
            best = min(best, time.perf_counter() - start)
        energy = kepler.energy(sol.y[:, 0], sol.y[:, 1], sol.y[:, 2], sol.y[:, 3], 1.0, 1.0)
        rows.append({"method": f"{method} rtol {rtol:.0e}", "error": float(
            np.max(np.abs(energy / e0 - 1))), "wall_time_s": best})
    # Levi-Civita regularized Kepler with Gauss-Legendre 6 (energy: a quadratic invariant)
    from ..core.models import kepler_regularized as lc

    state0 = lc.to_regularized(*y0)
    h_energy = float(e0)
    s_orbit = lc.orbit_fictitious_period(h_energy)
    s = np.linspace(0.0, orbits * s_orbit, outputs)
    reg = lc.model(h_energy)
    integrate(reg, state0, s[:3], method="gauss6", h=s_orbit / 12)
    for per_orbit in (12, 24, 48):
        best, sol = math.inf, None
        for _ in range(3):
            start = time.perf_counter()
            sol = integrate(reg, state0, s, method="gauss6", h=s_orbit / per_orbit)
            best = min(best, time.perf_counter() - start)
        x, y, vx, vy, _t = lc.from_regularized(sol.y)
        energy = kepler.energy(x, y, vx, vy, 1.0, 1.0)
        rows.append({"method": f"Levi-Civita + gauss6, {per_orbit}/orbit",
                     "error": float(np.max(np.abs(energy / e0 - 1))), "wall_time_s": best})
    try:
        import rebound
    except ImportError:
        rebound = None
        print("  REBOUND not installed (pip install 'reportgen[rebound]'): no peer baseline")
    if rebound is not None:
        for integrator in ("ias15", "whfast"):
            best, error = math.inf, math.nan
            for _ in range(3):
                sim = rebound.Simulation()
                sim.add(m=1.0)
                sim.add(m=1e-12, a=1.0, e=e)  # a test particle; nonzero so sim.energy() ≠ 0
                sim.integrator = integrator
                if integrator == "whfast":
                    sim.dt = period / 1000
                sim.move_to_com()
                start_energy = sim.energy()
                worst = 0.0
                start = time.perf_counter()
                for tt in t[1:]:
                    sim.integrate(tt, exact_finish_time=integrator == "ias15")
                    worst = max(worst, abs(sim.energy() / start_energy - 1))
                best, error = min(best, time.perf_counter() - start), worst
            rows.append({"method": f"REBOUND {integrator.upper()}", "error": error,
                         "wall_time_s": best})
    ias = next((r for r in rows if r["method"] == "REBOUND IAS15"), None)
    for r in rows:
        ratio = (f"  {ias['wall_time_s'] / r['wall_time_s']:5.2f}× IAS15's speed"
                 if ias is not None else "")
        met = "meets" if r["error"] <= target else "misses"
        print(f"  {r['method']:<34} |ΔE/E| {r['error']:.1e} ({met} target) in "
              f"{r['wall_time_s']:.3f} s{ratio}")
    if ias is not None:
        met = [r["method"] for r in rows if not r["method"].startswith("REBOUND")
               and r["error"] <= target and r["wall_time_s"] < ias["wall_time_s"]]
        print(f"  P2 (≤ {target:.0e} in less time than IAS15) met by: "
              f"{', '.join(met) if met else 'none'}")
    return {"rows": rows}


def kepler_against_heyoka(e=0.9, orbits=1000, outputs=10_001, repeats=5,
                          tolerances=(1e-9, 1e-11, 1e-13, 1e-15), print=builtins.print) -> dict:
    """Kepler orbit of eccentricity ``e`` over ``orbits`` periods at ``outputs`` times: our
    methods against heyoka (Taylor, LLVM JIT) at ``tolerances``, same run, same outputs.

    GM = 1, a = 1, started at pericentre.  Per row: max |ΔE/E| over the outputs and at the
    end (one energy function for all), the position error at the end against Kepler's
    equation (:func:`~reportgen.core.models.kepler.kepler_state`), wall time (one warm-up,
    best and median of ``repeats``; our compile and heyoka's JIT excluded, the JIT shown
    beside).  Then, per heyoka row, our fastest row whose max |ΔE/E| is at or below
    heyoka's, and our time over heyoka's (> 1: we are behind).
    """
    from ..core.integrators import integrate
    from ..core.integrators.regularized import SAFETY, STEP_CONSTANT
    from ..core.models import kepler

    y0 = np.array([1 - e, 0.0, 0.0, math.sqrt((1 + e) / (1 - e))])
    t = np.linspace(0.0, orbits * 2 * math.pi, outputs)
    model = kepler.model(1.0, 1.0)
    e0 = kepler.energy(*y0, 1.0, 1.0)
    exact_end = np.array(kepler.kepler_state(t[-1:], kepler.orbital_elements(*y0, 1.0)))[:, 0]

    def measures(y):
        de = np.abs(kepler.energy(y[:, 0], y[:, 1], y[:, 2], y[:, 3], 1.0, 1.0) / e0 - 1)
        return {"error": float(np.max(de)), "error_end": float(de[-1]),
                "position_end": float(np.hypot(*(y[-1, :2] - exact_end[:2])))}

    print(f"\nKepler e = {e}, {orbits} orbits, {outputs} outputs: |ΔE/E| max over the "
          f"outputs and at the end, |Δr| at the end against Kepler's equation; wall time "
          f"best (median) of {repeats} after a warm-up, compile/JIT excluded")
    speed = math.sqrt((1 + e) / (1 - e))
    ours_runs = [("dop853", 1e-13, "Cartesian DOP853 rtol 1e-13"),
                 ("dop853", 1e-14, "Cartesian DOP853 rtol 1e-14"),
                 ("levi_civita_dop853", 1e-13, "Levi-Civita + DOP853 rtol 1e-13"),
                 ("levi_civita_dop853", 1e-15, "Levi-Civita + DOP853 rtol 1e-15")]
    # levi_civita (Gauss–Legendre 6) at N steps per orbit: the rtol its grid rule
    # (regularized.grid_steps_per_orbit, a tenth of rtol: SAFETY) turns into N; at rtol
    # 1e-13 it takes its own N
    for n in (16, 24, 48):
        ours_runs.append(("levi_civita", STEP_CONSTANT * speed / (SAFETY * (n - 0.5) ** 6),
                          f"Levi-Civita + Gauss–Legendre 6, {n}/orbit"))
    ours_runs.append(("levi_civita", 1e-13, "Levi-Civita + GL6 rtol 1e-13 (auto)"))
    rows = []
    for method, rtol, label in ours_runs:
        def run(method=method, rtol=rtol):
            return integrate(model, y0, t, method=method, rtol=rtol, atol=rtol * 1e-2)

        run()  # compile / load outside the timing
        times, sol = _times(run, repeats)
        rows.append({"method": label, "ours": True, "wall_time_s": min(times),
                     "median_s": float(np.median(times)), "jit_s": math.nan,
                     "steps": int(sol.nsteps), **measures(sol.y)})
    hy = _heyoka(print, "  Kepler")
    if hy is not None:
        x, y, vx, vy = hy.make_vars("x", "y", "vx", "vy")
        r3 = (x**2 + y**2) ** -1.5
        system = [(x, vx), (y, vy), (vx, -x * r3), (vy, -y * r3)]
        for tol in tolerances:
            row = _heyoka_rows(hy, system, y0, t, tol, repeats)
            row.update(ours=False, **measures(row.pop("y")))
            rows.append(row)
    for r in rows:
        jit = f"  JIT {r['jit_s']:.3f} s" if math.isfinite(r["jit_s"]) else ""
        print(f"  {r['method']:<40} max {r['error']:.1e}  end {r['error_end']:.1e}  "
              f"|Δr| {r['position_end']:.1e}  {r['wall_time_s'] * 1e3:8.2f} ms "
              f"({r['median_s'] * 1e3:.2f}){jit}")
    matched = []
    for peer in (r for r in rows if not r["ours"]):
        for measure, keys in (("|ΔE/E|", ("error",)), ("|ΔE/E| and |Δr|",
                                                       ("error", "position_end"))):
            reach = [r for r in rows if r["ours"] and all(r[k] <= peer[k] for k in keys)]
            best = min(reach, key=lambda r: r["wall_time_s"], default=None)
            head = f"  vs {peer['method']} on {measure}:"
            if best is None:
                print(f"{head} none of ours reaches it: BEHIND")
                matched.append({"peer": peer["method"], "measure": measure, "ours": None,
                                "ratio": math.inf, "median_ratio": math.inf})
                continue
            ratio = best["wall_time_s"] / peer["wall_time_s"]
            median_ratio = best["median_s"] / peer["median_s"]
            print(f"{head} ours {best['method']} in {best['wall_time_s'] * 1e3:.2f} ms "
                  f"against {peer['wall_time_s'] * 1e3:.2f} ms: ours/heyoka {ratio:.2f} "
                  f"best, {median_ratio:.2f} median: {'BEHIND' if ratio > 1 else 'ahead'}")
            matched.append({"peer": peer["method"], "measure": measure, "ours": best["method"],
                            "ratio": ratio, "median_ratio": median_ratio})
    behind = [m for m in matched if m["ratio"] > 1]
    if behind:
        worst = max(behind, key=lambda m: m["ratio"])
        print(f"  Behind heyoka in {len(behind)} of {len(matched)} matched comparisons "
              f"(worst {worst['ratio']:.1f}× its time: {worst['peer']} on {worst['measure']}).")
    elif matched:
        print("  At or ahead of heyoka in every matched comparison.")
    return {"rows": rows, "matched": matched}


def _plot_long_run(periods, rel_error, method, out_dir: Path) -> Path:
    from ..rendering.plots.style import new_figure
    from ..support.fsutil import atomic_write

    fig, ax = new_figure(figsize=(7.0, 3.6))
    ax.semilogy(periods, np.maximum(rel_error, 1e-18), ".", markersize=2, rasterized=True)
    ax.set_xlabel("time [periods]")
    ax.set_ylabel("|ΔE / E0|")
    ax.set_title(f"Pendulum energy error with {method}: bounded, no drift")
    out_dir.mkdir(parents=True, exist_ok=True)
    import io

    for fmt_name in ("svg", "png"):
        buf = io.BytesIO()
        fig.savefig(buf, format=fmt_name,
                    metadata={"svg": {"Date": None}, "png": {"Software": None}}[fmt_name])
        atomic_write(out_dir / f"longtime_energy.{fmt_name}", buf.getvalue())
    return out_dir / "longtime_energy.svg"


def run_bench(paths: list[str], out_dir: str = "output/bench", long_run: bool = True,
              print=builtins.print) -> int:
    from ..pipeline.stages import UsageError, collect_configs, validate_all

    paths = paths or default_paths()
    if not paths:
        raise UsageError("no PATH given and no configs/ folder found")
    try:
        scenes = validate_all(collect_configs(paths))
    except ConfigError:
        raise
    print(f"Speed at matched error against {BASELINE} (rtol {BASELINE_RTOL:g}); "
          "wall time = min of repeats after a warm-up, compile excluded")
    results = [r for r in (scene_bench(scene, print=print) for scene in scenes) if r]
    summarize(results, print=print)
    heyoka_table(results, print=print)
    if long_run:
        long_time_energy(out_dir=Path(out_dir), print=print)
        kepler_against_rebound(print=print)
        kepler_against_heyoka(print=print)
        from .bench_nbody import pythagorean_against_rebound
        pythagorean_against_rebound(print=print)
        from .bench_single import single_run_against_warm
        single_run_against_warm(print=print)
    return 0
