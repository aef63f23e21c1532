"""What a ``rotation`` scene stores: every result once, with its symbol and unit.

Each exercise is a group of ``/analysis`` (``axis_angle``, ``euler``, ``stereographic``),
stored when its table is configured and its section shown; its ``errors`` are the
distances between independent constructions (dimensionless: matrix entries, unit
vectors, ω relative to its largest size).
"""

from __future__ import annotations

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema

#: every check of this kind must agree to this (matrix entries, unit vectors, relative ω)
TOLERANCE = 1e-12
#: archived distances that are contrasts, not checks (R(U)ᵀ is not the Möbius map)
NOT_CHECKS = ("transpose_mismatch", "transpose_mismatch_standard_orientation")
#: a contrast (R(U)ᵀ against the Möbius map, the reversed product) farther than this
#: shows another map; nearer, the two are one (a half turn, commuting turns)
CONTRAST = 1e-9
#: the order a central difference of the stored Euler path must show, 2, within this
ORDER_SLACK = 0.1
#: ... when the path's step h turns it by at most this much, h max|ω| (the order is 1.99
#: at 0.2, 1.95 at 0.45, 1.90 at 0.67): past it the check is not made
ORDER_RANGE = 0.5
#: the /analysis group each section reads
SECTION_DATA = {"axis_angle": "axis_angle", "euler_angles": "euler",
                "angular_velocity": "euler", "matrix_identities": "identities",
                "su2_euler": "su2_form", "stereographic": "stereographic",
                "matrix_proofs": "proofs"}
#: the matrices A the similarity S A S⁻¹ turns (textbook ex. 4.1–4.4), in the order of
#: the /analysis/identities arrays: R(n, Φ) of ex. 4.5, its generator Φ[n]×, ½(R + Rᵀ)
IDENTITY_MATRICES = ("rotation", "generator", "symmetric")


def _group(prefix: str, *quantities: Q) -> tuple[Q, ...]:
    """The quantities of one exercise's group, named ``prefix/...``, all optional."""
    return tuple(Q(f"{prefix}/{q.name}", q.symbol, q.unit, q.description, q.dims, q.kind,
                   optional=True) for q in quantities)


def _errors(prefix: str, **described: str) -> tuple[Q, ...]:
    return _group(f"{prefix}/errors", *(Q(name, "", "1", f"max error: {text}")
                                        for name, text in described.items()))


AXIS_ANGLE = _group(
    "axis_angle",
    Q("axis_given", "n", "1", "rotation axis as given", ("xyz",)),
    Q("axis", r"\hat{n}", "1", "rotation axis, normalized", ("xyz",)),
    Q("angle", r"\Phi", "rad", "rotation angle"),
    Q("vector", "r", "1", "the vector the rotation turns", ("xyz",)),
    Q("turned_vector", "R r", "1", "r turned by Phi about n: R r (textbook ex. 4.5)",
      ("xyz",)),
    Q("rotated_vector", "r'", "1", "Goldstein's r' = A r by Goldstein (4.62): r in the "
      "turned axes", ("xyz",)),
    Q("matrix_textbook", "R", "1", "the textbook's R(n, Phi) = cos Phi 1 + (1 - cos Phi) "
      "n n^T + sin Phi [n]x (textbook ex. 4.5), active", ("xyz", "xyz")),
    Q("matrix_formula", "A", "1", "Goldstein's passive A(n, Phi) from Goldstein (4.62); "
      "A = R^T", ("xyz", "xyz")),
    Q("matrix_expm", "R", "1", "exp(Phi [n]x) by diagonalization", ("xyz", "xyz")),
    Q("matrix_quaternion", "R", "1", "R(q) from the quaternion (cos Phi/2, n sin Phi/2)",
      ("xyz", "xyz")),
    Q("recovered_axis", r"\hat{n}", "1", "axis recovered from R", ("xyz",)),
    Q("recovered_angle", r"\Phi", "rad", "angle recovered from R"),
    Q("determinant", r"\det R", "1", "determinant of R"),
    Q("arc_turned", "R r", "1", "r turned by R(n, Phi s) for s = 0 ... 1", ("arc", "xyz")),
    Q("arc", "r'", "1", "Goldstein's r' (Goldstein (4.62)) for angles 0 ... Phi",
      ("arc", "xyz")),
    Q("circle", "r'", "1", "r turned by a full turn about n", ("arc_circle", "xyz")),
    Q("centre", "", "1", "centre of that circle, (n.r) n", ("xyz",)),
    Q("turned_axes", "", "1", "the turned axes R e_i (rows) in the old axes: A",
      ("xyz", "xyz")),
)

