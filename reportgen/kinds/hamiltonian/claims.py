"""The claim-carrying sentences of a ``hamiltonian`` report and what makes each true
(:mod:`reportgen.scene.claims`).

Each predicate checks its sentence against the archive without trusting the stored fact
that chose the words: what the configuration gives (H or L) from the archived config; the
structure of H (kinetic and potential parts split, t, cyclic coordinates, brackets)
numerically at states around the archived orbit, from the formulas derived again from the
archived config; conservation from the archived values along the run; chaos or regularity
from a second orbit integrated again by scipy's DOP853 next to the archived one; the
surface of section's direction from the archived samples.  Imported only by the claims
registry, never by the report.
"""

from __future__ import annotations

import numpy as np

from ...scene.claims import claim

#: a value is zero when below this fraction of the size of its terms (rounding, with room
#: for long derived expressions)
ZERO = 1e-9
#: a value is surely not zero above this fraction of the size of its terms
NONZERO = 1e-6
#: states around the orbit at which the structure of H is tested
STATES = 24

_BUILT: list = []


def _system(data):
    """The system derived again from the archived config (SymPy; memoized per archive)."""
    for held, system in _BUILT:
        if held is data:
            return system
    from ...core import formula

    cfg = data.config
    sys_ = cfg["system"]
    system = formula.build_system(list(sys_["coordinates"]), H=sys_.get("H"),
                                  L=sys_.get("L"), observables=dict(cfg.get("observables")
                                                                    or {}),
                                  params=dict(cfg.get("params") or {}))
    _BUILT[:] = [*_BUILT[-3:], (data, system)]
    return system


def _states(data, system, count: int = STATES, seed: int = 5) -> np.ndarray:
    """States near the archived orbit: archived samples moved by a few per cent of each
    column's range (a structure that holds only on the orbit is not a structure of H)."""
    y = np.asarray(data.runs["main"].y, dtype=float)
    rng = np.random.default_rng(seed)
    rows = y[rng.integers(0, len(y), size=count)]
    span = np.ptp(y, axis=0) + 0.1 * np.max(np.abs(y), axis=0) + 1e-3
    return rows + 0.05 * span * rng.uniform(-1.0, 1.0, size=rows.shape)


def _values(system, states, t=0.3):
    return system.values(states, np.full(len(states), float(t)))


def _at(expr, values, n):
    from ...core import numeric

    return np.broadcast_to(np.asarray(numeric.evaluate(expr, values), dtype=float), (n,))


def _size(expr, values, n):
    from ...core import mechanics

    return np.broadcast_to(np.asarray(mechanics.roundoff_scale(expr, values), dtype=float),
                           (n,))


def _vanishes(expr, values, n) -> bool | None:
    """Whether ``expr`` is zero at ``values`` against the size of its terms (None when no
    finite value)."""
    v, s = _at(expr, values, n), _size(expr, values, n)
    keep = np.isfinite(v) & np.isfinite(s)
    if not np.any(keep):
        return None
    return bool(np.all(np.abs(v[keep]) <= ZERO * s[keep] + 1e-300))


def _clearly_nonzero(expr, values, n) -> bool:
    v, s = _at(expr, values, n), _size(expr, values, n)
    keep = np.isfinite(v) & np.isfinite(s)
    return bool(np.any(np.abs(v[keep]) > NONZERO * s[keep]))


def _first_order(data) -> bool:
    return bool(data.analysis.get("first_order", False))


def _bracket(system, f, g):
    """{f, g} derived, not simplified."""
    space = system.space
    return sum(f.diff(q) * g.diff(p) - f.diff(p) * g.diff(q)
               for q, p in zip(space.q, space.p, strict=True))


# ----------------------------------------------------------------- what is given
@claim("hamiltonian: H as given",
       r"took the Hamiltonian as the configuration gives it|As the configuration gives the "
       r"Hamiltonian")
def h_given(data) -> bool | str:
    """the archived config gives H (not L)"""
    system = data.config["system"]
    if system.get("H") is None or system.get("L") is not None:
        return "the archived config gives L, not H"
    return True


def _velocity_curvature(data, system) -> tuple[float, float]:
    """The largest second difference of L in each velocity at states near the orbit, and
    the size of L there: zero for an L linear in the velocities."""
    from ...core import numeric

    space = system.space
    rng = np.random.default_rng(9)
    q = _states(data, system)[:, :system.n]
    v = rng.uniform(-1.5, 1.5, size=q.shape)
    base = {**{s: q[:, i] for i, s in enumerate(space.q)}, space.t: 0.3,
            **{system.param_symbols[k]: x for k, x in system.params.items()}}
    curvature, size = 0.0, 0.0
    for i in range(system.n):
        out = []
        for step in (-0.5, 0.0, 0.5):
            w = v.copy()
            w[:, i] += step
            vals = {**base, **{s: w[:, j] for j, s in enumerate(space.qdot)}}
            out.append(np.broadcast_to(numeric.evaluate(system.L, vals), (len(q),)))
        second = np.abs(out[0] - 2 * out[1] + out[2])
        keep = np.isfinite(second)
        curvature = max(curvature, float(np.max(second[keep], initial=0.0)))
        size = max(size, float(np.max(np.abs(out[1][keep]), initial=0.0)))
    return curvature, size


