"""``pendulum`` config: parameters, initial state, the boundary-value problem, presets."""

from __future__ import annotations

import math

from pydantic import Field, model_validator

from ...lazy import lazy_module
from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, RunConfig, Strict
from ...scene.units import check_turn

theory = lazy_module("reportgen.core.pendulum_theory")  # no numerics: validation uses it

#: crossings are located reliably only with this many samples per period
MIN_SAMPLES_PER_PERIOD = 16
#: most periods (of small oscillation, or of rotation at the initial rate) one run may
#: span: at ~100 steps a period, more would take days (and rounding swamps the phase)
MAX_PERIODS = 1e9
#: largest energy scale m·g·l [J]: beyond it squares of energies overflow float64
MAX_ENERGY_SCALE = 1e150


class Params(Strict):
    g: Positive = Field(description="gravitational acceleration [m/s^2]")
    l: Positive = Field(description="length of the pendulum [m]")
    m: Positive = Field(1.0, description="bob mass [kg]")


class Initial(Strict):
    theta: Real = Field(description="initial angle from the downward vertical, |θ| ≤ 2π "
                                    "[rad] (beyond a full turn: degrees, most likely)")
    theta_dot: Real = Field(0.0, description="initial angular velocity [rad/s]")

    @model_validator(mode="after")
    def _within_a_turn(self):
        check_turn("initial.theta", self.theta)
        return self


class Boundary(Strict):
    """``[boundary]``: the linearised boundary-value problem (notes (1.21))."""

    theta0: Real = Field(description="θ(0), |θ(0)| ≤ 2π [rad]")
    theta1: Real = Field(description="θ(T), |θ(T)| ≤ 2π [rad]")
    T: Positive = Field(description="end time of the boundary-value problem [s]")

    @model_validator(mode="after")
    def _within_a_turn(self):
        check_turn("boundary.theta0", self.theta0)
        check_turn("boundary.theta1", self.theta1)
        return self


class PendulumConfig(SceneConfig):
    params: Params
    initial: Initial
    run: RunConfig
    boundary: Boundary | None = None

    @model_validator(mode="after")
    def _physics(self):
        p, t_end = self.params, self.run.t_end
        scale = p.m * p.g * p.l
        if not scale <= MAX_ENERGY_SCALE:
            raise ValueError(f"params.g / params.l / params.m: the energy scale m·g·l = "
                             f"{scale:.3g} J is above {MAX_ENERGY_SCALE:.0e} J (float64 "
                             "overflows in its squares)")
        omega0 = math.sqrt(p.g / p.l)
        if not 0 < omega0 < math.inf:  # g/l under- or overflows: no time scale to run on
            raise ValueError(f"params.g / params.l: g/l = {p.g:.3g}/{p.l:.3g} is "
                             f"{p.g / p.l:.3g} in floating point; ω0 = √(g/l) must be a "
                             "positive finite rate (give g and l nearer each other)")
        periods = t_end * omega0 / (2 * math.pi)
        if not periods <= MAX_PERIODS:
            raise ValueError(f"params.g / params.l: ω0 = √(g/l) = {omega0:.3g} rad/s makes "
                             f"run.t_end = {t_end:g} s span {periods:.3g} periods of small "
                             f"oscillation; at most {MAX_PERIODS:.0e} can be integrated (lower "
                             "g or t_end, or raise l)")
        turns = t_end * abs(self.initial.theta_dot) / (2 * math.pi)
        if not turns <= MAX_PERIODS:
            raise ValueError(f"initial.theta_dot: {self.initial.theta_dot:.3g} rad/s makes "
                             f"run.t_end = {t_end:g} s span {turns:.3g} turns; at most "
                             f"{MAX_PERIODS:.0e} can be integrated")
        m1 = theory.complementary_parameter(self.initial.theta, self.initial.theta_dot, omega0)
        if m1 == 0.0:
            raise ValueError(
                "initial.theta / initial.theta_dot: the state lies exactly on the separatrix "
                "(k = 1, infinite period)"
            )
        if self.boundary is not None:
            s = math.sin(omega0 * self.boundary.T)
            if abs(s) < 1e-8:
                raise ValueError(
                    f"boundary.T: T = {self.boundary.T} is a multiple of π/ω0 = "
                    f"{math.pi / omega0:.6g} s (a conjugate point: the linear boundary-value "
                    "problem has no unique solution)"
                )
        return self


#: the classic cases, one line each (explicit keys override)
PRESETS = {
    "small_angle": {"params": {"g": 9.81, "l": 1.0}, "initial": {"theta": 0.1},
                    "run": {"t_end": 20.0}},
    "large_amplitude": {"params": {"g": 9.81, "l": 1.0}, "initial": {"theta": 2.5},
                        "run": {"t_end": 30.0}},
    "near_separatrix": {"params": {"g": 9.81, "l": 1.0},
                        "initial": {"theta": math.pi - 1e-3}, "run": {"t_end": 40.0}},
    "rotation": {"params": {"g": 9.81, "l": 1.0},
                 "initial": {"theta": 0.0, "theta_dot": 7.0}, "run": {"t_end": 10.0}},
}
