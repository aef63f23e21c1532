"""Sweeps: a family of runs of one scene from one config, in one archive.

A ``[sweep]`` table in any kind's config names config keys by their dotted paths and
the values each takes, as a list or as a range::

    [sweep]
    initial.theta = { start = 0.05, stop = 3.1, num = 2000 }   # or "initial.theta" = ...
    params.l = [0.5, 1.0, 2.0]
    zip = false      # several keys: their grid (default) or, with zip = true, paired
    store = 5        # members whose whole trajectory is kept, chosen evenly (default 5)

``{ start, stop, num }`` takes ``spacing = "linear"`` (default) or ``"log"``.  Every
member is the config with those values put in; the rest of the config is the template.

The archive holds the family (dimension ``member``)::

    /sweep/values/<path>       (M,) the member's value of each swept key
    /sweep/analysis/<name>     (M,) each numeric result of the kind's analysis per member
    /sweep/labels/<name>       (M,) each text result (the heavy top's case, say)
    /sweep/status              (M,) "ok", or why the member has no result
    /sweep/message             (M,) what went wrong, if anything
    /sweep/points/<set>/...    per-member point sets of varying length (a Poincaré
                               section's crossings), flat on the dimension ``point``:
                               ``member`` (P,) int64 and one array per column
    /runs/member_<i>           the whole run of the ``store`` members kept

A kind may return per-member point sets (:meth:`reportgen.scene.simulation.Simulation.member_points`);
each member keeps at most ``max_points`` points of each set (default 2000, the first ones),
and its result ``<set>_points`` counts all it had, so a report can say what was capped.

Members run in blocks; each finished block is saved on disk next to the archive (in
``.sweep-<key>/``) as it comes back and dropped from memory, so a sweep killed half-way
(the client, or a worker of a Dask cluster) resumes at its first unfinished block.  With
``submit`` (``reportgen run --scheduler``) the blocks run on a Dask cluster, a bounded
window of them at a time (:class:`reportgen.pipeline.stages.DaskBlocks`).  The family is
then assembled from the saved blocks into compact arrays: float64 results, and text
(status, message, labels) as codes into its few distinct values, held as shared strings
(8 bytes a member: a 10⁷-member family is ~50 bytes a member in all).  Memory stays
bounded by the per-member scalars and the capped point sets, never by trajectories.
"""

from __future__ import annotations

import copy
import itertools
import json
import math
import os
import shutil
import struct
import zipfile
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..archive.limits import MAX_DATASET_BYTES, MAX_DATASET_ELEMENTS, MAX_TOTAL_ELEMENTS
from ..support.fsutil import atomic_write, open_back, temp_name
from .config import ConfigError, _short
from .units import is_quantity_text

__all__ = ["SweepSpec", "SweepData", "PointSet", "parse_sweep", "run_sweep", "member_data",
           "block_arrays", "block_fits", "text_codes", "text_array"]

#: keys of a range value; the others of [sweep] that are not swept config paths
RANGE_KEYS = frozenset({"start", "stop", "num", "spacing"})
OPTIONS = frozenset({"zip", "store", "block", "max_points"})
MAX_MEMBERS = 10_000_000
MAX_STORE = 50
DEFAULT_STORE = 5
#: points of each point set kept per member (its first ones), and the most a config may ask
DEFAULT_MAX_POINTS = 2000
LIMIT_MAX_POINTS = 1_000_000
#: longer text results of a member (a reference's description, say) are not kept
MAX_LABEL = 40
#: a member's short numeric arrays (a spectrum) become one result per element
MAX_SPREAD = 12
#: the status of a member whose run gave its results
OK = "ok"
#: arrays a saved block may hold (a kind's results, its texts, its point sets' columns:
#: dozens), and components of one point set
MAX_BLOCK_ARRAYS = 10_000
MAX_POINT_COMPONENTS = 1_000


@dataclass(frozen=True)
class Axis:
    """One swept key: its dotted path and how its values were given."""

    path: str
    values: tuple[float, ...] = ()  # a list
    start: float = math.nan  # or a range
    stop: float = math.nan
    num: int = 0
    spacing: str = "linear"

    @property
    def size(self) -> int:
        return len(self.values) if self.values else self.num

    def array(self) -> np.ndarray:
        if self.values:
            return np.asarray(self.values, dtype=np.float64)
        if self.spacing == "log":
            return np.geomspace(self.start, self.stop, self.num)
        return np.linspace(self.start, self.stop, self.num)

    def resolved(self) -> Any:
        if self.values:
            return list(self.values)
        return {"start": self.start, "stop": self.stop, "num": self.num,
                "spacing": self.spacing}


