"""``reportgen watch``: the edit loop in one long-lived process.

A lecturer edits a config and looks again, many times an hour.  ``reportgen run`` is
already incremental (only the stages whose inputs changed run), but each run is a new
process that imports NumPy, h5py, matplotlib, numba's compiled drivers and WeasyPrint
again: more than a second of every edit.  ``watch`` runs the batch once, then polls the
configs' modification times and runs the batch again after each change, in the same
process: the libraries stay imported, the compiled drivers loaded, and a PDF worker with
WeasyPrint warm waits for the next report.  What it writes is exactly what ``run``
would write (same pipeline, same files); a config that fails validation is reported and
nothing is written until it is fixed.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from pathlib import Path

from ..errors import ConfigError, UsageError
from ..support.forked import Terminated, raise_if_stopped, stop_handled
from ..support.layout import collect_configs, printable


def _snapshot(paths: list[str]) -> dict[Path, int]:
    """Every config below ``paths`` with its modification time (ns)."""
    try:
        configs = collect_configs(paths)
    except UsageError:
        return {}
    stamps = {}
    for path in configs:
        try:
            stamps[path] = path.stat().st_mtime_ns
        except OSError:
            pass
    return stamps


def watch(paths: list[str], out_root: str = "output", jobs: int | None = None,
          formats: tuple[str, ...] | None = None, interval: float = 0.25,
          stream=None, stop: Callable[[], bool] | None = None,
          time_limit: float | None = None) -> int:
    """Run the batch, then again whenever a config under ``paths`` changes, appears or
    goes, until interrupted (Ctrl-C, SIGTERM, SIGHUP: child processes are stopped at
    once) or ``stop()`` is true.  Each batch holds the output folder's lock while it runs
    (:func:`reportgen.support.fsutil.output_lock`).  ``time_limit``: seconds a scene's
    validation or run may take (None: none); a scene over it is stopped and the watch goes
    on to the next edit.  Returns the exit status."""
    from ..support.forked import children_stop_with_me

    with children_stop_with_me():
        return _watch(paths, out_root, jobs, formats, interval, stream or sys.stderr, stop,
                      time_limit)


def _watch(paths, out_root, jobs, formats, interval, stream, stop, time_limit) -> int:
    from ..rendering.pdf import PdfWorker
    from .stages import _preload, run_batch

    wants_pdf = formats is None or "pdf" in formats
    worker: PdfWorker | None = None
    seen: dict[Path, int] | None = None
    preloaded = False
    try:
        while stop is None or not stop():
            raise_if_stopped()  # a SIGTERM swallowed in a fork hook still ends the watch
            now = _snapshot(paths)
            if now == seen:
                time.sleep(interval)
                continue
            if seen is not None:
                time.sleep(min(interval, 0.05))  # let an editor finish writing
                now = _snapshot(paths)
            changed = ([p.name for p in now if seen is None or seen.get(p) != now[p]]
                       + [p.name for p in (seen or {}) if p not in now])
            seen = now
            if not now:
                print(f"no *.toml config found in {', '.join(paths)}; waiting", file=stream,
                      flush=True)
                continue
            if wants_pdf and jobs != 1 and (worker is None or not worker.alive):
                if worker is not None:
                    worker.close()
                worker = PdfWorker()  # kept warm for every later edit
            started = time.perf_counter()
            what = (printable(", ".join(changed)) if len(changed) <= 3
                    else f"{len(changed)} configs")
            print(f"--- {what} changed: running" if preloaded else
                  f"--- watching {len(now)} configs: first run", file=stream, flush=True)
            try:
                outcomes = run_batch(list(now), out_root=out_root, jobs=jobs, formats=formats,
                                     stream=stream, pdf_worker=worker, time_limit=time_limit,
                                     in_process_limit=True)
            except ConfigError as exc:
                for line in exc.problems:
                    print(printable(line), file=stream)
                print("--- not run: fix the config (nothing was written); watching",
                      file=stream, flush=True)
                continue
            except UsageError as exc:  # the output folder: not a folder, not writable, full
                print(f"--- {printable(str(exc))}; watching", file=stream, flush=True)
                continue
            bad = sum(not o.ok for o in outcomes)
            print(f"--- done in {time.perf_counter() - started:.2f} s: "
                  f"{len(outcomes) - bad} of {len(outcomes)} scenes ok; index: "
                  f"{printable(str(Path(out_root) / 'index.html'))}; watching (Ctrl-C to stop)",
                  file=stream, flush=True)
            if not preloaded:
                # while the lecturer reads: what the next edit would otherwise import
                _preload([], formats)
                preloaded = True
    except KeyboardInterrupt as exc:  # Ctrl-C is how a watch ends: status 0; SIGTERM or
        print("watch stopped", file=stream)  # SIGHUP stop it as any command: 128 + n
        stop_handled()
        if isinstance(exc, Terminated):
            return 128 + exc.signum
    finally:
        if worker is not None:
            worker.close()
    return 0
