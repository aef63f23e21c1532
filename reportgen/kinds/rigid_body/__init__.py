r"""``rigid_body``: the torque-free rigid body (lecture notes §8–10; textbook ch. 4).

Euler's equations (10.5) with the attitude quaternion, checked against the exact
solution in Jacobi elliptic functions (both branches L² ≷ 2E·I2) or, for a symmetric
body, the precession (10.9)–(10.10); polhodes on the angular-momentum sphere and on
the inertia ellipsoid (10.17) with the separatrices, Poinsot's construction (the
ellipsoid rolling on the invariable plane, the herpolhode), the stability of rotation
about each principal axis (10.12)–(10.14) with the Dzhanibekov flip, and a geometric
splitting integrator next to the general-purpose ones.

The body frame is the principal frame: with ``[params]`` the moments I1, I2, I3 are
given in any order; with a solid ``[shape]`` the shape's own x, y, z axes; with
``type = "points"`` the principal axes by diagonalization (ascending moments).
``initial.omega`` (and an ``[impulse]``) are components in that frame.

Tolerance: the shared default rtol = 1e-12 (atol 1e-14) keeps ω(t) within ~2e-10 of
the elliptic solution even for the Dzhanibekov preset, whose polhode passes close to the
separatrix; that is why this kind does not loosen it.
"""

from __future__ import annotations

from .config import PRESETS, RigidBodyConfig
from .report import RigidBodyReport
from .simulation import RigidBodySimulation


class RigidBodyScene(RigidBodySimulation, RigidBodyReport):
    kind = "rigid_body"
    order = 60
    summary = "torque-free rigid body: Euler's equations, attitude, polhodes, axis stability"
    Config = RigidBodyConfig
    presets = PRESETS
