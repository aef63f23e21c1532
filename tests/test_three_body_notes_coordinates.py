"""three_body: the lecture notes' coordinates relative to body 1 (notes (3.32)–(3.34)),
r12 = r2 − r1, r13 = r3 − r1 and the centre of mass R, whose kinetic energy has a cross term

    T = ½ M Ṙ² + ½ [m2(m1 + m3)/M ṙ12² + m3(m1 + m2)/M ṙ13² − 2 m2 m3/M ṙ12·ṙ13],

against Cartesian kinetic energies computed here from the velocities, and the archive of the
shipped Sun–Earth–Moon config (shortened) storing them beside Jacobi's."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import h5py
import numpy as np
import pytest

from reportgen.archive.store import read_archive, write_archive
from reportgen.core.models import nbody as core
from reportgen.kinds import load_scene
from reportgen.kinds.three_body import ThreeBodyScene
from reportgen.scene.config import parse_config_text, to_toml
from reportgen.scene.content import fmt

REPO = Path(__file__).resolve().parent.parent


def cartesian_T(y, m):
    """½ Σ mᵢ |vᵢ|², straight from the state's velocity columns (9:18, body by body)."""
    v = np.asarray(y)[:, 9:18].reshape(-1, 3, 3)
    return 0.5 * np.sum(np.asarray(m)[None, :, None] * v**2, axis=(1, 2))


def test_cross_term_kinetic_energy_equals_cartesian_on_a_random_state():
    rng = np.random.default_rng(32)
    m = rng.uniform(0.2, 3.0, 3)
    y = rng.normal(size=(7, 18))
    (R, r12, r13), (Rd, r12d, r13d) = core.notes_coordinates(y, m)
    pos, vel = y[:, :9].reshape(-1, 3, 3), y[:, 9:].reshape(-1, 3, 3)
    np.testing.assert_array_equal(r12, pos[:, 1] - pos[:, 0])
    np.testing.assert_array_equal(r13d, vel[:, 2] - vel[:, 0])
    np.testing.assert_allclose(R, np.einsum("b,nbk->nk", m, pos) / m.sum(), rtol=1e-14)
    T_cart = cartesian_T(y, m)
    T_notes = core.notes_kinetic_energy(y, m)
    np.testing.assert_allclose(T_notes, T_cart, rtol=1e-13, atol=0)
    # the cross term −(m2 m3/M) ṙ12·ṙ13 matters: without it the identity fails by far more
    # than the tolerance above, so this test sees a missing or wrong cross term
    cross = core.notes_kinetic_cross_term(y, m)
    M = m.sum()
    np.testing.assert_allclose(cross, -m[1] * m[2] / M * np.sum(r12d * r13d, 1), rtol=1e-14)
    assert np.all(np.abs(T_notes - cross - T_cart) > 1e-3 * T_cart)
    # Jacobi's diagonal T (the standard hierarchical choice) is the same kinetic energy
    np.testing.assert_allclose(core.jacobi_kinetic_energy(y, m), T_cart, rtol=1e-13, atol=0)


def test_mass_matrix_off_diagonal_is_minus_m2_m3_over_M():
    m1, m2, m3 = m = np.array([1.3, 0.7, 2.1])
    M = m.sum()
    K = core.notes_mass_matrix(m)
    assert K[0, 1] == K[1, 0] == pytest.approx(-m2 * m3 / M, rel=1e-15)
    # independently, K from the Cartesian kinetic energy itself: with Ṙ = 0 the inverse map
    # (notes (3.32)–(3.34)) gives v1 = −(m2 u + m3 w)/M, v2 = v1 + u, v3 = v1 + w for
    # ṙ12 = u, ṙ13 = w, and T = ½ (K11 u² + K22 w² + 2 K12 u·w) (polarization)
    def T(u, w):
        v1 = -(m2 * u + m3 * w) / M
        return 0.5 * (m1 * v1 @ v1 + m2 * (v1 + u) @ (v1 + u) + m3 * (v1 + w) @ (v1 + w))

    e, o = np.array([1.0, 0.0, 0.0]), np.zeros(3)
    K11, K22 = 2 * T(e, o), 2 * T(o, e)
    K12 = T(e, e) - T(e, o) - T(o, e)
    np.testing.assert_allclose(K, [[K11, K12], [K12, K22]], rtol=1e-14)
    # and from Jacobi's diagonal form: (ρ1, ρ2) = (r12, r13 − m2 r12/(m1 + m2)) = A (r12, r13)
    # with det A = 1, so K = Aᵀ diag(μ1, μ2) A and det K = μ1 μ2 = m1 m2 m3/M
    _, mu1, mu2 = core.jacobi_masses(m)
    A = np.array([[1.0, 0.0], [-m2 / (m1 + m2), 1.0]])
    np.testing.assert_allclose(K, A.T @ np.diag([mu1, mu2]) @ A, rtol=1e-14)
    assert np.linalg.det(K) == pytest.approx(m1 * m2 * m3 / M, rel=1e-13)


