"""Run-time stability verdicts: a run that goes wrong says so.

Checks applied to every integrated run:

* the integrator's own status (non-finite state, step-size collapse, step limit);
* non-finite values anywhere in the stored state;
* drift of every conserved quantity beyond a bound tied to the tolerance asked for.

A flagged run keeps its data but gets ``status = "unstable"`` (or ``"failed"``)
and a message; the report shows it at the top and the exit status becomes 1.
"""

from __future__ import annotations

import math

import numpy as np

#: relative invariant drift allowed per unit of requested rtol, and its floor
DRIFT_PER_RTOL = 1e4
DRIFT_FLOOR = 1e-6
#: fixed-step methods have no tolerance; their energy error is judged against this
DRIFT_FIXED_STEP = 1e-3


def relative_drift(values: np.ndarray, scale: float | None = None) -> float:
    """max |I(t) - I(0)| / scale, with scale = max(|I(0)|, max |I|) unless given."""
    values = np.asarray(values, dtype=np.float64)
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return math.inf
    if scale is None:
        scale = max(abs(finite[0]), float(np.max(np.abs(finite))))
    if scale == 0.0:
        return float(np.max(np.abs(finite - finite[0])))
    if finite.size < values.size:
        return math.inf
    return float(np.max(np.abs(values - values[0]))) / scale


def drift_bound(rtol: float, fixed_step: bool) -> float:
    return DRIFT_FIXED_STEP if fixed_step else max(DRIFT_FLOOR, DRIFT_PER_RTOL * rtol)


def assess_run(record, rtol: float, scales: dict[str, float] | None = None) -> None:
    """Set ``record.attrs['status']``/``['message']`` from the checks above (in place).

    Also stores ``drift_<name>`` attrs, the relative drift of each invariant.
    """
    attrs = record.attrs
    status = attrs.get("status", "ok")
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
            messages.append(
                f"invariant '{name}' drifted by {drift:.2e} (relative), above the bound "
                f"{bound:.0e} for this tolerance"
            )
    attrs["drift_bound"] = bound
    attrs["status"] = status
    attrs["message"] = "; ".join(messages)
