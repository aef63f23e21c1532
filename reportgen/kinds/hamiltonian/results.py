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
TIME = Q("t", "t", "1", "time (scaled units)", ("t",))


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
)

SCHEMA = ResultsSchema(
    time=TIME,
    invariants=(Q("H", "H", "1", "Hamiltonian", ("t",)),),
    analysis=(
        # physical behaviour (not the run's numerical status): chaotic or regular
        _text("behaviour", "physical behaviour: chaotic or regular (two orbits 1e-10 apart)",
              optional=True),
        Q("separation_growth", r"\max d/d_0", "1", "growth of the separation of two orbits "
          "started 1e-10 apart", optional=True),
        Q("lyapunov_time", r"T_\lambda", "1", "Lyapunov time 1/lambda of a chaotic orbit",
          optional=True),
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
        _flag("separable", "whether H = T(p) + V(q)"),
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
        Q("jacobi_scale", "", "1", "sum of the largest Jacobi-identity terms"),
        _text("jacobi_triple", "the f, g, h of the Jacobi identity checked", ("triple",)),
        _text("jacobi_triple_latex", "the f, g, h of the Jacobi identity checked (TeX)",
              ("triple",), optional=True),
        Q("legendre_momentum_error", r"\max|p - \partial L/\partial\dot{q}|", "1",
          "largest error of the momenta along the run", optional=True),
        Q("legendre_energy_error", r"\max|H - (\dot{q} p - L)|", "1",
          "largest difference of H and the energy function along the run", optional=True),
        Q("legendre_energy_scale", r"\max|H|", "1", "largest |H| along the run",
          optional=True),
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
               tex: Callable[[str], str] = str) -> ResultsSchema:
    """:data:`SCHEMA` with what a config names: the columns (the coordinates, then
    ``p_<q>``, and a canonical transformation's new variables), the invariants (H, each
    observable, the momentum of each coordinate that may turn out cyclic) and the
    results per column and per observable.  ``tex(name)`` gives a name's TeX symbol."""
    coordinates, observables = list(coordinates), list(observables)
    columns = [Q(q, tex(q), "1", f"coordinate {q}", ("t",)) for q in coordinates]
    columns += [Q(f"p_{q}", tex(f"p_{q}"), "1", f"momentum conjugate to {q}", ("t",))
                for q in coordinates]
    columns += [Q(c, tex(c), "1", f"new canonical variable {c}", ("t",)) for c in new_columns]
    invariants = [Q(f, tex(f), "1", f"observable {f}", ("t",)) for f in observables]
    invariants += [Q(f"p_{q}", tex(f"p_{q}"), "1", f"momentum conjugate to {q} (cyclic)",
                     ("t",)) for q in coordinates]
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
