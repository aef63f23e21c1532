r"""``rotation``: the kinematics of rotations, checked two ways each (textbook exercises 4.5,
4.7, 4.8, 4.11).

* ``[axis_angle]`` (textbook ex. 4.5): the textbook's rotation matrix R(n, Φ) = cos Φ 1 +
  (1 − cos Φ) n nᵀ + sin Φ [n]× (active), against the transpose of Goldstein's passive
  A(n, Φ) built from Goldstein (4.62), against the matrix exponential exp(Φ[n]×) and against
  quaternions; the axis and angle recovered from R (trace and antisymmetric part).
* ``[euler]`` (textbook ex. 4.7, 4.8): z-x-z (Goldstein (4.46)) and z-y-z Euler matrices and
  the angular velocity from Euler-angle rates in space and body axes (Goldstein (4.87) and
  its z-y-z counterpart), cross-tested on the same physical rotation in both conventions
  and against ω read off the rotation matrix differentiated along a path of Euler angles.
* ``[su2]`` (textbook ex. 4.11): the stereographic projection of the unit sphere, the
  Möbius map of an SU(2) element against the SO(3) rotation R(U) of the sphere, the double
  cover; the projection's scale factor 1/(1 − z) (complex step and difference quotients);
  composition = matrix product, M(U U₂) = M(U) ∘ M(U₂) and R(U U₂) = R(U) R(U₂).
* ``[axis_angle]`` and ``[euler]`` together: the matrix identities of textbook ex. 4.1–4.4
  (orthogonality, det 1, the invariants of a similarity S A S⁻¹, Ṙ R⁻¹ = [ω]× exactly and
  by central differences of the stored path, their order measured) and the SU(2) form of
  Euler's theorem and of the Euler angles (notes (9.17)–(9.18)): U(n, Φ) and
  U_z(φ) U_x(θ) U_z(ψ) against the matrices, the sign of U kept.

Conventions (module docstring of :mod:`reportgen.core.rotations`): R is active (body ->
space); Goldstein's passive matrices are A = Rᵀ.  A non-unit axis is normalized (a zero
axis is rejected); an SU(2) element given by Cayley–Klein parameters is normalized when
|a|² + |b|² is within 1e-6 of 1 and rejected otherwise.

Nothing is integrated: like ``inertia``, the kind has no ``[run]``, no ``/runs/main`` and
no error-against-run-time study; every check is against an independent construction and
its error is archived under ``/analysis/<exercise>/errors`` and in ``/checks``.
"""

from __future__ import annotations

from .config import PRESETS, RotationConfig
from .report import RotationReport
from .simulation import RotationSimulation


class RotationScene(RotationSimulation, RotationReport):
    kind = "rotation"
    order = 95
    summary = ("rotations: axis–angle ↔ matrix, z-x-z and z-y-z Euler angles and ω from their "
               "rates, stereographic projection and SU(2) → SO(3) by Möbius maps")
    Config = RotationConfig
    presets = PRESETS
    name_in_words = "Rotations"

    @classmethod
    def default_title(cls, config):
        """``Rotations: axis and angle, Euler angles (z-x-z) and SU(2) → SO(3) by Möbius maps``: the
        parts the config asks for."""
        parts = []
        if config.axis_angle is not None:
            parts.append("axis and angle")
        if config.euler is not None:
            c = config.euler.convention
            parts.append(f"Euler angles ({c[0]}-{c[1]}-{c[2]})")
        if config.su2 is not None:
            parts.append("SU(2) → SO(3) by Möbius maps")
        if not parts:
            return "Rotations"
        return "Rotations: " + (", ".join(parts[:-1]) + " and " + parts[-1]
                                if len(parts) > 1 else parts[0])
