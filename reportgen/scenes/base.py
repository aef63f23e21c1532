"""The scene base class: configuration, presets, sections and the run bookkeeping.

A scene kind is one module under ``reportgen/scenes/`` holding one subclass of
:class:`Scene`; defining the subclass registers the kind (``kinds``, ``validate``,
``run`` and the docs find it), nothing else is edited.  A kind has two faces:

*simulate* (an instance, built from a validated config)
    computes every number and curve the report will show and returns them as
    :class:`~reportgen.results.Results`, which the archive stores.  Numerics come
    from ``reportgen.core``, named with :func:`reportgen.lazy.lazy_module` so that
    importing a kind imports no numerics.

*report* (classmethods taking the :class:`~reportgen.archive.ArchiveData` alone)
    draws and tabulates what the archive holds.  They never import ``reportgen.core``
    or evaluate physics: ``reportgen report`` works with core unimportable and gives
    byte-identical figures (``tests/test_archive_only.py``).

The subclass contract:

1. ``kind`` (the config's ``kind``), ``summary`` (one line) and ``Config``, a
   :class:`SceneConfig` subclass declaring the kind's tables (``params``,
   ``initial``, …) with their rules; cross-key physics checks go in pydantic
   ``model_validator``s and raise ``ValueError`` naming the keys.
2. ``presets``: name -> partial config dict; explicit keys override a preset.
3. ``sections``: the sections the kind can show, in order, as :class:`Section`;
   ``default_sections(data)`` narrows them to what this archive holds and needs.
4. ``simulate(progress)`` -> :class:`~reportgen.results.Results`; use
   :meth:`integrate` for trajectories (method choice, timing, invariants and the
   stability verdict done one way everywhere), :meth:`study` for the
   error-against-run-time study and :meth:`reference_run` for a reference
   trajectory where no closed form exists.  Put reference curves on the output grid
   in ``RunRecord.reference`` and every other curve a figure shows in
   ``Results.analysis``.
5. One classmethod ``section_<name>(data)`` per section returning
   :class:`SectionContent`; ``section_error_vs_runtime`` is provided here and
   :meth:`invariants_section` draws any run's conserved quantities.
6. ``headline(data)`` -> short list of (label, value) facts for the summary.
7. ``build_models()`` (optional): construct the models the run will integrate, so
   ``validate`` rejects a method that cannot integrate them before anything runs.

The pipeline never special-cases a kind.
"""

from __future__ import annotations

import fnmatch
import hashlib
import json
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from pydantic import Field, ValidationError

from .. import __version__
from .. import sweep as _sweep
from ..cache import default_cache
from ..codestamp import physics_code
from ..config import (
    ConfigError,
    ReportConfig,
    RunConfig,
    SourceConfig,
    Strict,
    deep_merge,
    format_validation_error,
)
from ..lazy import lazy_module
from ..results import AuditCase, Check, Results, RunRecord

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..archive import ArchiveData
    from ..core.model import OdeModel

_integrators = lazy_module("reportgen.core.integrators")
_stability = lazy_module("reportgen.core.integrators.stability")
_study = lazy_module("reportgen.core.study")
_common_plots = lazy_module("reportgen.plots.common")

#: config tables that never change the numbers: not part of the simulate key
PRESENTATION_KEYS = ("title", "report", "preset")


class SceneConfig(Strict):
    """Keys every kind shares.  Subclasses add ``params``, ``initial`` and their own tables."""

    kind: str
    title: str = Field("", max_length=300)
    preset: str | None = None
    run: RunConfig | None = None
    report: ReportConfig = ReportConfig()


@dataclass(frozen=True)
class Section:
    """A report section the kind can show."""

    name: str
    title: str
    integrates: bool = False  # needs /runs/main
    description: str = ""
    #: a family section that draws this point set of the sweep (``/sweep/points/<points>``):
    #: held only when the members gave it points
    points: str = ""


@dataclass
class FigureSpec:
    """A figure of a section: saved as its own files and shown inline."""

    name: str
    figure: Figure
    caption: str


