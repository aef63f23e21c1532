"""What a ``normal_modes`` run stores: every result once, with its symbol and unit.

The units follow the config's unit system (``units``, stored as ``/analysis/unit_system``):

``"SI"``
    kg, m, N/m, s; coupled pendula always (their coordinates are angles in rad).
``"molecular"``
    a molecule's default: masses in u, lengths in Å, force constants in mdyn/Å (bends in
    mdyn·Å/rad²).  The eigenproblem is solved in these units, whose time unit is
    τ = √(u/(mdyn/Å)) = 4.075 fs; the frequencies are stored in rad/s (ω/τ) with the
    wavenumbers ν̃ = ω/(2πc) in cm⁻¹, and a time evolution runs in units of τ.
``"dimensionless"``
    the default of a chain or of M and A: pure numbers, masses in units of a reference
    m₀ and springs of k₀, so time is in √(m₀/k₀) and ω in √(k₀/m₀).

An archive written before the unit systems (no ``unit_system``) keeps the old reading:
pendula in SI, everything else in the config's own units.
"""

from __future__ import annotations

import math

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

#: the systems given in SI units in an archive without ``unit_system``
SI_SOURCES = frozenset({"pendula"})
#: the unit systems a config may declare
UNIT_SYSTEMS = ("SI", "molecular", "dimensionless")
#: the unified atomic mass unit [kg] (CODATA 2018)
ATOMIC_MASS = 1.66053906660e-27
#: one mdyn/Å [N/m]
MDYN_PER_ANGSTROM = 100.0
#: ω of the molecular units (u, Å, mdyn/Å), 1/τ = √((mdyn/Å)/u) [rad/s] (2.454e14)
MOLECULAR_OMEGA = math.sqrt(MDYN_PER_ANGSTROM / ATOMIC_MASS)
#: the speed of light [cm/s]: wavenumber ν̃ = ω/(2πc)
LIGHT_CM_PER_S = 2.99792458e10
#: the molecular time unit τ, 4.075 fs (to full precision: the archive's CF ``scale_factor``
#: turns a time in τ into fs; pages print it to 4 digits)
_TAU_FS = f"{1e15 / MOLECULAR_OMEGA!r} fs"
#: what the numbers of the "dimensionless" system are (the archive's ``config_units``)
OWN_UNITS = "config units (masses of a reference m₀, springs of k₀, time in √(m₀/k₀))"

_SI = {"time": "s", "omega": "rad/s", "omega2": "1/s^2", "omega4": "1/s^4", "q": "rad",
       "p": "kg m^2/s", "energy": "J", "mass": "kg m^2", "stiffness": "J",
       "mode": "kg^-0.5/m", "gradient": "J"}
_SI_LENGTHS = {"time": "s", "omega": "rad/s", "omega2": "1/s^2", "omega4": "1/s^4",
               "q": "m", "p": "kg m/s", "energy": "J", "mass": "kg", "stiffness": "N/m",
               "mode": "kg^-0.5", "gradient": "N"}
_MOLECULAR = {"time": _TAU_FS, "omega": "rad/s", "omega2": "1/s^2", "omega4": "1/s^4",
              "q": "Å", "p": f"u Å/({_TAU_FS})", "energy": "aJ", "mass": "u",
              "stiffness": "mdyn/Å", "mode": "u^-0.5", "gradient": "mdyn"}
_DIMENSIONLESS = dict.fromkeys(_SI_LENGTHS, "1")
#: an archive without a unit system: the config's own units, unnamed
_OWN = {"time": "time unit", "omega": "1/time unit", "omega2": "1/time unit^2",
        "omega4": "1/time unit^4", "q": "length unit", "p": "momentum unit",
        "energy": "energy unit", "mass": "mass unit",
        "stiffness": "energy unit/length unit^2", "mode": "mass unit^-0.5",
        "gradient": "energy unit/length unit"}


