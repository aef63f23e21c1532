"""``rotation`` config: the tables [axis_angle], [euler] and [su2], the presets, and the
section each table feeds."""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ...lazy import lazy_module
from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, Strict
from ...scene.units import angle_hint, check_turn

rotations = lazy_module("reportgen.core.rotations")  # an SU(2) element from its table

#: |a|² + |b|² of given Cayley–Klein parameters may miss 1 by this much (then normalized)
NORM_SLACK = 1e-6
#: the default SU(2) element [[a, b], [−b̄, ā]]: a turn by 2 arcsin 0.6 about −(0.8, 0.6, 0)
DEFAULT_A, DEFAULT_B = (0.8, 0.0), (0.36, 0.48)

Vector = list[Real]


def _unit(key: str, v: list[float]) -> None:
    norm = math.sqrt(sum(x * x for x in v))
    if not norm > 0.0 or not math.isfinite(norm):
        raise ValueError(f"{key}: must be a non-zero vector (it is normalized; got {v})")


class AxisAngle(Strict):
    """``[axis_angle]``: a rotation by Φ about n (textbook ex. 4.5)."""

    axis: Vector = Field([1.0, 1.0, 1.0], min_length=3, max_length=3,
                         description="rotation axis n, normalized here (must not be zero) "
                                     "[dimensionless]")
    angle: Real = Field(2.0 * math.pi / 3.0, description="rotation angle Φ, 0 < Φ ≤ π [rad] "
                                                         "(−Φ about n is Φ about −n)")
    vector: Vector = Field([1.0, 0.0, 0.0], min_length=3, max_length=3,
                           description="the vector r the rotation formula turns (figure) "
                                       "[dimensionless]")

    @model_validator(mode="after")
    def _rules(self):
        _unit("axis_angle.axis", self.axis)
        _unit("axis_angle.vector", self.vector)
        if not 0.0 < self.angle <= math.pi:
            raise ValueError(f"axis_angle.angle: must satisfy 0 < Φ ≤ π (got {self.angle}); "
                             "turn about −n for a negative angle"
                             + angle_hint(self.angle, valid=lambda a: 0.0 < a <= math.pi))
        return self


class Euler(Strict):
    """``[euler]``: Euler angles and their rates in one convention (textbook ex. 4.7, 4.8)."""

    convention: Literal["zxz", "zyz"] = Field(
        "zxz", description='"zxz" (that of Goldstein (4.46)) or "zyz": the convention the '
                           'angles are in')
    angles: Vector = Field([0.5, 0.8, 0.3], min_length=3, max_length=3,
                           description="[φ, θ, ψ] at t = 0, each |angle| ≤ 2π [rad]")
    rates: Vector = Field([0.7, 0.4, 1.5], min_length=3, max_length=3,
                          description="[φ̇, θ̇, ψ̇] along the sample path [rad/s]")
    duration: Positive = Field(4.0, description="length of the sample path (φ, θ, ψ) + "
                                                "(φ̇, θ̇, ψ̇) t [s]")
    samples: int = Field(81, ge=2, le=100_000, description="points on the sample path")

    @model_validator(mode="after")
    def _within_a_turn(self):
        check_turn("euler.angles", self.angles, symbol="angle")
        return self


