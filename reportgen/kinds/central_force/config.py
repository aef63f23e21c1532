"""``central_force`` config: the two masses, the potential, the relative initial state
and the preset."""

from __future__ import annotations

import math
from typing import Any, Literal

from pydantic import Field, model_validator

from ...lazy import lazy_module
from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, RunConfig, Strict
from ...scene.units import convert_paths

integrators = lazy_module("reportgen.core.integrators")  # its method list imports no numba


class Params(Strict):
    m1: Positive = Field(description="mass of body 1 [kg]")
    m2: Positive = Field(description="mass of body 2 [kg]")
    k: Positive = Field(description="strength of the attraction, V = −k/r (or −k/rⁿ) "
                                    "[per `potential`: J·m or J·mⁿ]")
    potential: Literal["kepler", "power", "kepler_inverse_cube"] = Field(
        "kepler", description='"kepler" V = −k/r; "power" V = −k/rⁿ; '
                              '"kepler_inverse_cube" V = −k/r − ε/r²')
    n: Real | None = Field(None, description="exponent of the power law V = −k/rⁿ, 0 < n < 2 "
                                             "[dimensionless]")
    epsilon: Real | None = Field(None, description="strength ε of the −ε/r² term (a 1/r³ force)"
                                                   " [J·m²]")


class Initial(Strict):
    x: Real = Field(description="relative position r = r1 − r2, x [m]")
    y: Real = Field(description="relative position, y [m]")
    vx: Real = Field(description="relative velocity, x [m/s]")
    vy: Real = Field(description="relative velocity, y [m/s]")


class CentralForceConfig(SceneConfig):
    params: Params
    initial: Initial
    run: RunConfig

    @model_validator(mode="before")
    @classmethod
    def _strength_in_its_unit(cls, data: Any):
        """``params.k`` given as text ("0.5 J m") in J·m, or J·mⁿ for the power law (when
        ``params.n`` is a number)."""
        params = data.get("params") if isinstance(data, dict) else None
        if not isinstance(params, dict) or not isinstance(params.get("k"), str):
            return data
        n = params.get("n") if params.get("potential") == "power" else 1
        if isinstance(n, bool) or not isinstance(n, int | float) or not math.isfinite(n):
            return data  # the power law without a usable n: k takes plain numbers only
        return convert_paths(data, {("params", "k"): "J m" if n == 1 else f"J m^{n!r}"})

    @model_validator(mode="after")
    def _physics(self):
        p, ini = self.params, self.initial
        if p.potential == "power":
            if p.n is None:
                raise ValueError("params.n: required when params.potential = \"power\"")
            if not 0.0 < p.n < 2.0:
                raise ValueError(f"params.n: must satisfy 0 < n < 2 for V = −k/rⁿ (bound "
                                 f"orbits need an attraction weaker than 1/r³; got {p.n})")
        elif p.n is not None:
            raise ValueError(f"params.n: only used with params.potential = \"power\" "
                             f"(potential is {p.potential!r})")
        if p.potential == "kepler_inverse_cube":
            if p.epsilon is None:
                raise ValueError("params.epsilon: required when params.potential = "
                                 "\"kepler_inverse_cube\"")
        elif p.epsilon is not None:
            raise ValueError(f"params.epsilon: only used with params.potential = "
                             f"\"kepler_inverse_cube\" (potential is {p.potential!r})")
        if ini.x == 0.0 and ini.y == 0.0:
            raise ValueError("initial.x / initial.y: the bodies start at the same point "
                             "(r = 0, a collision)")
        mu = p.m1 * p.m2 / (p.m1 + p.m2)  # reduced mass (validation imports no numerics)
        L = mu * (ini.x * ini.vy - ini.y * ini.vx)
        if L == 0.0:
            raise ValueError("initial.x, initial.y, initial.vx, initial.vy: zero angular "
                             "momentum (r ∥ v): a radial orbit that ends in a collision")
        method = integrators.METHODS.get(self.run.method)
        if method is not None and method.needs_kepler:
            # the regularization is of the 1/r potential's bound orbits (core/integrators/
            # regularized.py): refused here, before anything runs, for any other
            name = self.run.method
            if p.potential != "kepler":
                raise ValueError(f"run.method: \"{name}\" integrates only the "
                                 f"inverse-square force, params.potential = \"kepler\" "
                                 f"(got potential {p.potential!r})")
            energy = 0.5 * mu * (ini.vx**2 + ini.vy**2) - p.k / math.hypot(ini.x, ini.y)
            if energy >= 0.0:
                raise ValueError(f"run.method: \"{name}\" needs a bound orbit, E < 0 "
                                 f"(got E = {energy:.6g} J)")
        if p.potential == "kepler_inverse_cube" and L**2 <= 2.0 * mu * p.epsilon:
            raise ValueError(f"params.epsilon: L² ≤ 2 μ ε (L² = {L**2:.6g}, 2με = "
                             f"{2 * mu * p.epsilon:.6g}): the orbit spirals into the centre")
        return self




PRESETS = {
    "kepler_e07": {"params": {"m1": 1.0, "m2": 1.0, "k": 0.5},
                   "initial": {"x": 0.3, "y": 0.0, "vx": 0.0,
                               "vy": math.sqrt(1.7 / 0.3)},
                   "run": {"t_end": 10 * 2 * math.pi, "samples": 4001}},
}
