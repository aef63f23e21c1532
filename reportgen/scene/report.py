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
3. ``headline(data)`` -> short list of (label, value) facts for the summary;
   ``behaviour(data)`` -> the physical behaviour in words (shown beside the numerical
   status, never as a status), default ``/analysis`` ``behaviour``.
4. Labels come from the kind's declared results (:meth:`label`), never config keys.
"""

from __future__ import annotations

import fnmatch
import importlib
import importlib.util
import math
import re
import sys
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from ..lazy import lazy_module
from . import gallery as _gallery
from .base import Scene, Section
from .content import FigureSpec, SectionContent, Table, fmt, fmt_err, member_text
from .schema import Quantity, config_quantity, unit_text

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..archive.store import ArchiveData
    from ..rendering.plots.motion import Motion

_common_plots = lazy_module("reportgen.rendering.plots.common")


class Report(Scene):
    """Base class of a kind's report (see the module docstring for the contract)."""

    faces: ClassVar[frozenset[str]] = frozenset({"report"})
    #: the gallery's heading over this kind's cards, where it differs from the kind's
    #: ``name_in_words`` (a heading for a group: "Three bodies", not "Three gravitating
    #: bodies"); empty: ``name_in_words``
    gallery_name: ClassVar[str] = ""
    #: the gallery's thumbnail: figure names (as given to :meth:`figure`) in order of
    #: preference, the first one drawn wins; none drawn (or ()): the report's first figure
    gallery_figures: ClassVar[tuple[str, ...]] = ()

    @classmethod
    def gallery_headline(cls, data: ArchiveData) -> str:
        """The gallery card's line in words, from a light archive (see
        :mod:`reportgen.scene.gallery`); default: the first summary check."""
        return _gallery.check_headline(data, words=lambda text: cls.check_words(data, text))

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
    def behaviour(cls, data: ArchiveData) -> str | None:
        """The scene's physical behaviour in words ("unstable: the tilt grows as e^(γt),
        γ = 0.71 1/s"), shown beside its numerical status in the summary; None when the
        kind gives none.  Default: ``/analysis`` ``behaviour``, stored at simulate time."""
        value = data.analysis.get("behaviour") if data.sweep is None else None
        return str(value) if value else None

    @classmethod
    def describe(cls, data: ArchiveData) -> str:
        """This scene in words, the report's subtitle: the default title of the archived
        config when the scene has its own title, else the kind's name.  Kinds say more;
        a sweep's subtitle is :meth:`family_words` instead."""
        words = cls.default_title(data.config)
        return words if words != data.title else (cls.name_in_words or cls.kind)

    @classmethod
    def subtitle(cls, data: ArchiveData) -> str:
        """The report's subtitle: :meth:`family_words` for a sweep, else :meth:`describe`."""
        return cls.family_words(data) if data.sweep is not None else cls.describe(data)

    @classmethod
    def family_words(cls, data: ArchiveData) -> str:
        """A sweep in words: the family's size and what it varies ("Heavy symmetric top:
        a family of 13 runs over precession rate φ̇0, −1 to 2 rad/s")."""
        sweep = data.sweep
        axes = []
        for path, values in sweep.values.items():
            q = cls.config_quantity(data, path)
            found = re.match(r"^(.*?)\s*\[([^\]]+)\]", q.description)  # "rate [rad/s] (or …)"
            what, unit = (found.group(1), found.group(2)) if found else (q.description,
                                                                         q.unit)
            unit = unit_text(unit) if unit not in ("", "1") else ""
            span = " to ".join(fmt(float(f(values)), 4).replace("-", "−")
                               for f in (np.min, np.max))
            axes.append(f"{what}, {span}{' ' + unit if unit else ''}")
        name = cls.name_in_words or cls.kind.replace("_", " ").capitalize()
        return (f"{name}: a family of {sweep.size} runs over "
                + (" and " if sweep.attrs.get("zip") else ", ").join(axes))

    @classmethod
    def prose_case(cls, data: ArchiveData) -> dict:
        """The case of this archive that the kind's prose macros branch on (symmetric or
        not, bound or escaping, …), as plain values read from the archive: the template
        sees it as ``case``."""
        return {}

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
        axes = []
        for p, v in sweep.values.items():
            lo, hi = (_minus(fmt(float(f(v)), 4)) for f in (np.min, np.max))
            unit = cls.config_unit_words(data, p)
            axes.append(f"{cls.config_words(data, p)} from {lo} to {hi}"
                        + (f" {unit}" if unit else ""))
        facts = [("members", f"{sweep.size} ({'paired values' if sweep.attrs.get('zip') else 'a grid'}"
                             f" of {', '.join(axes)})"),
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

    #: TeX symbols of config keys a sweep may vary ({"initial.theta": r"\theta_0"}); a key
    #: not named here is labelled with its field's description
    config_symbols: ClassVar[dict[str, str]] = {}

    @classmethod
    def config_quantity(cls, data: ArchiveData, path: str) -> Quantity:
        """A swept config key as a quantity: :attr:`config_symbols`' symbol, and the unit
        its field declares.  A kind whose keys are named by the config overrides it."""
        return config_quantity(cls.Config, path, cls.config_symbols.get(path, ""))

    @classmethod
    def config_words(cls, data: ArchiveData, path: str) -> str:
        """A config key as page text: its symbol in Unicode ("φ̇₀", "θ₀"), else its field's
        description ("initial energy"); never the key."""
        return cls.config_quantity(data, path).text

    @classmethod
    def config_unit_words(cls, data: ArchiveData, path: str) -> str:
        """The unit of a config key as printed after a value ("rad/s"; "" for a pure
        number)."""
        unit = unit_text(cls.config_quantity(data, path).unit)
        return "" if unit == "dimensionless" else unit

    @classmethod
    def config_value_words(cls, data: ArchiveData, path: str, value: float,
                           digits: int = 4) -> str:
        """A config key's value as page text: "θ₀ = 3.097 rad", "φ̇₀ = −0.125 rad/s"."""
        unit = cls.config_unit_words(data, path)
        return (f"{cls.config_words(data, path)} = {_minus(fmt(float(value), digits))}"
                + (f" {unit}" if unit else ""))

    @classmethod
    def member_words(cls, data: ArchiveData, i: int, digits: int = 4) -> str:
        """A sweep member's swept values as page text ("φ̇₀ = −1 rad/s"), never the keys."""
        return ", ".join(cls.config_value_words(data, p, float(v[i]), digits)
                         for p, v in data.sweep.values.items())

    @classmethod
    def time_unit_words(cls, data: ArchiveData) -> str:
        """The runs' time unit as printed ("s"; "" in scaled units): the config's own
        ``time_unit`` where it names one, else the kind's declared time axis."""
        own = getattr(data.config, "time_unit", None)
        if isinstance(own, str):
            return "" if own in ("1", "dimensionless") else own
        unit = unit_text(cls.schema.time.unit) if cls.schema is not None else "s"
        return "" if unit == "dimensionless" else unit

    @classmethod
    def run_end_words(cls, data: ArchiveData) -> str:
        """The end of the run as page text, "t = 10 s"."""
        unit = cls.time_unit_words(data)
        return f"t = {fmt(float(data.config.run.t_end), 4)}" + (f" {unit}" if unit else "")

    @classmethod
    def check_words(cls, data: ArchiveData, text: str) -> str:
        """A summary check's name (or source) as the page shows it.  The archive keeps the
        name it was stored under (tests and the gallery look checks up by it); the page
        says it in words: "θ(t_end)" -> "θ(t = 10 s)", "at t_end" -> "at t = 10 s", a
        member's "(initial.theta = 3.09691)" -> "(θ₀ = 3.097 rad)", and a config key left
        bare -> its description."""
        text = _gallery.run_end_words(str(text), data, cls.time_unit_words(data), "\u00a0")
        tables = set(getattr(cls.Config, "model_fields", {}) or {})

        def valued(m: re.Match) -> str:
            if m.group(1) not in tables:
                return m.group(0)
            try:
                value = float(m.group(3).replace("−", "-"))
            except ValueError:
                return m.group(0)
            return cls.config_value_words(data, f"{m.group(1)}.{m.group(2)}", value)

        def bare(m: re.Match) -> str:
            if m.group(1) not in tables:
                return m.group(0)
            words = cls.config_quantity(data, m.group(0)).description
            return m.group(0) if words == m.group(2) else words  # "run.h5": not a key

        text = re.sub(r"(?<![\w.])([a-z_]+)\.([A-Za-z_][\w.]*?) = "
                      r"([\-−+]?(?:\d+\.?\d*|\.\d+)(?:[eE][\-+]?\d+)?)", valued, text)
        return re.sub(r"(?<![\w.])([a-z_]+)\.([A-Za-z_]\w*)(?![\w(.])", bare, text)

    @classmethod
    def result_quantity(cls, data: ArchiveData, name: str) -> Quantity:
        """The declared result ``name`` of this archive (a kind whose results are named by
        the config overrides it); an undeclared one (the archive wrote it without a unit)
        by its name in words."""
        try:
            return cls.schema.quantity(name)
        except KeyError:
            return Quantity(name, "", "", name.replace("_", " ").replace("/", ": "))

    @classmethod
    def colour_key_label(cls, data: ArchiveData, key: str) -> str:
        """The colour bar's label of a family keyed by ``key`` (:func:`section_colours`):
        the swept quantity, or the member's number."""
        if key == "member":
            return "member of the sweep (dimensionless)"
        return cls.config_quantity(data, key).label()

    @classmethod
    def swept_keys(cls, data: ArchiveData) -> dict[str, tuple[str, str]]:
        """Each swept key as (symbol, typeset unit) for figure labels, never the key."""
        out = {}
        for path in data.sweep.values:
            q = cls.config_quantity(data, path)
            out[path] = (q.math, unit_text(q.unit))
        return out

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
            fig = common_plots.sweep_results(
                sweep.values, {n: sweep.analysis[n] for n in names}, sweep.ok,
                paired=bool(sweep.attrs.get("zip")), keys=cls.swept_keys(data),
                ylabels={n: cls.result_quantity(data, n).label() for n in names})
            figures.append(cls.figure("results", fig, "Each scalar result of the members' "
                                      "analysis against the swept value; members without a "
                                      "result are left out."))
        bad = ~sweep.ok
        rows = [[str(i), cls.member_words(data, i), str(sweep.status[i]),
                 str(sweep.message[i])]
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
        keys = cls.swept_keys(data)
        labels, rows = {}, []
        for i, name in members:
            labels[name] = ", ".join(common_plots.key_value_text(keys[p], float(v[i]))
                                     for p, v in data.sweep.values.items())
            a = runs[name].attrs
            rows.append([str(i), cls.member_words(data, i), str(a.get("method", "")),
                         str(a.get("nfev", "")), f"{a.get('nsteps', '')} ({a.get('nreject', '')})",
                         str(a.get("status", ""))])
        first = next(iter(runs.values()), None)
        ylabel = cls.result_quantity(data, first.columns[0]).label() if first else ""
        fig = common_plots.member_runs(runs, labels, ylabel=ylabel,
                                       time_unit=unit_text(cls.schema.time.unit))
        table = Table("The kept members' runs", ["member", "values", "method", "f evals",
                                                 "steps (rejected)", "status"], rows)
        return SectionContent(figures=[cls.figure(
            "members", fig, "The first coordinate of each kept member against time.")],
            tables=[table])

    @classmethod
    def invariants_section(cls, data: ArchiveData, *, labels: dict[str, str] | None = None,
                           caption: str = "", run: str = "main",
                           time_unit: str | None = None) -> SectionContent:
        """Drift of every conserved quantity of a run (relative to the scales stored with
        the run), with a table of the largest drift.  ``time_unit``: the run's time unit as
        printed, when the config names it (else the kind's declared one)."""
        rec = data.runs[run]
        scales = {q: rec.attrs[f"scale_{q}"] for q in rec.invariants
                  if f"scale_{q}" in rec.attrs}
        if not time_unit:
            time_unit = unit_text(cls.schema.time.unit) if cls.schema is not None else "s"
        fig = _common_plots.invariant_drift(rec.t, rec.invariants, scales=scales or None,
                                            labels=labels, time_unit=time_unit)
        rows = []
        for name, values in rec.invariants.items():
            drift = rec.attrs.get(f"drift_{name}", float("nan"))
            scale = scales.get(name)
            rows.append([(labels or {}).get(name, name), fmt(float(values[0])),
                         fmt(float(scale), 4) if scale is not None else "its largest |I|",
                         fmt_err(drift)])
        table = Table(caption=f"Conserved quantities: the largest drift |I(t) − I(0)| over "
                              f"the run, divided by the quantity's scale (declared by the "
                              f"scene, else its own largest size). Bound of a numerically "
                              f"stable run: "
                              f"{fmt_err(rec.attrs.get('drift_bound', math.nan))}.",
                      header=["quantity", "initial value", "scale", "max drift / scale"],
                      rows=rows)
        return SectionContent(
            figures=[cls.figure("invariants", fig,
                                caption or "Drift of the conserved quantities.")],
            tables=[table])

    @classmethod
    def section_error_vs_runtime(cls, data: ArchiveData) -> SectionContent:
        """Work-precision diagram and one row per method of ``/study/error_vs_runtime``.

        Each row: the fastest run at least as accurate as scipy DOP853 at rtol 1e-10
        (the baseline), its speed-up over the baseline, the smallest error the method
        reached, and its runs' statuses: "ok", "inaccurate" (error above 1e-3 of the
        scene's scale) or "failed", the reasons in numbered notes under the table.  Every
        run is in the archive's table.
        """
        study = data.study
        if study is None or len(study) == 0:
            return SectionContent(notes=["The error-against-run-time study was not run for "
                                         "this scene: the configuration switches it off."])
        fig = _common_plots.work_precision(study)
        status = np.array([str(v) for v in study["status"]])
        # an inaccurate run is a valid measurement (its error is just large): it counts
        measured = study[(status == "ok") | (status == "inaccurate")]
        baseline = measured[(measured["method"] == "scipy_dop853")
                            & np.isclose(measured["tolerance"], 1e-10, rtol=1e-6, atol=0.0)]
        base = baseline[0] if len(baseline) else None
        rows, reasons = [], []
        for method in dict.fromkeys(study["method"]):
            mine = study["method"] == method
            label = f"{study[mine]['label'][0]} ({_runs_text(int(mine.sum()))})"
            cell = _status_cell(study[mine], status[mine], data.study_attrs, reasons)
            runs = measured[measured["method"] == method]
            if len(runs) == 0:
                rows.append([label, "—", "—", "—", cell])
                continue
            best = runs[np.argmin(runs["error_max"])]
            matched, speedup = "—", "—"
            if base is not None:
                good = runs[runs["error_max"] <= base["error_max"]]
                if len(good):
                    fastest = good[np.argmin(good["wall_time_s"])]
                    matched = (f"{_setting(fastest)}: {fmt_err(float(fastest['error_max']))} in "
                               f"{fmt(float(fastest['wall_time_s']) * 1e3, 3)} ms")
                    speedup = _times(float(base["wall_time_s"]) / float(fastest["wall_time_s"]))
            rows.append([label, matched, speedup,
                         f"{fmt_err(float(best['error_max']))} ({_setting(best)})", cell])
        notes = [f"{_mark(k)} {text}" for k, text in enumerate(reasons, 1)]
        t_study, t_end = data.analysis.get("study_t_end"), data.config.run.t_end
        lyapunov = data.analysis.get("lyapunov_time")
        unit = cls.time_unit_words(data)
        unit = f" {unit}" if unit else ""
        if t_study is not None and t_study < t_end and lyapunov is not None:
            notes.append(f"The study integrates t ∈ [0, {fmt(t_study, 4)}]{unit} only (the "
                         f"report's run goes to {fmt(t_end, 6)}{unit}): the orbit is chaotic, "
                         "and the horizon is half its estimated Lyapunov time "
                         f"T = {fmt(lyapunov, 3)}{unit} "
                         "(the time over which two orbits started 1e-10 apart separate by a "
                         "factor e). Past it the error against any reference measures the "
                         "chaos, not the method; the main run is judged on its invariants.")
        elif t_study is not None and t_study < t_end:
            notes.append(f"The study integrates t ∈ [0, {fmt(t_study, 4)}]{unit} only (the "
                         f"report's run goes to {fmt(t_end, 6)}{unit}): "
                         f"{cls.study_horizon_reason}")
        heyoka = _heyoka_note(study, data.study_attrs)
        if heyoka:
            notes.append(heyoka)
        if "cached" in study.dtype.names and np.any(study["cached"]):
            cached = study[study["cached"].astype(bool)]
            where = sorted({(str(r["measured_at"]), str(r["machine"])) for r in cached})
            names = ", ".join(dict.fromkeys(str(v) for v in cached["label"]))
            when = sorted({m[:10] for m, _ in where})
            notes.append(f"The rows of {names} were measured earlier ({', '.join(when)}) "
                         "and taken from the peer measurement cache (reportgen cache info; "
                         "the colophon names the machine). reportgen's own methods were "
                         "timed in this run.")
        reference = data.study_attrs.get("reference_kind", "")
        budget = float(data.study_attrs.get("budget_s", math.inf))
        if math.isfinite(budget):
            notes.append(f"The study has a budget of {fmt(budget, 3)} s of timed runs, set in "
                         "the configuration: each method's ladder stops before a rung that "
                         "would overrun its share, so the tightest tolerances and smallest "
                         "steps may be absent; scipy DOP853 is always run down to the "
                         "baseline at rtol 1e-10.")
        over = [m for m in str(data.study_attrs.get("over_budget", "")).split(",") if m]
        if over:
            labels = {str(m): str(lab) for m, lab in zip(study["method"], study["label"],
                                                         strict=True)}
            notes.append("No run within the study budget (the loosest tolerance was stopped "
                         "when it overran its share; a larger study budget in the "
                         "configuration includes it): "
                         + ", ".join(labels.get(m, method_words(m)) for m in over) + ".")
        target = (f"scipy DOP853 at rtol 1e-10 reaches {fmt_err(float(base['error_max']))} in "
                  f"{fmt(float(base['wall_time_s']) * 1e3, 3)} ms" if base is not None
                  else "no scipy DOP853 baseline run")
        table = Table(caption=f"Per method (and its number of runs): the fastest run at least "
                              f"as accurate as the baseline ({target}), the smallest error "
                              f"reached, and the runs' status (notes below). Reference: "
                              f"{reference}. Wall time: minimum over repeats "
                              "after a warm-up; compile time excluded. Every run is in "
                              "the archive's study table (see the colophon).",
                      header=["method", "fastest at baseline error", "speed-up",
                              "smallest error", "status"],
                      rows=rows)
        return SectionContent(
            figures=[cls.figure("work_precision", fig,
                                "Work-precision diagram: max error over the run against wall "
                                "time. Filled markers on solid (or dash-dot) lines: reportgen's "
                                "compiled integrators; hollow markers on dashed lines: "
                                + ("scipy's integrators and heyoka (Taylor series, LLVM)."
                                   if np.any(study["method"] == "heyoka")
                                   else "scipy's integrators."))],
            tables=[table], notes=notes)



def _times(ratio: float) -> str:
    """A speed ratio as a factor: "1190×" (whole from 100 on, no exponent), "34.6×"."""
    return f"{ratio:.0f}×" if ratio >= 100 else f"{fmt(ratio, 3)}×"


def _heyoka_note(study, attrs=None) -> str:
    """What the heyoka rows of a study say against ours ("" when it has none): at each
    error heyoka reached in :data:`~reportgen.support.peers.PEER_ERROR_RANGE`, our fastest run
    at least as accurate, and heyoka's time over ours."""
    from ..support.peers import against_peer, compared_range, study_rows

    attrs = attrs or {}
    rows = study_rows(study)
    if not any(r["method"] == "heyoka" for r in rows):
        return ""

    lo, hi = compared_range(float(attrs.get("reference_agreement", math.nan)))
    matched = against_peer(rows, error_range=(lo, hi))
    jit = [r["compile_time_s"] for r in rows if r["method"] == "heyoka"
           and math.isfinite(r["compile_time_s"])]
    head = (f"heyoka (Taylor series compiled by LLVM; {fmt(sum(jit), 2)} s of JIT "
            f"compilation in all, not in its times) against reportgen's methods at matched "
            "error: ")
    if not matched:
        return head + (f"none of heyoka's runs has a max error between {fmt_err(lo)} and "
                       f"{fmt_err(hi)}, the range compared.")
    ahead = [m for m in matched if m["ratio"] >= 1.0]
    parts = []
    for m in matched:
        if m["ours"] is None:
            parts.append(f"{fmt_err(m['error_max'])}: none of ours as accurate")
        else:
            parts.append(f"{fmt_err(m['error_max'])}: {fmt(m['ratio'], 2)}×")
    count = ("none" if not ahead else "all" if len(ahead) == len(matched) else len(ahead))
    text = head + (f"at {len(matched)} of its errors between {fmt_err(lo)} and "
                   f"{fmt_err(hi)}, our fastest run at least as accurate was faster at "
                   f"{count}. heyoka's time over ours, by heyoka's error: "
                   + "; ".join(parts) + ".")
    if len(ahead) < len(matched) and not any(r["method"] == "taylor" for r in rows):
        text += (" reportgen's own Taylor-series integrator, which takes heyoka's steps, is "
                 "not in this study (it compiles a module per order for each model, too "
                 "dear for every report); reportgen bench measures it against heyoka.")
    return text


def no_period_reason(data: ArchiveData, period: float, *, noun: str, min_samples: int,
                     fallback: str) -> str:
    """Why a period was not measured on the archived main run, from its span and samples
    against the closed-form ``period`` (``noun``: "periods", "nutation periods"): fewer
    than two periods, or fewer than ``min_samples`` samples per period; else
    ``fallback`` (the run's own reason, e.g. too few turning points)."""
    run = data.runs.get("main")
    if run is None or len(run.t) < 2:
        return "the archive holds no integrated run to measure it on"
    periods = float(run.t[-1] - run.t[0]) / period
    per_period = (len(run.t) - 1) / periods
    reasons = []
    if periods < 2:
        reasons.append(f"the run covers {fmt(periods, 3)} {noun}, fewer than two")
    if per_period < min_samples:
        reasons.append(f"it stores {fmt(per_period, 3)} samples per period, fewer than "
                       f"{min_samples}")
    return "; ".join(reasons) or fallback


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
    points per member): orbits whose crossings were capped by the sweep's ``max_points`` (the
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
                     f"{int(np.max(total[capped]))}); a larger cap on the kept crossings "
                     "in the configuration's sweep settings keeps more.")
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


