"""``hamiltonian`` report: the equations, the trajectory, the phase portrait or surface of
section (one orbit's, or a sweep's many), the conserved quantities, the Poisson brackets,
a canonical transformation and the Hamilton–Jacobi comparison, from the archive alone."""

from __future__ import annotations

import math

import numpy as np
from markupsafe import Markup

from ...lazy import lazy_module
from ...rendering.equations import equation_html
from ...scene.base import Section
from ...scene.content import SectionContent, fmt, fmt_err
from ...scene.report import Report, method_words, section_colours, section_point_notes
from .config import (
    JACOBI_SAMPLES,
    STUDY_STEPS,
    family_energy,
)
from .report_canonical import CanonicalSections
from .report_legendre import LegendreGeometrySections
from .report_point import PointTransformSections
from .report_tables import SymbolTables
from .results import SCHEMA
from .symbols import dot_tex, split_sum, symbol_parts, symbol_tex, symbol_text, symbol_words

common_plots = lazy_module("reportgen.rendering.plots.common")
plots = lazy_module("reportgen.kinds.hamiltonian.plots")
section_plots = lazy_module("reportgen.rendering.plots.sections")


class HamiltonianReport(CanonicalSections, LegendreGeometrySections, PointTransformSections,
                        SymbolTables, Report):
    """The sections of a formula system, drawn from the archive alone."""

    schema = SCHEMA
    gallery_name = "Hamiltonian and Lagrangian systems"
    gallery_figures = ("poincare", "poincare_family", "configuration")

    @classmethod
    def gallery_headline(cls, data):
        from ...scene import gallery
        a = data.analysis
        if gallery.is_family(data):
            energy = a.get("poincare_edge_energy")
            members, ok = a.get("sweep_members", 0), a.get("sweep_ok", 0)
            return (f"{members} orbits on the section"
                    + (f" at H = {fmt(energy, 5)}" if energy is not None else "")
                    + (", all ok" if ok == members else f", {ok} ok"))
        check = gallery.worst_check(data, "H(t_end)")
        if check is None or "H0" not in a:
            return super().gallery_headline(data)
        given = "from L: " if a.get("given") == "L" else ""
        return f"{given}energy H = {fmt(a['H0'], 5)} conserved to {gallery.distance(check.rel_error)}"

    study_horizon_reason = (f"it covers at most {STUDY_STEPS} steps of the main run, since "
                            "long runs would spend most of their time on references, and in a "
                            "chaotic system errors that have grown to the size of the orbit "
                            "compare nothing.")
    sections = (
        Section("equations", "The system and its equations of motion"),
        Section("legendre_geometry", "The Legendre transform as geometry: tangent planes"),
        Section("trajectory", "Trajectory", integrates=True),
        Section("phase_portrait", "Phase portrait", integrates=True),
        Section("poincare", "Surface of section", integrates=True),
        Section("invariants", "Conserved quantities", integrates=True),
        Section("brackets", "Poisson brackets and symmetries", integrates=True),
        Section("noether", "Noether's theorem: the charge of a declared symmetry",
                integrates=True),
        Section("total_derivative", "Adding a total derivative to L", integrates=True),
        Section("point_transform", "A point transformation: the same equations in new "
                "coordinates", integrates=True),
        Section("transform", "Canonical transformation", integrates=True),
        Section("hamilton_jacobi", "Hamilton–Jacobi: the separated quadrature solution",
                integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    family_sections = (
        Section("poincare_family", "Surface of section from many orbits",
                description="The crossings of every member's orbit on one surface of "
                            "section, each orbit coloured by its swept value.",
                points="poincare"),
    )

    SWEEP_HIDDEN_RESULTS = ("jacobi_*", "poisson_*_max", "legendre_*", "study_t_end",
                            "initial_state_*",  # shown by name: initial_<column>
                            # the relative error at the crossings is the family's fact
                            "poincare_H_error", "poincare_H_farthest", "noether_*",
                            "transform_*", "total_derivative_*", "point_transform_*",
                            "first_order_velocity_*", "first_order_momentum_*")

    #: members of a sweep told apart by a legend; more get a colour bar
    LEGEND_MEMBERS = 7
    #: fewest crossings for a surface of section to be shown without being asked for
    MIN_CROSSINGS = 20
    #: equations whose TeX is longer than this are not typeset (unreadably small)
    LONGEST_EQUATION = 320
    #: samples of the configuration-space path drawn
    CONFIGURATION_SAMPLES = 5000
    #: samples the Jacobi identity is checked on
    JACOBI_SAMPLES = JACOBI_SAMPLES

    @classmethod
    def config_quantity(cls, data, path):
        """A swept initial value ``initial.<q>`` as q(0), in the system's scaled units."""
        from ...scene.schema import Quantity

        head, _, name = path.partition(".")
        if head != "initial" or not name:
            return super().config_quantity(data, path)
        return Quantity(path, f"{symbol_tex(name)}(0)", cls.unit_of(data, name),
                        f"initial {name}")

    @classmethod
    def result_quantity(cls, data, name):
        """A result of a formula system: every quantity is in the author's units (the
        config's, :attr:`UNITS`), an initial value in its column's (rad for an angle)."""
        from ...scene.schema import Quantity

        q = super().result_quantity(data, name)
        column = name[len("initial_"):] if name.startswith("initial_") else None
        if column and column != "state" and column in cls.symbols_of_columns(data):
            return Quantity(name, f"{symbol_tex(column)}(0)", cls.unit_of(data, column),
                            f"initial {symbol_words(column, cls.coordinates(data))}")
        if name == "poincare_H_error":
            return Quantity(name, q.symbol, cls.UNITS, q.description)
        return q if q.unit else Quantity(name, q.symbol, "1", q.description)

    @classmethod
    def symbols_of_columns(cls, data) -> list[str]:
        """The state columns' names: the coordinates and their momenta p_<q>."""
        coords = cls.coordinates(data)
        return coords + [f"p_{q}" for q in coords]

    @staticmethod
    def symbols(data) -> dict[str, str]:
        """Each state column's symbol for an axis label ("$p_{\\theta}$"), from the TeX
        the simulation stored (``/analysis/latex`` q and p), not the config's name."""
        a = data.analysis
        names, tex = list(a["coordinates"]), a["latex"]
        symbol = {n: f"${t}$" for n, t in zip(names, tex["q"], strict=True)}
        symbol.update({f"p_{n}": f"${t}$" for n, t in zip(names, tex["p"], strict=True)})
        return symbol

    #: the unit of every quantity of a formula system but an angle: the config's own,
    #: which it does not declare (Hénon–Heiles is scaled; a pendulum's g may be in m/s²)
    UNITS = "config units"

    @classmethod
    def axis_labels(cls, data) -> dict[str, str]:
        """Each state column's axis label: its symbol (:meth:`symbols`) and unit, [rad] for
        an angle (a coordinate H is 2π-periodic in), else :attr:`UNITS`."""
        return {n: f"{s} [{cls.unit_of(data, n)}]" for n, s in cls.symbols(data).items()}

    #: names of a coordinate that is an angle when H does not contain it (a cyclic φ: H
    #: periodic in it cannot be checked, yet it is measured in radians)
    ANGLE_NAMES = frozenset({"theta", "phi", "psi", "chi", "alpha", "beta", "gamma",
                             "varphi", "vartheta"})

    @classmethod
    def unit_of(cls, data, name: str) -> str:
        """The unit a state column is printed in: rad for an angle (H 2π-periodic in it,
        or a cyclic coordinate named as an angle), else :attr:`UNITS`."""
        a = data.analysis
        if name in list(a.get("angles", [])):
            return "rad"
        if (name in [str(c) for c in a.get("cyclic", [])]
                and symbol_parts(name)[0] in cls.ANGLE_NAMES):
            return "rad"
        return cls.UNITS

    @staticmethod
    def coordinates(data) -> list[str]:
        """The coordinates' names: archived with a run, else those of the archived config
        (a family stores no run's analysis)."""
        a = data.analysis
        if "coordinates" in a:
            return [str(q) for q in a["coordinates"]]
        system = getattr(data.config, "system", None)
        return list(getattr(system, "coordinates", None) or [])

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        a = data.analysis
        if "phase_grid" not in a:
            names.remove("phase_portrait")
        if "transform" not in a:
            names.remove("transform")
        if "legendre_sphere" not in a:  # L of two velocities, ∂²L/∂q̇∂q̇ positive definite
            names.remove("legendre_geometry")
        if "noether_symmetry" not in a:
            names.remove("noether")
        if "total_derivative_same_equations" not in a:
            names.remove("total_derivative")
        if "point_transform_covariant" not in a:
            names.remove("point_transform")
        if "hamilton_jacobi" not in a:
            names.remove("hamilton_jacobi")
        # a surface of section says something only with enough crossings (a closed orbit
        # crosses it at a few fixed points), unless the config asked for one
        if "poincare" not in a or (len(a["poincare"]["u"]) < cls.MIN_CROSSINGS
                                   and data.config.section is None):
            names.remove("poincare")
        return names

    @classmethod
    def section_poincare_family(cls, data):
        sweep, a = data.sweep, data.analysis
        pts = sweep.points["poincare"]
        s_col, value, direction = pts.attrs["surface"]
        uname, vname = pts.attrs["axes"]
        member = np.asarray(pts.member)
        kept = pts.counts(sweep.size)
        crossing, key, colour, labels = section_colours(sweep, pts, cls.LEGEND_MEMBERS)
        edge = a.get("poincare_edge")
        fig = section_plots.poincare_family(
            pts.columns["u"], pts.columns["v"], member, colour,
            f"${symbol_tex(uname)}$ [{cls.unit_of(data, uname)}]",
            f"${symbol_tex(vname)}$ [{cls.unit_of(data, vname)}]",
            colour_label=cls.colour_key_label(data, key), labels=labels,
            edge=None if edge is None else (edge["u"], edge["v"], edge["H"],
                                            a["poincare_edge_energy"]),
            edge_label=None if edge is None else
            f"${symbol_tex(str(a['poincare_edge_momentum']))}$ = 0 on H = "
            f"{fmt(a['poincare_edge_energy'])}")
        facts = [("orbits", f"{len(crossing)} of {sweep.size} members cross the surface"),
                 ("crossings drawn", f"{len(member)} ({int(kept[crossing].min())} to "
                                     f"{int(kept[crossing].max())} per orbit)")]
        h_error = sweep.analysis.get("poincare_H_relative_error")
        if h_error is not None and np.any(np.isfinite(h_error)):
            facts.append(("max |H − H(0)| at the crossings relative to the energy scale, over "
                          "the members",
                          fmt_err(float(np.nanmax(h_error)))))
        energy = family_energy(sweep)
        if energy is not None:
            facts.append(("energy of every orbit", f"H = {fmt(energy)}"))
        notes = ["A regular (quasi-periodic) orbit crosses the surface on a closed curve: an "
                 "island around a stable periodic orbit or a curve across the section; a "
                 "chaotic orbit scatters over an area, the chaotic sea between the islands."]
        notes += section_point_notes(sweep, "poincare", kept, "cross the surface")
        caption = (cls.surface_words(data, s_col, value, direction, uname, vname)
                   + f" at the crossings of {len(crossing)} orbits, each orbit in its own colour "
                   + (f"(keyed to {cls.config_words(data, key) if key != 'member' else 'its number'})"
                      if labels is None else "(legend)")
                   + ("; the closed curve: the edge of the allowed region, where "
                      + symbol_words(str(a["poincare_edge_momentum"]), cls.coordinates(data))
                      + " vanishes" if edge is not None else "") + ".")
        return SectionContent(figures=[cls.figure("poincare_family", fig, caption)],
                              facts=facts, notes=notes)

    @classmethod
    def surface_words(cls, data, s_col: str, value, direction: str, u: str, v: str) -> str:
        """The surface of section and its plotted columns in words: "Surface of section
        x = 0 crossed with x increasing: the momentum conjugate to y against y"."""
        coords = cls.coordinates(data)
        s = symbol_words(s_col, coords)
        where = (f"{s} = {fmt(float(value), 4)}" if s_col in coords
                 else f"where {s} is {fmt(float(value), 4)}")
        which = {"up": f"with {s} increasing", "down": f"with {s} decreasing",
                 "both": "in either direction"}[direction]
        return (f"Surface of section {where} crossed {which}: {symbol_words(v, coords)} "
                f"against {symbol_words(u, coords)}")

    # ------------------------------------------------------------------ report side
    @classmethod
    def prose_case(cls, data):
        """Regular or chaotic (the first word of the archived behaviour verdict, "" when
        the scene has none: one degree of freedom, or a family), the Lyapunov time, and the
        surface of section's crossings."""
        if data.sweep is not None:
            return {"behaviour": "", "crossings": 0, "lyapunov_time": "", "transform_kind": "",
                    "given": "", "chaos_threshold": "", "plane_map": False, "dof": 0,
                    "tables": {"invariants": [], "brackets": [], "hamilton_jacobi": []}}
        a = data.analysis
        behaviour = str(a.get("behaviour", ""))
        pts = a.get("poincare")
        return {"behaviour": behaviour.split(":", 1)[0] if behaviour else "",
                "given": str(a.get("given", "")),
                "plane_map": cls.plane_map(data),
                "dof": len(cls.coordinates(data)),
                "chaos_threshold": fmt(float(a.get("chaos_growth_threshold", math.nan)), 2),
                "lyapunov_time": fmt(float(a.get("lyapunov_time", math.nan)), 3),
                "crossings": len(pts["u"]) if pts is not None else 0,
                "transform_kind": str(a.get("transform_kind", "")),
                "tables": cls.symbol_tables(data)}

    @classmethod
    def plane_map(cls, data) -> bool:
        """Whether the surface of section is a map of a plane: two degrees of freedom on one
        energy surface (H does not depend on t); otherwise the figure is a projection."""
        a = data.analysis
        return len(cls.coordinates(data)) == 2 and not a.get("time_dependent", False) \
            and not a.get("first_order", False)

    @classmethod
    def behaviour(cls, data):
        """Chaotic or regular, in words from the archived divergence of two orbits started
        10⁻¹⁰ apart (its growth and, when chaotic, its Lyapunov time)."""
        a = data.analysis
        if data.sweep is not None or "separation_growth" not in a:
            return super().behaviour(data)
        growth = float(a["separation_growth"])
        threshold = fmt(float(a.get("chaos_growth_threshold", math.nan)), 2)
        if "lyapunov_time" in a:
            return (f"chaotic: two orbits 10⁻¹⁰ apart separate by {fmt(growth, 2)}× over the "
                    f"run (chaos is called from {threshold}×), as exp(t/T) with Lyapunov time "
                    f"T ≈ {fmt(float(a['lyapunov_time']), 2)}")
        return (f"regular: two orbits 10⁻¹⁰ apart separate by only {fmt(growth, 2)}× over the "
                f"run, below the {threshold}× that marks exponential divergence")

    @classmethod
    def describe(cls, data):
        """``Hamiltonian in (x, y), 2 degrees of freedom, at H = 0.1667: a chaotic orbit
        (Lyapunov time ≈ 9.3), 143 crossings of the surface x = 0``."""
        if data.sweep is not None:
            return super().describe(data)
        a, c = data.analysis, cls.prose_case(data)
        coords = [symbol_text(str(q)) for q in a["coordinates"]]
        n = len(coords)
        text = (f"{'Lagrangian' if a['given'] == 'L' else 'Hamiltonian'} in "
                f"({', '.join(coords)}), {n} degree{'s' if n > 1 else ''} of freedom")
        if "H0" in a and not a.get("time_dependent", False):
            text += f", at H = {fmt(float(a['H0']), 4)}"
        if c["behaviour"] == "chaotic":
            text += f": a chaotic orbit (Lyapunov time ≈ {c['lyapunov_time']})"
        elif c["behaviour"] == "regular":
            text += ": a regular orbit"
        if c["crossings"]:
            s_col, value, _ = a["poincare_surface"]
            text += (f"{',' if c['behaviour'] else ':'} {c['crossings']} crossings of the "
                     f"surface {symbol_text(str(s_col))} = {fmt(float(value), 4)}")
        return text

    @classmethod
    def headline(cls, data):
        a = data.analysis
        run = data.runs.get("main")
        split = ("; H = T(p) + V(q), kinetic and potential parts split"
                 if a.get("kinetic_potential_split", False) else "")
        facts = [("system", f"{'L' if a['given'] == 'L' else 'H'} in "
                            f"{', '.join(map(symbol_text, cls.coordinates(data)))} "
                            f"({len(a['coordinates'])} degree"
                            f"{'s' if len(a['coordinates']) > 1 else ''} of freedom{split})"),
                 ("H(0)", fmt(a["H0"]))]
        if run is not None and "drift_H" in run.attrs:
            facts.append(("drift of H, relative to its energy scale",
                          fmt_err(run.attrs["drift_H"])))
        conserved = [k[len("conserved_"):] for k, v in a.items()
                     if k.startswith("conserved_") and v]
        if conserved:  # typeset: A_xy has no spelling in text (the headline is not archived)
            facts.append(("conserved observables", Markup(", ").join(
                equation_html(cls.name_tex(data, f)) for f in conserved)))
        return facts

    @classmethod
    def section_equations(cls, data):
        a = data.analysis
        tex = a["latex"]
        eqs = []
        if a["given"] == "L":
            eqs.append(("Lagrangian", f"L = {tex['L']}"))
            for name, q, m in zip(a["coordinates"], tex["q"], tex["momenta"], strict=True):
                eqs.append(("momentum conjugate to " + symbol_text(name),
                            rf"p_{{{q}}} = {m}"))
            for q, v in zip(tex["q"], tex["velocities"], strict=True):
                eqs.append(("velocity", rf"\dot{{{q}}} = {v}"))
        for i, line in enumerate(split_sum("H", str(tex["H"]))):
            eqs.append(("Hamiltonian" if i == 0 else "", line))
        long = []
        for i, (q, e) in enumerate(zip(tex["q"], tex["qdot"], strict=True)):
            if len(e) > cls.LONGEST_EQUATION:
                long.append(rf"\dot{{{q}}}")
                continue
            eqs.append(("Hamilton's equations: q̇ = ∂H/∂p" if i == 0 else "",
                        rf"\dot{{{q}}} = {e}"))
        for i, (p, e) in enumerate(zip(tex["p"], tex["pdot"], strict=True)):
            if len(e) > cls.LONGEST_EQUATION:
                long.append(dot_tex(p))
                continue
            eqs.append(("ṗ = −∂H/∂q" if i == 0 else "", f"{dot_tex(p)} = {e}"))
        if long:  # named by their left-hand sides; the archive holds them whole
            eqs.append(("too long to read typeset, not shown (the archive holds their TeX)",
                        r",\ ".join(long)))
        for i, name in enumerate(k[len("observable_"):] for k in tex if k.startswith("observable_")):
            eqs.append(("observables" if i == 0 else "",
                        f"{cls.name_tex(data, name)} = {tex['observable_' + name]}"))
        facts = [("H = T(p) + V(q), its kinetic and potential parts split",
                  cls.split_words(a)),
                 ("H depends on t", "yes: H is not conserved" if a["time_dependent"] else
                  "no: H is conserved")]
        if a["given"] == "L":
            facts.append(("max |p − ∂L/∂q̇| along the run",
                          fmt_err(a["legendre_momentum_error"])))
            facts.append(("max |H − (q̇·∂L/∂q̇ − L)| along the run",
                          f"{fmt_err(a['legendre_energy_error'])} (|H| ≤ "
                          f"{fmt(a['legendre_energy_scale'], 4)})"))
            if "legendre_passive_error" in a:
                facts.append(("passive variables q, t, notes (4.8): max |∂H/∂q + ∂L/∂q|, "
                              "|∂H/∂t + ∂L/∂t| along the run",
                              f"{fmt_err(a['legendre_passive_error'])} (|∂L/∂q|, |∂L/∂t| ≤ "
                              f"{fmt(a['legendre_passive_scale'], 4)})"))
        return SectionContent(facts=facts, equations=eqs)



    @staticmethod
    def split_words(a) -> str:
        """Whether H = T(p) + V(q), from the archived structure (no t, every ∂²H/∂q∂p zero):
        the split a symplectic splitting method needs, not separation of variables."""
        if a.get("kinetic_potential_split", False):
            return ("yes: kinetic and potential parts split, so symplectic splitting methods "
                    "apply (a drift by T, a kick by V)")
        if a.get("time_dependent", False):
            return "no: H depends on t"
        return "no: H mixes coordinates and momenta (some ∂²H/∂q∂p ≠ 0)"

    @classmethod
    def section_trajectory(cls, data):
        run = data.runs["main"]
        names = list(data.analysis["coordinates"])
        symbol = cls.axis_labels(data)
        figs = [cls.figure("coordinates", plots.coordinates(run.t, {n: run[n] for n in names},
                                                            labels=symbol),
                           "The coordinates against time.")]
        if len(names) >= 2:
            # a long path fills its region with ink: the first CONFIGURATION_SAMPLES show it
            n = min(len(run.t), cls.CONFIGURATION_SAMPLES)
            part = ("" if n == len(run.t) else
                    f", for t ≤ {fmt(float(run.t[n - 1]), 4)} (of {fmt(float(run.t[-1]))})")
            figs.append(cls.figure("configuration", plots.configuration(
                run[names[0]][:n], run[names[1]][:n], symbol[names[0]], symbol[names[1]]),
                f"The path in the ({symbol_text(names[0])}, {symbol_text(names[1])}) plane of "
                f"configuration space{part}."))
        return SectionContent(figures=figs)

    @classmethod
    def section_phase_portrait(cls, data):
        run = data.runs["main"]
        a = data.analysis
        q = a["coordinates"][0]
        grid = a["phase_grid"]
        symbol = cls.axis_labels(data)
        fig = plots.phase_portrait(run[q], run[f"p_{q}"], grid["q"], grid["p"], grid["H"],
                                   a["H0"], q, angle=q in list(a.get("angles", [])),
                                   labels=(symbol[q], symbol[f"p_{q}"]))
        return SectionContent(figures=[cls.figure(
            "phase_portrait", fig, f"Level curves of H in the plane of {symbol_text(q)} and its "
                                   "conjugate momentum; the run's orbit on its level H = H(0) "
                                   "(highlighted).")])

    @classmethod
    def section_poincare(cls, data):
        a = data.analysis
        pts = a["poincare"]
        s_col, value, direction = a["poincare_surface"]
        u, v = a["poincare_axes"]
        symbol = cls.axis_labels(data)
        fig = plots.poincare(pts["u"], pts["v"], symbol[u], symbol[v])
        facts = [("crossings", str(len(pts["u"])))]
        on_surface = ""
        if "poincare_H_relative_error" in a:
            error = fmt_err(a["poincare_H_relative_error"])
            facts.append(("max |H − H(0)| at the crossings, relative to the energy scale",
                          error))
            on_surface = (f"; every crossing lies on the energy surface H = H(0) to {error} of "
                          "the energy scale")
        if not cls.plane_map(data):
            shape = ("The section of a system of more than two degrees of freedom is not a "
                     "plane: the figure projects the crossings onto two of their coordinates. "
                     if len(cls.coordinates(data)) > 2 else
                     "H depends on t, so there is no energy surface: the figure projects the "
                     "crossings onto two of their coordinates. ")
        else:
            shape = {"chaotic": "This orbit is chaotic (its behaviour, above): its crossings "
                                "scatter over an area of the section instead of lying on a "
                                "curve, as a regular orbit's would. ",
                     "regular": "This orbit is regular (quasi-periodic; its behaviour, above): "
                                "its crossings lie on a closed curve, or a chain of islands, "
                                "and fill it in as they accumulate. "}.get(
                cls.prose_case(data)["behaviour"],
                "A regular (quasi-periodic) orbit crosses the surface on a closed "
                "curve; a chaotic one scatters over an area. ")
        return SectionContent(
            figures=[cls.figure("poincare", fig,
                                cls.surface_words(data, s_col, value, direction, u, v)
                                + f" at each of the {len(pts['u'])} crossings{on_surface}.")],
            facts=facts,
            notes=[shape + cls.located_words(data)] if len(pts["u"]) else
                  ["The orbit did not cross the surface of section during the run."])

    @staticmethod
    def located_words(data) -> str:
        """How the crossings were found: on the integrator's steps, or between samples."""
        run = data.runs["main"]
        if str(data.analysis.get("poincare_located", "samples")) == "steps":
            return ("Each crossing is located during the integration, by root finding on the "
                    "continuous extension (dense output) of the DOP853 step that crosses the "
                    "surface, to rounding in the step's time: the crossings are as accurate as "
                    "the steps whatever the number of stored samples (Hairer, Nørsett & Wanner "
                    "§II.6).")
        return (f"The run's method ({method_words(run.attrs.get('method', ''))}) has no "
                "continuous extension "
                "here: each crossing is located between stored samples by cubic Hermite "
                "interpolation with the derivatives from Hamilton's equations, so its "
                "accuracy depends on the sampling.")

    @classmethod
    def section_invariants(cls, data):
        a = data.analysis
        content = cls.invariants_section(
            data, labels={n: f"${cls.name_tex(data, n)}$" for n in data.runs["main"].invariants},
            time_unit=cls.UNITS,
            caption="Drift of H and of every conserved quantity (observables whose total "
                    "time derivative {f, H} + ∂f/∂t simplifies to zero, the momenta of cyclic "
                    "coordinates), each relative to its scale.")
        content.tables = []  # the kind's template typesets it (symbol_tables: its names)
        cls.relabel_drift(content)
        moving = a.get("observables")
        if moving:
            run = data.runs["main"]
            content.figures.append(cls.figure(
                "observables", plots.observables(
                    run.t, {f"${cls.name_tex(data, f)}$": v for f, v in moving.items()}),
                "Observables that are not conserved ({f, H} + ∂f/∂t ≠ 0), against time."))
        return content