@pytest.fixture(scope="module")
def sun_earth_moon(tmp_path_factory):
    """The shipped Sun–Earth–Moon config over 0.1 yr (longer than a sidereal month) without
    its study, simulated, archived against the kind's declared results and read back."""
    data = tomllib.loads((REPO / "configs" / "three_body_sun_earth_moon.toml").read_text())
    data.setdefault("run", {}).update({"t_end": 0.1, "samples": 801, "study": False})
    text = to_toml(data)
    scene = load_scene(parse_config_text(text))
    results = scene.simulate()
    path = tmp_path_factory.mktemp("sun_earth_moon") / "run.h5"
    write_archive(path, kind=scene.kind, title=scene.title, scene="sun_earth_moon",
                  config_text=text, config_sha256="0", results=results,
                  resolved_config=scene.resolved_config(), schema=scene.results_schema())
    return path, read_archive(path)


def test_archive_stores_the_notes_coordinates(sun_earth_moon):
    path, data = sun_earth_moon
    a = data.analysis
    y = np.asarray(data.runs["main"].y)
    m = np.asarray(data.config.params.masses, dtype=float)
    M = m.sum()
    # the coordinates as the notes write them (notes (3.32)–(3.34))
    np.testing.assert_array_equal(a["notes_coordinates"]["r12"], y[:, 3:6] - y[:, 0:3])
    np.testing.assert_array_equal(a["notes_coordinates"]["r13"], y[:, 6:9] - y[:, 0:3])
    K = np.asarray(a["notes_mass_matrix"])
    assert K.shape == (2, 2)
    assert K[0, 1] == K[1, 0] == pytest.approx(-m[1] * m[2] / M, rel=1e-15)
    # the identity holds to round-off, and the stored error says so
    assert a["notes_kinetic_identity_error"] <= 1e-12
    assert a["jacobi_kinetic_identity_error"] <= 1e-12
    # recomputed here from the stored velocities: T with its cross term against Σ ½ mᵢ vᵢ²
    v = y[:, 9:18].reshape(-1, 3, 3)
    Rd = np.einsum("b,nbk->nk", m, v) / M
    d12, d13 = v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]
    T = 0.5 * (M * np.sum(Rd**2, 1) + m[1] * (m[0] + m[2]) / M * np.sum(d12**2, 1)
               + m[2] * (m[0] + m[1]) / M * np.sum(d13**2, 1)
               - 2 * m[1] * m[2] / M * np.sum(d12 * d13, 1))
    assert float(np.max(np.abs(T / cartesian_T(y, m) - 1))) <= 1e-12
    # the cross term is about 2 m3/M of T here (Earth and Moon move together about the
    # Sun): small, but some 1e4 times what the identity check resolves
    share = a["notes_cross_term_share"]
    assert share == pytest.approx(2 * m[2] / M, rel=0.05)
    assert share > 1e4 * max(a["notes_kinetic_identity_error"], 1e-15)
    # the mass ratios stay the notes' (notes (3.35)): ~1e-6 and ~1e-8
    assert 1e-6 < a["mass_ratios"]["m2_m1"] < 1e-5 and 1e-8 < a["mass_ratios"]["m3_m1"] < 1e-7
    # declared: each new dataset carries its unit and a description naming its source
    with h5py.File(path, "r") as f:
        for name in ("notes_coordinates/r12", "notes_coordinates/r13", "notes_mass_matrix"):
            attrs = f["analysis"][name].attrs
            assert attrs["units"] == "1" and "notes (3.32)" in attrs["long_name"]


def test_moon_section_names_its_sources(sun_earth_moon):
    """Every equation number on the section names its document (notes (3.32), never a bare
    (3.32)), and Jacobi's coordinates are not presented as the notes'."""
    _, data = sun_earth_moon
    content = ThreeBodyScene.section_moon(data)
    texts = [t for pair in content.facts for t in pair]
    texts += [f.caption for f in content.figures] + [t.caption for t in content.tables]
    for text in texts:
        for hit in re.finditer(r"\(\d+\.\d+\)", text):
            assert text[:hit.start()].endswith("notes "), text
    facts = dict(content.facts)
    assert "mass ratios, notes (3.35)" in facts
    assert any("Jacobi" in k and "not in the notes" in k for k in facts)
    jacobi = next(f for f in content.figures if f.name == "jacobi")
    assert "not in the notes" in jacobi.caption and "(3.32)" not in jacobi.caption
    # the ρ2 − r13 distance the caption quotes is m2/(m1 + m2) |r12| (r13 − ρ2 = m2 r12/m12)
    m = np.asarray(data.config.params.masses, dtype=float)
    r12 = np.asarray(data.analysis["notes_coordinates"]["r12"])
    apart = m[1] / (m[0] + m[1]) * float(np.max(np.linalg.norm(r12, axis=1)))
    assert f"at most {fmt(apart, 3)} AU" in jacobi.caption
