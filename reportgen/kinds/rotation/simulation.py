"""``rotation`` simulation: each exercise's constructions and the errors between them
(nothing is integrated)."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.results import Check, Results
from ...scene.simulation import Simulation
from .config import SECTION_TABLE, RotationConfig
from .results import NOT_CHECKS, SCHEMA, TOLERANCE

rotations = lazy_module("reportgen.core.rotations")


class RotationSimulation(Simulation):
    """Every rotation exercise computed two or more independent ways."""

    schema = SCHEMA
    config: RotationConfig
    computed_on_request = ("axis_angle", "euler_angles", "angular_velocity", "stereographic")

    def computes(self, name: str) -> bool:
        table = SECTION_TABLE.get(name)
        if table is not None:
            return getattr(self.config, table) is not None and self.wants_section(name)
        return super().computes(name)

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
                  "Goldstein (4.62) applied to the axis unit vectors; exp by eigenvectors; quaternion "
                  "q = (cos Φ/2, n sin Φ/2)", scale=1.0),
            Check("Φ from tr R = 1 + 2 cos Φ and ½(R − Rᵀ) = sin Φ [n]×", Phi_back, Phi, "rad",
                  "the angle Φ given in the configuration"),
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
            Check(f"max |R by {g} angles − R by {o} angles| over the path", errors["matrix_conventions"],
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
            Check(f"max |π⁻¹(M(π(x))) − R(U) x| over {c.points} points, M the Möbius map of U",
                  errors["mobius_vs_rotation"], 0.0, "",
                  "R(U)ᵢⱼ = ½ tr(σᵢ U σⱼ U†) applied on the sphere; ζ = (x − iy)/(1 − z)",
                  scale=1.0),
            Check("max |R(−U) − R(U)| (double cover)", errors["double_cover_rotation"], 0.0, "",
                  "R is quadratic in U", scale=1.0),
        ]
