"""Re-verify archives: ``reportgen verify`` and :func:`reportgen.verify` (issue 43).

An archive holds the config it was run from.  Verifying re-simulates that config with the
installed reportgen, into a temporary folder (nothing is written beside the archive), and
compares every stored number of the two archives: each dataset (every field of a table)
and each attribute, bit for bit.  What measures the machine rather than the physics (run
times, dates, whether a peer's measurement came from the cache: :data:`TIMINGS`) and
HDF5's own bookkeeping (dimension scales refer to objects by file address:
:data:`BOOKKEEPING`) are not compared; the library versions of ``/provenance`` are not
compared but said when they differ, and so is the code identity (the physics key hashes
the config, reportgen's version and the code the kind's simulation imports).

A difference is given as the largest absolute and relative difference of the values and
the relative tolerance that would pass them, so that a colleague can tell round-off of
another numpy from another result.
"""

from __future__ import annotations

import math
import tempfile
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["Difference", "Verification", "verify_archive", "archives_in", "TIMINGS"]

#: facts of an archive that measure the machine, not the physics: run, compile and
#: start-up times, when and where a measurement was made, whether it came from the peer
#: cache, how often a timing was repeated, a sweep's throughput, whether the study kept
#: to its time budget (every such name the archive writes: tests/test_verify.py)
TIMINGS = frozenset({"created", "wall_time_s", "compile_time_s", "warm_up_time_s",
                     "members_start_up_s", "members_wall_time_s", "sweep_members_per_s",
                     "measured_at", "machine", "cached", "repeats", "over_budget"})
#: attributes HDF5 and netCDF keep for themselves (dimension scales by file address)
BOOKKEEPING = frozenset({"DIMENSION_LIST", "REFERENCE_LIST", "CLASS", "NAME",
                         "_Netcdf4Dimid", "_Netcdf4Coordinates", "_NCProperties"})
#: not compared, said when different: the library versions of the run
PROVENANCE = "provenance"
#: the columns that name a row of a table whose rows a time budget chooses (the study's
#: error-against-run-time table: how many tolerances are timed depends on the machine);
#: such tables are compared row by row where both runs measured a row
ROW_KEY = ("method", "label", "kind", "tolerance", "h")
#: a table's row coordinate (netCDF's dimension of it), compared with the table itself
ROW_COORDINATE = "row"
#: the row numbers of the tables of a format-2 archive (format 3 keeps them in the
#: table, marked as an index like every other coordinate that only counts)
INDEXES = frozenset({"check", "study/row"})
#: the root attribute that identifies config, version and simulation code together
PHYSICS_KEY = "physics_key"
#: root attributes naming the release and format that wrote the archive: said, not compared
RELEASE = ("reportgen_version", "format_version")


@dataclass(frozen=True)
class Difference:
    """One stored item that is not the same after re-simulating: its ``path`` (a dataset,
    ``dataset:field`` for a table's column, ``path@attribute``), the largest absolute and
    relative difference of its values (``inf`` when they cannot be compared: another
    shape, text, an item missing on one side), and what is different in words."""

    path: str
    max_abs: float
    max_rel: float
    what: str = ""

    @property
    def passing_rtol(self) -> float:
        """The relative tolerance that would pass this difference (the next power of ten
        at or above :attr:`max_rel`), ``inf`` if none would."""
        if not math.isfinite(self.max_rel):
            return math.inf
        if self.max_rel <= 0:
            return 0.0
        return 10.0 ** math.ceil(math.log10(self.max_rel))


