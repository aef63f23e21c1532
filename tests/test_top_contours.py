"""Textbook ex. 4.10(a)–(e): t(u) = ∫du/√f(u) of the heavy top continued over its Riemann
surface by contour integration (reportgen.core.top_contours), against independent closed
forms: the real period T = 4K(k²)/√(β(u3 − u1)) of notes (10.31) by Carlson's R_F, and the
imaginary one τ = 2ω′ of the top's ℘ lattice by the arithmetic–geometric mean
(reportgen.core.heavy_top_theory.weierstrass_form; DLMF 23.22, 19.8)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from reportgen.core import heavy_top_theory as theory
from reportgen.core.top_contours import TopCubic, contour_map, path

#: (I1, I3, Mgl, θ0, θ̇0, φ̇0, ω3): a looping top (Fig. 4.3a's band), a wavy one, a narrow
#: fast one (u_U far out: k² small), a slow wide one with u_U just past 1 (k² near 1)
TOPS = {
    "loops": (1.0, 0.5, 1.0, 0.872664625997165, 0.0, -0.3168071689827444, 9.723477700446692),
    "waves": (1.0, 0.5, 1.0, 0.9, 0.0, 0.8, 6.0),
    "fast": (1.0, 0.8, 1.0, 1.0, 0.05, 0.1, 40.0),
    "wide": (1.0, 0.5, 1.0, 1.2, 0.0, 0.0, 2.9),
}


def _top(name):
    c = theory.constants(*TOPS[name])
    r = theory.roots(c)
    return c, r, TopCubic(c.beta, r.u1, r.w2 - r.w1, r.w2 - r.w3)


@pytest.mark.parametrize("name", TOPS)
def test_the_periods_are_the_independent_closed_forms(name):
    c, r, cubic = _top(name)
    T = theory.nutation_period(r, c)
    form = theory.weierstrass_form(r, c)
    assert cubic.period == pytest.approx(T, rel=1e-14)
    assert cubic.imaginary_period == pytest.approx(2.0 * form.omega_prime, rel=1e-12)


@pytest.mark.parametrize("name", TOPS)
def test_the_cut_plane_maps_onto_the_rectangle_its_corners_and_sides(name):
    """(a): u_X, u_N, u_U and ∞ go to 0, T/2, T/2 + iτ/2 and iτ/2, each real piece to its
    side, the upper half-plane into (0, T/2) × (0, τ/2); (b) below the axis the mirror."""
    c, r, cubic = _top(name)
    T, tau = theory.nutation_period(r, c), 2.0 * theory.weierstrass_form(r, c).omega_prime
    m = contour_map(cubic)
    assert m.corners["u_N"] == pytest.approx(0.5 * T, abs=1e-12 * T)
    assert m.corners["u_U"] == pytest.approx(complex(0.5 * T, 0.5 * tau), abs=1e-12 * T)
    assert m.corners["infinity"] == pytest.approx(0.5j * tau, abs=1e-12 * T)
    assert m.corners["infinity_left"] == pytest.approx(0.5j * tau, abs=1e-12 * T)
    assert max(m.sides.values()) < 1e-12 * T
    up, down = m.images["upper"], m.images["lower"]
    assert np.all(up.imag > 0) and np.all(up.real > -1e-12 * T) and np.all(up.real < 0.5 * T)
    assert np.all(down.imag < 0)
    assert np.max(np.abs(down - np.conj(up))) < 1e-12 * T
    assert max(m.defects.values()) < 1e-12 * T


@pytest.mark.parametrize("name", TOPS)
def test_the_second_sheet_through_either_cut(name):
    """(c) t₁ = −t₀ through (−∞, u_X]; (d) t₂ = t₁ + T through [u_N, u_U]; at points of
    both half-planes, along paths other than the map's."""
    c, r, cubic = _top(name)
    T = theory.nutation_period(r, c)
    d_N, d_U = cubic.d_N, cubic.d_U
    rng = np.random.default_rng(4)
    h, back = 0.7 * d_U, 0.5 * d_N
    for u in rng.uniform(-d_U, 2 * d_U, 6) + 1j * rng.uniform(-d_U, d_U, 6):
        t0, sheet = path(cubic, [0.0, complex(back, 0.0), u])  # via (u_X, u_N)
        assert sheet == 1
        # down through a cut, then below the axis to u_X < Re u < u_N and up or down to u's
        # height: through no other cut and round no branch point, so on the second sheet
        for x, expected in ((-0.3 * d_U, -t0), (0.5 * (d_N + d_U), T - t0)):
            t, sheet = path(cubic, [0.0, complex(x, h), complex(x, -h), complex(back, -h),
                                    complex(back, u.imag), u])
            assert sheet == -1
            assert t == pytest.approx(expected, abs=1e-12 * T)