AXIS_ANGLE_ERRORS = _errors(
    "axis_angle",
    textbook_vs_goldstein="R (textbook ex. 4.5) against the transpose of Goldstein's A "
                          "(Goldstein (4.62)): R = A^T",
    formula_vs_expm="R (textbook ex. 4.5) against exp(Phi [n]x)",
    formula_vs_quaternion="R (textbook ex. 4.5) against R(q)",
    turned_vector_vs_matrix="r cos Phi + n (n.r)(1 - cos Phi) + (n x r) sin Phi against "
                            "R r, over |r|",
    vector_formula_vs_matrix="r' by Goldstein (4.62) against A r, over |r|",
    orthogonality="R R^T - 1",
    recovered_angle="angle recovered from R",
    recovered_axis="axis recovered from R, times min(1, Phi)",
)


def _construction(convention: str) -> tuple[Q, ...]:
    return _group(
        f"euler/construction/{convention}",
        Q("space_axes", "", "1", f"space axes ({convention} construction, columns)",
          ("xyz", "xyz")),
        Q("body_axes", "", "1", f"body axes ({convention} construction, columns)",
          ("xyz", "xyz")),
        Q("node", "", "1", f"line of nodes ({convention})", ("xyz",)),
        Q("arc_phi", r"\phi", "1", f"arc of phi ({convention})", ("angle_arc", "xyz")),
        Q("arc_theta", r"\theta", "1", f"arc of theta ({convention})", ("angle_arc", "xyz")),
        Q("arc_psi", r"\psi", "1", f"arc of psi ({convention})", ("angle_arc", "xyz")),
    )


