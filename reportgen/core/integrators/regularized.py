r"""``levi_civita``: the Kepler problem integrated in Levi-Civita variables.

For the pure inverse-square force the model carries its Levi-Civita regularization
(``extra["levi_civita"]``: GM and the transformation, which the Kepler model offers; this
module names no model) and the orbit is carried to the regularized harmonic oscillator
(LC) it defines, integrated
there with ``gauss6`` at a step uniform in the fictitious time s (dt/ds = r: uniform in
eccentric anomaly, so the physical step shrinks ∝ r at pericentre and a highly eccentric
orbit costs no more than a circle), and brought back to the requested physical times:

1. The step: gauss6 on (LC) is the (3,3) Padé approximant of the oscillator's flow, so
   its phase error per orbit is ∝ 1/N⁶ with N steps per orbit; N is chosen so that the
   position error per orbit is ≈ ``rtol`` · a (:func:`steps_per_orbit`, measured), like an
   adaptive method's tolerance, which bounds the error per stretch of steps rather than
   over any number of orbits.
2. Output, two passes: t(s) is a state component.  The first run stores the state every
   ds; the s of each requested t is found by Newton's method on the quintic Hermite
   interpolant of t(s) (the transform's ``fictitious_times``, error O(ds⁶)).
   The second run steps (≤ ds) straight to those s, so every output is a gauss6 state,
   not an interpolated one, and a Taylor step of Δs ~ 1e-12 puts it at t exactly
   (the transform's ``shift_to_times``).
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

#: gauss6 on (LC) at N steps per orbit: the largest position error over one orbit is
#: ≈ STEP_CONSTANT · a · √((1 + e)/(1 − e)) / N⁶ (measured for e = 0 … 0.99 at N = 16 … 64:
#: 0.36, 1.16, 2.65, 5.07 at e = 0, 0.5, 0.9, 0.99; the phase error in s is the same
#: oscillator's at every e, times the pericentre speed in t)
STEP_CONSTANT = 0.36
#: fewest steps per orbit (below it the quintic interpolation of t(s) loses its order)
MIN_STEPS_PER_ORBIT = 16
#: fictitious-time steps of the first pass kept at once (bounds the memory of long runs)
CHUNK_STEPS = 100_000
#: gauss6's step budget per run (as the policy's default)
DEFAULT_MAX_STEPS = 10_000_000


def steps_per_orbit(rtol: float, eccentricity: float) -> int:
    """N steps per orbit for a position error per orbit of ≈ ``rtol`` · a."""
    speed = math.sqrt((1.0 + eccentricity) / (1.0 - eccentricity))
    return max(MIN_STEPS_PER_ORBIT, math.ceil((STEP_CONSTANT * speed / rtol) ** (1.0 / 6.0)))


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


def _gauss6(reg, state, s, ds, progress=None) -> Solution:
    """(LC) from ``state`` at s[0] to the fictitious times ``s`` with gauss6, steps ≤ ``ds``."""
    from .compiled_run import run_compiled
    from .symplectic import Gauss6

    return run_compiled(Gauss6(), reg, np.ascontiguousarray(state, dtype=np.float64),
                        np.ascontiguousarray(s, dtype=np.float64), 0.0, 0.0, ds, progress,
                        DEFAULT_MAX_STEPS)


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
        lc, energy = _bound_orbit(self.name, model, y0)
        elements = lc.orbital_elements(y0)
        n_orbit = steps_per_orbit(rtol, elements["eccentricity"])
        ds = lc.fictitious_period(energy) / n_orbit
        reg = lc.model(energy)
        state0 = lc.to_regularized(*y0, t=float(t_eval[0]))
        t0 = time.perf_counter()
        s_out, first = self._fictitious_times(lc, reg, state0, t_eval, ds, elements,
                                              n_orbit, progress)
        if not first.ok:
            return self._solution(t_eval, np.full((t_eval.size, 4), np.nan), first, [first],
                                  time.perf_counter() - t0, rtol, atol)
        # second pass: gauss6 straight to each output's s (steps ≤ ds), so every output is
        # a state of the method itself, invariant at round-off; then the tiny shift to t
        second = _gauss6(reg, state0, s_out, ds, progress=None if progress is None else
                         (lambda f: progress(0.5 + 0.5 * f)))
        x, y, vx, vy, _ = lc.from_regularized(lc.shift_to_times(second.y, t_eval, energy))
        Y = np.column_stack([x, y, vx, vy])
        Y[0] = y0  # t_eval[0] is the start: y0 exactly, as every method returns it
        return self._solution(t_eval, Y, second, [first, second], time.perf_counter() - t0,
                              rtol, atol)

    @staticmethod
    def _fictitious_times(lc, reg, state0, t_eval, ds, elements, n_orbit, progress):
        """First pass: (LC) every ``ds`` from ``state0`` until t passes ``t_eval[-1]``, in
        chunks; the s of each output (``lc.fictitious_times``, ``lc`` the model's
        transform) and the last chunk's run (with every chunk's counters added)."""
        # t(s) − t0 ≥ T (s/s_orbit − e/π) (Kepler's equation, E ∝ s): steps to t_end
        span = float(t_eval[-1] - t_eval[0])
        needed = math.ceil((span / elements["period"] + elements["eccentricity"] / math.pi)
                           * n_orbit) + 2
        chunk = min(CHUNK_STEPS, needed)  # one run, unless very long
        h = float(reg.params[0])
        s_out = np.empty(t_eval.size)
        done, s0, state, counts = 0, 0.0, state0, np.zeros(3)
        while done < t_eval.size:
            sol = _gauss6(reg, state, np.arange(chunk + 1) * ds, ds)
            counts += (sol.nfev, sol.nsteps, sol.compile_time_s)
            if not sol.ok:
                break
            upto = int(np.searchsorted(t_eval, sol.y[-1, 4], side="right"))
            s_out[done:upto] = s0 + lc.fictitious_times(ds, sol.y, t_eval[done:upto], h)
            done, s0, state = upto, s0 + chunk * ds, sol.y[-1]
            if progress is not None:
                progress(0.5 * done / t_eval.size)  # the second pass reports the rest
        s_out[0] = 0.0
        return s_out, replace(sol, nfev=int(counts[0]), nsteps=int(counts[1]),
                              compile_time_s=float(counts[2]))

    def _solution(self, t_eval, Y, last, runs, wall, rtol, atol) -> Solution:
        compile_s = sum(r.compile_time_s for r in runs)
        message = "ok" if last.ok else (f"{self.name}: the gauss6 run in fictitious time "
                                        f"failed: {last.message}")
        return Solution(t=t_eval.copy(), y=Y, method=self.name, rtol=float(rtol),
                        atol=float(atol), h=None, nfev=sum(r.nfev for r in runs),
                        nsteps=sum(r.nsteps for r in runs), nreject=0, code=last.code,
                        message=message, wall_time_s=wall - compile_s,
                        compile_time_s=compile_s)


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
