"""Poinsot's geometry of the free rigid body: polhodes on the inertia ellipsoid, the invariable
plane, the herpolhode (Goldstein 3rd ed. §5.6; Landau & Lifshitz §33, §37; notes (10.15)–(10.17))."""

from __future__ import annotations

import math

import h5py
import numpy as np
import pytest

from reportgen.core.integrators import integrate
from reportgen.core.models import rigid_body as core
from reportgen.core.models import rigid_body_poinsot as poinsot
from reportgen.core.rotations import quat_to_matrix

ATTITUDE = np.array([0.9, 0.1, -0.3, 0.2]) / math.sqrt(0.95)  # a generic start, not identity


def run(I, w, t_end=10.0, samples=1001, rtol=1e-12):
    I, w = np.asarray(I, float), np.asarray(w, float)
    t = np.linspace(0.0, t_end, samples)
    sol = integrate(core.model(*I), np.concatenate([w, ATTITUDE]), t, method="dop853",
                    rtol=rtol, atol=1e-14)
    return t, sol.y


@pytest.mark.parametrize("I, curves, seps", [
    ((1.0, 2.0, 3.0), 16, 2), ((3.0, 1.0, 2.0), 16, 2), ((2.0, 3.0, 1.0), 16, 2),
    ((1.0, 1.0, 1.5), 8, 0), ((0.075, 0.1875, 0.1875), 8, 0), ((2.0, 2.0, 2.0), 0, 0)])
def test_family_curves_lie_on_both_quadrics(I, curves, seps):
    """Every polhode of the family satisfies ω·Iω = 2T and ω·I²ω = L² (its own rung of the
    ladder) to 1e-12; the rungs lie strictly between 2T·I_min and 2T·I_max, off 2T·I_mid;
    the separatrices have L² = 2T·I_mid and pass through the intermediate axis, where a
    steady rotation ω = √(2T/I_mid) e_mid has exactly that L² (Landau & Lifshitz §37)."""
    I = np.array(I)
    w0 = np.array([0.4, -1.1, 0.7])
    T2 = float(np.sum(I * w0**2))
    p = poinsot.polhodes_on_ellipsoid(I, w0)
    assert p["family"].shape[0] == curves and p["separatrices"].shape[0] == seps
    assert math.isclose(p["twice_energy"], T2, rel_tol=1e-15)
    fam, L2 = p["family"], p["family_L_squared"]
    if curves:
        assert np.max(np.abs(np.sum(I * fam**2, axis=2) / T2 - 1.0)) < 1e-12
        assert np.max(np.abs(np.sum((I * fam) ** 2, axis=2) / L2[:, None] - 1.0)) < 1e-12
        Is = np.sort(I)
        assert np.all((L2 > T2 * Is[0]) & (L2 < T2 * Is[2]))
        assert np.all(np.abs(L2 / (T2 * Is[1]) - 1.0) > 1e-3)
        # closed curves, each on one side of the axis it circles (x_a never changes sign)
        assert np.allclose(fam[:, 0], fam[:, -1], atol=1e-12)
        for c in fam:
            a = int(np.argmax(np.min(np.abs(c), axis=0)))
            assert np.all(np.sign(c[:, a]) == np.sign(c[0, a]))
    for c in p["separatrices"]:
        m = int(np.argsort(I)[1])
        assert np.max(np.abs(np.sum(I * c**2, axis=1) / T2 - 1.0)) < 1e-12
        assert np.max(np.abs(np.sum((I * c) ** 2, axis=1) / p["separatrix_L_squared"] - 1.0)) \
            < 1e-12
        assert math.isclose(p["separatrix_L_squared"], T2 * I[m], rel_tol=1e-15)
        axis = np.zeros(3)
        axis[m] = math.sqrt(T2 / I[m])
        assert np.min(np.linalg.norm(c - axis, axis=1)) < 1e-12
    # the surface is the ellipsoid ω·Iω = 2T with semi-axes √(2T/I_k)
    assert np.allclose(p["semi_axes"], np.sqrt(T2 / I), rtol=1e-15)
    assert np.max(np.abs(np.sum(I * p["surface"] ** 2, axis=-1) / T2 - 1.0)) < 1e-12