@dataclass
class Table:
    caption: str
    header: list[str]
    rows: list[list[str]]


@dataclass
class SectionContent:
    figures: list[FigureSpec] = field(default_factory=list)
    tables: list[Table] = field(default_factory=list)
    facts: list[tuple[str, str]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    #: displayed equations: (what it is, TeX), typeset by the report (reportgen.equations)
    equations: list[tuple[str, str]] = field(default_factory=list)


ProgressFn = Callable[[float], None]


def fmt(x: Any, digits: int = 10) -> str:
    """A number as lecture-table text."""
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, (float, np.floating)):
        x = float(x)
        if not math.isfinite(x):
            return str(x)
        if x != 0 and (abs(x) < 1e-3 or abs(x) >= 1e6):
            return f"{x:.{min(digits, 4)}e}"
        return f"{x:.{digits}g}"
    return str(x)


def fmt_err(x: float) -> str:
    return f"{x:.1e}" if math.isfinite(x) else str(x)


def _solution_attrs(sol) -> dict[str, Any]:
    """The archived attributes of an integrator Solution."""
    return {
        "method": sol.method,
        "rtol": sol.rtol,
        "atol": sol.atol,
        "h": float("nan") if sol.h is None else float(sol.h),
        "nfev": int(sol.nfev),
        "nsteps": int(sol.nsteps),
        "nreject": int(sol.nreject),
        "wall_time_s": float(sol.wall_time_s),
        "compile_time_s": float(sol.compile_time_s),
        "status": sol.status,
        "message": "" if sol.status == "ok" else sol.message,
    }


#: every Scene subclass defined so far, by kind (filled by ``__init_subclass__``)
REGISTRY: dict[str, type[Scene]] = {}


