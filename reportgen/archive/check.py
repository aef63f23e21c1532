"""The one check every reader of a scene archive runs first.

An archive is a file from anywhere: mailed by a colleague, downloaded, or damaged.
:func:`check_archive` looks at an open archive before anything reads its data, and raises
:class:`~reportgen.archive.h5io.ArchiveError` (``"<path>: <what>"``) for anything the readers
(:func:`reportgen.archive.store.read_archive`, ``reportgen inspect``, the report, figures and
animations) could not take at face value:

* **links**: only hard links (no soft link, no link into another file, no external raw
  data, no virtual dataset), no group that contains itself, at most :data:`MAX_DEPTH`
  levels and :data:`MAX_OBJECTS` objects;
* **sizes, before reading**: each dataset at most :data:`MAX_DATASET_ELEMENTS` elements
  (:data:`MAX_STRINGS` for variable-length text), all together at most :data:`MAX_TOTAL_ELEMENTS`;
  each at most :data:`MAX_DATASET_BYTES` as read (fixed-width text counts its width);
  chunks at most :data:`MAX_CHUNK_BYTES`; a large dataset that stores nothing (declared
  only) is refused; attributes at most :data:`MAX_ATTR_ELEMENTS` elements; the config
  texts at most :data:`MAX_TEXT_BYTES`;
* **types**: numbers, text, or tables of them (no references, opaque or variable-length
  numeric data), no dataset without a dataspace;
* **layout** (SPEC.md "Archive"): the root attributes with their types, ``/config`` and
  ``/config_resolved`` (a JSON object) as scalar text, ``/provenance`` a group, every
  ``/runs/<name>`` with a 1-D ``t``, a 2-D ``y`` of ``len(t)`` rows and one column per
  name of its ``columns`` attribute, numeric ``invariants`` and ``reference``, typed run
  attributes, the ``/checks`` and study tables with their fields, and a sweep's arrays
  all on its members.

What a scene kind reads beyond this (its own analysis entries) is the kind's to check.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from .h5io import FORMAT, FORMAT_VERSION, OLDEST_READABLE, TABLE_ATTR, ArchiveError

# elements of one dataset, of all together, bytes of one: shared with the writers
from .limits import MAX_DATASET_BYTES, MAX_DATASET_ELEMENTS, MAX_TOTAL_ELEMENTS

#: elements of one variable-length text dataset (each becomes a Python string)
MAX_STRINGS = 5_000_000
#: bytes of one chunk (HDF5 decompresses whole chunks)
MAX_CHUNK_BYTES = 64 << 20
#: bytes of one attribute as read
MAX_ATTR_BYTES = 16 << 20
#: elements of one attribute
MAX_ATTR_ELEMENTS = 1_000_000
#: attributes of one object
MAX_ATTRS = 10_000
#: groups and datasets visited (a hard link visited again counts again)
MAX_OBJECTS = 200_000
#: levels of nested groups
MAX_DEPTH = 32
#: bytes of ``/config`` and of ``/config_resolved``
MAX_TEXT_BYTES = 1_000_000
#: nesting of the resolved config's JSON
MAX_JSON_DEPTH = 64
#: a dataset declaring more elements than this must store some bytes
DECLARED_ONLY_ELEMENTS = 100_000

#: run statuses an archive may hold (SPEC.md: numerical health)
STATUSES = ("ok", "inaccurate", "unstable", "failed")
#: HDF5's dimension-scale bookkeeping attributes (object references: not read as data)
_SCALE_ATTRS = frozenset({"DIMENSION_LIST", "REFERENCE_LIST", "CLASS", "NAME",
                          "_Netcdf4Dimid", "_Netcdf4Coordinates", "_nc3_strict"})
#: root attributes: name -> (type, required from format_version)
_ROOT_ATTRS = {
    "format": ("text", 1), "format_version": ("int", 1), "kind": ("text", 1),
    "title": ("text", 1), "config_sha256": ("text", 1), "created": ("text", 1),
    "reportgen_version": ("text", 1), "physics_key": ("text", 2), "scene": ("text", 99),
    "status": ("text", 99), "message": ("text", 99), "wall_time_s": ("number", 99),
}
#: run attributes with a fixed type (when present)
_RUN_TEXT = ("method", "method_reason", "status", "message", "reference_label")
_RUN_NUMBERS = ("rtol", "atol", "h", "nfev", "nsteps", "nreject", "wall_time_s",
                "compile_time_s", "warm_up_time_s")
_RUN_NUMBER_PREFIXES = ("drift_", "scale_")
#: the checks table: field -> type
_CHECK_FIELDS = {"quantity": "text", "value": "number", "reference": "number",
                 "abs_error": "number", "rel_error": "number", "unit": "text",
                 "source": "text"}


class _Problem(Exception):
    """What is wrong, without the path (added once, by :func:`check_archive`)."""


def check_archive(f: h5py.File, path: Path | str) -> None:
    """Check the open archive ``f`` (see the module docstring); ArchiveError
    ``"<path>: <what>"`` names the first problem found."""
    try:
        _check_root(f, FORMAT, FORMAT_VERSION, OLDEST_READABLE)
        _Walk().group(f, "/", (), 0)
        version = int(f.attrs["format_version"])
        _check_text(f, "config", required=True)
        if version >= 2 or "config_resolved" in f:
            resolved = _check_text(f, "config_resolved", required=version >= 2)
            if resolved is not None:
                _check_json(resolved)
        _group(f, "provenance", required=True)
        runs = _group(f, "runs")
        if runs is not None:
            for name in runs:
                _check_run(runs, name)
        _group(f, "analysis")
        if "checks" in f:
            _check_table(f, "checks", _CHECK_FIELDS)  # a dataset (format 2) or a group (3)
        study = _group(f, "study")
        if study is not None and "error_vs_runtime" in study:
            _check_table(study, "error_vs_runtime", {"method": "text"}, where="study/")
        sweep = _group(f, "sweep")
        if sweep is not None:
            _check_sweep(sweep)
    except _Problem as exc:
        raise ArchiveError(f"{path}: {exc}") from None
    except ArchiveError:
        raise
    except (OSError, KeyError, TypeError, ValueError, RuntimeError, OverflowError) as exc:
        raise ArchiveError(f"{path}: malformed archive ({type(exc).__name__}: "
                           f"{_short(exc)})") from None


# ------------------------------------------------------------------- structure
class _Walk:
    """Every object, by its hard links, before any data is read: link kinds, depth,
    cycles, types and sizes."""

    def __init__(self):
        self.objects = 0
        self.elements = 0
        self.counted: set[tuple[int, int]] = set()

    def group(self, group: h5py.Group, name: str, ancestors: tuple, depth: int) -> None:
        me = _address(group)
        if me in ancestors:
            raise _Problem(f"{name}: a link cycle (the group contains itself)")
        if depth > MAX_DEPTH:
            raise _Problem(f"{name}: groups nested more than {MAX_DEPTH} deep")
        self.attrs(group, name)
        ancestors = (*ancestors, me)
        for key in group:
            full = f"{name.rstrip('/')}/{key}"
            self.objects += 1
            if self.objects > MAX_OBJECTS:
                raise _Problem(f"more than {MAX_OBJECTS} objects")
            link = group.get(key, getlink=True)
            if isinstance(link, h5py.ExternalLink):
                raise _Problem(f"{full}: a link into another file "
                               f"({_short(link.filename)}); an archive is self-contained")
            if isinstance(link, h5py.SoftLink):
                raise _Problem(f"{full}: a soft link ({_short(link.path)}); an archive "
                               "holds hard links only")
            obj = group.get(key)
            if isinstance(obj, h5py.Group):
                self.group(obj, full, ancestors, depth + 1)
            elif isinstance(obj, h5py.Dataset):
                self.dataset(obj, full)
            else:
                raise _Problem(f"{full}: not a group or a dataset")

    def dataset(self, ds: h5py.Dataset, name: str) -> None:
        if ds.shape is None:
            raise _Problem(f"{name}: a dataset without a dataspace (no data)")
        if ds.is_virtual or ds.external:
            raise _Problem(f"{name}: its data lives in other files; an archive is "
                           "self-contained")
        kind = _dtype_kind(ds.dtype)
        if kind is None:
            raise _Problem(f"{name}: data of type {_short(ds.dtype)}, not numbers, text "
                           "or a table of them")
        size = _count(ds.shape)
        # variable-length text becomes a Python string per element; fixed-width text (a
        # sweep's status of 10⁷ members) is read as bytes, like numbers
        limit = MAX_STRINGS if kind == "text" and h5py.check_string_dtype(
            ds.dtype).length is None else MAX_DATASET_ELEMENTS
        if size > limit:
            raise _Problem(f"{name}: {_shape(ds.shape)} = {size} elements, more than the "
                           f"{limit} an archive may hold in one dataset")
        if size * ds.dtype.itemsize > MAX_DATASET_BYTES:
            raise _Problem(f"{name}: {_shape(ds.shape)} elements of {ds.dtype.itemsize} bytes, "
                           f"more than the {MAX_DATASET_BYTES >> 20} MiB an archive may hold "
                           "in one dataset")
        if ds.chunks is not None and _count(ds.chunks) * ds.dtype.itemsize > MAX_CHUNK_BYTES:
            raise _Problem(f"{name}: chunks of {_shape(ds.chunks)} elements, larger than "
                           f"{MAX_CHUNK_BYTES >> 20} MiB")
        if size > DECLARED_ONLY_ELEMENTS and ds.id.get_storage_size() == 0:
            raise _Problem(f"{name}: declares {_shape(ds.shape)} elements but stores none")
        me = _address(ds)
        if me not in self.counted:
            self.counted.add(me)
            self.elements += size
            if self.elements > MAX_TOTAL_ELEMENTS:
                raise _Problem(f"more than {MAX_TOTAL_ELEMENTS} elements in all (at {name})")
        self.attrs(ds, name)

    def attrs(self, obj, name: str) -> None:
        names = list(obj.attrs)
        if len(names) > MAX_ATTRS:
            raise _Problem(f"{name}: more than {MAX_ATTRS} attributes")
        for key in names:
            aid = obj.attrs.get_id(key)
            shape = aid.shape
            if shape is not None and _count(shape) > MAX_ATTR_ELEMENTS:
                raise _Problem(f"{name}: attribute {_short(key)} of {_shape(shape)} elements, "
                               f"more than {MAX_ATTR_ELEMENTS}")
            if shape is not None and _count(shape) * aid.dtype.itemsize > MAX_ATTR_BYTES:
                raise _Problem(f"{name}: attribute {_short(key)} of {_shape(shape)} elements "
                               f"of {aid.dtype.itemsize} bytes, more than "
                               f"{MAX_ATTR_BYTES >> 20} MiB")
            if key not in _SCALE_ATTRS and _dtype_kind(aid.dtype) is None:
                raise _Problem(f"{name}: attribute {_short(key)} of type {_short(aid.dtype)}, "
                               "not numbers or text")


def _address(obj) -> tuple[int, int]:
    info = h5py.h5o.get_info(obj.id)
    return info.fileno, info.addr


def _count(shape) -> int:
    n = 1
    for d in shape:
        n *= int(d)
    return n


def _shape(shape) -> str:
    return " x ".join(str(int(d)) for d in shape) or "scalar"


def _dtype_kind(dt: np.dtype) -> str | None:
    """"number", "text", "table" (a compound of numbers and text) or None (refused)."""
    if h5py.check_string_dtype(dt) is not None:
        return "text"
    if dt.names:
        fields = [_dtype_kind(dt.fields[n][0]) for n in dt.names]
        return "table" if all(k in ("number", "text") for k in fields) else None
    if dt.subdtype is not None:
        return None
    if dt.kind in "biufc":
        return "number"
    return None


# ------------------------------------------------------------------- values
def _short(value, limit: int = 80) -> str:
    text = repr(value) if not isinstance(value, BaseException) else str(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def is_number(value) -> bool:
    return (isinstance(value, (int, float, np.integer, np.floating))
            and not isinstance(value, (bool, np.bool_)))


def is_int(value) -> bool:
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def _as_text(value) -> str | None:
    """A text attribute's value, or None if it is not one text (an array, a number)."""
    if isinstance(value, (bytes, np.bytes_)):
        try:
            return bytes(value).decode("utf-8")
        except UnicodeDecodeError:
            return None
    if isinstance(value, str):
        return value
    return None