@pytest.mark.parametrize("I, w, axis", [
    ((1.0, 2.0, 3.0), (0.01, 2.0, 0.01), 3),   # Dzhanibekov: just outside the separatrix
    ((1.0, 2.0, 3.0), (2.0, 0.5, 0.3), 1),     # L² < 2T·I2: about the smallest moment
    ((3.0, 1.0, 2.0), (0.3, 1.0, 2.0), None)])
def test_integrated_omega_stays_on_both_surfaces(I, w, axis):
    """The integrated ω (rtol 1e-12) stays on ω·Iω = 2T and ω·I²ω = L² of its start to a
    few rtol over the run (the two conserved quantities, (10.17)); the polhode it traces
    circles the axis named by the sign of L² − 2T·I_mid."""
    I = np.array(I)
    t, y = run(I, w, t_end=40.0, samples=2001)
    p = poinsot.polhodes_on_ellipsoid(I, w)
    omega = y[:, :3]
    assert np.max(np.abs(np.sum(I * omega**2, axis=1) / p["twice_energy"] - 1.0)) < 2e-11
    assert np.max(np.abs(np.sum((I * omega) ** 2, axis=1) / p["L_squared"] - 1.0)) < 2e-11
    circled = int(p["circled_axis"])
    if axis is not None:
        assert circled == axis
    # the component along the circled axis never changes sign: ω goes round that axis
    assert np.all(np.sign(omega[:, circled - 1]) == np.sign(omega[0, circled - 1]))


@pytest.mark.parametrize("I, w", [((1.0, 2.0, 3.0), (0.01, 2.0, 0.01)),
                                  ((1.0, 2.0, 3.0), (1.0, 0.5, 1.5)),
                                  ((0.6, 0.9, 0.5), (4.0, 0.5, 0.5))])
def test_tip_of_x_stays_on_the_invariable_plane_and_the_ellipsoid_touches_it(I, w):
    """Poinsot (Goldstein §5.6): x = ω/√(2T) in space has x·L/|L| = √(2T)/|L| for all t,
    to the integration error; at the drawn instant the ellipsoid x·Ix = 1 touches the plane
    there (contact point on both, the ellipsoid's normal Ix along L) and the polhode on the
    body passes through it."""
    I, w = np.array(I), np.array(w)
    t, y = run(I, w)
    c = poinsot.poinsot_construction(y[:, :3], y[:, 3:7], I)
    T2, L = float(np.sum(I * w**2)), float(np.linalg.norm(I * w))
    assert math.isclose(c["plane_height"], -math.sqrt(T2) / L, rel_tol=1e-14)
    # the basis: orthonormal, right-handed, e3 = −L/|L| with L the space-frame momentum
    B = c["basis"]
    assert np.allclose(B @ B.T, np.eye(3), atol=1e-15) and math.isclose(np.linalg.det(B), 1.0)
    L_space = quat_to_matrix(ATTITUDE) @ (I * w)
    assert np.allclose(B[2], -L_space / L, atol=1e-15)
    her = c["herpolhode"]
    assert np.max(np.abs(her[:, 2] - c["plane_height"])) < 1e-11 * abs(c["plane_height"])
    # independent: the space-frame ω from the attitude, projected on L, is 2T/|L|
    R = quat_to_matrix(y[:, 3:7])
    w_space = np.einsum("nij,nj->ni", R, y[:, :3])
    assert np.allclose(w_space @ (L_space / L), T2 / L, rtol=1e-11, atol=0.0)
    assert np.allclose(her, (w_space / math.sqrt(T2)) @ B.T, atol=1e-14)
    # the drawn instant (the last): the ellipsoid and the polhode at that attitude
    k = c["contact_index"]
    assert k == len(t) - 1
    P = B @ R[k]
    body = c["polhode"] @ P  # back to body components
    assert np.max(np.abs(np.sum(I * body**2, axis=1) - 1.0)) < 2e-11
    assert np.allclose(c["polhode"][k], her[k], atol=1e-14)
    normal = P @ (I * body[k])
    assert np.allclose(normal / np.linalg.norm(normal), [0.0, 0.0, -1.0], atol=1e-11)
    surf_body = c["surface"] @ P
    assert np.max(np.abs(np.sum(I * surf_body**2, axis=-1) - 1.0)) < 1e-12
    assert np.all(c["surface"][..., 2] >= c["plane_height"] - 1e-12)  # resting on the plane
    assert np.allclose(c["axes"], P / np.sqrt(I), atol=1e-15)


