r"""A first-order Lagrangian L = a(q, t)·q̇ − V(q, t) (notes (3.36–3.38)): simulated.

∂²L/∂q̇∂q̇ vanishes, so there is no Legendre transform; Lagrange's equations are first order,
Σⱼ ωᵢⱼ q̇ⱼ = ∂ᵢV + ∂ₜaᵢ with ωᵢⱼ = ∂ᵢaⱼ − ∂ⱼaᵢ (:func:`reportgen.core.mechanics.first_order`
derives them).  The state is q alone, the velocities follow from it: the config gives the
coordinates only (velocities, an ``energy`` to solve for, a surface of section, a
transformation, a symmetry, L + dF/dt or a Hamilton–Jacobi separation are refused with
the reason).  Along the run: V (the energy function a·q̇ − L) conserved for a
t-independent L, det ω keeping its sign, the Euler–Lagrange expressions of L (derived on
their own, :func:`~reportgen.core.mechanics.euler_lagrange`) vanishing with the reduced
velocities, and for linear equations q̇ = A q the closed form q(t) = exp(tA) q(0).

:class:`FirstOrderSimulation` comes before :class:`HamiltonianSimulation` in the scene's
bases and hands every other system on to it.
"""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from ...scene.results import Check, Results
from .config import STUDY_STEPS
from .simulation import invariant_scales, vanishes_for

formula = lazy_module("reportgen.core.formula")
numeric = lazy_module("reportgen.core.numeric")
mechanics = lazy_module("reportgen.core.mechanics")

#: what a first-order L does not take, by config key, and why
REFUSED = {"section": "a surface of section",
           "transform": "a canonical transformation of (q, p)",
           "noether": "a declared symmetry",
           "total_derivative": "adding dF/dt to L",
           "point_transform": "a point transformation (integrated through L′'s Legendre "
                              "transform)",
           "hamilton_jacobi": "a Hamilton–Jacobi separation"}


def _config_error(message: str):
    from ...scene.config import ConfigError

    return ConfigError([message])