def _attr(obj, name: str, kind: str, where: str, required: bool = False):
    if name not in obj.attrs:
        if required:
            raise _Problem(f"{where}has no {name} attribute")
        return None
    value = obj.attrs[name]
    if kind == "text":
        text = _as_text(value)
        if text is None:
            raise _Problem(f"{where}attribute {name} must be text (got {_short(value)})")
        return text
    if kind == "int":
        if not is_int(value):
            raise _Problem(f"{where}attribute {name} must be a whole number "
                           f"(got {_short(value)})")
        return int(value)
    if not is_number(value):
        raise _Problem(f"{where}attribute {name} must be a number (got {_short(value)})")
    return value


def _check_root(f: h5py.File, fmt: str, newest: int, oldest: int) -> None:
    if _as_text(f.attrs.get("format")) != fmt:
        raise _Problem("not a reportgen archive (no format attribute 'reportgen')")
    version = _attr(f, "format_version", "int", "", required=True)
    if version > newest:
        raise _Problem(f"written by a newer reportgen (format_version {version} > {newest})")
    if version < oldest:
        raise _Problem(f"format_version {version} is older than {oldest}: not readable by "
                       "this reportgen")
    for name, (kind, since) in _ROOT_ATTRS.items():
        _attr(f, name, kind, "", required=version >= since)
    if not _attr(f, "kind", "text", ""):
        raise _Problem("attribute kind is empty")
    status = _attr(f, "status", "text", "")
    if status is not None and status not in STATUSES:
        raise _Problem(f"attribute status must be one of {', '.join(STATUSES)} "
                       f"(got {_short(status)})")


