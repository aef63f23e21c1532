"""``rotation`` simulation: each exercise's constructions and the errors between them
(nothing is integrated)."""

from __future__ import annotations

import itertools
import math

import numpy as np

from ...lazy import lazy_module
from ...scene.results import Check, Results
from ...scene.simulation import Simulation
from .config import SECTION_TABLES, RotationConfig
from .euler_sketch import euler_sketch
from .notes_su2 import notes_su2
from .results import CONTRAST, NOT_CHECKS, ORDER_RANGE, ORDER_SLACK, SCHEMA, TOLERANCE
from .time_ordered import rebuild

rotations = lazy_module("reportgen.core.rotations")

#: the arc lengths δ of the difference quotients of the stereographic projection
DIFFERENCE_STEPS = (1e-2, 1e-3)


def textbook_matrix(n, Phi: float) -> np.ndarray:
    """The textbook's rotation matrix (textbook ex. 4.5): the active rotation of a vector by
    Φ about the unit vector n, R(n, Φ) = cos Φ 1 + (1 − cos Φ) n nᵀ + sin Φ [n]× (Rodrigues),
    with [n]× v = n × v written out here (not :func:`reportgen.core.rotations.skew`, which
    the exp check uses).  It is the transpose of Goldstein's passive A(n, Φ) of Goldstein
    (4.62): R = Aᵀ = A(n, −Φ).  About e_z by π/2 it takes e_x to e_y."""
    nx, ny, nz = (float(x) for x in n)
    cross = np.array([[0.0, -nz, ny], [nz, 0.0, -nx], [-ny, nx, 0.0]])
    c, s = math.cos(Phi), math.sin(Phi)
    return c * np.eye(3) + (1.0 - c) * np.outer([nx, ny, nz], [nx, ny, nz]) + s * cross


def _set_distance(a, b) -> float:
    """The largest distance between two sets of three complex numbers, paired the way
    that makes it least (all six pairings tried)."""
    a, b = np.asarray(a, dtype=complex), np.asarray(b, dtype=complex)
    return float(min(np.max(np.abs(a[list(p)] - b)) for p in itertools.permutations(range(3))))


def _sorted(values) -> np.ndarray:
    """Complex numbers in reading order: by real part (to 9 figures), then imaginary."""
    values = np.asarray(values, dtype=complex)
    return values[np.lexsort((values.imag, np.round(values.real, 9)))]


def _complex_pairs(z) -> np.ndarray:
    """Complex numbers as (real, imaginary) pairs, shape (..., 2)."""
    z = np.asarray(z, dtype=complex)
    return np.stack([z.real, z.imag], axis=-1)


def _cross_matrices(w) -> np.ndarray:
    """[w]× for vectors w (..., 3), shape (..., 3, 3)."""
    w = np.asarray(w, dtype=float)
    out = np.zeros(w.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2], out[..., 1, 2] = -w[..., 2], w[..., 1], -w[..., 0]
    return out - np.swapaxes(out, -1, -2)


def _central_differences(t, R, Omega, scale: float) -> dict:
    """Ṙ from the stored path R(t) (N ≥ 5 samples, step h) by central differences,
    D_h = (R(t + h) − R(t − h))/(2h) = Ṙ + h² R⃛/6 + O(h⁴), against the exact [ω]×:
    the deviation of D_h R⁻¹ from [ω]× and that of D_2h on the samples both reach
    (k = 2 … N − 3), their ratio's order log₂(e_2h/e_h) (2 for a central difference),
    the Richardson combination (4 D_h − D_2h)/3 (error ∝ h⁴) and the symmetric part of
    D_h R⁻¹ (k = 1 … N − 2), all relative to max |ω|."""
    h = float(t[1] - t[0])
    D1 = (R[2:] - R[:-2]) / (2.0 * h)
    W1 = D1 @ np.linalg.inv(R[1:-1])
    D1, D2 = D1[1:-1], (R[4:] - R[:-4]) / (4.0 * h)
    R_inv, Om = np.linalg.inv(R[2:-2]), Omega[2:-2]

    def deviation(D):
        return float(np.max(np.abs(D @ R_inv - Om))) / scale

    out = {"step": h,
           "antisymmetry": float(np.max(np.abs(W1 + np.swapaxes(W1, -1, -2)))) / scale,
           "omega": deviation(D1), "omega_double_step": deviation(D2),
           "omega_richardson": deviation((4.0 * D1 - D2) / 3.0)}
    if out["omega"] > 1e-10:  # well above rounding: the ratio is the truncation's
        out["order"] = math.log2(out["omega_double_step"] / out["omega"])
    return out


