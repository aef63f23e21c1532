"""oscillator words that follow the scene's own stored facts (issue 41).

Whether the swap is canonical and whether the Hamilton–Jacobi pair (E, β) stays constant
along the integrated trajectory are stored with their thresholds; the report says what
they hold, and every claim it makes holds (:func:`claimgen.contradictions_of`).  The
predicates measure independently: {Q, P} from a linear fit of the archived image of the
orbit (Goldstein §9.5: 1 for a canonical map), E and β = atan2(mωq, p)/ω − t recomputed
along the run (notes (7.38)).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from claimgen import contradictions_of, run_config
from reportgen.kinds.oscillator import claims
from reportgen.scene.claims import contradictions


def scene(**run):
    """Not the shipped oscillator: m = 0.4 kg, ω = 3 rad/s from q₀ = −0.5 m, p₀ = 0.9."""
    return {"kind": "oscillator", "params": {"m": 0.4, "omega": 3.0},
            "initial": {"q": -0.5, "p": 0.9},
            "run": {"t_end": 12.0, "samples": 601, "study": False, **run}}


def test_pair_constant_and_swap_canonical(tmp_path):
    found, text = contradictions_of(scene(), tmp_path)
    assert found == []
    assert "integrated trajectory stays constant: it drifts by less than 10⁻⁶" in text
    assert "so the map is canonical" in text and "1 (canonical: |{Q, P} − 1| < 10⁻⁹" in text
    assert "drifts by more than" not in text


def test_a_drifting_pair_is_not_called_constant(tmp_path):
    # rtol 1e-5 over 40 periods: E and β drift by more than 10⁻⁶. The caption said "stays
    # constant" whatever the run.
    config = scene(t_end=40 * 2 * math.pi / 3.0, samples=1201, rtol=1e-5, atol=1e-7,
                   method="rk45")
    data = run_config(config, tmp_path)
    assert data.analysis["hj_pair_constant"] == "no"
    assert max(claims._drifts(data)) > 1e-6
    found, text = contradictions_of(config, tmp_path / "words")
    assert found == []
    assert "integrated trajectory drifts by more than 10⁻⁶" in text
    assert "stays constant" not in text


def test_study_reference_is_named_from_the_archive(tmp_path):
    config = scene(study=True, study_budget=0.3)
    data = run_config(config, tmp_path)
    assert data.study_attrs["reference_kind"].startswith("the closed form q₀ cos ωt")
    found, text = contradictions_of(config, tmp_path / "words")
    assert found == []
    assert "against the study's reference, the closed form q₀ cos ωt + p₀/(mω) sin ωt" in text


def test_predicates_measure_rather_than_reread(tmp_path):
    data = run_config(scene(), tmp_path)
    assert claims._bracket(data) == pytest.approx(1.0, abs=1e-12)
    # a map that is not canonical, (Q, P) = (p, −1.1 q): {Q, P} = 1.1 whatever is stored
    swapped = data.runs["swapped"]
    swapped.reference["P"] = 1.1 * np.asarray(swapped.reference["P"])
    assert data.analysis["swap_canonical"] == "yes"
    assert contradictions(data, "so the map is canonical")
    # a run whose E drifts, whatever hj_pair_constant says
    run = data.runs["main"]
    run.y[:, 1] *= 1 + 1e-4 * np.linspace(0, 1, len(run.t))
    assert contradictions(data, "the integrated trajectory stays constant")
    # a reference that is not the closed form
    run.reference["q"] = np.asarray(run.reference["q"]) * 1.001
    assert contradictions(data, "against the closed form")