@dataclass
class Verification:
    """The outcome of re-verifying one archive."""

    archive: Path
    scene: str = ""
    #: "identical", "different" or "unreadable"
    verdict: str = "unreadable"
    message: str = ""
    differences: list[Difference] = field(default_factory=list)
    compared: int = 0
    #: the stored and re-computed physics keys (config, reportgen version, simulation code)
    stored_key: str = ""
    key: str = ""
    #: provenance item (a library, the processor, the source revision, the simulation
    #: code): (stored, now), where they differ
    libraries: dict[str, tuple[str, str]] = field(default_factory=dict)
    #: (reportgen version, format version) that wrote the archive, and of the re-run
    release: tuple[str, str] = ("", "")
    release_now: tuple[str, str] = ("", "")
    #: items the re-run stores that the archive does not (a later release stores more)
    added: int = 0
    seconds: float = 0.0

    @property
    def identical(self) -> bool:
        return self.verdict == "identical"

    @property
    def code_changed(self) -> bool:
        """Whether the config, reportgen's version or the kind's simulation code differs
        from the run's (the physics key is their hash)."""
        return bool(self.stored_key and self.key and self.stored_key != self.key)


def archives_in(paths: Iterable[str | Path]) -> list[Path]:
    """The archives named: each path an archive, or a folder searched for ``run.h5``
    (hidden folders skipped), in order."""
    found: list[Path] = []
    for path in map(Path, paths):
        if path.is_dir():
            found += sorted(p for p in path.rglob("run.h5")
                            if not any(part.startswith(".") for part in
                                       p.relative_to(path).parts[:-1]))
        else:
            found.append(path)
    return found


def verify_archive(archive: str | Path,
                   progress: Callable[[float], None] | None = None) -> Verification:
    """Re-simulate ``archive`` from its own stored config with the installed code and
    compare every stored number (see the module's docstring)."""
    from ..archive.store import ArchiveError, read_archive
    from ..errors import ConfigError
    from ..kinds import load_scene
    from ..scene.config import parse_config_text
    from .stages import simulate_scene

    archive = Path(archive)
    result = Verification(archive=archive)
    start = time.perf_counter()
    try:
        data = read_archive(archive)
    except ArchiveError as exc:
        result.message = str(exc)
        return result
    result.scene = str(data.attrs.get("scene") or archive.parent.name)
    result.stored_key = str(data.attrs.get(PHYSICS_KEY, ""))
    try:
        scene = load_scene(parse_config_text(data.config_text,
                                             Path(f"{result.scene}.toml")))
    except ConfigError as exc:
        result.verdict = "different"
        result.message = ("its stored config is not valid for this reportgen: "
                          + "; ".join(exc.problems))
        return result
    result.key = scene.physics_key()
    result.release = tuple(str(data.attrs.get(k, "")) for k in RELEASE)
    with tempfile.TemporaryDirectory(prefix="reportgen-verify-") as tmp:
        again = simulate_scene(scene, Path(tmp), progress, key=result.key)
        compared = compare_archives(archive, again)
        result.differences, result.compared, result.libraries, result.added = compared
        result.release_now = _release(again)
    result.verdict = "different" if result.differences else "identical"
    result.seconds = time.perf_counter() - start
    return result


def _release(archive: Path) -> tuple[str, str]:
    import h5py

    with h5py.File(archive, "r") as f:
        return tuple(str(_text(f.attrs.get(k, ""))) for k in RELEASE)


