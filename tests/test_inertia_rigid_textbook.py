"""Textbook ex. 4.6 and 4.9 in the ``inertia`` and ``rigid_body`` kinds: the cone's centre
of mass 3h/4 below the apex by quadrature, the octahedron on an a × b rectangle (closed
form against its split into tetrahedra, stable and unstable spin axes), and the cone
struck at its apex (the centre of mass drifting at P/M, the apex's path)."""

from __future__ import annotations

import itertools
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from reportgen.core import inertia as core
from reportgen.kinds.rigid_body.impulse import impulse_motion

REPO = Path(__file__).resolve().parent.parent


# --------------------------------------------------------------------- closed forms
def tetrahedron_moments(v) -> tuple[float, np.ndarray]:
    """Volume and ∫ x_i x_j dV of the tetrahedron with vertices v (4, 3): the exact
    polynomial formula ∫ x_i x_j dV = V/20 (Σ_k v_ki v_kj + S_i S_j), S = Σ_k v_k
    (Tonon, J. Math. Stat. 1 (2004) 8, eq. 2; a tetrahedron's quadratic moments)."""
    v = np.asarray(v, dtype=float)
    vol = abs(np.linalg.det(v[1:] - v[0])) / 6.0
    S = v.sum(axis=0)
    return vol, vol / 20.0 * (v.T @ v + np.outer(S, S))


def tensor_from_tetrahedra(mass, tetrahedra):
    vol, second = 0.0, np.zeros((3, 3))
    for tet in tetrahedra:
        dv, m2 = tetrahedron_moments(tet)
        vol += dv
        second += m2
    second *= mass / vol
    return vol, np.trace(second) * np.eye(3) - second


def rectangle_octahedron_tetrahedra(a, b, h):
    """The double pyramid over the a × b rectangle, apexes (0, 0, ±h), as 8 tetrahedra:
    centre, two neighbouring corners of the rectangle, one apex."""
    corners = [(a / 2, b / 2, 0), (-a / 2, b / 2, 0), (-a / 2, -b / 2, 0), (a / 2, -b / 2, 0)]
    out = []
    for i, apex in itertools.product(range(4), ((0, 0, h), (0, 0, -h))):
        out.append([(0, 0, 0), corners[i], corners[(i + 1) % 4], apex])
    return out


@pytest.mark.parametrize("a, b, h", [(1.2, 0.8, 0.4), (0.3, 2.0, 1.1), (1.0, 1.0, 3.0)])
def test_rectangle_octahedron_against_tetrahedra(a, b, h):
    M = 2.5
    vol, tensor = tensor_from_tetrahedra(M, rectangle_octahedron_tetrahedra(a, b, h))
    assert math.isclose(vol, core.octahedron_rectangle_volume(a, b, h), rel_tol=1e-14)
    assert math.isclose(vol, 2 * a * b * h / 3, rel_tol=1e-14)  # two pyramids, base ab
    closed = core.tensor_octahedron_rectangle(M, a, b, h)
    assert np.allclose(tensor, closed, rtol=1e-13, atol=1e-15 * np.max(closed))


def test_regular_octahedron_is_isotropic():
    """A square equator of side s with apexes at s/√2 is the regular octahedron of edge s:
    every axis has I = M s²/10 (its tensor is a multiple of 1 by its cubic symmetry)."""
    s, M = 0.7, 3.0
    T = core.tensor_octahedron_rectangle(M, s, s, s / math.sqrt(2))
    assert np.allclose(T, M * s * s / 10 * np.eye(3), rtol=1e-14)
    # and it is the rhombic octahedron |x| + |y| + |z| ≤ s/√2 turned by 45° about z
    assert np.allclose(T, core.tensor_octahedron(M, *(3 * [s / math.sqrt(2)])), rtol=1e-14)


