"""What a ``normal_modes`` run stores: every result once, with its symbol and unit.

The units follow the config: coupled pendula are given in SI (kg, m, m/s², N/m), so
their frequencies are in rad/s; a molecule (masses in u, positions in Å, force
constants in mdyn/Å, or any other consistent set), a chain of unit-less masses and
springs or M and A given as matrices are in the config's own units, and their
frequencies in 1/(time unit) of that set.
"""

from __future__ import annotations

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

#: the systems given in SI units (the others are in the config's own consistent units)
SI_SOURCES = frozenset({"pendula"})

_SI = {"time": "s", "omega": "rad/s", "omega2": "1/s^2", "omega4": "1/s^4", "q": "rad",
       "p": "kg m^2/s", "energy": "J", "mass": "kg m^2", "stiffness": "J",
       "mode": "kg^-0.5/m"}
_OWN = {"time": "time unit", "omega": "1/time unit", "omega2": "1/time unit^2",
        "omega4": "1/time unit^4", "q": "length unit", "p": "momentum unit",
        "energy": "energy unit", "mass": "mass unit",
        "stiffness": "energy unit/length unit^2", "mode": "mass unit^-0.5"}


def units(source: str) -> dict[str, str]:
    """The units of a system given as ``source`` ("molecule", "chain", "pendula",
    "matrices"): time, omega, omega2, omega4, q, p, energy, mass, stiffness, mode."""
    return _SI if source in SI_SOURCES else _OWN


