"""The audit archive ``audit.h5`` (``reportgen audit``): one table row per case and
method, and the drift series of every run."""

from __future__ import annotations

from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from .. import __version__
from ..scene.config import to_toml
from ..support.fsutil import install, temp_name
from .h5io import (
    STR,
    ArchiveError,
    dataset,
    decode,
    provenance,
    read_mapping,
    read_table,
    table,
    write_mapping,
)

FORMAT = "reportgen-audit"
FORMAT_VERSION = 1
#: audit drift series are stored at most this long (decimated evenly)
AUDIT_SERIES_POINTS = 2000

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
    records = np.array(rows, dtype=dtype)
    tmp = temp_name(path)
    try:
        with h5py.File(tmp, "w") as f:
            f.attrs.update({"format": FORMAT, "format_version": FORMAT_VERSION,
                            "created": datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
                            "reportgen_version": __version__})
            f.create_group("provenance").attrs.update(provenance())
            table(f, "table", records)
            cases = f.create_group("cases")
            for i, r in enumerate(results):
                g = cases.create_group(str(i))
                g.attrs.update({"name": r.case.name, "kind": r.kind, "what": r.case.what,
                                "verdict": r.verdict, "reason": r.reason})
                g.create_dataset("config", data=to_toml(r.case.config), dtype=STR)
                for j, run in enumerate(r.runs):
                    if run.t is None:
                        continue
                    rg = g.create_group(str(j))
                    rg.attrs.update({"method": run.method, "used": run.used})
                    step = max(1, len(run.t) // AUDIT_SERIES_POINTS)
                    dataset(rg, "t", run.t[::step])
                    write_mapping(rg.create_group("drift"),
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
            if f.attrs.get("format") != FORMAT:
                raise ArchiveError(f"{path}: not a reportgen audit archive")
            out = {"attrs": {k: decode(v) for k, v in f.attrs.items()},
                   "provenance": {k: decode(v) for k, v in f["provenance"].attrs.items()},
                   "table": read_table(f["table"]), "cases": []}
            for i in sorted(f["cases"], key=int):
                g = f["cases"][i]
                case = {k: decode(v) for k, v in g.attrs.items()}
                case["config"] = decode(g["config"][()])
                case["runs"] = []
                for j in sorted((k for k in g if k != "config"), key=int):
                    rg = g[j]
                    case["runs"].append({"method": decode(rg.attrs["method"]),
                                         "used": decode(rg.attrs["used"]),
                                         "t": rg["t"][()],
                                         "drift": read_mapping(rg["drift"])})
                out["cases"].append(case)
    except OSError as exc:
        raise ArchiveError(f"{path}: unreadable audit archive ({exc})") from None
    return out
