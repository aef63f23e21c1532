"""The solver policy (reportgen.core.integrators.policy): choice, stiffness, failures.

Every verdict is checked through :class:`RunStatus`, never through message text.
Method lists come from the capability flags, so a new method is covered by adding it.

Closed forms used:
* Prothero-Robinson y' = -λ (y - cos t) - sin t, y(0) = 1: y = cos t for any λ
  (Prothero & Robinson, Math. Comp. 28 (1974) 145-162); stiff for λ = 1e5.
* Pendulum: reportgen.core.models.pendulum.exact_period (DLMF 22.19.2 via K(m)).
"""

import dataclasses
import math

import numba
import numpy as np
import pytest

import stiff_model
from reportgen.core.integrators import (
    METHODS,
    MethodMismatch,
    RunStatus,
    SolverSpec,
    Status,
    choose_auto,
    solve,
)
from reportgen.core.integrators.base import STATUS_OF_CODE
from reportgen.core.integrators.policy import LONG_RUN_PERIODS, STIFF_FALLBACK
from reportgen.core.integrators.status import POLICY_STATUSES
from reportgen.core.model import OdeModel
from reportgen.core.models import pendulum

G, L, THETA0 = 9.81, 1.0, 1.0
T_PEND = pendulum.exact_period(THETA0, 0.0, G, L)
T_NAN = 0.5  # the test model's right-hand side is NaN from here on

COMPILED = [n for n, m in METHODS.items() if m.compiled]
EXPLICIT_ADAPTIVE = [n for n, m in METHODS.items() if m.compiled and m.adaptive and not m.implicit]
IMPLICIT = [n for n, m in METHODS.items() if m.implicit and not m.needs_kepler]
# heyoka runs only the models it has a translation of (tests/test_heyoka_peer.py)
PEERS = [n for n, m in METHODS.items() if m.peer and n != "heyoka"]


@numba.njit(cache=True)
def nan_rhs(t, y, params, out):
    out[0] = -y[0] if t < 0.5 else math.nan


@numba.njit(cache=True)
def damped_rhs(t, y, params, out):
    out[0] = y[1]
    out[1] = -y[0] - params[0] * y[1]


NAN_MODEL = OdeModel(name="nan_after_half", columns=("y",), rhs=nan_rhs, params=np.zeros(0))
DAMPED = OdeModel(name="damped_oscillator", columns=("x", "v"), rhs=damped_rhs,
                  params=np.array([0.1]))


def spec(method="auto", rtol=1e-10, atol=1e-12, **kw):
    return SolverSpec(method=method, rtol=rtol, atol=atol, **kw)


# ------------------------------------------------------------------ the spec itself
def test_spec_defaults_and_is_frozen():
    s = SolverSpec(rtol=1e-8, atol=1e-10)
    assert s.method == "auto" and s.auto and s.h is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.method = "dop853"


def test_unknown_method_names_the_value_and_the_known_names():
    with pytest.raises(ValueError) as info:
        spec("rk99")
    text = str(info.value)
    assert "'rk99'" in text and "auto" in text
    assert all(name in text for name in METHODS)


@pytest.mark.parametrize("field, value", [("rtol", 0.0), ("rtol", 1.5), ("atol", -1e-9),
                                          ("atol", math.inf), ("h", 0.0), ("h", math.nan),
                                          ("max_steps", 0)])
def test_spec_rejects_bad_numbers(field, value):
    with pytest.raises(ValueError, match=field):
        spec(**{field: value})


def test_every_method_name_is_a_valid_spec():
    for name in METHODS:
        assert spec(name).method == name


def test_run_status_is_the_one_vocabulary_and_the_policy_archives_six_of_it():
    assert RunStatus is Status
    assert {s.value for s in POLICY_STATUSES} == {"ok", "stiff", "max_steps", "nonfinite",
                                                  "failed", "switched"}
    # every integrator outcome maps into the archived six; the others archive as FAILED
    assert {STATUS_OF_CODE[s] for s in Status} <= POLICY_STATUSES
    assert STATUS_OF_CODE[Status.STEP_UNDERFLOW] is RunStatus.FAILED
    verdicts = {s: s.verdict for s in POLICY_STATUSES}
    assert {s for s, v in verdicts.items() if v == "ok"} == {RunStatus.OK, RunStatus.SWITCHED}
    assert {s for s, v in verdicts.items() if v == "unstable"} == {RunStatus.STIFF}
    assert {s for s, v in verdicts.items() if v == "failed"} == {
        RunStatus.MAX_STEPS, RunStatus.NONFINITE, RunStatus.FAILED}
    # every failure of the whole vocabulary is judged failed
    assert {s for s in Status if s.verdict == "ok"} == {Status.OK, Status.SWITCHED}
    # the archived spellings of clean runs are unchanged
    assert RunStatus.OK == "ok" and RunStatus.SWITCHED == "switched"


