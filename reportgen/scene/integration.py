"""The simulate face of a kind that integrates: trajectories, references and the
error-against-run-time study, done one way for every kind (:class:`IntegratingSimulation`).

Kept apart from :mod:`.simulation` so that only kinds that integrate import the
integrators: their simulate key follows the integrators' code, and an edit of an
integrator re-simulates them and no other kind.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from ..lazy import lazy_module
from ..support.cache import default_cache
from .base import ProgressFn
from .config import ConfigError
from .results import ACCURACY_TOLERANCE, Results, RunRecord
from .simulation import Simulation

if TYPE_CHECKING:
    from ..core.model import OdeModel

_integrators = lazy_module("reportgen.core.integrators")
_stability = lazy_module("reportgen.core.integrators.stability")
_study = lazy_module("reportgen.core.study")
_lyapunov = lazy_module("reportgen.core.lyapunov")


def _solution_attrs(sol) -> dict[str, Any]:
    """The archived attributes of an integrator Solution.

    ``wall_time_s`` is the time of the run that produced the archived trajectory;
    ``compile_time_s`` (compiling or loading the driver, 0 once loaded in this process)
    and ``warm_up_time_s`` (a rehearsal of the run just before it, whole when short,
    :func:`reportgen.core.integrators.compiled_run.warm_up_run`; 0 for a method that has
    none) are outside it and kept beside it."""
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
        "warm_up_time_s": float(sol.warm_up_time_s),
        "status": sol.status,
        "message": "" if sol.status == "ok" else sol.message,
    }


#: the scales of a run's invariants: by name, or a function (t, y) -> {name: scale} of the
#: run (see :meth:`IntegratingSimulation.integrate`)
InvariantScales = dict[str, float] | Callable[[np.ndarray, np.ndarray], dict[str, float]] | None

#: how far a configured step may sit from a whole fraction of the output spacing (rounding
#: of the decimal the config writes; 0.005 / 0.001 is 5.000000000000001)
STEP_MATCH = 1e-9


def step_problem(method: str, h: float | None, t_end: float, samples: int) -> str | None:
    """Why the configured step ``h`` cannot be honoured by ``method`` with ``samples``
    outputs over ``t_end``, or None.  A fixed-step method steps from output to output, so
    its step must divide the output spacing into whole steps (or it would run at another
    step than the config, and its report, say); an adaptive method chooses its own steps
    from ``rtol`` and ``atol`` and takes no ``h``."""
    if h is None:
        return None
    if method == "auto":
        return (f"a step is for a fixed-step method; name one with run.method (rk4, verlet, "
                f"yoshida4, yoshida6, yoshida8, gauss4, gauss6) or remove h (got {h:g})")
    chosen = _integrators.METHODS.get(method)
    if chosen is None:
        return None  # an unknown method has its own message
    if chosen.adaptive:
        return (f"{method} is adaptive: rtol and atol set its steps, it takes no h; remove "
                f"h or name a fixed-step method (got {h:g})")
    spacing = t_end / (samples - 1)
    ratio = spacing / h

    def whole(x: float) -> bool:
        return round(x) >= 1 and abs(x - round(x)) <= STEP_MATCH * x

    if whole(ratio):
        return None
    if ratio < 1:
        steps = t_end / h
        fix = (f"samples = {round(steps) + 1} (an output after every step)" if whole(steps)
               else f"h = t_end/n for a whole n with samples = n + 1 (n = {math.floor(steps)}: "
                    f"h = {t_end / math.floor(steps):.6g})" if steps >= 1
               else f"h ≤ t_end = {t_end:g}")
        return (f"a step longer than the output spacing t_end/(samples − 1) = {spacing:.6g} "
                f"puts outputs between steps; give {fix} (got {h:g})")
    lo, hi = math.floor(ratio), math.ceil(ratio)
    return (f"a fixed step must divide the output spacing t_end/(samples − 1) = {spacing:.6g} "
            f"into whole steps ({ratio:.6g} here): h = {spacing / hi:.6g} ({hi} steps) or "
            f"{spacing / lo:.6g} ({lo}) would (got {h:g})")


class IntegratingSimulation(Simulation):
    """A simulation that integrates models with the configured ``[run]`` method."""

    @classmethod
    def _check_run_keys(cls, data: dict) -> list[str]:
        run = data.get("run")
        method = run.get("method", "auto") if isinstance(run, dict) else "auto"
        if isinstance(method, str) and method != "auto" and method not in _integrators.METHODS:
            return [f"key 'run.method': unknown integrator (got {method!r}; known: auto, "
                    f"{', '.join(sorted(_integrators.METHODS))})"]
        return []

    def build_models(self) -> None:
        """Construct the models this scene integrates (``validate`` calls it); raise
        ConfigError when the configured method cannot integrate one.  With ``method =
        "auto"`` (the policy picks a method that fits) nothing is built: validation then
        imports no numerics."""
        run = self.config.run
        if run is None:
            return
        problem = step_problem(run.method, run.h, float(run.t_end), run.samples)
        if problem is not None:
            raise ConfigError([f"{self.source.label}: key 'run.h': {problem}"])
        if run.method == "auto":
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


    def integrate(
        self,
        model: OdeModel,
        y0: np.ndarray,
        t_eval: np.ndarray,
        invariants: Callable[[np.ndarray, np.ndarray], dict[str, np.ndarray]] | None = None,
        progress: ProgressFn | None = None,
        n_periods: float | None = None,
        invariant_scales: InvariantScales = None,
        method: str | None = None,
        method_reason: str | None = None,
        fictitious_time: tuple[int, tuple[str, ...], Callable] | None = None,
    ) -> RunRecord:
        """Integrate ``model`` with the configured method and return the archived run.

        ``invariants(t, y)`` gives the conserved quantities, each shape (N,);
        their drift (relative to ``invariant_scales[name]``, default the
        invariant's own size) is part of the run's stability verdict.
        ``invariant_scales`` is a dict, or a function ``(t, y) -> dict`` of the run (a
        scale measured along it: the size of a quantity's terms); give one for every
        quantity that may start at or near 0, whose own size is round-off.  The scales
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
        if run.h is not None and len(t_eval) > 1:  # a kind's own output grid: same rule
            gaps = np.diff(np.asarray(t_eval, dtype=np.float64))
            for gap in {float(gaps.min()), float(gaps.max())}:
                problem = step_problem(method, run.h, gap, 2)
                if problem is not None:
                    raise ConfigError([f"{self.source.label}: key 'run.h': {problem}"])
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
                   | None = None, invariant_scales: InvariantScales = None) -> RunRecord:
        """The archived run of a solver-policy result (:class:`PolicyResult`): attrs, the
        invariants and the stability verdict (see :meth:`integrate`).  ``y`` (N, len(columns))
        replaces the solution's states when the integrated variables are not the archived
        ones (a regularized formulation, converted back by the scene)."""
        sol = res.solution
        y = sol.y if y is None else y
        inv = invariants(sol.t, y) if invariants is not None else {}
        scales = invariant_scales(sol.t, y) if callable(invariant_scales) else invariant_scales
        attrs = _solution_attrs(sol) | {
            "method_reason": res.reason, "solver_status": res.status.value,
            "status": res.status.verdict, "message": res.message}
        record = RunRecord(t=sol.t, y=y, columns=list(columns), invariants=inv, attrs=attrs)
        _stability.assess_run(record, rtol=self.config.run.rtol, scales=scales)
        for name, scale in (scales or {}).items():
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
                                       our_tolerances=self.study_tolerances,
                                       extra_methods=self.study_extra_methods)
        results.study = result.to_records()
        results.study_attrs = {"reference_kind": result.reference_kind,
                               "budget_s": float(self.config.run.study_budget),
                               "over_budget": ",".join(result.over_budget),
                               "reference_size": result.reference_size,
                               "reference_agreement": result.reference_agreement}

    def judge_accuracy(self, results: Results) -> None:
        """The runs (:meth:`Simulation.judge_accuracy`), then every study row: "inaccurate"
        when its ``error_max`` exceeds ``ACCURACY_TOLERANCE`` × :meth:`accuracy_scale` of
        the study's reference (rows a kind appended included); the scale is kept in the
        study table's attrs ``accuracy_scale``, ``accuracy_scale_what``,
        ``accuracy_scale_unit`` and ``accuracy_tolerance``."""
        super().judge_accuracy(results)
        if results.study is None or not len(results.study):
            return
        size = float(results.study_attrs.pop("reference_size", math.nan))
        scale = self.accuracy_scale(size if math.isfinite(size) else 1.0)
        _study.judge_records(results.study, scale.limit, scale.reason)
        results.study_attrs.update({"accuracy_scale": scale.value,
                                    "accuracy_scale_what": scale.what,
                                    "accuracy_scale_unit": scale.unit,
                                    "accuracy_tolerance": ACCURACY_TOLERANCE})

    def divergence(self, results: Results, model: OdeModel, y0, t_eval) -> float:
        """Whether this orbit is chaotic, from two reference runs ``1e-10`` apart
        (:func:`reportgen.core.lyapunov.divergence`): stores ``/analysis``
        ``separation_growth`` and, for a chaotic orbit, ``lyapunov_time`` (declare both).
        Returns the end of the error-against-run-time study's horizon this allows:
        :data:`STUDY_LYAPUNOV_FRACTION` of the Lyapunov time (``t_eval[-1]`` for a regular
        orbit).  Nothing is run for a sweep's member (it has no study)."""
        if self.family_member:
            return float(t_eval[-1])
        est = _lyapunov.divergence(model, np.asarray(y0, dtype=float), np.asarray(t_eval))
        results.analysis["separation_growth"] = est.growth
        if not est.chaotic:
            return float(t_eval[-1])
        results.analysis["lyapunov_time"] = est.lyapunov_time
        return min(float(t_eval[-1]), STUDY_LYAPUNOV_FRACTION * est.lyapunov_time)


#: a chaotic scene's study ends at this fraction of its Lyapunov time: an error made at the
#: start has grown by at most e^0.5 ≈ 1.6 by then, so the error against the reference still
#: measures the method, not the chaos
STUDY_LYAPUNOV_FRACTION = 0.5