@dataclass(frozen=True)
class SweepSpec:
    """A validated ``[sweep]`` table."""

    axes: tuple[Axis, ...]
    zip: bool = False
    store: int = DEFAULT_STORE
    block: int = 0  # members per block; 0: chosen by size
    max_points: int = DEFAULT_MAX_POINTS  # points of each point set kept per member

    @property
    def shape(self) -> tuple[int, ...]:
        return (self.axes[0].size,) if self.zip else tuple(a.size for a in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    @property
    def paths(self) -> list[str]:
        return [a.path for a in self.axes]

    def block_size(self, minimum: int = 1) -> int:
        """Members per block (``block``, else about 100 blocks of ``minimum`` to 20000
        members: a kind whose members are cheap asks for large blocks, so that writing a
        finished block does not cost more than running it)."""
        return self.block or int(min(max(math.ceil(self.size / 100), minimum), 20_000))

    def values(self) -> dict[str, np.ndarray]:
        """Each swept key's value for every member (grid order: the last key fastest)."""
        arrays = [a.array() for a in self.axes]
        if self.zip:
            return {a.path: v for a, v in zip(self.axes, arrays, strict=True)}
        grids = np.meshgrid(*arrays, indexing="ij")
        return {a.path: g.ravel() for a, g in zip(self.axes, grids, strict=True)}

    def stored_members(self) -> np.ndarray:
        """The ``store`` members kept whole: spread evenly from the first to the last."""
        if self.store == 0:
            return np.zeros(0, dtype=np.int64)
        return np.unique(np.round(np.linspace(0, self.size - 1, min(self.store, self.size)))
                         .astype(np.int64))

    def resolved(self) -> dict[str, Any]:
        """The table as JSON, itself a valid ``[sweep]`` table (paths as dotted keys,
        ranges stay ranges, options filled in): part of the physics key."""
        return {**{a.path: a.resolved() for a in self.axes}, "zip": self.zip,
                "store": self.store, "block": self.block, "max_points": self.max_points}


def _flatten(table: dict, prefix: str = "") -> list[tuple[str, Any]]:
    """(dotted path, value) of every swept key: nested tables (TOML's dotted keys) are
    walked down to a list or a range table."""
    out = []
    for key, value in table.items():
        path = f"{prefix}{key}"
        if not prefix and key in OPTIONS:
            continue
        if isinstance(value, dict) and value and not set(value) & RANGE_KEYS:
            out.extend(_flatten(value, path + "."))  # a table of paths, not a range
        else:
            out.append((path, value))
    return out


def _number(x: Any) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def parse_sweep(table: Any, label: str,
                convert: Callable[[str, Any], Any] | None = None,
                ) -> tuple[SweepSpec | None, list[str]]:
    """The validated ``[sweep]`` table, or None and every problem found (each naming the
    file, the key, the rule and the value).

    ``convert(path, value)``: a value given as text with a unit ("5 deg") as the number in
    the unit the swept key declares (ValueError naming the rule), as the key itself would
    be converted; the sweep then holds numbers in the declared units."""
    problems: list[str] = []

    def bad(key: str, rule: str, value: Any) -> None:
        problems.append(f"{label}: key 'sweep{'.' + key if key else ''}': {rule} "
                        f"(got {_short(value)})")

    def number(path: str, key: str, value: Any) -> float | None:
        """The swept ``value`` at ``key`` as a finite number, else None (problem noted)."""
        if isinstance(value, str) and convert is not None:
            try:
                value = convert(path, value)
            except ValueError as exc:
                bad(key, str(exc), value)
                return None
        if _number(value):
            return float(value)
        rule = "must be a finite number"
        if is_quantity_text(value):
            rule += " (this key declares no unit, so text with a unit is not converted)"
        bad(key, rule, value)
        return None

    if not isinstance(table, dict):
        bad("", "must be a table of swept keys", table)
        return None, problems
    zip_ = table.get("zip", False)
    if not isinstance(zip_, bool):
        bad("zip", "must be true or false", zip_)
    store = table.get("store", DEFAULT_STORE)
    if not isinstance(store, int) or isinstance(store, bool) or not 0 <= store <= MAX_STORE:
        bad("store", f"must be a whole number from 0 to {MAX_STORE}", store)
    block = table.get("block", 0)
    if not isinstance(block, int) or isinstance(block, bool) or block < 0:
        bad("block", "must be a whole number of members per block (0: automatic)", block)
    max_points = table.get("max_points", DEFAULT_MAX_POINTS)
    if not isinstance(max_points, int) or isinstance(max_points, bool) \
            or not 0 <= max_points <= LIMIT_MAX_POINTS:
        bad("max_points", f"must be a whole number of points kept per member, from 0 to "
                          f"{LIMIT_MAX_POINTS}", max_points)
    axes = []
    for path, value in _flatten(table):
        if isinstance(value, list):
            if not value:
                bad(path, "a list of values must hold at least one", value)
                continue
            numbers = []
            for i, v in enumerate(value):
                v = number(path, f"{path}.{i}", v)
                if v is None:
                    break
                numbers.append(v)
            else:
                axes.append(Axis(path, values=tuple(numbers)))
        elif isinstance(value, dict):
            unknown = sorted(set(value) - RANGE_KEYS)
            start, stop, num = value.get("start"), value.get("stop"), value.get("num")
            spacing = value.get("spacing", "linear")
            if unknown:
                bad(f"{path}.{unknown[0]}", "unknown key of a range (start, stop, num, "
                                            "spacing)", value[unknown[0]])
            elif start is None or stop is None or num is None:
                bad(path, "a range is { start, stop, num } with optional spacing", value)
            elif (start := number(path, path + ".start", start)) is None:
                pass
            elif (stop := number(path, path + ".stop", stop)) is None:
                pass
            elif not isinstance(num, int) or isinstance(num, bool) or not 1 <= num <= MAX_MEMBERS:
                bad(path + ".num", f"must be a whole number from 1 to {MAX_MEMBERS}", num)
            elif spacing not in ("linear", "log"):
                bad(path + ".spacing", 'must be "linear" or "log"', spacing)
            elif spacing == "log" and not (start > 0 and stop > 0):
                bad(path, "a log range needs start > 0 and stop > 0", value)
            else:
                axes.append(Axis(path, start=float(start), stop=float(stop), num=num,
                                 spacing=spacing))
        else:
            bad(path, "must be a list of values or a range { start, stop, num }", value)
    if not axes and not problems:
        bad("", "names no swept key (e.g. initial.theta = { start = 0.1, stop = 3, num = 100 })",
            table)
    if problems:
        return None, problems
    spec = SweepSpec(axes=tuple(axes), zip=zip_, store=store, block=block,
                     max_points=max_points)
    if zip_ and len({a.size for a in axes}) > 1:
        bad("zip", "paired keys need the same number of values",
            {a.path: a.size for a in axes})
    elif spec.size > MAX_MEMBERS:
        bad("", f"the grid has {spec.size} members, more than {MAX_MEMBERS}",
            {a.path: a.size for a in axes})
    return (None, problems) if problems else (spec, [])


def member_data(template: dict, assignments: dict[str, float]) -> dict:
    """The config data of one member: ``template`` with each dotted path set."""
    data = copy.deepcopy(template)
    for path, value in assignments.items():
        node = data
        *parents, last = path.split(".")
        for key in parents:
            child = node.get(key)
            if not isinstance(child, dict):
                child = node[key] = {}
            node = child
        current = node.get(last)
        node[last] = int(value) if isinstance(current, int) and float(value).is_integer() \
            else float(value)
    return data


def corner_members(spec: SweepSpec) -> list[dict[str, float]]:
    """The members validated before anything runs: every combination of each key's
    smallest and largest value (paired keys: the first and last member)."""
    values = spec.values()
    if spec.zip:
        picks = sorted({0, spec.size - 1})
        return [{p: float(v[i]) for p, v in values.items()} for i in picks]
    ends = [sorted({float(a.array().min()), float(a.array().max())}) for a in spec.axes]
    return [dict(zip(spec.paths, combo, strict=True)) for combo in itertools.product(*ends)]


@dataclass
class PointSet:
    """Points of a varying number per member (a surface of section's crossings), flat:
    row k belongs to member ``member[k]``; ``/sweep/points/<set>`` of the archive.

    Attributes
    ----------
    columns : dict of str -> ndarray, shape (P,) or (P, d)
        One array per quantity, rows in the member's own order (time, say).
    member : ndarray of int64, shape (P,)
        The member each row belongs to (in a block, counted from the block's first).
    components : tuple of str, length d
        Names of the second axis of the (P, d) columns (a state's columns), if any.
    attrs : dict
        What the points are (strings, numbers, lists of strings): the same for every
        member, taken from the first member that has the set.
    """

    columns: dict[str, np.ndarray]
    member: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    components: tuple[str, ...] = ()
    attrs: dict[str, Any] = field(default_factory=dict)

    @property
    def rows(self) -> int:
        return len(next(iter(self.columns.values()))) if self.columns else 0

    def of_member(self, i: int, limit: int) -> PointSet:
        """The first ``limit`` rows, all given to member ``i``."""
        n = min(self.rows, limit)
        return PointSet({k: np.asarray(v)[:n] for k, v in self.columns.items()},
                        np.full(n, i, dtype=np.int64), tuple(self.components), dict(self.attrs))

    def counts(self, members: int) -> np.ndarray:
        """(members,) the number of rows each member has."""
        return np.bincount(np.asarray(self.member, dtype=np.int64), minlength=members)

    @staticmethod
    def section_crossings(results, components, surface, axes) -> dict[str, PointSet]:
        """A member's surface-of-section crossings as the point set ``poincare``, from its
        analysis entry ``poincare`` (``t``, the two plotted coordinates ``u`` and ``v``, and
        the whole ``state`` there, of ``components``); ``surface`` ((coordinate, value,
        direction)) and ``axes`` (the plotted pair) describe it.  Empty without crossings."""
        pts = results.analysis.get("poincare")
        if pts is None:
            return {}
        return {"poincare": PointSet(
            columns={"t": pts["t"], "u": pts["u"], "v": pts["v"], "state": pts["state"]},
            components=tuple(components), attrs={"surface": list(surface), "axes": list(axes)})}

    @staticmethod
    def concat(sets: list[PointSet], offsets: list[int] | None = None) -> PointSet:
        """One set of the rows of ``sets`` in turn, their members shifted by ``offsets``."""
        offsets = offsets if offsets is not None else [0] * len(sets)
        names = dict.fromkeys(k for s in sets for k in s.columns)
        first = next((s for s in sets if s.attrs or s.components), sets[0])
        return PointSet(
            {k: np.concatenate([np.asarray(s.columns[k], dtype=np.float64) for s in sets
                                if k in s.columns]) for k in names},
            np.concatenate([np.asarray(s.member, dtype=np.int64) + o
                            for s, o in zip(sets, offsets, strict=True)]),
            tuple(first.components), dict(first.attrs))


@dataclass
class SweepBlock:
    """What a kind's ``sweep_block`` returns for members ``lo:hi``."""

    analysis: dict[str, np.ndarray]
    status: np.ndarray  # (n,) str
    message: np.ndarray | None = None  # (n,) str
    labels: dict[str, np.ndarray] = field(default_factory=dict)  # text results, (n,) str
    #: per-member point sets, members counted from the block's first
    points: dict[str, PointSet] = field(default_factory=dict)


@dataclass
class SweepData:
    """A sweep's results: ``/sweep`` of the archive."""

    values: dict[str, np.ndarray]
    analysis: dict[str, np.ndarray] = field(default_factory=dict)
    labels: dict[str, np.ndarray] = field(default_factory=dict)
    status: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=object))
    message: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=object))
    attrs: dict[str, Any] = field(default_factory=dict)
    #: per-member point sets of varying length (``/sweep/points``)
    points: dict[str, PointSet] = field(default_factory=dict)

    @property
    def size(self) -> int:
        return len(self.status)

    @property
    def ok(self) -> np.ndarray:
        return np.asarray(self.status) == OK

    def counts(self) -> dict[str, int]:
        """Members of each status, by status name (sorted)."""
        codes, names = text_codes(self.status)
        found = np.bincount(codes, minlength=len(names))
        return {n: int(found[i]) for i, n in sorted(enumerate(names), key=lambda x: x[1])
                if found[i]}


