"""The claim-carrying sentences of a ``hamiltonian`` report about its run: chaotic or
regular, the surface of section, what each drift is relative to, the Jacobi identity, a
declared symmetry, a canonical transformation, a Hamilton–Jacobi separation and a
first-order L (:mod:`.claims`, which registers these with its own)."""

from __future__ import annotations

import math

import numpy as np

from ...scene.claims import claim
from .claims import NONZERO, _at, _bracket, _observables, _states, _system, _values, _vanishes

#: how far a re-measured separation growth may sit on the wrong side of the stored
#: threshold before a chaotic (or regular) verdict is contradicted
GROWTH_MARGIN = 100.0


# --------------------------------------------------------------------- behaviour
def _growth(data) -> float:
    """How far an orbit started 10⁻¹⁰ × max|y| from the archived initial state separates
    from the archived orbit: scipy's DOP853 (rtol 1e-12) on Hamilton's equations derived
    again from the config, against the archived samples (at most 4000 of them)."""
    import sympy
    from scipy.integrate import solve_ivp

    system, run = _system(data), data.runs["main"]
    numbers = {system.param_symbols[k]: v for k, v in system.params.items()}
    rhs = [sympy.sympify(e).xreplace(numbers) for e in system.hamilton.rhs]
    f = sympy.lambdify((system.space.t, *system.state_symbols), rhs, "numpy")
    t, y = np.asarray(run.t, dtype=float), np.asarray(run.y, dtype=float)
    keep = np.unique(np.linspace(0, len(t) - 1, min(len(t), 4000)).astype(int))
    t, y = t[keep], y[keep]
    y0 = y[0]
    direction = np.where(np.arange(y0.size) % 2 == 0, 1.0, -1.0) / math.sqrt(y0.size)
    # against the orbit's size along the run (an orbit may start at the origin)
    d0 = 1e-10 * max(float(np.max(np.abs(y))), 1e-300)
    sol = solve_ivp(lambda tt, s: np.array(np.broadcast_arrays(*f(tt, *s)), dtype=float),
                    (t[0], t[-1]), y0 + d0 * direction, method="DOP853", t_eval=t,
                    rtol=1e-12, atol=1e-14 * max(float(np.max(np.abs(y))), 1e-300))
    d = np.linalg.norm(sol.y.T - y[:sol.y.shape[1]], axis=1)
    d = d[np.isfinite(d)]
    if sol.status != 0 or d.size == 0:
        return math.inf  # the neighbour orbit ran away or failed: not regular
    return float(np.max(d) / d0)


@claim("hamiltonian: chaotic orbit",
       r"chaotic: two orbits|a chaotic orbit \(Lyapunov|This orbit is chaotic")
def chaotic(data) -> bool | str:
    """an orbit started 10⁻¹⁰ away, integrated again by scipy, separates from the archived
    one by at least the chaos threshold / GROWTH_MARGIN"""
    threshold = float(data.analysis.get("chaos_growth_threshold", 1e6))
    growth = _growth(data)
    if growth < threshold / GROWTH_MARGIN:
        return f"a neighbour orbit separates by only {growth:.2g}× (chaos from {threshold:.0e}×)"
    return True


@claim("hamiltonian: regular orbit",
       r"regular: two orbits|: a regular orbit|This orbit is regular")
def regular(data) -> bool | str:
    """an orbit started 10⁻¹⁰ away, integrated again by scipy, separates from the archived
    one by less than the chaos threshold × GROWTH_MARGIN"""
    threshold = float(data.analysis.get("chaos_growth_threshold", 1e6))
    growth = _growth(data)
    if growth >= threshold * GROWTH_MARGIN:
        return f"a neighbour orbit separates by {growth:.2g}× (chaos from {threshold:.0e}×)"
    return True


# -------------------------------------------------------------- surface of section
@claim("hamiltonian: surface crossed in one direction",
       r"crossed with \S+ (?:increasing|decreasing)")
def section_direction(data) -> bool | str:
    """at the archived crossings the surface's column moves in the stated direction: the
    archived samples around each crossing (90 % of them, coarse sampling aside), and the
    crossing state lies on the surface"""
    a, run = data.analysis, data.runs["main"]
    column, value, direction = [str(x) for x in a["poincare_surface"]]
    value = float(value)
    col = np.asarray(run.y[:, list(run.columns).index(column)], dtype=float)
    t = np.asarray(run.t, dtype=float)
    times = np.asarray(a["poincare"]["t"], dtype=float)
    state = np.asarray(a["poincare"]["state"], dtype=float)
    if len(times) == 0:
        return True
    on = np.abs(state[:, list(run.columns).index(column)] - value)
    if np.max(on) > 1e-6 * max(float(np.max(np.abs(col))), 1.0):
        return f"a crossing lies {np.max(on):.2g} off the surface"
    i = np.clip(np.searchsorted(t, times) - 1, 0, len(t) - 2)
    rising = col[i + 1] > col[i]
    share = float(np.mean(rising if direction == "up" else ~rising))
    if share < 0.9:
        return f"only {share:.0%} of the crossings go the stated way ({direction})"
    return True


