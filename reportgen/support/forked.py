"""Forked helper processes fed jobs on a pipe: the scene workers of a batch, the edit
loop's PDF worker and its figure helper.

Every process forked here dies with its parent, whatever ends the parent: on Linux the
kernel sends it SIGKILL when the parent goes (``PR_SET_PDEATHSIG``, even for a parent
killed with -9), and a parent stopped by SIGTERM, SIGHUP or Ctrl-C kills its children
first (:func:`children_stop_with_me`).  (The kernel ties the parent-death signal to the
*thread* that forked: a helper must be forked by a thread that outlives it, as the main
thread does.)

Standard library only, so that a worker can be forked before the heavy imports.
"""

from __future__ import annotations

import os
import signal
import sys
import threading
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from multiprocessing import get_context
from multiprocessing.connection import Connection
from typing import Any

#: prctl(2) option: the signal a process gets when its parent ends
PR_SET_PDEATHSIG = 1


class Terminated(KeyboardInterrupt):
    """SIGTERM or SIGHUP: stops the command like Ctrl-C (children killed, finished work
    kept), with the exit status 128 + the signal's number."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


def interrupt_behind(exc: BaseException | None) -> KeyboardInterrupt | None:
    """The Ctrl-C or stop signal (:class:`Terminated`) behind ``exc``, if any.

    A signal handled while an extension module initialises raises inside its
    initialisation, and pybind11 turns that into ``ImportError: initialization failed``
    (the KeyboardInterrupt its cause), leaving the module's types registered: the module
    can never be imported again in this process or its forks ("type ... is already
    registered").  Such an ImportError must stop the command as the signal does, not fail a
    scene or be taken for a missing optional library."""
    seen: set[int] = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return exc
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return None


def reraise_interrupt(exc: BaseException) -> None:
    """If a stop signal is behind ``exc`` (:func:`interrupt_behind`): kill this process's
    children and raise that signal's exception, as the signal itself would have; else
    return, for the caller to handle ``exc``."""
    stop = interrupt_behind(exc)
    if stop is not None:
        kill_children()
        raise stop from None


def die_with_parent(parent: int) -> None:
    """In a process just forked from ``parent``: be killed when ``parent`` ends.

    The kernel's parent-death signal covers a parent killed with SIGKILL; a parent that
    ended between the fork and this call is seen by ``getppid`` (the child was re-parented)
    and this process ends at once.  The signal handlers the parent installed
    (:func:`children_stop_with_me`) are undone: SIGTERM and SIGHUP kill this process, and
    Ctrl-C, sent to the whole foreground process group, is the parent's to handle (it
    kills its children)."""
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(ctypes.c_int(PR_SET_PDEATHSIG), ctypes.c_ulong(signal.SIGKILL),
                       ctypes.c_ulong(0), ctypes.c_ulong(0), ctypes.c_ulong(0))
        except (OSError, AttributeError):
            pass  # no prctl: the parent's signal handlers and the closed pipes remain
    if os.getppid() != parent:
        os._exit(1)
    try:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        signal.signal(signal.SIGHUP, signal.SIG_DFL)
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    except ValueError:  # not the main thread (cannot happen right after a fork)
        pass


def run_child(parent: int, target: Callable[..., Any], *args: Any) -> None:
    """A forked process's target: :func:`die_with_parent`, then ``target(*args)``."""
    die_with_parent(parent)
    target(*args)


def kill_children() -> None:
    """Kill every process this one forked through :mod:`multiprocessing` that still runs
    (and reap them)."""
    mp = sys.modules.get("multiprocessing")
    if mp is None:
        return
    for child in mp.active_children():
        try:
            child.kill()
        except (OSError, ValueError, AttributeError):
            pass
    for child in mp.active_children():
        try:
            child.join(timeout=2)
        except (OSError, ValueError, AssertionError):
            pass


#: the stop signals received under :func:`children_stop_with_me`, in order
_requested: list[int] = []


def _stop_exception(signum: int) -> KeyboardInterrupt:
    return KeyboardInterrupt() if signum == signal.SIGINT else Terminated(signum)


def raise_if_stopped() -> None:
    """Raise the stop of a signal received earlier whose exception never arrived: a
    handler that runs inside a fork hook or a destructor ("Exception ignored in …", as
    logging's after-fork hook does) has its exception swallowed, and the command would go
    on (a ``watch`` would never end).  Loops that run for long call this between steps."""
    if _requested:
        raise _stop_exception(_requested[-1])


def stop_handled() -> None:
    """Say that the stop's exception arrived and was handled (a ``watch`` ended by Ctrl-C
    returns 0): :func:`raise_if_stopped` then has nothing to raise."""
    _requested.clear()


@contextmanager
def children_stop_with_me() -> Iterator[None]:
    """While in the body, SIGINT (Ctrl-C), SIGTERM and SIGHUP kill this process's children
    at once and raise KeyboardInterrupt (:class:`Terminated` for SIGTERM and SIGHUP) here,
    so that the command stops promptly, keeps what it finished and says so.  Outside the
    main thread (where handlers cannot be set) it does nothing.  The earlier handlers are
    restored afterwards."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    me = os.getpid()
    _requested.clear()

    def stop(signum, frame):
        if os.getpid() != me:  # a forked child that has not reset its handlers yet
            os._exit(128 + signum)
        _requested.append(signum)
        kill_children()
        raise _stop_exception(signum)

    previous = {}
    for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        try:
            previous[signum] = signal.signal(signum, stop)
        except (ValueError, OSError):
            pass
    try:
        yield
        raise_if_stopped()  # a stop whose exception something swallowed: taken now
    finally:
        for signum, handler in previous.items():
            try:
                signal.signal(signum, handler if handler is not None else signal.SIG_DFL)
            except (ValueError, OSError, TypeError):
                pass


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
                                args=(os.getpid(), main, inherited, job_out, result_in, *args))
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


def _child(parent, main, inherited, jobs, results, *args) -> None:
    die_with_parent(parent)
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
