r"""``inertia``: the inertia tensor of a shape or a point set, its principal moments and axes,
the parallel-axis shift (8.49) and which free-spin axes are stable (10.12)–(10.14).

Nothing is integrated.  Solid shapes are uniform and given in their own frame
(centre of mass at the origin, symmetry axis / half-diagonals along x, y, z); an
optional ``euler_angles`` = [φ, θ, ψ] (z-x-z) turns the shape in the lab frame so that
the tensor is full and the principal axes come out of the diagonalization.
"""

from __future__ import annotations

from typing import Annotated, Literal

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, Strict
from ..lazy import lazy_module
from ..results import Check, Results
from .base import Scene, SceneConfig, Section, SectionContent, Table, fmt, fmt_err

core = lazy_module("reportgen.core.inertia")
rotations = lazy_module("reportgen.core.rotations")
plots = lazy_module("reportgen.plots.rigid_body")


class _ShapeBase(Strict):
    euler_angles: list[Real] | None = Field(
        None, description="[φ, θ, ψ] (z-x-z, rad): orientation of the shape in the lab frame")
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
        return "I_xx = M(b² + c²)/12, cyclic (Landau & Lifshitz §32 Problem 2)"


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
        return "I_xx = M(b² + c²)/5, cyclic (Landau & Lifshitz §32 Problem 2)"


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
        return "I_xx = M(b² + c²)/10, cyclic (exercise 4.9; Dirichlet integral)"


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


class InertiaScene(Scene):
    kind = "inertia"
    order = 90
    summary = "inertia tensor of a shape or point set, principal axes, stable spin axes"
    Config = InertiaConfig
    presets = {
        "cone": {"shape": {"type": "cone", "mass": 1.0, "radius": 0.5, "height": 2.0}},
        "octahedron": {"shape": {"type": "octahedron", "mass": 1.0, "a": 1.0, "b": 0.8,
                                 "c": 0.6}},
    }
    sections = (
        Section("tensor", "Inertia tensor and principal axes"),
        Section("parallel_axis", "Parallel-axis shift"),
        Section("stability", "Stability of free spin about each principal axis"),
    )

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        if "parallel_axis" not in data.analysis:
            names.remove("parallel_axis")
        return names

    def simulate(self, progress=None) -> Results:
        shape = self.config.shape
        tensor = shape.lab_tensor()
        moments, axes = core.principal_axes(tensor)
        results = Results()
        stab = core.axis_stability(moments)
        results.analysis.update({
            "tensor": tensor,
            "principal_moments": moments,
            "principal_axes": axes,
            "centre_of_mass": shape.centre_of_mass(),
            "mass": float(shape.mass),
            "shape": shape.describe(),
            "axis_stability": {f"axis_{k + 1}": s for k, s in enumerate(stab)},
            "inertia_ellipsoid": core.inertia_ellipsoid(moments, axes),
        })
        if shape.type == "points":
            results.analysis["points"] = {"positions": shape.lab_positions(),
                                          "masses": np.asarray(shape.masses, dtype=float)}
        else:
            closed = np.sort(np.diag(shape.body_tensor()))
            results.analysis["closed_form"] = {
                "principal_moments": closed, "source": shape.closed_form_source(),
                "max_relative_difference": float(np.max(np.abs(moments - closed)) / closed[2])}
            for k in range(3):
                results.checks.append(Check(
                    f"principal moment I{k + 1} (diagonalized lab tensor)", float(moments[k]),
                    float(closed[k]), "kg m²", shape.closed_form_source(),
                    scale=float(closed[2])))
        if shape.about is not None:
            d = np.asarray(shape.about, dtype=float) - shape.centre_of_mass()
            shifted = core.parallel_axis(tensor, shape.mass, d)
            m2, a2 = core.principal_axes(shifted)
            results.analysis["parallel_axis"] = {
                "about": np.asarray(shape.about, dtype=float), "tensor": shifted,
                "principal_moments": m2, "principal_axes": a2}
            if shape.type == "points":
                direct = core.tensor_points(shape.masses, shape.lab_positions(),
                                            about=shape.about)
                idx = np.unravel_index(np.argmax(np.abs(direct)), direct.shape)
                results.checks.append(Check(
                    f"I_{'xyz'[idx[0]]}{'xyz'[idx[1]]} about the shifted point", float(shifted[idx]),
                    float(direct[idx]), "kg m²", "(8.49) against the direct sum Σ m (r² δ − r r)"))
        return results

    @classmethod
    def headline(cls, data):
        a = data.analysis
        m = a["principal_moments"]
        verdicts = [a["axis_stability"][f"axis_{k + 1}"]["verdict"] for k in range(3)]
        return [("body", a["shape"]),
                ("principal moments", ", ".join(f"{fmt(x)}" for x in m) + " kg m²"),
                ("spin stability", ", ".join(f"I{k + 1}: {v}" for k, v in enumerate(verdicts)))]

    @classmethod
    def section_tensor(cls, data):
        a = data.analysis
        T, m, ax = a["tensor"], a["principal_moments"], a["principal_axes"]
        tensor = Table(caption="Inertia tensor about the centre of mass, lab frame [kg m²]",
                       header=["", "x", "y", "z"],
                       rows=[[c] + [fmt(float(v)) for v in T[i]] for i, c in
                             enumerate("xyz")])
        principal = Table(caption="Principal moments (ascending) and axes (lab-frame unit "
                                  "vectors) from diagonalization",
                          header=["axis", "moment [kg m²]", "direction"],
                          rows=[[f"{k + 1}", fmt(float(m[k]), 12),
                                 "(" + ", ".join(f"{float(v):+.6f}" for v in ax[:, k]) + ")"]
                                for k in range(3)])
        ell = a["inertia_ellipsoid"]
        pts = a.get("points")
        fig = plots.inertia_ellipsoid(m, ax, ell["surface"], ell["semi_axes"],
                                      points=pts["positions"] if pts else None,
                                      masses=pts["masses"] if pts else None)
        notes = []
        if "closed_form" in a:
            cf = a["closed_form"]
            notes.append(f"Closed form: {cf['source']}; largest relative difference of the "
                         f"diagonalized moments: {fmt_err(cf['max_relative_difference'])}.")
        return SectionContent(
            figures=[cls.figure("inertia_ellipsoid", fig,
                                "Inertia ellipsoid Σ I_k x_k² = 1 (semi-axes 1/√I_k) with the "
                                "principal axes; points shown where the body is a point set.")],
            tables=[tensor, principal], notes=notes)

    @classmethod
    def section_parallel_axis(cls, data):
        p = data.analysis["parallel_axis"]
        T = p["tensor"]
        return SectionContent(tables=[
            Table(caption=f"Tensor about ({', '.join(fmt(float(x)) for x in p['about'])}) by "
                          "(8.49): I = I_cm + M(d² 1 − d dᵀ) [kg m²]",
                  header=["", "x", "y", "z"],
                  rows=[[c] + [fmt(float(v)) for v in T[i]] for i, c in enumerate("xyz")]),
            Table(caption="Principal moments and axes about that point",
                  header=["axis", "moment [kg m²]", "direction"],
                  rows=[[f"{k + 1}", fmt(float(p["principal_moments"][k]), 12),
                         "(" + ", ".join(f"{float(v):+.6f}" for v in p["principal_axes"][:, k])
                         + ")"] for k in range(3)])])

    @classmethod
    def section_stability(cls, data):
        return stability_table_section(data.analysis)


