"""The KS-pair three-body model against physics and the Cartesian model; the Pythagorean
bench on a short span (against REBOUND IAS15 when installed)."""

from __future__ import annotations

import numpy as np
import pytest

from reportgen.commands.bench_nbody import MASSES, initial_state, pythagorean_against_rebound
from reportgen.core.integrators import integrate
from reportgen.core.models import nbody
from reportgen.core.models import three_body_ks as ks

G = 1.0
MOVING_MASSES = (1.0, 2.0, 1.5)


def _moving_state():
    """A bound, non-planar triple with angular momentum (centre-of-mass frame)."""
    m = np.asarray(MOVING_MASSES)
    pos = np.array([[1.0, 0.2, 0.1], [-0.6, 0.1, -0.2], [0.3, -1.1, 0.3]])
    vel = np.array([[0.1, 0.6, 0.05], [-0.3, -0.2, 0.1], [0.4, 0.1, -0.2]])
    pos -= m @ pos / m.sum()
    vel -= m @ vel / m.sum()
    return np.concatenate([pos.ravel(), vel.ravel()])


@pytest.mark.parametrize("pair", [(0, 1), (1, 2), (2, 0)])
def test_conversion_round_trip_and_energy(pair):
    y0 = _moving_state()
    reg = ks.model(G, MOVING_MASSES, pair)
    z0 = ks.to_regularized(y0, G, MOVING_MASSES, pair, t=0.5)
    cart, t = ks.to_cartesian(reg, z0)
    assert np.max(np.abs(cart[0] - y0)) < 1e-14
    assert t[0] == 0.5
    e = nbody.energy(y0, G, MOVING_MASSES)[0]
    assert abs(ks.energy(reg, z0)[0] / e - 1) < 1e-14
    # the carried Kepler energy of the pair: 2|u'|² − G m_ij = h r
    u, w = z0[:4], z0[4:8]
    m_ij = MOVING_MASSES[pair[0]] + MOVING_MASSES[pair[1]]
    assert abs(2 * w @ w - G * m_ij - z0[8] * (u @ u)) < 1e-14


@pytest.mark.parametrize("fictitious_time", [True, False])
def test_agrees_with_cartesian_model_and_conserves_invariants(fictitious_time):
    y0 = _moving_state()
    reg = ks.model(G, MOVING_MASSES, (0, 2), fictitious_time=fictitious_time)
    z0 = ks.to_regularized(y0, G, MOVING_MASSES, (0, 2))
    grid = np.linspace(0.0, 2.0, 41)
    sol = integrate(reg, z0, grid, method="dop853", rtol=1e-13, atol=1e-15)
    assert sol.status == "ok"
    cart, t = ks.to_cartesian(reg, sol.y)
    if not fictitious_time:
        assert np.max(np.abs(t - grid)) < 1e-13
    ref = integrate(nbody.model(G, MOVING_MASSES), y0, t, method="dop853", rtol=1e-13,
                    atol=1e-15)
    assert np.max(np.abs(cart - ref.y)) < 1e-9
    e = nbody.energy(cart, G, MOVING_MASSES)
    assert np.max(np.abs(e / e[0] - 1)) < 1e-12
    L = nbody.angular_momentum(cart, MOVING_MASSES)
    assert np.max(np.abs(L - L[0])) < 1e-12 * np.max(np.abs(L[0]))
    assert np.max(np.abs(nbody.momentum(cart, MOVING_MASSES))) < 1e-13


def test_regularized_pair_keeps_energy_through_the_close_encounter():
    """Pythagorean problem to t ≈ 16.5, through the encounter of the bodies of mass 4 and 5
    at t ≈ 15.83 (separation ~4e-4): the Cartesian run loses ~4e-10 there."""
    reg = ks.model(G, MASSES, (1, 2))
    z0 = ks.to_regularized(initial_state(), G, MASSES, (1, 2))
    sol = integrate(reg, z0, np.linspace(0.0, 17.0, 171), method="dop853", rtol=1e-14,
                    atol=1e-16)
    cart, t = ks.to_cartesian(reg, sol.y)
    assert t[-1] > 16.0
    assert np.min(np.linalg.norm(ks.relative(sol.y)[0], axis=1)) < 0.2  # it went through
    e0 = nbody.energy(initial_state(), G, MASSES)[0]
    assert abs(nbody.energy(cart[-1], G, MASSES)[0] / e0 - 1) < 1e-12


def test_bench_rows_on_a_short_span():
    lines = []
    out = pythagorean_against_rebound(t_end=2.0, outputs=21, repeats=1, print=lines.append)
    rows = {r["method"]: r for r in out["rows"]}
    for method in ("dop853 rtol 1e-13", "KS pair (t) dop853 rtol 1e-15",
                   "KS pair (s) dop853 rtol 1e-15"):
        assert rows[method]["error"] < 1e-11
        assert rows[method]["wall_time_s"] > 0
    assert rows["KS pair (s) dop853 rtol 1e-15"]["error_end"] < 1e-13
    ours = [r["final"] for r in out["rows"] if not r["method"].startswith("REBOUND")]
    assert max(np.max(np.abs(f - ours[0])) for f in ours) < 1e-8
    assert any(line.startswith("Pythagorean three-body problem to t = 2") for line in lines)


def test_bench_agrees_with_rebound_ias15_on_early_positions():
    pytest.importorskip("rebound")
    out = pythagorean_against_rebound(t_end=2.0, outputs=21, repeats=1, print=lambda *a: None)
    ias = out["ias15"]
    assert ias is not None and ias["error"] < 1e-11
    for r in out["rows"]:
        assert r["final_position_difference"] < 1e-8, r["method"]
        assert r["ias15_time_ratio"] > 0
    # same frame: IAS15 after move_to_com starts where our centre-of-mass state does
    assert np.allclose(ias["final"][:9].reshape(3, 3).T @ np.asarray(MASSES), 0.0, atol=1e-12)
