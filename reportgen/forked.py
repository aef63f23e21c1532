"""Forked helper processes fed jobs on a pipe: the scene workers of a batch, the edit
loop's PDF worker and its figure helper.

Standard library only, so that a worker can be forked before the heavy imports.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from multiprocessing import get_context
from multiprocessing.connection import Connection
from typing import Any


class JobProcess:
    """A forked process running ``main(jobs, results, *args)``: it receives jobs on
    ``jobs`` and answers on ``results`` (see :func:`serve`); this side keeps
    :attr:`jobs` (to send on) and :attr:`results` (to receive from).

    The child first closes its copies of this side's ends and of ``siblings`` (other
    helpers' ends, copied by the fork too), so that it sees EOF when this process goes
    even if a sibling was forked after it."""

    def __init__(self, main: Callable[..., None], *args: Any,
                 siblings: Iterable[Connection] = ()):
        ctx = get_context("fork")
        job_out, self.jobs = ctx.Pipe(duplex=False)
        self.results, result_in = ctx.Pipe(duplex=False)
        inherited = [self.jobs, self.results, *siblings]
        self.proc = ctx.Process(target=_child, daemon=True,
                                args=(main, inherited, job_out, result_in, *args))
        self.proc.start()
        job_out.close()
        result_in.close()

    def stop(self, graceful: bool = True, timeout: float = 5.0) -> None:
        """End the process: ask it to stop (None) and wait up to ``timeout`` seconds when
        ``graceful``, then kill it if it still runs.  Closes this side's ends."""
        if graceful:
            try:
                self.jobs.send(None)
            except OSError:
                pass
            else:
                self.proc.join(timeout=timeout)
        if self.proc.is_alive():
            self.proc.kill()
        self.proc.join()
        self.jobs.close()
        self.results.close()


def _child(main, inherited, jobs, results, *args) -> None:
    for conn in inherited:
        conn.close()
    main(jobs, results, *args)


def serve(jobs: Connection, results: Connection, handle: Callable[[Any], Any]) -> None:
    """A helper's loop: send back ``handle(job)`` for each job received, until None or
    until the other side closes."""
    while True:
        try:
            job = jobs.recv()
        except (EOFError, OSError):
            return
        if job is None:
            return
        results.send(handle(job))
