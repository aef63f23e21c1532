"""Every run ends, with a named status (issue 35, items 1 and 10).

A NaN step size used to spin the adaptive loops forever (``h < min_step`` is False for
NaN, and ``max_steps`` counted only accepted steps); a tiny fixed step overflowed the
step count into one step per sample, reported ok with a negative ``h``.  The runs that
used to hang run in a child process that kills itself (SIGALRM) if one takes more than
``BUDGET_S`` after the drivers are loaded, and the parent has its own timeout, so a
regression fails here instead of hanging the suite.

Closed forms: the Kepler right-hand side -GM r_vec / r^3 is 0/0 = NaN at the origin
(lecture notes §3); y' = c has y = y0 + c t, which overflows once c t > 1.8e308.
"""

import json
import math
import os
import subprocess
import sys

import numba
import numpy as np
import pytest

from reportgen.core import ensemble
from reportgen.core.integrators import METHODS, RunStatus, SolveCode, Status, compiled, integrate
from reportgen.core.integrators.base import STATUS_OF_CODE
from reportgen.core.integrators.fictitious_time import integrate_fictitious_time
from reportgen.core.integrators.kernels import kernels_for
from reportgen.core.integrators.status import POLICY_STATUSES
from reportgen.core.models import kepler, pendulum

#: seconds one run may take once the drivers are loaded (they end in milliseconds)
BUDGET_S = 10
#: the child's whole life, compiling on an empty numba cache included
CHILD_TIMEOUT_S = 600

_CHILD = r"""
import json, signal, sys, time
import numpy as np
from reportgen.core.ensemble import run_ensemble
from reportgen.core.integrators import SolverSpec, integrate, solve
from reportgen.core.integrators.fictitious_time import integrate_fictitious_time
from reportgen.core.models import kepler

BUDGET = int(sys.argv[1])
model = kepler.model(1.0, 1.0)
t = np.linspace(0.0, 10.0, 11)
ORIGIN = np.array([0.0, 0.0, 0.0, 1.0])
AT_REST = np.array([0.0, 0.0, 0.0, 0.0])
ORBIT = np.array([1.0, 0.0, 0.0, 1.0])


def one(method, y0, **kw):
    s = integrate(model, y0, t, method=method, **kw)
    return s.code, s.nsteps, s.nreject


def ens(y0, **kw):
    e = run_ensemble(model, y0[None], t_end=10.0, **kw)
    return int(e.status[0]), e.counters[0, 1], e.counters[0, 2]


def own_time(y0, **kw):
    s = integrate_fictitious_time(model, y0, t, None, **kw)
    return s.code, s.nsteps, s.nreject


def policy(y0):
    r = solve(model, y0, t, SolverSpec(rtol=1e-10, atol=1e-12))
    return r.status, r.solution.nsteps, r.solution.nreject


CASES = {
    "dop853_origin": lambda: one("dop853", ORIGIN),
    "dop853_at_rest": lambda: one("dop853", AT_REST),
    "dop853_tiny_tolerances": lambda: one("dop853", ORBIT, rtol=1e-300, atol=1e-300),
    "rk45_origin": lambda: one("rk45", ORIGIN),
    "rk45_tiny_tolerances": lambda: one("rk45", ORBIT, rtol=1e-300, atol=1e-300),
    "ensemble_origin": lambda: ens(ORIGIN),
    "ensemble_tiny_tolerances": lambda: ens(ORBIT, rtol=1e-300, atol=1e-300),
    "own_time_origin": lambda: own_time(ORIGIN),
    "own_time_tiny_tolerances": lambda: own_time(ORBIT, rtol=1e-300, atol=1e-300),
    "policy_auto_origin": lambda: policy(ORIGIN),
}
# load (or compile) every driver on a good orbit first: the budget is for the runs
one("dop853", ORBIT), one("rk45", ORBIT), ens(ORBIT), own_time(ORBIT), policy(ORBIT)
for case, run in CASES.items():
    print(json.dumps({"start": case}), flush=True)
    signal.alarm(BUDGET)  # default action: the process dies (compiled loops ignore Python)
    start = time.perf_counter()
    code, nsteps, nreject = run()
    elapsed = time.perf_counter() - start
    signal.alarm(0)
    print(json.dumps({"case": case, "code": str(code) if not isinstance(code, int) else code,
                      "nsteps": int(nsteps), "nreject": int(nreject), "s": elapsed}),
          flush=True)
"""


