"""``hamiltonian`` report: the equations, the trajectory, the phase portrait or surface of
section (one orbit's, or a sweep's many), the conserved quantities, the Poisson brackets,
a canonical transformation and the Hamilton–Jacobi comparison, from the archive alone."""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from ...scene.report import Report, section_colours, section_point_notes
from .config import JACOBI_SAMPLES, STUDY_STEPS, family_energy
from .results import SCHEMA

common_plots = lazy_module("reportgen.rendering.plots.common")
plots = lazy_module("reportgen.kinds.hamiltonian.plots")
section_plots = lazy_module("reportgen.rendering.plots.sections")


class HamiltonianReport(Report):
    """The sections of a formula system, drawn from the archive alone."""

    schema = SCHEMA
    study_horizon_reason = (f"it covers at most {STUDY_STEPS} steps of the main run, since "
                            "long runs would spend most of their time on references, and in a "
                            "chaotic system errors that have grown to the size of the orbit "
                            "compare nothing.")
    sections = (
        Section("equations", "The system and its equations of motion"),
        Section("trajectory", "Trajectory", integrates=True),
        Section("phase_portrait", "Phase portrait", integrates=True),
        Section("poincare", "Surface of section", integrates=True),
        Section("invariants", "Conserved quantities", integrates=True),
        Section("brackets", "Poisson brackets and symmetries", integrates=True),
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
                            "initial_state_*")  # shown by name: initial_<column>

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

    @staticmethod
    def symbols(data) -> dict[str, str]:
        """Each state column's symbol for an axis label ("$p_{\\theta}$"), from the TeX
        the simulation stored (``/analysis/latex`` q and p), not the config's name."""
        a = data.analysis
        names, tex = list(a["coordinates"]), a["latex"]
        symbol = {n: f"${t}$" for n, t in zip(names, tex["q"], strict=True)}
        symbol.update({f"p_{n}": f"${t}$" for n, t in zip(names, tex["p"], strict=True)})
        return symbol

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        a = data.analysis
        if "phase_grid" not in a:
            names.remove("phase_portrait")
        if "transform" not in a:
            names.remove("transform")
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
            pts.columns["u"], pts.columns["v"], member, colour, uname, vname,
            colour_label=key, labels=labels,
            edge=None if edge is None else (edge["u"], edge["v"], edge["H"],
                                            a["poincare_edge_energy"]),
            edge_label=None if edge is None else
            f"{a['poincare_edge_momentum']} = 0 on H = {fmt(a['poincare_edge_energy'], 6)}")
        which = {"up": f"with {s_col} increasing", "down": f"with {s_col} decreasing",
                 "both": "in either direction"}[direction]
        facts = [("orbits", f"{len(crossing)} of {sweep.size} members cross the surface"),
                 ("crossings drawn", f"{len(member)} ({int(kept[crossing].min())} to "
                                     f"{int(kept[crossing].max())} per orbit)")]
        h_error = sweep.analysis.get("poincare_H_error")
        if h_error is not None and np.any(np.isfinite(h_error)):
            facts.append(("max |H − H(0)| at the crossings, over the members",
                          fmt_err(float(np.nanmax(h_error)))))
        energy = family_energy(sweep)
        if energy is not None:
            facts.append(("energy of every orbit", f"H = {fmt(energy, 12)}"))
        notes = ["A regular (quasi-periodic) orbit crosses the surface on a closed curve: an "
                 "island around a stable periodic orbit or a curve across the section; a "
                 "chaotic orbit scatters over an area, the chaotic sea between the islands."]
        notes += section_point_notes(sweep, "poincare", kept, "cross the surface")
        caption = (f"Surface of section {s_col} = {value} crossed {which}: ({uname}, {vname}) "
                   f"at the crossings of {len(crossing)} orbits, each orbit in its own colour "
                   + (f"(keyed to {key})" if labels is None else "(legend)")
                   + (f"; the closed curve: the edge of the allowed region, where "
                      f"{a['poincare_edge_momentum']} = 0" if edge is not None else "") + ".")
        return SectionContent(figures=[cls.figure("poincare_family", fig, caption)],
                              facts=facts, notes=notes)

    # ------------------------------------------------------------------ report side
    @classmethod
    def headline(cls, data):
        a = data.analysis
        run = data.runs.get("main")
        facts = [("system", f"{'L' if a['given'] == 'L' else 'H'} in "
                            f"{', '.join(a['coordinates'])} ({len(a['coordinates'])} degree"
                            f"{'s' if len(a['coordinates']) > 1 else ''} of freedom"
                            f"{', separable' if a['separable'] else ''})"),
                 ("H(0)", fmt(a["H0"], 14))]
        if run is not None and "drift_H" in run.attrs:
            facts.append(("relative drift of H", fmt_err(run.attrs["drift_H"])))
        conserved = [k[len("conserved_"):] for k, v in a.items()
                     if k.startswith("conserved_") and v]
        if conserved:
            facts.append(("conserved observables", ", ".join(conserved)))
        return facts

    @classmethod
    def section_equations(cls, data):
        a = data.analysis
        tex = a["latex"]
        eqs = []
        if a["given"] == "L":
            eqs.append(("Lagrangian", f"L = {tex['L']}"))
            for q, m in zip(tex["q"], tex["momenta"], strict=True):
                eqs.append((f"momentum conjugate to {q}", rf"p_{{{q}}} = {m}"))
            for q, v in zip(tex["q"], tex["velocities"], strict=True):
                eqs.append(("velocity", rf"\dot{{{q}}} = {v}"))
        eqs.append(("Hamiltonian", f"H = {tex['H']}"))
        long = []
        for i, (q, e) in enumerate(zip(tex["q"], tex["qdot"], strict=True)):
            if len(e) > cls.LONGEST_EQUATION:
                long.append(f"q̇ of {q}")
                continue
            eqs.append(("Hamilton's equations: q̇ = ∂H/∂p" if i == 0 else "",
                        rf"\dot{{{q}}} = {e}"))
        for i, (p, e) in enumerate(zip(tex["p"], tex["pdot"], strict=True)):
            if len(e) > cls.LONGEST_EQUATION:
                long.append(f"ṗ of {p}")
                continue
            eqs.append(("ṗ = −∂H/∂q" if i == 0 else "", rf"\dot{{{p}}} = {e}"))
        for i, name in enumerate(k[len("observable_"):] for k in tex if k.startswith("observable_")):
            eqs.append(("observables" if i == 0 else "", f"{name} = {tex['observable_' + name]}"))
        facts = [("H separable (T(p) + V(q))", "yes: symplectic splitting methods apply"
                  if a["separable"] else "no"),
                 ("H depends on t", "yes: H is not conserved" if a["time_dependent"] else "no")]
        if a["given"] == "L":
            facts.append(("max |p − ∂L/∂q̇| along the run",
                          fmt_err(a["legendre_momentum_error"])))
            facts.append(("max |H − (q̇·∂L/∂q̇ − L)| along the run",
                          f"{fmt_err(a['legendre_energy_error'])} (|H| ≤ "
                          f"{fmt(a['legendre_energy_scale'], 4)})"))
        notes = [f"Too long to read when typeset, and not shown: {', '.join(long)} (the "
                 "derivatives of H above; their TeX is in the archive, /analysis/latex)."] \
            if long else []
        return SectionContent(facts=facts, equations=eqs, notes=notes)

    @classmethod
    def section_trajectory(cls, data):
        run = data.runs["main"]
        names = list(data.analysis["coordinates"])
        symbol = cls.symbols(data)
        figs = [cls.figure("coordinates", plots.coordinates(run.t, {n: run[n] for n in names},
                                                            labels=symbol),
                           "The coordinates against time.")]
        if len(names) >= 2:
            # a long path fills its region with ink: the first CONFIGURATION_SAMPLES show it
            n = min(len(run.t), cls.CONFIGURATION_SAMPLES)
            part = ("" if n == len(run.t) else
                    f", for t ≤ {fmt(float(run.t[n - 1]), 4)} (of {fmt(float(run.t[-1]), 6)})")
            figs.append(cls.figure("configuration", plots.configuration(
                run[names[0]][:n], run[names[1]][:n], symbol[names[0]], symbol[names[1]]),
                f"The path in the ({names[0]}, {names[1]}) plane of configuration space{part}."))
        return SectionContent(figures=figs)

    @classmethod
    def section_phase_portrait(cls, data):
        run = data.runs["main"]
        a = data.analysis
        q = a["coordinates"][0]
        grid = a["phase_grid"]
        symbol = cls.symbols(data)
        fig = plots.phase_portrait(run[q], run[f"p_{q}"], grid["q"], grid["p"], grid["H"],
                                   a["H0"], q, angle=q in list(a.get("angles", [])),
                                   labels=(symbol[q], symbol[f"p_{q}"]))
        return SectionContent(figures=[cls.figure(
            "phase_portrait", fig, f"Level curves of H in the ({q}, p_{q}) plane; the run's "
                                   "orbit on its level H = H(0) (highlighted).")])

    @classmethod
    def section_poincare(cls, data):
        a = data.analysis
        pts = a["poincare"]
        s_col, value, direction = a["poincare_surface"]
        u, v = a["poincare_axes"]
        symbol = cls.symbols(data)
        fig = plots.poincare(pts["u"], pts["v"], symbol[u], symbol[v])
        which = {"up": f"with {s_col} increasing", "down": f"with {s_col} decreasing",
                 "both": "in either direction"}[direction]
        return SectionContent(
            figures=[cls.figure("poincare", fig,
                                f"Surface of section {s_col} = {value} crossed {which}: "
                                f"({u}, {v}) at each of the {len(pts['u'])} crossings.")],
            facts=[("crossings", str(len(pts["u"])))],
            notes=["A regular (quasi-periodic) orbit crosses the surface on a closed curve; a "
                   "chaotic one scatters over an area. Crossings are located between stored "
                   "samples by cubic Hermite interpolation with the derivatives from "
                   "Hamilton's equations."] if len(pts["u"]) else
                  ["The orbit did not cross the surface of section during the run."])

    @classmethod
    def section_invariants(cls, data):
        a = data.analysis
        content = cls.invariants_section(
            data, caption="Relative drift of H and of every conserved quantity: observables "
                          "whose total time derivative {f, H} + ∂f/∂t simplifies to zero, and "
                          "the momenta of cyclic coordinates.")
        moving = a.get("observables")
        if moving:
            run = data.runs["main"]
            content.figures.append(cls.figure(
                "observables", plots.observables(run.t, moving),
                "Observables that are not conserved ({f, H} + ∂f/∂t ≠ 0), against time."))
        return content

    @classmethod
    def section_brackets(cls, data):
        a = data.analysis
        rows = []
        for key, value in a.items():
            if key.startswith("poisson_") and not key.endswith(("_latex", "_max")):
                name = key[len("poisson_"):]
                rows.append([name, value, "yes" if a[f"conserved_{name}"] else "no",
                             fmt_err(a[f"poisson_{name}_max"])])
        tables = []
        if rows:
            tables.append(Table(
                caption="{f, H} = Σ ∂f/∂q ∂H/∂p − ∂f/∂p ∂H/∂q, simplified by SymPy (archived as "
                        "/analysis attrs poisson_<name>); conserved when {f, H} + ∂f/∂t = 0. "
                        "The last column evaluates {f, H} along the run.",
                header=["observable f", "{f, H}", "conserved", "max |{f, H}| on the run"],
                rows=rows))
        pairs = a.get("pair_brackets")
        if pairs:
            tables.append(Table(caption="Brackets between the observables, simplified.",
                                 header=["f", "g", "{f, g}"],
                                 rows=[list(r) for r in zip(pairs["f"], pairs["g"],
                                                            pairs["bracket"], strict=True)]))
        cyclic = list(a["cyclic"])
        f, g, h = a["jacobi_triple"]
        facts = [("cyclic coordinates", ", ".join(cyclic) + " (their momenta "
                  + ", ".join(f"p_{c}" for c in cyclic) + " are conserved)" if cyclic
                  else "none"),
                 ("Jacobi identity {f,{g,h}} + {g,{h,f}} + {h,{f,g}}",
                  f"max {fmt_err(a['jacobi_max'])} on {cls.JACOBI_SAMPLES} samples of the run "
                  f"(terms up to {fmt(a['jacobi_scale'], 3)}), f = {f}, g = {g}, h = {h}")]
        return SectionContent(facts=facts, tables=tables)


    @classmethod
    def section_transform(cls, data):
        a = data.analysis
        tr = a["transform"]
        new = list(a["transform_new"])
        n = len(new) // 2
        run = data.runs.get("transformed")
        series = {new[i]: tr["Q"][:, i] for i in range(n)}
        series.update({new[n + i]: tr["P"][:, i] for i in range(n)})
        fig = plots.new_variables(data.runs["main"].t, series,
                                  run[new[0]] if run is not None else None, new[0])
        eqs = [("generating function and relations" if i == 0 else "", line)
               for i, line in enumerate(a["transform_latex"])]
        if a["transform_K_latex"]:
            eqs.append(("K in the new variables", f"K = {a['transform_K_latex']}"))
        facts = [("max |MᵀJM − J| along the run (M = ∂(Q, P)/∂(q, p))",
                  fmt_err(a["transform_defect_max"])),
                 ("max |{Qᵢ, Pⱼ} − δᵢⱼ|, |{Qᵢ, Qⱼ}|, |{Pᵢ, Pⱼ}|",
                  fmt_err(a["transform_bracket_max"]))]
        if run is not None:
            facts.append(("max |(Q, P) from integrating K − (Q, P) of the H orbit|",
                          fmt_err(a["transform_run_difference"])))
        else:
            facts.append(("K in closed form", "not found (the old variables are not linear "
                          "in the new ones); K = H + ∂F/∂t is evaluated along the run"))
        caption = ("The new variables along the integrated orbit" +
                   (f"; dashed: {new[0]} from integrating K's own Hamilton equations from "
                    "(Q0, P0)." if run is not None else "."))
        return SectionContent(figures=[cls.figure("new_variables", fig, caption)],
                              equations=eqs, facts=facts)

    @classmethod
    def section_hamilton_jacobi(cls, data):
        a = data.analysis
        hj = a["hamilton_jacobi"]
        run = data.runs["main"]
        fig = common_plots.error_against_time(
            run.t, {f"|{c}_HJ − {c}|": d for c, d in hj["difference"].items()},
            time_unit="time units", ylabel="quadrature − integration")
        rows = [[k, fmt(v, 14), fmt_err(a["hj_constant_drift"][k])]
                for k, v in a["hj_constants"].items()]
        which = ("Kepler's equation for t(r) (∂W/∂E), the argument of latitude (∂W/∂L) and the "
                 "node (∂W/∂L_z)" if a["hj_separation"] == "central" else
                 "Charlier's quadratures in the fictitious time dt = m a²(cosh²ξ − cos²η) dτ, "
                 "each coordinate through its turning points")
        return SectionContent(
            figures=[cls.figure("hj_difference", fig,
                                f"The quadrature solution ({which}) minus the integration.")],
            tables=[Table(caption="The separated constants at t = 0 and their relative drift "
                                  "along the integration.",
                          header=["constant", "value", "max relative drift"], rows=rows)],
            facts=[("max |quadrature − integration|", fmt_err(a["hj_max_difference"]))])
