"""config → scene → core → archive → plots → report, for one scene and for a batch.

Every config of a batch is validated before anything runs; one bad config stops
the batch with exit status 2 and nothing written.  Scenes then run in a local
process pool (``--jobs``); a scene that fails does not stop the others.
"""

from __future__ import annotations

import os
import sys
import time
import traceback
from collections.abc import Callable, Iterable
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from multiprocessing import get_context
from pathlib import Path

from . import __version__
from .archive import read_archive, stored_identity, write_archive
from .config import ConfigError, read_config
from .results import worst_status
from .scenes import load_scene
from .scenes.base import Scene


class UsageError(Exception):
    """Bad command-line usage (exit status 2)."""


@dataclass
class Outcome:
    """What happened to one scene of a batch."""

    name: str
    kind: str = ""
    title: str = ""
    status: str = "ok"
    message: str = ""
    wall_time_s: float | None = None
    skipped: bool = False
    folder: str = ""
    reports: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.status == "ok"


def collect_configs(paths: Iterable[str | Path]) -> list[Path]:
    """Config files named directly, or every ``*.toml`` below a folder, in sorted order."""
    found: list[Path] = []
    for raw in paths:
        path = Path(raw)
        if path.is_dir():
            found.extend(sorted(p for p in path.rglob("*.toml") if p.is_file()))
        elif path.is_file():
            found.append(path)
        else:
            raise UsageError(f"{path}: no such file or folder")
    unique = list({p.resolve(): p for p in reversed(found)}.values())[::-1]
    if not unique:
        raise UsageError("no *.toml config found in " + ", ".join(str(p) for p in paths))
    return unique


def validate_all(paths: list[Path]) -> list[Scene]:
    """Validate every config; one ConfigError listing every problem of every file."""
    scenes, problems = [], []
    for path in paths:
        try:
            scenes.append(load_scene(read_config(path)))
        except ConfigError as exc:
            problems.extend(exc.problems)
    names: dict[str, Path] = {}
    for scene in scenes:
        name = scene.source.name
        if name in names:
            problems.append(f"{scene.source.path}: scene name '{name}' (the file name) is also "
                            f"used by {names[name]}; both would write output/{name}/")
        names[name] = scene.source.path
    if problems:
        raise ConfigError(problems)
    return scenes


def _formats(scene: Scene, override: tuple[str, ...] | None) -> tuple[str, ...]:
    return tuple(override) if override else tuple(scene.config.report.formats)


def run_scene(config_path: str, out_root: str, force: bool = False,
              formats: tuple[str, ...] | None = None,
              progress: Callable[[float], None] | None = None) -> Outcome:
    """Run one scene end to end.  Never raises: failures come back in the Outcome."""
    path = Path(config_path)
    outcome = Outcome(name=path.stem)
    folder = Path(out_root) / path.stem
    outcome.folder = str(folder)
    start = time.perf_counter()
    try:
        scene = load_scene(read_config(path))
        outcome.kind, outcome.title = scene.kind, scene.title
        archive = folder / "run.h5"
        stored = stored_identity(archive) if archive.exists() else None
        fresh = stored is not None and stored[:2] == (scene.source.sha256, __version__)
        if fresh and not force:
            outcome.skipped = True
            outcome.status = stored[2]
        else:
            results = scene.simulate(progress=progress)
            for name, run in results.runs.items():
                if run.status != "ok":
                    results.flag(run.status, f"run '{name}': {run.message}")
            results.wall_time_s = time.perf_counter() - start
            write_archive(archive, kind=scene.kind, title=scene.title, scene=scene.source.name,
                          config_text=scene.source.text, config_sha256=scene.source.sha256,
                          results=results)
            outcome.status = results.status
            outcome.message = results.message
        wanted = _formats(scene, formats)
        report_files = {"html": folder / "report.html", "pdf": folder / "report.pdf"}
        missing = [f for f in wanted if not report_files[f].exists()]
        if not outcome.skipped or missing:
            from .report import build_report

            build_report(archive, formats=wanted if not outcome.skipped else missing)
        outcome.reports = [str(report_files[f]) for f in wanted]
        if outcome.skipped:
            data = read_archive(archive)
            outcome.message = data.message
            outcome.wall_time_s = float(data.attrs.get("wall_time_s", 0.0))
        else:
            outcome.wall_time_s = time.perf_counter() - start
    except ConfigError as exc:
        outcome.status, outcome.message = "failed", str(exc)
    except Exception as exc:  # noqa: BLE001 - one scene's crash must not stop the batch
        outcome.status = "failed"
        log = folder / "error.log"
        try:
            folder.mkdir(parents=True, exist_ok=True)
            log.write_text(traceback.format_exc())
            where = f" (traceback in {log})"
        except OSError:
            where = ""
        outcome.message = f"{type(exc).__name__}: {exc}{where}"
    return outcome


