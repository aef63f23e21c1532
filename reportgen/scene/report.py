"""The report face of a kind: archive -> sections, figures, tables and prose.

A kind's ``report.py`` subclasses :class:`Report`.  Its methods are classmethods taking
the :class:`~reportgen.archive.store.ArchiveData` alone: they never import ``reportgen.core``
or evaluate physics, so ``reportgen report`` works with core unimportable and gives
byte-identical figures (``tests/test_archive_only.py``).  The subclass contract:

1. ``sections``: the sections the kind can show, in order, as
   :class:`~reportgen.scene.base.Section`; ``default_sections(data)`` narrows them to
   what this archive holds and needs.
2. One classmethod ``section_<name>(data)`` per section returning
   :class:`~reportgen.scene.content.SectionContent`; ``section_error_vs_runtime`` is
   provided here and :meth:`invariants_section` draws any run's conserved quantities.
3. ``headline(data)`` -> short list of (label, value) facts for the summary.
4. Labels come from the kind's declared results (:meth:`label`), never config keys.
"""

from __future__ import annotations

import fnmatch
import importlib
import importlib.util
import math
import sys
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from ..lazy import lazy_module
from .base import Scene, Section
from .content import FigureSpec, SectionContent, Table, fmt, fmt_err, member_text
from .schema import unit_text

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..archive.store import ArchiveData
    from ..rendering.plots.motion import Motion

_common_plots = lazy_module("reportgen.rendering.plots.common")


