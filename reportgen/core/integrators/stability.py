"""Run-time stability verdicts: a run that goes wrong says so.

Checks applied to every integrated run:

* the solver policy's status (``solver_status``: non-finite state, step limit,
  other failure, stiffness of a named explicit method);
* non-finite values anywhere in the stored state;
* drift of every conserved quantity beyond a bound tied to the tolerance asked for;
* signs of stiffness in an explicit adaptive run: many rejected steps, or a step
  budget used up (the step size collapsed to what stability, not accuracy, allows).

A flagged run keeps its data but gets ``status = "unstable"`` (or ``"failed"``)
and a message; the report shows it at the top and the exit status becomes 1.
"""

from __future__ import annotations

import math

import numpy as np

from .base import SolveCode
from .status import Status

#: relative invariant drift allowed per unit of requested rtol, and its floor
DRIFT_PER_RTOL = 1e4
DRIFT_FLOOR = 1e-6
#: fixed-step methods have no tolerance; their energy error is judged against this
DRIFT_FIXED_STEP = 1e-3


#: h * max(-Re λ(J)) above which an explicit method's step is limited by stability
#: rather than accuracy (DOP853's stability region reaches about -6 on the real axis)
STIFF_H_RHO = 2.0
STIFF_REJECT_SHARE = 0.2
STIFF_MIN_STEPS = 1000
#: rejected steps are a sign of stiffness only if the mean step times the Jacobian's
#: spectral radius reaches this (the step is near where stability, not accuracy, binds);
#: below it a high rejection share is the controller's business (measured: the spherical
#: pendulum at rtol 1e-12 rejects 23-30 % of DOP853 steps, scipy's and ours, at h|λ| ≈ 0.1)
STIFF_REJECT_MIN_RATIO = 1.0


def stiffness_ratio(model, t: np.ndarray, y: np.ndarray, nsteps: int, samples: int = 5,
                    spectral: bool = False) -> float:
    """Mean accepted step times the largest decay rate max(-Re λ) of the Jacobian.

    The Jacobian is the model's own, or a forward-difference one, at ``samples``
    stored states.  Values well below 1 mean the step was set by accuracy; near the
    method's stability bound (~2-6 for explicit Runge-Kutta) it was set by stability:
    the problem is stiff for that method.  (Hairer & Wanner, *Solving ODEs II*, §IV.2.)
    ``spectral``: the largest |λ| instead (oscillatory stiffness counts too).
    """
    if nsteps <= 0 or len(t) < 2:
        return 0.0
    h_mean = (t[-1] - t[0]) / nsteps
    rho = 0.0
    for i in np.linspace(0, len(t) - 1, samples).astype(int):
        if not np.all(np.isfinite(y[i])):
            continue
        jac = model.jacobian(t[i], y[i])
        if jac is None:
            jac = _fd_jacobian(model, t[i], y[i])
        eig = np.linalg.eigvals(jac)
        size = np.abs(eig) if spectral else -eig.real
        rho = max(rho, float(np.max(size, initial=0.0)))
    return h_mean * rho


def _fd_jacobian(model, t, y):
    f0 = model.f(t, y)
    jac = np.empty((y.size, y.size))
    for j in range(y.size):
        dy = np.zeros_like(y)
        dy[j] = 1e-7 * max(1.0, abs(y[j]))
        jac[:, j] = (model.f(t, y + dy) - f0) / dy[j]
    return jac


def stiffness_signs(sol, explicit_adaptive: bool, model=None) -> str | None:
    """Why an explicit adaptive run looks stiff, or None.

    ``sol`` is the run's :class:`~reportgen.core.integrators.Solution`.  Signs: the
    integrator gave up with finite values (its ``code`` is a step budget used up or a
    step-size underflow); the mean step sits at the stability bound
    (:func:`stiffness_ratio` > ``STIFF_H_RHO``, needs ``model``); or the controller
    keeps proposing steps that get rejected.
    """

    if not explicit_adaptive:
        return None
    steps, rejected = int(sol.nsteps), int(sol.nreject)
    if sol.code in (SolveCode.MAX_STEPS, SolveCode.STEP_UNDERFLOW):
        return f"explicit method gave up ({sol.message})"
    if model is not None and steps >= STIFF_MIN_STEPS:
        ratio = stiffness_ratio(model, sol.t, sol.y, steps)
        if ratio > STIFF_H_RHO:
            return (f"mean step × largest decay rate of the Jacobian = {ratio:.1f}: the step "
                    f"is limited by stability, not accuracy")
    if (steps >= STIFF_MIN_STEPS and rejected > STIFF_REJECT_SHARE * (steps + rejected)
            and (model is None or stiffness_ratio(model, sol.t, sol.y, steps, spectral=True)
                 >= STIFF_REJECT_MIN_RATIO)):
        return (f"{rejected} of {steps + rejected} attempted steps rejected "
                f"({100 * rejected / (steps + rejected):.0f} %)")
    return None


