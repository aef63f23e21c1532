"""Command line: argument parsing and exit codes only.

Exit status: 0 all scenes ok; 1 some scene failed, was inaccurate or numerically unstable;
2 bad usage or invalid config (nothing run, nothing overwritten).
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from .. import __version__
from ..errors import ConfigError, UsageError
from ..support.cache import NO_CACHE_ENV, PeerCache
from ..support.layout import FORMATS, collect_configs, printable
from ..support.threads import one_blas_thread_by_default

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2


def _formats(text: str) -> tuple[str, ...]:
    items = tuple(f.strip().lower() for f in text.split(",") if f.strip())
    bad = [f for f in items if f not in FORMATS]
    if bad or not items:
        raise argparse.ArgumentTypeError(
            f"--format takes a comma-separated subset of {','.join(FORMATS)} (got {text!r})")
    return items


def _jobs(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"--jobs must be a whole number ≥ 1 (got {text!r})")
    return value


def _dpi(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if not 20 <= value <= 1200:
        raise argparse.ArgumentTypeError(f"--dpi must be a whole number from 20 to 1200 "
                                         f"(got {text!r})")
    return value


def _positive(option: str, what: str = "a positive number"):
    """An argparse type: a positive, finite number for ``option``."""

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            value = -1.0
        if not value > 0 or value == float("inf"):
            raise argparse.ArgumentTypeError(f"{option} must be {what} (got {text!r})")
        return value

    return parse


#: wall-clock seconds one scene of ``reportgen run`` may take (``--time-limit``; 0: none)
DEFAULT_TIME_LIMIT = 600.0


def _time_limit(text: str) -> float:
    """``--time-limit``: seconds per scene, 0 for no limit."""
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not 0 <= value < float("inf"):
        raise argparse.ArgumentTypeError(f"--time-limit must be a number of seconds ≥ 0 "
                                         f"(0: no limit) (got {text!r})")
    return value


def _seconds(option: str):
    """An argparse type: a positive, finite number of seconds for ``option``."""
    return _positive(option, "a positive number of seconds")


def _batch_parser(sub, name: str, help_text: str) -> argparse.ArgumentParser:
    """A subcommand that runs a batch: config paths, --out, --jobs, --format."""
    parser = sub.add_parser(name, help=help_text)
    parser.add_argument("paths", nargs="+", metavar="PATH")
    parser.add_argument("--out", default="output", metavar="DIR",
                        help="output folder (default: output)")
    parser.add_argument("--jobs", type=_jobs, default=None, metavar="N",
                        help="worker processes (default: CPU count)")
    parser.add_argument("--format", type=_formats, default=None, metavar="html,pdf",
                        help="report formats (default: the config's [report] formats)")
    return parser


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="reportgen",
        description="Simulate classical-mechanics scenes from TOML configs and write HDF5 "
                    "archives, figures and HTML/PDF reports.")
    parser.add_argument("--version", action="version", version=f"reportgen {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    run = _batch_parser(sub, "run", "run scenes (config files or folders) and write reports")
    run.add_argument("--force", action="store_true", help="re-run scenes whose archive is current")
    run.add_argument("--no-cache", action="store_true",
                     help="measure scipy peers again instead of using the user cache")
    run.add_argument("--scheduler", default=None, metavar="ADDR",
                     help="Dask distributed scheduler address (needs the 'dask' extra)")
    run.add_argument("--time-limit", type=_time_limit, default=None,
                     metavar="SECONDS",
                     help=f"stop a scene that runs longer than this; its earlier archive is "
                          f"kept (default: {DEFAULT_TIME_LIMIT:g}; 0: no limit)")

    wat = _batch_parser(sub, "watch", "run, then run again whenever a config changes "
                                      "(the edit loop, kept warm)")
    wat.add_argument("--interval", type=_seconds("--interval"), default=0.25,
                     metavar="SECONDS",
                     help="how often the configs are looked at (default: 0.25)")
    wat.add_argument("--time-limit", type=_time_limit, default=None, metavar="SECONDS",
                     help="stop validating or running a scene that takes longer than this, "
                          "and watch on (default: 600; 0: no limit)")

    rep = sub.add_parser("report", help="rebuild reports from archives alone")
    rep.add_argument("archives", nargs="+", metavar="ARCHIVE.h5")
    rep.add_argument("--format", type=_formats, default=FORMATS, metavar="html,pdf")

    fig = sub.add_parser("figures", help="a scene's figures as PNG, SVG and PDF files for "
                                         "slides and print, drawn from its archive")
    fig.add_argument("path", metavar="PATH", help="a run.h5 archive, or a config (its archive "
                     "under the output folder --out is used, as `reportgen run --out` wrote "
                     "it; the scene is run first if that is missing or stale)")
    fig.add_argument("--size", default="report", metavar="SIZE",
                     help="slide (10x5.625 in, larger text), print (6.5 in wide), WxH in "
                          "inches, or report (as in the report; the default)")
    fig.add_argument("--dpi", type=_dpi, default=200, metavar="N",
                     help="PNG resolution, recorded in the file (default 200)")
    fig.add_argument("--format", default="png,svg,pdf", metavar="png,svg,pdf",
                     help="file formats (default: all three)")
    fig.add_argument("--only", action="append", default=[], metavar="PATTERN",
                     help="only figures whose id matches this shell pattern (repeatable), "
                          "e.g. 'nutation*'")
    _output_root_options(fig, "the files go to SCENE/figures-SIZE under it")
    fig.add_argument("--folder", default=None, metavar="DIR",
                     help="put the files in exactly this folder instead")

    ani = sub.add_parser("animate", help="the scene's motion as a GIF (and MP4 with the "
                                         "'video' extra), drawn from its archive")
    ani.add_argument("path", metavar="PATH", help="a run.h5 archive, or a config (its archive "
                     "under the output folder is used, run first if missing or stale)")
    ani.add_argument("--fps", type=_positive("--fps"), default=15.0, metavar="N",
                     help="frames per second (default 15)")
    ani.add_argument("--duration", type=_positive("--duration"), default=6.0, metavar="SECONDS",
                     help="length of the animation; the whole run is spread over it (default 6)")
    ani.add_argument("--dpi", type=_dpi, default=100, metavar="N",
                     help="resolution (default 100: about 640 pixels wide)")
    ani.add_argument("--format", default=None, metavar="gif,mp4",
                     help="default: gif, and mp4 when ffmpeg is available")
    _output_root_options(ani, "animation.gif/.mp4 go to SCENE/ under it")
    ani.add_argument("--folder", default=None, metavar="DIR",
                     help="put the files in exactly this folder instead")

    ins = sub.add_parser("inspect", help="summary of an archive, checksums verified")
    ins.add_argument("archive", metavar="ARCHIVE.h5")

    ver = sub.add_parser("verify", help="re-simulate archives from their own configs and "
                                        "compare every stored number")
    ver.add_argument("paths", nargs="+", metavar="ARCHIVE|FOLDER")

    kin = sub.add_parser("kinds", help="scene kinds, their keys, presets and sections")
    kin.add_argument("kind", nargs="?", default=None, metavar="KIND",
                     help="only this kind (its keys, sections and presets)")
    kin.add_argument("--presets", action="store_true",
                     help="each preset in words and the keys it sets (of KIND, or of all)")

    val = sub.add_parser("validate", help="check configs, run nothing")
    val.add_argument("paths", nargs="+", metavar="PATH")
    val.add_argument("--resolved", action="store_true",
                     help="print each config as run sees it (preset, the config's keys and "
                          "the defaults) as TOML")
    val.add_argument("--time-limit", type=_time_limit, default=None, metavar="SECONDS",
                     help="stop validating a config after this many seconds of CPU time "
                          f"(its formulas' symbolic work; default: {DEFAULT_TIME_LIMIT:g}; 0: "
                          "no limit)")

    audit = sub.add_parser("audit", help="stability audit on stiff and extreme cases")
    audit.add_argument("paths", nargs="*", metavar="PATH")
    audit.add_argument("--out", default="output/audit", metavar="DIR")
    audit.add_argument("--format", type=_formats, default=FORMATS, metavar="html,pdf")

    cache = sub.add_parser("cache", help="the user cache of peer (scipy) measurements")
    cache.add_argument("action", choices=("info", "clear"))

    bench = sub.add_parser("bench", help="error against run time, against peer solvers")
    bench.add_argument("paths", nargs="*", metavar="PATH")
    bench.add_argument("--pipeline", action="store_true",
                       help="time the edit loop instead: the pack (PATH, default configs/) "
                            "cold and warm, a title edit, a physics edit, the light commands")
    bench.add_argument("--scene", default="pendulum_small",
                       help="with --pipeline: the scene edited (default pendulum_small)")
    bench.add_argument("--previous", default=None, metavar="DIR",
                       help="with --pipeline: a source checkout of an earlier release, "
                            "measured in the same call for comparison")
    return parser


def console_main() -> None:
    """The ``reportgen`` command: :func:`main`, then a fast exit.

    When ``main`` returns, everything the command wrote is complete (renamed into place)
    and every process it started has stopped; tearing the interpreter down object by
    object would add 0.1-0.2 s to each edit-loop run for nothing.  So the standard
    streams are flushed and the process ends with ``os._exit`` -- unless a child process
    is somehow still running, which the normal exit then handles."""
    one_blas_thread_by_default()
    for stream in (sys.stdout, sys.stderr):  # a character the terminal's encoding lacks
        try:  # (PYTHONIOENCODING=ascii, LC_ALL=C) is printed as an escape, not a crash
            stream.reconfigure(errors="backslashreplace")
        except (AttributeError, ValueError):  # not a text stream of io's
            pass
    code = main()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe (| head): nothing left to say
            pass
    children = sys.modules.get("multiprocessing")
    if children is not None and children.active_children():
        raise SystemExit(code)
    os._exit(code)


#: set (to anything) to see the traceback of an unexpected error instead of its one line
DEBUG_ENV = "REPORTGEN_DEBUG"


def main(argv: list[str] | None = None) -> int:
    """Run one command; its exit status.  Whatever goes wrong ends in one or a few lines
    on stderr, never a traceback: an invalid config, bad usage or an unusable output
    folder is status 2, a signal 128 + its number (SIGTERM, SIGHUP and Ctrl-C stop the
    command's child processes first), an unexpected error 1 (its traceback with
    ``REPORTGEN_DEBUG=1``)."""
    from ..support.forked import Terminated, children_stop_with_me

    args = build_parser().parse_args(argv)
    try:
        with children_stop_with_me():
            return COMMANDS[args.command](args)
    except ConfigError as exc:
        for line in exc.problems:
            _err(line)
        return EXIT_USAGE
    except UsageError as exc:
        return _usage(str(exc))
    except Terminated as exc:
        import signal

        _err(f"stopped by {signal.Signals(exc.signum).name}: finished scenes are kept; run "
             "again to resume")
        return 128 + exc.signum
    except KeyboardInterrupt:
        _err("interrupted: finished scenes are kept; run again to resume")
        return 130
    except BrokenPipeError:  # the reader of stdout went (| head): nothing left to say
        _silence_stdout()
        return EXIT_OK
    except OSError as exc:  # a file-system problem outside any scene (those fail the scene)
        where = f"{exc.filename}: " if exc.filename else ""
        _err(f"reportgen {args.command}: {where}{exc.strerror or exc}")
        return EXIT_USAGE
    except Exception as exc:
        if os.environ.get(DEBUG_ENV):
            raise
        _err(f"reportgen {args.command}: unexpected error: {type(exc).__name__}: {exc} "
             f"({DEBUG_ENV}=1 shows the traceback)")
        return EXIT_FAILED


def _err(message: str) -> None:
    """One message on stderr, its control characters shown, not acted on (file names,
    titles and messages come from configs and archives)."""
    try:
        print(printable(message), file=sys.stderr, flush=True)
    except (OSError, ValueError):
        pass


def _say(text: str) -> None:
    """Output on stdout (control characters shown, not acted on); a reader that went away
    (``| head``) ends the output quietly."""
    try:
        print(printable(text), flush=True)
    except BrokenPipeError:
        _silence_stdout()


def _silence_stdout() -> None:
    """Point stdout at /dev/null: once its reader is gone, every later write (the flush at
    exit among them) would fail again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(devnull, sys.stdout.fileno())
        finally:
            os.close(devnull)
    except (OSError, ValueError):
        pass