def schema_for(source: str, coordinates: tuple[str, ...] = ()) -> ResultsSchema:
    """The results of a system given as ``source`` with the run columns ``coordinates``
    (the coordinates, then ``p_<coordinate>``, of an ``[evolve]`` run)."""
    u = units(source)
    t = ("t",)
    return ResultsSchema(
        time=Q("t", "t", u["time"], "time", t),
        columns=(*(Q(c, c, u["q"], f"coordinate {c}", t) for c in coordinates),
                 *(Q(f"p_{c}", f"p_{{{c}}}", u["p"], f"momentum conjugate to {c}", t)
                   for c in coordinates)),
        invariants=(Q("energy", "E", u["energy"], "energy of the small oscillations", t),),
        analysis=(
            Q("source", "", "", "how the system is given: molecule, chain, pendula or "
              "matrices", kind="str"),
            Q("frequencies", r"\omega", u["omega"], "eigenfrequencies, ascending", ("mode",)),
            Q("omega_squared", r"\omega^2", u["omega2"], "eigenvalues of A eta = omega^2 M eta",
              ("mode",)),
            Q("modes", r"\eta", u["mode"], "mode vectors, columns mass-normalized "
              "(eta^T M eta = 1)", ("coordinate", "mode")),
            Q("n_dof", "n", "1", "number of coordinates", kind="int"),
            Q("n_zero_modes", "", "1", "number of zero-frequency modes", kind="int"),
            Q("n_vibrational", "", "1", "number of vibrations", kind="int"),
            Q("degenerate_group", "", "1", "degenerate set of each mode (equal ids)",
              ("mode",), kind="int"),
            Q("mass_matrix", "M", u["mass"], "kinetic (mass) matrix",
              ("coordinate", "coordinate")),
            Q("hessian", "A", u["stiffness"], "potential Hessian at equilibrium",
              ("coordinate", "coordinate")),
            Q("coordinate_names", "", "", "names of the coordinates", ("coordinate",),
              kind="str"),
            Q("three_step_max_difference", r"\max|\Delta\omega^2|/\omega^2_\mathrm{max}", "1",
              "largest difference of the textbook's three steps against the generalized "
              "solver"),
            Q("orthonormality_error", r"\max|\eta^T M \eta - 1|", "1",
              "largest departure of the modes from M-orthonormality"),
            Q("mode_type", "", "", "type of each mode", ("mode",), kind="str"),
            Q("stiffness_ratio", r"\omega_\mathrm{max}/\omega_\mathrm{min}", "1",
              "ratio of the highest to the lowest non-zero frequency"),
            # a molecule
            Q("masses", "m", "mass unit", "atomic masses", ("atom",), optional=True),
            Q("positions", "x", "length unit", "equilibrium positions", ("atom", "xyz"),
              optional=True),
            Q("elements", "", "", "chemical symbols", ("atom",), kind="str", optional=True),
            Q("bonds", "", "1", "bonded atom pairs (zero-based)", ("bond", "pair"),
              kind="int", optional=True),
            Q("angles", "", "1", "bend angles (zero-based, vertex in the middle)",
              ("angle", "triple"), kind="int", optional=True),
            Q("linear", "", "", "whether the molecule is linear", kind="bool", optional=True),
            Q("frame", "", "1", "drawing frame: rows e1, e2, e3", ("xyz", "xyz"),
              optional=True),
            Q("drawing/positions", "x - x_{cm}", "length unit",
              "positions relative to the centre of mass in the drawing frame",
              ("atom", "xyz"), optional=True),
            Q("drawing/displacements", r"\eta_a", u["mode"],
              "each vibration's per-atom displacement in the drawing frame",
              ("vibration", "atom", "xyz"), optional=True),
            Q("n_rigid_translations", "", "1", "rigid-body translations", kind="int",
              optional=True),
            Q("n_rigid_rotations", "", "1", "rigid-body rotations", kind="int",
              optional=True),
            Q("expected_zero_modes", "", "1", "zero modes expected (5 linear, 6 otherwise)",
              kind="int", optional=True),
            Q("expected_vibrational", "", "1", "vibrations expected (3n - 5 or 3n - 6)",
              kind="int", optional=True),
            Q("rigid_residual", r"\max\|A v\|/(\|A\| \|v\|)", "1",
              "largest residual of A on the rigid-body vectors", optional=True),
            Q("n_symmetry_operations", "", "1", "symmetry operations found", kind="int",
              optional=True),
            Q("n_floppy", "", "1", "internal zero-frequency modes", kind="int",
              optional=True),
            Q("n_longitudinal", "", "1", "longitudinal vibrations (linear molecule)",
              kind="int", optional=True),
            Q("n_transverse", "", "1", "transverse vibrations (linear molecule)",
              kind="int", optional=True),
            Q("expected_longitudinal", "", "1", "longitudinal vibrations expected (n - 1)",
              kind="int", optional=True),
            Q("expected_transverse", "", "1", "transverse vibrations expected (2(n - 2))",
              kind="int", optional=True),
            # a chain or pendula: the closed form
            Q("frequencies_exact", r"\omega_\mathrm{exact}", u["omega"],
              "closed-form eigenfrequencies, ascending", ("mode",), optional=True),
            Q("closed_form_max_rel_error", r"\max|\omega/\omega_\mathrm{exact} - 1|", "1",
              "largest relative error against the closed form", optional=True),
            Q("closed_form_source", "", "", "the closed form's formula and source",
              kind="str", optional=True),
            Q("standing_waves/s", "s", "1", "position along the chain in mass spacings",
              ("wave_point",), optional=True),
            Q("standing_waves/amplitude", "", "1", "closed-form standing wave of each of the "
              "lowest modes, largest value at the masses 1", ("wave_point", "shown_mode"),
              optional=True),
            # [evolve]
            Q("evolution_max_error", r"\max|q - q_\mathrm{modal}|", u["q"],
              "largest difference of direct integration against modal superposition",
              optional=True),
            Q("evolution_amplitude", r"\max|q_\mathrm{modal}|", u["q"],
              "largest amplitude of the modal superposition", optional=True),
            Q("stiff", "", "", "whether the evolution is stiff", kind="bool", optional=True),
            Q("stiff_reason", "", "", "why the evolution is (not) stiff", kind="str",
              optional=True),
            Q("study_t_end", r"t_{study}", u["time"], "end of the error-against-run-time "
              "study's integration", optional=True),
        ),
    )


#: the kind's results for a system in the config's own units (the report narrows it to
#: the archive's system with :func:`schema_for`)
SCHEMA = schema_for("matrices")