@pytest.fixture(scope="module")
def ended():
    """case -> the child's record of it (code, nsteps, nreject, seconds)."""
    proc = subprocess.run([sys.executable, "-c", _CHILD, str(BUDGET_S)], capture_output=True,
                          text=True, timeout=CHILD_TIMEOUT_S, env=dict(os.environ))
    lines = [json.loads(x) for x in proc.stdout.splitlines() if x.startswith("{")]
    started = [x["start"] for x in lines if "start" in x]
    done = {x["case"]: x for x in lines if "case" in x}
    hung = [c for c in started if c not in done]
    assert not hung and proc.returncode == 0, (
        f"run(s) {hung} did not end within {BUDGET_S} s (exit {proc.returncode}): "
        f"{proc.stderr[-2000:]}")
    return done


@pytest.mark.parametrize("case", ["dop853_origin", "dop853_at_rest", "rk45_origin",
                                  "own_time_origin"])
def test_kepler_at_the_origin_ends_nonfinite(ended, case):
    run = ended[case]
    assert run["code"] == Status.NONFINITE and run["s"] < BUDGET_S


def test_kepler_ensemble_member_at_the_origin_ends_nonfinite(ended):
    run = ended["ensemble_origin"]
    assert Status.from_code(run["code"]) is Status.NONFINITE and run["s"] < BUDGET_S


def test_the_policy_reports_a_kepler_start_at_the_origin(ended):
    # auto asks for the orbit's eccentricity first: at r = 0 there is none (K / r), and
    # the choice must not raise; the run then says what happened
    run = ended["policy_auto_origin"]
    assert run["code"] == RunStatus.NONFINITE and RunStatus(run["code"]).verdict == "failed"


@pytest.mark.parametrize("case", ["dop853_tiny_tolerances", "rk45_tiny_tolerances",
                                  "own_time_tiny_tolerances", "ensemble_tiny_tolerances"])
def test_tolerances_of_1e_300_end_with_a_named_status(ended, case):
    run = ended[case]
    code = Status.from_code(run["code"]) if isinstance(run["code"], int) else Status(run["code"])
    assert code in (Status.NONFINITE, Status.STEP_UNDERFLOW) and run["s"] < BUDGET_S


@pytest.mark.parametrize("method", ["rk4", "verlet", "yoshida6", "gauss4"])
def test_a_tiny_fixed_step_is_refused_not_run_with_a_negative_h(method):
    t = np.linspace(0.0, 1.0, 11)
    sol = integrate(pendulum.model(9.81, 1.0), np.array([1.0, 0.0]), t, method=method,
                    h=1e-300)
    assert sol.code is Status.MAX_STEPS and not sol.ok and sol.nsteps == 0
    assert sol.h > 0.0 and "needs 1e+299 steps" in sol.message, sol.message
    assert np.isnan(sol.y[1:]).all() and np.array_equal(sol.y[0], [1.0, 0.0])


@pytest.mark.parametrize("h", [0.0, -0.1, math.nan, math.inf])
def test_a_step_that_is_not_positive_and_finite_is_a_value_error(h):
    model = pendulum.model(9.81, 1.0)
    with pytest.raises(ValueError, match="h: expected a positive"):
        integrate(model, np.array([1.0, 0.0]), np.linspace(0.0, 1.0, 3), method="rk4", h=h)
    kern, Y = kernels_for(model), np.zeros((3, 2))
    with pytest.raises(ValueError, match="h: expected a positive"):
        METHODS["rk4"].start(kern, model, np.array([1.0, 0.0]), np.linspace(0.0, 1.0, 3), Y,
                             1e-6, 1e-6, h)


