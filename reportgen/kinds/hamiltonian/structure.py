"""``hamiltonian`` simulation, the structure of the system: a canonical transformation
(finite, or infinitesimal from a generator G), the Noether charge of a declared symmetry,
the total-derivative invariance of L and the Hamilton–Jacobi quadrature solution."""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from .config import _PresetFormulas

expressions = lazy_module("reportgen.core.expressions")
formula = lazy_module("reportgen.core.formula")
integrators = lazy_module("reportgen.core.integrators")
numeric = lazy_module("reportgen.core.numeric")
mechanics = lazy_module("reportgen.core.mechanics")
canonical = lazy_module("reportgen.core.canonical")
hamilton_jacobi = lazy_module("reportgen.core.hamilton_jacobi")

_hj = _PresetFormulas


def sympy_simplify(expr):
    """SymPy's simplify (imported when used: validation imports no SymPy)."""
    import sympy

    return sympy.simplify(expr)


class HamiltonianStructure:
    """Mixed into :class:`.simulation.HamiltonianSimulation` (its ``config`` and
    ``integrate``)."""

    @staticmethod
    def _kinetic_potential_split(system) -> bool:
        """Whether H = T(p) + V(q): H does not contain t and every mixed second derivative
        ∂²H/∂qᵢ∂pⱼ simplifies to zero (the threshold: exactly zero).  It is the structure a
        symplectic splitting method needs (a drift by T, a kick by V), and it is not what a
        reader calls "separable" (separation of variables in the Hamilton–Jacobi equation,
        notes §7), which the report does not claim from it."""
        import sympy

        space = system.space
        if system.first_order is not None or space.t in system.H.free_symbols:
            return False
        return all(sympy.simplify(sympy.diff(system.H, q, p)) == 0
                   for q in space.q for p in space.p)

    def _transform(self, results, system, main) -> None:
        """New variables along the run, the symplectic condition MᵀJM = J there and the
        fundamental brackets {Qᵢ, Pⱼ} = δᵢⱼ (computed from M, relative to the size of their
        terms), K = H + ∂F/∂t; where K has a closed form, K integrated from (Q0, P0)
        against the image.  An infinitesimal transformation: :meth:`_infinitesimal`."""
        import sympy

        from ...scene.config import ConfigError

        cfg, a, n = self.config.transform, results.analysis, system.n
        if cfg.infinitesimal:
            self._infinitesimal(a, system, main)
            return
        numbers = {system.param_symbols[k]: v for k, v in system.params.items()}
        H = system.H.xreplace(numbers)
        coords = list(system.space.names)
        new_q, new_p = cfg.new_coordinates(coords), cfg.new_momenta(coords)
        try:
            ct = canonical.generating_function(system.space, cfg.formula, cfg.kind,
                                               new_q, new_p, params=system.params)
            q, p, t = main.y[:, :n], main.y[:, n:], main.t
            Q, P = canonical.new_variables(ct, q, p, t)
        except ValueError as exc:
            raise ConfigError([f"{self.source.label}: key 'transform.{cfg.kind}': {exc}"]) \
                from None
        M = canonical.phase_jacobian(ct, q, p, Q, P, t)
        defect = canonical.symplectic_defect_of(M)
        J = canonical.symplectic_unit(n)
        brackets = M @ J @ np.swapaxes(M, -1, -2)
        K_along = canonical.hamiltonian_along(ct, H, q, p, Q, P, t)
        a["transform"] = {"Q": Q, "P": P, "defect": defect, "K": K_along}
        a["transform_kind"] = cfg.kind
        a["transform_new"] = new_q + new_p
        a["transform_latex"] = canonical.relations_latex(ct)
        a["transform_defect_max"] = float(np.max(defect))
        # how far (Q, P) is from (q, p), relative to their sizes: 0 for the identity, notes
        # (6.15)'s F = −Σ pᵢQᵢ
        a["transform_identity_defect"] = max(
            float(np.max(np.abs(moved - given)) / max(float(np.max(np.abs(given))), 1e-300))
            for moved, given in ((Q, q), (P, p)))
        a["transform_bracket_max"] = float(np.max(np.abs(brackets - J)))
        a["transform_bracket_relative"] = canonical.bracket_departure(
            brackets, canonical.bracket_sizes(M))
        K = canonical.new_hamiltonian(ct, H)
        a["transform_K_latex"] = "" if K is None else sympy.latex(K)
        if K is None or K.free_symbols - set(ct.Q + ct.P + (system.space.t,)):
            return
        # Hamilton's equations of K, compiled like any formula system, from (Q0, P0)
        space = mechanics.PhaseSpace(tuple(new_q), ct.Q, ct.P, (), system.space.t)
        image = np.column_stack([Q, P])

        def integrate_K(K, suffix):
            new = formula.FormulaSystem(space, {}, {}, K, None, None,
                                        mechanics.hamiltonian_system(space, K))
            model = formula.compiled_model(new, name=f"{self.source.name}-{suffix}")
            return model, self.integrate(model, image[0], t)

        model, run = integrate_K(K, "K")
        run.reference = {c: v for c, v in zip(model.columns, image.T, strict=True)}
        run.attrs["reference_label"] = "(Q, P) of the integrated H orbit"
        results.runs["transformed"] = run
        a["transform_run_difference"] = float(np.max(np.abs(run.y - image)))
        if ct.dF_dt != 0:  # the other sign, K = H − ∂F/∂t as notes (6.14) prints it for F3
            _, other = integrate_K(canonical.new_hamiltonian(ct, H, sign=-1), "K-other")
            a["transform_K_other_sign_difference"] = float(np.max(np.abs(other.y - image)))

    def _infinitesimal(self, a: dict, system, main) -> None:
        """The infinitesimal canonical transformation generated by G (notes (6.16–6.18)):
        (Q, P) along the run; the brackets {zₐ, z_b} of the new variables, derived from
        their formulas and evaluated, against their closed form J + ε²{wₐ, w_b} (canonical
        to first order); the change of H, H(Q, P) − H(q, p), against ε{H, G} and the
        second-order term ε²/2 wᵀ∇²H w."""
        import sympy

        from ...scene.config import ConfigError

        cfg, n = self.config.transform, system.n
        coords = list(system.space.names)
        new_q, new_p = cfg.new_coordinates(coords), cfg.new_momenta(coords)
        numbers = {system.param_symbols[k]: v for k, v in system.params.items()}
        try:
            it = canonical.infinitesimal(system.space, cfg.G, cfg.step(), new_q, new_p,
                                         params=system.params)
        except ValueError as exc:
            raise ConfigError([f"{self.source.label}: key 'transform.G': {exc}"]) from None
        q, p, t = main.y[:, :n], main.y[:, n:], main.t
        Q, P = canonical.infinitesimal_new_variables(it, q, p, t)
        vals = {**system.values(main.y, t), it.epsilon: it.value}
        shape = t.shape
        B, R = canonical.infinitesimal_brackets(it)
        departure = B - sympy.Matrix(canonical.symplectic_unit(n))
        # the identity {zₐ, z_b} = J + ε²{wₐ, w_b} in SymPy's algebra (ε a symbol)
        symbolic = all(sympy.expand(e) == 0 for e in (B - R))
        b_vals = np.stack(numeric.evaluate_many(list(B), vals, shape=shape), axis=-1)
        d_vals = np.stack(numeric.evaluate_many(list(departure), vals, shape=shape), axis=-1)
        r_vals = np.stack(numeric.evaluate_many(list(R - sympy.Matrix(
            canonical.symplectic_unit(n))), vals, shape=shape), axis=-1)
        sizes = np.stack([mechanics.roundoff_scale(e, vals) * np.ones(shape) for e in B],
                         axis=-1)
        H = system.H.xreplace(numbers)
        dH, first, second = canonical.change_of_hamiltonian(it, H)
        dH_v, first_v, second_v = numeric.evaluate_many([dH, first, second], vals, shape=shape)
        H_v = numeric.evaluate(H, vals) * np.ones(shape)
        HG = mechanics.poisson_bracket(system.space, system.H, it.G)  # constants by name
        a["transform"] = {"Q": Q, "P": P, "dH": dH_v, "first_order": first_v,
                          "second_order": second_v}
        a["transform_kind"] = "G"
        a["transform_new"] = new_q + new_p
        a["transform_latex"] = canonical.infinitesimal_latex(it)
        a["transform_epsilon"] = it.value
        a["transform_bracket_max"] = float(np.max(np.abs(d_vals)))
        a["transform_bracket_closed_max"] = float(np.max(np.abs(r_vals)))
        a["transform_bracket_agreement"] = float(np.max(np.abs(b_vals - np.ravel(
            canonical.symplectic_unit(n)) - r_vals) / np.maximum(sizes, np.finfo(float).tiny)))
        a["transform_bracket_symbolic"] = bool(symbolic)
        a["transform_HG_latex"] = system.latex(HG)
        a["transform_dH_max"] = float(np.max(np.abs(dH_v)))
        a["transform_first_order_max"] = float(np.max(np.abs(first_v)))
        a["transform_second_order_residual"] = float(np.max(np.abs(dH_v - first_v - second_v)))
        a["transform_H_scale"] = float(np.max(np.abs(H_v)))

    def _noether(self, system):
        """The declared symmetry's charge (notes (3.9–3.16)): (the NoetherCharge, the
        charge in (q, p, t))."""
        from ...scene.config import ConfigError

        cfg, space = self.config.noether, system.space
        names = {**{q.name: q for q in space.q}, "t": space.t, **system.param_symbols}

        def parse(key, text):
            try:
                return expressions.parse_expression(text, names)
            except expressions.ExpressionError as exc:
                raise ConfigError([f"{self.source.label}: key '{key}': {exc}"]) from None

        delta = [parse(f"noether.delta.{n}", cfg.delta[n]) if n in cfg.delta else 0
                 for n in space.names]
        F = parse("noether.F", cfg.F) if cfg.F is not None else None
        sym = mechanics.noether(space, system.L, delta, F, system.param_symbols.values())
        to_qp = dict(zip(space.qdot, system.legendre.velocities, strict=True))
        return sym, sympy_simplify(sym.charge.subs(to_qp))

    def _noether_along(self, results, system, main, sym, charge, scale: float) -> None:
        """The charge along the run and its drift, its bracket with H (the test that finds
        conserved observables, an independent route), and the derivation for the report."""
        import sympy

        a, space = results.analysis, system.space
        vals = system.values(main.y, main.t)
        values = np.array(np.broadcast_to(numeric.evaluate(charge, vals), main.t.shape))
        bracket = sympy.simplify(mechanics.poisson_bracket(space, charge, system.H)
                                 + sympy.diff(charge, space.t))
        a["noether_symmetry"] = bool(sym.symmetry)
        a["noether_delta_latex"] = [system.latex(d) for d in sym.delta]
        a["noether_delta_velocity_latex"] = [system.latex(d) for d in sym.delta_velocity]
        a["noether_delta_L_latex"] = system.latex(sympy.simplify(sym.delta_L))
        a["noether_F_latex"] = system.latex(sym.F)
        a["noether_residual_latex"] = system.latex(sym.residual)
        a["noether_charge_latex"] = system.latex(sympy.simplify(sym.charge))
        a["noether_charge_qp_latex"] = system.latex(charge)
        a["noether_bracket_latex"] = system.latex(bracket)
        a["noether_bracket_zero"] = bool(bracket == 0)
        a["noether_charge0"] = float(values[0])
        a["noether_scale"] = float(scale)
        a["noether_drift"] = float(np.max(np.abs(values - values[0])) / scale)
        if not sym.symmetry:
            a["noether_values"] = values

    def _total_derivative(self, a: dict, system, main) -> None:
        """L and L + dF/dt (notes (3.48–3.49)): their Euler–Lagrange expressions compared
        symbolically, and the Hamiltonian of L' derived on its own against H(q, p − ∂F/∂q)
        − ∂F/∂t; along the run, H' at the shifted momenta against H − ∂F/∂t."""
        from ...scene.config import ConfigError

        space = system.space
        names = {**{q.name: q for q in space.q}, "t": space.t, **system.param_symbols}
        try:
            F = expressions.parse_expression(self.config.total_derivative.F, names)
            td = mechanics.add_total_derivative(space, system.L, system.H, F,
                                                system.param_symbols.values())
        except (expressions.ExpressionError, ValueError) as exc:
            raise ConfigError([f"{self.source.label}: key 'total_derivative.F': {exc}"]) \
                from None
        vals = system.values(main.y, main.t)
        shift = numeric.evaluate_many(td.momenta_shift, vals, shape=main.t.shape)
        shifted = dict(vals)
        shifted.update({p: vals[p] + s for p, s in zip(space.p, shift, strict=True)})
        H_new = numeric.evaluate(td.H_new, shifted) * np.ones(main.t.shape)
        H_old = numeric.evaluate(system.H - F.diff(space.t), vals) * np.ones(main.t.shape)
        a["total_derivative_F_latex"] = system.latex(F)
        a["total_derivative_L_latex"] = system.latex(td.L_new)
        a["total_derivative_same_equations"] = bool(td.same_equations)
        a["total_derivative_difference_latex"] = [system.latex(d) for d in td.difference]
        a["total_derivative_shift_latex"] = [system.latex(s) for s in td.momenta_shift]
        a["total_derivative_H_latex"] = system.latex(td.H_new)
        a["total_derivative_H_same"] = bool(td.H_difference == 0)
        a["total_derivative_H_error"] = float(np.max(np.abs(H_new - H_old)))
        a["total_derivative_H_scale"] = float(np.max(np.abs(H_old)))

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
