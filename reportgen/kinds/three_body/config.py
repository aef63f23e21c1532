"""``three_body`` config: masses, initial states, labels, presets (Sun–Earth–Moon,
figure-eight, Pythagorean); or ``[restricted]``, the planar circular restricted problem
in the rotating frame (a test particle and two primaries of mass ratio μ)."""

from __future__ import annotations

import math
from typing import Annotated

import numpy as np
from pydantic import AfterValidator, Field, model_validator

from ...scene.base import SceneConfig
from ...scene.config import OwnUnitsRunConfig, Positive, Real, Strict, _finite

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


class Restricted(Strict):
    """``[restricted]``: the planar circular restricted three-body problem in the frame
    rotating with the primaries (Murray & Dermott §3.2): masses 1 − μ at (−μ, 0) and μ at
    (1 − μ, 0), G = m1 + m2 = 1, separation 1, mean motion 1 (so the unit of time is the
    primaries' period / 2π).  The test particle starts at (x, y) with (ẋ, ẏ), or with ẏ
    solved from the Jacobi constant C."""

    mu: Annotated[float, Field(gt=0, le=0.5), AfterValidator(_finite)] = Field(
        description="mass ratio μ = m2/(m1 + m2) of the smaller primary, 0 < μ ≤ 0.5 "
                    "[dimensionless]")
    x: Real = Field(description="initial position x in the rotating frame, in units of the "
                                "primaries' separation [dimensionless]")
    y: Real = Field(0.0, description="initial position y in the rotating frame, in units of "
                                     "the primaries' separation [dimensionless]")
    vx: Real = Field(0.0, description="initial velocity ẋ in the rotating frame, in units of "
                                      "the separation times the mean motion [dimensionless]")
    vy: Real | None = Field(None, description="initial velocity ẏ in the rotating frame "
                                              "[dimensionless]; leave it out and give jacobi "
                                              "to have it solved for (ẏ ≥ 0)")
    jacobi: Real | None = Field(None, description="Jacobi constant C = 2Ω − ẋ² − ẏ² "
                                                  "(then ẏ ≥ 0 is solved for, so that a "
                                                  "sweep's members share one C) "
                                                  "[dimensionless]")

    @model_validator(mode="after")
    def _a_start_the_level_allows(self):
        for name, xp in (("larger", -self.mu), ("smaller", 1.0 - self.mu)):
            if self.y == 0.0 and self.x == xp:
                raise ValueError(f"restricted.x / restricted.y: the particle starts at the "
                                 f"{name} primary ({xp:g}, 0) (a collision)")
        if (self.vy is None) == (self.jacobi is None):
            raise ValueError("restricted.vy / restricted.jacobi: give exactly one of them "
                             "(got " + ("both" if self.vy is not None else "neither") + ")")
        if self.jacobi is not None:
            ceiling = 2.0 * omega(self.x, self.y, self.mu) - self.vx ** 2
            if self.jacobi > ceiling:
                raise ValueError(
                    f"restricted.jacobi: the start (x, y) = ({self.x:.12g}, {self.y:.12g}) "
                    f"lies in the region the level C = {self.jacobi!r} forbids (inside its "
                    f"zero-velocity curve, where ẏ² = 2Ω − C − ẋ² < 0): C may be at most "
                    f"2Ω − ẋ² = {ceiling:.12g} there")
        return self

    def initial_state(self) -> tuple[float, float, float, float]:
        """(x, y, ẋ, ẏ), ẏ = +√(2Ω − C − ẋ²) when ``jacobi`` is given."""
        if self.vy is not None:
            return self.x, self.y, self.vx, self.vy
        vy2 = 2.0 * omega(self.x, self.y, self.mu) - self.jacobi - self.vx ** 2
        return self.x, self.y, self.vx, math.sqrt(max(vy2, 0.0))

    def jacobi_constant(self) -> float:
        """C of the initial state (the given one, or 2Ω − v² from vy)."""
        x, y, vx, vy = self.initial_state()
        return self.jacobi if self.jacobi is not None else \
            2.0 * omega(x, y, self.mu) - vx * vx - vy * vy


def omega(x: float, y: float, mu: float) -> float:
    """Ω = (x² + y²)/2 + (1 − μ)/r1 + μ/r2 at (x, y) (the config's check of
    restricted.jacobi; the numerics use :mod:`reportgen.core.models.restricted_three_body`)."""
    return (0.5 * (x * x + y * y) + (1.0 - mu) / math.hypot(x + mu, y)
            + mu / math.hypot(x - 1.0 + mu, y))


class ThreeBodyConfig(SceneConfig):
    params: Params | None = Field(None, description="G and the masses (not with the "
                                                       "restricted problem's table)")
    initial: Initial | None = Field(None, description="the bodies' positions and velocities "
                                                      "(not with the restricted problem's "
                                                      "table)")
    restricted: Restricted | None = Field(None, description="the planar circular restricted "
                                                            "problem, instead of the params "
                                                            "and initial tables")
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
                                                         "the run is flagged unstable (for the "
                                                         "restricted problem: the Jacobi "
                                                         "constant's error relative to its "
                                                         "term 2Ω) [dimensionless]")

    @model_validator(mode="after")
    def _one_problem(self):
        if self.restricted is None:
            if self.params is None or self.initial is None:
                missing = " and ".join(t for t in ("params", "initial")
                                       if getattr(self, t) is None)
                raise ValueError(f"{missing.replace(' and ', ' / ')}: required key is "
                                 f"missing: [{missing.replace(' and ', '] and [')}] (the "
                                 "masses and the bodies' states), or [restricted] for the "
                                 "restricted problem")
            return self
        given = [t for t in ("params", "initial") if getattr(self, t) is not None]
        if given:
            raise ValueError(f"{' / '.join(given)}: [restricted] is the whole physics of the "
                             "restricted problem (masses 1 − μ and μ, G = 1, the particle's "
                             f"start): leave out [{'] and ['.join(given)}]")
        if self.period is not None:
            raise ValueError("period: a known period is checked on the full problem's "
                             "bodies; the restricted problem has none to give")
        return self

    @property
    def is_restricted(self) -> bool:
        return self.restricted is not None

    @model_validator(mode="after")
    def _no_collision(self):
        if self.initial is None:
            return self
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
