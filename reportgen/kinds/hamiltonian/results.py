"""What a ``hamiltonian`` run stores: every result once, with its symbol and unit.

The kind's columns, invariants and some results are named by the config (its
coordinates and observables): :data:`SCHEMA` declares what every run stores and
:func:`schema_for` adds what one config names.  A formula system is in whatever units
its author chose: every quantity is "1" (scaled units), the time too.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import replace

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

#: the time of a formula system: in the author's (scaled) units
TIME = Q("t", "t", "1", "time (scaled units)", ("t",), own_units="config units of time")
#: what every number of a formula system declared "1" is (the archive's ``config_units``)
OWN_UNITS = "config units (the formula's own; a pure number stays one)"


def _text(name: str, description: str, dims: tuple[str, ...] = (), optional: bool = False):
    return Q(name, "", "", description, dims, kind="str", optional=optional)


def _flag(name: str, description: str, optional: bool = False):
    return Q(name, "", "", description, kind="bool", optional=optional)


_TRANSFORM = (
    Q("transform/Q", "Q", "1", "new coordinates along the run", ("t", "new_coordinate")),
    Q("transform/P", "P", "1", "new momenta along the run", ("t", "new_coordinate")),
    Q("transform/defect", r"|M^T J M - J|", "1", "symplectic defect along the run", ("t",)),
    Q("transform/K", "K", "1", "new Hamiltonian K = H + dF/dt along the run", ("t",)),
    _text("transform_new", "names of the new coordinates and momenta", ("new_column",)),
    _text("transform_latex", "the generating function and its relations (TeX)",
          ("relation",)),
    Q("transform_defect_max", r"\max|M^T J M - J|", "1",
      "largest symplectic defect along the run"),
    Q("transform_bracket_max", r"\max|\{Q_i, P_j\} - \delta_{ij}|", "1",
      "largest departure of the fundamental brackets along the run"),
    _text("transform_K_latex", "K in the new variables (TeX), empty if no closed form"),
    Q("transform_run_difference", r"\max|(Q, P)_K - (Q, P)_H|", "1",
      "largest difference between integrating K and the image of the H orbit"),
    Q("transform_identity_defect", r"\max|(Q, P) - (q, p)|", "1",
      "largest distance of the new variables from the old, relative to their size (0: the "
      "identity transformation)", optional=True),
    Q("transform_K_other_sign_difference", r"\max|(Q, P)_{K_-} - (Q, P)_H|", "1",
      "largest difference between integrating K = H - dF/dt (the other sign, as notes (6.14) "
      "prints it for F3) and the image of the H orbit; a time-dependent F only",
      optional=True),
    _text("transform_kind", "the transformation's type: F1, F2, F3, F4 (generating "
          "function) or G (infinitesimal)"),
    Q("transform_bracket_relative", r"\max|\{z_a, z_b\} - J_{ab}|/s_{ab}", "1",
      "largest departure of the fundamental brackets, relative to the size s of their terms "
      "(|M| |J| |M|^T)"),
    Q("transform/dH", r"\Delta H", "1", "H(Q, P) - H(q, p) along the run (infinitesimal)",
      ("t",)),
    Q("transform/first_order", r"\epsilon\{H, G\}", "1",
      "first-order change of H along the run (infinitesimal)", ("t",)),
    Q("transform/second_order", r"\epsilon^2 w^T H'' w/2", "1",
      "second-order change of H along the run (infinitesimal)", ("t",)),
    Q("transform_epsilon", r"\epsilon", "1", "parameter of the infinitesimal transformation"),
    Q("transform_bracket_closed_max", r"\epsilon^2\max|\{w_a, w_b\}|", "1",
      "largest departure of the brackets from J by the closed form eps^2 {w_a, w_b}"),
    Q("transform_bracket_agreement", "", "1", "largest |{z_a, z_b} - J - eps^2 {w_a, w_b}| "
      "relative to the size of the bracket's terms"),
    _flag("transform_bracket_symbolic", "whether {z_a, z_b} = J + eps^2 {w_a, w_b} holds "
          "in SymPy's algebra"),
    _text("transform_HG_latex", "{H, G} simplified (TeX)"),
    Q("transform_dH_max", r"\max|\Delta H|", "1", "largest change of H along the run"),
    Q("transform_first_order_max", r"\max|\epsilon\{H, G\}|", "1",
      "largest first-order change of H"),
    Q("transform_second_order_residual", "", "1", "largest |Delta H - eps{H, G} - eps^2 "
      "w^T H'' w/2| along the run (third order in eps)"),
    Q("transform_H_scale", r"\max|H|", "1", "largest |H| along the run"),
)

_NOETHER = (
    _flag("noether_symmetry", "whether delta L - dF/dt simplifies to zero (a symmetry)"),
    _text("noether_delta_latex", "the generator delta q of each coordinate (TeX)",
          ("coordinate",)),
    _text("noether_delta_velocity_latex", "delta q_dot = d(delta q)/dt (TeX)",
          ("coordinate",)),
    _text("noether_delta_L_latex", "delta L, simplified (TeX)"),
    _text("noether_F_latex", "F with delta L = dF/dt (TeX)"),
    _text("noether_residual_latex", "delta L - dF/dt, simplified (TeX)"),
    _text("noether_charge_latex", "the charge sum dL/dq_dot delta q - F in q, q_dot (TeX)"),
    _text("noether_charge_qp_latex", "the charge in q, p (TeX)"),
    _text("noether_bracket_latex", "{Q, H} + dQ/dt simplified (TeX)"),
    _flag("noether_bracket_zero", "whether {Q, H} + dQ/dt simplifies to zero"),
    Q("noether_charge0", r"Q_{\mathrm{N}}(0)", "1", "the charge at t = 0"),
    Q("noether_scale", "", "1", "the size of the charge's parts at t = 0 (its drift's scale)"),
    Q("noether_drift", r"\max|Q_{\mathrm{N}} - Q_{\mathrm{N}}(0)|/s", "1",
      "largest drift of the charge along the run, relative to noether_scale"),
    Q("noether_values", r"Q_{\mathrm{N}}", "1", "the charge along the run (when the "
      "transformation is not a symmetry)", ("t",)),
)

_TOTAL_DERIVATIVE = (
    _text("total_derivative_F_latex", "F(q, t) of L' = L + dF/dt (TeX)"),
    _text("total_derivative_L_latex", "L' = L + dF/dt (TeX)"),
    _flag("total_derivative_same_equations", "whether E(L') - E(L) simplifies to zero for "
          "every coordinate"),
    _text("total_derivative_difference_latex", "E(L') - E(L) simplified (TeX)",
          ("coordinate",)),
    _text("total_derivative_shift_latex", "p' - p = dF/dq (TeX)", ("coordinate",)),
    _text("total_derivative_H_latex", "the Hamiltonian H' of L' (TeX)"),
    _flag("total_derivative_H_same", "whether H'(q, p) = H(q, p - dF/dq) - dF/dt simplifies"),
    Q("total_derivative_H_error", r"\max|H' - (H - \partial F/\partial t)|", "1",
      "largest |H'(q, p + dF/dq) - H(q, p) + dF/dt| along the run"),
    Q("total_derivative_H_scale", r"\max|H - \partial F/\partial t|", "1",
      "largest |H - dF/dt| along the run"),
)

#: a point transformation q = q(q′) of L (notes (3.39)–(3.47)), its run carried back
_POINT_TRANSFORM = (
    _text("point_transform_coordinates", "names of the new coordinates q'", ("new_coordinate",)),
    _text("point_transform_coordinates_latex", "the new coordinates (TeX)", ("new_coordinate",)),
    _text("point_transform_old_latex", "each old coordinate as a function of the new (TeX)",
          ("coordinate",)),
    _text("point_transform_det_latex", "det J, J = dq/dq' (TeX)"),
    _text("point_transform_L_latex", "L'(q', q_dot') = L(q(q'), J q_dot') (TeX)"),
    _text("point_transform_H_latex", "the Hamiltonian of L' (TeX)"),
    _flag("point_transform_velocity_identity", "whether d q_dot/d q_dot' - dq/dq' simplifies "
          "to zero (notes (3.42))"),
    _flag("point_transform_second_identity", "whether d q_dot/dq' - sum_k d2q/dq'_k dq' "
          "q_dot'_k simplifies to zero (notes (3.43))"),
    _flag("point_transform_covariant", "whether E_q'(L') - J^T E_q(L) simplifies to zero for "
          "every new coordinate (notes (3.47))"),
    _text("point_transform_residual_latex", "E_q'(L') - J^T E_q(L) simplified (TeX)",
          ("new_coordinate",)),
    Q("point_transform_initial", r"(q'_0, p'_0)", "1", "initial state of L': q'(0) by "
      "Newton's method, p' = dL'/dq_dot' at q_dot'(0) = J^-1 q_dot(0)", ("new_column",)),
    Q("point_transform_det0", r"|\det J|/\prod\|J_k\|", "1", "|det J| at t = 0 relative "
      "to the product of the lengths of J's columns (1: orthogonal, 0: singular)"),
    Q("point_transform_det_min", r"\min|\det J|/\prod\|J_k\|", "1", "smallest relative "
      "|det J| along the run of L'"),
    Q("point_transform_singular_threshold", "", "1", "relative |det J| below which J is "
      "called singular"),
    Q("point_transform_q_difference", r"\max|q(q') - q|/\max|q|", "1", "largest difference "
      "of the run of L' carried back by q(q') from the main run, relative to max|q|"),
    Q("point_transform_q_scale", r"\max|q|", "1", "largest |q| of the main run"),
    Q("point_transform_p_difference", r"\max|p' - J^T p|/\max|p'|", "1", "largest "
      "difference of the momenta of L' from J^T p of the main run, relative to max|p'|"),
    Q("point_transform_p_scale", r"\max|p'|", "1", "largest |p'| of the run of L'"),
    Q("point_transform_samples", "", "1", "samples of the run of L' compared", kind="int"),
    _text("point_transform_run_status", "the numerical status of the run of L'"),
    Q("point_transform_nfev", "", "1", "right-hand-side evaluations of the run of L'",
      kind="int"),
    Q("point_transform_tolerance", "", "1", "the runs agree below this relative difference: "
      "1e4 times the larger of the run's rtol and its energy drift"),
    _flag("point_transform_agree", "whether both relative differences are below "
          "point_transform_tolerance over the whole run"),
)


def _sphere(name: str, symbol: str, description: str):
    return Q(f"legendre_sphere/{name}", symbol, "1", f"unit sphere, at each tangent point: "
             f"{description}", ("tangent_point",))


def _surface_of_l(name: str, symbol: str, description: str, dims=("velocity_point",)):
    return Q(f"legendre_lagrangian/{name}", symbol, "1", f"surface z = L(qdot_1, qdot_2) at "
             f"the initial coordinates, at each sampled velocity: {description}", dims)


#: the Legendre transform as geometry (notes (4.15)–(4.28)): the velocity Hessian of a regular
#: L (every L run), and, for two velocities and a positive-definite Hessian, the notes' unit
#: sphere and the surface z = L(q̇₁, q̇₂) with their tangent planes
_LEGENDRE_GEOMETRY = (
    Q("legendre_velocity_hessian", r"\partial^2 L/\partial\dot{q}_i\partial\dot{q}_j", "1",
      "velocity Hessian of L at the initial point (t = 0)", ("coordinate", "coordinate_j")),
    Q("legendre_velocity_hessian_eigenvalues", r"\lambda", "1",
      "eigenvalues of the velocity Hessian of L at the initial point", ("coordinate",)),
    _flag("legendre_convex", "whether the velocity Hessian is positive definite (every "
          "eigenvalue above legendre_convex_threshold of the largest)"),
    Q("legendre_convex_threshold", "", "1", "fraction of the largest eigenvalue every "
      "eigenvalue must exceed for a positive-definite velocity Hessian"),
    _sphere("x0", "x_0", "x of the point"),
    _sphere("y0", "y_0", "y of the point"),
    _sphere("z0", "z_0", "height z = sqrt(1 - x^2 - y^2) of the point (notes (4.19))"),
    _sphere("xi", r"\xi", "plane coordinate xi = -dz/dx by differences (notes (4.23))"),
    _sphere("eta", r"\eta", "plane coordinate eta = -dz/dy by differences (notes (4.23))"),
    _sphere("omega", r"\omega", "intercept omega = z0 + x0 xi + y0 eta (notes (4.24))"),
    _sphere("omega_closed", r"\sqrt{1 + \xi^2 + \eta^2}", "closed form of omega(xi, eta)"),
    _sphere("domega_dxi", r"\partial\omega/\partial\xi", "d omega/d xi by differences of "
            "omega(xi, eta), each from its own tangent point (notes (4.26))"),
    _sphere("domega_deta", r"\partial\omega/\partial\eta", "d omega/d eta by differences "
            "(notes (4.27))"),
    Q("legendre_sphere_slope_error", r"\max|\xi - x_0/z_0|", "1", "largest difference of "
      "the slopes by differences from the tangent plane (4.20), xi = x0/z0, eta = y0/z0"),
    Q("legendre_sphere_omega_error", r"\max|\omega - \sqrt{1 + \xi^2 + \eta^2}|", "1",
      "largest difference of omega (4.24) from its closed form"),
    Q("legendre_sphere_intercept_error", r"\max|\omega z_0 - 1|", "1", "largest departure "
      "of the intercept from 1/z0, where the plane x.x0 = 1 (4.21) meets the z axis"),
    Q("legendre_sphere_derivative_error", r"\max|\partial\omega/\partial\xi - x_0|", "1",
      "largest difference of d omega/d xi, d omega/d eta from x0, y0 (notes (4.26)-(4.27))"),
    Q("legendre_sphere_sign_minus", r"\max|\omega - z - x\xi - y\eta|", "1",
      "largest residual of omega - z = x xi + y eta, omega(xi, eta) in closed form"),
    Q("legendre_sphere_sign_plus", r"\max|\omega + z - x\xi - y\eta|", "1",
      "largest residual of omega + z = x xi + y eta, as notes (4.28) prints it"),
    Q("legendre_sphere_sign_scale", r"\max(|\omega| + |z| + |x\xi| + |y\eta|)", "1",
      "largest size of the terms of the two relations"),
    _text("legendre_sphere_relation", "which relation holds to legendre_relation_threshold "
          "of the size of its terms: minus (omega - z = x xi + y eta), plus (omega + z = "
          "x xi + y eta), both or neither"),
    Q("legendre_relation_threshold", "", "1", "fraction of the size of its terms below "
      "which a relation's residual is rounding"),
    Q("legendre_slope_step", "h", "1", "step of the slopes' central differences, relative "
      "to the coordinates' scale"),
    Q("legendre_plane_step", r"\delta", "1", "step of omega's central differences in xi "
      "and eta (unit sphere)"),
    Q("legendre_sphere_curve/x", "x", "1", "the cut y = 0 of the unit sphere: x",
      ("curve_point",)),
    Q("legendre_sphere_curve/z", "z", "1", "the cut y = 0 of the unit sphere: z = "
      "sqrt(1 - x^2)", ("curve_point",)),
    Q("legendre_sphere_dual/xi", r"\xi", "1", "the dual curve at eta = 0: xi",
      ("dual_point",)),
    Q("legendre_sphere_dual/omega", r"\omega", "1", "the dual curve at eta = 0: omega = "
      "sqrt(1 + xi^2) (closed form)", ("dual_point",)),
    _surface_of_l("x", r"\dot{q}_1", "the first velocity"),
    _surface_of_l("y", r"\dot{q}_2", "the second velocity"),
    _surface_of_l("z", "L", "the Lagrangian"),
    _surface_of_l("xi", r"\xi", "xi = -dL/dqdot_1 by differences"),
    _surface_of_l("eta", r"\eta", "eta = -dL/dqdot_2 by differences"),
    _surface_of_l("omega", r"\omega", "intercept omega = L + x xi + y eta (notes (4.24))"),
    _surface_of_l("p", "p", "momenta dL/dqdot (SymPy)", ("velocity_point", "coordinate")),
    _surface_of_l("H", "H", "the scene's Hamiltonian at those momenta"),
    _surface_of_l("domega_dxi", r"\partial\omega/\partial\xi", "d omega/d xi by "
                  "differences of omega(xi, eta)"),
    _surface_of_l("domega_deta", r"\partial\omega/\partial\eta", "d omega/d eta by "
                  "differences of omega(xi, eta)"),
    Q("legendre_lagrangian_slope_error", r"\max|\xi + p|", "1", "largest |xi + p_1|, "
      "|eta + p_2| over the sampled velocities"),
    Q("legendre_lagrangian_momentum_scale", r"\max|p|", "1", "largest |p| over the "
      "sampled velocities"),
    Q("legendre_lagrangian_omega_error", r"\max|\omega + H|", "1", "largest |omega + H| "
      "over the sampled velocities (omega = -H, notes (4.31))"),
    Q("legendre_lagrangian_energy_scale", r"\max|H|", "1", "largest |H| over the sampled "
      "velocities"),
    Q("legendre_lagrangian_derivative_error", r"\max|\partial\omega/\partial\xi - \dot{q}|",
      "1", "largest difference of d omega/d xi, d omega/d eta from the velocities"),
    Q("legendre_lagrangian_velocity_scale", r"\max|\dot{q}|", "1", "largest |qdot| over "
      "the sampled velocities"),
    Q("legendre_lagrangian_sign_minus", r"\max|\omega - z - x\xi - y\eta|", "1",
      "largest residual of omega - L = qdot.xi, omega(xi, eta) = -H(q, -xi, -eta)"),
    Q("legendre_lagrangian_sign_plus", r"\max|\omega + z - x\xi - y\eta|", "1",
      "largest residual of omega + L = qdot.xi, as notes (4.28) prints it"),
    Q("legendre_lagrangian_sign_scale", r"\max(|\omega| + |z| + |x\xi| + |y\eta|)", "1",
      "largest size of the terms of the two relations"),
    _text("legendre_lagrangian_relation", "which relation holds for z = L (as "
          "legendre_sphere_relation)"),
)

#: a first-order Lagrangian L = a(q, t)·q̇ − V(q, t) reduced (notes (3.36–3.38)): the state is
#: q alone, the energy function (the invariant H) is V
_FIRST_ORDER = (
    _flag("first_order", "whether L is linear in the velocities, reduced to first-order "
          "equations (notes (3.36–3.38))"),
    _text("first_order_latex/a", "a_i = dL/dq_dot_i (TeX)", ("coordinate",)),
    _text("first_order_latex/V", "V = a.q_dot - L, the energy function (TeX)"),
    _text("first_order_latex/omega", "omega_ij = d_i a_j - d_j a_i, row by row (TeX)",
          ("coordinate",)),
    _text("first_order_latex/det", "det omega (TeX)"),
    _text("first_order_latex/inverse", "the brackets {q_i, q_j} = (omega^-1)_ij, row by row "
          "(TeX)", ("coordinate",)),
    _text("first_order_latex/qdot", "the reduced equations dq/dt = omega^-1 (grad V + da/dt) "
          "(TeX)", ("coordinate",)),
    Q("first_order_det0", r"\det\omega(0)", "1", "det omega at the initial point"),
    Q("first_order_det_min", r"\min|\det\omega|", "1", "smallest |det omega| along the run"),
    _flag("first_order_det_sign_kept", "whether det omega keeps the sign of det omega(0) at "
          "every sample of the run"),
    Q("first_order_el_residual", r"\max|E_i|", "1", "largest Euler-Lagrange expression "
      "d/dt dL/dq_dot - dL/dq along the run, with the reduced velocities"),
    Q("first_order_el_scale", "", "1", "largest size of the Euler-Lagrange expression's "
      "terms along the run (its rounding scale)"),
    _flag("first_order_bracket_generates", "whether {q_i, V} = dq_i/dt simplifies for "
          "every coordinate (a t-independent L)"),
    _flag("first_order_energy_rate_zero", "whether dV/dt = grad V . dq/dt + dV/dt "
          "simplifies to zero"),
    _flag("first_order_linear", "whether the reduced equations are dq/dt = A q with a "
          "constant A (closed form q(t) = exp(tA) q(0))"),
    Q("first_order_A", "A", "1", "the constant matrix of linear reduced equations",
      ("coordinate", "coordinate_j"), optional=True),
    Q("first_order_closed_form", r"e^{tA}q_0", "1", "the closed form exp(tA) q(0) along the "
      "run (linear reduced equations)", ("t", "coordinate"), optional=True),
    Q("first_order_closed_form_error", r"\max|q - e^{tA}q_0|", "1", "largest difference of "
      "the integration and the closed form (linear reduced equations)", optional=True),
    Q("first_order_closed_form_scale", r"\max|q|", "1", "largest |q| along the run",
      optional=True),
    # why there is no Legendre transform: the linear function of notes (4.13)-(4.14)
    Q("first_order_velocity_hessian", r"\partial^2 L/\partial\dot{q}_i\partial\dot{q}_j",
      "1", "velocity Hessian of L at the initial point (t = 0)",
      ("coordinate", "coordinate_j")),
    Q("first_order_velocity_hessian_rank", "", "1", "rank of the velocity Hessian of L, "
      "simplified by SymPy", kind="int"),
    _flag("first_order_momenta_contain_velocities", "whether some p_i = dL/dqdot_i, "
          "simplified, contains a velocity"),
    Q("first_order_momentum_spread", r"\max(p) - \min(p)", "1", "largest spread of a "
      "momentum dL/dqdot_i at the initial point over the sampled velocities"),
    Q("first_order_momentum_scale", r"\max|p|", "1", "largest |p_i| at the initial point "
      "over the sampled velocities"),
    Q("first_order_velocity_samples", "", "1", "velocities drawn at random to evaluate "
      "the momenta at the initial point", kind="int"),
    Q("first_order_velocity_range", "", "1", "the velocities are drawn from [-v, v] with "
      "this v"),
)

SCHEMA = ResultsSchema(
    time=TIME,
    own_units=OWN_UNITS,
    invariants=(Q("H", "H", "1", "Hamiltonian", ("t",)),),
    analysis=(
        # physical behaviour (not the run's numerical status): chaotic or regular
        _text("behaviour", "physical behaviour: chaotic or regular (two orbits 1e-10 apart)",
              optional=True),
        Q("separation_growth", r"\max d/d_0", "1", "growth of the separation of two orbits "
          "started 1e-10 apart", optional=True),
        Q("lyapunov_time", r"T_\lambda", "1", "Lyapunov time 1/lambda of a chaotic orbit",
          optional=True),
        Q("chaos_growth_threshold", r"G_\mathrm{chaos}", "1", "growth of the separation of "
          "two orbits within the run from which the orbit is called chaotic (below it: "
          "regular)", optional=True),
        _text("angles", "coordinates H depends on 2 pi-periodically", ("angle",)),
        _text("latex/H", "the Hamiltonian (TeX)"),
        _text("latex/qdot", "Hamilton's equations dq/dt = dH/dp (TeX)", ("coordinate",)),
        _text("latex/pdot", "Hamilton's equations dp/dt = -dH/dq (TeX)", ("coordinate",)),
        _text("latex/q", "the coordinates (TeX)", ("coordinate",)),
        _text("latex/p", "the momenta (TeX)", ("coordinate",)),
        _text("latex/L", "the Lagrangian (TeX)", optional=True),
        _text("latex/momenta", "the momenta dL/dq_dot (TeX)", ("coordinate",), optional=True),
        _text("latex/velocities", "the velocities dq/dt(q, p) (TeX)", ("coordinate",),
              optional=True),
        _text("coordinates", "names of the coordinates", ("coordinate",)),
        _text("given", "what the config gives: H or L"),
        _flag("kinetic_potential_split", "whether H = T(p) + V(q): no t, every mixed "
              "second derivative d2H/dq_i dp_j simplifies to zero (the split symplectic "
              "splitting methods need; not separation of variables)"),
        _flag("time_dependent", "whether H depends on t"),
        _text("cyclic", "coordinates H does not contain", ("cyclic",)),
        Q("H0", "H_0", "1", "H of the initial state"),
        Q("initial_state", "y_0", "1", "initial state (q, p)", ("column",)),
        _text("pair_brackets/f", "first observable of a bracket", ("pair",), optional=True),
        _text("pair_brackets/g", "second observable of a bracket", ("pair",), optional=True),
        _text("pair_brackets/bracket", "{f, g} simplified", ("pair",), optional=True),
        _text("pair_brackets/latex", "{f, g} simplified (TeX)", ("pair",), optional=True),
        Q("jacobi_max", r"\max|\{f,\{g,h\}\} + \{g,\{h,f\}\} + \{h,\{f,g\}\}|", "1",
          "largest Jacobi-identity sum on samples of the run"),
        Q("jacobi_scale", "", "1", "largest sum of the sizes of the three Jacobi-identity "
          "terms on the samples"),
        Q("jacobi_terms", "", "1", "largest |value| of each Jacobi-identity term on the "
          "samples", ("term",)),
        Q("jacobi_roundoff", "", "1", "largest size of each term's parts (sums and products "
          "in absolute value): the scale of its rounding", ("term",)),
        _flag("jacobi_tested", "whether some Jacobi-identity term is above rounding (false: "
              "every term vanishes, and the identity is not tested)"),
        _flag("brackets_canonical", "{q_i, p_j} = delta_ij, {q_i, q_j} = {p_i, p_j} = 0 "
              "expanded by SymPy (notes (4.38))", optional=True),
        _flag("brackets_antisymmetric", "{f, g} + {g, f} expands to 0 for the cubics f, g "
              "(notes (4.38))", optional=True),
        _flag("brackets_homogeneous", "{C f, h} - C {f, h} expands to 0 for the cubic h "
              "(notes (4.38))", optional=True),
        _flag("brackets_leibniz", "{f g, h} - f {g, h} - {f, h} g expands to 0 (notes (4.38))",
              optional=True),
        Q("jacobi_relative", "", "1", "largest Jacobi-identity sum relative to jacobi_scale "
          "(NaN when not tested)"),
        _text("jacobi_triple", "the f, g, h of the Jacobi identity checked", ("triple",)),
        _text("jacobi_triple_latex", "the f, g, h of the Jacobi identity checked (TeX)",
              ("triple",), optional=True),
        Q("legendre_momentum_error", r"\max|p - \partial L/\partial\dot{q}|", "1",
          "largest error of the momenta along the run", optional=True),
        Q("legendre_energy_error", r"\max|H - (\dot{q} p - L)|", "1",
          "largest difference of H and the energy function along the run", optional=True),
        Q("legendre_energy_scale", r"\max|H|", "1", "largest |H| along the run",
          optional=True),
        Q("legendre_passive_error", r"\max|\partial H/\partial x + \partial L/\partial x|",
          "1", "largest |dH/dx + dL/dx| along the run over the passive variables x = q, t of "
          "the Legendre transform (notes (4.8))", optional=True),
        Q("legendre_passive_scale", r"\max|\partial L/\partial x|", "1",
          "largest |dL/dx| along the run over the passive variables", optional=True),
        Q("phase_grid/q", "q", "1", "phase-portrait grid: coordinate", ("grid_q",),
          optional=True),
        Q("phase_grid/p", "p", "1", "phase-portrait grid: momentum", ("grid_p",),
          optional=True),
        Q("phase_grid/H", "H", "1", "H over the phase-portrait grid", ("grid_p", "grid_q"),
          optional=True),
        Q("poincare/t", "t", "1", "time of each crossing of the surface of section",
          ("crossing",), optional=True),
        Q("poincare/u", "u", "1", "first plotted column at each crossing", ("crossing",),
          optional=True),
        Q("poincare/v", "v", "1", "second plotted column at each crossing", ("crossing",),
          optional=True),
        Q("poincare/state", "y", "1", "the state at each crossing", ("crossing", "column"),
          optional=True),
        _text("poincare_surface", "the surface of section: column, value, direction",
              ("surface",), optional=True),
        _text("poincare_axes", "the two columns plotted on the surface of section",
              ("axis",), optional=True),
        Q("poincare_H_error", r"\max|H - H_0|", "1",
          "largest departure of H from H(0) at the crossings", optional=True),
        Q("poincare_H_relative_error", r"\max|H - H_0|/E_s", "1",
          "largest departure of H from H(0) at the crossings, relative to the energy scale "
          "E_s = max(|H0|, |T0|, |V0|) of the run's drift", optional=True),
        Q("poincare_H_farthest", "H", "1", "H at the crossing furthest from H(0)",
          optional=True),
        _text("poincare_located", "where the crossings were located: \"steps\" (on the "
              "integrator's continuous extension of each step) or \"samples\" (cubic Hermite "
              "interpolation between stored samples)", optional=True),
        Q("poincare_points", "", "1", "crossings of the surface of section", optional=True),
        Q("poincare_edge/u", "u", "1", "edge grid: first plotted column", ("edge_u",),
          optional=True),
        Q("poincare_edge/v", "v", "1", "edge grid: second plotted column", ("edge_v",),
          optional=True),
        Q("poincare_edge/H", "H", "1", "H over the edge grid", ("edge_v", "edge_u"),
          optional=True),
        Q("poincare_edge_energy", "E", "1", "the members' common energy", optional=True),
        _text("poincare_edge_momentum", "the momentum that vanishes on the edge",
              optional=True),
        *(replace(q, optional=True) for q in _TRANSFORM),
        *(replace(q, optional=True) for q in _LEGENDRE_GEOMETRY),
        *(replace(q, optional=True) for q in _FIRST_ORDER),
        *(replace(q, optional=True) for q in _NOETHER),
        *(replace(q, optional=True) for q in _TOTAL_DERIVATIVE),
        *(replace(q, optional=True) for q in _POINT_TRANSFORM),
        _text("hj_separation", "the separation of the quadrature solution", optional=True),
        Q("hj_max_difference", r"\max|y_{HJ} - y|", "1",
          "largest difference of the quadrature solution and the integration",
          optional=True),
    ),
    open_groups={
        "observables": Q("observables", "", "1", "observable that is not conserved",
                         ("t",)),
        "hamilton_jacobi/solution": Q("solution", "", "1", "quadrature solution", ("t",)),
        "hamilton_jacobi/difference": Q("difference", "", "1",
                                        "|quadrature solution - integration|", ("t",)),
        "hamilton_jacobi/constants": Q("constants", "", "1",
                                       "separated constant along the run", ("t",)),
        "hj_constants": Q("hj_constants", "", "1", "separated constant at t = 0"),
        "hj_constant_drift": Q("hj_constant_drift", "", "1",
                               "largest relative drift of a separated constant"),
    },
)


def schema_for(coordinates: Iterable[str], observables: Iterable[str],
               new_columns: Iterable[str] = (),
               tex: Callable[[str], str] = str, noether: bool = False,
               first_order: bool = False) -> ResultsSchema:
    """:data:`SCHEMA` with what a config names: the columns (the coordinates, then
    ``p_<q>``, and a canonical transformation's new variables), the invariants (H, each
    observable, the momentum of each coordinate that may turn out cyclic) and the
    results per column and per observable.  ``tex(name)`` gives a name's TeX symbol.
    ``first_order``: L linear in the velocities (notes (3.36–3.38)): the columns are the
    coordinates alone, the reduction's results are stored and Hamilton's are not."""
    coordinates, observables = list(coordinates), list(observables)
    columns = [Q(q, tex(q), "1", f"coordinate {q}", ("t",)) for q in coordinates]
    if first_order:
        return _first_order_schema(columns, observables, tex)
    columns += [Q(f"p_{q}", tex(f"p_{q}"), "1", f"momentum conjugate to {q}", ("t",))
                for q in coordinates]
    columns += [Q(c, tex(c), "1", f"new canonical variable {c}", ("t",)) for c in new_columns]
    invariants = [Q(f, tex(f), "1", f"observable {f}", ("t",)) for f in observables]
    invariants += [Q(f"p_{q}", tex(f"p_{q}"), "1", f"momentum conjugate to {q} (cyclic)",
                     ("t",)) for q in coordinates]
    if noether:
        invariants.append(Q("noether_charge", r"Q_{\mathrm{N}}", "1",
                            "Noether charge of the declared symmetry", ("t",)))
    analysis = [Q(f"initial_{c.name}", c.symbol + "(0)" if c.symbol else "", "1",
                  f"initial value of {c.name}") for c in columns[:2 * len(coordinates)]]
    for f in observables:
        analysis += [
            _text(f"poisson_{f}", f"{{{f}, H}} simplified (\"0\": conserved)"),
            _text(f"poisson_{f}_latex", f"{{{f}, H}} (TeX)"),
            _flag(f"conserved_{f}", f"whether {f} is conserved"),
            Q(f"poisson_{f}_max", rf"\max|\{{{tex(f)}, H\}}|", "1",
              f"largest |{{{f}, H}}| along the run"),
            _text(f"latex/observable_{f}", f"the observable {f} (TeX)"),
        ]
    return SCHEMA.merged(ResultsSchema(columns=tuple(columns), invariants=tuple(invariants),
                                       analysis=tuple(analysis), time=TIME))


#: what every run stores, first-order or not
_ALWAYS = frozenset({"angles", "latex/H", "latex/q", "latex/L", "coordinates", "given",
                     "kinetic_potential_split", "time_dependent", "H0",
                     "initial_state"})


def _first_order_schema(columns: list[Q], observables: list[str],
                        tex: Callable[[str], str]) -> ResultsSchema:
    """The schema of a reduced first-order L: the reduction's results required, Hamilton's
    (momenta, Jacobi identity, Legendre checks) not stored."""
    required = {q.name for q in _FIRST_ORDER if not q.optional} | _ALWAYS
    analysis = [replace(q, optional=q.name not in required) for q in SCHEMA.analysis]
    analysis += [Q(f"initial_{c.name}", c.symbol + "(0)" if c.symbol else "", "1",
                   f"initial value of {c.name}") for c in columns]
    for f in observables:
        analysis += [
            _text(f"poisson_{f}", f"{{{f}, V}} of the reduced bracket, simplified"),
            _flag(f"conserved_{f}", f"whether {f} is conserved"),
            _text(f"latex/observable_{f}", f"the observable {f} (TeX)"),
        ]
    invariants = [*SCHEMA.invariants,
                  *(Q(f, tex(f), "1", f"observable {f}", ("t",)) for f in observables)]
    return ResultsSchema(columns=tuple(columns), invariants=tuple(invariants),
                         analysis=tuple(analysis), time=TIME, open_groups=SCHEMA.open_groups,
                         own_units=OWN_UNITS)
