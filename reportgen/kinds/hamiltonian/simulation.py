"""``hamiltonian`` simulation: the formula parsed and derived with SymPy, compiled and
integrated; the Poisson brackets, conserved quantities, the phase portrait or surface of
section, a canonical transformation, the Hamilton–Jacobi quadrature solution and the
surface of section of a sweep's many orbits."""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from ...scene.content import member_text
from ...scene.integration import IntegratingSimulation
from ...scene.results import Check, Results
from ...scene.schema import ResultsSchema
from ...scene.sweep import PointSet
from .analysis import HamiltonianAnalysis
from .config import STUDY_STEPS, HamiltonianConfig, family_energy
from .legendre_geometry import legendre_geometry
from .point_transform import PointTransformSimulation
from .results import SCHEMA, schema_for
from .structure import HamiltonianStructure

expressions = lazy_module("reportgen.core.expressions")
formula = lazy_module("reportgen.core.formula")
integrators = lazy_module("reportgen.core.integrators")
numeric = lazy_module("reportgen.core.numeric")
mechanics = lazy_module("reportgen.core.mechanics")
canonical = lazy_module("reportgen.core.canonical")
hamilton_jacobi = lazy_module("reportgen.core.hamilton_jacobi")
lyapunov = lazy_module("reportgen.core.lyapunov")

def vanishes_for(system, expr) -> bool:
    """Whether ``expr`` (a rate df/dt) simplifies to zero for this system: with its named
    constants as symbols, or else at their values taken exactly (each float as the binary
    rational it is), so that L_z of an oscillator with ω_x = ω_y written as two constants
    is found conserved (the threshold: exactly zero, no tolerance)."""
    import sympy

    if sympy.simplify(expr) == 0:
        return True
    exact = {system.param_symbols[k]: sympy.Rational(v) for k, v in system.params.items()}
    return bool(exact) and sympy.simplify(expr.xreplace(exact)) == 0


def invariant_scales(system, quantities: dict, cyclic, vals) -> dict[str, float]:
    """The scale each conserved quantity's drift is measured against, along the run
    (``vals``: the run's values): for an observable (or a charge), the largest size of its
    terms, Σ|term| (:func:`~reportgen.core.mechanics.roundoff_scale`), so that one that
    starts at 0 (a total momentum) is judged against the momenta it is built from, never
    against its own round-off; for the momentum of a cyclic coordinate, the largest
    |momentum| of the run (the system's own momentum scale)."""
    out = {}
    for name, expr in quantities.items():
        size = np.max(mechanics.roundoff_scale(expr, vals))
        out[name] = max(float(size), 1e-300)
    if cyclic:
        momenta = np.stack([np.abs(np.broadcast_to(vals[p], np.shape(vals[system.space.t])))
                            for p in system.space.p])
        out.update({f"p_{c}": max(float(np.max(momenta)), 1e-300) for c in cyclic})
    return out


