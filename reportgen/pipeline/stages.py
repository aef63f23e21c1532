"""config → scene → core → archive → plots → report, for one scene and for a batch.

Every config of a batch is validated before anything runs; one bad config stops
the batch with exit status 2 and nothing written.  Scenes then run in a local
process pool (``--jobs``); a scene that fails does not stop the others.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import os
import re
import sys
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from multiprocessing import get_context
from pathlib import Path
from urllib.parse import quote

from .. import __version__
from ..archive.store import (
    FORMAT_VERSION,
    Identity,
    gallery_entry,
    restamp,
    stored_identity,
    write_archive,
)
from ..errors import UsageError  # noqa: F401 - part of this module's interface
from ..kinds import KINDS, load_scene
from ..scene.base import Scene
from ..scene.config import ConfigError, read_config
from ..scene.gallery import check_headline, chosen_figure
from ..scene.results import STATUSES, worst_status
from ..support.forked import JobProcess, kill_children, reraise_interrupt, run_child, serve
from ..support.fsutil import (
    atomic_write,
    install,
    links_out,
    output_folder,
    output_lock,
    read_back,
    read_json_back,
    remove_stale_temps,
    temp_name,
)
from ..support.layout import (
    MAX_FIGURE_BYTES,
    MAX_MANIFEST_BYTES,
    collect_configs,
    drawn_svg_figures,
    printable,
    report_stamp,
    scene_name,
)
from ..support.svgsafe import svg_safe


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
    #: the stages that ran: simulate, restamp, report (none: everything was current)
    stages: list[str] = field(default_factory=list)
    #: seconds per stage that ran (simulate, restamp, figures, html, pdf)
    stage_s: dict[str, float] = field(default_factory=dict)
    #: the scene failed on bad input found only when it ran: exit status 2, like validate's
    config_error: bool = False

    @property
    def ok(self) -> bool:
        return self.status == "ok"


def validate_all(paths: list[Path], time_limit: float | None = None,
                 stopped: list[Outcome] | None = None) -> list[Scene]:
    """Validate every config and build its models (so a method that cannot integrate the
    system is caught before anything runs); one ConfigError listing every problem of
    every file.

    ``time_limit``: seconds of CPU time each config's validation may take (a formula's
    symbolic work grows fast with its degree: a Lagrangian of degree 32 took minutes;
    enforced by an alarm, in the main thread only).  A config over it is a failed :class:`Outcome`
    appended to ``stopped`` (a run's scene stopped by its limit), or, without
    ``stopped``, a problem."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        time_limit = None
    scenes, problems = [], []
    for path in paths:
        try:
            with _alarm(time_limit, cpu=True):
                scene = load_scene(read_config(path))
                scene.build_models()
            scenes.append(scene)
        except ConfigError as exc:
            problems.extend(exc.problems)
        except _TimeLimit:
            message = _time_limit_message(time_limit, "while validating it (building its "
                                          "model: its formulas' symbolic work, compiling)")
            if stopped is None:
                problems.append(f"{printable(str(path))}: {message}")
            else:
                stopped.append(Outcome(name=Path(path).stem, status="failed", message=message))
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


#: a report stamp is a line of JSON: a larger file is not one this reportgen wrote
MAX_STAMP_BYTES = 1_000_000


def _report_current(folder: Path, identity: Identity, formats, scene: Scene) -> bool:
    """Whether every wanted report was rendered from this very archive content."""
    stamp = read_json_back(report_stamp(folder), MAX_STAMP_BYTES)
    if not (isinstance(stamp, dict) and isinstance(stamp.get("formats", ()), list)):
        return False  # not a stamp this reportgen wrote: render again
    return (stamp.get("archive") == _archive_stamp(identity, scene)
            and all((folder / f"report.{f}").exists() and f in stamp.get("formats", ())
                    for f in formats))


def _archive_stamp(identity: Identity, scene: Scene) -> str:
    """What a scene's reports were rendered from: the archive's content and the code and
    templates that render its kind (an updated checkout renders again)."""
    return (f"{identity.physics_key}:{identity.config_sha256}:{identity.reportgen_version}:"
            f"{scene.report_code()}")


def run_scene(config_path: str, out_root: str, force: bool = False,
              formats: tuple[str, ...] | None = None,
              progress: Callable[[float], None] | None = None, draw_jobs: int = 1,
              pdf_worker=None, sweep_submit=None) -> Outcome:
    """Run one scene's stages, each only if its inputs changed.  Never raises: failures
    come back in the Outcome.

    simulate  keyed by the physics key (validated, preset-resolved physics + version);
              a config edit that leaves it unchanged (title, [report]) only re-stamps the
              archive with the new config text, every array keeping its bytes
    figures   keyed by the physics key, the chosen sections and the version
    report    HTML/PDF from the archive and the figures, when either changed

    ``pdf_worker`` (a :class:`reportgen.rendering.pdf.PdfWorker`, owned by the caller) renders
    the PDF; without one, a scene drawing with ``draw_jobs > 1`` starts its own.
    ``sweep_submit``: where a sweep's member blocks run (:data:`reportgen.scene.sweep.Submit`;
    default: here).
    """
    path = Path(config_path)
    outcome = Outcome(name=path.stem)
    folder = Path(out_root) / path.stem
    outcome.folder = str(folder)
    start = time.perf_counter()
    own_worker = helper = None
    writable = False  # whether the scene's folder may take an error.log
    try:
        scene_name(path)  # a name leading out of --out: a ConfigError, nothing written
        escaping = links_out(folder, Path(out_root))
        if escaping:
            outcome.status = "failed"
            outcome.message = (f"{printable(str(escaping[0]))} is a symbolic link leading "
                               f"outside {printable(str(out_root))}: not followed, scene "
                               "skipped (remove the link)")
            return outcome
        writable = True
        scene = load_scene(read_config(path))
        outcome.kind, outcome.title = scene.kind, scene.title
        wanted = _formats(scene, formats)
        if pdf_worker is None and draw_jobs > 1 and "pdf" in wanted:
            from ..rendering.pdf import PdfWorker

            pdf_worker = own_worker = PdfWorker()  # imports WeasyPrint while this simulates
        remove_stale_temps(folder)
        archive = folder / "run.h5"
        stored = stored_identity(archive) if archive.exists() else None
        key = scene.physics_key()
        if (force or stored is None or stored.physics_key != key
                or stored.format_version < FORMAT_VERSION):
            if draw_jobs > 1:
                from ..rendering.report import FigureHelper

                helper = FigureHelper()  # warms up its drawing while this simulates
            t0 = time.perf_counter()
            simulate_scene(scene, folder, progress, sweep_submit, start=start, key=key)
            outcome.stages.append("simulate")
            outcome.stage_s["simulate"] = time.perf_counter() - t0
        elif stored.config_sha256 != scene.source.sha256:
            t0 = time.perf_counter()
            restamp(archive, title=scene.title, config_text=scene.source.text,
                    config_sha256=scene.source.sha256, resolved_config=scene.resolved_config())
            outcome.stages.append("restamp")
            outcome.stage_s["restamp"] = time.perf_counter() - t0
        identity = stored_identity(archive)
        if force or not _report_current(folder, identity, wanted, scene):
            from ..rendering.report import build_report  # matplotlib and jinja2 only when drawing

            build_report(archive, formats=wanted, force_figures=force, timings=outcome.stage_s,
                         jobs=draw_jobs, pdf_worker=pdf_worker, figure_helper=helper)
            atomic_write(report_stamp(folder), json.dumps(
                {"archive": _archive_stamp(identity, scene), "formats": list(wanted)}).encode("utf-8"))
            outcome.stages.append("report")
        outcome.reports = [str(folder / f"report.{f}") for f in wanted]
        outcome.skipped = "simulate" not in outcome.stages
        outcome.status, outcome.message = identity.status, identity.message
        outcome.wall_time_s = (identity.wall_time_s if outcome.skipped
                               else time.perf_counter() - start)
    except ConfigError as exc:  # found only when simulating (e.g. a singular Lagrangian)
        outcome.status, outcome.message = "failed", str(exc)
        outcome.config_error = True
    except Exception as exc:  # noqa: BLE001 - one scene's crash must not stop the batch
        reraise_interrupt(exc)  # a signal inside an extension's import stops the batch
        outcome.status = "failed"
        log = folder / "error.log"
        where = ""
        if writable:
            try:
                folder.mkdir(parents=True, exist_ok=True)
                atomic_write(log, traceback.format_exc().encode("utf-8", "backslashreplace"))
                where = f" (traceback in {log})"
            except OSError:
                pass
        outcome.message = f"{type(exc).__name__}: {exc}{where}"
    except BaseException:  # Ctrl-C, a signal: the helpers go at once, not after their job
        kill_children()
        raise
    finally:
        for worker in (helper, own_worker):
            if worker is not None:
                worker.close()
    return outcome


def simulate_scene(scene: Scene, folder: Path, progress: Callable[[float], None] | None = None,
                   sweep_submit=None, start: float | None = None,
                   key: str | None = None) -> Path:
    """The simulate stage alone: run ``scene`` and write ``folder/run.h5`` (atomically),
    whatever is there; returns the archive's path.  ``start``: when the scene's run began
    (its archived wall time counts from it; default now); ``key``: its physics key, if
    the caller has it already."""
    start = time.perf_counter() if start is None else start
    archive = Path(folder) / "run.h5"
    results = (scene.simulate_sweep(folder, progress, submit=sweep_submit)
               if scene.sweep is not None else scene.simulate(progress=progress))
    for name, run in results.runs.items():
        if run.status != "ok":
            results.flag(run.status, f"run '{name}': {run.message}")
    results.wall_time_s = time.perf_counter() - start
    key = key or scene.physics_key()
    write_archive(archive, kind=scene.kind, title=scene.title, scene=scene.source.name,
                  config_text=scene.source.text, config_sha256=scene.source.sha256,
                  results=results, resolved_config=scene.resolved_config(),
                  physics_key=key, schema=scene.results_schema(),
                  code={"simulation": scene.simulation_code()})
    del results  # the report reads the archive; a 10⁷-member family is ~570 MiB
    if scene.sweep is not None:  # its finished blocks are in the archive now
        from ..scene.sweep import discard_partial

        discard_partial(folder, key)
    return archive


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
        if not outcome.skipped:
            note = f"{outcome.wall_time_s:.1f} s" if outcome.wall_time_s is not None else ""
        elif "report" in outcome.stages:
            note = "physics unchanged: report re-rendered from the archive"
        else:
            note = "up to date"
        line = f"[{self.done}/{self.total}] {outcome.name:<28} {outcome.status:<8} {note}"
        if outcome.message and not outcome.ok:
            line += f"\n      {outcome.message}"
        self._clear()
        print(printable(line), file=self.stream, flush=True)

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
              scheduler: str | None = None, time_limit: float | None = None,
              stream=None, pdf_worker=None, in_process_limit: bool = False) -> list[Outcome]:
    """Validate all, run all, write ``index.html``.

    Scenes run in-process (``jobs == 1``), in a local pool of ``jobs`` processes,
    or on the Dask distributed scheduler at ``scheduler``.  ``pdf_worker``: a
    :class:`reportgen.rendering.pdf.PdfWorker` the caller started (``reportgen run`` does, on the
    hint of :func:`reportgen.rendering.pdf.edit_loop_worker`, before its heavy imports) and closes;
    it renders the PDF of a single scene to do.  ``time_limit``: seconds per scene (None:
    none); with ``in_process_limit`` (``reportgen run``'s default limit) a single scene to
    do still runs in this process, stopped by an alarm.
    """
    stopped: list[Outcome] = []  # over the time limit while validating
    scenes = validate_all(collect_configs(paths), time_limit, stopped)
    progress = Progress(len(scenes) + len(stopped), stream)
    root = output_folder(out_root)
    with output_lock(root, stream=progress.stream):  # one run at a time on a folder
        for outcome in stopped:
            progress.scene_done(outcome)
        if scheduler:
            outcomes = _run_on_dask(scenes, out_root, force, formats, scheduler, progress,
                                    time_limit)
        else:
            outcomes = _run_locally(scenes, out_root, force, formats, jobs, progress,
                                    time_limit, pdf_worker, in_process_limit)
        order = {s.source.name: i for i, s in enumerate(scenes)}
        outcomes.sort(key=lambda o: order[o.name])
        outcomes = stopped + outcomes
        try:
            write_index(out_root, outcomes)
        except OSError as exc:
            where = exc.filename or root / "index.html"
            raise UsageError(f"{printable(str(where))}: cannot write the index "
                             f"({exc.strerror or exc})") from None
    return outcomes


