"""``reportgen audit``: stability audit on stiff and extreme cases.

Every kind ships its extreme cases (:meth:`Scene.audit_cases`); a config given
on the command line is audited too.  Each case is run with the automatic method
and with alternatives; for each run the audit records the invariant drift, the
agreement with the exact or independent reference (the scene's headline
checks), steps taken and rejected and wall time, and gives the case a verdict
with its reason:

ok          the automatic method's run is stable and agrees with the reference
inaccurate  stable, but the reference disagrees by more than ``ACCURACY``
unstable    the run was flagged (non-finite state, invariant drift, failure)
stiff       the explicit method showed stiffness and the run switched method
"""

from __future__ import annotations

import builtins
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..archive.audit import write_audit
from ..kinds import KINDS, load_scene
from ..lazy import lazy_module
from ..pipeline.stages import collect_configs, validate_all
from ..rendering.report import build_audit_report
from ..scene.config import ConfigError, SourceConfig, parse_config_text, to_toml
from ..scene.results import AuditCase

_policy = lazy_module("reportgen.core.integrators.policy")

#: relative disagreement with the reference above which a stable run is "inaccurate"
ACCURACY = 1e-6
VERDICTS = ("ok", "inaccurate", "stiff", "unstable")


@dataclass
class MethodRun:
    method: str  # as asked ("auto" or a name)
    used: str  # what ran
    status: str
    message: str
    drift: float
    error: float
    nsteps: int
    nreject: int
    nfev: int
    wall_time_s: float
    reason: str = ""
    #: the solver policy's RunStatus value (run attr ``solver_status``; "" if nothing ran)
    solver_status: str = ""
    t: np.ndarray | None = None
    drift_series: dict[str, np.ndarray] = field(default_factory=dict)


@dataclass
class CaseResult:
    case: AuditCase
    kind: str
    runs: list[MethodRun]
    verdict: str
    reason: str


def builtin_cases() -> list[AuditCase]:
    cases = []
    for cls in KINDS.values():
        cases.extend(cls.audit_cases())
    return cases


def _scene_for(config: dict, label: str):
    text = to_toml(config)
    source = parse_config_text(text)
    return load_scene(SourceConfig(path=Path(f"{label}.toml"), text=text, data=source.data))


def _with_method(config: dict, method: str) -> dict:
    run = dict(config.get("run", {}))
    run.update({"method": method, "study": False})
    return {**config, "run": run}


def run_method(case: AuditCase, method: str) -> MethodRun:
    """Run ``case`` with ``method``; never raises for numerical trouble."""
    scene = _scene_for(_with_method(case.config, method), case.name.replace(" ", "_"))
    start = time.perf_counter()
    try:
        results = scene.simulate()
    except ConfigError as exc:  # e.g. the method does not fit this model
        return MethodRun(method, method, "failed", str(exc.problems[0]), math.nan, math.nan,
                         0, 0, 0, time.perf_counter() - start)
    except (FloatingPointError, ValueError, ZeroDivisionError, OverflowError) as exc:
        return MethodRun(method, method, "failed", f"{type(exc).__name__}: {exc}", math.nan,
                         math.nan, 0, 0, 0, time.perf_counter() - start)
    main = results.runs.get("main")
    if main is None:
        return MethodRun(method, "—", results.status, "integrates nothing", 0.0, _error(results),
                         0, 0, 0, time.perf_counter() - start)
    a = main.attrs
    drift = max((float(a.get(f"drift_{q}", 0.0)) for q in main.invariants), default=0.0)
    series = {}
    for q, values in main.invariants.items():
        scale = max(abs(values[0]), float(np.max(np.abs(values))), 1e-300)
        series[q] = (values - values[0]) / scale
    return MethodRun(
        method=method, used=str(a.get("method")), status=main.status, message=main.message,
        drift=drift, error=_error(results), nsteps=int(a.get("nsteps", 0)),
        nreject=int(a.get("nreject", 0)), nfev=int(a.get("nfev", 0)),
        wall_time_s=float(a.get("wall_time_s", math.nan)), reason=str(a.get("method_reason", "")),
        solver_status=str(a.get("solver_status", "")), t=main.t, drift_series=series)


def _error(results) -> float:
    """Worst relative disagreement among the scene's headline checks (NaN if none)."""
    errors = [c.rel_error for c in results.checks if math.isfinite(c.rel_error)]
    return max(errors) if errors else math.nan


def verdict(runs: list[MethodRun]) -> tuple[str, str]:
    """The case's verdict from its automatic run, with the alternatives as evidence."""
    auto = runs[0]
    others = ", ".join(f"{r.used}: {r.status}" for r in runs[1:]) or "none"
    if auto.status == "inaccurate":  # ran cleanly; its error is large against the scale
        return "inaccurate", (f"{auto.used} is stable (drift {auto.drift:.1e}) but "
                              f"{auto.message or 'errs by more than the accuracy bound'}")
    if auto.status != "ok":
        return "unstable", f"{auto.used}: {auto.message or auto.status} (alternatives: {others})"
    if auto.solver_status == _policy.RunStatus.SWITCHED:
        return "stiff", auto.reason
    if math.isfinite(auto.error) and auto.error > ACCURACY:
        return "inaccurate", (f"{auto.used} is stable (drift {auto.drift:.1e}) but disagrees "
                              f"with the reference by {auto.error:.1e} (> {ACCURACY:.0e})")
    return "ok", (f"{auto.used}: drift {auto.drift:.1e}, reference agreement "
                  f"{auto.error:.1e}" if math.isfinite(auto.error) else
                  f"{auto.used}: drift {auto.drift:.1e}")


def audit_case(case: AuditCase) -> CaseResult:
    runs = [run_method(case, "auto")]
    for method in case.methods:
        runs.append(run_method(case, method))
    v, reason = verdict(runs)
    return CaseResult(case=case, kind=case.config["kind"], runs=runs, verdict=v, reason=reason)


def cases_from_paths(paths: list[str]) -> list[AuditCase]:
    cases = []
    for scene in validate_all(collect_configs(paths)):
        if scene.config.run is None:
            continue
        cases.append(AuditCase(name=scene.source.name, config=dict(scene.source.data),
                               what="user scene", methods=("dop853", "gauss6")))
    return cases


def run_audit(paths: list[str], out_dir: str = "output/audit", formats=("html", "pdf"),
              print=builtins.print) -> int:
    """Audit the built-in cases (no PATH) or the given configs; write audit.h5 and reports."""
    cases = cases_from_paths(paths) if paths else builtin_cases()
    results = []
    for i, case in enumerate(cases, 1):
        result = audit_case(case)
        results.append(result)
        auto = result.runs[0]
        print(f"[{i}/{len(cases)}] {case.name:<44} {result.verdict:<10} {auto.used:<10} "
              f"{auto.wall_time_s:7.3f} s  {result.reason}")
    out = Path(out_dir)
    write_audit(out / "audit.h5", results)
    build_audit_report(out / "audit.h5", formats=formats)
    counts = {v: sum(r.verdict == v for r in results) for v in VERDICTS}
    print(", ".join(f"{n} {v}" for v, n in counts.items()) + f"; report: {out / 'report.html'}")
    # the built-in cases are meant to find trouble; the user's own scenes gate on it
    return 1 if paths and counts["unstable"] else 0
