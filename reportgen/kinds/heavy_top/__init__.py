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

import math

from ...scene.content import fmt as _fmt
from .config import PRESETS, HeavyTopConfig
from .report import HeavyTopReport
from .simulation import HeavyTopSimulation


def fmt(x, digits: int = 10) -> str:
    """A number of a title: :func:`~reportgen.scene.content.fmt` with a true minus sign."""
    return _fmt(x, digits).replace("-", "−")


class HeavyTopScene(HeavyTopSimulation, HeavyTopReport):
    kind = "heavy_top"
    order = 70
    summary = ("heavy symmetric top: nutation loci (loops, waves, cusps), f(u), steady "
               "precession, the sleeping top")
    Config = HeavyTopConfig
    presets = PRESETS
    name_in_words = "Heavy symmetric top"
    #: the nutation cases in words
    CASE_WORDS = {"loops": "looping nutation", "waves": "wavy nutation",
                  "cusps": "cusped nutation (released at rest)",
                  "all": "loops, waves and cusps on one band", "steady": "steady precession"}

    @classmethod
    def default_title(cls, config):
        """``Heavy top: looping nutation, θ from 45.8° to 57.3°`` for a band; a steady,
        sleeping or general start by its numbers."""
        p, band, ini = config.params, config.band, config.initial

        def deg(x: float) -> str:
            return f"{math.degrees(x):.3g}°"

        if band is not None:
            return (f"Heavy top: {cls.CASE_WORDS[band.case]}, θ from {deg(band.theta_min)} "
                    f"to {deg(band.theta_max)}")
        if ini is None:
            return "Heavy symmetric top"
        spin = f"ω3 = {fmt(ini.omega3, 4)} rad/s"
        if ini.steady is not None:
            return f"Heavy top: {ini.steady} steady precession at θ = {deg(ini.theta)}, {spin}"
        if ini.theta < 1e-3 and not ini.theta_dot:
            above = (p.I3 * ini.omega3) ** 2 > 4.0 * p.I1 * p.Mgl  # (10.50)
            return (f"Sleeping top {'above' if above else 'below'} its threshold: {spin}, "
                    f"tilt {fmt(ini.theta, 3)} rad")
        case = cls.CASE_WORDS.get(config.expect_case or "")
        start = (f"θ0 = {deg(ini.theta)}, φ̇0 = {fmt(ini.phi_dot, 4)} rad/s, {spin}")
        return f"Heavy top: {case}, {start}" if case else f"Heavy top released at {start}"
