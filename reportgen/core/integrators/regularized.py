r"""``levi_civita``: the Kepler problem integrated in Levi-Civita variables.

For the pure inverse-square force the model carries its Levi-Civita regularization
(``extra["levi_civita"]``: GM and the transformation, which the Kepler model offers; this
module names no model) and the orbit is carried to the regularized harmonic oscillator
(LC) it defines, integrated
there with ``gauss6`` at a step uniform in the fictitious time s (dt/ds = r: uniform in
eccentric anomaly, so the physical step shrinks ∝ r at pericentre and a highly eccentric
orbit costs no more than a circle), and brought back to the requested physical times:

1. The step: gauss6 on (LC) is the (3,3) Padé approximant of the oscillator's flow, so
   its phase error per orbit is ∝ 1/N⁶ with N steps per orbit; :func:`steps_per_orbit`
   gives the N for a position error per orbit of ≈ ``rtol`` · a (measured), and the run
   takes :func:`grid_steps_per_orbit` = the N for a tenth of that (``SAFETY``), so that
   the error stays below ``rtol`` · a over about ten orbits, as the two-pass version did
   through the extra steps its dense outputs forced.
2. One pass, solved in closed form.  The (w, w') part of (LC) is linear with constant
   coefficients, so gauss6's stage equations are linear and are solved exactly
   (:func:`_stage_weights`: a 3×3 elimination, what simplified Newton with the exact
   Jacobian reaches in one iteration): a step of size σ is a fixed matrix R(σ) on each
   (w_k, w_k') and a quadratic form for its t increment σ Σ b_i |W_i|².  R(ds) is a
   rotation of (w, w'/ω) by an angle φ (it conserves the quadratic invariant
   ω²|w|² + |w'|²), so the state after n steps, R(ds)ⁿ u₀, is the rotation by nφ,
   evaluated directly: no round-off accumulates in it, and t is summed with compensation.
   Each output t lies in one step [t_n, t_{n+1}]; its state is one gauss6 step of size
   σ from the grid state u_n, σ solved from t_n + τ(σ) = t by Newton's method, started on
   the quintic Hermite interpolant of t over the step.  Every output is thus a gauss6
   state (n steps of ds, one of σ), at t exactly.
3. Energy, angular momentum and the LRL vector are quadratic invariants of (LC) (the
   oscillator's energy, its angular momentum w × w' and its Fradkin tensor), which Gauss
   collocation conserves exactly: they stay at round-off at every output.  The phase
   (the time t(s) of each point of the orbit) carries the method's error.

Bound orbits only (E < 0): the step is a fraction of the orbit's fictitious period.

References
----------
.. [1] Stiefel & Scheifele, *Linear and Regular Celestial Mechanics* (1971), §4, §9.
.. [2] Hairer, Lubich, Wanner, *Geometric Numerical Integration*, 2nd ed., VIII.2
       (time transformations, Levi-Civita), IV.2 (Gauss methods conserve quadratic
       invariants).
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from .base import Method, Solution
from .status import Status
from .symplectic import Gauss6

#: gauss6 on (LC) at N steps per orbit: the largest position error over one orbit is
#: ≈ STEP_CONSTANT · a · √((1 + e)/(1 − e)) / N⁶ (measured for e = 0 … 0.99 at N = 16 … 64:
#: 0.36, 1.16, 2.65, 5.07 at e = 0, 0.5, 0.9, 0.99; the phase error in s is the same
#: oscillator's at every e, times the pericentre speed in t)
STEP_CONSTANT = 0.36
#: fewest steps per orbit (below it the quintic first guess of an output's σ loses its order)
MIN_STEPS_PER_ORBIT = 16
#: the run's steps aim at this fraction of ``rtol`` · a per orbit (:func:`grid_steps_per_orbit`)
SAFETY = 0.1
#: gauss6's step budget per run (as the policy's default)
DEFAULT_MAX_STEPS = 10_000_000


def steps_per_orbit(rtol: float, eccentricity: float) -> int:
    """N steps per orbit for a position error per orbit of ≈ ``rtol`` · a."""
    speed = math.sqrt((1.0 + eccentricity) / (1.0 - eccentricity))
    return max(MIN_STEPS_PER_ORBIT, math.ceil((STEP_CONSTANT * speed / rtol) ** (1.0 / 6.0)))


def grid_steps_per_orbit(rtol: float, eccentricity: float) -> int:
    """The steps per orbit ``levi_civita`` takes at ``rtol``: :func:`steps_per_orbit` for
    ``SAFETY`` · ``rtol`` (10^(1/6) ≈ 1.47 times as many; measured at e = 0.99, rtol 1e-12,
    20 orbits: position error 1.8e-11 at 132 steps per orbit, ≤ 1e-11 from ~146)."""
    return steps_per_orbit(SAFETY * rtol, eccentricity)


def _bound_orbit(method: str, model, y0):
    """(the model's Levi-Civita transform, specific energy h of the Kepler orbit from
    ``y0``); a ValueError naming ``method`` unless it is bound (h < 0), which both
    regularizations need."""
    lc = model.extra["levi_civita"]
    energy = lc.specific_energy(y0)
    if not energy < 0.0:
        raise ValueError(f"y0: method '{method}' needs a bound orbit (specific energy "
                         f"< 0), got {energy:.6g}")
    return lc, energy


_COMPILED = [False]


def _warm() -> float:
    """Compile (or load from numba's cache) the kernel once per process; the seconds."""
    if _COMPILED[0]:
        return 0.0
    from .levi_civita_kernels import lc_gauss6_outputs as _lc_gauss6_outputs

    t0 = time.perf_counter()
    Y = np.empty((2, 5))
    _lc_gauss6_outputs(Gauss6.A, Gauss6.b, Gauss6.c, -1.0, 0.1, np.array([1.0, 0, 0, 0.5]),
                       np.array([0.0, 0.01]), 0, 2, Y, np.zeros(3), 100)
    _COMPILED[0] = True
    return time.perf_counter() - t0


#: kernel calls (chunks of the outputs) when a progress callback is given
_PROGRESS_CHUNKS = 20


class LeviCivita(Method):
    """Levi-Civita regularization + Gauss–Legendre 6, for the inverse-square force only.

    ``adaptive`` in the sense the study and the policy use: it takes ``rtol`` (not ``h``)
    and sets its own step, uniform in s and so ∝ r in t.
    """

    name, label, order = "levi_civita", "Levi-Civita + Gauss–Legendre 6 (Kepler only)", 6
    adaptive = True
    implicit = True
    needs_kepler = True
    compiled = False

    def solve(self, model, y0, t_eval, rtol, atol, progress=None) -> Solution:
        from .levi_civita_kernels import lc_gauss6_outputs as _lc_gauss6_outputs

        t_eval = np.ascontiguousarray(t_eval, dtype=np.float64)
        lc, energy = _bound_orbit(self.name, model, y0)
        elements = lc.orbital_elements(y0)
        n_orbit = grid_steps_per_orbit(rtol, elements["eccentricity"])
        ds = lc.fictitious_period(energy) / n_orbit
        compile_s = _warm()
        t0 = time.perf_counter()
        state0 = lc.to_regularized(*y0, t=float(t_eval[0]))
        N = t_eval.size
        Yr = np.full((N, 5), np.nan)
        carry = np.array([0.0, float(t_eval[0]), 0.0])
        n_chunks = _PROGRESS_CHUNKS if (progress is not None and N > _PROGRESS_CHUNKS) else 1
        bounds = np.linspace(0, N, n_chunks + 1).round().astype(int)
        status = 0
        for k in range(n_chunks):
            status = _lc_gauss6_outputs(Gauss6.A, Gauss6.b, Gauss6.c, float(energy), ds,
                                        np.ascontiguousarray(state0[:4]), t_eval,
                                        int(bounds[k]), int(bounds[k + 1]), Yr, carry,
                                        DEFAULT_MAX_STEPS)
            if progress is not None:
                progress(float(bounds[k + 1]) / N)
            if status != 0:
                break
        with np.errstate(invalid="ignore"):  # the NaN rows a failed run leaves
            x, y, vx, vy, _ = lc.from_regularized(Yr)
        Y = np.column_stack([x, y, vx, vy])
        Y[0] = y0  # t_eval[0] is the start: y0 exactly, as every method returns it
        steps = int(carry[0]) + N  # the grid's steps and one step of size σ per output
        code = Status.OK if status == 0 else (Status.MAX_STEPS if status == 1
                                              else Status.NEWTON)
        message = "ok"
        if status == 1:
            message = (f"{self.name}: more than {DEFAULT_MAX_STEPS} gauss6 steps in "
                       f"fictitious time (the step budget)")
        elif status == 2:
            message = (f"{self.name}: the fictitious time of an output did not converge")
        return Solution(t=t_eval.copy(), y=Y, method=self.name, rtol=float(rtol),
                        atol=float(atol), h=None, nfev=3 * steps, nsteps=steps, nreject=0,
                        code=code, message=message,
                        wall_time_s=time.perf_counter() - t0, compile_time_s=compile_s)


class LeviCivitaDop853(Method):
    """Levi-Civita regularization + DOP853 in the fictitious time, for the inverse-square
    force only: the adaptive sibling of :class:`LeviCivita`.

    (LC) is a harmonic oscillator in s, as smooth at pericentre as at apocentre, so DOP853's
    steps in s are nearly uniform in eccentric anomaly whatever the eccentricity: 10 orbits
    at e = 0.95 take 101 steps (1,532 evaluations) at rtol 1e-10, where DOP853 on the
    Cartesian equations takes 16,800 evaluations.  The outputs at the physical times are
    located on each step's 7th-order continuous extension by Newton's method on its t
    component (:func:`.fictitious_time.integrate_fictitious_time`), so they are as accurate
    as the steps.  ``rtol``/``atol`` apply to the regularized state (w, w', t).

    Unlike :class:`LeviCivita` (Gauss collocation) it does not keep the energy at
    round-off: DOP853's error drifts it like any non-symplectic method's.  ``auto`` keeps
    choosing ``levi_civita`` for eccentric orbits; this one is for speed at a given phase
    error, and is one of ours in the error-against-run-time study.
    """

    name, label, order = "levi_civita_dop853", "Levi-Civita + DOP853 (Kepler only)", 8
    adaptive = True
    needs_kepler = True
    compiled = False

    def solve(self, model, y0, t_eval, rtol, atol, progress=None) -> Solution:
        from .fictitious_time import integrate_fictitious_time

        start = time.perf_counter()
        y0 = np.asarray(y0, dtype=np.float64)
        t_eval = np.ascontiguousarray(t_eval, dtype=np.float64)
        lc, energy = _bound_orbit(self.name, model, y0)
        sol = integrate_fictitious_time(lc.model(energy), lc.to_regularized(*y0, t=float(
            t_eval[0])), t_eval, 4, rtol, atol, progress=progress)
        x, y, vx, vy, _ = lc.from_regularized(sol.y)
        Y = np.column_stack([x, y, vx, vy])
        Y[0] = y0  # t_eval[0] is the start: y0 exactly, as every method returns it
        message = sol.message if sol.ok else f"{self.name}: {sol.message}"
        # the wall time is the whole call's (conversions included), compile excluded
        return replace(sol, y=Y, method=self.name, message=message,
                       wall_time_s=time.perf_counter() - start - sol.compile_time_s)