class Report(Scene):
    """Base class of a kind's report (see the module docstring for the contract)."""

    faces: ClassVar[frozenset[str]] = frozenset({"report"})

    @classmethod
    def label(cls, name: str, unit: str | None = None) -> str:
        """Axis label or table header of the declared quantity ``name``: its symbol and
        unit ("$\\dot{\\theta}$ [rad/s]")."""
        return cls.schema.quantity(name).label(unit)

    @classmethod
    def default_sections(cls, data: ArchiveData) -> list[str]:
        """The sections this archive needs; subclasses drop what it makes irrelevant."""
        names = cls.default_section_names or tuple(s.name for s in cls.sections)
        return list(names)

    @classmethod
    def held_family_sections(cls, data: ArchiveData) -> list[str]:
        """The family sections this sweep's archive holds the data of (a kind drops those
        whose results its members did not give).  Default: all, but the kept members only
        if some were kept, and a section drawing a point set only if it has points."""
        def held(f: Section) -> bool:
            if f.points:
                pts = data.sweep.points.get(f.points)
                return pts is not None and len(pts.member) > 0
            return f.name != "sweep_members" or bool(data.runs)

        return [f.name for f in cls.family_sections + cls.SWEEP_SECTIONS if held(f)]

    @classmethod
    def chosen_sections(cls, data: ArchiveData) -> list[Section]:
        """The configured sections, or the defaults, minus what the archive does not hold."""
        asked = data.config.report.sections
        if data.sweep is not None:
            family = cls.family_sections + cls.SWEEP_SECTIONS
            names = [n for n in asked if any(f.name == n for f in family)] if asked else None
            held = cls.held_family_sections(data)
            return [f for f in family if (names is None or f.name in names) and f.name in held]
        names = list(asked) if asked else cls.default_sections(data)
        if data.study is None:
            names = [n for n in names if n != "error_vs_runtime"]
        return [s for s in cls.sections if s.name in names
                and not (s.integrates and "main" not in data.runs)]

    @classmethod
    def headline(cls, data: ArchiveData) -> list[tuple[str, str]]:
        return []

    @classmethod
    def motion_module(cls) -> str | None:
        """The kind's animation module, ``kinds/<kind>/motion.py``, if its package has one
        (a kind animates by having it, as it registers by existing)."""
        package = sys.modules[cls.__module__].__package__
        name = f"{package}.motion"
        return name if package and importlib.util.find_spec(name) is not None else None

    @classmethod
    def motion(cls, data: ArchiveData, frames: int) -> Motion | None:
        """The scene's motion over ``frames`` frames for ``reportgen animate``: what the
        kind's :meth:`motion_module` draws (imported only now, so matplotlib loads only to
        animate); None when the kind has nothing to animate."""
        name = cls.motion_module()
        return None if name is None else importlib.import_module(name).motion(data, frames)

    @staticmethod
    def figure(name: str, figure: Figure, caption: str) -> FigureSpec:
        return FigureSpec(name=name, figure=figure, caption=caption)

    @classmethod
    def sweep_headline(cls, data: ArchiveData) -> list[tuple[str, str]]:
        """The summary facts of a sweep's archive."""
        sweep = data.sweep
        counts = sweep.counts()
        axes = ", ".join(f"{p} from {fmt(float(np.min(v)), 6)} to {fmt(float(np.max(v)), 6)}"
                         for p, v in sweep.values.items())
        facts = [("members", f"{sweep.size} ({'paired' if sweep.attrs.get('zip') else 'grid'}"
                             f" of {axes})"),
                 ("status", ", ".join(f"{n} {k}" for k, n in sorted(counts.items())))]
        wall = float(sweep.attrs.get("members_wall_time_s", math.nan))
        resumed = int(sweep.attrs.get("resumed", 0))
        if math.isfinite(wall):
            run = sweep.size - resumed
            start_up_s = float(sweep.attrs.get("members_start_up_s", math.nan))
            facts.append(("run time of the members",
                          f"{fmt(wall, 4)} s ({fmt(run / max(wall, 1e-12), 4)} members/s"
                          + (f"; {resumed} resumed from an interrupted run" if resumed else "")
                          + ")" + (f"; start-up (imports, compiled code from numba's cache or "
                                   f"compiled anew) {fmt(start_up_s, 2)} s more"
                                   if math.isfinite(start_up_s) and start_up_s >= 0.01 else "")))
        return facts

    @classmethod
    def section_sweep_results(cls, data: ArchiveData) -> SectionContent:
        """Every scalar result against the first swept key (a line per value of the
        others, at most six), and the members without a result."""
        from ..rendering.plots import common as common_plots

        sweep = data.sweep
        swept = list(sweep.values.values())

        def telling(v: np.ndarray) -> bool:  # varies, and is not a swept value itself
            v = v[sweep.ok & np.isfinite(v)]
            if v.size == 0 or np.ptp(v) <= 1e-12 * max(np.max(np.abs(v)), 1e-300):
                return False
            return not any(np.array_equal(v, np.abs(x[sweep.ok & np.isfinite(x)]))
                           or np.array_equal(v, x[sweep.ok & np.isfinite(x)]) for x in swept)

        names = [n for n, v in sweep.analysis.items() if telling(np.asarray(v, dtype=float))
                 and not any(fnmatch.fnmatchcase(n, p) for p in cls.SWEEP_HIDDEN_RESULTS)]
        figures = []
        if names:
            fig = common_plots.sweep_results(sweep.values, {n: sweep.analysis[n] for n in names},
                                             sweep.ok, paired=bool(sweep.attrs.get("zip")))
            figures.append(cls.figure("results", fig, "Each scalar result of the members' "
                                      "analysis against the swept value; members without a "
                                      "result are left out."))
        bad = ~sweep.ok
        rows = [[str(i), member_text(sweep, i), str(sweep.status[i]), str(sweep.message[i])]
                for i in np.flatnonzero(bad)[:20]]
        tables = [Table("Members without a result" + (f" (first 20 of {int(bad.sum())})"
                                                      if bad.sum() > 20 else ""),
                        ["member", "values", "status", "why"], rows)] if rows else []
        return SectionContent(figures=figures, tables=tables)

    @classmethod
    def section_sweep_members(cls, data: ArchiveData) -> SectionContent:
        """The kept members' first coordinate against time, one line each."""
        from ..rendering.plots import common as common_plots

        members = kept_members(data)
        runs = {name: data.runs[name] for _, name in members}
        labels, rows = {}, []
        for i, name in members:
            labels[name] = member_text(data.sweep, i, short=True)
            a = runs[name].attrs
            rows.append([str(i), labels[name], str(a.get("method", "")), str(a.get("nfev", "")),
                         f"{a.get('nsteps', '')} ({a.get('nreject', '')})",
                         str(a.get("status", ""))])
        fig = common_plots.member_runs(runs, labels)
        table = Table("The kept members' runs", ["member", "values", "method", "f evals",
                                                 "steps (rejected)", "status"], rows)
        return SectionContent(figures=[cls.figure(
            "members", fig, "The first coordinate of each kept member against time.")],
            tables=[table])

    @classmethod
    def invariants_section(cls, data: ArchiveData, *, labels: dict[str, str] | None = None,
                           caption: str = "", run: str = "main") -> SectionContent:
        """Drift of every conserved quantity of a run (relative to the scales stored with
        the run), with a table of the largest drift."""
        rec = data.runs[run]
        scales = {q: rec.attrs[f"scale_{q}"] for q in rec.invariants
                  if f"scale_{q}" in rec.attrs}
        time_unit = unit_text(cls.schema.time.unit) if cls.schema is not None else "s"
        fig = _common_plots.invariant_drift(rec.t, rec.invariants, scales=scales or None,
                                            labels=labels, time_unit=time_unit)
        rows = []
        for name, values in rec.invariants.items():
            drift = rec.attrs.get(f"drift_{name}", float("nan"))
            rows.append([(labels or {}).get(name, name), fmt(float(values[0]), 14),
                         fmt_err(drift)])
        table = Table(caption=f"Conserved quantities (bound for a stable run: relative drift ≤ "
                              f"{fmt_err(rec.attrs.get('drift_bound', math.nan))})",
                      header=["quantity", "initial value", "max relative drift"], rows=rows)
        return SectionContent(
            figures=[cls.figure("invariants", fig,
                                caption or "Drift of the conserved quantities.")],
            tables=[table])

    @classmethod
    def section_error_vs_runtime(cls, data: ArchiveData) -> SectionContent:
        """Work-precision diagram and one row per method of ``/study/error_vs_runtime``.

        Each row: the fastest run at least as accurate as scipy DOP853 at rtol 1e-10
        (the baseline), its speed-up over the baseline, and the smallest error the
        method reached.  Every run is in the archive's table.
        """
        study = data.study
        if study is None or len(study) == 0:
            return SectionContent(notes=["The error-against-run-time study was not run for "
                                         "this scene ([run] study = false)."])
        fig = _common_plots.work_precision(study)
        ok = study[study["status"] == "ok"]
        baseline = ok[(ok["method"] == "scipy_dop853")
                      & np.isclose(ok["tolerance"], 1e-10, rtol=1e-6, atol=0.0)]
        base = baseline[0] if len(baseline) else None
        rows = []
        for method in dict.fromkeys(study["method"]):
            runs = ok[ok["method"] == method]
            if len(runs) == 0:
                rows.append([str(study[study["method"] == method]["label"][0]), "—", "—", "—",
                             "—", "failed"])
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
        notes = []
        t_study, t_end = data.analysis.get("study_t_end"), data.config.run.t_end
        if t_study is not None and t_study < t_end:
            notes.append(f"The study integrates t ∈ [0, {fmt(t_study, 4)}] only (the report's "
                         f"run goes to {fmt(t_end, 6)}): {cls.study_horizon_reason}")
        if "cached" in study.dtype.names and np.any(study["cached"]):
            cached = study[study["cached"].astype(bool)]
            where = sorted({(str(r["measured_at"]), str(r["machine"])) for r in cached})
            notes.append("The scipy rows were measured earlier and taken from the peer "
                         "measurement cache (reportgen cache info): "
                         + "; ".join(f"{m} on {w}" for m, w in where)
                         + ". reportgen's own methods were timed in this run.")
        reference = data.study_attrs.get("reference_kind", "")
        budget = float(data.study_attrs.get("budget_s", math.inf))
        if math.isfinite(budget):
            notes.append(f"Study budget {budget:g} s of timed runs ([run] study_budget): each "
                         "method's ladder stops before a rung that would overrun its share, "
                         "so the tightest tolerances and smallest steps may be absent; scipy "
                         "DOP853 is always run down to the rtol-1e-10 baseline.")
        over = [m for m in str(data.study_attrs.get("over_budget", "")).split(",") if m]
        if over:
            notes.append("No run within the study budget (the loosest tolerance was stopped "
                         "when it overran its share; raise [run] study_budget to include it): "
                         + ", ".join(over) + ".")
        target = (f"scipy DOP853 at rtol 1e-10 reaches {fmt_err(float(base['error_max']))} in "
                  f"{float(base['wall_time_s']) * 1e3:.3g} ms" if base is not None
                  else "no scipy DOP853 baseline run")
        table = Table(caption=f"Per method: the fastest run at least as accurate as the baseline "
                              f"({target}), and the smallest error reached. Reference: "
                              f"{reference}. Wall time: minimum over repeats after a warm-up; "
                              "compile time excluded. All runs are in /study/error_vs_runtime.",
                      header=["method", "fastest at baseline error", "speed-up",
                              "smallest error", "runs", "status"],
                      rows=rows)
        return SectionContent(
            figures=[cls.figure("work_precision", fig,
                                "Work-precision diagram: max error over the run against wall "
                                "time. Filled markers on solid (or dash-dot) lines: reportgen's "
                                "compiled integrators; hollow markers on dashed lines: scipy "
                                "solve_ivp.")],
            tables=[table], notes=notes)



