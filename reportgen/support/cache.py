"""The user cache of peer (scipy) measurements: ``$XDG_CACHE_HOME/reportgen``.

A scipy run of the work-precision study costs ~20 µs per right-hand-side call, a
compiled one ~30 ns; the peers are most of a study's time and give the same numbers
for the same problem.  Their rows are kept here, keyed by the problem (model,
parameters, initial state, output grid, tolerance ladder, reference, library
versions; see :func:`reportgen.core.study.peer_key`), with when and on what machine
they were measured.  Our own methods are re-timed on every run.

One JSON file per (problem, method) under ``peers/``, written atomically; a corrupt or
unreadable entry is a miss.  ``REPORTGEN_NO_CACHE=1`` (``reportgen run --no-cache``)
bypasses the cache; ``reportgen cache info|clear`` shows or empties it.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from .. import cache_root
from .fsutil import atomic_write

#: set to a non-empty value to bypass the cache (what ``--no-cache`` does)
NO_CACHE_ENV = "REPORTGEN_NO_CACHE"
#: bump when the stored rows change meaning
CACHE_FORMAT = 1


class PeerCache:
    """Peer rows of the work-precision study by key (see the module docstring)."""

    def __init__(self, root: Path | None = None):
        self.root = Path(root) if root is not None else cache_root()

    @property
    def folder(self) -> Path:
        return self.root / "peers"

    def _path(self, key: str) -> Path:
        return self.folder / f"{key}.json"

    def get(self, key: str) -> list[dict[str, Any]] | None:
        """The stored rows of ``key``, or None (missing, unreadable or another format)."""
        try:
            entry = json.loads(self._path(key).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        if not isinstance(entry, dict) or entry.get("format") != CACHE_FORMAT:
            return None
        rows = entry.get("rows")
        return rows if isinstance(rows, list) else None

    def put(self, key: str, rows: list[dict[str, Any]]) -> None:
        """Store ``rows`` (each carries ``measured_at`` and ``machine``) under ``key``."""
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
            atomic_write(self._path(key), json.dumps(
                {"format": CACHE_FORMAT, "rows": rows}, sort_keys=True).encode("utf-8"))
        except OSError:
            pass  # a read-only or full cache costs time, never a result

    def entries(self) -> list[Path]:
        return sorted(self.folder.glob("*.json")) if self.folder.is_dir() else []

    def info(self) -> str:
        files = self.entries()
        size = sum(p.stat().st_size for p in files)
        lines = [f"peer measurement cache: {self.root}",
                 f"  {len(files)} entries, {size / 1024:.1f} KiB"]
        dates = []
        for p in files:
            rows = self.get(p.stem) or []
            dates.extend(r.get("measured_at", "") for r in rows if r.get("measured_at"))
        if dates:
            lines.append(f"  measured between {min(dates)} and {max(dates)}")
        if os.environ.get(NO_CACHE_ENV):
            lines.append(f"  (bypassed: {NO_CACHE_ENV} is set)")
        return "\n".join(lines)

    def clear(self) -> int:
        """Delete every entry; return how many."""
        files = self.entries()
        for p in files:
            try:
                p.unlink()
            except OSError:
                pass
        return len(files)


def default_cache() -> PeerCache | None:
    """The user cache, or None when bypassed (``REPORTGEN_NO_CACHE``)."""
    if os.environ.get(NO_CACHE_ENV):
        return None
    return PeerCache()