class RotationSimulation(Simulation):
    """Every rotation exercise computed two or more independent ways."""

    schema = SCHEMA
    config: RotationConfig
    computed_on_request = ("axis_angle", "euler_angles", "angular_velocity",
                           "matrix_identities", "su2_euler", "stereographic",
                           "matrix_proofs")

    def computes(self, name: str) -> bool:
        tables = SECTION_TABLES.get(name)
        if tables is not None:
            return (all(getattr(self.config, t) is not None for t in tables)
                    and self.wants_section(name))
        return super().computes(name)

    def simulate(self, progress=None) -> Results:
        results = Results()
        if self.computes("axis_angle"):
            self._axis_angle(results)
        if self.computes("euler_angles") or self.computes("angular_velocity"):
            self._euler(results)
        if self.computes("euler_angles"):  # the notes' Figure 2
            results.analysis["euler"]["sketch"] = euler_sketch(results.analysis["euler"])
        if self.computes("matrix_identities"):
            self._identities(results)
        if self.computes("su2_euler"):
            self._su2_form(results)
        if self.computes("stereographic"):
            self._stereographic(results)
        if self.computes("matrix_proofs"):
            from .proofs import prove

            results.analysis["proofs"] = prove(self.config.proofs.sizes, self.config.proofs.seed)
        bad = [f"{group}/{name}" for group, a in results.analysis.items()
               for name, error in a["errors"].items()
               if name not in NOT_CHECKS and not error <= TOLERANCE]
        identities = results.analysis.get("identities", {})
        differences = identities.get("central_differences", {})
        if ("order" in differences
                and differences["step"] * identities["omega_scale"] <= ORDER_RANGE
                and not abs(differences["order"] - 2.0) <= ORDER_SLACK):
            bad.append(f"identities/central_differences/order = {differences['order']:.4g}, "
                       f"not 2 ± {ORDER_SLACK:g}")
        bad += [c.quantity for c in results.checks if not c.rel_error <= TOLERANCE]
        bad += [f"proofs/proved/{k}: not expanded to 0" for k, ok
                in results.analysis.get("proofs", {}).get("proved", {}).items() if not ok]
        if bad:
            results.flag("failed", f"errors above {TOLERANCE:g}: " + "; ".join(bad))
        return results

    def _conventions(self) -> tuple[str, str]:
        """The Euler convention the config gives and the other one."""
        given = self.config.euler.convention
        return given, "zyz" if given == "zxz" else "zxz"

    def _path(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The sample path of [euler]: t (N,), the angles (φ, θ, ψ)(0) + (φ̇, θ̇, ψ̇) t
        (N, 3), the rates (3,) and R(t) (N, 3, 3) in the given convention."""
        c = self.config.euler
        t = np.linspace(0.0, c.duration, c.samples)
        rates = np.asarray(c.rates, dtype=float)
        path = np.asarray(c.angles, dtype=float) + t[:, None] * rates
        return t, path, rates, rotations.euler_matrices(path, c.convention)

    def _path_other(self, path: np.ndarray) -> np.ndarray:
        """The same rotations' angles in the other convention, (N, 3)."""
        convert = (rotations.zxz_to_zyz if self.config.euler.convention == "zxz"
                   else rotations.zyz_to_zxz)
        return np.stack(convert(path[:, 0], path[:, 1], path[:, 2]), axis=-1)

    def _axis_and_angle(self) -> tuple[np.ndarray, float]:
        """n (normalized) and Φ of [axis_angle]."""
        c = self.config.axis_angle
        return np.asarray(c.axis, dtype=float) / np.linalg.norm(c.axis), float(c.angle)

    def _axis_angle(self, results: Results) -> None:
        """The textbook's matrix R(n, Φ) (textbook ex. 4.5) by its closed form; Goldstein's
        passive A(n, Φ) of Goldstein (4.62) column by column, which is Rᵀ; exp(Φ[n]×) by
        diagonalization; R(q) from the quaternion."""
        c = self.config.axis_angle
        n = np.asarray(c.axis, dtype=float) / np.linalg.norm(c.axis)
        Phi, r = float(c.angle), np.asarray(c.vector, dtype=float)
        R = textbook_matrix(n, Phi)
        A = rotations.rotation_formula_matrix(n, Phi)
        by_expm = rotations.expm_by_diagonalization(Phi * rotations.skew(n))
        by_quat = rotations.quat_to_matrix(rotations.quat_from_axis_angle(n, Phi))
        n_back, Phi_back = rotations.axis_angle_from_matrix(R)
        axis_sign = 1.0 if Phi < math.pi or float(n_back @ n) >= 0 else -1.0
        turned = rotations.rotate_about(r, n, Phi)  # r cos Φ + n (n·r)(1 − cos Φ) + n × r sin Φ
        rotated = rotations.rotation_formula(r, n, Phi)  # Goldstein (4.62): A r
        s = np.linspace(0.0, 1.0, 61)
        size = float(np.linalg.norm(r))
        errors = {
            "textbook_vs_goldstein": float(np.max(np.abs(R - A.T))),
            "formula_vs_expm": float(np.max(np.abs(R - by_expm))),
            "formula_vs_quaternion": float(np.max(np.abs(R - by_quat))),
            "turned_vector_vs_matrix": float(np.max(np.abs(turned - R @ r))) / size,
            "vector_formula_vs_matrix": float(np.max(np.abs(rotated - A @ r))) / size,
            "orthogonality": float(np.max(np.abs(R @ R.T - np.eye(3)))),
            "recovered_angle": abs(Phi_back - Phi),
            # a turn by a small Φ fixes its axis only to ε/Φ: the error is weighed by that
            "recovered_axis": float(np.max(np.abs(axis_sign * n_back - n))) * min(1.0, Phi),
        }
        results.analysis["axis_angle"] = {
            "axis_given": np.asarray(c.axis, dtype=float), "axis": n, "angle": Phi,
            "vector": r, "turned_vector": turned, "rotated_vector": rotated,
            "matrix_textbook": R, "matrix_formula": A, "matrix_expm": by_expm,
            "matrix_quaternion": by_quat,
            "recovered_axis": n_back, "recovered_angle": Phi_back,
            "determinant": float(np.linalg.det(R)),
            # the figure: r turned by R(n, Φx) for x in 0..1 (active), Goldstein's r′ = A r
            # for the same angles (the components in axes turning with it: r turning by
            # −Φ), the full circle through r about n, its centre
            "arc_turned": np.array([rotations.rotate_about(r, n, Phi * x) for x in s]),
            "arc": np.array([rotations.rotation_formula(r, n, Phi * x) for x in s]),
            "circle": np.array([rotations.rotation_formula(r, n, 2 * math.pi * x)
                                for x in np.linspace(0.0, 1.0, 121)]),
            "centre": n * float(n @ r),
            "turned_axes": A,  # rows: the turned axes e'_i = R e_i in the old axes
            "errors": errors,
        }
        results.checks += [
            Check("max |R − exp(Φ[n]×)|, |R − R(q)|, |R − Aᵀ|",
                  max(errors["formula_vs_expm"], errors["formula_vs_quaternion"],
                      errors["textbook_vs_goldstein"]), 0.0, "",
                  "R = cos Φ 1 + (1 − cos Φ) n nᵀ + sin Φ [n]× (textbook ex. 4.5); exp by "
                  "eigenvectors; quaternion q = (cos Φ/2, n sin Φ/2); A from Goldstein (4.62) "
                  "applied to the axis unit vectors", scale=1.0),
            Check("Φ from tr R = 1 + 2 cos Φ and ½(R − Rᵀ) = sin Φ [n]×", Phi_back, Phi, "rad",
                  "the angle Φ given in the configuration"),
        ]

    def _euler(self, results: Results) -> None:
        """Both conventions on one path; ω by formula (both) and by the complex step."""
        given, other = self._conventions()
        t, path, rates, R = self._path()
        path_other = self._path_other(path)
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
            # R(t) from ω(t) alone by the time-ordered exponential, notes (8.36)–(8.37)
            "time_ordered": rebuild(path[0], rates, given, float(t[-1])),
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

    def _identities(self, results: Results) -> None:
        """Textbook ex. 4.1–4.4 on the scene's own matrices: the textbook's R(n, Φ) of ex. 4.5
        and the Euler path R(t).  Orthogonality and det 1; the similarity A′ = S A S⁻¹ by
        the Euler matrix S = R(0) of R(n, Φ), its generator Φ[n]× and its symmetric part,
        against the same matrices built on S n and their closed-form trace, determinant and
        eigenvalues; Ṙ R⁻¹ = [ω]× with Ṙ exact (complex step) and by central differences
        of the stored path (error ∝ h², its order measured)."""
        n, Phi = self._axis_and_angle()
        R = textbook_matrix(n, Phi)
        t, path, rates, Rt = self._path()
        S = Rt[0]
        S_inv = np.linalg.inv(S)
        Sn = S @ n
        c = math.cos(Phi)

        def symmetric(m):  # ½(R + Rᵀ) of R(m, Φ): cos Φ 1 + (1 − cos Φ) m mᵀ
            return c * np.eye(3) + (1.0 - c) * np.outer(m, m)

        turn = np.exp(1j * Phi)
        # A, A built on S n, and A's closed-form trace, determinant and eigenvalues
        matrices = {
            "rotation": (R, textbook_matrix(Sn, Phi), 1.0 + 2.0 * c, 1.0,
                         [1.0, turn, turn.conjugate()]),
            "generator": (Phi * rotations.skew(n), Phi * rotations.skew(Sn), 0.0, 0.0,
                          [0.0, 1j * Phi, -1j * Phi]),
            "symmetric": (0.5 * (R + R.T), symmetric(Sn), 1.0 + 2.0 * c, c * c, [1.0, c, c]),
        }
        every = np.concatenate([R[None], (S @ R)[None], Rt, Rt @ R])
        eye = np.eye(3)
        errors = {
            "orthogonality": float(np.max(np.abs(np.swapaxes(every, -1, -2) @ every - eye))),
            "determinant": float(np.max(np.abs(np.linalg.det(every) - 1.0))),
            "inverse_is_transpose": float(np.max(np.abs(S_inv - S.T))),
        }
        turned, invariants = {}, {k: [] for k in ("trace", "trace_turned", "determinant",
                                                  "determinant_turned", "eigenvalues",
                                                  "eigenvalues_turned", "eigenvalues_closed")}
        similarity = trace = det = eig = kept = 0.0
        for name, (A, closed, tr_closed, det_closed, eig_closed) in matrices.items():
            A2 = S @ A @ S_inv
            turned[name] = A2
            ev, ev2 = np.linalg.eigvals(A), np.linalg.eigvals(A2)
            similarity = max(similarity, float(np.max(np.abs(A2 - closed))))
            trace = max(trace, abs(np.trace(A2) - np.trace(A)), abs(np.trace(A) - tr_closed))
            det = max(det, abs(np.linalg.det(A2) - np.linalg.det(A)),
                      abs(np.linalg.det(A) - det_closed))
            eig = max(eig, _set_distance(ev2, ev), _set_distance(ev, eig_closed))
            if name == "generator":  # antisymmetry kept: S K S⁻¹ = [S Φn]×
                kept = max(kept, float(np.max(np.abs(A2 + A2.T))))
            elif name == "symmetric":
                kept = max(kept, float(np.max(np.abs(A2 - A2.T))))
            for key, value in (("trace", np.trace(A)), ("trace_turned", np.trace(A2)),
                               ("determinant", np.linalg.det(A)),
                               ("determinant_turned", np.linalg.det(A2)),
                               ("eigenvalues", _sorted(ev)), ("eigenvalues_turned", _sorted(ev2)),
                               ("eigenvalues_closed", _sorted(np.asarray(eig_closed, complex)))):
                invariants[key].append(value)
        errors.update({"similarity_closed_form": similarity, "trace_invariant": float(trace),
                       "determinant_invariant": float(det), "eigenvalue_invariant": float(eig),
                       "symmetry_kept": kept})

        # Ṙ R⁻¹ = [ω]× (space axes); Goldstein's A = Rᵀ: Ȧ A⁻¹ = Ṙᵀ R = −[ω′]× (body axes)
        omega = rotations.omega_from_euler_rates(*path.T, *rates, frame="space",
                                                 convention=self.config.euler.convention)
        omega_body = rotations.omega_from_euler_rates(*path.T, *rates, frame="body",
                                                      convention=self.config.euler.convention)
        largest = float(np.max(np.linalg.norm(omega, axis=-1)))
        scale = largest or 1.0  # a path at rest: the deviations are absolute [rad/s]
        Omega, Omega_body = _cross_matrices(omega), _cross_matrices(omega_body)
        _, Rdot = rotations.euler_matrices_and_rate(path, np.broadcast_to(rates, path.shape),
                                                    self.config.euler.convention)
        R_inv = np.linalg.inv(Rt)
        W = Rdot @ R_inv
        A_dot, A_inv = np.swapaxes(Rdot, -1, -2), np.linalg.inv(np.swapaxes(Rt, -1, -2))
        errors.update({
            "rdot_antisymmetric": float(np.max(np.abs(W + np.swapaxes(W, -1, -2)))) / scale,
            "rdot_is_omega": float(np.max(np.abs(W - Omega))) / scale,
            "adot_is_omega_body": float(np.max(np.abs(A_dot @ A_inv + Omega_body))) / scale,
        })
        group = {
            "second_rotation": S,
            "turned_axis": Sn, "turned": np.array([turned[k] for k in matrices]),
            "trace": np.array(invariants["trace"]).real,
            "trace_turned": np.array(invariants["trace_turned"]).real,
            "determinant": np.array(invariants["determinant"]).real,
            "determinant_turned": np.array(invariants["determinant_turned"]).real,
            **{k: _complex_pairs(np.array(invariants[k]))
               for k in ("eigenvalues", "eigenvalues_turned", "eigenvalues_closed")},
            "omega_scale": largest,
            "errors": errors,
        }
        if len(t) >= 5:
            group["central_differences"] = _central_differences(t, Rt, Omega, scale)
        results.analysis["identities"] = group

    def _su2_form(self, results: Results) -> None:
        """The SU(2) form of Euler's theorem and of the Euler angles (notes (9.17)–(9.18)):
        U(n, Φ) = cos(Φ/2) 1 − i sin(Φ/2) n·σ against exp(−iΦ n·σ/2) and R(U) against the
        textbook's R(n, Φ); U = U_z(φ) U_x(θ) U_z(ψ) (or U_y) along the Euler path against
        the Euler matrices, the multiplied-out Cayley–Klein parameters and the other
        convention; the single turn (m, α) read off U(0); φ + 2π gives −U, the same R."""
        n, Phi = self._axis_and_angle()
        U = (math.cos(0.5 * Phi) * np.eye(2)
             - 1j * math.sin(0.5 * Phi) * np.einsum("k,kab->ab", n, rotations.PAULI))
        by_exp = rotations.su2_exp(n, Phi)
        R_U = rotations.so3_from_su2(U)
        given, other = self._conventions()
        t, path, rates, Rt = self._path()
        U_path = rotations.su2_euler(path, given)
        U_other = rotations.su2_euler(self._path_other(path), other)
        a, b = rotations.su2_euler_cayley_klein(*path.T, given)
        closed = np.moveaxis(np.array([[a, b], [-np.conj(b), np.conj(a)]]), (0, 1), (-2, -1))
        R_path = rotations.so3_from_su2_many(U_path)
        m, alpha = rotations.su2_axis_angle(U_path[0])
        flipped = rotations.su2_euler(path + np.array([2.0 * math.pi, 0.0, 0.0]), given)
        eye = np.eye(2)
        every = np.concatenate([U[None], U_path])
        errors = {
            "closed_form_vs_exp": float(np.max(np.abs(U - by_exp))),
            "unitarity": float(max(
                np.max(np.abs(every @ np.conj(np.swapaxes(every, -1, -2)) - eye)),
                np.max(np.abs(np.linalg.det(every) - 1.0)))),
            "rotation_vs_textbook": float(np.max(np.abs(R_U - textbook_matrix(n, Phi)))),
            "euler_rotation_vs_matrix": float(np.max(np.abs(R_path - Rt))),
            "euler_product_vs_cayley_klein": float(np.max(np.abs(U_path - closed))),
            "euler_conventions": float(np.max(np.abs(U_path - U_other))),
            "euler_theorem": float(np.max(np.abs(textbook_matrix(m, alpha) - Rt[0]))),
            "two_pi_flip": float(np.max(np.abs(flipped + U_path))),
            "double_cover": float(np.max(np.abs(rotations.so3_from_su2_many(flipped)
                                                - R_path))),
        }
        notes, notes_errors = notes_su2(U, path[0])
        errors.update(notes_errors)
        results.analysis["su2_form"] = {
            "notes": notes,
            "convention": given, "axis": n, "angle": Phi,
            "a": _complex_pairs(U[0, 0]), "b": _complex_pairs(U[0, 1]), "rotation": R_U,
            "euler_angles": path[0], "euler_a": _complex_pairs(U_path[0, 0, 0]),
            "euler_b": _complex_pairs(U_path[0, 0, 1]), "euler_rotation": R_path[0],
            "euler_axis": m, "euler_angle": alpha,
            "errors": errors,
        }

    def _conformal_factor(self, x: np.ndarray) -> tuple[dict, dict]:
        """The stereographic projection's scale factor (textbook ex. 4.11), |dζ| = |dx|/(1 − z),
        at the points x (n, 3): dζ/ds along the two tangents e_φ, e_θ by the complex step
        (|dζ/ds| (1 − z) − 1, and Re(dζ₁ dζ̄₂) (1 − z)², zero as angles are kept), and the
        difference quotient |Δζ|/|Δx| between x(±δ) = x cos δ ± t sin δ on the great circles,
        which is exactly 1/√((1 − z₊)(1 − z₋)) (the chordal distance of the Riemann sphere) and
        tends to 1/(1 − z) as δ² (the contrasts).  Returns (errors, contrasts)."""
        factor = 1.0 / (1.0 - x[:, 2])
        # a point on the sphere to rounding has 1 − z to ε/(1 − z) near the pole: the
        # relative errors are weighed by min(1, 1 − z), as the axis error by min(1, Φ)
        weight = np.minimum(1.0, 1.0 - x[:, 2])
        tangents = rotations.tangent_frame(x)
        d = [rotations.stereographic_derivative(x, tan) for tan in tangents]
        exact, towards = 0.0, []
        for delta in DIFFERENCE_STEPS:
            worst = 0.0
            for tan in tangents:
                plus = x * math.cos(delta) + tan * math.sin(delta)
                minus = x * math.cos(delta) - tan * math.sin(delta)
                quotient = (np.abs(rotations.stereographic(plus) - rotations.stereographic(minus))
                            / np.linalg.norm(plus - minus, axis=-1))
                worst = max(worst, float(np.max(np.abs(quotient / factor - 1.0))))
                if delta == DIFFERENCE_STEPS[0]:  # the exact form, where Δζ is not too small
                    chord = 1.0 / np.sqrt((1.0 - plus[:, 2]) * (1.0 - minus[:, 2]))
                    exact = max(exact, float(np.max(np.abs(quotient / chord - 1.0) * weight)))
            towards.append(worst)
        errors = {
            "scale_factor": float(max(np.max(np.abs(np.abs(di) / factor - 1.0) * weight)
                                      for di in d)),
            "conformal_angle": float(np.max(np.abs((d[0] * np.conj(d[1])).real) / factor**2)),
            "difference_quotient_chordal": exact,
        }
        return errors, {"steps": np.array(DIFFERENCE_STEPS),
                        "quotient_vs_factor": np.array(towards)}

    def _second_element(self) -> tuple[np.ndarray, str]:
        """U₂ for the composition check: the SU(2) element of the ex. 4.5 turn when
        [axis_angle] is given, else that of the Euler angles at t = 0, else U itself."""
        if self.config.axis_angle is not None:
            n, Phi = self._axis_and_angle()
            return rotations.su2_from_axis_angle(n, Phi), "axis_angle"
        if self.config.euler is not None:
            c = self.config.euler
            return rotations.su2_euler(np.asarray(c.angles, dtype=float), c.convention), "euler"
        return self.config.su2.element(), "su2"

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
            "isometry": rotations.mobius_isometry_defect(U, zeta),
            # not checks: how far the other candidates are (R(U)ᵀ is not the Möbius map)
            "transpose_mismatch": float(np.max(np.linalg.norm(back - x @ R, axis=-1))),
            "transpose_mismatch_standard_orientation": float(np.max(np.linalg.norm(
                back_std - x @ R, axis=-1))),
        }
        conformal, contrasts = self._conformal_factor(x)
        U2, second = self._second_element()
        R2 = rotations.so3_from_su2(U2)
        U12 = U @ U2
        composed = rotations.inverse_stereographic(rotations.mobius(U, rotations.mobius(U2, zeta)))
        reversed_ = rotations.inverse_stereographic(rotations.mobius(U2, rotations.mobius(U, zeta)))
        errors.update(conformal)
        errors.update({
            "composition_mobius": float(np.max(chordal(rotations.mobius(U12, zeta), composed))),
            "composition_rotation": float(np.max(np.abs(rotations.so3_from_su2(U12) - R @ R2))),
        })
        contrasts.update({
            "reversed_mobius": float(np.max(chordal(rotations.mobius(U12, zeta), reversed_))),
            "reversed_rotation": float(np.max(np.abs(rotations.so3_from_su2(U12) - R2 @ R))),
        })
        circle = rotations.latitude_circle(-0.5)
        circle_zeta = rotations.stereographic(circle)

        def plane(z):
            return np.stack([np.real(z), np.imag(z)], axis=-1)

        results.analysis["stereographic"] = {
            # textbook ex. 4.11(d): a Möbius map of det 1 that is not unitary does not keep
            # distances (U followed by the boost diag(2, ½))
            "isometry_non_unitary": rotations.mobius_isometry_defect(
                U @ np.diag([2.0, 0.5]), zeta),
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
            "conformal_factor": 1.0 / (1.0 - x[:, 2]),
            "second_source": second, "second_a": _complex_pairs(U2[0, 0]),
            "second_b": _complex_pairs(U2[0, 1]), "second_rotation": R2,
            "errors": errors, "contrasts": contrasts,
            "transpose_differs": bool(errors["transpose_mismatch"] > CONTRAST),
            "transpose_differs_standard": bool(
                errors["transpose_mismatch_standard_orientation"] > CONTRAST),
            "reversed_differs": bool(contrasts["reversed_rotation"] > CONTRAST),
            "contrast_threshold": CONTRAST,
        }
        results.checks += [
            Check(f"max |π⁻¹(M(π(x))) − R(U) x| over {c.points} points, M the Möbius map of U",
                  errors["mobius_vs_rotation"], 0.0, "",
                  "R(U)ᵢⱼ = ½ tr(σᵢ U σⱼ U†) applied on the sphere; ζ = (x − iy)/(1 − z)",
                  scale=1.0),
            Check("max |R(−U) − R(U)| (double cover)", errors["double_cover_rotation"], 0.0, "",
                  "R is quadratic in U", scale=1.0),
        ]
