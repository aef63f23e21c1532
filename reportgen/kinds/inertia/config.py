"""``inertia`` config: the uniform solid shapes and point sets (shared with ``rigid_body``),
the config class and the presets.

Each shape gives its inertia tensor in its own frame (:mod:`reportgen.core.inertia`,
imported on first use: validating a config imports no numerics but for a point set's
centre of mass).
"""

from __future__ import annotations

from typing import Annotated, Literal

import numpy as np
from pydantic import Field, model_validator

from ...lazy import lazy_module
from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, Strict
from ...scene.content import fmt

core = lazy_module("reportgen.core.inertia")
rotations = lazy_module("reportgen.core.rotations")


class _ShapeBase(Strict):
    euler_angles: list[Real] | None = Field(
        None, description="[φ, θ, ψ] (z-x-z): orientation of the shape in the lab frame "
                          "[rad]")
    about: list[Real] | None = Field(
        None, description="[x, y, z] lab-frame point for the parallel-axis shift (8.49) [m]")

    @model_validator(mode="after")
    def _vectors(self):
        for key in ("euler_angles", "about"):
            value = getattr(self, key)
            if value is not None and len(value) != 3:
                raise ValueError(f"shape.{key}: expected 3 numbers (got {len(value)})")
        return self

    def rotation(self) -> np.ndarray:
        return np.eye(3) if self.euler_angles is None else rotations.euler_matrix(*self.euler_angles)

    def lab_tensor(self) -> np.ndarray:
        return core.rotate_tensor(self.body_tensor(), self.rotation())

    def centre_of_mass(self) -> np.ndarray:
        return np.zeros(3)


class Cone(_ShapeBase):
    type: Literal["cone"]
    mass: Positive = Field(description="mass M [kg]")
    radius: Positive = Field(description="base radius R [m]")
    height: Positive = Field(description="height h [m]; apex at z = +3h/4 from the CM")

    def body_tensor(self):
        return core.tensor_cone(self.mass, self.radius, self.height)

    def apex(self):
        return np.array([0.0, 0.0, core.cone_apex_height(self.height)])

    def describe(self):
        return f"solid cone, M = {fmt(self.mass)} kg, R = {fmt(self.radius)} m, " \
               f"h = {fmt(self.height)} m"

    def closed_form_source(self):
        return "I⊥ = 3M(R² + h²/4)/20, I3 = 3MR²/10 (Landau & Lifshitz §32 Problem 2; ex. 4.6)"


class Box(_ShapeBase):
    type: Literal["box"]
    mass: Positive = Field(description="mass M [kg]")
    a: Positive = Field(description="full side length along x [m]")
    b: Positive = Field(description="full side length along y [m]")
    c: Positive = Field(description="full side length along z [m]")

    def body_tensor(self):
        return core.tensor_box(self.mass, self.a, self.b, self.c)

    def describe(self):
        return f"box, M = {fmt(self.mass)} kg, sides {fmt(self.a)} × {fmt(self.b)} × " \
               f"{fmt(self.c)} m"

    def closed_form_source(self):
        return "Iₓₓ = M(b² + c²)/12, cyclic (Landau & Lifshitz §32 Problem 2)"


class Cylinder(_ShapeBase):
    type: Literal["cylinder"]
    mass: Positive = Field(description="mass M [kg]")
    radius: Positive = Field(description="radius R [m]")
    height: Positive = Field(description="height h along z [m]")

    def body_tensor(self):
        return core.tensor_cylinder(self.mass, self.radius, self.height)

    def describe(self):
        return f"solid cylinder, M = {fmt(self.mass)} kg, R = {fmt(self.radius)} m, " \
               f"h = {fmt(self.height)} m"

    def closed_form_source(self):
        return "I⊥ = M(R²/4 + h²/12), I3 = MR²/2 (Landau & Lifshitz §32 Problem 2)"


