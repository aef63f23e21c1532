"""three_body: words chosen by the scene's own stored facts (issue 41).

- A hierarchical triple (a tight binary and a distant third body) is classified from its
  trajectory (a pair bound throughout, its largest separation under 0.2 of the third body's
  smallest distance), and its pages say "not close encounters" without a section, panel or
  caption titled by close encounters (``close_encounters``: a closest approach under 0.05 of
  the pair's scale).
- The closest approach is located between the samples on the continuous solution, stored
  once and used by the headline, the gallery card, the prose and the figure; the sampled
  minimum is named as such.  Burrau's problem: 4.14 × 10⁻⁴ (bodies 4 and 5) at t ≈ 15.83,
  where the samples at the shipped spacing 0.005 come down only to 0.00597 (Szebehely &
  Peters 1967 put the closest approach near 10⁻⁴ around t ≈ 15.8).
- The figure-eight's words follow ``figure_eight`` (a planar choreography whose tangent
  turns by 0 in one period), not the preset; the restricted problem's words follow the
  run's formulation.
"""

from __future__ import annotations

import math

import pytest

import claimgen
from reportgen.rendering.report import report_text
from reportgen.scene.claims import contradictions

HIERARCHICAL = {"kind": "three_body", "params": {"masses": [1.0, 1.0, 0.05]},
                "initial": {"positions": [[-0.5, 0.0, 0.0], [0.5, 0.0, 0.0], [0.0, 10.0, 0.0]],
                            "velocities": [[0.0, -0.70711, 0.0], [0.0, 0.70711, 0.0],
                                           [-0.45, 0.0, 0.0]]},
                "run": {"t_end": 60.0, "samples": 3001, "study": False}}


def test_hierarchical_triple_has_no_close_encounter_titles(tmp_path):
    found, text = claimgen.contradictions_of(HIERARCHICAL, tmp_path)
    assert found == []
    assert "The system is hierarchical: body 1 and body 2 form a tight pair" in text
    assert "not close encounters" in text
    assert "Pair distances and close encounters" not in text
    assert "close encounters, coloured by time" not in text
    assert "the region of the close encounters" not in text


def test_the_claims_catch_close_encounter_words_on_a_hierarchical_triple(tmp_path):
    data = claimgen.run_config(HIERARCHICAL, tmp_path)
    assert data.analysis["hierarchical"] and not data.analysis["close_encounters"]
    said = contradictions(data, "Right: the region of the close encounters, enlarged")
    assert said and said[0].startswith("three_body close encounters")


@pytest.fixture(scope="module")
def burrau(tmp_path_factory):
    # Burrau's problem to t = 20 at the shipped output spacing 0.005: the first deep
    # encounter (bodies 4 and 5, t ≈ 15.83) is in it
    config = {"kind": "three_body", "preset": "pythagorean",
              "run": {"t_end": 20.0, "samples": 4001, "study": False}}
    return claimgen.run_config(config, tmp_path_factory.mktemp("burrau"))


def test_pythagorean_closest_approach_is_located_between_the_samples(burrau):
    a = burrau.analysis
    # measured: 4.13825e-4 at t = 15.82992 (bodies 2 and 3, masses 4 and 5); scipy's
    # DOP853 over the whole run at rtol 1e-13 with event location gives the same
    assert a["closest_approach"] == pytest.approx(4.138e-4, rel=2e-3)
    assert a["closest_approach_time"] == pytest.approx(15.830, abs=2e-3)
    assert list(a["closest_approach_pair"]) == [2, 3]
    assert a["min_pair_distance"] > 10 * a["closest_approach"]  # the samples miss it
    assert a["close_encounters"] and a["burrau"]


def test_pythagorean_headline_gallery_and_prose_use_the_one_closest_approach(burrau):
    from reportgen.kinds.three_body import ThreeBodyScene

    headline = dict(ThreeBodyScene.headline(burrau))
    assert headline["closest approach"].startswith("4.13")
    assert ThreeBodyScene.gallery_headline(burrau).startswith("closest approach 4.14e-4 at t = 15.83")
    text = report_text(burrau)
    assert contradictions(burrau, text) == []
    assert "closest approach 4.14 × 10⁻⁴" in text
    sampled = f"{burrau.analysis['min_pair_distance']:.5g}"
    assert f"closest approach {sampled}" not in text
    assert "smallest sampled pair distance" in text and "this is Burrau's problem" in text


def test_rescaled_figure_eight_is_named_by_its_shape_not_the_preset(tmp_path):
    L, m = 2.0, 0.5  # lengths × 2, masses × 1/2: period × 2^1.5 × √2 = 4
    v = math.sqrt(m / L)
    config = {"kind": "three_body", "params": {"masses": [m, m, m]},
              "initial": {"positions": [[0.97000436 * L, -0.24308753 * L, 0.0],
                                        [-0.97000436 * L, 0.24308753 * L, 0.0],
                                        [0.0, 0.0, 0.0]],
                          "velocities": [[0.466203685 * v, 0.43236573 * v, 0.0]] * 2
                          + [[-0.93240737 * v, -0.86473146 * v, 0.0]]},
              "period": 6.32591398 * 4.0,
              "run": {"t_end": 6.32591398 * 4.0, "samples": 1501, "study": False,
                      "rtol": 1e-12, "atol": 1e-14}}
    found, text = claimgen.contradictions_of(config, tmp_path)
    assert found == []
    assert "Three equal masses on the figure-eight choreography" in text
    config["params"]["masses"] = [m, m, 1.1 * m]
    found, text = claimgen.contradictions_of(config, tmp_path / "perturbed")
    assert found == [] and "figure-eight" not in text and "not periodic" in text


def test_restricted_words_follow_the_formulation(tmp_path):
    config = {"kind": "three_body",
              "restricted": {"mu": 0.1, "x": 0.3, "jacobi": 3.5},
              "run": {"t_end": 10.0, "samples": 801, "study": False, "method": "rk45"}}
    found, text = claimgen.contradictions_of(config, tmp_path)
    assert found == []
    assert "integrates the Cartesian equations of the rotating frame" in text
    assert "The run uses the Thiele–Burrau variables" not in text


def test_restricted_start_next_to_its_zero_velocity_curve_is_confined(tmp_path):
    """μ = 1/2, C between the values at L2 and L1, the start 10⁻³ inside its curve: the
    grid cell at the start is forbidden, yet the region is enclosed (it was called "not
    confined")."""
    x = -1.0
    two_omega = x * x + 1.0 / abs(x + 0.5) + 1.0 / abs(x - 0.5)
    config = {"kind": "three_body",
              "restricted": {"mu": 0.5, "x": x, "vy": math.sqrt(1e-3)},
              "run": {"t_end": 10.0, "samples": 801, "study": False}}
    found, text = claimgen.contradictions_of(config, tmp_path)
    assert two_omega - 1e-3 == pytest.approx(3.665667, abs=1e-6)
    assert found == [] and "encloses the region of its start" in text
