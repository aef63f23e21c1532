r"""``rigid_body``: the torque-free rigid body (lecture notes §8–10; textbook ch. 4).

Euler's equations notes (10.5) with the attitude quaternion, checked against the exact
solution in Jacobi elliptic functions (both branches L² ≷ 2E·I2) or, for a symmetric
body, the precession notes (10.9)–(10.10); polhodes on the angular-momentum sphere and on
the inertia ellipsoid notes (10.15)–(10.16) with the separatrices, Poinsot's construction (the
ellipsoid rolling on the invariable plane, the herpolhode), the stability of rotation
about each principal axis notes (10.12)–(10.14) with the Dzhanibekov flip, and a geometric
splitting integrator next to the general-purpose ones.

The body frame is the principal frame: with ``[params]`` the moments I1, I2, I3 are
given in any order; with a solid ``[shape]`` the shape's own x, y, z axes; with
``type = "points"`` the principal axes by diagonalization (ascending moments).
``initial.omega`` (and an ``[impulse]``) are components in that frame.  An impulse
(textbook ex. 4.6(c)) also sets the centre of mass drifting at P/M: the report draws
the struck point's path in space against that straight line (:mod:`.impulse`).

Tolerance: the shared default rtol = 1e-12 (atol 1e-14) keeps ω(t) within ~2e-10 of
the elliptic solution even for the Dzhanibekov preset, whose polhode passes close to the
separatrix; that is why this kind does not loosen it.
"""

from __future__ import annotations

from ...scene.content import fmt as _fmt
from ..inertia import shape_in_words
from ..inertia.config import body_symmetry
from .config import PRESETS, RigidBodyConfig
from .report import RigidBodyReport
from .simulation import FLIP_ANGLE, RigidBodySimulation, nearest_axis


def fmt(x, digits: int = 10) -> str:
    """A number of a title: :func:`~reportgen.scene.content.fmt` with a true minus sign."""
    return _fmt(x, digits).replace("-", "−")


class RigidBodyScene(RigidBodySimulation, RigidBodyReport):
    kind = "rigid_body"
    order = 60
    summary = "torque-free rigid body: Euler's equations, attitude, polhodes, axis stability"
    Config = RigidBodyConfig
    presets = PRESETS
    name_in_words = "Torque-free rigid body"

    @classmethod
    def default_title(cls, config):
        """``Torque-free asymmetric body (I = 1, 2, 3 kg m²) spun near its intermediate
        axis``: the case by the moments (spherical, symmetric, asymmetric, equal within
        ``EQUAL_MOMENTS_RTOL``), "spun near" an axis only when ω0 is within ``FLIP_ANGLE``
        of it (else ω0 itself)."""
        omega = [float(w) for w in config.initial.omega]
        spin = "(" + ", ".join(fmt(w, 4) for w in omega) + ") rad/s"
        if config.params is None:
            body = shape_in_words(config.shape)
            body = body[2:] if body.startswith("a ") else f"body of {body}"
            title = f"Torque-free {body}, ω0 = {spin}"
            if config.impulse is not None:
                title += (", struck at the apex" if config.impulse.at == "apex"
                          else ", struck by an impulse")
            return title
        moments = [float(config.params.I1), float(config.params.I2), float(config.params.I3)]
        case, _axis = body_symmetry(moments)
        body = {"spherical": "spherical top", "symmetric": "symmetric body",
                "asymmetric": "asymmetric body"}[case]
        title = f"Torque-free {body} (I = {', '.join(fmt(m, 4) for m in moments)} kg m²)"
        near, angle = nearest_axis(omega)
        if case == "asymmetric" and config.impulse is None and angle < FLIP_ANGLE:
            # near an axis: within FLIP_ANGLE of it (the stored spin_axis fact)
            rank = sorted(moments).index(moments[near])
            which = ("smallest-moment", "intermediate", "largest-moment")[rank]
            title += f" spun near its {which} axis"
        else:
            title += f", ω0 = {spin}"
        if config.impulse is not None:
            title += ", struck by an impulse"
        return title