_MARKS = "¹²³⁴⁵⁶⁷⁸⁹"


def _mark(k: int) -> str:
    """The note mark of the ``k``-th reason (1-based): ¹ … ⁹, then (10), (11) …"""
    return _MARKS[k - 1] if k <= len(_MARKS) else f"({k})"


def _minus(text: str) -> str:
    """A number's text with a typeset minus sign ("−1"), for prose."""
    return text.replace("-", "−") if not re.search(r"e-\d", text) else \
        re.sub(r"^-", "−", text)


_METHOD_CODES = re.compile(r"^(?:rk\d+|dop\d+|lsoda|bdf)$")


def method_words(name: str) -> str:
    """An integrator's name as a reader says it, when the archive holds no label for it:
    "scipy_rk45" -> "scipy RK45", "levi_civita_dop853" -> "Levi-Civita + DOP853"."""
    name = str(name)
    text = name.replace("levi_civita", "Levi-Civita")
    scipy = text.startswith("scipy_")
    parts = [p for p in (text[6:] if scipy else text).split("_") if p]
    words = [p.upper() if _METHOD_CODES.match(p) else
             (p.capitalize() if scipy and p.isalpha() else p) for p in parts]
    return ("scipy " if scipy else "") + " + ".join(words) if words else name


def _runs_text(n: int) -> str:
    return f"{n} run" + ("" if n == 1 else "s")


