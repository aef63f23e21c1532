r"""``three_body``: three gravitating bodies (lecture notes §3, notes (3.32)–(3.35)).

Arbitrary masses and states, and presets: the Sun–Earth–Moon system with the
notes' mass ratios m2/m1 ~ 1e-6, m3/m1 ~ 1e-8 (notes (3.35)), described in the notes'
coordinates relative to body 1 (r12 = r2 − r1, r13 = r3 − r1 and the centre of mass,
notes (3.32)–(3.34); their kinetic energy has a cross term) and in Jacobi coordinates
(the standard hierarchical choice; not in the notes; a diagonal kinetic energy); the
Chenciner–Montgomery figure-eight; Burrau's Pythagorean problem with its close
encounters.  Energy, total momentum and angular momentum are the
conserved quantities; a run whose energy error exceeds ``energy_tolerance`` is
flagged unstable, never drawn silently.

With ``[restricted]``: the planar circular restricted problem in the frame rotating with
two primaries of mass ratio μ (Murray & Dermott ch. 3), a test particle integrated in
regularized (Thiele–Burrau) variables; a sweep over its start draws a surface of section.

Archive columns: x1, y1, z1, x2, y2, z2, x3, y3, z3 (positions body by body), then
vx1, vy1, vz1, …, vz3 in the same order; restricted runs: x, y, vx, vy (rotating frame).
"""

from __future__ import annotations

from ...scene.content import fmt as _fmt
from .config import PRESETS, ThreeBodyConfig
from .report import ThreeBodyReport
from .simulation import ThreeBodySimulation


def fmt(x, digits: int = 10) -> str:
    """A number of a title: :func:`~reportgen.scene.content.fmt` with a true minus sign."""
    return _fmt(x, digits).replace("-", "−")


class ThreeBodyScene(ThreeBodySimulation, ThreeBodyReport):
    kind = "three_body"
    order = 40
    summary = "three gravitating bodies: Sun–Earth–Moon (relative and Jacobi coordinates), " \
              "figure-eight, Pythagorean problem; the planar circular restricted problem " \
              "in the rotating frame"
    Config = ThreeBodyConfig
    presets = PRESETS
    name_in_words = "Three gravitating bodies"
    #: the presets in words, each completed by its masses
    PRESET_WORDS = {"pythagorean": "Pythagorean three-body problem",
                    "figure_eight": "Figure-eight orbit of three equal masses",
                    "sun_earth_moon": "Sun, Earth and Moon in relative and Jacobi coordinates"}

    @classmethod
    def default_title(cls, config):
        """``Pythagorean three-body problem (masses 3, 4, 5)``; without a preset, the
        bodies' names (when given) and masses; for the restricted problem, μ, the start
        and the Jacobi constant."""
        if config.restricted is not None:
            return ThreeBodyReport.restricted_title(config)
        masses = ", ".join(fmt(float(m), 4) for m in config.params.masses)
        preset = cls.preset_as_given(config)
        words = cls.PRESET_WORDS.get(preset or "")
        if preset == "sun_earth_moon":
            return f"{words} over {fmt(float(config.run.t_end), 4)} {config.time_unit}".strip()
        if preset == "figure_eight":
            return f"{words} (period {fmt(float(config.period), 6)})"
        if words is not None:
            return f"{words} (masses {masses})"
        names = list(config.names)
        if names != ["body 1", "body 2", "body 3"]:
            return f"Three bodies: {', '.join(names)} (masses {masses})"
        return f"Three gravitating bodies (masses {masses})"
