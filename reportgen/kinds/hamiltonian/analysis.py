"""``hamiltonian`` analysis of a run: the angles among the coordinates, the brackets
between observables and the Jacobi identity, the Legendre checks, the phase portrait's
grid and the crossings of a surface of section.  Numerics only; no drawing."""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from .config import JACOBI_SAMPLES

numeric = lazy_module("reportgen.core.numeric")
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

