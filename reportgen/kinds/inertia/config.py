"""``inertia`` config: the uniform solid shapes and point sets (shared with ``rigid_body``),
the config class and the presets.

Each shape gives its inertia tensor in its own frame (:mod:`reportgen.core.inertia`,
imported on first use: validating a config imports no numerics but for a point set's
centre of mass).
"""

from __future__ import annotations

import math
from typing import Annotated, ClassVar, Literal

import numpy as np
from pydantic import Field, model_validator

from ...lazy import lazy_module
from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, Strict
from ...scene.content import fmt
from ...scene.units import check_turn

core = lazy_module("reportgen.core.inertia")
rotations = lazy_module("reportgen.core.rotations")


class _ShapeBase(Strict):
    euler_angles: list[Real] | None = Field(
        None, description="[φ, θ, ψ] (z-x-z): orientation of the shape in the lab frame, "
                          "each |angle| ≤ 2π [rad]")
    about: list[Real] | None = Field(
        None, description="[x, y, z] lab-frame point for the parallel-axis shift "
                          "(notes (8.49)) [m]")

    @model_validator(mode="after")
    def _vectors(self):
        for key in ("euler_angles", "about"):
            value = getattr(self, key)
            if value is not None and len(value) != 3:
                raise ValueError(f"shape.{key}: expected 3 numbers (got {len(value)})")
        if self.euler_angles is not None:
            check_turn("shape.euler_angles", self.euler_angles, symbol="angle")
        return self

    def rotation(self) -> np.ndarray:
        return np.eye(3) if self.euler_angles is None else rotations.euler_matrix(*self.euler_angles)

    def lab_tensor(self) -> np.ndarray:
        return core.rotate_tensor(self.body_tensor(), self.rotation())

    def centre_of_mass(self) -> np.ndarray:
        return np.zeros(3)

    #: the shape's own axes x, y, z in words (for the principal axes they turn out to be)
    AXIS_WORDS: ClassVar[dict[str, str]] = {"x": "x", "y": "y", "z": "z"}

    def axis_words(self) -> dict[str, str]:
        return dict(self.AXIS_WORDS)

    def mass_elements(self) -> tuple[np.ndarray, np.ndarray, float]:
        """The body as point masses at quadrature nodes (:mod:`reportgen.core.inertia`),
        own frame with the origin at the closed-form centre of mass: masses [kg],
        positions (N, 3) [m], the volume they integrate [m³]."""
        raise NotImplementedError


class Cone(_ShapeBase):
    type: Literal["cone"]
    mass: Positive = Field(description="mass M [kg]")
    radius: Positive = Field(description="base radius R [m]")
    height: Positive = Field(description="height h [m]; apex at z = +3h/4 from the CM")

    def body_tensor(self):
        return core.tensor_cone(self.mass, self.radius, self.height)

    def apex(self):
        return np.array([0.0, 0.0, core.cone_apex_height(self.height)])

    AXIS_WORDS: ClassVar[dict[str, str]] = {"x": "x, transverse", "y": "y, transverse",
                  "z": "z, the symmetry axis through the apex"}

    def volume(self):
        return core.cone_volume(self.radius, self.height)

    def mass_elements(self):
        m, r, vol = core.quadrature_cone(self.mass, self.radius, self.height)
        return m, r + self.apex(), vol  # quadrature from the apex, shifted by the closed form

    def describe(self):
        return f"solid cone, M = {fmt(self.mass)} kg, R = {fmt(self.radius)} m, " \
               f"h = {fmt(self.height)} m"

    def closed_form_source(self):
        return ("I⊥ = 3M(R² + h²/4)/20, I3 = 3MR²/10 (Landau & Lifshitz §32 Problem 2; "
                "textbook ex. 4.6)")


class Box(_ShapeBase):
    type: Literal["box"]
    mass: Positive = Field(description="mass M [kg]")
    a: Positive = Field(description="full side length along x [m]")
    b: Positive = Field(description="full side length along y [m]")
    c: Positive = Field(description="full side length along z [m]")

    def body_tensor(self):
        return core.tensor_box(self.mass, self.a, self.b, self.c)

    AXIS_WORDS: ClassVar[dict[str, str]] = {"x": "x, along the side a", "y": "y, along the side b",
                  "z": "z, along the side c"}

    def volume(self):
        return self.a * self.b * self.c

    def mass_elements(self):
        return core.quadrature_box(self.mass, self.a, self.b, self.c)

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

    AXIS_WORDS: ClassVar[dict[str, str]] = {"x": "x, transverse", "y": "y, transverse",
                                            "z": "z, the symmetry axis"}

    def volume(self):
        return math.pi * self.radius**2 * self.height

    def mass_elements(self):
        return core.quadrature_cylinder(self.mass, self.radius, self.height)

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

    AXIS_WORDS: ClassVar[dict[str, str]] = {"x": "x, along the semi-axis a",
                                            "y": "y, along the semi-axis b",
                  "z": "z, along the semi-axis c"}

    def volume(self):
        return 4.0 * math.pi * self.a * self.b * self.c / 3.0

    def mass_elements(self):
        return core.quadrature_ellipsoid(self.mass, self.a, self.b, self.c)

    def describe(self):
        return f"solid ellipsoid, M = {fmt(self.mass)} kg, semi-axes {fmt(self.a)}, " \
               f"{fmt(self.b)}, {fmt(self.c)} m"

    def closed_form_source(self):
        return "Iₓₓ = M(b² + c²)/5, cyclic (Landau & Lifshitz §32 Problem 2)"