def _usage(message: str) -> int:
    _err(f"reportgen: {message}")
    return EXIT_USAGE


def _unusable(archive, exc: Exception) -> int:
    """An archive that passed the checks yet broke its kind's drawing: one line naming it
    (status 2: the file is not what its kind's report needs)."""
    if os.environ.get(DEBUG_ENV):
        raise exc
    _err(f"{archive}: cannot draw from this archive ({type(exc).__name__}: {exc}); it does "
         f"not hold what its kind needs ({DEBUG_ENV}=1 shows the traceback)")
    return EXIT_USAGE


def cmd_run(args) -> int:
    from ..rendering.pdf import edit_loop_worker

    if args.no_cache:
        os.environ[NO_CACHE_ENV] = "1"  # inherited by the scene processes
    try:
        configs = collect_configs(args.paths)
    except UsageError as exc:
        return _usage(str(exc))
    # forked before the heavy imports below, so WeasyPrint's import overlaps them too
    worker = edit_loop_worker(configs, args.out, args.format, args.jobs, args.force,
                              args.scheduler)
    try:
        from ..pipeline.stages import batch_status, run_batch

        outcomes = run_batch(configs, out_root=args.out, jobs=args.jobs, formats=args.format,
                             force=args.force, scheduler=args.scheduler,
                             time_limit=(DEFAULT_TIME_LIMIT if args.time_limit is None
                                         else args.time_limit or None),
                             in_process_limit=args.time_limit is None, pdf_worker=worker)
    except UsageError as exc:
        return _usage(str(exc))
    finally:
        if worker is not None:
            worker.close()
    status = batch_status(outcomes)
    bad = [o for o in outcomes if not o.ok]
    _err(f"{len(outcomes) - len(bad)} of {len(outcomes)} scenes ok; index: "
         f"{Path(args.out) / 'index.html'}")
    if bad and all(o.config_error for o in bad):
        return EXIT_USAGE
    return EXIT_OK if status == "ok" else EXIT_FAILED