# ------------------------------------------------------------------ automatic choice
def test_auto_picks_an_adaptive_explicit_method_for_a_short_run():
    t = np.linspace(0.0, 2 * T_PEND, 101)
    r = solve(pendulum.model(G, L), np.array([THETA0, 0.0]), t, spec(), n_periods=2)
    assert r.status is RunStatus.OK and r.solution.ok and r.method in EXPLICIT_ADAPTIVE
    assert r.reason.endswith(".") and r.message == ""
    exact = np.column_stack(pendulum.exact_solution(t, THETA0, 0.0, G, L))
    assert np.max(np.abs(r.solution.y - exact)) < 1e-8


def test_auto_picks_a_symplectic_method_for_a_long_separable_run():
    t = np.linspace(0.0, 2 * T_PEND, 101)  # n_periods is the hint the choice reads
    r = solve(pendulum.model(G, L), np.array([THETA0, 0.0]), t, spec(),
              n_periods=2 * LONG_RUN_PERIODS)
    assert METHODS[r.method].symplectic and r.status is RunStatus.OK
    # the same model without a separable split cannot take a symplectic splitting method
    assert not METHODS[choose_auto(DAMPED, 1e-10, n_periods=2 * LONG_RUN_PERIODS)[0]].symplectic


def test_auto_picks_an_implicit_method_for_a_model_marked_stiff():
    marked = dataclasses.replace(stiff_model.model(1e5), stiff_hint=True)
    t = np.linspace(0.0, 10.0, 101)
    r = solve(marked, np.array([1.0]), t, spec(rtol=1e-12, atol=1e-14))
    # chosen before running; still reported as the policy's answer to stiffness
    assert METHODS[r.method].implicit and r.status is RunStatus.SWITCHED
    assert r.status.verdict == "ok"
    assert np.max(np.abs(r.solution.y[:, 0] - np.cos(t))) < 1e-8


def test_oscillatory_stiffness_takes_gauss6_with_a_step_resolving_the_fastest_mode():
    """Two uncoupled oscillators, ω = 1 and 1000 (ratio 10³), both excited: auto picks the
    symplectic implicit Gauss-Legendre 6 with h = 0.5/ω_max, which follows the fast mode
    (exact: q_k = cos ω_k t)."""
    from reportgen.core.integrators.policy import OSCILLATORY_STEP
    from reportgen.core.models import linear_chain

    omega = np.array([1.0, 1000.0])
    model = linear_chain.model(np.eye(2), np.diag(omega**2), ["slow", "fast"],
                               stiff_hint=True, omega_max=omega.max())
    t = np.linspace(0.0, 2.0, 201)
    r = solve(model, np.array([1.0, 1.0, 0.0, 0.0]), t, spec(rtol=1e-12, atol=1e-14))
    assert r.method == "gauss6" and r.status is RunStatus.SWITCHED
    assert r.solution.h == pytest.approx(OSCILLATORY_STEP / 1000.0)
    error = np.abs(r.solution.y[:, :2] - np.cos(np.outer(t, omega)))
    assert np.max(error[:, 0]) < 1e-12  # the slow mode is resolved exactly
    # the fast one is followed, not damped: ~320 periods at h·ω = 0.5 cost a phase error of
    # a few 1e-4 (order 6: 4000 steps × (hω)^7/…), and the amplitude is kept
    assert np.max(error[:, 1]) < 1e-3
    y = r.solution.y
    fast_energy = 0.5 * y[:, 3] ** 2 + 0.5 * omega[1] ** 2 * y[:, 1] ** 2
    assert np.max(np.abs(fast_energy / fast_energy[0] - 1.0)) < 1e-9  # no damping