def _split_current(scenes, out_root, force, formats, progress) -> tuple[list[Outcome], list]:
    """(outcomes of the scenes whose archive and reports are current, the scenes to run);
    the current ones are reported to ``progress`` at once.  ``force``: none is current."""
    outcomes, todo = [], []
    for scene in scenes:
        current = None if force else _up_to_date(scene, out_root, formats)
        if current is not None:
            progress.scene_done(current)
            outcomes.append(current)
        else:
            todo.append(scene)
    return outcomes, todo


def _run_locally(scenes, out_root, force, formats, jobs, progress,
                 time_limit: float | None = None, pdf_worker=None,
                 in_process_limit: bool = False) -> list[Outcome]:
    """Scenes whose archive and reports are current are answered here, without a worker.

    One scene left to do (the edit loop's case) runs in this process when no time limit
    is set, or only the default one (``in_process_limit``: stopped by an alarm); its PDF
    is rendered by ``pdf_worker`` if one was started.  More run in forked
    processes, at most ``jobs`` at once, forked after the heavy libraries are imported
    here (:func:`_preload`), so no scene pays for them.
    """
    outcomes, todo = _split_current(scenes, out_root, force, formats, progress)
    if pdf_worker is not None and pdf_worker.speculative and len(todo) != 1:
        pdf_worker.close()  # started on a hint that did not hold: stop it at once
    if not todo:
        return outcomes
    requested = jobs
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(todo)))
    import threading

    # the default limit (``in_process_limit``) keeps a single scene in this process, stopped
    # by an alarm; a limit the user set runs scenes in workers, killed when over it
    in_process = jobs == 1 and (time_limit is None or (
        in_process_limit and len(todo) == 1
        and threading.current_thread() is threading.main_thread()))
    if in_process:
        # the edit loop's one scene: its figures are drawn by as many processes as allowed
        draw_jobs = max(1, requested or os.cpu_count() or 1) if len(todo) == 1 else 1
        for scene in todo:
            try:
                with _alarm(time_limit):
                    outcome = run_scene(str(scene.source.path), out_root, force, formats,
                                        progress=progress.within(scene.source.name),
                                        draw_jobs=draw_jobs,
                                        pdf_worker=pdf_worker if len(todo) == 1 else None)
            except _TimeLimit:
                outcome = Outcome(name=scene.source.name, kind=scene.kind, title=scene.title,
                                  status="failed", message=_time_limit_message(time_limit))
            progress.scene_done(outcome)
            outcomes.append(outcome)
        return outcomes
    _preload(todo, formats)
    return outcomes + _run_in_processes(_interleave_kinds(todo), out_root, force, formats,
                                        jobs, progress, time_limit)


