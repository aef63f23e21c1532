"""Every integrator by name, with its capability flags (``METHODS``)."""

from __future__ import annotations

from .base import Method
from .explicit_rk import DOP853, RK4, RK45
from .heyoka_peer import Heyoka
from .regularized import LeviCivita, LeviCivitaDop853
from .scipy_peer import RadauFallback, ScipyDOP853, ScipyLSODA, ScipyRadau, ScipyRK45
from .symplectic import Gauss4, Gauss6, Verlet, Yoshida4, Yoshida6, Yoshida8
from .taylor import Taylor

METHODS: dict[str, Method] = {
    m.name: m
    for m in (
        DOP853(), RK45(), RK4(),
        Verlet(), Yoshida4(), Yoshida6(), Yoshida8(),
        Gauss4(), Gauss6(),
        LeviCivita(), LeviCivitaDop853(),
        RadauFallback(),
        ScipyRK45(), ScipyDOP853(), ScipyLSODA(), ScipyRadau(),
        Heyoka(),
        Taylor(),
    )
}
