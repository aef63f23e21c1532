r"""``hamiltonian`` report, the section on the Legendre transform as geometry (notes
(4.15)–(4.28)): the notes' unit sphere and the scene's own L as surfaces described by their
tangent planes, and the sign of the dual relation (4.28) as measured; from the archive alone.

Every sentence that states a result is chosen by a stored value: the relation that holds
(``legendre_*_relation``, with its threshold), whether ∂²L/∂q̇∂q̇ is positive definite
(``legendre_convex``, with its eigenvalues).
"""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from ...scene.content import SectionContent, fmt, fmt_err
from .results import SCHEMA
from .symbols import symbol_text

plots = lazy_module("reportgen.kinds.hamiltonian.plots")

#: tangent lines drawn on the sphere's cut y = 0, at most (stored points with x₀ ≥ 0)
DRAWN_LINES = 5


def _velocity(name: str) -> str:
    return symbol_text(f"{name}_dot")


class LegendreGeometrySections:
    """Mixed into :class:`.report.HamiltonianReport`."""

    @classmethod
    def section_legendre_geometry(cls, data):
        a = data.analysis
        names = cls.coordinates(data)
        tex_q = [str(q) for q in a["latex"]["q"]]
        at = ", ".join(f"{symbol_text(n)} = {fmt(float(a[f'initial_{n}']), 4)}" for n in names)
        v1, v2 = (_velocity(n) for n in names)
        equations = [
            ("the notes' unit sphere, notes (4.19), and its tangent plane at (x₀, y₀, z₀), "
             "notes (4.20)",
             r"z = \sqrt{1 - x^2 - y^2},\quad z - z_0 + (x - x_0)\,\frac{x_0}{z_0}"
             r" + (y - y_0)\,\frac{y_0}{z_0} = 0"),
            ("the plane coordinates of the tangent plane (x, y, z)·(ξ, η, 1) = ω, notes "
             "(4.22)–(4.24)",
             r"\xi = -\frac{\partial z}{\partial x},\quad \eta = -\frac{\partial z}"
             r"{\partial y},\quad \omega = z_0 + x_0\xi + y_0\eta"),
            ("for the unit sphere, from notes (4.20)–(4.21)",
             r"\xi = \frac{x_0}{z_0},\quad \eta = \frac{y_0}{z_0},\quad \omega = "
             r"\frac{1}{z_0} = \sqrt{1 + \xi^2 + \eta^2}"),
            ("the dual description ω(ξ, η) gives the points back, notes (4.25)–(4.27)",
             r"\frac{\partial\omega}{\partial\xi} = x_0,\quad \frac{\partial\omega}"
             r"{\partial\eta} = y_0"),
            (f"this scene's Lagrangian as the surface, at {at} (t = 0): the Legendre "
             "correspondence of notes (4.29)–(4.31)",
             rf"z = L(\dot{{{tex_q[0]}}}, \dot{{{tex_q[1]}}}),\quad \xi = -p_{{{tex_q[0]}}},"
             rf"\quad \eta = -p_{{{tex_q[1]}}},\quad \omega = L - p\cdot\dot q = -H"),
        ]
        sphere = a["legendre_sphere"]
        x0, y0, z0 = (np.asarray(sphere[k], dtype=float) for k in ("x0", "y0", "z0"))
        radius = np.hypot(x0, y0)
        spacing = float(np.min(np.diff(np.unique(x0))))
        facts = [
            ("tangent points of the unit sphere, notes (4.19)–(4.21)",
             f"{len(x0)} on a square grid of spacing {fmt(spacing, 4)}, up to "
             f"{fmt(float(np.max(radius)), 4)} from the z axis (z₀ ≥ "
             f"{fmt(float(np.min(z0)), 4)})"),
            ("slopes ξ, η by central differences of step h = "
             f"{fmt(float(a['legendre_slope_step']), 2)}: max |ξ − x₀/z₀|, |η − y₀/z₀| "
             "against the tangent plane of notes (4.20)",
             fmt_err(a["legendre_sphere_slope_error"])),
            ("the intercept ω = z₀ + x₀ξ + y₀η of notes (4.24): max |ω − √(1 + ξ² + η²)|",
             fmt_err(a["legendre_sphere_omega_error"])),
            ("max |ω z₀ − 1|: the tangent plane x·x₀ = 1 of the unit sphere, notes (4.21), "
             "meets the z axis at 1/z₀", fmt_err(a["legendre_sphere_intercept_error"])),
            ("max |∂ω/∂ξ − x₀|, |∂ω/∂η − y₀|, notes (4.26)–(4.27): ω(ξ, η) at shifted plane "
             "coordinates, each from its own tangent point (Newton's method), by central "
             f"differences of step δ = {fmt(float(a['legendre_plane_step']), 2)}",
             fmt_err(a["legendre_sphere_derivative_error"])),
            ("notes (4.28) with ω = √(1 + ξ² + η²): max |ω − z − xξ − yη| and "
             "max |ω + z − xξ − yη| over the tangent points",
             f"{fmt_err(a['legendre_sphere_sign_minus'])} and "
             f"{fmt_err(a['legendre_sphere_sign_plus'])} (terms ≤ "
             f"{fmt(a['legendre_sphere_sign_scale'], 4)})"),
        ]
        facts += cls._lagrangian_facts(data, v1, v2, at)
        notes = [cls.relation_words(a, "legendre_sphere"),
                 cls.relation_words(a, "legendre_lagrangian")]
        return SectionContent(equations=equations, facts=facts,
                              figures=[cls._tangent_figure(data)],
                              notes=[n for n in notes if n])

    @classmethod
    def _lagrangian_facts(cls, data, v1, v2, at) -> list[tuple[str, str]]:
        a = data.analysis
        surface = a["legendre_lagrangian"]
        x, y = (np.asarray(surface[k], dtype=float) for k in ("x", "y"))
        eig = [fmt(float(e), 4) for e in np.asarray(a["legendre_velocity_hessian_eigenvalues"])]
        shape = ("positive definite, eigenvalues " + " and ".join(eig) + ": a convex surface, "
                 "one tangent plane for each slope (ξ, η)" if a["legendre_convex"] else
                 "not positive definite, eigenvalues " + " and ".join(eig))
        return [
            (f"∂²L/∂q̇ᵢ∂q̇ⱼ of the surface z = L({v1}, {v2})", f"at {at} (t = 0): {shape}"),
            ("sampled velocities",
             f"{len(x)}: {v1} from {fmt(float(np.min(x)), 4)} to {fmt(float(np.max(x)), 4)}"
             f" and {v2} from {fmt(float(np.min(y)), 4)} to {fmt(float(np.max(y)), 4)}"),
            ("max |ξ + p₁|, |η + p₂|: the slopes by differences against the momenta "
             "p = ∂L/∂q̇ (SymPy), notes (4.30)",
             f"{fmt_err(a['legendre_lagrangian_slope_error'])} (|p| ≤ "
             f"{fmt(a['legendre_lagrangian_momentum_scale'], 4)})"),
            ("max |ω + H|: the intercept ω = L + xξ + yη against the scene's Hamiltonian at "
             "p = ∂L/∂q̇, notes (4.31)",
             f"{fmt_err(a['legendre_lagrangian_omega_error'])} (|H| ≤ "
             f"{fmt(a['legendre_lagrangian_energy_scale'], 4)})"),
            (f"max |∂ω/∂ξ − {v1}|, |∂ω/∂η − {v2}|, notes (4.26)–(4.27): ∂H/∂p = q̇ read off "
             "the tangent planes",
             f"{fmt_err(a['legendre_lagrangian_derivative_error'])} (|q̇| ≤ "
             f"{fmt(a['legendre_lagrangian_velocity_scale'], 4)})"),
            ("notes (4.28) for z = L with ω(ξ, η) = −H(q, −ξ, −η): max |ω − z − xξ − yη| and "
             "max |ω + z − xξ − yη| over the sampled velocities",
             f"{fmt_err(a['legendre_lagrangian_sign_minus'])} and "
             f"{fmt_err(a['legendre_lagrangian_sign_plus'])} (terms ≤ "
             f"{fmt(a['legendre_lagrangian_sign_scale'], 4)})"),
        ]

    @staticmethod
    def relation_words(a, prefix: str) -> str:
        """The sign of notes (4.28) as measured: the sentence chosen by the stored
        ``<prefix>_relation`` (its threshold ``legendre_relation_threshold``)."""
        relation = str(a.get(f"{prefix}_relation", ""))
        minus, plus = fmt_err(a[f"{prefix}_sign_minus"]), fmt_err(a[f"{prefix}_sign_plus"])
        bound = fmt_err(float(a["legendre_relation_threshold"]))
        lagrangian = prefix == "legendre_lagrangian"
        if relation == "minus":
            if lagrangian:
                return (f"For z = L the measured relation ω − z = xξ + yη (residual {minus}) "
                        "reads −H − L = −p·q̇, that is H = p·q̇ − L, the Hamiltonian of notes "
                        f"(4.31); the printed sign would give H = p·q̇ + L and misses by "
                        f"{plus}.")
            return (f"Measured, the dual relation holds as ω − z = xξ + yη: residual {minus}, "
                    f"below {bound} of the size of its terms. That is what the definitions of "
                    "the plane coordinates, notes (4.23)–(4.24), give (ω = z₀ + x₀ξ + y₀η). As "
                    f"printed, notes (4.28) reads ω + z = xξ + yη, which misses by {plus} "
                    "(where ω − z = xξ + yη holds, ω + z − xξ − yη = 2z): the sign of z there "
                    "does not follow from the definitions.")
        if relation == "plus":
            return (f"Measured, the relation ω + z = xξ + yη of notes (4.28) holds as printed "
                    f"(residual {plus}, below {bound} of its terms); ω − z = xξ + yη misses "
                    f"by {minus}.")
        if relation in ("both", "neither"):
            return (f"Neither sign of the dual relation of notes (4.28), ω ± z = xξ + yη, is "
                    f"singled out to {bound} of its terms: residuals {minus} (ω − z) and "
                    f"{plus} (ω + z).")
        return ""

    @classmethod
    def _tangent_figure(cls, data):
        a = data.analysis
        sphere, curve, dual = (a[k] for k in ("legendre_sphere", "legendre_sphere_curve",
                                              "legendre_sphere_dual"))
        x0, y0 = np.asarray(sphere["x0"], dtype=float), np.asarray(sphere["y0"], dtype=float)
        # one side of the cut: the tangent planes at ±x₀ meet the z axis at the same ω
        row = np.flatnonzero((y0 == 0.0) & (x0 >= 0.0))
        row = row[np.argsort(x0[row])]
        drawn = row[np.linspace(0, len(row) - 1, min(DRAWN_LINES, len(row))).round()
                    .astype(int)]
        points = [np.asarray(sphere[k], dtype=float)[drawn] for k in ("x0", "z0", "xi",
                                                                       "omega")]
        labels = {"x": SCHEMA.result("legendre_sphere_curve/x").label(),
                  "z": SCHEMA.result("legendre_sphere_curve/z").label(),
                  "xi": SCHEMA.result("legendre_sphere_dual/xi").label(),
                  "omega": SCHEMA.result("legendre_sphere_dual/omega").label()}
        fig = plots.tangent_planes((curve["x"], curve["z"]), points,
                                   (dual["xi"], dual["omega"]), labels)
        return cls.figure(
            "legendre_tangent_planes", fig,
            f"Left: the cut y = 0 of the unit sphere, z = √(1 − x²) (notes (4.19)), with the "
            f"tangent lines z = ω − ξx at {len(drawn)} of the stored tangent points (those "
            "with y₀ = 0, x₀ ≥ 0) and their intercepts ω on the z axis (notes (4.24)). "
            "Right: the same planes as points (ξ, ω) of the dual curve, on its closed form "
            "ω = √(1 + ξ²) at η = 0: the surface described by its tangent planes, notes "
            "(4.25).")
