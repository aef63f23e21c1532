"""Inertia tensors against closed forms and quadrature; parallel axes; the inertia scene."""

from __future__ import annotations

import math

import h5py
import numpy as np
import pytest
from scipy import integrate

from reportgen.core import inertia as core
from reportgen.core.rotations import euler_matrix


def quadrature_tensor(density_region, bounds):
    """∫ (r² δ_ij − x_i x_j) dV / V over a region given as nested tplquad bounds."""
    (x0, x1), y_lim, z_lim = bounds

    def integral(f):
        return integrate.tplquad(lambda z, y, x: f(x, y, z), x0, x1, *y_lim, *z_lim,
                                 epsabs=1e-12, epsrel=1e-10)[0]

    vol = integral(lambda x, y, z: 1.0)
    xx = integral(lambda x, y, z: x * x) / vol
    yy = integral(lambda x, y, z: y * y) / vol
    zz = integral(lambda x, y, z: z * z) / vol
    return np.diag([yy + zz, xx + zz, xx + yy]), vol


def test_cone_against_quadrature_and_landau():
    M, R, h = 2.0, 0.7, 1.6
    zc = core.cone_apex_height(h)  # apex at z = 3h/4, base at z = −h/4

    def rad(z):
        return R * (zc - z) / h

    # integrate over x, y in the disc of radius rad(z): use x outer, z middle via tplquad order
    def f_bounds():
        return ((-R, R), (lambda x: -h / 4, lambda x: zc - h * abs(x) / R),
                (lambda x, z: -math.sqrt(max(rad(z) ** 2 - x * x, 0.0)),
                 lambda x, z: math.sqrt(max(rad(z) ** 2 - x * x, 0.0))))

    (x0, x1), zl, yl = f_bounds()

    def integral(g):
        return integrate.tplquad(lambda y, z, x: g(x, y, z), x0, x1, *zl, *yl,
                                 epsabs=1e-13, epsrel=1e-10)[0]

    vol = integral(lambda x, y, z: 1.0)
    assert math.isclose(vol, math.pi * R * R * h / 3, rel_tol=1e-8)
    zbar = integral(lambda x, y, z: z) / vol
    assert abs(zbar) < 1e-8  # the CM is h/4 above the base
    m2 = [integral(lambda x, y, z, k=k: (x, y, z)[k] ** 2) / vol for k in range(3)]
    quad = M * np.diag([m2[1] + m2[2], m2[0] + m2[2], m2[0] + m2[1]])
    closed = core.tensor_cone(M, R, h)
    assert np.allclose(closed, quad, rtol=1e-7)
    # Landau & Lifshitz §32 Problem 2: about the CM I⊥ = 3M(R² + h²/4)/20, I3 = 3MR²/10;
    # about the apex (parallel axis (8.49)) I⊥ = 3M(R²/4 + h²)/5
    apex = core.parallel_axis(closed, M, [0.0, 0.0, zc])
    assert math.isclose(apex[0, 0], 3 * M * (R * R / 4 + h * h) / 5, rel_tol=1e-13)
    assert math.isclose(apex[2, 2], 0.3 * M * R * R, rel_tol=1e-13)


def test_box_against_quadrature():
    M, a, b, c = 3.0, 1.0, 0.6, 0.3
    quad, vol = quadrature_tensor(None, ((-a / 2, a / 2), (-b / 2, b / 2), (-c / 2, c / 2)))
    assert math.isclose(vol, a * b * c, rel_tol=1e-10)
    # Landau & Lifshitz §32 Problem 2: I_xx = M(b² + c²)/12
    assert np.allclose(core.tensor_box(M, a, b, c), M * quad, rtol=1e-9)
    assert math.isclose(core.tensor_box(M, a, b, c)[0, 0], M * (b * b + c * c) / 12, rel_tol=1e-15)


def test_octahedron_against_quadrature():
    """Exercise 4.9: half-diagonals a, b, c; closed form I_xx = M(b² + c²)/10."""
    M, a, b, c = 1.5, 1.0, 0.8, 0.6
    bounds = ((-a, a), (lambda x: -b * (1 - abs(x) / a), lambda x: b * (1 - abs(x) / a)),
              (lambda x, y: -c * (1 - abs(x) / a - abs(y) / b),
               lambda x, y: c * (1 - abs(x) / a - abs(y) / b)))
    quad, vol = quadrature_tensor(None, bounds)
    assert math.isclose(vol, 4 * a * b * c / 3, rel_tol=1e-8)
    assert np.allclose(core.tensor_octahedron(M, a, b, c), M * quad, rtol=1e-7)


