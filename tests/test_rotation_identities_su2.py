"""The ``rotation`` kind's matrix identities (textbook ex. 4.1–4.4), the SU(2) form of Euler's
theorem and of the Euler angles (notes (9.17)–(9.18)) and the rest of textbook ex. 4.11 (the
stereographic projection's scale factor, composition = matrix product), against references
recomputed here.

References, independent of reportgen:
- matrix exponentials by ``scipy.linalg.expm``: the active R(n, Φ) = exp(Φ[n]×) (textbook
  ex. 4.5) and U(n, α) = exp(−iα n·σ/2) (the SU(2) map of notes (9.4)–(9.8)); elementary SU(2) factors
  exp(−iα σ_k/2), multiplied in the order of the Euler angles (notes (9.18));
- Euler matrices by ``scipy.spatial.transform.Rotation.from_euler`` ("ZXZ"/"ZYZ",
  intrinsic: R = R_z(φ) R_k(θ) R_z(ψ), Goldstein (4.46) transposed);
- a similarity keeps the characteristic polynomial: tr, det and eigenvalues of R(n, Φ)
  are 1 + 2 cos Φ, 1 and {1, e^{±iΦ}}; of Φ[n]×, 0, 0 and {0, ±iΦ}; of ½(R + Rᵀ),
  1 + 2 cos Φ, cos²Φ and {1, cos Φ, cos Φ}; S R(n, Φ) Sᵀ = R(S n, Φ);
- the stereographic projection ζ = (x − iy)/(1 − z) has 1 + |ζ|² = 2/(1 − z), hence
  |ζ₁ − ζ₂| = |x₁ − x₂|/√((1 − z₁)(1 − z₂)) (the chordal metric of the Riemann sphere) and the
  scale factor |dζ|/|dx| = 1/(1 − z);
- a central difference errs by h² R⃛/6 + O(h⁴): quartering h divides its error by 16.
"""

from __future__ import annotations

import html
import math
import re

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.spatial.transform import Rotation

from reportgen.archive.store import read_archive
from reportgen.core import rotations as rot

SIGMA = np.array([[[0, 1], [1, 0]], [[0, -1j], [1j, 0]], [[1, 0], [0, -1]]], dtype=complex)
SHIPPED = "configs/rotation_exercises.toml"
ANGLES = [(0.5, 0.8, 0.3), (2.5, 2.9, -1.9), (-1.2, 0.2, 3.0)]


def skew(v):
    x, y, z = v
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def u_of(axis, alpha):
    """exp(−iα n·σ/2) by scipy."""
    n = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    return expm(-0.5j * alpha * np.einsum("k,kab->ab", n, SIGMA))


def euler_u(angles, convention):
    phi, theta, psi = angles
    middle = {"zxz": (1, 0, 0), "zyz": (0, 1, 0)}[convention]
    return u_of((0, 0, 1), phi) @ u_of(middle, theta) @ u_of((0, 0, 1), psi)


def euler_r(angles, convention):
    return Rotation.from_euler(convention.upper(), angles).as_matrix()


# ----------------------------------------------------------------- core functions
@pytest.mark.parametrize("convention", ["zxz", "zyz"])
@pytest.mark.parametrize("angles", ANGLES)
def test_su2_euler_is_the_product_of_exponentials_and_covers_the_euler_matrix(angles,
                                                                             convention):
    U = rot.su2_euler(np.array(angles), convention)
    assert np.allclose(U, euler_u(angles, convention), atol=1e-15)
    assert np.allclose(rot.so3_from_su2_many(U), euler_r(angles, convention), atol=1e-15)
    a, b = rot.su2_euler_cayley_klein(*angles, convention)
    assert np.allclose(U, [[a, b], [-np.conj(b), np.conj(a)]], atol=1e-15)
    # ½ tr U = cos(θ/2) cos((φ + ψ)/2) in both conventions
    phi, theta, psi = angles
    assert math.isclose(0.5 * np.trace(U).real, math.cos(theta / 2) * math.cos((phi + psi) / 2),
                        abs_tol=1e-15)


def test_su2_exp_and_the_many_element_cover_against_scipy():
    n, alpha = np.array([0.3, -0.4, 1.2]), 2.2
    assert np.allclose(rot.su2_exp(n, alpha), u_of(n, alpha), atol=1e-15)
    U = np.stack([u_of(n, alpha), u_of((1, 0, 0), 0.7)])
    R = rot.so3_from_su2_many(U)
    assert np.allclose(R[0], expm(alpha * skew(n / np.linalg.norm(n))), atol=1e-15)
    assert np.allclose(R[1], expm(0.7 * skew((1, 0, 0))), atol=1e-15)


