r"""``inertia``: the inertia tensor of a shape or a point set, its principal moments and axes,
the parallel-axis shift, notes (8.49), and which free-spin axes are stable, notes (10.12)–(10.14).

No equation of motion is integrated; each solid's closed-form tensor is checked against
a quadrature of its volume (and the cone's centre of mass, 3h/4 below the apex, textbook
ex. 4.6).  Solid shapes are uniform and given in their own frame
(centre of mass at the origin, symmetry axis / half-diagonals along x, y, z); an
optional ``euler_angles`` = [φ, θ, ψ] (z-x-z) turns the shape in the lab frame so that
the tensor is full and the principal axes come out of the diagonalization.
"""

from __future__ import annotations

from ...scene.content import fmt as _fmt
from .config import PRESETS, InertiaConfig
from .report import InertiaReport
from .simulation import InertiaSimulation


def fmt(x, digits: int = 10) -> str:
    """A number of a title: :func:`~reportgen.scene.content.fmt` with a true minus sign."""
    return _fmt(x, digits).replace("-", "−")


def shape_in_words(shape) -> str:
    """A ``[shape]`` table in words with its numbers: ``a solid cone (M = 1 kg, R = 0.5 m,
    h = 2 m)`` (shared with ``rigid_body``)."""
    def n(key: str) -> str:
        return fmt(float(getattr(shape, key)), 4)

    if shape.type == "points":
        count = len(shape.masses)
        return f"{count} point mass{'es' if count != 1 else ''}"
    if shape.type in ("cone", "cylinder"):
        size = f"R = {n('radius')} m, h = {n('height')} m"
    elif shape.type == "octahedron" and getattr(shape, "equator", "rhombus") == "rectangle":
        size = f"equator {n('a')} × {n('b')} m, apexes at ±{n('h')} m"
    else:
        word = {"box": "sides", "ellipsoid": "semi-axes", "octahedron": "half-diagonals"}
        size = f"{word[shape.type]} {n('a')}, {n('b')}, {n('c')} m"
    return f"a solid {shape.type} (M = {n('mass')} kg, {size})"


class InertiaScene(InertiaSimulation, InertiaReport):
    kind = "inertia"
    order = 90
    summary = "inertia tensor of a shape or point set, principal axes, stable spin axes"
    Config = InertiaConfig
    presets = PRESETS
    name_in_words = "Inertia tensor"

    @classmethod
    def default_title(cls, config):
        """``Inertia of a solid cone (M = 1 kg, R = 0.5 m, h = 2 m), tilted``."""
        shape = config.shape
        return (f"Inertia of {shape_in_words(shape)}"
                + (", tilted" if shape.euler_angles is not None else "")
                + (", about (" + ", ".join(fmt(float(x), 4) for x in shape.about) + ") m"
                   if shape.about is not None else ""))
