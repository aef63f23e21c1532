r"""``hamiltonian`` config: the coordinates, H or L as text, observables, the surface of
section, a canonical transformation, the Hamilton–Jacobi comparison and the presets.

The formulas are checked against the allow-list of :mod:`reportgen.core.expressions`
(no SymPy) when the config is validated.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ...lazy import lazy_module
from ...scene.base import SceneConfig
from ...scene.config import Real, RunConfig, Strict

expressions = lazy_module("reportgen.core.expressions")  # no SymPy: validation uses it


class _PresetFormulas:
    """The separable presets' H, from reportgen.core.hamilton_jacobi without importing it
    (a module of numerics) when the kind is only listed or validated."""

    CENTRAL_H = "(p_r**2 + p_theta**2/r**2 + p_phi**2/(r**2*sin(theta)**2))/(2*m) - k/r"
    TWO_CENTRES_H = ("(p_xi**2 + p_eta**2)/(2*m*a**2*(cosh(xi)**2 - cos(eta)**2))"
                     " - m*mu1/(a*(cosh(xi) - cos(eta))) - m*mu2/(a*(cosh(xi) + cos(eta)))")


#: the error-against-run-time study covers at most this many steps of the main run
STUDY_STEPS = 2000
#: samples the Jacobi identity is checked on
JACOBI_SAMPLES = 200


def _reserved() -> frozenset[str]:
    """Names a coordinate, constant or observable may not take: the parser's own, and the
    keys H and energy."""
    return expressions.RESERVED | {"H", "energy"}


def _usable(name: str) -> bool:
    return expressions.name_problem(name) is None and name not in _reserved()


def _name_rule(name) -> str:
    """Why ``name`` is not usable, as a rule."""
    problem = expressions.name_problem(name)
    if problem is None:
        problem = f"{name!r} is reserved (H, energy)"
    return f"not a usable name: {problem}"


class System(Strict):
    """``[system]``: the coordinates and H or L."""

    coordinates: list[str] = Field(min_length=1, max_length=6,
                                   description="names of the generalized coordinates q")
    H: str | None = Field(None, description="Hamiltonian in q, p_<q>, t and the constants")
    L: str | None = Field(None, description="Lagrangian in q, <q>_dot, t and the constants")


class SurfaceOfSection(Strict):
    """``[section]``: the surface of section of a Poincaré map."""

    coordinate: str = Field(description="state column that defines the surface (a "
                                        "coordinate or a momentum)")
    value: Real = Field(0.0, description="the surface is coordinate = value")
    direction: Literal["up", "down", "both"] = Field(
        "up", description="crossings counted: increasing, decreasing or both")
    axes: list[str] | None = Field(None, min_length=2, max_length=2,
                                   description="two state columns plotted (default: the "
                                               "next coordinate and its momentum)")


class Transform(Strict):
    """``[transform]``: a canonical transformation from a generating function (notes §6)."""

    F1: str | None = Field(None, description="F1(q, Q, t): p = ∂F1/∂q, P = −∂F1/∂Q")
    F2: str | None = Field(None, description="F2(q, P, t): p = ∂F2/∂q, Q = ∂F2/∂P")
    coordinates: list[str] = Field(min_length=1, max_length=6,
                                   description="names of the new coordinates Q")
    momenta: list[str] | None = Field(None, description="names of the new momenta P "
                                                        "(default P_<Q>)")

    @property
    def kind(self) -> str:
        return "F1" if self.F1 is not None else "F2"

    @property
    def formula(self) -> str:
        return self.F1 if self.F1 is not None else self.F2

    def new_momenta(self) -> list[str]:
        return list(self.momenta) if self.momenta else [f"P_{c}" for c in self.coordinates]


class HamiltonJacobi(Strict):
    """``[hamilton_jacobi]``: compare with the separated quadrature solution (notes §7)."""

    separation: Literal["central", "two_centres"] = Field(
        description='"central": V = −k/r in spherical (r, theta, phi), constants m, k; '
                    '"two_centres": elliptic (xi, eta), constants m, mu1, mu2, a')


#: the coordinates and constants each separable preset's H is written in
SEPARATIONS = {"central": (["r", "theta", "phi"], {"m", "k"}),
               "two_centres": (["xi", "eta"], {"m", "mu1", "mu2", "a"})}
PRESET_OF = {"central": "central_potential", "two_centres": "two_centres"}


def _problem(key: str, rule: str, got=None) -> ValueError:
    """A config error in the form every kind uses: ``key 'a.b': rule (got value)``."""
    return ValueError(f"key '{key}': {rule}" + ("" if got is None else f" (got {got!r})"))


class HamiltonianConfig(SceneConfig):
    params: dict[str, Real] = Field(default_factory=dict,
                                    description="named constants usable in the formulas")
    system: System
    observables: dict[str, str] = Field(default_factory=dict,
                                        description="named functions of q, p (or q̇) and t")
    initial: dict[str, Real] = Field(description="the coordinates and p_<q> (for H) or "
                                                 "<q>_dot (for L); with `energy`, one of "
                                                 "those may be left out and is solved for")
    run: RunConfig
    section: SurfaceOfSection | None = None
    transform: Transform | None = None
    hamilton_jacobi: HamiltonJacobi | None = None

    @model_validator(mode="after")
    def _formulas(self):
        """Names, formulas (allow-list, without SymPy) and the initial state's keys."""
        sys_ = self.system
        if (sys_.H is None) == (sys_.L is None):
            raise _problem("system", "give exactly one of H and L")
        coords = sys_.coordinates
        for c in coords:
            if not _usable(c):
                raise _problem("system.coordinates", _name_rule(c))
        if len(set(coords)) != len(coords):
            raise _problem("system.coordinates", "names must not repeat", coords)
        alias = expressions.alias_problem(coords)
        if alias is not None:
            raise _problem("system.coordinates", f"aliased names: {alias}")
        if len(self.params) > expressions.MAX_CONSTANTS:
            raise _problem("params", f"at most {expressions.MAX_CONSTANTS} named constants "
                                     f"(got {len(self.params)})")
        if len(self.observables) > expressions.MAX_OBSERVABLES:
            raise _problem("observables", f"at most {expressions.MAX_OBSERVABLES} observables "
                                          f"(got {len(self.observables)})")
        momenta = [f"p_{c}" for c in coords]
        velocities = [f"{c}_dot" for c in coords]
        state = set(coords) | set(momenta) | set(velocities)
        for name, value in self.params.items():
            if not _usable(name):
                raise _problem(f"params.{name}", _name_rule(name))
            if name in state:
                raise _problem(f"params.{name}", "a constant may not take the name of a "
                               "coordinate, momentum or velocity", value)
        constants = list(self.params)
        used: set[str] = set()

        def check(key: str, text: str, names: list[str]) -> None:
            try:
                used.update(expressions.check_expression(text, names))
            except expressions.ExpressionError as exc:
                raise _problem(key, str(exc)) from None

        if sys_.H is not None:
            check("system.H", sys_.H, coords + momenta + ["t"] + constants)
        else:
            check("system.L", sys_.L, coords + velocities + ["t"] + constants)
        for name, text in self.observables.items():
            if not _usable(name):
                raise _problem(f"observables.{name}", _name_rule(name))
            if name in state or name in self.params:
                raise _problem(f"observables.{name}", "an observable may not take the name of "
                               "a coordinate, momentum, velocity or constant", text)
            check(f"observables.{name}", text, coords + momenta + velocities + ["t"]
                  + constants)
        speeds = momenta if sys_.H is not None else velocities
        wanted = coords + speeds
        for key, value in self.initial.items():
            if key != "energy" and key not in wanted:
                raise _problem(f"initial.{key}", f"not a coordinate or "
                               f"{'momentum' if sys_.H is not None else 'velocity'} of the "
                               f"system (expected {', '.join(wanted)}, and optionally energy)",
                               value)
        missing = [k for k in wanted if k not in self.initial]
        if "energy" in self.initial:
            if len(missing) != 1 or missing[0] in coords:
                raise _problem("initial.energy", f"leave out exactly one of {', '.join(speeds)}"
                               " (it is solved for so that H = energy)", missing or "none left out")
        elif missing:
            raise _problem(f"initial.{missing[0]}", "required key is missing")
        if self.section is not None:
            columns = coords + momenta
            for i, name in enumerate([self.section.coordinate, *(self.section.axes or [])]):
                key = "section.coordinate" if i == 0 else "section.axes"
                if name not in columns:
                    raise _problem(key, f"must be a state column ({', '.join(columns)})", name)
            if len(coords) < 2:
                raise _problem("section", "a surface of section needs two or more degrees of "
                               "freedom (one degree of freedom gets a phase portrait)")
        tr = self.transform
        if tr is not None:
            if (tr.F1 is None) == (tr.F2 is None):
                raise _problem("transform", "give exactly one of F1 and F2")
            new = list(tr.coordinates) + tr.new_momenta()
            if len(tr.coordinates) != len(coords) or len(tr.new_momenta()) != len(coords):
                raise _problem("transform.coordinates", f"needs {len(coords)} new coordinate "
                               "(and momentum) names, one per coordinate", tr.coordinates)
            for name in new:
                if not _usable(name) or name in state or name in self.params \
                        or new.count(name) > 1:
                    raise _problem("transform.coordinates", "new names must be distinct "
                                   "identifiers, not an old coordinate, momentum, velocity or "
                                   "constant", name)
            key = f"transform.{tr.kind}"
            unknowns = list(tr.coordinates) if tr.kind == "F1" else tr.new_momenta()
            check(key, tr.formula, coords + unknowns + ["t"] + constants)
        hj = self.hamilton_jacobi
        if hj is not None:
            names, constants_needed = SEPARATIONS[hj.separation]
            if list(coords) != names or sys_.H is None \
                    or not constants_needed <= set(self.params):
                raise _problem("hamilton_jacobi.separation", f"{hj.separation!r} solves H "
                               f"written in coordinates {names} with constants "
                               f"{', '.join(sorted(constants_needed))} (use preset = "
                               f"\"{PRESET_OF[hj.separation]}\")", hj.separation)
        for name, value in self.params.items():
            if name not in used:
                raise _problem(f"params.{name}", "a constant no formula uses (a misspelt "
                               "name?)", value)
        return self