def drift_scale(values: np.ndarray, scale: float | None = None) -> float:
    """The size an invariant's drift is measured against: ``scale`` when the caller
    declares one (the system's own energy or momentum scale, the size of the quantity's
    terms), else the quantity's own size max(|I(0)|, max |I|).

    The fallback is for quantities bounded away from zero (an energy, a total angular
    momentum): for one that starts at or near 0 it is round-off, and the drift would be
    round-off divided by round-off.  Such a quantity must be given its scale."""
    if scale is not None:
        return float(scale)
    values = np.asarray(values, dtype=np.float64)
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return math.nan
    return max(abs(float(finite[0])), float(np.max(np.abs(finite))))


def absolute_drift(values: np.ndarray) -> float:
    """max |I(t) − I(0)| (inf when some value is not finite)."""
    values = np.asarray(values, dtype=np.float64)
    if values.size == 0 or not np.all(np.isfinite(values)):
        return math.inf
    return float(np.max(np.abs(values - values[0])))


def relative_drift(values: np.ndarray, scale: float | None = None) -> float:
    """max |I(t) − I(0)| / :func:`drift_scale` (the declared ``scale``, else the quantity's
    own size); the absolute drift when that scale is 0 (a quantity identically zero)."""
    values = np.asarray(values, dtype=np.float64)
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return math.inf
    size = drift_scale(values, scale)
    if size == 0.0:
        return float(np.max(np.abs(finite - finite[0])))
    return absolute_drift(values) / size


def drift_bound(rtol: float, fixed_step: bool) -> float:
    return DRIFT_FIXED_STEP if fixed_step else max(DRIFT_FLOOR, DRIFT_PER_RTOL * rtol)


def assess_run(record, rtol: float, scales: dict[str, float] | None = None) -> None:
    """Set ``record.attrs['status']``/``['message']`` from the checks above (in place).

    The starting verdict is the solver policy's (``attrs['solver_status']``, a
    :class:`~reportgen.core.integrators.RunStatus` value, read as a :class:`.status.Status`
    so that any spelling of the vocabulary is understood: ok/switched -> "ok",
    stiff -> "unstable", a failure -> "failed"), else ``attrs['status']``.  Also
    stores ``drift_<name>`` attrs, each invariant's drift relative to its scale
    (``scales[name]`` when given: an absolute drift against the system's own scale, never
    divided by the quantity's initial value; :func:`drift_scale`).
    """

    attrs = record.attrs
    solver = attrs.get("solver_status")
    status = Status(solver).verdict if solver else attrs.get("status", "ok")
    messages = [attrs["message"]] if attrs.get("message") else []
    if status == "ok" and not np.all(np.isfinite(record.y)):
        status = "failed"
        bad = int(np.argmax(~np.all(np.isfinite(record.y), axis=1)))
        messages.append(f"non-finite state at t = {record.t[bad]:.6g}")
    fixed_step = not math.isnan(attrs.get("h", math.nan))
    bound = drift_bound(rtol, fixed_step)
    scales = scales or {}
    for name, values in record.invariants.items():
        drift = relative_drift(values, scales.get(name))
        attrs[f"drift_{name}"] = drift
        if drift > bound and status == "ok":
            status = "unstable"
            size = drift_scale(values, scales.get(name))
            against = ("its declared scale" if name in scales else "its own size")
            messages.append(
                f"invariant '{name}' drifted by {absolute_drift(values):.2e}, "
                f"{drift:.2e} of {against} {size:.3g}, above the bound {bound:.0e} for "
                "this tolerance"
            )
    attrs["drift_bound"] = bound
    attrs["status"] = status
    attrs["message"] = "; ".join(messages)