def cmd_watch(args) -> int:
    from ..pipeline.watch import watch

    try:
        collect_configs(args.paths)
    except UsageError as exc:
        return _usage(str(exc))
    return watch(args.paths, out_root=args.out, jobs=args.jobs, formats=args.format,
                 interval=args.interval,
                 time_limit=(DEFAULT_TIME_LIMIT if args.time_limit is None
                             else args.time_limit or None))


def cmd_report(args) -> int:
    from ..archive.store import ArchiveError
    from ..rendering.report import ReportError, build_report
    from ..support.fsutil import links_out

    code = EXIT_OK
    for archive in args.archives:
        folder = Path(archive).parent
        escaping = links_out(folder, folder)
        if escaping:  # the report writes its figures there: never through a link out
            _err(f"{escaping[0]}: a symbolic link leading out of {folder}; not followed, "
                 f"no report written for {archive}")
            code = EXIT_USAGE
            continue
        try:
            written = build_report(Path(archive), formats=args.format)
        except (ArchiveError, ReportError) as exc:
            _err(str(exc))
            code = EXIT_USAGE
            continue
        except OSError as exc:  # writing the report (reading errors are ArchiveErrors)
            _err(f"{archive}: cannot write its report: {exc.filename or ''} "
                 f"({exc.strerror or exc})")
            code = EXIT_USAGE
            continue
        except Exception as exc:  # noqa: BLE001 - one line per archive, never a traceback
            code = _unusable(archive, exc)
            continue
        _say("wrote " + ", ".join(str(w) for w in written))
    return code


