"""What a ``heavy_top`` run stores: every result once, with its symbol and unit.

Symbols follow the lecture notes §10.1: u = cos θ, a = I3ω3/I1, b = p_φ/I1, notes (10.25),
α = 2E'/I1, β = 2Mgl/I1, notes (10.30), the roots u1 ≤ u2 ≤ u3 of f(u), notes (10.31).  Rates are
written dφ/dt, not with a dot accent: in an SVG figure the dot is a combining character,
which the PDF engine draws as a dotted circle (see ``plots.py``).
"""

from __future__ import annotations

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

#: the runs a ``[band]`` may hold: ``main`` (one case) or the three of ``case = "all"``
BAND_RUNS = ("main", "loops", "waves", "cusps")


def _contours() -> tuple[Q, ...]:
    """``/analysis/contours``: textbook ex. 4.10(a)–(e), t(u) = ∫du/√f(u) by contour
    integration on the cut plane (the textbook's names u_X = u1, u_N = u2, u_U = u3)."""
    g = "contours/"
    grid = ("contour_line", "contour_point")
    out = [
        Q(g + "u_X", "u_X", "1", "smallest root of f(u) (u1), the bottom of a wobble"),
        Q(g + "u_N", "u_N", "1", "middle root of f(u) (u2)"),
        Q(g + "u_U", "u_U", "1", "root of f(u) past u = 1 (u3)"),
        Q(g + "period", "T", "s", "nutation period 4K(k^2)/sqrt(beta (u3 - u1))"),
        Q(g + "imaginary_period", r"\tau", "s",
          "imaginary period 4K(1 - k^2)/sqrt(beta (u3 - u1))"),
        Q(g + "grid_re", r"\mathrm{Re}\,u", "1", "grid of horizontal lines in the upper "
          "half u plane", grid),
        Q(g + "grid_im", r"\mathrm{Im}\,u", "1", "their heights", grid),
    ]
    for name, words in (("u_N", "t(u_N), the rectangle's corner T/2"),
                        ("u_U", "t(u_U), the corner T/2 + i tau/2"),
                        ("infinity", "t(infinity) along the real axis past u_U: i tau/2"),
                        ("infinity_left", "t(-infinity) along the real axis below u_X: "
                         "i tau/2"),
                        ("loop", "the loop integral clockwise round [u_N, u_U]: i tau"),
                        ("loop_real", "the loop integral round [u_X, u_N], through both "
                         "cuts: T")):
        out += [Q(f"{g}t_{name}_re", r"\mathrm{Re}\,t", "s", f"real part of {words}"),
                Q(f"{g}t_{name}_im", r"\mathrm{Im}\,t", "s", f"imaginary part of {words}")]
    for name, words in (("upper", "the grid on the first sheet"),
                        ("lower", "the grid's mirror image below the axis, through "
                         "(u_X, u_N)"),
                        ("left", "the mirror grid on the second sheet, through (-inf, u_X)"),
                        ("right", "the mirror grid on the second sheet, through "
                         "(u_N, u_U)")):
        out += [Q(f"{g}{name}_re", r"\mathrm{Re}\,t", "s", f"t of {words}", grid),
                Q(f"{g}{name}_im", r"\mathrm{Im}\,t", "s", f"t of {words}", grid)]
    for name, words in (
            ("corner_u_N", "|t(u_N) - T/2|"), ("corner_u_U", "|t(u_U) - (T + i tau)/2|"),
            ("corner_infinity", "|t(infinity) - i tau/2|"),
            ("infinity_both_ways", "|t(+infinity) - t(-infinity)|"),
            ("sides", "largest distance of a real point's image from its side"),
            ("upper_in_rectangle", "farthest first-sheet image outside (0, T/2) x (0, tau/2)"),
            ("lower_reflection", "max |t(conj u) - conj t(u)|"),
            ("lower_in_rectangle", "farthest image below the axis outside (0, T/2) x "
             "(-tau/2, 0)"),
            ("second_sheet_left", "max |t1 + t0| through (-inf, u_X]"),
            ("second_sheet_right", "max |t2 - (T - t0)| through [u_N, u_U]"),
            ("loop", "|loop integral - i tau|"),
            ("loop_real", "|loop integral round [u_X, u_N] - T|")):
        out.append(Q(f"{g}defects/{name}", r"\delta", "s", f"defect: {words}"))
    for name, side in (("bottom", "Im t = 0 on (u_X, u_N)"), ("right", "Re t = T/2 on "
                       "(u_N, u_U)"), ("top", "Im t = tau/2 on (u_U, inf)"),
                       ("left", "Re t = 0 on (-inf, u_X)")):
        out.append(Q(f"{g}sides/{name}", r"\delta", "s", f"largest defect of {side}"))
    return tuple(Q(q.name, q.symbol, q.unit, q.description, q.dims, q.kind, optional=True)
                 for q in out)