def text_codes(values) -> tuple[np.ndarray, list[str]]:
    """``values`` (n,) text (str, StrEnum, bytes of UTF-8 or objects) as (codes, names):
    ``names[codes[i]]`` is ``str(values[i])``, names in order of first appearance.

    A sweep's status, message and labels hold a few distinct values over up to 10⁷
    members: each distinct value is found by one vectorised comparison, the rest (a
    member's own message, say) one by one."""
    arr = np.asarray(values)
    arr = arr.ravel() if arr.ndim else arr.reshape(1)
    n = arr.size
    codes = np.zeros(n, dtype=np.int32)
    raw: list[Any] = []
    rest: np.ndarray | None = None  # indexes not yet coded (None: all of them)
    while len(raw) < 16:
        sub = arr if rest is None else arr[rest]
        if sub.size == 0:
            break
        hit = np.asarray(sub == sub[0], dtype=bool)
        if hit.shape != sub.shape or not hit[0]:
            break  # not comparable as a whole (a NaN, say): one by one below
        where = np.flatnonzero(hit) if rest is None else rest[hit]
        codes[where] = len(raw)
        raw.append(sub[0])
        rest = np.flatnonzero(~hit) if rest is None else rest[~hit]
    if rest is None:
        rest = np.arange(n)
    if rest.size:
        index = {_text(v): i for i, v in enumerate(raw)}
        for i in rest.tolist():
            codes[i] = index.setdefault(_text(arr[i]), len(index))
        names = list(index)
    else:
        names = [_text(v) for v in raw]
    return codes.astype(_code_dtype(len(names))), names


