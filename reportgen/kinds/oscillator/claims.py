"""``oscillator``: the claim-carrying sentences of its reports and what makes each true
(:mod:`reportgen.scene.claims`).

Each predicate measures again from the archived runs and config, not from the stored fact
that chose the words (``swap_canonical``, ``hj_pair_constant``): the swap's Poisson bracket
from a linear fit of the archived image (Q, P) against the archived (q, p), not by SymPy;
E and β recomputed along the archived run; the closed form recomputed from the config.
"""

from __future__ import annotations

import math

import numpy as np

from ...scene.claims import claim

#: the thresholds the simulation decides by, and the margin a predicate allows its own
#: measurement: a word chosen within MARGIN × the threshold of it is not contradicted
CANONICAL_DEFECT, CONSTANT_DRIFT, MARGIN = 1e-9, 1e-6, 2.0
#: the archived reference within this of the closed form, relative to the amplitudes
CLOSED_FORM_MATCH = 1e-12


def _params(data) -> tuple[float, float, float, float]:
    p, ini = data.config.params, data.config.initial
    return float(p.m), float(p.omega), float(ini.q), float(ini.p)


def _bracket(data) -> float:
    """{Q, P} = ∂Q/∂q ∂P/∂p − ∂Q/∂p ∂P/∂q of the map (q, p) ↦ (Q, P), from the least-squares
    affine fit of the archived image of the orbit against the archived orbit."""
    main, swapped = data.runs["main"], data.runs["swapped"]
    basis = np.column_stack((main["q"], main["p"], np.ones_like(main["q"])))
    (dQ_dq, dQ_dp, _), *_ = np.linalg.lstsq(basis, swapped.reference["Q"], rcond=None)
    (dP_dq, dP_dp, _), *_ = np.linalg.lstsq(basis, swapped.reference["P"], rcond=None)
    return float(dQ_dq * dP_dp - dQ_dp * dP_dq)


def _drifts(data) -> tuple[float, float]:
    """The drifts of E (relative to E) and β (relative to the period) along the archived
    run: E = p²/2m + mω²q²/2, β = atan2(mωq, p)/ω − t taken modulo the period."""
    m, omega, _, _ = _params(data)
    run = data.runs["main"]
    q, p, t = run["q"], run["p"], run.t
    energy = p * p / (2 * m) + m * omega**2 * q * q / 2
    period = 2 * math.pi / omega
    beta = np.arctan2(m * omega * q, p) / omega - t
    shift = np.mod(beta - beta[0] + period / 2, period) - period / 2
    return (float(np.max(np.abs(energy - energy[0])) / energy[0]),
            float(np.max(np.abs(shift)) / period))


@claim("oscillator: canonical swap", r"so the map is canonical|\(canonical:")
def canonical(data) -> bool | str:
    """{Q, P} = 1 for the archived image of the orbit (a linear fit, not SymPy)"""
    bracket = _bracket(data)
    return True if abs(bracket - 1) < CANONICAL_DEFECT * MARGIN else (
        f"{{Q, P}} = {bracket:.12g} from the archived (q, p) and (Q, P)")


@claim("oscillator: swap not canonical", r"not canonical")
def not_canonical(data) -> bool | str:
    """{Q, P} ≠ 1 for the archived image of the orbit"""
    bracket = _bracket(data)
    return True if abs(bracket - 1) >= CANONICAL_DEFECT / MARGIN else (
        f"{{Q, P}} = {bracket:.12g} from the archived (q, p) and (Q, P): canonical")


@claim("oscillator: Hamilton–Jacobi pair constant", r"integrated trajectory stays constant")
def pair_constant(data) -> bool | str:
    """E and β recomputed along the archived run drift by less than the threshold"""
    e_drift, b_drift = _drifts(data)
    if max(e_drift, b_drift) < CONSTANT_DRIFT * MARGIN:
        return True
    return f"E drifts by {e_drift:.2g} of itself, β by {b_drift:.2g} of the period"


@claim("oscillator: Hamilton–Jacobi pair drifts", r"integrated trajectory drifts by more")
def pair_drifts(data) -> bool | str:
    """E or β recomputed along the archived run drifts by more than the threshold"""
    e_drift, b_drift = _drifts(data)
    if max(e_drift, b_drift) >= CONSTANT_DRIFT / MARGIN:
        return True
    return f"E drifts by {e_drift:.2g} of itself, β by {b_drift:.2g} of the period: constant"


@claim("oscillator: closed form", r"against the closed form|reference, the closed form|"
                                  r"[Ee]rror against the closed form")
def closed_form(data) -> bool | str:
    """the archived reference of the main run is q₀ cos ωt + p₀/(mω) sin ωt,
    p₀ cos ωt − mωq₀ sin ωt, recomputed from the config"""
    m, omega, q0, p0 = _params(data)
    run = data.runs["main"]
    c, s = np.cos(omega * run.t), np.sin(omega * run.t)
    q, p = q0 * c + p0 / (m * omega) * s, p0 * c - m * omega * q0 * s
    q_amp, p_amp = math.hypot(q0, p0 / (m * omega)), math.hypot(p0, m * omega * q0)
    if "q" not in run.reference or "p" not in run.reference:
        return "the main run has no archived reference"
    worst = max(float(np.max(np.abs(run.reference["q"] - q))) / q_amp,
                float(np.max(np.abs(run.reference["p"] - p))) / p_amp)
    return True if worst < CLOSED_FORM_MATCH else (
        f"the archived reference differs from the closed form by {worst:.2g} of the amplitude")


@claim("oscillator: three checks", r"checked three ways")
def three_checks(data) -> bool | str:
    """the archive holds the swapped run, started at (Q₀, P₀) = (p₀, −q₀), and the
    Hamilton–Jacobi solution along the main run"""
    _, _, q0, p0 = _params(data)
    if "swapped" not in data.runs:
        return "no swapped run in the archive"
    start = data.runs["swapped"].y[0]
    if not np.allclose(start, (p0, -q0), rtol=1e-15, atol=0):
        return f"the swapped run starts at {tuple(start)}, not (p₀, −q₀) = {(p0, -q0)}"
    hj = data.analysis.get("hamilton_jacobi", {})
    if "q" not in hj or len(hj["q"]) != len(data.runs["main"].t):
        return "no Hamilton–Jacobi solution along the main run in the archive"
    return True