class _TimeLimit(BaseException):
    """A scene run in this process went over its time limit (raised by SIGALRM)."""


def _time_limit_message(time_limit: float, when: str = "") -> str:
    return (f"time limit of {time_limit:g} s exceeded{' ' + when if when else ''}: the scene "
            "was stopped (--time-limit; 0 for none) and any earlier archive kept")


class _alarm:
    """Raise :class:`_TimeLimit` in the main thread after ``seconds`` (None: never) of wall
    time, or of this process's CPU time with ``cpu`` (validation: its symbolic work is
    CPU-bound, and a busy machine must not make a quick config fail).  The scene's
    archive and reports are renamed into place only when complete, so stopping it
    anywhere keeps the earlier ones; compiled code is stopped when it returns to Python;
    an import in progress is let finish (a half-done one would stay broken)."""

    def __init__(self, seconds: float | None, cpu: bool = False):
        import signal

        self.seconds = seconds
        self.timer, self.signal = ((signal.ITIMER_PROF, signal.SIGPROF) if cpu
                                   else (signal.ITIMER_REAL, signal.SIGALRM))

    def __enter__(self):
        import signal

        if self.seconds is not None:
            def expired(signum, frame):
                if _importing():
                    signal.setitimer(self.timer, 0.05)
                    return
                raise _TimeLimit

            self.previous = signal.signal(self.signal, expired)
            signal.setitimer(self.timer, self.seconds)
        return self

    def __exit__(self, *exc):
        import signal

        if self.seconds is not None:
            signal.setitimer(self.timer, 0)
            signal.signal(self.signal, self.previous)
        return False


def _importing() -> bool:
    """Whether a module is being imported in this process (its spec says so while its code
    runs): an exception raised there would leave it half-initialised in ``sys.modules``
    for every later scene of a long-lived process (``watch``, the API)."""
    return any(getattr(getattr(module, "__spec__", None), "_initializing", False)
               for module in list(sys.modules.values()))


def _interleave_kinds(scenes: list[Scene]) -> list[Scene]:
    """The scenes round-robin over their kinds (first of each kind, then second, ...).

    Scenes running at the same time are then of different kinds, so on a cold numba
    cache two workers do not compile the same kind's functions at once, and a kind's
    later scenes find its code compiled."""
    by_kind: dict[str, list[Scene]] = {}
    for scene in scenes:
        by_kind.setdefault(scene.kind, []).append(scene)
    queues = sorted(by_kind.values(), key=len, reverse=True)
    order = []
    for i in range(max(len(q) for q in queues)):
        order.extend(q[i] for q in queues if i < len(q))
    return order


