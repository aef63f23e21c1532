"""Claim-carrying sentences and the facts that make them true (issue 41).

A sentence of a report that states a case, a sign, a direction, a comparison, a method or
a name ("the pericentre advances", "derived from a Lagrangian", "the symmetric stretch",
"a libration") is a *claim*: it is chosen by a stored fact (a classification in
``/analysis`` with its threshold), never by the kind, the preset or what the shipped
configs happen to be.  Each such sentence is registered here with

- a ``pattern`` that finds it in a report's visible text, and
- a predicate ``holds(data)`` over the archive alone that says whether it is true of
  this scene, computed independently of the fact that chose the words where it can be
  (the apsides' direction from the archived trajectory, not from the stored sign that
  picked "advances").

The claims test (``tests/test_claims.py``) generates configs across every kind's case
space, runs them, renders each report's text and checks every claim it finds against its
archive: a sentence written for the shipped cases that is false of a new one fails it.

A kind registers its claims in ``kinds/<kind>/claims.py`` (and ``claims_*.py``; imported
only by :func:`registry`, never by the report: their code is no part of a stage key); claims any
kind's report may make (the study's, the invariants') are registered in
:mod:`reportgen.scene.claims_shared`.
"""

from __future__ import annotations

import importlib
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..archive.store import ArchiveData

__all__ = ["Claim", "claim", "registry", "contradictions"]


@dataclass(frozen=True)
class Claim:
    """One claim-carrying sentence: how to find it, and when it is true.

    ``holds(data)`` returns True when the claim is true of the archive ``data`` (False,
    or a string saying what was measured instead, when it is not)."""

    name: str
    pattern: re.Pattern[str]
    holds: Callable[[ArchiveData], bool | str]
    #: the kind whose reports make it (None: any kind's)
    kind: str | None = None
    #: what the predicate checks, in words (for a contradiction's message)
    checks: str = ""


_REGISTRY: dict[str, Claim] = {}


def claim(name: str, pattern: str, *, kind: str | None = None, flags: int = 0,
          checks: str = "") -> Callable:
    """Register the decorated predicate ``holds(data) -> bool | str`` as the claim
    ``name``, found in a report's visible text by the regular expression ``pattern``.

    ``kind``: the kind whose reports make the claim; by default the kind whose package the
    predicate's module is in (``reportgen.kinds.<kind>.claims``), None for a shared one."""

    def register(holds: Callable[[ArchiveData], bool | str]):
        owner = kind
        if owner is None:
            parts = holds.__module__.split(".")
            owner = parts[2] if parts[:2] == ["reportgen", "kinds"] and len(parts) > 3 else None
        if name in _REGISTRY and _REGISTRY[name].holds.__qualname__ != holds.__qualname__:
            raise ValueError(f"claim {name!r} is registered twice")
        _REGISTRY[name] = Claim(name, re.compile(pattern, flags), holds, owner,
                                checks or (holds.__doc__ or "").strip().split("\n")[0])
        return holds

    return register


def registry() -> list[Claim]:
    """Every registered claim: the shared ones and each kind's ``claims`` module (and its
    ``claims_*`` modules, a kind's claims split by topic)."""
    import pkgutil

    from ..kinds import KINDS

    importlib.import_module(f"{__package__}.claims_shared")
    for kind in KINDS:
        package = importlib.import_module(f"reportgen.kinds.{kind}")
        for info in pkgutil.iter_modules(package.__path__):
            if info.name == "claims" or info.name.startswith("claims_"):
                importlib.import_module(f"{package.__name__}.{info.name}")
    return list(_REGISTRY.values())


def contradictions(data: ArchiveData, text: str) -> list[str]:
    """The claims found in ``text`` (a report's visible text) that are false of ``data``,
    one line each: the claim, where it was said and what the archive holds instead."""
    text = " ".join(text.split())
    out = []
    for c in registry():
        if c.kind is not None and c.kind != data.kind:
            continue
        m = c.pattern.search(text)
        if m is None:
            continue
        try:
            verdict = c.holds(data)
        except Exception as exc:  # noqa: BLE001 - a predicate that cannot decide fails
            verdict = f"the predicate raised {type(exc).__name__}: {exc}"
        if verdict is True:
            continue
        said = text[max(0, m.start() - 40):m.end() + 40]
        why = verdict if isinstance(verdict, str) else f"false ({c.checks})"
        out.append(f"{c.name}: '…{said}…': {why}")
    return out


def said(text: str) -> list[str]:
    """The names of the registered claims found in ``text`` (whatever their kind)."""
    text = " ".join(text.split())
    return [c.name for c in registry() if c.pattern.search(text)]