class Scene:
    """Base class of every scene kind (see the module docstring for the contract)."""

    kind: ClassVar[str]
    summary: ClassVar[str]
    Config: ClassVar[type[SceneConfig]]
    presets: ClassVar[dict[str, dict[str, Any]]] = {}
    sections: ClassVar[tuple[Section, ...]] = ()
    #: sections shown when the config names none (None: all of ``sections``)
    default_section_names: ClassVar[tuple[str, ...] | None] = None
    #: position in ``reportgen kinds`` and the docs (the SPEC's order)
    order: ClassVar[int] = 100
    #: sections whose data ``simulate`` computes only when the report shows them (costly
    #: work, promise 3); which of them are wanted is part of the simulate key
    computed_on_request: ClassVar[tuple[str, ...]] = ("error_vs_runtime",)
    #: why the study covers only t ≤ ``/analysis`` ``study_t_end`` of the run, for a kind
    #: whose simulate stores one (shown in the error-against-run-time section)
    study_horizon_reason: ClassVar[str] = ""
    #: the report's sections for an archive of a sweep (a family of runs, ``[sweep]``):
    #: the kind's family figures, then the generic ones of every sweep
    family_sections: ClassVar[tuple[Section, ...]] = ()
    SWEEP_SECTIONS: ClassVar[tuple[Section, ...]] = (
        Section("sweep_results", "Results across the family",
                description="Each result of the kind's analysis against the swept value."),
        Section("sweep_members", "Members kept whole",
                description="The members whose whole run the archive keeps ([sweep] store)."),
    )
    #: results of the members' analysis left out of the family's results figure (fnmatch
    #: patterns): the kind's own bookkeeping and self-checks, noise against a swept value
    SWEEP_HIDDEN_RESULTS: ClassVar[tuple[str, ...]] = ()
    #: the validated ``[sweep]`` table, if the config has one (set by ``__init__``)
    sweep: _sweep.SweepSpec | None
    #: this scene is a member of a sweep (made by :meth:`member`): it computes what the
    #: family figures need of it (a surface of section's crossings, say), which a single
    #: run of the same config does not show and so does not compute
    family_member: bool = False
    #: rtol ladder of the study's runs of our adaptive methods (None: the study's default);
    #: ``reportgen bench`` sets a finer one so that the run matching scipy is the cheapest
    study_tolerances: tuple[float, ...] | None = None

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        kind = cls.__dict__.get("kind")
        if kind is None:
            return  # an abstract intermediate class
        other = REGISTRY.get(kind)
        if other is not None and other.__qualname__ != cls.__qualname__:
            raise TypeError(f"scene kind {kind!r} is defined twice: {other.__module__} and "
                            f"{cls.__module__}")
        REGISTRY[kind] = cls

    def __init__(self, config: SceneConfig, source: SourceConfig,
                 sweep: _sweep.SweepSpec | None = None, template: dict | None = None):
        self.config = config
        self.source = source
        self.sweep = sweep
        #: the config data members of a sweep are made from (presets applied, no [sweep])
        self._template = template if template is not None else {
            k: v for k, v in source.data.items() if k != "sweep"}

    # ----------------------------------------------------------------- config
    @classmethod
    def from_source(cls, source: SourceConfig) -> Scene:
        """Validate ``source`` (presets applied) and build the scene; ConfigError lists
        every problem found."""
        data = dict(source.data)
        preset = data.get("preset")
        if preset is not None:
            if not isinstance(preset, str) or preset not in cls.presets:
                known = ", ".join(sorted(cls.presets)) or "none"
                raise ConfigError(
                    [f"{source.label}: key 'preset': must be one of {known} (got {preset!r})"]
                )
            data = deep_merge(cls.presets[preset], data)
        sweep_table = data.pop("sweep", None)
        problems = [f"{source.label}: {p}" for p in cls._check_report_keys(data)]
        try:
            config = cls.Config.model_validate(data)
        except ValidationError as exc:
            raise ConfigError(format_validation_error(source.label, exc, cls.Config)
                              + problems) from None
        spec = None
        if sweep_table is not None:
            spec, sweep_problems = _sweep.parse_sweep(sweep_table, source.label)
            problems += sweep_problems
            if spec is not None:
                problems += cls._check_members(spec, data, source.label)
        if problems:
            raise ConfigError(problems)
        return cls(config, source, sweep=spec, template=data)

    @classmethod
    def _check_members(cls, spec: _sweep.SweepSpec, data: dict, label: str) -> list[str]:
        """Problems of the members at the corners of a sweep's grid (each key at its
        smallest and largest value), each naming the swept key and the member."""
        problems = []
        for assignments in _sweep.corner_members(spec):
            try:
                cls.Config.model_validate(_sweep.member_data(data, assignments))
            except ValidationError as exc:
                member = ", ".join(f"{p} = {v:g}" for p, v in assignments.items())
                for line in format_validation_error(label, exc, cls.Config):
                    rule = line.removeprefix(f"{label}: ")
                    entry = (f"{label}: key 'sweep': the member with {member} is invalid: "
                             f"{rule}")
                    if entry not in problems:
                        problems.append(entry)
        return problems

    @classmethod
    def _check_report_keys(cls, data: dict) -> list[str]:
        problems = []
        known = [s.name for s in cls.sections + cls.family_sections + cls.SWEEP_SECTIONS]
        report = data.get("report")
        sections = report.get("sections") if isinstance(report, dict) else None
        for name in sections if isinstance(sections, list) else []:
            if name not in known:
                problems.append(
                    f"key 'report.sections': '{name}' is not a section of kind "
                    f"'{cls.kind}' (known: {', '.join(known)})"
                )
        run = data.get("run")
        method = run.get("method", "auto") if isinstance(run, dict) else "auto"
        if isinstance(method, str) and method != "auto" and method not in _integrators.METHODS:
            problems.append(f"key 'run.method': unknown integrator (got {method!r}; known: auto, "
                            f"{', '.join(sorted(_integrators.METHODS))})")
        return problems

    @property
    def title(self) -> str:
        return self.config.title or f"{self.kind.replace('_', ' ')} ({self.source.name})"

    def resolved_config(self) -> dict[str, Any]:
        """The validated config with presets and defaults filled in (JSON types), and the
        ``[sweep]`` table if any (ranges as ranges)."""
        resolved = self.config.model_dump(mode="json")
        if self.sweep is not None:
            resolved["sweep"] = self.sweep.resolved()
        return resolved

    # ------------------------------------------------------------------ sweeps
    def member(self, assignments: dict[str, float]) -> Scene:
        """The scene of one sweep member: this config with the swept keys set, without
        its study (a family's members are not each timed against scipy)."""
        data = _sweep.member_data(self._template, assignments)
        if isinstance(data.get("run"), dict):
            data["run"] = {**data["run"], "study": False}
        scene = type(self).from_source(SourceConfig(path=self.source.path,
                                                    text=self.source.text, data=data))
        scene.family_member = True
        return scene

    def sweep_block(self, lo: int, hi: int, values: dict[str, np.ndarray]) -> _sweep.SweepBlock:
        """Members ``lo:hi`` of the sweep (``values``: their swept values).  Default: each
        member run as a whole scene; kinds with a compiled ensemble override it."""
        return _sweep.generic_block(self.member, values, points=self.member_points,
                                    max_points=self.sweep.max_points)

    @staticmethod
    def member_points(results: Results) -> dict[str, _sweep.PointSet]:
        """A member's point sets of varying length from its results (a surface of
        section's crossings), kept in ``/sweep/points/<set>`` for the family figures.
        Default: none."""
        return {}

    def sweep_min_block(self) -> int:
        """The fewest members per block of this sweep (see :meth:`SweepSpec.block_size`):
        1 for members run as whole scenes; a compiled ensemble asks for more."""
        return 1

    def sweep_warm_up(self) -> None:
        """Import and compile (or load from numba's cache) what this sweep's member blocks
        run, so that their run time leaves it out.  Default: nothing (members run as whole scenes
        pay it in the first member)."""

    def sweep_extras(self, sweep: _sweep.SweepData) -> dict[str, Any]:
        """What the kind's family figures need besides the members' results (an exact
        curve, say), stored in ``/analysis``.  Default: nothing."""
        return {}

    def sweep_checks(self, sweep: _sweep.SweepData) -> list[Check]:
        """The family's headline numbers against their references (the worst member's,
        say).  Default: none."""
        return []

    def simulate_sweep(self, folder, progress: ProgressFn | None = None,
                       submit: _sweep.Submit | None = None) -> Results:
        """The sweep: every member's scalar results (resumable, block by block, see
        :mod:`reportgen.sweep`; with ``submit``, the blocks run on a Dask cluster) and the
        whole run of the ``store`` members."""
        import time

        spec = self.sweep
        start_up_s = math.nan
        if submit is None:  # on a cluster the workers compile
            t0 = time.perf_counter()
            self.sweep_warm_up()
            start_up_s = time.perf_counter() - t0
        t0 = time.perf_counter()
        data, resumed = _sweep.run_sweep(spec, self.sweep_block, folder, self.physics_key(),
                                         progress, min_block=self.sweep_min_block(),
                                         submit=submit)
        members_s = time.perf_counter() - t0
        results = Results()
        for i in spec.stored_members():
            member = self.member({p: float(v[i]) for p, v in data.values.items()})
            run = member.simulate().runs.get("main")
            if run is not None:
                results.runs[f"member_{i}"] = run
        counts = data.counts()
        data.attrs.update({"members_wall_time_s": members_s, "resumed": resumed,
                           "members_start_up_s": start_up_s})
        results.sweep = data
        results.analysis = {"sweep_members": spec.size, "sweep_ok": counts.get("ok", 0),
                            "sweep_members_per_s": (spec.size - resumed) / max(members_s, 1e-9),
                            **self.sweep_extras(data)}
        results.checks = self.sweep_checks(data)
        bad = spec.size - counts.get("ok", 0)
        if bad:
            results.flag("unstable" if counts.get("ok", 0) else "failed",
                         f"{bad} of {spec.size} members without a result: " + ", ".join(
                             f"{n} {k}" for k, n in counts.items() if k != "ok"))
        return results

    def wants_section(self, name: str) -> bool:
        """Whether the report will show section ``name`` (the configured list, else all the
        kind's sections)."""
        asked = self.config.report.sections
        return any(s.name == name for s in self.sections) and (asked is None or name in asked)

    def computes(self, name: str) -> bool:
        """Whether ``simulate`` computes the data of the on-request section ``name``."""
        return self.wants_study() if name == "error_vs_runtime" else self.wants_section(name)

    def wants_study(self) -> bool:
        """Whether this run computes the error-against-run-time study (promise 3: not if
        the report will not show it)."""
        run = self.config.run
        return run is not None and run.study and self.wants_section("error_vs_runtime")

    def physics_key(self) -> str:
        """Content key of the simulate stage: the validated, preset-resolved physics, the
        reportgen version and its code (:func:`reportgen.codestamp.physics_code`).  Title,
        ``[report]`` and the preset's name are not in it; whether the study and the other
        ``computed_on_request`` sections are wanted is (they are computed only then)."""
        physics = {k: v for k, v in self.resolved_config().items()
                   if k not in PRESENTATION_KEYS}
        computed = sorted(name for name in self.computed_on_request if self.computes(name))
        blob = json.dumps({"physics": physics, "computed": computed,
                           "reportgen": __version__, "code": physics_code()},
                          sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(blob.encode("utf-8")).hexdigest()

    def models(self) -> list[OdeModel]:
        """The models :meth:`simulate` integrates with the configured ``[run] method``
        (not those it integrates with a method it fixes itself), built as simulate builds
        them and without integrating.  Default: none."""
        return []

    def build_models(self) -> None:
        """Construct the models this scene integrates (``validate`` calls it); raise
        ConfigError when the configured method cannot integrate one.  With ``method =
        "auto"`` (the policy picks a method that fits) nothing is built: validation then
        imports no numerics."""
        run = self.config.run
        if run is None or run.method == "auto":
            return
        models = self.models()
        method = _integrators.METHODS[run.method]
        problems: list[str] = []
        for model in models:
            try:
                method.check(model)
            except _integrators.MethodMismatch as exc:
                line = f"{self.source.label}: key 'run.method': {exc}"
                if line not in problems:
                    problems.append(line)
        if problems:
            raise ConfigError(problems)

    # ------------------------------------------------- report side (archive only)
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
    def audit_cases(cls) -> list[AuditCase]:
        """Stiff and extreme cases of this kind for ``reportgen audit``."""
        return []

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
        from ..plots import common as common_plots

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
        from ..plots import common as common_plots

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
        fig = _common_plots.invariant_drift(rec.t, rec.invariants, scales=scales or None,
                                            labels=labels)
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

    # --------------------------------------------------- simulate side (physics)
    def simulate(self, progress: ProgressFn | None = None) -> Results:
        raise NotImplementedError

    def integrate(
        self,
        model: OdeModel,
        y0: np.ndarray,
        t_eval: np.ndarray,
        invariants: Callable[[np.ndarray, np.ndarray], dict[str, np.ndarray]] | None = None,
        progress: ProgressFn | None = None,
        n_periods: float | None = None,
        invariant_scales: dict[str, float] | None = None,
        method: str | None = None,
        method_reason: str | None = None,
        fictitious_time: tuple[int, tuple[str, ...], Callable] | None = None,
    ) -> RunRecord:
        """Integrate ``model`` with the configured method and return the archived run.

        ``invariants(t, y)`` gives the conserved quantities, each shape (N,);
        their drift (relative to ``invariant_scales[name]``, default the
        invariant's own size) is part of the run's stability verdict.  The scales
        are archived as run attrs ``scale_<name>``.  ``method`` (with ``method_reason``)
        overrides the config's method, for a scene whose physics decides it.

        The choice, the stiffness switch and the failure verdict are the solver policy's
        (:func:`reportgen.core.integrators.solve`); its :class:`RunStatus` is archived as
        the run attr ``solver_status`` next to the overall ``status``.

        ``fictitious_time`` = (index of the physical time in the state, archived columns,
        ``convert``) for a regularized ``model`` integrated in its fictitious time
        (:func:`reportgen.core.integrators.solve_fictitious_time`, outputs at the physical
        times ``t_eval``); ``convert(states)`` gives the archived (N, len(columns)) array.
        """
        run = self.config.run
        if method is None:
            method, method_reason = run.method, "named in the config"
        spec = _integrators.SolverSpec(method=method, rtol=run.rtol, atol=run.atol, h=run.h,
                                       reason=method_reason or "chosen by the scene")
        if fictitious_time is not None:
            time_index, columns, convert = fictitious_time
            res = _integrators.solve_fictitious_time(model, y0, t_eval, time_index, spec,
                                                     spec.reason, progress=progress)
            return self.run_record(res, columns, y=convert(res.solution.y),
                                   invariants=invariants, invariant_scales=invariant_scales)
        try:
            res = _integrators.solve(model, y0, t_eval, spec, n_periods=n_periods,
                                     progress=progress)
        except _integrators.MethodMismatch as exc:
            raise ConfigError([f"{self.source.label}: key 'run.method': {exc}"]) from None
        return self.run_record(res, model.columns, invariants=invariants,
                               invariant_scales=invariant_scales)

    def run_record(self, res, columns, y: np.ndarray | None = None,
                   invariants: Callable[[np.ndarray, np.ndarray], dict[str, np.ndarray]]
                   | None = None, invariant_scales: dict[str, float] | None = None) -> RunRecord:
        """The archived run of a solver-policy result (:class:`PolicyResult`): attrs, the
        invariants and the stability verdict (see :meth:`integrate`).  ``y`` (N, len(columns))
        replaces the solution's states when the integrated variables are not the archived
        ones (a regularized formulation, converted back by the scene)."""
        sol = res.solution
        y = sol.y if y is None else y
        inv = invariants(sol.t, y) if invariants is not None else {}
        attrs = _solution_attrs(sol) | {
            "method_reason": res.reason, "solver_status": res.status.value,
            "status": res.status.verdict, "message": res.message}
        record = RunRecord(t=sol.t, y=y, columns=list(columns), invariants=inv, attrs=attrs)
        _stability.assess_run(record, rtol=self.config.run.rtol, scales=invariant_scales)
        for name, scale in (invariant_scales or {}).items():
            record.attrs[f"scale_{name}"] = float(scale)
        return record

    def reference_run(self, model: OdeModel, y0: np.ndarray, t_eval: np.ndarray) -> np.ndarray:
        """An independent reference trajectory, shape (N, d), where no closed form exists:
        compiled DOP853 at rtol 1e-14 (the recipe the study's references share)."""
        return _study.reference_run(model, y0, t_eval)

    def study(self, results: Results, model: OdeModel, y0, t_eval, reference=None,
              progress: ProgressFn | None = None, reference_kind: str = "exact") -> None:
        """Fill ``results.study`` with the error-against-run-time study, if this run wants
        it (:meth:`wants_study`).  scipy peers' rows come from the user cache when it
        holds this problem (:mod:`reportgen.cache`); ours are measured every time.
        ``reference_kind`` says what a given ``reference`` is (default: a closed form)."""
        if not self.wants_study():
            return
        result = _study.work_precision(model, y0, t_eval, reference=reference,
                                       progress=progress, cache=default_cache(),
                                       budget_s=self.config.run.study_budget,
                                       reference_kind=reference_kind,
                                       our_tolerances=self.study_tolerances)
        results.study = result.to_records()
        results.study_attrs = {"reference_kind": result.reference_kind,
                               "budget_s": float(self.config.run.study_budget),
                               "over_budget": ",".join(result.over_budget)}


def member_text(sweep, i: int, short: bool = False) -> str:
    """A sweep member's swept values as text: ``initial.theta = 0.5`` (``short``: the
    last part of each key at 4 digits, ``theta = 0.5``, for figure labels)."""
    return ", ".join(f"{p.rsplit('.', 1)[-1] if short else p} = "
                     f"{fmt(float(v[i]), 4 if short else 8)}" for p, v in sweep.values.items())


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
