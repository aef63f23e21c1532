"""What a ``central_force`` run stores: every result once, with its symbol and unit.

SI units, as the config's keys document them (masses in kg, lengths in m, the
strength k of V = −k/rⁿ in J·mⁿ).
"""

from __future__ import annotations

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

#: the Laplace–Runge–Lenz vector A = p × L − μk r̂
LRL_UNIT = "kg^2 m^3/s^2"

SCHEMA = ResultsSchema(
    columns=(
        Q("x", "x", "m", "relative position r = r1 - r2, x", ("t",)),
        Q("y", "y", "m", "relative position r = r1 - r2, y", ("t",)),
        Q("vx", r"\dot{x}", "m/s", "relative velocity, x", ("t",)),
        Q("vy", r"\dot{y}", "m/s", "relative velocity, y", ("t",)),
    ),
    invariants=(
        Q("energy", "E", "J", "energy", ("t",)),
        Q("angular_momentum", "L", "kg m^2/s", "angular momentum", ("t",)),
        Q("lrl_x", "A_x", LRL_UNIT, "Laplace-Runge-Lenz vector, x", ("t",)),
        Q("lrl_y", "A_y", LRL_UNIT, "Laplace-Runge-Lenz vector, y", ("t",)),
    ),
    analysis=(
        # the orbit's scales: Kepler elements, or from the turning points
        Q("eccentricity", "e", "1", "eccentricity: Kepler's e for V = -k/r, else "
          "(r_max - r_min)/(r_max + r_min) from the turning points", optional=True),
        Q("semi_major_axis", "a", "m", "semi-major axis: Kepler's a = -k/(2E) for V = -k/r, "
          "else (r_min + r_max)/2", optional=True),
        Q("pericentre", r"r_\mathrm{min}", "m", "pericentre distance"),
        Q("apocentre", r"r_\mathrm{max}", "m", "apocentre distance", optional=True),
        Q("period", "T", "s", "period: Kepler's third law for V = -k/r; else the radial "
          "period (pericentre to pericentre), or a circular orbit's period of revolution",
          optional=True),
        Q("reduced_mass", r"\mu", "kg", "reduced mass m1 m2/(m1 + m2)"),
        Q("total_mass", "M", "kg", "total mass m1 + m2"),
        Q("energy", "E", "J", "energy of the relative motion"),
        Q("angular_momentum", "L", "kg m^2/s", "angular momentum of the relative motion"),
        Q("potential", "", "", "the potential's name (config)", kind="str"),
        Q("bound", "", "", "whether the orbit is bound (yes or no)", kind="str"),
        Q("period_note", "", "", "why an unbound orbit has no period", kind="str",
          optional=True),
        # the cases the report's words follow, with their thresholds (cases.py)
        Q("orbit_shape", "", "", "the orbit: circle or ellipse (bound) and parabola or "
          "hyperbola (unbound) for V = -k/r; else circle, closed or rosette (bound, by the "
          "apsidal shift) or escape", kind="str"),
        Q("circular_threshold", "", "1", "eccentricity below which the orbit is a circle"),
        Q("apsidal_shift", r"2\psi - 2\pi", "rad", "turn of the pericentre per radial "
          "period, 2 psi - 2 pi from the exact apsidal angle psi (positive: with the motion)",
          optional=True),
        Q("apsides", "", "", "how the pericentre moves: advance, regress, or fixed when "
          "|2 psi - 2 pi| is below the threshold (bound non-circular orbits)", kind="str",
          optional=True),
        Q("apsidal_shift_threshold", "", "rad", "|2 psi - 2 pi| per radial period below "
          "which the apsides are fixed"),
        Q("heavier_body", "", "", "the heavier body: body 1, body 2 or neither (equal "
          "masses to 1e-12)", kind="str"),
        Q("turning_points", r"r_\mathrm{min}, r_\mathrm{max}", "m",
          "turning points of the radial motion", ("turning",)),
        Q("mass_fraction_m1", "m_1/M", "1", "mass fraction of body 1"),
        Q("mass_fraction_m2", "m_2/M", "1", "mass fraction of body 2"),
        Q("body_tracks/r1", r"\mathbf{r}_1", "m", "track of body 1 in the centre-of-mass "
          "frame", ("t", "xy")),
        Q("body_tracks/r2", r"\mathbf{r}_2", "m", "track of body 2 in the centre-of-mass "
          "frame", ("t", "xy")),
        Q("effective_potential_curve/r", "r", "m", "radii of the effective-potential curve",
          ("curve_r",)),
        Q("effective_potential_curve/potential", "V", "J", "potential V(r)", ("curve_r",)),
        Q("effective_potential_curve/effective_potential", r"V_\mathrm{eff}", "J",
          "effective potential V + L^2/(2 mu r^2)", ("curve_r",)),
        Q("effective_potential_curve/circular_radius", "r_c", "m",
          "radius of the circular orbit at this angular momentum"),
        Q("effective_potential_curve/circular_energy", "E_c", "J",
          "energy of the circular orbit at this angular momentum"),
        # the Kepler problem's checks (V = -k/r, bound)
        Q("kepler_orbit/x", "x", "m", "one orbit of the exact ellipse, x", ("orbit_sample",),
          optional=True),
        Q("kepler_orbit/y", "y", "m", "one orbit of the exact ellipse, y", ("orbit_sample",),
          optional=True),
        Q("eccentricity_vector", r"\mathbf{A}/(\mu k)", "1", "eccentricity vector", ("xy",),
          optional=True),
        Q("kepler_position_error", r"|\mathbf{r} - \mathbf{r}_\mathrm{Kepler}|", "m",
          "distance to the solution of Kepler's equation", ("t",), optional=True),
        Q("kepler_position_error_max", r"\max|\mathbf{r} - \mathbf{r}_\mathrm{Kepler}|", "m",
          "largest distance to the solution of Kepler's equation", optional=True),
        Q("kepler_velocity_error_max", r"\max|\mathbf{v} - \mathbf{v}_\mathrm{Kepler}|", "m/s",
          "largest velocity difference to the solution of Kepler's equation", optional=True),
        Q("lrl_eccentricity_error", r"|\mathbf{A}|/(\mu k) - e", "1",
          "change of the LRL vector's length", ("t",), optional=True),
        Q("lrl_eccentricity_drift", r"\max||\mathbf{A}|/(\mu k) - e|", "1",
          "largest change of the LRL vector's length", optional=True),
        Q("period_measured", r"T_\mathrm{meas}", "s",
          "period measured from pericentre passages", optional=True),
        Q("semi_major_axis_measured", r"a_\mathrm{meas}", "m",
          "semi-major axis (r_min + r_max)/2 measured", optional=True),
        Q("period_measured_note", "", "", "why the period was not measured", kind="str",
          optional=True),
        # the apsidal angle (other potentials, bound)
        Q("apsidal_angle_exact", r"\Delta\varphi", "rad", "exact apsidal angle, by quadrature "
          "or the closed form", optional=True),
        Q("apsidal_angle_exact_method", "", "", "how the exact apsidal angle was computed: "
          "quadrature or closed form", kind="str", optional=True),
        Q("apsidal_angle_near_circular", r"\pi/\sqrt{2 - n}", "rad",
          "near-circular limit of the apsidal angle", optional=True),
        Q("apsidal_angle_closed_form", r"\pi/\sqrt{1 - 2\mu\epsilon/L^2}", "rad",
          "closed-form apsidal angle of V = -k/r - epsilon/r^2", optional=True),
        Q("apsidal_angle_family/eccentricity", "e", "1",
          "eccentricities of the apsidal-angle curve", ("family_e",), optional=True),
        Q("apsidal_angle_family/angle", r"\Delta\varphi", "rad",
          "exact apsidal angle against eccentricity at this L", ("family_e",), optional=True),
        Q("apsidal_angle_note", "", "", "why the apsidal angle was not measured", kind="str",
          optional=True),
        Q("apsidal_angle_measured", r"\Delta\varphi_\mathrm{meas}", "rad",
          "apsidal angle measured from the run", optional=True),
        Q("pericentre_times", r"t_p", "s", "times of the pericentre passages",
          ("pericentre",), optional=True),
        Q("pericentre_positions/x", "x", "m", "pericentre passages, x", ("pericentre",),
          optional=True),
        Q("pericentre_positions/y", "y", "m", "pericentre passages, y", ("pericentre",),
          optional=True),
        # the Hamilton-Jacobi equations along a bound run, W = W_r(r) + alpha_theta theta,
        # relative to |E| (notes (7.16), (7.32))
        Q("hj_residual", r"\max|\partial_t S + H(q, \partial_q S)|/|E|", "1",
          "largest residual of the Hamilton-Jacobi equation along the run, dW/dr from the "
          "integrand (dS/dt = -E: also that of H(q, dW/dq) = E)", optional=True),
        Q("hj_residual_quadrature", r"\max|\partial_t S + H(q, \partial_q S)|/|E|", "1",
          "the same, S = W_r(r) + L theta - E t with W_r by quadrature and every derivative "
          "by central differences", optional=True),
        Q("hj_characteristic_residual_quadrature", r"\max|H(q, \partial_q W) - E|/|E|", "1",
          "largest residual of H(q, dW/dq) = E along the run, W_r by quadrature and its "
          "derivatives by central differences", optional=True),
        Q("hj_half_action", r"\int p_r\,dr", "J s",
          "integral of p_r dr from r_min to r_max by quadrature: half the radial action",
          optional=True),
        Q("hj_half_action_closed_form", r"\pi(k\sqrt{\mu/(-2E)} - \alpha_\theta)", "J s",
          "half the radial action in closed form (Goldstein 10.8)", optional=True),
        Q("hj_characteristic_quadrature_error",
          r"\max|W_r - W_{r,\mathrm{exact}}|/(\pi k\sqrt{\mu/(-2E)})", "1",
          "largest difference of W_r by quadrature from its closed form along the run",
          optional=True),
        Q("hj_momentum_difference", r"\max|p - \partial_q W|", "1",
          "largest difference of the integrated p_r from dW/dr on its branch (relative to "
          "the largest p_r) and of p_theta from alpha_theta (relative to it)", optional=True),
        Q("hamilton_jacobi/radius", "r", "m", "distance r along the run", ("t",),
          optional=True),
        Q("hamilton_jacobi/radial_momentum", "p_r", "kg m/s",
          "radial momentum mu dr/dt along the run", ("t",), optional=True),
        Q("hamilton_jacobi/curve_r", "r", "m", "radii from r_min to r_max", ("hj_curve",),
          optional=True),
        Q("hamilton_jacobi/curve_p_r", r"\partial W/\partial r", "kg m/s",
          "dW/dr from the integrand sqrt(2 mu (E - V) - L^2/r^2)", ("hj_curve",),
          optional=True),
        Q("hamilton_jacobi/marks_r", "r", "m", "radii of the quadrature derivative marks",
          ("hj_marks",), optional=True),
        Q("hamilton_jacobi/marks_p_r", r"\partial W/\partial r", "kg m/s",
          "dW/dr by central differences of W_r by quadrature", ("hj_marks",), optional=True),
    ),
)