def _output_root_options(parser, where: str) -> None:
    """``--out`` and ``--root``: the output root, as in ``reportgen run``, in every command."""
    parser.add_argument("--out", default=None, metavar="DIR",
                        help="the output folder, as in `reportgen run` (default: beside the "
                             f"archive; for a config, output); {where}")
    parser.add_argument("--root", default=None, metavar="DIR", help="the same as --out")


def _where(args, command: str) -> tuple[Path, Path | None]:
    """(archive, output root) of ``reportgen figures|animate PATH``: PATH's archive (a
    config's is brought up to date under the root first) and the root its files go
    under (None: beside the archive)."""
    if args.out and args.root and Path(args.out) != Path(args.root):
        raise UsageError(f"{command}: --out and --root both name the output folder; give "
                         f"one (got --out {args.out}, --root {args.root})")
    root = args.out or args.root
    path = Path(args.path)
    is_config = path.suffix.lower() == ".toml"
    archive = _archive_of(path, Path(root or "output") if is_config else None)
    return archive, Path(root) if root else None


def _files_folder(archive: Path, root: Path | None, folder: str | None, name: str) -> Path:
    """Where a command's files go: ``--folder``, else ``<root>/<scene>/<name>`` for an
    output root (the scene's folder as `reportgen run` names it), else beside the
    archive."""
    if folder:
        return Path(folder)
    # the scene's name from the archive's folder as written out ("src/sub/../run.h5" is
    # in src, whose name is the scene's: never "..", which would lead out of the root)
    scene = Path(os.path.abspath(archive)).parent.name
    return (archive.parent if root is None else root / scene) / name


