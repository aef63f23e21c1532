"""The ``rotation`` kind end to end: archive contents against closed forms recomputed here,
sections present only when asked, presets, and bad input refused with exit status 2."""

from __future__ import annotations

import math

import h5py
import numpy as np
import pytest
from scipy.linalg import expm

from reportgen.archive.h5io import read_table
from reportgen.archive.store import read_archive

SHIPPED = "configs/rotation_exercises.toml"


def skew(v):
    x, y, z = v
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def circle_fit_residual(points: np.ndarray) -> float:
    """Largest relative deviation of plane points (m, 2) from their least-squares circle
    x² + y² + D x + E y + F = 0 (Kåsa's algebraic fit)."""
    x, y = points[:, 0], points[:, 1]
    M = np.stack([x, y, np.ones_like(x)], axis=-1)
    D, E, F = np.linalg.lstsq(M, -(x * x + y * y), rcond=None)[0]
    centre = np.array([-D / 2, -E / 2])
    radius = math.sqrt(centre @ centre - F)
    return float(np.max(np.abs(np.linalg.norm(points - centre, axis=1) - radius)) / radius)


@pytest.fixture(scope="module")
def shipped(tmp_path_factory):
    from reportgen.pipeline.stages import run_scene

    out = tmp_path_factory.mktemp("rotation")
    outcome = run_scene(SHIPPED, str(out), formats=("html",))
    assert outcome.ok, outcome.message
    return out / "rotation_exercises"


def test_shipped_archive_holds_every_check_within_1e_12(shipped):
    with h5py.File(shipped / "run.h5") as f:
        assert f.attrs["kind"] == "rotation" and f.attrs["status"] == "ok"
        assert "runs" not in f or len(f["runs"]) == 0  # nothing integrated, like inertia
        assert "study" not in f
        checks = read_table(f["checks"])
        assert len(checks) == 7  # the headline checks; every one is under /analysis/*/errors
        assert np.all(checks["rel_error"] <= 1e-12), checks
    data = read_archive(shipped / "run.h5")
    for group in ("axis_angle", "euler", "stereographic"):
        errors = data.analysis[group]["errors"]
        checked = {k: v for k, v in errors.items() if not k.startswith("transpose_mismatch")}
        assert len(checked) >= 6 and max(checked.values()) <= 1e-12, (group, errors)


def test_axis_angle_archive_against_scipy_expm(shipped):
    """The archived A is exp(−Φ[n]×) (Goldstein (4.62) is passive) and turns the axes
    x -> y -> z for 2π/3 about the body diagonal: r = e_x has r′ = e_z."""
    a = read_archive(shipped / "run.h5").analysis["axis_angle"]
    n, Phi = a["axis"], a["angle"]
    assert np.allclose(n, np.ones(3) / math.sqrt(3), atol=1e-16)  # [1, 1, 1] normalized
    assert np.allclose(a["matrix_formula"], expm(-Phi * skew(n)), atol=1e-14)
    assert np.allclose(a["rotated_vector"], [0.0, 0.0, 1.0], atol=1e-15)
    # the figure's arc runs from r to r′ on the circle about n through r
    arc = a["arc"]
    assert np.allclose(arc[0], a["vector"], atol=1e-15)
    assert np.allclose(arc[-1], a["rotated_vector"], atol=1e-15)
    assert np.allclose(arc @ n, a["vector"] @ n, atol=1e-15)
    assert np.allclose(np.linalg.norm(arc, axis=1), 1.0, atol=1e-15)


def test_euler_archive_same_rotation_in_both_conventions(shipped):
    e = read_archive(shipped / "run.h5").analysis["euler"]
    assert e["convention"] == "zyz" and e["other_convention"] == "zxz"
    phi, theta, psi = e["path"][0]
    # Goldstein's y-convention: z-x-z angles are φ + π/2, θ, ψ − π/2
    assert np.allclose(e["path_other"][0], [phi + math.pi / 2, theta, psi - math.pi / 2],
                       atol=1e-15)
    # R = R_z(φ) R_y(θ) R_z(ψ) by scipy's expm of the generators, independently
    Lz, Ly = skew([0, 0, 1]), skew([0, 1, 0])
    R = expm(phi * Lz) @ expm(theta * Ly) @ expm(psi * Lz)
    assert np.allclose(e["matrix"], R, atol=1e-14)
    assert np.allclose(e["matrix_other"], R, atol=1e-14)
    # body ω3 = φ̇ cos θ + ψ̇ (Goldstein 4.87) along the whole path, in both conventions
    rates = e["rates"]
    expected = rates[0] * np.cos(e["path"][:, 1]) + rates[2]
    assert np.allclose(e["omega_body"][:, 2], expected, atol=1e-15)
    assert np.allclose(e["omega_body_other"][:, 2], expected, atol=1e-15)
    assert np.allclose(e["omega_body_derivative"][:, 2], expected, atol=1e-14)