def _text(value: Any) -> str:
    if isinstance(value, (bytes, np.bytes_)):
        return bytes(value).decode("utf-8", "replace")
    return str(value)


def _code_dtype(distinct: int) -> np.dtype:
    return np.dtype(np.uint8 if distinct <= 1 << 8 else np.uint16 if distinct <= 1 << 16
                    else np.int32)


def text_array(codes: np.ndarray, names: list[str]) -> np.ndarray:
    """The object array of ``names[codes]``: one Python string per distinct value, shared
    by every member that has it (8 bytes a member, not one string each)."""
    table = np.empty(len(names), dtype=object)
    table[:] = [str(n) for n in names]
    return table[np.asarray(codes, dtype=np.intp)] if len(names) else \
        np.full(len(codes), "", dtype=object)


def block_arrays(block: SweepBlock) -> dict[str, np.ndarray]:
    """A finished block as flat numpy arrays (what a block file holds and a Dask worker
    sends back): numbers as float64, each text array as codes into its distinct values
    (``status/codes``, ``status/names``), point sets as their columns."""
    n = len(block.status)
    arrays = {f"analysis/{k}": np.asarray(v, dtype=np.float64) for k, v in block.analysis.items()}
    texts = {"status": block.status,
             "message": block.message if block.message is not None else np.full(n, "")}
    texts.update({f"labels/{k}": v for k, v in block.labels.items()})
    for name, values in texts.items():
        codes, names = text_codes(values)
        arrays[f"{name}/codes"] = codes
        arrays[f"{name}/names"] = np.asarray(names, dtype=str) if names else np.zeros(0, "U1")
    for name, points in block.points.items():
        arrays[f"points/{name}/member"] = np.asarray(points.member, dtype=np.int64)
        arrays[f"points/{name}/components"] = np.asarray(points.components, dtype=str)
        arrays[f"points/{name}/attrs"] = np.asarray(json.dumps(points.attrs))
        arrays.update({f"points/{name}/columns/{k}": np.asarray(v, dtype=np.float64)
                       for k, v in points.columns.items()})
    return arrays


