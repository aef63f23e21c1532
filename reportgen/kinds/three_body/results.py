"""What a ``three_body`` run stores: every result once, with its symbol and unit.

The kind works in the config's units (G = 1 for the figure-eight and the Pythagorean
problem; AU, years and solar masses for Sun–Earth–Moon): lengths, times, masses and the
conserved quantities are numbers in those units, declared "1".

A hierarchical triple stores two sets of relative coordinates, each named for what it is:
the lecture notes' (``notes_*``: r12 = r2 − r1, r13 = r3 − r1 and the centre of mass,
notes (3.32)–(3.34), whose kinetic energy has a cross term −(m2 m3/M) ṙ12·ṙ13) and
Jacobi's (``jacobi_*``: ρ1 = r2 − r1, ρ2 = r3 − (m1 r1 + m2 r2)/(m1 + m2), the standard
hierarchical choice with a diagonal kinetic energy; not in the notes).  The mass ratios
are the notes' (3.35).
"""

from __future__ import annotations

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

_XYZ = "xyz"


def _columns() -> tuple[Q, ...]:
    pos = tuple(Q(f"{c}{b}", f"{c}_{b}", "1", f"{c} coordinate of body {b}", ("t",))
                for b in (1, 2, 3) for c in _XYZ)
    vel = tuple(Q(f"v{c}{b}", f"v_{{{c},{b}}}", "1", f"{c} velocity of body {b}", ("t",))
                for b in (1, 2, 3) for c in _XYZ)
    return pos + vel


