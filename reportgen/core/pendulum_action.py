r"""The action of the linearised pendulum's boundary-value problem as a function of its
ends and as a functional of the path.

The problem θ'' = −ω² θ, θ(0) = θ0, θ(T) = θ1 (lecture notes (1.21)) has the action
S(θ0, θ1, T) of notes (2.4); its closed forms are in :mod:`reportgen.core.pendulum_theory`.
Here, with I = m l²:

* :func:`end_variation` — ∂S/∂θ0, ∂S/∂θ1, ∂S/∂T of a *computed* action by central
  differences of neighbouring boundary-value solutions, for δS = p δq − H δt
  (notes (7.1–7.15)): −p(0), p(T) and −E;
* :func:`action_variations` — the phase-space action S = ∫ (p q̇ − H) dt (notes §5)
  on the closed-form solution and its first and second variations;
* :func:`free_particle_limit` — S and θ(t) as ω → 0 against the free rotor
  (notes (1.22) and (2.5)).

No integration: the paths are closed forms sampled on a grid, the integrals composite
Simpson sums.

References
----------
.. [1] Lecture notes §1 (1.21), (1.22); §2 (2.4), (2.5); §5 (5.1–5.6); §7 (7.1–7.15).
.. [2] NIST DLMF 4.19.6 (series of x cot x).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from . import pendulum_theory as theory
from .models.pendulum import linear_boundary_solution

#: finite-difference steps: this fraction of the ends' size (θ) and of the distance from T
#: to the nearest singular time k π/ω (T).  With Richardson's O(h⁴) the truncation is
#: ~4 (h/d)⁴ ≈ 4e-12 of ∂S/∂T; the solve_bvp action is smooth in its ends to ~1e-13, so
#: the round-off is ~1e-13/1e-3 ≈ 1e-10 at worst (measured: 2e-12 at T = 1.3 s, ω = 3.13 rad/s)
RELATIVE_STEP = 1e-3
#: Simpson points on [0, T] for the phase-space action (its error ~ (T/n)⁴ (kπ/T)⁴: < 1e-15)
SAMPLES = 20001
#: the variations' ε [rad], as a fraction of max(|θ0|, |θ1|): S is exactly quadratic in ε,
#: so central differences give dS/dε and d²S/dε² exactly; a large ε keeps round-off small
EPSILON_FRACTION = 0.1
#: mode numbers k of the perturbations sin(kπt/T)
MODES = (1, 2, 3)
#: ω/ω0 of the free-particle limit's rows
LIMIT_FRACTIONS = (1.0, 1e-1, 1e-2, 1e-3, 1e-6, 0.0)


def richardson_derivative(f: Callable[[float], float], x: float, h: float) -> float:
    """f'(x) by central differences at steps h and 2h, Richardson-extrapolated:
    (4 D(h) − D(2h))/3, D(h) = [f(x + h) − f(x − h)]/(2h); error O(h⁴)."""
    d1 = (f(x + h) - f(x - h)) / (2.0 * h)
    d2 = (f(x + 2.0 * h) - f(x - 2.0 * h)) / (4.0 * h)
    return (4.0 * d1 - d2) / 3.0


def end_variation(action: Callable[[float, float, float], float], theta0: float,
                  theta1: float, T: float, omega: float) -> dict:
    """The derivatives of a computed action S(θ0, θ1, T) with respect to its ends.

    Parameters
    ----------
    action : callable
        ``action(theta0, theta1, T)`` [J·s]: the action of the boundary-value solution
        with these ends, however it is computed (a numerical solve and quadrature).
    theta0, theta1 : float
        End angles [rad].
    T : float
        End time [s], not a conjugate point.
    omega : float
        √(g/l) [rad/s]: where the singular times k π/ω are, for the T step.

    Returns
    -------
    dict
        ``dS_dtheta0``, ``dS_dtheta1`` [J·s], ``dS_dT`` [J] (:func:`richardson_derivative`),
        ``step_theta`` [rad], ``step_T`` [s].  By notes (7.1–7.15), δS = p δq − H δt:
        −p(0), p(T) and −E.
    """
    h_theta = RELATIVE_STEP * (max(abs(theta0), abs(theta1)) or 1.0)
    h_T = RELATIVE_STEP * theory.conjugate_distance(T, omega)
    return {
        "dS_dtheta0": richardson_derivative(lambda a: action(a, theta1, T), theta0, h_theta),
        "dS_dtheta1": richardson_derivative(lambda b: action(theta0, b, T), theta1, h_theta),
        "dS_dT": richardson_derivative(lambda s: action(theta0, theta1, s), T, h_T),
        "step_theta": h_theta,
        "step_T": h_T,
    }


def linear_path(t, theta0, theta1, T, omega):
    """θ(t) and θ̇(t) of the solution, notes (1.21), of θ'' = −ω² θ with θ(0) = θ0, θ(T) = θ1.

    Parameters
    ----------
    t : ndarray, shape (N,)
        Times in [0, T] [s].

    Returns
    -------
    theta : ndarray, shape (N,)
        [θ0 sin ω(T − t) + θ1 sin ωt] / sin ωT [rad].
    theta_dot : ndarray, shape (N,)
        ω [−θ0 cos ω(T − t) + θ1 cos ωt] / sin ωT [rad/s].
    """
    t = np.asarray(t, dtype=np.float64)
    theta = linear_boundary_solution(t, theta0, theta1, T, omega)
    theta_dot = omega * (-theta0 * np.cos(omega * (T - t)) + theta1 * np.cos(omega * t)) \
        / math.sin(omega * T)
    return theta, theta_dot


def simpson(y, t) -> float:
    """Composite Simpson sum of ``y`` on the grid ``t`` (scipy's)."""
    from scipy.integrate import simpson as scipy_simpson

    return float(scipy_simpson(np.asarray(y, dtype=np.float64), x=t))


def phase_space_action(t, q, q_dot, p, inertia, omega) -> float:
    """S = ∫ (p q̇ − H) dt, notes §5, H = p²/(2I) + I ω² q²/2, by Simpson on ``t`` [J·s].

    ``q`` and ``p`` are independent paths (``q_dot`` the derivative of ``q``); only on a
    solution is p = I q̇ and the integrand the Lagrangian."""
    hamiltonian = p * p / (2.0 * inertia) + 0.5 * inertia * omega**2 * q * q
    return simpson(p * q_dot - hamiltonian, t)


def action_variations(theta0, theta1, T, omega, inertia, modes: Sequence[int] = MODES,
                      samples: int = SAMPLES) -> dict:
    """The phase-space action on the solution, notes (1.21), and its variations.

    The solution (q, p) = (θ, I θ̇) is sampled on ``samples`` points; the perturbations,
    ω_k = kπ/T, vanishing at both ends:

    * ``q``: δq = ε sin ω_k t, δp = 0;
    * ``p``: δq = 0, δp = ε I ω_k cos ω_k t;
    * ``qp``: both (δp = I δq̇, the variation of the Lagrangian action).

    S(ε) is a quadratic polynomial in ε (and so is its Simpson sum), so central
    differences at ±ε give dS/dε and d²S/dε² at ε = 0 up to round-off.

    Returns
    -------
    dict
        ``action_hamiltonian`` ∫ (p q̇ − H) dt and ``action_lagrangian`` ∫ L dt [J·s] on the
        solution; ``mode`` (K,) int; ``first_variation_<name>``, ``second_variation_<name>``
        and ``second_variation_<name>_exact`` (K,) [J·s] for ``name`` in q, p, qp
        (:func:`~reportgen.core.pendulum_theory.phase_space_second_variations`);
        ``first_variation_free_path`` (K,) [J·s], δq about the free path
        θ0 + (θ1 − θ0) t/T with p = I q̇ (not a solution), and its closed form
        ``first_variation_free_path_exact`` = −I ω² (T/kπ) [θ0 − (−1)^k θ1];
        ``epsilon`` [rad]; ``samples``.
    """
    t = np.linspace(0.0, T, samples)
    q, q_dot = linear_path(t, theta0, theta1, T, omega)
    p = inertia * q_dot

    def action(q, q_dot, p):
        return phase_space_action(t, q, q_dot, p, inertia, omega)

    eps = EPSILON_FRACTION * (max(abs(theta0), abs(theta1)) or 1.0)
    s0 = action(q, q_dot, p)
    free_q = theta0 + (theta1 - theta0) * t / T
    free_q_dot = np.full_like(t, (theta1 - theta0) / T)
    out: dict = {"action_hamiltonian": s0,
                 "action_lagrangian": simpson(0.5 * inertia * (q_dot**2 - omega**2 * q**2), t),
                 "mode": np.asarray(modes, dtype=np.int64), "epsilon": eps,
                 "samples": int(samples)}
    rows: dict[str, list[float]] = {}
    zero = np.zeros_like(t)
    for k in modes:
        wk = k * math.pi / T
        eta, eta_dot = np.sin(wk * t), wk * np.cos(wk * t)
        zeta = inertia * eta_dot
        exact = dict(zip(("q", "p", "qp"),
                         theory.phase_space_second_variations(T, omega, inertia, k), strict=True))
        for name, (dq, dq_dot, dp) in {"q": (eta, eta_dot, zero), "p": (zero, zero, zeta),
                                       "qp": (eta, eta_dot, zeta)}.items():
            plus = action(q + eps * dq, q_dot + eps * dq_dot, p + eps * dp)
            minus = action(q - eps * dq, q_dot - eps * dq_dot, p - eps * dp)
            rows.setdefault(f"first_variation_{name}", []).append((plus - minus) / (2 * eps))
            rows.setdefault(f"second_variation_{name}", []).append(
                (plus - 2.0 * s0 + minus) / eps**2)
            rows.setdefault(f"second_variation_{name}_exact", []).append(exact[name])
        free = [action(free_q + s * eps * eta, free_q_dot + s * eps * eta_dot,
                       inertia * free_q_dot) for s in (1.0, -1.0)]
        rows.setdefault("first_variation_free_path", []).append((free[0] - free[1]) / (2 * eps))
        rows.setdefault("first_variation_free_path_exact", []).append(
            -inertia * omega**2 * T / (k * math.pi) * (theta0 - (-1) ** k * theta1))
    out.update({name: np.asarray(v) for name, v in rows.items()})
    return out


#: (sin a − a)/a³ = Σ (−1)^n a^(2n−2)/(2n+1)!, n = 1 … 8, below |a| = 1/2 (the first
#: omitted term is 2e-19 of the sum there)
_SINC_EXCESS = tuple((-1) ** n / math.factorial(2 * n + 1) for n in range(1, 9))


def _sinc_excess(a):
    """(sin a − a)/a³, elementwise, to full relative precision (−1/6 at a = 0)."""
    a = np.asarray(a, dtype=np.float64)
    a2 = a * a
    series = np.zeros_like(a)
    for c in reversed(_SINC_EXCESS):
        series = series * a2 + c
    with np.errstate(invalid="ignore", divide="ignore"):
        direct = (np.sin(a) - a) / (a2 * a)
    return np.where(np.abs(a) < 0.5, series, direct)


def path_excess(t, theta0, theta1, T, omega):
    """θ(t) − θ_free(t) of the solution, notes (1.21), against the free rotor
    θ0 + (θ1 − θ0) t/T, notes (1.22) [rad], without cancellation as ω → 0.

    With f(a) = sin a / a = 1 + a² g(a): sin ωτ / sin ωT − τ/T = (τ/T) ω² [τ² g(ωτ) −
    T² g(ωT)] / f(ωT), for τ = t (θ1's term) and τ = T − t (θ0's)."""
    t = np.asarray(t, dtype=np.float64)
    x = omega * T
    f_T = theory.x_over_sin_x(x) ** -1
    g_T = float(_sinc_excess(x))

    def weight_excess(tau):
        return tau / T * omega**2 * (tau**2 * _sinc_excess(omega * tau) - T**2 * g_T) / f_T

    return theta0 * weight_excess(T - t) + theta1 * weight_excess(t)


def free_particle_limit(theta0, theta1, T, omega0, inertia,
                        fractions: Sequence[float] = LIMIT_FRACTIONS, samples: int = 2001) -> dict:
    """The linear problem's action and path as ω = fraction × ω0 → 0.

    Returns
    -------
    dict
        ``omega`` (R,) [rad/s]; ``action`` S (:func:`~reportgen.core.pendulum_theory.linear_action`)
        and ``action_excess`` S − S_free (R,) [J·s]; ``action_excess_leading`` (R,) [J·s],
        −∫ V dt along the free path, the O(ω²) term of S − S_free; ``path_excess`` (R,)
        [rad], max over t of |θ − θ_free| on ``samples`` points; ``action_free`` S_free [J·s].
    """
    t = np.linspace(0.0, T, samples)
    omega = omega0 * np.asarray(fractions, dtype=np.float64)
    rows = [(theory.linear_action(theta0, theta1, T, w, inertia),
             theory.linear_action_excess(theta0, theta1, T, w, inertia),
             -theory.free_path_potential_action(theta0, theta1, T, w, inertia),
             float(np.max(np.abs(path_excess(t, theta0, theta1, T, w)))))
            for w in map(float, omega)]
    action, excess, leading, deviation = (np.array(c) for c in zip(*rows, strict=True))
    return {"omega": omega, "action": action, "action_excess": excess,
            "action_excess_leading": leading, "path_excess": deviation,
            "action_free": theory.free_particle_action(theta0, theta1, T, inertia)}
