"""Words that follow the scene's own facts (issue 41): the inertia report calls a body a
spherical, symmetric or asymmetric top and names its stable axes from the principal
moments with one stored tolerance, on scenes nobody shipped."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

import claimgen

UNSEEN = Path(__file__).parent / "data" / "unseen"


def _box(a, b, c, **extra):
    return {"kind": "inertia", "shape": {"type": "box", "mass": 1.0, "a": a, "b": b, "c": c,
                                         **extra}}


def test_a_box_just_off_square_is_asymmetric(tmp_path):
    """Sides 1, 1.000001, 0.5: the moments print alike to six figures, yet differ by 10⁻⁶ of
    the largest; the report says so, and the intermediate axis is unstable."""
    contradictions, text = claimgen.contradictions_of(_box(1.0, 1.000001, 0.5), tmp_path)
    assert contradictions == []
    assert "The three moments differ (the closest two by 10⁻⁶ of the largest" in text
    assert "unstable about the intermediate axis 2" in text
    assert "symmetric body" not in text


def test_axis_words_and_verdicts_use_one_tolerance(tmp_path):
    """Sides differing by 10⁻¹⁰: the verdicts (asymmetric, one axis unstable) and the
    shape's axis words agree; the words used to say "any axis ⊥ z" (equal within 10⁻⁹)
    beside an "unstable" verdict (equal within 10⁻¹²)."""
    contradictions, text = claimgen.contradictions_of(_box(1.0, 1.0 + 1e-10, 0.5), tmp_path)
    assert contradictions == []
    assert "any axis ⊥" not in text and "unstable" in text


def test_square_box_is_a_symmetric_top(tmp_path):
    contradictions, text = claimgen.contradictions_of(_box(1.0, 1.0, 0.5), tmp_path)
    assert contradictions == []
    assert "Two principal moments are equal (a symmetric body)" in text
    assert "any axis ⊥ z" in text and "unstable about" not in text


@pytest.mark.parametrize("shape", [
    {"type": "cone", "mass": 1.0, "radius": 0.5, "height": 1.0},  # h = 2R
    {"type": "box", "mass": 1.0, "a": 0.4, "b": 0.4, "c": 0.4},
    {"type": "points", "masses": [1, 1, 1, 1],
     "positions": [[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]]},
])
def test_spherical_tops(tmp_path, shape):
    """A cone with h = 2R, a cube, a regular tetrahedron of equal masses: three equal
    moments, every axis marginal."""
    contradictions, text = claimgen.contradictions_of({"kind": "inertia", "shape": shape},
                                                      tmp_path)
    assert contradictions == []
    assert "All three principal moments are equal" in text
    assert "every axis marginal (three equal moments)" in text


def test_unseen_octahedron_scene(tmp_path):
    config = tomllib.loads((UNSEEN / "inertia_octahedron_square.toml").read_text())
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "Two principal moments are equal" in text