def _preload(scenes, formats) -> None:
    """Import, before forking, what every scene process would otherwise import for itself
    (numba and the integrators, scipy, matplotlib with the figure style, WeasyPrint) and
    load the compiled drivers: forked children share these pages instead of spending
    seconds each on imports, and two children never compile the same driver at once.

    On a cold numba cache the drivers take seconds to compile: two forked helpers compile
    them into the disk cache (one the written-out DOP853 and the splitting driver, the other
    the generic explicit, fixed-step and implicit ones: about equal compile times) while
    this process imports the rest, then this process loads them from the cache."""
    import importlib

    import reportgen.core.integrators  # noqa: F401 - numba, before the helpers fork

    ctx = get_context("fork")
    groups = (("dop853", "verlet"), ("rk45", "rk4", "gauss4"))
    from ..core.integrators.driver import warm_up

    helpers = [ctx.Process(target=run_child, args=(os.getpid(), warm_up, group), daemon=True)
               for group in groups]
    for helper in helpers:
        helper.start()
    modules = ["reportgen.core.study", "scipy.integrate", "scipy.special", "scipy.optimize",
               "reportgen.rendering.report", "reportgen.rendering.plots.style",
               "reportgen.rendering.plots.common",
               "matplotlib.backends.backend_svg"]
    if any("pdf" in _formats(scene, formats) for scene in scenes):
        modules.append("weasyprint")
    for name in modules:
        try:
            importlib.import_module(name)
        except ImportError as exc:  # a missing optional library fails in the scene, with its
            reraise_interrupt(exc)  # message; a signal inside the import stops here
    for helper in helpers:
        helper.join()
    for group in groups:
        warm_up(group)  # from the disk cache now (compiled here if a helper failed)


def _scene_worker(jobs, results, out_root, force, formats) -> None:
    """A scene worker's loop: each config path received, run; its Outcome sent back."""
    serve(jobs, results, lambda path: run_scene(path, out_root, force, formats))


class _Worker(JobProcess):
    """A forked scene process that runs scenes one after another.

    What a scene process pays for on first use stays for the next scene: the kind's
    modules and compiled callbacks, fonts, matplotlib's mathtext parser and font lookups,
    WeasyPrint's first document, SymPy.  Forking once per scene paid it per scene."""

    def __init__(self, out_root, force, formats, others: list[_Worker]):
        super().__init__(_scene_worker, out_root, force, formats,
                         siblings=[c for w in others for c in (w.jobs, w.results)])
        self.scene: Scene | None = None  # the scene it runs now
        self.kind = ""  # the kind of the last scene it ran
        self.started = 0.0

    def submit(self, scene: Scene) -> None:
        self.jobs.send(str(scene.source.path))
        self.scene, self.kind, self.started = scene, scene.kind, time.monotonic()


def _next_scene(pending: list[Scene], worker: _Worker, running_kinds: set[str]) -> Scene:
    """The scene a free worker takes: one more of its last kind (its code is loaded there),
    else the first of a kind no other worker is running (on a cold numba cache two
    workers then never compile the same kind at once), else the first."""
    for rule in (lambda s: s.kind == worker.kind, lambda s: s.kind not in running_kinds):
        for i, scene in enumerate(pending):
            if rule(scene):
                return pending.pop(i)
    return pending.pop(0)


def _run_in_processes(scenes, out_root, force, formats, jobs, progress, time_limit):
    """The scenes on at most ``jobs`` worker processes, each running scene after scene.

    A scene over ``time_limit`` seconds is stopped by killing its worker (a fresh one,
    forked from this process, takes the next scene); so is nothing else.  Killing is
    safe: archives and reports are renamed into place only when complete.
    """
    from multiprocessing.connection import wait

    pending = list(scenes)
    workers: list[_Worker] = []
    outcomes = []

    def failed(scene: Scene, message: str) -> Outcome:
        return Outcome(name=scene.source.name, kind=scene.kind, title=scene.title,
                       status="failed", message=message)

    try:
        while True:
            for worker in [w for w in workers if w.scene is None]:
                if pending:
                    running = {w.scene.kind for w in workers if w.scene is not None}
                    worker.submit(_next_scene(pending, worker, running))
                else:
                    worker.stop(timeout=10)
                    workers.remove(worker)
            while pending and len(workers) < jobs:
                worker = _Worker(out_root, force, formats, workers)
                workers.append(worker)
                worker.submit(_next_scene(pending, worker,
                                          {w.scene.kind for w in workers if w.scene}))
            if not workers:
                return outcomes
            # sleep until a result or a worker's exit (or the next time-limit check)
            wait([w.results for w in workers] + [w.proc.sentinel for w in workers],
                 timeout=1.0 if time_limit is not None else None)
            for worker in list(workers):
                scene, outcome = worker.scene, None
                if worker.results.poll():
                    try:
                        outcome = worker.results.recv()
                    except (EOFError, OSError):
                        outcome = failed(scene, "worker process ended without a result")
                        worker.stop(graceful=False)
                        workers.remove(worker)
                    worker.scene = None
                elif not worker.proc.is_alive():
                    outcome = failed(scene, f"worker process died (exit code "
                                            f"{worker.proc.exitcode})")
                    worker.stop(graceful=False)
                    workers.remove(worker)
                elif time_limit is not None and time.monotonic() - worker.started > time_limit:
                    outcome = failed(scene, _time_limit_message(time_limit))
                    worker.stop(graceful=False)
                    workers.remove(worker)
                if outcome is not None:
                    progress.scene_done(outcome)
                    outcomes.append(outcome)
    finally:
        for worker in workers:  # an interrupt: stop what still runs
            worker.stop(graceful=False)