#: the two separable presets (explicit keys override)
PRESETS = {
    # V = −k/r in spherical coordinates: H separates as W_r(r) + W_θ(θ) + p_φ φ
    "central_potential": {
        "params": {"m": 1.0, "k": 1.0},
        "system": {"coordinates": ["r", "theta", "phi"], "H": _PresetFormulas.CENTRAL_H},
        "observables": {"L2": "p_theta**2 + p_phi**2/sin(theta)**2",
                        "Lx": "-sin(phi)*p_theta - cos(theta)/sin(theta)*cos(phi)*p_phi",
                        "Ly": "cos(phi)*p_theta - cos(theta)/sin(theta)*sin(phi)*p_phi"},
        "hamilton_jacobi": {"separation": "central"},
        "initial": {"r": 1.0, "theta": 1.1, "phi": 0.0, "p_r": 0.2, "p_theta": 0.5,
                    "p_phi": 0.8},
        "run": {"t_end": 40.0}},
    # two fixed centres in elliptic coordinates: separates with a second constant β
    "two_centres": {
        "params": {"m": 1.0, "mu1": 1.0, "mu2": 0.5, "a": 1.0},
        "system": {"coordinates": ["xi", "eta"], "H": _PresetFormulas.TWO_CENTRES_H},
        "hamilton_jacobi": {"separation": "two_centres"},
        "initial": {"xi": 0.8, "eta": 1.0, "p_xi": 0.0, "p_eta": 0.6},
        "run": {"t_end": 40.0}},
}


def family_energy(sweep) -> float | None:
    """The members' common energy H(0), or None if they differ (beyond rounding): the
    edge of a family's surface of section (simulation) and its facts (report)."""
    h0 = np.asarray(sweep.analysis.get("H0", []), dtype=float)
    h0 = h0[sweep.ok & np.isfinite(h0)] if h0.size else h0
    if h0.size == 0 or np.ptp(h0) > 1e-12 * max(float(np.max(np.abs(h0))), 1.0):
        return None
    return float(np.median(h0))