def compare_archives(stored: Path, again: Path
                     ) -> tuple[list[Difference], int, dict[str, tuple[str, str]], int]:
    """The differences of the items ``stored`` holds from those of ``again`` (numbers
    first, largest relative difference first; then text; then items the re-run lacks),
    how many items were compared, the library versions that differ, and how many items
    only ``again`` holds."""
    import h5py

    with h5py.File(stored, "r") as a, h5py.File(again, "r") as b:
        old, new = _items(a), _items(b)
        libraries = {k: (str(_text(v)), str(_text(b[PROVENANCE].attrs.get(k, ""))))
                     for k, v in a[PROVENANCE].attrs.items()
                     if PROVENANCE in b and _text(v) != _text(b[PROVENANCE].attrs.get(k, ""))}
    differences = []
    keyed = {path.rsplit("/", 1)[0] for path, value in old.items()
             if isinstance(value, np.ndarray) and set(ROW_KEY) <= set(value.dtype.names or ())}
    for path in sorted(old):
        if path not in new:
            differences.append(Difference(path, math.inf, math.inf, "not in the re-run"))
        elif path.rsplit("/", 1)[0] in keyed and path.rsplit("/", 1)[-1] == ROW_COORDINATE:
            continue  # the rows of a keyed table: matched by their key instead
        elif isinstance(old[path], np.ndarray) and set(ROW_KEY) <= set(old[path].dtype.names
                                                                        or ()):
            differences += _compare_rows(path, old[path], new[path])
        else:
            differences += _compare(path, old[path], new[path])
    order = {"": 0, "not in the re-run": 2}
    differences.sort(key=lambda d: (order.get(d.what, 1), -d.max_rel, d.path))
    return differences, len(old), libraries, len(new.keys() - old.keys())


def _items(f) -> dict[str, Any]:
    """Every compared value of an open archive: ``path`` -> dataset values, and
    ``path@name`` -> attribute values (the root's as ``@name``).  A table is one item
    whichever way it is stored (a compound dataset, format 2, or a group of columns, format
    3: read back as one structured array), so archives of either format compare; the
    coordinates that only number rows or index an axis (:data:`INDEXES`) are not results."""
    import h5py

    from ..archive.h5io import TABLE_ATTR, is_dimension, is_table, read_table

    items: dict[str, Any] = {}
    tables: list[str] = []

    def attrs(prefix: str, obj) -> None:
        for name, value in obj.attrs.items():
            if name not in TIMINGS and name not in BOOKKEEPING and name != PHYSICS_KEY \
                    and name != TABLE_ATTR and not (prefix == "" and name in RELEASE):
                items[f"{prefix}@{name}"] = value

    def visit(name: str, obj) -> None:
        if name == PROVENANCE or name.startswith(PROVENANCE + "/"):
            return
        if any(name.startswith(t + "/") for t in tables):  # a column: in its table
            if not is_dimension(obj):
                attrs(name, obj)
            return
        if is_dimension(obj) or (name in INDEXES and getattr(obj, "is_scale", False)):
            return
        attrs(name, obj)
        if isinstance(obj, h5py.Group) and is_table(obj):
            tables.append(name)
            items[name] = read_table(obj)
        elif isinstance(obj, h5py.Dataset) and obj.dtype != h5py.ref_dtype:
            items[name] = obj[()]

    attrs("", f)
    f.visititems(visit)
    return items


