"""Low-level HDF5 encoding shared by the scene archive and the audit archive.

Arrays carry the fletcher32 checksum (a corrupted chunk raises on read instead of
returning wrong numbers) and shuffle + gzip; strings are UTF-8; structured arrays
become compound tables; nested dicts become groups.
"""

from __future__ import annotations

import functools
import json
import os
import platform
import re
import sys
from collections.abc import Callable
from typing import Any

import h5py
import numpy as np

STR = h5py.string_dtype("utf-8")

#: the archive format (see :mod:`reportgen.archive.store`)
FORMAT = "reportgen"
FORMAT_VERSION = 3
#: oldest format this reader opens (1: no dimension scales, no resolved config; 2: the
#: checks and study tables as compound datasets, ``/analysis``'s dimension scales in
#: ``/analysis`` only, modes indexed from 0, text with an empty ``units``)
OLDEST_READABLE = 1


class ArchiveError(Exception):
    """An archive that cannot be read: names the file and what is wrong."""


#: provenance keys that name the software, printed in a report's colophon; the others
#: (the machine's processor, the source revision, the code hashes) are for ``inspect`` and
#: ``verify``
LIBRARIES = ("python", "numpy", "scipy", "h5py", "hdf5", "matplotlib", "numba", "platform")


def provenance(code: dict[str, str] | None = None) -> dict[str, str]:
    """What an archive was written with: the library versions (read from the installed
    distributions' metadata: importing matplotlib only for its version cost a fifth of a
    second of every simulate stage), the processor (``cpu``), the revision of reportgen's
    source (``source``) and ``code``, the identity of the code of each stage (name ->
    hash)."""
    from importlib.metadata import PackageNotFoundError, version

    def installed(name: str) -> str:
        try:
            return version(name)
        except PackageNotFoundError:
            return "not installed"

    return {
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "scipy": installed("scipy"),
        "h5py": h5py.__version__,
        "hdf5": h5py.version.hdf5_version,
        "matplotlib": installed("matplotlib"),
        "numba": installed("numba"),
        "platform": platform.platform(),
        "cpu": _cpu_model(),
        "source": _source_revision(),
        **{f"{stage} code": value for stage, value in (code or {}).items()},
    }


@functools.cache
def _cpu_model() -> str:
    """The processor's model name (/proc/cpuinfo on Linux), else what the platform says."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as f:
            for line in f:
                key, _, value = line.partition(":")
                if key.strip() in ("model name", "Model", "Hardware") and value.strip():
                    return " ".join(value.split())[:200]
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown"


@functools.cache
def _source_revision() -> str:
    """The git commit of reportgen's source tree when it runs from a checkout ("git
    <hash>", "+ changes" when its package files differ from that commit), else "release"
    (an installed wheel: its version is the identity).  git is asked with a time limit
    and never from the user's folders."""
    import subprocess
    from pathlib import Path

    package = Path(__file__).resolve().parent.parent
    root = package.parent
    if not (root / ".git").exists():
        return "release"
    # GIT_OPTIONAL_LOCKS=0: git status would otherwise refresh (write) the checkout's index
    env = {**os.environ, "GIT_OPTIONAL_LOCKS": "0"}
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"],
                              capture_output=True, text=True, timeout=5, env=env)
        changed = subprocess.run(["git", "-C", str(root), "status", "--porcelain",
                                  "--untracked-files=no", "--", package.name],
                                 capture_output=True, text=True, timeout=5, env=env)
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    commit = head.stdout.strip()
    if head.returncode != 0 or not re.fullmatch(r"[0-9a-f]{40}", commit):
        return "unknown"
    return f"git {commit}" + (" + changes" if changed.returncode != 0 or changed.stdout.strip()
                              else "")