@claim("hamiltonian: crossings on the energy surface",
       r"every crossing lies on the energy surface H = H\(0\)")
def crossings_on_energy_surface(data) -> bool | str:
    """H of the archived crossing states (H derived again) is H(0) to the run's drift bound
    of the energy scale"""
    system, run, a = _system(data), data.runs["main"], data.analysis
    state = np.asarray(a["poincare"]["state"], dtype=float)
    times = np.asarray(a["poincare"]["t"], dtype=float)
    h = _at(system.H, system.values(state, times), len(times))
    h0 = float(_at(system.H, system.values(run.y[:1], run.t[:1]), 1)[0])
    scale = float(run.attrs.get("scale_H", abs(h0)))
    worst = float(np.max(np.abs(h - h0), initial=0.0)) / max(scale, 1e-300)
    if worst > float(run.attrs.get("drift_bound", 1e-6)):
        return f"H at a crossing departs from H(0) by {worst:.2g} of the energy scale"
    return True


@claim("hamiltonian: crossings located on the DOP853 steps",
       r"continuous extension \(dense output\) of the DOP853 step")
def located_on_steps(data) -> bool | str:
    """the archived run is DOP853 with adaptive steps (no fixed step)"""
    attrs = data.runs["main"].attrs
    if not str(attrs.get("method", "")).startswith("dop853") or \
            math.isfinite(float(attrs.get("h", math.nan))):
        return f"the run's method is {attrs.get('method')} (step {attrs.get('h')})"
    return True


@claim("hamiltonian: crossings located between samples",
       r"has no continuous extension here")
def located_between_samples(data) -> bool | str:
    """the archived run is not adaptive DOP853"""
    attrs = data.runs["main"].attrs
    if str(attrs.get("method", "")).startswith("dop853") and \
            not math.isfinite(float(attrs.get("h", math.nan))):
        return "the run is adaptive DOP853, which has a continuous extension"
    return True


# ------------------------------------------------------------------------ drift
@claim("hamiltonian: drift relative to the energy scale",
       r"the energy scale max\(\|H\(0\)\|, \|T\(0\)\|, \|V\(0\)\|\)")
def energy_scale(data) -> bool | str:
    """the archived scale of H is max(|H(0)|, |T(0)|, |V(0)|) with V = H at p = 0,
    evaluated again at the archived initial state"""
    system, run = _system(data), data.runs["main"]
    y0 = np.asarray(run.y[:1], dtype=float)
    h0 = float(_at(system.H, system.values(y0, run.t[:1]), 1)[0])
    at_rest = y0.copy()
    at_rest[:, system.n:] = 0.0
    v0 = float(_at(system.H, system.values(at_rest, run.t[:1]), 1)[0])
    want = max(abs(h0), abs(v0), abs(h0 - v0), 1e-300)  # the floor the run stores
    scale = float(run.attrs.get("scale_H", math.nan))
    if not abs(scale - want) <= 1e-9 * max(want, 1e-300):
        return f"the archived scale of H is {scale:.6g}, max(|H0|, |T0|, |V0|) is {want:.6g}"
    return True


@claim("hamiltonian: drift relative to the size of the terms",
       r"the largest sum of the sizes of its terms along the run")
def terms_scale(data) -> bool | str:
    """each conserved observable's archived scale is at least the largest sum of its
    top-level terms' sizes along the archived run (recomputed) and at least its own size,
    and its archived drift is max|f − f(0)| over that scale"""
    system, run = _system(data), data.runs["main"]
    along = system.values(np.asarray(run.y), np.asarray(run.t))
    for name in _observables(data, True):
        if name not in run.invariants:
            continue
        f = system.observables[name]
        terms = f.args if f.is_Add else (f,)
        size = float(np.max(sum(np.abs(_at(term, along, len(run.t))) for term in terms)))
        values = np.asarray(run.invariants[name], dtype=float)
        scale = float(run.attrs.get(f"scale_{name}", math.nan))
        if not scale >= (1 - 1e-12) * max(size, float(np.max(np.abs(values)))):
            return f"{name}: the archived scale {scale:.3g} is below its terms' size {size:.3g}"
        drift = float(np.max(np.abs(values - values[0]))) / scale
        if not math.isclose(drift, float(run.attrs[f"drift_{name}"]), rel_tol=1e-9,
                            abs_tol=1e-300):
            return f"{name}: drift {drift:.3g} recomputed, {run.attrs[f'drift_{name}']:.3g} stored"
    return True