def _save_block(path: Path, block: SweepBlock | dict[str, np.ndarray]) -> None:
    """One finished block (a SweepBlock or its :func:`block_arrays`), written whole
    under a temporary name, then renamed."""
    arrays = block if isinstance(block, dict) else block_arrays(block)
    tmp = temp_name(path)
    with open(tmp, "wb") as fh:
        np.savez(fh, **arrays)
        fh.flush()
        os.fsync(fh.fileno())
    os.replace(tmp, path)


def _open_block(path: Path):
    """A saved block open for reading (:func:`reportgen.support.fsutil.open_back`: a regular
    file, not a link, no larger than the numbers an archive holds in all)."""
    return open_back(path, 8 * MAX_TOTAL_ELEMENTS)


def _zip_entries(fh) -> int | None:
    """How many arrays the saved block ``fh`` says it holds, from its end record (read
    before the directory, whose every entry costs memory): None if it has none there."""
    fh.seek(0, os.SEEK_END)
    if fh.tell() < 22:
        return None
    fh.seek(-22, os.SEEK_END)  # numpy writes no archive comment: the record ends the file
    end = fh.read(22)
    fh.seek(0)
    return struct.unpack("<H", end[10:12])[0] if end[:4] == b"PK\x05\x06" else None


def _block_shapes(path: Path) -> dict[str, tuple[tuple[int, ...], np.dtype]] | None:
    """Each array of a saved block by name, (shape, dtype) from its header alone, or None
    if the file is not a block numpy wrote: too many arrays, an entry over the bytes of
    one dataset, a header claiming more than its entry holds, objects."""
    readers = {(1, 0): np.lib.format.read_array_header_1_0,
               (2, 0): np.lib.format.read_array_header_2_0}
    shapes = {}
    try:
        with _open_block(path) as fh:
            entries = _zip_entries(fh)
            if entries is None or entries > MAX_BLOCK_ARRAYS:
                return None
            with zipfile.ZipFile(fh) as zf:
                for info in zf.infolist():
                    if not info.filename.endswith(".npy") or info.file_size > MAX_DATASET_BYTES:
                        return None
                    with zf.open(info) as entry:
                        reader = readers.get(np.lib.format.read_magic(entry))
                        if reader is None:
                            return None
                        shape, _, dtype = reader(entry)
                    if dtype.hasobject or math.prod(shape) * dtype.itemsize > info.file_size:
                        return None
                    shapes[info.filename[:-len(".npy")]] = (tuple(shape), dtype)
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile, struct.error):
        return None
    return shapes


