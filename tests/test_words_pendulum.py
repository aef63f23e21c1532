"""The pendulum's words follow its own stored facts (issue 41), on scenes nobody shipped.

Each scene below has the shape of a case a reviewer found misdescribed (a libration just
below the separatrix read as "the period growing without bound"), or of a case the shipped
configs never reach (a start on the separatrix, a rotation just above it, a libration about
2π, a boundary-value problem past its conjugate point).  Each asserts the true words and
the absence of the false ones, and that every registered claim its report makes holds of its
archive (:func:`claimgen.contradictions_of`).  The numbers are recomputed here:
1 − k² = cos²(θ0/2) − (θ̇0/2ω0)² (DLMF 22.19.2 with k = sin(θmax/2)).
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

import claimgen
from reportgen.kinds.pendulum import claims

UNSEEN = Path(__file__).parent / "data" / "unseen"


def scene(initial, *, g=9.81, l=1.0, t_end=20.0, samples=2001, boundary=None):
    config = {"kind": "pendulum", "params": {"g": g, "l": l}, "initial": initial,
              "run": {"t_end": t_end, "samples": samples, "study": False}}
    if boundary is not None:
        config["boundary"] = boundary
    return config


def words(config, tmp_path, name="scene"):
    """(report text on one line, archive), asserting no claim of the text is false."""
    found, text = claimgen.contradictions_of(config, tmp_path, name)
    assert found == [], "\n".join(found)
    from reportgen.archive.store import read_archive
    return " ".join(text.split()), read_archive(tmp_path / name / "run.h5")


def test_libration_below_the_separatrix_states_its_own_finite_period(tmp_path):
    # the shape of configs/pendulum_separatrix.toml, not its numbers: 2e-3 rad below the
    # upright, l = 1.3 m: 1 − k² = sin²(1e-3) = 1e-6, a libration of finite period
    text, data = words(scene({"theta": math.pi - 2e-3}, l=1.3, t_end=40.0, samples=4001),
                       tmp_path)
    assert "the period growing without bound" not in text
    assert "libration just inside the separatrix (1 − k² = 10⁻⁶" in text
    assert "is a libration of finite period T = " in text
    # the divergence is the curve's, said of the curve
    assert ("grows without bound as θmax approaches π (logarithmically in the distance to the "
            "separatrix): a property of the curve, not of any one swing") in text
    assert data.analysis["separatrix_proximity"] == "near"
    assert float(data.analysis["complementary_parameter"]) == pytest.approx(
        math.sin(1e-3) ** 2, rel=1e-9)
    assert math.isfinite(float(data.analysis["period_measured"]))


def test_released_half_a_degree_below_the_upright(tmp_path):
    config = tomllib.loads((UNSEEN / "pendulum_179p5deg.toml").read_text(encoding="utf-8"))
    config["run"]["study"] = False
    text, data = words(config, tmp_path)
    # 1 − k² = cos²(89.75°) = 1.9e-5: near, below 1e-2; most of each period beyond 135°
    gap = math.cos(math.radians(89.75)) ** 2
    assert float(data.analysis["complementary_parameter"]) == pytest.approx(gap, rel=1e-9)
    assert "A pendulum librating just inside the separatrix" in text
    assert "spends most of each period beyond ±135°" in text
    assert "growing without bound" not in text and "on its separatrix" not in text
    share = claims._upright_fraction(data, gap)
    assert share > 0.7  # ~0.75 at 1 − k² = 1.9e-5 (t = F(φ | k²)/ω0)


def test_a_start_on_the_upright_is_on_the_separatrix(tmp_path):
    # θ0 = 180°: 1 − k² = cos²(π/2) = 3.7e-33 < 1e-12; no elliptic function resolves it
    text, data = words(scene({"theta": "180 deg"}, l=0.7), tmp_path)
    assert "A pendulum on its separatrix" in text and "below 10⁻¹²" in text
    assert "librating" not in text and "rotating" not in text
    assert "a reference run of scipy's DOP853" in text
    assert "exact elliptic-function solution" not in text
    assert "small-angle solution, an oscillation about the bottom, does not describe it" in text
    assert data.analysis["separatrix_proximity"] == "on"
    assert "small_angle_solution" not in data.analysis


def test_a_rotation_backwards_reads_as_one(tmp_path):
    # θ̇0 = −8 rad/s at θ0 = −1 rad, ω0 = √9.81: k² = sin²(½) + (8/2ω0)² = 1.86, a rotation
    text, data = words(scene({"theta": -1.0, "theta_dot": -8.0}, t_end=6.0), tmp_path)
    assert "A pendulum rotating over the top" in text
    assert "θ decreasing by 2π" in text and "θ increasing" not in text
    assert "librating" not in text and "a libration between" not in text
    assert "This orbit lies above it" in text
    assert "exact (Jacobi am)" in text  # the rotation's solution is the amplitude am


def test_a_rotation_just_above_the_separatrix(tmp_path):
    w0 = math.sqrt(9.81)  # k² − 1 = 1e-4 from the bottom
    text, data = words(scene({"theta": 0.0, "theta_dot": 2 * w0 * math.sqrt(1 + 1e-4)},
                             t_end=20.0), tmp_path)
    assert "A pendulum rotating just above the separatrix (k² − 1 = 10⁻⁴)" in text
    assert "spends most of each turn beyond ±135°" in text
    assert data.analysis["rotation_sense"] == "increasing"


def test_a_libration_about_two_pi(tmp_path):
    # θ0 = 4 rad is 2π − 2.283 rad: a libration about 2π, against the exact solution taken
    # about the same bottom (core's phase of such a start is off by half a period)
    text, data = words(scene({"theta": 4.0, "theta_dot": 0.5}, t_end=8.0), tmp_path)
    assert "between 2π ± " in text
    assert data.status == "ok"
    assert float(data.analysis["theta_max_error"]) < 1e-8
    theta = data.runs["main"]["theta"]
    assert np.all(np.abs(theta - 2 * math.pi) < math.pi)


@pytest.mark.parametrize("theta, said, unsaid", [
    (-0.25, "At this amplitude the two nearly agree", "runs ahead"),  # T/T0 − 1 = 0.39 %
    (2.2, "the linear solution runs ahead", "nearly agree")])  # T/T0 − 1 = 38 %
def test_the_small_angle_comparison_follows_the_period(tmp_path, theta, said, unsaid):
    text, data = words(scene({"theta": theta}, g=1.62, l=0.6, t_end=25.0), tmp_path)
    assert said in text and unsaid not in text
    excess = claims._excess(data)  # measured from the archived θ(t)
    assert (excess < 0.01) == (said.endswith("agree"))


@pytest.mark.parametrize("omega_T, said", [(2.0, "is short of the first conjugate point"),
                                           (4.0, "is past the first conjugate point")])
def test_the_action_is_a_minimum_only_before_the_conjugate_point(tmp_path, omega_T, said):
    w0 = math.sqrt(9.81 / 2.0)
    text, data = words(scene({"theta": 0.3}, l=2.0, t_end=5.0, samples=501,
                             boundary={"theta0": 0.2, "theta1": -0.1, "T": omega_T / w0}),
                       tmp_path)
    assert said in text
    assert data.analysis["boundary_value"]["conjugate_points"] == int(omega_T // math.pi)
    assert "solve_bvp" not in text


def test_predicates_fail_on_the_wrong_scene(tmp_path):
    """A predicate that cannot fail would be no check: each, run on an archive of the other
    case, says what it measured instead."""
    _, rotation = words(scene({"theta": 0.0, "theta_dot": 9.0}, t_end=4.0), tmp_path / "r")
    _, libration = words(scene({"theta": 1.0}, t_end=6.0), tmp_path / "l")
    assert isinstance(claims.librates(rotation), str)
    assert isinstance(claims.rotates(libration), str)
    assert isinstance(claims.on_separatrix(libration), str)
    assert isinstance(claims.near_inside(libration), str)
    assert isinstance(claims.nearly_agree(libration), str)  # 1 rad: T/T0 − 1 = 6.6 %
    assert isinstance(claims.rotation_decreasing(rotation), str)
    assert isinstance(claims.run_reference(libration), str)