_CONTOURS = _contours()


def _band_run(run: str) -> tuple[Q, ...]:
    """``/analysis/band/runs/<run>``: one band run in a few numbers."""
    g = f"band/runs/{run}/"
    return (
        Q(g + "case", "", "", f"case of the {run} run (loops, waves, cusps)", kind="str",
          optional=True),
        Q(g + "theta1", r"\theta_1", "rad", "upper turning circle arccos u2", optional=True),
        Q(g + "theta2", r"\theta_2", "rad", "lower turning circle arccos u1", optional=True),
        Q(g + "theta_min_measured", r"\theta_\mathrm{min}", "rad",
          "smallest theta of the integrated run", optional=True),
        Q(g + "theta_max_measured", r"\theta_\mathrm{max}", "rad",
          "largest theta of the integrated run", optional=True),
        Q(g + "omega3", r"\omega_3", "rad/s", "spin of the run", optional=True),
        Q(g + "phi_dot0", r"\mathrm{d}\varphi/\mathrm{d}t\,(0)", "rad/s",
          "precession rate at the release", optional=True),
        Q(g + "b_over_a", "b/a", "1", "ratio b/a, where phi_dot = 0", optional=True),
        Q(g + "u1", "u_1", "1", "smallest root of f(u)", optional=True),
        Q(g + "u2", "u_2", "1", "middle root of f(u)", optional=True),
        Q(g + "u3", "u_3", "1", "largest root of f(u)", optional=True),
        Q(g + "nutation_period", "T", "s", "nutation period", optional=True),
        Q(g + "precession_per_period", r"\Delta\varphi", "rad",
          "precession per nutation period", optional=True),
        Q(g + "u_max_error", r"\max|\Delta u|", "1",
          "largest difference of cos theta from the closed form", optional=True),
        Q(g + "weierstrass_max_difference", r"\max|u_\wp - u_{sn^2}|", "1",
          "largest difference of the wp form from the sn^2 form", optional=True),
        Q(g + "period_loop", r"\oint \mathrm{d}u/\sqrt{f}", "s",
          "nutation period as the loop integral round the cut [u1, u2] (textbook ex. 4.10)",
          optional=True),
        Q(g + "energy_drift", r"\Delta E/E", "1", "relative energy drift of the run",
          optional=True),
        Q(g + "phi_dot_upper", r"\mathrm{d}\varphi/\mathrm{d}t\,(\theta_1)", "rad/s",
          "precession rate on the upper circle", optional=True),
        Q(g + "phi_dot_lower", r"\mathrm{d}\varphi/\mathrm{d}t\,(\theta_2)", "rad/s",
          "precession rate on the lower circle", optional=True),
        Q(g + "locus_stop", "", "1", "samples of the locus textbook Fig. 4.3 draws", kind="int",
          optional=True),
        Q(g + "locus_periods", "", "1", "nutation periods of the locus textbook Fig. 4.3 draws",
          kind="int", optional=True),
        Q(g + "view_azimuth", "", "rad", "azimuth the locus is seen from", optional=True),
        Q(g + "locus_full_turn", "", "", "whether the locus drawn goes once round the band "
          "(locus_periods times the precession per period at least 2 pi)", kind="bool",
          optional=True),
    )


