"""``oscillator`` config: mass, angular frequency, initial state, presets."""

from __future__ import annotations

from pydantic import Field, model_validator

from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, RunConfig, Strict


class Params(Strict):
    m: Positive = Field(description="mass [kg]")
    omega: Positive = Field(description="angular frequency ω [rad/s]")


class Initial(Strict):
    q: Real = Field(description="initial coordinate [m]")
    p: Real = Field(description="initial momentum [kg·m/s]")


class OscillatorConfig(SceneConfig):
    params: Params
    initial: Initial
    run: RunConfig

    @model_validator(mode="after")
    def _not_at_rest(self):
        if self.initial.q == 0.0 and self.initial.p == 0.0:
            raise ValueError("initial.q / initial.p: both zero, the oscillator rests at E = 0 "
                             "and the Hamilton–Jacobi constants are undefined")
        return self


#: the classic cases, one line each (explicit keys override)
PRESETS = {
    "unit": {"params": {"m": 1.0, "omega": 1.0}, "initial": {"q": 1.0, "p": 0.0},
             "run": {"t_end": 20.0}},
}