def run_scene_portable(config_text: str, name: str, formats: tuple[str, ...] | None,
                       label: str) -> tuple[Outcome, dict[str, bytes]]:
    """Run one scene in a private temporary folder; return its outcome and every file it wrote.

    This is the task a Dask worker runs: it needs no filesystem shared with the
    submitting process, which installs the returned files itself.
    """
    import tempfile

    with tempfile.TemporaryDirectory(prefix="reportgen-") as tmp:
        cfg = Path(tmp) / f"{name}.toml"
        cfg.write_text(config_text, encoding="utf-8")
        outcome = run_scene(str(cfg), str(Path(tmp) / "out"), True, formats)
        outcome.message = outcome.message.replace(str(cfg), label)
        folder = Path(tmp) / "out" / name
        files = {str(p.relative_to(folder)): p.read_bytes()
                 for p in sorted(folder.rglob("*")) if p.is_file()}
    return outcome, files


def _install_files(out_root: str, outcome: Outcome, files: dict[str, bytes]) -> Outcome:
    """Write a worker's files into ``out_root/<name>/`` atomically, archive first."""
    folder = Path(out_root) / scene_name(Path(outcome.name + ".toml"))
    escaping = links_out(folder, Path(out_root))
    if escaping:
        outcome.status = "failed"
        outcome.message = (f"{printable(str(escaping[0]))} is a symbolic link leading outside "
                           f"{printable(str(out_root))}: not followed, scene skipped")
        return outcome
    folder.mkdir(parents=True, exist_ok=True)
    if "run.h5" in files:
        tmp = temp_name(folder / "run.h5")
        tmp.write_bytes(files["run.h5"])
        install(tmp, folder / "run.h5")
    for rel, data in files.items():
        if rel != "run.h5" and ".." not in Path(rel).parts and not Path(rel).is_absolute():
            (folder / rel).parent.mkdir(parents=True, exist_ok=True)
            atomic_write(folder / rel, data)
    outcome.folder = str(folder)
    outcome.reports = [str(folder / Path(r).name) for r in outcome.reports]
    return outcome


def _up_to_date(scene: Scene, out_root: str, formats) -> Outcome | None:
    """The outcome of a scene whose archive and reports are current, else None."""
    folder = Path(out_root) / scene.source.name
    stored = stored_identity(folder / "run.h5") if (folder / "run.h5").exists() else None
    wanted = _formats(scene, formats)
    if (stored is None or stored.physics_key != scene.physics_key()
            or stored.config_sha256 != scene.source.sha256
            or not _report_current(folder, stored, wanted, scene)):
        return None
    return Outcome(name=scene.source.name, kind=scene.kind, title=scene.title,
                   status=stored.status, message=stored.message, skipped=True,
                   folder=str(folder), wall_time_s=stored.wall_time_s,
                   reports=[str(folder / f"report.{f}") for f in wanted])


def _refused(scheduler: str) -> None:
    """A UsageError at once when nothing listens at a tcp:// scheduler's address (a port
    that refuses the connection), rather than after the client's 10 s of retrying."""
    import socket
    from urllib.parse import urlsplit

    try:
        where = urlsplit(scheduler)
        host, port = where.hostname, where.port
    except ValueError:
        return
    if where.scheme != "tcp" or not host or port is None:
        return  # another protocol, or no port: the client's own checks
    try:
        socket.create_connection((host, port), timeout=10.0).close()
    except ConnectionRefusedError as exc:
        raise UsageError(f"--scheduler {scheduler}: cannot connect ({exc.strerror})") from None
    except OSError:
        return  # unreachable or slow: the client retries and says so


#: seconds a scheduler has to answer the handshake and an identity request
HANDSHAKE_S = 10.0


def _handshake(scheduler: str, seconds: float = HANDSHAKE_S) -> None:
    """A UsageError unless a Dask scheduler answers at ``scheduler`` within ``seconds``:
    distributed's own comm (its handshake), then the scheduler's "identity" request.  A
    listener that accepts and never answers hung ``run`` past 300 s; one that answers
    with something else gave exit 1 (a MemoryError from a length field, an unknown
    scheme, TLS without a context)."""
    import asyncio

    from distributed.comm import connect

    async def identity():
        comm = await connect(scheduler, timeout=seconds)
        try:
            await comm.write({"op": "identity", "reply": True})
            return await comm.read()
        finally:
            comm.abort()

    try:
        reply = asyncio.run(asyncio.wait_for(identity(), seconds))
    except TimeoutError:
        raise UsageError(f"--scheduler {scheduler}: no answer from a Dask scheduler within "
                         f"{seconds:g} s") from None
    except Exception as exc:  # noqa: BLE001 - whatever the peer is, it is not a scheduler
        raise UsageError(f"--scheduler {scheduler}: not a Dask scheduler "
                         f"({type(exc).__name__}: {printable(str(exc))[:200]})") from None
    if not (isinstance(reply, dict) and reply.get("type") == "Scheduler"):
        raise UsageError(f"--scheduler {scheduler}: not a Dask scheduler (it answered "
                         f"{printable(repr(reply))[:120]})")


def _run_on_dask(scenes, out_root, force, formats, scheduler, progress,
                 time_limit: float | None = None) -> list[Outcome]:
    try:
        from distributed import Client
        from distributed import as_completed as dask_completed
    except ImportError:
        raise UsageError("--scheduler needs Dask distributed: pip install 'reportgen[dask]'") \
            from None
    outcomes, todo = _split_current(scenes, out_root, force, formats, progress)
    if not todo:
        return outcomes
    _refused(scheduler)
    _handshake(scheduler)
    try:
        client = Client(scheduler, timeout="10s")
    except OSError as exc:
        raise UsageError(f"--scheduler {scheduler}: cannot connect ({exc})") from None
    with client:
        sweeps = [s for s in todo if s.sweep is not None]
        todo = [s for s in todo if s.sweep is None]
        futures = [client.submit(run_scene_portable, s.source.text, s.source.name, formats,
                                 str(s.source.path), pure=False, key=f"reportgen-{s.source.name}-"
                                 f"{s.source.sha256[:12]}-{os.getpid()}")
                   for s in todo]
        for scene in sweeps:  # here, its member blocks spread over the cluster
            outcome = run_scene(str(scene.source.path), out_root, force, formats,
                                progress=progress.within(scene.source.name),
                                sweep_submit=DaskBlocks(client, scene, time_limit))
            progress.scene_done(outcome)
            outcomes.append(outcome)
        deadline = None if time_limit is None else time.monotonic() + time_limit * len(todo)
        try:
            for future in dask_completed(futures, timeout=None if deadline is None
                                         else max(1.0, deadline - time.monotonic())):
                try:
                    outcome, files = future.result()
                    outcome = _install_files(out_root, outcome, files)
                except Exception as exc:  # noqa: BLE001 - a lost worker fails one scene only
                    name = todo[futures.index(future)].source.name
                    outcome = Outcome(name=name, status="failed",
                                      message=f"Dask task failed: {type(exc).__name__}: {exc}")
                progress.scene_done(outcome)
                outcomes.append(outcome)
        except TimeoutError:
            done = {o.name for o in outcomes}
            for scene, future in zip(todo, futures, strict=True):
                if scene.source.name not in done:
                    future.cancel()
                    outcome = Outcome(name=scene.source.name, status="failed",
                                      message="time limit exceeded on the Dask cluster")
                    progress.scene_done(outcome)
                    outcomes.append(outcome)
    return outcomes


