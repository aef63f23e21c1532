"""Words that follow the scene's own facts (issue 41): the normal-mode report names each
vibration by the molecule's symmetry and the internal coordinates that hold its energy,
and says the time of an evolution in a unit, on scenes nobody shipped.

Each scene here is simulated without the study and its report's visible text checked
against the claims registry (``claimgen.contradictions_of``) and for the words it must
(and must no longer) say.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

import claimgen

UNSEEN = Path(__file__).parent / "data" / "unseen"


def _molecule(elements, positions, ks, k_bend=None, angle=(0, 1, 2), **extra):
    config = {"kind": "normal_modes",
              "atoms": [{"element": e, "position": list(p)} for e, p in zip(elements, positions,
                                                                             strict=True)],
              "bonds": [{"atoms": [i, i + 1], "k": k} for i, k in enumerate(ks)]}
    if k_bend is not None:
        config["angles"] = [{"atoms": list(angle), "k": k_bend}]
    config.update(extra)
    return config


def _ocs(**extra) -> dict:
    config = tomllib.loads((UNSEEN / "normal_modes_ocs.toml").read_text())
    config.pop("evolve")
    config.update(extra)
    return config


@pytest.fixture(scope="module")
def ocs(tmp_path_factory):
    return claimgen.contradictions_of(_ocs(), tmp_path_factory.mktemp("ocs"))


def test_ocs_stretches_are_named_by_their_bonds_not_by_a_symmetry_it_lacks(ocs):
    """O=C=S has no centre of inversion: its stretches are the C–O and the C–S stretch
    (each holds ~81 % of its mode's potential energy), not CO₂'s symmetric and
    antisymmetric stretch (what the report said before)."""
    contradictions, text = ocs
    assert contradictions == []
    assert "longitudinal, C–S stretch" in text and "longitudinal, C–O stretch" in text
    assert not re.search(r"\b(?:anti)?symmetric stretch", text)
    assert "has no centre of inversion" in text
    assert "81 %" in text  # the share of the potential energy that names each stretch


def test_ocs_evolution_time_is_one_number_with_a_unit(tmp_path):
    """The check at the end of an evolution said "t = 49.08 4.075 fs" (the time in τ
    followed by τ in fs); it is now the time in femtoseconds."""
    config = _ocs(evolve={"displacement": [[-0.02, 0, 0], [0, 0, 0], [0.01, 0, 0]],
                          "t_end": "200 fs"}, run={"samples": 801, "study": False})
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert re.search(r"\(t\s=\s200 fs\)", text), text[:2000]
    assert not re.search(r"\d\s+4\.075 fs", text)
    assert "times in τ = √(u/(mdyn/Å)) = 4.075 fs" in text
    assert "time t [fs]" in text  # the evolution's time axis in femtoseconds


def test_equal_masses_on_a_line_have_a_centre_of_inversion(tmp_path):
    """O–O–O on a line (all three masses equal, equal bonds): the inversion names the
    stretches symmetric (g) and antisymmetric (u)."""
    config = _molecule("OOO", [(-1.28, 0, 0), (0, 0, 0), (1.28, 0, 0)], [6.0, 6.0], 0.5)
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "longitudinal, symmetric stretch" in text
    assert "longitudinal, antisymmetric stretch" in text
    assert "has a centre of inversion" in text


def test_unequal_ends_name_each_bond_and_say_mixed_when_none_dominates(tmp_path):
    """N–C–O with equal bonds: N and O nearly equal in mass, so each stretch moves both
    bonds about equally (53 % and 47 %): "mixed", never "symmetric"."""
    config = _molecule("NCO", [(-1.16, 0, 0), (0, 0, 0), (1.16, 0, 0)], [16.0, 16.0], 0.6)
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "mixed C–O stretch and C–N stretch" in text
    assert not re.search(r"\b(?:anti)?symmetric stretch", text)


def test_bent_molecule_without_symmetry(tmp_path):
    """H–O–D: bent, no two bonds alike: an O–H, an O–D stretch and a bend; non-linear,
    3n − 6, no linear-molecule words."""
    config = _molecule("HOD", [(-0.7575, 0.585, 0), (0, 0, 0), (0.7575, 0.585, 0)],
                       [8.45, 8.45], 0.76)  # r = 0.957 Å, ∠HOD = 104.5°
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "O–H stretch" in text and "O–D stretch" in text and "bend" in text
    assert "A non-linear triatomic molecule" in text and "3n − 6" in text
    assert "This molecule is linear" not in text and "longitudinal" not in text


def test_symmetric_bent_molecule_keeps_its_symmetric_and_antisymmetric_stretch(tmp_path):
    """A bent Y–X–Y given by masses alone (no element): its two bonds are alike, so the
    stretches are symmetric and antisymmetric (equal and opposite changes)."""
    config = tomllib.loads((Path(__file__).parent / "data" / "variants"
                            / "normal_modes_triatomic.toml").read_text())
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "symmetric stretch" in text and "antisymmetric stretch" in text


@pytest.mark.parametrize("system", [{"chain": {"n": 3, "ends": "free"}},
                                    {"pendula": {"n": 3, "k": 0.7}}])
def test_chains_and_pendula_say_nothing_of_bonds_or_angles(tmp_path, system):
    """A chain or a row of pendula has no molecule words; its modes are named by their
    nodes, its degenerate sets by the coordinates they move (no symmetry operations)."""
    contradictions, text = claimgen.contradictions_of({"kind": "normal_modes", **system},
                                                      tmp_path)
    assert contradictions == []
    for words in ("bond", "bending angle", "stretch", "molecule", "symmetry operations"):
        assert words not in text
    assert re.search(r"\b[12] nodes?\b", text)