@pytest.mark.parametrize("alpha", [0.4, 2.0, math.pi, 4.0, 6.0])
def test_axis_and_angle_of_an_su2_element_keep_its_sign(alpha):
    m = np.array([2.0, -1.0, 2.0]) / 3.0
    got_m, got_alpha = rot.su2_axis_angle(u_of(m, alpha))
    assert math.isclose(got_alpha, alpha, abs_tol=1e-14)
    assert np.allclose(got_m, m, atol=1e-14)
    # −U = U(m, α + 2π) = U(−m, 2π − α): the other sign of the same rotation
    neg_m, neg_alpha = rot.su2_axis_angle(-u_of(m, alpha))
    assert math.isclose(neg_alpha, 2 * math.pi - alpha, abs_tol=1e-14)
    assert np.allclose(neg_m, -m, atol=1e-14)


def test_stereographic_scale_factor_and_tangents():
    x = rot.fibonacci_sphere(64)
    east, south = rot.tangent_frame(x)
    for t in (east, south):
        assert np.allclose(np.linalg.norm(t, axis=-1), 1.0, atol=1e-15)
        assert np.allclose(np.sum(t * x, axis=-1), 0.0, atol=1e-15)
    assert np.allclose(np.sum(east * south, axis=-1), 0.0, atol=1e-15)
    assert np.all(south[:, 2] <= 0.0)  # south: z falls
    for t in (east, south):
        d = rot.stereographic_derivative(x, t)
        # |dζ/ds| = 1/(1 − z)
        assert np.allclose(np.abs(d), 1.0 / (1.0 - x[:, 2]), rtol=1e-13)
        # against a central difference of ζ = (x − iy)/(1 − z) along the great circle
        h = 1e-6

        def zeta(p):
            return (p[:, 0] - 1j * p[:, 1]) / (1.0 - p[:, 2])

        fd = (zeta(x * math.cos(h) + t * math.sin(h))
              - zeta(x * math.cos(h) - t * math.sin(h))) / (2 * h)
        assert np.allclose(d, fd, rtol=1e-7)


# --------------------------------------------------------------- the shipped scene
@pytest.fixture(scope="module")
def shipped(tmp_path_factory):
    from reportgen.pipeline.stages import run_scene

    out = tmp_path_factory.mktemp("rotation_identities")
    outcome = run_scene(SHIPPED, str(out), formats=("html",))
    assert outcome.ok, outcome.message
    return out / "rotation_exercises"


def test_identities_against_closed_forms(shipped):
    data = read_archive(shipped / "run.h5")
    d, euler = data.analysis["identities"], data.analysis["euler"]
    assert max(d["errors"].values()) <= 1e-12, d["errors"]
    n, Phi = np.ones(3) / math.sqrt(3), 2 * math.pi / 3  # the shipped [axis_angle]
    S = euler_r(euler["path"][0], str(euler["convention"]))
    assert np.allclose(d["second_rotation"], S, atol=1e-15)
    assert np.allclose(d["turned_axis"], S @ n, atol=1e-15)
    # S R(n, Φ) Sᵀ = R(S n, Φ); S Φ[n]× Sᵀ = Φ[S n]×
    assert np.allclose(d["turned"][0], expm(Phi * skew(S @ n)), atol=1e-14)
    assert np.allclose(d["turned"][1], Phi * skew(S @ n), atol=1e-14)
    c = math.cos(Phi)
    assert np.allclose(d["trace_turned"], [1 + 2 * c, 0.0, 1 + 2 * c], atol=1e-14)
    assert np.allclose(d["determinant_turned"], [1.0, 0.0, c * c], atol=1e-14)
    closed = [[1, np.exp(1j * Phi), np.exp(-1j * Phi)], [0, 1j * Phi, -1j * Phi], [1, c, c]]
    for got, want in zip(d["eigenvalues_turned"], closed, strict=True):
        got = got[:, 0] + 1j * got[:, 1]
        assert all(np.min(np.abs(got - w)) < 1e-14 for w in want), (got, want)