def sweep_block_portable(config_text: str, lo: int, hi: int, values: dict) -> dict:
    """Members ``lo:hi`` of the sweep of the config ``config_text``: the task a Dask
    worker runs for one block (:meth:`reportgen.scene.simulation.Simulation.sweep_block`),
    sent back as flat arrays (:func:`reportgen.scene.sweep.block_arrays`: text as codes)."""
    from ..scene.sweep import block_arrays

    return block_arrays(_sweep_scene(config_text).sweep_block(lo, hi, values))


@functools.lru_cache(maxsize=4)
def _sweep_scene(config_text: str) -> Scene:
    """The scene of a sweep's config, loaded once per worker process, not once a block."""
    from ..scene.config import parse_config_text

    return load_scene(parse_config_text(config_text))


#: blocks of a sweep in flight on a Dask cluster per worker thread: one running, one
#: waiting beside it so a thread never idles while the client saves a block.  The rest
#: wait in this process as (lo, hi) only, so neither the client, the scheduler nor a
#: worker ever holds more than this many blocks.
SWEEP_BLOCKS_PER_THREAD = 2
#: times one block is sent before its failure ends the sweep (Dask itself re-runs the
#: tasks of a lost worker; this covers a task that still fails, e.g. KilledWorker
#: after ``distributed.scheduler.allowed-failures`` losses)
SWEEP_BLOCK_TRIES = 3
#: seconds a sweep waits while the cluster has no worker before it gives up
SWEEP_NO_WORKER_S = 300.0
#: seconds between looks at the clock and at the cluster while no block finishes
SWEEP_POLL_S = 2.0


class DaskBlocks:
    """A sweep's ``submit`` (:data:`reportgen.scene.sweep.Submit`) on a Dask cluster: a
    bounded window of member blocks in flight (:data:`SWEEP_BLOCKS_PER_THREAD` per
    worker thread), refilled as each finishes; each result handed back at once and its
    future released, so the cluster forgets it.

    A block whose task fails (its worker lost more often than the scheduler allows, or
    an error) is sent again, up to :data:`SWEEP_BLOCK_TRIES` times; then the sweep stops
    with a message naming the block and the error.  It also stops, never hangs, when
    ``time_limit`` seconds pass or the cluster has had no worker for
    :data:`SWEEP_NO_WORKER_S` seconds.  Whatever it stops, the finished blocks are on disk
    and a rerun resumes them.  ``max_in_flight``: the most blocks it had out at once."""

    def __init__(self, client, scene: Scene, time_limit: float | None = None):
        self.client, self.scene, self.time_limit = client, scene, time_limit
        self.max_in_flight = 0
        self.resent = 0
        self._window, self._window_at = 0, -math.inf

    def window(self) -> int:
        """Blocks in flight at most: per worker thread, looked up every few seconds (a
        worker lost or joined changes it)."""
        now = time.monotonic()
        if now - self._window_at > SWEEP_POLL_S:
            threads = sum(self.client.nthreads().values())
            self._window = max(2, SWEEP_BLOCKS_PER_THREAD * threads)
            self._window_at = now
        return self._window

    def _submit(self, lo: int, hi: int, values: dict, tries: int):
        import numpy as np

        scene = self.scene
        key = (f"reportgen-{scene.source.name}-{lo}-{hi}-{scene.source.sha256[:12]}-"
               f"{os.getpid()}" + (f"-try{tries}" if tries > 1 else ""))
        return self.client.submit(sweep_block_portable, scene.source.text, lo, hi,
                                  {p: np.array(v) for p, v in values.items()}, pure=False,
                                  key=key)

    def __call__(self, chunks):
        from distributed import wait

        chunks = iter(chunks)
        deadline = None if not self.time_limit else time.monotonic() + self.time_limit
        pending: dict = {}  # future -> (b, lo, hi, values, tries)
        no_worker_since = None
        try:
            more = True
            while True:
                while more and len(pending) < self.window():
                    item = next(chunks, None)
                    if item is None:
                        more = False
                        break
                    b, lo, hi, values = item
                    pending[self._submit(lo, hi, values, 1)] = (b, lo, hi, values, 1)
                    self.max_in_flight = max(self.max_in_flight, len(pending))
                if not pending:
                    return
                try:
                    done = wait(list(pending), timeout=SWEEP_POLL_S,
                                return_when="FIRST_COMPLETED").done
                except TimeoutError:
                    done = set()
                finished = []
                for future in done:
                    b, lo, hi, values, tries = pending.pop(future)
                    if future.status == "finished":
                        finished.append((b, future.result()))
                    else:
                        self._again(future, b, lo, hi, values, tries, pending)
                    future.release()
                for item in finished:
                    yield item
                if deadline is not None and time.monotonic() > deadline:
                    raise TimeoutError(
                        f"time limit of {self.time_limit:g} s exceeded on the Dask cluster with "
                        f"{len(pending)} blocks still running: the sweep was stopped "
                        "(--time-limit; 0 for none); its finished blocks are kept and a "
                        "rerun resumes them")
                if finished:
                    no_worker_since = None
                elif not self.client.nthreads():
                    no_worker_since = no_worker_since or time.monotonic()
                    if time.monotonic() - no_worker_since > SWEEP_NO_WORKER_S:
                        raise RuntimeError(
                            f"the Dask cluster has had no worker for {SWEEP_NO_WORKER_S:g} s: "
                            "the sweep was stopped; its finished blocks are kept and a "
                            "rerun resumes them")
                else:
                    no_worker_since = None
        finally:
            if pending:  # stopped early: the cluster drops what still runs
                try:
                    self.client.cancel(list(pending))
                except Exception:  # noqa: BLE001 - a client already closed: nothing to drop
                    pass

    def _again(self, future, b, lo, hi, values, tries, pending) -> None:
        """Send a failed block again, or stop the sweep naming it."""
        try:
            error = future.exception(timeout=SWEEP_POLL_S)
            why = f"{type(error).__name__}: {error}"
        except Exception as exc:  # noqa: BLE001 - cancelled: the scheduler dropped it
            why = f"{type(exc).__name__}: {exc}" if str(exc) else type(exc).__name__
        if tries >= SWEEP_BLOCK_TRIES:
            raise RuntimeError(f"members {lo}:{hi} of the sweep failed on the Dask cluster "
                               f"{tries} times, last: {why[:300]}; the finished blocks are "
                               "kept and a rerun resumes them")
        self.resent += 1
        pending[self._submit(lo, hi, values, tries + 1)] = (b, lo, hi, values, tries + 1)


