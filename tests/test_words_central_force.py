"""central_force words that follow the scene's own stored facts (issue 41).

Scenes of the same shape as the shipped ones but not shipped: the words for the apsides'
direction, the orbit's shape, the study's reference, the Laplace–Runge–Lenz vector and the
Kepler elements are each chosen by a stored case with its threshold, and every claim the
report makes holds (:func:`claimgen.contradictions_of`).

References: the near-circular apsidal angle π/√(2 − n) of V = −k/rⁿ (Landau & Lifshitz
§14 problem 2): below π for n < 1 (the pericentre regresses), above π for n > 1; the exact
π/√(1 − 2με/L²) of V = −k/r − ε/r² (Landau & Lifshitz §15 problem 3): below π for ε < 0.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from claimgen import contradictions_of, run_config
from reportgen.kinds.central_force import apsides
from reportgen.kinds.central_force.cases import APSIDAL_SHIFT_NONE


def scene(params=None, initial=None, **run):
    """The lecture's rosette (m1 = m2 = 1 kg, k = 0.5, started at (1, 0) with vy = 0.8)
    with other params; no study unless asked."""
    return {"kind": "central_force",
            "params": {"m1": 1.0, "m2": 1.0, "k": 0.5, **(params or {})},
            "initial": initial or {"x": 1.0, "y": 0.0, "vx": 0.0, "vy": 0.8},
            "run": {"t_end": 40.0, "samples": 4001, "study": False, **run}}


def words(config, tmp_path):
    found, text = contradictions_of(config, tmp_path)
    assert found == [], found
    return text


def test_weaker_than_coulomb_power_law_regresses(tmp_path):
    # n = 0.6 < 1: ψ < π. The report said "the pericentre advances −78.47°" for n = 0.4.
    text = words(scene({"potential": "power", "n": 0.6}), tmp_path)
    assert "a rosette whose pericentre regresses" in text
    assert "is less than π, so the pericentre regresses by" in text
    assert "advances" not in text and "advancing" not in text
    assert "advances −" not in text and "−7" not in text.split("regresses")[1][:4]


def test_stronger_than_coulomb_power_law_advances(tmp_path):
    text = words(scene({"potential": "power", "n": 1.35}), tmp_path)
    assert "a rosette whose pericentre advances" in text
    assert "is greater than π, so the pericentre advances by" in text
    assert "regress" not in text


@pytest.mark.parametrize("epsilon, expect, absent", [
    (-0.02, "pericentre regresses", "advances"),
    (0.02, "pericentre advances", "regresses"),
    (0.0, "the pericentre stays put", "rosette")])
def test_inverse_cube_term_decides_the_direction(tmp_path, epsilon, expect, absent):
    data = run_config(scene({"potential": "kepler_inverse_cube", "epsilon": epsilon}),
                      tmp_path)
    shift = data.analysis["apsidal_shift"]
    # 2ψ − 2π with ψ = π/√(1 − 2με/L²), μ = 0.5, L = 0.4
    exact = 2 * math.pi / math.sqrt(1 - 2 * 0.5 * epsilon / 0.4**2) - 2 * math.pi
    assert shift == pytest.approx(exact, rel=1e-12, abs=1e-15)
    text = words(scene({"potential": "kepler_inverse_cube", "epsilon": epsilon}),
                 tmp_path / "words")
    assert expect in text and absent not in text


def test_power_law_with_n_one_closes(tmp_path):
    data = run_config(scene({"potential": "power", "n": 1.0}), tmp_path)
    assert data.analysis["apsides"] == "fixed" and data.analysis["orbit_shape"] == "closed"
    assert abs(data.analysis["apsidal_shift"]) < APSIDAL_SHIFT_NONE
    text = words(scene({"potential": "power", "n": 1.0}), tmp_path / "words")
    assert "it closes, the pericentre turning by less than 10⁻⁸ rad" in text
    assert "rosette" not in text and "advances" not in text


def test_rosette_has_no_lrl_and_no_kepler_elements(tmp_path):
    text = words(scene({"potential": "power", "n": 0.6}), tmp_path)
    # only V = −k/r conserves (and draws) the Laplace–Runge–Lenz vector
    assert "LRL" not in text and "Laplace–Runge–Lenz" not in text
    assert "Drift of the conserved quantities: E and L relative to their size." in text
    # e, a, period named for what they are off V = −k/r
    assert "Kepler elements" not in text
    assert "orbit, from its turning points" in text
    assert "radial period (pericentre to pericentre)" in text


def test_kepler_orbit_keeps_lrl_and_its_elements(tmp_path):
    text = words(scene(initial={"x": 1.0, "y": 0.0, "vx": 0.0, "vy": 0.8}), tmp_path)
    assert "orbit, Kepler elements" in text and "bound Kepler ellipse" in text
    assert "the LRL components relative to μk" in text


@pytest.mark.parametrize("potential, n", [("power", 0.6), ("kepler", None)])
def test_study_reference_is_the_one_the_archive_used(tmp_path, potential, n):
    params = {"potential": potential, "n": n} if n else {}
    config = scene(params, t_end=12.0, samples=601, study=True, study_budget=0.3)
    data = run_config(config, tmp_path)
    reference = data.study_attrs["reference_kind"]
    text = words(config, tmp_path / "words")
    if potential == "power":  # no Kepler's equation for V = −k/rⁿ
        assert reference.startswith("a reference run, compiled DOP853")
        assert "Kepler's equation" not in text and "Kepler-equation" not in text
        assert "its maximum error against the study's reference, a reference run" in text
    else:
        assert "Kepler's equation" in reference
        assert "against the study's reference, the solution of Kepler's equation" in text


def test_heavier_body_is_named(tmp_path):
    text = words(scene({"m2": 3.0, "potential": "power", "n": 1.35}), tmp_path)
    assert "The heavier body, body 2 (m₂ = 3 kg), moves on the smaller curve." in text
    assert "With equal masses" not in text


def test_circular_orbit_of_a_power_law(tmp_path):
    # v = √(k n/(μ rⁿ)) at r = 1: the circle of V = −k/r^1.5 (this crashed the quadrature)
    v = math.sqrt(0.5 * 1.5 / 0.5)
    text = words(scene({"potential": "power", "n": 1.5},
                       {"x": 1.0, "y": 0.0, "vx": 0.0, "vy": v}, t_end=10.0, samples=1001),
                 tmp_path)
    assert "A circular orbit in V = −k/r¹·⁵, r = 1 m: period of revolution" in text
    assert "rosette" not in text and "pericentre advances" not in text


def test_inverse_cube_title_counts_the_epsilon_term():
    # E = ½μv² − k/r − ε/r²: 0.25·0.81 − 0.5 + 0.4 > 0 escapes although −k/r alone binds
    from reportgen.kinds.central_force import CentralForceScene
    from reportgen.kinds.central_force.config import CentralForceConfig

    config = CentralForceConfig.model_validate(
        scene({"potential": "kepler_inverse_cube", "epsilon": -0.4},
              {"x": 1.0, "y": 0.0, "vx": 0.0, "vy": 0.9}) | {"kind": "central_force"})
    assert CentralForceScene.default_title(config).endswith(": an escaping orbit")


def test_apsidal_angle_keeps_its_figures_near_the_circle():
    # n = 1: ψ = π at every e, the near-circular limit π/√(2 − n) as e → 0
    for e in (1e-9, 1e-5, 1e-2, 0.5, 0.95):
        assert apsides.apsidal_angle_power(1 - e, 1 + e, 1.0) == pytest.approx(math.pi,
                                                                               rel=1e-14)
    for n in (0.3, 1.7):
        assert apsides.apsidal_angle_power(1.0, 1.0 + 1e-9, n) == pytest.approx(
            math.pi / math.sqrt(2 - n), rel=1e-8)
    # against mpmath at 40 digits: ψ = ∫ du/√f(u) from u₁ to u₂, f = a + b uⁿ − u² (tanh-sinh
    # takes the inverse square-root ends; a node where f rounds to 0 weighs nothing)
    mp.mp.dps = 40
    u1, u2, n = mp.mpf(1) / 3, mp.mpf(1), mp.mpf("0.4")
    b = (u2**2 - u1**2) / (u2**n - u1**n)
    a = u1**2 - b * u1**n

    def integrand(u):
        f = a + b * u**n - u * u
        return 1 / mp.sqrt(f) if f > 0 else mp.mpf(0)

    psi = float(mp.quad(integrand, [u1, u2]))
    mp.mp.dps = 15
    assert apsides.apsidal_angle_power(1.0, 3.0, 0.4) == pytest.approx(psi, rel=1e-13)
    assert np.isfinite(apsides.apsidal_angle_family_power(np.linspace(0, 0.9, 10), 0.4)).all()


def test_predicates_measure_rather_than_reread(tmp_path):
    # the n = 0.4 rosette: the old words contradict its archive, whatever is stored
    from reportgen.scene.claims import contradictions

    data = run_config(scene({"potential": "power", "n": 0.4}, t_end=80.0, samples=8001),
                      tmp_path)
    assert data.analysis["apsides"] == "regress"
    old = ("a rosette whose pericentre advances −77.31° per radial period. "
           "the LRL components relative to μk. orbit, Kepler elements e = 0.33")
    found = contradictions(data, old)
    assert any("apsides advance" in f for f in found)
    assert any("Laplace–Runge–Lenz" in f for f in found)
    # the measured shift, between the run's own pericentres and by quadrature, agree with
    # the stored one: 2ψ − 2π = −77.31° (ψ = 2.46691 rad)
    from reportgen.kinds.central_force import claims

    shift, err = claims._measured_shift(data)
    assert math.degrees(data.analysis["apsidal_shift"]) == pytest.approx(-77.31, abs=0.01)
    assert shift == pytest.approx(data.analysis["apsidal_shift"], abs=max(3 * err, 1e-9))
    assert claims._quadrature_shift(data) == pytest.approx(data.analysis["apsidal_shift"],
                                                           abs=1e-10)
    # a flag flipped in the archive does not make the old sentence true
    data.analysis["apsides"] = "advance"
    assert any("apsides advance" in f for f in contradictions(data, old))
