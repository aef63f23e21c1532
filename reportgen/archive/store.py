"""The HDF5 archive: the only module that touches h5py.

Layout (``format_version`` 3, see SPEC.md "Archive")::

    /                         attrs: format, format_version, kind, title, config_sha256,
                                     physics_key, created, reportgen_version, scene,
                                     status, message, wall_time_s
    /config                   scalar string: the TOML text exactly as given
    /config_resolved          scalar string: the validated config, presets and defaults
                              filled in, as JSON (what the report step reads)
    /provenance               attrs: python, numpy, scipy, h5py, hdf5, matplotlib, numba,
                              platform (the software), cpu (the processor's model),
                              source ("git <commit>" [+ changes], or "release") and
                              "simulation code" (hash of the code the kind's simulation runs)
    /runs/<name>/t            (N,) float64, dimension scale ``t``
    /runs/<name>/component    (d,) strings, dimension scale: the state components' names
    /runs/<name>/y            (N, d) float64, dims (t, component), attrs columns,
                              column_units, column_long_names, column_symbols
    /runs/<name>/invariants/<q>  (N,) float64, also linked as /runs/<name>/<q> (dim t)
    /runs/<name>/reference/<c>   (N,) float64: exact or reference solution of column c,
                              also linked as /runs/<name>/reference_<c>
                              (a run the results give under two names is one group with
                              two hard links, e.g. /runs/main = /runs/loops)
    /analysis                 attrs (scalars, strings; their CF attributes in the attr
                              __quantities__, JSON) and datasets (arrays); sub-dicts are
                              groups, each holding the coordinates of the dimensions its
                              arrays use: t (the main run's times), a numbered dimension
                              1 … n (mode), else an index 0 … n − 1
    /checks                   table (a group of columns on its dimension scale check):
                              quantity, value, reference, scale, abs_error, rel_error, unit,
                              source
    /study/error_vs_runtime   table (a group of columns on its dimension scale row), one
                              row per method x tolerance; attrs reference_kind, accuracy_*
    /sweep                    a family of runs ([sweep], see reportgen.scene.sweep), on the
                              dimension scale /sweep/member: status, message (M,) strings
                              (fixed-width UTF-8, attr _Encoding; older archives: variable),
                              values/<config path>, analysis/<result> (M,) float64,
                              labels/<result> (M,) strings; points/<set>/ (only for a
                              kind giving per-member point sets): its own dimension scale
                              ``point`` (P,), member (P,) int64, one (P,) float64 per
                              column (a (P, d) column also on the scale ``component``),
                              attrs what the points are and ``max_points``

A table is a group of one dataset per column, all on the group's own dimension scale,
listed in order by the group's attr ``table_columns``: text as UTF-8 strings, flags as int8
with ``dtype = "bool"`` (xarray reads them back as bool), so that
``xarray.open_datatree(path, engine="h5netcdf")`` shows named, typed columns.

Attributes (CF): every dataset has ``long_name`` and ``symbol`` (TeX); every number a
``units`` that pint and UDUNITS read ("rad/s", "kg m^2", "1"), except a number of several
units, which says where they are instead: a state ``y`` whose columns differ by
``column_units``, a checks column by ``units_column`` (the column holding each row's
unit), a study error over such a state by ``units_note``.  A number in the config's own
units (a formula system's time) is "1" with ``config_units`` saying what it measures
("config units of time"); a number stored as a multiple of its unit (times in τ = 4.0746
fs) has ``units`` "fs" and CF's ``scale_factor``.  Text has no ``units``.

Earlier formats stay readable by every reader: format 2 stored the tables as compound
datasets (row numbers at /check and /study/row), ``/analysis``'s dimension scales in
``/analysis`` alone with modes indexed from 0, text with ``units`` "" and a mixed ``y``
with ``units`` "various"; format 1 had no dimension scales and no resolved config.

Every array is stored with the fletcher32 checksum, so a corrupted chunk raises
on read instead of returning wrong numbers.  Writes go to a temporary file in
the same folder, are flushed and fsynced, then renamed over the final name; an
archive being replaced is first kept as ``<name>.prev.h5``.
"""

from __future__ import annotations