def _group(parent: h5py.Group, name: str, required: bool = False,
           where: str = "/") -> h5py.Group | None:
    if name not in parent:
        if required:
            raise _Problem(f"has no {where}{name}")
        return None
    obj = parent[name]
    if not isinstance(obj, h5py.Group):
        raise _Problem(f"{where}{name} must be a group, not a dataset")
    return obj


def _dataset(parent: h5py.Group, name: str, where: str, kind: str | None = None,
             ndim: int | None = None) -> h5py.Dataset:
    if name not in parent:
        raise _Problem(f"has no {where}{name}")
    ds = parent[name]
    if not isinstance(ds, h5py.Dataset):
        raise _Problem(f"{where}{name} must be a dataset, not a group")
    if kind is not None and _dtype_kind(ds.dtype) != kind:
        raise _Problem(f"{where}{name} must hold {'numbers' if kind == 'number' else kind} "
                       f"(got {_short(ds.dtype)})")
    if ndim is not None and ds.ndim != ndim:
        raise _Problem(f"{where}{name} must be {ndim}-D (got shape {_shape(ds.shape)})")
    return ds


def _check_text(f: h5py.File, name: str, required: bool) -> str | None:
    """A scalar text dataset of at most MAX_TEXT_BYTES, decoded."""
    if name not in f:
        if required:
            raise _Problem(f"has no /{name}")
        return None
    ds = _dataset(f, name, "/", kind="text", ndim=0)
    info = h5py.check_string_dtype(ds.dtype)
    if info.length is not None and info.length > MAX_TEXT_BYTES:
        raise _Problem(f"/{name} is longer than {MAX_TEXT_BYTES} bytes")
    raw = ds[()]
    text = _as_text(raw)
    if text is None:
        raise _Problem(f"/{name} is not UTF-8 text")
    if len(text) > MAX_TEXT_BYTES:
        raise _Problem(f"/{name} is longer than {MAX_TEXT_BYTES} bytes")
    return text