def section_colours(sweep, points, legend_members: int):
    """How a family's surface of section tells its members apart: (crossing members,
    colour key, colour per member, labels or None).  One swept key (or zipped keys) colours
    by its value, a grid of several by the member's number; up to ``legend_members``
    members with crossings get a legend label each (more: a colour bar)."""
    crossing = np.flatnonzero(points.counts(sweep.size))
    paths = list(sweep.values)
    if len(paths) == 1 or sweep.attrs.get("zip"):
        key = paths[0]
        colour = np.asarray(sweep.values[key], dtype=float)
    else:  # a grid of several keys: the member's number keys its colour
        key = "member"
        colour = np.arange(sweep.size, dtype=float)
    labels = ({int(i): member_text(sweep, int(i), short=True) for i in crossing}
              if len(crossing) <= legend_members else None)
    return crossing, key, colour, labels


def section_point_notes(sweep, name: str, kept, not_crossing: str) -> list[str]:
    """The notes of a family's surface of section on its point set ``name`` (``kept``
    points per member): orbits whose crossings were capped by ``[sweep] max_points`` (the
    members' ``<name>_points`` result counts them all), and ok members with none
    (``not_crossing`` says what they did not do, e.g. "cross the surface")."""
    points = sweep.points[name]
    notes = []
    total = np.asarray(sweep.analysis.get(f"{name}_points", kept), dtype=float)
    capped = np.flatnonzero(sweep.ok & (total > kept))
    if len(capped):
        cap = int(points.attrs.get("max_points", 0))
        notes.append(f"Capped: the archive keeps the first {cap} crossings of each orbit; "
                     f"{len(capped)} of the orbits had more (up to "
                     f"{int(np.max(total[capped]))}). [sweep] max_points keeps more.")
    missing = np.flatnonzero(sweep.ok & (kept == 0))
    if len(missing):
        notes.append(f"{len(missing)} member(s) did not {not_crossing} during the run: "
                     + ", ".join(member_text(sweep, int(i), short=True)
                                 for i in missing[:5]) + (" …" if len(missing) > 5 else ""))
    return notes


def kept_members(data: ArchiveData) -> list[tuple[int, str]]:
    """(member index, run name) of a sweep's members kept whole, in member order."""
    return sorted((int(name.split("_", 1)[1]), name) for name in data.runs
                  if name.startswith("member_"))


def _setting(row) -> str:
    tol, h = float(row["tolerance"]), float(row["h"])
    if math.isfinite(tol):
        return f"rtol {tol:.0e}"
    return f"h {h:.3g}" if math.isfinite(h) else ""
