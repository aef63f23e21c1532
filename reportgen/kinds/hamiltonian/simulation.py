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
from .config import STUDY_STEPS, HamiltonianConfig, _PresetFormulas, family_energy
from .results import SCHEMA, schema_for

expressions = lazy_module("reportgen.core.expressions")
formula = lazy_module("reportgen.core.formula")
numeric = lazy_module("reportgen.core.numeric")
mechanics = lazy_module("reportgen.core.mechanics")
canonical = lazy_module("reportgen.core.canonical")
hamilton_jacobi = lazy_module("reportgen.core.hamilton_jacobi")

_hj = _PresetFormulas


class HamiltonianSimulation(HamiltonianAnalysis, IntegratingSimulation):
    """A system given as H(q, p, t) or L(q, q̇, t): derived, compiled, integrated, checked."""

    schema = SCHEMA
    config: HamiltonianConfig

    #: grid points per axis of H on the surface of section (its allowed region's edge)
    SECTION_GRID = 301
    #: the left-out momentum or velocity of ``initial.energy`` is sought in [0, this]
    ENERGY_SEARCH_MAX = 1e12

    def results_schema(self) -> ResultsSchema:
        """The schema with this config's columns, invariants and observables, each
        coordinate's symbol as SymPy typesets it (``p_theta`` -> ``p_{\\theta}``)."""
        import sympy

        cfg = self.config
        new = [] if cfg.transform is None else (list(cfg.transform.coordinates)
                                                 + cfg.transform.new_momenta())
        return schema_for(cfg.system.coordinates, cfg.observables, new,
                          tex=lambda name: sympy.latex(sympy.Symbol(name)))

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
        h0 = float(np.ravel(numeric.evaluate(H, vals0))[0])  # a scalar if constant
        if h_conserved:
            # the energy's scale: the largest of |H0| and its parts at p = 0 and the rest, so
            # that a zero-energy orbit is measured against its kinetic and potential energy
            v0 = float(np.ravel(numeric.evaluate(H.subs({p: 0 for p in space.p}), vals0))[0])
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
        if (system.n >= 2 or system.time_dependent) and not self.family_member:
            # chaotic or regular: a chaotic orbit's study ends before its Lyapunov time
            horizon = min(horizon, self.divergence(results, model, y0, t))
            a["behaviour"] = self._chaos_words(a)
        a["study_t_end"] = float(horizon)
        self.study(results, model, y0, np.linspace(0.0, horizon, 201))
        return results

    @staticmethod
    def _chaos_words(a: dict) -> str:
        """The behaviour verdict from the divergence of two orbits 1e-10 apart."""
        if "lyapunov_time" in a:
            return (f"chaotic: two orbits 1e-10 apart separate by {a['separation_growth']:.1e}"
                    f"× over the run, as e^(t/T) with Lyapunov time T ≈ "
                    f"{a['lyapunov_time']:.2g}")
        return (f"regular: two orbits 1e-10 apart separate by only "
                f"{a['separation_growth']:.2g}× over the run (no exponential divergence)")

    def _transform(self, results, system, main) -> None:
        """New variables along the run, the symplectic condition MᵀJM = J there, K = H +
        ∂F/∂t; where K has a closed form, K integrated from (Q0, P0) against the image."""
        import sympy

        from ...scene.config import ConfigError

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
        from ...scene.config import ConfigError

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

