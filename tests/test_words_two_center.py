"""two_center: the words follow the orbit's own motion (issue 41, issue 42).

The shipped reports printed a behaviour line that contradicted their titles (the ring
round both centres called "about one centre", the one-side orbit "around both centres"):
the words are now chosen by ``/analysis`` ``motion``, classified at simulate time from E,
β and q(1) = 2a²E + 4aμ + β (notes (7.59)), and each sentence family is a registered claim
checked here on configs nobody shipped.

The classes carry the literature's names (Waalkens, Dullin & Richter, Physica D 196 (2004),
after Charlier; the project had the first two reversed): a satellite orbit about one
centre, a planetary orbit round both, a lemniscate orbit through the segment between them;
each name is a claim of its own case."""

from __future__ import annotations

import pytest

import claimgen
from reportgen.scene.claims import contradictions

BASE = {"kind": "two_center", "params": {"mu": 1.0, "a": 1.0},
        "run": {"t_end": 30.0, "samples": 1501, "study": False}}


def scene(tmp_path, **initial):
    return claimgen.contradictions_of({**BASE, "initial": initial}, tmp_path)


def test_ring_round_both_centres_is_not_called_about_one_centre(tmp_path):
    # the shipped planetary orbit's shape, another start: (0, 1.4), ẋ = 1.2 (β < 0, q(1) < 0)
    found, text = scene(tmp_path, x=0.0, y=1.4, vx=1.2, vy=0.0)
    assert found == []
    assert "bound: a planetary orbit around both centres" in text
    assert "This orbit is a planetary orbit" in text and "satellite orbit:" not in text
    assert "it encircles both centres" in text
    assert "about one centre" not in text.split("Behaviour")[1].split("Euler's problem")[0]


def test_one_side_orbit_names_its_own_centre(tmp_path):
    # the shipped satellite orbit's shape, mirrored: about the centre at (−1, 0)
    found, text = scene(tmp_path, x=-1.7, y=0.0, vx=0.0, vy=-1.0)
    assert found == []
    assert "bound: a satellite orbit on one side of the mid-line, about the centre at (−1, 0)" \
        in text
    assert "This orbit is a satellite orbit" in text and "planetary orbit:" not in text
    assert "around both centres" not in text and "encircles both centres" not in text


def test_orbit_through_the_middle_is_its_own_case(tmp_path):
    # β = −1.25 ≤ 0 but q(1) = 0.17 ≥ 0: ξ reaches the segment between the centres
    found, text = scene(tmp_path, x=0.0, y=0.5, vx=1.0, vy=0.0)
    assert found == []
    assert "lemniscate orbit through the segment between the centres" in text
    assert "This orbit is a lemniscate orbit" in text
    assert "encircles both centres" not in text and "between the ellipses" not in text


@pytest.mark.parametrize("said", ["bound: a satellite orbit around both centres",
                                  "A satellite orbit round both centres at E = −1.3"])
def test_the_claims_catch_the_old_words(tmp_path, said):
    """What the shipped one-centre report once printed (the words of the ring round both
    centres) is a contradiction of its archive."""
    data = claimgen.run_config({**BASE, "initial": {"x": 1.6, "y": 0.0, "vx": 0.0,
                                                    "vy": 1.2}}, tmp_path)
    assert any(line.startswith("two_center round both centres") for line in
               contradictions(data, said))
    assert contradictions(data, "a satellite orbit on one side of the mid-line, about the "
                                "centre at (1, 0)") == []


@pytest.mark.parametrize("state, said, claim", [
    # the reversed names: the orbit about one centre called planetary …
    ((1.6, 0.0, 0.0, 1.2), "This orbit is planetary: β = 0.4162 > 0", "planetary orbit"),
    ((1.6, 0.0, 0.0, 1.2), "bound: a planetary orbit on one side of the mid-line",
     "planetary orbit"),
    # … the ring round both centres called satellite, and so the orbit through the middle
    ((0.0, 1.6, 1.05, 0.0), "This orbit is a satellite orbit: β = −3.925 ≤ 0",
     "satellite orbit"),
    ((0.0, 0.5, 1.0, 0.0), "This orbit is a satellite orbit through the middle",
     "satellite orbit"),
    ((0.0, 1.6, 1.05, 0.0), "A lemniscate orbit through the segment", "lemniscate orbit"),
])
def test_a_name_is_a_claim_of_its_own_case(tmp_path, state, said, claim):
    """The literature's names (Waalkens, Dullin & Richter 2004): a name given to another
    case's orbit is a contradiction of its archive, whatever else the sentence says."""
    x, y, vx, vy = state
    data = claimgen.run_config({**BASE, "initial": {"x": x, "y": y, "vx": vx, "vy": vy}},
                               tmp_path)
    assert any(line.startswith(f"two_center {claim}") for line in contradictions(data, said))
