"""``central_force``: the cases a report's words are chosen by, with their thresholds.

Computed at simulate time and stored in ``/analysis`` (``orbit_shape``, ``apsides``,
``heavier_body``, with the thresholds used), so that every sentence stating a shape, a
direction or a comparison follows a stored fact of this scene.  Plain floats in, words
out: the default title (from the config) uses the same rules.
"""

from __future__ import annotations

import math

#: (r_max − r_min)/(r_max + r_min), or Kepler's e, below this: a circle
CIRCULAR_E = 1e-6
#: |e − 1| below this for an unbound Kepler orbit: a parabola
PARABOLIC_E = 1e-9
#: |2ψ − 2π| per radial period below this [rad]: the apsides stay put (the orbit closes)
APSIDAL_SHIFT_NONE = 1e-8
#: |m1 − m2|/(m1 + m2) below this: equal masses
EQUAL_MASSES = 1e-12

#: the shapes of ``orbit_shape``
SHAPES = ("circle", "ellipse", "closed", "rosette", "parabola", "hyperbola", "escape")


def conic(eccentricity: float, bound: bool) -> str:
    """The Kepler orbit's conic: circle, ellipse, parabola or hyperbola."""
    if bound:
        return "circle" if eccentricity < CIRCULAR_E else "ellipse"
    return "parabola" if abs(eccentricity - 1.0) < PARABOLIC_E else "hyperbola"


def apsides(shift: float) -> str:
    """How the pericentre moves per radial period, from the apsidal shift 2ψ − 2π [rad]:
    "advance" (with the motion), "regress" (against it) or "fixed"."""
    if abs(shift) < APSIDAL_SHIFT_NONE:
        return "fixed"
    return "advance" if shift > 0 else "regress"


def orbit_shape(*, kepler: bool, bound: bool, eccentricity: float,
                shift: float = math.nan) -> str:
    """One of :data:`SHAPES`: a conic for V = −k/r; otherwise a circle, a closed orbit or a
    rosette when bound (by the apsidal shift), an escape when not."""
    if kepler:
        return conic(eccentricity, bound)
    if not bound:
        return "escape"
    if eccentricity < CIRCULAR_E:
        return "circle"
    return "closed" if apsides(shift) == "fixed" else "rosette"


def heavier_body(m1: float, m2: float) -> str:
    """ "body 1", "body 2", or "neither" (equal masses, to :data:`EQUAL_MASSES`)."""
    if abs(m1 - m2) <= EQUAL_MASSES * (m1 + m2):
        return "neither"
    return "body 1" if m1 > m2 else "body 2"
