"""The simulate face of a kind: config -> results (the physics).

A kind's ``simulation.py`` subclasses :class:`Simulation`.  The subclass contract:

1. ``simulate(progress)`` -> :class:`~reportgen.scene.results.Results`; use :meth:`integrate`
   for trajectories (method choice, timing, invariants and the stability verdict done
   one way everywhere), :meth:`study` for the error-against-run-time study and
   :meth:`reference_run` for a reference trajectory where no closed form exists.  Put
   reference curves on the output grid in ``RunRecord.reference`` and every other curve
   a figure shows in ``Results.analysis``.
2. ``schema``: the kind's declared results (:class:`~reportgen.scene.schema.ResultsSchema`,
   in ``results.py``); what ``simulate`` returns must match it, or the archive is not
   written (:func:`reportgen.archive.store.write_archive`).  :meth:`results_schema` may
   refine it per config (user-named coordinates).
3. ``models()`` (optional): the models the run will integrate, so ``validate`` rejects a
   method that cannot integrate them before anything runs.
4. Sweeps: ``sweep_block`` and its friends, for kinds with a compiled ensemble.
5. ``audit_cases()``: the kind's stiff and extreme cases for ``reportgen audit``.
6. ``accuracy_scale(reference_size)``: the scene's own scale for the error against a
   reference (a Kepler orbit's semi-major axis); default the reference's largest value.
   After ``simulate`` returns, every run with a reference and every study row whose error
   exceeds :data:`~reportgen.scene.results.ACCURACY_TOLERANCE` of it is "inaccurate"
   (:meth:`judge_accuracy`, applied to every kind's ``simulate``).  For a chaotic scene
   (``/analysis`` ``lyapunov_time``) runs are compared with their reference up to that time
   only: beyond it the error measures the chaos (the invariants' drift still judges them).
7. Physical behaviour (a sleeping top that tilts away, an escape, chaos) is not a status:
   store its verdict in words as ``/analysis`` ``behaviour`` (declared by the kind).
8. The archive's size before anything runs (:mod:`reportgen.scene.budget`), from the
   config alone (no symbolic work: it is checked before a time limit starts):
   ``budget_schema()`` (default the kind's ``schema``), ``stored_runs()`` (default one),
   ``stored_columns()`` (default the declared columns) and ``dimension_size(name)`` of a
   declared dimension other than ``t``, where a kind knows them.

Numerics come from ``reportgen.core`` (and the kind's own numerical modules); nothing
here draws or renders.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from . import sweep as _sweep
from .base import ProgressFn, Scene
from .config import SourceConfig
from .results import AccuracyScale, AuditCase, Check, Results, RunRecord
from .schema import ResultsSchema

if TYPE_CHECKING:
    from ..core.model import OdeModel


class Simulation(Scene):
    """Base class of a kind's simulation (see the module docstring for the contract)."""

    faces: ClassVar[frozenset[str]] = frozenset({"simulation"})

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        own = cls.__dict__.get("simulate")
        if own is not None and not getattr(own, "judges_accuracy", False):
            cls.simulate = _judged(own)

    # -------------------------------------------------------------- accuracy
    def accuracy_scale(self, reference_size: float) -> AccuracyScale:
        """The scene's own scale for the error of a run or study row against its reference
        (contract point 6).  ``reference_size``: the reference's largest |value|, the
        default.  Kinds override it with a physical size (an orbit's semi-major axis)."""
        return AccuracyScale(float(reference_size), "the reference's largest |value|")

    def accuracy_horizon(self, results: Results) -> float:
        """The time up to which a run is compared with its reference: a chaotic scene's
        Lyapunov time (``/analysis`` ``lyapunov_time``), else the whole run (inf).  A kind
        whose motion passes near an unstable equilibrium overrides it (a sleeping top
        below its threshold: one nutation period, up to its first return to the vertical,
        where any error is amplified again)."""
        return float(results.analysis.get("lyapunov_time", math.inf))

    def judge_accuracy(self, results: Results) -> None:
        """Mark "inaccurate" (in place) every run whose largest error against its
        reference exceeds :data:`~reportgen.scene.results.ACCURACY_TOLERANCE` ×
        :meth:`accuracy_scale`.  A run stores ``error_max``, ``accuracy_scale`` and
        ``accuracy_horizon`` attrs.  Runs already worse than "ok" keep their status.  (The
        study's rows: :meth:`IntegratingSimulation.judge_accuracy`; a kind that does not
        integrate imports no integrator.)"""
        horizon = self.accuracy_horizon(results)
        judged: set[int] = set()
        for run in results.runs.values():
            if id(run) in judged or not run.reference:
                continue
            judged.add(id(run))
            error, size = reference_error(run, horizon)
            if not math.isfinite(size):
                continue
            scale = self.accuracy_scale(size)
            run.attrs.update({"error_max": error, "accuracy_scale": scale.value,
                              "accuracy_horizon": min(horizon, float(run.t[-1]))})
            if run.status == "ok" and scale.verdict(error) == "inaccurate":
                run.attrs["status"] = "inaccurate"
                run.attrs["message"] = "; ".join(m for m in (run.message, scale.reason(error)
                                                             + " against its reference") if m)

    def results_schema(self) -> ResultsSchema | None:
        """The results this scene stores.  Default: the kind's ``schema``."""
        return self.schema

    def config_unit(self, path: str) -> str:
        """The unit of the config key ``path`` ("params.g"), from its declared field
        description ("... [m/s^2]", :func:`~reportgen.scene.schema.config_quantity`); ""
        when none is declared."""
        from .schema import config_quantity

        return config_quantity(self.Config, path).unit

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
        :mod:`reportgen.scene.sweep`; with ``submit``, the blocks run on a Dask cluster) and the
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
        data.value_units = {p: self.config_unit(p) for p in data.values}
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

    # ------------------------------------------------- the archive, before it runs
    def stored_runs(self) -> int:
        """How many runs (``/runs/<name>``) a run of this config stores (contract point
        8): one, the main run, unless the kind keeps others beside it."""
        return 1

    def budget_schema(self) -> ResultsSchema | None:
        """The declared results :mod:`reportgen.scene.budget` counts, from the config alone
        (contract point 8): the kind's ``schema``; a kind whose results follow its config
        (user-named coordinates) declares them without the symbolic work
        :meth:`results_schema` may do (typesetting, a Lagrangian's analysis)."""
        return self.schema

    def stored_columns(self) -> int:
        """State columns of each run this config stores: the budget's declared columns (an
        upper bound) unless the kind counts them for the config (contract point 8)."""
        schema = self.budget_schema()
        return len(schema.columns) if schema is not None else 0

    def dimension_size(self, name: str) -> int | None:
        """The size of the declared dimension ``name`` (not ``t``) for this config, or
        None when the kind does not say (counted as :meth:`stored_columns`)."""
        return None

    def models(self) -> list[OdeModel]:
        """The models :meth:`simulate` integrates with the configured ``[run] method``
        (not those it integrates with a method it fixes itself), built as simulate builds
        them and without integrating.  Default: none."""
        return []

    def build_models(self) -> None:
        """Construct the models this scene integrates, so that ``validate`` refuses what
        ``run`` would.  Default: nothing (see
        :meth:`~reportgen.scene.integration.IntegratingSimulation.build_models`)."""

    @classmethod
    def audit_cases(cls) -> list[AuditCase]:
        """Stiff and extreme cases of this kind for ``reportgen audit``."""
        return []

    # --------------------------------------------------- simulate side (physics)
    def simulate(self, progress: ProgressFn | None = None) -> Results:
        raise NotImplementedError


