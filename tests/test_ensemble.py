"""Compiled ensembles (``reportgen.core.ensemble``, and the pendulum kind's periods built on
it, ``reportgen.kinds.pendulum.ensemble``) against closed forms and our single run.

Closed forms used:
* Pendulum period from rest at theta0: T = 4 K(k) sqrt(l / g), k = sin(theta0 / 2)
  (DLMF 19.2.8 and 22.19(i); scipy.special.ellipk takes m = k^2).
* Pendulum energy per unit m l^2: theta_dot^2 / 2 - (g / l) cos(theta), conserved
  (Landau & Lifshitz, Mechanics, sec. 6).
* Harmonic oscillator q' = p, p' = -q from (1, 0): q = cos t, zero at t = pi/2 + n pi,
  going down for even n (Landau & Lifshitz, Mechanics, sec. 21).
"""

import math

import numba
import numpy as np
import pytest
from scipy.special import ellipk

from reportgen.core import ensemble
from reportgen.core.ensemble import (
    MAXSTEPS,
    NONFINITE,
    OK,
    run_ensemble,
)
from reportgen.core.integrators import integrate
from reportgen.core.models import oscillator, pendulum
from reportgen.kinds.pendulum.ensemble import NO_PERIOD, NOT_LIBRATING, pendulum_periods

G, L = 9.81, 1.0
RESULT_FIELDS = ("y_end", "t_final", "status", "counters", "events", "n_events", "y_store")


def exact_period(theta0, g=G, l=L):
    return 4.0 * ellipk(np.sin(0.5 * theta0) ** 2) * np.sqrt(l / g)


