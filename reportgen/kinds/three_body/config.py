"""``three_body`` config: masses, initial states, labels, presets (Sun–Earth–Moon,
figure-eight, Pythagorean)."""

from __future__ import annotations

import math
from typing import Annotated

import numpy as np
from pydantic import Field, model_validator

from ...scene.base import SceneConfig
from ...scene.config import OwnUnitsRunConfig, Positive, Real, Strict

Vector3 = Annotated[list[Real], Field(min_length=3, max_length=3)]


class Params(Strict):
    """``[params]``: G and the masses, in the config's own units.

    AU, years and solar masses give G = 4π²; G = 1 with any units of length and time
    makes the unit of mass."""

    G: Positive = Field(1.0, description="gravitational constant "
                                         "[config units of length³/(mass·time²)]")
    masses: list[Positive] = Field(min_length=3, max_length=3,
                                   description="[m1, m2, m3] [config units of mass]")


class Initial(Strict):
    """``[initial]``: the bodies' positions and velocities in the config's own units."""

    positions: list[Vector3] = Field(min_length=3, max_length=3,
                                     description="[[x, y, z] × 3] of bodies 1, 2, 3 "
                                                 "[config units of length]")
    velocities: list[Vector3] = Field(min_length=3, max_length=3,
                                      description="[[vx, vy, vz] × 3] of bodies 1, 2, 3 "
                                                  "[config units of length/time]")


class ThreeBodyConfig(SceneConfig):
    params: Params
    initial: Initial
    run: OwnUnitsRunConfig
    names: list[str] = Field(["body 1", "body 2", "body 3"], min_length=3, max_length=3,
                             description="labels of the bodies in figures")
    length_unit: str = Field("", max_length=20, description="name of the config's unit of "
                                                            "length, shown on axes (\"AU\")")
    time_unit: str = Field("", max_length=20, description="name of the config's unit of "
                                                          "time, shown on axes (\"yr\")")
    period: Positive | None = Field(None, description="known period of a periodic orbit: "
                                                      "checks the return to the start "
                                                      "[config units of time]")
    energy_tolerance: Positive = Field(1e-8, description="relative energy error above which "
                                                         "the run is flagged unstable "
                                                         "[dimensionless]")

    @model_validator(mode="after")
    def _no_collision(self):
        pos = np.asarray(self.initial.positions, dtype=float)
        for i in range(3):
            for j in range(i + 1, 3):
                if np.array_equal(pos[i], pos[j]):
                    raise ValueError(f"initial.positions: bodies {i + 1} and {j + 1} start at "
                                     f"the same point {pos[i].tolist()} (a collision)")
        return self


def _sun_earth_moon() -> dict:
    """Sun, Earth, Moon in AU, years, solar masses (G = 4π²); centre of mass at rest at 0.

    Masses: Earth/Sun 3.0035e-6, Moon/Sun 3.6943e-8 (IAU 2012 values; the notes' ~1e-6 and
    ~1e-8, 3.35).  Earth on a circular orbit at 1 AU, the Moon at 384 400 km = 0.0025696 AU
    on a circular orbit about the Earth inclined 5.145° to the ecliptic.
    """
    G = 4 * math.pi**2
    m = np.array([1.0, 3.0035e-6, 3.6943e-8])
    d, inc = 0.0025696, math.radians(5.145)
    r = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0 + d, 0.0, 0.0]])
    v_earth = math.sqrt(G * m.sum())
    v_moon = math.sqrt(G * (m[1] + m[2]) / d)
    v = np.array([[0.0, 0.0, 0.0], [0.0, v_earth, 0.0],
                  [0.0, v_earth + v_moon * math.cos(inc), v_moon * math.sin(inc)]])
    r -= m @ r / m.sum()
    v -= m @ v / m.sum()
    return {"params": {"G": G, "masses": m.tolist()},
            "initial": {"positions": r.tolist(), "velocities": v.tolist()},
            "names": ["Sun", "Earth", "Moon"], "length_unit": "AU", "time_unit": "yr",
            "run": {"t_end": 1.0, "samples": 8001}}


# Chenciner & Montgomery (2000), initial conditions of Simó: x1 = −x2, x3 = 0,
# v1 = v2 = −v3/2, G = m = 1; period 6.32591398 (Simó 2002, Table 1).
_V3 = (-0.93240737, -0.86473146)
FIGURE_EIGHT_PERIOD = 6.32591398

PRESETS = {
    "sun_earth_moon": _sun_earth_moon(),
    "figure_eight": {
        "params": {"G": 1.0, "masses": [1.0, 1.0, 1.0]},
        "initial": {"positions": [[0.97000436, -0.24308753, 0.0],
                                  [-0.97000436, 0.24308753, 0.0], [0.0, 0.0, 0.0]],
                    "velocities": [[-_V3[0] / 2, -_V3[1] / 2, 0.0],
                                   [-_V3[0] / 2, -_V3[1] / 2, 0.0], [_V3[0], _V3[1], 0.0]]},
        "period": FIGURE_EIGHT_PERIOD,
        "run": {"t_end": FIGURE_EIGHT_PERIOD, "samples": 2001},
    },
    # Burrau's problem: masses 3, 4, 5 at rest at the vertices of a 3-4-5 triangle, each
    # opposite the side of its own length (Szebehely & Peters 1967).
    "pythagorean": {
        "params": {"G": 1.0, "masses": [3.0, 4.0, 5.0]},
        "initial": {"positions": [[1.0, 3.0, 0.0], [-2.0, -1.0, 0.0], [1.0, -1.0, 0.0]],
                    "velocities": [[0.0, 0.0, 0.0]] * 3},
        "run": {"t_end": 70.0, "samples": 14001, "rtol": 1e-13, "atol": 1e-15},
    },
}

#: m3/m2 and m2/m1 below this make a hierarchical triple (planet + moon; Moon/Earth = 0.0123)
HIERARCHY_RATIO = 0.05