class SU2(Strict):
    """``[su2]``: an SU(2) element by Cayley–Klein parameters or axis and angle (textbook ex. 4.11).

    Neither given: a = 0.8, b = 0.36 + 0.48 i."""

    a: Vector | None = Field(None, min_length=2, max_length=2,
                             description="[Re a, Im a] of U = [[a, b], [−b̄, ā]] "
                                         "[dimensionless]")
    b: Vector | None = Field(None, min_length=2, max_length=2,
                             description="[Re b, Im b]; |a|² + |b|² = 1 (normalized if "
                                         "within 1e-6) [dimensionless]")
    axis: Vector | None = Field(None, min_length=3, max_length=3,
                                description="or: axis n of U = exp(−i α n·σ/2), normalized "
                                            "[dimensionless]")
    angle: Real | None = Field(None, description="and its angle α, |α| ≤ 4π [rad] (α and "
                                                 "α + 2π give U and −U)")
    points: int = Field(200, ge=4, le=100_000,
                        description="sample points on the sphere (golden-angle spiral)")

    @model_validator(mode="after")
    def _one_form(self):
        ck = (self.a is not None, self.b is not None)
        aa = (self.axis is not None, self.angle is not None)
        if any(ck) and any(aa):
            raise ValueError("su2.a / su2.b / su2.axis / su2.angle: give U either by "
                             "Cayley–Klein parameters (a, b) or by axis and angle, not both")
        if any(ck) and not all(ck):
            raise ValueError("su2.a / su2.b: give both Cayley–Klein parameters")
        if any(aa) and not all(aa):
            raise ValueError("su2.axis / su2.angle: give both the axis and the angle")
        if all(ck):
            norm2 = sum(x * x for x in (*self.a, *self.b))
            if not abs(norm2 - 1.0) <= NORM_SLACK:
                raise ValueError(f"su2.a / su2.b: |a|² + |b|² must be 1 (within {NORM_SLACK:g}; "
                                 f"got {norm2:.9g})")
        if self.axis is not None:
            _unit("su2.axis", self.axis)
        if self.angle is not None:
            check_turn("su2.angle", self.angle, turns=2, symbol="α")
        return self

    def element(self) -> np.ndarray:
        """U, shape (2, 2), exactly unitary."""
        if self.axis is not None:
            return rotations.su2_from_axis_angle(self.axis, self.angle)
        a, b = (self.a, self.b) if self.a is not None else (DEFAULT_A, DEFAULT_B)
        a, b = complex(*a), complex(*b)
        norm = math.sqrt(abs(a) ** 2 + abs(b) ** 2)
        return rotations.su2_from_cayley_klein(a / norm, b / norm)


#: the config tables each section draws from, all needed (its /analysis group:
#: results.SECTION_DATA): the matrix identities turn the axis–angle matrix by the Euler
#: matrix and differentiate the Euler path; the SU(2) form writes both in SU(2)
SECTION_TABLES = {"axis_angle": ("axis_angle",), "euler_angles": ("euler",),
                  "angular_velocity": ("euler",),
                  "matrix_identities": ("axis_angle", "euler"),
                  "su2_euler": ("axis_angle", "euler"), "stereographic": ("su2",),
                  "matrix_proofs": ("proofs",)}


class Proofs(Strict):
    """``[proofs]``: textbook ex. 4.1–4.4 proved for all n × n matrices by SymPy, and checked
    on random ones."""

    sizes: list[Literal[2, 3]] = Field([2, 3], min_length=1, max_length=2,
                                       description="the matrix sizes n to prove for (2, 3)")
    seed: int = Field(4, ge=0, le=2**32 - 1, description="seed of the random matrices of "
                      "the numerical checks")


class RotationConfig(SceneConfig):
    axis_angle: AxisAngle | None = None
    euler: Euler | None = None
    su2: SU2 | None = None
    proofs: Proofs | None = None

    @model_validator(mode="after")
    def _rules(self):
        if self.run is not None:
            raise ValueError("run: the rotation kind integrates nothing; remove the [run] table")
        if (self.axis_angle is None and self.euler is None and self.su2 is None
                and self.proofs is None):
            raise ValueError("axis_angle / euler / su2 / proofs: give at least one of the "
                             "tables [axis_angle], [euler], [su2], [proofs] (or a preset)")
        for name in self.report.sections or ():
            missing = [t for t in SECTION_TABLES.get(name, ()) if getattr(self, t) is None]
            if missing:
                tables = " and ".join(f"[{t}]" for t in missing)
                noun = "tables" if len(missing) > 1 else "table"
                raise ValueError(f"report.sections: section '{name}' needs the {tables} {noun}")
        return self


#: one table each, or all (explicit keys override)
PRESETS = {
    "axis_angle": {"axis_angle": {}},
    "euler_zxz": {"euler": {"convention": "zxz"}},
    "euler_zyz": {"euler": {"convention": "zyz"}},
    "su2": {"su2": {}},
    "all": {"axis_angle": {}, "euler": {}, "su2": {}},
}
