"""Free rigid body: exact elliptic solution, integration, stability, splitting, the scene."""

from __future__ import annotations

import math
from pathlib import Path

import h5py
import numpy as np
import pytest

from reportgen.core import special
from reportgen.core.integrators import integrate
from reportgen.core.models import rigid_body as core
from reportgen.core.models.rigid_body_splitting import integrate_splitting

REPO = Path(__file__).resolve().parent.parent

# (moments in any order, ω0, expected branch in the sorted frame)
CASES = [
    ((1.0, 2.0, 3.0), (1.0, 0.5, 1.5), "L² > 2E·I2"),
    ((1.0, 2.0, 3.0), (2.0, 0.5, 0.3), "L² < 2E·I2"),
    ((3.0, 1.0, 2.0), (0.3, 1.0, 2.0), None),  # odd/even sorting permutations
    ((2.0, 1.0, 3.0), (0.3, 1.0, 2.0), None),
    ((1.0, 2.0, 3.0), (0.01, 2.0, 0.01), None),  # Dzhanibekov: close to the separatrix
]


def y0_of(w):
    return np.concatenate([np.asarray(w, float), [1.0, 0.0, 0.0, 0.0]])


@pytest.mark.parametrize("I, w, branch", CASES)
def test_exact_solution_solves_euler_equations(I, w, branch):
    """Independent of any integrator: the elliptic ω(t) satisfies (10.5) and ω(0) = ω0."""
    I, w = np.array(I), np.array(w)
    if branch is not None:
        assert core.elliptic_parameters(w, I)["branch"].startswith(branch)
    t = np.linspace(0.0, 7.0, 71)
    h = 1e-5
    wt = core.exact_omega(t, w, I)
    dw = (core.exact_omega(t + h, w, I) - core.exact_omega(t - h, w, I)) / (2 * h)
    rhs = np.column_stack([(I[1] - I[2]) * wt[:, 1] * wt[:, 2] / I[0],
                           (I[2] - I[0]) * wt[:, 2] * wt[:, 0] / I[1],
                           (I[0] - I[1]) * wt[:, 0] * wt[:, 1] / I[2]])
    assert np.allclose(wt[0], w, atol=1e-13)
    assert np.max(np.abs(dw - rhs)) < 1e-8


@pytest.mark.parametrize("I, w, branch", CASES)
def test_integration_matches_exact_at_default_tolerance(I, w, branch):
    """Must show: |ω − ω_exact| ≤ 1e-9 at the default rtol 1e-12, atol 1e-14 (RunConfig)."""
    I = np.array(I)
    t = np.linspace(0.0, 40.0, 2001)
    sol = integrate(core.model(*I), y0_of(w), t, method="dop853", rtol=1e-12, atol=1e-14)
    err = np.max(np.abs(sol.y[:, :3] - core.exact_omega(t, w, I)))
    assert err <= 1e-9
    inv = core.invariants(sol.y, I)
    assert np.ptp(inv["L_squared"]) / inv["L_squared"][0] < 1e-10


def test_symmetric_body_precession_rate():
    """(10.9)–(10.10): ω3 constant, ω1 + iω2 ∝ e^{−iΩt}, Ω = (I1 − I3) ω3 / I1."""
    I = np.array([1.0, 1.0, 1.5])
    w = np.array([0.3, 0.0, 2.0])
    axis, Omega = core.symmetric_precession_rate(I, w)
    assert axis == 2 and math.isclose(Omega, (1.0 - 1.5) * 2.0 / 1.0)
    t = np.linspace(0.0, 20.0, 801)
    sol = integrate(core.model(*I), y0_of(w), t, method="dop853", rtol=1e-12, atol=1e-14)
    phase = np.unwrap(np.arctan2(sol.y[:, 1], sol.y[:, 0]))
    assert math.isclose(-np.polyfit(t, phase, 1)[0], Omega, rel_tol=1e-9)
    assert np.max(np.abs(sol.y[:, 2] - 2.0)) < 1e-12