class Ellipsoid(_ShapeBase):
    type: Literal["ellipsoid"]
    mass: Positive = Field(description="mass M [kg]")
    a: Positive = Field(description="semi-axis along x [m]")
    b: Positive = Field(description="semi-axis along y [m]")
    c: Positive = Field(description="semi-axis along z [m]")

    def body_tensor(self):
        return core.tensor_ellipsoid(self.mass, self.a, self.b, self.c)

    def describe(self):
        return f"solid ellipsoid, M = {fmt(self.mass)} kg, semi-axes {fmt(self.a)}, " \
               f"{fmt(self.b)}, {fmt(self.c)} m"

    def closed_form_source(self):
        return "Iₓₓ = M(b² + c²)/5, cyclic (Landau & Lifshitz §32 Problem 2)"


class Octahedron(_ShapeBase):
    type: Literal["octahedron"]
    mass: Positive = Field(description="mass M [kg]")
    a: Positive = Field(description="half-diagonal along x [m]")
    b: Positive = Field(description="half-diagonal along y [m]")
    c: Positive = Field(description="half-diagonal along z [m]")

    def body_tensor(self):
        return core.tensor_octahedron(self.mass, self.a, self.b, self.c)

    def describe(self):
        return f"solid octahedron, M = {fmt(self.mass)} kg, half-diagonals {fmt(self.a)}, " \
               f"{fmt(self.b)}, {fmt(self.c)} m"

    def closed_form_source(self):
        return "Iₓₓ = M(b² + c²)/10, cyclic (exercise 4.9; Dirichlet integral)"


class Points(_ShapeBase):
    type: Literal["points"]
    masses: list[Positive] = Field(min_length=1, description="point masses [kg]")
    positions: list[list[Real]] = Field(description="[[x, y, z], …] positions [m]")

    @model_validator(mode="after")
    def _shapes(self):
        if len(self.positions) != len(self.masses):
            raise ValueError(f"shape.positions: expected one [x, y, z] per mass "
                             f"({len(self.masses)}), got {len(self.positions)}")
        for i, p in enumerate(self.positions):
            if len(p) != 3:
                raise ValueError(f"shape.positions[{i}]: expected [x, y, z] (got {p})")
        r = np.asarray(self.positions, dtype=float)
        d = r - core.centre_of_mass(self.masses, r)
        if len(self.masses) < 2 or np.linalg.matrix_rank(d, tol=1e-12 * max(1e-300, np.abs(
                d).max())) < 1:
            raise ValueError("shape.positions: the points must not all coincide (a single "
                             "point has no rotational inertia)")
        return self

    @property
    def mass(self):
        return float(sum(self.masses))

    def body_tensor(self):
        return core.tensor_points(self.masses, self.positions)

    def lab_tensor(self):
        return core.rotate_tensor(self.body_tensor(), self.rotation())

    def centre_of_mass(self):
        return self.rotation() @ core.centre_of_mass(self.masses, self.positions)

    def lab_positions(self):
        return np.asarray(self.positions, dtype=float) @ self.rotation().T

    def describe(self):
        return f"{len(self.masses)} point masses, M = {fmt(self.mass)} kg"

    def closed_form_source(self):
        return "Σ m (r² δ_ij − r_i r_j) about the centre of mass"


Shape = Annotated[Cone | Box | Cylinder | Ellipsoid | Octahedron | Points,
                  Field(discriminator="type")]


def shape_moments(shape) -> tuple[np.ndarray, np.ndarray]:
    """Principal moments (ascending) and axes (columns, lab frame) of a shape about its CM."""
    return core.principal_axes(shape.lab_tensor())


class InertiaConfig(SceneConfig):
    shape: Shape

    @model_validator(mode="after")
    def _no_run(self):
        if self.run is not None:
            raise ValueError("run: the inertia kind integrates nothing; remove the [run] table")
        return self


#: the classic cases, one line each (explicit keys override)
PRESETS = {
    "cone": {"shape": {"type": "cone", "mass": 1.0, "radius": 0.5, "height": 2.0}},
    "octahedron": {"shape": {"type": "octahedron", "mass": 1.0, "a": 1.0, "b": 0.8,
                             "c": 0.6}},
}
