"""``normal_modes`` report: the spectrum, the mode shapes, the counting of the modes and
the time evolution, drawn from the archive alone."""

from __future__ import annotations

import re

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from ...scene.report import Report
from ...scene.schema import ResultsSchema, unit_text
from .config import SHAPES_SHOWN, STIFF_RATIO, system_of, unit_system
from .report_potential import PotentialReport
from .results import MOLECULAR_OMEGA, SCHEMA, schema_for, units

plots = lazy_module("reportgen.kinds.normal_modes.plots")
common_plots = lazy_module("reportgen.rendering.plots.common")


class NormalModesReport(PotentialReport, Report):
    """The normal modes' sections; units follow the system's (:func:`schema_for`)."""

    schema = SCHEMA
    gallery_figures = ("modes",)

    @classmethod
    def gallery_headline(cls, data):
        from ...scene import gallery
        omega = np.asarray(data.analysis.get("frequencies", ()), dtype=float)
        top = float(np.max(omega, initial=0.0))
        omega = np.sort(omega[np.isfinite(omega) & (omega > 1e-9 * top)])
        if omega.size == 0:
            return super().gallery_headline(data)
        check = gallery.worst_check(data, "ω")
        symbol, unit = "ω", cls._omega_unit(data)
        if "wavenumbers" in data.analysis:  # a molecule: its spectrum in cm⁻¹
            nu = np.asarray(data.analysis["wavenumbers"], dtype=float)
            omega, symbol, unit = np.sort(nu[nu > 1e-9 * float(np.max(nu))]), "ν̃", "cm⁻¹"
        values, counts = np.unique(np.round(omega, 6), return_counts=True)
        shown = [fmt(float(v), 6) + (f" (×{c})" if c > 1 else "")
                 for v, c in zip(values[:5], counts[:5], strict=True)]
        unit = ("per time unit" if "time unit" in unit
                else "(dimensionless)" if unit == "dimensionless" else unit)
        text = (f"{omega.size} mode{'s' if omega.size != 1 else ''}: {symbol} = "
                f"{', '.join(shown)}" + (", …" if values.size > 5 else "")
                + (f" {unit}" if unit else ""))
        return text + (f"; {gallery.from_reference(check.rel_error, 'the closed form')}"
                       if check is not None else "")

    family_sections = (
        Section("frequencies_family", "Eigenfrequencies across the family",
                description="Each member's eigenfrequencies against the swept value, with "
                            "the closed form where the system has one."),
    )
    sections = (
        Section("equilibrium", "Equilibrium and the expansion of U",
                description="a written potential's stationary point found from the guess, "
                            "its stability, and M and A = ∂²U/∂q∂q there"),
        Section("spectrum", "Frequency spectrum",
                description="eigenfrequencies ω of A η = ω² M η, ascending, with their types"),
        Section("mode_shapes", "Mode shapes",
                description="displacement pattern of every vibration, with phase snapshots"),
        Section("counting", "Counting the modes",
                description="rigid-body zero modes and the 3n−6 / 3n−5 vibrations"),
        Section("evolution", "Time evolution: modal superposition against integration",
                integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def section_frequencies_family(cls, data):
        sweep = data.sweep
        path, x = next(iter(sweep.values.items()))
        a, ok = sweep.analysis, sweep.ok

        def spectrum(name):
            cols = sorted((int(k.rsplit("_", 1)[1]), k) for k in a
                          if k.rsplit("_", 1)[0] == name and k.rsplit("_", 1)[1].isdigit())
            return [a[k][ok] for _, k in cols]

        numeric, exact = spectrum("frequencies"), spectrum("frequencies_exact")
        fig = common_plots.family_lines(x[ok], numeric, reference=exact or None,
                                        xlabel=cls.config_quantity(data, path).label(),
                                        ylabel=cls._schema(data).label("frequencies"),
                                        label="ω", reference_label="closed form")
        facts = [("modes", str(len(numeric)))]
        if exact:
            worst = max(float(np.max(np.abs(n / e - 1))) for n, e in zip(numeric, exact,
                                                                         strict=True))
            facts.append(("max relative difference to the closed form", fmt_err(worst)))
        return SectionContent(figures=[cls.figure(
            "frequencies_family", fig, "Eigenfrequencies ωⱼ of every member against "
            f"{cls.config_words(data, path)}"
            + ("; dashed: the closed form." if exact else "."))], facts=facts)

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        if data.analysis["source"] != "molecule":
            names.remove("counting")
        if data.analysis["source"] != "potential":
            names.remove("equilibrium")
        if "main" not in data.runs:
            names = [n for n in names if n not in ("evolution", "error_vs_runtime")]
        return names

    @staticmethod
    def _schema(data) -> ResultsSchema:
        """The declared results in the units of this archive's system."""
        analysis = getattr(data, "analysis", None) or {}
        system, coordinates = analysis.get("unit_system"), analysis.get("coordinate_unit")
        if getattr(data, "sweep", None) is not None:  # a family keeps no strings: its config's
            system = unit_system(data.config)
            if system_of(data.config) == "potential":
                coordinates = data.config.system.get("coordinate_unit")
        return schema_for(system_of(data.config), system=system, coordinate_unit=coordinates)

    @classmethod
    def result_quantity(cls, data, name):
        """A declared result in this archive's units (a family's too), else the shared
        reading."""
        try:
            return cls._schema(data).quantity(name)
        except KeyError:
            return super().result_quantity(data, name)

    @staticmethod
    def _in_tau(data) -> bool:
        """Whether this archive's times are in the molecular unit τ = √(u/(mdyn/Å))."""
        return (getattr(data, "analysis", None) or {}).get("unit_system") == "molecular"

    @classmethod
    def time_unit_words(cls, data) -> str:
        """The time unit of this archive's unit system: "τ" in molecular units (the page
        says τ = 4.075 fs where it gives the units), "s" for pendula, "" when
        dimensionless; not the kind's generic one."""
        if cls._in_tau(data):
            return "τ"
        unit = unit_text(cls._schema(data).time.unit)
        return "" if unit == "dimensionless" else unit

    @classmethod
    def run_end_words(cls, data) -> str:
        """The end of the evolution, "t = 203.7 fs" in molecular units (t_end is kept in
        τ, one number times a unit), else the shared wording."""
        if cls._in_tau(data):
            return f"t = {fmt(float(data.config.run.t_end) * FS_PER_TAU, 4)} fs"
        return super().run_end_words(data)

    @classmethod
    def check_words(cls, data, text: str) -> str:
        """A check's archived name in words, its ``t_end`` in femtoseconds in molecular
        units."""
        if cls._in_tau(data) and data.config.run is not None:
            text = re.sub(r"(?<![\w.])t_end(?!\w)",
                          cls.run_end_words(data).replace(" ", "\u00a0"), str(text))
        return super().check_words(data, text)

    @staticmethod
    def _units(data) -> dict[str, str]:
        """This archive's units as printed ("dimensionless" for a pure number)."""
        a = data.analysis
        return {k: unit_text(v) for k, v in units(a["source"], a.get("unit_system"),
                                                  a.get("coordinate_unit")).items()}

    @staticmethod
    def _with_unit(text: str, unit: str) -> str:
        """``text [unit]``, or ``text (dimensionless)``."""
        return f"{text} (dimensionless)" if unit == "dimensionless" else f"{text} [{unit}]"

    @staticmethod
    def _vib(data):
        a = data.analysis
        z = int(a["n_zero_modes"])
        return z, np.asarray(a["frequencies"])[z:], list(a["mode_type"])[z:]

    @classmethod
    def prose_case(cls, data):
        """Whether the system is a molecule (its valence force field explained) or pendula,
        a chain or given matrices."""
        a = data.analysis
        return {"molecule": a.get("source") == "molecule", "linear": bool(a.get("linear")),
                "potential": a.get("source") == "potential",
                "lagrangian": a.get("given") == "L",
                "neutral": a.get("equilibrium_stability") == "neutral"}

    @classmethod
    def describe(cls, data):
        """``A linear triatomic molecule, CO₂: 3 atoms, 2 bonds, 1 bending angle``."""
        a = data.analysis
        if a["source"] == "molecule":
            n = len(a["masses"])
            size = {1: "monatomic", 2: "diatomic", 3: "triatomic", 4: "four-atom"}.get(
                n, f"{n}-atom")
            shape = "linear" if a["linear"] else "non-linear"
            name = formula([atom.element for atom in data.config.atoms])
            return (f"A {shape} {size} molecule{', ' + name if name else ''}: "
                    f"{counted(n, 'atom')}, {counted(len(a['bonds']), 'bond')}, "
                    f"{counted(len(a['angles']), 'bending angle')}; its small oscillations "
                    "about equilibrium")
        n = int(a["n_dof"])
        if a["source"] == "chain":
            ends = data.config.chain.ends
            return (f"Small oscillations of a chain of {n} equal mass{'es' if n != 1 else ''} "
                    + ("between fixed walls" if ends == "fixed" else "with free ends"))
        if a["source"] == "pendula":
            return (f"Small oscillations of {n} pendula coupled by springs" if n != 1
                    else "Small oscillations of a pendulum")
        if a["source"] == "potential":
            return cls.potential_describe(data)
        return f"Small oscillations of a system given by its matrices M and A ({n} coordinates)"

    @classmethod
    def headline(cls, data):
        a = data.analysis
        z, w, types = cls._vib(data)
        out = [("system", cls._describe(a)),
               ("vibrations", f"{int(a['n_vibrational'])} of {int(a['n_dof'])} coordinates "
                              f"({z} zero modes)")]
        if a["source"] == "potential":
            out += cls.potential_headline(data)
        if a.get("linear") and "n_longitudinal" in a:
            out.append(("along and across the axis",
                        f"{int(a['n_longitudinal'])} longitudinal (n − 1), "
                        f"{int(a['n_transverse'])} transverse (2(n − 2))"))
        if w.size:
            unit = cls._omega_unit(data)
            out.append(("frequencies ω", ", ".join(fmt(x) for x in w[:8]) +
                        (" …" if w.size > 8 else "")
                        + (" (dimensionless)" if unit == "dimensionless" else f" {unit}")))
        if "wavenumbers" in a and w.size:
            nu = np.asarray(a["wavenumbers"])[z:]
            out.append(("wavenumbers ν̃ = ω/2πc", ", ".join(fmt(x, 4) for x in nu[:8])
                        + (" …" if nu.size > 8 else "") + " cm⁻¹"))
        if "unit_system" in a:
            out.append(("units", UNIT_WORDS["SI, rad"] if a.get("coordinate_unit") == "rad"
                        else UNIT_WORDS[str(a["unit_system"])]))
        if "closed_form_max_rel_error" in a:
            out.append(("max relative error against the closed form",
                        fmt_err(a["closed_form_max_rel_error"])))
        if "evolution_max_error" in a:
            q_unit = cls._units(data)["q"]
            out.append(("evolution: max |q − q(modal)|, q integrated",
                        fmt_err(a["evolution_max_error"])
                        + ("" if q_unit == "dimensionless" else f" {q_unit}")))
            if a.get("stiff"):
                out.append(("stiffness", a["stiff_reason"]))
        return out

    @staticmethod
    def _describe(a) -> str:
        src = a["source"]
        if src == "molecule":
            n = len(a["masses"])
            return (f"{'linear' if a['linear'] else 'non-linear'} molecule, "
                    f"{counted(n, 'atom')}, {counted(len(a['bonds']), 'bond')}, "
                    f"{counted(len(a['angles']), 'bending angle')}")
        if src == "chain":
            return f"chain of {int(a['n_dof'])} masses"
        if src == "pendula":
            return f"{int(a['n_dof'])} coupled pendula"
        if src == "potential":
            return {"L": "a Lagrangian", "T": "a potential and a kinetic energy",
                    "M": "a potential and a mass matrix"}[str(a["given"])] + (
                f" in {int(a['n_dof'])} coordinates")
        return f"M and A given ({int(a['n_dof'])} coordinates)"

    @classmethod
    def section_spectrum(cls, data):
        a = data.analysis
        z, w, types = cls._vib(data)
        groups = np.asarray(a["degenerate_group"])[z:]
        exact = a.get("frequencies_exact")
        u = cls._units(data)
        nu = np.asarray(a["wavenumbers"])[z:] if "wavenumbers" in a else None
        if nu is not None:  # a molecule: the spectroscopist's axis
            fig = plots.spectrum(nu, types, groups, unit="cm⁻¹", quantity="wavenumber",
                                 named=a["source"] == "molecule")
        else:
            fig = plots.spectrum(w, types, groups, exact=None if exact is None else
                                 np.asarray(exact)[z:], unit=u["omega"],
                                 named=a["source"] == "molecule")
        rows = []
        w2 = np.asarray(a["omega_squared"])[z:]
        parity = list(a["mode_parity"])[z:] if "mode_parity" in a else None
        shares = cls._named_shares(data)
        for i, (wi, t) in enumerate(zip(w, types, strict=True)):
            g = int(np.sum(groups == groups[i]))
            row = [str(z + i + 1), fmt(wi), fmt(w2[i])]
            row += [fmt(float(nu[i]), 5)] if nu is not None else []
            row += [t, str(g)]
            row += [shares[i]] if shares else []
            row += [PARITY_WORDS.get(str(parity[i]), "—")] if parity is not None else []
            if exact is not None:
                ex = float(np.asarray(exact)[z + i])
                row += [fmt(ex), fmt_err(abs(wi - ex) / ex if ex else abs(wi))]
            rows.append(row)
        header = ["mode", cls._with_unit("ω", u["omega"]), cls._with_unit("ω²", u["omega2"])]
        header += ["ν̃ [cm⁻¹]"] if nu is not None else []
        header += ["type", "degeneracy"]
        header += ["share of V"] if shares else []
        header += ["inversion"] if parity is not None else []
        if exact is not None:
            header += ["closed form", "relative error"]
        facts = [("eigenproblem", "A η = ω² M η (scipy's symmetric-definite eigensolver on "
                                  "the pair), ηᵀ M η = 1"),
                 ("textbook three steps (diagonalize M, unit mass, diagonalize A′): "
                  "max |Δω²|/ω²ₘₐₓ", fmt_err(a["three_step_max_difference"])),
                 ("max |ηᵀ M η − 1|", fmt_err(a["orthonormality_error"]))]
        if w.size > 1:
            facts.append(("ωₘₐₓ/ωₘᵢₙ", fmt(a["stiffness_ratio"])))
        if exact is not None:
            facts.append(("closed form", str(a["closed_form_source"])))
        if shares:
            facts.append(("type", cls._naming_words(data)))
        if parity is not None:
            facts.append(("inversion", "the molecule and its force field have a centre of "
                                       "symmetry: each mode is even (g) or odd (u) when every "
                                       "position from the centre of mass is reversed"))
        return SectionContent(
            figures=[cls.figure("spectrum", fig, (
                "Vibrational wavenumbers ν̃ = ω/2πc" if nu is not None
                else "Vibrational frequencies") + "; bar height is the degeneracy"
                + ("; hollow circles: closed form." if exact is not None and nu is None
                   else "."))],
            tables=[Table("Vibrational modes (zero modes omitted), ascending ω", header, rows)],
            facts=facts)

    @staticmethod
    def _named_shares(data) -> list[str]:
        """Per vibration, the share of its potential energy in the class of internal
        coordinates that names it ("81 %"; a mixed one: its two largest, "48 %, 45 %");
        [] without the potential-energy distribution."""
        a = data.analysis
        if "coordinate_shares" not in a:
            return []
        rows = np.atleast_2d(np.asarray(a["coordinate_shares"], dtype=float))
        threshold = float(a["dominant_share"])
        out = []
        for row in rows:
            top = np.sort(row)[::-1]
            shown = top[:1] if top[0] >= threshold or top.size == 1 else top[:2]
            out.append(", ".join(f"{fmt(round(100 * float(x)), 3)} %" for x in shown))
        return out

    @staticmethod
    def _naming_words(data) -> str:
        """How the vibrations are named, with this molecule's symmetry and the threshold."""
        a = data.analysis
        share = fmt(round(100 * float(a["dominant_share"])), 3)
        rule = ("named by the class of like internal coordinates (the stretches of like "
                f"bonds, the bends of like angles) holding at least {share} % of the "
                "vibration's potential energy, mixed when none does; ")
        if a.get("centre_of_inversion"):
            return rule + ("this molecule has a centre of inversion, so a stretch or bend "
                           "is symmetric when even (g) under it, antisymmetric when odd (u)")
        return rule + ("this molecule has no centre of inversion: a stretch or bend of like "
                       "coordinates is symmetric when they change by equal amounts, "
                       "antisymmetric when their changes sum to zero")

    @classmethod
    def _omega_unit(cls, data) -> str:
        """The frequencies' unit as printed: rad/s for a system given in SI, else per
        time unit of the config's own units."""
        return unit_text(cls._schema(data).result("frequencies").unit)

    @classmethod
    def _frequency_titles(cls, data, digits: int = 5) -> list[str]:
        """Each vibration's frequency as a panel title: "mode 9, 2494 cm⁻¹" for a molecule
        with wavenumbers (the figures' fonts draw no ν̃), else "ω1 = 3.1321 rad/s" (no unit
        when dimensionless)."""
        a = data.analysis
        z, w, _ = cls._vib(data)
        if "wavenumbers" in a:
            nu = np.asarray(a["wavenumbers"])[z:]
            return [f"mode {z + i + 1}, {fmt(float(x), 4)} cm⁻¹" for i, x in enumerate(nu)]
        unit = cls._omega_unit(data)
        unit = "" if unit == "dimensionless" else f" {unit}"
        return [f"ω{z + i + 1} = {fmt(float(x), digits)}{unit}" for i, x in enumerate(w)]

    @classmethod
    def _titles(cls, data):
        _, _, types = cls._vib(data)
        # a long type goes under the frequency: two panels side by side share the width
        return [f"{f}: {t}" if len(t) <= 24 else f"{f}\n{t}"
                for f, t in zip(cls._frequency_titles(data), types, strict=True)]

    @classmethod
    def section_mode_shapes(cls, data):
        a = data.analysis
        z, w, _ = cls._vib(data)
        modes = np.asarray(a["modes"])[:, z:]
        titles = cls._titles(data)
        figs = []
        src = a["source"]
        if src == "molecule":
            pos = np.asarray(a["drawing"]["positions"])
            disps = list(np.asarray(a["drawing"]["displacements"]))
            bonds = [tuple(b) for b in np.asarray(a["bonds"]).tolist()]
            # an atom given by its mass alone ("X" in the archive) is labelled by its number
            # in the configuration, so the mode shapes say which atom moves
            elems = [str(e) if str(e) != "X" else str(i + 1)
                     for i, e in enumerate(a["elements"])]
            numbered = any(str(e) == "X" for e in a["elements"])
            fig = plots.molecule_modes(pos[:, :2], a["masses"], elems, bonds, disps, titles)
            figs.append(cls.figure("modes", fig, "Each vibration at equilibrium: arrows are the "
                                   "mass-normalized displacement η (scaled to be visible); faint "
                                   "atoms the extreme phases ωt = 0, π; ⊙/⊗ motion toward/away "
                                   "from the viewer."
                                   + (" Atoms without an element are numbered in the order "
                                      "of the configuration." if numbered else "")))
            shown = min(len(disps), 6)
            snap = plots.molecule_snapshots(pos, a["masses"], elems, bonds, disps[:shown],
                                            cls._frequency_titles(data, 4)[:shown])
            figs.append(cls.figure("snapshots", snap, "Phase snapshots over half a period: "
                                   "x(t) = x₀ + η cos ωt for ωt from 0 to π (faint: equilibrium)."))
        elif src in ("chain", "pendula"):
            shown = min(modes.shape[1], SHAPES_SHOWN)
            waves = a.get("standing_waves")
            exact = None if waves is None else (np.asarray(waves["s"]),
                                                np.asarray(waves["amplitude"])[:, :shown])
            fig = plots.chain_modes(modes[:, :shown], titles[:shown],
                                    coordinate="q" if src == "chain" else "φ",
                                    exact_shapes=exact)
            cap = ("Mode shapes: amplitude of each " + ("mass" if src == "chain" else "pendulum") +
                   (" (dashed: the standing wave sin(jsπ/(N+1)))." if exact is not None else "."))
            if shown < modes.shape[1]:
                cap += f" The {shown} lowest of {modes.shape[1]} modes are shown."
            figs.append(cls.figure("modes", fig, cap))
        else:
            shown = min(modes.shape[1], SHAPES_SHOWN)
            names = (cls.coordinate_texts(data) if "coordinate_symbols" in a
                     else list(a["coordinate_names"]))
            fig = plots.matrix_modes(modes[:, :shown], titles[:shown], names)
            figs.append(cls.figure("modes", fig, "Components of each mode η (normalized to the "
                                   "largest)."))
        return SectionContent(figures=figs)

    @classmethod
    def section_counting(cls, data):
        a = data.analysis
        n_atoms = len(a["masses"])
        linear = bool(a["linear"])
        z = int(a["n_zero_modes"])
        rows = [["atoms n", str(n_atoms), ""],
                ["coordinates 3n", str(3 * n_atoms), ""],
                ["rigid translations", str(int(a["n_rigid_translations"])), "3"],
                ["rigid rotations (rank of ω × r)", str(int(a["n_rigid_rotations"])),
                 "2 (linear)" if linear else "3"],
                ["zero modes found", str(z), str(int(a["expected_zero_modes"]))],
                ["vibrations", str(int(a["n_vibrational"])),
                 f"3n − {int(a['expected_zero_modes'])} = {int(a['expected_vibrational'])}"]]
        tables = []
        if linear:
            rows += [["longitudinal vibrations", str(int(a["n_longitudinal"])),
                      f"n − 1 = {int(a['expected_longitudinal'])}"],
                     ["transverse vibrations", str(int(a["n_transverse"])),
                      f"2(n − 2) = {int(a['expected_transverse'])}"]]
            tables.append(cls._axis_table(data))
        notes = []
        if int(a["n_floppy"]):
            notes.append(f"{int(a['n_floppy'])} internal mode(s) have ω = 0: the force field "
                         "does not hold the shape (add bonds or angles).")
        return SectionContent(
            tables=[Table("Counting: found against expected", ["quantity", "found", "expected"],
                          rows), *tables],
            facts=[("max ‖A v‖ / (‖A‖ ‖v‖) over the rigid-body vectors",
                    fmt_err(a["rigid_residual"])),
                   ("symmetry operations found", str(int(a["n_symmetry_operations"])))],
            notes=notes)

    @classmethod
    def _axis_table(cls, data) -> Table:
        """A linear molecule's vibrations along and across its axis, with their frequencies
        (wavenumbers for a molecule in physical units), each degenerate set once."""
        a = data.analysis
        z, w, types = cls._vib(data)
        groups = np.asarray(a["degenerate_group"])[z:]
        values, unit = w, cls._omega_unit(data)
        if "wavenumbers" in a:
            values, unit = np.asarray(a["wavenumbers"])[z:], "cm⁻¹"
        rows = []
        for kind, words in (("longitudinal", "longitudinal: along the axis"),
                            ("transverse", "transverse: across the axis (bends)")):
            idx = [i for i, t in enumerate(types) if t.startswith(kind)]
            sets = list(dict.fromkeys(int(groups[i]) for i in idx))
            shown = []
            for gid in sets:
                members = [i for i in idx if groups[i] == gid]
                shown.append(fmt(float(values[members[0]]), 5)
                             + (f" (×{len(members)})" if len(members) > 1 else ""))
            rows.append([words, str(len(idx)), ", ".join(shown) or "—"])
        return Table("The vibrations of a linear molecule along and across its axis",
                     ["vibrations", "count", cls._with_unit("frequencies", unit)
                      if unit != "cm⁻¹" else "wavenumbers ν̃ [cm⁻¹]"], rows)

    @classmethod
    def section_error_vs_runtime(cls, data):
        content = super().section_error_vs_runtime(data)
        a = data.analysis
        if a.get("stiff"):  # what the diagram shows only a stiff scene needs said
            content.notes.insert(0, (
                f"This scene is stiff (ωₘₐₓ/ωₘᵢₙ = {fmt(a['stiffness_ratio'], 3)} ≥ "
                f"{fmt(STIFF_RATIO)}): explicit methods cannot step past the stability bound "
                "set by the fastest mode, however loose the tolerance; implicit methods "
                "(Gauss–Legendre, Radau) stay stable at any step, and at large steps their "
                "error is the small amplitude of the unresolved fast mode."))
        return content

    @classmethod
    def section_evolution(cls, data):
        a = data.analysis
        run = data.runs["main"]
        n = int(a["n_dof"])
        q_ref = np.column_stack([run.reference[c] for c in run.columns[:n]])
        amp = np.max(np.abs(q_ref), axis=0)
        show = [int(i) for i in np.argsort(-amp, kind="stable")[:min(3, n)] if amp[i] > 0]
        show.sort()
        schema = cls._schema(data)
        unit = cls._units(data)["q"]
        words = (cls.coordinate_texts(data) if "coordinate_symbols" in a
                 else [c.replace("phi", "φ") for c in run.columns[:n]])
        names = [cls._with_unit(words[i], unit) for i in show]
        t, t_unit = run.t, unit_text(schema.time.unit)
        if cls._in_tau(data):  # the time axis in femtoseconds, not in units of 4.075 fs
            t, t_unit = run.t * FS_PER_TAU, "fs"
        fig = plots.evolution(t, run.y[:, show], q_ref[:, show], names,
                              time_unit=t_unit, unit=unit)
        facts = [("method", f"{run.attrs.get('method')} ({run.attrs.get('method_reason', '')})"),
                 ("max |q − q(modal)|, q integrated", fmt_err(a["evolution_max_error"])
                  + ("" if unit == "dimensionless" else f" {unit}")),
                 ("largest amplitude", fmt(a["evolution_amplitude"])
                  + ("" if unit == "dimensionless" else f" {unit}")),
                 ("stiffness", str(a["stiff_reason"]))]
        return SectionContent(
            figures=[cls.figure("evolution", fig, "Coordinates with the largest amplitude: direct "
                                "integration of M q̈ + A q = 0 against the exact modal "
                                "superposition; bottom: their largest difference.")],
            facts=facts)


#: the molecular unit of time τ = √(u/(mdyn/Å)) in femtoseconds (4.075)
FS_PER_TAU = 1e15 / MOLECULAR_OMEGA

#: a mode's parity under the inversion, as the spectrum table states it
PARITY_WORDS = {"g": "even (g)", "u": "odd (u)"}

#: each unit system in words, as the report states it
UNIT_WORDS = {
    "SI": "SI: kg, m, N/m and s (ω in rad/s)",
    "SI, rad": "SI: kg, m, J and s, the coordinates angles in rad (M in kg m², A in J, ω in "
               "rad/s)",
    "molecular": "molecular: masses in u, lengths in Å, force constants in mdyn/Å; ω in rad/s "
                 f"(one unit of the eigenproblem is √((mdyn/Å)/u) = {fmt(MOLECULAR_OMEGA, 4)} rad/s); "
                 f"times in τ = √(u/(mdyn/Å)) = {fmt(FS_PER_TAU, 4)} fs",
    "dimensionless": "dimensionless: masses and spring constants in units of a reference m₀ "
                     "and k₀, time in units of √(m₀/k₀), ω in units of √(k₀/m₀)",
}


def counted(n: int, noun: str) -> str:
    """``1 angle``, ``2 angles``: a count and its noun, singular or plural."""
    return f"{n} {noun}{'' if n == 1 else 's'}"


_SUBSCRIPTS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def formula(elements) -> str:
    """The chemical formula of a list of symbols in Hill order (C, then H, then the rest
    alphabetically; without carbon all alphabetically): ``CO₂``, ``H₂O``; "" when an atom
    has no element."""
    if not elements or any(not e for e in elements):
        return ""
    counts = {e: list(elements).count(e) for e in set(elements)}
    order = (["C", "H"] if "C" in counts else []) + sorted(
        e for e in counts if "C" not in counts or e not in ("C", "H"))
    return "".join(e + (str(counts[e]).translate(_SUBSCRIPTS) if counts[e] > 1 else "")
                   for e in order if e in counts)
