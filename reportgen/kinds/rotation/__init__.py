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