def reference_error(run: RunRecord, horizon: float = math.inf) -> tuple[float, float]:
    """(largest |y - reference| over the run's reference columns and the samples with
    t <= ``horizon``, the reference's largest |value| there); NaNs when it has none."""
    columns = [c for c in run.reference if c in run.columns]
    keep = np.asarray(run.t) <= horizon
    if not columns or not np.any(keep):
        return math.nan, math.nan
    ref = np.column_stack([np.asarray(run.reference[c], dtype=float) for c in columns])[keep]
    y = np.column_stack([run.column(c) for c in columns])[keep]
    finite = np.isfinite(ref)
    if not np.any(finite):
        return math.nan, math.nan
    diff = np.abs(y - ref)[finite]
    error = float(np.max(diff)) if np.all(np.isfinite(diff)) else math.inf
    return error, float(np.max(np.abs(ref[finite])))


def _judged(simulate):
    """``simulate`` followed by :meth:`Simulation.judge_accuracy` (once per results)."""
    import functools

    @functools.wraps(simulate)
    def wrapper(self, *args, **kwargs):
        depth = self.__dict__.get("_simulate_depth", 0)  # a kind calling super().simulate
        self._simulate_depth = depth + 1
        try:
            results = simulate(self, *args, **kwargs)
        finally:
            self._simulate_depth = depth
        if depth == 0 and isinstance(results, Results) and not results.accuracy_judged:
            results.accuracy_judged = True
            self.judge_accuracy(results)
        return results

    wrapper.judges_accuracy = True
    return wrapper