def dataset(group: h5py.Group, name: str, data) -> h5py.Dataset:
    data = np.asarray(data)
    if data.dtype.kind in "US":
        data = data.astype(object)
    if data.dtype == object:
        return group.create_dataset(name, data=data, dtype=STR)
    if data.ndim == 0 or data.size == 0:
        return group.create_dataset(name, data=data)
    return group.create_dataset(
        name, data=data, chunks=True, fletcher32=True, shuffle=True, compression="gzip",
        compression_opts=4,
    )


def attr_value(value):
    if isinstance(value, str):
        return value
    if isinstance(value, (bool, np.bool_)):
        return np.bool_(value)
    if isinstance(value, (list, tuple)) and value and all(isinstance(v, str) for v in value):
        return np.array(value, dtype=STR)
    return value


def write_mapping(group: h5py.Group, mapping: dict[str, Any],
                  describe: Callable[[str], dict[str, str]] | None = None,
                  prefix: str = "") -> None:
    """Scalars and strings become attrs, arrays datasets, dicts subgroups.

    ``describe(path)`` (path below ``group``, "/"-joined) gives an entry's CF attributes:
    a dataset carries them, and a group's scalar attrs have theirs in its attr
    :data:`QUANTITIES_ATTR` (JSON)."""
    described = {}
    for key, value in mapping.items():
        path = f"{prefix}{key}"
        if isinstance(value, dict):
            write_mapping(group.create_group(key), value, describe, path + "/")
        elif isinstance(value, np.ndarray) or (
            isinstance(value, (list, tuple)) and not all(isinstance(v, str) for v in value)
        ):
            ds = dataset(group, key, value)
            if describe is not None:
                ds.attrs.update(describe(path))
        else:
            group.attrs[key] = attr_value(value)
            if describe is not None:
                described[key] = describe(path)
    if described:
        group.attrs[QUANTITIES_ATTR] = json.dumps(described, ensure_ascii=False, sort_keys=True)


def table(group: h5py.Group, name: str, records: np.ndarray) -> h5py.Dataset:
    """A structured array as a compound dataset; string fields become UTF-8 strings."""
    fields = []
    for fname in records.dtype.names:
        kind = records.dtype[fname].kind
        fields.append((fname, STR if kind in "OUS" else records.dtype[fname]))
    dtype = np.dtype(fields)
    out = np.empty(records.shape, dtype=dtype)
    for fname in records.dtype.names:
        col = records[fname]
        if col.dtype.kind == "S":  # UTF-8 bytes (numpy's own cast would decode ASCII)
            out[fname] = [v.decode("utf-8") for v in col]
        else:
            out[fname] = col.astype(str).astype(object) if col.dtype.kind in "OU" else col
    return group.create_dataset(name, data=out, chunks=True if out.size else None,
                                fletcher32=bool(out.size))


def decode(value):
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray) and value.dtype == object:
        return [decode(v) for v in value.tolist()]
    if isinstance(value, np.generic):
        return value.item()
    return value


#: a group attr holding the CF attributes of the group's scalar attrs (JSON), not a result
QUANTITIES_ATTR = "__quantities__"


#: the attr marking a dimension scale of ``/analysis`` (an index, not a result)
DIMENSION_ATTR = "reportgen_dimension"


def is_dimension(item) -> bool:
    """Whether ``item`` is one of the index datasets ``archive.store._analysis_dimensions``
    adds to ``/analysis`` (every reader of results skips them)."""
    return isinstance(item, h5py.Dataset) and bool(item.attrs.get(DIMENSION_ATTR, False))


def read_mapping(group: h5py.Group) -> dict[str, Any]:
    out: dict[str, Any] = {k: decode(v) for k, v in group.attrs.items()
                           if k != QUANTITIES_ATTR}
    for key, item in group.items():
        if isinstance(item, h5py.Group):
            out[key] = read_mapping(item)
        elif is_dimension(item):
            continue
        elif item.dtype.kind == "O":
            out[key] = decode(item[()])
        else:
            out[key] = item[()]
    return out


