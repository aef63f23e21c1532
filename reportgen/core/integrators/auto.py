"""``method = "auto"``: pick an integrator from the model's structure.

Decision (from benchmarks/bench_pendulum.py on this machine, see benchmarks/README.md):
stiff -> scipy Radau; otherwise DOP853 with dense output, which reaches a given
accuracy fastest over short and moderate runs; for long runs (many periods) of a
separable Hamiltonian a symplectic method keeps the energy error bounded where
DOP853's error grows linearly in time.
"""

from __future__ import annotations

# Beyond ~1e5 periods DOP853's linearly growing energy error (~1e-14 per period at
# rtol 1e-12) becomes visible; below it DOP853 is both faster and more accurate in
# phase than a fixed-step method with a heuristic step (measured by `reportgen audit`).
LONG_RUN_PERIODS = 1e5


def choose_auto(model, rtol: float, n_periods: float | None = None) -> tuple[str, str]:
    """Return (method name, one-sentence reason)."""
    if model.stiff_hint:
        return "radau", (f"model '{model.name}' is marked stiff, so the implicit scipy Radau "
                         "solver is used.")
    if model.separable is not None and n_periods is not None and n_periods >= LONG_RUN_PERIODS:
        return "yoshida6", (f"separable Hamiltonian over {n_periods:g} periods: a symplectic "
                            "method keeps the energy error bounded instead of drifting.")
    if model.separable is not None:
        return "dop853", (f"separable but short run: DOP853 with dense output is the fastest "
                          f"way to reach rtol={rtol:g} here (measured).")
    return "dop853", (f"general non-stiff system: adaptive DOP853 with dense output at "
                      f"rtol={rtol:g}.")