def stability_table_section(analysis: dict) -> SectionContent:
    """Table of the linear stability of free rotation about each principal axis, from an
    archive's ``analysis`` alone (shared by ``inertia`` and ``rigid_body``).

    Reads ``axis_stability/axis_<k>`` (verdict, growth_rate, oscillation_frequency and,
    from ``rigid_body``, growth_rate_jacobian), ``principal_moments`` and, when the rates
    are for a given spin rather than per unit spin, ``spin`` [rad/s].
    """
    stability = analysis["axis_stability"]
    moments = analysis["principal_moments"]
    spin = analysis.get("spin")
    rows = []
    unit = "1/s" if spin is not None else "× Ω"
    for k in range(3):
        s = stability[f"axis_{k + 1}"]
        rate = s["growth_rate"] if s["verdict"] == "unstable" else s["oscillation_frequency"]
        what = "growth rate" if s["verdict"] == "unstable" else "wobble frequency"
        row = [f"{k + 1}", fmt(float(moments[k])), s["verdict"], f"{what}: {fmt(float(rate))}"
               f" {unit}"]
        if "growth_rate_jacobian" in s:
            row.append(fmt(float(s["growth_rate_jacobian"])))
        rows.append(row)
    header = ["axis", "moment [kg m²]", "verdict", "rate (10.12)–(10.14)"]
    if rows and len(rows[0]) == 5:
        header.append("max Re λ of the Jacobian [1/s]")
    return SectionContent(tables=[Table(
        caption="Free rotation about each principal axis, linearized (10.12)–(10.14)"
                + ("" if spin is None else f" at spin Ω = {fmt(spin)} rad/s")
                + ": unstable about the intermediate axis with growth Ω√((I2−I1)(I3−I2)/(I1 I3))",
        header=header, rows=rows)])
