"""The scene base class: owns configuration, presets, sections and the run bookkeeping.

A scene kind is one module under ``reportgen/scenes/`` with one subclass of
:class:`Scene`, registered in ``reportgen/scenes/__init__.py``.  The subclass
contract:

1. ``kind`` (the config's ``kind``), ``summary`` (one line) and ``Config``, a
   :class:`SceneConfig` subclass declaring the kind's tables (``params``,
   ``initial``, …) with their rules; cross-key physics checks go in pydantic
   ``model_validator``s and raise ``ValueError`` naming the keys.
2. ``presets``: name -> partial config dict; explicit keys override a preset.
3. ``sections``: the sections the kind can show, in order, as :class:`Section`;
   ``default_sections()`` narrows them to what this scene needs.
4. ``simulate(progress)`` -> :class:`~reportgen.results.Results`; use
   :meth:`integrate` for trajectories so method choice, timing, invariants and
   stability checks are done one way everywhere.
5. One method ``section_<name>(data)`` per section, reading only the archived
   :class:`~reportgen.archive.ArchiveData` and returning :class:`SectionContent`.
6. ``headline(data)`` -> short list of (label, value) facts for the summary.

The pipeline never special-cases a kind.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from pydantic import Field, ValidationError

from ..config import (
    ConfigError,
    ReportConfig,
    RunConfig,
    SourceConfig,
    Strict,
    deep_merge,
    format_validation_error,
)
from ..results import Results, RunRecord

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..archive import ArchiveData
    from ..core.model import OdeModel


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


class Scene:
    """Base class of every scene kind (see the module docstring for the contract)."""

    kind: ClassVar[str]
    summary: ClassVar[str]
    Config: ClassVar[type[SceneConfig]]
    presets: ClassVar[dict[str, dict[str, Any]]] = {}
    sections: ClassVar[tuple[Section, ...]] = ()
    #: sections shown when the config names none (None: all of ``sections``)
    default_section_names: ClassVar[tuple[str, ...] | None] = None

    def __init__(self, config: SceneConfig, source: SourceConfig):
        self.config = config
        self.source = source

    # ----------------------------------------------------------------- config
    @classmethod
    def from_source(cls, source: SourceConfig) -> Scene:
        """Validate ``source`` (presets applied) and build the scene; ConfigError on any problem."""
        data = dict(source.data)
        preset = data.get("preset")
        if preset is not None:
            if not isinstance(preset, str) or preset not in cls.presets:
                known = ", ".join(sorted(cls.presets)) or "none"
                raise ConfigError(
                    [f"{source.label}: key 'preset': must be one of {known} (got {preset!r})"]
                )
            data = deep_merge(cls.presets[preset], data)
        try:
            config = cls.Config.model_validate(data)
        except ValidationError as exc:
            raise ConfigError(format_validation_error(source.label, exc)) from None
        scene = cls(config, source)
        problems = scene._check_report_keys()
        if problems:
            raise ConfigError([f"{source.label}: {p}" for p in problems])
        return scene

    def _check_report_keys(self) -> list[str]:
        problems = []
        known = [s.name for s in self.sections]
        for name in self.config.report.sections or []:
            if name not in known:
                problems.append(
                    f"key 'report.sections': '{name}' is not a section of kind "
                    f"'{self.kind}' (known: {', '.join(known)})"
                )
        run = self.config.run
        if run is not None and run.method != "auto":
            from ..core.integrators import METHODS

            if run.method not in METHODS:
                problems.append(
                    f"key 'run.method': unknown integrator (got {run.method!r}; "
                    f"known: auto, {', '.join(sorted(METHODS))})"
                )
        return problems

    @property
    def title(self) -> str:
        return self.config.title or f"{self.kind.replace('_', ' ')} ({self.source.name})"

    # --------------------------------------------------------------- sections
    def default_sections(self) -> list[str]:
        """The sections this scene needs; subclasses drop what their config makes irrelevant."""
        names = self.default_section_names or tuple(s.name for s in self.sections)
        return list(names)

    def chosen_sections(self) -> list[Section]:
        """The configured sections, or the defaults minus what this run will not produce."""
        names = self.config.report.sections or self.default_sections()
        if self.config.run is not None and not self.config.run.study:
            names = [n for n in names if n != "error_vs_runtime"]
        return [s for s in self.sections if s.name in names]

    def headline(self, data: ArchiveData) -> list[tuple[str, str]]:
        return []

    @classmethod
    def audit_cases(cls) -> list:
        """Stiff and extreme cases of this kind for ``reportgen audit`` (AuditCase list)."""
        return []

    @staticmethod
    def figure(name: str, figure: Figure, caption: str) -> FigureSpec:
        return FigureSpec(name=name, figure=figure, caption=caption)

    # ------------------------------------------------------------- simulation
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
    ) -> RunRecord:
        """Integrate ``model`` with the configured method and return the archived run.

        ``invariants(t, y)`` gives the conserved quantities, each shape (N,);
        their drift (relative to ``invariant_scales[name]``, default the
        invariant's own size) is part of the run's stability verdict.
        """
        from ..core.integrators import METHODS, MethodMismatch, choose_auto, integrate
        from ..core.stability import assess_run, stiffness_signs

        run = self.config.run
        method, reason = run.method, "named in the config"
        auto = method == "auto"
        if auto:
            method, reason = choose_auto(model, run.rtol, n_periods=n_periods)
        try:
            sol = integrate(model, y0, t_eval, method=method, rtol=run.rtol, atol=run.atol,
                            h=run.h, progress=progress)
        except MethodMismatch as exc:
            raise ConfigError([f"{self.source.label}: key 'run.method': {exc}"]) from None
        m = METHODS[method]
        stiff = stiffness_signs(_solution_attrs(sol), m.adaptive and not m.implicit and not m.peer,
                                model, sol.t, sol.y)
        if stiff and auto:
            # promise 2: an automatic choice that turns out stiff switches, and says so
            switched = "radau"
            reason = f"{reason} Stiffness detected with {method}: {stiff}; switched to Radau."
            method, sol = switched, integrate(model, y0, t_eval, method=switched, rtol=run.rtol,
                                              atol=run.atol, progress=progress)
        inv = invariants(sol.t, sol.y) if invariants is not None else {}
        attrs = _solution_attrs(sol) | {"method_reason": reason}
        if stiff and not auto:
            attrs["status"] = "unstable" if sol.status == "ok" else sol.status
            attrs["message"] = "; ".join(x for x in (
                sol.message if sol.status != "ok" else "",
                f"looks stiff for {method}: {stiff}; use method = \"radau\" or \"gauss6\"")
                if x)
        record = RunRecord(t=sol.t, y=sol.y, columns=list(model.columns), invariants=inv,
                           attrs=attrs)
        assess_run(record, rtol=run.rtol, scales=invariant_scales)
        return record

    def study(self, results: Results, model: OdeModel, y0, t_eval, reference=None,
              progress: ProgressFn | None = None) -> None:
        """Fill ``results.study`` with the error-against-run-time study, if the config asks."""
        if self.config.run is None or not self.config.run.study:
            return
        if "error_vs_runtime" not in [s.name for s in self.chosen_sections()]:
            return  # promise 3: do not compute what the report will not show
        from ..core.study import work_precision

        result = work_precision(model, y0, t_eval, reference=reference, progress=progress)
        results.study = result.to_records()
        results.study_attrs = {"reference_kind": result.reference_kind}
