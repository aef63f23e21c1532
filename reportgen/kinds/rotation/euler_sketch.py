"""The notes' Figure 2, the Euler angles, as stored points for the figure to draw.

The notes name their Euler angles by (9.17), R = R₃(ψ) R₁(θ) R₃(φ): the z-x-z
convention (Goldstein (4.46)).  The sketch shows the scene's rotation at t = 0 in that
convention whatever convention the scene's angles are given in (both are in ``/analysis/
euler``); its axes, line of nodes and angle arcs are ``construction/<convention>`` of that
group, and this adds the angles and the two planes the line of nodes is the meeting of.
"""

from __future__ import annotations

import numpy as np

#: the convention of notes (9.17), in which the notes' Figure 2 is drawn
NOTES_CONVENTION = "zxz"
#: points of each plane's circle
CIRCLE_POINTS = 145


def euler_sketch(euler: dict) -> dict:
    """The ``/analysis/euler/sketch`` group from the ``euler`` group: ``convention``
    (:data:`NOTES_CONVENTION`), ``angles`` (φ, θ, ψ) [rad] of the rotation at t = 0 in it,
    ``plane`` the unit circle in the fixed xy plane and ``body_plane`` the unit circle
    in the body x′y′ plane (both (CIRCLE_POINTS, 3)); the two circles meet on the line of
    nodes."""
    convention = NOTES_CONVENTION
    angles = euler["path"][0] if euler["convention"] == convention else euler["path_other"][0]
    body = np.asarray(euler["construction"][convention]["body_axes"])
    t = np.linspace(0.0, 2.0 * np.pi, CIRCLE_POINTS)[:, None]
    return {"convention": convention, "angles": np.asarray(angles, dtype=float),
            "plane": np.cos(t) * np.array([1.0, 0.0, 0.0]) + np.sin(t) * np.array([0.0, 1.0, 0.0]),
            "body_plane": np.cos(t) * body[:, 0] + np.sin(t) * body[:, 1]}
