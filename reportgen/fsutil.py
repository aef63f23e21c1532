"""Atomic file writes: a crash never leaves a half-written file under a final name."""

from __future__ import annotations

import os
import uuid
from pathlib import Path


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
        with open(tmp, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def remove_stale_temps(folder: Path) -> list[Path]:
    """Delete temporary files left by writers that no longer run (e.g. killed with -9).

    Temporary names carry the writer's pid; a file whose pid is alive belongs to a
    concurrent writer and is left alone.
    """
    removed = []
    folder = Path(folder)
    if not folder.is_dir():
        return removed
    for path in folder.rglob(".*.tmp"):
        parts = path.name.split(".")
        try:
            pid = int(parts[-3])
        except (IndexError, ValueError):
            continue
        if pid == os.getpid() or _alive(pid):
            continue
        try:
            path.unlink()
            removed.append(path)
        except OSError:
            pass
    return removed


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
            os.link(path, staged)
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