import json
import math
import shutil
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from .. import __version__
from ..scene.results import Check, Results, RunRecord
from ..scene.schema import ResultsSchema
from ..support.fsutil import NotRegularFile, install, regular_file, temp_name
from ..support.layout import printable
from .cf import CHECK_COLUMNS, analysis_dimensions, declared, described, study_columns
from .check import STATUSES as _CHECKED_STATUSES
from .check import check_archive, is_int, is_number
from .h5io import (  # noqa: F401 - FORMAT* are part of this module's interface
    DIMENSION_ATTR,
    FORMAT,
    FORMAT_VERSION,
    OLDEST_READABLE,
    STR,
    TABLE_ATTR,
    ArchiveError,
    attr_value,
    column_table,
    dataset,
    decode,
    is_dimension,
    is_table,
    provenance,
    read_mapping,
    read_table,
    table_columns,
    write_mapping,
)


class ConfigView(dict):
    """The resolved config as nested dicts that also read as attributes:
    ``data.config.params.g`` or ``data.config["params"]["g"]``."""

    def __getattr__(self, key: str):
        try:
            return self[key]
        except KeyError:
            raise AttributeError(key) from None

    @classmethod
    def of(cls, value):
        if isinstance(value, dict):
            return cls({k: cls.of(v) for k, v in value.items()})
        if isinstance(value, list):
            return [cls.of(v) for v in value]
        return value


@dataclass
class ArchiveData:
    """An archive read back into memory: all the report step may look at."""

    path: Path | None
    attrs: dict[str, Any]
    config_text: str
    provenance: dict[str, str]
    #: the validated config with presets and defaults (format 2; {} for format 1)
    config: ConfigView = field(default_factory=ConfigView)
    runs: dict[str, RunRecord] = field(default_factory=dict)
    analysis: dict[str, Any] = field(default_factory=dict)
    checks: list[Check] = field(default_factory=list)
    study: np.ndarray | None = None
    study_attrs: dict[str, Any] = field(default_factory=dict)
    #: a sweep's family (:class:`reportgen.scene.sweep.SweepData`), or None
    sweep: Any = None

    @property
    def kind(self) -> str:
        return str(self.attrs["kind"])

    @property
    def status(self) -> str:
        return str(self.attrs.get("status", "ok"))

    @property
    def message(self) -> str:
        return str(self.attrs.get("message", ""))

    @property
    def title(self) -> str:
        return str(self.attrs.get("title", ""))

    @property
    def format_version(self) -> int:
        return int(self.attrs.get("format_version", 1))


# ------------------------------------------------------------------- writing
def _checks_records(checks: list[Check]) -> np.ndarray:
    dtype = [("quantity", object), ("value", "f8"), ("reference", "f8"), ("scale", "f8"),
             ("abs_error", "f8"), ("rel_error", "f8"), ("unit", object), ("source", object)]
    return np.array(
        [(c.quantity, c.value, c.reference, math.nan if c.scale is None else c.scale,
          c.abs_error, c.rel_error, c.unit, c.source) for c in checks],
        dtype=dtype,
    )


class ResultsError(Exception):
    """A kind's results depart from its declared schema (a bug of the kind, found at
    write time rather than when a figure is drawn)."""


