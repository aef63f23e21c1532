"""Words that follow the scene's own facts (issue 41), ``fput`` kind.

The energy-sharing sentences are chosen by stored classifications with their thresholds:
the stiff spring that starts with most of I (and its share, against 70 %), when it first
holds less than 70 % of I, whether ω is at least 5 times the soft springs' typical
frequency (two time scales), whether ω·max|I − I(0)|/I(0) is below 10, whether the stiff
springs start at rest.  Each on a chain nobody shipped; every claim its report makes holds
against its archive.  The studies are off.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np

import claimgen

UNSEEN = Path(__file__).resolve().parent / "data" / "unseen"


def _unseen(name: str, **run) -> dict:
    config = tomllib.loads((UNSEEN / f"{name}.toml").read_text(encoding="utf-8"))
    config["run"].update({"study": False, **run})
    return config


def _chain(m, omega, q, p, t_end=40.0):
    return {"kind": "fput", "params": {"m": m, "omega": omega},
            "initial": {"q": q, "p": p},
            "run": {"t_end": t_end, "samples": 801, "study": False}}


def test_energy_put_into_the_second_spring_is_followed_from_there(tmp_path):
    """The exchange time was the first time spring 1 held less than 70 % of I: with the
    energy in spring 2, t = 0 ("handed on from t ≈ 0").  Now it is spring 2's, the spring
    holding most of I(0); measured t ≈ 29.7 for ω = 40."""
    config = _unseen("fput_second_spring", t_end=60.0, samples=1201)
    data = claimgen.run_config(config, tmp_path)
    a = data.analysis
    assert a["first_spring"] == 2 and a["first_spring_share"] == 1.0
    energies = np.asarray(a["oscillatory_energies"])
    k = int(np.argmax(energies[:, 1] < 0.7 * energies.sum(axis=1)))
    assert k > 0 and a["exchange_time"] == data.runs["main"].t[k] and a["exchange_time"] > 10
    found, text = claimgen.contradictions_of(config, tmp_path, "again")
    assert "the energy put into stiff spring 2 is handed on from t ≈" in text
    assert "the energy put into stiff spring 1" not in text
    assert "I₂ first below 70 % of I" in text
    assert found == [], found


def test_a_soft_chain_has_no_two_time_scales(tmp_path):
    """ω = 4 is comparable with the soft springs' own frequency (measured ratio 1.5): the
    summary no longer says the stiff springs oscillate on a separate fast scale."""
    found, text = claimgen.contradictions_of(_unseen("fput_soft_chain", t_end=30.0,
                                                     samples=601), tmp_path)
    assert "comparable time scales" in text
    assert "two time scales)" not in text and "Two time scales" not in text
    assert "force explicit methods to resolve the period" not in text
    assert "this stays of order one here" not in text
    assert found == [], found


def test_stiff_springs_at_rest(tmp_path):
    """No oscillatory energy at t = 0: no spring "holds" it, and no ratio over I(0) = 0
    (it printed nan)."""
    config = _chain(2, 30.0, [0.8, 0.8, -0.8, -0.8], [0.4, 0.4, 0.4, 0.4])
    found, text = claimgen.contradictions_of(config, tmp_path)
    assert "the stiff springs start at rest" in text
    assert "nan" not in text.lower().split() and "the energy put into" not in text
    assert "ω (I(t) − I(0)) (dimensionless)" in text  # the panel is not divided by I(0)
    assert found == [], found


def test_one_stiff_spring_has_nothing_to_hand_on(tmp_path):
    config = _chain(1, 50.0, [1.0, 0.02], [1.0, 1.0], t_end=20.0)
    found, text = claimgen.contradictions_of(config, tmp_path)
    assert "one stiff spring, which holds all the oscillatory energy" in text
    assert "handed on" not in text and "moves between them" not in text
    assert found == [], found


def test_energy_spread_over_the_springs(tmp_path):
    config = _chain(3, 50.0, [0.5, -0.5, 0.4, -0.4, 0.3, -0.3], [0.0] * 6, t_end=20.0)
    found, text = claimgen.contradictions_of(config, tmp_path)
    assert "the oscillatory energy starts spread over the stiff springs" in text
    assert "the energy put into" not in text
    assert found == [], found