def test_intermediate_axis_growth_rate():
    """(10.14): a small perturbation about axis 2 grows at Ω√((I2−I1)(I3−I2)/(I1 I3))."""
    I = np.array([1.0, 2.0, 4.0])
    Omega, eps = 1.5, 1e-8
    gamma = Omega * math.sqrt((I[1] - I[0]) * (I[2] - I[1]) / (I[0] * I[2]))
    t = np.linspace(0.0, 6.0, 61)
    # start on the growing eigenvector of the linearization: ω3/ω1 = γ I1 / ((I3 − I2)... )
    m = core.model(*I)
    J = m.jacobian(0.0, np.array([0.0, Omega, 0.0, 1.0, 0.0, 0.0, 0.0]))[:3, :3]
    lam, vec = np.linalg.eig(J)
    k = int(np.argmax(lam.real))
    assert math.isclose(lam[k].real, gamma, rel_tol=1e-12)
    w0 = np.array([0.0, Omega, 0.0]) + eps * vec[:, k].real / np.linalg.norm(vec[:, k].real)
    sol = integrate(m, y0_of(w0), t, method="dop853", rtol=1e-13, atol=1e-20)
    amp = np.hypot(sol.y[:, 0], sol.y[:, 2])
    measured = np.polyfit(t, np.log(amp), 1)[0]
    assert math.isclose(measured, gamma, rel_tol=1e-4)


def test_special_functions_elliptic_identities():
    """DLMF 19.2.10: F(φ + nπ | m) = F(φ | m) + 2nK(m); 22.16.1: am(F(φ | m)) = φ, so
    sn(F) = sin φ, cn(F) = cos φ, dn(F) = √(1 − m sin²φ); m = 0 gives sin, cos, 1."""
    m = 0.7
    K = special.ellipk(m)
    assert special.ellipk(1.0) == math.inf
    for phi in (0.3, 1.2, -2.0):
        for n in (-2, 1, 3):
            assert math.isclose(special.ellipf(phi + n * math.pi, m),
                                special.ellipf(phi, m) + 2 * n * K, rel_tol=1e-13)
    phis = np.array([-4.0, -1.0, 0.2, 1.5, 2.5, 7.0])
    sn, cn, dn = special.jacobi_sn_cn_dn([special.ellipf(p, m) for p in phis], m)
    assert np.allclose(sn, np.sin(phis), atol=1e-13)
    assert np.allclose(cn, np.cos(phis), atol=1e-13)
    assert np.allclose(dn, np.sqrt(1 - m * np.sin(phis) ** 2), atol=1e-13)
    u = np.linspace(-3.0, 3.0, 13)
    sn0, cn0, dn0 = special.jacobi_sn_cn_dn(u, 0.0)
    assert np.allclose(sn0, np.sin(u), atol=1e-15) and np.allclose(cn0, np.cos(u), atol=1e-15)
    assert np.allclose(dn0, 1.0, atol=1e-15)


@pytest.mark.parametrize("I", [(1.0, 2.0, 3.0), (3.0, 1.0, 2.0), (1.0, 1.0, 1.5)])
def test_polhodes_lie_on_sphere_and_energy_ellipsoid(I):
    """Each polhode of unit L satisfies |l| = 1 and Σ l_k²/I_k = const (2E/L²); the
    separatrices have 2E/L² = 1/I2 (Landau & Lifshitz §37)."""
    I = np.array(I)
    fam = core.polhode_family(I)
    distinct = len(set(I)) == 3
    assert fam.shape == ((20 if distinct else 10), 400, 3)
    assert np.allclose(np.linalg.norm(fam, axis=2), 1.0, atol=1e-14)
    e = np.sum(fam**2 / I, axis=2)
    assert np.max(np.ptp(e, axis=1)) < 1e-13
    # energies strictly between an extreme axis and the separatrix
    inv = np.sort(1.0 / I)
    assert np.all((e[:, 0] > inv[0]) & (e[:, 0] < inv[2]))
    assert np.all(np.abs(e[:, 0] - 1.0 / np.median(I)) > 1e-3)
    sep = core.polhode_separatrices(I)
    if not distinct:
        assert sep.shape == (0, 400, 3)
        return
    assert sep.shape == (2, 400, 3)
    assert np.allclose(np.linalg.norm(sep, axis=2), 1.0, atol=1e-14)
    assert np.allclose(np.sum(sep**2 / I, axis=2), 1.0 / np.median(I), atol=1e-14)


