"""Sections several kinds show the same way: invariants and error against run time."""

from __future__ import annotations

import math

import numpy as np

from ..plots import common as common_plots
from .base import SectionContent, Table, fmt, fmt_err


def invariants_section(scene, data, *, scales=None, labels=None, caption="", run="main"):
    """Drift of every conserved quantity of a run, with a table of the largest drift."""
    rec = data.runs[run]
    fig = common_plots.invariant_drift(rec.t, rec.invariants, scales=scales, labels=labels)
    rows = []
    for name, values in rec.invariants.items():
        drift = rec.attrs.get(f"drift_{name}", float("nan"))
        rows.append([(labels or {}).get(name, name), fmt(float(values[0]), 14), fmt_err(drift)])
    table = Table(caption=f"Conserved quantities (bound for a stable run: relative drift ≤ "
                          f"{fmt_err(rec.attrs.get('drift_bound', math.nan))})",
                  header=["quantity", "initial value", "max relative drift"], rows=rows)
    return SectionContent(
        figures=[scene.figure("invariants", fig, caption or "Drift of the conserved quantities.")],
        tables=[table])


def error_vs_runtime_section(scene, data):
    """Work-precision diagram and its table from ``/study/error_vs_runtime``."""
    study = data.study
    if study is None or len(study) == 0:
        return SectionContent(notes=["The error-against-run-time study was not run for this "
                                     "scene ([run] study = false)."])
    fig = common_plots.work_precision(study)
    rows = []
    for r in study:
        tol = r["tolerance"]
        h = r["h"]
        setting = (f"rtol {tol:.0e}" if np.isfinite(tol) else f"h {h:.3g}") if (
            np.isfinite(tol) or np.isfinite(h)) else ""
        rows.append([str(r["label"]), setting, fmt_err(float(r["error_final"])),
                     fmt_err(float(r["error_max"])), f"{float(r['wall_time_s']) * 1e3:.3f}",
                     str(int(r["nfev"])), str(r["status"])])
    reference = data.study_attrs.get("reference_kind", "")
    table = Table(caption=f"Error against run time; reference: {reference}. Wall time is the "
                          "minimum over repeats after one warm-up; compile time excluded.",
                  header=["method", "setting", "final error", "max error", "wall time [ms]",
                          "f evals", "status"],
                  rows=rows)
    return SectionContent(
        figures=[scene.figure("work_precision", fig,
                              "Work-precision diagram: max error over the run against wall time. "
                              "Solid: reportgen's compiled integrators; dashed: scipy solve_ivp.")],
        tables=[table])