@claim("hamiltonian: H from L by the Legendre transform",
       r"from the Lagrangian the configuration gives, through the Legendre transform")
def legendre_from_l(data) -> bool | str:
    """the archived config gives L, and L is not linear in the velocities (its second
    difference in a velocity is not zero near the orbit)"""
    if data.config["system"].get("L") is None:
        return "the archived config gives H, not L"
    curvature, size = _velocity_curvature(data, _system(data))
    if curvature <= ZERO * max(size, 1e-300):
        return f"L is linear in the velocities (second difference {curvature:.2g})"
    return True


@claim("hamiltonian: first-order Lagrangian",
       r"found the Lagrangian linear in the velocities|First-order Lagrangian in|L linear in "
       r"the velocities, in")
def first_order_lagrangian(data) -> bool | str:
    """the archived config gives L, and its second difference in every velocity vanishes
    near the orbit"""
    if data.config["system"].get("L") is None:
        return "the archived config gives H, not L"
    curvature, size = _velocity_curvature(data, _system(data))
    if curvature > ZERO * max(size, 1.0):
        return f"L is not linear in the velocities (second difference {curvature:.3g})"
    return True


@claim("hamiltonian: degrees of freedom", r"\d+ degrees? of freedom")
def degrees_of_freedom(data) -> bool | str:
    """the archived run has 2n state columns for the config's n coordinates (n for a
    first-order L, whose n coordinates are n/2 degrees of freedom), as the report counts"""
    n = len(data.config["system"]["coordinates"])
    columns = list(data.runs["main"].columns)
    said = len(data.analysis.get("coordinates", []))
    want = n if _first_order(data) else 2 * n
    if len(columns) != want or said != n:
        return f"{n} coordinates in the config, {len(columns)} state columns archived"
    return True


# ------------------------------------------------------------------ structure of H
def _split_defect(data, system) -> tuple[float, float, float]:
    """H(q, p) + H(q', p') − H(q, p') − H(q', p) (zero for H = T(p) + V(q)) and the change
    of H with t, at pairs of states near the orbit, and the size of H there."""
    n = system.n
    a, b = _states(data, system, seed=3), _states(data, system, seed=4)
    mixed_a = np.concatenate([a[:, :n], b[:, n:]], axis=1)
    mixed_b = np.concatenate([b[:, :n], a[:, n:]], axis=1)
    H = system.H
    h = [_at(H, _values(system, s), len(a)) for s in (a, b, mixed_a, mixed_b)]
    later = _at(H, _values(system, a, t=1.7), len(a))
    defect = np.abs(h[0] + h[1] - h[2] - h[3])
    size = np.abs(h[0]) + np.abs(h[1]) + np.abs(h[2]) + np.abs(h[3])
    keep = np.isfinite(defect) & np.isfinite(later)
    return (float(np.max(defect[keep] / np.maximum(size[keep], 1e-300), initial=0.0)),
            float(np.max(np.abs(later[keep] - h[0][keep])
                         / np.maximum(np.abs(h[0][keep]), 1e-300), initial=0.0)), 1.0)


@claim("hamiltonian: kinetic and potential parts split",
       r"yes: kinetic and potential parts split|; H = T\(p\) \+ V\(q\), kinetic and potential "
       r"parts split")
def split(data) -> bool | str:
    """H(q, p) + H(q', p') = H(q, p') + H(q', p) and H(q, p, t) = H(q, p, t') at states
    near the orbit (H of the archived config, derived again from L when L is given)"""
    defect, moving, _ = _split_defect(data, _system(data))
    if defect > ZERO or moving > ZERO:
        return f"H mixes q and p (defect {defect:.2g}) or changes with t ({moving:.2g})"
    return True


@claim("hamiltonian: H mixes coordinates and momenta",
       r"no: H mixes coordinates and momenta")
def mixes(data) -> bool | str:
    """H(q, p) + H(q', p') − H(q, p') − H(q', p) is not zero at some pair of states"""
    defect, _, _ = _split_defect(data, _system(data))
    if defect <= NONZERO:
        return f"H(q, p) + H(q', p') − H(q, p') − H(q', p) ≤ {defect:.2g} of H: split"
    return True


def _changes_with_t(data) -> float:
    _, moving, _ = _split_defect(data, _system(data))
    return moving


@claim("hamiltonian: H depends on t", r"no: H depends on t|yes: H is not conserved")
def depends_on_t(data) -> bool | str:
    """H at the same states changes between two times"""
    moving = _changes_with_t(data)
    if moving <= NONZERO:
        return f"H changes by only {moving:.2g} of itself between two times"
    return True