EULER = _group(
    "euler",
    Q("time_ordered/orders", "K", "1", "orders of the partial sums of notes (8.37)",
      ("series_order",), "int"),
    Q("time_ordered/series_error", r"\max|S_K R(0) - R(t)|", "1", "largest entry of the "
      "partial sum's difference from the Euler matrix at the end of the path",
      ("series_order",)),
    Q("time_ordered/series_term", r"\max|I_K|", "1", "largest entry of the K-th term on the "
      "path", ("series_order",)),
    Q("time_ordered/series_bound", r"(|\omega|t)^{K+1}/(K+1)!", "1", "the bound of the "
      "terms left out", ("series_order",)),
    Q("time_ordered/omega_t", r"|\omega| t", "1", "largest |omega| on the path times its "
      "length"),
    Q("time_ordered/series_best", "", "1", "the smallest error of the partial sums"),
    Q("time_ordered/series_largest_term", "", "1", "the largest entry of any term"),
    Q("time_ordered/magnus_steps", "n", "1", "steps of Magnus's method", ("magnus_run",), "int"),
    Q("time_ordered/magnus_error", r"\max|R - R(t)|", "1", "error of Magnus's method at the "
      "end of the path", ("magnus_run",)),
    Q("time_ordered/magnus_order", "p", "1", "convergence order of Magnus's method "
      "(median of log2 of successive error ratios)"),
    Q("convention", "", "", "convention the angles are given in", kind="str"),
    Q("other_convention", "", "", "the other convention", kind="str"),
    Q("t", "t", "s", "time along the sample path", ("path",)),
    Q("rates", r"(\dot\phi, \dot\theta, \dot\psi)", "rad/s", "Euler-angle rates",
      ("angle",)),
    Q("path", r"(\phi, \theta, \psi)", "rad", "Euler angles along the path",
      ("path", "angle")),
    Q("path_other", r"(\phi, \theta, \psi)", "rad",
      "the same rotations' angles in the other convention", ("path", "angle")),
    Q("matrix", "R", "1", "R at t = 0, product of elementary rotations", ("xyz", "xyz")),
    Q("matrix_other", "R", "1", "R at t = 0 in the other convention", ("xyz", "xyz")),
    Q("elements", "A", "1", "Goldstein's A, Goldstein (4.46), by its elements", ("xyz", "xyz")),
    Q("elements_other", "A", "1", "A by its elements, the other convention",
      ("xyz", "xyz")),
    Q("omega_space", r"\omega", "rad/s", "omega in space axes from the rates",
      ("path", "xyz")),
    Q("omega_body", r"\omega'", "rad/s", "omega in body axes from the rates",
      ("path", "xyz")),
    Q("omega_space_other", r"\omega", "rad/s",
      "omega in space axes, the other convention's formula", ("path", "xyz")),
    Q("omega_body_other", r"\omega'", "rad/s",
      "omega in body axes, the other convention's formula", ("path", "xyz")),
    Q("omega_space_derivative", r"\omega", "rad/s",
      "omega in space axes from dR/dt by the complex step", ("path", "xyz")),
    Q("omega_body_derivative", r"\omega'", "rad/s",
      "omega in body axes from dR/dt by the complex step", ("path", "xyz")),
    Q("omega_scale", r"\max|\omega|", "rad/s", "largest |omega| over the path"),
    # the notes' Figure 2 (kinds/rotation/euler_sketch.py): drawn with construction/<convention>
    Q("sketch/convention", "", "", "convention of the sketch of the notes' Figure 2: that of "
      "notes (9.17), z-x-z", kind="str"),
    Q("sketch/angles", r"(\phi, \theta, \psi)", "rad", "the sketch's Euler angles: the "
      "rotation at t = 0 in that convention", ("angle",)),
    Q("sketch/plane", "", "1", "unit circle in the fixed xy plane", ("sketch_circle", "xyz")),
    Q("sketch/body_plane", "", "1", "unit circle in the body x'y' plane, which meets the xy "
      "plane in the line of nodes", ("sketch_circle", "xyz")),
) + _construction("zxz") + _construction("zyz")

EULER_ERRORS = _errors(
    "euler",
    matrix_product_vs_elements="R by elementary rotations against Goldstein (4.46) elements",
    matrix_conventions="R in one convention against the other, whole path",
    omega_space_conventions="space omega, one convention's formula against the other's",
    omega_body_conventions="body omega, one convention's formula against the other's",
    omega_space_derivative="space omega by formula against vee(dR/dt R^T)",
    omega_body_derivative="body omega by formula against vee(R^T dR/dt)",
    body_is_space_rotated="space omega against R times body omega",
    antisymmetry="dR/dt R^T + its transpose",
)

