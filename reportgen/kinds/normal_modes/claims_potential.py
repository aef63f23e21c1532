"""The claims of a ``normal_modes`` report about a written potential's equilibrium
(``[system]``, textbook §5.1), each measured again from the archive's raw record with numpy:
the stability from the archived M and A (not from the stored classification that chose the
words), the stationary point from the archived gradient."""

from __future__ import annotations

import numpy as np

from ...scene.claims import claim
from .claims import _omega2

#: ω² within this share of the largest count as zero (the simulation's is 10⁻¹⁰; a claim
#: fails only when it is measurably false)
_ZERO = 1e-9


@claim("normal modes: a minimum of U (A positive definite)", r"\bA is positive definite\b")
def positive_definite(data) -> bool | str:
    """every ω² of the archived (M, A), recomputed, is positive: q₀ is a minimum of U"""
    w2 = _omega2(data)
    low = float(w2.min()) / float(np.max(np.abs(w2)))
    return low > _ZERO or f"ω²ₘᵢₙ/max|ω²| = {low:.3g}"


@claim("normal modes: neutral to second order", r"\bneutral to second order\b"
       r"|\bneutral in some directions\b")
def neutral(data) -> bool | str:
    """the archived (M, A), recomputed, has a zero ω² and no negative one"""
    w2 = _omega2(data)
    scale = float(np.max(np.abs(w2)))
    if float(w2.min()) < -_ZERO * scale:
        return f"ω²ₘᵢₙ = {float(w2.min()):.3g} < 0: unstable"
    return bool(np.any(np.abs(w2) <= _ZERO * scale)) or "every ω² is positive: A is definite"


@claim("normal modes: a stationary point of U", r"\bthe stationary point it found\b")
def stationary(data) -> bool | str:
    """the archived gradient of U at q₀ is the stored norm's, and that is rounding: its
    relative size is below the archived threshold"""
    a = data.analysis
    g = np.asarray(a["equilibrium_gradient"], dtype=float)
    norm = float(np.linalg.norm(g))
    if not np.isclose(norm, float(a["equilibrium_gradient_norm"]), rtol=1e-12, atol=0.0):
        return f"|∇U| recomputed {norm:.6g}, stored {float(a['equilibrium_gradient_norm']):.6g}"
    residual, tol = float(a["equilibrium_residual"]), float(a["equilibrium_residual_tol"])
    return residual <= tol or f"relative gradient {residual:.3g} > {tol:.3g}"