def test_stereographic_archive_circles_go_to_circles(shipped):
    s = read_archive(shipped / "run.h5").analysis["stereographic"]
    # what the figure draws as coincident markers does coincide
    assert np.allclose(s["plane_mobius"], s["plane_rotated"], rtol=1e-12, atol=1e-12)
    # the circle of latitude z = −1/2 projects to the circle |ζ| = √3/3 ... (1+z)/(1−z)…:
    # |ζ| = √(1 − z²)/(1 − z) = √(3/4)/(3/2) = 1/√3
    assert np.allclose(np.linalg.norm(s["circle_plane"], axis=1), 1 / math.sqrt(3), atol=1e-15)
    # and its Möbius image is again a circle (stereographic projection keeps circles)
    assert circle_fit_residual(s["circle_plane_mobius"]) < 1e-12
    # M_U(∞) = a/(−b̄) is the projection of R(U) N
    a, b = complex(*s["a"]), complex(*s["b"])
    at_inf = a / -b.conjugate()
    assert np.allclose(s["pole_image_plane"], [at_inf.real, at_inf.imag], atol=1e-15)
    x, y, z = s["pole_image"]
    assert np.isclose((x - 1j * y) / (1 - z), at_inf, atol=1e-14)
    # the double cover: −U gives the same R
    assert np.array_equal(s["rotation"], s["rotation_minus_u"])
    # R(U) is not symmetric here, so R and Rᵀ differ: the contrast row means something
    assert s["errors"]["transpose_mismatch"] > 0.5


def test_report_lists_each_check(shipped):
    html = (shipped / "report.html").read_text(encoding="utf-8")
    for title in ("exercise 4.5", "exercises 4.7, 4.8", "exercise 4.11", "line of nodes",
                  "Möbius map of U vs R(U)", "max error"):
        assert title in html, title
    # ex. 4.5, the two Euler constructions, the notes' Figure 2 and the Möbius map
    assert len(list((shipped / "figures").glob("*.svg"))) == 4


def test_only_the_asked_exercise_is_computed_and_shown(tmp_path, write_config, cli):
    cfg = write_config("aa", """
        kind = "rotation"
        [axis_angle]
        axis = [0.0, 0.0, 2.0]
        angle = 0.7
        """)
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    data = read_archive(tmp_path / "o" / "aa" / "run.h5")
    assert set(data.analysis) == {"axis_angle"}
    a = data.analysis["axis_angle"]
    # a non-unit axis is normalized; about z, (4.62) is Goldstein's D (first factor of 4.46)
    assert np.allclose(a["axis"], [0, 0, 1], atol=0) and np.allclose(a["axis_given"], [0, 0, 2])
    c, s = math.cos(0.7), math.sin(0.7)
    assert np.allclose(a["matrix_formula"], [[c, s, 0], [-s, c, 0], [0, 0, 1]], atol=1e-15)
    html = (tmp_path / "o" / "aa" / "report.html").read_text(encoding="utf-8")
    assert "exercise 4.5" in html and "exercise 4.11" not in html and "line of nodes" not in html


def test_sections_narrowed_by_report_are_not_computed(tmp_path, write_config, cli):
    cfg = write_config("narrow", """
        kind = "rotation"
        preset = "all"
        [report]
        sections = ["stereographic"]
        formats = ["html"]
        """)
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1)
    assert code == 0, out + err
    data = read_archive(tmp_path / "o" / "narrow" / "run.h5")
    assert set(data.analysis) == {"stereographic"}


def test_zxz_and_zyz_configs_of_one_rotation_agree(tmp_path, write_config, cli):
    phi, theta, psi = 0.5, 0.8, 0.3
    write_config("given_zyz", f"""
        kind = "rotation"
        [euler]
        convention = "zyz"
        angles = [{phi}, {theta}, {psi}]
        rates = [0.2, -0.5, 1.0]
        """)
    cfg = write_config("given_zxz", f"""
        kind = "rotation"
        [euler]
        convention = "zxz"
        angles = [{phi + math.pi / 2!r}, {theta}, {psi - math.pi / 2!r}]
        rates = [0.2, -0.5, 1.0]
        """)
    code, out, err = cli("run", cfg.parent, "--out", tmp_path / "o", "--jobs", 1, "--format",
                         "html")
    assert code == 0, out + err
    a = read_archive(tmp_path / "o" / "given_zyz" / "run.h5").analysis["euler"]
    b = read_archive(tmp_path / "o" / "given_zxz" / "run.h5").analysis["euler"]
    assert np.allclose(a["matrix"], b["matrix"], atol=1e-15)
    assert np.allclose(a["omega_space"], b["omega_space"], atol=1e-14)
    assert np.allclose(a["omega_body"], b["omega_body"], atol=1e-14)