STEREOGRAPHIC = _group(
    "stereographic",
    Q("a", "a", "1", "Cayley-Klein parameter a (real, imaginary part)", ("complex",)),
    Q("b", "b", "1", "Cayley-Klein parameter b (real, imaginary part)", ("complex",)),
    Q("rotation", "R(U)", "1", "R(U) = tr(sigma_i U sigma_j U^+)/2", ("xyz", "xyz")),
    Q("rotation_minus_u", "R(-U)", "1", "R(-U)", ("xyz", "xyz")),
    Q("rotation_conjugate", r"R(\bar{U})", "1", "R of the complex conjugate of U",
      ("xyz", "xyz")),
    Q("rotation_from_mobius", "R", "1", "R read off the Moebius map", ("xyz", "xyz")),
    Q("su2_axis", r"\hat{n}", "1", "axis of U = exp(-i alpha n.sigma/2)", ("xyz",)),
    Q("su2_angle", r"\alpha", "rad", "angle of U = exp(-i alpha n.sigma/2)"),
    Q("points", "x", "1", "sample points on the unit sphere", ("point", "xyz")),
    Q("images", "R(U) x", "1", "their images under R(U)", ("point", "xyz")),
    Q("plane", r"\zeta", "1", "stereographic projections (real, imaginary part)",
      ("point", "complex")),
    Q("plane_mobius", r"M_U(\zeta)", "1", "their Moebius images", ("point", "complex")),
    Q("plane_rotated", r"\pi(R(U) x)", "1", "projections of the rotated points",
      ("point", "complex")),
    Q("circle", "", "1", "a circle of latitude", ("circle", "xyz")),
    Q("circle_image", "", "1", "its image under R(U)", ("circle", "xyz")),
    Q("circle_plane", "", "1", "its projection", ("circle", "complex")),
    Q("circle_plane_mobius", "", "1", "the Moebius image of its projection",
      ("circle", "complex")),
    Q("pole", "N", "1", "the north pole", ("xyz",)),
    Q("pole_image", "R(U) N", "1", "its image under R(U)", ("xyz",)),
    Q("pole_image_plane", r"M_U(\infty)", "1", "the Moebius image of infinity",
      ("complex",)),
)

IDENTITIES = _group(
    "identities",
    Q("second_rotation", "S", "1", "the Euler matrix R(t = 0) that turns A: A' = S A S^-1",
      ("xyz", "xyz")),
    Q("turned_axis", "S n", "1", "the axis of R(n, Phi) turned by S", ("xyz",)),
    Q("turned", "A'", "1", "S A S^-1 for A = R(n, Phi), Phi [n]x, (R + R^T)/2",
      ("matrix", "xyz", "xyz")),
    Q("trace", r"\mathrm{tr}\,A", "1", "trace of each A", ("matrix",)),
    Q("trace_turned", r"\mathrm{tr}\,A'", "1", "trace of each S A S^-1", ("matrix",)),
    Q("determinant", r"\det A", "1", "determinant of each A", ("matrix",)),
    Q("determinant_turned", r"\det A'", "1", "determinant of each S A S^-1", ("matrix",)),
    Q("eigenvalues", r"\lambda", "1", "eigenvalues of each A (real, imaginary part)",
      ("matrix", "eigen", "complex")),
    Q("eigenvalues_turned", r"\lambda'", "1", "eigenvalues of each S A S^-1",
      ("matrix", "eigen", "complex")),
    Q("eigenvalues_closed", r"\lambda", "1", "the closed forms: 1, exp(+-i Phi); 0, +-i Phi; "
      "1, cos Phi, cos Phi", ("matrix", "eigen", "complex")),
    Q("omega_scale", r"\max|\omega|", "rad/s", "largest |omega| over the path (0: the "
      "deviations divided by it are absolute)"),
    Q("central_differences/step", "h", "s", "the stored path's time step"),
    Q("central_differences/antisymmetry", "", "1", "max |W + W^T| / max|omega|, W = D_h R^-1, "
      "D_h the central difference"),
    Q("central_differences/omega", "", "1", "max |D_h R^-1 - [omega]x| / max|omega|"),
    Q("central_differences/omega_double_step", "", "1",
      "max |D_2h R^-1 - [omega]x| / max|omega|"),
    Q("central_differences/omega_richardson", "", "1",
      "max |(4 D_h - D_2h)/3 R^-1 - [omega]x| / max|omega|"),
    Q("central_differences/order", "p", "1", "log2 of the ratio of the last two: 2 for a "
      "central difference"),
)