class FirstOrderSimulation:
    """The reduced run of a first-order L; any other system is the parent's."""

    def is_first_order(self) -> bool:
        """Whether the config's L is linear in the velocities (SymPy work, memoized by
        :meth:`system`)."""
        return self.config.system.L is not None and self.system().first_order is not None

    def results_schema(self):
        if self.config.system.L is None or not self.is_first_order():
            return super().results_schema()
        import sympy

        from .results import schema_for

        cfg = self.config
        return schema_for(cfg.system.coordinates, cfg.observables,
                          tex=lambda name: sympy.latex(sympy.Symbol(name)), first_order=True)

    def build_models(self) -> None:
        """The parent's, then the keys a first-order L refuses (or, for an L that is not
        first order, the velocities the config left out) and det ω at the initial point."""
        cfg = self.config
        if cfg.system.L is None:
            return super().build_models()
        where = f"{self.source.label}: key"
        system = self.system()
        space = system.space
        velocities = [v.name for v in space.qdot]
        if system.first_order is None:
            missing = [v for v in velocities if v not in cfg.initial]
            if missing and "energy" not in cfg.initial:
                raise _config_error(f"{where} 'initial.{missing[0]}': required key is missing")
            return super().build_models()
        given = [k for k in (*velocities, "energy") if k in cfg.initial]
        if given:
            raise _config_error(
                f"{where} 'initial.{given[0]}': L is linear in the velocities (a first-order "
                "Lagrangian, notes (3.36–3.38)): the velocities and the energy follow from the "
                f"coordinates; give {', '.join(space.names)} only")
        for key, what in REFUSED.items():
            if getattr(cfg, key) is not None:
                raise _config_error(f"{where} '{key}': {what} needs the momenta of a regular L "
                                    "or an H; this L is linear in the velocities (a first-order "
                                    "Lagrangian, notes (3.36–3.38))")
        super().build_models()
        det0 = float(np.ravel(numeric.evaluate(system.first_order.det, system.values(
            self.initial_state()[None, :], np.array([0.0]))))[0])
        if not (np.isfinite(det0) and det0 != 0.0):
            raise _config_error(f"{where} 'initial': det ω = {det0:.6g} at the initial point: "
                                "ω = ∂ᵢaⱼ − ∂ⱼaᵢ is singular there and the velocities are not "
                                "determined (notes (3.36–3.38))")

    def initial_state(self) -> np.ndarray:
        """q0 alone for a first-order L (the velocities follow from it)."""
        if self.config.system.L is None or not self.is_first_order():
            return super().initial_state()
        names = self.system().space.names
        return np.array([self.config.initial[n] for n in names], dtype=float)

    def simulate(self, progress=None) -> Results:
        if self.config.system.L is None or not self.is_first_order():
            return super().simulate(progress)
        return self._simulate_first_order(progress)

    # ------------------------------------------------------------------ the reduced run
    def _simulate_first_order(self, progress) -> Results:
        import sympy

        system, run = self.system(), self.config.run
        space, fo, V = system.space, system.first_order, system.H
        t = np.linspace(0.0, run.t_end, run.samples)
        y0 = self.initial_state()
        model = self.models()[0]
        results = Results()
        a = results.analysis
        h_conserved = not system.time_dependent

        # an observable is conserved when ḟ = Σ ∂ᵢf q̇ᵢ + ∂ₜf simplifies to zero; for a
        # t-independent L the first part is the reduced bracket {f, V}
        brackets, conserved = {}, {}
        for name, f in system.observables.items():
            brackets[name] = sympy.simplify(fo.bracket(space, f, V))
            rate = sum((sympy.diff(f, q) * v for q, v in zip(space.q, fo.qdot, strict=True)),
                       sympy.diff(f, space.t))
            conserved[name] = vanishes_for(system, rate)

        def quantities(tt, y):
            vals = system.values(y, tt)
            names = (["H"] if h_conserved else []) + [n for n, c in conserved.items() if c]
            exprs = [V if n == "H" else system.observables[n] for n in names]
            return dict(zip(names, numeric.evaluate_many(exprs, vals, shape=np.shape(tt)),
                            strict=True))

        vals0 = system.values(y0[None, :], np.array([0.0]))
        h0 = float(np.ravel(numeric.evaluate(V, vals0))[0])
        # V's scale: |V(0)| or the size of its parts, so that V(0) = 0 is still measured
        scales = {"H": max(abs(h0), float(np.max(mechanics.roundoff_scale(V, vals0))),
                           1e-300)} if h_conserved else {}
        kept = {n: system.observables[n] for n, c in conserved.items() if c}

        def scales_along(tt, y):
            """V's scale, and each conserved observable's: the size of its terms."""
            return {**scales, **invariant_scales(system, kept, [], system.values(y, tt))}

        main = self.integrate(model, y0, t, invariants=quantities, progress=progress,
                              invariant_scales=scales_along)
        results.runs["main"] = main
        vals = system.values(main.y, main.t)
        moving = [n for n, c in conserved.items() if not c] + ([] if h_conserved else ["H"])
        if moving:
            exprs = [V if n == "H" else system.observables[n] for n in moving]
            a["observables"] = dict(zip(moving, numeric.evaluate_many(exprs, vals,
                                                                      shape=main.t.shape),
                                        strict=True))

        a["first_order"] = True
        a["latex"] = {"H": system.latex(V), "L": system.latex(system.L),
                      "q": [system.latex(q) for q in space.q]}
        for name, f in system.observables.items():
            a["latex"][f"observable_{name}"] = system.latex(f)
            a[f"poisson_{name}"] = str(brackets[name])
            a[f"conserved_{name}"] = bool(conserved[name])
        n = system.n
        a["first_order_latex"] = {
            "a": [system.latex(e) for e in fo.a], "V": system.latex(V),
            "omega": [" & ".join(system.latex(fo.omega[i, j]) for j in range(n))
                      for i in range(n)],
            "det": system.latex(fo.det),
            "inverse": [" & ".join(system.latex(fo.inverse[i, j]) for j in range(n))
                        for i in range(n)],
            "qdot": [system.latex(e) for e in fo.qdot]}
        a["coordinates"] = list(space.names)
        a["given"] = "L"
        a["kinetic_potential_split"] = False  # no momenta: the state is q alone
        a["time_dependent"] = bool(system.time_dependent)
        a["angles"] = self._angles(system)
        a["H0"] = h0
        a["initial_state"] = y0
        for column, value in zip(system.columns, y0, strict=True):
            a[f"initial_{column}"] = float(value)
        self._first_order_checks(results, system, main, t_independent=h_conserved)
        self._no_legendre_transform(a, system, y0)
        if h_conserved:
            results.checks.append(Check("V(t_end), the energy function a·q̇ − L",
                                        float(main.invariants["H"][-1]), h0, "",
                                        "V(0) of the initial point", scale=scales["H"]))
        a["study_t_end"] = float(run.t_end * min(1.0, STUDY_STEPS / max(int(main.attrs["nsteps"]),
                                                                  1)))
        self.study(results, model, y0, np.linspace(0.0, a["study_t_end"], 201))
        return results

    def _first_order_checks(self, results: Results, system, main, t_independent: bool) -> None:
        """det ω along the run, the Euler–Lagrange residual, the bracket generating the flow,
        dV/dt, and the closed form of linear equations."""
        import sympy

        a = results.analysis
        space, fo = system.space, system.first_order
        vals = system.values(main.y, main.t)
        shape = main.t.shape
        det = np.broadcast_to(numeric.evaluate(fo.det, vals), shape)
        a["first_order_det0"] = float(det[0])
        a["first_order_det_min"] = float(np.min(np.abs(det)))
        kept = bool(np.all(np.sign(det) == np.sign(det[0])))
        a["first_order_det_sign_kept"] = kept
        if not kept:
            results.flag("failed", "det ω changes sign along the run: ω is singular between "
                                   "samples and the reduced equations do not hold there")
        # Lagrange's equations of L itself (derived on their own, a first-order L has no q̈
        # in them) at the velocities the compiled right-hand side gives on each sample:
        # substituted symbolically they would cancel to 0 and test nothing
        model = self.models()[0]
        qdot = np.empty_like(main.y)
        for k, (tt, y) in enumerate(zip(main.t, main.y, strict=True)):
            model.rhs(float(tt), np.ascontiguousarray(y), model.params, qdot[k])
        vals.update(zip(space.qdot, qdot.T, strict=True))
        at = {s: 0 for s in mechanics.accelerations(space)}
        el = [e.xreplace(at) for e in mechanics.euler_lagrange(space, system.L)]
        residual = numeric.evaluate_many(el, vals, shape=shape)
        a["first_order_el_residual"] = float(max(np.max(np.abs(r)) for r in residual))
        a["first_order_el_scale"] = float(max(np.max(mechanics.roundoff_scale(e, vals))
                                              for e in el))
        results.checks.append(Check(
            "largest Euler–Lagrange expression d/dt ∂L/∂q̇ − ∂L/∂q at the compiled velocities",
            a["first_order_el_residual"], 0.0, "", "0: Lagrange's equations of L, notes "
            "(3.36–3.38)", scale=max(a["first_order_el_scale"], 1e-300)))
        generates = t_independent and all(
            sympy.simplify(fo.bracket(space, q, system.H) - v) == 0
            for q, v in zip(space.q, fo.qdot, strict=True))
        a["first_order_bracket_generates"] = bool(generates)
        rate = sum((sympy.diff(system.H, q) * v for q, v in zip(space.q, fo.qdot, strict=True)),
                   sympy.diff(system.H, space.t))
        a["first_order_energy_rate_zero"] = bool(sympy.simplify(rate) == 0)
        self._closed_form(results, system, main)

    #: velocities drawn at random to evaluate p = ∂L/∂q̇ at the initial point ...
    VELOCITY_SAMPLES = 16
    #: ... from [−v, v] with this v (in the config's units)
    VELOCITY_RANGE = 10.0

    def _no_legendre_transform(self, a: dict, system, q0) -> None:
        """Why there is no Legendre transform, as for the linear function of notes
        (4.13)–(4.14): ∂²L/∂q̇ᵢ∂q̇ⱼ (SymPy), its rank and its value at the initial point;
        whether some p = ∂L/∂q̇ contains a velocity; and p at the initial point for
        :attr:`VELOCITY_SAMPLES` velocities drawn at random, whose spread is 0 when p does
        not depend on q̇ (then q̇ cannot be solved for p)."""
        import sympy

        space = system.space
        momenta = [sympy.simplify(sympy.diff(system.L, v)) for v in space.qdot]
        hessian = sympy.Matrix([[sympy.simplify(sympy.diff(m, v)) for v in space.qdot]
                                for m in momenta])
        draws = np.random.default_rng(4).uniform(
            -self.VELOCITY_RANGE, self.VELOCITY_RANGE,
            size=(self.VELOCITY_SAMPLES, system.n))
        values = {**dict(zip(space.q, np.asarray(q0, dtype=float), strict=True)),
                  **dict(zip(space.qdot, draws.T, strict=True)), space.t: 0.0,
                  **{system.param_symbols[k]: v for k, v in system.params.items()}}
        p = np.stack(numeric.evaluate_many(momenta, values, shape=(self.VELOCITY_SAMPLES,)))
        at_start = {s: (v[0] if np.ndim(v) else v) for s, v in values.items()}
        a["first_order_velocity_hessian"] = np.array(
            [[float(numeric.evaluate(e, at_start)) for e in hessian.row(i)]
             for i in range(system.n)])
        a["first_order_velocity_hessian_rank"] = int(hessian.rank(simplify=True))
        a["first_order_momenta_contain_velocities"] = any(
            bool(m.free_symbols & set(space.qdot)) for m in momenta)
        a["first_order_momentum_spread"] = float(np.max(np.ptp(p, axis=1)))
        a["first_order_momentum_scale"] = float(np.max(np.abs(p)))
        a["first_order_velocity_samples"] = self.VELOCITY_SAMPLES
        a["first_order_velocity_range"] = self.VELOCITY_RANGE

    def _closed_form(self, results: Results, system, main) -> None:
        """For q̇ = A q with A constant: q(t) = exp(tA) q(0), compared with the run."""
        import sympy
        from scipy.linalg import expm

        a = results.analysis
        space, fo = system.space, system.first_order
        rhs = sympy.Matrix(fo.qdot)
        A = rhs.jacobian(sympy.Matrix(space.q))
        moving = set(space.q) | {space.t}
        linear = (not any(e.free_symbols & moving for e in A)
                  and all(sympy.simplify(e) == 0 for e in rhs - A * sympy.Matrix(space.q)))
        a["first_order_linear"] = bool(linear)
        if not linear:
            return
        constants = {system.param_symbols[k]: v for k, v in system.params.items()}
        A_num = np.array([[float(numeric.evaluate(e, constants)) for e in A.row(i)]
                          for i in range(system.n)])
        y0 = main.y[0]
        closed = np.array([expm(tt * A_num) @ y0 for tt in main.t])
        a["first_order_A"] = A_num
        a["first_order_closed_form"] = closed
        a["first_order_closed_form_error"] = float(np.max(np.abs(main.y - closed)))
        a["first_order_closed_form_scale"] = float(max(np.max(np.abs(main.y)), 1e-300))
        results.checks.append(Check(
            "largest |q − exp(tA) q(0)| along the run", a["first_order_closed_form_error"],
            0.0, "", "closed form of the linear reduced equations q̇ = A q",
            scale=a["first_order_closed_form_scale"]))