def _check_json(text: str) -> None:
    try:
        value = json.loads(text)
    except (ValueError, RecursionError) as exc:
        raise _Problem(f"/config_resolved is not valid JSON ({_short(exc)})") from None
    if not isinstance(value, dict):
        raise _Problem("/config_resolved must be a JSON object")
    stack = [(value, 0)]
    while stack:
        item, depth = stack.pop()
        if depth > MAX_JSON_DEPTH:
            raise _Problem(f"/config_resolved is nested more than {MAX_JSON_DEPTH} deep")
        children = item.values() if isinstance(item, dict) else (
            item if isinstance(item, list) else ())
        stack.extend((c, depth + 1) for c in children if isinstance(c, (dict, list)))


def _check_run(runs: h5py.Group, name: str) -> None:
    where = f"/runs/{name}/"
    g = _group(runs, name, where="/runs/")
    t = _dataset(g, "t", where, kind="number", ndim=1)
    y = _dataset(g, "y", where, kind="number", ndim=2)
    if "columns" not in y.attrs:
        raise _Problem(f"{where}y has no columns attribute")
    columns = y.attrs["columns"]
    if isinstance(columns, (str, bytes)):
        columns = np.array([columns], dtype=object)
    if not (isinstance(columns, np.ndarray) and columns.ndim == 1
            and all(_as_text(c) is not None for c in columns)):
        raise _Problem(f"{where}y: attribute columns must be a list of names")
    if y.shape != (t.shape[0], len(columns)):
        raise _Problem(f"{where}y has shape {_shape(y.shape)}; it must be len(t) x "
                       f"len(columns) = {t.shape[0]} x {len(columns)}")
    for sub, required in (("invariants", True), ("reference", False)):
        group = _group(g, sub, required=required, where=where)
        for q in group if group is not None else ():
            _dataset(group, q, f"{where}{sub}/", kind="number")
    for key in g.attrs:
        if key in _RUN_TEXT:
            _attr(g, key, "text", where)
        elif key in _RUN_NUMBERS or key.startswith(_RUN_NUMBER_PREFIXES):
            _attr(g, key, "number", where)
    status = _attr(g, "status", "text", where)
    if status is not None and status not in STATUSES:
        raise _Problem(f"{where}attribute status must be one of {', '.join(STATUSES)} "
                       f"(got {_short(status)})")


