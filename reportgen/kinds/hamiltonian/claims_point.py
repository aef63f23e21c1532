"""The claim-carrying sentences of a ``hamiltonian`` report about a point transformation
q = q(q′) of L (notes (3.39)–(3.47)): the Euler–Lagrange expressions transform with the
Jacobian, and the run of L′ carried back is the main run (:mod:`.claims`, which registers
these with its own)."""

from __future__ import annotations

import numpy as np

from ...scene.claims import claim
from .claims import ZERO, _system

#: points of the new coordinates and velocities at which E(L′) − JᵀE(L) is evaluated
POINTS = 12


def _map(data):
    """(old space, new space, the old coordinates as SymPy formulas of the new) from the
    archived config, parsed again."""
    from ...core import expressions, mechanics

    system = _system(data)
    table = dict(data.config["point_transform"])
    new = mechanics.PhaseSpace.of(list(table["coordinates"]))
    names = {**{q.name: q for q in new.q}, **system.param_symbols}
    old = [expressions.parse_expression(table[n], names) for n in system.space.names]
    return system, new, old


@claim("hamiltonian: Euler–Lagrange expressions covariant under a point transformation",
       r"yes: every component of the difference simplifies to 0")
def point_covariant(data) -> bool | str:
    """E(L′) − JᵀE(L), derived again by plain differentiation (no simplification) from the
    archived config, vanishes at points near the transformed initial state to ZERO of the
    size of its terms"""
    import sympy

    from ...core import mechanics, numeric

    system, new, old = _map(data)
    n = system.n
    space = system.space
    J = sympy.Matrix([[sympy.diff(q, s) for s in new.q] for q in old])
    qdot = list(J * sympy.Matrix(new.qdot))
    acc_new, acc_old = mechanics.accelerations(new), mechanics.accelerations(space)
    qddot = [sum((sympy.diff(v, s) * sd + sympy.diff(v, sd) * sa for s, sd, sa in
                  zip(new.q, new.qdot, acc_new, strict=True)), sympy.S.Zero) for v in qdot]
    to_new = {**dict(zip(space.q, old, strict=True)), **dict(zip(space.qdot, qdot,
                                                                 strict=True)),
              **dict(zip(acc_old, qddot, strict=True)), space.t: new.t}
    L_new = system.L.xreplace(to_new)
    E_old = [e.xreplace(to_new) for e in mechanics.euler_lagrange(space, system.L)]
    E_new = mechanics.euler_lagrange(new, L_new)
    start = np.asarray(data.analysis["point_transform_initial"], dtype=float)[:n]
    rng = np.random.default_rng(11)
    points = start + 0.05 * (np.abs(start) + 0.1) * rng.uniform(-1, 1, size=(POINTS, n))
    values = {**dict(zip(new.q, points.T, strict=True)), new.t: 0.3,
              **{s: rng.uniform(-1, 1, POINTS) for s in (*new.qdot, *acc_new)},
              **{system.param_symbols[k]: v for k, v in system.params.items()}}
    for j in range(n):
        terms = [E_new[j], *(-J[i, j] * E_old[i] for i in range(n))]
        parts = [np.abs(np.broadcast_to(np.asarray(numeric.evaluate(e, values),
                                                   dtype=float), (POINTS,))) for e in terms]
        total = np.broadcast_to(np.asarray(numeric.evaluate(sum(terms, sympy.S.Zero),
                                                            values), dtype=float), (POINTS,))
        if np.any(np.abs(total) > ZERO * np.maximum(sum(parts), 1e-300)):
            return (f"E(L′) − JᵀE(L) of {new.names[j]} is {float(np.max(np.abs(total))):.2g} "
                    "at points near the initial state")
    return True


@claim("hamiltonian: a point transformation gives the same orbit",
       r"yes: [^ ]+(?: × 10\S+)? of the coordinates' size at most over the whole run")
def point_same_orbit(data) -> bool | str:
    """the archived new initial coordinates, put through the config's q(q′), are the main
    run's q(0), and the archived differences of the runs are within the archived threshold
    over every sample of the main run"""
    from ...core import numeric

    system, new, old = _map(data)
    n, a, run = system.n, data.analysis, data.runs["main"]
    q0 = np.asarray(run.y, dtype=float)[0, :n]
    start = np.asarray(a["point_transform_initial"], dtype=float)[:n]
    values = {**dict(zip(new.q, start, strict=True)),
              **{system.param_symbols[k]: v for k, v in system.params.items()}}
    back = np.array([float(numeric.evaluate(e, values)) for e in old])
    if np.max(np.abs(back - q0)) > ZERO * max(float(np.max(np.abs(q0))), 1.0):
        return f"q(q′(0)) = {back.tolist()} is not the run's q(0) = {q0.tolist()}"
    tolerance = float(a["point_transform_tolerance"])
    worst = max(float(a["point_transform_q_difference"]),
                float(a["point_transform_p_difference"]))
    if worst > tolerance or int(a["point_transform_samples"]) != len(run.t):
        return f"the runs differ by {worst:.2g} (threshold {tolerance:.2g})"
    return True
