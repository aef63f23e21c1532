"""rotation: the words of each checks table and of the contrasts follow the scene's own
stored facts (issue 41).

Every checks table says whether its identities hold ("all 7 axis–angle checks hold"),
chosen by the stored errors against the bound 10⁻¹²; the stereographic section's
contrasts say whether R(U)ᵀ is the Möbius map and whether the reversed product is another
rotation, chosen by ``transpose_differs`` / ``transpose_differs_standard`` /
``reversed_differs`` (a distance above 10⁻⁹).  They used to say "the transpose is not the
Möbius map" and "the reversed order is another rotation" for every scene: false for a half
turn (R symmetric) and for an [su2] table alone (U₂ = U commutes with U)."""

from __future__ import annotations

import claimgen
from reportgen.scene.claims import contradictions


def plain(text: str) -> str:
    """The page's words with the transpose's superscript T as a letter (the typesetter
    sets Rᵀ as R<sup>T</sup>)."""
    return " ".join(text.replace("ᵀ", "T").split())


def test_half_turn_alone_says_the_transpose_is_the_map_and_the_order_commutes(tmp_path):
    config = {"kind": "rotation", "su2": {"axis": [1.0, 0.0, 1.0], "angle": "180 deg",
                                          "points": 120}}
    found, text = claimgen.contradictions_of(config, tmp_path)
    text = plain(text)
    assert found == []
    assert plain("here R(U)ᵀ is the Möbius map too: R(U) is symmetric (a half turn)") in text
    assert "the reversed order gives the same rotation here (U and U₂ commute)" in text
    assert plain("R(U)ᵀ is the same map") in text
    assert plain("R(U)ᵀ is not the Möbius map") not in text
    assert "the reversed order is another rotation" not in text
    assert "all 13 Möbius-map checks hold" in text


def test_general_turn_keeps_the_contrasts(tmp_path):
    config = {"kind": "rotation", "axis_angle": {"axis": [1.0, 2.0, 2.0], "angle": 1.0},
              "su2": {"axis": [0.3, -0.4, 0.8], "angle": 2.5, "points": 120}}
    found, text = claimgen.contradictions_of(config, tmp_path)
    text = plain(text)
    assert found == []
    assert plain("R(U)ᵀ is not the Möbius map; nor is it with the usual orientation") in text
    assert "the reversed order is another rotation" in text
    assert "all 7 axis–angle checks hold" in text


def test_the_claims_catch_the_old_contrast_words(tmp_path):
    data = claimgen.run_config({"kind": "rotation",
                                "su2": {"axis": [0.0, 1.0, 0.0], "angle": "180 deg"}},
                               tmp_path)
    said = contradictions(data, "Not checks: R(U)ᵀ is not the Möbius map; the reversed "
                                "order is another rotation")
    assert {line.split(":")[0] for line in said} == {"rotation transpose differs",
                                                     "rotation reversed order differs"}
    assert contradictions(data, "all 13 Möbius-map checks hold") == []
    assert contradictions(data, "2 of 13 Möbius-map checks fail")  # they all hold


def test_euler_path_verdicts_and_order_words(tmp_path):
    # fast spin on a coarse path: h max|ω| = 0.6 > 0.5, the order is not checked
    config = {"kind": "rotation",
              "axis_angle": {"axis": [1.0, 1.0, 0.0], "angle": "0.5 deg"},
              "euler": {"convention": "zyz", "angles": ["30 deg", "60 deg", "-45 deg"],
                        "rates": [0.2, 0.1, 6.0], "duration": 3.0, "samples": 31}}
    found, text = claimgen.contradictions_of(config, tmp_path)
    assert found == []
    assert "both Euler-matrix checks hold" in text
    assert "all 6 angular-velocity checks hold" in text
    assert "not checked, as h max |ω| is above 0.5" in text
