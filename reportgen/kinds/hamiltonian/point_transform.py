"""``hamiltonian`` simulation, a point transformation q = q(q′) of L (notes (3.39)–(3.47)):
L′(q′, q̇′) = L(q(q′), J q̇′) derived with SymPy, the notes' identities (3.42), (3.43) and
(3.47) simplified, and L′'s own equations integrated from the transformed initial state
and carried back to the old coordinates, against the main run."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...lazy import lazy_module

expressions = lazy_module("reportgen.core.expressions")
formula = lazy_module("reportgen.core.formula")
mechanics = lazy_module("reportgen.core.mechanics")
numeric = lazy_module("reportgen.core.numeric")
point_transformation = lazy_module("reportgen.core.point_transformation")

#: the Jacobian ∂q/∂q′ is singular where |det J| is below this fraction of the product of
#: its columns' lengths (Hadamard's bound on |det J|): notes (3.40) asks det J ≠ 0
SINGULAR = 1e-10
#: Newton's method for q′(0) stops when |q(q′) − q(0)| is below this fraction of the
#: coordinates' size (a few rounding errors), within NEWTON_STEPS steps
NEWTON_RTOL = 1e-14
NEWTON_STEPS = 60
#: the two runs agree when the run of L′, carried back, stays within this multiple of the
#: larger of the main run's relative tolerance and its energy drift, of the coordinates'
#: size (two integrations, each to rtol per step, whose global errors grow along the run)
AGREEMENT_FACTOR = 1e4


@dataclass(frozen=True)
class PointStart:
    """The parsed map and the new initial coordinates: ``new`` the new PhaseSpace, ``old``
    qᵢ(q′), ``jacobian`` ∂q/∂q′ (SymPy), ``q0`` the new coordinates at t = 0 (Newton),
    ``det0`` det J there relative to Hadamard's bound."""

    new: object
    old: tuple
    jacobian: object
    q0: np.ndarray
    det0: float


def relative_det(J: np.ndarray) -> np.ndarray:
    """|det J| / Π‖columns‖ of J (..., n, n): 1 for orthogonal columns, 0 when singular."""
    size = np.prod(np.linalg.norm(J, axis=-2), axis=-1)
    return np.abs(np.linalg.det(J)) / np.maximum(size, np.finfo(float).tiny)