def test_herpolhode_and_polhode_track_of_a_run():
    """Poinsot: ω·L/|L| = 2T/|L| is constant; the polhode track is Iω/|Iω|."""
    I = np.array([1.0, 2.0, 3.0])
    w = np.array([1.0, 0.5, 1.5])
    t = np.linspace(0.0, 10.0, 501)
    sol = integrate(core.model(*I), y0_of(w), t, method="dop853", rtol=1e-12, atol=1e-14)
    h = core.herpolhode(sol.y[:, :3], sol.y[:, 3:7], I)
    T2, L = np.sum(I * w**2), np.linalg.norm(I * w)
    assert np.allclose(h["along_L"], T2 / L, rtol=1e-10)
    # |ω|² = (ω·n)² + x² + y²: the plane coordinates carry the rest of ω
    assert np.allclose(h["x"] ** 2 + h["y"] ** 2 + h["along_L"] ** 2,
                       np.sum(sol.y[:, :3] ** 2, axis=1), rtol=1e-10)
    track = core.polhode_track(sol.y[:, :3], I)
    assert np.allclose(track * np.linalg.norm(I * sol.y[:, :3], axis=1)[:, None],
                       I * sol.y[:, :3], atol=1e-14)


def test_impulse_growth_envelope_and_flips():
    """Δω = I⁻¹ (r × P) (ex. 4.6c); δ(t) = δ0 e^{γt}; flips every 2K(m)/λ."""
    dw = core.omega_after_impulse([0.0, 0.0, 1.0], [2.0, 4.0, 8.0], [0.0, 0.0, 1.5],
                                  [0.1, 0.0, 0.0])
    assert np.allclose(dw, [0.0, 0.15 / 4.0, 1.0], atol=1e-16)
    assert np.allclose(core.growth_envelope(np.array([0.0, 2.0]), 0.01, 0.5),
                       [0.01, 0.01 * math.e], rtol=1e-15)
    I, w = np.array([1.0, 2.0, 3.0]), np.array([0.01, 2.0, 0.01])
    t = np.linspace(0.0, 40.0, 4001)
    ell = core.elliptic_parameters(w, I)
    f = core.flip_analysis(t, core.exact_omega(t, w, I), 1, 1.0, ell["period"] / 2)
    assert f["axis"] == 2 and len(f["flip_times"]) >= 2
    assert math.isclose(f["half_period_measured"], ell["period"] / 2, rel_tol=1e-4)
    assert math.isclose(f["perturbation_initial"], math.hypot(0.01, 0.01), rel_tol=1e-10)
    assert f["growth_envelope"].shape == t.shape
    # the Jacobian at steady rotation gives (10.14) about the intermediate axis
    assert math.isclose(core.steady_rotation_growth_rate(I, 1, 2.0),
                        2.0 * math.sqrt(1 * 1 / 3), rel_tol=1e-12)


@pytest.mark.parametrize("order", [2, 4])
def test_splitting_order_and_invariants(order):
    I = np.array([1.0, 2.0, 3.0])
    w = np.array([1.0, 0.5, 1.5])
    t = np.linspace(0.0, 10.0, 101)
    exact = core.exact_omega(t, w, I)
    errs = []
    for h in (0.05, 0.025, 0.0125):  # divide the output spacing 0.1 exactly
        Y, _, _ = integrate_splitting(I, y0_of(w), t, h, order)
        errs.append(np.max(np.abs(Y[:, :3] - exact)))
        inv = core.invariants(Y, I)
        # every sub-step is a rotation: |L|, space-frame L and |q| to round-off
        assert np.ptp(inv["L_squared"]) / inv["L_squared"][0] < 1e-13
        for c in ("L_x", "L_y", "L_z"):
            assert np.ptp(inv[c]) < 1e-13 * math.sqrt(inv["L_squared"][0])
        assert np.max(np.abs(inv["quaternion_norm"] - 1.0)) < 1e-14
    slopes = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(np.abs(slopes - order) < 0.15), slopes


RIGID = """
kind = "rigid_body"
{body}
[initial]
omega = {omega}
{extra}
[run]
t_end = {t_end}
samples = 801
study = false
"""