@pytest.mark.parametrize("I, w", [((1.0, 1.0, 1.5), (0.3, 0.0, 2.0)),
                                  ((0.075, 0.1875, 0.1875), (20.0, 0.8, -0.3)),
                                  ((2.0, 1.0, 2.0), (0.2, 1.5, -0.4))])
def test_symmetric_herpolhode_is_a_circle_of_the_closed_form_radius(I, w):
    """Symmetric body (Landau & Lifshitz §33): L = I⊥ω + (I_s − I⊥) ω_s e_s, so the part of ω
    normal to L is (I_s − I⊥) ω_s (e_s)⊥/I⊥, |(e_s)⊥| = sin θ = I⊥ ω⊥/|L|, and e_s
    precesses about L at |L|/I⊥: the herpolhode is a circle about the foot of L of radius
    |I_s − I⊥| |ω_s| ω⊥/(|L| √(2T)) in units of x = ω/√(2T), run at −|L|/I⊥ in the
    picture frame (whose e3 is −L/|L|)."""
    I, w = np.array(I), np.array(w)
    t, y = run(I, w)
    axis, _ = core.symmetric_precession_rate(I, w)
    s, b, c3 = axis, (axis + 1) % 3, (axis + 2) % 3
    T2, L = float(np.sum(I * w**2)), float(np.linalg.norm(I * w))
    r = abs(I[s] - I[b]) * abs(w[s]) * math.hypot(w[b], w[c3]) / (L * math.sqrt(T2))
    assert math.isclose(poinsot.symmetric_herpolhode_radius(w, I, axis), r, rel_tol=1e-14)
    her = poinsot.poinsot_construction(y[:, :3], y[:, 3:7], I)["herpolhode"]
    rho = np.hypot(her[:, 0], her[:, 1])
    assert np.max(np.abs(rho - r)) < 1e-10 * r
    rate = np.polyfit(t, np.unwrap(np.arctan2(her[:, 1], her[:, 0])), 1)[0]
    assert math.isclose(rate, -L / I[b], rel_tol=1e-10)


def test_asymmetric_herpolhode_is_not_a_circle():
    """Control for the test above: for three distinct moments the distance from the foot of L
    varies (the herpolhode oscillates between two circles, Goldstein §5.6)."""
    t, y = run((1.0, 2.0, 3.0), (1.0, 0.5, 1.5))
    her = poinsot.poinsot_construction(y[:, :3], y[:, 3:7], np.array([1.0, 2.0, 3.0]))
    rho = np.hypot(her["herpolhode"][:, 0], her["herpolhode"][:, 1])
    assert np.ptp(rho) > 0.1 * np.max(rho)


RIGID = """
kind = "rigid_body"
[params]
I1 = {I1}
I2 = {I2}
I3 = {I3}
[initial]
omega = {omega}
attitude = {attitude}
[run]
t_end = 20.0
samples = 801
study = false
{report}
"""


def rigid(I=(1.0, 2.0, 3.0), omega="[0.01, 2.0, 0.01]", report=""):
    attitude = "[" + ", ".join(repr(float(q)) for q in ATTITUDE) + "]"
    return RIGID.format(I1=I[0], I2=I[1], I3=I[2], omega=omega, attitude=attitude,
                        report=report)