IDENTITIES_ERRORS = _errors(
    "identities",
    orthogonality="M^T M - 1 over R(n, Phi), S R(n, Phi), R(t) and R(t) R(n, Phi)",
    determinant="det M - 1 over the same matrices",
    inverse_is_transpose="S^-1 (by LU) against S^T",
    similarity_closed_form="S A S^-1 against A built on S n",
    trace_invariant="tr S A S^-1 against tr A and tr A against its closed form",
    determinant_invariant="det S A S^-1 against det A and det A against its closed form",
    eigenvalue_invariant="eigenvalues of S A S^-1 against those of A and their closed forms",
    symmetry_kept="S A S^-1 stays antisymmetric (generator) and symmetric (symmetric part)",
    rdot_antisymmetric="dR/dt R^-1 + its transpose, dR/dt by the complex step, / max|omega|",
    rdot_is_omega="dR/dt R^-1 against [omega]x (space axes, from the rates), / max|omega|",
    adot_is_omega_body="dA/dt A^-1 against -[omega']x for A = R^T (body axes), / max|omega|",
)

SU2_FORM = _group(
    "su2_form",
    Q("convention", "", "", "convention of the Euler angles", kind="str"),
    Q("axis", r"\hat{n}", "1", "axis of the ex. 4.5 turn", ("xyz",)),
    Q("angle", r"\Phi", "rad", "angle of the ex. 4.5 turn"),
    Q("a", "a", "1", "Cayley-Klein a of U(n, Phi) = cos(Phi/2) 1 - i sin(Phi/2) n.sigma",
      ("complex",)),
    Q("b", "b", "1", "Cayley-Klein b of U(n, Phi)", ("complex",)),
    Q("rotation", "R(U)", "1", "R(U) = tr(sigma_i U sigma_j U^+)/2 of U(n, Phi)",
      ("xyz", "xyz")),
    Q("euler_angles", r"(\phi, \theta, \psi)", "rad", "Euler angles at t = 0", ("angle",)),
    Q("euler_a", "a", "1", "Cayley-Klein a of U_z(phi) U_x(theta) U_z(psi) at t = 0",
      ("complex",)),
    Q("euler_b", "b", "1", "Cayley-Klein b of the Euler-angle U at t = 0", ("complex",)),
    Q("euler_rotation", "R(U)", "1", "R of the Euler-angle U at t = 0", ("xyz", "xyz")),
    Q("euler_axis", r"\hat{m}", "1", "axis m of the Euler-angle U = cos(alpha/2) 1 - "
      "i sin(alpha/2) m.sigma", ("xyz",)),
    Q("euler_angle", r"\alpha", "rad", "its angle alpha, 0 ... 2 pi"),
)

SU2_FORM_ERRORS = _errors(
    "su2_form",
    closed_form_vs_exp="cos(Phi/2) 1 - i sin(Phi/2) n.sigma against exp(-i Phi n.sigma/2) "
                       "by eigenvectors",
    unitarity="U U^+ - 1 and det U - 1, U(n, Phi) and the Euler-angle U along the path",
    rotation_vs_textbook="R(U(n, Phi)) against the textbook's R(n, Phi) (textbook ex. 4.5)",
    euler_rotation_vs_matrix="R(U_z U_x U_z) against the Euler matrix, whole path",
    euler_product_vs_cayley_klein="U_z U_x U_z against its multiplied-out Cayley-Klein "
                                  "parameters, whole path",
    euler_conventions="U by the given convention against U by the other (converted angles)",
    euler_theorem="R(m, alpha) of the single turn read off U against the Euler matrix",
    two_pi_flip="U(phi + 2 pi, theta, psi) + U(phi, theta, psi)",
    double_cover="R(U(phi + 2 pi, theta, psi)) against R(U(phi, theta, psi))",
    notes_parametrization="u(alpha, beta, gamma) of notes (9.4), its angles read off U, "
                          "against U",
    notes_determinant="det M against 1 - r^2 (notes (9.5)-(9.6)) at the sample points",
    notes_determinant_kept="det u M u^+ against det M (notes (9.7))",
    notes_map_vs_rotation="r' read off u M u^+ against R(U) r (notes (9.8))",
    notes_second_axis="R(u(alpha, 0, 0)) against R2(2 alpha) of notes (9.10), its last "
                      "entry cos 2 alpha",
    notes_third_axis="R(u(0, beta, 0)) against R3(2 beta) of notes (9.11)",
    notes_first_axis="R(u(alpha, 0, pi/2)) against R1(2 alpha) of notes (9.15)-(9.16)",
    notes_euler_identification="U3(psi) U1(theta) U3(phi) of notes (9.18) against "
                               "u(theta/2, phi + psi, psi - phi + pi/2) of notes (9.4)",
    notes_euler_half_angles="R(U3(psi/2) U1(theta) U3(phi/2)) against R3(psi) R1(theta) "
                            "R3(phi) of notes (9.17)",
)

