r"""``inertia``: the inertia tensor of a shape or a point set, its principal moments and axes,
the parallel-axis shift (8.49) and which free-spin axes are stable (10.12)–(10.14).

Nothing is integrated.  Solid shapes are uniform and given in their own frame
(centre of mass at the origin, symmetry axis / half-diagonals along x, y, z); an
optional ``euler_angles`` = [φ, θ, ψ] (z-x-z) turns the shape in the lab frame so that
the tensor is full and the principal axes come out of the diagonalization.
"""

from __future__ import annotations

from .config import PRESETS, InertiaConfig
from .report import InertiaReport
from .simulation import InertiaSimulation


class InertiaScene(InertiaSimulation, InertiaReport):
    kind = "inertia"
    order = 90
    summary = "inertia tensor of a shape or point set, principal axes, stable spin axes"
    Config = InertiaConfig
    presets = PRESETS