def units(source: str, system: str | None = None,
          coordinate_unit: str | None = None) -> dict[str, str]:
    """The units of a system given as ``source`` ("molecule", "chain", "pendula",
    "potential", "matrices") in the unit ``system`` (one of :data:`UNIT_SYSTEMS`; None: an
    archive written before them): time, omega, omega2, omega4, q, p, energy, mass,
    stiffness, mode, gradient (∂U/∂q); a molecule's atoms also atom_mass and length.
    ``coordinate_unit``: a potential's coordinates in SI, "rad" (angles, as pendula's) or
    "m"."""
    if system is None:
        u = _SI if source in SI_SOURCES else _OWN
        return {**u, "atom_mass": "mass unit", "length": "length unit"}
    if system == "SI":
        u = _SI if source == "pendula" or coordinate_unit == "rad" else _SI_LENGTHS
        return {**u, "atom_mass": "kg", "length": "m"}
    if system == "molecular":
        return {**_MOLECULAR, "atom_mass": "u", "length": "Å"}
    return {**_DIMENSIONLESS, "atom_mass": "1", "length": "1"}


def omega_scale(system: str | None) -> float:
    """Stored ω per ω of the eigenproblem: 1/τ [rad/s] in molecular units, else 1."""
    return MOLECULAR_OMEGA if system == "molecular" else 1.0