def test_central_differences_converge_as_h_squared(shipped, tmp_path, write_config):
    """e(h) falls as h²: order log₂(e(2h)/e(h)) ≈ 2 on the shipped path, and a path with a
    quarter of the step has a 16th of the error; Richardson's combination is far smaller."""
    from reportgen.pipeline.stages import run_scene

    cd = read_archive(shipped / "run.h5").analysis["identities"]["central_differences"]
    assert math.isclose(cd["step"], 0.05, rel_tol=1e-15)  # 4 s over 80 steps
    assert abs(cd["order"] - 2.0) < 0.01
    assert cd["omega_richardson"] < cd["omega"] / 100
    assert 0.3 * cd["omega"] < cd["antisymmetry"] < 3 * cd["omega"]  # also ∝ h²
    text = open(SHIPPED, encoding="utf-8").read()
    fine = write_config("fine", text.replace("samples = 81", "samples = 321")
                        + '\n[report]\nsections = ["matrix_identities"]\n')
    outcome = run_scene(str(fine), str(tmp_path / "o"), formats=("html",))
    assert outcome.ok, outcome.message
    f = read_archive(tmp_path / "o" / "fine" / "run.h5").analysis["identities"]
    assert set(read_archive(tmp_path / "o" / "fine" / "run.h5").analysis) == {"identities"}
    ratio = cd["omega"] / f["central_differences"]["omega"]
    assert 15.0 < ratio < 17.0, ratio


def test_su2_form_against_closed_forms(shipped):
    data = read_archive(shipped / "run.h5")
    s, euler = data.analysis["su2_form"], data.analysis["euler"]
    assert max(s["errors"].values()) <= 1e-12, s["errors"]
    # U(n, 2π/3), n = (1, 1, 1)/√3: a = cos 60° − i sin 60° n_z = ½ − ½ i,
    # b = −i sin 60° (n_x − i n_y) = −½ − ½ i
    assert np.allclose(s["a"], [0.5, -0.5], atol=1e-15)
    assert np.allclose(s["b"], [-0.5, -0.5], atol=1e-15)
    assert np.allclose(s["rotation"], expm(2 * math.pi / 3 * skew(np.ones(3) / math.sqrt(3))),
                       atol=1e-15)
    angles, convention = euler["path"][0], str(euler["convention"])
    U = euler_u(angles, convention)
    assert np.allclose(s["euler_a"], [U[0, 0].real, U[0, 0].imag], atol=1e-15)
    assert np.allclose(s["euler_b"], [U[0, 1].real, U[0, 1].imag], atol=1e-15)
    # Euler's theorem: the one turn is scipy's rotation vector of the Euler matrix
    rotvec = Rotation.from_matrix(euler_r(angles, convention)).as_rotvec()
    assert math.isclose(s["euler_angle"], np.linalg.norm(rotvec), rel_tol=1e-13)
    assert np.allclose(s["euler_axis"], rotvec / np.linalg.norm(rotvec), atol=1e-13)


def test_the_sign_of_the_euler_product_is_kept(tmp_path, write_config, cli):
    """(φ + ψ)/2 = 3 rad: ½ tr U = cos(θ/2) cos 3 < 0, so the product is the turn by
    α > 180° about m, i.e. −U turns by 360° − α about −m; R is the Euler matrix still."""
    cfg = write_config("neg", """
        kind = "rotation"
        [axis_angle]
        [euler]
        convention = "zxz"
        angles = [3.0, 0.8, 3.0]
        samples = 9
        [report]
        sections = ["su2_euler"]
        formats = ["html"]
        """)
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1)
    assert code == 0, out + err
    s = read_archive(tmp_path / "o" / "neg" / "run.h5").analysis["su2_form"]
    half = math.acos(math.cos(0.4) * math.cos(3.0))  # α/2 from ½ tr U
    assert math.isclose(s["euler_angle"], 2 * half, rel_tol=1e-13) and s["euler_angle"] > math.pi
    rotvec = Rotation.from_matrix(euler_r((3.0, 0.8, 3.0), "zxz")).as_rotvec()
    assert np.allclose(s["euler_axis"], -rotvec / np.linalg.norm(rotvec), atol=1e-13)
    assert max(s["errors"].values()) <= 1e-12
    page = (tmp_path / "o" / "neg" / "report.html").read_text(encoding="utf-8")
    assert "360° − α about −m" in page


