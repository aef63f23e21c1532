"""What an ``inertia`` scene stores: every result once, with its symbol and unit.

:func:`axis_stability_results` is shared with ``rigid_body``, which stores the same
per-axis verdicts (for a given spin, with the Jacobian's growth rate besides).
"""

from __future__ import annotations

from ...scene.schema import Quantity as Q
from ...scene.schema import ResultsSchema


def axis_stability_results(rate_unit: str, *, jacobian: bool = False,
                           optional: bool = False) -> tuple[Q, ...]:
    """``axis_stability/axis_<k>/...``: free rotation about principal axis k, linearized
    (notes (10.12)–(10.14)); rates in ``rate_unit`` ("1": per unit spin; "1/s": for the given
    spin)."""
    out: list[Q] = []
    for k in (1, 2, 3):
        group = f"axis_stability/axis_{k}"
        out += [
            Q(f"{group}/moment", f"I_{k}", "kg m^2", f"principal moment {k}",
              optional=optional),
            Q(f"{group}/verdict", "", "", f"stable, unstable or marginal about axis {k}",
              kind="str", optional=optional),
            Q(f"{group}/growth_rate", r"\gamma", rate_unit,
              f"growth rate of a perturbation about axis {k}", optional=optional),
            Q(f"{group}/oscillation_frequency", r"\omega_w", rate_unit,
              f"wobble frequency about axis {k}", optional=optional),
        ]
        if jacobian:
            out.append(Q(f"{group}/growth_rate_jacobian", r"\max \mathrm{Re}\,\lambda", "1/s",
                         f"largest real part of the Jacobian's eigenvalues about axis {k}",
                         optional=optional))
    return tuple(out)


SCHEMA = ResultsSchema(
    analysis=(
        Q("tensor", "I", "kg m^2", "inertia tensor about the centre of mass, lab frame",
          ("xyz", "xyz")),
        Q("principal_moments", "I_k", "kg m^2", "principal moments, ascending", ("axis",)),
        Q("principal_axes", r"\hat{e}_k", "1", "principal axes (columns), lab frame",
          ("xyz", "axis")),
        Q("centre_of_mass", r"r_\mathrm{cm}", "m", "centre of mass, lab frame", ("xyz",)),
        Q("mass", "M", "kg", "total mass"),
        Q("shape", "", "", "the body, described", kind="str"),
        Q("top", "", "", "spherical (three equal principal moments), symmetric (two) or "
          "asymmetric, equal within equal_moments_rtol of the largest", kind="str",
          optional=True),
        Q("equal_moments_rtol", "", "1", "share of the largest moment within which two "
          "principal moments are equal", optional=True),
        *axis_stability_results("1"),
        *(Q(f"axis_stability/axis_{k}/shape_axis", "", "",
            f"the shape's own axis that principal axis {k} lies along, in words", kind="str",
            optional=True) for k in (1, 2, 3)),
        Q("inertia_ellipsoid/semi_axes", r"1/\sqrt{I_k}", "kg^-0.5/m",
          "semi-axes of the inertia ellipsoid", ("axis",)),
        Q("inertia_ellipsoid/surface", "x", "kg^-0.5/m",
          "inertia ellipsoid sum I_k x_k^2 = 1, surface grid",
          ("ellipsoid_u", "ellipsoid_v", "xyz")),
        Q("points/positions", "r", "m", "point masses' positions, lab frame",
          ("point", "xyz"), optional=True),
        Q("points/masses", "m", "kg", "point masses", ("point",), optional=True),
        Q("closed_form/principal_moments", "I_k", "kg m^2",
          "principal moments in closed form, ascending", ("axis",), optional=True),
        Q("closed_form/source", "", "", "where the closed form comes from", kind="str",
          optional=True),
        Q("closed_form/max_relative_difference", "", "1",
          "largest difference of the diagonalized and closed-form moments over I_3",
          optional=True),
        Q("quadrature/nodes", "N", "1", "point masses of the quadrature", kind="int",
          optional=True),
        Q("quadrature/volume", "V", "m^3", "volume by quadrature", optional=True),
        Q("quadrature/volume_closed", "V", "m^3", "volume in closed form", optional=True),
        Q("quadrature/centre_of_mass", r"r_\mathrm{cm}", "m",
          "centre of mass by quadrature, shape frame, from the closed-form centre of mass",
          ("xyz",), optional=True),
        Q("quadrature/moments", "I", "kg m^2",
          "moments about the shape's own axes by quadrature", ("xyz",), optional=True),
        Q("quadrature/moments_closed", "I", "kg m^2",
          "moments about the shape's own axes in closed form", ("xyz",), optional=True),
        Q("quadrature/products_max", r"\max|I_{ij}|", "kg m^2",
          "largest product of inertia (off the diagonal) by quadrature", optional=True),
        Q("quadrature/max_relative_difference", "", "1",
          "largest difference of the quadrature and closed-form moments over the largest",
          optional=True),
        Q("quadrature/apex_distance", "d", "m",
          "centre of mass below the cone's apex by quadrature", optional=True),
        Q("quadrature/apex_distance_closed", "3h/4", "m",
          "centre of mass below the cone's apex, closed form", optional=True),
        Q("parallel_axis/about", "a", "m", "point of the parallel-axis shift, notes (8.49)",
          ("xyz",), optional=True),
        Q("parallel_axis/tensor", "I", "kg m^2", "inertia tensor about that point, notes (8.49)",
          ("xyz", "xyz"), optional=True),
        Q("parallel_axis/principal_moments", "I_k", "kg m^2",
          "principal moments about that point", ("axis",), optional=True),
        Q("parallel_axis/principal_axes", r"\hat{e}_k", "1",
          "principal axes about that point (columns)", ("xyz", "axis"), optional=True),
    ),
)