SCHEMA = ResultsSchema(
    columns=(
        Q("theta", r"\theta", "rad", "tilt of the symmetry axis from the upward vertical",
          ("t",)),
        Q("phi", r"\varphi", "rad", "precession angle", ("t",)),
        Q("psi", r"\psi", "rad", "spin angle", ("t",)),
        Q("axis_x", r"\hat{e}_{3,x}", "1", "symmetry axis, space x component", ("t",)),
        Q("axis_y", r"\hat{e}_{3,y}", "1", "symmetry axis, space y component", ("t",)),
        Q("axis_z", r"\hat{e}_{3,z}", "1", "symmetry axis, space z component", ("t",)),
        Q("theta_dot", r"\mathrm{d}\theta/\mathrm{d}t", "rad/s", "nutation rate", ("t",)),
        Q("phi_dot", r"\mathrm{d}\varphi/\mathrm{d}t", "rad/s", "precession rate", ("t",)),
        Q("q_w", "q_w", "1", "body attitude quaternion, scalar part", ("t",)),
        Q("q_x", "q_x", "1", "body attitude quaternion, x part", ("t",)),
        Q("q_y", "q_y", "1", "body attitude quaternion, y part", ("t",)),
        Q("q_z", "q_z", "1", "body attitude quaternion, z part", ("t",)),
        Q("omega_1", r"\omega_1", "rad/s", "body angular velocity, component 1", ("t",)),
        Q("omega_2", r"\omega_2", "rad/s", "body angular velocity, component 2", ("t",)),
        Q("omega_3", r"\omega_3", "rad/s", "body angular velocity, component 3 (the spin)",
          ("t",)),
        Q("cos_theta_weierstrass", r"u_\wp", "1",
          "cos theta through Weierstrass's wp (textbook ex. 4.10)", ("t",)),
    ),
    invariants=(
        Q("energy", "E", "J", "energy", ("t",)),
        Q("p_phi", r"p_\varphi", "kg m^2/s", "vertical angular momentum L.z", ("t",)),
        Q("p_psi", r"p_\psi", "kg m^2/s", "angular momentum about the symmetry axis I3 omega3",
          ("t",)),
    ),
    analysis=(
        Q("a", "a", "1/s", "a = I3 omega3/I1, notes (10.25)"),
        Q("b", "b", "1/s", "b = p_phi/I1, notes (10.25)"),
        Q("alpha", r"\alpha", "1/s^2", "alpha = 2E'/I1, notes (10.30)"),
        Q("beta", r"\beta", "1/s^2", "beta = 2Mgl/I1, notes (10.30)"),
        Q("b_over_a", "b/a", "1", "ratio b/a, where phi_dot = 0"),
        Q("u1", "u_1", "1", "smallest root of f(u): cos theta on the lower circle"),
        Q("u2", "u_2", "1", "middle root of f(u): cos theta on the upper circle"),
        Q("u3", "u_3", "1", "largest root of f(u) (unphysical, > 1)"),
        Q("one_minus_u1", "1 - u_1", "1", "1 - u1, accurate near the vertical"),
        Q("one_minus_u2", "1 - u_2", "1", "1 - u2, accurate near the vertical"),
        Q("theta1", r"\theta_1", "rad", "upper turning circle arccos u2"),
        Q("theta2", r"\theta_2", "rad", "lower turning circle arccos u1"),
        Q("theta_min_measured", r"\theta_\mathrm{min}", "rad",
          "smallest theta of the integrated run"),
        Q("theta_max_measured", r"\theta_\mathrm{max}", "rad",
          "largest theta of the integrated run"),
        Q("k2", "k^2", "1", "elliptic parameter (u2 - u1)/(u3 - u1)"),
        Q("case", "", "", "case of textbook Fig. 4.3: loops, waves, cusps, steady or sleeping",
          kind="str"),
        Q("phi_dot_upper", r"\mathrm{d}\varphi/\mathrm{d}t\,(\theta_1)", "rad/s",
          "precession rate on the upper circle (b - a u2)/(1 - u2^2), notes (10.26)"),
        Q("phi_dot_lower", r"\mathrm{d}\varphi/\mathrm{d}t\,(\theta_2)", "rad/s",
          "precession rate on the lower circle (b - a u1)/(1 - u1^2), notes (10.26)"),
        Q("case_cusp_tolerance", "", "1", "cusps when |phi_dot| on the upper circle is below "
          "this times |phi_dot| on the lower one"),
        Q("case_steady_tolerance", "", "1", "steady when u2 - u1 is below this times 1 - u1"),
        Q("released_at_rest", "", "", "whether the top starts with theta_dot = phi_dot = 0",
          kind="bool"),
        Q("periods_in_run", "", "1", "whole nutation periods the run spans", kind="int"),
        Q("steady_root", "", "", "for steady precession, the root of notes (10.45) nearer "
          "the start's phi_dot: slow or fast (else empty)", kind="str"),
        Q("sleeping_top", "", "", "whether the start is within sleeping_tilt_below of the "
          "vertical", kind="bool", optional=True),
        Q("sleeping_tilt_below", "", "rad", "a start tilted less than this is a sleeping top",
          optional=True),
        Q("tilt_growth", r"\theta_2/\theta_1", "1", "lower over upper turning angle of a "
          "sleeping top", optional=True),
        Q("tilt_of_the_order_below", "", "1", "tilt_growth below this: the tilt stays of the "
          "order of the initial one", optional=True),
        Q("tilt_of_the_order", "", "", "stable, tilted, and tilt_growth below "
          "tilt_of_the_order_below", kind="bool", optional=True),
        Q("stays_upright", "", "", "stable and theta2 below stays_upright_below", kind="bool",
          optional=True),
        Q("stays_upright_below", "", "rad", "theta2 below this: the sleeping top stays "
          "upright", optional=True),
        Q("tilt_reached", r"\theta_\mathrm{max}", "rad", "largest tilt of the run's samples",
          optional=True),
        Q("tilts_away_factor", "", "1", "largest tilt at least this many initial ones: the "
          "run shows the top tilting away", optional=True),
        Q("tilted_away", "", "", "whether the run's largest tilt is at least tilts_away_factor "
          "initial ones", kind="bool", optional=True),
        Q("nutation_period", "T", "s", "nutation period in closed form"),
        Q("nutation_period_quadrature", r"T_\mathrm{quad}", "s",
          "nutation period by quadrature of du/sqrt(f)"),
        Q("nutation_period_measured", r"T_\mathrm{meas}", "s",
          "nutation period measured from theta(t)"),
        Q("precession_per_period", r"\Delta\varphi", "rad",
          "precession per nutation period in closed form"),
        Q("precession_quadrature", r"\Delta\varphi_\mathrm{quad}", "rad",
          "precession per nutation period by quadrature"),
        Q("precession_measured", r"\Delta\varphi_\mathrm{meas}", "rad",
          "precession per nutation period measured from phi(t)"),
        Q("reduced_energy", "E'", "J", "E' = E - I3 omega3^2/2"),
        Q("steady_rate_slow", r"(\mathrm{d}\varphi/\mathrm{d}t)_\mathrm{slow}", "rad/s",
          "slow steady precession rate at theta0, notes (10.45)"),
        Q("steady_rate_fast", r"(\mathrm{d}\varphi/\mathrm{d}t)_\mathrm{fast}", "rad/s",
          "fast steady precession rate at theta0, notes (10.45)"),
        Q("steady_exists", "", "", "whether steady precession exists at theta0, notes (10.46)",
          kind="bool"),
        Q("theta0", r"\theta_0", "rad", "initial tilt"),
        Q("theta_dot0", r"\mathrm{d}\theta/\mathrm{d}t\,(0)", "rad/s",
          "initial nutation rate"),
        Q("phi_dot0", r"\mathrm{d}\varphi/\mathrm{d}t\,(0)", "rad/s",
          "initial precession rate"),
        Q("omega3", r"\omega_3", "rad/s", "spin omega3 = psi_dot + phi_dot cos theta"),
        Q("sleeping_threshold_omega3", r"\omega_{3,c}", "rad/s",
          "sleeping-top threshold 2 sqrt(I1 Mgl)/I3, notes (10.50)"),
        Q("sleeping_stable", "", "", "whether the spin is above the sleeping threshold",
          kind="bool"),
        Q("sleeping_growth_rate", r"\gamma", "1/s",
          "linear growth rate of a tilt of the sleeping top"),
        Q("behaviour", "", "", "physical behaviour of a sleeping top: stable or unstable "
          "(not the run's numerical status)", kind="str", optional=True),
        Q("u_max_error", r"\max|\Delta u|", "1",
          "largest difference of cos theta from the closed form"),
        Q("mean_phi_dot", r"\langle\mathrm{d}\varphi/\mathrm{d}t\rangle", "rad/s",
          "mean precession rate"),
        Q("period_sensitivity", r"|\Delta T/T|", "1",
          "change of the period by an energy error of the run's drift"),
        Q("cos_theta_error/difference", r"\Delta\cos\theta", "1",
          "cos theta minus the closed form (over u2 - u1 when relative)", ("t",)),
        Q("cos_theta_error/relative_to_width", "", "",
          "whether the difference is relative to u2 - u1", kind="bool"),
        Q("cubic_curve/variable", "", "", "variable of the curve: u, or w = 1 - u",
          kind="str"),
        Q("cubic_curve/x", "u", "1", "u (or w = 1 - u) where f is drawn", ("cubic",)),
        Q("cubic_curve/f", "f(u)", "1/s^2", "f(u), notes (10.31), or g(w)", ("cubic",)),
        Q("cubic_curve/root1", "u_1", "1", "first root on the curve's axis"),
        Q("cubic_curve/root2", "u_2", "1", "second root on the curve's axis"),
        Q("cubic_curve/root3", "u_3", "1", "third root on the curve's axis"),
        Q("cubic_curve/ratio", "b/a", "1", "b/a on the curve's axis"),
        Q("cubic_curve/start", "u_0", "1", "initial value on the curve's axis"),
        Q("effective_potential/theta", r"\theta", "rad", "tilt where V' is drawn",
          ("potential",), optional=True),
        Q("effective_potential/V", "V'", "J", "effective potential V'(theta), notes (10.28)",
          ("potential",), optional=True),
        Q("effective_potential/energy", "E'", "J", "energy E' drawn against V'",
          optional=True),
        Q("effective_potential/minus_Mgl", "", "", "whether V' and E' are shifted by -Mgl",
          kind="bool", optional=True),
        Q("steady_rates/omega3", r"\omega_3", "rad/s", "spins of the steady-rate curves",
          ("spin",)),
        Q("steady_rates/slow", r"(\mathrm{d}\varphi/\mathrm{d}t)_\mathrm{slow}", "rad/s",
          "slow steady precession rate against the spin", ("spin",)),
        Q("steady_rates/fast", r"(\mathrm{d}\varphi/\mathrm{d}t)_\mathrm{fast}", "rad/s",
          "fast steady precession rate against the spin", ("spin",)),
        Q("steady_rates/omega3_min", r"\omega_{3,\mathrm{min}}", "rad/s",
          "least spin with steady precession at theta0, notes (10.46)"),
        Q("weierstrass_max_difference", r"\max|u_\wp - u_{sn^2}|", "1",
          "largest difference of the wp form from the sn^2 form", optional=True),
        Q("weierstrass/g2", "g_2", "1/s^4", "invariant g2 of wp", optional=True),
        Q("weierstrass/g3", "g_3", "1/s^6", "invariant g3 of wp", optional=True),
        Q("weierstrass/e1", "e_1", "1/s^2", "root e1 = wp(omega)", optional=True),
        Q("weierstrass/e2", "e_2", "1/s^2", "root e2 = wp(omega + omega')", optional=True),
        Q("weierstrass/e3", "e_3", "1/s^2", "root e3 = wp(omega')", optional=True),
        Q("weierstrass/omega", r"\omega", "s", "real half-period", optional=True),
        Q("weierstrass/omega_prime", r"\omega'/i", "s", "imaginary half-period",
          optional=True),
        Q("weierstrass/x0", "x_0", "s", "offset of the motion's line z(0) = x0 + omega'",
          optional=True),
        Q("weierstrass/scale", r"\lambda", "s^2", "u = lambda wp + mu: lambda = 4/beta",
          optional=True),
        Q("weierstrass/shift", r"\mu", "1", "u = lambda wp + mu: mu = (u1 + u2 + u3)/3",
          optional=True),
        Q("weierstrass/t_end", r"t_\mathrm{end}", "s", "end of the run", optional=True),
        Q("weierstrass/period", r"2\omega", "s", "nutation period 2 omega of the lattice",
          optional=True),
        Q("weierstrass/series_terms", "", "1", "terms of the theta series", kind="int",
          optional=True),
        Q("weierstrass/nome", "q", "1", "nome exp(i pi omega'/omega)", optional=True),
        Q("weierstrass/max_difference", r"\max|u_\wp - u_{sn^2}|", "1",
          "largest difference of the wp form from the sn^2 form", optional=True),
        Q("weierstrass/textbook_scale_agrees", "", "", "whether beta^2 = 4 (to 1e-6): the "
          "textbook's u = beta wp + c gives the same numbers as u = (4/beta) wp + mu",
          kind="bool", optional=True),
        Q("weierstrass/ode_residual", r"\max|\lambda^2\wp'^2 - f(u)|/\max f", "1",
          "(du/dt)^2 = f(u) for u = lambda wp + mu, lambda = 4/beta, on the output grid",
          optional=True),
        # the period round the cut (textbook ex. 4.10)
        Q("weierstrass/period_loop", r"\oint \mathrm{d}u/\sqrt{f}", "s",
          "nutation period: the loop integral of du/sqrt(f(u)) round the cut [u1, u2] by "
          "the trapezoidal rule on an ellipse (NaN when u3 is too close to the cut for the "
          "node budget)", optional=True),
        Q("weierstrass/period_loop_imag", r"\mathrm{Im}\oint \mathrm{d}u/\sqrt{f}", "s",
          "imaginary part the loop sum leaves (zero in exact arithmetic)", optional=True),
        Q("weierstrass/period_loop_nodes", "N", "1", "nodes of the converged loop rule (the "
          "nodes it would need when the period is NaN)", kind="int", optional=True),
        Q("weierstrass/period_loop_rho", r"\rho", "1",
          "the ellipse u - (u1 + u2)/2 = (u2 - u1)/2 cos(phi - i rho) round the cut",
          optional=True),
        Q("weierstrass/period_loop_strip", "a", "1",
          "arccosh of (u3 - m)/r: the rule's error falls as exp(-N (a - rho))", optional=True),
        Q("weierstrass/period_sine_squared", r"2\int_{u_1}^{u_2} \mathrm{d}u/\sqrt{f}", "s",
          "nutation period on the real axis, u = u1 + (u2 - u1) sin^2 s, trapezoidal rule",
          optional=True),
        Q("weierstrass/period_sine_squared_nodes", "N", "1",
          "nodes of the converged sin^2 rule (or needed)", kind="int", optional=True),
        Q("weierstrass/omega_loop", r"\omega", "s",
          "real half-period: half the loop integral of d wp/sqrt(4 wp^3 - g2 wp - g3) "
          "round [e3, e2]", optional=True),
        Q("weierstrass/omega_loop_nodes", "N", "1", "nodes of the converged loop rule in "
          "the wp plane (or needed)", kind="int", optional=True),
        *_CONTOURS,
        Q("band/theta_min", r"\theta_\mathrm{min}", "rad", "upper circle of the band asked for",
          optional=True),
        Q("band/theta_max", r"\theta_\mathrm{max}", "rad", "lower circle of the band asked for",
          optional=True),
        Q("band/case", "", "", "case asked for: loops, waves, cusps or all", kind="str",
          optional=True),
        Q("band/omega3_cusps", r"\omega_{3,\mathrm{cusps}}", "rad/s",
          "the spin of cusps on the band", optional=True),
        Q("band/omega3_waves_min", r"\omega_{3,\mathrm{waves}}", "rad/s",
          "least spin of waves on the band", optional=True),
        Q("band/sigma", r"\sigma", "1", "u1 + u2 = cos theta_min + cos theta_max",
          optional=True),
        Q("band/possible_spins", "", "", "which spins give which case on the band",
          kind="str", optional=True),
        *(q for run in BAND_RUNS for q in _band_run(run)),
        Q("sleeping_sweep/t", "t", "s", "time of the sleeping-top sweep's runs",
          ("sleeping_t",), optional=True),
        Q("sleeping_sweep/omega3_over_threshold", r"\omega_3/\omega_{3,c}", "1",
          "spin of each sweep run over the threshold", ("sleeping_run",), optional=True),
        Q("sleeping_sweep/omega3", r"\omega_3", "rad/s", "spin of each sweep run",
          ("sleeping_run",), optional=True),
        Q("sleeping_sweep/theta", r"\theta", "rad", "tilt of each sweep run against time",
          ("sleeping_run", "sleeping_t"), optional=True),
        Q("sleeping_sweep/theta_max", r"\theta_\mathrm{max}", "rad",
          "largest tilt of each sweep run", ("sleeping_run",), optional=True),
        Q("sleeping_sweep/tilt", r"\theta_0", "rad", "initial tilt of every sweep run",
          optional=True),
        Q("sleeping_sweep/growth_rate", r"\gamma", "1/s",
          "linear growth rate of each sweep run's tilt", ("sleeping_run",), optional=True),
        Q("sleeping_sweep/status", "", "", "integrator status of each sweep run",
          ("sleeping_run",), kind="str", optional=True),
    ),
)