@pytest.mark.parametrize("name", TOPS)
def test_loops_round_the_cuts_are_the_periods(name):
    """(e): a loop clockwise once more round [u_N, u_U] adds iτ; round [u_X, u_N] (through
    both cuts, so back on the first sheet) it adds T: the two periods of u(t)."""
    c, r, cubic = _top(name)
    T, tau = theory.nutation_period(r, c), 2.0 * theory.weierstrass_form(r, c).omega_prime
    d_N, d_U = cubic.d_N, cubic.d_U
    h = 0.3 * d_U
    a, b = 0.5 * d_N, 1.5 * d_U
    loop, sheet = path(cubic, [a, complex(a, h), complex(b, h), complex(b, -h), complex(a, -h), a])
    assert sheet == 1 and loop == pytest.approx(1j * tau, abs=1e-12 * T)
    a, b, m = -0.5 * d_N, 0.5 * (d_N + d_U), complex(0.5 * d_N, h)
    loop, sheet = path(cubic, [m, complex(b, h), complex(b, -h), complex(a, -h), complex(a, h), m])
    assert sheet == 1 and loop == pytest.approx(T, abs=1e-12 * T)
    with pytest.raises(ValueError, match="on a cut"):
        path(cubic, [complex(a, h), a, complex(a, -h)])


def test_a_point_on_a_cut_is_taken_on_the_side_it_is_approached_from():
    _, _, cubic = _top("loops")
    x = 0.5 * (cubic.d_N + cubic.d_U)
    above = cubic.root(complex(x, 0.0))
    below = cubic.root(np.conj(complex(x, 0.0)))
    assert above == pytest.approx(-below) and abs(above.real) < 1e-12 * abs(above)
    inside = cubic.root(complex(0.5 * cubic.d_N, 0.0))
    assert inside.real > 0 and inside == pytest.approx(math.sqrt(
        cubic.beta * 0.5 * cubic.d_N * 0.5 * cubic.d_N * (cubic.d_U - 0.5 * cubic.d_N)))


def test_a_scene_nobody_shipped_shows_the_section_with_every_check_ok(tmp_path):
    """A wavy top on another band, its [report] naming the section: the archive holds the
    map, the checks pass, the page has the section; without the name nothing is computed."""
    import h5py

    from reportgen.commands.cli import main

    text = """kind = "heavy_top"
title = "A wavy top, t(u) continued"
[params]
I1 = 2.0
I3 = 0.7
Mgl = 1.5
[initial]
theta = 0.7
theta_dot = 0.0
phi_dot = 0.6
omega3 = 9.0
[run]
t_end = 20.0
samples = 2001
study = false
[report]
formats = ["html"]
sections = ["cubic", "contour_map"]
"""
    (tmp_path / "wavy.toml").write_text(text)
    (tmp_path / "plain.toml").write_text(text.replace(', "contour_map"', ""))
    assert main(["run", str(tmp_path / "wavy.toml"), str(tmp_path / "plain.toml"),
                 "--out", str(tmp_path / "out")]) == 0
    with h5py.File(tmp_path / "out" / "wavy" / "run.h5", "r") as f:
        k = f["analysis/contours"]
        T = float(k.attrs["period"])
        defects = {n: v for n, v in k["defects"].attrs.items() if not n.startswith("__")}
        assert len(defects) == 12 and max(map(float, defects.values())) < 1e-12 * T
        assert k["upper_re"].shape == k["grid_re"].shape
    with h5py.File(tmp_path / "out" / "plain" / "run.h5", "r") as f:
        assert "contours" not in f["analysis"]
    page = (tmp_path / "out" / "wavy" / "report.html").read_text(encoding="utf-8")
    assert '<section id="contour_map">' in page
    assert '<section id="contour_map">' not in (
        tmp_path / "out" / "plain" / "report.html").read_text(encoding="utf-8")
