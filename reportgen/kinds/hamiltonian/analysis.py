"""``hamiltonian`` analysis of a run: the angles among the coordinates, the brackets
between observables and the Jacobi identity, the Legendre checks, the phase portrait's
grid and the crossings of a surface of section.  Numerics only; no drawing."""

from __future__ import annotations

from functools import partial

import numpy as np

from ...lazy import lazy_module
from .config import JACOBI_ROUNDOFF, JACOBI_SAMPLES

numeric = lazy_module("reportgen.core.numeric")
formula = lazy_module("reportgen.core.formula")
mechanics = lazy_module("reportgen.core.mechanics")


class HamiltonianAnalysis:
    """The parts of the simulation that analyse the integrated run (mixed into
    :class:`~reportgen.kinds.hamiltonian.simulation.HamiltonianSimulation`)."""

    #: phase-portrait grid points per axis (one degree of freedom)
    PHASE_GRID = 241
    #: samples the Jacobi identity is checked on
    JACOBI_SAMPLES = JACOBI_SAMPLES

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
                                  "bracket": [r[2] for r in rows],
                                  "latex": [r[3] for r in rows]}
        self._jacobi(a, system, vals)
        self._facts_of_life(a, system)

    @staticmethod
    def _facts_of_life(a: dict, system) -> None:
        """The other brackets' properties of notes (4.38), in SymPy on this system: the
        canonical brackets {qᵢ, pⱼ} = δᵢⱼ, {qᵢ, qⱼ} = {pᵢ, pⱼ} = 0; antisymmetry, {C f, g} =
        C {f, g} and Leibniz's rule {fg, h} = f{g, h} + {f, h}g for f, g, h cubics in the
        system's (q, p) (H itself can make SymPy's expansion slow: the double pendulum's),
        each difference expanded to 0 (True) or not (False)."""
        import sympy as sp

        space = system.space
        bracket = mechanics.poisson_bracket
        q, p = space.q, space.p
        canonical = all(
            sp.expand(bracket(space, q[i], p[j]) - (1 if i == j else 0)) == 0
            and sp.expand(bracket(space, q[i], q[j])) == 0
            and sp.expand(bracket(space, p[i], p[j])) == 0
            for i in range(len(q)) for j in range(len(q)))
        f, g = q[0] ** 2 * p[-1] + p[0], p[0] ** 2 * q[-1] + q[0] * p[-1]
        h = q[-1] * p[0] ** 2 + q[0] ** 3
        C = sp.Symbol("C")
        a["brackets_canonical"] = bool(canonical)
        a["brackets_antisymmetric"] = bool(sp.expand(bracket(space, f, g)
                                                     + bracket(space, g, f)) == 0)
        a["brackets_homogeneous"] = bool(sp.expand(bracket(space, C * f, h)
                                                   - C * bracket(space, f, h)) == 0)
        a["brackets_leibniz"] = bool(sp.expand(
            bracket(space, f * g, h) - f * bracket(space, g, h) - bracket(space, f, h) * g) == 0)

    def _jacobi(self, a: dict, system, vals) -> None:
        """The Jacobi identity {f,{g,h}} + {g,{h,f}} + {h,{f,g}} = 0 (Goldstein §9.5) with
        h = H, on a sample of the run, judged against the size of its terms.

        f, g: the first pair of observables, then an observable with a cubic in (q, p), then
        two cubics, whose terms are not all rounding (each term against its own
        :func:`~reportgen.core.mechanics.roundoff_scale`): two conserved observables, or
        {q, p} with a separable H, give terms that vanish identically, and a sum of three
        zeros tests nothing.  The brackets are derived, not simplified, and evaluated."""
        space, names = system.space, list(system.observables)
        q1, p1, qn, pn = space.q[0], space.p[0], space.q[-1], space.p[-1]
        obs = [system.observables[n] for n in names]
        cubic_f, cubic_g = q1**2 * pn + p1, p1**2 * qn + q1 * pn
        candidates = [(obs[i], obs[k]) for i in range(len(obs)) for k in range(i + 1, len(obs))]
        candidates += [(f, cubic_g) for f in obs] + [(cubic_f, cubic_g)]
        n = len(np.atleast_1d(vals[space.t]))
        pick = np.unique(np.linspace(0, n - 1, min(n, self.JACOBI_SAMPLES)).astype(int))
        sample = {s: (v[pick] if np.ndim(v) else v) for s, v in vals.items()}
        for f, g in candidates:
            values, sizes, rounding, vanish = jacobi_terms(space, f, g, system.H, sample,
                                                           pick.shape)
            if not all(vanish):
                break
        total = np.abs(values[0] + values[1] + values[2])
        scale = float(np.max(np.abs(values[0]) + np.abs(values[1]) + np.abs(values[2])))
        a["jacobi_max"] = float(np.max(total))
        a["jacobi_scale"] = scale
        a["jacobi_terms"] = np.array(sizes)
        a["jacobi_roundoff"] = np.array(rounding)
        a["jacobi_tested"] = not all(vanish)
        a["jacobi_relative"] = (a["jacobi_max"] / scale if scale > 0 and a["jacobi_tested"]
                                else float("nan"))
        a["jacobi_triple"] = [str(f), str(g), "H"]
        a["jacobi_triple_latex"] = [system.latex(f), system.latex(g), "H"]

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
        # the passive variables of the transform (notes (4.8)): q and t are not transformed,
        # and ∂H/∂q at fixed p is −∂L/∂q at fixed q̇ (with q̇ = q̇(q, p)), ∂H/∂t = −∂L/∂t
        passive = [*space.q, space.t]
        dH = numeric.evaluate_many([system.H.diff(x) for x in passive], vals,
                                   shape=main.t.shape)
        dL = numeric.evaluate_many([system.L.diff(x) for x in passive], vals,
                                   shape=main.t.shape)
        a["legendre_passive_error"] = float(max(np.max(np.abs(h_ + l_))
                                                for h_, l_ in zip(dH, dL, strict=True)))
        a["legendre_passive_scale"] = float(max(np.max(np.abs(l_)) for l_ in dL))

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

    def _surface(self, system) -> tuple[str, float, str, list[str]] | None:
        """The surface of section (its column, value, direction and the two plotted
        columns), or None: none with one degree of freedom, nor with three or more unless
        the config asks for one (default with two: q₁ = 0 upward, (q₂, p₂) plotted)."""
        cfg = self.config.section
        columns = list(system.columns)
        n = system.n
        if n < 2 or (cfg is None and n != 2):
            return None
        if cfg is None:
            return columns[0], 0.0, "up", [columns[1], columns[n + 1]]
        axes = list(cfg.axes) if cfg.axes else [c for c in columns[:n] if c != cfg.coordinate][:1]
        if not cfg.axes:
            axes.append(f"p_{axes[0]}")
        return cfg.coordinate, float(cfg.value), cfg.direction, axes

    def _poincare(self, a: dict, system, main, crossings=None) -> None:
        """The crossings of the surface of section: ``crossings`` (rows t, state) located on
        the integrator's steps, or, without them (a fixed-step or implicit method), located
        between the stored samples by cubic Hermite interpolation (the derivatives from
        Hamilton's equations).  H at the crossings against H(0), absolute and relative to
        the energy scale the run's drift is measured against."""
        s_col, value, direction, axes = self._surface(system)
        columns = list(system.columns)
        column = columns.index(s_col)
        vals = system.values(main.y, main.t)
        ydot = np.column_stack(numeric.evaluate_many(system.hamilton.rhs, vals,
                                                     shape=main.t.shape))
        if crossings is not None:
            rows = np.asarray(crossings, dtype=float).reshape(-1, 1 + len(columns))
            if direction == "both" and len(rows):
                slope = numeric.evaluate(system.hamilton.rhs[column],
                                         system.values(rows[:, 1:], rows[:, 0]))
                sizes = (float(np.max(np.abs(main.y[:, column] - value))),
                         float(np.max(np.abs(ydot[:, column]))))
                rows = formula.section_rows(rows, column, value, direction,
                                            np.broadcast_to(slope, rows[:, 0].shape), sizes)
            points, located = rows, "steps"
        else:
            # every column at the crossings: the whole state there, u and v among them
            points = section_crossings(main.t, main.y, ydot, column, value, direction,
                                       list(range(len(columns))))
            located = "samples"
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
        a["poincare_located"] = located
        if not system.time_dependent and len(times):
            # on the run's energy surface up to the steps' error (or the interpolation's)
            H = np.broadcast_to(numeric.evaluate(system.H, system.values(state, times)),
                                times.shape)
            far = int(np.argmax(np.abs(H - a["H0"])))
            scale = float(main.attrs.get("scale_H", abs(a["H0"]) or 1.0))
            a["poincare_H_error"] = float(abs(H[far] - a["H0"]))
            a["poincare_H_relative_error"] = a["poincare_H_error"] / scale
            a["poincare_H_farthest"] = float(H[far])


def jacobi_terms(space, f, g, h, sample: dict, shape) -> tuple[list, list, list, list]:
    """The three terms {f,{g,h}}, {g,{h,f}}, {h,{f,g}} at ``sample`` (brackets derived, not
    simplified): their values (each of ``shape``), their largest |values|, the largest
    size of their parts (:func:`~reportgen.core.mechanics.roundoff_scale`), and whether
    each vanishes (largest |value| ≤ JACOBI_ROUNDOFF × that size: rounding)."""
    pb = partial(mechanics.bracket, space)
    terms = (pb(f, pb(g, h)), pb(g, pb(h, f)), pb(h, pb(f, g)))
    values = numeric.evaluate_many(terms, sample, shape=shape)
    sizes = [float(np.max(np.abs(v))) for v in values]
    rounding = [float(np.max(mechanics.roundoff_scale(term, sample))) for term in terms]
    vanish = [size <= JACOBI_ROUNDOFF * r for size, r in zip(sizes, rounding, strict=True)]
    return values, sizes, rounding, vanish


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

