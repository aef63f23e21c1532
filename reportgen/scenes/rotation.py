r"""``rotation``: the kinematics of rotations, checked two ways each (exercises 4.5, 4.7, 4.8,
4.11).

* ``[axis_angle]`` (ex. 4.5): Goldstein's rotation formula (4.62) as a matrix, against the
  matrix exponential of the cross-product matrix and against quaternions; the axis and angle
  recovered from the matrix (trace and antisymmetric part).
* ``[euler]`` (ex. 4.7, 4.8): z-x-z (Goldstein 4.46) and z-y-z Euler matrices and the angular
  velocity from Euler-angle rates in space and body axes (Goldstein 4.87 and its z-y-z
  counterpart), cross-tested on the same physical rotation in both conventions and against
  ω read off the rotation matrix differentiated along a path of Euler angles.
* ``[su2]`` (ex. 4.11): the stereographic projection of the unit sphere, the Möbius map of
  an SU(2) element against the SO(3) rotation R(U) of the sphere, the double cover.

Conventions (module docstring of :mod:`reportgen.core.rotations`): R is active (body ->
space); Goldstein's passive matrices are A = Rᵀ.  A non-unit axis is normalized (a zero
axis is rejected); an SU(2) element given by Cayley–Klein parameters is normalized when
|a|² + |b|² is within 1e-6 of 1 and rejected otherwise.

Nothing is integrated: like ``inertia``, the kind has no ``[run]``, no ``/runs/main`` and
no error-against-run-time study; every check is against an independent construction and
its error is archived under ``/analysis/<exercise>/errors`` and in ``/checks``.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, Strict
from ..lazy import lazy_module
from ..results import Check, Results
from .base import Scene, SceneConfig, Section, SectionContent, Table, fmt, fmt_err

rotations = lazy_module("reportgen.core.rotations")
plots = lazy_module("reportgen.plots.rotation")

#: every check of this kind must agree to this (matrix entries, unit vectors, relative ω)
TOLERANCE = 1e-12
#: archived distances that are contrasts, not checks (R(U)ᵀ is not the Möbius map)
NOT_CHECKS = ("transpose_mismatch", "transpose_mismatch_standard_orientation")
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
    """``[axis_angle]``: a rotation by Φ about n (exercise 4.5)."""

    axis: Vector = Field([1.0, 1.0, 1.0], min_length=3, max_length=3,
                         description="rotation axis n, normalized here (must not be zero)")
    angle: Real = Field(2.0 * math.pi / 3.0, description="rotation angle Φ, 0 < Φ ≤ π [rad] "
                                                         "(−Φ about n is Φ about −n)")
    vector: Vector = Field([1.0, 0.0, 0.0], min_length=3, max_length=3,
                           description="the vector r the rotation formula turns (figure)")

    @model_validator(mode="after")
    def _rules(self):
        _unit("axis_angle.axis", self.axis)
        _unit("axis_angle.vector", self.vector)
        if not 0.0 < self.angle <= math.pi:
            raise ValueError(f"axis_angle.angle: must satisfy 0 < Φ ≤ π (got {self.angle}); "
                             "turn about −n for a negative angle")
        return self


class Euler(Strict):
    """``[euler]``: Euler angles and their rates in one convention (exercises 4.7, 4.8)."""

    convention: Literal["zxz", "zyz"] = Field(
        "zxz", description='"zxz" (Goldstein 4.46) or "zyz": the convention the angles are in')
    angles: Vector = Field([0.5, 0.8, 0.3], min_length=3, max_length=3,
                           description="[φ, θ, ψ] at t = 0 [rad]")
    rates: Vector = Field([0.7, 0.4, 1.5], min_length=3, max_length=3,
                          description="[φ̇, θ̇, ψ̇] along the sample path [rad/s]")
    duration: Positive = Field(4.0, description="length of the sample path (φ, θ, ψ) + "
                                                "(φ̇, θ̇, ψ̇) t [s]")
    samples: int = Field(81, ge=2, le=100_000, description="points on the sample path")


class SU2(Strict):
    """``[su2]``: an SU(2) element, by Cayley–Klein parameters or by axis and angle
    (exercise 4.11).  Neither given: a = 0.8, b = 0.36 + 0.48 i."""

    a: Vector | None = Field(None, min_length=2, max_length=2,
                             description="[Re a, Im a] of U = [[a, b], [−b̄, ā]]")
    b: Vector | None = Field(None, min_length=2, max_length=2,
                             description="[Re b, Im b]; |a|² + |b|² = 1 (normalized if "
                                         "within 1e-6)")
    axis: Vector | None = Field(None, min_length=3, max_length=3,
                                description="or: axis n of U = exp(−i α n·σ/2), normalized")
    angle: Real | None = Field(None, description="and its angle α [rad] (α and α + 2π give "
                                                 "U and −U)")
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
        return self

    def element(self) -> np.ndarray:
        """U, shape (2, 2), exactly unitary."""
        if self.axis is not None:
            return rotations.su2_from_axis_angle(self.axis, self.angle)
        a, b = (self.a, self.b) if self.a is not None else (DEFAULT_A, DEFAULT_B)
        a, b = complex(*a), complex(*b)
        norm = math.sqrt(abs(a) ** 2 + abs(b) ** 2)
        return rotations.su2_from_cayley_klein(a / norm, b / norm)


#: the config table each section draws from, and the /analysis group it reads
SECTION_TABLE = {"axis_angle": "axis_angle", "euler_angles": "euler",
                 "angular_velocity": "euler", "stereographic": "su2"}
SECTION_DATA = {"axis_angle": "axis_angle", "euler_angles": "euler",
                "angular_velocity": "euler", "stereographic": "stereographic"}


class RotationConfig(SceneConfig):
    axis_angle: AxisAngle | None = None
    euler: Euler | None = None
    su2: SU2 | None = None

    @model_validator(mode="after")
    def _rules(self):
        if self.run is not None:
            raise ValueError("run: the rotation kind integrates nothing; remove the [run] table")
        if self.axis_angle is None and self.euler is None and self.su2 is None:
            raise ValueError("axis_angle / euler / su2: give at least one of the tables "
                             "[axis_angle], [euler], [su2] (or a preset)")
        for name in self.report.sections or ():
            table = SECTION_TABLE.get(name)
            if table is not None and getattr(self, table) is None:
                raise ValueError(f"report.sections: section '{name}' needs a [{table}] table")
        return self


def _vec(v) -> str:
    return "(" + ", ".join(f"{float(x):+.6f}" for x in v) + ")"


def _matrix_rows(M, digits: int = 12) -> list[list[str]]:
    return [[f"{float(x):+.{digits}f}" for x in row] for row in np.asarray(M)]


def _complex(pair) -> str:
    re_, im = (float(x) for x in pair)
    return f"{re_:.12g} {'+' if im >= 0 else '−'} {abs(im):.12g} i"


class RotationScene(Scene):
    kind = "rotation"
    order = 95
    summary = ("rotations: axis–angle ↔ matrix, z-x-z and z-y-z Euler angles and ω from their "
               "rates, stereographic projection and SU(2) → SO(3) by Möbius maps")
    Config = RotationConfig
    presets = {
        "axis_angle": {"axis_angle": {}},
        "euler_zxz": {"euler": {"convention": "zxz"}},
        "euler_zyz": {"euler": {"convention": "zyz"}},
        "su2": {"su2": {}},
        "all": {"axis_angle": {}, "euler": {}, "su2": {}},
    }
    sections = (
        Section("axis_angle", "Axis and angle ↔ rotation matrix (exercise 4.5)"),
        Section("euler_angles", "Euler angles: z-x-z and z-y-z (exercises 4.7, 4.8)"),
        Section("angular_velocity", "Angular velocity from Euler-angle rates "
                                    "(exercises 4.7, 4.8)"),
        Section("stereographic", "Stereographic projection, Möbius maps and SU(2) → SO(3) "
                                 "(exercise 4.11)"),
    )
    computed_on_request = ("axis_angle", "euler_angles", "angular_velocity", "stereographic")

    def computes(self, name: str) -> bool:
        table = SECTION_TABLE.get(name)
        if table is not None:
            return getattr(self.config, table) is not None and self.wants_section(name)
        return super().computes(name)

    @classmethod
    def default_sections(cls, data):
        return [s.name for s in cls.sections if SECTION_DATA[s.name] in data.analysis]

    # ------------------------------------------------------------------ simulate
    def simulate(self, progress=None) -> Results:
        results = Results()
        if self.computes("axis_angle"):
            self._axis_angle(results)
        if self.computes("euler_angles") or self.computes("angular_velocity"):
            self._euler(results)
        if self.computes("stereographic"):
            self._stereographic(results)
        bad = [f"{group}/{name}" for group, a in results.analysis.items()
               for name, error in a["errors"].items()
               if name not in NOT_CHECKS and not error <= TOLERANCE]
        bad += [c.quantity for c in results.checks if not c.rel_error <= TOLERANCE]
        if bad:
            results.flag("failed", f"errors above {TOLERANCE:g}: " + "; ".join(bad))
        return results

    def _axis_angle(self, results: Results) -> None:
        """Goldstein (4.62) column by column; exp(−Φ[n]×) by diagonalization; R(q)ᵀ."""
        c = self.config.axis_angle
        n = np.asarray(c.axis, dtype=float) / np.linalg.norm(c.axis)
        Phi, r = float(c.angle), np.asarray(c.vector, dtype=float)
        A = rotations.rotation_formula_matrix(n, Phi)
        by_expm = rotations.expm_by_diagonalization(-Phi * rotations.skew(n))
        by_quat = rotations.quat_to_matrix(rotations.quat_from_axis_angle(n, Phi)).T
        n_back, Phi_back = rotations.axis_angle_from_matrix(A.T)
        axis_sign = 1.0 if Phi < math.pi or float(n_back @ n) >= 0 else -1.0
        rotated = rotations.rotation_formula(r, n, Phi)
        s = np.linspace(0.0, 1.0, 61)
        errors = {
            "formula_vs_expm": float(np.max(np.abs(A - by_expm))),
            "formula_vs_quaternion": float(np.max(np.abs(A - by_quat))),
            "vector_formula_vs_matrix": float(np.max(np.abs(rotated - A @ r))
                                              / np.linalg.norm(r)),
            "orthogonality": float(np.max(np.abs(A @ A.T - np.eye(3)))),
            "recovered_angle": abs(Phi_back - Phi),
            # a turn by a small Φ fixes its axis only to ε/Φ: the error is weighed by that
            "recovered_axis": float(np.max(np.abs(axis_sign * n_back - n))) * min(1.0, Phi),
        }
        results.analysis["axis_angle"] = {
            "axis_given": np.asarray(c.axis, dtype=float), "axis": n, "angle": Phi,
            "vector": r, "rotated_vector": rotated,
            "matrix_formula": A, "matrix_expm": by_expm, "matrix_quaternion": by_quat,
            "recovered_axis": n_back, "recovered_angle": Phi_back,
            "determinant": float(np.linalg.det(A)),
            # the figure: r turned by the formula through 0..Φ (the passive picture: r seen
            # from axes turning with it, i.e. r turning by −Φ), its full circle, the centre
            "arc": np.array([rotations.rotation_formula(r, n, Phi * x) for x in s]),
            "circle": np.array([rotations.rotation_formula(r, n, 2 * math.pi * x)
                                for x in np.linspace(0.0, 1.0, 121)]),
            "centre": n * float(n @ r),
            "turned_axes": A,  # rows: the turned axes e'_i in the old axes
            "errors": errors,
        }
        results.checks += [
            Check("max |A(4.62) − exp(−Φ[n]×)|, |A(4.62) − R(q)ᵀ|",
                  max(errors["formula_vs_expm"], errors["formula_vs_quaternion"]), 0.0, "",
                  "Goldstein (4.62) applied to e_x, e_y, e_z; exp by eigenvectors; quaternion "
                  "q = (cos Φ/2, n sin Φ/2)", scale=1.0),
            Check("Φ from tr R = 1 + 2 cos Φ and ½(R − Rᵀ) = sin Φ [n]×", Phi_back, Phi, "rad",
                  "the angle given in [axis_angle]"),
        ]

    def _euler(self, results: Results) -> None:
        """Both conventions on one path; ω by formula (both) and by the complex step."""
        c = self.config.euler
        given = c.convention
        other = "zyz" if given == "zxz" else "zxz"
        convert = rotations.zxz_to_zyz if given == "zxz" else rotations.zyz_to_zxz
        t = np.linspace(0.0, c.duration, c.samples)
        rates = np.asarray(c.rates, dtype=float)
        path = np.asarray(c.angles, dtype=float) + t[:, None] * rates
        path_other = np.stack(convert(path[:, 0], path[:, 1], path[:, 2]), axis=-1)
        R = rotations.euler_matrices(path, given)
        R_other = rotations.euler_matrices(path_other, other)
        elements = {conv: rotations.euler_matrix_elements(*angles, conv)
                    for conv, angles in ((given, path[0]), (other, path_other[0]))}
        omega = {}
        for frame in ("space", "body"):
            omega[frame] = rotations.omega_from_euler_rates(*path.T, *rates, frame=frame,
                                                            convention=given)
            omega[f"{frame}_other"] = rotations.omega_from_euler_rates(
                *path_other.T, *rates, frame=frame, convention=other)
        numeric = rotations.omega_by_complex_step(path, np.broadcast_to(rates, path.shape),
                                                  given)
        scale = float(np.max(np.linalg.norm(omega["space"], axis=-1))) or 1.0
        errors = {
            "matrix_product_vs_elements": max(
                float(np.max(np.abs(R[0].T - elements[given]))),
                float(np.max(np.abs(R_other[0].T - elements[other])))),
            "matrix_conventions": float(np.max(np.abs(R - R_other))),
            "omega_space_conventions": float(np.max(np.abs(omega["space"]
                                                           - omega["space_other"]))) / scale,
            "omega_body_conventions": float(np.max(np.abs(omega["body"]
                                                          - omega["body_other"]))) / scale,
            "omega_space_derivative": float(np.max(np.abs(omega["space"] - numeric["space"])))
            / scale,
            "omega_body_derivative": float(np.max(np.abs(omega["body"] - numeric["body"])))
            / scale,
            "body_is_space_rotated": float(np.max(np.abs(
                np.einsum("nij,nj->ni", R, omega["body"]) - omega["space"]))) / scale,
            "antisymmetry": float(np.max(numeric["asymmetry"])) / scale,
        }
        constructions = {conv: rotations.euler_construction(*angles, conv)
                         for conv, angles in ((given, path[0]), (other, path_other[0]))}
        results.analysis["euler"] = {
            "convention": given, "other_convention": other, "t": t, "rates": rates,
            "path": path, "path_other": path_other,
            "matrix": R[0], "matrix_other": R_other[0],
            "elements": elements[given], "elements_other": elements[other],
            "omega_space": omega["space"], "omega_body": omega["body"],
            "omega_space_other": omega["space_other"], "omega_body_other": omega["body_other"],
            "omega_space_derivative": numeric["space"], "omega_body_derivative": numeric["body"],
            "omega_scale": scale,
            "construction": constructions,
            "errors": errors,
        }
        names = {"zxz": "z-x-z", "zyz": "z-y-z"}
        g, o = names[given], names[other]
        shift = ("z-x-z angles (φ + π/2, θ, ψ − π/2)" if given == "zyz"
                 else "z-y-z angles (φ − π/2, θ, ψ + π/2)")
        results.checks += [
            Check(f"max |R_{given}(φ, θ, ψ) − R_{other}| over the path", errors["matrix_conventions"],
                  0.0, "", f"the same rotation in {o}: {shift}", scale=1.0),
            Check(f"max |ω ({g} rates) − ω ({o} rates)| / max|ω|, space and body axes",
                  max(errors["omega_space_conventions"], errors["omega_body_conventions"]), 0.0,
                  "", "Goldstein (4.87) and its z-y-z counterpart on the same path", scale=1.0),
            Check("max |ω (rates) − ω from Ṙ| / max|ω|, space and body axes",
                  max(errors["omega_space_derivative"], errors["omega_body_derivative"]), 0.0,
                  "", "vee(Ṙ Rᵀ), vee(Rᵀ Ṙ); Ṙ by the complex step (Squire & Trapp 1998)",
                  scale=1.0),
        ]

    def _stereographic(self, results: Results) -> None:
        """Möbius map of U on the projected points against R(U) on the sphere."""
        c = self.config.su2
        U = c.element()
        R = rotations.so3_from_su2(U)
        x = rotations.fibonacci_sphere(c.points)
        zeta = rotations.stereographic(x)
        mapped = rotations.mobius(U, zeta)
        images = x @ R.T

        def chordal(zeta_a, points):  # |π⁻¹(ζ) − x| on the sphere: well defined at ∞
            return np.linalg.norm(rotations.inverse_stereographic(zeta_a) - points, axis=-1)

        back = rotations.inverse_stereographic(mapped)
        zeta_std = rotations.stereographic(x, orientation=1)
        back_std = rotations.inverse_stereographic(rotations.mobius(U, zeta_std), orientation=1)
        R_bar = rotations.so3_from_su2(U.conj())
        q = rotations.su2_to_quat(U)
        half = math.atan2(float(np.linalg.norm(q[1:])), float(q[0]))
        errors = {
            "mobius_vs_rotation": float(np.max(np.linalg.norm(back - images, axis=-1))),
            "mobius_vs_rotation_standard_orientation": float(np.max(np.linalg.norm(
                back_std - x @ R_bar.T, axis=-1))),
            "rotation_from_mobius": float(np.max(np.abs(rotations.so3_from_mobius(U) - R))),
            "rotation_trace_vs_quaternion": float(np.max(np.abs(
                R - rotations.quat_to_matrix(q)))),
            "double_cover_rotation": float(np.max(np.abs(rotations.so3_from_su2(-U) - R))),
            "double_cover_mobius": float(np.max(chordal(rotations.mobius(-U, zeta), back))),
            "unitarity": float(max(np.max(np.abs(U @ U.conj().T - np.eye(2))),
                                   abs(np.linalg.det(U) - 1.0))),
            "round_trip": float(np.max(chordal(zeta, x))),
            # not checks: how far the other candidates are (R(U)ᵀ is not the Möbius map)
            "transpose_mismatch": float(np.max(np.linalg.norm(back - x @ R, axis=-1))),
            "transpose_mismatch_standard_orientation": float(np.max(np.linalg.norm(
                back_std - x @ R, axis=-1))),
        }
        circle = rotations.latitude_circle(-0.5)
        circle_zeta = rotations.stereographic(circle)

        def plane(z):
            return np.stack([np.real(z), np.imag(z)], axis=-1)

        results.analysis["stereographic"] = {
            "a": np.array([U[0, 0].real, U[0, 0].imag]),
            "b": np.array([U[0, 1].real, U[0, 1].imag]),
            "rotation": R, "rotation_minus_u": rotations.so3_from_su2(-U),
            "rotation_conjugate": R_bar, "rotation_from_mobius": rotations.so3_from_mobius(U),
            "su2_axis": q[1:] / (np.linalg.norm(q[1:]) or 1.0), "su2_angle": 2.0 * half,
            "points": x, "images": images, "plane": plane(zeta),
            "plane_mobius": plane(mapped), "plane_rotated": plane(rotations.stereographic(images)),
            "circle": circle, "circle_image": circle @ R.T, "circle_plane": plane(circle_zeta),
            "circle_plane_mobius": plane(rotations.mobius(U, circle_zeta)),
            "pole": rotations.NORTH_POLE, "pole_image": R @ rotations.NORTH_POLE,
            "pole_image_plane": plane(rotations.mobius(U, np.array([np.inf + 0j]))[0]),
            "errors": errors,
        }
        results.checks += [
            Check(f"max |π⁻¹(M_U(π(x))) − R(U) x| over {c.points} points",
                  errors["mobius_vs_rotation"], 0.0, "",
                  "R_ij = ½ tr(σ_i U σ_j U†) applied on the sphere; ζ = (x − iy)/(1 − z)",
                  scale=1.0),
            Check("max |R(−U) − R(U)| (double cover)", errors["double_cover_rotation"], 0.0, "",
                  "R is quadratic in U", scale=1.0),
        ]

    # ------------------------------------------------------- report (archive only)
    @classmethod
    def headline(cls, data):
        a = data.analysis
        facts = []
        if "axis_angle" in a:
            e = a["axis_angle"]["errors"]
            facts.append(("ex. 4.5 axis–angle ↔ matrix",
                          f"max error {fmt_err(max(e.values()))} (Φ = "
                          f"{fmt(a['axis_angle']['angle'], 8)} rad about "
                          f"{_vec(a['axis_angle']['axis'])})"))
        if "euler" in a:
            e = a["euler"]["errors"]
            facts.append(("ex. 4.7, 4.8 Euler matrices and ω",
                          f"max error {fmt_err(max(e.values()))} (z-x-z vs z-y-z, formulas vs "
                          "dR/dt)"))
        if "stereographic" in a:
            s = a["stereographic"]
            facts.append(("ex. 4.11 Möbius map vs R(U)",
                          f"max error {fmt_err(s['errors']['mobius_vs_rotation'])} over "
                          f"{len(s['points'])} points; R(U)ᵀ would be off by "
                          f"{fmt(s['errors']['transpose_mismatch'], 3)}"))
        facts.append(("computed in", f"{1e3 * float(data.attrs.get('wall_time_s', 0.0)):.0f} ms"
                                     " (nothing integrated)"))
        return facts

    @classmethod
    def section_axis_angle(cls, data):
        a = data.analysis["axis_angle"]
        e = a["errors"]
        fig = plots.axis_angle(a["axis"], a["angle"], a["vector"], a["rotated_vector"], a["arc"],
                               a["circle"], a["centre"], a["turned_axes"])
        facts = [("axis n (normalized)", _vec(a["axis"])),
                 ("angle Φ", f"{fmt(a['angle'], 12)} rad = {math.degrees(a['angle']):.6g}°"),
                 ("r", _vec(a["vector"])),
                 ("r′ by (4.62)", _vec(a["rotated_vector"])),
                 ("recovered from the matrix", f"Φ = {fmt(a['recovered_angle'], 15)} rad, "
                                               f"n = {_vec(a['recovered_axis'])}"),
                 ("det A", fmt(a["determinant"], 15))]
        matrix = Table(caption="A(n, Φ) from Goldstein (4.62), column j = the formula applied to "
                               "e_j (passive: components in the turned axes); the active "
                               "rotation reportgen uses elsewhere is R = Aᵀ",
                       header=["", "x", "y", "z"],
                       rows=[[c] + row for c, row in zip("xyz", _matrix_rows(a["matrix_formula"]),
                                                          strict=True)])
        checks = Table(caption=f"Each check's error (bound {TOLERANCE:g}). A small turn fixes "
                               "its axis only to ε/Φ, so the axis error is weighed by min(1, Φ); "
                               "near Φ = π the axis comes from the symmetric part.",
                       header=["check", "max error"],
                       rows=[["A(4.62) vs exp(−Φ[n]×) by eigenvectors",
                              fmt_err(e["formula_vs_expm"])],
                             ["A(4.62) vs R(q)ᵀ, quaternion",
                              fmt_err(e["formula_vs_quaternion"])],
                             ["r′ by (4.62) vs A r, / |r|",
                              fmt_err(e["vector_formula_vs_matrix"])],
                             ["A Aᵀ − 1", fmt_err(e["orthogonality"])],
                             ["Φ from tr R and ½(R − Rᵀ)",
                              fmt_err(e["recovered_angle"])],
                             ["n recovered, × min(1, Φ)",
                              fmt_err(e["recovered_axis"])]])
        return SectionContent(
            figures=[cls.figure("rotation_formula", fig,
                                "The rotation formula (4.62) applied to r for angles 0 … Φ: r′ "
                                "are the components of r in axes turned by +Φ about n (thin "
                                "dashed: the turned axes), so drawn in the old axes r′ is r "
                                "turned by −Φ.")],
            facts=facts, tables=[matrix, checks])

    @classmethod
    def section_euler_angles(cls, data):
        a = data.analysis["euler"]
        e = a["errors"]
        given, other = a["convention"], a["other_convention"]
        fig = plots.euler_constructions(a["construction"], (given, other))
        names = {"zxz": "z-x-z", "zyz": "z-y-z"}

        def angles(v):
            return ", ".join(f"{float(x):.10g}" for x in v)

        facts = [(f"{names[given]} angles (given) φ, θ, ψ", angles(a["path"][0]) + " rad"),
                 (f"{names[other]} angles of the same rotation", angles(a["path_other"][0])
                  + " rad")]
        matrix = Table(caption=f"R = Aᵀ at t = 0 ({names[given]} product of elementary "
                               "rotations; Goldstein's A of (4.46) is its transpose)",
                       header=["", "x′", "y′", "z′"],
                       rows=[[c] + row for c, row in zip("xyz", _matrix_rows(a["matrix"]),
                                                          strict=True)])
        checks = Table(caption=f"Each check's error (bound {TOLERANCE:g})",
                       header=["check", "max error"],
                       rows=[["R by elementary rotations vs (4.46) elements",
                              fmt_err(e["matrix_product_vs_elements"])],
                             [f"R_{given} vs R_{other} at the converted angles, whole path",
                              fmt_err(e["matrix_conventions"])]])
        return SectionContent(
            figures=[cls.figure("line_of_nodes", fig,
                                "One rotation, two constructions: the body axes x′, y′, z′ "
                                "are the same; the line of nodes (the intermediate x axis for "
                                "z-x-z, y axis for z-y-z) and φ, ψ differ by π/2.")],
            facts=facts, tables=[matrix, checks])

    @classmethod
    def section_angular_velocity(cls, data):
        a = data.analysis["euler"]
        e = a["errors"]
        names = {"zxz": "z-x-z", "zyz": "z-y-z"}
        given, other = names[a["convention"]], names[a["other_convention"]]
        t = a["t"]
        picks = np.unique(np.linspace(0, len(t) - 1, 5).round().astype(int))
        path = Table(caption=f"ω along the path by the {given} rate formulas (the {other} "
                             "formulas and Ṙ give the same to the errors below) [rad/s]",
                     header=["t [s]", "ω space axes", "ω body axes"],
                     rows=[[fmt(float(t[i]), 6), _vec(a["omega_space"][i]),
                            _vec(a["omega_body"][i])] for i in picks])
        rows = [[f"ω space: {given} vs {other} formulas", fmt_err(e["omega_space_conventions"])],
                [f"ω body: {given} vs {other} formulas", fmt_err(e["omega_body_conventions"])],
                ["ω space: formula vs vee(Ṙ Rᵀ)", fmt_err(e["omega_space_derivative"])],
                ["ω body: formula vs vee(Rᵀ Ṙ)", fmt_err(e["omega_body_derivative"])],
                ["ω space vs R ω body", fmt_err(e["body_is_space_rotated"])],
                ["Ṙ Rᵀ + (Ṙ Rᵀ)ᵀ, zero as R Rᵀ = 1", fmt_err(e["antisymmetry"])]]
        facts = [("rates φ̇, θ̇, ψ̇", ", ".join(f"{float(x):.10g}" for x in a["rates"])
                  + " rad/s"),
                 ("sample path", f"(φ, θ, ψ)(t) = (φ, θ, ψ)(0) + (φ̇, θ̇, ψ̇) t, {len(t)} "
                                 f"points, t = 0 … {fmt(float(t[-1]))} s")]
        return SectionContent(
            facts=facts,
            tables=[path, Table(caption=f"Each check's error relative to max |ω| = "
                                        f"{fmt(a['omega_scale'])} rad/s over the path (bound "
                                        f"{TOLERANCE:g})",
                                header=["check", "max error"], rows=rows)])

    @classmethod
    def section_stereographic(cls, data):
        s = data.analysis["stereographic"]
        e = s["errors"]
        fig = plots.stereographic(s)
        facts = [("U = [[a, b], [−b̄, ā]]", f"a = {_complex(s['a'])}, b = {_complex(s['b'])}"),
                 ("U = exp(−i α n·σ/2)", f"α = {fmt(s['su2_angle'], 12)} rad about "
                                          f"{_vec(s['su2_axis'])}; −U: α + 2π"),
                 ("sample points", f"{len(s['points'])} (golden-angle spiral, no pole)")]
        matrix = Table(caption="R(U) = ½ tr(σ_i U σ_j U†), the same for −U",
                       header=["", "x", "y", "z"],
                       rows=[[c] + row for c, row in zip("xyz", _matrix_rows(s["rotation"]),
                                                          strict=True)])
        checks = Table(
            caption=f"Each check's error (bound {TOLERANCE:g}; distances on the unit sphere, "
                    "which stay finite where ζ → ∞)",
            header=["check", "max error"],
            rows=[["Möbius map of U vs R(U), ζ = (x − iy)/(1 − z)",
                   fmt_err(e["mobius_vs_rotation"])],
                  ["Möbius map of U vs R(Ū), ζ = (x + iy)/(1 − z)",
                   fmt_err(e["mobius_vs_rotation_standard_orientation"])],
                  ["R from the Möbius map (e_x, e_y, e_z) vs ½ tr",
                   fmt_err(e["rotation_from_mobius"])],
                  ["½ tr(σ_i U σ_j U†) vs quaternion formula",
                   fmt_err(e["rotation_trace_vs_quaternion"])],
                  ["R(−U) vs R(U)", fmt_err(e["double_cover_rotation"])],
                  ["Möbius map of −U vs that of U", fmt_err(e["double_cover_mobius"])],
                  ["U U† − 1, det U − 1", fmt_err(e["unitarity"])],
                  ["π⁻¹(π(x)) − x", fmt_err(e["round_trip"])]])
        contrast = Table(
            caption="Not checks: the transpose is not the Möbius map (for a half turn, or an "
                    "axis in the x–z plane with the usual orientation, it would be)",
            header=["candidate", "max distance"],
            rows=[["R(U)ᵀ, ζ = (x − iy)/(1 − z)", fmt(e["transpose_mismatch"], 4)],
                  ["R(U)ᵀ, ζ = (x + iy)/(1 − z)",
                   fmt(e["transpose_mismatch_standard_orientation"], 4)]])
        return SectionContent(
            figures=[cls.figure("mobius", fig,
                                "Left: sample points x on the sphere and their images R(U) x; "
                                "a circle of latitude and its image. Right: the projections "
                                "ζ = (x − iy)/(1 − z) (plane seen from below) and their Möbius "
                                "images (aζ + b)/(−b̄ζ + ā), which fall on the projections of "
                                "R(U) x (dots in rings); circles go to circles.")],
            facts=facts, tables=[matrix, checks, contrast])
