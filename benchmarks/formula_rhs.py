"""ns per right-hand-side evaluation: a system written as a formula against the same system
hand-written as a kind's model.

    python benchmarks/formula_rhs.py

Each right-hand side is called as the integrators call it -- a numba C callback, from a
compiled loop -- 10⁶ times on a state that changes every call (so nothing is hoisted); the
figure is the minimum over 5 repeats divided by 10⁶, after a warm-up that compiles.  The
formula systems go through reportgen.core.formula exactly as the ``hamiltonian`` kind does.
Not a test: numbers depend on the machine.
"""

from __future__ import annotations

import time

import numba
import numpy as np

from reportgen.core import formula
from reportgen.core.integrators.kernels import RHS_SIG, as_cfunc
from reportgen.core.models import kepler, pendulum, two_center

CALLS = 1_000_000


@numba.njit(cache=True)
def _loop(rhs, y0, params, n):
    y = y0.copy()
    out = np.empty_like(y)
    acc = 0.0
    for i in range(n):
        y[0] = y0[0] + 1e-9 * i
        rhs(0.0, y, params, out)
        acc += out[-1]
    return acc


def ns_per_call(model, y0) -> float:
    rhs = as_cfunc(model.rhs, RHS_SIG)
    y0 = np.asarray(y0, dtype=np.float64)
    _loop(rhs, y0, model.params, 10)
    best = np.inf
    for _ in range(5):
        start = time.perf_counter()
        _loop(rhs, y0, model.params, CALLS)
        best = min(best, time.perf_counter() - start)
    return best / CALLS * 1e9


def cases():
    """(name, hand-written model, formula model, state)."""
    g_over_l = 9.81
    pend = formula.build_system(["theta"], H="p_theta**2/2 - w2*cos(theta)",
                                params={"w2": g_over_l})
    kep = formula.build_system(["x", "y"], H="(p_x**2 + p_y**2)/(2*mu) - k/sqrt(x**2 + y**2)",
                               params={"k": 1.0, "mu": 1.0})
    mu, a = 1.0, 1.0
    two = formula.build_system(
        ["x", "y"], H="(p_x**2 + p_y**2)/2 - mu/sqrt((x - a)**2 + y**2) "
                      "- mu/sqrt((x + a)**2 + y**2)", params={"mu": mu, "a": a})
    return [
        ("pendulum", pendulum.model(9.81, 1.0), formula.compiled_model(pend), [1.0, 0.2]),
        ("Kepler (Cartesian)", kepler.model(1.0, 1.0), formula.compiled_model(kep),
         [1.0, 0.1, 0.0, 1.2]),
        ("two fixed centres", two_center.model(mu, a), formula.compiled_model(two),
         [0.3, 0.9, 0.5, 0.1]),
    ]


def main() -> None:
    print(f"{'system':<22} {'hand-written':>14} {'formula':>10}  ratio")
    for name, hand, written, y0 in cases():
        # the same state in both: our hand models use (q, v) with unit mass as the formulas
        assert np.allclose(hand.f(0.0, np.array(y0)), written.f(0.0, np.array(y0))), name
        h, f = ns_per_call(hand, y0), ns_per_call(written, y0)
        print(f"{name:<22} {h:>11.1f} ns {f:>7.1f} ns  {f / h:5.2f}")


if __name__ == "__main__":
    main()