class Progress:
    """Per-scene lines on stderr; an in-place percentage within a long integration on a TTY."""

    def __init__(self, total: int, stream=None):
        self.total = total
        self.done = 0
        self.stream = stream or sys.stderr
        self.tty = self.stream.isatty()
        self._last = 0.0

    def scene_done(self, outcome: Outcome) -> None:
        self.done += 1
        note = "up to date" if outcome.skipped else (
            f"{outcome.wall_time_s:.1f} s" if outcome.wall_time_s is not None else "")
        line = f"[{self.done}/{self.total}] {outcome.name:<28} {outcome.status:<8} {note}"
        if outcome.message and not outcome.ok:
            line += f"\n      {outcome.message}"
        self._clear()
        print(line, file=self.stream, flush=True)

    def within(self, name: str) -> Callable[[float], None] | None:
        if not self.tty:
            return None

        def report(fraction: float) -> None:
            now = time.monotonic()
            if now - self._last > 0.1 or fraction >= 1.0:
                self._last = now
                print(f"\r  {name}: integrating {100 * fraction:5.1f} %", end="",
                      file=self.stream, flush=True)

        return report

    def _clear(self) -> None:
        if self.tty:
            print("\r\033[K", end="", file=self.stream)


def run_batch(paths: list[str], out_root: str = "output", jobs: int | None = None,
              formats: tuple[str, ...] | None = None, force: bool = False,
              stream=None) -> list[Outcome]:
    """Validate all, run all (pool of ``jobs`` processes), write ``index.html``."""
    configs = collect_configs(paths)
    scenes = validate_all(configs)
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(scenes)))
    progress = Progress(len(scenes), stream)
    outcomes: list[Outcome] = []
    Path(out_root).mkdir(parents=True, exist_ok=True)
    if jobs == 1:
        for scene in scenes:
            name = scene.source.name
            outcome = run_scene(str(scene.source.path), out_root, force, formats,
                                progress=progress.within(name))
            progress.scene_done(outcome)
            outcomes.append(outcome)
    else:
        with ProcessPoolExecutor(max_workers=jobs, mp_context=get_context("fork")) as pool:
            futures = {pool.submit(run_scene, str(s.source.path), out_root, force, formats): s
                       for s in scenes}
            for future in as_completed(futures):
                outcome = future.result()
                progress.scene_done(outcome)
                outcomes.append(outcome)
    order = {s.source.name: i for i, s in enumerate(scenes)}
    outcomes.sort(key=lambda o: order[o.name])
    write_index(out_root, outcomes)
    return outcomes


def write_index(out_root: str, outcomes: list[Outcome]) -> Path:
    from .report import build_index

    entries = []
    for o in outcomes:
        links = [(Path(r).suffix[1:].upper(), f"{o.name}/{Path(r).name}") for r in o.reports
                 if Path(r).exists()]
        if (Path(out_root) / o.name / "run.h5").exists():
            links.append(("HDF5", f"{o.name}/run.h5"))
        entries.append({"name": o.name, "kind": o.kind, "title": o.title, "status": o.status,
                        "message": o.message, "wall_time_s": o.wall_time_s, "links": links})
    return build_index(Path(out_root), entries)


def batch_status(outcomes: list[Outcome]) -> str:
    return worst_status(*(o.status for o in outcomes))
