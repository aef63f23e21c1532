"""Weierstrass's ℘ from theta series (reportgen.core.weierstrass) against known values.

References checked here:
- lemniscatic lattice, g2 = 1, g3 = 0: ω1 = Γ(1/4)²/(4√π), ω3 = iω1, e = (½, 0, −½)
                                                              (DLMF 23.5(iii))
- equianharmonic lattice, g2 = 0, g3 = 1: ω1 = Γ(1/3)³/(4π), ω3 = e^{iπ/3} ω1,
  ℘(ω1) = 4^{-1/3}, the e_j the roots of 4e³ − 1                (DLMF 23.5(v))
- Laurent series ℘ = 1/z² + g2 z²/20 + g3 z⁴/28 + g2² z⁶/1200 + …  (DLMF 23.9.2-3)
- ℘'² = 4℘³ − g2℘ − g3 (DLMF 23.3.10), periodicity and evenness (DLMF 23.2.1, 23.2.8)
- duplication ℘(2z) = −2℘(z) + (℘''(z)/(2℘'(z)))², ℘'' = 6℘² − g2/2 (DLMF §23.10(i))
"""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
from scipy.special import gamma

from reportgen.core import weierstrass as W

LEMNISCATIC_OMEGA = gamma(0.25) ** 2 / (4 * math.sqrt(math.pi))  # DLMF 23.5(iii), g2 = 1
EQUIANHARMONIC_OMEGA = gamma(1 / 3) ** 3 / (4 * math.pi)  # DLMF 23.5(v), g3 = 1

RNG = np.random.default_rng(11)


def random_rectangular(n=4):
    """Lattices of random real roots e1 > e2 > e3 (sum 0), from nearly degenerate to wide."""
    out = []
    for _ in range(n):
        gaps = RNG.uniform(0.05, 3.0, size=2)
        e3 = -(2 * gaps[0] + gaps[1]) / 3  # e2 = e3 + gaps[0], e1 = e2 + gaps[1]
        e = (e3 + gaps[0] + gaps[1], e3 + gaps[0], e3)
        out.append((e, W.Lattice.from_roots(*e)))
    return out


def sample_points(lattice, n=12):
    s, r = RNG.uniform(-0.5, 0.5, size=(2, n))
    return 2 * lattice.omega1 * s + 2 * lattice.omega3 * r


def test_lemniscatic_half_periods_and_values():
    # DLMF 23.5(iii): g2 = 1, g3 = 0 has e = ½, 0, −½ and the square lattice ω3 = iω1
    omega, omega_prime = W.half_periods(0.5, 0.0, -0.5)
    assert omega == pytest.approx(LEMNISCATIC_OMEGA, rel=1e-15)
    assert omega_prime == pytest.approx(LEMNISCATIC_OMEGA, rel=1e-15)
    lattice = W.Lattice.from_roots(0.5, 0.0, -0.5)
    g2, g3 = lattice.invariants
    assert abs(g2 - 1.0) <= 1e-14 and abs(g3) <= 1e-14
    values = W.wp(np.array([lattice.omega1, lattice.omega1 + lattice.omega3, lattice.omega3]),
                  lattice)
    np.testing.assert_allclose(values, [0.5, 0.0, -0.5], atol=1e-14)


def test_equianharmonic_lattice_values():
    # DLMF 23.5(v): the rhombic lattice ω1 = Γ(1/3)³/(4π), ω3 = e^{iπ/3} ω1 has g2 = 0,
    # g3 = 1; ℘ at the half-periods are the roots of 4e³ − 1 = 0, ℘(ω1) = 4^{-1/3} real
    lattice = W.Lattice(EQUIANHARMONIC_OMEGA, np.exp(1j * math.pi / 3) * EQUIANHARMONIC_OMEGA)
    g2, g3 = lattice.invariants
    assert abs(g2) <= 1e-13 and abs(g3 - 1.0) <= 1e-13
    root = 4 ** (-1 / 3)
    assert W.wp(np.array([lattice.omega1]), lattice)[0] == pytest.approx(root, abs=1e-14)
    halves = [lattice.omega1, lattice.omega3, lattice.omega1 + lattice.omega3]
    values = W.wp(np.array(halves), lattice)
    expected = root * np.exp(2j * math.pi * np.arange(3) / 3)
    distance = np.abs(values[:, None] - expected[None, :])
    assert np.max(np.min(distance, axis=1)) <= 1e-14  # each value is a root ...
    assert sorted(np.argmin(distance, axis=1)) == [0, 1, 2]  # ... and each root is taken
    # the ODE on this non-rectangular lattice too
    z = sample_points(lattice)
    p, dp = W.wp(z, lattice), W.wp_prime(z, lattice)
    np.testing.assert_allclose(dp**2, 4 * p**3 - 1.0, rtol=1e-12)


def laurent_coefficients(g2, g3, n=14):
    """c_2..c_n of ℘ = 1/z² + Σ c_k z^{2k−2}: c2 = g2/20, c3 = g3/28 and
    c_k = 3/((2k + 1)(k − 3)) Σ_{m=2}^{k−2} c_m c_{k−m} (DLMF 23.9.2-3)."""
    c = {2: g2 / 20, 3: g3 / 28}
    for k in range(4, n + 1):
        c[k] = 3 / ((2 * k + 1) * (k - 3)) * sum(c[m] * c[k - m] for m in range(2, k - 1))
    return c