def write_index(out_root: str, outcomes: list[Outcome] = ()) -> Path:
    """``index.html``: a gallery of every scene archive in ``out_root`` (not only this
    batch's), plus the scenes of this batch that failed before writing one; the cards
    grouped by kind (in the kinds' order), by title within a kind, each with its kind's
    signature figure (:attr:`~reportgen.scene.report.Report.gallery_figures`)."""
    from ..rendering.report import build_index  # matplotlib and jinja2 only when drawing

    root = Path(out_root)
    entries = []
    thumbs = _read_cache(root / THUMB_CACHE)
    checked: dict[str, dict] = {}
    for archive, entry in _gallery_entries(root).items():
        folder = archive.parent
        name = folder.name
        links = [(fmt.upper(), gallery_href(name, f"report.{fmt}")) for fmt in ("html", "pdf")
                 if (folder / f"report.{fmt}").exists()]
        links.append(("HDF5", gallery_href(name, "run.h5")))
        entries.append({**entry, "name": name, "links": links,
                        **_gallery_figure(folder, entry["kind"], thumbs, checked)})
    if checked != thumbs:
        try:
            atomic_write(root / THUMB_CACHE, json.dumps(checked, sort_keys=True).encode("utf-8"))
        except OSError:
            pass  # a cache that cannot be written costs time, not correctness
    seen = {e["name"] for e in entries}
    for o in outcomes:
        if o.name not in seen and not o.ok:
            entries.append({"name": o.name, "kind": o.kind, "title": o.title,
                            "status": o.status, "message": o.message, "wall_time_s": None,
                            "headline": "", "links": [], "thumbnail": None,
                            "thumbnail_alt": "", "wide": False})
    return build_index(root, gallery_groups(entries))


def gallery_groups(entries: list[dict]) -> list[dict]:
    """The gallery's cards grouped by kind: a group per kind present, in the kinds' order
    (``reportgen kinds``; a kind this reportgen does not know last), each with its
    heading and its cards sorted by title, then name."""
    groups: dict[str, list[dict]] = {}
    for e in entries:
        groups.setdefault(e.get("kind") or "", []).append(e)
    rank = {kind: i for i, kind in enumerate(KINDS)}
    ordered = sorted(groups.items(), key=lambda kv: (rank.get(kv[0], len(rank)), kv[0]))
    return [{"kind": kind, "name": _kind_heading(kind),
             # the heading's anchor: a kind's id, or a number for a name read from a file
             "anchor": kind if kind in rank else f"other-{i}",
             "entries": sorted(cards, key=lambda e: ((e.get("title") or e["name"]).casefold(),
                                                     e["name"]))}
            for i, (kind, cards) in enumerate(ordered)]


def _kind_heading(kind: str) -> str:
    """A kind's human name: its report's ``gallery_name``, else the kind's
    ``name_in_words``, else its id in words."""
    cls = KINDS.get(kind)
    name = (getattr(cls, "gallery_name", "") or getattr(cls, "name_in_words", "")
            if cls is not None else "")
    return name or (kind.replace("_", " ").capitalize() if kind else "Unknown kind")


def _gallery_headline(data) -> str:
    """The card's line: the kind's ``gallery_headline`` of the light archive (a kind
    this reportgen does not know: the checks' default)."""
    cls = KINDS.get(data.kind)
    return (cls.gallery_headline if cls is not None and hasattr(cls, "gallery_headline")
            else check_headline)(data)


#: the gallery's entry of each archive, kept with the archive's size and time of change:
#: an edit loop's run re-reads only the archive it changed (each read opens the HDF5 file)
GALLERY_CACHE = ".gallery.json"
#: bump when an entry's contents change (the headline's wording, a new key): every
#: cached entry is then read again, as it is after a new reportgen version
GALLERY_FORMAT = 2


