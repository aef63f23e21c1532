r"""``hamiltonian``: any system written as a formula, H(q, p, t) or L(q, q̇, t) (notes §2–§7).

The config names the coordinates and gives H or L as text; named constants come from
``[params]``.  The text is parsed against an allow-list (:mod:`reportgen.core.expressions`),
derived with SymPy (Hamilton's equations; for L the Legendre transform) and compiled with
numba through the same integrators and study as every kind
(:mod:`reportgen.core.formula`).  The report shows the equations, the phase portrait
(one degree of freedom) or a surface of section (two or more), the conserved quantities
with their drift, the Poisson brackets of the observables with H and with each other (the
Jacobi identity checked on the trajectory), cyclic coordinates, and error against run
time.  ``[transform]`` adds a canonical transformation from a generating function and
``[hamilton_jacobi]`` the separated quadrature solution of the shipped presets.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ..config import Real, RunConfig, Strict
from ..lazy import lazy_module
from ..results import Check, Results
from ..sweep import PointSet
from .base import (
    Scene,
    SceneConfig,
    Section,
    SectionContent,
    Table,
    fmt,
    fmt_err,
    member_text,
    section_colours,
    section_point_notes,
)

common_plots = lazy_module("reportgen.plots.common")
plots = lazy_module("reportgen.plots.hamiltonian")
section_plots = lazy_module("reportgen.plots.sections")
expressions = lazy_module("reportgen.core.expressions")  # no SymPy: validation uses it
formula = lazy_module("reportgen.core.formula")
numeric = lazy_module("reportgen.core.numeric")
mechanics = lazy_module("reportgen.core.mechanics")
canonical = lazy_module("reportgen.core.canonical")


class _PresetFormulas:
    """The separable presets' H, from reportgen.core.hamilton_jacobi without importing it
    (a module of numerics) when the kind is only listed or validated."""

    CENTRAL_H = "(p_r**2 + p_theta**2/r**2 + p_phi**2/(r**2*sin(theta)**2))/(2*m) - k/r"
    TWO_CENTRES_H = ("(p_xi**2 + p_eta**2)/(2*m*a**2*(cosh(xi)**2 - cos(eta)**2))"
                     " - m*mu1/(a*(cosh(xi) - cos(eta))) - m*mu2/(a*(cosh(xi) + cos(eta)))")


_hj = _PresetFormulas
hamilton_jacobi = lazy_module("reportgen.core.hamilton_jacobi")

#: the error-against-run-time study covers at most this many steps of the main run
STUDY_STEPS = 2000



def _reserved() -> frozenset[str]:
    """Names a coordinate, constant or observable may not take: the parser's own, and the
    keys H and energy."""
    return expressions.RESERVED | {"H", "energy"}


def _usable(name: str) -> bool:
    return name.isidentifier() and not name.startswith("_") and name not in _reserved()


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
        rule = (f"must be an identifier not starting with _ and not one of "
                f"{', '.join(sorted(_reserved()))}")
        for c in coords:
            if not _usable(c):
                raise _problem("system.coordinates", rule, c)
        if len(set(coords)) != len(coords):
            raise _problem("system.coordinates", "names must not repeat", coords)
        momenta = [f"p_{c}" for c in coords]
        velocities = [f"{c}_dot" for c in coords]
        state = set(coords) | set(momenta) | set(velocities)
        for name, value in self.params.items():
            if not _usable(name) or name in state:
                raise _problem(f"params.{name}", "a constant's name " + rule + " and not a "
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
            if not _usable(name) or name in state or name in self.params:
                raise _problem(f"observables.{name}", "an observable's name " + rule + " and "
                               "not a coordinate, momentum, velocity or constant", text)
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


class HamiltonianScene(Scene):
    kind = "hamiltonian"
    order = 95
    summary = "any system written as H(q, p, t) or L(q, q̇, t): derived, compiled, checked"
    Config = HamiltonianConfig
    study_horizon_reason = (f"it covers at most {STUDY_STEPS} steps of the main run, since "
                            "long runs would spend most of their time on references, and in a "
                            "chaotic system errors that have grown to the size of the orbit "
                            "compare nothing.")
    presets = {
        # V = −k/r in spherical coordinates: H separates as W_r(r) + W_θ(θ) + p_φ φ
        "central_potential": {
            "params": {"m": 1.0, "k": 1.0},
            "system": {"coordinates": ["r", "theta", "phi"], "H": _hj.CENTRAL_H},
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
            "system": {"coordinates": ["xi", "eta"], "H": _hj.TWO_CENTRES_H},
            "hamilton_jacobi": {"separation": "two_centres"},
            "initial": {"xi": 0.8, "eta": 1.0, "p_xi": 0.0, "p_eta": 0.6},
            "run": {"t_end": 40.0}},
    }
    sections = (
        Section("equations", "The system and its equations of motion"),
        Section("trajectory", "Trajectory", integrates=True),
        Section("phase_portrait", "Phase portrait", integrates=True),
        Section("poincare", "Surface of section", integrates=True),
        Section("invariants", "Conserved quantities", integrates=True),
        Section("brackets", "Poisson brackets and symmetries", integrates=True),
        Section("transform", "Canonical transformation", integrates=True),
        Section("hamilton_jacobi", "Hamilton–Jacobi: the separated quadrature solution",
                integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    family_sections = (
        Section("poincare_family", "Surface of section from many orbits",
                description="The crossings of every member's orbit on one surface of "
                            "section, each orbit coloured by its swept value.",
                points="poincare"),
    )

    SWEEP_HIDDEN_RESULTS = ("jacobi_*", "poisson_*_max", "legendre_*", "study_t_end",
                            "initial_state_*")  # shown by name: initial_<column>

    #: phase-portrait grid points per axis (one degree of freedom)
    PHASE_GRID = 241
    #: grid points per axis of H on the surface of section (its allowed region's edge)
    SECTION_GRID = 301
    #: members of a sweep told apart by a legend; more get a colour bar
    LEGEND_MEMBERS = 7
    #: fewest crossings for a surface of section to be shown without being asked for
    MIN_CROSSINGS = 20
    #: equations whose TeX is longer than this are not typeset (unreadably small)
    LONGEST_EQUATION = 320
    #: samples of the configuration-space path drawn
    CONFIGURATION_SAMPLES = 5000
    #: samples the Jacobi identity is checked on
    JACOBI_SAMPLES = 200

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        a = data.analysis
        if "phase_grid" not in a:
            names.remove("phase_portrait")
        if "transform" not in a:
            names.remove("transform")
        if "hamilton_jacobi" not in a:
            names.remove("hamilton_jacobi")
        # a surface of section says something only with enough crossings (a closed orbit
        # crosses it at a few fixed points), unless the config asked for one
        if "poincare" not in a or (len(a["poincare"]["u"]) < cls.MIN_CROSSINGS
                                   and data.config.section is None):
            names.remove("poincare")
        return names

    # ----------------------------------------------------------------- helpers
    def system(self):
        """The parsed and derived system (memoized; SymPy work)."""
        if getattr(self, "_system", None) is None:
            cfg = self.config
            try:
                self._system = formula.build_system(
                    cfg.system.coordinates, H=cfg.system.H, L=cfg.system.L,
                    observables=cfg.observables, params=cfg.params)
            except formula.FormulaError as exc:
                from ..config import ConfigError

                raise ConfigError([f"{self.source.label}: key '{exc.key}': {exc.detail}"]) \
                    from None
        return self._system

    def models(self) -> list:
        return [formula.compiled_model(self.system(), name=self.source.name)]

    def initial_state(self) -> np.ndarray:
        """(q0, p0); for L the momenta p = ∂L/∂q̇ at (q0, q̇0, 0); with ``energy`` the left-out
        momentum or velocity solved (the root ≥ 0 of H = energy)."""
        system, ini = self.system(), dict(self.config.initial)
        space = system.space
        energy = ini.pop("energy", None)
        speeds = (space.p if system.L is None else space.qdot)
        if energy is not None:
            missing = next(s for s in speeds if s.name not in ini)
            ini[missing.name] = self._solve_energy(missing, ini, energy)
        q0 = np.array([ini[n] for n in space.names], dtype=float)
        if system.L is None:
            p0 = np.array([ini[p.name] for p in space.p], dtype=float)
        else:
            values = {**{q: ini[q.name] for q in space.q}, **{v: ini[v.name] for v in space.qdot},
                      space.t: 0.0, **{system.param_symbols[k]: v
                                       for k, v in system.params.items()}}
            p0 = np.array([float(numeric.evaluate(m, values))
                           for m in system.legendre.momenta])
        return np.concatenate([q0, p0])

    def _solve_energy(self, unknown, ini: dict, energy: float) -> float:
        from scipy.optimize import brentq

        system = self.system()
        space = system.space
        target = system.H if system.L is None else self._energy_function()

        def h(value):
            vals = {s: ini.get(s.name, 0.0) for s in space.q + space.p + space.qdot}
            vals[unknown] = value
            vals[space.t] = 0.0
            vals.update({system.param_symbols[k]: v for k, v in system.params.items()})
            return float(numeric.evaluate(target, vals)) - energy

        lo, hi = 0.0, 1.0
        if h(lo) > 0:
            from ..config import ConfigError

            raise ConfigError([f"{self.source.label}: initial.energy: {energy} is below the "
                               f"energy with {unknown.name} = 0 ({h(lo) + energy:.10g}); no "
                               "state on that energy surface"])
        while h(hi) < 0 and hi < 1e12:
            hi *= 2
        return brentq(h, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=500)

    def _energy_function(self):
        """E(q, q̇) = q̇·∂L/∂q̇ − L (Jacobi's energy function)."""
        system = self.system()
        L = system.L
        return sum(v * system.legendre.momenta[i]
                   for i, v in enumerate(system.space.qdot)) - L

    # ------------------------------------------------------------------ simulate
    def simulate(self, progress=None) -> Results:
        import sympy

        system, run = self.system(), self.config.run
        space = system.space
        t = np.linspace(0.0, run.t_end, run.samples)
        y0 = self.initial_state()
        model = self.models()[0]
        results = Results()
        a = results.analysis

        # brackets first: they decide which observables are conserved
        H = system.H
        brackets, conserved = {}, {}
        for name, f in system.observables.items():
            bracket = mechanics.poisson_bracket(space, f, H)
            brackets[name] = bracket
            total = sympy.simplify(bracket + sympy.diff(f, space.t))
            conserved[name] = total == 0
        cyclic = mechanics.cyclic_coordinates(space, H)
        h_conserved = not system.time_dependent

        def quantities(tt, y):
            vals = system.values(y, tt)
            names = (["H"] if h_conserved else []) + [n for n, c in conserved.items() if c]
            exprs = [H if n == "H" else system.observables[n] for n in names]
            out = dict(zip(names, numeric.evaluate_many(exprs, vals, shape=np.shape(tt)),
                           strict=True))
            for c in cyclic:
                out[f"p_{c}"] = np.array(y[:, space.names.index(c) + system.n])
            return out

        angles = self._angles(system)
        a["angles"] = angles
        scales = {}
        vals0 = system.values(y0[None, :], np.array([0.0]))
        h0 = float(numeric.evaluate(H, vals0)[0])
        if h_conserved:
            # the energy's scale: the largest of |H0| and its parts at p = 0 and the rest, so
            # that a zero-energy orbit is measured against its kinetic and potential energy
            v0 = float(numeric.evaluate(H.subs({p: 0 for p in space.p}), vals0)[0])
            scales["H"] = max(abs(h0), abs(v0), abs(h0 - v0), 1e-300)
        main = self.integrate(model, y0, t, invariants=quantities, progress=progress,
                              invariant_scales=scales or None)
        results.runs["main"] = main
        vals = system.values(main.y, main.t)
        # observables that are not conserved: their time series (not judged as invariants)
        moving = [n for n, c in conserved.items() if not c]
        if not h_conserved:
            moving = ["H", *moving]
        if moving:
            exprs = [H if n == "H" else system.observables[n] for n in moving]
            a["observables"] = dict(zip(moving, numeric.evaluate_many(exprs, vals,
                                                                      shape=main.t.shape),
                                        strict=True))

        # what the equations are, for the report
        latex = {"H": system.latex(H), "qdot": [system.latex(e) for e in system.hamilton.qdot],
                 "pdot": [system.latex(e) for e in system.hamilton.pdot],
                 "q": [system.latex(q) for q in space.q], "p": [system.latex(p) for p in space.p]}
        if system.L is not None:
            latex["L"] = system.latex(system.L)
            latex["momenta"] = [system.latex(m) for m in system.legendre.momenta]
            latex["velocities"] = [system.latex(v) for v in system.legendre.velocities]
        for name, f in system.observables.items():
            latex[f"observable_{name}"] = system.latex(f)
        a["latex"] = latex
        a["coordinates"] = list(space.names)
        a["given"] = "L" if system.L is not None else "H"
        a["separable"] = bool(system.separable)
        a["time_dependent"] = bool(system.time_dependent)
        a["cyclic"] = [str(c) for c in cyclic]
        a["H0"] = h0
        a["initial_state"] = y0
        for column, value in zip(system.columns, y0, strict=True):
            a[f"initial_{column}"] = float(value)  # by name: a sweep's results plot these
        for name, bracket in brackets.items():
            a[f"poisson_{name}"] = str(bracket)
            a[f"poisson_{name}_latex"] = system.latex(bracket)
            a[f"conserved_{name}"] = bool(conserved[name])
            a[f"poisson_{name}_max"] = float(np.max(np.abs(numeric.evaluate(bracket, vals))))
        self._pairwise_brackets(a, system, vals)
        if system.L is not None:
            self._legendre_checks(a, system, main)
        if system.n == 1:
            self._phase_grid(a, system, main)
        elif self.config.section is not None or system.n == 2:
            self._poincare(a, system, main)

        results.checks.append(Check("H(t_end)" if h_conserved else "H(0)",
                                    float(main.invariants["H"][-1]) if h_conserved else h0,
                                    h0, "", "H(0) of the initial state", scale=scales.get("H",
                                                                                           1.0)))
        if self.config.transform is not None:
            self._transform(results, system, main)
        if self.config.hamilton_jacobi is not None:
            self._hamilton_jacobi(a, system, main)
        # the study over at most STUDY_STEPS of the main run's steps: long (and chaotic) runs
        # would spend seconds on references, and errors that have grown to the orbit's size
        # compare nothing
        horizon = run.t_end * min(1.0, STUDY_STEPS / max(int(main.attrs["nsteps"]), 1))
        a["study_t_end"] = float(horizon)
        self.study(results, model, y0, np.linspace(0.0, horizon, 201))
        return results

    def _transform(self, results, system, main) -> None:
        """New variables along the run, the symplectic condition MᵀJM = J there, K = H +
        ∂F/∂t; where K has a closed form, K integrated from (Q0, P0) against the image."""
        import sympy

        from ..config import ConfigError

        cfg, a, n = self.config.transform, results.analysis, system.n
        numbers = {system.param_symbols[k]: v for k, v in system.params.items()}
        H = system.H.xreplace(numbers)
        try:
            ct = canonical.generating_function(system.space, cfg.formula, cfg.kind,
                                               cfg.coordinates, cfg.new_momenta(),
                                               params=system.params)
            q, p, t = main.y[:, :n], main.y[:, n:], main.t
            Q, P = canonical.new_variables(ct, q, p, t)
        except ValueError as exc:
            raise ConfigError([f"{self.source.label}: key 'transform.{cfg.kind}': {exc}"]) \
                from None
        defect = canonical.symplectic_defect(ct, q, p, Q, P, t)
        brackets = canonical.poisson_brackets(ct, q, p, Q, P, t)
        unit = np.zeros((2 * n, 2 * n))
        unit[:n, n:], unit[n:, :n] = np.eye(n), -np.eye(n)
        K_along = canonical.hamiltonian_along(ct, H, q, p, Q, P, t)
        a["transform"] = {"Q": Q, "P": P, "defect": defect, "K": K_along}
        a["transform_new"] = list(cfg.coordinates) + cfg.new_momenta()
        a["transform_latex"] = canonical.relations_latex(ct)
        a["transform_defect_max"] = float(np.max(defect))
        a["transform_bracket_max"] = float(np.max(np.abs(brackets - unit)))
        K = canonical.new_hamiltonian(ct, H)
        a["transform_K_latex"] = "" if K is None else sympy.latex(K)
        if K is None or K.free_symbols - set(ct.Q + ct.P + (system.space.t,)):
            return
        # Hamilton's equations of K, compiled like any formula system, from (Q0, P0)
        space = mechanics.PhaseSpace(tuple(cfg.coordinates), ct.Q, ct.P, (), system.space.t)
        new = formula.FormulaSystem(space, {}, {}, K, None, None,
                                    mechanics.hamiltonian_system(space, K))
        model = formula.compiled_model(new, name=f"{self.source.name}-K")
        run = self.integrate(model, np.concatenate([Q[0], P[0]]), t)
        run.reference = {c: v for c, v in zip(model.columns, np.column_stack([Q, P]).T,
                                              strict=True)}
        run.attrs["reference_label"] = "(Q, P) of the integrated H orbit"
        results.runs["transformed"] = run
        a["transform_run_difference"] = float(np.max(np.abs(run.y - np.column_stack([Q, P]))))

    def _hamilton_jacobi(self, a: dict, system, main) -> None:
        """The preset's quadrature solution against the run, and its separated constants
        along the run."""
        from ..config import ConfigError

        kind = self.config.hamilton_jacobi.separation
        prm = system.params
        # the config's H must be the one the quadrature solves: compared at random states
        text = _hj.CENTRAL_H if kind == "central" else _hj.TWO_CENTRES_H
        ref = expressions.parse_expression(text, {**system.space.symbols_for_h(),
                                                  **system.param_symbols})
        states = np.random.default_rng(7).uniform(0.3, 1.3, size=(5, 2 * system.n))
        vals = system.values(states, 0.0)
        if not np.allclose(numeric.evaluate(system.H, vals), numeric.evaluate(ref, vals),
                           rtol=1e-12, atol=1e-12):
            raise ConfigError([f"{self.source.label}: key 'hamilton_jacobi.separation': H is "
                               f"not the Hamiltonian the {kind!r} quadrature solves "
                               f"({text})"])
        y, t = main.y, main.t
        cols = list(system.columns)
        try:
            if kind == "central":
                sol = hamilton_jacobi.central_quadrature(prm["m"], prm["k"], y[0], t)
                consts = hamilton_jacobi.central_integrals(*y.T, prm["m"], prm["k"])
            else:
                sol = hamilton_jacobi.two_centres_quadrature(prm["m"], prm["mu1"], prm["mu2"],
                                                             prm["a"], y[0], t)
                consts = hamilton_jacobi.two_centres_integrals(*y.T, prm["m"], prm["mu1"],
                                                               prm["mu2"], prm["a"])
        except ValueError as exc:
            raise ConfigError([f"{self.source.label}: key 'initial': the {kind!r} quadrature "
                               f"does not apply: {exc}"]) from None
        diff = {c: np.abs(np.asarray(sol[c]) - y[:, cols.index(c)]) for c in cols}
        a["hamilton_jacobi"] = {"solution": {c: np.asarray(sol[c]) for c in cols},
                                "difference": diff,
                                "constants": {k: np.asarray(v) for k, v in consts.items()}}
        a["hj_separation"] = kind
        a["hj_max_difference"] = float(max(np.max(d) for d in diff.values()))
        a["hj_constants"] = {k: float(np.asarray(v)[0]) for k, v in consts.items()}
        a["hj_constant_drift"] = {
            k: float(np.max(np.abs(np.asarray(v) - np.asarray(v)[0]))
                     / max(abs(float(np.asarray(v)[0])), 1e-300)) for k, v in consts.items()}

    @staticmethod
    def _angles(system) -> list[str]:
        """The coordinates H depends on 2π-periodically (checked at random states): angles,
        drawn wrapped to (−π, π] in the phase portrait and the surface of section."""
        rng = np.random.default_rng(11)
        states = rng.uniform(-1.0, 1.0, size=(6, 2 * system.n))
        base = numeric.evaluate(system.H, system.values(states, 0.3))
        found = []
        for i, (name, q) in enumerate(zip(system.space.names, system.space.q, strict=True)):
            if q not in system.H.free_symbols:
                continue
            shifted = states.copy()
            shifted[:, i] += 2 * np.pi
            moved = numeric.evaluate(system.H, system.values(shifted, 0.3))
            if np.all(np.isfinite(base)) and np.allclose(moved, base, rtol=1e-11, atol=1e-12):
                found.append(name)
        return found

    def _pairwise_brackets(self, a: dict, system, vals) -> None:
        """{f, g} between observables, and the Jacobi identity on a sample of the run."""
        space = system.space
        names = list(system.observables)
        rows = []
        for i, f in enumerate(names):
            for g in names[i + 1:]:
                bracket = mechanics.poisson_bracket(space, system.observables[f],
                                                    system.observables[g])
                rows.append([f, g, str(bracket), system.latex(bracket)])
        if rows:
            a["pair_brackets"] = {"f": [r[0] for r in rows], "g": [r[1] for r in rows],
                                  "bracket": [r[2] for r in rows]}
        # Jacobi: {f,{g,h}} + {g,{h,f}} + {h,{f,g}} = 0 for f, g from the observables (or q1,
        # p1) and h = H; evaluated, not simplified
        # the first pair whose terms do not all vanish (two conserved observables, or
        # {q, p} with a separable H, would check nothing): observables, then cubics
        q1, p1, qn, pn = space.q[0], space.p[0], space.q[-1], space.p[-1]
        obs = [system.observables[n] for n in names]
        cubic_f, cubic_g = q1**2 * pn + p1, p1**2 * qn + q1 * pn
        candidates = ([(obs[0], obs[1])] if len(obs) > 1 else []) \
            + ([(obs[0], cubic_g)] if obs else []) + [(cubic_f, cubic_g)]
        h = system.H

        def pb(u, v):
            return sum(u.diff(q) * v.diff(p) - u.diff(p) * v.diff(q)
                       for q, p in zip(space.q, space.p, strict=True))

        n = len(vals[space.t])
        pick = np.unique(np.linspace(0, n - 1, min(n, self.JACOBI_SAMPLES)).astype(int))
        sample = {s: (v[pick] if np.ndim(v) else v) for s, v in vals.items()}
        for f, g in candidates:
            terms = (pb(f, pb(g, h)), pb(g, pb(h, f)), pb(h, pb(f, g)))
            scale = sum(float(np.max(np.abs(numeric.evaluate(term, sample)))) for term in terms)
            if scale > 0:
                break
        a["jacobi_max"] = float(np.max(np.abs(numeric.evaluate(sum(terms), sample))))
        a["jacobi_scale"] = scale
        a["jacobi_triple"] = [str(f), str(g), "H"]

    def _legendre_checks(self, a: dict, system, main) -> None:
        """Along the run: p = ∂L/∂q̇ at q̇(q, p), and H = q̇·∂L/∂q̇ − L (Jacobi's energy)."""
        space = system.space
        vals = system.values(main.y, main.t)
        qdot = numeric.evaluate_many(system.legendre.velocities, vals, shape=main.t.shape)
        vals.update(dict(zip(space.qdot, qdot, strict=True)))
        p_back = numeric.evaluate_many(system.legendre.momenta, vals, shape=main.t.shape)
        a["legendre_momentum_error"] = float(max(np.max(np.abs(pb - vals[p]))
                                                 for pb, p in zip(p_back, space.p, strict=True)))
        energy = numeric.evaluate(self._energy_function(), vals)
        h = numeric.evaluate(system.H, vals)
        a["legendre_energy_error"] = float(np.max(np.abs(energy - h)))
        a["legendre_energy_scale"] = float(np.max(np.abs(h)))

    def _phase_grid(self, a: dict, system, main) -> None:
        """H on a grid around the orbit (the portrait's level curves)."""
        q, p = main.y[:, 0], main.y[:, 1]
        pad_q = max(0.5 * float(np.ptp(q)), 0.5)
        pad_p = max(0.5 * float(np.ptp(p)), 0.5)
        gq = np.linspace(float(np.min(q)) - pad_q, float(np.max(q)) + pad_q, self.PHASE_GRID)
        if system.space.names[0] in a["angles"]:  # an angle: one period, the orbit wrapped
            gq = np.linspace(-np.pi, np.pi, self.PHASE_GRID)
        gp = np.linspace(float(np.min(p)) - pad_p, float(np.max(p)) + pad_p, self.PHASE_GRID)
        Q, P = np.meshgrid(gq, gp)
        space = system.space
        vals = {space.q[0]: Q, space.p[0]: P, space.t: 0.0,
                **{system.param_symbols[k]: v for k, v in system.params.items()}}
        a["phase_grid"] = {"q": gq, "p": gp, "H": numeric.evaluate(system.H, vals)}

    def _poincare(self, a: dict, system, main) -> None:
        """Crossings of the surface of section, located by cubic Hermite interpolation
        between samples (the derivatives from Hamilton's equations)."""
        cfg = self.config.section
        columns = list(system.columns)
        n = system.n
        if cfg is None:
            s_col, value, direction = columns[0], 0.0, "up"
            axes = [columns[1], columns[n + 1]]
        else:
            s_col, value, direction = cfg.coordinate, cfg.value, cfg.direction
            axes = list(cfg.axes) if cfg.axes else [c for c in columns[:n] if c != s_col][:1]
            if not cfg.axes:
                axes.append(f"p_{axes[0]}")
        vals = system.values(main.y, main.t)
        ydot = np.column_stack(numeric.evaluate_many(system.hamilton.rhs, vals,
                                                     shape=main.t.shape))
        # every column at the crossings: the whole state there, u and v among them
        points = section_crossings(main.t, main.y, ydot, columns.index(s_col), value, direction,
                                   list(range(len(columns))))
        times, state = points[:, 0], points[:, 1:]
        u, v = state[:, columns.index(axes[0])], state[:, columns.index(axes[1])]
        wrap = [name in a["angles"] for name in axes]
        if wrap[0]:
            u = _wrapped(u)
        if wrap[1]:
            v = _wrapped(v)
        a["poincare"] = {"t": times, "u": u, "v": v, "state": state}
        a["poincare_surface"] = [s_col, f"{value!r}", direction]
        a["poincare_axes"] = axes
        if not system.time_dependent and len(times):
            # the crossings lie on the run's energy surface up to the interpolation error
            H = numeric.evaluate(system.H, system.values(state, times))
            a["poincare_H_error"] = float(np.max(np.abs(H - a["H0"])))

    # ------------------------------------------------------------------ sweeps
    @staticmethod
    def member_points(results) -> dict[str, PointSet]:
        """A member's crossings of the surface of section: time, the two plotted columns
        (angles wrapped) and the whole state there."""
        a = results.analysis
        pts = a.get("poincare")
        if pts is None:
            return {}
        surface, axes = a["poincare_surface"], a["poincare_axes"]
        return {"poincare": PointSet(
            columns={"t": pts["t"], "u": pts["u"], "v": pts["v"], "state": pts["state"]},
            components=tuple(results.runs["main"].columns),
            attrs={"surface": list(surface), "axes": list(axes)})}

    def sweep_extras(self, sweep) -> dict:
        """The edge of the section's allowed region when every member has one energy E:
        H on a grid of the two plotted columns, the surface's coordinate at its value and
        the remaining momentum zero (so the crossings lie inside H ≤ E there)."""
        pts = sweep.points.get("poincare")
        energy = self._family_energy(sweep)
        system = self.system()
        if pts is None or not len(pts.member) or energy is None or system.n != 2 \
                or any(not p.startswith("initial.") for p in sweep.values):
            return {}  # one H and one energy for all members, or no common edge
        s_col, value, _ = pts.attrs["surface"]
        axes = list(pts.attrs["axes"])
        columns = list(system.columns)
        rest = [c for c in columns if c not in (s_col, *axes)]
        if len(rest) != 1 or rest[0] not in columns[system.n:] \
                or set(axes) & set(self._angles(system)):
            return {}  # the edge is where a momentum vanishes, in unwrapped columns

        def span(x):
            lo, hi = float(np.min(x)), float(np.max(x))
            pad = 0.08 * max(hi - lo, 1e-9)
            return np.linspace(lo - pad, hi + pad, self.SECTION_GRID)

        gu, gv = span(pts.columns["u"]), span(pts.columns["v"])
        U, V = np.meshgrid(gu, gv)
        state = np.zeros((U.size, len(columns)))
        state[:, columns.index(s_col)] = float(value)
        state[:, columns.index(axes[0])] = U.ravel()
        state[:, columns.index(axes[1])] = V.ravel()
        H = numeric.evaluate(system.H, system.values(state, 0.0))
        return {"poincare_edge": {"u": gu, "v": gv, "H": np.reshape(H, U.shape)},
                "poincare_edge_energy": energy, "poincare_edge_momentum": rest[0]}

    @staticmethod
    def _family_energy(sweep) -> float | None:
        """The members' common energy H(0), or None if they differ (beyond rounding)."""
        h0 = np.asarray(sweep.analysis.get("H0", []), dtype=float)
        h0 = h0[sweep.ok & np.isfinite(h0)] if h0.size else h0
        if h0.size == 0 or np.ptp(h0) > 1e-12 * max(float(np.max(np.abs(h0))), 1.0):
            return None
        return float(np.median(h0))

    def sweep_checks(self, sweep) -> list[Check]:
        """The member whose H(0) is furthest from the configured energy (the left-out
        momentum is solved for each member so that H = energy)."""
        h0 = sweep.analysis.get("H0")
        given = self.config.initial.get("energy")
        energy = sweep.values.get("initial.energy")
        if h0 is None or (given is None and energy is None):
            return []
        energy = energy if energy is not None else np.full(sweep.size, float(given))
        gap = np.where(sweep.ok, np.abs(h0 - energy), np.nan)
        if not np.any(np.isfinite(gap)):
            return []
        i = int(np.nanargmax(gap))
        return [Check(f"H(0) of the member furthest from its energy ({member_text(sweep, i)})",
                      float(h0[i]), float(energy[i]), "",
                      "initial.energy (the left-out momentum solved so that H = energy)",
                      scale=max(abs(float(energy[i])), 1e-300))]

    @classmethod
    def section_poincare_family(cls, data):
        sweep, a = data.sweep, data.analysis
        pts = sweep.points["poincare"]
        s_col, value, direction = pts.attrs["surface"]
        uname, vname = pts.attrs["axes"]
        member = np.asarray(pts.member)
        kept = pts.counts(sweep.size)
        crossing, key, colour, labels = section_colours(sweep, pts, cls.LEGEND_MEMBERS)
        edge = a.get("poincare_edge")
        fig = section_plots.poincare_family(
            pts.columns["u"], pts.columns["v"], member, colour, uname, vname,
            colour_label=key, labels=labels,
            edge=None if edge is None else (edge["u"], edge["v"], edge["H"],
                                            a["poincare_edge_energy"]),
            edge_label=None if edge is None else
            f"{a['poincare_edge_momentum']} = 0 on H = {fmt(a['poincare_edge_energy'], 6)}")
        which = {"up": f"with {s_col} increasing", "down": f"with {s_col} decreasing",
                 "both": "in either direction"}[direction]
        facts = [("orbits", f"{len(crossing)} of {sweep.size} members cross the surface"),
                 ("crossings drawn", f"{len(member)} ({int(kept[crossing].min())} to "
                                     f"{int(kept[crossing].max())} per orbit)")]
        h_error = sweep.analysis.get("poincare_H_error")
        if h_error is not None and np.any(np.isfinite(h_error)):
            facts.append(("max |H − H(0)| at the crossings, over the members",
                          fmt_err(float(np.nanmax(h_error)))))
        energy = cls._family_energy(sweep)
        if energy is not None:
            facts.append(("energy of every orbit", f"H = {fmt(energy, 12)}"))
        notes = ["A regular (quasi-periodic) orbit crosses the surface on a closed curve: an "
                 "island around a stable periodic orbit or a curve across the section; a "
                 "chaotic orbit scatters over an area, the chaotic sea between the islands."]
        notes += section_point_notes(sweep, "poincare", kept, "cross the surface")
        caption = (f"Surface of section {s_col} = {value} crossed {which}: ({uname}, {vname}) "
                   f"at the crossings of {len(crossing)} orbits, each orbit in its own colour "
                   + (f"(keyed to {key})" if labels is None else "(legend)")
                   + (f"; the closed curve: the edge of the allowed region, where "
                      f"{a['poincare_edge_momentum']} = 0" if edge is not None else "") + ".")
        return SectionContent(figures=[cls.figure("poincare_family", fig, caption)],
                              facts=facts, notes=notes)

    # ------------------------------------------------------------------ report side
    @classmethod
    def headline(cls, data):
        a = data.analysis
        run = data.runs.get("main")
        facts = [("system", f"{'L' if a['given'] == 'L' else 'H'} in "
                            f"{', '.join(a['coordinates'])} ({len(a['coordinates'])} degree"
                            f"{'s' if len(a['coordinates']) > 1 else ''} of freedom"
                            f"{', separable' if a['separable'] else ''})"),
                 ("H(0)", fmt(a["H0"], 14))]
        if run is not None and "drift_H" in run.attrs:
            facts.append(("relative drift of H", fmt_err(run.attrs["drift_H"])))
        conserved = [k[len("conserved_"):] for k, v in a.items()
                     if k.startswith("conserved_") and v]
        if conserved:
            facts.append(("conserved observables", ", ".join(conserved)))
        return facts

    @classmethod
    def section_equations(cls, data):
        a = data.analysis
        tex = a["latex"]
        eqs = []
        if a["given"] == "L":
            eqs.append(("Lagrangian", f"L = {tex['L']}"))
            for q, m in zip(tex["q"], tex["momenta"], strict=True):
                eqs.append((f"momentum conjugate to {q}", rf"p_{{{q}}} = {m}"))
            for q, v in zip(tex["q"], tex["velocities"], strict=True):
                eqs.append(("velocity", rf"\dot{{{q}}} = {v}"))
        eqs.append(("Hamiltonian", f"H = {tex['H']}"))
        long = []
        for i, (q, e) in enumerate(zip(tex["q"], tex["qdot"], strict=True)):
            if len(e) > cls.LONGEST_EQUATION:
                long.append(f"q̇ of {q}")
                continue
            eqs.append(("Hamilton's equations: q̇ = ∂H/∂p" if i == 0 else "",
                        rf"\dot{{{q}}} = {e}"))
        for i, (p, e) in enumerate(zip(tex["p"], tex["pdot"], strict=True)):
            if len(e) > cls.LONGEST_EQUATION:
                long.append(f"ṗ of {p}")
                continue
            eqs.append(("ṗ = −∂H/∂q" if i == 0 else "", rf"\dot{{{p}}} = {e}"))
        for i, name in enumerate(k[len("observable_"):] for k in tex if k.startswith("observable_")):
            eqs.append(("observables" if i == 0 else "", f"{name} = {tex['observable_' + name]}"))
        facts = [("H separable (T(p) + V(q))", "yes: symplectic splitting methods apply"
                  if a["separable"] else "no"),
                 ("H depends on t", "yes: H is not conserved" if a["time_dependent"] else "no")]
        if a["given"] == "L":
            facts.append(("max |p − ∂L/∂q̇| along the run",
                          fmt_err(a["legendre_momentum_error"])))
            facts.append(("max |H − (q̇·∂L/∂q̇ − L)| along the run",
                          f"{fmt_err(a['legendre_energy_error'])} (|H| ≤ "
                          f"{fmt(a['legendre_energy_scale'], 4)})"))
        notes = [f"Too long to read when typeset, and not shown: {', '.join(long)} (the "
                 "derivatives of H above; their TeX is in the archive, /analysis/latex)."] \
            if long else []
        return SectionContent(facts=facts, equations=eqs, notes=notes)

    @classmethod
    def section_trajectory(cls, data):
        run = data.runs["main"]
        names = list(data.analysis["coordinates"])
        figs = [cls.figure("coordinates", plots.coordinates(run.t, {n: run[n] for n in names}),
                           "The coordinates against time.")]
        if len(names) >= 2:
            # a long path fills its region with ink: the first CONFIGURATION_SAMPLES show it
            n = min(len(run.t), cls.CONFIGURATION_SAMPLES)
            part = ("" if n == len(run.t) else
                    f", for t ≤ {fmt(float(run.t[n - 1]), 4)} (of {fmt(float(run.t[-1]), 6)})")
            figs.append(cls.figure("configuration", plots.configuration(
                run[names[0]][:n], run[names[1]][:n], names[0], names[1]),
                f"The path in the ({names[0]}, {names[1]}) plane of configuration space{part}."))
        return SectionContent(figures=figs)

    @classmethod
    def section_phase_portrait(cls, data):
        run = data.runs["main"]
        a = data.analysis
        q = a["coordinates"][0]
        grid = a["phase_grid"]
        fig = plots.phase_portrait(run[q], run[f"p_{q}"], grid["q"], grid["p"], grid["H"],
                                   a["H0"], q, angle=q in list(a.get("angles", [])))
        return SectionContent(figures=[cls.figure(
            "phase_portrait", fig, f"Level curves of H in the ({q}, p_{q}) plane; the run's "
                                   "orbit on its level H = H(0) (highlighted).")])

    @classmethod
    def section_poincare(cls, data):
        a = data.analysis
        pts = a["poincare"]
        s_col, value, direction = a["poincare_surface"]
        u, v = a["poincare_axes"]
        fig = plots.poincare(pts["u"], pts["v"], u, v)
        which = {"up": f"with {s_col} increasing", "down": f"with {s_col} decreasing",
                 "both": "in either direction"}[direction]
        return SectionContent(
            figures=[cls.figure("poincare", fig,
                                f"Surface of section {s_col} = {value} crossed {which}: "
                                f"({u}, {v}) at each of the {len(pts['u'])} crossings.")],
            facts=[("crossings", str(len(pts["u"])))],
            notes=["A regular (quasi-periodic) orbit crosses the surface on a closed curve; a "
                   "chaotic one scatters over an area. Crossings are located between stored "
                   "samples by cubic Hermite interpolation with the derivatives from "
                   "Hamilton's equations."] if len(pts["u"]) else
                  ["The orbit did not cross the surface of section during the run."])

    @classmethod
    def section_invariants(cls, data):
        a = data.analysis
        content = cls.invariants_section(
            data, caption="Relative drift of H and of every conserved quantity: observables "
                          "whose total time derivative {f, H} + ∂f/∂t simplifies to zero, and "
                          "the momenta of cyclic coordinates.")
        moving = a.get("observables")
        if moving:
            run = data.runs["main"]
            content.figures.append(cls.figure(
                "observables", plots.observables(run.t, moving),
                "Observables that are not conserved ({f, H} + ∂f/∂t ≠ 0), against time."))
        return content

    @classmethod
    def section_brackets(cls, data):
        a = data.analysis
        rows = []
        for key, value in a.items():
            if key.startswith("poisson_") and not key.endswith(("_latex", "_max")):
                name = key[len("poisson_"):]
                rows.append([name, value, "yes" if a[f"conserved_{name}"] else "no",
                             fmt_err(a[f"poisson_{name}_max"])])
        tables = []
        if rows:
            tables.append(Table(
                caption="{f, H} = Σ ∂f/∂q ∂H/∂p − ∂f/∂p ∂H/∂q, simplified by SymPy (archived as "
                        "/analysis attrs poisson_<name>); conserved when {f, H} + ∂f/∂t = 0. "
                        "The last column evaluates {f, H} along the run.",
                header=["observable f", "{f, H}", "conserved", "max |{f, H}| on the run"],
                rows=rows))
        pairs = a.get("pair_brackets")
        if pairs:
            tables.append(Table(caption="Brackets between the observables, simplified.",
                                 header=["f", "g", "{f, g}"],
                                 rows=[list(r) for r in zip(pairs["f"], pairs["g"],
                                                            pairs["bracket"], strict=True)]))
        cyclic = list(a["cyclic"])
        f, g, h = a["jacobi_triple"]
        facts = [("cyclic coordinates", ", ".join(cyclic) + " (their momenta "
                  + ", ".join(f"p_{c}" for c in cyclic) + " are conserved)" if cyclic
                  else "none"),
                 ("Jacobi identity {f,{g,h}} + {g,{h,f}} + {h,{f,g}}",
                  f"max {fmt_err(a['jacobi_max'])} on {cls.JACOBI_SAMPLES} samples of the run "
                  f"(terms up to {fmt(a['jacobi_scale'], 3)}), f = {f}, g = {g}, h = {h}")]
        return SectionContent(facts=facts, tables=tables)


    @classmethod
    def section_transform(cls, data):
        a = data.analysis
        tr = a["transform"]
        new = list(a["transform_new"])
        n = len(new) // 2
        run = data.runs.get("transformed")
        series = {new[i]: tr["Q"][:, i] for i in range(n)}
        series.update({new[n + i]: tr["P"][:, i] for i in range(n)})
        fig = plots.new_variables(data.runs["main"].t, series,
                                  run[new[0]] if run is not None else None, new[0])
        eqs = [("generating function and relations" if i == 0 else "", line)
               for i, line in enumerate(a["transform_latex"])]
        if a["transform_K_latex"]:
            eqs.append(("K in the new variables", f"K = {a['transform_K_latex']}"))
        facts = [("max |MᵀJM − J| along the run (M = ∂(Q, P)/∂(q, p))",
                  fmt_err(a["transform_defect_max"])),
                 ("max |{Qᵢ, Pⱼ} − δᵢⱼ|, |{Qᵢ, Qⱼ}|, |{Pᵢ, Pⱼ}|",
                  fmt_err(a["transform_bracket_max"]))]
        if run is not None:
            facts.append(("max |(Q, P) from integrating K − (Q, P) of the H orbit|",
                          fmt_err(a["transform_run_difference"])))
        else:
            facts.append(("K in closed form", "not found (the old variables are not linear "
                          "in the new ones); K = H + ∂F/∂t is evaluated along the run"))
        caption = ("The new variables along the integrated orbit" +
                   (f"; dashed: {new[0]} from integrating K's own Hamilton equations from "
                    "(Q0, P0)." if run is not None else "."))
        return SectionContent(figures=[cls.figure("new_variables", fig, caption)],
                              equations=eqs, facts=facts)

    @classmethod
    def section_hamilton_jacobi(cls, data):
        a = data.analysis
        hj = a["hamilton_jacobi"]
        run = data.runs["main"]
        fig = common_plots.error_against_time(
            run.t, {f"|{c}_HJ − {c}|": d for c, d in hj["difference"].items()},
            time_unit="time units", ylabel="quadrature − integration")
        rows = [[k, fmt(v, 14), fmt_err(a["hj_constant_drift"][k])]
                for k, v in a["hj_constants"].items()]
        which = ("Kepler's equation for t(r) (∂W/∂E), the argument of latitude (∂W/∂L) and the "
                 "node (∂W/∂L_z)" if a["hj_separation"] == "central" else
                 "Charlier's quadratures in the fictitious time dt = m a²(cosh²ξ − cos²η) dτ, "
                 "each coordinate through its turning points")
        return SectionContent(
            figures=[cls.figure("hj_difference", fig,
                                f"The quadrature solution ({which}) minus the integration.")],
            tables=[Table(caption="The separated constants at t = 0 and their relative drift "
                                  "along the integration.",
                          header=["constant", "value", "max relative drift"], rows=rows)],
            facts=[("max |quadrature − integration|", fmt_err(a["hj_max_difference"]))])


def _wrapped(angle):
    """Angles to (−π, π]."""
    return np.pi - np.mod(np.pi - np.asarray(angle), 2 * np.pi)


def section_crossings(t, y, ydot, column: int, value: float, direction: str,
                      axes: list[int]) -> np.ndarray:
    """Rows (t, u, v, ...) where ``y[:, column]`` crosses ``value``, with u, v, ... the
    ``axes`` columns there; each crossing located by Newton on the cubic Hermite
    interpolant of the interval (derivatives ``ydot``), the other columns interpolated the
    same way.  Shape (crossings, 1 + len(axes))."""
    s = y[:, column] - value
    if direction == "up":
        idx = np.nonzero((s[:-1] < 0) & (s[1:] >= 0))[0]
    elif direction == "down":
        idx = np.nonzero((s[:-1] > 0) & (s[1:] <= 0))[0]
    else:
        idx = np.nonzero(np.sign(s[:-1]) * np.sign(s[1:]) < 0)[0]
    h = t[idx + 1] - t[idx]

    def hermite(col, x):
        y0, y1 = y[idx, col], y[idx + 1, col]
        d0, d1 = ydot[idx, col] * h, ydot[idx + 1, col] * h
        h00 = 2 * x**3 - 3 * x**2 + 1
        h10 = x**3 - 2 * x**2 + x
        h01 = -2 * x**3 + 3 * x**2
        h11 = x**3 - x**2
        return h00 * y0 + h10 * d0 + h01 * y1 + h11 * d1

    def slope(col, x):
        y0, y1 = y[idx, col], y[idx + 1, col]
        d0, d1 = ydot[idx, col] * h, ydot[idx + 1, col] * h
        return ((6 * x**2 - 6 * x) * y0 + (3 * x**2 - 4 * x + 1) * d0
                + (-6 * x**2 + 6 * x) * y1 + (3 * x**2 - 2 * x) * d1)

    # start from the secant, then Newton on the interpolant, kept inside [0, 1]
    x = np.clip(-s[idx] / np.where(s[idx + 1] != s[idx], s[idx + 1] - s[idx], 1.0), 0.0, 1.0)
    for _ in range(8):
        d = slope(column, x)
        step = np.where(d != 0, (hermite(column, x) - value) / np.where(d != 0, d, 1.0), 0.0)
        x = np.clip(x - step, 0.0, 1.0)
    return np.column_stack([t[idx] + x * h, *(hermite(c, x) for c in axes)]) \
        if len(idx) else np.empty((0, 1 + len(axes)))