def test_su2_by_axis_and_angle(tmp_path, write_config, cli):
    """U = exp(−iα σz/2) turns by +α about z: R(U) = R_z(α)."""
    cfg = write_config("su", """
        kind = "rotation"
        [su2]
        axis = [0.0, 0.0, 1.0]
        angle = 0.9
        points = 16
        """)
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    s = read_archive(tmp_path / "o" / "su" / "run.h5").analysis["stereographic"]
    c, si = math.cos(0.9), math.sin(0.9)
    assert np.allclose(s["rotation"], [[c, -si, 0], [si, c, 0], [0, 0, 1]], atol=1e-15)
    assert np.allclose(s["a"], [math.cos(0.45), -math.sin(0.45)], atol=1e-16)
    assert len(s["points"]) == 16


@pytest.mark.parametrize("text, key", [
    ('[axis_angle]\naxis = [0.0, 0.0, 0.0]\n', "axis_angle.axis"),
    ('[axis_angle]\naxis = [1.0, 0.0]\n', "axis_angle.axis"),
    ('[axis_angle]\nangle = 0.0\n', "axis_angle.angle"),
    ('[axis_angle]\nangle = 4.0\n', "axis_angle.angle"),
    ('[axis_angle]\nvector = [0.0, 0.0, 0.0]\n', "axis_angle.vector"),
    ('[euler]\nconvention = "xyz"\n', "euler.convention"),
    ('[euler]\nsamples = 1\n', "euler.samples"),
    ('[euler]\nduration = -1.0\n', "euler.duration"),
    ('[su2]\na = [0.8, 0.0]\nb = [0.8, 0.0]\n', "su2.a"),
    ('[su2]\na = [0.8, 0.0]\n', "su2.a"),
    ('[su2]\na = [1.0, 0.0]\nb = [0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nangle = 1.0\n', "su2"),
    ('[su2]\naxis = [0.0, 0.0, 0.0]\nangle = 1.0\n', "su2.axis"),
    ('[su2]\npoints = 2\n', "su2.points"),
    ('[axis_angle]\n[run]\nt_end = 1.0\n', "run"),
    ('title = "nothing asked"\n', "axis_angle / euler / su2"),
    ('[axis_angle]\n[report]\nsections = ["stereographic"]\n', "report.sections"),
    ('[axis_angle]\nspin = 1.0\n', "axis_angle.spin"),
])
def test_bad_input_exits_2_naming_the_key(write_config, cli, text, key):
    cfg = write_config("bad", 'kind = "rotation"\n' + text)
    code, out, err = cli("validate", cfg)
    assert code == 2, out + err
    assert key in out + err and "bad.toml" in out + err
    assert "Traceback" not in out + err


def test_presets(tmp_path, write_config, cli):
    cfg = write_config("pre", """
        kind = "rotation"
        preset = "euler_zyz"
        [euler]
        samples = 5
        """)
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    e = read_archive(tmp_path / "o" / "pre" / "run.h5").analysis["euler"]
    assert e["convention"] == "zyz" and len(e["t"]) == 5


@pytest.mark.parametrize("angle", [1e-6, math.pi])
def test_small_turns_and_half_turns_pass_their_checks(tmp_path, write_config, cli, angle):
    """Near Φ = 0 the axis is fixed only to ε/Φ (the check weighs it so); at Φ = π the
    antisymmetric part vanishes and the axis comes from the symmetric part."""
    cfg = write_config("edge", f"""
        kind = "rotation"
        [axis_angle]
        axis = [0.3, -0.4, 1.2]
        angle = {angle!r}
        """)
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    a = read_archive(tmp_path / "o" / "edge" / "run.h5").analysis["axis_angle"]
    n = np.array([0.3, -0.4, 1.2]) / 1.3
    assert abs(a["recovered_angle"] - angle) < 1e-15
    assert np.allclose(a["recovered_axis"] * np.sign(a["recovered_axis"] @ n), n,
                       atol=1e-15 / min(angle, 1.0))


def test_a_check_above_1e_12_fails_the_scene(tmp_path, write_config, monkeypatch):
    """The checks can fail: a matrix exponential off by 1e-9 flags the scene as failed,
    naming the check (exit status 1 from `reportgen run`)."""
    from reportgen.core import rotations
    from reportgen.pipeline.stages import run_scene

    exact = rotations.expm_by_diagonalization
    monkeypatch.setattr(rotations, "expm_by_diagonalization", lambda M: exact(M) + 1e-9)
    cfg = write_config("off", 'kind = "rotation"\npreset = "axis_angle"\n')
    outcome = run_scene(str(cfg), str(tmp_path / "o"), formats=("html",))
    assert outcome.status == "failed"
    assert "axis_angle/formula_vs_expm" in outcome.message
