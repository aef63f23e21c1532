"""The scene base class: a kind's configuration, presets and stage keys.

A kind is a package ``reportgen/kinds/<kind>/`` (see :mod:`reportgen.kinds`): its
config schema and presets (``config.py``), its declared results (``results.py``), its
simulation (``simulation.py``, a :class:`~reportgen.scene.simulation.Simulation`), its
report (``report.py``, a :class:`~reportgen.scene.report.Report`), plots and template.
Its ``__init__.py`` joins the two faces into one class with a ``kind``; defining that
class registers the kind.  The pipeline never special-cases a kind.

The stage keys are computed from the code each face imports
(:func:`reportgen.support.codestamp.code_hash`): the simulate key from the simulation's modules
and the config's, the figures key from the report's.  So a caption edit re-renders that
kind's reports and simulates nothing.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

from pydantic import Field, ValidationError

from .. import __version__
from ..support.codestamp import code_hash, files_hash
from ..support.layout import template_dir
from . import sweep as _sweep
from .config import (
    ConfigError,
    ReportConfig,
    RunConfig,
    SourceConfig,
    Strict,
    deep_merge,
    did_you_mean,
    format_validation_error,
)
from .schema import ResultsSchema
from .units import convert_at

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



ProgressFn = Callable[[float], None]

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
    #: the kind in words, the start of its default titles ("Plane pendulum")
    name_in_words: ClassVar[str] = ""
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
                description="The members whose whole run the archive keeps, spread evenly "
                            "over the family."),
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
    #: methods the study runs beyond its default list (``reportgen bench``: the Taylor
    #: integrator, whose compile is too dear for every report's study)
    study_extra_methods: tuple[str, ...] = ()
    #: which faces this class has: "simulation" (:class:`~.simulation.Simulation`),
    #: "report" (:class:`~.report.Report`) or both (a kind's joined class)
    faces: ClassVar[frozenset[str]] = frozenset()
    #: the kind's declared results (``kinds/<kind>/results.py``); None: undeclared
    schema: ClassVar[ResultsSchema | None] = None

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "faces" not in cls.__dict__:  # a kind's joined class has both of its bases' faces
            cls.faces = frozenset().union(*(getattr(b, "faces", ()) for b in cls.__bases__))
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
                    [f"{source.label}: key 'preset': must be one of {known}"
                     f"{did_you_mean(preset, cls.presets)} (got {preset!r})"]
                )
            data = deep_merge(cls.presets[preset], data)
        sweep_table = data.pop("sweep", None)
        problems = [f"{source.label}: {p}" for p in cls._check_report_keys(data)]
        try:
            config = cls.Config.model_validate(data)
        except ValidationError as exc:
            raise ConfigError(format_validation_error(source.label, exc, cls.Config)
                              + problems) from None
        if (preset is not None and "title" not in source.data
                and "title" in cls.presets[preset] and cls.preset_as_given(config) is None):
            # the preset's title names the preset's scene; a config that changes its
            # physics is another scene, titled by its own numbers (default_title)
            config = config.model_copy(update={"title": ""})
        spec = None
        if sweep_table is not None:
            spec, sweep_problems = _sweep.parse_sweep(
                sweep_table, source.label, convert=functools.partial(convert_at, cls.Config))
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
                    f"key 'report.sections': {name!r} is not a section of kind "
                    f"'{cls.kind}' (known: {', '.join(known)})"
                )
        return problems + cls._check_run_keys(data)

    @classmethod
    def _check_run_keys(cls, data: dict) -> list[str]:
        """Problems of ``[run]`` the schema cannot see (the simulate face names them)."""
        return []

    @property
    def title(self) -> str:
        """The config's ``title``, else :meth:`default_title` of this scene (for a sweep,
        the kind's name, the family's size and what it varies)."""
        if self.config.title:
            return self.config.title
        if self.sweep is None:
            return self.default_title(self.config)
        # a family: the base config's own numbers (the swept value among them) would
        # describe one member, so the kind's name and what the family varies
        from .schema import config_quantity

        name = self.name_in_words or self.summary.split(":")[0]
        keys = " and ".join(config_quantity(type(self.config), p).text
                            for p in self.sweep.paths)
        return f"{name[:1].upper() + name[1:]}: a family of {self.sweep.size} runs over {keys}"

    @classmethod
    def preset_as_given(cls, config: Any) -> str | None:
        """The config's preset, if its physics is the preset's as given: a config that
        changes a preset's parameters or initial state (the figure-eight with one mass
        changed) is no longer that preset's scene, so its words must not name it.
        ``[run]``, ``[report]`` and the title may differ."""
        preset = getattr(config, "preset", None)
        if preset is None or preset not in cls.presets:
            return None
        for table, values in cls.presets[preset].items():
            if table in ("run", "report", "title", "sweep") or not isinstance(values, dict):
                continue
            given = getattr(config, table, None)
            for key, value in values.items():
                ours = given.get(key) if isinstance(given, dict) else getattr(given, key, None)
                if ours is None or not _same_value(ours, value):
                    return None
        return preset

    @classmethod
    def default_title(cls, config: Any) -> str:
        """A title in words for a config without one: the kind's name, its preset's and
        the numbers that define the scene.  ``config`` is the validated config or the
        archive's resolved one (read by attribute only, so either serves).  Kinds
        override it; this default names the kind and the preset."""
        name = cls.name_in_words or cls.summary.split(":")[0]
        name = name[:1].upper() + name[1:]
        preset = cls.preset_as_given(config)
        return f"{name} ({preset.replace('_', ' ')})" if preset else name

    def resolved_config(self) -> dict[str, Any]:
        """The validated config with presets and defaults filled in (JSON types), and the
        ``[sweep]`` table if any (ranges as ranges)."""
        resolved = self.config.model_dump(mode="json")
        if self.sweep is not None:
            resolved["sweep"] = self.sweep.resolved()
        return resolved


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
        reportgen version and the code the kind's simulation imports
        (:meth:`simulation_modules`, hashed with all they import).  Title, ``[report]``
        and the preset's name are not in it; whether the study and the other
        ``computed_on_request`` sections are wanted is (they are computed only then)."""
        physics = {k: v for k, v in self.resolved_config().items()
                   if k not in PRESENTATION_KEYS}
        computed = sorted(name for name in self.computed_on_request if self.computes(name))
        blob = json.dumps({"physics": physics, "computed": computed,
                           "reportgen": __version__,
                           "code": self.simulation_code()},
                          sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(blob.encode("utf-8")).hexdigest()

    @classmethod
    def simulation_modules(cls) -> list[str]:
        """The modules that decide this kind's numbers: those of its simulation classes
        and of its config schema (the simulate key follows their imports)."""
        return _faces(cls, "simulation") + [cls.Config.__module__]

    @classmethod
    def simulation_code(cls) -> str:
        """Hash of the code :meth:`simulation_modules` import, once per process (the code
        this process runs was read when it was imported)."""
        key = cls.__dict__.get("_simulation_code")
        if key is None:
            key = cls._simulation_code = code_hash(cls.simulation_modules())
        return key

    @classmethod
    def report_modules(cls) -> list[str]:
        """The modules that turn this kind's archive into figures and pages: those of its
        report classes (the figures key follows their imports)."""
        return _faces(cls, "report")

    @classmethod
    def template_path(cls) -> Path | None:
        """The kind's prose template, ``kinds/<kind>/template.html.j2`` (None if it has
        none)."""
        path = Path(sys.modules[cls.__module__].__file__)
        own = path.parent / "template.html.j2"
        return own if path.name == "__init__.py" and own.is_file() else None

    @classmethod
    def report_code(cls) -> str:
        """Hash of the code and templates that turn this kind's archive into figures and
        pages: its report modules and the rendering modules with all they import, the
        shared templates and the kind's own.  A caption edit in one kind changes only
        that kind's."""
        key = cls.__dict__.get("_report_code")
        if key is None:
            shared = template_dir()
            own = cls.template_path()
            key = (code_hash([*cls.report_modules(), *RENDERING_MODULES])
                   + files_hash([p for p in shared.rglob("*") if p.is_file()], shared)
                   + (files_hash([own], own.parent) if own is not None else ""))
            cls._report_code = key
        return key


#: the shared modules that render every kind's report (besides the kind's own report code)
RENDERING_MODULES = ("reportgen.rendering.report", "reportgen.rendering.pdf",
                     "reportgen.rendering.svgslim")


def _faces(cls: type, face: str) -> list[str]:
    """Modules of the classes in ``cls``'s MRO that have the ``face`` ("simulation" or
    "report", see ``Scene.faces``) and only that one: the kind's package joins its
    simulation and report in one class (with both faces), which is left out, as its
    ``__init__`` only composes."""
    mods = []
    for c in cls.__mro__:
        if getattr(c, "faces", None) == {face} and c.__module__ not in mods:
            mods.append(c.__module__)
    return mods


def _same_value(ours: Any, preset: Any) -> bool:
    """Whether a config value equals a preset's (numbers to 1e-12 relative, lists and
    tables element by element; a model or enum is compared by its value)."""
    if hasattr(ours, "model_dump"):
        ours = ours.model_dump(mode="json")
    ours = getattr(ours, "value", ours)
    if isinstance(preset, dict):
        return isinstance(ours, dict) and all(
            k in ours and _same_value(ours[k], v) for k, v in preset.items())
    if isinstance(preset, (list, tuple)):
        try:
            return len(ours) == len(preset) and all(
                _same_value(a, b) for a, b in zip(ours, preset, strict=True))
        except TypeError:
            return False
    if isinstance(preset, (int, float)) and not isinstance(preset, bool):
        try:
            return math.isclose(float(ours), float(preset), rel_tol=1e-12, abs_tol=1e-300)
        except (TypeError, ValueError):
            return False
    return ours == preset
