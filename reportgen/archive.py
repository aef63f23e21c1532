"""The HDF5 archive: the only module that touches h5py.

Layout (``format_version`` 1, see SPEC.md "Archive")::

    /                         attrs: format, format_version, kind, title, config_sha256,
                                     created, reportgen_version, scene, status, message,
                                     wall_time_s
    /config                   scalar string: the TOML text exactly as given
    /provenance               attrs: python, numpy, scipy, h5py, matplotlib, numba, platform
    /runs/<name>/t            (N,) float64
    /runs/<name>/y            (N, d) float64, attr columns
    /runs/<name>/invariants/<q>  (N,) float64
    /analysis                 attrs (scalars, strings) and datasets (arrays); sub-dicts are groups
    /checks                   table: quantity, value, reference, abs_error, rel_error, unit, source
    /study/error_vs_runtime   table (one row per method x tolerance), attrs reference_kind

Every array is stored with the fletcher32 checksum, so a corrupted chunk raises
on read instead of returning wrong numbers.  Writes go to a temporary file in
the same folder, are flushed and fsynced, then renamed over the final name; an
archive being replaced is first kept as ``<name>.prev.h5``.
"""

from __future__ import annotations

import math
import os
import platform
import sys
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from . import __version__
from .fsutil import fsync_path, temp_name
from .results import Check, Results, RunRecord

FORMAT = "reportgen"
FORMAT_VERSION = 1
_STR = h5py.string_dtype("utf-8")


#: audit drift series are stored at most this long (decimated evenly)
AUDIT_SERIES_POINTS = 2000


class ArchiveError(Exception):
    """An archive that cannot be read: names the file and what is wrong."""


@dataclass
class ArchiveData:
    """An archive read back into memory: all the report step may look at."""

    path: Path | None
    attrs: dict[str, Any]
    config_text: str
    provenance: dict[str, str]
    runs: dict[str, RunRecord] = field(default_factory=dict)
    analysis: dict[str, Any] = field(default_factory=dict)
    checks: list[Check] = field(default_factory=list)
    study: np.ndarray | None = None
    study_attrs: dict[str, Any] = field(default_factory=dict)

    @property
    def kind(self) -> str:
        return str(self.attrs["kind"])

    @property
    def status(self) -> str:
        return str(self.attrs.get("status", "ok"))

    @property
    def message(self) -> str:
        return str(self.attrs.get("message", ""))


# ------------------------------------------------------------------- writing
def provenance() -> dict[str, str]:
    import matplotlib
    import numba
    import scipy

    return {
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "h5py": h5py.__version__,
        "hdf5": h5py.version.hdf5_version,
        "matplotlib": matplotlib.__version__,
        "numba": numba.__version__,
        "platform": platform.platform(),
    }


def _array(group: h5py.Group, name: str, data) -> h5py.Dataset:
    data = np.asarray(data)
    if data.dtype.kind in "US":
        data = data.astype(object)
    if data.dtype == object:
        return group.create_dataset(name, data=data, dtype=_STR)
    if data.ndim == 0 or data.size == 0:
        return group.create_dataset(name, data=data)
    return group.create_dataset(
        name, data=data, chunks=True, fletcher32=True, shuffle=True, compression="gzip",
        compression_opts=4,
    )


def _attr_value(value):
    if isinstance(value, str):
        return value
    if isinstance(value, (bool, np.bool_)):
        return np.bool_(value)
    if isinstance(value, (list, tuple)) and value and all(isinstance(v, str) for v in value):
        return np.array(value, dtype=_STR)
    return value


def _write_mapping(group: h5py.Group, mapping: dict[str, Any]) -> None:
    """Scalars and strings become attrs, arrays datasets, dicts subgroups."""
    for key, value in mapping.items():
        if isinstance(value, dict):
            _write_mapping(group.create_group(key), value)
        elif isinstance(value, np.ndarray) or (
            isinstance(value, (list, tuple)) and not all(isinstance(v, str) for v in value)
        ):
            _array(group, key, value)
        else:
            group.attrs[key] = _attr_value(value)