def cmd_figures(args) -> int:
    from ..archive.store import ArchiveError
    from ..rendering.export import export_figures, parse_formats, parse_size, pixel_problem
    from ..rendering.report import ReportError

    try:
        size, formats = parse_size(args.size), parse_formats(args.format)
        if size.width is not None and size.height is not None and "png" in formats:
            problem = pixel_problem(size.width, size.height, args.dpi, f"--size {size.label}")
            if problem is not None:  # before the archive is read, or a scene run for it
                raise UsageError(problem)
        archive, root = _where(args, "figures")
    except UsageError as exc:
        return _usage(str(exc))
    if archive is None:
        return EXIT_FAILED
    out = _files_folder(archive, root, args.folder, f"figures-{size.label}")
    if not args.folder:
        from ..support.fsutil import links_out
        from ..support.layout import printable

        escaping = [p for p in links_out(out.parent, out.parent.parent) if p == out]
        if escaping:
            return _usage(f"{printable(str(out))} is a symbolic link leading outside "
                          f"{printable(str(out.parent.parent))}: not followed (remove the "
                          "link, or give --folder)")

    def report(path: Path) -> None:
        _err(f"wrote {path}")

    try:
        written = export_figures(archive, out, size=size, dpi=args.dpi, formats=formats,
                                 only=tuple(args.only), progress=report)
    except UsageError as exc:
        return _usage(str(exc))
    except (ArchiveError, ReportError) as exc:
        _err(str(exc))
        return EXIT_USAGE
    except OSError as exc:
        _err(f"{out}: cannot write the figures: {exc.filename or ''} ({exc.strerror or exc})")
        return EXIT_USAGE
    except Exception as exc:  # noqa: BLE001 - one line, never a traceback
        return _unusable(archive, exc)
    _err(f"{len(written)} files in {out}")
    return EXIT_OK


