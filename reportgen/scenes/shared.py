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
    """Work-precision diagram and a one-row-per-method summary of ``/study/error_vs_runtime``.

    Each row: the fastest run at least as accurate as scipy DOP853 at rtol 1e-10 (the
    baseline), its speed-up over the baseline, and the smallest error the method reached.
    Every run is in the archive's table.
    """
    study = data.study
    if study is None or len(study) == 0:
        return SectionContent(notes=["The error-against-run-time study was not run for this "
                                     "scene ([run] study = false)."])
    fig = common_plots.work_precision(study)
    ok = study[study["status"] == "ok"]
    baseline = ok[(ok["method"] == "scipy_dop853")
                  & np.isclose(ok["tolerance"], 1e-10, rtol=1e-6, atol=0.0)]
    base = baseline[0] if len(baseline) else None
    rows = []
    for method in dict.fromkeys(study["method"]):
        runs = ok[ok["method"] == method]
        if len(runs) == 0:
            rows.append([str(study[study["method"] == method]["label"][0]), "—", "—", "—", "—",
                         "failed"])
            continue
        best = runs[np.argmin(runs["error_max"])]
        matched, speedup = "—", "—"
        if base is not None:
            good = runs[runs["error_max"] <= base["error_max"]]
            if len(good):
                fastest = good[np.argmin(good["wall_time_s"])]
                matched = (f"{_setting(fastest)}: {fmt_err(float(fastest['error_max']))} in "
                           f"{float(fastest['wall_time_s']) * 1e3:.3g} ms")
                speedup = f"{float(base['wall_time_s']) / float(fastest['wall_time_s']):.3g}×"
        rows.append([str(runs["label"][0]), matched, speedup,
                     f"{fmt_err(float(best['error_max']))} ({_setting(best)})",
                     str(len(runs)), "ok"])
    reference = data.study_attrs.get("reference_kind", "")
    target = (f"scipy DOP853 at rtol 1e-10 reaches {fmt_err(float(base['error_max']))} in "
              f"{float(base['wall_time_s']) * 1e3:.3g} ms" if base is not None
              else "no scipy DOP853 baseline run")
    table = Table(caption=f"Per method: the fastest run at least as accurate as the baseline "
                          f"({target}), and the smallest error reached. Reference: {reference}. "
                          "Wall time: minimum over repeats after a warm-up; compile time "
                          "excluded. All runs are in /study/error_vs_runtime.",
                  header=["method", "fastest at baseline error", "speed-up", "smallest error",
                          "runs", "status"],
                  rows=rows)
    return SectionContent(
        figures=[scene.figure("work_precision", fig,
                              "Work-precision diagram: max error over the run against wall time. "
                              "Solid: reportgen's compiled integrators; dashed: scipy solve_ivp.")],
        tables=[table])


def _setting(row) -> str:
    tol, h = float(row["tolerance"]), float(row["h"])
    if math.isfinite(tol):
        return f"rtol {tol:.0e}"
    return f"h {h:.3g}" if math.isfinite(h) else ""
