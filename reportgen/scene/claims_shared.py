"""Claims any kind's report may make (see :mod:`reportgen.scene.claims`): the numerical
status and what the summary says of conserved quantities."""

from __future__ import annotations

import math

import numpy as np

from .claims import claim


@claim("numerical status ok", r"Numerical status: ok\b", kind=None)
def status_ok(data) -> bool | str:
    """every run is finite and each conserved quantity's drift, measured again from the
    archived values against the run's stored scale, is within the run's drift bound"""
    for name, run in data.runs.items():
        if not np.all(np.isfinite(run.y)):
            return f"run {name!r} holds non-finite states"
        bound = float(run.attrs.get("drift_bound", math.inf))
        for q, values in run.invariants.items():
            values = np.asarray(values, dtype=float)
            scale = run.attrs.get(f"scale_{q}")
            if scale is None:
                scale = max(abs(values[0]), float(np.max(np.abs(values))))
            if scale == 0:
                continue
            drift = float(np.max(np.abs(values - values[0]))) / float(scale)
            if drift > bound:
                return (f"run {name!r}: {q} drifts by {drift:.2g} of its scale {scale:.3g}, "
                        f"above the bound {bound:.2g}")
    return True
