"""Compiled (numba) integrators for :class:`reportgen.core.model.OdeModel`, plus scipy peers.

Public API::

    solve(model, y0, t_eval, SolverSpec(method="auto", rtol=..., atol=..., h=None),
          n_periods=None, progress=None) -> PolicyResult   # the solver policy
    integrate(model, y0, t_eval, method="dop853", rtol=1e-10, atol=1e-12, h=None,
              progress=None, max_steps=10_000_000) -> Solution   # one named method
    METHODS: dict name -> method object with capability flags
    choose_auto(model, rtol, n_periods=None) -> (method name, reason)
    solve_fictitious_time(model, y0, t_eval, t_index, spec, reason, section=None)
        -> PolicyResult   # a regularized model, outputs at physical t (t_index None: a
                          # model in its own time); a section's crossings located on the steps
    Status (the one status vocabulary; SolveCode and RunStatus are it: the policy archives
    its subset POLICY_STATUSES),
    MethodMismatch, Solution
"""

from __future__ import annotations

import importlib

#: public name -> the submodule that defines it.  Loaded on first use (PEP 562), so that
#: listing the methods (``METHODS``, ``reportgen kinds``) does not import numba or scipy.
_EXPORTS = {
    "Method": ".base", "MethodMismatch": ".base", "RunStatus": ".base", "Solution": ".base",
    "SolveCode": ".base", "Status": ".status",
    "integrate": ".driver",
    "PolicyResult": ".policy", "SolverSpec": ".policy", "choose_auto": ".policy",
    "solve": ".policy", "solve_fictitious_time": ".policy",
    "METHODS": ".registry",
}

__all__ = list(_EXPORTS)


def __getattr__(name: str):
    if name not in _EXPORTS:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(_EXPORTS[name], __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))