def _family_share(shapes: dict, members: int, max_points: int) -> tuple[set[str], int] | None:
    """What a saved block of ``members`` members gives the family: the names of its
    results and texts (each a column of the family's size) and its point sets' numbers;
    None if an array is not what such a block holds (one entry per member of each result
    and text, at most a distinct text per member, at most ``max_points`` points a member)."""
    columns: set[str] = set()
    points = 0
    for key, (shape, dtype) in shapes.items():
        n = math.prod(shape)
        parts = key.split("/")
        if parts[0] == "points" and len(parts) >= 3:
            if parts[2] == "attrs":
                ok = shape == () and dtype.itemsize <= 1 << 16
            elif parts[2] == "components":
                ok = len(shape) == 1 and n <= MAX_POINT_COMPONENTS
            else:  # member, columns/<name>: rows of points, a column may be (P, d)
                ok = (parts[2] in ("member", "columns") and 1 <= len(shape) <= 2
                      and shape[0] <= members * max_points and n <= MAX_DATASET_ELEMENTS)
                points += n
        elif parts[-1] == "names":  # the distinct texts of a text column
            ok = len(shape) == 1 and shape[0] <= max(members, 1)
        elif (parts[0] == "analysis" and len(parts) == 2) or parts[-1] == "codes" or (
                key in ("status", "message") or (parts[0] == "labels" and len(parts) == 2)):
            ok = shape == (members,)  # a result, or a text column (as codes, or before)
            columns.add(key.removesuffix("/codes"))
        else:
            ok = False
        if not ok:
            return None
    return columns, points


def block_fits(path: Path, members: int, *, size: int, max_points: int) -> bool:
    """Whether the saved block ``path`` is one a sweep may take as its ``members`` members
    (of ``size`` in all, at most ``max_points`` points each), read from its arrays' headers
    alone: what a killed run left, or a file put there.  A block that does not fit (a 3 MB
    file inflating to 3 GB, arrays of another length, more results than an archive holds
    for the family) is run again, never read."""
    shapes = _block_shapes(path)
    share = None if shapes is None else _family_share(shapes, members, max_points)
    return share is not None and len(share[0]) * size + share[1] <= MAX_TOTAL_ELEMENTS


def _block_texts(z) -> dict[str, tuple[np.ndarray, list[str]]]:
    """Every text array of a saved block as (codes, names), by name ("status",
    "message", "labels/<name>")."""
    out = {}
    for key in z.files:
        if key.endswith("/codes") and not key.startswith("points/"):
            name = key[:-len("/codes")]
            out[name] = (z[key], [str(v) for v in z[f"{name}/names"]])
        elif key in ("status", "message") or (key.startswith("labels/") and
                                              key.count("/") == 1):
            out[key] = text_codes(z[key])  # a block saved before the codes
    return out


def _load_points(z) -> dict[str, PointSet]:
    """The point sets of a saved block (``points/<set>/...`` entries of the npz)."""
    names = dict.fromkeys(k.split("/")[1] for k in z.files if k.startswith("points/"))
    points = {}
    for name in names:
        prefix = f"points/{name}/columns/"
        points[name] = PointSet(
            {k[len(prefix):]: z[k] for k in z.files if k.startswith(prefix)},
            z[f"points/{name}/member"], tuple(str(c) for c in z[f"points/{name}/components"]),
            json.loads(str(z[f"points/{name}/attrs"])))
    return points


def partial_folder(folder: Path, key: str) -> Path:
    """Where a sweep keeps its finished blocks until the archive is written."""
    return Path(folder) / f".sweep-{key[:16]}"


#: ``submit(chunks)``: run the blocks ``chunks`` (an iterator of ``(b, lo, hi, values)``:
#: block number, members ``lo:hi``, their swept values) elsewhere (a Dask cluster,
#: :class:`reportgen.pipeline.stages.DaskBlocks`) and yield ``(b, result)`` as each
#: finishes, in any order; ``result`` a SweepBlock or its :func:`block_arrays`.  It takes
#: the next chunk only when it has room for it, so the blocks waiting to run are never
#: all in memory; a block that fails for good raises, naming it.
Submit = Callable[[Iterator[tuple[int, int, int, dict[str, np.ndarray]]]],
                  Iterator[tuple[int, "SweepBlock | dict[str, np.ndarray]"]]]