def _scale_text(attrs) -> str:
    """"0.001 × 1 m (the orbit's semi-major axis a)" from the study table's attrs, or "".
    The value comes before its meaning: a bare "(1.67)" would read as an equation number."""
    value = attrs.get("accuracy_scale")
    if value is None or not math.isfinite(float(value)):
        return ""
    unit = str(attrs.get("accuracy_scale_unit", "") or "")
    return (f"{float(attrs.get('accuracy_tolerance', 1e-3)):g} × "
            f"{fmt(float(value), 3)}{' ' + unit if unit else ''} "
            f"({attrs.get('accuracy_scale_what', 'the scene scale')})")


def _status_cell(rows, status: np.ndarray, attrs, reasons: list[str]) -> str:
    """A method's runs' statuses in a table cell ("ok", "9 inaccurate¹, 3 ok"), the
    reasons appended to ``reasons`` (the numbered notes under the table)."""
    label = str(rows["label"][0])
    messages = ([str(m) for m in rows["message"]] if "message" in rows.dtype.names
                else [""] * len(rows))
    parts = []
    for word in ("failed", "inaccurate", "unstable", "ok"):
        which = np.flatnonzero(status == word)
        if len(which) == 0:
            continue
        count = "" if len(which) == len(rows) else f"{len(which)} "
        if word == "ok":
            parts.append(f"{count}ok")
            continue
        settings = [_setting(rows[i]) for i in which]
        span = settings[0] if len(which) == 1 else f"{settings[0]} … {settings[-1]}"
        if word == "inaccurate":  # one reason for every method: the scene's scale
            scale = _scale_text(attrs)
            text = ("inaccurate: the run's max error (the smallest error column shows the "
                    "best run's) is above " + (scale or "1e-3 of the scene's scale") + ".")
        else:
            found = [messages[i] for i in which if messages[i]]
            why = found[0] if found else ("no reason stored (an archive written before "
                                          "study rows had a message)")
            if len(set(found)) > 1:
                why += f" (and {len(set(found)) - 1} other reason(s), in the archive)"
            text = f"{label}, {_runs_text(len(which))} {word} ({span}): {why}."
        if text not in reasons:
            reasons.append(text)
        parts.append(f"{count}{word}{_mark(reasons.index(text) + 1)}")
    return ", ".join(parts)


def _setting(row) -> str:
    tol, h = float(row["tolerance"]), float(row["h"])
    if math.isfinite(tol):
        return f"rtol {fmt(tol)}"
    return f"h {fmt(h, 3)}" if math.isfinite(h) else ""