class HamiltonianSimulation(HamiltonianStructure, PointTransformSimulation, HamiltonianAnalysis,
                            IntegratingSimulation):
    """A system given as H(q, p, t) or L(q, q̇, t): derived, compiled, integrated, checked."""

    schema = SCHEMA
    config: HamiltonianConfig
    #: the transform as geometry (notes (4.15)–(4.28): the unit sphere, then L's surface) is
    #: a lecture on its own: computed only for a scene whose [report] sections name it
    computed_on_request = ("error_vs_runtime", "legendre_geometry")

    def computes(self, name: str) -> bool:
        if name == "legendre_geometry":
            asked = self.config.report.sections
            return asked is not None and name in asked
        return super().computes(name)

    #: grid points per axis of H on the surface of section (its allowed region's edge)
    SECTION_GRID = 301
    #: the left-out momentum or velocity of ``initial.energy`` is sought in [0, this]
    ENERGY_SEARCH_MAX = 1e12

    def results_schema(self) -> ResultsSchema:
        """The schema with this config's columns, invariants and observables, each
        coordinate's symbol as SymPy typesets it (``p_theta`` -> ``p_{\\theta}``)."""
        import sympy

        cfg = self.config
        coords = list(cfg.system.coordinates)
        new = [] if cfg.transform is None else (cfg.transform.new_coordinates(coords)
                                                 + cfg.transform.new_momenta(coords))
        return schema_for(cfg.system.coordinates, cfg.observables, new,
                          tex=lambda name: sympy.latex(sympy.Symbol(name)),
                          noether=cfg.noether is not None)

    def budget_schema(self) -> ResultsSchema:
        """:meth:`results_schema` from the config alone: names for symbols, and Hamilton's
        columns (a first-order L stores fewer), for the archive's budget."""
        cfg = self.config
        coords = list(cfg.system.coordinates)
        new = [] if cfg.transform is None else (cfg.transform.new_coordinates(coords)
                                                 + cfg.transform.new_momenta(coords))
        return schema_for(coords, cfg.observables, new, noether=cfg.noether is not None)

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
                from ...scene.config import ConfigError

                raise ConfigError([f"{self.source.label}: key '{exc.key}': {exc.detail}"]) \
                    from None
        return self._system

    def models(self) -> list:
        return [formula.compiled_model(self.system(), name=self.source.name)]

    def build_models(self) -> None:
        """As every kind's, and with ``initial.energy`` the left-out momentum or velocity
        solved, so that an energy no state reaches is refused before anything runs; an L
        is Legendre-transformed (SymPy, nothing integrated), so a singular one is refused too."""
        super().build_models()
        if self.config.system.L is not None:
            self.system()
        if self.config.point_transform is not None:  # a singular Jacobian is refused here
            self._point_start()
        if "energy" in self.config.initial:
            ini = dict(self.config.initial)
            energy = ini.pop("energy")
            space = self.system().space
            speeds = space.p if self.system().L is None else space.qdot
            missing = next(s for s in speeds if s.name not in ini)
            self._solve_energy(missing, ini, energy, solve=False)

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

    def _solve_energy(self, unknown, ini: dict, energy: float, solve: bool = True) -> float:
        """The value of ``unknown`` that gives ``energy`` (ConfigError if none is reached);
        ``solve=False`` only checks that one is bracketed (``validate``: no scipy.optimize)."""
        system = self.system()
        space = system.space
        target = system.H if system.L is None else self._energy_function()

        def energy_at(value):
            vals = {s: ini.get(s.name, 0.0) for s in space.q + space.p + space.qdot}
            vals[unknown] = value
            vals[space.t] = 0.0
            vals.update({system.param_symbols[k]: v for k, v in system.params.items()})
            return float(np.ravel(numeric.evaluate(target, vals))[0])

        def h(value):
            return energy_at(value) - energy

        from ...scene.config import ConfigError

        where = f"{self.source.label}: key 'initial.energy'"
        lo, hi = 0.0, 1.0
        low = energy_at(lo)
        if not np.isfinite(low):
            raise ConfigError([f"{where}: the energy with {unknown.name} = 0 is not finite "
                               f"({low}); no state to start from"])
        if low > energy:
            raise ConfigError([f"{where}: {energy:.10g} is below the energy with "
                               f"{unknown.name} = 0 ({low:.10g}); no state on that energy "
                               "surface"])
        highest, reached = low, lo
        while True:
            top = energy_at(hi)
            if not np.isfinite(top) or top >= energy or hi >= self.ENERGY_SEARCH_MAX:
                break
            highest, reached = max(highest, top), hi
            hi *= 2
        if not (np.isfinite(top) and top >= energy):
            raise ConfigError([f"{where}: {energy:.10g} is not reachable: with "
                               f"{unknown.name} from 0 to {reached:.3g} the energy ranges over "
                               f"[{low:.10g}, {highest:.10g}]"])
        if not solve:
            return hi
        from scipy.optimize import brentq

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
            conserved[name] = vanishes_for(system, bracket + sympy.diff(f, space.t))
        cyclic = mechanics.cyclic_coordinates(space, H)
        h_conserved = not system.time_dependent
        symmetry = self._noether(system) if self.config.noether is not None else None
        charge = None if symmetry is None or not symmetry[0].symmetry else symmetry[1]

        def quantities(tt, y):
            vals = system.values(y, tt)
            names = (["H"] if h_conserved else []) + [n for n, c in conserved.items() if c]
            exprs = [H if n == "H" else system.observables[n] for n in names]
            out = dict(zip(names, numeric.evaluate_many(exprs, vals, shape=np.shape(tt)),
                           strict=True))
            for c in cyclic:
                out[f"p_{c}"] = np.array(y[:, space.names.index(c) + system.n])
            if charge is not None:  # a declared symmetry's charge (notes (3.9–3.16))
                out["noether_charge"] = np.array(np.broadcast_to(
                    numeric.evaluate(charge, vals), np.shape(tt)))
            return out

        angles = self._angles(system)
        a["angles"] = angles
        vals0 = system.values(y0[None, :], np.array([0.0]))
        h0 = float(np.ravel(numeric.evaluate(H, vals0))[0])  # a scalar if constant
        scales = {}
        if h_conserved:
            # the energy's scale: the largest of |H0| and its parts at p = 0 and the rest, so
            # that a zero-energy orbit is measured against its kinetic and potential energy
            v0 = float(np.ravel(numeric.evaluate(H.subs({p: 0 for p in space.p}), vals0))[0])
            scales["H"] = max(abs(h0), abs(v0), abs(h0 - v0), 1e-300)
        kept = {n: system.observables[n] for n, c in conserved.items() if c}
        if charge is not None:
            kept["noether_charge"] = charge

        def scales_along(tt, y):
            """Each invariant's scale, measured along the run (:func:`invariant_scales`)."""
            return {**scales, **invariant_scales(system, kept, cyclic, system.values(y, tt))}

        surface = self._surface(system)
        located = surface is not None and self._locates_on_steps()
        main = self.integrate(model, y0, t, invariants=quantities, progress=progress,
                              invariant_scales=scales_along,
                              section=surface if located else None)
        crossings = self._crossings if located else None
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
        a["kinetic_potential_split"] = self._kinetic_potential_split(system)
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
        if a["jacobi_tested"]:
            results.checks.append(Check(
                "Jacobi identity {f,{g,H}} + {g,{H,f}} + {H,{f,g}}, largest on the run",
                a["jacobi_max"], 0.0, "", "0, relative to the sum of the sizes of its three "
                "terms", scale=a["jacobi_scale"]))
        if system.L is not None:
            self._legendre_checks(a, system, main)
            # the transform as geometry (notes (4.15)–(4.28)) where L's surface is convex
            qdot0 = [float(np.ravel(v)[0]) for v in numeric.evaluate_many(
                system.legendre.velocities, vals0, shape=(1,))]
            legendre_geometry(a, system, y0[:system.n], qdot0,
                              planes=self.computes("legendre_geometry"))
        if system.n == 1:
            self._phase_grid(a, system, main)
        elif surface is not None:
            self._poincare(a, system, main, crossings)
            if "poincare_H_error" in a:
                results.checks.append(Check(
                    "H at the crossing of the surface of section furthest from H(0)",
                    a["poincare_H_farthest"], h0, "",
                    "H(0), conserved; crossings located "
                    + ("on the integrator's steps" if crossings is not None else
                       "between the stored samples"), scale=scales.get("H", 1.0)))

        results.checks.append(Check("H(t_end)" if h_conserved else "H(0)",
                                    float(main.invariants["H"][-1]) if h_conserved else h0,
                                    h0, "", "H(0) of the initial state", scale=scales.get("H",
                                                                                           1.0)))
        if self.config.transform is not None:
            self._transform(results, system, main)
        if symmetry is not None:
            self._noether_along(results, system, main, *symmetry, main.attrs.get(
                "scale_noether_charge") or invariant_scales(
                    system, {"noether_charge": symmetry[1]}, [], vals)["noether_charge"])
        if self.config.total_derivative is not None:
            self._total_derivative(a, system, main)
        if self.config.point_transform is not None:
            self._point_transform(a, system, main)
        if self.config.hamilton_jacobi is not None:
            self._hamilton_jacobi(a, system, main)
        # the study over at most STUDY_STEPS of the main run's steps: long (and chaotic) runs
        # would spend seconds on references, and errors that have grown to the orbit's size
        # compare nothing
        horizon = run.t_end * min(1.0, STUDY_STEPS / max(int(main.attrs["nsteps"]), 1))
        if (system.n >= 2 or system.time_dependent) and not self.family_member:
            # chaotic or regular: a chaotic orbit's study ends before its Lyapunov time
            horizon = min(horizon, self.divergence(results, model, y0, t))
            a["chaos_growth_threshold"] = float(lyapunov.CHAOTIC_GROWTH)
            a["behaviour"] = self._chaos_words(a)
        a["study_t_end"] = float(horizon)
        self.study(results, model, y0, np.linspace(0.0, horizon, 201))
        return results

    def integrate(self, model, y0, t_eval, *args, section=None, **kwargs):
        """As every kind's (:meth:`IntegratingSimulation.integrate`); with ``section`` (a
        surface from :meth:`_surface`) the run is stepped so that its crossings are located
        on the steps (:meth:`_run_with_section`), kept in ``self._crossings``."""
        if section is None:
            return super().integrate(model, y0, t_eval, *args, **kwargs)
        main, self._crossings = self._run_with_section(
            model, y0, t_eval, section, kwargs.get("invariants"),
            kwargs.get("invariant_scales"), kwargs.get("progress"))
        return main

    def _locates_on_steps(self) -> bool:
        """Whether the run can locate its crossings on its own steps: DOP853 (named, or
        the automatic choice for a formula system, which is neither stiff nor a Kepler
        orbit) stepped one step at a time with its continuous extension at hand."""
        run = self.config.run
        return run.method in ("auto", "dop853") and run.h is None

    def _run_with_section(self, model, y0, t, surface, invariants, scales, progress):
        """The main run, stepped so that the crossings of ``surface`` are located on each
        DOP853 step's 7th-order continuous extension (the integrators' surface-of-section
        search, as the two-centre kind's): as accurate as the steps whatever the output
        samples, whose states are the plain DOP853 run's.  Returns (the run, rows (t,
        state) at the crossings)."""
        run, system = self.config.run, self.system()
        s_col, value, direction, _ = surface
        section = formula.compiled_section(system, list(system.columns).index(s_col),
                                           value, direction)
        why = (integrators.choose_auto(model, run.rtol)[1] if run.method == "auto"
               else "named in the config.")
        reason = (f"{why} Stepped so that the crossings of the surface of section are "
                  "located on each step's continuous extension, whatever the output samples.")
        spec = integrators.SolverSpec(method=run.method, rtol=run.rtol, atol=run.atol,
                                      reason=reason)
        res = integrators.solve_fictitious_time(model, y0, t, None, spec, reason,
                                                progress=progress, section=section)
        main = self.run_record(res, model.columns, invariants=invariants,
                               invariant_scales=scales)
        return main, res.solution.crossings

    @staticmethod
    def _chaos_words(a: dict) -> str:
        """The behaviour verdict from the divergence of two orbits 1e-10 apart: chaotic when
        their separation grows by ``chaos_growth_threshold`` within the run."""
        threshold = a["chaos_growth_threshold"]
        if "lyapunov_time" in a:
            return (f"chaotic: two orbits 1e-10 apart separate by {a['separation_growth']:.1e}"
                    f"× over the run (chaos from {threshold:.0e}×), as e^(t/T) with Lyapunov "
                    f"time T ≈ {a['lyapunov_time']:.2g}")
        return (f"regular: two orbits 1e-10 apart separate by only "
                f"{a['separation_growth']:.2g}× over the run, below the {threshold:.0e}× of "
                "exponential divergence")

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
        energy = family_energy(sweep)
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