def test_stereographic_scale_factor_and_composition(shipped):
    s = read_archive(shipped / "run.h5").analysis["stereographic"]
    e, c = s["errors"], s["contrasts"]
    for key in ("scale_factor", "conformal_angle", "difference_quotient_chordal",
                "composition_mobius", "composition_rotation"):
        assert e[key] <= 1e-12, (key, e[key])
    x = s["points"]
    assert np.allclose(s["conformal_factor"], 1.0 / (1.0 - x[:, 2]), rtol=1e-15)
    # the chordal form, recomputed here for neighbouring points of the spiral
    zeta = (x[:, 0] - 1j * x[:, 1]) / (1.0 - x[:, 2])
    lhs = np.abs(zeta[1:] - zeta[:-1])
    rhs = (np.linalg.norm(x[1:] - x[:-1], axis=-1)
           / np.sqrt((1.0 - x[1:, 2]) * (1.0 - x[:-1, 2])))
    assert np.allclose(lhs, rhs, rtol=1e-12)
    # the difference quotient tends to 1/(1 − z) as δ²: δ 10 times smaller, error 100 times
    steps, towards = c["steps"], c["quotient_vs_factor"]
    assert np.allclose(steps, [1e-2, 1e-3])
    assert 90 < towards[0] / towards[1] < 110
    # U₂ is the ex. 4.5 turn, U(n, 2π/3): a = ½ − ½ i, b = −½ − ½ i; R(U U₂) = R(U) R(U₂)
    assert str(s["second_source"]) == "axis_angle"
    assert np.allclose(s["second_a"], [0.5, -0.5], atol=1e-15)
    assert np.allclose(s["second_b"], [-0.5, -0.5], atol=1e-15)
    U1 = np.array([[0.8, 0.36 + 0.48j], [-(0.36 - 0.48j), 0.8]])  # the shipped [su2]
    U2 = u_of(np.ones(3), 2 * math.pi / 3)

    def cover(U):  # R_ij = ½ tr(σ_i U σ_j U†), written here
        return 0.5 * np.einsum("iab,bc,jcd,da->ij", SIGMA, U, SIGMA, U.conj().T).real

    R1, R2 = s["rotation"], s["second_rotation"]
    assert np.allclose(R1, cover(U1), atol=1e-15)
    assert np.allclose(R2, expm(2 * math.pi / 3 * skew(np.ones(3) / math.sqrt(3))), atol=1e-15)
    assert np.allclose(cover(U1 @ U2), R1 @ R2, atol=1e-15)
    # the order matters here: the reversed product is another rotation, far off
    assert c["reversed_rotation"] > 0.1 and c["reversed_mobius"] > 0.1


def test_report_shows_the_new_sections(shipped):
    page = (shipped / "report.html").read_text(encoding="utf-8")
    # the typesetter writes U₂ as U<sub>2</sub> and Rᵀ as R<sup>T</sup>: read them back
    page = re.sub(r"<sub>(\d)</sub>", lambda m: "₀₁₂₃₄₅₆₇₈₉"[int(m.group(1))], page)
    page = re.sub(r"<sup>T</sup>", "ᵀ", page)
    visible = " ".join(html.unescape(re.sub(r"<[^>]+>", " ", page)).split())
    for text in ("Matrix identities (textbook ex. 4.1–4.4)",
                 "Euler angles in SU(2) (notes (9.17)–(9.18))",
                 "1, −0.5 ± 0.866025 i", "RᵀR = 1, det R = 1",
                 "Möbius map of U U₂ vs that of U after that of U₂",
                 "scale factor 1/(1 − z)"):
        assert text in visible, text


@pytest.mark.parametrize("tables", ['[euler]\n', '[axis_angle]\n'])
@pytest.mark.parametrize("section", ["matrix_identities", "su2_euler"])
def test_the_new_sections_need_both_tables(write_config, cli, tables, section):
    cfg = write_config("bad", f'kind = "rotation"\n{tables}[report]\nsections = ["{section}"]\n')
    code, out, err = cli("validate", cfg)
    assert code == 2, out + err
    assert "report.sections" in out + err and "Traceback" not in out + err


def test_a_wrong_su2_sign_fails_the_scene(tmp_path, write_config, monkeypatch):
    """U_k(α) = exp(+iα σ_k/2), the other sign: the product covers R_z(−φ) R_x(−θ) R_z(−ψ),
    not the Euler matrix, and the check fails naming itself."""
    from reportgen.pipeline.stages import run_scene

    exact = rot.su2_elementary
    monkeypatch.setattr(rot, "su2_elementary", lambda axis, angle: exact(axis, -np.asarray(angle)))
    cfg = write_config("wrong", 'kind = "rotation"\npreset = "all"\n'
                                '[report]\nsections = ["su2_euler"]\n')
    outcome = run_scene(str(cfg), str(tmp_path / "o"), formats=("html",))
    assert outcome.status == "failed"
    assert "su2_form/euler_rotation_vs_matrix" in outcome.message


def test_a_wrong_scale_factor_fails_the_scene(tmp_path, write_config, monkeypatch):
    from reportgen.pipeline.stages import run_scene

    exact = rot.stereographic_derivative
    monkeypatch.setattr(rot, "stereographic_derivative",
                        lambda x, t, **kw: exact(x, t, **kw) * (1 + 1e-9))
    cfg = write_config("stretched", 'kind = "rotation"\npreset = "su2"\n')
    outcome = run_scene(str(cfg), str(tmp_path / "o"), formats=("html",))
    assert outcome.status == "failed"
    assert "stereographic/scale_factor" in outcome.message
