"""The Poisson bracket's properties of notes (4.38) ("facts of life": {qᵢ, pⱼ} = δᵢⱼ,
antisymmetry, {Cf, g} = C{f, g}, Leibniz's rule), checked by SymPy in the hamiltonian
kind's brackets section (issue 42): they hold for reportgen's bracket on phase spaces of 1
to 3 degrees of freedom, and the check finds a bracket that lacks them."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from reportgen.core import mechanics
from reportgen.kinds.hamiltonian.analysis import HamiltonianAnalysis

FLAGS = ("brackets_canonical", "brackets_antisymmetric", "brackets_homogeneous",
         "brackets_leibniz")


@pytest.mark.parametrize("names", [("x",), ("r", "theta"), ("x", "y", "z")])
def test_the_bracket_has_the_notes_facts_of_life(names):
    a: dict = {}
    HamiltonianAnalysis._facts_of_life(a, SimpleNamespace(space=mechanics.PhaseSpace.of(names)))
    assert [a[k] for k in FLAGS] == [True] * 4


def test_a_bracket_without_them_is_found(monkeypatch):
    """Half the bracket, Σ ∂f/∂q ∂g/∂p: {q, p} = 1 still, but it is not antisymmetric."""
    import sympy

    def half(space, f, g):
        return sum(sympy.diff(f, q) * sympy.diff(g, p) for q, p in zip(space.q, space.p, strict=True))

    monkeypatch.setattr(mechanics, "poisson_bracket", half)
    a: dict = {}
    HamiltonianAnalysis._facts_of_life(a, SimpleNamespace(space=mechanics.PhaseSpace.of(("x",))))
    assert a["brackets_antisymmetric"] is False and a["brackets_canonical"] is True