def test_laurent_coefficients_recursion():
    # DLMF 23.9.3's first cases: c4 = c2²/3, c5 = 3 c2 c3/11
    c = laurent_coefficients(1.7, -0.4)
    assert c[4] == pytest.approx(c[2] ** 2 / 3, rel=1e-15)
    assert c[5] == pytest.approx(3 * c[2] * c[3] / 11, rel=1e-15)


@pytest.mark.parametrize("z", [0.05, 0.1 + 0.07j, -0.12j, 0.15 - 0.1j])
def test_laurent_series_near_the_pole(z):
    for e, lattice in random_rectangular(3):
        c = laurent_coefficients(*W.invariants(*e))
        series = 1 / z**2 + sum(ck * z ** (2 * k - 2) for k, ck in c.items())
        derivative = -2 / z**3 + sum((2 * k - 2) * ck * z ** (2 * k - 3) for k, ck in c.items())
        assert W.wp(np.array([z]), lattice)[0] == pytest.approx(series, rel=1e-13)
        assert W.wp_prime(np.array([z]), lattice)[0] == pytest.approx(derivative, rel=1e-12)


def test_differential_equation_derivative_and_roots():
    for e, lattice in random_rectangular():
        g2, g3 = W.invariants(*e)
        # the theta constants give back the roots the lattice was built from
        np.testing.assert_allclose(np.real(lattice.roots), e, atol=1e-13 * max(map(abs, e)))
        z = sample_points(lattice)
        p, dp = W.wp(z, lattice), W.wp_prime(z, lattice)
        # DLMF 23.3.10: ℘'² = 4℘³ − g2℘ − g3
        scale = np.abs(4 * p**3) + abs(g2 * p) + abs(g3)
        assert np.max(np.abs(dp**2 - (4 * p**3 - g2 * p - g3)) / scale) <= 1e-13
        # ℘' against a central difference of ℘ (O(h⁴) five-point stencil)
        h = 1e-3 * abs(lattice.omega1)
        fd = (-W.wp(z + 2 * h, lattice) + 8 * W.wp(z + h, lattice) - 8 * W.wp(z - h, lattice)
              + W.wp(z - 2 * h, lattice)) / (12 * h)
        assert np.max(np.abs(fd - dp) / np.abs(dp)) <= 1e-7


def test_periodicity_evenness_and_duplication():
    for e, lattice in random_rectangular():
        g2, _g3 = W.invariants(*e)
        z = sample_points(lattice, 8)
        p = W.wp(z, lattice)
        # DLMF 23.2.1, 23.2.8: periods 2ω1, 2ω3; ℘ even
        for shift in (2 * lattice.omega1, 2 * lattice.omega3, 6 * lattice.omega1 - 4 * lattice.omega3):
            np.testing.assert_allclose(W.wp(z + shift, lattice), p, rtol=1e-12)
        np.testing.assert_allclose(W.wp(-z, lattice), p, rtol=1e-13)
        # duplication (DLMF §23.10(i)): ℘(2z) = −2℘ + (℘''/(2℘'))², ℘'' = 6℘² − g2/2
        dp = W.wp_prime(z, lattice)
        doubled = -2 * p + ((6 * p**2 - g2 / 2) / (2 * dp)) ** 2
        np.testing.assert_allclose(W.wp(2 * z, lattice), doubled, rtol=1e-10)


def test_real_on_the_line_through_the_imaginary_half_period():
    # ℘ is real on z = ω3 + x and runs monotonically from e3 (x = 0) to e2 (x = ω1)
    for e, lattice in random_rectangular():
        x = np.linspace(0.0, lattice.omega1.real, 200)
        values = W.wp(x + lattice.omega3, lattice)
        assert np.max(np.abs(values.imag)) <= 1e-13 * max(map(abs, e))
        assert np.all(np.diff(values.real) > 0)
        assert values.real[0] == pytest.approx(e[2], abs=1e-13)
        assert values.real[-1] == pytest.approx(e[1], abs=1e-13)
        np.testing.assert_allclose(W.wp_minus_e3(x + lattice.omega3, lattice).real,
                                   values.real - e[2], atol=1e-13)


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="e1 > e2 > e3"):
        W.half_periods(0.0, 0.5, -0.5)
    with pytest.raises(ValueError, match="Im"):
        W.Lattice(1.0, -1j)
    with pytest.raises(ValueError, match="degenerate"):
        W.Lattice(1.0, 1e-3j)  # |q| = exp(−π 1e-3) ≈ 0.997


def test_independent_of_the_jacobi_functions():
    # the ℘ route must not go through sn/cn/dn or scipy's elliptic functions: evaluated
    # with reportgen.core.special and scipy.special unimportable
    code = """
import sys
sys.modules["reportgen.core.special"] = None
sys.modules["scipy.special"] = None
import numpy as np
from reportgen.core import weierstrass as W
lattice = W.Lattice.from_roots(0.5, 0.0, -0.5)
print(float(W.wp(np.array([lattice.omega1]), lattice)[0].real))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert float(out.stdout) == pytest.approx(0.5, abs=1e-14)
