"""``normal_modes`` report of a potential written as formulas (``[system]``): the
equilibrium found from the guess and the expansion of U about it (textbook §5.1), drawn
from the archive alone."""

from __future__ import annotations

import re

import numpy as np

from ...scene.content import SectionContent, Table, fmt, fmt_err, fmt_matrix
from ...scene.schema import TEX_GREEK, Quantity, symbol_text, unit_text
from ..hamiltonian.symbols import split_sum
from .config import unit_system
from .results import units

#: how the system was written, in words (``/analysis/given``)
GIVEN_WORDS = {"L": "a Lagrangian L(q, q̇)",
               "T": "a potential energy U(q) and a kinetic energy T(q, q̇)",
               "M": "a potential energy U(q) and a mass matrix M(q)"}


def name_tex(name: str) -> str:
    """A constant's or coordinate's name as TeX: ``theta1`` -> ``\\theta_{1}``, ``m2`` ->
    ``m_{2}``, ``k`` -> ``k`` (a Greek letter spelt out, trailing digits as a subscript;
    another name upright)."""
    found = re.fullmatch(r"([A-Za-z]+?)_?(\d*)", name)
    if found is None:
        return rf"\mathrm{{{name}}}".replace("_", r"\_")
    head, index = found.groups()
    tex = (f"\\{head}" if head in TEX_GREEK else head if len(head) == 1
           else rf"\mathrm{{{head}}}")
    return tex + (f"_{{{index}}}" if index else "")