def _table(group: h5py.Group, name: str, records: np.ndarray) -> h5py.Dataset:
    """A structured array as a compound dataset; string fields become UTF-8 strings."""
    fields = []
    for fname in records.dtype.names:
        kind = records.dtype[fname].kind
        fields.append((fname, _STR if kind in "OUS" else records.dtype[fname]))
    dtype = np.dtype(fields)
    table = np.empty(records.shape, dtype=dtype)
    for fname in records.dtype.names:
        col = records[fname]
        table[fname] = col.astype(str).astype(object) if col.dtype.kind in "OUS" else col
    return group.create_dataset(name, data=table, chunks=True if table.size else None,
                                fletcher32=bool(table.size))


def _checks_records(checks: list[Check]) -> np.ndarray:
    dtype = [("quantity", object), ("value", "f8"), ("reference", "f8"), ("scale", "f8"),
             ("abs_error", "f8"), ("rel_error", "f8"), ("unit", object), ("source", object)]
    return np.array(
        [(c.quantity, c.value, c.reference, math.nan if c.scale is None else c.scale,
          c.abs_error, c.rel_error, c.unit, c.source) for c in checks],
        dtype=dtype,
    )


def write_archive(path: Path, *, kind: str, title: str, scene: str, config_text: str,
                  config_sha256: str, results: Results) -> None:
    """Write ``results`` atomically to ``path`` (see the module docstring)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temp_name(path)
    try:
        with h5py.File(tmp, "w") as f:
            _write_contents(f, kind=kind, title=title, scene=scene, config_text=config_text,
                            config_sha256=config_sha256, results=results)
            f.flush()
        install(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def _write_contents(f: h5py.File, *, kind, title, scene, config_text, config_sha256,
                    results: Results) -> None:
    f.attrs.update({
        "format": FORMAT,
        "format_version": FORMAT_VERSION,
        "kind": kind,
        "title": title,
        "scene": scene,
        "config_sha256": config_sha256,
        "created": datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "reportgen_version": __version__,
        "status": results.status,
        "message": results.message,
        "wall_time_s": float(results.wall_time_s),
    })
    f.create_dataset("config", data=config_text, dtype=_STR)
    f.create_group("provenance").attrs.update(provenance())
    runs = f.create_group("runs")
    for name, run in results.runs.items():
        g = runs.create_group(name)
        _array(g, "t", np.asarray(run.t, dtype=np.float64))
        y = _array(g, "y", np.asarray(run.y, dtype=np.float64))
        y.attrs["columns"] = np.array(run.columns, dtype=_STR)
        inv = g.create_group("invariants")
        for q, values in run.invariants.items():
            _array(inv, q, np.asarray(values, dtype=np.float64))
        for key, value in run.attrs.items():
            g.attrs[key] = _attr_value(value)
    _write_mapping(f.create_group("analysis"), results.analysis)
    _table(f, "checks", _checks_records(results.checks))
    if results.study is not None:
        study = f.create_group("study")
        table = _table(study, "error_vs_runtime", results.study)
        for key, value in results.study_attrs.items():
            table.attrs[key] = _attr_value(value)


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


# ------------------------------------------------------------------- reading
def _decode(value):
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray) and value.dtype == object:
        return [_decode(v) for v in value.tolist()]
    if isinstance(value, np.generic):
        return value.item()
    return value


def _read_mapping(group: h5py.Group) -> dict[str, Any]:
    out: dict[str, Any] = {k: _decode(v) for k, v in group.attrs.items()}
    for key, item in group.items():
        if isinstance(item, h5py.Group):
            out[key] = _read_mapping(item)
        elif item.dtype.kind == "O":
            out[key] = _decode(item[()])
        else:
            out[key] = item[()]
    return out


def _read_table(ds: h5py.Dataset) -> np.ndarray:
    raw = ds[()]
    fields = [(n, object if raw.dtype[n].kind in "OS" else raw.dtype[n]) for n in raw.dtype.names]
    out = np.empty(raw.shape, dtype=fields)
    for n in raw.dtype.names:
        col = raw[n]
        out[n] = [_decode(v) for v in col] if raw.dtype[n].kind in "OS" else col
    return out


#: what makes an archive unreadable: (check, fatal?, message)
_LOAD_PROBLEMS = (
    (lambda f: f.attrs.get("format") == FORMAT, True, "not a reportgen archive (no format attr)"),
    (lambda f: int(f.attrs.get("format_version", -1)) <= FORMAT_VERSION, True,
     f"written by a newer reportgen (format_version > {FORMAT_VERSION})"),
    (lambda f: "config" in f, True, "has no /config"),
    (lambda f: "kind" in f.attrs, True, "has no kind attribute"),
)


def read_archive(path: Path) -> ArchiveData:
    """Read a whole archive; ArchiveError names the file and the problem."""
    path = Path(path)
    try:
        with h5py.File(path, "r") as f:
            for check, fatal, message in _LOAD_PROBLEMS:
                if fatal and not check(f):
                    raise ArchiveError(f"{path}: {message}")
            data = ArchiveData(
                path=path,
                attrs={k: _decode(v) for k, v in f.attrs.items()},
                config_text=_decode(f["config"][()]),
                provenance={k: _decode(v) for k, v in f["provenance"].attrs.items()},
            )
            for name, g in f.get("runs", {}).items():
                data.runs[name] = RunRecord(
                    t=g["t"][()],
                    y=g["y"][()],
                    columns=_decode(g["y"].attrs["columns"]),
                    invariants={q: ds[()] for q, ds in g["invariants"].items()},
                    attrs={k: _decode(v) for k, v in g.attrs.items()},
                )
            data.analysis = _read_mapping(f["analysis"]) if "analysis" in f else {}
            if "checks" in f:
                for row in _read_table(f["checks"]):
                    scale = float(row["scale"]) if "scale" in row.dtype.names else math.nan
                    data.checks.append(Check(quantity=row["quantity"], value=float(row["value"]),
                                             reference=float(row["reference"]),
                                             unit=row["unit"], source=row["source"],
                                             scale=None if math.isnan(scale) else scale))
            if "study/error_vs_runtime" in f:
                ds = f["study/error_vs_runtime"]
                data.study = _read_table(ds)
                data.study_attrs = {k: _decode(v) for k, v in ds.attrs.items()}
    except ArchiveError:
        raise
    except FileNotFoundError:
        raise ArchiveError(f"{path}: no such file") from None
    except OSError as exc:
        raise ArchiveError(f"{path}: unreadable or corrupted HDF5 file ({exc})") from None
    except KeyError as exc:
        raise ArchiveError(f"{path}: incomplete archive, missing {exc}") from None
    return data


def stored_identity(path: Path) -> tuple[str, str, str] | None:
    """(config_sha256, reportgen_version, status) of an existing archive, or None if unreadable."""
    try:
        with h5py.File(path, "r") as f:
            a = f.attrs
            return (_decode(a["config_sha256"]), _decode(a["reportgen_version"]),
                    _decode(a.get("status", "ok")))
    except (OSError, KeyError):
        return None


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
        with h5py.File(path, "r") as f:
            f.visititems(visit)
    except OSError as exc:
        problems.append(f"cannot open: {exc}")
    return problems


def summarize(path: Path) -> str:
    """A short human-readable description of an archive (``reportgen inspect``)."""
    data = read_archive(path)
    a = data.attrs
    lines = [
        f"{path}",
        f"  kind      {a['kind']}   title: {a.get('title', '')}",
        f"  status    {a.get('status', 'ok')}" + (f"  ({a['message']})" if a.get("message") else ""),
        f"  created   {a.get('created')}   reportgen {a.get('reportgen_version')}",
        f"  config    sha256 {str(a.get('config_sha256'))[:16]}…  ({len(data.config_text)} chars)",
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
    lines.append("  checksums ok" if not problems else "  CHECKSUM PROBLEMS: " + "; ".join(problems))
    return "\n".join(lines)


# --------------------------------------------------------------------- audit
AUDIT_FIELDS = ("case", "kind", "what", "method", "used", "status", "verdict", "reason",
                "message", "drift", "error", "nsteps", "nreject", "nfev", "wall_time_s")


def write_audit(path: Path, results) -> None:
    """``audit.h5``: one table row per (case, method) and the drift series of each run.

    Layout::

        /                  attrs: format="reportgen-audit", format_version, created, versions
        /table             one row per case x method (AUDIT_FIELDS)
        /cases/<i>         attrs name, kind, what, verdict, reason; dataset config (TOML)
        /cases/<i>/<j>/t, /cases/<i>/<j>/drift/<q>   relative drift of run j
    """
    from .config import to_toml

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    rows = []
    for r in results:
        for run in r.runs:
            rows.append((r.case.name, r.kind, r.case.what, run.method, run.used, run.status,
                         r.verdict, r.reason, run.message, run.drift, run.error, run.nsteps,
                         run.nreject, run.nfev, run.wall_time_s))
    dtype = [(n, object) for n in AUDIT_FIELDS[:9]] + [
        ("drift", "f8"), ("error", "f8"), ("nsteps", "i8"), ("nreject", "i8"), ("nfev", "i8"),
        ("wall_time_s", "f8")]
    table = np.array(rows, dtype=dtype)
    tmp = temp_name(path)
    try:
        with h5py.File(tmp, "w") as f:
            f.attrs.update({"format": "reportgen-audit", "format_version": FORMAT_VERSION,
                            "created": datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
                            "reportgen_version": __version__})
            f.create_group("provenance").attrs.update(provenance())
            _table(f, "table", table)
            cases = f.create_group("cases")
            for i, r in enumerate(results):
                g = cases.create_group(str(i))
                g.attrs.update({"name": r.case.name, "kind": r.kind, "what": r.case.what,
                                "verdict": r.verdict, "reason": r.reason})
                g.create_dataset("config", data=to_toml(r.case.config), dtype=_STR)
                for j, run in enumerate(r.runs):
                    if run.t is None:
                        continue
                    rg = g.create_group(str(j))
                    rg.attrs.update({"method": run.method, "used": run.used})
                    step = max(1, len(run.t) // AUDIT_SERIES_POINTS)
                    _array(rg, "t", run.t[::step])
                    _write_mapping(rg.create_group("drift"),
                                   {q: v[::step] for q, v in run.drift_series.items()})
            f.flush()
        install(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def read_audit(path: Path) -> dict[str, Any]:
    """The audit archive as {'table': records, 'cases': [dict], 'attrs', 'provenance'}."""
    path = Path(path)
    try:
        with h5py.File(path, "r") as f:
            if f.attrs.get("format") != "reportgen-audit":
                raise ArchiveError(f"{path}: not a reportgen audit archive")
            out = {"attrs": {k: _decode(v) for k, v in f.attrs.items()},
                   "provenance": {k: _decode(v) for k, v in f["provenance"].attrs.items()},
                   "table": _read_table(f["table"]), "cases": []}
            for i in sorted(f["cases"], key=int):
                g = f["cases"][i]
                case = {k: _decode(v) for k, v in g.attrs.items()}
                case["config"] = _decode(g["config"][()])
                case["runs"] = []
                for j in sorted((k for k in g if k != "config"), key=int):
                    rg = g[j]
                    case["runs"].append({"method": _decode(rg.attrs["method"]),
                                         "used": _decode(rg.attrs["used"]),
                                         "t": rg["t"][()],
                                         "drift": _read_mapping(rg["drift"])})
                out["cases"].append(case)
    except OSError as exc:
        raise ArchiveError(f"{path}: unreadable audit archive ({exc})") from None
    return out
