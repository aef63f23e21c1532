"""``two_center`` config: the centres, the initial state (or its energy), the
formulation of the run."""

from __future__ import annotations

import math
from typing import Literal

from pydantic import Field, model_validator

from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, RunConfig, Strict

#: ``formulation = "auto"`` regularizes a bound orbit whose region of motion (7.59) comes
#: within CLOSE_APPROACH·a of a centre.  Measured at rtol 1e-12 (μ = a = 1, outputs
#: every 0.01): the shipped satellite orbit (region reaching the centre, sampled closest
#: approach 0.044) has a max state error of 1.1e-6 in Cartesian DOP853 (2142 steps,
#: 1.7 ms) against 1.9e-8 regularized (776 steps, 2.4 ms); a fall from (2, 0) with
#: vy = 0.01 is 0.6 off (energy error 1e-4, 3773 steps) in Cartesian, 4e-9 (4e-10,
#: 321 steps, 0.9 ms) regularized; with vy ≤ 3e-3 the Cartesian step underflows.  Far
#: from the centres (the shipped planetary orbit, ≥ 0.89 a away) both are as accurate and
#: the Cartesian run is ~3x faster (481 vs 201 steps, but the transformed right-hand side
#: and the located outputs cost more per step and per output).
CLOSE_APPROACH = 0.1


class Params(Strict):
    mu: Positive = Field(description="G·M of each fixed centre [m³/s²]")
    a: Positive = Field(description="half the distance between the centres, at (±a, 0) [m]")


class Initial(Strict):
    x: Real = Field(description="initial position x [m]")
    y: Real = Field(description="initial position y [m]")
    vx: Real = Field(description="initial velocity x [m/s]")
    vy: Real | None = Field(None, description="initial velocity y [m/s]; leave it out and give "
                                              "energy to have it solved for (vy ≥ 0)")
    energy: Real | None = Field(None, description="energy per unit mass E [m²/s²], instead of "
                                                  "vy: vy = +√(2(E − V(x, y)) − vx²), so that "
                                                  "a sweep's members share one energy")


class TwoCenterRun(RunConfig):
    formulation: Literal["auto", "cartesian", "regularized"] = Field(
        "auto", description='"cartesian" (x, y, vx, vy in t), "regularized" (Thiele–Burrau '
                            'variables, dt/ds = r1 r2: regular at both centres; dop853 only) or '
                            '"auto": regularized when the orbit can come within '
                            f'{CLOSE_APPROACH:g}·a of a centre')

    @model_validator(mode="after")
    def _regularized_with_dop853(self):
        if self.formulation == "regularized" and self.method not in ("auto", "dop853"):
            raise ValueError(f'run.method: the regularized formulation integrates with dop853: '
                             f'expected "auto" or "dop853", got {self.method!r}')
        return self


class TwoCenterConfig(SceneConfig):
    params: Params
    initial: Initial
    run: TwoCenterRun

    @model_validator(mode="after")
    def _not_at_a_centre(self):
        ini, a = self.initial, self.params.a
        for sign in (-1, 1):
            if ini.y == 0.0 and ini.x == sign * a:
                raise ValueError(f"initial.x / initial.y: the particle starts at the centre "
                                 f"({sign * a:g}, 0) = (±params.a, 0) (a collision)")
        if (ini.vy is None) == (ini.energy is None):
            raise ValueError("initial.vy / initial.energy: give exactly one of them (got "
                             + ("both" if ini.vy is not None else "neither") + ")")
        if ini.energy is not None:
            floor = potential(ini.x, ini.y, self.params.mu, a) + 0.5 * ini.vx**2
            if ini.energy < floor:
                raise ValueError(f"initial.energy: must be at least V(x, y) + vx²/2 = "
                                 f"{floor:.12g} at the start, where vy would be imaginary "
                                 f"(got {ini.energy!r})")
        return self

    def initial_state(self) -> tuple[float, float, float, float]:
        """(x, y, vx, vy), vy solved for when ``initial.energy`` is given (vy ≥ 0)."""
        ini, p = self.initial, self.params
        if ini.vy is not None:
            return ini.x, ini.y, ini.vx, ini.vy
        vy2 = 2.0 * (ini.energy - potential(ini.x, ini.y, p.mu, p.a)) - ini.vx**2
        return ini.x, ini.y, ini.vx, math.sqrt(max(vy2, 0.0))


def potential(x: float, y: float, mu: float, a: float) -> float:
    """V = −μ/r1 − μ/r2 per unit mass at (x, y) (the config's check of initial.energy;
    the numerics use :mod:`reportgen.core.models.two_center`)."""
    return -mu / math.hypot(x + a, y) - mu / math.hypot(x - a, y)
