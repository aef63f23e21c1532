"""The solver policy, in one place: which integrator runs, and what its run means.

A :class:`SolverSpec` says what was asked (``method = "auto"`` or a name, the
tolerances, the step); :func:`solve` decides and runs:

1. ``auto`` picks a method from the model's structure (:func:`choose_auto`);
2. the run's outcome is read from the integrator's :class:`~.base.SolveCode` (the one
   vocabulary, :class:`~.status.Status`), and archived as its :class:`RunStatus`;
3. an explicit adaptive run is checked for stiffness
   (:func:`reportgen.core.integrators.stability.stiffness_signs`): an *automatic* choice that
   looks stiff is rerun with the implicit fallback (``radau``) and says so; a method
   *named* by the user that looks stiff is kept and flagged.

The verdict is a :class:`RunStatus`; callers branch on it, never on message text
(``message`` and ``reason`` are sentences for the report).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from . import stability
from .base import STATUS_OF_CODE, RunStatus, Solution
from .driver import integrate
from .registry import METHODS

#: Beyond ~1e5 periods DOP853's linearly growing energy error (~1e-14 per period at
#: rtol 1e-12) becomes visible; below it DOP853 is both faster and more accurate in
#: phase than a fixed-step method with a heuristic step (measured by `reportgen audit`).
LONG_RUN_PERIODS = 1e5
#: the implicit method an automatic choice switches to when it turns out stiff
STIFF_FALLBACK = "radau"
#: for a stiff separable model whose fastest frequency is known (``model.extra["omega_max"]``)
OSCILLATORY_STIFF = "gauss6"
#: its step, h·ω_max (Gauss–Legendre 6 resolves the fast mode to ~1e-12 at this step)
OSCILLATORY_STEP = 0.5
DEFAULT_MAX_STEPS = 10_000_000
#: A bound Kepler orbit (a model offering ``extra["levi_civita"]``) goes to ``levi_civita``
#: at any eccentricity and length: it is the method that meets the asked tolerance on the
#: scene's own error measure, the energy, and DOP853 at the same rtol is not.  Measured
#: (``python benchmarks/kepler_auto.py policy``; GM = a = 1 from pericentre, 100 outputs
#: per orbit, max |ΔE/E| over the run, best of 5): at e = 0.1 … 0.95, 1 … 1000 orbits and
#: rtol 1e-8 … 1e-13 (96 cases), DOP853 missed the rtol on the energy in every case, by 3x
#: to 9600x (its error grows
#: by about rtol every orbit: e = 0.7, 100 orbits, rtol 1e-10 -> 2.5e-8), and reaching it
#: takes an rtol up to ~300N times tighter, out of reach below ~1e-12 (over 10 orbits its
#: floor is 1.5e-12 … 5e-12); levi_civita met it in every case (|ΔE/E| ≤ 6e-14), at
#: 0.38 µs per output (0.4 ms for 10 orbits, 3.9 ms for 100) whatever the rtol.  (DOP853
#: at a tightened rtol is cheaper on short, loose runs (e = 0.5, 10 orbits, target 1e-8:
#: rtol 3.2e-10 in 0.17 ms against 0.38 ms), but ``auto`` runs the tolerance asked.)
#: Levi-Civita + DOP853 drifts like DOP853 (no better than 4.7e-12 at any rtol over 1000
#: orbits, e = 0.9), so it is not the choice.
KEPLER_ENERGY_MEASURED = ("e = 0.1 to 0.95, 1 to 1000 orbits, rtol 1e-8 to 1e-13")


@dataclass(frozen=True, kw_only=True)
class SolverSpec:
    """What was asked of the solver; checked when built.

    Attributes
    ----------
    method : str
        ``"auto"`` or a key of ``METHODS``.
    rtol, atol : float
        Tolerances of adaptive methods (and the target of a fixed step left to
        :func:`~.compiled_run.default_step`).
    h : float or None
        Step of fixed-step methods; None lets the driver choose.
    max_steps : int
        Budget of attempted steps (accepted + rejected) of the compiled methods.
    reason : str
        Why a named method was chosen (the archived ``method_reason``); ignored for
        ``auto``, which gives its own.
    """

    method: str = "auto"
    rtol: float
    atol: float
    h: float | None = None
    max_steps: int = DEFAULT_MAX_STEPS
    reason: str = ""

    def __post_init__(self):
        methods = METHODS
        if not isinstance(self.method, str) or (self.method != "auto"
                                                and self.method not in methods):
            raise ValueError(f"method: unknown integrator {self.method!r} (known: auto, "
                             f"{', '.join(sorted(methods))})")
        if not (isinstance(self.rtol, numbers.Real) and 0.0 < self.rtol < 1.0):
            raise ValueError(f"rtol: expected 0 < rtol < 1, got {self.rtol!r}")
        if not (isinstance(self.atol, numbers.Real) and 0.0 < self.atol < math.inf):
            raise ValueError(f"atol: expected a positive finite number, got {self.atol!r}")
        if self.h is not None and not (isinstance(self.h, numbers.Real)
                                       and 0.0 < self.h < math.inf):
            raise ValueError(f"h: expected a positive finite step or None, got {self.h!r}")
        if isinstance(self.max_steps, bool) or not isinstance(self.max_steps, numbers.Integral) \
                or self.max_steps < 1:
            raise ValueError(f"max_steps: expected a positive integer, got {self.max_steps!r}")

    @property
    def auto(self) -> bool:
        return self.method == "auto"


@dataclass(frozen=True)
class PolicyResult:
    """The run :func:`solve` kept, and what the policy made of it.

    Attributes
    ----------
    solution : Solution
        The kept run (the fallback's after a switch).
    method : str
        The method that produced ``solution``.
    reason : str
        One or two sentences: why this method (archived as ``method_reason``).
    status : RunStatus
    message : str
        Empty for a clean run; otherwise what went wrong, for the report.
    stiffness : str
        The stiffness sign found in the first run ("" if none).
    """

    solution: Solution
    method: str
    reason: str
    status: RunStatus
    message: str = ""
    stiffness: str = ""


def choose_auto(model, rtol: float, n_periods: float | None = None,
                y0=None) -> tuple[str, str]:
    """``method = "auto"``: (method name, one-sentence reason) from the model's structure.

    Decision (from benchmarks/bench_pendulum.py, see benchmarks/README.md): stiff ->
    scipy Radau; a bound Kepler orbit (the model offers ``levi_civita``; ``y0`` given) ->
    ``levi_civita`` (the energy at round-off, where DOP853's grows about rtol per orbit:
    see the comment at ``KEPLER_ENERGY_MEASURED``); otherwise DOP853 with dense
    output, which reaches a given accuracy fastest over short and moderate runs; for
    long runs (``n_periods`` >= ``LONG_RUN_PERIODS``) of a separable Hamiltonian a
    symplectic method keeps the energy error bounded where DOP853's error grows linearly
    in time.
    """
    omega_max = model.extra.get("omega_max")
    if model.stiff_hint and model.separable is not None and omega_max:
        # Oscillatory stiffness: the fast mode is excited and must be followed, so Radau
        # both damps it and needs ~10⁶ steps at rtol 1e-12.  Gauss–Legendre 6 is implicit
        # (A-stable) and symplectic: no stability bound on h, no damping; h resolves ω_max.
        return OSCILLATORY_STIFF, (
            f"model '{model.name}' is marked stiff with its fastest frequency ω_max = "
            f"{omega_max:.6g} excited: the implicit symplectic Gauss–Legendre 6 with h = "
            f"{OSCILLATORY_STEP:g}/ω_max follows the fast mode without damping it (Radau "
            "would damp it).")
    if model.stiff_hint:
        return STIFF_FALLBACK, (f"model '{model.name}' is marked stiff, so the implicit scipy "
                                "Radau solver is used.")
    eccentricity = _bound_kepler_eccentricity(model, y0)
    if eccentricity is not None:
        length = (f" over {n_periods:.4g} orbits" if n_periods is not None else "")
        return "levi_civita", (
            f"Kepler orbit (e = {eccentricity:.4g}){length}: Levi-Civita regularization with "
            "Gauss–Legendre 6 steps uniformly in eccentric anomaly and keeps the energy at "
            f"round-off, meeting rtol {rtol:g} on it; Cartesian DOP853 at that rtol "
            "misses it, its energy error growing by about rtol every orbit (measured at "
            f"{KEPLER_ENERGY_MEASURED}: 3 to 9600 times the rtol).")
    if model.separable is not None and n_periods is not None and n_periods >= LONG_RUN_PERIODS:
        return "yoshida6", (f"H = T(p) + V(q) over {n_periods:g} periods: a symplectic "
                            "method keeps the energy error bounded instead of drifting.")
    if model.separable is not None:
        return "dop853", (f"H = T(p) + V(q) but a short run: DOP853 with dense output is "
                          f"the fastest way to reach rtol {rtol:g} here (measured).")
    return "dop853", (f"general non-stiff system: adaptive DOP853 with dense output at "
                      f"rtol {rtol:g}.")


def _bound_kepler_eccentricity(model, y0) -> float | None:
    """e of the bound Kepler orbit through ``y0`` (None: not Kepler, not bound, no y0, or
    ``y0`` at the centre or not finite)."""
    if y0 is None or "levi_civita" not in model.extra:
        return None
    x, y, vx, vy = (float(v) for v in y0)
    if not (math.hypot(x, y) > 0.0 and math.isfinite(vx) and math.isfinite(vy)):
        return None  # no orbit through the centre (1/r): the run reports what happens
    elements = model.extra["levi_civita"].orbital_elements((x, y, vx, vy))
    return elements["eccentricity"] if elements["bound"] else None


def is_explicit_adaptive(name: str) -> bool:
    """Whether stiffness can show in a run of ``name`` (compiled, adaptive, explicit)."""
    m = METHODS[name]
    return m.adaptive and not m.implicit and not m.peer


def solve(model, y0, t_eval, spec: SolverSpec, *, n_periods: float | None = None,
          progress: Callable[[float], None] | None = None) -> PolicyResult:
    """Choose, run and judge one integration of ``model`` from ``y0`` over ``t_eval``.

    Parameters
    ----------
    model : OdeModel
    y0 : ndarray, shape (d,)
    t_eval : ndarray, shape (N,)
        Strictly increasing output times.
    spec : SolverSpec
    n_periods : float or None
        Length of the run in natural periods (informs the automatic choice).
    progress : callable(fraction) or None
        Passed to the integrator (a switched run reports from 0 again).

    Raises
    ------
    MethodMismatch
        The method (named, or chosen) needs structure the model lacks.
    ValueError
        Malformed ``y0`` / ``t_eval``.
    """
    def run(name: str, h: float | None = spec.h) -> Solution:
        return integrate(model, y0, t_eval, method=name, rtol=spec.rtol, atol=spec.atol,
                         h=h, progress=progress, max_steps=spec.max_steps)

    h = spec.h
    if spec.auto:
        method, reason = choose_auto(model, spec.rtol, n_periods=n_periods, y0=y0)
        if method == OSCILLATORY_STIFF and spec.h is None:
            spacing = float(np.min(np.diff(t_eval))) if len(t_eval) > 1 else math.inf
            h = min(OSCILLATORY_STEP / float(model.extra["omega_max"]), spacing)
    else:
        method, reason = spec.method, spec.reason or f"method '{spec.method}' named explicitly"
    sol = run(method, h)
    status = STATUS_OF_CODE[sol.code]
    if spec.auto and model.stiff_hint and status is RunStatus.OK:
        status = RunStatus.SWITCHED  # stiffness known in advance: auto left its explicit default
    message = "" if sol.ok else sol.message
    stiff = stability.stiffness_signs(sol, is_explicit_adaptive(method), model) or ""
    if stiff and spec.auto:
        # an automatic choice that turns out stiff switches, and says so
        reason = f"{reason} Stiffness detected with {method}: {stiff}; switched to Radau."
        method, sol = STIFF_FALLBACK, run(STIFF_FALLBACK)
        status = RunStatus.SWITCHED if sol.ok else STATUS_OF_CODE[sol.code]
        message = "" if sol.ok else sol.message
    elif stiff:
        # a named method is kept: flag it (a failure keeps its own, more specific status)
        if status is RunStatus.OK:
            status = RunStatus.STIFF
        message = "; ".join(x for x in (
            message, f"looks stiff for {method}: {stiff}; use method = \"radau\" or \"gauss6\"")
            if x)
    return PolicyResult(solution=sol, method=method, reason=reason, status=status,
                        message=message, stiffness=stiff)


def solve_fictitious_time(model, y0, t_eval, t_index: int | None, spec: SolverSpec,
                          reason: str, progress: Callable[[float], None] | None = None,
                          section=None) -> PolicyResult:
    """Run and judge a regularized ``model`` in its fictitious time (component ``t_index``
    of the state is the physical time), outputs at the physical times ``t_eval``.

    DOP853 only (:func:`.fictitious_time.integrate_fictitious_time`): ``spec.method`` must
    be ``"auto"`` or ``"dop853"``.  A regularized model is not stiff (that is what the
    regularization is for), so there is no stiffness check; the verdict is the run's code.

    ``section`` (a :class:`~reportgen.core.model.SurfaceOfSection`): its crossings are
    located on the steps (``solution.crossings``).  ``t_index = None`` runs a model in its
    own time this way, for its section: the steps and outputs of DOP853 in :func:`solve`,
    without the stiffness check (a model with a section is one the scene knows).
    """
    from .fictitious_time import integrate_fictitious_time

    if spec.method not in ("auto", "dop853"):
        raise ValueError(f"method: a regularized formulation or a surface of section runs "
                         f"with dop853 (or auto), got {spec.method!r}")
    sol = integrate_fictitious_time(model, y0, t_eval, t_index, rtol=spec.rtol, atol=spec.atol,
                                    progress=progress, max_steps=spec.max_steps,
                                    section=section)
    return PolicyResult(solution=sol, method="dop853", reason=reason,
                        status=STATUS_OF_CODE[sol.code], message="" if sol.ok else sol.message)


__all__ = ["LONG_RUN_PERIODS", "PolicyResult",
           "RunStatus", "SolverSpec", "choose_auto", "is_explicit_adaptive", "solve",
           "solve_fictitious_time"]
