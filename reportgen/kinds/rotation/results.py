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
#: the /analysis group each section reads
SECTION_DATA = {"axis_angle": "axis_angle", "euler_angles": "euler",
                "angular_velocity": "euler", "stereographic": "stereographic"}


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
    Q("vector", "r", "1", "the vector the rotation formula turns", ("xyz",)),
    Q("rotated_vector", "r'", "1", "r by the rotation formula (4.62)", ("xyz",)),
    Q("matrix_formula", "A", "1", "A(n, Phi) from the rotation formula (4.62)",
      ("xyz", "xyz")),
    Q("matrix_expm", "A", "1", "exp(-Phi [n]x) by diagonalization", ("xyz", "xyz")),
    Q("matrix_quaternion", "A", "1", "R(q) transposed, from the quaternion",
      ("xyz", "xyz")),
    Q("recovered_axis", r"\hat{n}", "1", "axis recovered from the matrix", ("xyz",)),
    Q("recovered_angle", r"\Phi", "rad", "angle recovered from the matrix"),
    Q("determinant", r"\det A", "1", "determinant of A"),
    Q("arc", "r'", "1", "r by the rotation formula for angles 0 ... Phi", ("arc", "xyz")),
    Q("circle", "r'", "1", "r by the rotation formula for a full turn",
      ("arc_circle", "xyz")),
    Q("centre", "", "1", "centre of that circle, (n.r) n", ("xyz",)),
    Q("turned_axes", "", "1", "the turned axes (rows) in the old axes", ("xyz", "xyz")),
)

AXIS_ANGLE_ERRORS = _errors(
    "axis_angle",
    formula_vs_expm="A(4.62) against exp(-Phi [n]x)",
    formula_vs_quaternion="A(4.62) against R(q) transposed",
    vector_formula_vs_matrix="r' by (4.62) against A r, over |r|",
    orthogonality="A A^T - 1",
    recovered_angle="angle recovered from the matrix",
    recovered_axis="axis recovered from the matrix, times min(1, Phi)",
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
    Q("elements", "A", "1", "Goldstein's A (4.46) by its elements", ("xyz", "xyz")),
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
) + _construction("zxz") + _construction("zyz")

EULER_ERRORS = _errors(
    "euler",
    matrix_product_vs_elements="R by elementary rotations against (4.46) elements",
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
    transpose_mismatch="(not a check) distance of R(U)^T from the Moebius map",
    transpose_mismatch_standard_orientation="(not a check) the same, zeta = (x + iy)/(1 - z)",
)

SCHEMA = ResultsSchema(analysis=AXIS_ANGLE + AXIS_ANGLE_ERRORS + EULER + EULER_ERRORS
                       + STEREOGRAPHIC + STEREOGRAPHIC_ERRORS)
