"""Stability: stiffness detection, auto switching, the audit's verdicts and its report."""

from __future__ import annotations

import math

import numpy as np

import stiff_model
from conftest import pendulum_text
from reportgen.archive.audit import read_audit
from reportgen.commands.audit import MethodRun, builtin_cases, run_audit, verdict
from reportgen.core.integrators import METHODS, RunStatus, integrate
from reportgen.core.integrators.policy import STIFF_FALLBACK
from reportgen.core.integrators.stability import stiffness_ratio
from reportgen.kinds import KINDS, load_scene
from reportgen.scene.config import parse_config_text


def _scene(method="auto"):
    text = pendulum_text().replace("study = false", f'study = false\nmethod = "{method}"')
    return load_scene(parse_config_text(text))


def test_stiffness_ratio_separates_stiff_from_accuracy_limited():
    t = np.linspace(0.0, 10.0, 101)
    ratios = {}
    for lam in (1e3, 1e5):
        sol = integrate(stiff_model.model(lam), np.array([1.0]), t, method="dop853", rtol=1e-12,
                        atol=1e-14)
        ratios[lam] = stiffness_ratio(stiff_model.model(lam), sol.t, sol.y, sol.nsteps)
    assert ratios[1e3] < 1.0 < 2.0 < ratios[1e5]


def test_auto_switches_to_an_implicit_method_on_a_stiff_problem():
    scene = _scene("auto")
    t = np.linspace(0.0, 10.0, 101)
    run = scene.integrate(stiff_model.model(1e5), np.array([1.0]), t)
    assert run.attrs["solver_status"] == RunStatus.SWITCHED
    assert run.attrs["method"] == STIFF_FALLBACK and METHODS[run.attrs["method"]].implicit
    assert run.attrs["method_reason"]  # says why, for the report
    assert np.max(np.abs(run.y[:, 0] - np.cos(t))) < 1e-8  # exact solution y = cos t
    assert run.status == "ok"


def test_named_explicit_method_on_a_stiff_problem_is_flagged():
    scene = _scene("dop853")
    run = scene.integrate(stiff_model.model(1e5), np.array([1.0]), np.linspace(0, 10, 101))
    assert run.attrs["solver_status"] == RunStatus.STIFF and run.attrs["method"] == "dop853"
    assert run.status == "unstable" and run.message


def test_non_finite_state_is_failed_not_silent():
    scene = _scene("dop853")
    # y' = y² from y = 1 blows up at t = 1
    run = scene.integrate(stiff_model.model(0.0), np.array([1.0]), np.linspace(0, 1, 11))
    assert run.status == "ok"  # the scalar test model is regular: sanity of the harness
    assert run.attrs["solver_status"] == RunStatus.OK
    from reportgen.core.models import oscillator

    bad = scene.integrate(oscillator.model(1.0, -1e4), np.array([1.0, 0.0]),
                          np.linspace(0, 1e3, 11))  # exponential growth e^{100 t}
    assert bad.attrs["solver_status"] in (RunStatus.NONFINITE, RunStatus.FAILED)
    assert bad.status == "failed" and bad.message


def _run(status="ok", error=1e-12, reason="", used="dop853", solver_status="ok"):
    return MethodRun(method="auto", used=used, status=status, message="boom" if status != "ok"
                     else "", drift=1e-12, error=error, nsteps=10, nreject=0, nfev=100,
                     wall_time_s=0.01, reason=reason, solver_status=solver_status)


def test_verdict_rules():
    assert verdict([_run()])[0] == "ok"
    assert verdict([_run(error=1e-3)])[0] == "inaccurate"
    assert verdict([_run(status="unstable")])[0] == "unstable"
    assert verdict([_run(reason="x. Stiffness detected …", used="radau",
                         solver_status=RunStatus.SWITCHED.value)])[0] == "stiff"
    # the verdict reads the status, not the wording of the reason
    assert verdict([_run(reason="the method switched to something")])[0] == "ok"
    v, reason = verdict([_run(status="failed"), _run(used="gauss6")])
    assert v == "unstable" and "gauss6: ok" in reason


def test_every_builtin_case_is_a_valid_config():
    cases = builtin_cases()
    assert {c.config["kind"] for c in cases} >= {"pendulum", "oscillator"}
    for case in cases:
        from reportgen.commands.audit import _scene_for

        scene = _scene_for(case.config, "case")
        assert scene.kind in KINDS and case.what


def test_audit_report_on_user_scenes(tmp_path, write_config):
    good = write_config("fine", pendulum_text(theta=0.5, t_end=5.0, samples=501))
    near = write_config("edge", pendulum_text(theta=math.pi - 1e-8, t_end=60.0, samples=3001))
    code = run_audit([str(good), str(near)], out_dir=str(tmp_path / "audit"), formats=("html",),
                     print=lambda *a: None)
    assert code == 0  # inaccurate is not unstable
    data = read_audit(tmp_path / "audit" / "audit.h5")
    verdicts = {c["name"]: c["verdict"] for c in data["cases"]}
    assert verdicts == {"fine": "ok", "edge": "inaccurate"}
    assert all(c["reason"] for c in data["cases"])
    assert set(data["table"]["method"]) == {"auto", "dop853", "gauss6"}
    html = (tmp_path / "audit" / "report.html").read_text()
    assert "<table>" in html and "edge" in html and "What went wrong" in html