SU2_NOTES = _group(
    "su2_form/notes",
    Q("alpha", r"\alpha", "rad", "alpha of notes (9.4) read off U: |u11| = cos alpha"),
    Q("beta", r"\beta", "rad", "beta of notes (9.4): the phase of u11"),
    Q("gamma", r"\gamma", "rad", "gamma of notes (9.4): the phase of u12"),
    Q("points", "r", "1", "sample points r = (x, y, z) of M(r), notes (9.5)", ("sample", "xyz")),
    Q("printed_9_10_entry", "", "1", "|sin 2 alpha - cos 2 alpha|: how far the last entry of "
      "notes (9.10) as printed (sin 2 alpha) is from the map's (cos 2 alpha), at the scene's "
      "alpha"),
    Q("case_9_12_trace", r"\mathrm{tr}\,R", "1", "trace of R(u(pi/2, 0, gamma)), the case "
      "alpha = pi/2, beta = 0 of notes (9.12), at the scene's gamma"),
    Q("case_9_12_axis", r"\hat{m}", "1", "axis of that rotation", ("xyz",)),
    Q("case_9_12_vs_third_axis", "", "1", "max |R(u(pi/2, 0, gamma)) - R3(2 gamma)|: how far "
      "it is from the R3(2 gamma) the notes state"),
    Q("euler_angles", r"(\phi, \theta, \psi)", "rad", "the angles of notes (9.17)-(9.18) "
      "checked: the scene's Euler angles at t = 0", ("angle",)),
    Q("printed_9_18_full_angles", "", "1", "max |R(U3(psi) U1(theta) U3(phi)) - R3(psi) "
      "R1(theta) R3(phi)|: (9.18) as printed, with full angles, against (9.17)"),
)

STEREOGRAPHIC_ERRORS = _errors(
    "stereographic",
    mobius_vs_rotation="Moebius map of U against R(U) on the sphere",
    mobius_vs_rotation_standard_orientation="Moebius map of U against R(conj U), "
                                            "zeta = (x + iy)/(1 - z)",
    rotation_from_mobius="R from the Moebius map against tr(sigma_i U sigma_j U^+)/2",
    rotation_trace_vs_quaternion="tr(sigma_i U sigma_j U^+)/2 against the quaternion formula",
    double_cover_rotation="R(-U) against R(U)",
    double_cover_mobius="Moebius map of -U against that of U",
    unitarity="U U^+ - 1 and det U - 1",
    round_trip="inverse projection of the projection against x",
    isometry="| |f'(zeta)| (1 + |zeta|^2)/(1 + |f(zeta)|^2) - 1 | for the Moebius map f of U: "
             "the sphere's distances kept (textbook ex. 4.11(d))",
    transpose_mismatch="(not a check) distance of R(U)^T from the Moebius map",
    transpose_mismatch_standard_orientation="(not a check) the same, zeta = (x + iy)/(1 - z)",
    scale_factor="|d zeta/ds| (1 - z) - 1 along two tangents, d zeta/ds by the complex "
                 "step, times min(1, 1 - z)",
    conformal_angle="Re(d zeta_1 conj(d zeta_2)) (1 - z)^2 for orthogonal tangents",
    difference_quotient_chordal="|zeta+ - zeta-| / |x+ - x-| against "
                                "1/sqrt((1 - z+)(1 - z-)), over its value, times min(1, 1 - z)",
    composition_mobius="Moebius map of U U2 against that of U after that of U2",
    composition_rotation="R(U U2) against R(U) R(U2)",
)