class PointTransformSimulation:
    """Mixed into :class:`.simulation.HamiltonianSimulation` (its ``config``, ``source``,
    ``system`` and ``integrate``)."""

    def _refuse(self, key: str, message: str):
        from ...scene.config import ConfigError

        return ConfigError([f"{self.source.label}: key 'point_transform{key}': {message}"])

    @staticmethod
    def _jacobian_at(J, values: dict, shape) -> np.ndarray:
        """The SymPy matrix J = ∂q/∂q′ evaluated on ``values``: shape (*shape, n, n)."""
        n = J.shape[0]
        entries = numeric.evaluate_many(list(J), values, shape=shape)
        return np.stack(entries, axis=-1).reshape(*shape, n, n)

    def _point_start(self) -> PointStart:
        """Parse the map q(q′), find q′(0) with q(q′(0)) = q(0) by Newton's method from the
        config's starting point, and refuse a Jacobian singular there (notes (3.40))
        (memoized: ``validate`` calls it, and ``run``)."""
        if getattr(self, "_point_start_memo", None) is not None:
            return self._point_start_memo
        import sympy

        cfg, system = self.config.point_transform, self.system()
        new = mechanics.PhaseSpace.of(cfg.coordinates)
        names = {**{q.name: q for q in new.q}, **system.param_symbols}
        formulas = cfg.formulas()
        old = []
        for name in system.space.names:
            try:
                old.append(expressions.parse_expression(formulas[name], names))
            except expressions.ExpressionError as exc:
                raise self._refuse(f".{name}", str(exc)) from None
        J = sympy.Matrix([[sympy.diff(q, s) for s in new.q] for q in old])
        q_target = np.array([float(self.config.initial[n]) for n in system.space.names])
        params = {system.param_symbols[k]: v for k, v in system.params.items()}
        given = np.array([float(cfg.initial[n]) for n in cfg.coordinates])
        x = given.copy()
        scale = max(float(np.max(np.abs(q_target))), 1.0)

        def at(x):
            vals = {**dict(zip(new.q, x, strict=True)), **params}
            q = np.array([float(numeric.evaluate(e, vals)) for e in old])
            return q, self._jacobian_at(J, vals, ())

        def where(x) -> str:
            return "at " + ", ".join(f"{n} = {v:.6g}" for n, v in
                                     zip(cfg.coordinates, x, strict=True))

        for _ in range(NEWTON_STEPS):
            q, Jx = at(x)
            if not (np.all(np.isfinite(q)) and np.all(np.isfinite(Jx))):
                raise self._refuse(".initial", f"the old coordinates are not finite {where(x)}")
            if relative_det(Jx) < SINGULAR:
                raise self._refuse(".coordinates", "the Jacobian ∂q/∂q′ is singular "
                                   f"{where(x)} (notes (3.40) asks det ≠ 0): not an invertible "
                                   "change of coordinates there")
            miss = q - q_target
            if np.max(np.abs(miss)) <= NEWTON_RTOL * scale:
                break
            x = x - np.linalg.solve(Jx, miss)
        else:
            raise self._refuse(".initial", f"no new coordinates near {given.tolist()} give "
                               f"the initial {', '.join(system.space.names)} = "
                               f"{q_target.tolist()} (Newton's method did not converge)")
        self._point_start_memo = PointStart(new, tuple(old), J, x, float(relative_det(Jx)))
        return self._point_start_memo

    def _point_transform(self, a: dict, system, main) -> None:
        """L′ and the notes' identities (SymPy); L′ integrated from q′(0), q̇′(0) = J⁻¹q̇(0)
        with its momenta from its own Legendre transform, carried back by q(q′) and
        compared with the main run; its momenta against p′ = Jᵀp (a covector)."""
        start = self._point_start()
        new, n = start.new, system.n
        constants = list(system.param_symbols.values())
        try:
            pt = point_transformation.point_transformation(system.space, system.L, start.old,
                                                           new, constants)
            legendre = mechanics.legendre(new, pt.L_new, constants)
            hamilton = mechanics.hamiltonian_system(new, legendre.H, constants)
        except ValueError as exc:
            raise self._refuse("", str(exc)) from None
        new_system = formula.FormulaSystem(new, system.params, system.param_symbols,
                                           legendre.H, pt.L_new, legendre, hamilton)
        model = formula.compiled_model(new_system, name=f"{self.source.name}-point")
        # q̇′(0) = J⁻¹ q̇(0), then p′(0) = ∂L′/∂q̇′ there
        params = {system.param_symbols[k]: v for k, v in system.params.items()}
        vals0 = system.values(main.y[:1], main.t[:1])
        qdot0 = np.array([float(np.ravel(v)[0]) for v in numeric.evaluate_many(
            list(system.legendre.velocities), vals0, shape=(1,))])
        at0 = {**dict(zip(new.q, start.q0, strict=True)), new.t: 0.0, **params}
        J0 = self._jacobian_at(start.jacobian, at0, ())
        at0.update(zip(new.qdot, np.linalg.solve(J0, qdot0), strict=True))
        p0 = np.array([float(np.ravel(numeric.evaluate(m, at0))[0]) for m in legendre.momenta])
        run = self.integrate(model, np.concatenate([start.q0, p0]), main.t)
        # carried back: q(q′(t)) against q(t); p′(t) against Jᵀ p(t)
        vals = new_system.values(run.y, run.t)
        shape = run.t.shape
        back = np.stack(numeric.evaluate_many(list(start.old), vals, shape=shape), axis=-1)
        q_main, p_main = main.y[:, :n], main.y[:, n:]
        rows = min(len(back), len(q_main))  # a failed run stops early
        J = self._jacobian_at(start.jacobian, vals, shape)
        covector = np.einsum("tij,ti->tj", J[:rows], p_main[:rows])
        q_scale = max(float(np.max(np.abs(q_main))), 1e-300)
        p_new = run.y[:rows, n:]
        p_scale = max(float(np.max(np.abs(p_new))), 1e-300)
        det = relative_det(J)
        a["point_transform_coordinates"] = list(new.names)
        a["point_transform_coordinates_latex"] = [new_system.latex(q) for q in new.q]
        a["point_transform_old_latex"] = [new_system.latex(e) for e in pt.old]
        a["point_transform_det_latex"] = new_system.latex(pt.det)
        a["point_transform_L_latex"] = new_system.latex(pt.L_new)
        a["point_transform_H_latex"] = new_system.latex(legendre.H)
        a["point_transform_velocity_identity"] = bool(pt.velocity_identity)
        a["point_transform_second_identity"] = bool(pt.second_identity)
        a["point_transform_covariant"] = bool(pt.covariant)
        a["point_transform_residual_latex"] = [new_system.latex(r)
                                               for r in pt.covariance_residual]
        a["point_transform_initial"] = np.concatenate([start.q0, p0])
        a["point_transform_det0"] = start.det0
        a["point_transform_det_min"] = float(np.min(det))
        a["point_transform_singular_threshold"] = SINGULAR
        a["point_transform_q_difference"] = float(np.max(np.abs(back[:rows]
                                                                - q_main[:rows]))) / q_scale
        a["point_transform_q_scale"] = q_scale
        a["point_transform_p_difference"] = float(np.max(np.abs(p_new - covector))) / p_scale
        a["point_transform_p_scale"] = p_scale
        a["point_transform_samples"] = int(rows)
        a["point_transform_run_status"] = str(run.attrs.get("status", ""))
        a["point_transform_nfev"] = int(run.attrs.get("nfev", 0))
        tolerance = AGREEMENT_FACTOR * max(float(self.config.run.rtol),
                                           float(main.attrs.get("drift_H", 0.0)))
        a["point_transform_tolerance"] = tolerance
        a["point_transform_agree"] = bool(
            rows == len(q_main) and a["point_transform_q_difference"] <= tolerance
            and a["point_transform_p_difference"] <= tolerance)
