"""Our Taylor integrator (method "taylor") against heyoka, same problems, same run.

For each scene the study's own problem is taken (the model, y0 and output grid the scene
hands to its work-precision study, captured by running the scene with the study on), and
at each tolerance both integrators run it: max abs error over the run against compiled
DOP853 at rtol 1e-14, best wall time of 5 repeats (ours and heyoka's interleaved),
compile/JIT excluded.  "ours/heyoka" compares the runs at the same tolerance; "matched"
our fastest run at least as accurate as heyoka's (over those and a quarter-decade
ladder 1e-5..1e-14, as ``reportgen bench`` runs ours) over heyoka's time.

    python benchmarks/taylor_vs_heyoka.py [scene config stems ...]

This is a benchmark, not a test: the times depend on the machine.
"""

from __future__ import annotations

import functools
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SCENES = ("pendulum_large", "kepler_e07", "three_body_figure_eight",
          "hamiltonian_henon_heiles_chaotic", "heavy_top_fig4.3")
TOLS = (1e-6, 1e-9, 1e-12, 1e-13)
REPEATS = 5
#: our ladder for the matched-error column: quarter decades, as ``reportgen bench``'s
MATCH_TOLS = tuple(10.0 ** (-k / 4) for k in range(20, 57))


def study_problem(stem: str):
    """(model, y0, t_eval) the scene ``stem`` gives its work-precision study."""
    from reportgen.pipeline.stages import collect_configs, validate_all

    (scene,) = validate_all(collect_configs([str(ROOT / "configs" / f"{stem}.toml")]))
    config = scene.config.model_copy(update={"run": scene.config.run.model_copy(
        update={"study": True})})
    scene = type(scene)(config, scene.source)
    captured = []

    def capture(results, model, y0, t_eval, *args, **kwargs):
        captured.append((model, np.array(y0, dtype=float), np.array(t_eval, dtype=float)))

    scene.study = capture
    scene.simulate()
    if not captured:
        raise RuntimeError(f"{stem}: the scene ran no study")
    return captured[0]


def best_of(runs, repeats=REPEATS):
    """[(last solution, best wall time, compile time of the first run)] of each of
    ``runs``, their repeats interleaved (so that both meet the same machine load)."""
    first = [run() for run in runs]  # warm-up (and the compile, kept out of the times)
    best = [math.inf] * len(runs)
    sols = list(first)
    for _ in range(repeats):
        for k, run in enumerate(runs):
            sols[k] = run()
            best[k] = min(best[k], sols[k].wall_time_s)
    return [(s, b, f.compile_time_s) for s, b, f in zip(sols, best, first, strict=True)]


def main(stems) -> None:
    from reportgen.core.integrators import METHODS, integrate
    from reportgen.core.study import reference_run

    heyoka = METHODS["heyoka"]
    print(f"{'scene':<34}{'tol':>7} | {'taylor err':>10} {'ms':>8} {'steps':>6} | "
          f"{'heyoka err':>10} {'ms':>8} {'steps':>6} | ours/heyoka | matched")
    for stem in stems:
        model, y0, t_eval = study_problem(stem)
        ref = reference_run(model, y0, t_eval)
        rows = []
        for tol in TOLS:
            (ours, t_ours, c_ours), (hy, t_hy, c_hy) = best_of([
                functools.partial(integrate, model, y0, t_eval, method="taylor", rtol=tol,
                                  atol=tol),
                functools.partial(heyoka.solve, model, y0, t_eval, tol, tol)])
            rows.append((tol, float(np.max(np.abs(ours.y - ref))), t_ours, ours.nsteps, c_ours,
                         float(np.max(np.abs(hy.y - ref))), t_hy, hy.nsteps, c_hy))
        # our runs on a finer ladder, for the matched-error column
        ladder = [(r[1], r[2]) for r in rows]
        for tol in MATCH_TOLS:
            ((sol, best, _),) = best_of([functools.partial(
                integrate, model, y0, t_eval, method="taylor", rtol=tol, atol=tol)])
            ladder.append((float(np.max(np.abs(sol.y - ref))), best))
        for tol, e_ours, t_ours, n_ours, c_ours, e_hy, t_hy, n_hy, c_hy in rows:
            # matched error: our fastest run at least as accurate as heyoka's
            fits = [t for e, t in ladder if e <= e_hy]
            matched = f"{min(fits) / t_hy:6.2f}" if fits else "  none"
            print(f"{stem:<34}{tol:>7.0e} | {e_ours:>10.2e} {t_ours * 1e3:>8.3f} "
                  f"{n_ours:>6} | {e_hy:>10.2e} {t_hy * 1e3:>8.3f} {n_hy:>6} | "
                  f"{t_ours / t_hy:>11.2f} | {matched}  (compile {c_ours:.2f} s, "
                  f"JIT {c_hy:.2f} s)", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or SCENES)
