"""Compiled (numba) integrators for :class:`reportgen.core.model.OdeModel`, plus scipy peers.

Public API::

    solve(model, y0, t_eval, SolverSpec(method="auto", rtol=..., atol=..., h=None),
          n_periods=None, progress=None) -> PolicyResult   # the solver policy
    integrate(model, y0, t_eval, method="dop853", rtol=1e-10, atol=1e-12, h=None,
              progress=None, max_steps=10_000_000) -> Solution   # one named method
    METHODS: dict name -> method object with capability flags
    choose_auto(model, rtol, n_periods=None) -> (method name, reason)
    RunStatus, SolveCode, MethodMismatch, Solution
"""

from __future__ import annotations

from .base import Method, MethodMismatch, RunStatus, Solution, SolveCode
from .driver import integrate
from .policy import PolicyResult, SolverSpec, choose_auto, solve
from .registry import METHODS

__all__ = ["integrate", "solve", "METHODS", "choose_auto", "Solution", "SolveCode",
           "SolverSpec", "PolicyResult", "RunStatus", "MethodMismatch", "Method"]
