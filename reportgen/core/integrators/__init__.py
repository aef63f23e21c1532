"""Compiled (numba) integrators for :class:`reportgen.core.model.OdeModel`, plus scipy peers.

Public API::

    integrate(model, y0, t_eval, method="dop853", rtol=1e-10, atol=1e-12, h=None,
              progress=None, max_steps=10_000_000) -> Solution
    METHODS: dict name -> method object with capability flags
    choose_auto(model, rtol, n_periods=None) -> (method name, reason)
    MethodMismatch, Solution
"""

from __future__ import annotations

from .auto import choose_auto
from .base import Method, MethodMismatch, Solution
from .driver import integrate
from .explicit_rk import DOP853, RK4, RK45
from .scipy_peer import RadauFallback, ScipyDOP853, ScipyLSODA, ScipyRadau, ScipyRK45
from .symplectic import Gauss4, Gauss6, Verlet, Yoshida4, Yoshida6, Yoshida8

METHODS: dict[str, Method] = {
    m.name: m
    for m in (
        DOP853(), RK45(), RK4(),
        Verlet(), Yoshida4(), Yoshida6(), Yoshida8(),
        Gauss4(), Gauss6(),
        RadauFallback(),
        ScipyRK45(), ScipyDOP853(), ScipyLSODA(), ScipyRadau(),
    )
}

__all__ = ["integrate", "METHODS", "choose_auto", "Solution", "MethodMismatch", "Method"]
