"""The kinetic energy of a moving rigid body split at its centre of mass, lecture notes
(8.38)–(8.42): T = ½ M Ṙ² + ½ ω·I ω, checked on the cone's point masses against the
closed-form moments, and on the archive of the cone struck at its apex."""

from __future__ import annotations

import math

import h5py
import numpy as np

from reportgen.kinds.inertia.config import Cone
from reportgen.kinds.rigid_body.energy_split import kinetic_energy_split, sample_indices
from reportgen.kinds.rigid_body.impulse import rotation_matrices

M, RADIUS, HEIGHT = 1.0, 0.5, 2.0
# Landau & Lifshitz §32 problem 2(c), about the centre of mass (3h/4 below the apex):
# I⊥ = 3M(R² + h²/4)/20, I3 = 3MR²/10
I_PERP = 3 * M * (RADIUS**2 + HEIGHT**2 / 4) / 20
MOMENTS = np.array([I_PERP, I_PERP, 3 * M * RADIUS**2 / 10])


CONE_STRUCK = f"""
kind = "rigid_body"
title = "cone struck at its apex"

[shape]
type = "cone"
mass = {M}
radius = {RADIUS}
height = {HEIGHT}

[initial]
omega = [0.0, 0.0, 20.0]

[impulse]
P = [0.1, 0.0, 0.0]
at = "apex"

[run]
t_end = 2.0
samples = 801
study = false
"""


def _cone_points():
    cone = Cone(type="cone", mass=M, radius=RADIUS, height=HEIGHT)
    m, b, _ = cone.mass_elements()
    return m, b


def _state(n=7, seed=3):
    """Seeded body-frame ω and unit quaternions at n samples."""
    rng = np.random.default_rng(seed)
    omega = rng.normal(scale=5.0, size=(n, 3))
    q = rng.normal(size=(n, 4))
    return np.linspace(0.0, 3.0, n), omega, rotation_matrices(q / np.linalg.norm(q, axis=1,
                                                                                 keepdims=True))


def test_the_split_holds_on_the_cone_point_masses_to_rounding():
    m, b = _cone_points()
    t, omega, R = _state()
    V = np.array([0.3, -0.2, 0.7])
    e = kinetic_energy_split(t, omega, R, MOMENTS, mass=M, cm_velocity=V, masses=m,
                             positions=b, count=len(t))
    closed = 0.5 * M * float(V @ V) + 0.5 * np.einsum("ni,i,ni->n", omega, MOMENTS, omega)
    assert np.allclose(e["kinetic_split"], closed, rtol=1e-15, atol=0)
    # Σ ½ m_A |Ṙ + ω × x_A|² from the 128 points equals ½ M Ṙ² + ½ ω·I ω (8.42)
    assert np.max(np.abs(e["kinetic_points"] - closed) / closed) < 1e-13
    assert e["max_relative_error"] < 1e-13
    # (8.40): the quadrature is centred on the closed-form centre of mass
    assert np.max(e["first_moment"]) < 1e-14 * e["first_moment_scale"]
    assert np.max(np.abs(e["cross_term"])) < 1e-13 * float(np.min(closed))
    assert e["nodes"] == len(m) and math.isclose(float(np.sum(m)), M, rel_tol=1e-14)


def test_points_measured_from_the_apex_break_the_split_by_the_cross_term():
    """Offsets taken from the apex (Σ m x ≠ 0, (8.40) false): the cross term of (8.41) is
    M Ṙ·(ω × R a), a the centre of mass from the apex, and the point sum no longer equals
    ½ M Ṙ² + ½ ω·I_cm ω — so a wrong split would fail the test above."""
    m, b = _cone_points()
    apex = np.array([0.0, 0.0, 0.75 * HEIGHT])
    t, omega, R = _state()
    V = np.array([0.3, -0.2, 0.7])
    e = kinetic_energy_split(t, omega, R, MOMENTS, mass=M, cm_velocity=V, masses=m,
                             positions=b - apex, count=len(t))
    a = -apex  # the centre of mass seen from the apex, body frame
    w_space = np.einsum("nij,nj->ni", R, omega)
    cross = M * np.einsum("i,ni->n", V, np.cross(w_space, np.einsum("nij,j->ni", R, a)))
    assert np.allclose(e["cross_term"], cross, rtol=1e-12, atol=1e-14)
    assert np.allclose(e["first_moment"], M * np.linalg.norm(a), rtol=1e-13)
    # about the apex: T = ½ M V² + M V·(ω × a) + ½ ω·I_apex ω (parallel axes: + M a²)
    I_apex = MOMENTS + M * np.array([a[2] ** 2, a[2] ** 2, 0.0])
    expect = (0.5 * M * float(V @ V) + cross
              + 0.5 * np.einsum("ni,i,ni->n", omega, I_apex, omega))
    assert np.allclose(e["kinetic_points"], expect, rtol=1e-13)
    assert e["max_relative_error"] > 1e-3


def test_sample_indices_take_both_ends():
    assert list(sample_indices(3001)) == [0, 600, 1200, 1800, 2400, 3000]
    assert list(sample_indices(3)) == [0, 1, 2]


def test_struck_cone_archive_stores_the_split(tmp_path, write_config, cli):
    """The cone struck at its apex (textbook ex. 4.6(c)): the split is archived with its
    units and shown in the blow's section."""
    cfg = write_config("cone", CONE_STRUCK)
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    with h5py.File(tmp_path / "o" / "cone" / "run.h5") as f:
        s = f["analysis/energy_split"]
        assert s["kinetic_points"].attrs["units"] == "J"
        assert "cross term" in s["cross_term"].attrs["long_name"]
        t = s["times"][()]
        assert t[0] == 0.0 and t[-1] == 2.0 and len(t) == 6
        V = 0.1 / M
        # ω after the blow: (0, 0.15/I⊥, 20); ω·I ω is conserved
        w = np.array([0.0, 0.15 / I_PERP, 20.0])
        closed = 0.5 * M * V**2 + 0.5 * float(w @ (MOMENTS * w))
        assert np.allclose(s["kinetic_points"][()], closed, rtol=1e-9)
        assert math.isclose(s.attrs["translational"], 0.5 * M * V**2, rel_tol=1e-14)
        assert s.attrs["max_relative_error"] < 1e-13
        assert np.max(np.abs(s["cross_term"][()])) < 1e-13 * closed
    html = (tmp_path / "o" / "cone" / "report.html").read_text()
    assert "notes (8.38)–(8.42)" in html and "point masses" in html
