"""What an ``oscillator`` run stores: every result once, with its symbol and unit."""

from __future__ import annotations

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

SCHEMA = ResultsSchema(
    columns=(
        Q("q", "q", "m", "coordinate", ("t",)),
        Q("p", "p", "kg m/s", "momentum", ("t",)),
        # the swapped run integrates K(Q, P) = H(-P, Q): Q = p, P = -q (6.7)
        Q("Q", "Q", "kg m/s", "new coordinate of the swap F1 = q Q (Q = p)", ("t",)),
        Q("P", "P", "m", "new momentum of the swap F1 = q Q (P = -q)", ("t",)),
    ),
    invariants=(
        Q("energy", "E", "J", "energy", ("t",)),
    ),
    analysis=(
        Q("omega", r"\omega", "rad/s", "angular frequency"),
        Q("period", "T", "s", "period 2 pi/omega"),
        Q("energy", "E", "J", "energy of the initial state"),
        Q("q_max_error", r"\max|q - q_\mathrm{exact}|", "m",
          "largest coordinate error over the run"),
        Q("p_max_error", r"\max|p - p_\mathrm{exact}|", "kg m/s",
          "largest momentum error over the run"),
        # mixes a momentum and a coordinate difference: the larger of the two SI numbers
        Q("swap_max_difference", r"\max|(Q, P) - (p, -q)|", "1",
          "larger of max|Q - p| (kg m/s) and max|P + q| (m): the integrated K orbit "
          "against the image of the H orbit"),
        Q("hj_energy", "E", "J", "Hamilton-Jacobi constant E at t = 0"),
        Q("hj_beta", r"\beta", "s", "Hamilton-Jacobi constant beta = dS/dE at t = 0"),
        Q("hj_beta_drift", r"\max|\beta(t) - \beta(0)|", "s",
          "largest drift of beta along the integrated trajectory"),
        Q("hj_q_max_difference", r"\max|q_\mathrm{HJ} - q|", "m",
          "largest difference between the Hamilton-Jacobi solution and the integration"),
        Q("poisson_bracket_QP", r"\{Q, P\}", "1",
          "Poisson bracket of the new pair, by SymPy from F1 = q Q (notes (6.6-6.11))"),
        Q("poisson_bracket_QP_defect", r"\max|\{Q, P\} - 1|", "1",
          "largest |{Q, P} - 1| along the run, the map's partial derivatives by central "
          "differences"),
        Q("canonical_threshold", "", "1", "|{Q, P} - 1| below which the map is canonical"),
        Q("swap_canonical", "", "", "whether the swap is canonical (yes or no): {Q, P} by "
          "SymPy and along the run within the threshold of 1", kind="str"),
        Q("hj_energy_drift", r"\max|E(t) - E(0)|/E", "1",
          "largest drift of E along the integrated trajectory, relative to E"),
        Q("hj_constant_threshold", "", "1", "drift of E (relative to E) and of beta "
          "(relative to the period) below which the pair stays constant"),
        Q("hj_pair_constant", "", "", "whether (E, beta) stay constant along the "
          "integrated trajectory (yes or no), within the threshold", kind="str"),
        # the Hamilton-Jacobi equations along the run, relative to E (notes (7.16), (7.32)–(7.33))
        Q("hj_residual", r"\max|\partial_t S + H(q, \partial_q S)|/E", "1",
          "largest residual of the Hamilton-Jacobi equation along the run, dW/dq from the "
          "integrand (dS/dt = -E: also that of H(q, dW/dq) = E)"),
        Q("hj_residual_quadrature", r"\max|\partial_t S + H(q, \partial_q S)|/E", "1",
          "the same, S = W - E t with W by quadrature and both derivatives by central "
          "differences"),
        Q("hj_characteristic_residual_quadrature", r"\max|H(q, \partial_q W) - E|/E", "1",
          "largest residual of H(q, dW/dq) = E along the run, W by quadrature and dW/dq by "
          "central differences"),
        Q("hj_characteristic_quadrature_error", r"\max|W - W_\mathrm{exact}|/(\pi E/\omega)",
          "1", "largest difference of W by quadrature from its closed form along the run, "
          "relative to the half action pi E/omega"),
        Q("hj_half_action", r"\int p\,dq", "J s",
          "integral of p dq from turning point to turning point by quadrature (pi E/omega)"),
        Q("hj_momentum_difference", r"\max|p - \partial_q W|/\sqrt{2mE}", "1",
          "largest difference of the integrated p from dW/dq on its branch, relative to the "
          "momentum amplitude"),
        Q("hamilton_jacobi/energy", "E", "J",
          "E evaluated along the integrated trajectory", ("t",)),
        Q("hamilton_jacobi/beta", r"\beta", "s",
          "beta evaluated along the integrated trajectory", ("t",)),
        Q("hamilton_jacobi/q", r"q_\mathrm{HJ}", "m",
          "Hamilton-Jacobi solution q(t), notes (7.38)", ("t",)),
    ),
)
