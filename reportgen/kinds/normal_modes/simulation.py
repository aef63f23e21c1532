"""``normal_modes`` simulation: the generalized eigenproblem A η = ω² M η of a molecule,
matrices, a chain, coupled pendula or a written potential (its equilibrium found first,
:mod:`.simulation_potential`); zero modes projected out, vibrations counted and
classified, closed forms checked; with ``[evolve]``, the time evolution by modal
superposition (exact) and by direct integration of M q̈ + A q = 0."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.content import fmt
from ...scene.integration import IntegratingSimulation
from ...scene.results import AuditCase, Check, Results
from ...scene.schema import ResultsSchema, unit_text
from . import naming
from .config import (
    SHAPES_SHOWN,
    STIFF_RATIO,
    NormalModesConfig,
    flat_values,
    system_of,
    unit_system,
)
from .results import LIGHT_CM_PER_S, SCHEMA, omega_scale, schema_for, units
from .simulation_potential import PotentialSimulation

core = lazy_module("reportgen.core.normal_modes")
linear_chain = lazy_module("reportgen.core.models.linear_chain")


class NormalModesSimulation(PotentialSimulation, IntegratingSimulation):
    """Small oscillations about a stable equilibrium (textbook ch. 5, §5.1)."""

    schema = SCHEMA
    config: NormalModesConfig

    @classmethod
    def audit_cases(cls):
        return [AuditCase(
            name="normal modes: stiffness ratio 10⁴ (frequency ratio 10³)",
            what="heavy mass on a soft spring (k = 1), light mass on a stiff one (k = 10⁴; "
                 "ω ≈ 1 and 1000): explicit steps are bounded by the fast mode over many slow "
                 "periods",
            methods=("dop853", "rk4"),
            config={"kind": "normal_modes", "title": "normal modes: frequency ratio 10³",
                    "M": [[1.0, 0.0], [0.0, 0.01]],
                    "A": [[10001.0, -10000.0], [-10000.0, 10000.0]],
                    "evolve": {"displacement": [0.1, 0.1], "t_end": 10.0},
                    "run": {"samples": 1001}})]

    def results_schema(self) -> ResultsSchema:
        """The results in this system's units, with its coordinates as the evolution's
        columns."""
        c = self.config
        if c.system is not None:  # a written potential: its coordinates' own symbols
            return schema_for("potential", tuple(self.coordinate_names()), unit_system(c),
                              c.system.coordinate_unit, tuple(self.coordinate_symbols()))
        return schema_for(self.system(), tuple(self.coordinate_names()), unit_system(c))

    def budget_schema(self) -> ResultsSchema:
        """:meth:`results_schema` from the config alone (a potential's coordinates' names
        for their symbols, which its formula gives), for the archive's budget."""
        c = self.config
        return schema_for(self.system(), tuple(self.coordinate_names()), unit_system(c),
                          c.system.coordinate_unit if c.system is not None else None)

    # ------------------------------------------------------------------ system
    def molecule(self) -> core.Molecule:
        c = self.config
        masses = np.array([a.mass if a.mass is not None else core.ELEMENT_MASSES[a.element]
                           for a in c.atoms])
        positions = np.array([a.position for a in c.atoms], dtype=float)
        return core.Molecule(masses=masses, positions=positions,
                             bonds=tuple((b.atoms[0], b.atoms[1], b.k) for b in c.bonds),
                             angles=tuple((*a.atoms, a.k) for a in c.angles))

    def elements(self) -> list[str | None]:
        """Each atom's chemical symbol, None for an atom given by its mass alone."""
        return [a.element for a in self.config.atoms]

    def system(self) -> str:
        """Which way the config gives the system: molecule, chain, pendula or matrices."""
        return system_of(self.config)

    def coordinate_names(self) -> list[str]:
        c = self.config
        if c.atoms:
            return [f"{ax}{a}" for a in range(len(c.atoms)) for ax in "xyz"]
        if c.chain is not None:
            return [f"q{s + 1}" for s in range(c.chain.n)]
        if c.pendula is not None:
            return [f"phi{s + 1}" for s in range(c.pendula.n)]
        if c.system is not None:
            return list(c.system.coordinates)
        return [f"q{s + 1}" for s in range(len(c.M))]

    def matrices(self) -> tuple[np.ndarray, np.ndarray]:
        c = self.config
        if c.atoms:
            mol = self.molecule()
            return mol.mass_matrix(), mol.hessian()
        if c.chain is not None:
            n, springs = c.chain.n, c.chain.n + 1 if c.chain.ends == "fixed" else c.chain.n - 1
            return core.chain_matrices(np.full(n, c.chain.m), np.full(springs, c.chain.k))
        if c.pendula is not None:
            p = c.pendula
            return core.pendula_matrices(p.n, p.m, p.l, p.g, p.k)
        if c.system is not None:  # M and A at the equilibrium found (textbook §5.1)
            found = self.equilibrium()
            return found.M, found.A
        return np.array(c.M, dtype=float), np.array(c.A, dtype=float)

    def exact_frequencies(self) -> tuple[np.ndarray, str] | None:
        """Closed-form frequencies of a generated system, ascending, and their source."""
        c = self.config
        if c.chain is not None:
            src = ("ωⱼ = 2√(k/m) sin(jπ/(2(N+1))), fixed ends (textbook §5.1; Goldstein §6.4)"
                   if c.chain.ends == "fixed" else "ωⱼ = 2√(k/m) sin(jπ/(2N)), free ends")
            return core.chain_exact_frequencies(c.chain.n, c.chain.m, c.chain.k,
                                                c.chain.ends), src
        if c.pendula is not None:
            p = c.pendula
            return (core.pendula_exact_frequencies(p.n, p.m, p.l, p.g, p.k),
                    "ωⱼ² = g/l + (4k/m) sin²(jπ/(2N)) (Goldstein §6.3 for N = 2)")
        if c.system is not None:
            return self.exact_potential_frequencies()
        return None

    # -------------------------------------------------------------- simulation
    def _solve(self):
        """The matrices and normal modes: ``(M, A, molecule, symmetry operations,
        rigid-body labels, modes)``; molecule and operations are None unless given by atoms."""
        M, A = self.matrices()
        if self.config.atoms:
            mol = self.molecule()
            ops = mol.symmetry_operations(A)
            rigid, rigid_labels = core.rigid_body_basis(mol, M)
            return M, A, mol, ops, rigid_labels, core.solve_modes(M, A, rigid, ops)
        return M, A, None, None, [], core.solve_modes(M, A)

    @staticmethod
    def _stiffness_ratio(modes) -> float:
        vib = modes.omega[modes.n_zero:]
        return float(vib.max() / vib.min()) if vib.size else 1.0

    def _evolve_model(self, M, A, modes, ratio: float):
        """The linear model the [evolve] run integrates and whether it is stiff."""
        stiff = bool(ratio >= STIFF_RATIO)
        return linear_chain.model(M, A, self.coordinate_names(), stiff_hint=stiff,
                                  omega_max=float(modes.omega.max())), stiff

    def build_models(self) -> None:
        """As every kind's, and a written potential's equilibrium sought, so that ``validate``
        refuses a potential with no stable equilibrium near its guess, as ``run`` would."""
        super().build_models()
        if self.config.system is not None:
            self.equilibrium()

    def models(self) -> list:
        """The linear model of the [evolve] run; none without [evolve]."""
        if self.config.evolve is None:
            return []
        M, A, *_, modes = self._solve()
        return [self._evolve_model(M, A, modes, self._stiffness_ratio(modes))[0]]

    def simulate(self, progress=None) -> Results:
        c = self.config
        results = Results()
        M, A, mol, ops, rigid_labels, modes = self._solve()
        a = results.analysis
        n = M.shape[0]
        system = self.system()
        # ω of the eigenproblem in the config's units; stored in rad/s for molecular units
        scale = omega_scale(unit_system(c))
        a.update({
            "source": system, "unit_system": unit_system(c),
            "frequencies": modes.omega * scale, "omega_squared": modes.omega2 * scale ** 2,
            "modes": modes.modes,
            "n_dof": n, "n_zero_modes": modes.n_zero, "n_vibrational": n - modes.n_zero,
            "degenerate_group": modes.groups, "mass_matrix": M, "hessian": A,
            "coordinate_names": self.coordinate_names(),
        })
        # the textbook's three steps against the one-call generalized solver
        w_gen, _ = core.generalized_modes(M, A)
        w_3, v_3 = core.three_step_modes(M, A)
        scale = max(float(np.max(np.abs(w_gen))), 1e-300)
        a["three_step_max_difference"] = float(np.max(np.abs(w_gen - w_3)) / scale)
        a["orthonormality_error"] = float(np.max(np.abs(modes.modes.T @ M @ modes.modes
                                                        - np.eye(n))))
        named = None
        if mol is not None:  # named by the coordinates that hold their energy
            inversion = mol.inversion(A)
            parity = core.mode_parity(modes.modes, M, inversion)
            a["centre_of_inversion"] = inversion is not None
            if inversion is not None:  # a centre of symmetry: each mode even (g) or odd (u)
                a["mode_parity"] = parity
            named = naming.mode_names(modes, mol, self.elements(), parity)
        a["mode_type"] = (self.potential_mode_types(modes) if system == "potential" else
                          core.classify_modes(modes, M, system, mol, rigid_labels,
                                              named[0] if named else None))
        if system == "potential":
            self.potential_analysis(results)
        a["stiffness_ratio"] = self._stiffness_ratio(modes)
        if mol is not None:
            if unit_system(c) != "dimensionless":
                a["wavenumbers"] = a["frequencies"] / (2 * math.pi * LIGHT_CM_PER_S)
            self._molecule_analysis(results, mol, modes, M, ops, named)
        exact = self.exact_frequencies()
        if exact is not None:
            w_ex, src = exact
            w_num = modes.omega
            rel = np.abs(w_num - w_ex) / np.where(w_ex > 0, w_ex, 1.0)
            a["frequencies_exact"] = w_ex
            a["closed_form_max_rel_error"] = float(rel.max())
            a["closed_form_source"] = src
            j = int(np.argmax(rel))
            unit = unit_text(units(system, unit_system(c))["omega"])
            results.checks.append(Check(f"ω{j + 1} (worst of {n})", float(w_num[j]),
                                        float(w_ex[j]), unit, src))
            results.checks.append(Check(f"ω{n} (highest)", float(w_num[-1]), float(w_ex[-1]),
                                        unit, src))
        if c.chain is not None and c.chain.ends == "fixed":
            # the closed-form standing waves drawn over the lowest modes
            s, waves = core.chain_standing_waves(modes.modes[:, modes.n_zero:][:, :SHAPES_SHOWN])
            a["standing_waves"] = {"s": s, "amplitude": waves}
        if c.evolve is not None:
            self._evolve(results, M, A, modes, progress)
        return results

    def _molecule_analysis(self, results, mol, modes, M, ops, named):
        a = results.analysis
        axis = mol.axis()
        n_atoms = mol.n_atoms
        n_rot = modes.n_rigid - 3
        expected_zero = 3 + (2 if axis is not None else 3)
        frame = mol.drawing_frame()
        z = modes.n_zero
        positions, displacements = core.drawing_projection(mol.masses, mol.positions, frame,
                                                            modes.modes[:, z:])
        a.update({
            "masses": mol.masses, "positions": mol.positions,
            "elements": [at.element or "X" for at in self.config.atoms],
            "bonds": np.array([b[:2] for b in mol.bonds], dtype=np.int64).reshape(-1, 2),
            "angles": np.array([g[:3] for g in mol.angles], dtype=np.int64).reshape(-1, 3),
            "linear": axis is not None, "frame": frame,
            "drawing": {"positions": positions, "displacements": displacements},
            "n_rigid_translations": 3, "n_rigid_rotations": n_rot,
            "expected_zero_modes": expected_zero,
            "expected_vibrational": 3 * n_atoms - expected_zero,
            "rigid_residual": modes.rigid_residual, "n_symmetry_operations": len(ops),
            "n_floppy": modes.n_zero - modes.n_rigid,
        })
        shape = "linear" if axis is not None else "non-linear"
        results.checks.append(Check("vibrational modes counted",
                                    float(3 * n_atoms - modes.n_zero),
                                    float(3 * n_atoms - expected_zero), "",
                                    f"3n − {expected_zero} ({shape} molecule, n = {n_atoms})"))
        if modes.n_zero != expected_zero:
            results.flag("unstable", f"{modes.n_zero - modes.n_rigid} internal zero-frequency "
                                     "mode(s): the bonds and angles do not hold the molecule "
                                     "in shape (neutral, not stable, equilibrium)")
        if axis is not None:
            types = a["mode_type"][modes.n_zero:]
            a["n_longitudinal"] = sum(t.startswith("longitudinal") for t in types)
            a["n_transverse"] = sum(t.startswith("transverse") for t in types)
            # a linear molecule: n − 1 longitudinal, 2(n − 2) transverse vibrations
            a["expected_longitudinal"] = n_atoms - 1
            a["expected_transverse"] = 2 * (n_atoms - 2)
        _names, classes, shares = named
        if classes:  # the potential-energy distribution that names each vibration
            a["coordinate_classes"] = [c.label for c in classes]
            a["coordinate_shares"] = shares
            a["dominant_share"] = naming.DOMINANT_SHARE
        self._triatomic_checks(results, mol, modes)
        self._four_atom_checks(results, mol, modes)

    def _triatomic_checks(self, results, mol, modes):
        """Closed forms for symmetric XY₂ (Y–X–Y) molecules with one bend."""
        xy2 = core.symmetric_xy2(mol)
        if xy2 is None:
            return
        k, kb, my, mx, r = xy2.k, xy2.k_bend, xy2.m_y, xy2.m_x, xy2.r
        types = list(results.analysis["mode_type"])
        system = unit_system(self.config)
        scale = omega_scale(system)  # the closed forms below are in the config's units
        w = results.analysis["frequencies"]
        u = units("molecule", system)
        w_unit, w2_unit = unit_text(u["omega"]), unit_text(u["omega2"])

        def find(label):
            return [float(w[i]) for i, t in enumerate(types) if label in t]

        if xy2.linear:
            # Goldstein §6.4 (linear triatomic molecule); textbook §5.1, Fig. 5.1
            src = "Goldstein §6.4: ω² = k/m, (k/m)(1 + 2m/M), m and M the end and centre masses"
            w_sym, w_asym = (scale * x for x in core.linear_xy2_frequencies(k, my, mx))
            sym, asym = find("longitudinal, symmetric"), find("longitudinal, antisymmetric")
            if sym:
                results.checks.append(Check("ω symmetric stretch", sym[0], w_sym, w_unit,
                                            src))
            if asym:
                results.checks.append(Check("ω antisymmetric stretch", asym[0], w_asym,
                                            w_unit, src))
            bend = find("transverse")
            if kb is not None and len(bend) == 2:
                results.checks.append(Check("ω bend (twofold)", bend[1],
                                            scale * core.linear_xy2_bend_frequency(kb, my, mx, r),
                                            w_unit, "ω² = 2κ(1 + 2m/M)/(m r²), κ the bend "
                                            "constant, linear bend"))
        elif kb is not None:
            src = "Herzberg (1945) ch. II, XY₂ valence force field"
            lam3, tot, prod = core.bent_xy2_eigenvalues(k, kb, my, mx, r, xy2.half_angle)
            asym = find("antisymmetric stretch")
            if len(asym) == 1:
                results.checks.append(Check("ω antisymmetric stretch", asym[0],
                                            scale * math.sqrt(lam3), w_unit, src))
            others = [float(v) ** 2 for i, v in enumerate(w)
                      if i >= modes.n_zero and "antisymmetric" not in types[i]]
            if len(others) == 2:
                results.checks.append(Check("ω₁² + ω₂² (symmetric block)", sum(others),
                                            scale ** 2 * tot, w2_unit, src))
                results.checks.append(Check("ω₁² ω₂² (symmetric block)", others[0] * others[1],
                                            scale ** 4 * prod, unit_text(u["omega4"]), src))

    #: the closed forms of a symmetric linear X–Y–Y–X and their check labels, numbered as
    #: acetylene's ν1…ν5 (even: symmetric under the inversion, odd: antisymmetric)
    FOUR_ATOM_MODES = (("stretch_even_high", "ω of ν1, even stretch (the higher)"),
                       ("stretch_even_low", "ω of ν2, even stretch (the lower)"),
                       ("stretch_odd", "ω of ν3, odd stretch"),
                       ("bend_trans", "ω of ν4, trans bend (even, twofold)"),
                       ("bend_cis", "ω of ν5, cis bend (odd, twofold)"))

    def _four_atom_checks(self, results, mol, modes):
        """Closed forms of a symmetric linear X–Y–Y–X (C₂H₂, textbook §5.1): the stretches
        against the chain of springs k1, k2, k1, the bends against the two linear bends
        (:func:`reportgen.core.normal_modes.linear_x2y2_eigenvalues`); with its bends, the
        whole spectrum as ``frequencies_exact``."""
        x2y2 = core.symmetric_linear_x2y2(mol)
        if x2y2 is None:
            return
        a = results.analysis
        system = unit_system(self.config)
        scale = omega_scale(system)
        w_unit = unit_text(units("molecule", system)["omega"])
        closed = {key: scale * math.sqrt(v)
                  for key, v in core.linear_x2y2_eigenvalues(x2y2).items()}
        types, parity = list(a["mode_type"]), list(a.get("mode_parity", []))
        w = np.asarray(a["frequencies"])
        src = ("closed form of the symmetric X–Y–Y–X: along the axis the springs k1, k2, k1, "
               "across it the two linear bends, split by the inversion")
        sources = {"stretch": "X–Y–Y–X: springs k1, k2, k1 along the axis, split by the "
                              "inversion",
                   "bend": "X–Y–Y–X: the two linear bends, split by the inversion"}

        def measured(longitudinal: bool, even: bool) -> list[float]:
            return sorted(float(w[i]) for i in range(modes.n_zero, len(w))
                          if types[i].startswith("longitudinal") == longitudinal
                          and parity and parity[i] == ("g" if even else "u"))

        found = {"stretch_even_high": measured(True, True)[-1:],
                 "stretch_even_low": measured(True, True)[:1],
                 "stretch_odd": measured(True, False),
                 "bend_trans": measured(False, True)[-1:],
                 "bend_cis": measured(False, False)[-1:]}
        for key, label in self.FOUR_ATOM_MODES:
            if key in closed and len(found[key]) == 1:
                results.checks.append(Check(label, found[key][0], closed[key], w_unit,
                                            sources[key.split("_")[0]]))
        if x2y2.k_bend is not None and modes.n_zero == 5:  # 3 translations, 2 rotations
            vib = [closed[k] for k, _label in self.FOUR_ATOM_MODES]
            exact = np.sort(np.concatenate([np.zeros(5), vib, closed["bend_trans"],
                                            closed["bend_cis"]], axis=None))
            a["frequencies_exact"] = exact
            a["closed_form_max_rel_error"] = float(np.max(np.abs(w[5:] / exact[5:] - 1.0)))
            a["closed_form_source"] = src

    # ------------------------------------------------------------------ evolution
    def initial_state(self) -> tuple[np.ndarray, np.ndarray]:
        ev = self.config.evolve
        q0 = np.array(flat_values(ev.displacement), dtype=float)
        v0 = np.array(flat_values(ev.velocity), dtype=float) if ev.velocity is not None else (
            np.zeros_like(q0))
        return q0, v0

    def _evolve(self, results, M, A, modes, progress):
        a = results.analysis
        run = self.config.run
        t = np.linspace(0.0, run.t_end, run.samples)
        q0, v0 = self.initial_state()
        ratio = a["stiffness_ratio"]
        model, stiff = self._evolve_model(M, A, modes, ratio)
        y0 = np.concatenate([q0, M @ v0])
        vib = modes.omega[modes.omega > 0]
        n_periods = run.t_end * float(vib.min()) / (2 * math.pi) if vib.size else None
        e0 = float(linear_chain.energy(y0[None, :], M, A)[0])

        def invariants(_t, y):
            return {"energy": linear_chain.energy(y, M, A)}

        main = self.integrate(model, y0, t, invariants=invariants, progress=progress,
                              n_periods=n_periods, invariant_scales={"energy": e0 or None})

        def reference(ts):
            q, v = core.modal_evolution(modes.modes, modes.omega, M, q0, v0, ts)
            return np.column_stack([q, v @ M.T])

        ref = reference(t)
        main.reference = {col: ref[:, i] for i, col in enumerate(main.columns)}
        main.attrs["reference_label"] = ("modal superposition q = Σ ηₖ (aₖ cos ωₖt + "
                                         "bₖ sin ωₖt / ωₖ), p = M q̇ (textbook §5.1)")
        results.runs["main"] = main
        n = M.shape[0]
        err_q = np.abs(main.y[:, :n] - ref[:, :n])
        a["evolution_max_error"] = float(np.max(err_q))
        a["evolution_amplitude"] = float(np.max(np.abs(ref[:, :n])))
        a["stiff"] = stiff
        a["stiff_reason"] = (
            f"ωₘₐₓ/ωₘᵢₙ = {fmt(ratio, 3)} ≥ {fmt(STIFF_RATIO)}: an explicit method's step is bounded by "
            "the fastest mode (h ≲ 3/ωₘₐₓ) while the motion lasts many slow periods; the modal "
            "superposition is exact at any t, and auto chooses an implicit method (Gauss–Legendre "
            "6, A-stable and symplectic)"
            if stiff else f"ωₘₐₓ/ωₘᵢₙ = {fmt(ratio, 3)} < {fmt(STIFF_RATIO)}: not stiff")
        c_idx = int(np.argmax(np.max(np.abs(ref[:, :n]), axis=0)))
        name = (self.coordinate_words() if self.config.system is not None else
                [n.replace("phi", "φ") for n in self.coordinate_names()])[c_idx]
        results.checks.append(Check(f"{name}(t_end), direct integration",
                                    float(main.y[-1, c_idx]), float(ref[-1, c_idx]), "",
                                    "modal superposition q = Σ ηₖ aₖ cos ωₖt (textbook §5.1)"))
        if stiff:
            results.message = "; ".join(x for x in (results.message, (
                f"stiff: ωₘₐₓ/ωₘᵢₙ = {fmt(ratio, 3)}; direct integration by "
                f"{main.attrs.get('method')}")) if x)
        t_study = np.linspace(0.0, run.t_end, 201)
        self.study(results, model, y0, t_study, reference=reference, progress=progress)