#: the attr of a table stored as a group of columns: its column names, in order
TABLE_ATTR = "table_columns"


def column_table(parent: h5py.Group, name: str, records: np.ndarray, dim: str,
                 row_long_name: str,
                 describe: Callable[[str], dict[str, Any]] | None = None) -> h5py.Group:
    """The structured array ``records`` as the group ``name`` of one dataset per field on
    the dimension scale ``dim`` (format 3; netCDF's table, which xarray opens as named,
    typed columns): text as UTF-8 strings, flags as int8 with xarray's ``dtype = "bool"``,
    numbers as they are.  ``describe(field)`` gives a column's CF attributes; the group's
    attr :data:`TABLE_ATTR` lists the columns in order (:func:`read_table` reads it back)."""
    g = parent.create_group(name, track_order=True)  # xarray lists the columns in order
    rows = dataset(g, dim, np.arange(len(records), dtype=np.int64))
    rows.attrs.update({"long_name": row_long_name, "units": "1",
                       DIMENSION_ATTR: np.bool_(True)})
    rows.make_scale(dim)
    for field in records.dtype.names:
        column = records[field]
        if column.dtype.kind in "OUS":
            text = [v.decode("utf-8") if isinstance(v, bytes) else str(v) for v in column]
            ds = g.create_dataset(field, shape=(len(text),), dtype=STR)
            if text:
                ds[...] = np.array(text, dtype=object)
        elif column.dtype.kind == "b":
            ds = dataset(g, field, column.astype(np.int8))
            ds.attrs["dtype"] = "bool"  # xarray's mark of a flag stored as int8
        else:
            ds = dataset(g, field, column)
        if describe is not None:
            ds.attrs.update(describe(field))
        ds.dims[0].attach_scale(rows)
    g.attrs[TABLE_ATTR] = np.array(records.dtype.names, dtype=STR)
    return g


def is_table(obj) -> bool:
    """Whether ``obj`` is a table: a compound dataset (format ≤ 2) or a group of columns
    (:func:`column_table`, format 3)."""
    if isinstance(obj, h5py.Group):
        return TABLE_ATTR in obj.attrs
    return isinstance(obj, h5py.Dataset) and obj.dtype.names is not None


def table_columns(g: h5py.Group) -> list[str]:
    """The column names of a group of columns, in order."""
    names = decode(g.attrs[TABLE_ATTR])
    return [names] if isinstance(names, str) else [str(n) for n in names]


def read_table(ds: h5py.Dataset | h5py.Group) -> np.ndarray:
    """A table as a structured array, text as str objects: a compound dataset (format ≤ 2)
    or a group of columns (format 3), read alike."""
    if isinstance(ds, h5py.Group):
        return _read_column_table(ds)
    raw = ds[()]
    fields = [(n, object if raw.dtype[n].kind in "OS" else raw.dtype[n]) for n in raw.dtype.names]
    out = np.empty(raw.shape, dtype=fields)
    for n in raw.dtype.names:
        col = raw[n]
        out[n] = [decode(v) for v in col] if raw.dtype[n].kind in "OS" else col
    return out


def _read_column_table(g: h5py.Group) -> np.ndarray:
    names = table_columns(g)
    columns = {n: g[n] for n in names}
    lengths = {c.shape for c in columns.values()}
    if len(lengths) > 1 or any(len(shape) != 1 for shape in lengths):
        raise ValueError(f"the columns of table {g.name} differ in length or are not 1-D")
    n = next(iter(lengths))[0] if lengths else 0

    def field(ds: h5py.Dataset):
        if h5py.check_string_dtype(ds.dtype) is not None:
            return object
        return np.bool_ if ds.attrs.get("dtype") == "bool" else ds.dtype

    out = np.empty(n, dtype=[(name, field(ds)) for name, ds in columns.items()])
    for name, ds in columns.items():
        values = ds[()]
        out[name] = [decode(v) for v in values] if field(ds) is object else values
    return out