def test_scene_archives_and_shows_the_poinsot_geometry(tmp_path, write_config, cli):
    """The archive holds every curve the two sections draw, the run's ω stays on the stored
    ellipsoid and L² surface, the tip of x on the stored plane; the report shows both
    sections, one titled with the inertia ellipsoid, and keeps the L-sphere view."""
    code, out, err = cli("run", write_config("dz", rigid()), "--out", tmp_path / "o",
                         "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    with h5py.File(tmp_path / "o" / "dz" / "run.h5") as f:
        y = f["runs/main/y"][()]
        rtol = f["runs/main"].attrs["rtol"]
        a = f["analysis"]
        I = a["principal_moments"][()]
        p = a["polhode_ellipsoid"]
        T2, L2 = p.attrs["twice_energy"], p.attrs["L_squared"]
        assert math.isclose(T2, a.attrs["twice_energy"], rel_tol=1e-15)
        omega = y[:, :3]
        assert np.max(np.abs(np.sum(I * omega**2, axis=1) / T2 - 1.0)) < 20 * rtol
        assert np.max(np.abs(np.sum((I * omega) ** 2, axis=1) / L2 - 1.0)) < 20 * rtol
        assert p["family"].shape == (16, 121, 3) and p["separatrices"].shape == (2, 121, 3)
        assert p.attrs["circled_axis"] == 3 and 0 < p.attrs["separatrix_offset"] < 1e-4
        c = a["poinsot"]
        her = c["herpolhode"][()]
        assert her.shape == (801, 3) and c["polhode"].shape == (801, 3)
        d = c.attrs["plane_distance"]
        assert math.isclose(d, math.sqrt(T2 / L2), rel_tol=1e-14)
        assert np.max(np.abs(her[:, 2] + d)) == c.attrs["plane_distance_max_error"] < 20 * rtol
        assert "herpolhode" not in a  # the old ω-unit copy is gone: one set of curves
    html = (tmp_path / "o" / "dz" / "report.html").read_text()
    assert "Polhodes on the inertia ellipsoid" in html
    assert "Poinsot&#39;s construction" in html or "Poinsot's construction" in html
    assert "Polhodes on the angular-momentum sphere" in html
    figures = {p.name for p in (tmp_path / "o" / "dz" / "figures").glob("*.svg")}
    assert {"polhode_ellipsoid-polhode_ellipsoid.svg", "herpolhode-poinsot.svg",
            "polhodes-polhodes.svg"} <= figures


def test_symmetric_scene_checks_the_herpolhode_radius(tmp_path, write_config, cli):
    code, out, err = cli("run", write_config("sym", rigid(I=(1.0, 1.0, 1.5),
                                                          omega="[0.3, 0.0, 2.0]")),
                         "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    with h5py.File(tmp_path / "o" / "sym" / "run.h5") as f:
        c = f["analysis/poinsot"]
        # Landau & Lifshitz §33: |I3 − I⊥| ω3 ω⊥ / (|L| √(2T)) with ω⊥ = 0.3, ω3 = 2
        T2, L = 0.09 + 1.5 * 4.0, math.hypot(0.3, 3.0)
        r = 0.5 * 2.0 * 0.3 / (L * math.sqrt(T2))
        assert math.isclose(c.attrs["herpolhode_radius"], r, rel_tol=1e-14)
        her = c["herpolhode"][()]
        assert np.max(np.abs(np.hypot(her[:, 0], her[:, 1]) - r)) < 1e-10 * r
        assert f["analysis/polhode_ellipsoid/separatrices"].shape[0] == 0
    html = (tmp_path / "o" / "sym" / "report.html").read_text()
    assert "herpolhode radius (symmetric body)" in html


def test_poinsot_data_only_when_its_sections_are_shown(tmp_path, write_config, cli):
    """Promise 3: asked for other sections only, the archive holds no Poinsot curves; a
    spherical body (constant ω) gets neither section."""
    text = rigid(report='[report]\nsections = ["omega", "polhodes"]')
    code, out, err = cli("run", write_config("few", text), "--out", tmp_path / "o",
                         "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    with h5py.File(tmp_path / "o" / "few" / "run.h5") as f:
        assert "poinsot" not in f["analysis"] and "polhode_ellipsoid" not in f["analysis"]
    code, out, err = cli("run", write_config("ball", rigid(I=(2.0, 2.0, 2.0))), "--out",
                         tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    with h5py.File(tmp_path / "o" / "ball" / "run.h5") as f:
        assert "poinsot" not in f["analysis"] and "polhode_ellipsoid" not in f["analysis"]
    html = (tmp_path / "o" / "ball" / "report.html").read_text()
    assert "Polhodes on the inertia ellipsoid" not in html
    assert "Poinsot" not in html and "Polhodes on the angular-momentum sphere" not in html