def rigid_text(body='[params]\nI1 = 1.0\nI2 = 2.0\nI3 = 3.0', omega="[0.01, 2.0, 0.01]",
               extra="", t_end=20.0):
    return RIGID.format(body=body, omega=omega, extra=extra, t_end=t_end)


def test_scene_archive_per_spec(tmp_path, write_config, cli):
    cfg = write_config("dz", rigid_text())
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    with h5py.File(tmp_path / "o" / "dz" / "run.h5") as f:
        main = f["runs/main"]
        cols = [c.decode() if isinstance(c, bytes) else c for c in main["y"].attrs["columns"]]
        assert cols == ["omega_1", "omega_2", "omega_3", "q_w", "q_x", "q_y", "q_z"]
        y, t = main["y"][()], main["t"][()]
        a = f["analysis"]
        assert np.allclose(a["principal_moments"][()], [1.0, 2.0, 3.0])
        st = a["axis_stability"]
        verdicts = [st[f"axis_{k}"].attrs["verdict"] for k in (1, 2, 3)]
        assert verdicts == ["stable", "unstable", "stable"]
        spin = float(a.attrs["spin"])
        gamma = spin * math.sqrt((2 - 1) * (3 - 2) / (1 * 3))  # (10.14)
        assert math.isclose(st["axis_2"].attrs["growth_rate"], gamma, rel_tol=1e-14)
        assert math.isclose(st["axis_2"].attrs["growth_rate_jacobian"], gamma, rel_tol=1e-12)
        assert a.attrs["omega_max_error"] <= 1e-9
        assert np.max(np.abs(y[:, :3] - core.exact_omega(t, [0.01, 2.0, 0.01], [1, 2, 3]))) <= 1e-9
        assert np.max(np.abs(np.linalg.norm(y[:, 3:], axis=1) - 1.0)) <= 1e-12
        assert a.attrs["quaternion_norm_max_deviation"] < 1e-10
        assert "flip" in a and len(a["flip/flip_times"]) >= 2
        assert "symmetric" not in a
        # the archive is the whole truth: exact ω on the output grid, Poinsot geometry
        ref = main["reference"]
        exact = core.exact_omega(t, [0.01, 2.0, 0.01], [1, 2, 3])
        for k in range(3):
            assert np.array_equal(ref[f"omega_{k + 1}"][()], exact[:, k])
        assert "Jacobi elliptic" in main.attrs["reference_label"]
        assert np.array_equal(f["runs/splitting/reference/omega_1"][()], exact[:, 0])
        assert f["runs/splitting"].attrs["scale_L_squared"] == main.attrs["scale_L_squared"]
        assert a["polhodes/family"].shape == (20, 400, 3)
        assert a["polhodes/separatrices"].shape == (2, 400, 3)
        assert a["polhodes/track"].shape == (801, 3)
        poinsot = a["poinsot"]  # tests/test_rigid_body_poinsot.py checks the geometry
        assert poinsot["herpolhode"].shape == (801, 3)
        assert poinsot.attrs["plane_distance_max_error"] < 1e-9
        assert a["polhode_ellipsoid/family"].shape == (16, 121, 3)
        env = a["flip/growth_envelope"][()]
        assert math.isclose(env[0], math.hypot(0.01, 0.01), rel_tol=1e-14)
    html = (tmp_path / "o" / "dz" / "report.html").read_text()
    assert "Dzhanibekov" in html and "Polhodes on the inertia ellipsoid" in html
    assert "Precession of the symmetric body" not in html  # promise 3


def test_cone_impulse_sets_initial_state(tmp_path, write_config, cli):
    """Exercise 4.6c: ΔL = r × P at the apex r = (0, 0, 3h/4); Δω = I⁻¹ ΔL."""
    body = '[shape]\ntype = "cone"\nmass = 1.0\nradius = 0.5\nheight = 2.0'
    cfg = write_config("cone", rigid_text(body=body, omega="[0.0, 0.0, 20.0]", t_end=2.0,
                                          extra='[impulse]\nP = [0.1, 0.0, 0.0]\nat = "apex"'))
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    with h5py.File(tmp_path / "o" / "cone" / "run.h5") as f:
        a = f["analysis"]
        I_perp = 3 * (0.25 + 1.0) / 20  # Landau §32 P.2: 3M(R² + h²/4)/20
        assert np.allclose(a["principal_moments"][()], [I_perp, I_perp, 0.3 * 0.25])
        # r × P = (0, 1.5·0.1, 0) with the apex at 3h/4 = 1.5
        assert np.allclose(a["omega_initial"][()], [0.0, 0.15 / I_perp, 20.0], atol=1e-14)
        sym = a["symmetric"].attrs
        assert math.isclose(sym["Omega"], (I_perp - 0.075) * 20.0 / I_perp, rel_tol=1e-14)
        assert math.isclose(sym["Omega_measured"], sym["Omega"], rel_tol=1e-8)


