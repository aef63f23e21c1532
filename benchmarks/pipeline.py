"""The edit loop, measured whole: the lecture pack cold and warm, a title edit, a physics edit.

Run from the repository root::

    .venv/bin/python benchmarks/pipeline.py [--scene pendulum_small] [--configs configs]

Each row is one ``reportgen`` process timed from outside (wall clock), in a private
temporary folder:

cold          the pack with empty numba and peer-measurement caches (NUMBA_CACHE_DIR and
              XDG_CACHE_HOME point into the temporary folder)
warm          the same command again, nothing changed
title edit    one scene's title changed (re-stamp + report only)
physics edit  one scene's ``[run] t_end`` raised by 10 % (re-simulated, study included)
--help, validate   the light commands

Targets are those of the project's edit-loop issue (2 cores).
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
REPORTGEN = [sys.executable, "-m", "reportgen"]
TARGETS = {"cold": 60.0, "warm": 2.0, "title edit": 2.0, "physics edit": 5.0,
           "--help": 0.5, "validate": 1.0}


def timed(args: list[str], env: dict[str, str], cwd: Path) -> tuple[float, str]:
    start = time.perf_counter()
    proc = subprocess.run([*REPORTGEN, *args], env=env, cwd=cwd, capture_output=True,
                          text=True, check=False)
    elapsed = time.perf_counter() - start
    if proc.returncode not in (0, 1):
        raise SystemExit(f"reportgen {' '.join(args)} failed ({proc.returncode}):\n"
                         f"{proc.stderr[-2000:]}")
    return elapsed, proc.stderr


def edit(path: Path, pattern: str, replace) -> None:
    text = path.read_text(encoding="utf-8")
    new, n = re.subn(pattern, replace, text, count=1, flags=re.M)
    if n == 0:
        raise SystemExit(f"{path}: no line matches {pattern!r}")
    path.write_text(new, encoding="utf-8")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--configs", default=str(REPO / "configs"))
    parser.add_argument("--scene", default="pendulum_small",
                        help="the scene edited in the title and physics rows")
    args = parser.parse_args()
    rows: list[tuple[str, float, str]] = []
    with tempfile.TemporaryDirectory(prefix="reportgen-pipeline-") as tmp:
        tmp = Path(tmp)
        pack = tmp / "configs"
        shutil.copytree(args.configs, pack)
        env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp / "numba"),
               "XDG_CACHE_HOME": str(tmp / "xdg"), "PYTHONPATH": str(REPO)}
        env.pop("REPORTGEN_NO_CACHE", None)
        out = ["--out", str(tmp / "output")]
        n = len(list(pack.glob("*.toml")))
        wall, _ = timed(["run", str(pack), *out], env, tmp)
        rows.append(("cold", wall, f"{n} scenes, {wall / n:.2f} s per scene"))
        wall, _ = timed(["run", str(pack), *out], env, tmp)
        rows.append(("warm", wall, "nothing changed"))
        scene = pack / f"{args.scene}.toml"
        if not re.search(r"^title\s*=", scene.read_text(encoding="utf-8"), flags=re.M):
            raise SystemExit(f"{scene}: needs a title line for the title edit")
        edit(scene, r"^title\s*=.*$", 'title = "An edited title"')
        wall, _ = timed(["run", str(scene), *out, "--jobs", "1"], env, tmp)
        rows.append(("title edit", wall, args.scene))
        edit(scene, r"^t_end\s*=\s*([0-9.eE+-]+)",
             lambda m: f"t_end = {1.1 * float(m.group(1)):g}")
        wall, _ = timed(["run", str(scene), *out, "--jobs", "1"], env, tmp)
        rows.append(("physics edit", wall, f"{args.scene}, t_end +10 %"))
        wall, _ = timed(["--help"], env, tmp)
        rows.append(("--help", wall, ""))
        wall, _ = timed(["validate", str(pack)], env, tmp)
        rows.append(("validate", wall, f"{n} configs"))
    print(f"{'what':<14} {'wall [s]':>9} {'target [s]':>11}  {'':<4} note")
    for name, wall, note in rows:
        target = TARGETS[name]
        print(f"{name:<14} {wall:9.2f} {target:11.1f}  {'ok' if wall <= target else 'OVER':<4} "
              f"{note}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
