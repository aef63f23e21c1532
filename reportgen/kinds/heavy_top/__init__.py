r"""``heavy_top``: the heavy symmetric top (lecture notes §10.1, eqs. 10.21-10.50).

Integrated as a quaternion with the body angular velocity (no Euler-angle
singularity: θ = 0 is an ordinary point); θ, φ, ψ and the symmetry axis are
derived for output.  Closed form from the cubic f(u) (10.31): its roots, the
Fig. 4.3 case (loops / waves / cusps), nutation period, precession per period,
u(t) in Jacobi sn² and through Weierstrass's ℘ (exercise 4.10), steady precession
rates (10.45-10.46) and the sleeping-top threshold (10.49-10.50), each checked against
an independent evaluation.

Instead of ``[initial]`` a ``[band]`` asks for a nutation band θmin ≤ θ ≤ θmax and a
case; the scene solves for the release on the upper circle that gives it
(:func:`reportgen.core.heavy_top_theory.band_start`).  ``case = "all"`` integrates the
three cases on the same band as runs ``loops``, ``waves`` and ``cusps`` (``/runs/main``
is ``/runs/loops``) and draws them as Fig. 4.3 is printed.
"""

from __future__ import annotations

from .config import PRESETS, HeavyTopConfig
from .report import HeavyTopReport
from .simulation import HeavyTopSimulation


class HeavyTopScene(HeavyTopSimulation, HeavyTopReport):
    kind = "heavy_top"
    order = 70
    summary = ("heavy symmetric top: nutation loci (loops, waves, cusps), f(u), steady "
               "precession, the sleeping top")
    Config = HeavyTopConfig
    presets = PRESETS