def _check_table(parent: h5py.Group, name: str, fields: dict[str, str],
                 where: str = "") -> None:
    """A table: a 1-D compound dataset (format ≤ 2) or a group of 1-D columns of one
    length listed in its attr ``table_columns`` (format 3), with ``fields`` of their kinds."""
    if isinstance(parent.get(name), h5py.Group):
        _check_column_table(parent[name], f"/{where}{name}", fields)
        return
    ds = _dataset(parent, name, f"/{where}", kind="table", ndim=1)
    for field, kind in fields.items():
        if field not in ds.dtype.names:
            raise _Problem(f"/{where}{name} has no field {field}")
        if _dtype_kind(ds.dtype.fields[field][0]) != kind:
            raise _Problem(f"/{where}{name}: field {field} must hold "
                           f"{'numbers' if kind == 'number' else kind}")


def _check_column_table(g: h5py.Group, where: str, fields: dict[str, str]) -> None:
    if TABLE_ATTR not in g.attrs:
        raise _Problem(f"{where} is a group without the attribute {TABLE_ATTR}: not a table")
    names = g.attrs[TABLE_ATTR]
    if isinstance(names, (str, bytes)):
        names = np.array([names], dtype=object)
    if not (isinstance(names, np.ndarray) and names.ndim == 1
            and all(_as_text(n) is not None for n in names)):
        raise _Problem(f"{where}: attribute {TABLE_ATTR} must be a list of column names")
    columns = [_as_text(n) for n in names]
    rows = None
    for column in columns:
        ds = _dataset(g, column, f"{where}/", ndim=1)
        if _dtype_kind(ds.dtype) not in ("number", "text"):
            raise _Problem(f"{where}/{column} must hold numbers or text")
        if rows is not None and ds.shape[0] != rows:
            raise _Problem(f"{where}/{column} has {ds.shape[0]} rows, the table {rows}")
        rows = ds.shape[0]
    for field, kind in fields.items():
        if field not in columns:
            raise _Problem(f"{where} has no field {field}")
        if _dtype_kind(g[field].dtype) != kind:
            raise _Problem(f"{where}: field {field} must hold "
                           f"{'numbers' if kind == 'number' else kind}")


def _check_sweep(g: h5py.Group) -> None:
    where = "/sweep/"
    status = _dataset(g, "status", where, kind="text", ndim=1)
    members = status.shape[0]
    message = _dataset(g, "message", where, kind="text", ndim=1)
    if message.shape[0] != members:
        raise _Problem(f"{where}message has {message.shape[0]} entries, status {members}")
    for sub, kind, required in (("values", "number", True), ("analysis", "number", True),
                                ("labels", "text", False)):
        group = _group(g, sub, required=required, where=where)
        for key in group if group is not None else ():
            ds = _dataset(group, key, f"{where}{sub}/", kind=kind, ndim=1)
            if ds.shape[0] != members:
                raise _Problem(f"{where}{sub}/{key} has {ds.shape[0]} entries for "
                               f"{members} members")
    for key in ("paths", "shape"):
        text = _attr(g, key, "text", where)
        if text is None:
            continue
        try:
            value = json.loads(text)
        except (ValueError, RecursionError):
            raise _Problem(f"{where}attribute {key} is not valid JSON") from None
        if not isinstance(value, list) or (key == "paths" and not all(
                isinstance(v, str) for v in value)):
            raise _Problem(f"{where}attribute {key} must be a JSON list")
    points = _group(g, "points", where=where)
    for name in points if points is not None else ():
        pset = _group(points, name, where=f"{where}points/")
        here = f"{where}points/{name}/"
        member = _dataset(pset, "member", here, kind="number", ndim=1)
        if member.dtype.kind not in "iu":
            raise _Problem(f"{here}member must hold whole numbers")
        n = member.shape[0]
        width = None
        if "component" in pset:
            width = _dataset(pset, "component", here, kind="text", ndim=1).shape[0]
        for key in pset:
            if key in ("member", "component", "point"):
                continue
            ds = _dataset(pset, key, here, kind="number")
            if ds.ndim not in (1, 2) or ds.shape[0] != n or (
                    ds.ndim == 2 and width is not None and ds.shape[1] != width):
                raise _Problem(f"{here}{key} has shape {_shape(ds.shape)} for {n} points")


def limits() -> dict[str, Any]:
    """The limits :func:`check_archive` applies (for the docs and the tests)."""
    return {name: value for name, value in globals().items()
            if name.startswith("MAX_") or name == "DECLARED_ONLY_ELEMENTS"}