def schema_for(source: str, coordinates: tuple[str, ...] = (),
               system: str | None = None, coordinate_unit: str | None = None,
               symbols: tuple[str, ...] = ()) -> ResultsSchema:
    """The results of a system given as ``source`` in the unit ``system`` with the run
    columns ``coordinates`` (the coordinates, then ``p_<coordinate>``, of an ``[evolve]``
    run), ``symbols`` their TeX (default: the names); ``coordinate_unit`` a potential's
    coordinates' unit in SI."""
    u = units(source, system, coordinate_unit)
    t = ("t",)
    tex = dict(zip(coordinates, symbols or coordinates, strict=True))
    return ResultsSchema(
        time=Q("t", "t", u["time"], "time", t),
        columns=(*(Q(c, tex[c], u["q"], f"coordinate {c}", t) for c in coordinates),
                 *(Q(f"p_{c}", f"p_{{{tex[c]}}}", u["p"], f"momentum conjugate to {c}", t)
                   for c in coordinates)),
        invariants=(Q("energy", "E", u["energy"], "energy of the small oscillations", t),),
        analysis=(
            Q("source", "", "", "how the system is given: molecule, chain, pendula, "
              "potential or matrices", kind="str"),
            Q("unit_system", "", "", "the config's units: SI, molecular or dimensionless",
              kind="str", optional=True),
            Q("wavenumbers", r"\tilde\nu", "1/cm", "wavenumbers omega/(2 pi c) of a molecule "
              "in SI or molecular units, ascending", ("mode",), optional=True),
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
            Q("mode_parity", "", "", "g or u: each mode even or odd under the inversion "
              "through the centre of mass (a molecule with a centre of symmetry)", ("mode",),
              kind="str", optional=True),
            Q("centre_of_inversion", "", "", "whether the molecule, its masses and its force "
              "field have a centre of inversion (each atom has an atom of equal mass opposite "
              "it through the centre of mass, within 1e-9 of the size, and A is unchanged by "
              "the inversion): it names the stretches symmetric (g) or antisymmetric (u)",
              kind="bool", optional=True),
            Q("coordinate_classes", "", "", "the classes of like internal coordinates "
              "(stretches of like bonds, bends of like angles) that name the vibrations",
              ("coordinate_class",), kind="str", optional=True),
            Q("coordinate_shares", "", "1", "each vibration's share of potential energy in "
              "each class of internal coordinates (the potential-energy distribution; rows "
              "sum to 1)", ("vibration", "coordinate_class"), optional=True),
            Q("dominant_share", "", "1", "the share of a vibration's potential energy a class "
              "of internal coordinates must hold to name it (below it: mixed)",
              optional=True),
            Q("stiffness_ratio", r"\omega_\mathrm{max}/\omega_\mathrm{min}", "1",
              "ratio of the highest to the lowest non-zero frequency"),
            # a molecule
            Q("masses", "m", u["atom_mass"], "atomic masses", ("atom",), optional=True),
            Q("positions", "x", u["length"], "equilibrium positions", ("atom", "xyz"),
              optional=True),
            Q("elements", "", "", "chemical symbols", ("atom",), kind="str", optional=True),
            Q("bonds", "", "1", "bonded atom pairs (zero-based)", ("bond", "pair"),
              kind="int", optional=True),
            Q("angles", "", "1", "bend angles (zero-based, vertex in the middle)",
              ("angle", "triple"), kind="int", optional=True),
            Q("linear", "", "", "whether the molecule is linear", kind="bool", optional=True),
            Q("frame", "", "1", "drawing frame: rows e1, e2, e3", ("xyz", "xyz"),
              optional=True),
            Q("drawing/positions", "x - x_{cm}", u["length"],
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
            # a chain, pendula or a symmetric linear X-Y-Y-X molecule: the closed form
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
            # a potential written as formulas ([system]): its equilibrium
            *potential_results(u),
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
        numbered={"mode": "mode number, 1 to n in ascending frequency (as the report "
                          "numbers the modes)"},
        own_units=OWN_UNITS if system == "dimensionless" else "",
    )


def potential_results(u: dict[str, str]) -> tuple[Q, ...]:
    """The results of a potential written as formulas (``[system]``), in the units ``u``."""
    return (
        Q("given", "", "", "how the system is written: L (a Lagrangian), T (U with a kinetic "
          "energy) or M (U with a mass matrix)", kind="str", optional=True),
        Q("coordinate_unit", "", "", "the coordinates' unit in SI: rad or m", kind="str",
          optional=True),
        Q("coordinate_symbols", "", "", "each coordinate's symbol (TeX)", ("coordinate",),
          kind="str", optional=True),
        Q("lagrangian_latex", "", "", "the Lagrangian as written, simplified (TeX)",
          kind="str", optional=True),
        Q("potential_latex", "", "", "the potential energy U(q) (TeX)", kind="str",
          optional=True),
        Q("kinetic_latex", "", "", "the kinetic energy T(q, q_dot) as written (TeX)",
          kind="str", optional=True),
        Q("equilibrium_guess", r"q_\mathrm{guess}", u["q"], "where the search for the "
          "equilibrium started", ("coordinate",), optional=True),
        Q("equilibrium", "q_0", u["q"], "the equilibrium: the stationary point of U found "
          "from the guess", ("coordinate",), optional=True),
        Q("equilibrium_potential", "U(q_0)", u["energy"], "the potential energy at the "
          "equilibrium", optional=True),
        Q("equilibrium_gradient", r"\partial U/\partial q", u["gradient"], "the gradient of U "
          "at the equilibrium", ("coordinate",), optional=True),
        Q("equilibrium_gradient_norm", r"|\nabla U|", u["gradient"], "the norm of the gradient "
          "of U at the equilibrium", optional=True),
        Q("equilibrium_residual", r"\max|\partial U/\partial q_i|/s_i", "1",
          "largest |dU/dq_i| at the equilibrium relative to the size of its parts plus the "
          "curvature times the distance searched", optional=True),
        Q("equilibrium_residual_tol", "", "1", "the relative gradient below which a point is "
          "stationary", optional=True),
        Q("equilibrium_evaluations", "", "1", "evaluations of the gradient in the search",
          kind="int", optional=True),
        Q("hessian_positive_definite", "", "", "whether A is positive definite at the "
          "equilibrium (every omega^2 > 0: a minimum of U)", kind="bool", optional=True),
        Q("equilibrium_stability", "", "", "stable (A positive definite) or neutral (A "
          "positive semidefinite with zero eigenvalues, within 1e-10 of the largest)",
          kind="str", optional=True),
        Q("hessian_finite_difference", r"\max|A_\mathrm{fd} - A|/\max|A|", "1",
          "largest difference of a central second difference of U from the symbolic A",
          optional=True),
        Q("finite_difference_step", "h", u["q"], "the step of that central difference",
          optional=True),
    )


#: the kind's results for a system in the config's own units (the report narrows it to
#: the archive's system with :func:`schema_for`)
SCHEMA = schema_for("matrices")