# ------------------------------------------------------------------ stiffness
def test_auto_switches_to_the_implicit_fallback_on_a_stiff_model():
    t = np.linspace(0.0, 10.0, 101)
    r = solve(stiff_model.model(1e5), np.array([1.0]), t, spec(rtol=1e-12, atol=1e-14))
    assert r.status is RunStatus.SWITCHED and r.status.verdict == "ok"
    assert r.method == STIFF_FALLBACK and METHODS[r.method].implicit and r.stiffness
    assert r.solution.method == STIFF_FALLBACK
    assert np.max(np.abs(r.solution.y[:, 0] - np.cos(t))) < 1e-8  # exact y = cos t


def test_auto_keeps_its_choice_on_the_same_model_when_not_stiff():
    t = np.linspace(0.0, 10.0, 101)
    r = solve(stiff_model.model(1e3), np.array([1.0]), t, spec(rtol=1e-12, atol=1e-14))
    assert r.status is RunStatus.OK and r.method in EXPLICIT_ADAPTIVE and not r.stiffness


@pytest.mark.parametrize("method", EXPLICIT_ADAPTIVE)
def test_named_explicit_method_on_a_stiff_model_is_kept_and_flagged(method):
    # at rtol 1e-8 accuracy asks for steps far longer than the stability bound ~3/λ allows
    # (at 1e-12 a low-order method's step is set by accuracy: not stiff for it)
    t = np.linspace(0.0, 10.0, 101)
    r = solve(stiff_model.model(1e5), np.array([1.0]), t, spec(method, rtol=1e-8, atol=1e-10))
    assert r.status is RunStatus.STIFF and r.status.verdict == "unstable"
    assert r.method == method and r.solution.ok and r.message


@pytest.mark.parametrize("method", IMPLICIT)
def test_named_implicit_method_on_a_stiff_model_is_ok(method):
    t = np.linspace(0.0, 10.0, 101)
    r = solve(stiff_model.model(1e5), np.array([1.0]), t,
              spec(method, rtol=1e-10, atol=1e-12, h=0.01))
    assert r.status is RunStatus.OK and r.method == method
    # loose: Prothero-Robinson is the textbook case of order reduction (stage order)
    assert np.max(np.abs(r.solution.y[:, 0] - np.cos(t))) < 1e-5


# ------------------------------------------------------------------ failures
@pytest.mark.parametrize("method", COMPILED)
def test_step_budget_used_up_is_max_steps(method):
    t = np.linspace(0.0, 10 * T_PEND, 101)
    r = solve(pendulum.model(G, L), np.array([THETA0, 0.0]), t,
              spec(method, h=T_PEND / 1000, max_steps=50))
    assert r.status is RunStatus.MAX_STEPS and r.status.verdict == "failed"
    assert r.method == method and not r.solution.ok
    assert np.isfinite(r.solution.y[0]).all() and np.isnan(r.solution.y[-1]).all()


@pytest.mark.parametrize("method", ["auto"] + [n for n in COMPILED
                                               if not METHODS[n].needs_separable])
def test_nan_right_hand_side_is_nonfinite(method):
    t = np.linspace(0.0, 1.0, 11)
    r = solve(NAN_MODEL, np.array([1.0]), t, spec(method, rtol=1e-8, atol=1e-10, h=1e-3))
    # a NaN is not stiffness: the automatic choice does not switch
    assert r.status is RunStatus.NONFINITE and r.status.verdict == "failed"
    assert method == "auto" or r.method == method
    before = t < T_NAN - 0.05
    assert np.allclose(r.solution.y[before, 0], np.exp(-t[before]), rtol=1e-5)
    assert np.all(np.isnan(r.solution.y[t > T_NAN + 0.05]))


@pytest.mark.parametrize("method", [n for n in PEERS if n != "scipy_lsoda"])
def test_peer_failures_are_failures(method):
    # scipy reports why only in prose; the policy still gives a failure status, never ok
    t = np.linspace(0.0, 1.0, 11)
    r = solve(NAN_MODEL, np.array([1.0]), t, spec(method, rtol=1e-8, atol=1e-10))
    assert r.status in (RunStatus.FAILED, RunStatus.NONFINITE)
    assert np.all(np.isnan(r.solution.y[t > T_NAN + 0.05]))


def test_method_that_needs_structure_the_model_lacks_raises_before_work():
    for name in [n for n, m in METHODS.items() if m.needs_separable]:
        with pytest.raises(MethodMismatch):
            solve(DAMPED, np.array([1.0, 0.0]), np.linspace(0.0, 1.0, 3), spec(name))
