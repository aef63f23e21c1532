"""The claims registry (issue 41).

The claims test itself is one file per kind, ``tests/test_claims_<kind>.py``: hypothesis
draws configs across the kind's case space (``tests/claimgen/<kind>.py``), each is
simulated (without its study) and its report's text read
(:func:`reportgen.rendering.report.report_text`, figures drawn but not saved); every
registered claim found in the text (:mod:`reportgen.scene.claims`) must hold for the
archive.  ``REPORTGEN_CLAIMS_SCALE=N`` draws N times each kind's ``EXAMPLES``.
"""

from __future__ import annotations

import re
from pathlib import Path

import claimgen
from reportgen.kinds import KINDS
from reportgen.scene.claims import Claim, contradictions, registry


def test_every_kind_has_a_generator_and_a_claims_test():
    assert set(claimgen.kinds()) == set(KINDS)
    here = Path(__file__).parent
    for kind in KINDS:
        text = (here / f"test_claims_{kind}.py").read_text(encoding="utf-8")
        assert f'claims_test("{kind}")' in text


def test_claims_are_registered_once_with_their_kind():
    claims = registry()
    assert len({c.name for c in claims}) == len(claims)
    for c in claims:
        assert c.kind is None or c.kind in KINDS, c


class _Archive:
    """The least of an archive a claim reads: its kind."""

    kind = "pendulum"


def test_a_false_claim_is_reported_with_where_it_was_said(monkeypatch):
    from reportgen.scene import claims

    fake = Claim("test: always false", re.compile(r"the moon is made of cheese"),
                 lambda data: "it is rock", None, "")
    monkeypatch.setitem(claims._REGISTRY, fake.name, fake)
    found = contradictions(_Archive(), "Here the moon is made of cheese, we say.")
    assert len(found) == 1 and "it is rock" in found[0] and "cheese" in found[0]
    assert contradictions(_Archive(), "Nothing is said here.") == []
