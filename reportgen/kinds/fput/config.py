"""``fput`` config: the chain's size and stiffness, its initial state, presets."""

from __future__ import annotations

from pydantic import Field, model_validator

from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, RunConfig, Strict

#: the largest number of stiff springs a config may ask for (2m masses)
MAX_STIFF_SPRINGS = 50

#: the stiff spring holding most of I(0) has handed its energy on once it holds less than
#: this share of I; energy starts concentrated in one spring when it holds at least this
EXCHANGE_SHARE = 0.7
#: the chain has two time scales (stiff springs much faster than the soft ones) when ω is at
#: least this many times the soft springs' typical frequency √(24⟨Δ²⟩) along the run
#: (measured: GNI's data at ω = 50 give 21, ω = 10 gives 3.9)
STIFF_RATIO = 5.0
#: ω·max|I − I(0)|/I(0) below this is "of order one" (I(t) − I(0) = O(1/ω)); GNI's data
#: give 0.16 at ω = 50
ORDER_ONE = 10.0
#: I(0) below this fraction of the total energy: the stiff springs start at rest
AT_REST = 1e-12


class Params(Strict):
    """``[params]``: the chain in the scaled units of Hairer GNI §I.5.1.

    Unit masses and soft quartic springs of unit strength; time, positions and momenta are
    pure numbers."""

    m: int = Field(3, ge=1, le=MAX_STIFF_SPRINGS,
                   description="number of stiff springs (2m masses)")
    omega: Positive = Field(50.0, description="frequency ω of the stiff springs "
                                              "[dimensionless]")


class Initial(Strict):
    """``[initial]``: the state, in the same scaled units."""

    q: list[Real] | None = Field(None, description="initial positions q₁ … q₂ₘ "
                                                   "[dimensionless] (default: Hairer GNI "
                                                   "§I.5.1 data)")
    p: list[Real] | None = Field(None, description="initial momenta p₁ … p₂ₘ "
                                                   "[dimensionless] (default: Hairer GNI "
                                                   "§I.5.1 data)")


class FputRun(RunConfig):
    """``[run]``: how the scene is integrated, in the chain's scaled time."""

    t_end: Positive = Field(description="end time of the integration [dimensionless]")
    h: Positive | None = Field(None, description="step size of fixed-step methods "
                                                 "[dimensionless]")


class FputConfig(SceneConfig):
    params: Params = Params()
    initial: Initial = Initial()
    run: FputRun

    @model_validator(mode="after")
    def _lengths(self):
        n = 2 * self.params.m
        for key in ("q", "p"):
            values = getattr(self.initial, key)
            if values is not None and len(values) != n:
                raise ValueError(f"initial.{key}: must have 2m = {n} entries for params.m = "
                                 f"{self.params.m} (got {len(values)})")
        return self


#: the classic cases, one line each (explicit keys override)
PRESETS = {
    "gni": {"params": {"m": 3, "omega": 50.0},
            "run": {"t_end": 200.0, "samples": 4001}},
}