@pytest.mark.parametrize("make, closed, volume", [
    (lambda: core.quadrature_cone(2.0, 0.7, 1.6), core.tensor_cone(2.0, 0.7, 1.6),
     math.pi * 0.49 * 1.6 / 3),
    (lambda: core.quadrature_cylinder(2.0, 0.7, 1.6), core.tensor_cylinder(2.0, 0.7, 1.6),
     math.pi * 0.49 * 1.6),
    (lambda: core.quadrature_box(2.0, 1.0, 0.6, 0.3), core.tensor_box(2.0, 1.0, 0.6, 0.3),
     0.18),
    (lambda: core.quadrature_ellipsoid(2.0, 1.0, 0.6, 0.3),
     core.tensor_ellipsoid(2.0, 1.0, 0.6, 0.3), 4 * math.pi * 0.18 / 3),
    (lambda: core.quadrature_octahedron(2.0, 1.0, 0.8, 0.6),
     core.tensor_octahedron(2.0, 1.0, 0.8, 0.6), 4 * 0.48 / 3),
    (lambda: core.quadrature_octahedron_rectangle(2.0, 1.2, 0.8, 0.4),
     tensor_from_tetrahedra(2.0, rectangle_octahedron_tetrahedra(1.2, 0.8, 0.4))[1],
     2 * 1.2 * 0.8 * 0.4 / 3),
])
def test_quadratures_against_closed_forms(make, closed, volume):
    """Each quadrature integrates degree ≤ 2 exactly: volume (elementary formulas), the
    tensor (Landau & Lifshitz §32 Problem 2; the tetrahedra above) at round-off."""
    m, r, vol = make()
    assert math.isclose(vol, volume, rel_tol=1e-14)
    assert math.isclose(m.sum(), 2.0, rel_tol=1e-15)
    assert np.allclose(core.tensor_points(m, r), closed, rtol=0, atol=1e-14 * np.max(closed))


def test_cone_centre_of_mass_three_quarters_below_the_apex():
    """Textbook ex. 4.6: slices πR²s²/h² at depth s, s̄ = ∫ s³ / ∫ s² = 3h/4."""
    for h in (0.3, 1.6, 5.0):
        m, r, _ = core.quadrature_cone(1.0, 0.4, h)  # apex at the origin, axis along −z
        cm = core.centre_of_mass(m, r)
        assert math.isclose(-cm[2], 3 * h / 4, rel_tol=1e-14)
        assert np.hypot(cm[0], cm[1]) < 1e-15 * h


# ------------------------------------------------------------------- inertia scenes
def test_shipped_octahedron_moments_and_stable_axes(shipped_archives):
    """Textbook ex. 4.9 (b): stable about the axes of smallest and largest moment, unstable
    about the intermediate one (notes (10.12)–(10.14)), each named by the shape's axis."""
    cfg = tomllib.loads((REPO / "configs/inertia_octahedron_rectangle.toml").read_text())
    shape = cfg["shape"]
    assert shape["type"] == "octahedron" and shape["equator"] == "rectangle"
    M, a, b, h = (shape[k] for k in ("mass", "a", "b", "h"))
    own = np.array([M * (b * b / 20 + h * h / 10), M * (a * a / 20 + h * h / 10),
                    M * (a * a + b * b) / 20])  # derived by slices, checked above
    data = shipped_archives("inertia_octahedron_rectangle")
    an = data.analysis
    order = np.argsort(own)
    assert len(set(np.round(own / own.max(), 9))) == 3  # three distinct moments
    assert np.allclose(an["principal_moments"], own[order], rtol=1e-14)
    st = [an["axis_stability"][f"axis_{k + 1}"] for k in range(3)]
    assert [s["verdict"] for s in st] == ["stable", "unstable", "stable"]
    for k in range(3):  # principal axis k lies along the shape's axis of the k-th moment
        assert st[k]["shape_axis"].startswith("xyz"[order[k]] + ",")
        assert abs(an["principal_axes"][order[k], k]) == pytest.approx(1.0, abs=1e-14)
    q = an["quadrature"]
    assert q["max_relative_difference"] < 1e-14
    assert math.isclose(q["volume"], 2 * a * b * h / 3, rel_tol=1e-14)
    names = [c.quantity for c in data.checks]
    assert any("by quadrature" in n for n in names)


def test_shipped_cone_centre_of_mass_by_quadrature(shipped_archives):
    cfg = tomllib.loads((REPO / "configs/inertia_cone.toml").read_text())
    h = cfg["shape"]["height"]
    data = shipped_archives("inertia_cone")
    q = data.analysis["quadrature"]
    assert math.isclose(q["apex_distance"], 3 * h / 4, rel_tol=1e-14)
    assert q["apex_distance_closed"] == 3 * h / 4
    check = next(c for c in data.checks if c.quantity.startswith("centre of mass below"))
    assert check.rel_error < 1e-14
    # a cone's transverse principal axes are any two ⊥ the symmetry axis
    words = [data.analysis["axis_stability"][f"axis_{k}"]["shape_axis"] for k in (1, 2, 3)]
    assert words[0].startswith("z,") and words[1] == words[2] == "any axis ⊥ z"


@pytest.mark.parametrize("text, key", [
    ('equator = "rectangle"\na = 1.0\nb = 1.0\nc = 1.0', "shape.h"),
    ('a = 1.0\nb = 1.0\nc = 1.0\nh = 1.0', "shape.h"),
    ('equator = "rectangle"\na = 1.0\nb = 1.0', "shape.h"),
    ('a = 1.0\nb = 1.0', "shape.c"),
])
def test_octahedron_sizes_name_the_key(write_config, cli, text, key):
    cfg = write_config("bad", 'kind = "inertia"\n[shape]\ntype = "octahedron"\nmass = 1.0\n'
                       + text + "\n")
    code, out, err = cli("validate", cfg)
    assert code == 2
    assert key in out + err