def _archive_of(path: Path, root: Path | None) -> Path | None:
    """The archive ``reportgen figures PATH`` draws from: PATH itself, or the archive of
    the config PATH under ``root``, which is brought up to date first (run, as
    ``reportgen run`` would, only if it is missing or its physics changed).  None when
    that run failed (said on stderr)."""
    if not path.exists():
        raise UsageError(f"{path}: no such file")
    if path.suffix.lower() != ".toml":
        return path
    from ..archive.store import FORMAT_VERSION, stored_identity
    from ..kinds import load_scene
    from ..pipeline.stages import run_scene
    from ..scene.config import read_config
    from ..support.fsutil import output_folder, output_lock

    scene = load_scene(read_config(path))  # a ConfigError is exit 2, via main
    archive = root / path.stem / "run.h5"
    stored = stored_identity(archive) if archive.exists() else None
    if (stored is None or stored.physics_key != scene.physics_key()
            or stored.format_version < FORMAT_VERSION):
        why = "missing" if stored is None else "out of date"
        _err(f"{archive}: {why}; running {path} first")
        with output_lock(output_folder(root)):  # as a `reportgen run` into ``root`` would
            outcome = run_scene(str(path), str(root))
        if outcome.status == "failed":
            _err(f"{path}: {outcome.message}")
            return None
    return archive


def cmd_animate(args) -> int:
    from ..archive.store import ArchiveError
    from ..rendering.animate import animate, parse_formats, plan_frames, terminal_progress

    archive = Path(args.path)
    try:
        formats = parse_formats(args.format)
        frames = plan_frames(args.fps, args.duration)
        archive, root = _where(args, "animate")
        if archive is None:
            return EXIT_FAILED
        out = _files_folder(archive, root, args.folder, "")
        _err(f"{archive}: {frames} frames at {args.fps:g} fps -> {', '.join(formats)}")
        written = animate(archive, out, fps=args.fps, duration=args.duration, dpi=args.dpi,
                          formats=formats, progress=terminal_progress())
    except UsageError as exc:
        return _usage(str(exc))
    except ArchiveError as exc:
        _err(str(exc))
        return EXIT_USAGE
    except OSError as exc:
        _err(f"{archive}: cannot write the animation: {exc.filename or ''} "
             f"({exc.strerror or exc})")
        return EXIT_USAGE
    except Exception as exc:  # noqa: BLE001 - one line, never a traceback
        return _unusable(archive, exc)
    for path in written:
        _err(f"wrote {path}")
    if args.format is None and "mp4" not in formats:
        print("(no MP4: install the 'video' extra for ffmpeg)", file=sys.stderr)
    return EXIT_OK


def cmd_inspect(args) -> int:
    from ..archive.store import ArchiveError, summarize

    archive = Path(args.archive)
    problems: list[str] = []
    try:
        text = summarize(archive, problems)
    except ArchiveError as exc:
        _err(str(exc))
        return EXIT_USAGE
    except Exception as exc:  # noqa: BLE001 - one line, never a traceback
        return _unusable(archive, exc)
    _say(text)
    return EXIT_FAILED if problems else EXIT_OK


def cmd_verify(args) -> int:
    """Each archive (or every ``run.h5`` below a folder) re-simulated from its stored config
    and compared: 0 when all are identical, 1 when one differs, 2 when one is unreadable."""
    from ..pipeline.verify import archives_in, describe, verify_archive

    archives = archives_in(args.paths)
    if not archives:
        return _usage(f"no archive (run.h5) in {', '.join(map(str, args.paths))}")
    worst = EXIT_OK
    for i, archive in enumerate(archives, 1):
        result = verify_archive(archive)
        lines = describe(result)
        head = f"[{i}/{len(archives)}] {result.scene or archive}: {lines[0]}"
        _say("\n".join([head, *lines[1:]]))
        if result.verdict == "unreadable":
            worst = EXIT_USAGE
        elif not result.identical and worst == EXIT_OK:
            worst = EXIT_FAILED
    return worst