@pytest.mark.parametrize("text, key", [
    (rigid_text(body="[params]\nI1 = 1.0\nI2 = 1.0\nI3 = 2.5"), "params.I3"),
    (rigid_text(body='[shape]\ntype = "box"\nmass = 0.0\na = 1.0\nb = 1.0\nc = 1.0'),
     "shape.mass"),
    (rigid_text(omega="[1.0, 2.0]"), "initial.omega"),
    (rigid_text(extra="attitude = [1.0, 1.0, 0.0, 0.0]"), "initial.attitude"),
])
def test_bad_input_names_the_key(write_config, cli, text, key):
    code, out, err = cli("validate", write_config("bad", text))
    assert code == 2
    assert key in out + err


def test_shipped_presets_validate(cli):
    paths = sorted(REPO.glob("configs/rigid_body_*.toml")) + [REPO / "configs/inertia_cone.toml"]
    assert len(paths) >= 5  # every shipped rigid-body config, and the cone of the inertia kind
    code, out, err = cli("validate", *paths)
    assert code == 0, out + err


def test_omega_error_figure_names_an_exactly_zero_component_instead_of_a_floor_line():
    """A symmetric body's ω along the figure axis is integrated exactly: its error is 0,
    which a log axis would draw as a line at the 1e-18 floor. It is left out of the
    figure and named in the caption; a nonzero error is kept."""
    from reportgen.kinds.rigid_body.report import omega_errors, zero_error_words

    t = np.linspace(0.0, 1.0, 5)
    run = {"omega_1": np.cos(t) + 1e-15, "omega_2": np.sin(t), "omega_3": np.full(5, 2.0)}
    exact = {"omega_1": np.cos(t), "omega_2": np.sin(t) - 3e-16, "omega_3": np.full(5, 2.0)}
    errors, zero = omega_errors(run, exact)
    assert list(errors) == ["|ω1 − exact|", "|ω2 − exact|"] and zero == [3]
    assert "ω3 is exactly zero" in zero_error_words(zero)
    assert zero_error_words([]) == ""


def test_ellipsoid_view_takes_the_camera_off_the_lab_axes():
    """The octahedron's principal axes are the lab axes; the old view (along the
    shortest semi-axis, tilted to the middle one) sat square on azimuth 90° at 63°
    elevation and stacked the y and z tick labels."""
    from reportgen.rendering.plots.rigid_body import ellipsoid_view

    semi = 1.0 / np.sqrt([0.1, 0.136, 0.164])
    elev, azim = ellipsoid_view(np.eye(3), semi)
    off_axis = min(azim % 90.0, 90.0 - azim % 90.0)
    assert 0.0 <= elev <= 60.0 and off_axis >= 10.0


def test_a_spherical_top_draws_no_empty_error_plot(tmp_path):
    """Three equal moments (notes (10.6)): ω is exact to the last bit, so the error figure
    would be an empty log axis; it is left out and the fact says why."""
    from reportgen.commands.cli import main

    config = tmp_path / "sphere.toml"
    config.write_text('kind = "rigid_body"\n[params]\nI1 = 2.0\nI2 = 2.0\nI3 = 2.0\n'
                      '[initial]\nomega = [0.4, -0.3, 1.2]\n[run]\nt_end = 5.0\n'
                      'samples = 501\nstudy = false\n[report]\nformats = ["html"]\n',
                      encoding="utf-8")
    assert main(["run", str(config), "--out", str(tmp_path / "out")]) == 0
    folder = tmp_path / "out" / "sphere"
    assert not (folder / "figures" / "omega-omega_error.svg").exists()
    assert "equal at every sample" in (folder / "report.html").read_text(encoding="utf-8")