def run_sweep(spec: SweepSpec, run_block: Callable[[int, int, dict[str, np.ndarray]], SweepBlock],
              folder: Path, key: str, progress: Callable[[float], None] | None = None,
              min_block: int = 1, submit: Submit | None = None) -> tuple[SweepData, int]:
    """Every member's results, block by block: ``run_block(lo, hi, values)`` gives members
    ``lo:hi`` (``values``: the swept keys' values of those members; blocks of at least
    ``min_block`` members unless the table sets ``block``).  With ``submit`` the blocks
    run elsewhere and come back in any order (:data:`Submit`).  Each finished block is
    saved under ``folder`` at once and dropped from memory; blocks already finished there
    for this ``key`` (a killed run) are not run again.  The family is then assembled from
    the saved blocks into compact arrays: float64 results, text as shared strings.
    Returns the sweep and the number of members resumed from disk."""
    values = spec.values()
    size, block = spec.size, spec.block_size(min_block)
    partial = partial_folder(folder, key)
    partial.mkdir(parents=True, exist_ok=True)
    for stale in partial.glob(".*.tmp"):  # a block half-written when a run was killed
        stale.unlink(missing_ok=True)
    atomic_write(partial / "key", key.encode("utf-8"))  # renamed over a link, never through
    starts = list(range(0, size, block))
    ends = [min(lo + block, size) for lo in starts]
    paths = [partial / f"block-{b:06d}.npz" for b in range(len(starts))]
    done: set[int] = set()
    resumed = 0
    for b, path in enumerate(paths):
        if path.exists() and block_fits(path, ends[b] - starts[b], size=size,
                                        max_points=spec.max_points):
            done.add(b)
            resumed += ends[b] - starts[b]

    def chunks() -> Iterator[tuple[int, int, int, dict[str, np.ndarray]]]:
        for b in range(len(starts)):
            if b not in done:
                lo, hi = starts[b], ends[b]
                yield b, lo, hi, {p: v[lo:hi] for p, v in values.items()}

    finished = (submit(chunks()) if submit is not None
                else ((b, run_block(lo, hi, vals)) for b, lo, hi, vals in chunks()))
    try:
        for b, result in finished:
            if b in done:
                continue  # a block that came back twice (run again after a lost worker)
            _save_block(paths[b], result)
            del result
            done.add(b)
            if progress is not None:
                progress(len(done) / len(starts))
    finally:
        close = getattr(finished, "close", None)
        if close is not None:
            close()  # a pool stops what it still runs
    missing = [b for b in range(len(starts)) if b not in done]
    if missing:
        raise RuntimeError(f"the sweep's members {starts[missing[0]]}:{ends[missing[0]]} "
                           f"(and {len(missing) - 1} more blocks) never came back; the "
                           f"{len(done)} finished blocks are kept in {partial} and a rerun "
                           "resumes them")
    _check_family(paths, starts, ends, size, spec.max_points)
    data = _assemble(paths, starts, size, values)
    data.attrs = {"paths": json.dumps(spec.paths), "shape": json.dumps(spec.shape),
                  "zip": spec.zip, "block": block}
    for pset in data.points.values():
        pset.attrs["max_points"] = spec.max_points
    return data, resumed


class _TextColumn:
    """One text array of the family, assembled block by block as codes."""

    def __init__(self, size: int):
        self.codes = np.zeros(size, dtype=np.int32)
        self.index: dict[str, int] = {"": 0}  # members of a block without it: ""

    def put(self, lo: int, codes: np.ndarray, names: list[str]) -> None:
        mapping = np.array([self.index.setdefault(n, len(self.index)) for n in names],
                           dtype=np.int32)
        if mapping.size:
            self.codes[lo:lo + len(codes)] = mapping[np.asarray(codes, dtype=np.intp)]

    def array(self) -> np.ndarray:
        return text_array(self.codes, list(self.index))


def _check_family(paths: list[Path], starts: list[int], ends: list[int], size: int,
                  max_points: int) -> None:
    """Before the saved blocks are read: each is still one of this sweep's, and the family
    they make holds no more numbers than an archive takes (each result any block gives is
    a column of ``size``); else a RuntimeError saying so."""
    columns: set[str] = set()
    points = 0
    for path, lo, hi in zip(paths, starts, ends, strict=True):
        shapes = _block_shapes(path)
        share = None if shapes is None else _family_share(shapes, hi - lo, max_points)
        if share is None:
            raise RuntimeError(f"{path}: the sweep's saved block of members {lo}:{hi} changed "
                               "while it ran, or is not a block of this sweep")
        columns |= share[0]
        points += share[1]
    numbers = len(columns) * size + points
    if numbers > MAX_TOTAL_ELEMENTS:
        raise RuntimeError(f"the sweep's {size} members gave {len(columns)} results and texts "
                           f"and {points} points: {numbers:.3g} numbers, more than the "
                           f"{MAX_TOTAL_ELEMENTS:.0e} an archive holds (fewer members, or a "
                           "smaller sweep.max_points)")


