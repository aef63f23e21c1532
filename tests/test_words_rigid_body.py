"""Words that follow the scene's own facts (issue 41): the rigid-body report says which
axis the spin is near, whether the body flips and how often within the run, how a
symmetric body precesses (or that it spins steadily), and what an impulse does, each
from a stored classification -- on scenes nobody shipped."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import claimgen

UNSEEN = Path(__file__).parent / "data" / "unseen"


def _scene(params, omega, t_end=6.0, **extra):
    return {"kind": "rigid_body", "params": dict(zip(("I1", "I2", "I3"), params, strict=True)),
            "initial": {"omega": list(omega)},
            "run": {"t_end": t_end, "samples": 601, "study": False}, **extra}


def test_box_spun_near_its_intermediate_axis_flips(tmp_path):
    """The brick of tests/data/unseen/rigid_body_box.toml: spun 0.012 rad from its
    intermediate axis (the side b), its polhode passes close to that axis and it flips; the
    words count the flips in the run."""
    config = tomllib.loads((UNSEEN / "rigid_body_box.toml").read_text())
    config["run"]["study"] = False
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "Torque-free solid box (M = 2 kg, sides 0.3, 0.2, 0.1 m)" in text
    assert re.search(r"the polhode passes within \S+ rad of the intermediate axis 2", text)
    assert re.search(r"the body flips over \d+ times within the run", text)
    assert "again and again" not in text


def test_a_run_shorter_than_a_flip_says_so(tmp_path):
    """Near the intermediate axis but stopped before the first flip: the caption no
    longer says the body flips "again and again"."""
    config = _scene((1.0, 2.0, 3.0), (0.001, 2.0, 0.001), t_end=1.0)
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "the run ends before the body's first flip" in text
    assert "spun near its intermediate axis" in text


def test_asymmetric_spin_far_from_every_axis_is_not_said_to_be_near_one(tmp_path):
    """ω0 = (1, 1, 1) is 0.96 rad from the axis of its largest |I ω|: the title gives ω0
    instead of "spun near its largest-moment axis" (what it said before)."""
    config = _scene((1.0, 2.0, 3.0), (1.0, 1.0, 1.0))
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "spun near" not in text
    assert "Torque-free asymmetric body (I = 1, 2, 3 kg m²), ω₀ = (1, 1, 1) rad/s" in text
    assert ("polhode keeps 0.714 rad or more from the intermediate axis" in text
            and "circling axis 3, which keeps its sense along L" in text)


def test_symmetric_body_spun_about_its_figure_axis_is_steady(tmp_path):
    """ω along the figure axis: nothing precesses; no "prograde" or "retrograde", no
    precession figure, the figure axis does not precess about L (it is along it)."""
    config = _scene((1.0, 1.0, 1.5), (0.0, 0.0, 2.0))
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "a steady rotation" in text
    assert not re.search(r"\b(?:prograde|retrograde)\b", text)
    assert "ω circles the figure axis" not in text
    assert "none: the figure axis lies along L" in text


def test_symmetric_body_spun_across_its_figure_axis_is_steady(tmp_path):
    """ω3 = 0 on a prolate body: Ω = 0, so ω⊥ does not turn (it was said to turn "against
    the spin" before)."""
    config = _scene((1.0, 1.0, 0.5), (1.0, 0.5, 0.0))
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "across the figure axis" in text and "a steady rotation" in text
    assert "against the spin" not in text


def test_prolate_precession_is_retrograde(tmp_path):
    config = _scene((1.0, 1.0, 0.5), (0.3, 0.0, 2.0))
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "turns against the spin (retrograde)" in text


def test_impulse_on_a_body_without_a_mass(tmp_path):
    """A body given by its moments has no mass: the impulse text no longer says the centre
    of mass moves off at P/M."""
    config = _scene((1.0, 2.0, 3.0), (0.0, 0.0, 2.0),
                    impulse={"P": [0.2, 0.0, 0.0], "at": [0.0, 0.0, 0.5]})
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "by its principal moments alone, without a mass" in text
    assert "V = P/M" not in text


def test_impulse_off_the_figure_axis_of_a_cylinder(tmp_path):
    """A cylinder struck off its figure axis: no "like the apex" circling L."""
    config = {"kind": "rigid_body",
              "shape": {"type": "cylinder", "mass": 1.0, "radius": 0.3, "height": 1.0},
              "initial": {"omega": [0.0, 0.0, 5.0]},
              "impulse": {"P": [0.0, 0.1, 0.0], "at": [0.3, 0.0, 0.2]},
              "run": {"t_end": 3.0, "samples": 601, "study": False}}
    contradictions, text = claimgen.contradictions_of(config, tmp_path)
    assert contradictions == []
    assert "off the figure axis, combines both turnings" in text
    assert "apex" not in text