def test_points_parallel_axis_and_principal_axes():
    rng = np.random.default_rng(3)
    m = rng.uniform(0.5, 2.0, 6)
    r = rng.normal(size=(6, 3))
    cm = core.centre_of_mass(m, r)
    I_cm = core.tensor_points(m, r)
    P = np.array([0.3, -1.0, 2.0])
    # (8.49) against the direct sum about P
    assert np.allclose(core.parallel_axis(I_cm, m.sum(), P - cm), core.tensor_points(m, r, about=P),
                       atol=1e-13)
    moments, axes = core.principal_axes(I_cm)
    assert np.all(np.diff(moments) >= 0)
    assert math.isclose(np.linalg.det(axes), 1.0, abs_tol=1e-12)
    assert np.allclose(axes.T @ I_cm @ axes, np.diag(moments), atol=1e-12)
    # a rotated box: diagonalization recovers the closed-form moments and the turned axes
    R = euler_matrix(0.4, 1.0, -0.3)
    box = core.tensor_box(1.0, 1.0, 2.0, 3.0)
    mom, ax = core.principal_axes(core.rotate_tensor(box, R))
    assert np.allclose(mom, np.sort(np.diag(box)), rtol=1e-13)
    # principal axis k is the body axis of the k-th smallest moment, turned by R
    assert np.allclose(np.abs(ax.T @ R[:, np.argsort(np.diag(box))]), np.eye(3), atol=1e-12)


def test_axis_stability_verdicts_and_rate():
    I1, I2, I3 = 1.0, 2.0, 4.0
    st = core.axis_stability([I2, I3, I1], spin=3.0)  # any order
    assert [s["verdict"] for s in st] == ["unstable", "stable", "stable"]
    # (10.14): γ = Ω √((I2 − I1)(I3 − I2)/(I1 I3))
    assert math.isclose(st[0]["growth_rate"], 3.0 * math.sqrt((I2 - I1) * (I3 - I2) / (I1 * I3)),
                        rel_tol=1e-14)
    # stable axes wobble at Ω √((I1 − I2)(I1 − I3)/(I2 I3)) (Landau §37 problem 1)
    assert math.isclose(st[2]["oscillation_frequency"],
                        3.0 * math.sqrt((I2 - I1) * (I3 - I1) / (I2 * I3)), rel_tol=1e-14)
    sym = core.axis_stability([1.0, 1.0, 2.0])
    assert [s["verdict"] for s in sym] == ["marginal", "marginal", "stable"]
    assert core.triangle_violation([1.0, 1.0, 2.5]) == 2
    assert core.triangle_violation([1.0, 1.0, 2.0]) is None  # a flat lamina is allowed


def test_inertia_scene_end_to_end(tmp_path, write_config, cli):
    cfg = write_config("oct", """
        kind = "inertia"
        [shape]
        type = "octahedron"
        mass = 1.0
        a = 1.0
        b = 0.8
        c = 0.6
        euler_angles = [0.3, 0.5, 0.2]
        about = [0.0, 0.0, 1.0]
        """)
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    with h5py.File(tmp_path / "o" / "oct" / "run.h5") as f:
        a = f["analysis"]
        assert "runs" not in f or len(f["runs"]) == 0
        moments = a["principal_moments"][()]
        assert np.allclose(moments, np.sort([0.1 * (0.64 + 0.36), 0.1 * (1 + 0.36),
                                             0.1 * (1 + 0.64)]), rtol=1e-13)
        axes = a["principal_axes"][()]
        assert np.allclose(axes.T @ a["tensor"][()] @ axes, np.diag(moments), atol=1e-14)
        assert a["axis_stability"]["axis_2"].attrs["verdict"] == "unstable"
        assert "parallel_axis" in a
        # the inertia ellipsoid Σ I_k x_k² = 1 (x_k along the principal axes), from the archive
        surface = a["inertia_ellipsoid/surface"][()]
        x = surface @ axes
        assert np.allclose(np.sum(moments * x**2, axis=-1), 1.0, rtol=1e-13)
        assert np.allclose(a["inertia_ellipsoid/semi_axes"][()], 1 / np.sqrt(moments),
                           rtol=1e-15)
        closed = a["closed_form"]
        assert closed.attrs["max_relative_difference"] < 1e-14
        assert "exercise 4.9" in closed.attrs["source"]
    html = (tmp_path / "o" / "oct" / "report.html").read_text()
    assert "Parallel-axis shift" in html


@pytest.mark.parametrize("shape, key", [
    ('type = "cone"\nmass = -1.0\nradius = 1.0\nheight = 1.0', "shape.mass"),
    ('type = "box"\nmass = 1.0\na = 1.0\nb = 0.0\nc = 1.0', "shape.b"),
    ('type = "points"\nmasses = [1.0, 2.0]\npositions = [[0.0, 0.0, 0.0]]', "shape.positions"),
])
def test_inertia_bad_input_names_the_key(tmp_path, write_config, cli, shape, key):
    cfg = write_config("bad", 'kind = "inertia"\n[shape]\n' + shape + "\n")
    code, out, err = cli("validate", cfg)
    assert code == 2
    assert key in out + err