STEREOGRAPHIC_MORE = _group(
    "stereographic",
    Q("isometry_non_unitary", "", "1", "max | |f'| (1 + |zeta|^2)/(1 + |f|^2) - 1 | for the "
      "Moebius map of U diag(2, 1/2): det 1 but not unitary, so not an isometry (textbook "
      "ex. 4.11(d))"),
    Q("conformal_factor", "1/(1 - z)", "1", "the projection's scale factor at the points",
      ("point",)),
    Q("second_source", "", "", "where U2 comes from: axis_angle, euler or su2", kind="str"),
    Q("second_a", "a_2", "1", "Cayley-Klein a of U2", ("complex",)),
    Q("second_b", "b_2", "1", "Cayley-Klein b of U2", ("complex",)),
    Q("second_rotation", "R(U_2)", "1", "R(U2)", ("xyz", "xyz")),
    Q("contrasts/steps", r"\delta", "1", "arc lengths of the difference quotients",
      ("step",)),
    Q("contrasts/quotient_vs_factor", "", "1", "(not a check) max relative distance of "
      "|zeta+ - zeta-| / |x+ - x-| from 1/(1 - z), each step", ("step",)),
    Q("contrasts/reversed_mobius", "", "1", "(not a check) Moebius map of U U2 against "
      "that of U2 after that of U"),
    Q("contrasts/reversed_rotation", "", "1", "(not a check) R(U U2) against R(U2) R(U)"),
    Q("transpose_differs", "", "", "whether R(U)^T is another map than the Moebius map of U "
      "(transpose_mismatch above CONTRAST; R symmetric, a half turn, makes them one)",
      kind="bool"),
    Q("transpose_differs_standard", "", "", "whether R(U)^T is another map than the Moebius "
      "map with zeta = (x + iy)/(1 - z), R(conj U) (above CONTRAST)", kind="bool"),
    Q("reversed_differs", "", "", "whether R(U2) R(U) is another rotation than R(U) R(U2) "
      "(reversed_rotation above CONTRAST; U and U2 commute otherwise)", kind="bool"),
    Q("contrast_threshold", "", "1", "CONTRAST: a contrast's distance above which two maps "
      "differ"),
)

