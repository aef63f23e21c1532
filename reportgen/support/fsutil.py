"""Atomic file writes (a crash never leaves a half-written file under a final name),
staying inside the output folder (symbolic links are neither written through nor
followed out), and the output folder's lock."""

from __future__ import annotations

import errno
import json
import os
import stat
import sys
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any, BinaryIO

from ..errors import UsageError


def temp_name(path: Path) -> Path:
    """A unique hidden temporary name in the same folder (same filesystem, so rename is atomic)."""
    return path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")


def fsync_path(path: Path) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def atomic_write(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` via a temporary file, fsync, rename."""
    path = Path(path)
    tmp = temp_name(path)
    try:
        # a new file of our own (never an existing file, never through a link): the rename
        # then replaces whatever ``path`` was, a symbolic link included, not its target
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC,
                     0o666)
        with open(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if os.path.lexists(tmp):
            tmp.unlink()


def remove_stale_temps(folder: Path) -> list[Path]:
    """Delete temporary files left by writers that no longer run (e.g. killed with -9).

    Temporary names carry the writer's pid; a file whose pid is alive belongs to a
    concurrent writer and is left alone.  Only regular files inside ``folder`` are
    deleted: symbolic links to folders are not descended into (what they lead to is not
    the scene's), and ``folder`` itself must not be a link.
    """
    removed: list[Path] = []
    folder = Path(folder)
    if folder.is_symlink() or not folder.is_dir():
        return removed
    for top, dirs, files in os.walk(folder, followlinks=False):
        dirs[:] = [d for d in dirs if not os.path.islink(os.path.join(top, d))]
        for name in files:
            if not (name.startswith(".") and name.endswith(".tmp")):
                continue
            parts = name.split(".")
            try:
                pid = int(parts[-3])
            except (IndexError, ValueError):
                continue
            if pid == os.getpid() or _alive(pid):
                continue
            path = Path(top) / name
            try:
                if os.path.islink(path):  # a link is unlinked itself, never its target
                    continue
                path.unlink()
                removed.append(path)
            except OSError:
                pass
    return removed


def inside(path: Path | str, root: Path | str) -> bool:
    """Whether ``path``, its symbolic links resolved, is ``root`` or below it (``root``'s
    own links resolved too: ``--out`` may itself be a link)."""
    real, base = os.path.realpath(path), os.path.realpath(root)
    return real == base or real.startswith(base.rstrip(os.sep) + os.sep)


#: the folders of a scene folder that reportgen writes into (``.sweep-*`` too)
SCENE_SUBFOLDERS = ("figures", ".pdf-figures")


class NotRegularFile(OSError):
    """A path to read back that is no regular file: a FIFO (reading it waits for a writer
    that never comes), a device (/dev/zero reads without end), a folder or a socket."""


def regular_file(path: Path) -> Path:
    """``path``, if it is a regular file (through links, as a path given on the command
    line may be); NotRegularFile says what else it is, FileNotFoundError that it is
    missing.  ``os.stat`` never blocks, where opening a FIFO does."""
    mode = os.stat(path).st_mode
    if stat.S_ISREG(mode):
        return Path(path)
    raise NotRegularFile(errno.EINVAL, f"{_what(mode)}, not a regular file", str(path))


def _what(mode: int) -> str:
    return ("a FIFO" if stat.S_ISFIFO(mode) else "a folder" if stat.S_ISDIR(mode)
            else "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else "a socket")


class FileTooLarge(OSError):
    """A file read back that is larger than its reader accepts."""


def read_back(path: Path, limit: int, follow_links: bool = False) -> bytes:
    """The bytes of ``path``, a file read back from an output folder (untrusted): a regular
    file (NotRegularFile for a FIFO, a device...; not a symbolic link, an OSError, unless
    ``follow_links``) of at most ``limit`` bytes (FileTooLarge, before reading).

    The checks are made on the open file, so the file checked is the file read; opening
    does not wait (``O_NONBLOCK``: a FIFO is refused, not waited on)."""
    with open_back(path, limit, follow_links) as f:
        data = f.read(limit + 1)
    if len(data) > limit:  # grew since
        raise FileTooLarge(errno.EFBIG, f"larger than {limit} bytes", str(path))
    return data


def read_json_back(path: Path, limit: int) -> Any:
    """The JSON value of ``path``, read back as :func:`read_back` reads (no link, at most
    ``limit`` bytes), or None when it is missing, not such a file, or not JSON (a cache
    or stamp that cannot be read is one that was not written)."""
    try:
        return json.loads(read_back(path, limit).decode("utf-8"))
    except (OSError, ValueError, RecursionError):
        return None


def open_back(path: Path, limit: int, follow_links: bool = False) -> BinaryIO:
    """``path`` open for reading after :func:`read_back`'s checks (a regular file of at
    most ``limit`` bytes), for a reader that takes a file, not its bytes (numpy reads a
    sweep block's arrays one at a time)."""
    flags = os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC | (0 if follow_links else os.O_NOFOLLOW)
    fd = os.open(path, flags)
    f = open(fd, "rb")
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise NotRegularFile(errno.EINVAL, f"{_what(info.st_mode)}, not a regular file",
                                 str(path))
        if info.st_size > limit:
            raise FileTooLarge(errno.EFBIG, f"larger than {limit} bytes", str(path))
    except BaseException:
        f.close()
        raise
    return f


def links_out(folder: Path, root: Path) -> list[Path]:
    """The symbolic links through which writing into the scene folder ``folder`` would
    leave ``root`` (``--out``): the folder itself, or a folder in it that reportgen writes
    into (``figures/``, ``.pdf-figures/``, ``.sweep-*/``, the exports' ``figures-*/``)
    linked outside.  A link to a file is harmless: files are replaced by renaming, never
    written through."""
    folder, root = Path(folder), Path(root)
    bad = []
    if os.path.lexists(folder) and not inside(folder, root):
        return [folder]
    if not folder.is_dir():
        return bad
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return bad
    for entry in entries:
        if (entry.is_symlink() and (entry.name in SCENE_SUBFOLDERS
                                    or entry.name.startswith((".sweep-", "figures-")))
                and not inside(entry.path, root)):
            bad.append(Path(entry.path))
    return bad


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def install(tmp: Path, path: Path) -> None:
    """fsync the finished archive ``tmp`` and rename it over ``path``.

    An existing ``path`` is kept as ``<stem>.prev.h5``: it is hard-linked to its
    backup name first, so at every instant ``path`` names a complete archive
    (old or new).
    """
    fsync_path(tmp)
    if path.exists():
        backup = path.with_name(path.stem + ".prev" + path.suffix)
        staged = temp_name(backup)
        try:
            os.link(path, staged, follow_symlinks=False)  # a link is kept as the link
            os.replace(staged, backup)
        except OSError:
            if staged.exists():
                staged.unlink()
    os.replace(tmp, path)
    dir_fd = os.open(path.parent, os.O_RDONLY)
    try:
        os.fsync(dir_fd)
    finally:
        os.close(dir_fd)


def output_folder(root: Path | str) -> Path:
    """``--out``, made if missing; a path that is not a folder, or one that cannot be made,
    is a UsageError naming it."""
    root = Path(root)
    if os.path.lexists(root) and not root.is_dir():
        raise UsageError(f"--out {root}: exists and is not a folder")
    try:
        root.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"--out {root}: cannot create the folder ({exc.strerror})") from None
    return root


#: the lock file of an output folder: held by one ``reportgen run`` (or one batch of a
#: ``watch``) at a time, so that two runs on one folder never undo each other's work
LOCK_FILE = ".lock"


@contextmanager
def output_lock(root: Path, stream=None) -> Iterator[None]:
    """Hold the lock of the output folder ``root`` (``flock`` on ``root/.lock``) for the
    body; when another run holds it, say so on ``stream`` and wait for it.

    The lock goes with the process that holds it (a killed run never leaves it taken).
    A folder where no lock can be taken (a file system without ``flock``) is used
    unlocked; one that cannot be written at all is a UsageError."""
    import fcntl

    path = Path(root) / LOCK_FILE
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC, 0o644)
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise UsageError(f"{path}: a symbolic link, not followed; remove it") from None
        raise UsageError(f"--out {root}: cannot write there ({exc.strerror})") from None
    locked = False
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            locked = True
        except BlockingIOError:
            holder = _lock_holder(fd)
            print(f"waiting for another reportgen run on {root}"
                  + (f" (pid {holder})" if holder else "") + " to finish",
                  file=stream or sys.stderr, flush=True)
            fcntl.flock(fd, fcntl.LOCK_EX)
            locked = True
        except OSError:  # ENOLCK and the like: no locking on this file system
            pass
        if locked:
            try:
                os.ftruncate(fd, 0)
                os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
            except OSError:
                pass
        yield
    finally:
        if locked:
            fcntl.flock(fd, fcntl.LOCK_UN)  # also for children forked while it was held
        os.close(fd)


def _lock_holder(fd: int) -> int | None:
    try:
        return int(os.pread(fd, 32, 0).decode("ascii").strip() or "0") or None
    except (OSError, ValueError):
        return None
