"""The heavy top's words follow its own stored facts (issue 41), on scenes nobody shipped.

A band with ``case = "all"`` holds three runs: its summary speaks of all three, each by its
own case and period; no report cites the internal "FIELD-NOTES"; a top near the vertical that
is not released at rest is not said to be; an exactly upright top below its threshold stays
upright; negative spins are printed with their sign.  Each scene asserts the true words, the
absence of the false ones, and that every registered claim its report makes holds of its
archive (:func:`claimgen.contradictions_of`).  Reference values are recomputed here from
notes (10.25)–(10.50): a = I3 ω3/I1, β = 2Mgl/I1, the threshold I3² ω3² = 4 I1 Mgl.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

import claimgen
from reportgen.archive.store import read_archive
from reportgen.core import heavy_top_theory as theory
from reportgen.kinds.heavy_top import claims
from reportgen.scene.content import fmt

UNSEEN = Path(__file__).parent / "data" / "unseen"


def words(config, tmp_path, name="scene"):
    """(report text on one line, archive), asserting no claim of the text is false."""
    found, text = claimgen.contradictions_of(config, tmp_path, name)
    assert found == [], "\n".join(found)
    return " ".join(text.split()), read_archive(tmp_path / name / "run.h5")


def top(*, initial=None, band=None, I1=1.0, I3=0.5, Mgl=1.0, t_end=12.0, samples=2401):
    config = {"kind": "heavy_top", "params": {"I1": I1, "I3": I3, "Mgl": Mgl},
              "run": {"t_end": t_end, "samples": samples, "study": False}}
    if band is not None:
        config["band"] = band
    else:
        config["initial"] = initial
    return config


@pytest.fixture(scope="module")
def all_band(tmp_path_factory):
    """Fig. 4.3's three cases on a band nobody shipped: 40°–55°, I3 = 0.8."""
    return words(top(band={"theta_min": "40 deg", "theta_max": "55 deg", "case": "all"},
                       I3=0.8, t_end=20.0, samples=4001), tmp_path_factory.mktemp("all"))


def test_the_summary_of_a_band_speaks_of_all_three_runs(all_band):
    text, data = all_band
    runs = data.analysis["band"]["runs"]
    for name in ("loops", "waves", "cusps"):
        run = runs[name]
        assert run["case"] == name
        assert (f"{name} run {name}, nutation period {fmt(run['nutation_period'])} s, "
                f"precession per period {fmt(run['precession_per_period'])} rad") in text
    # the loops run's case and period alone, as before, are gone; so is the archive path
    assert "case loops (a =" not in text
    assert "/runs/" not in text
    assert "Three heavy tops released on the same band, θ from 40° to 55°: looping, wavy and " \
           "cusped nutation" in text
    # the sections after Fig. 4.3 say whose constants they show
    assert "Constants of the motion and the roots of f(u) (the loops run)" in text


def test_no_report_cites_the_internal_notes(all_band, tmp_path):
    text, _ = all_band
    assert "FIELD-NOTES" not in text and "Goldstein §5.7" in text
    single, _ = words(top(initial={"theta": 0.9, "theta_dot": 0.0, "phi_dot": 0.7,
                                   "omega3": 7.0}), tmp_path)
    assert "FIELD-NOTES" not in single
    assert "the Jacobi form of t = ∫du/√f(u), notes (10.31) (Goldstein §5.7" in single


def test_the_band_of_25_to_40_degrees(tmp_path):
    config = tomllib.loads((UNSEEN / "heavy_top_band_25_40deg.toml").read_text(
        encoding="utf-8"))
    config["run"]["study"] = False
    text, data = words(config, tmp_path)
    band = data.analysis["band"]
    assert band["theta_min"] == pytest.approx(math.radians(25.0), rel=1e-15)
    assert band["theta_max"] == pytest.approx(math.radians(40.0), rel=1e-15)
    assert "θ from 25° to 40°" in text
    for name in ("loops", "waves", "cusps"):
        assert band["runs"][name]["case"] == name
        assert claims.band_loops(data) is True
    # φ̇ against the spin on the upper circle, with it on the lower one, for the loops
    loops = band["runs"]["loops"]
    assert loops["phi_dot_upper"] * loops["omega3"] < 0 < loops["phi_dot_lower"] * loops["omega3"]


@pytest.mark.parametrize("ratio, side, said", [
    (1.6, "above", "stable: the sleeping top stays upright"),
    (0.6, "below", "unstable: the sleeping top tilts away")])