def sweep(M=60, **kw):
    """A pendulum ensemble: amplitudes up to 3 rad, several g / l, events and stored members."""
    theta0 = np.linspace(0.05, 3.0, M)
    Y0 = np.column_stack([theta0, np.linspace(-0.5, 0.5, M)])
    P = np.linspace(4.0, 12.0, M)[:, None]
    t_eval = np.linspace(0.0, 4.0, 41)
    args = dict(t_end=4.0, rtol=1e-10, atol=1e-12, event="theta", direction=0,
                max_events=5, t_eval=t_eval, store=[0, M // 2, M - 1])
    args.update(kw)
    return run_ensemble(pendulum.model(G, L), Y0, P, **args)


def assert_same(a, b, members=slice(None)):
    for name in RESULT_FIELDS:
        x, y = getattr(a, name), getattr(b, name)
        if name != "y_store":
            x, y = x[members], y[members]
        assert np.array_equal(x, y, equal_nan=True), name


def test_periods_against_elliptic_integral():
    """2000 amplitudes in [0.01, 3.1]: every period within 1e-9 of 4 K(k) sqrt(l/g)
    (measured: max relative error 1.5e-10, at theta0 = 3.1, with the defaults)."""
    theta0 = np.linspace(0.01, 3.1, 2000)
    periods, status = pendulum_periods(theta0, G, L)
    assert np.all(status == OK)
    err = np.abs(periods / exact_period(theta0) - 1.0)
    assert err.max() < 1e-9, (err.max(), theta0[np.argmax(err)])


def test_periods_statuses_and_broadcasting():
    """Rotation (theta0 > pi), the separatrix (theta0 = pi), theta0 <= 0 and NaN are
    flagged, not integrated; g and l broadcast against theta0."""
    theta0 = np.array([[1.0, math.pi, 4.0], [0.0, np.nan, 2.0]])
    l = np.array([[0.5], [2.0]])
    periods, status = pendulum_periods(theta0, G, l)
    assert periods.shape == status.shape == (2, 3)
    expect = np.array([[OK, NOT_LIBRATING, NOT_LIBRATING], [NOT_LIBRATING, NOT_LIBRATING, OK]])
    assert np.array_equal(status, expect)
    assert np.all(np.isnan(periods[status != OK]))
    ok = status == OK
    exact = exact_period(theta0[ok], G, np.broadcast_to(l, theta0.shape)[ok])
    assert np.allclose(periods[ok], exact, rtol=1e-9, atol=0.0)


@pytest.mark.skipif(numba.config.NUMBA_NUM_THREADS < 2, reason="needs 2 threads")
def test_threads_and_blocks_do_not_change_results():
    """Bitwise: 1 thread vs 2, one block vs blocks of 7 members (progress per block)."""
    threads = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = sweep()
        numba.set_num_threads(2)
        two = sweep()
        seen = []
        blocks = sweep(block=7, progress=seen.append)
    finally:
        numba.set_num_threads(threads)
    assert np.all(one.status == OK) and np.sum(one.n_events >= 2) > 50  # last ones rotate
    assert_same(one, two)
    assert_same(one, blocks)
    assert seen == [min(k + 7, 60) / 60 for k in range(0, 60, 7)]


def test_states_match_single_run_bit_for_bit():
    """Members take integrate(..., "dop853")'s steps: the same states at t_eval and at
    t_end, bit for bit, and (without events, whose interpolants cost extra evaluations)
    the same counts of evaluations, accepted and rejected steps."""
    ens = sweep(event=None, max_events=0)
    ens_ev = sweep()
    t_eval = ens.t_eval
    for row, m in enumerate(ens.store):
        y0 = np.array([np.linspace(0.05, 3.0, 60)[m], np.linspace(-0.5, 0.5, 60)[m]])
        g_over_l = np.linspace(4.0, 12.0, 60)[m]
        sol = integrate(pendulum.model(g_over_l, 1.0), y0, t_eval, method="dop853",
                        rtol=1e-10, atol=1e-12)
        assert np.array_equal(ens.y_store[row], sol.y)
        assert np.array_equal(ens_ev.y_store[row], sol.y)
        assert np.array_equal(ens.y_end[m], sol.y[-1])
        assert list(ens.counters[m]) == [sol.nfev, sol.nsteps, sol.nreject]
        assert ens.t_final[m] == t_eval[-1]


def test_event_times_oscillator():
    """q = cos t: crossings at pi/2 + n pi (down for even n), each on the interpolant:
    integrate's dense output at the found time (same steps, same interpolant) is zero
    to rounding, and the times are exact to the integration's accuracy."""
    model = oscillator.model(1.0, 1.0)
    Y0 = np.array([[1.0, 0.0], [2.0, 0.0]])
    exact = math.pi / 2 + math.pi * np.arange(6)
    for direction, n in ((0, slice(0, 6)), (-1, slice(0, 6, 2)), (1, slice(1, 6, 2))):
        ens = run_ensemble(model, Y0, t_end=20.0, rtol=1e-12, atol=1e-14, event="q",
                           direction=direction, max_events=3 if direction else 6)
        assert np.all(ens.n_events == (3 if direction else 6))
        assert np.max(np.abs(ens.events - exact[n])) < 1e-11
    ens = run_ensemble(model, Y0[:1], t_end=20.0, rtol=1e-12, atol=1e-14, event=0,
                       max_events=6)
    for t_ev in ens.events[0]:
        sol = integrate(model, Y0[0], [0.0, t_ev, 20.0], method="dop853", rtol=1e-12,
                        atol=1e-14)
        assert abs(sol.y[1, 0]) < 4 * np.finfo(float).eps * t_ev  # |q'| = 1: ulp(t) scale


def test_terminal_events_stop_members():
    """terminal: each member stops at the step holding its last wanted crossing."""
    model = oscillator.model(1.0, 1.0)
    Y0 = np.array([[1.0, 0.0], [1.0, 0.0]])
    P = np.array([[1.0, 1.0], [4.0, 4.0]])  # frequencies 1 and 4
    ens = run_ensemble(model, Y0, P, t_end=100.0, rtol=1e-10, atol=1e-12, event=0,
                       direction=1, max_events=2, terminal=True)
    assert np.all(ens.status == OK) and np.all(ens.n_events == 2)
    periods = ens.events[:, 1] - ens.events[:, 0]
    assert np.allclose(periods, [2 * math.pi, math.pi / 2], rtol=1e-9, atol=0.0)
    assert np.all(ens.t_final >= ens.events[:, 1]) and np.all(ens.t_final < 100.0)
    assert np.all(ens.counters[:, 1] < 100)  # a run to t_end would take hundreds of steps
    whole = run_ensemble(model, Y0, P, t_end=100.0, rtol=1e-10, atol=1e-12, terminal=True)
    assert np.all(whole.t_final == 100.0)  # nothing to wait for: no early stop


def test_failing_members_are_flagged_and_others_unchanged():
    """A NaN initial state gives NONFINITE at once; a stiff member (g/l = 1e10) exceeds
    max_steps (attempted steps, accepted and rejected); the other members are bit for bit
    those of a run without them."""
    good = sweep(max_steps=2000)
    M = good.status.size
    Y0 = np.column_stack([np.linspace(0.05, 3.0, M), np.linspace(-0.5, 0.5, M)])
    P = np.linspace(4.0, 12.0, M)[:, None]
    Y0[7, 0] = np.nan
    P[M // 2, 0] = 1e10  # a stored member
    bad = run_ensemble(pendulum.model(G, L), Y0, P, t_end=4.0, rtol=1e-10, atol=1e-12,
                       event="theta", max_events=5, t_eval=good.t_eval,
                       store=[0, M // 2, M - 1], max_steps=2000)
    assert bad.status[7] == NONFINITE and bad.counters[7, 0] == 0
    assert bad.status[M // 2] == MAXSTEPS and bad.counters[M // 2, 1:].sum() == 2000
    others = np.setdiff1d(np.arange(M), [7, M // 2])
    assert np.all(bad.status[others] == OK)
    for name in RESULT_FIELDS[:-1]:
        a, b = getattr(good, name)[others], getattr(bad, name)[others]
        assert np.array_equal(a, b, equal_nan=True), name
    assert np.array_equal(bad.y_store[[0, 2]], good.y_store[[0, 2]])
    assert np.isnan(bad.y_store[1, -1]).all()


def test_energy_of_stored_members():
    """Energy theta_dot^2/2 - (g/l) cos(theta) along the stored trajectories stays within
    50 rtol of its initial value, relative to g/l (measured: 1.1e-11 at rtol 1e-12)."""
    theta0 = np.linspace(0.1, 3.1, 200)
    omega2 = 9.81
    t_eval = np.linspace(0.0, 20.0, 2001)
    store = [0, 50, 150, 199]
    ens = run_ensemble(pendulum.model(omega2, 1.0), np.column_stack([theta0, 0 * theta0]),
                       t_end=20.0, rtol=1e-12, atol=1e-12, t_eval=t_eval, store=store)
    assert np.all(ens.status == OK)
    theta, theta_dot = ens.y_store[..., 0], ens.y_store[..., 1]
    energy = 0.5 * theta_dot**2 - omega2 * np.cos(theta)
    drift = np.abs(energy - energy[:, :1]) / omega2
    assert drift.max() < 50 * 1e-12, drift.max()
    assert np.allclose(theta[:, 0], theta0[store], rtol=0, atol=0)


def test_input_validation():
    model = pendulum.model(G, L)
    Y0 = np.array([[1.0, 0.0]])
    with pytest.raises(ValueError, match="Y0"):
        run_ensemble(model, np.ones((2, 3)), t_end=1.0)
    with pytest.raises(ValueError, match="t_eval"):
        run_ensemble(model, Y0, t_end=1.0, t_eval=[0.0, 2.0], store=[0])
    with pytest.raises(ValueError, match="store"):
        run_ensemble(model, Y0, t_end=1.0, store=[1])
    with pytest.raises(ValueError, match="event"):
        run_ensemble(model, Y0, t_end=1.0, event="x", max_events=1)
    with pytest.raises(ValueError, match="atol"):
        run_ensemble(model, Y0, t_end=1.0, atol=0.0)
    with pytest.raises(ValueError, match="P"):
        run_ensemble(model, Y0, np.ones((2, 1)), t_end=1.0)


def test_status_names_cover_codes():
    codes = {v for k, v in vars(ensemble).items() if k.isupper() and isinstance(v, int)
             and k not in ("EPS",)}
    assert codes <= set(ensemble.STATUS_NAMES)
    assert {NOT_LIBRATING, NO_PERIOD} <= set(ensemble.STATUS_NAMES)


def _child_periods(queue):
    from reportgen.kinds.pendulum.ensemble import pendulum_periods as periods

    queue.put(periods(np.array([0.5, 1.0]), 9.81, 1.0)[0].tolist())


def test_ensemble_runs_in_a_process_forked_after_one_ran():
    """reportgen forks (scene workers, figure and PDF helpers, watch): a child forked after
    its parent ran an ensemble must run one too (under GNU OpenMP, which a ``prange``
    driver used, it was killed)."""
    import multiprocessing

    parent = pendulum_periods(np.array([0.5, 1.0]), 9.81, 1.0)[0]
    ctx = multiprocessing.get_context("fork")
    queue = ctx.Queue()
    child = ctx.Process(target=_child_periods, args=(queue,))
    child.start()
    child.join(120)
    assert child.exitcode == 0
    assert queue.get(timeout=5) == parent.tolist()
