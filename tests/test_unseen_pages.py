"""Every page of a scene nobody shipped as fit to hand out as the pack's (issue 41): the
checks of ``tests/pages.py`` over varied, untitled configs of every kind --
``tests/data/variants`` (a rotating pendulum, a Kepler hyperbola, a prolate and a stable
asymmetric body, a molecule written from scratch ...) and ``tests/data/unseen`` (scenes
written as a lecturer would: O=C=S, V = −k/r⁰·⁴, a hierarchical triple, a pendulum at
179.5°, the Toda lattice, a top on a band given in degrees, a box-shaped body ...); all
with the study off (the shipped pack holds the study's pages to the same rules, one scene
of each kind: test_shipped_pages.py), which is most of a scene's cost."""

from __future__ import annotations

from pathlib import Path

from pages import page_tests

DATA = Path(__file__).resolve().parent / "data"
VARIANTS = sorted((DATA / "variants").glob("*.toml"))
UNSEEN = sorted((DATA / "unseen").glob("*.toml"))

globals().update(page_tests([*VARIANTS, *UNSEEN], study_off=[*VARIANTS, *UNSEEN]))