@pytest.mark.parametrize("method", ["rk4", "verlet", "gauss4"])
@pytest.mark.parametrize("h", [1e-300, -0.1, 0.0, math.nan, math.inf])
def test_fixed_step_kernels_refuse_a_step_count_they_cannot_take(method, h):
    # below the Python checks: a kernel given such a step returns BAD_STEP at the first
    # interval instead of overflowing its int count into one step
    model = pendulum.model(9.81, 1.0)
    t, y0 = np.linspace(0.0, 1.0, 3), np.array([1.0, 0.0])
    integrate(model, y0, t, method=method, h=0.1)  # compile / load
    Y = np.full((3, 2), np.nan)
    run = METHODS[method].start(kernels_for(model), model, y0, t, Y, 1e-6, 1e-6, 0.1)
    run.h = h
    assert Status.from_code(run.advance(1, 3)) is Status.BAD_STEP
    assert run.t_fail == 0.0 and run.counters[1] == 0 and np.isnan(Y[1:]).all()


def test_steps_in_refuses_counts_beyond_its_bound():
    assert compiled.steps_in(1.0, 0.1) == 10 and compiled.steps_in(1.0, 3.0) == 1
    assert 0 < compiled.steps_in(1.0, 1e-15) <= 10 ** 15 < compiled.MAX_FIXED_STEPS
    for h in (1e-16, 1e-300, 0.0, -1.0, math.nan, math.inf):
        assert compiled.steps_in(1.0, h) == -1, h


@pytest.mark.parametrize("method", ["dop853", "rk45"])  # a generated driver, erk_adaptive
@pytest.mark.parametrize("h, status", [(math.nan, Status.NONFINITE), (math.inf, Status.NONFINITE),
                                       (-1.0, Status.STEP_UNDERFLOW),
                                       (1e-30, Status.STEP_UNDERFLOW)])  # t + h == t
def test_a_step_that_cannot_advance_t_stops_the_adaptive_drivers(method, h, status):
    model = pendulum.model(9.81, 1.0)
    t, y0 = np.array([1e6, 1e6 + 1.0]), np.array([1.0, 0.0])
    integrate(model, y0, t, method=method)  # compile / load
    Y = np.full((2, 2), np.nan)
    run = METHODS[method].start(kernels_for(model), model, y0, t, Y, 1e-8, 1e-10, None, 100)
    run.state[1] = h  # as if the controller had proposed it
    assert Status.from_code(run.advance(0, 2)) is status
    assert run.counters[1] + run.counters[2] == 0 and np.array_equal(Y[0], y0)


_ORBIT = np.array([1.0, 0.0, 0.0, 0.3])  # e = 0.91: the controller rejects many steps
_T = np.linspace(0.0, 20.0, 41)


def _attempts(sol) -> int:
    return sol.nsteps + sol.nreject


@pytest.mark.parametrize("method", ["dop853", "rk45"])
def test_the_step_budget_counts_rejected_steps(method):
    model = kepler.model(1.0, 1.0)
    free = integrate(model, _ORBIT, _T, method=method, rtol=1e-6, atol=1e-9)
    assert free.ok and free.nreject > 10
    need = _attempts(free)
    exact = integrate(model, _ORBIT, _T, method=method, rtol=1e-6, atol=1e-9, max_steps=need)
    assert exact.ok and _attempts(exact) == need
    # enough accepted steps, not enough attempts: the budget is of attempts
    short = integrate(model, _ORBIT, _T, method=method, rtol=1e-6, atol=1e-9,
                      max_steps=free.nsteps + 1)
    assert short.code is Status.MAX_STEPS and _attempts(short) == free.nsteps + 1
    assert "attempted steps" in short.message


