"""C₂H₂ (acetylene, H–C≡C–H), a linear molecule of four atoms (textbook ch. 5, §5.1):
3 translations and 2 rotations, n − 1 = 3 longitudinal and 2(n − 2) = 4 transverse vibrations.

References checked here (each an independent computation, not the kind's code):
- along the axis: the 1-D chain of masses m_H, m_C, m_C, m_H and springs k1, k2, k1, whose
  stiffness matrix is written out here and solved with numpy; in closed form, even modes
  (x1 = −x4, x2 = −x3) have ω² summing to k1/m + (k1 + 2k2)/M with product 2k1k2/(mM), the
  odd one ω² = k1(1/m + 1/M) (derived from m ä = −k1(a − b), M b̈ = −k1(b − a) − 2k2 b)
- across the axis: V = ½k_θ(ρ1² + ρ2²), ρ the linear-bend coordinates of Wilson, Decius &
  Cross ch. 4 written out here, solved with numpy; closed forms: trans bend
  ω² = k_θ[1/(m r1²) + (1/r1 + 2/r2)²/M], cis bend ω² = k_θ(1/m + 1/M)/r1²
- ν̃ = ω/(2πc), c = 2.99792458e10 cm/s (exact, SI definition)
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from reportgen.core import normal_modes as core
from reportgen.kinds import load_scene
from reportgen.kinds.normal_modes.results import MOLECULAR_OMEGA
from reportgen.scene.config import parse_config_text

REPO = Path(__file__).resolve().parent.parent
CONFIG = REPO / "configs" / "normal_modes_c2h2.toml"
M_H, M_C = core.ELEMENT_MASSES["H"], core.ELEMENT_MASSES["C"]
LIGHT_CM_PER_S = 2.99792458e10


def constants():
    """k(C–H), k(C≡C), k_θ, r(C–H), r(C≡C) as the shipped config gives them."""
    cfg = tomllib.loads(CONFIG.read_text())
    x = [atom["position"][0] for atom in cfg["atoms"]]
    k1, k2, _k1 = (bond["k"] for bond in cfg["bonds"])
    kb = cfg["angles"][0]["k"]
    return k1, k2, kb, x[1] - x[0], x[2] - x[1]


@pytest.fixture(scope="module")
def c2h2():
    s = load_scene(parse_config_text(CONFIG.read_text()))
    return s, s.simulate()


def chain_omega(k1, k2, m, M):
    """ω of the longitudinal chain m–M–M–m with springs k1, k2, k1 (numpy), zero dropped."""
    K = np.array([[k1, -k1, 0, 0], [-k1, k1 + k2, -k2, 0],
                  [0, -k2, k2 + k1, -k1], [0, 0, -k1, k1]], dtype=float)
    s = 1 / np.sqrt([m, M, M, m])
    w2 = np.linalg.eigvalsh(s[:, None] * K * s[None, :])
    assert abs(w2[0]) < 1e-12 * w2[-1]  # the translation along the axis
    return np.sqrt(w2[1:])


def bend_omega(kb, r1, r2, m, M):
    """ω of the transverse motion in one plane (numpy), the translation and rotation dropped."""
    B = np.array([[1 / r1, -1 / r1 - 1 / r2, 1 / r2, 0],
                  [0, 1 / r2, -1 / r2 - 1 / r1, 1 / r1]])
    K = kb * B.T @ B
    s = 1 / np.sqrt([m, M, M, m])
    w2 = np.linalg.eigvalsh(s[:, None] * K * s[None, :])
    assert np.all(np.abs(w2[:2]) < 1e-12 * w2[-1])  # translation and rotation in the plane
    return np.sqrt(w2[2:])


def test_counting_three_longitudinal_four_transverse(c2h2):
    _s, res = c2h2
    a = res.analysis
    assert a["linear"] and len(a["masses"]) == 4
    types = list(a["mode_type"])
    assert types[:5] == ["translation"] * 3 + ["rotation"] * 2  # 3n − 5 = 7 vibrations left
    assert a["n_zero_modes"] == 5 and a["n_vibrational"] == 7
    assert a["n_longitudinal"] == 3 == a["expected_longitudinal"]  # n − 1
    assert a["n_transverse"] == 4 == a["expected_transverse"]  # 2(n − 2)
    groups = np.asarray(a["degenerate_group"])
    transverse = [i for i, t in enumerate(types) if t.startswith("transverse")]
    pairs = {int(groups[i]) for i in transverse}
    assert len(pairs) == 2 and all(np.sum(groups == g) == 2 for g in pairs)  # two twofold bends
    # named by the bonds that hold their potential energy (two kinds: C–H and C≡C), and by
    # their parity under the centre of inversion
    assert sorted(t for t in types if t.startswith("longitudinal")) == [
        "longitudinal, antisymmetric C–H stretch", "longitudinal, symmetric C–C stretch",
        "longitudinal, symmetric C–H stretch"]


def test_longitudinal_frequencies_are_the_four_mass_chain(c2h2):
    _s, res = c2h2
    a = res.analysis
    k1, k2, *_ = constants()
    w = np.asarray(a["frequencies"]) / MOLECULAR_OMEGA  # the config's units
    types = list(a["mode_type"])
    longitudinal = np.sort([w[i] for i, t in enumerate(types) if t.startswith("longitudinal")])
    np.testing.assert_allclose(longitudinal, chain_omega(k1, k2, M_H, M_C), rtol=1e-12)
    # closed form: ω² = [S ± √(S² − 4P)]/2 (even) and k1(1/m + 1/M) (odd)
    S, P = k1 / M_H + (k1 + 2 * k2) / M_C, 2 * k1 * k2 / (M_H * M_C)
    even = [(S - math.sqrt(S * S - 4 * P)) / 2, (S + math.sqrt(S * S - 4 * P)) / 2]
    odd = k1 * (1 / M_H + 1 / M_C)
    np.testing.assert_allclose(longitudinal, np.sqrt(sorted([*even, odd])), rtol=1e-12)


def test_transverse_frequencies_are_the_two_linear_bends(c2h2):
    _s, res = c2h2
    a = res.analysis
    _k1, _k2, kb, r1, r2 = constants()
    w = np.asarray(a["frequencies"]) / MOLECULAR_OMEGA
    types = list(a["mode_type"])
    transverse = np.sort([w[i] for i, t in enumerate(types) if t.startswith("transverse")])
    plane = bend_omega(kb, r1, r2, M_H, M_C)
    np.testing.assert_allclose(transverse, np.sort(np.repeat(plane, 2)), rtol=1e-12)
    trans = math.sqrt(kb * (1 / (M_H * r1 * r1) + (1 / r1 + 2 / r2) ** 2 / M_C))
    cis = math.sqrt(kb * (1 / M_H + 1 / M_C) / (r1 * r1))
    np.testing.assert_allclose(plane, sorted([trans, cis]), rtol=1e-12)


def test_wavenumbers_parity_and_checks(c2h2):
    _s, res = c2h2
    a = res.analysis
    nu = np.asarray(a["wavenumbers"])
    np.testing.assert_allclose(nu, np.asarray(a["frequencies"]) / (2 * math.pi * LIGHT_CM_PER_S),
                               rtol=1e-15)
    # the inversion by hand: atom a → 3 − a, every displacement reversed
    S = np.zeros((12, 12))
    for atom in range(4):
        S[3 * (3 - atom):3 * (3 - atom) + 3, 3 * atom:3 * atom + 3] = -np.eye(3)
    modes, types, parity = np.asarray(a["modes"]), list(a["mode_type"]), list(a["mode_parity"])
    for i in range(5, 12):
        sign = {"g": 1.0, "u": -1.0}[parity[i]]
        np.testing.assert_allclose(S @ modes[:, i], sign * modes[:, i], atol=1e-12)
    # symmetric stretches are the even ones; the trans bend (even) lies above the cis bend here
    for i in range(5, 12):
        if types[i].startswith("longitudinal"):
            assert ("antisymmetric" in types[i]) == (parity[i] == "u")
    bends = sorted((nu[i], parity[i]) for i in range(5, 12) if types[i].startswith("trans"))
    assert [p for _n, p in bends] == ["u", "u", "g", "g"]
    # every closed-form check of the kind (ν1 … ν5), and the whole spectrum
    assert len(res.checks) >= 6 and all(c.rel_error < 1e-12 for c in res.checks)
    assert a["closed_form_max_rel_error"] < 1e-12
    np.testing.assert_allclose(a["frequencies_exact"][5:], a["frequencies"][5:], rtol=1e-12)


def test_report_counts_and_lists_the_wavenumbers(c2h2):
    s, res = c2h2
    from reportgen.archive.store import ArchiveData, ConfigView

    data = ArchiveData(path=Path("x.h5"), attrs={}, config_text="", provenance={},
                       analysis=res.analysis, runs=res.runs,
                       config=ConfigView.of(s.resolved_config()))
    counting = type(s).section_counting(data)
    found = {row[0]: row[1:] for row in counting.tables[0].rows}
    assert found["longitudinal vibrations"] == ["3", "n − 1 = 3"]
    assert found["transverse vibrations"] == ["4", "2(n − 2) = 4"]
    assert found["rigid rotations (rank of ω × r)"] == ["2", "2 (linear)"]
    axis = counting.tables[1]
    assert axis.header[-1] == "wavenumbers ν̃ [cm⁻¹]"
    nu = np.asarray(res.analysis["wavenumbers"])
    longitudinal, transverse = axis.rows
    assert longitudinal[1] == "3" and transverse[1] == "4"
    assert transverse[2].count("(×2)") == 2
    assert longitudinal[2].split(", ")[0] == f"{float(np.sort(nu)[-3]):.5g}"
    spectrum = type(s).section_spectrum(data).tables[0]
    assert "inversion" in spectrum.header and "closed form" in spectrum.header


def test_co2_parity_and_h2o_without_a_centre():
    # CO₂ has a centre of symmetry: the symmetric stretch is even, the others odd
    co2 = load_scene(parse_config_text('kind = "normal_modes"\npreset = "co2"\n')).simulate()
    a = co2.analysis
    parity = dict(zip(a["mode_type"][5:], a["mode_parity"][5:], strict=True))
    assert parity == {"longitudinal, symmetric stretch": "g",
                      "longitudinal, antisymmetric stretch": "u",
                      "transverse (in-plane)": "u", "transverse (out-of-plane)": "u"}
    assert "frequencies_exact" not in a  # not an X–Y–Y–X
    h2o = load_scene(parse_config_text('kind = "normal_modes"\npreset = "h2o"\n')).simulate()
    assert "mode_parity" not in h2o.analysis


def test_an_unsymmetric_four_atom_chain_has_no_closed_form():
    # H–C≡C–D: the end masses differ, so neither the inversion nor the closed form applies
    text = CONFIG.read_text().replace('element = "H"\nposition = [1.6645',
                                      'mass = 2.014\nposition = [1.6645')
    res = load_scene(parse_config_text(text)).simulate()
    a = res.analysis
    assert a["n_longitudinal"] == 3 and a["n_transverse"] == 4
    assert "mode_parity" not in a and "frequencies_exact" not in a
    k1, k2, *_ = constants()
    w = np.asarray(a["frequencies"]) / MOLECULAR_OMEGA
    longitudinal = np.sort([w[i] for i, t in enumerate(a["mode_type"])
                            if t.startswith("longitudinal")])
    # the chain m_H–M–M–m_D, by numpy
    K = np.array([[k1, -k1, 0, 0], [-k1, k1 + k2, -k2, 0],
                  [0, -k2, k2 + k1, -k1], [0, 0, -k1, k1]], dtype=float)
    s = 1 / np.sqrt([M_H, M_C, M_C, 2.014])
    ref = np.sqrt(np.linalg.eigvalsh(s[:, None] * K * s[None, :])[1:])
    np.testing.assert_allclose(longitudinal, ref, rtol=1e-12)
