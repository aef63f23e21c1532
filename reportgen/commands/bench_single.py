"""A heavy top's archived run time against the warm best of the same integration.

For every heavy top config in the configs folder (a ``[sweep]`` family excepted: its
members have no archived run of their own), the scene is run as ``reportgen run`` runs
it, in a fresh process, so the archived run is really its process's first: then
``/runs/main`` ``wall_time_s`` is read from the archive.  The same integration (the
scene's model and initial state, the archived output times, method, tolerances and
step) is then run here ``REPEATS`` times after a warm-up, and its best ``wall_time_s``
taken.  The archived time should be at most ``LIMIT`` times that best: it measures the
run that produced the archived trajectory, and a rehearsal before it
(:func:`reportgen.core.integrators.compiled_run.warm_up_run`, its seconds archived as
``warm_up_time_s``) keeps the cold caches of whatever ran before out of it.

This is a benchmark, not a test: the numbers depend on the machine and its load.
"""

from __future__ import annotations

import builtins
import math
import os
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

#: the archived time may be at most this many times the warm best (issue 34)
LIMIT = 1.2
#: timed repeats of the warm integration (after one untimed warm-up)
REPEATS = 20


def heavy_top_configs(folder: Path | None = None) -> list[Path]:
    """The heavy top configs of ``folder`` (default: the configs folder) without a
    ``[sweep]``, by name."""
    if folder is None:
        from . import default_paths

        found = default_paths()
        if not found:
            return []
        folder = Path(found[0])
    out = []
    for path in sorted(Path(folder).glob("*.toml")):
        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
        except (OSError, tomllib.TOMLDecodeError):
            continue
        if data.get("kind") == "heavy_top" and "sweep" not in data:
            out.append(path)
    return out


def archived_run(config: Path, out_dir: Path) -> dict:
    """Run ``config`` as ``reportgen run`` does (HTML only, ``--force``) in a fresh
    process into ``out_dir``, and return its archived ``/runs/main`` attributes and
    output times."""
    import h5py
    import numpy as np

    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    proc = subprocess.run([sys.executable, "-m", "reportgen", "run", str(config), "--out",
                           str(out_dir), "--format", "html", "--force"],
                          env=env, capture_output=True, text=True, timeout=600)
    archive = out_dir / config.stem / "run.h5"
    if proc.returncode != 0 or not archive.exists():
        raise RuntimeError(f"reportgen run {config.name} failed ({proc.returncode}): "
                           f"{(proc.stderr or proc.stdout).strip()[-400:]}")
    with h5py.File(archive, "r") as f:
        run = f["runs/main"]
        attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in run.attrs.items()}
        attrs["t"] = np.asarray(run["t"][...], dtype=np.float64)
    return attrs


def warm_best(config: Path, archived: dict, repeats: int = REPEATS) -> tuple[float, object]:
    """(best ``wall_time_s`` of ``repeats`` runs after a warm-up, the last Solution) of the
    integration the archived run made: the scene's model and initial state, the archived
    output times, method, tolerances and step."""
    from ..core.integrators import integrate
    from ..kinds import load_scene
    from ..scene.config import read_config

    scene = load_scene(read_config(config))
    starts = scene.starts
    start = starts.get("main", next(iter(starts.values())))
    model, y0, *_ = scene._integration(start)
    h = float(archived["h"])
    kwargs = {"method": str(archived["method"]), "rtol": float(archived["rtol"]),
              "atol": float(archived["atol"]), "h": None if math.isnan(h) else h}
    sol = integrate(model, y0, archived["t"], **kwargs)  # warm-up (and compile, if needed)
    best = math.inf
    for _ in range(repeats):
        sol = integrate(model, y0, archived["t"], **kwargs)
        best = min(best, sol.wall_time_s)
    return best, sol


def single_run_against_warm(print=builtins.print, folder: Path | None = None) -> list[dict]:
    """For each heavy top config (:func:`heavy_top_configs`): its archived main run's wall
    time from a fresh ``reportgen run`` against the warm best of the same integration,
    one line per scene; returns one dict per scene (``scene``, ``method``, ``nsteps``,
    ``archived_s``, ``warm_up_s``, ``warm_best_s``, ``ratio``, ``within`` = ratio ≤
    :data:`LIMIT`, ``same_run`` = the warm runs took the archived run's steps)."""
    configs = heavy_top_configs(folder)
    print(f"Single run against warm best (heavy tops): the archived /runs/main wall time "
          f"of a fresh `reportgen run` against the min of {REPEATS} warm runs of the same "
          f"integration; limit {LIMIT:g}×")
    rows = []
    with tempfile.TemporaryDirectory(prefix="reportgen-single-") as tmp:
        for config in configs:
            try:
                archived = archived_run(config, Path(tmp))
                best, sol = warm_best(config, archived)
            except (RuntimeError, subprocess.TimeoutExpired, KeyError, OSError) as exc:
                print(f"  {config.stem:28s} failed: {exc}")
                continue
            wall = float(archived["wall_time_s"])
            ratio = wall / best if best > 0 else math.inf
            row = {"scene": config.stem, "method": str(archived["method"]),
                   "nsteps": int(archived["nsteps"]), "archived_s": wall,
                   "warm_up_s": float(archived.get("warm_up_time_s", math.nan)),
                   "warm_best_s": best, "ratio": ratio, "within": bool(ratio <= LIMIT),
                   "same_run": bool(sol.nsteps == int(archived["nsteps"])
                                    and sol.nfev == int(archived["nfev"]))}
            rows.append(row)
            print(f"  {row['scene']:28s} {row['method']:8s} {row['nsteps']:6d} steps  "
                  f"archived {wall * 1e3:8.4f} ms  warm best {best * 1e3:8.4f} ms  "
                  f"ratio {ratio:5.2f}  ≤ {LIMIT:g}×: {'yes' if row['within'] else 'no'}"
                  + ("" if row["same_run"] else "  (warm runs took other steps)"))
    if rows:
        worst = max(rows, key=lambda r: r["ratio"])
        print(f"  {sum(r['within'] for r in rows)} of {len(rows)} within {LIMIT:g}×; worst "
              f"{worst['scene']} at {worst['ratio']:.2f}×")
    return rows
