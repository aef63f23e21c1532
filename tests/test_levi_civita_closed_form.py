"""``levi_civita``'s one-pass, closed-form gauss6 on the Levi-Civita oscillator (issue 34).

The fast path solves Gauss collocation's stage equations on w'' = (h/2) w in closed form
and takes the n-th grid state as the n-th power of the step's rotation.  Checked here
against independent computations:

* the generic compiled gauss6 (simplified Newton on the collocation equations,
  :func:`reportgen.core.integrators.compiled.collocation_fixed`) run on the same (LC)
  model with the same step: the same states at the same t (Hairer & Wanner, *Solving
  ODEs II* IV.5: one method, two ways of solving its stage equations);
* Kepler's equation (``kepler.kepler_state``, Murray & Dermott §2.4): the position error
  at the end is the method's phase error, ≈ STEP_CONSTANT · speed / N⁶ per orbit (the
  measured constant of ``regularized.STEP_CONSTANT``), growing linearly with the orbits;
* E, L and the LRL vector, quadratic invariants of (LC) that Gauss collocation conserves
  exactly (Hairer, Lubich & Wanner, *Geometric Numerical Integration* IV.2): round-off.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from reportgen.core.integrators import integrate, regularized
from reportgen.core.integrators.compiled_run import run_compiled
from reportgen.core.integrators.regularized import (
    SAFETY,
    STEP_CONSTANT,
    LeviCivita,
    grid_steps_per_orbit,
)
from reportgen.core.integrators.status import Status
from reportgen.core.integrators.symplectic import Gauss6
from reportgen.core.models import kepler

MODEL = kepler.model(k=1.0, mu=1.0)  # GM = 1, a = 1: period 2π


def pericentre_state(e):
    return np.array([1.0 - e, 0.0, 0.0, math.sqrt((1.0 + e) / (1.0 - e))])


def rtol_for(n, e):
    """The rtol at which ``levi_civita`` takes n grid steps per orbit."""
    speed = math.sqrt((1 + e) / (1 - e))
    rtol = STEP_CONSTANT * speed / (SAFETY * (n - 0.5) ** 6)
    assert grid_steps_per_orbit(rtol, e) == n
    return rtol


@pytest.mark.parametrize("e, n", [(0.9, 16), (0.3, 40), (0.99, 24)])
def test_closed_form_steps_are_the_generic_gauss6_steps(e, n):
    y0 = pericentre_state(e)
    lc = MODEL.extra["levi_civita"]
    h = lc.specific_energy(y0)
    ds = lc.fictitious_period(h) / n
    steps = 3 * n  # three orbits
    s = np.arange(steps + 1) * ds
    generic = run_compiled(Gauss6(), lc.model(h), lc.to_regularized(*y0), s, 0.0, 0.0, ds,
                           None, 10**6)
    assert generic.ok
    t_grid = generic.y[:, 4]
    x, y, vx, vy, _ = lc.from_regularized(generic.y)
    sol = integrate(MODEL, y0, t_grid, method="levi_civita", rtol=rtol_for(n, e))
    assert sol.ok
    speed = math.hypot(y0[2], y0[3])
    # round-off of two ways of solving the same equations (Newton's stops at ~4 eps)
    assert np.max(np.hypot(sol.y[:, 0] - x, sol.y[:, 1] - y)) < 1e-12
    assert np.max(np.hypot(sol.y[:, 2] - vx, sol.y[:, 3] - vy)) < 1e-11 * speed


@pytest.mark.parametrize("n", [16, 48])
def test_dense_outputs_keep_invariants_and_the_sixth_order_phase(n):
    # issue 34's case, 1000 orbits at 10,001 outputs: every output's energy at round-off
    # (≤ 2e-13 asked; heyoka at tol 1e-15 reaches 1.6e-13), the phase error the method's
    e, orbits = 0.9, 1000
    y0 = pericentre_state(e)
    t = np.linspace(0.0, orbits * 2 * math.pi, 10 * orbits + 1)
    sol = integrate(MODEL, y0, t, method="levi_civita", rtol=rtol_for(n, e))
    assert sol.ok and np.array_equal(sol.t, t)
    y = sol.y.T
    energy = kepler.energy(*y, 1.0, 1.0)
    L = kepler.angular_momentum(*y, 1.0)
    ax, ay = kepler.lrl_vector(*y, 1.0, 1.0)
    assert np.max(np.abs(energy / energy[0] - 1)) < 1e-13
    assert np.max(np.abs(L / L[0] - 1)) < 1e-13
    assert np.max(np.hypot(ax - ax[0], ay - ay[0])) < 1e-13
    # position error at the end: K orbits of the per-orbit phase error, within a factor
    # 1.5 either way (a coarser grid or a broken step shows above, a secretly finer grid
    # below)
    exact = np.column_stack(kepler.kepler_state(t[-1:], kepler.orbital_elements(*y0, 1.0)))
    err = math.hypot(*(sol.y[-1, :2] - exact[0, :2]))
    expected = orbits * STEP_CONSTANT * math.sqrt((1 + e) / (1 - e)) / n**6
    assert expected / 1.5 < err < 1.5 * expected, (err, expected)  # measured 0.997
    # the grid: n steps per orbit plus one step of size σ per output
    assert sol.nsteps == pytest.approx(orbits * n + t.size, abs=n)


def test_progress_chunks_give_the_same_states():
    y0 = pericentre_state(0.95)
    t = np.linspace(0.3, 40 * 2 * math.pi, 4001)
    seen = []
    a = LeviCivita().solve(MODEL, y0, t, 1e-12, 1e-14)
    b = LeviCivita().solve(MODEL, y0, t, 1e-12, 1e-14, progress=seen.append)
    assert np.array_equal(a.y, b.y)
    assert seen == sorted(seen) and seen[-1] == 1.0 and len(seen) > 1


def test_step_budget_ends_the_run_with_its_status(monkeypatch):
    monkeypatch.setattr(regularized, "DEFAULT_MAX_STEPS", 1000)
    y0 = pericentre_state(0.5)
    t = np.linspace(0.0, 200 * 2 * math.pi, 201)  # ≥ 16 steps per orbit: > 1000 steps
    sol = LeviCivita().solve(MODEL, y0, t, 1e-10, 1e-12)
    assert not sol.ok and sol.code is Status.MAX_STEPS
    assert "step budget" in sol.message
