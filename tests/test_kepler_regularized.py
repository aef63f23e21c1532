"""Levi-Civita regularized Kepler motion against Kepler's equation (Stiefel & Scheifele §4)."""

from __future__ import annotations

import math

import numpy as np

from reportgen.core.integrators import integrate
from reportgen.core.models import kepler
from reportgen.core.models import kepler_regularized as lc


def test_regularized_orbit_matches_keplers_equation_and_conserves_energy():
    e = 0.9
    x, y, vx, vy = 1 - e, 0.0, 0.0, math.sqrt((1 + e) / (1 - e))  # GM = 1, a = 1, T = 2π
    h = 0.5 * (vx**2 + vy**2) - 1.0 / math.hypot(x, y)
    s_orbit = lc.orbit_fictitious_period(h)
    s = np.linspace(0.0, 20 * s_orbit, 801)
    sol = integrate(lc.model(h), lc.to_regularized(x, y, vx, vy), s, method="gauss6",
                    h=s_orbit / 24)
    X, Y, VX, VY, T = lc.from_regularized(sol.y)
    energy = 0.5 * (VX**2 + VY**2) - 1.0 / np.hypot(X, Y)
    assert np.max(np.abs(energy / h - 1)) < 1e-13
    assert abs(T[-1] / (20 * 2 * math.pi) - 1) < 1e-9  # 20 orbits of fictitious time = 20 T
    # positions at the times reached, from the independent Kepler-equation solution
    elements = kepler.orbital_elements(x, y, vx, vy, 1.0)
    ref = kepler.kepler_state(T, elements)
    assert np.max(np.hypot(X - ref[0], Y - ref[1])) < 1e-8


def test_energy_over_1000_eccentric_orbits_stays_below_1e_13():
    """Kepler e = 0.9, 1000 orbits at 48 steps per orbit (the bench's REBOUND comparison):
    the energy error is round-off only, and round-off a random walk, not a drift: the
    b-weighted update, compensated summation and the tableau as double pairs keep max
    |ΔE/E| below 1e-13 (measured 6.8e-14; 2.6e-13 with the d-form update)."""
    e = 0.9
    x, y, vx, vy = 1 - e, 0.0, 0.0, math.sqrt((1 + e) / (1 - e))
    h = 0.5 * (vx**2 + vy**2) - 1.0 / math.hypot(x, y)
    s_orbit = lc.orbit_fictitious_period(h)
    s = np.linspace(0.0, 1000 * s_orbit, 1001)
    sol = integrate(lc.model(h), lc.to_regularized(x, y, vx, vy), s, method="gauss6",
                    h=s_orbit / 48)
    X, Y, VX, VY, _ = lc.from_regularized(sol.y)
    energy = 0.5 * (VX**2 + VY**2) - 1.0 / np.hypot(X, Y)
    assert np.max(np.abs(energy / h - 1)) < 1e-13