class Octahedron(_ShapeBase):
    """Two octahedra (textbook ex. 4.9): ``equator = "rhombus"`` (the default),
    |x|/a + |y|/b + |z|/c ≤ 1 with half-diagonals a, b, c; ``equator = "rectangle"``, the
    double pyramid over the a × b rectangle in z = 0 with apexes at (0, 0, ±h)."""

    type: Literal["octahedron"]
    mass: Positive = Field(description="mass M [kg]")
    equator: Literal["rhombus", "rectangle"] = Field(
        "rhombus", description='"rhombus": half-diagonals a, b, c; "rectangle": an a × b '
                               "rectangular equator and apexes at ±h")
    a: Positive = Field(description="half-diagonal along x (rhombus) or full side of the "
                                    "equator along x (rectangle) [m]")
    b: Positive = Field(description="half-diagonal along y (rhombus) or full side of the "
                                    "equator along y (rectangle) [m]")
    c: Positive | None = Field(None, description="half-diagonal along z (rhombus only) [m]")
    h: Positive | None = Field(None, description="height of each apex above the equator "
                                                 "(rectangle only) [m]")

    @model_validator(mode="after")
    def _sizes(self):
        need, other = ("c", "h") if self.equator == "rhombus" else ("h", "c")
        if getattr(self, need) is None:
            raise ValueError(f"shape.{need}: required for equator = \"{self.equator}\"")
        if getattr(self, other) is not None:
            raise ValueError(f"shape.{other}: not used with equator = \"{self.equator}\" "
                             f"(give {need})")
        return self

    @property
    def rectangle(self) -> bool:
        return self.equator == "rectangle"

    def body_tensor(self):
        if self.rectangle:
            return core.tensor_octahedron_rectangle(self.mass, self.a, self.b, self.h)
        return core.tensor_octahedron(self.mass, self.a, self.b, self.c)

    def axis_words(self):
        if self.rectangle:
            return {"x": "x, along the side a", "y": "y, along the side b",
                    "z": "z, through the apexes"}
        return {"x": "x, along the diagonal 2a", "y": "y, along the diagonal 2b",
                "z": "z, along the diagonal 2c"}

    def volume(self):
        if self.rectangle:
            return core.octahedron_rectangle_volume(self.a, self.b, self.h)
        return core.octahedron_volume(self.a, self.b, self.c)

    def mass_elements(self):
        if self.rectangle:
            return core.quadrature_octahedron_rectangle(self.mass, self.a, self.b, self.h)
        return core.quadrature_octahedron(self.mass, self.a, self.b, self.c)

    def describe(self):
        if self.rectangle:
            return (f"solid octahedron, M = {fmt(self.mass)} kg, equator a rectangle "
                    f"{fmt(self.a)} × {fmt(self.b)} m, apexes at ±{fmt(self.h)} m")
        return f"solid octahedron, M = {fmt(self.mass)} kg, half-diagonals {fmt(self.a)}, " \
               f"{fmt(self.b)}, {fmt(self.c)} m"

    def closed_form_source(self):
        if self.rectangle:
            return ("M(b² + 2h²)/20, M(a² + 2h²)/20, M(a² + b²)/20 about x, y, z "
                    "(textbook ex. 4.9)")
        return "Iₓₓ = M(b² + c²)/10, cyclic (textbook exercise 4.9; Dirichlet integral)"


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
        rank = 0 if len(self.masses) < 2 else np.linalg.matrix_rank(
            d, tol=1e-12 * max(1e-300, np.abs(d).max()))
        if rank < 1:
            raise ValueError("shape.positions: the points must not all coincide (a single "
                             "point has no rotational inertia)")
        if rank < 2:
            raise ValueError("shape.positions: the points lie on one line, so their moment "
                             "about it is 0; a body needs three positive principal moments "
                             "(its inertia ellipsoid and Euler's equations divide by each)")
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

    def mass_elements(self):
        r = np.asarray(self.positions, dtype=float)
        return (np.asarray(self.masses, dtype=float), r - core.centre_of_mass(self.masses, r),
                math.nan)

    def describe(self):
        return f"{len(self.masses)} point masses, M = {fmt(self.mass)} kg"

    def closed_form_source(self):
        return "Σ m (r² δ_ij − r_i r_j) about the centre of mass"


Shape = Annotated[Cone | Box | Cylinder | Ellipsoid | Octahedron | Points,
                  Field(discriminator="type")]


#: principal moments closer than this share of the largest are equal: the body is a
#: symmetric top (two equal) or a spherical one (three); the one threshold of the words of
#: both ``inertia`` and ``rigid_body`` (imports no numerics: titles use it too)
EQUAL_MOMENTS_RTOL = 1e-12


def body_symmetry(moments, rtol: float = EQUAL_MOMENTS_RTOL) -> tuple[str, int | None]:
    """Which kind of top the principal moments make: ("spherical", None) for three equal
    moments, ("symmetric", s) for two, s the index of the odd (figure) axis, else
    ("asymmetric", None); equal within ``rtol`` of the largest moment."""
    I = [float(x) for x in moments]
    tol = rtol * max(abs(x) for x in I)
    if max(I) - min(I) <= tol:
        return "spherical", None
    for s in range(3):
        if abs(I[(s + 1) % 3] - I[(s + 2) % 3]) <= tol:
            return "symmetric", s
    return "asymmetric", None


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
