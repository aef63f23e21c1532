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
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from . import sweep as _sweep
from .base import ProgressFn, Scene
from .config import SourceConfig
from .results import AuditCase, Check, Results
from .schema import ResultsSchema

if TYPE_CHECKING:
    from ..core.model import OdeModel


class Simulation(Scene):
    """Base class of a kind's simulation (see the module docstring for the contract)."""

    faces: ClassVar[frozenset[str]] = frozenset({"simulation"})

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