class PotentialReport:
    """The equilibrium section and the summary's words of a written potential (mixed into
    the kind's report; every number from ``/analysis``)."""

    #: a family's results that are rounding-level checks of each member, not physics that
    #: varies along the sweep (shown in each member's own report)
    SWEEP_HIDDEN_RESULTS = ("equilibrium_gradient*", "equilibrium_residual*",
                            "equilibrium_evaluations", "hessian_finite_difference",
                            "finite_difference_step", "closed_form_max_rel_error",
                            "three_step_max_difference", "orthonormality_error")

    @classmethod
    def config_quantity(cls, data, path):
        """A swept named constant ``params.<name>`` as its symbol (m₂), a pure number in a
        dimensionless system, else in the SI units the formulas are written in."""
        head, _, name = path.partition(".")
        if head != "params" or not name:
            return super().config_quantity(data, path)
        unit = "1" if unit_system(data.config) == "dimensionless" else "SI units"
        return Quantity(path, name_tex(name), unit, f"the constant {name}")

    @staticmethod
    def coordinate_texts(data) -> list[str]:
        """Each coordinate's symbol as text (θ₁), from the archived TeX; its name where
        text has no spelling of it."""
        a = data.analysis
        names = [str(n) for n in a["coordinate_names"]]
        tex = [str(t) for t in a.get("coordinate_symbols", names)]
        return [symbol_text(t) or n for t, n in zip(tex, names, strict=True)]

    @staticmethod
    def _potential_units(data) -> dict[str, str]:
        a = data.analysis
        u = units("potential", a.get("unit_system"), a.get("coordinate_unit"))
        return {k: unit_text(v) for k, v in u.items()}

    @staticmethod
    def _unit_suffix(unit: str) -> str:
        return "" if unit == "dimensionless" else f" {unit}"

    @classmethod
    def _point(cls, data, name: str) -> str:
        """``θ₁ = 0, θ₂ = 0 rad``: an archived point named by the coordinates."""
        values = np.asarray(data.analysis[name], dtype=float)
        unit = cls._potential_units(data)["q"]
        return (", ".join(f"{c} = {fmt(float(v))}" for c, v in zip(
            cls.coordinate_texts(data), values, strict=True)) + cls._unit_suffix(unit))

    @staticmethod
    def stability_words(data) -> str:
        """The equilibrium's stability, as the archived classification says it."""
        a = data.analysis
        if str(a["equilibrium_stability"]) == "stable" and bool(a["hessian_positive_definite"]):
            return "stable: A is positive definite (every ω² > 0), so q₀ is a minimum of U"
        zero = int(a["n_zero_modes"])
        return (f"neutral to second order: A is positive semidefinite with {zero} zero "
                f"eigenvalue{'s' if zero != 1 else ''} (ω² within 10⁻¹⁰ of the largest), "
                "directions in which U is flat to second order, where higher orders decide "
                "the stability")

    @classmethod
    def potential_describe(cls, data) -> str:
        """``Small oscillations of a system given by a Lagrangian L(q, q̇) in θ₁, θ₂``."""
        a = data.analysis
        coords = cls.coordinate_texts(data)
        return (f"Small oscillations of a system given by {GIVEN_WORDS[str(a['given'])]} in "
                f"{len(coords)} coordinate{'s' if len(coords) != 1 else ''}, "
                f"{', '.join(coords)}, about the equilibrium found from a guess")

    @classmethod
    def potential_headline(cls, data) -> list[tuple[str, str]]:
        a = data.analysis
        return [("equilibrium q₀", f"{cls._point(data, 'equilibrium')} (found from "
                                   f"{cls._point(data, 'equilibrium_guess')})"),
                ("|∇U| at q₀", fmt(float(a["equilibrium_gradient_norm"]))
                 + cls._unit_suffix(cls._potential_units(data)["gradient"])),
                ("stability", cls.stability_words(data))]

    @classmethod
    def _equations(cls, data) -> list[tuple[str, str]]:
        a = data.analysis
        eqs = []
        if "lagrangian_latex" in a:
            for i, line in enumerate(split_sum("L", str(a["lagrangian_latex"]))):
                eqs.append(("the Lagrangian" if i == 0 else "", line))
        for i, line in enumerate(split_sum("U", str(a["potential_latex"]))):
            eqs.append((("the potential energy, U = −L at rest" if "lagrangian_latex" in a
                         else "the potential energy") if i == 0 else "", line))
        if "kinetic_latex" in a:
            for i, line in enumerate(split_sum("T", str(a["kinetic_latex"]))):
                eqs.append(("the kinetic energy" if i == 0 else "", line))
        return eqs

    @classmethod
    def section_equilibrium(cls, data):
        a = data.analysis
        u = cls._potential_units(data)
        coords = cls.coordinate_texts(data)
        guess = np.asarray(a["equilibrium_guess"], dtype=float)
        q0 = np.asarray(a["equilibrium"], dtype=float)
        grad = np.asarray(a["equilibrium_gradient"], dtype=float)
        rows = [[c, fmt(float(g)), fmt(float(q)), fmt(float(d))]
                for c, g, q, d in zip(coords, guess, q0, grad, strict=True)]

        def bracket(text: str, unit: str) -> str:
            return text if unit == "dimensionless" else f"{text} [{unit}]"

        tables = [Table("The equilibrium: where the search started and the stationary point "
                        "it found, with the gradient of U there",
                        ["coordinate", bracket("guess", u["q"]), bracket("q₀", u["q"]),
                         bracket("∂U/∂q at q₀", u["gradient"])], rows)]
        for name, title, unit in (("mass_matrix", "Mass matrix M at q₀", u["mass"]),
                                  ("hessian", "A = ∂²U/∂q∂q at q₀", u["stiffness"])):
            cells = fmt_matrix(np.asarray(a[name], dtype=float))
            tables.append(Table(bracket(title, unit), ["", *coords],
                                [[c, *row] for c, row in zip(coords, cells, strict=True)]))
        n_eval = int(a["equilibrium_evaluations"])
        facts = [
            ("search", "∇U(q) = 0 solved from the guess by Newton's method with the exact "
                       "Jacobian A(q), each step halved until |∇U| falls: "
                       f"{n_eval} evaluations of ∇U"),
            ("|∇U| at q₀", fmt(float(a["equilibrium_gradient_norm"]))
             + cls._unit_suffix(u["gradient"])),
            ("largest |∂U/∂qᵢ| against the size of its terms",
             f"{fmt_err(float(a['equilibrium_residual']))} (a point is stationary below "
             f"{fmt(float(a['equilibrium_residual_tol']))})"),
            ("U(q₀)", fmt(float(a["equilibrium_potential"])) + cls._unit_suffix(u["energy"])),
            ("A", "∂²U/∂qᵢ∂qⱼ differentiated symbolically from the formula, evaluated at q₀: "
                  "exact up to rounding"),
            (f"central-difference check of A, step h = {fmt(float(a['finite_difference_step']))}"
             f"{cls._unit_suffix(u['q'])}: max |A(h) − A| / max |A|",
             fmt_err(float(a["hessian_finite_difference"]))),
            ("stability", cls.stability_words(data)),
        ]
        return SectionContent(tables=tables, facts=facts, equations=cls._equations(data))
