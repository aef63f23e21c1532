"""What a ``pendulum`` run stores: every result once, with its symbol and unit."""

from __future__ import annotations

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

SCHEMA = ResultsSchema(
    columns=(
        Q("theta", r"\theta", "rad", "angle from the downward vertical", ("t",)),
        Q("theta_dot", r"\dot{\theta}", "rad/s", "angular velocity", ("t",)),
    ),
    invariants=(
        Q("energy", "E", "J", "energy", ("t",)),
    ),
    analysis=(
        Q("period", "T", "s", "exact period 4K(k) sqrt(l/g)"),
        Q("period_measured", r"T_\mathrm{meas}", "s",
          "period measured from the integrated theta(t)"),
        Q("period_small_angle", "T_0", "s", "small-angle period 2 pi sqrt(l/g)"),
        Q("period_relative_error", r"|T_\mathrm{meas}/T - 1|", "1",
          "relative error of the measured period", optional=True),
        Q("omega0", r"\omega_0", "rad/s", "small-angle angular frequency sqrt(g/l)"),
        Q("k", "k", "1", "elliptic modulus"),
        Q("motion", "", "", "libration or rotation", kind="str"),
        Q("behaviour", "", "", "physical behaviour: libration, rotation or separatrix",
          kind="str", optional=True),
        Q("complementary_parameter", "1 - k^2", "1", "complementary elliptic parameter"),
        Q("reference", "", "", "what the reference solution is", kind="str"),
        Q("theta_max_error", r"\max|\theta - \theta_\mathrm{exact}|", "rad",
          "largest angle error over the run"),
        Q("theta_dot_max_error", r"\max|\dot{\theta} - \dot{\theta}_\mathrm{exact}|", "rad/s",
          "largest angular-velocity error over the run"),
        Q("amplitude", r"\theta_\mathrm{max}", "rad", "libration amplitude", optional=True),
        Q("small_angle_solution/theta", r"\theta_\mathrm{lin}", "rad",
          "small-angle solution (1.19)", ("t",), optional=True),
        Q("small_angle_solution/theta_dot", r"\dot{\theta}_\mathrm{lin}", "rad/s",
          "angular velocity of the small-angle solution", ("t",), optional=True),
        Q("phase_portrait/theta", r"\theta", "rad", "phase-portrait grid: angle",
          ("grid_theta",)),
        Q("phase_portrait/theta_dot", r"\dot{\theta}", "rad/s",
          "phase-portrait grid: angular velocity", ("grid_theta_dot",)),
        Q("phase_portrait/energy", r"E/(m l^2)", "1/s^2",
          "energy per m l^2 over the phase-portrait grid", ("grid_theta_dot", "grid_theta")),
        Q("phase_portrait/levels", r"E/(m l^2)", "1/s^2", "energy levels drawn",
          ("level",)),
        Q("phase_portrait/separatrix", r"E_s/(m l^2)", "1/s^2",
          "energy of the separatrix per m l^2"),
        Q("period_curve/amplitude", r"\theta_0", "rad", "amplitude of the period curve",
          ("curve",)),
        Q("period_curve/period", "T", "s", "exact period against amplitude", ("curve",)),
        Q("boundary_value/t", "t", "s", "time of the boundary-value solution", ("bvp_t",),
          optional=True),
        Q("boundary_value/theta_exact", r"\theta", "rad",
          "linearised boundary-value solution (1.21), closed form", ("bvp_t",), optional=True),
        Q("boundary_value/theta_numeric", r"\theta", "rad",
          "linearised boundary-value solution by solve_bvp", ("bvp_t",), optional=True),
        Q("boundary_value/theta_nonlinear", r"\theta", "rad",
          "nonlinear pendulum's boundary-value solution", ("bvp_t",), optional=True),
        Q("boundary_value/action_exact", "S", "J s", "action (2.4) in closed form",
          optional=True),
        Q("boundary_value/action_numeric", "S", "J s",
          "action by quadrature of the numerical solution", optional=True),
        Q("boundary_value/action_nonlinear", "S", "J s",
          "action of the nonlinear boundary-value solution", optional=True),
        Q("boundary_value/nonlinear_converged", "", "", "whether the nonlinear solve "
          "converged", kind="bool", optional=True),
    ),
)