def _gallery_entries(root: Path) -> dict[Path, dict]:
    """:func:`reportgen.archive.store.gallery_entry` of every ``*/run.h5`` under ``root``,
    from ``root/.gallery.json`` where an archive is unchanged since it was read (by this
    reportgen version and gallery format)."""
    cache = root / GALLERY_CACHE
    stored = _read_cache(cache)
    fresh, entries = {}, {}
    # the kinds' report code writes the headlines: an edit to it reads every entry again
    # (~0.05 s once per process), as a new reportgen version does
    code = hashlib.sha256("".join(k.report_code() for k in KINDS.values())
                          .encode("utf-8")).hexdigest()[:16]
    for archive in sorted(root.glob("*/run.h5")):
        try:
            st = archive.stat()
        except OSError:
            continue
        stamp = [st.st_mtime_ns, st.st_size, st.st_ino, GALLERY_FORMAT, __version__, code]
        name = archive.parent.name
        hit = stored.get(name)
        entry = (hit["entry"] if isinstance(hit, dict) and hit.get("stamp") == stamp
                 and _valid_entry(hit.get("entry"))
                 else gallery_entry(archive, headline=_gallery_headline))
        if entry is None:
            continue
        fresh[name] = {"stamp": stamp, "entry": entry}
        entries[archive] = entry
    if fresh != stored:
        try:
            atomic_write(cache, json.dumps(fresh, sort_keys=True).encode("utf-8"))
        except OSError:
            pass  # a cache that cannot be written costs time, not correctness
    return entries


#: a thumbnail this much wider than tall gets a card two columns wide (Fig. 4.3's
#: three loci side by side would be a strip of 17em by 4em in one column)
WIDE_ASPECT = 2.2


#: the gallery's memory of which thumbnails passed the sanitizer, by file identity: each
#: write of index.html sanitized every scene's thumbnail again (0.3 s for 58 scenes, in
#: every edit-loop turn).  A forged entry can only show a figure as an ``<img>``, in which
#: a browser runs no script and loads nothing
THUMB_CACHE = ".gallery-thumbs.json"


def _read_cache(path: Path) -> dict:
    """A JSON cache of the output folder, read as untrusted: {} when absent or not one."""
    stored = read_json_back(path, MAX_MANIFEST_BYTES)
    return stored if isinstance(stored, dict) else {}


def _gallery_figure(folder: Path, kind: str, thumbs: dict | None = None,
                    checked: dict | None = None) -> dict:
    """The card's thumbnail: the kind's signature figure (the first of its report's
    ``gallery_figures`` that this scene drew, else the report's first figure) as a link
    relative to the output folder, its caption as the image's alt text, and whether it
    is wide; from the figures' manifest, validated
    (:func:`reportgen.support.layout.figure_manifest`).  A figure the sanitizer would
    change is not shown; its verdict is taken from ``thumbs`` (the last write's) while the
    file is unchanged, and put in ``checked``."""
    none = {"thumbnail": None, "thumbnail_alt": "", "wide": False}
    figures = drawn_svg_figures(folder)
    cls = KINDS.get(kind)
    i = chosen_figure([str(fig.get("id", "")) for fig in figures],
                      tuple(getattr(cls, "gallery_figures", ())))
    if i is None:
        return none
    fig = figures[i]
    path = folder / fig["files"]["svg"]
    try:
        st = path.stat()
        key = [fig["files"]["svg"], st.st_mtime_ns, st.st_size, st.st_ino, __version__]
    except OSError:
        key = None
    hit = (thumbs or {}).get(folder.name)
    if (key is not None and isinstance(hit, dict) and hit.get("key") == key
            and isinstance(hit.get("safe"), bool) and isinstance(hit.get("wide"), bool)):
        safe, wide = hit["safe"], hit["wide"]
    else:
        try:  # the report draws a figure the sanitizer would change again
            svg = read_back(path, MAX_FIGURE_BYTES, follow_links=True)
        except OSError:
            svg = b""
        safe = svg_safe(svg)
        wide = safe and _svg_aspect(svg) >= WIDE_ASPECT
    if key is not None and checked is not None:
        checked[folder.name] = {"key": key, "safe": safe, "wide": wide}
    if not safe:
        return none
    caption = fig.get("caption") if isinstance(fig.get("caption"), str) else ""
    return {"thumbnail": gallery_href(folder.name, fig["files"]["svg"]),
            "thumbnail_alt": caption[:300] or f"figure of {folder.name}",
            "wide": wide}


_SVG_SIZE = re.compile(rb'<svg\b[^>]*?\bwidth="([\d.]+)(?:pt|px)?"[^>]*?\bheight="([\d.]+)'
                       rb'(?:pt|px)?"')


def _svg_aspect(svg: bytes) -> float:
    """Width over height of an SVG figure, from its opening tag (in the first 4 kB); 1
    when it cannot be told."""
    head = svg[:4096]
    found = _SVG_SIZE.search(head)
    try:
        w, h = (float(v) for v in found.groups()) if found else (1.0, 1.0)
    except ValueError:
        return 1.0
    return w / h if h > 0 and math.isfinite(w / h) else 1.0


def gallery_href(name: str, rel: str) -> str:
    """The gallery's link to ``rel`` in the scene folder ``name``: a relative path, each
    segment URL-quoted, so no folder name (``javascript:...``, ``?``, ``#``) can make it a
    scheme or anything but that file (a quoted ``:`` is ``%3A``, and a segment holds no
    ``/``: a relative path whose first segment has no ``:`` never names a scheme)."""
    return "/".join(quote(part, safe="") for part in [name, *rel.split("/")])


#: what a gallery entry holds (kept in ``.gallery.json``): text, and the wall time
_ENTRY_TEXT = ("kind", "title", "status", "message", "headline", "created")


def _valid_entry(entry) -> bool:
    """Whether ``entry`` (read back from ``.gallery.json``) is what
    :func:`reportgen.archive.store.gallery_entry` gives: else the archive is read again."""
    return (isinstance(entry, dict) and {*_ENTRY_TEXT, "wall_time_s"} <= set(entry)
            and all(isinstance(entry[k], str) for k in _ENTRY_TEXT)
            and (entry["wall_time_s"] is None
                 or (isinstance(entry["wall_time_s"], (int, float))
                     and not isinstance(entry["wall_time_s"], bool))))


def batch_status(outcomes: list[Outcome]) -> str:
    """The worst status of the batch; a status :func:`worst_status` does not rank (one
    read back from an archive, "inaccurate") counts as not ok."""
    return worst_status(*(o.status if o.status in STATUSES else "failed" for o in outcomes))