#: /analysis/proofs: textbook ex. 4.1–4.4 for all n × n matrices (kinds/rotation/proofs.py),
#: each identity by (key, exercise, statement), in the order of the exercises
PROOF_STATEMENTS = (
    ("associative", "4.1(a)", "associative: A(BC) = (AB)C"),
    ("transpose", "4.1(b)", "transpose of a product: (AB)ᵀ = BᵀAᵀ"),
    ("determinant_product", "4.1(c)", "the inverse of AB exists with A⁻¹ and B⁻¹: "
                                      "det(AB) = det A det B"),
    ("inverse", "4.1(c)", "inverse of a product: (AB)⁻¹ = B⁻¹A⁻¹, as adj(AB) = adj(B) adj(A)"),
    ("hermitian", "4.1(d)", "hermitian conjugate, complex entries: (AB)† = B†A†"),
    ("basis_vectors", "4.2(a)", "a basis e′ that need not be orthonormal, êᵢ = Σⱼ Aⱼᵢ e′ⱼ: "
                                "e′ⱼ = Σᵢ (A⁻¹)ᵢⱼ êᵢ"),
    ("components", "4.2(b)", "components of V in that basis: V′ᵢ = Σⱼ Aᵢⱼ Vⱼ, V′ = AV"),
    ("components_back", "4.2(c)", "components back in the basis êᵢ: Vᵢ = Σⱼ (A⁻¹)ᵢⱼ V′ⱼ, "
                                  "V = A⁻¹V′"),
    ("basis_change", "4.2(d)", "change of basis: W = BV and V′ = AV give W′ = ABA⁻¹V′"),
    ("trace", "4.3(a)", "trace: tr(ABA⁻¹) = tr B"),
    ("symmetric", "4.3(d)", "symmetric B = Bᵀ stays symmetric: (ABAᵀ)ᵀ = ABAᵀ (Aᵀ = A⁻¹ for "
                            "an orthogonal A)"),
    ("antisymmetric", "4.3(d)", "antisymmetric B = −Bᵀ stays antisymmetric: (ABAᵀ)ᵀ = −ABAᵀ"),
    ("derivative_of_inverse", "4.4", "derivative of the inverse: Ȧ A⁻¹ = −A dA⁻¹/dt"),
)
PROOF_KEYS = tuple(key for key, _, _ in PROOF_STATEMENTS)
PROOFS = _group(
    "proofs",
    Q("sizes", "n", "1", "the matrix sizes proved for", ("proof_size",), "int"),
    Q("seed", "", "1", "seed of the random matrices of the numerical checks", (), "int"),
    *(q for key in PROOF_KEYS for n in (2, 3) for q in (
        Q(f"proved/{key}_{n}", "", "", f"whether SymPy expanded the two sides' difference of "
          f"'{key}' for {n} x {n} matrices of symbols to 0", (), "bool"),
        Q(f"terms/{key}_{n}", "N", "1", f"terms of the left side of '{key}' expanded, "
          f"{n} x {n}", (), "int"),
        Q(f"errors/{key}_{n}", "", "1", f"max error: '{key}' on random {n} x {n} matrices, "
          "relative to the largest entry"))),
    # ex. 4.2(a)-(c) on a random basis that is not orthonormal (kinds/rotation/basis.py)
    *(q for n in (2, 3) for q in (
        Q(f"basis/hat_{n}", r"\hat{e}_i", "1", f"a random orthonormal basis e^_i, {n} x {n} "
          "(columns)", (f"basis_{n}", f"basis_{n}")),
        Q(f"basis/matrix_{n}", "A", "1", "A of e^_i = sum_j A_ji e'_j, random, condition "
          "number below 20", (f"basis_{n}", f"basis_{n}")),
        Q(f"basis/prime_{n}", "e'_j", "1", "the basis e'_j (columns), solved from the "
          "definition: not orthonormal", (f"basis_{n}", f"basis_{n}")),
        Q(f"basis/gram_{n}", "G", "1", "Gram matrix G_ij = e'_i . e'_j",
          (f"basis_{n}", f"basis_{n}")),
        Q(f"basis/gram_distance_{n}", r"\max|G - 1|", "1", "distance of the Gram matrix "
          "from the identity (0 for an orthonormal basis)"),
        Q(f"basis/condition_{n}", r"\kappa(A)", "1", "condition number of A (2-norm)"),
        Q(f"basis/vector_{n}", "V", "1", "a random vector (Cartesian components)",
          (f"basis_{n}",)),
        Q(f"basis/components_{n}", "V_i", "1", "its components in the basis e^_i: e^_i . V",
          (f"basis_{n}",)),
        Q(f"basis/components_prime_{n}", "V'_i", "1", "its components in the basis e'_i, "
          "from the Gram equations G V' = (e'_i . V)", (f"basis_{n}",)),
        Q(f"basis/projections_{n}", r"e'_i \cdot V", "1", "its projections e'_i . V (not "
          "its components, e' not being orthonormal)", (f"basis_{n}",)),
        Q(f"basis/projection_gap_{n}", "", "1", "(not a check) largest distance of the "
          "projections from the components V', relative to the largest entry"))),
)

SCHEMA = ResultsSchema(analysis=AXIS_ANGLE + AXIS_ANGLE_ERRORS + EULER + EULER_ERRORS
                       + IDENTITIES + IDENTITIES_ERRORS + SU2_FORM + SU2_FORM_ERRORS + SU2_NOTES
                       + STEREOGRAPHIC + STEREOGRAPHIC_ERRORS + STEREOGRAPHIC_MORE + PROOFS)