SCHEMA = ResultsSchema(
    time=Q("t", "t", "1", "time (scaled units)", ("t",), own_units="config units of time"),
    own_units="config units (G, lengths, masses and times as the config gives them; a pure "
              "number stays one)",
    columns=_columns(),
    invariants=(
        Q("energy", "E", "1", "total energy", ("t",)),
        *(Q(f"momentum_{c}", f"P_{c}", "1", f"total momentum ({c})", ("t",))
          for c in _XYZ),
        *(Q(f"angular_momentum_{c}", f"L_{c}", "1", f"total angular momentum ({c})",
            ("t",)) for c in _XYZ),
    ),
    analysis=(
        Q("hierarchical", "", "", "whether the run is a hierarchical triple: a pair bound "
          "throughout whose largest separation is below hierarchy_threshold times the third "
          "body's smallest distance from the pair's centre of mass", kind="bool"),
        Q("hierarchy_ratio", "", "1", "the inner pair's largest separation over the third "
          "body's smallest distance from its centre of mass (NaN: no pair stays bound)"),
        Q("hierarchy_threshold", "", "1", "hierarchy_ratio below which the triple is "
          "hierarchical"),
        Q("inner_pair", "", "1", "the bodies (1 to 3) of the pair with the smallest "
          "hierarchy_ratio", ("pair_member",), kind="int"),
        Q("inner_separation", "s", "1", "the inner pair's separation over the run: min, "
          "median, max", ("statistic",)),
        Q("outer_distance", "D", "1", "the third body's distance from the inner pair's centre "
          "of mass over the run: min, median, max", ("statistic",)),
        Q("pair_closest", r"r_\mathrm{min}", "1", "closest approach of each pair (r12, r13, "
          "r23) on the continuous solution (minima of the pair distance located between the "
          "samples)", ("pair",)),
        Q("pair_closest_time", r"t_\mathrm{min}", "1", "time of each pair's closest "
          "approach", ("pair",)),
        Q("encounter_threshold", "", "1", "each pair's distance below which an approach is a "
          "close encounter: 0.05 of the initial size (of the inner pair's median separation "
          "for the inner pair of a hierarchical triple)", ("pair",)),
        Q("close_encounters", "", "", "whether some pair's closest approach is below its "
          "encounter_threshold", kind="bool"),
        Q("closest_approach", r"r_\mathrm{min}", "1", "the closest approach of any pair, on "
          "the continuous solution"),
        Q("closest_approach_time", r"t_\mathrm{min}", "1", "time of the closest approach"),
        Q("closest_approach_pair", "", "1", "the two bodies (1 to 3) of the closest approach",
          ("pair_member",), kind="int"),
        Q("burrau", "", "", "whether the initial data are Burrau's configuration: at rest, "
          "masses 3 : 4 : 5, each body opposite the side of its own length", kind="bool"),
        Q("fate", "", "", "the physical fate at the end of the run: collision, escape, bound "
          "or unbound (no body left yet)", kind="str"),
        Q("energy_error_max", r"\max|E(t) - E(0)|/|E(0)|", "1",
          "largest relative energy error over the run"),
        Q("energy_tolerance", "", "1", "relative energy error above which the run is "
          "flagged unstable"),
        Q("pair_distances/r12", "r_{12}", "1", "distance between bodies 1 and 2", ("t",)),
        Q("pair_distances/r13", "r_{13}", "1", "distance between bodies 1 and 3", ("t",)),
        Q("pair_distances/r23", "r_{23}", "1", "distance between bodies 2 and 3", ("t",)),
        Q("min_pair_distance", r"r_\mathrm{sampled}", "1", "smallest sampled pair distance"),
        Q("min_pair_distance_time", r"t_\mathrm{sampled}", "1",
          "time of the smallest sampled pair distance"),
        # a periodic orbit (config key ``period``)
        Q("period", "T", "1", "known period of the orbit (config)", optional=True),
        Q("return_position_error", r"\max|r_i(T) - r_i(0)|", "1",
          "largest position error after one period", optional=True),
        Q("return_velocity_error", r"\max|v_i(T) - v_i(0)|", "1",
          "largest velocity error after one period", optional=True),
        Q("periodic", "", "", "whether the orbit is back after the period within "
          "periodic_threshold", kind="bool", optional=True),
        Q("periodic_threshold", "", "1", "return distance below which the orbit is periodic: "
          "1e-3 of the initial size", optional=True),
        Q("choreography", "", "", "whether the periodic orbit is a choreography: equal "
          "masses, each body starting on body 1's track within 1e-3 of the initial size",
          kind="bool", optional=True),
        Q("figure_eight", "", "", "whether the choreography is a planar figure-eight: its "
          "track turns its tangent by less than pi in one period (a simple loop: 2 pi)",
          kind="bool", optional=True),
        # a hierarchical triple
        Q("mass_ratios/m2_m1", "m_2/m_1", "1", "mass ratio of body 2 to body 1 (notes (3.35))",
          optional=True),
        Q("mass_ratios/m3_m1", "m_3/m_1", "1", "mass ratio of body 3 to body 1 (notes (3.35))",
          optional=True),
        Q("moon_pair", "", "1", "the inner pair's primary (the heavier, the first when "
          "equal) and moon (bodies 1 to 3)", ("pair_member",), kind="int", optional=True),
        Q("moon_relative_position", r"\mathbf{r}_\mathrm{moon} - \mathbf{r}_\mathrm{primary}",
          "1", "the inner pair's moon relative to its primary", ("t", "xyz"), optional=True),
        Q("moon_inclination", "i", "rad", "inclination of the moon's osculating orbit about "
          "its primary", optional=True),
        Q("moon_semi_major_axis", "a", "1", "semi-major axis of the moon's osculating orbit "
          "about its primary at t = 0", optional=True),
        Q("moon_semi_major_axis_spread", r"\Delta a/a", "1", "range of the moon's osculating "
          "semi-major axis over the run, relative to its mean", optional=True),
        Q("kepler_spread_threshold", "", "1", "moon_semi_major_axis_spread below which the "
          "relative orbit is near-Keplerian", optional=True),
        Q("moon_kepler_period", r"T_\mathrm{Kepler}", "1",
          "two-body Kepler period of the moon about its primary", optional=True),
        Q("moon_period_measured", r"T_\mathrm{sid}", "1",
          "sidereal period of the moon about its primary, measured from the run",
          optional=True),
        Q("moon_reference_error", r"|\Delta r|", "1", "the moon about its primary at t_end "
          "against a DOP853 run at rtol 1e-14", optional=True),
        # the lecture notes' coordinates, relative to body 1 (notes (3.32)-(3.34))
        Q("notes_coordinates/r12", r"\mathbf{r}_{12}", "1", "the notes' coordinate "
          "r12 = r2 - r1, body 2 relative to body 1 (notes (3.32)-(3.34))", ("t", "xyz"),
          optional=True),
        Q("notes_coordinates/r13", r"\mathbf{r}_{13}", "1", "the notes' coordinate "
          "r13 = r3 - r1, body 3 relative to body 1 (notes (3.32)-(3.34))", ("t", "xyz"),
          optional=True),
        Q("notes_mass_matrix", "K", "1", "mass matrix of the notes' coordinates: "
          "T = M |dR/dt|^2/2 + sum_ab K_ab (dr_a/dt . dr_b/dt)/2 over a, b in (r12, r13), "
          "off-diagonal K_12 = -m2 m3/M (notes (3.32)-(3.34))",
          ("relative_coordinate", "relative_coordinate"), optional=True),
        Q("notes_kinetic_identity_error", r"\max|T_N - T_C|/T", "1",
          "largest relative difference of the kinetic energy in the notes' coordinates, "
          "cross term included, and the Cartesian one (notes (3.32)-(3.34))", optional=True),
        Q("notes_cross_term_share", r"\max|T_\mathrm{cross}|/T", "1",
          "largest size of the cross term -m2 m3/M dr12/dt . dr13/dt relative to the "
          "kinetic energy (notes (3.32)-(3.34))", optional=True),
        # Jacobi coordinates: the standard hierarchical choice, not in the notes
        Q("jacobi_kinetic_identity_error", r"\max|T_J - T_C|/T", "1",
          "largest relative difference of the diagonal kinetic energy in Jacobi coordinates "
          "(the standard hierarchical choice; not in the notes) and the Cartesian one",
          optional=True),
        Q("jacobi_masses", r"(M, \mu_1, \mu_2)", "1", "total mass and the reduced masses of "
          "Jacobi coordinates (not in the notes): M, m1 m2/(m1 + m2), m3 (m1 + m2)/M",
          ("jacobi",), optional=True),
        Q("jacobi_coordinates/rho1", r"\rho_1", "1", "Jacobi coordinate rho1 = r2 - r1 (the "
          "standard hierarchical choice; not in the notes)", ("t", "xyz"), optional=True),
        Q("jacobi_coordinates/rho2", r"\rho_2", "1", "Jacobi coordinate rho2 = r3 - (m1 r1 "
          "+ m2 r2)/(m1 + m2): body 3 from the inner pair's centre of mass (not in the "
          "notes)", ("t", "xyz"), optional=True),
        Q("earth_eccentricity", "e", "1", "initial osculating eccentricity of body 2 about "
          "body 1", optional=True),
        # physical behaviour (not the run's numerical status) and chaos
        Q("behaviour", "", "", "physical behaviour: collision, escape or bound (and chaotic)",
          kind="str"),
        Q("separation_growth", r"\max d/d_0", "1", "growth of the separation of two orbits "
          "started 1e-10 apart", optional=True),
        Q("lyapunov_time", r"T_\lambda", "1", "Lyapunov time 1/lambda of a chaotic orbit",
          optional=True),
    ),
)


