"""``rigid_body`` config: the principal moments or a solid shape (the shapes are
``inertia``'s), the initial state, an impulse, the splitting integrator, the presets."""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ...lazy import lazy_module
from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, RunConfig, Strict
from ..inertia.config import Shape

inertia_core = lazy_module("reportgen.core.inertia")


class Params(Strict):
    I1: Positive = Field(description="principal moment about body axis 1 [kg m²]")
    I2: Positive = Field(description="principal moment about body axis 2 [kg m²]")
    I3: Positive = Field(description="principal moment about body axis 3 [kg m²]")

    @model_validator(mode="after")
    def _triangle(self):
        # checked on the table itself, so it is reported together with problems elsewhere
        k = inertia_core.triangle_violation((self.I1, self.I2, self.I3))
        if k is not None:
            names = ["I1", "I2", "I3"]
            others = " + ".join(n for i, n in enumerate(names) if i != k)
            raise ValueError(f"params.{names[k]}: violates the triangle inequality "
                             f"{names[k]} ≤ {others} that every real body satisfies "
                             f"(got I1 = {self.I1}, I2 = {self.I2}, I3 = {self.I3})")
        return self


class Initial(Strict):
    omega: list[Real] = Field(description="[ω1, ω2, ω3] body-frame angular velocity [rad/s]")
    attitude: list[Real] = Field([1.0, 0.0, 0.0, 0.0],
                                 description="[w, x, y, z] unit quaternion body -> space "
                                             "[dimensionless]")

    @model_validator(mode="after")
    def _lengths(self):
        if len(self.omega) != 3:
            raise ValueError(f"initial.omega: expected [ω1, ω2, ω3] (got {self.omega})")
        if len(self.attitude) != 4:
            raise ValueError(f"initial.attitude: expected [w, x, y, z] (got {self.attitude})")
        n = math.sqrt(sum(x * x for x in self.attitude))
        if abs(n - 1.0) > 1e-6:
            raise ValueError(f"initial.attitude: must be a unit quaternion, |q| = 1 within 1e-6 "
                             f"(got |q| = {n:.9g})")
        return self


class Impulse(Strict):
    """``[impulse]``: an impulse P applied at a point r of the body at t = 0 (textbook ex. 4.6c)."""

    P: list[Real] = Field(description="[Px, Py, Pz] impulse, body frame [kg m/s]")
    at: list[Real] | Literal["apex"] = Field(
        description='[x, y, z] point of application relative to the CM, body frame [m], '
                    'or "apex" for a cone')


class Splitting(Strict):
    """``[splitting]``: the geometric integrator (free rotations about the principal axes)."""

    order: Literal[2, 4] = Field(4, description="2 (Strang) or 4 (Yoshida triple jump)")
    h: Positive | None = Field(None, description="step [s] (default: 1/200 of 2π/|ω0|)")


class RigidBodyConfig(SceneConfig):
    params: Params | None = None
    shape: Shape | None = None
    initial: Initial
    impulse: Impulse | None = None
    splitting: Splitting = Splitting()
    run: RunConfig

    @model_validator(mode="after")
    def _physics(self):
        if (self.params is None) == (self.shape is None):
            raise ValueError("params / shape: give either [params] I1, I2, I3 or a [shape] "
                             "table, not both and not neither")
        if self.shape is not None:
            for key in ("euler_angles", "about"):
                if getattr(self.shape, key) is not None:
                    raise ValueError(f"shape.{key}: not used by rigid_body (the body frame is "
                                     "the principal frame; set initial.attitude instead)")
        if self.impulse is not None:
            if len(self.impulse.P) != 3:
                raise ValueError(f"impulse.P: expected [Px, Py, Pz] (got {self.impulse.P})")
            at = self.impulse.at
            if at == "apex" and (self.shape is None or self.shape.type != "cone"):
                raise ValueError('impulse.at: "apex" needs a [shape] of type "cone"')
            if at != "apex" and len(at) != 3:
                raise ValueError(f"impulse.at: expected [x, y, z] (got {at})")
        return self


def body_moments(config: RigidBodyConfig) -> np.ndarray:
    """Principal moments along the body axes 1, 2, 3 (the configured order)."""
    if config.params is not None:
        p = config.params
        return np.array([p.I1, p.I2, p.I3])
    shape = config.shape
    if shape.type == "points":
        return inertia_core.principal_axes(shape.body_tensor())[0]
    return np.diag(shape.body_tensor()).copy()


#: the classic cases, one line each (explicit keys override)
PRESETS = {
    "dzhanibekov": {"title": "Dzhanibekov effect: flips about the intermediate axis",
                    "params": {"I1": 1.0, "I2": 2.0, "I3": 3.0},
                    "initial": {"omega": [0.01, 2.0, 0.01]},
                    "run": {"t_end": 40.0, "samples": 4001}},
    "symmetric_precession": {"title": "Symmetric body: precession of ω about the figure axis",
                             "params": {"I1": 1.0, "I2": 1.0, "I3": 1.5},
                             "initial": {"omega": [0.3, 0.0, 2.0]},
                             "run": {"t_end": 30.0, "samples": 3001}},
    "cone_impulse": {"title": "Spinning cone struck at its apex (textbook ex. 4.6c)",
                     "shape": {"type": "cone", "mass": 1.0, "radius": 0.5, "height": 2.0},
                     "initial": {"omega": [0.0, 0.0, 20.0]},
                     "impulse": {"P": [0.1, 0.0, 0.0], "at": "apex"},
                     "run": {"t_end": 5.0, "samples": 3001}},
    "octahedron_spin": {"title": "Octahedron spinning near its smallest-moment axis "
                                 "(textbook ex. 4.9)",
                        "shape": {"type": "octahedron", "equator": "rectangle",
                                  "mass": 1.0, "a": 0.4, "b": 0.8, "h": 1.2},
                        "initial": {"omega": [0.5, 0.5, 4.0]},
                        "run": {"t_end": 20.0, "samples": 4001}},
}