def _assemble(paths: list[Path], starts: list[int], size: int,
              values: dict[str, np.ndarray]) -> SweepData:
    """The family from its saved blocks, read one at a time into compact arrays."""
    analysis: dict[str, np.ndarray] = {}
    texts: dict[str, _TextColumn] = {"status": _TextColumn(size),
                                     "message": _TextColumn(size)}
    having: dict[str, list[tuple[PointSet, int]]] = {}
    for path, lo in zip(paths, starts, strict=True):
        with _open_block(path) as fh, np.load(fh, allow_pickle=False) as z:
            for key in z.files:
                if key.startswith("analysis/"):
                    column = z[key]
                    target = analysis.setdefault(key[len("analysis/"):],
                                                 np.full(size, np.nan))
                    target[lo:lo + column.size] = column
            for name, (codes, names) in _block_texts(z).items():
                texts.setdefault(name, _TextColumn(size)).put(lo, codes, names)
            for name, pset in _load_points(z).items():
                having.setdefault(name, []).append((pset, lo))
    points = {name: PointSet.concat([p for p, _ in sets], [lo for _, lo in sets])
              for name, sets in having.items()}
    labels = {name[len("labels/"):]: column.array() for name, column in texts.items()
              if name.startswith("labels/")}
    return SweepData(values=values, analysis=analysis, labels=labels,
                     status=texts["status"].array(), message=texts["message"].array(),
                     points=points)


def discard_partial(folder: Path, key: str) -> None:
    """Remove a sweep's finished blocks once its archive holds them."""
    shutil.rmtree(partial_folder(folder, key), ignore_errors=True)


def generic_block(make_member: Callable[[dict[str, float]], Any], values: dict[str, np.ndarray],
                  points: Callable[[Any], dict[str, PointSet]] | None = None,
                  max_points: int = DEFAULT_MAX_POINTS) -> SweepBlock:
    """Members run one by one as whole scenes (``make_member(assignments)`` builds one;
    its ``simulate`` is called): every number of their ``/analysis`` becomes a sweep
    result (a short array, such as a spectrum, one per element: ``name_1``, ``name_2``
    ...), every short text a label.  ``points(results)`` (optional) gives a member's point
    sets: each keeps its first ``max_points`` rows, and the result ``<set>_points`` counts
    all of them.  The fallback of kinds without a compiled ensemble."""
    n = len(next(iter(values.values())))
    rows: list[dict[str, float]] = []
    texts: list[dict[str, str]] = []
    kept: dict[str, list[PointSet]] = {}
    status = np.full(n, OK, dtype=object)
    message = np.full(n, "", dtype=object)
    for i in range(n):
        assignments = {p: float(v[i]) for p, v in values.items()}
        row: dict[str, float] = {}
        text: dict[str, str] = {}
        try:
            results = make_member(assignments).simulate()
            for name, value in results.analysis.items():
                if isinstance(value, (bool, np.bool_)):
                    row[name] = float(value)
                elif isinstance(value, (int, float, np.integer, np.floating)):
                    row[name] = float(value)
                elif isinstance(value, str) and len(value) <= MAX_LABEL:
                    text[name] = value
                elif (isinstance(value, np.ndarray) and value.ndim == 1
                      and value.size <= MAX_SPREAD and value.dtype.kind in "fiub"):
                    for j, x in enumerate(value):  # frequencies -> frequencies_1, _2, ...
                        row[f"{name}_{j + 1}"] = float(x)
            for name, found in (points(results) if points is not None else {}).items():
                row[f"{name}_points"] = float(found.rows)
                kept.setdefault(name, []).append(found.of_member(i, max_points))
            status[i] = OK if results.status == "ok" else results.status
            message[i] = results.message
        except ConfigError as exc:
            status[i], message[i] = "invalid", "; ".join(exc.problems)[:300]
        except Exception as exc:  # noqa: BLE001 - one member's failure is its own
            status[i], message[i] = "failed", f"{type(exc).__name__}: {exc}"[:300]
        rows.append(row)
        texts.append(text)
    names = dict.fromkeys(k for row in rows for k in row)
    analysis = {k: np.array([row.get(k, np.nan) for row in rows]) for k in names}
    label_names = dict.fromkeys(k for text in texts for k in text)
    labels = {k: np.array([text.get(k, "") for text in texts], dtype=object)
              for k in label_names}
    return SweepBlock(analysis=analysis, status=status, message=message, labels=labels,
                      points={k: PointSet.concat(sets) for k, sets in kept.items()})
