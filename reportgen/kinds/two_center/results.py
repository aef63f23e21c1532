"""What a ``two_center`` run stores: every result once, with its symbol and unit.

Per unit mass of the test particle, in the units the config's keys document (μ = G·M
in m³/s², lengths in m): energy in m²/s², the separation constant, notes (7.59), in m⁴/s²
(its terms L1 L2 and 2aμ).
"""

from __future__ import annotations

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

_ELLIPSE = ("ellipse_sample",)
_HYPERBOLA = ("hyperbola_sample",)

SCHEMA = ResultsSchema(
    columns=(
        Q("x", "x", "m", "position x", ("t",)),
        Q("y", "y", "m", "position y", ("t",)),
        Q("vx", r"\dot{x}", "m/s", "velocity x", ("t",)),
        Q("vy", r"\dot{y}", "m/s", "velocity y", ("t",)),
    ),
    invariants=(
        Q("energy", "E", "m^2/s^2", "energy per unit mass", ("t",)),
        Q("separation_constant", "C", "m^4/s^2", "separation constant, notes (7.59)", ("t",)),
    ),
    analysis=(
        Q("energy", "E", "m^2/s^2", "energy per unit mass at t = 0"),
        Q("separation_constant", "C", "m^4/s^2", "separation constant, notes (7.59), at t = 0"),
        Q("beta", r"\beta", "m^4/s^2", "separation constant beta = -C - 2 a^2 E of notes (7.59)"),
        Q("family", "", "", "orbit family, as the literature names it: satellite (beta > 0: "
          "about one centre), planetary (beta <= 0 and q(1) < 0: round both), lemniscate "
          "(beta <= 0 and q(1) >= 0: through the segment between them) or unbound",
          kind="str"),
        Q("behaviour", "", "", "physical behaviour: bound (satellite, planetary, lemniscate), "
          "escape or collision", kind="str", optional=True),
        Q("motion", "", "", "how the orbit moves in the plane, notes (7.59): one_centre "
          "(beta > 0: one side of the mid-line), both_centres (beta <= 0 and q(1) < 0: a "
          "ring between two ellipses), through_middle (beta <= 0 and q(1) >= 0: crosses "
          "the segment between the centres) or escape (E >= 0)", kind="str"),
        Q("segment_reach", "q(1)", "m^4/s^2", "q(1) = 2 a^2 E + 4 a mu + beta, the xi "
          "equation of notes (7.59) at the segment between the centres (xi = 1): the orbit "
          "reaches the segment where q(1) >= 0"),
        Q("side", "", "1", "the side of the mid-line x = 0 a one-side orbit keeps (+1: the "
          "centre at (a, 0), -1: at (-a, 0); 0: not a one-side orbit)", kind="int"),
        Q("xi_bounds", r"\xi_\mathrm{min}, \xi_\mathrm{max}", "1",
          "bounds of xi from notes (7.59)", ("bound",)),
        Q("eta_abs_bounds", r"|\eta|_\mathrm{min}, |\eta|_\mathrm{max}", "1",
          "bounds of |eta| from notes (7.59)", ("bound",)),
        Q("xi_range_run", r"\xi", "1", "range of xi the sampled run reaches", ("bound",)),
        Q("eta_abs_range_run", r"|\eta|", "1", "range of |eta| the sampled run reaches",
          ("bound",)),
        Q("elliptic_grid/xi_levels", r"\xi", "1", "ellipses of the grid drawn",
          ("xi_level",)),
        Q("elliptic_grid/eta_levels", r"\eta", "1", "hyperbolas of the grid drawn",
          ("eta_level",)),
        Q("elliptic_grid/ellipses/x", "x", "m", "grid ellipses xi = const, x",
          ("xi_level", *_ELLIPSE)),
        Q("elliptic_grid/ellipses/y", "y", "m", "grid ellipses xi = const, y",
          ("xi_level", *_ELLIPSE)),
        Q("elliptic_grid/hyperbolas/x", "x", "m", "grid hyperbolas eta = const (both "
          "branches), x", ("eta_branch", *_HYPERBOLA)),
        Q("elliptic_grid/hyperbolas/y", "y", "m", "grid hyperbolas eta = const (both "
          "branches), y", ("eta_branch", *_HYPERBOLA)),
        Q("motion_bounds/xi", r"\xi", "1", "the ellipses xi = const that bound the motion",
          ("xi_bound",), optional=True),
        Q("motion_bounds/ellipses/x", "x", "m", "bounding ellipses, x",
          ("xi_bound", *_ELLIPSE), optional=True),
        Q("motion_bounds/ellipses/y", "y", "m", "bounding ellipses, y",
          ("xi_bound", *_ELLIPSE), optional=True),
        Q("motion_bounds/eta", r"\eta", "1", "the hyperbolas eta = const that bound the "
          "motion", ("eta_bound",), optional=True),
        Q("motion_bounds/hyperbolas/x", "x", "m", "bounding hyperbolas (both branches), x",
          ("eta_bound_branch", *_HYPERBOLA), optional=True),
        Q("motion_bounds/hyperbolas/y", "y", "m", "bounding hyperbolas (both branches), y",
          ("eta_bound_branch", *_HYPERBOLA), optional=True),
        Q("closest_approach_bound", r"d_{\mathrm{min}}", "m",
          "closest approach to a centre the region of motion, notes (7.59), allows"),
        Q("closest_approach_run", r"d_{\mathrm{run}}", "m",
          "closest approach to a centre in the sampled run"),
        # a sweep member's crossings of y = 0 (the family's surface of section)
        Q("poincare/t", "t", "s", "times of the crossings of y = 0 upward", ("crossing",),
          optional=True),
        Q("poincare/u", "x", "m", "x at the crossings", ("crossing",), optional=True),
        Q("poincare/v", r"\dot{x}", "m/s", "x velocity at the crossings", ("crossing",),
          optional=True),
        Q("poincare/state", "", "", "state (x, y, vx, vy) at the crossings",
          ("crossing", "component"), optional=True),
        Q("formulation", "", "", "cartesian or regularized", kind="str", optional=True),
        Q("poincare_E_error", r"\max|E - E(0)|/|V(0)|", "1",
          "largest relative energy error at the crossings", optional=True),
        Q("poincare_C_error", r"\max|C - C(0)|", "1",
          "largest relative error of the separation constant at the crossings",
          optional=True),
        # the family's predicted curves on the section (members of one energy)
        Q("poincare_grid/u", "x", "m", "grid of the section, x", ("grid_u",), optional=True),
        Q("poincare_grid/v", r"\dot{x}", "m/s", "grid of the section, x velocity",
          ("grid_v",), optional=True),
        Q("poincare_grid/C", "C", "m^4/s^2", "separation constant on the section at the "
          "family's energy", ("grid_v", "grid_u"), optional=True),
        Q("poincare_grid/vy2", r"\dot{y}^2", "m^2/s^2", "y velocity squared on the section "
          "at the family's energy", ("grid_v", "grid_u"), optional=True),
        Q("poincare_energy", "E", "m^2/s^2", "the members' common energy", optional=True),
        # a family's results table: each member's count of crossings, and its bounds
        # (7.59) element by element, each with its own symbol
        Q("poincare_points", "", "1", "crossings per orbit", optional=True),
        Q("xi_bounds_1", r"\xi_\mathrm{min}", "1", "lower bound of xi from notes (7.59)",
          optional=True),
        Q("xi_bounds_2", r"\xi_\mathrm{max}", "1", "upper bound of xi from notes (7.59)",
          optional=True),
        Q("eta_abs_bounds_1", r"|\eta|_\mathrm{min}", "1", "lower bound of |eta| from notes (7.59)",
          optional=True),
        Q("eta_abs_bounds_2", r"|\eta|_\mathrm{max}", "1", "upper bound of |eta| from notes (7.59)",
          optional=True),
    ),
)
