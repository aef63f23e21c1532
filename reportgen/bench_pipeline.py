"""The edit loop, measured whole: the lecture pack cold and warm, a title edit, a physics
edit, the light commands, and one scene's stages.

Each row is one ``reportgen`` process timed from outside (wall clock), in a private
temporary folder (``reportgen bench --pipeline``, or ``benchmarks/pipeline.py``):

cold          the pack with empty numba and peer-measurement caches (NUMBA_CACHE_DIR and
              XDG_CACHE_HOME point into the temporary folder)
warm          the same command again, nothing changed
title edit    one scene's title changed, then the whole pack run again (re-stamp + report
              of that scene; the others are current)
physics edit  that scene's ``[run] t_end`` raised by 10 %, the pack run again (the scene is
              re-simulated, study included)
title edit (watch), physics edit (watch)
              the same two edits under ``reportgen watch`` (one process kept running):
              from the file's write to the watch's "done" line, polling included
--help, validate   the light commands
stages        the edited scene run alone with ``--force``, per stage (warm caches)

Targets are those of the project's edit-loop issue (2 cores).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
TARGETS = {"cold": 60.0, "warm": 2.0, "title edit": 2.0, "physics edit": 5.0,
           "title edit (watch)": 2.0, "physics edit (watch)": 5.0,
           "--help": 0.5, "validate": 1.0}


def _timed(args: list[str], env: dict[str, str], cwd: Path) -> float:
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "reportgen", *args], env=env, cwd=cwd,
                          capture_output=True, text=True, check=False)
    elapsed = time.perf_counter() - start
    if proc.returncode not in (0, 1):
        raise RuntimeError(f"reportgen {' '.join(args)} failed ({proc.returncode}):\n"
                           f"{proc.stderr[-2000:]}")
    return elapsed


def _edit(path: Path, pattern: str, replace) -> None:
    text = path.read_text(encoding="utf-8")
    new, n = re.subn(pattern, replace, text, count=1, flags=re.M)
    if n == 0:
        raise RuntimeError(f"{path}: no line matches {pattern!r}")
    path.write_text(new, encoding="utf-8")


def _stages(config: Path, out: Path, env: dict[str, str]) -> dict[str, float]:
    code = ("import json, sys\nfrom reportgen.pipeline import run_scene\n"
            "o = run_scene(sys.argv[1], sys.argv[2], force=True)\n"
            "print(json.dumps(o.stage_s))")
    proc = subprocess.run([sys.executable, "-c", code, str(config), str(out)], env=env,
                          capture_output=True, text=True, check=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _watched_edits(pack: Path, path: Path, out: list[str], env: dict[str, str],
                   cwd: Path) -> list[tuple[str, float, str]]:
    """The title and the physics edit under ``reportgen watch``: seconds from the write
    to the "--- done" line."""
    import queue
    import threading

    proc = subprocess.Popen([sys.executable, "-m", "reportgen", "watch", str(pack), *out],
                            env=env, cwd=cwd, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    lines: queue.Queue = queue.Queue()
    threading.Thread(target=lambda: [lines.put(line) for line in proc.stderr],
                     daemon=True).start()

    def done(timeout: float = 600.0) -> float:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            try:
                line = lines.get(timeout=1.0)
            except queue.Empty:
                continue
            if line.startswith("--- done"):
                return time.perf_counter()
            if line.startswith("--- not run"):
                raise RuntimeError("reportgen watch did not run the edited pack")
        raise RuntimeError("reportgen watch gave no result")

    rows = []
    try:
        done()  # the first run: everything current
        time.sleep(3.0)  # the watch imports what an edit needs while it waits
        start = time.perf_counter()
        _edit(path, r"^title\s*=.*$", 'title = "Edited under watch"')
        rows.append(("title edit (watch)", done() - start, f"{path.stem}, reportgen watch"))
        time.sleep(1.0)
        start = time.perf_counter()
        _edit(path, r"^t_end\s*=\s*([0-9.eE+-]+)",
              lambda m: f"t_end = {1.1 * float(m.group(1)):g}")
        rows.append(("physics edit (watch)", done() - start,
                     f"{path.stem}, t_end +10 %, reportgen watch"))
    finally:
        proc.terminate()
        proc.wait(timeout=30)
    return rows


def measure(configs: Path, scene: str, print=print) -> list[tuple[str, float, str]]:
    """Measure every row; print the table; return (row, seconds, note) tuples."""
    rows: list[tuple[str, float, str]] = []
    with tempfile.TemporaryDirectory(prefix="reportgen-pipeline-") as tmp:
        tmp = Path(tmp)
        pack = tmp / "configs"
        shutil.copytree(configs, pack)
        env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp / "numba"),
               "XDG_CACHE_HOME": str(tmp / "xdg")}
        env["PYTHONPATH"] = os.pathsep.join(
            [str(REPO), *filter(None, [os.environ.get("PYTHONPATH")])])
        env.pop("REPORTGEN_NO_CACHE", None)
        out = ["--out", str(tmp / "output")]
        n = len(list(pack.glob("*.toml")))
        wall = _timed(["run", str(pack), *out], env, tmp)
        rows.append(("cold", wall, f"{n} scenes, {wall / n:.2f} s per scene"))
        print(f"cold: {wall:.1f} s", file=sys.stderr)
        wall = _timed(["run", str(pack), *out], env, tmp)
        rows.append(("warm", wall, "nothing changed"))
        path = pack / f"{scene}.toml"
        if not re.search(r"^title\s*=", path.read_text(encoding="utf-8"), flags=re.M):
            raise RuntimeError(f"{path}: needs a title line for the title edit")
        _edit(path, r"^title\s*=.*$", 'title = "An edited title"')
        wall = _timed(["run", str(pack), *out], env, tmp)
        rows.append(("title edit", wall, f"{scene}, pack re-run"))
        _edit(path, r"^t_end\s*=\s*([0-9.eE+-]+)",
              lambda m: f"t_end = {1.1 * float(m.group(1)):g}")
        wall = _timed(["run", str(pack), *out], env, tmp)
        rows.append(("physics edit", wall, f"{scene}, t_end +10 %, pack re-run"))
        rows.extend(_watched_edits(pack, path, out, env, tmp))
        rows.append(("--help", _timed(["--help"], env, tmp), ""))
        rows.append(("validate", _timed(["validate", str(pack)], env, tmp), f"{n} configs"))
        stages = _stages(path, tmp / "stages", env)
    print(f"{'what':<20} {'wall [s]':>9} {'target [s]':>11}  {'':<4} note")
    for name, wall, note in rows:
        target = TARGETS[name]
        print(f"{name:<20} {wall:9.2f} {target:11.1f}  {'ok' if wall <= target else 'OVER':<4} "
              f"{note}")
    print(f"stages of {scene} (--force, warm caches, in-process): "
          + ", ".join(f"{k} {v:.2f} s" for k, v in stages.items()))
    return rows