@claim("hamiltonian: drift relative to the momenta", r"the largest \|momentum\| along the run")
def momentum_scale(data) -> bool | str:
    """each cyclic momentum's archived scale is the largest |momentum| of the archived run"""
    run = data.runs["main"]
    y = np.asarray(run.y, dtype=float)
    n = len(data.config["system"]["coordinates"])
    want = float(np.max(np.abs(y[:, n:])))
    for name in [str(c) for c in data.analysis.get("cyclic", [])]:
        scale = float(run.attrs.get(f"scale_p_{name}", math.nan))
        if not math.isclose(scale, want, rel_tol=1e-12) and want > 0:
            return f"p_{name}: archived scale {scale:.3g}, largest |momentum| {want:.3g}"
    return True


# ---------------------------------------------------------------- Jacobi identity
@claim("hamiltonian: Jacobi identity holds", r"holds: largest sum")
def jacobi_holds(data) -> bool | str:
    """the archived largest Jacobi sum is below 10⁻¹⁰ of the archived size of its terms"""
    a = data.analysis
    if not a["jacobi_max"] <= 1e-10 * a["jacobi_scale"]:
        return f"the Jacobi sum is {a['jacobi_max']:.2g} of terms of size {a['jacobi_scale']:.2g}"
    return True


@claim("hamiltonian: Jacobi identity fails", r"FAILS: largest sum")
def jacobi_fails(data) -> bool | str:
    """the archived largest Jacobi sum is above 10⁻¹⁰ of the archived size of its terms"""
    a = data.analysis
    if a["jacobi_max"] <= 1e-10 * a["jacobi_scale"]:
        return f"the Jacobi sum is {a['jacobi_max']:.2g} of terms of size {a['jacobi_scale']:.2g}"
    return True


@claim("hamiltonian: Jacobi identity not tested", r"not tested: every term is round-off")
def jacobi_not_tested(data) -> bool | str:
    """each archived Jacobi term is below 10⁻¹² of the size of its parts"""
    a = data.analysis
    terms, parts = np.asarray(a["jacobi_terms"]), np.asarray(a["jacobi_roundoff"])
    if np.any(terms > 1e-12 * parts):
        return f"a Jacobi term is {np.max(terms / np.maximum(parts, 1e-300)):.2g} of its parts"
    return True


# ------------------------------------------------- Noether, transforms, separations
def _charge_moves(data) -> float:
    """How much the declared symmetry's charge changes along the archived run, against
    its archived scale."""
    a, run = data.analysis, data.runs["main"]
    values = run.invariants.get("noether_charge")
    if values is None:
        values = a.get("noether_values")
    values = np.asarray(values, dtype=float)
    return float(np.ptp(values)) / max(float(a["noether_scale"]), 1e-300)


@claim("hamiltonian: a declared symmetry is one",
       r"zero: a symmetry, so the charge is conserved|zero: found conserved by the bracket too")
def noether_symmetry(data) -> bool | str:
    """the charge's archived values hold along the run to the drift bound"""
    moves = _charge_moves(data)
    if moves > float(data.runs["main"].attrs.get("drift_bound", 1e-6)):
        return f"the charge changes by {moves:.2g} of its scale along the run"
    return True


@claim("hamiltonian: a declared symmetry is not one",
       r"not zero: not a symmetry|\{Q, H\} \+ ∂Q/∂t, simplified \(the bracket test of the "
       r"observables\) not zero")
def noether_not_symmetry(data) -> bool | str:
    """the charge's archived values change along the run"""
    moves = _charge_moves(data)
    if moves <= NONZERO:
        return f"the charge changes by only {moves:.2g} of its scale along the run"
    return True


@claim("hamiltonian: generating function type", r"generating function of type F\d")
def generating_type(data) -> bool | str:
    """the type the archive names is the one formula the archived config's transform gives"""
    given = [k for k in ("F1", "F2", "F3", "F4", "G")
             if (data.config.get("transform") or {}).get(k) is not None]
    if given != [str(data.analysis.get("transform_kind"))]:
        return f"the config gives {given}, the archive says {data.analysis.get('transform_kind')}"
    return True


@claim("hamiltonian: G generates a symmetry", r"zero: G generates a symmetry")
def generator_symmetry(data) -> bool | str:
    """{H, G} of the archived config's G vanishes near the orbit"""
    from ...core import expressions

    system = _system(data)
    names = {**system.space.symbols_for_h(), **system.param_symbols}
    G = expressions.parse_expression(data.config["transform"]["G"], names)
    states = _states(data, system)
    if not _vanishes(_bracket(system, system.H, G), _values(system, states), len(states)):
        return "{H, G} is not zero near the orbit"
    return True