@claim("hamiltonian: H conserved", r"no: H is conserved")
def h_conserved(data) -> bool | str:
    """H does not change with t at states near the orbit, and its archived values hold to
    the run's drift bound of its energy scale"""
    moving = _changes_with_t(data)
    if moving > ZERO:
        return f"H changes with t by {moving:.2g} of itself"
    run = data.runs["main"]
    values = np.asarray(run.invariants.get("H", []), dtype=float)
    if values.size == 0:
        return "no archived H along the run"
    scale = float(run.attrs.get("scale_H", np.max(np.abs(values))))
    drift = float(np.max(np.abs(values - values[0])))
    if drift > float(run.attrs.get("drift_bound", 1e-6)) * scale:
        return f"H drifts by {drift:.2g} along the run (scale {scale:.3g})"
    return True


def _observables(data, conserved: bool) -> list[str]:
    a = data.analysis
    return [k[len("conserved_"):] for k in a
            if k.startswith("conserved_") and bool(a[k]) is conserved]


def _total_rate(system, f):
    """df/dt = {f, H} + ∂f/∂t, derived, not simplified."""
    return _bracket(system, f, system.H) + f.diff(system.space.t)


@claim("hamiltonian: observables conserved",
       r"observables conserved \(\{f, H\}|conserved observables")
def observables_conserved(data) -> bool | str:
    """every observable the report calls conserved: {f, H} + ∂f/∂t vanishes at states near
    the orbit against the size of its terms, and its archived values hold along the run to
    the drift bound of the largest sum of its terms' sizes (recomputed here)"""
    system, run = _system(data), data.runs["main"]
    states = _states(data, system)
    vals = _values(system, states)
    along = system.values(np.asarray(run.y), np.asarray(run.t))
    for name in _observables(data, True):
        f = system.observables[name]
        # a first-order L's reduced bracket is not {f, H}: checked on the run alone
        if not _first_order(data) and not _vanishes(_total_rate(system, f), vals,
                                                    len(states)):
            return f"{{{name}, H}} + ∂{name}/∂t is not zero near the orbit"
        values = np.asarray(run.invariants.get(name, []), dtype=float)
        if values.size == 0:
            return f"{name} is not archived as an invariant"
        terms = f.args if f.is_Add else (f,)
        size = float(np.max(sum(np.abs(_at(term, along, len(run.t))) for term in terms)))
        bound = float(run.attrs.get("drift_bound", 1e-6))
        drift = float(np.max(np.abs(values - values[0])))
        if drift > bound * max(size, 1e-300) and drift > 1e-12:
            return f"{name} drifts by {drift:.2g} along the run; its terms are ≤ {size:.3g}"
    return True


@claim("hamiltonian: observables not conserved",
       r"observables not conserved \(\{f, H\}|Observables that are not conserved")
def observables_not_conserved(data) -> bool | str:
    """every observable the report calls not conserved changes along the archived run or
    has {f, H} + ∂f/∂t clearly nonzero near the orbit"""
    system = _system(data)
    states = _states(data, system)
    vals = _values(system, states)
    moving = data.analysis.get("observables", {})
    for name in _observables(data, False):
        series = np.asarray(moving.get(name, []), dtype=float)
        if series.size and np.ptp(series) > NONZERO * max(float(np.max(np.abs(series))),
                                                         1e-300):
            continue
        if _first_order(data):
            return f"{name} does not change along the run"
        if not _clearly_nonzero(_total_rate(system, system.observables[name]), vals,
                                len(states)):
            return f"{name} is constant on the run and {{{name}, H}} vanishes near the orbit"
    return True


@claim("hamiltonian: no cyclic coordinate", r"none: H depends on every coordinate")
def no_cyclic(data) -> bool | str:
    """∂H/∂q is clearly nonzero near the orbit for every coordinate"""
    system = _system(data)
    states = _states(data, system)
    vals = _values(system, states)
    for name, q in zip(system.space.names, system.space.q, strict=True):
        if not _clearly_nonzero(system.H.diff(q), vals, len(states)):
            return f"∂H/∂{name} vanishes near the orbit: {name} is cyclic"
    return True


@claim("hamiltonian: cyclic coordinates",
       r"\(its conjugate momentum is conserved\)|\(their conjugate momenta are conserved\)")
def cyclic(data) -> bool | str:
    """for every coordinate called cyclic, ∂H/∂q vanishes near the orbit and its archived
    momentum column does not change along the run"""
    system, run = _system(data), data.runs["main"]
    states = _states(data, system)
    vals = _values(system, states)
    y = np.asarray(run.y, dtype=float)
    momenta = float(np.max(np.abs(y[:, system.n:]), initial=0.0))
    for name in [str(c) for c in data.analysis.get("cyclic", [])]:
        q = system.space.q[system.space.names.index(name)]
        if not _vanishes(system.H.diff(q), vals, len(states)):
            return f"∂H/∂{name} is not zero near the orbit"
        p = y[:, list(run.columns).index(f"p_{name}")]
        if np.ptp(p) > 1e-10 * max(momenta, 1e-300):
            return f"p_{name} changes by {np.ptp(p):.2g} along the run"
    return True