def _text(value: Any) -> Any:
    """``value`` with its bytes decoded (in lists too), for comparing text."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.ndarray):
        return _text(value.tolist())
    if isinstance(value, list | tuple):
        return [_text(v) for v in value]
    return value


def _compare(path: str, old: Any, new: Any) -> list[Difference]:
    """The differences of one stored item (a table: of each of its columns that is not a
    timing)."""
    a, b = np.asarray(old), np.asarray(new)
    if a.dtype.names or b.dtype.names:
        if a.dtype.names != b.dtype.names or a.shape != b.shape:
            return [Difference(path, math.inf, math.inf, "another table layout")]
        return [d for name in a.dtype.names if name not in TIMINGS
                for d in _compare(f"{path}:{name}", a[name], b[name])]
    if a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes() \
            and a.dtype.kind not in "OU":
        return []
    if a.dtype.kind in "biufc" and b.dtype.kind in "biufc":
        if a.shape != b.shape:
            return [Difference(path, math.inf, math.inf, f"shape {a.shape} → {b.shape}")]
        return _numbers(path, a, b)
    if _text(a.tolist()) == _text(b.tolist()):
        return []
    return [Difference(path, math.inf, math.inf, "text differs")]


def _compare_rows(path: str, old: np.ndarray, new: Any) -> list[Difference]:
    """A table whose rows a time budget chooses, compared on the rows both runs measured
    (matched by :data:`ROW_KEY`): a row only one run measured is no difference."""
    new = np.asarray(new)
    if old.dtype.names != new.dtype.names:
        return [Difference(path, math.inf, math.inf, "another table layout")]

    def key(row) -> tuple:
        values = (_text(row[k].tolist() if hasattr(row[k], "tolist") else row[k])
                  for k in ROW_KEY)
        return tuple(None if isinstance(v, float) and math.isnan(v) else v for v in values)

    theirs = {key(row): i for i, row in enumerate(new)}
    pairs = [(i, theirs[key(row)]) for i, row in enumerate(old) if key(row) in theirs]
    if not pairs:
        return [Difference(path, math.inf, math.inf, "no row measured by both runs")]
    mine, other = (np.array(idx) for idx in zip(*pairs, strict=True))
    return _compare(path, old[mine], new[other])


def _numbers(path: str, a: np.ndarray, b: np.ndarray) -> list[Difference]:
    """The largest absolute and relative difference of two numeric arrays of one shape
    (NaN against NaN is the same; NaN against a number, or infinities of other sign,
    differ infinitely); [] when the same."""
    a = a.astype(complex if a.dtype.kind == "c" or b.dtype.kind == "c" else float)
    b = b.astype(a.dtype)
    nan_a, nan_b = np.isnan(a), np.isnan(b)
    same_inf = np.isinf(a) & (a == b)
    if np.any(nan_a != nan_b) or np.any(np.isinf(a) != np.isinf(b)) or \
            np.any(np.isinf(a) & ~same_inf):
        return [Difference(path, math.inf, math.inf, "a non-finite value differs")]
    finite = ~(nan_a | np.isinf(a))
    if not np.any(finite):
        return []
    diff = np.abs(a[finite] - b[finite])
    if not np.any(diff):
        return []
    scale = np.maximum(np.abs(a[finite]), np.abs(b[finite]))
    rel = np.where(scale > 0, diff / np.where(scale > 0, scale, 1.0), 0.0)
    return [Difference(path, float(diff.max()), float(rel.max()))]


def describe(result: Verification) -> list[str]:
    """The lines that say a verification's outcome: the verdict, then (when different) a
    table of the differences and what else differs."""
    if result.verdict == "unreadable":
        return [result.message]
    if result.identical:
        lines = [f"identical ({result.compared} stored items compared bit for bit; run "
                 "times not compared)"]
    else:
        lines = [f"different: {result.message}" if result.message else
                 f"different in {len(result.differences)} of {result.compared} stored items"]
    if result.differences:
        width = max(len("item"), *(len(d.path) for d in result.differences[:40]))
        lines.append(f"  {'item':<{width}}  {'max |Δ|':>10}  {'max rel':>10}  "
                     f"{'passes at rtol':>14}")
        for d in result.differences[:40]:
            lines.append(f"  {d.path:<{width}}  {_g(d.max_abs):>10}  {_g(d.max_rel):>10}  "
                         f"{_g(d.passing_rtol):>14}" + (f"  ({d.what})" if d.what else ""))
        if len(result.differences) > 40:
            lines.append(f"  … and {len(result.differences) - 40} more")
    if result.added:
        lines.append(f"  the re-run stores {result.added} items more (not compared)")
    then, now = result.release, result.release_now
    if then != now and all(then):
        lines.append(f"  written by reportgen {then[0]} (archive format {then[1]}); "
                     f"re-run by {now[0]} (format {now[1]})")
    if result.code_changed:
        lines.append("  the physics key differs: reportgen's version or the kind's "
                     "simulation code is not the run's")
    elif result.stored_key:
        lines.append("  the same reportgen version and simulation code as the run's")
    for library, (then, now) in sorted(result.libraries.items()):
        lines.append(f"  {library}: {then} then, {now} now")
    return lines


def _g(x: float) -> str:
    return "none" if math.isinf(x) else f"{x:.2g}"
