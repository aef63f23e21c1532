"""What an ``fput`` run stores: every result once, with its symbol and unit.

The chain is written in scaled units (unit masses, GNI eq. I.5.1): time, positions,
momenta and energies are dimensionless.
"""

from __future__ import annotations

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema
from .config import MAX_STIFF_SPRINGS

_MASSES = range(1, 2 * MAX_STIFF_SPRINGS + 1)

SCHEMA = ResultsSchema(
    time=Q("t", "t", "1", "time (scaled units)", ("t",)),
    # q1 … q2m then p1 … p2m; a run has 2m of each (params.m = m)
    columns=(
        *(Q(f"q{i}", f"q_{{{i}}}", "1", f"position of mass {i}", ("t",)) for i in _MASSES),
        *(Q(f"p{i}", f"p_{{{i}}}", "1", f"momentum of mass {i}", ("t",)) for i in _MASSES),
    ),
    invariants=(
        Q("energy", "H", "1", "total energy (GNI eq. I.5.1)", ("t",)),
    ),
    analysis=(
        Q("m", "m", "1", "number of stiff springs", kind="int"),
        Q("omega", r"\omega", "1", "frequency of the stiff springs"),
        Q("energy", "H", "1", "total energy of the initial state"),
        Q("oscillatory_energies", "I_j", "1",
          "oscillatory energy of each stiff spring (GNI eq. I.5.3)", ("t", "stiff_spring")),
        Q("oscillatory_energy_total", "I", "1", "total oscillatory energy of the stiff "
          "springs, an adiabatic invariant", ("t",)),
        Q("oscillatory_energy_scaled_deviation", r"\omega (I - I(0))/I(0)", "1",
          "relative deviation of I scaled by omega", ("t",)),
        Q("oscillatory_energy_initial", "I(0)", "1", "total oscillatory energy at t = 0"),
        Q("oscillatory_energy_max_deviation", r"\max|I - I(0)|", "1",
          "largest deviation of I over the run"),
        Q("oscillatory_energy_deviation_times_omega", r"\omega \max|I - I(0)|", "1",
          "largest deviation of I times omega (of order one)"),
        Q("oscillatory_energy_relative_deviation_times_omega",
          r"\omega \max|I - I(0)|/I(0)", "1",
          "largest relative deviation of I times omega"),
        Q("exchange_time", r"t_\mathrm{ex}", "1",
          "first time the first stiff spring holds less than 0.7 I", optional=True),
        Q("study_t_end", r"t_{study}", "1", "end of the error-against-run-time study's "
          "integration", optional=True),
    ),
)