def test_the_ensemble_and_own_time_budgets_count_rejected_steps():
    model = kepler.model(1.0, 1.0)
    free = integrate(model, _ORBIT, _T, rtol=1e-6, atol=1e-9)
    budget = free.nsteps + 1
    ens = ensemble.run_ensemble(model, _ORBIT[None], t_end=_T[-1], rtol=1e-6, atol=1e-9,
                                max_steps=budget)
    assert ens.status[0] == ensemble.MAXSTEPS and ens.counters[0, 1:].sum() == budget
    own = integrate_fictitious_time(model, _ORBIT, _T, None, rtol=1e-6, atol=1e-9,
                                    max_steps=budget)
    assert own.code is Status.MAX_STEPS and _attempts(own) == budget
    whole = ensemble.run_ensemble(model, _ORBIT[None], t_end=_T[-1], rtol=1e-6, atol=1e-9,
                                  max_steps=_attempts(free))
    assert whole.status[0] == ensemble.OK


@numba.njit(cache=True)
def _huge_slope(t, y, params, out):
    out[0] = 1e140  # y = 1e140 t: overflows at t = 1.8e168 with f finite throughout


def test_a_state_that_overflows_with_a_finite_slope_is_nonfinite():
    # the attempt past 1.8e308 has y_new = inf but a finite f and error norm (its scale
    # atol + rtol |y_new| is inf too): it must be rejected, not accepted as ok
    from reportgen.core.model import OdeModel

    model = OdeModel(name="huge_slope", columns=("y",), rhs=_huge_slope, params=np.zeros(0))
    t = np.linspace(0.0, 3e168, 7)
    for method in ("dop853", "rk45"):
        sol = integrate(model, np.array([0.0]), t, method=method, rtol=1e-6, atol=1e-6)
        assert sol.code is Status.NONFINITE, (method, sol.message)
        assert np.isfinite(sol.y[t < 1.7e168]).all() and np.isnan(sol.y[t > 1.8e168]).all()
    ens = ensemble.run_ensemble(model, np.zeros((1, 1)), t_end=3e168, rtol=1e-6, atol=1e-6)
    assert ens.status[0] == ensemble.NONFINITE and 1.7e168 < ens.t_final[0] < 1.8e168


# -- one vocabulary (issue 30) ---------------------------------------------------------

def test_driver_codes_are_the_enums():
    assert (compiled.OK, compiled.NONFINITE, compiled.UNDERFLOW, compiled.MAXSTEPS,
            compiled.NEWTON, compiled.BAD_STEP) == tuple(s.code for s in (
                Status.OK, Status.NONFINITE, Status.STEP_UNDERFLOW, Status.MAX_STEPS,
                Status.NEWTON, Status.BAD_STEP))
    assert all(type(c) is int for c in (compiled.OK, compiled.UNDERFLOW, ensemble.UNDERFLOW))
    assert {Status.from_code(s.code) for s in Status} == set(Status)
    assert SolveCode is Status


def test_ensemble_names_are_the_enums_spellings():
    assert ensemble.STATUS_NAMES == {s.code: s.value for s in Status}
    assert ensemble.STATUS_NAMES[ensemble.UNDERFLOW] == "step_underflow" == SolveCode.STEP_UNDERFLOW
    assert ensemble.STATUS_NAMES.get(int(np.int64(Status.NOT_LIBRATING.code))) == "not_librating"


def test_the_policy_archives_a_subset_of_the_vocabulary():
    assert RunStatus is Status
    for s in Status:
        assert STATUS_OF_CODE[s] is s.policy
        assert s.policy is (s if s in POLICY_STATUSES else Status.FAILED)
    assert STATUS_OF_CODE[Status.STEP_UNDERFLOW] is RunStatus.FAILED
    assert RunStatus.MAX_STEPS == Status.MAX_STEPS == "max_steps"