# ------------------------------------------------------------------------------------
# [restricted]: the planar circular restricted problem in the rotating frame (units:
# separation of the primaries, G(m1 + m2) = 1, mean motion 1 -- all numbers "1")
_LAGRANGE = ("lagrange_point",)

RESTRICTED_SCHEMA = ResultsSchema(
    time=Q("t", "t", "1", "time (scaled units)", ("t",)),  # the mean motion's: not the config's
    columns=(
        Q("x", "x", "1", "position x in the rotating frame", ("t",)),
        Q("y", "y", "1", "position y in the rotating frame", ("t",)),
        Q("vx", r"\dot{x}", "1", "velocity x in the rotating frame", ("t",)),
        Q("vy", r"\dot{y}", "1", "velocity y in the rotating frame", ("t",)),
    ),
    invariants=(
        Q("jacobi_constant", "C", "1", "Jacobi constant C = 2 Omega - v^2", ("t",)),
    ),
    analysis=(
        Q("mu", r"\mu", "1", "mass ratio of the smaller primary, m2/(m1 + m2)"),
        Q("jacobi_constant", "C", "1", "Jacobi constant of the initial state"),
        Q("jacobi_error_max", r"\max|C - C(0)|", "1", "largest error of the Jacobi constant "
          "over the stored samples and the crossings of y = 0"),
        Q("jacobi_error_relative", r"\max|C - C(0)|/2\Omega", "1", "largest error of the "
          "Jacobi constant relative to its term 2 Omega at the same point (samples and "
          "crossings)"),
        Q("jacobi_tolerance", "", "1", "error of the Jacobi constant relative to 2 Omega "
          "above which the run is flagged unstable"),
        Q("closest_approach_1", r"r_{1,\mathrm{min}}", "1", "closest sampled distance to the "
          "larger primary"),
        Q("closest_approach_2", r"r_{2,\mathrm{min}}", "1", "closest sampled distance to the "
          "smaller primary"),
        Q("formulation", "", "", "regularized (Thiele-Burrau, DOP853 in fictitious time) or "
          "cartesian", kind="str"),
        Q("region", "", "", "which regions the level C opens: the gates L1, L2, L3 and the "
          "triangular points", kind="str"),
        Q("behaviour", "", "", "physical behaviour: the regions the orbit is confined to",
          kind="str", optional=True),
        Q("lagrange_points/x", "x", "1", "x of the Lagrange points L1 to L5", _LAGRANGE,
          optional=True),
        Q("lagrange_points/y", "y", "1", "y of the Lagrange points L1 to L5", _LAGRANGE,
          optional=True),
        Q("lagrange_points/jacobi", "C", "1", "Jacobi constant at the Lagrange points L1 to "
          "L5", _LAGRANGE, optional=True),
        Q("zero_velocity/x", "x", "1", "grid of the plane, x", ("grid_x",), optional=True),
        Q("zero_velocity/y", "y", "1", "grid of the plane, y", ("grid_y",), optional=True),
        Q("zero_velocity/level", r"2\Omega - C", "1", "2 Omega - C on the grid: negative in "
          "the forbidden region", ("grid_y", "grid_x"), optional=True),
        Q("separation_growth", r"\max d/d_0", "1", "growth of the separation of two orbits "
          "started 1e-10 apart", optional=True),
        Q("lyapunov_time", r"T_\lambda", "1", "Lyapunov time 1/lambda of a chaotic orbit",
          optional=True),
        # a sweep member's crossings of y = 0 upward (the family's surface of section)
        Q("poincare/t", "t", "1", "times of the crossings of y = 0 upward", ("crossing",),
          optional=True),
        Q("poincare/u", "x", "1", "x at the crossings", ("crossing",), optional=True),
        Q("poincare/v", r"\dot{x}", "1", "x velocity at the crossings", ("crossing",),
          optional=True),
        Q("poincare/state", "", "", "state (x, y, vx, vy) at the crossings",
          ("crossing", "component"), optional=True),
        Q("poincare_points", "", "1", "crossings per orbit", optional=True),
        # the family: the section's edge at the members' common C
        Q("poincare_grid/u", "x", "1", "grid of the section, x", ("grid_u",), optional=True),
        Q("poincare_grid/v", r"\dot{x}", "1", "grid of the section, x velocity",
          ("grid_v",), optional=True),
        Q("poincare_grid/vy2", r"\dot{y}^2", "1", "y velocity squared on the section at the "
          "family's Jacobi constant", ("grid_v", "grid_u"), optional=True),
        Q("poincare_jacobi", "C", "1", "the members' common Jacobi constant", optional=True),
    ),
)
