"""Every page of a scene nobody shipped as fit to hand out as the pack's (issue 41): the
checks of ``tests/pages.py`` over varied, untitled configs of every kind --
``tests/data/variants`` (a rotating pendulum, a Kepler hyperbola, a prolate and a stable
asymmetric body, a molecule written from scratch ...; study on) and ``tests/data/unseen``
(scenes written as a lecturer would: O=C=S, V = −k/r⁰·⁴, a hierarchical triple, a pendulum
at 179.5°, the Toda lattice, a top on a band given in degrees, a box-shaped body ...;
study off: the pack and the variants hold the study's pages to the same rules)."""

from __future__ import annotations

from pathlib import Path

from pages import page_tests

DATA = Path(__file__).resolve().parent / "data"
VARIANTS = sorted((DATA / "variants").glob("*.toml"))
UNSEEN = sorted((DATA / "unseen").glob("*.toml"))

globals().update(page_tests([*VARIANTS, *UNSEEN], study_off=UNSEEN))