@claim("hamiltonian: brackets exactly J + ε²{w, w}", r"holds exactly in SymPy's algebra")
def infinitesimal_brackets(data) -> bool | str:
    """the brackets computed along the run agree with J + ε²{wᵢ, wⱼ} to 10⁻⁸ of their terms"""
    agreement = float(data.analysis["transform_bracket_agreement"])
    if agreement > 1e-8:
        return f"the brackets depart from the closed form by {agreement:.2g}"
    return True


@claim("hamiltonian: separation of the Kepler problem",
       r"Kepler's equation for t\(r\)")
def kepler_separation(data) -> bool | str:
    """the archived config separates the central potential, and the quadrature agrees with
    the run to 10⁻⁶ of the orbit's size"""
    return _separation(data, "central")


@claim("hamiltonian: separation of two centres", r"Charlier's quadratures")
def two_centres_separation(data) -> bool | str:
    """the archived config separates two centres, and the quadrature agrees with the run"""
    return _separation(data, "two_centres")


def _separation(data, kind: str) -> bool | str:
    given = (data.config.get("hamilton_jacobi") or {}).get("separation")
    if given != kind:
        return f"the archived config separates {given!r}"
    y = np.asarray(data.runs["main"].y, dtype=float)
    diff = max(float(np.max(np.abs(np.asarray(d, dtype=float))))
               for d in data.analysis["hamilton_jacobi"]["difference"].values())
    if diff > 1e-6 * max(float(np.max(np.abs(y))), 1.0):
        return f"the quadrature departs from the run by {diff:.2g}"
    return True


@claim("hamiltonian: L + dF/dt gives the same motion",
       r"yes: every E\(L'\) − E\(L\) simplifies to 0|yes, simplified by SymPy")
def total_derivative(data) -> bool | str:
    """H' at the shifted momenta equals H − ∂F/∂t along the run to 10⁻⁸ of its size"""
    a = data.analysis
    if a["total_derivative_H_error"] > 1e-8 * max(a["total_derivative_H_scale"], 1e-300):
        return f"H' departs from H − ∂F/∂t by {a['total_derivative_H_error']:.2g}"
    return True


# -------------------------------------------------------------- first-order L
def _det_along(data):
    system, run = _system(data), data.runs["main"]
    det = system.first_order.det
    return _at(det, system.values(np.asarray(run.y), np.asarray(run.t)), len(run.t))


@claim("hamiltonian: det ω keeps its sign", r"sign kept: ω invertible on the whole run")
def det_sign_kept(data) -> bool | str:
    """det ω derived again, on the archived run, keeps one sign"""
    det = _det_along(data)
    if not (np.all(det > 0) or np.all(det < 0)):
        return "det ω changes sign or vanishes on the run"
    return True


@claim("hamiltonian: V conserved", r"yes: V is conserved")
def v_conserved(data) -> bool | str:
    """the archived energy function holds along the run to the drift bound of its scale"""
    run = data.runs["main"]
    values = np.asarray(run.invariants.get("H", []), dtype=float)
    if values.size == 0:
        return "V is not archived as an invariant"
    scale = float(run.attrs.get("scale_H", np.max(np.abs(values))))
    if np.max(np.abs(values - values[0])) > float(run.attrs["drift_bound"]) * scale:
        return "V drifts beyond the bound"
    return True


@claim("hamiltonian: V changes", r"no: V changes along the run")
def v_changes(data) -> bool | str:
    """the archived energy function changes along the run"""
    series = np.asarray(data.analysis.get("observables", {}).get("H", []), dtype=float)
    if series.size == 0 or np.ptp(series) <= NONZERO * max(float(np.max(np.abs(series))),
                                                           1e-300):
        return "V does not change along the run"
    return True


@claim("hamiltonian: closed form of linear reduced equations",
       r"linear reduced equations q̇ = A q: closed form")
def linear_closed_form(data) -> bool | str:
    """the archived run agrees with exp(tA) q(0), computed here from the archived A"""
    from scipy.linalg import expm

    run = data.runs["main"]
    A = np.asarray(data.analysis["first_order_A"], dtype=float)
    y = np.asarray(run.y, dtype=float)
    closed = np.array([expm(t * A) @ y[0] for t in np.asarray(run.t)])
    error = float(np.max(np.abs(closed - y)))
    if error > 1e-6 * max(float(np.max(np.abs(y))), 1e-300):
        return f"the run departs from exp(tA) q(0) by {error:.2g}"
    return True