def write_archive(path: Path, *, kind: str, title: str, scene: str, config_text: str,
                  config_sha256: str, results: Results, resolved_config: dict | None = None,
                  physics_key: str = "", schema: ResultsSchema | None = None,
                  code: dict[str, str] | None = None) -> None:
    """Write ``results`` atomically to ``path`` (see the module docstring).

    ``code``: the identity of the code of each stage that made the results (stage ->
    hash), stored in ``/provenance``.
    ``schema``: the kind's declared results; every dataset then carries its ``units``,
    ``long_name`` and ``symbol``, and results that depart from the declaration raise
    :class:`ResultsError` before anything is written."""
    path = Path(path)
    if schema is not None:
        problems = schema.problems(results)
        if problems:
            raise ResultsError(f"kind {kind!r}: results depart from its declaration: "
                               + "; ".join(problems[:8])
                               + (f" (and {len(problems) - 8} more)" if len(problems) > 8
                                  else ""))
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temp_name(path)
    try:
        with h5py.File(tmp, "w") as f:
            _write_contents(f, kind=kind, title=title, scene=scene, config_text=config_text,
                            config_sha256=config_sha256, results=results,
                            resolved_config=resolved_config or {}, physics_key=physics_key,
                            schema=schema or UNDECLARED, code=code)
            f.flush()
        install(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def _config_json(resolved_config: dict) -> str:
    return json.dumps(resolved_config, sort_keys=True, ensure_ascii=False)


def _write_contents(f: h5py.File, *, kind, title, scene, config_text, config_sha256,
                    results: Results, resolved_config: dict, physics_key: str,
                    schema: ResultsSchema, code: dict[str, str] | None = None) -> None:
    f.attrs.update({
        "format": FORMAT,
        "format_version": FORMAT_VERSION,
        "kind": kind,
        "title": title,
        "scene": scene,
        "config_sha256": config_sha256,
        "physics_key": physics_key,
        "created": datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "reportgen_version": __version__,
        "status": results.status,
        "message": results.message,
        "wall_time_s": float(results.wall_time_s),
    })
    _write_config(f, config_text, resolved_config)
    f.create_group("provenance").attrs.update(provenance(code))
    runs = f.create_group("runs")
    first_name: dict[int, str] = {}
    for name, run in results.runs.items():
        if id(run) in first_name:  # one run under two names: stored once, hard-linked
            runs[name] = runs[first_name[id(run)]]
            continue
        first_name[id(run)] = name
        _write_run(runs.create_group(name), run, schema)
    analysis = f.create_group("analysis")
    write_mapping(analysis, results.analysis,
                  describe=lambda name: schema.cf_attrs(declared(schema.result, name)))
    analysis_dimensions(analysis, schema, runs.get("main"))
    checks = column_table(f, "checks", _checks_records(results.checks), "check",
                          "row of the checks table", describe=CHECK_COLUMNS.get)
    checks.attrs["long_name"] = "headline numbers against their exact or independent references"
    if results.study is not None:
        study = f.create_group("study")
        study_table = column_table(study, "error_vs_runtime", results.study, "row",
                                   "method and tolerance of the study",
                                   describe=study_columns(schema, results.runs.get("main")))
        study_table.attrs["long_name"] = ("error against run time: one row per method and "
                                          "tolerance")
        for key, value in results.study_attrs.items():
            study_table.attrs[key] = attr_value(value)
    if results.sweep is not None:
        _write_sweep(f.create_group("sweep"), results.sweep, schema)


#: the schema of a kind that declares none: every dataset still gets CF attributes
UNDECLARED = ResultsSchema()


def _write_config(f: h5py.File, config_text: str, resolved_config: dict) -> None:
    described(f.create_dataset("config", data=config_text, dtype=STR),
              "the TOML config exactly as given")
    described(f.create_dataset("config_resolved", data=_config_json(resolved_config),
                               dtype=STR),
              "the validated config with its preset and defaults, as JSON")


def sweep_units(sweep, path: str) -> str:
    """The unit of a swept config key (from the config schema, kept with the sweep)."""
    return str(getattr(sweep, "value_units", {}).get(path, ""))


def _write_sweep(g: h5py.Group, sweep, schema: ResultsSchema) -> None:
    """A sweep's family on the dimension ``member`` (netCDF-style scale), so that
    ``xarray.open_dataset(path, group="sweep", engine="h5netcdf")`` (and the groups
    ``sweep/values``, ``sweep/analysis``) show every array on ``member``.

    Written a slice of :data:`SWEEP_SLICE` members at a time, in chunks of
    :data:`SWEEP_CHUNK`; text (status, message, labels) as fixed-width UTF-8 strings, as
    wide as the longest value (a family of 10⁷ members repeats a few values: gzip keeps
    them small, and reading them back makes no Python string per member)."""
    size = sweep.size
    member = _member_array(g, "member", size, np.dtype(np.int64),
                           lambda lo, hi: np.arange(lo, hi, dtype=np.int64))
    described(member, "member of the sweep", "1")
    member.make_scale("member")
    for name, values, what in (("status", sweep.status, "the member's run status"),
                               ("message", sweep.message, "why the member is not ok")):
        described(_member_text(g, name, values), what).dims[0].attach_scale(member)
    labels = g.create_group("labels")
    for name, values in sweep.labels.items():
        ds = _member_text(labels, name, values)
        described(ds, declared(schema.result, name).description)
        ds.dims[0].attach_scale(member)
    sub = g.create_group("values")
    for name, values in sweep.values.items():
        ds = described(_member_numbers(sub, name, values), f"swept value of {name}",
                       sweep_units(sweep, name))
        ds.dims[0].attach_scale(member)
    sub = g.create_group("analysis")
    for name, values in sweep.analysis.items():
        ds = _member_numbers(sub, name, values)
        ds.attrs.update(schema.cf_attrs(declared(schema.result, name)))
        ds.dims[0].attach_scale(member)
    for key, value in sweep.attrs.items():
        g.attrs[key] = attr_value(value)
    if sweep.points:
        points = g.create_group("points")
        for name, pset in sweep.points.items():
            _write_points(points.create_group(name), pset)


#: members of a sweep written or read at once (bounds the conversion buffers)
SWEEP_SLICE = 1 << 20
#: members per chunk of a sweep's arrays
SWEEP_CHUNK = 1 << 16


def _member_array(g: h5py.Group, name: str, size: int, dtype, part) -> h5py.Dataset:
    """A (size,) dataset on ``member`` filled by ``part(lo, hi)`` a slice at a time, with
    the archive's filters (fletcher32, shuffle, gzip)."""
    if size == 0:
        return g.create_dataset(name, shape=(0,), dtype=dtype)
    ds = g.create_dataset(name, shape=(size,), dtype=dtype, chunks=(min(size, SWEEP_CHUNK),),
                          fletcher32=True, shuffle=True, compression="gzip",
                          compression_opts=4)
    for lo in range(0, size, SWEEP_SLICE):
        hi = min(lo + SWEEP_SLICE, size)
        ds[lo:hi] = part(lo, hi)
    return ds


def _member_numbers(g: h5py.Group, name: str, values) -> h5py.Dataset:
    values = np.asarray(values, dtype=np.float64)
    return _member_array(g, name, values.size, values.dtype, lambda lo, hi: values[lo:hi])


def _member_text(g: h5py.Group, name: str, values) -> h5py.Dataset:
    """Text on ``member`` as fixed-width UTF-8 (``_Encoding`` tells xarray to decode it)."""
    from ..scene.sweep import text_codes

    codes, names = text_codes(values)
    encoded = [n.encode("utf-8") for n in names]
    width = max([1, *(len(e) for e in encoded)])
    dtype = h5py.string_dtype("utf-8", width)  # numpy bytes marked UTF-8 for HDF5
    table = np.array(encoded or [b""], dtype=dtype)
    ds = _member_array(g, name, codes.size, dtype, lambda lo, hi: table[codes[lo:hi]])
    ds.attrs["_Encoding"] = "utf-8"
    return ds


def _read_member_text(ds: h5py.Dataset) -> np.ndarray:
    """A sweep's text array as an object array of shared strings: fixed-width text read
    a slice at a time as codes; variable-length text (older archives) as it is."""
    from ..scene.sweep import text_array, text_codes

    if h5py.check_string_dtype(ds.dtype).length is None:
        return np.array(decode(ds[()]), dtype=object).reshape(ds.shape)
    size = ds.shape[0]
    codes = np.zeros(size, dtype=np.int32)
    index: dict[str, int] = {}
    for lo in range(0, size, SWEEP_SLICE):
        hi = min(lo + SWEEP_SLICE, size)
        part, names = text_codes(ds[lo:hi])
        mapping = np.array([index.setdefault(n, len(index)) for n in names], dtype=np.int32)
        codes[lo:hi] = mapping[part.astype(np.intp)]
    return text_array(codes, list(index))


def _write_points(g: h5py.Group, pset) -> None:
    """One point set flat on its own dimension ``point`` (and ``component`` for (P, d)
    columns), so that ``xarray.open_dataset(path, group="sweep/points/<set>",
    engine="h5netcdf")`` shows named dimensions; ``member`` is a variable on ``point``."""
    point = described(dataset(g, "point", np.arange(len(pset.member), dtype=np.int64)),
                      "point of the set", "1")
    point.make_scale("point")
    component = None
    if pset.components:
        component = described(g.create_dataset(
            "component", data=np.array(pset.components, dtype=object), dtype=STR),
            "component of a point")
        component.make_scale("component")
    member = described(dataset(g, "member", np.asarray(pset.member, dtype=np.int64)),
                       "the member the point belongs to", "1")
    member.dims[0].attach_scale(point)
    for name, values in pset.columns.items():
        ds = described(dataset(g, name, np.asarray(values, dtype=np.float64)),
                       str(pset.attrs.get(f"long_name_{name}", name.replace("_", " "))),
                       str(pset.attrs.get(f"units_{name}", "")))
        ds.dims[0].attach_scale(point)
        if ds.ndim == 2 and component is not None:
            ds.dims[1].attach_scale(component)
    for key, value in pset.attrs.items():
        g.attrs[key] = attr_value(value)


def _write_run(g: h5py.Group, run: RunRecord, schema: ResultsSchema) -> None:
    """One trajectory with netCDF-style dimension scales, so that
    ``xarray.open_dataset(path, group="runs/<name>", engine="h5netcdf")`` shows the
    dimensions ``t`` and ``component`` (with the column names) and every invariant and
    reference as a variable on ``t``.  ``y`` holds columns of several units: its
    ``column_units``, ``column_long_names`` and ``column_symbols`` attrs give them, and
    its ``units`` is theirs when they agree ("various" otherwise)."""
    t = dataset(g, "t", np.asarray(run.t, dtype=np.float64))
    t.attrs.update(schema.cf_attrs(schema.time))
    t.make_scale("t")
    component = described(g.create_dataset(
        "component", data=np.array(run.columns, dtype=object), dtype=STR),
        "state component")
    component.make_scale("component")
    y = dataset(g, "y", np.asarray(run.y, dtype=np.float64).reshape(len(run.t), -1))
    y.attrs["columns"] = np.array(run.columns, dtype=STR)
    columns = [declared(schema.column, c) for c in run.columns]
    cf = [schema.cf_attrs(q) for q in columns]
    units = {(a.get("units", ""), a.get("scale_factor"), a.get("config_units")) for a in cf}
    described(y, "state: " + ", ".join(q.description for q in columns))
    if len(units) == 1:  # one unit for all: y's own (several: per column only, below)
        y.attrs.update({k: v for k, v in cf[0].items() if k not in ("long_name", "symbol")})
    y.attrs["column_units"] = np.array([a.get("units", "") for a in cf], dtype=STR)
    if any("scale_factor" in a for a in cf):
        y.attrs["column_scale_factors"] = np.array([a.get("scale_factor", 1.0) for a in cf])
    for key, attr in (("long_names", "description"), ("symbols", "symbol")):
        y.attrs[f"column_{key}"] = np.array([getattr(q, attr) for q in columns], dtype=STR)
    y.dims[0].attach_scale(t)
    y.dims[1].attach_scale(component)
    inv = g.create_group("invariants")
    taken = {"t", "y", "component", "invariants", "reference"}
    for q, values in run.invariants.items():
        ds = dataset(inv, q, np.asarray(values, dtype=np.float64))
        ds.attrs.update(schema.cf_attrs(declared(schema.invariant, q)))
        if ds.ndim == 1 and len(ds) == len(run.t):
            ds.dims[0].attach_scale(t)
            g[q if q not in taken else f"invariant_{q}"] = ds  # hard link: a variable on t
    if run.reference:
        ref = g.create_group("reference")
        for c, values in run.reference.items():
            ds = dataset(ref, c, np.asarray(values, dtype=np.float64))
            q = declared(schema.column, c)
            ds.attrs.update({**schema.cf_attrs(q),
                             "long_name": f"reference solution: {q.description}"})
            if ds.ndim == 1 and len(ds) == len(run.t):
                ds.dims[0].attach_scale(t)
                if f"reference_{c}" not in g:
                    g[f"reference_{c}"] = ds  # hard link: a variable on t
    for key, value in run.attrs.items():
        g.attrs[key] = attr_value(value)


def restamp(path: Path, *, title: str, config_text: str, config_sha256: str,
            resolved_config: dict) -> None:
    """Give an archive a new config whose physics is unchanged (a title or ``[report]``
    edit): the attrs and config datasets are rewritten in a copy that replaces the
    archive atomically; every array keeps its bytes."""
    path = Path(path)
    tmp = temp_name(path)
    try:
        shutil.copyfile(path, tmp)
        with h5py.File(tmp, "r+") as f:
            f.attrs["title"] = title
            f.attrs["config_sha256"] = config_sha256
            for name in ("config", "config_resolved"):
                if name in f:
                    del f[name]
            _write_config(f, config_text, resolved_config)
            f.flush()
        install(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


# ------------------------------------------------------------------- reading

def read_archive(path: Path) -> ArchiveData:
    """Read a whole archive; ArchiveError names the file and the problem."""
    path = Path(path)
    try:
        with h5py.File(regular_file(path), "r") as f:
            check_archive(f, path)  # types, shapes, sizes and links, before reading data
            data = ArchiveData(
                path=path,
                attrs={k: decode(v) for k, v in f.attrs.items()},
                config_text=decode(f["config"][()]),
                provenance={k: decode(v) for k, v in f["provenance"].attrs.items()},
            )
            if "config_resolved" in f:
                data.config = ConfigView.of(json.loads(decode(f["config_resolved"][()])))
            for name, g in f.get("runs", {}).items():
                data.runs[name] = RunRecord(
                    t=g["t"][()],
                    y=g["y"][()],
                    columns=decode(g["y"].attrs["columns"]),
                    invariants={q: ds[()] for q, ds in g["invariants"].items()},
                    attrs={k: decode(v) for k, v in g.attrs.items()},
                    reference={c: ds[()] for c, ds in g["reference"].items()}
                    if "reference" in g else {},
                )
            data.analysis = read_mapping(f["analysis"]) if "analysis" in f else {}
            if "checks" in f:
                for row in read_table(f["checks"]):
                    scale = float(row["scale"]) if "scale" in row.dtype.names else math.nan
                    data.checks.append(Check(quantity=row["quantity"], value=float(row["value"]),
                                             reference=float(row["reference"]),
                                             unit=row["unit"], source=row["source"],
                                             scale=None if math.isnan(scale) else scale))
            if "study/error_vs_runtime" in f:
                ds = f["study/error_vs_runtime"]
                data.study = read_table(ds)
                data.study_attrs = {k: decode(v) for k, v in ds.attrs.items()
                                    if k != TABLE_ATTR}
            if "sweep" in f:
                data.sweep = _read_sweep(f["sweep"])
    except ArchiveError:
        raise
    except FileNotFoundError:
        raise ArchiveError(f"{path}: no such file") from None
    except NotRegularFile as exc:
        raise ArchiveError(f"{path}: {exc.strerror}; not read") from None
    except OSError as exc:
        if _looks_like_a_config(path):
            raise ArchiveError(f"{path}: a scene config (TOML), not an archive: `reportgen run "
                               f"{path}` makes its run.h5") from None
        raise ArchiveError(f"{path}: unreadable or corrupted HDF5 file ({exc})") from None
    except KeyError as exc:
        raise ArchiveError(f"{path}: incomplete archive, missing {exc}") from None
    except (TypeError, ValueError, IndexError, AttributeError, RecursionError) as exc:
        raise ArchiveError(f"{path}: malformed archive ({type(exc).__name__}: {exc})") from None
    return data


def _read_sweep(g: h5py.Group):
    from ..scene.sweep import SweepData

    attrs = {k: decode(v) for k, v in g.attrs.items()}
    # HDF5 lists a group's members by name; the swept keys keep the config's order
    order = json.loads(attrs.get("paths", "[]"))
    names = sorted(g["values"], key=lambda k: order.index(k) if k in order else len(order))
    return SweepData(
        values={k: g["values"][k][()] for k in names},
        analysis={k: ds[()] for k, ds in g["analysis"].items()},
        labels={k: _read_member_text(ds) for k, ds in g.get("labels", {}).items()},
        status=_read_member_text(g["status"]),
        message=_read_member_text(g["message"]),
        attrs=attrs,
        points={k: _read_points(p) for k, p in g.get("points", {}).items()})


def _read_points(g: h5py.Group):
    from ..scene.sweep import PointSet

    skip = {"point", "member", "component"}
    return PointSet(columns={k: ds[()] for k, ds in g.items() if k not in skip},
                    member=g["member"][()],
                    components=tuple(decode(g["component"][()])) if "component" in g else (),
                    attrs={k: decode(v) for k, v in g.attrs.items()})


@dataclass(frozen=True)
class Identity:
    """What the pipeline compares to decide which stages must run."""

    config_sha256: str
    physics_key: str
    reportgen_version: str
    status: str
    format_version: int
    message: str = ""
    wall_time_s: float = 0.0


def stored_identity(path: Path) -> Identity | None:
    """The identity of an existing archive, or None if it is missing or unreadable."""
    try:
        with h5py.File(regular_file(path), "r") as f:
            a = f.attrs
            identity = Identity(config_sha256=decode(a["config_sha256"]),
                                physics_key=decode(a.get("physics_key", "")),
                                reportgen_version=decode(a["reportgen_version"]),
                                status=decode(a.get("status", "ok")),
                                format_version=a.get("format_version", 1),
                                message=decode(a.get("message", "")),
                                wall_time_s=a.get("wall_time_s", 0.0))
    except (OSError, KeyError, TypeError, ValueError):
        return None
    # read back from an output folder: an identity of the wrong types is no identity
    if not (all(isinstance(v, str) for v in (identity.config_sha256, identity.physics_key,
                                             identity.reportgen_version, identity.message))
            and identity.status in _CHECKED_STATUSES and is_int(identity.format_version)
            and is_number(identity.wall_time_s)):
        return None
    return replace(identity, format_version=int(identity.format_version),
                   wall_time_s=float(identity.wall_time_s))


#: bytes of the checks table the gallery reads for a card (a scene's is a few KiB)
GALLERY_TABLE_BYTES = 4 << 20


def gallery_entry(path: Path, headline: Callable[[ArchiveData], str] | None = None
                  ) -> dict[str, Any] | None:
    """What the output folder's gallery shows of one archive: kind, title, status,
    message, wall time and the headline in words, ``headline(light)`` of the archive
    read light (:func:`read_light`: no runs, no arrays but small ones); without
    ``headline`` (or when it fails), the check with the largest relative error.
    None if unreadable."""
    try:
        with h5py.File(regular_file(path), "r") as f:
            if f.attrs.get("format") != FORMAT:
                return None
            # every archive the gallery reads is checked as every other reader checks it: a
            # neighbour's 3.6 GB of fixed-width text cost every later run into its folder
            check_archive(f, path)
            a = {k: decode(v) for k, v in f.attrs.items()}
            # a small table only (read back from an output folder: not a declared giant)
            checks = _small_table(f.get("checks"))
            light = _read_light(f, path, a, checks) if headline is not None else None
    except (OSError, KeyError, TypeError, ValueError, RuntimeError, ArchiveError):
        return None
    line = ""
    if light is not None:
        try:
            line = str(headline(light))
        except Exception:  # noqa: BLE001 - a kind's bad line costs its card the line only
            line = ""
    if not line:
        line = _worst_check_text(checks)

    def text(key: str, default: str = "") -> str:
        value = a.get(key, default)
        return value if isinstance(value, str) else default

    wall = a.get("wall_time_s", math.nan)
    return {"kind": text("kind"), "title": text("title"),
            "status": text("status", "ok"), "message": text("message"),
            "wall_time_s": float(wall) if is_number(wall) else math.nan,
            "headline": printable(line, newlines=False), "created": text("created")}


def _small_table(obj) -> np.ndarray | None:
    """The checks table ``obj`` (a compound dataset or a group of columns) if it is small
    enough for a gallery card (:data:`GALLERY_TABLE_BYTES`, 10,000 rows), else None."""
    if isinstance(obj, h5py.Dataset):
        if not (obj.ndim == 1 and obj.dtype.names):
            return None
        rows, width = obj.shape[0], obj.dtype.itemsize
    elif isinstance(obj, h5py.Group) and is_table(obj):
        columns = [obj.get(n) for n in table_columns(obj)]
        if not columns or not all(isinstance(c, h5py.Dataset) and c.ndim == 1
                                  for c in columns):
            return None
        rows, width = columns[0].shape[0], sum(c.dtype.itemsize for c in columns)
    else:
        return None
    return read_table(obj) if rows <= 10_000 and rows * width <= GALLERY_TABLE_BYTES else None


def _worst_check_text(checks) -> str:
    try:
        if checks is not None and len(checks):
            worst = checks[int(np.nanargmax(checks["rel_error"]))] if np.any(
                np.isfinite(checks["rel_error"])) else checks[0]
            return f"{worst['quantity']}: {float(worst['rel_error']):.1e} from its reference"
    except (KeyError, TypeError, ValueError, IndexError):
        pass
    return ""


#: the largest ``/analysis`` array a light read keeps (a few frequencies, a 3x3 tensor)
LIGHT_ARRAY_SIZE = 64


def _read_light(f: h5py.File, path: Path, attrs: dict, checks) -> ArchiveData | None:
    """The archive without its runs and big arrays: attrs, resolved config, the
    scalars and small arrays of ``/analysis`` (no sub-groups), the checks.  None when
    a part is malformed (the caller then falls back to the checks alone)."""
    try:
        config = ConfigView()
        raw = f.get("config_resolved")
        if isinstance(raw, h5py.Dataset) and raw.shape == () and raw.dtype.kind in "OS":
            config = ConfigView.of(json.loads(decode(raw[()])))
        analysis: dict[str, Any] = {}
        g = f.get("analysis")
        if isinstance(g, h5py.Group):
            analysis = {k: decode(v) for k, v in g.attrs.items() if not k.startswith("__")}
            for k, item in g.items():
                if is_dimension(item):
                    continue
                if (isinstance(item, h5py.Dataset) and item.size <= LIGHT_ARRAY_SIZE
                        and item.dtype.kind in "biuf"):
                    analysis[k] = item[()]
        rows = []
        for row in checks if checks is not None else ():
            scale = float(row["scale"]) if "scale" in row.dtype.names else math.nan
            rows.append(Check(quantity=str(row["quantity"]), value=float(row["value"]),
                              reference=float(row["reference"]), unit=str(row["unit"]),
                              source=str(row["source"]),
                              scale=None if math.isnan(scale) else scale))
    except (OSError, KeyError, TypeError, ValueError, RecursionError):
        return None
    return ArchiveData(path=Path(path), attrs=attrs, config_text="", provenance={},
                       config=config, analysis=analysis, checks=rows)


def verify_checksums(path: Path) -> list[str]:
    """Read every dataset in full; return the problems found (fletcher32 errors raise on read)."""
    problems = []

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            try:
                obj[()]
            except OSError as exc:
                problems.append(f"{name}: {exc}")

    try:
        with h5py.File(regular_file(path), "r") as f:
            f.visititems(visit)
    except OSError as exc:
        problems.append(f"cannot open: {exc}")
    return problems


def summarize(path: Path, checksum_problems: list[str] | None = None) -> str:
    """A short human-readable description of an archive (``reportgen inspect``);
    ``checksum_problems``, if given, receives what :func:`verify_checksums` found."""
    data = read_archive(path)
    a = data.attrs
    lines = [
        f"{path}",
        f"  kind      {a['kind']}   title: {a.get('title', '')}",
        f"  status    {a.get('status', 'ok')}" + (f"  ({a['message']})" if a.get("message") else ""),
        f"  created   {a.get('created')}   reportgen {a.get('reportgen_version')}",
        f"  config    sha256 {str(a.get('config_sha256'))[:16]}…  ({len(data.config_text)} chars)",
        f"  physics   key {str(a.get('physics_key', ''))[:16] or '(none: format 1)'}…  "
        f"format_version {data.format_version}",
        f"  wall time {float(a.get('wall_time_s', 0.0)):.3f} s",
    ]
    for name, run in data.runs.items():
        ra = run.attrs
        lines.append(
            f"  run {name}: {run.y.shape[0]} samples x {run.y.shape[1]} "
            f"({', '.join(run.columns)}); method {ra.get('method')}, nfev {ra.get('nfev')}, "
            f"{float(ra.get('wall_time_s', 0)):.4f} s, {ra.get('status')}"
        )
        for q in run.invariants:
            drift = ra.get(f"drift_{q}")
            lines.append(f"      invariant {q}: relative drift {drift:.2e}" if drift is not None
                         else f"      invariant {q}")
    for c in data.checks:
        lines.append(f"  check {c.quantity}: {c.value:.12g} vs {c.reference:.12g} "
                     f"(rel. error {c.rel_error:.1e}) {c.unit}")
    scalars = {k: v for k, v in data.analysis.items() if np.ndim(v) == 0 and not isinstance(v, dict)}
    if scalars:
        lines.append("  analysis: " + ", ".join(f"{k}={v:.10g}" if isinstance(v, float)
                                               else f"{k}={v}" for k, v in scalars.items()))
    if data.study is not None:
        lines.append(f"  study error_vs_runtime: {len(data.study)} rows "
                     f"({data.study_attrs.get('reference_kind', '')})")
    problems = verify_checksums(path)
    if checksum_problems is not None:
        checksum_problems.extend(problems)
    lines.append("  checksums ok" if not problems else "  CHECKSUM PROBLEMS: " + "; ".join(problems))
    if data.provenance:
        lines.append("  provenance: " + ", ".join(f"{k} {v}" for k, v in
                                                  sorted(data.provenance.items())))
    lines.append("  config (as run; `reportgen verify` re-simulates it):")
    lines += [f"    {line}" for line in data.config_text.splitlines()]
    # titles, names and messages come from the file: shown, never acted on by the terminal
    return "\n".join(printable(line, newlines=False) for line in lines)



def _looks_like_a_config(path) -> bool:
    """Whether ``path`` (not an HDF5 file) reads as a scene config: TOML with a ``kind``."""
    import tomllib

    try:
        with open(path, "rb") as fh:
            head = fh.read(1 << 20)
        return "kind" in tomllib.loads(head.decode("utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return False