# --------------------------------------------------------------------- the impulse
def test_cone_impulse_centre_of_mass_and_apex(shipped_archives):
    """Textbook ex. 4.6(c): after P at the apex p the centre of mass moves at P/M; the apex
    starts at V + Δω × p = P/M + P p²/I⊥ (P ⊥ p; Δω = (p × P)/I⊥)."""
    data = shipped_archives("rigid_body_cone_impulse")
    imp = data.analysis["impulse"]
    M = 1.0
    R, h = 0.5, 2.0  # the preset's cone
    I_perp = 3 * M * (R * R + h * h / 4) / 20  # Landau & Lifshitz §32 Problem 2
    P = np.asarray(data.config["impulse"]["P"], dtype=float)
    p = 3 * h / 4
    assert np.allclose(imp["point"], [0, 0, p], rtol=1e-15)
    assert np.allclose(imp["cm_velocity"], P / M, rtol=1e-15)
    assert np.allclose(imp["point_velocity_initial"], P / M + P * p * p / I_perp, rtol=1e-14)
    V = float(np.linalg.norm(P / M))
    assert imp["cm_velocity_run_max_error"] < 1e-14 * V
    assert imp["cm_path_run_max_error"] < 1e-14 * p
    # the apex at height p cos θ along L for ever: θ the tilt of the figure axis from L
    L = I_perp * imp["delta_omega"] + np.array([0, 0, 0.3 * M * R * R * 20.0])
    Lhat = L / np.linalg.norm(L)
    along = (imp["point_path"] - imp["cm_path"]) @ Lhat
    assert np.allclose(along, p * Lhat[2], rtol=1e-9)
    assert imp["point_path_max_error"] < 1e-9 * p


def _free_symmetric_run(moments, omega0, q0, t):
    from reportgen.core.integrators import integrate
    from reportgen.core.models import rigid_body as rb

    y0 = np.concatenate([omega0, q0])
    return integrate(rb.model(*moments), y0, t, method="dop853", rtol=1e-12, atol=1e-14).y


def test_symmetric_closed_form_path_of_an_off_axis_point():
    """The closed form R(t) = Rot(L̂, |L|t/I⊥) R0 Rot(e3, Ωt) (Landau & Lifshitz §33) for a
    point off the figure axis and a turned start, against the integrated attitude."""
    from reportgen.core.models import rigid_body as rb
    from reportgen.core.rotations import euler_to_quat

    I = np.array([0.4, 0.4, 0.15])
    w = np.array([0.7, -0.3, 5.0])
    q0 = euler_to_quat(0.3, 0.8, -0.5)
    t = np.linspace(0.0, 4.0, 801)
    y = _free_symmetric_run(I, w, q0, t)
    sym = rb.symmetric_precession_rate(I, w)
    out = impulse_motion(t, y[:, :3], y[:, 3:7], I, P=[0.2, 0.1, -0.05],
                         point=[0.3, -0.2, 0.5], omega_before=w, mass=2.0, symmetric=sym)
    assert out["point_path_max_error"] < 1e-8


def test_wrong_centre_of_mass_shows_in_the_run_check():
    """The check can fail: point masses whose centre of mass is off by d give a centre of
    mass that leaves the line V t by |d| and a velocity off by up to |ω||d|."""
    t = np.linspace(0.0, 1.0, 201)
    I = np.array([1.0, 1.0, 0.5])
    w = np.array([0.0, 0.0, 3.0])
    quat = np.column_stack([np.cos(1.5 * t), 0 * t, 0 * t, np.sin(1.5 * t)])  # ω3 t about z
    m, r, _ = core.quadrature_box(1.0, 1.0, 1.0, 1.0)
    d = np.array([1e-3, 0.0, 0.0])
    good = impulse_motion(t, np.tile(w, (len(t), 1)), quat, I, P=[0.1, 0, 0], point=[0, 0, 0.5],
                          omega_before=w, mass=1.0, elements=(m, r))
    bad = impulse_motion(t, np.tile(w, (len(t), 1)), quat, I, P=[0.1, 0, 0], point=[0, 0, 0.5],
                         omega_before=w, mass=1.0, elements=(m, r + d))
    assert good["cm_path_run_max_error"] < 1e-15
    assert bad["cm_path_run_max_error"] == pytest.approx(1e-3, rel=1e-12)
    assert bad["cm_velocity_run_max_error"] == pytest.approx(3.0 * 1e-3, rel=1e-9)
