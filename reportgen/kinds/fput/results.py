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
          "first time the stiff spring that starts with most of I holds less than "
          "exchange_share of I (when it starts with at least that share, m >= 2)",
          optional=True),
        Q("stiff_at_rest", "", "", "whether the stiff springs start at rest: I(0) <= 1e-12 "
          "of the total energy", kind="bool"),
        Q("first_spring", "j_0", "1", "the stiff spring holding most of I(0) (1-based)",
          kind="int"),
        Q("first_spring_share", r"I_{j_0}(0)/I(0)", "1", "its share of I(0) (NaN at rest)"),
        Q("exchange_share", "", "1", "share of I below which the first spring has handed its "
          "energy on, and from which energy starts concentrated in one spring"),
        Q("order_one_bound", "", "1", "omega max|I - I(0)|/I(0) below this is of order one"),
        Q("adiabatic_order_one", "", "", "whether omega max|I - I(0)|/I(0) is below "
          "order_one_bound", kind="bool", optional=True),
        Q("soft_frequency", r"\omega_\mathrm{soft}", "1", "typical frequency of the soft "
          "springs along the run, sqrt(24 <Delta^2>) over their elongations Delta"),
        Q("stiffness_ratio", r"\omega/\omega_\mathrm{soft}", "1",
          "frequency of the stiff springs over the soft springs' typical frequency"),
        Q("stiff_ratio_bound", "", "1", "stiffness_ratio from which the chain has two time "
          "scales"),
        Q("two_time_scales", "", "", "whether stiffness_ratio >= stiff_ratio_bound: the stiff "
          "springs oscillate much faster than the soft ones", kind="bool"),
        Q("study_t_end", r"t_{study}", "1", "end of the error-against-run-time study's "
          "integration", optional=True),
    ),
)