def cmd_kinds(args) -> int:
    from ..scene.catalogue import describe_kind, describe_kinds, describe_presets

    if args.presets:
        _say(describe_presets(args.kind))
    else:
        _say(describe_kind(args.kind) if args.kind else describe_kinds())
    return EXIT_OK


def cmd_validate(args) -> int:
    from ..pipeline.stages import UsageError, collect_configs, validate_all

    try:
        scenes = validate_all(collect_configs(args.paths),
                              time_limit=(DEFAULT_TIME_LIMIT if args.time_limit is None
                                          else args.time_limit or None))
    except UsageError as exc:
        return _usage(str(exc))
    if args.resolved:
        from ..scene.config import to_toml

        for scene in scenes:
            _say(f"# {scene.source.path}: resolved (preset, keys given, defaults)\n"
                 + to_toml(_given(scene.resolved_config())))
        return EXIT_OK
    for scene in scenes:
        asked = scene.config.report.sections
        if scene.sweep is not None:
            family = f"a sweep of {scene.sweep.size} members"
            sections = f"{family}: " + (", ".join(asked) if asked
                                        else "the kind's family sections")
        else:
            sections = ", ".join(asked) if asked else "the kind's default sections"
        _say(f"{scene.source.path}: ok ({scene.kind}: {sections})")
    return EXIT_OK


def _given(data):
    """``data`` without its None values (keys left unset: TOML has no null)."""
    if isinstance(data, dict):
        return {k: _given(v) for k, v in data.items() if v is not None}
    if isinstance(data, list):
        return [_given(v) for v in data]
    return data


def cmd_bench(args) -> int:
    from ..pipeline.stages import UsageError
    from .bench import run_bench

    if args.pipeline:
        from pathlib import Path

        from .bench_pipeline import measure

        folder = Path(args.paths[0]) if args.paths else Path("configs")
        if len(args.paths) > 1 or not folder.is_dir():
            return _usage(f"bench --pipeline: expected one folder of configs, got "
                          f"{' '.join(args.paths) or 'configs/ (missing)'}")
        if not (folder / f"{args.scene}.toml").exists():
            return _usage(f"bench --pipeline: --scene {args.scene}: no {args.scene}.toml in "
                          f"{folder}")
        previous = Path(args.previous) if args.previous else None
        if previous is not None and not (previous / "reportgen" / "cli.py").exists():
            return _usage(f"bench --pipeline: --previous {previous}: not a reportgen source "
                          "checkout (no reportgen/cli.py)")
        measure(folder, args.scene, previous)
        return 0

    os.environ[NO_CACHE_ENV] = "1"  # peers measured in the same run as ours

    try:
        return run_bench(args.paths)
    except UsageError as exc:
        return _usage(str(exc))


def cmd_audit(args) -> int:
    from ..pipeline.stages import UsageError
    from .audit import run_audit

    try:
        return run_audit(args.paths, out_dir=args.out, formats=args.format)
    except UsageError as exc:
        return _usage(str(exc))


def cmd_cache(args) -> int:
    cache = PeerCache()
    if args.action == "clear":
        print(f"removed {cache.clear()} entries from {cache.root}")
    else:
        print(cache.info())
    return EXIT_OK


COMMANDS = {
    "cache": cmd_cache,
    "audit": cmd_audit,
    "run": cmd_run,
    "watch": cmd_watch,
    "report": cmd_report,
    "figures": cmd_figures,
    "animate": cmd_animate,
    "inspect": cmd_inspect,
    "verify": cmd_verify,
    "kinds": cmd_kinds,
    "validate": cmd_validate,
    "bench": cmd_bench,
}
