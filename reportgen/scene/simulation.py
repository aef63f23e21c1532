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

Numerics come from ``reportgen.core`` (and the kind's own numerical modules); nothing
here draws or renders.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from ..lazy import lazy_module
from ..support.cache import default_cache
from . import sweep as _sweep
from .base import ProgressFn, Scene
from .config import ConfigError, SourceConfig
from .results import AuditCase, Check, Results, RunRecord
from .schema import ResultsSchema

if TYPE_CHECKING:
    from ..core.model import OdeModel

_integrators = lazy_module("reportgen.core.integrators")
_stability = lazy_module("reportgen.core.integrators.stability")
_study = lazy_module("reportgen.core.study")


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



class Simulation(Scene):
    """Base class of a kind's simulation (see the module docstring for the contract)."""

    faces: ClassVar[frozenset[str]] = frozenset({"simulation"})

    @classmethod
    def _check_run_keys(cls, data: dict) -> list[str]:
        run = data.get("run")
        method = run.get("method", "auto") if isinstance(run, dict) else "auto"
        if isinstance(method, str) and method != "auto" and method not in _integrators.METHODS:
            return [f"key 'run.method': unknown integrator (got {method!r}; known: auto, "
                    f"{', '.join(sorted(_integrators.METHODS))})"]
        return []

    def results_schema(self) -> ResultsSchema | None:
        """The results this scene stores.  Default: the kind's ``schema``."""
        return self.schema

    def config_unit(self, path: str) -> str:
        """The unit of the config key ``path`` ("params.g"), from its declared field
        description ("... [m/s^2]"); "" when none is declared."""
        import re

        model: Any = self.Config
        field = None
        for part in path.split("."):
            fields = getattr(model, "model_fields", None)
            if not fields or part not in fields:
                return ""
            field = fields[part]
            model = field.annotation
            for arg in getattr(model, "__args__", ()) or ():  # X | None
                if hasattr(arg, "model_fields"):
                    model = arg
        found = re.search(r"\[([^\]]+)\]\s*$", (field.description or "") if field else "")
        return found.group(1) if found else ""

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


    @classmethod
    def audit_cases(cls) -> list[AuditCase]:
        """Stiff and extreme cases of this kind for ``reportgen audit``."""
        return []

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
        holds this problem (:mod:`reportgen.support.cache`); ours are measured every time.
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