def test_a_sleeping_top_on_either_side_of_its_threshold(tmp_path, ratio, side, said):
    I1, I3, Mgl = 2.0, 0.8, 1.5
    omega3 = ratio * 2.0 * math.sqrt(I1 * Mgl) / I3  # threshold ω3 = 2√(I1 Mgl)/I3, (10.50)
    text, data = words(top(initial={"theta": 2e-5, "theta_dot": 0.0, "phi_dot": 0.0,
                                    "omega3": omega3}, I1=I1, I3=I3, Mgl=Mgl, t_end=40.0,
                           samples=4001), tmp_path)
    assert f"{side} its sleeping threshold {fmt(2.0 * math.sqrt(I1 * Mgl) / I3, 4)} rad/s" in text
    assert said in text
    assert "released at rest 2 × 10⁻⁵ rad from the vertical" in text
    assert data.analysis["case"] == "cusps"
    if side == "above":  # θ2/θ1 = r/√(r² − 1) = 1.25 for r = 1.6: of the order of θ0
        assert "a band of the order of the initial tilt" in text
        assert data.analysis["tilt_growth"] == pytest.approx(ratio / math.sqrt(ratio**2 - 1),
                                                             rel=1e-3)
    else:  # γ = ½√(2β − a²) = √(Mgl/I1) √(1 − r²) = 0.693/s: 2e-5 rad grows to order one
        assert "then rises back to the vertical" in text


def test_an_upright_top_below_its_threshold_stays_upright(tmp_path):
    config = tomllib.loads((UNSEEN / "heavy_top_upright_too_slow.toml").read_text(
        encoding="utf-8"))
    config["run"]["study"] = False
    text, data = words(config, tmp_path)
    assert "standing exactly upright" in text
    assert "unstable equilibrium: the top starts exactly upright and stays there" in text
    assert "tilts away" not in text and "falls to θ" not in text
    assert float(max(data.runs["main"]["theta"])) == 0.0


def test_a_nearly_upright_top_with_a_precession_rate_is_not_released_at_rest(tmp_path):
    # θ0 = 1e-6 with φ̇0 = 0.3 a: φ̇ on the upper circle is φ̇0, not 0 — waves, not cusps
    # (b/a against u2 alone, relative to the band's width, called this a cusp)
    a = 0.5 * 2.4 / 1.0
    text, data = words(top(initial={"theta": 1e-6, "theta_dot": 0.0, "phi_dot": 0.3 * a,
                                    "omega3": 2.4}, t_end=10.0, samples=2001), tmp_path)
    assert data.analysis["case"] == "waves"
    assert "released at rest 10⁻⁶ rad" not in text and "so the tiny path has cusps" not in text
    assert "started 10⁻⁶ rad from the vertical with θ̇₀ = 0 rad/s, φ̇₀ = 0.36 rad/s" in text
    c = theory.constants(1.0, 0.5, 1.0, 1e-6, 0.0, 0.3 * a, 2.4)
    assert theory.classify(theory.roots(c), c) == "waves"


@pytest.mark.parametrize("steady, theta", [("fast", 2.0), ("slow", 0.7)])
def test_steady_precession_with_a_negative_spin(tmp_path, steady, theta):
    text, data = words(top(initial={"theta": theta, "theta_dot": 0.0, "steady": steady,
                                    "omega3": -7.0}, t_end=6.0, samples=1201), tmp_path)
    assert f"(the {steady} root of notes (10.45))" in text
    assert "ω₃ = −7 rad/s" in text or "ω3 = −7 rad/s" in text
    assert data.analysis["steady_root"] == steady


def test_a_top_spun_backwards_is_said_to_be(tmp_path):
    config = tomllib.loads((UNSEEN / "heavy_top_spun_backwards.toml").read_text(
        encoding="utf-8"))
    config["run"]["study"] = False
    text, data = words(config, tmp_path)
    assert "A heavy top spun at ω₃ = −9 rad/s" in text or "spun at ω3 = −9 rad/s" in text
    assert data.analysis["case"] == "loops"


def test_predicates_fail_on_the_wrong_scene(all_band):
    """Each case predicate, asked of another case's run, says what it measured instead."""
    _, data = all_band
    assert claims._case_holds(data, "loops", "waves") is not True
    assert claims._case_holds(data, "waves", "loops") is not True
    assert claims._case_holds(data, "cusps", "loops") is not True
    assert claims._case_holds(data, "steady", "cusps") is not True
    assert isinstance(claims.above_threshold(data), str) or isinstance(
        claims.below_threshold(data), str)
    assert isinstance(claims.exactly_upright(data), str)
