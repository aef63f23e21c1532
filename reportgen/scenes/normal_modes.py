r"""``normal_modes``: small oscillations about a stable equilibrium (lecture notes ch. 5, §5.1).

The generalized eigenproblem A η = ω² M η for a system given as matrices, as a
molecule (atoms, bond stretches, angle bends; Fig. 5.1), as a chain of masses
and springs or as coupled pendula.  Rigid-body zero modes are identified and
projected out, vibrations counted (3n − 6 or 3n − 5) and classified, mode
shapes drawn.  Nothing is integrated unless ``[evolve]`` asks for a time
evolution, which is then done two ways: modal superposition (exact) and direct
integration of M q̈ + A q = 0.

Atom indices in ``[[bonds]]`` and ``[[angles]]`` are zero-based.
"""

from __future__ import annotations

import math
from typing import Any, Literal

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, Strict
from ..lazy import lazy_module
from ..results import AuditCase, Check, Results
from .base import Scene, SceneConfig, Section, SectionContent, Table, fmt, fmt_err

plots = lazy_module("reportgen.plots.normal_modes")
common_plots = lazy_module("reportgen.plots.common")
core = lazy_module("reportgen.core.normal_modes")
geometry = lazy_module("reportgen.core.molecule_geometry")  # no scipy: validation uses it
linear_chain = lazy_module("reportgen.core.models.linear_chain")

#: ω_max / ω_min (non-zero) at or above which direct integration is treated as stiff
STIFF_RATIO = 1e3
#: mode-shape panels drawn for a chain, row of pendula or matrix system (the lowest modes)
SHAPES_SHOWN = 8


class Atom(Strict):
    element: str | None = Field(None, description="chemical symbol; sets the mass if `mass` "
                                                    "is not given [u]")
    mass: Positive | None = Field(None, description="mass (overrides the element's) [u or kg]")
    position: list[Real] = Field(description="equilibrium position [x, y, z] [Å or m]")


class Bond(Strict):
    atoms: list[int] = Field(description="[i, j], zero-based atom indices")
    k: Positive = Field(description="stretch constant, V = ½ k (r − r0)²")


class Angle(Strict):
    atoms: list[int] = Field(description="[i, j, l], zero-based, j the vertex")
    k: Positive = Field(description="bend constant, V = ½ k (θ − θ0)² [energy/rad²]")


class Chain(Strict):
    n: int = Field(ge=1, le=400, description="number of masses N")
    m: Positive = Field(1.0, description="mass of each bead")
    k: Positive = Field(1.0, description="spring constant of each spring")
    ends: Literal["fixed", "free"] = Field("fixed", description="fixed (walls) or free ends")


class Pendula(Strict):
    n: int = Field(2, ge=1, le=400, description="number of pendula")
    m: Positive = Field(1.0, description="bob mass [kg]")
    l: Positive = Field(1.0, description="length [m]")
    g: Positive = Field(9.81, description="gravitational acceleration [m/s²]")
    k: Positive = Field(description="coupling spring between neighbouring bobs [N/m]")


class Evolve(Strict):
    displacement: list[Real] | list[list[Real]] = Field(
        description="initial displacement from equilibrium: one number per coordinate, or "
                    "[dx, dy, dz] per atom")
    velocity: list[Real] | list[list[Real]] | None = Field(
        None, description="initial velocity (same shape; default at rest)")
    t_end: Positive = Field(description="end time of the evolution")


def _flat(value) -> list[float] | None:
    if value is None:
        return None
    if value and isinstance(value[0], list):
        return [float(x) for row in value for x in row]
    return [float(x) for x in value]


class NormalModesConfig(SceneConfig):
    atoms: list[Atom] = Field([], description="the molecule's atoms (zero-based indices)")
    bonds: list[Bond] = []
    angles: list[Angle] = []
    M: list[list[Real]] | None = Field(None, description="kinetic (mass) matrix, symmetric "
                                                         "positive definite")
    A: list[list[Real]] | None = Field(None, description="potential Hessian at equilibrium")
    chain: Chain | None = None
    pendula: Pendula | None = None
    evolve: Evolve | None = None

    @model_validator(mode="before")
    @classmethod
    def _run_from_evolve(cls, data: Any):
        """[run] settings of the evolution: [evolve].t_end plus an optional [run] table."""
        if not isinstance(data, dict):
            return data
        evolve, run = data.get("evolve"), data.get("run")
        if isinstance(evolve, dict) and "t_end" in evolve and (run is None or isinstance(run, dict)):
            run = dict(run or {})
            run.setdefault("t_end", evolve["t_end"])
            data = {**data, "run": run}
        return data

    @model_validator(mode="after")
    def _physics(self):
        sources = [name for name, present in (
            ("atoms", bool(self.atoms)), ("M/A", self.M is not None or self.A is not None),
            ("chain", self.chain is not None), ("pendula", self.pendula is not None)) if present]
        if len(sources) != 1:
            raise ValueError("atoms / M and A / chain / pendula: give exactly one system "
                             f"(got {', '.join(sources) or 'none'})")
        if (self.bonds or self.angles) and not self.atoms:
            raise ValueError("bonds / angles: need [[atoms]]")
        if self.run is not None and self.evolve is None:
            raise ValueError("run: a normal-mode scene integrates only a time evolution; "
                             "[run] needs an [evolve] table")
        if self.evolve is not None and self.run.t_end != self.evolve.t_end:
            raise ValueError(f"run.t_end: must equal evolve.t_end (got {self.run.t_end} and "
                             f"{self.evolve.t_end}); give it once, in [evolve]")
        if self.atoms:
            self._check_molecule()
        elif sources == ["M/A"]:
            self._check_matrices()
        if self.evolve is not None:
            n = self.n_coordinates
            for key in ("displacement", "velocity"):
                value = getattr(self.evolve, key)
                if value is None:
                    continue
                nested = bool(value) and isinstance(value[0], list)
                if nested and (not self.atoms or any(len(r) != 3 for r in value)
                               or len(value) != len(self.atoms)):
                    raise ValueError(f"evolve.{key}: nested form needs one [dx, dy, dz] per atom "
                                     f"({len(self.atoms)} atoms)")
                if len(_flat(value)) != n:
                    raise ValueError(f"evolve.{key}: expected {n} numbers (one per coordinate), "
                                     f"got {len(_flat(value))}")
            if not any(_flat(self.evolve.displacement)) and not any(
                    _flat(self.evolve.velocity) or [0.0]):
                raise ValueError("evolve.displacement: all zero and no velocity: nothing moves")
        return self

    @property
    def n_coordinates(self) -> int:
        if self.atoms:
            return 3 * len(self.atoms)
        if self.chain is not None:
            return self.chain.n
        if self.pendula is not None:
            return self.pendula.n
        return len(self.M)

    def _check_molecule(self):
        n = len(self.atoms)
        if n < 2:
            raise ValueError(f"atoms: need at least 2 atoms (got {n})")
        for a, atom in enumerate(self.atoms):
            if len(atom.position) != 3:
                raise ValueError(f"atoms[{a}].position: must be [x, y, z] "
                                 f"(got {len(atom.position)} numbers)")
            if atom.mass is None:
                if atom.element is None:
                    raise ValueError(f"atoms[{a}]: give `mass` or `element`")
                if atom.element not in geometry.ELEMENT_MASSES:
                    raise ValueError(f"atoms[{a}].element: unknown element {atom.element!r} "
                                     f"(known: {', '.join(geometry.ELEMENT_MASSES)}; or give `mass`)")
        x = np.array([a.position for a in self.atoms], dtype=float)
        size = max(float(np.max(np.ptp(x, axis=0))), 1e-300)
        for a in range(n):
            for b in range(a):
                if np.linalg.norm(x[a] - x[b]) <= 1e-9 * size:
                    raise ValueError(f"atoms[{a}].position: same position as atoms[{b}]")
        seen = set()
        for i, bond in enumerate(self.bonds):
            self._check_indices(f"bonds[{i}].atoms", bond.atoms, 2, n)
            key = frozenset(bond.atoms)
            if key in seen:
                raise ValueError(f"bonds[{i}].atoms: bond {bond.atoms} given twice")
            seen.add(key)
        seen = set()
        for i, angle in enumerate(self.angles):
            self._check_indices(f"angles[{i}].atoms", angle.atoms, 3, n)
            a, j, b = angle.atoms
            key = (j, frozenset((a, b)))
            if key in seen:
                raise ValueError(f"angles[{i}].atoms: angle {angle.atoms} given twice")
            seen.add(key)
            if geometry.bond_angle(x, a, j, b) < 1e-6:
                raise ValueError(f"angles[{i}].atoms: θ0 = 0 (atoms {a} and {b} on the same ray "
                                 f"from vertex {j}); the bend is undefined")

    @staticmethod
    def _check_indices(key: str, idx: list[int], count: int, n: int):
        if len(idx) != count:
            raise ValueError(f"{key}: needs {count} atom indices (got {len(idx)})")
        for i in idx:
            if not 0 <= i < n:
                raise ValueError(f"{key}: index {i} out of range ({n} atoms; indices are "
                                 "zero-based)")
        if len(set(idx)) != count:
            raise ValueError(f"{key}: repeated atom index in {idx}")

    def _check_matrices(self):
        if self.M is None or self.A is None:
            raise ValueError("M / A: give both matrices")
        mats = {}
        for key in ("M", "A"):
            rows = getattr(self, key)
            n = len(rows)
            if n == 0 or any(len(r) != n for r in rows):
                raise ValueError(f"{key}: must be a square matrix (list of equal-length rows)")
            mat = np.array(rows, dtype=float)
            if not np.allclose(mat, mat.T, rtol=1e-12, atol=1e-12 * np.max(np.abs(mat))):
                i, j = np.unravel_index(np.argmax(np.abs(mat - mat.T)), mat.shape)
                raise ValueError(f"{key}: not symmetric ({key}[{i}][{j}] = {mat[i, j]} ≠ "
                                 f"{key}[{j}][{i}] = {mat[j, i]})")
            mats[key] = mat
        if mats["M"].shape != mats["A"].shape:
            raise ValueError(f"M / A: sizes differ ({len(self.M)} and {len(self.A)})")
        d = np.linalg.eigvalsh(mats["M"])
        if d.min() <= 0:
            raise ValueError(f"M: not positive definite (smallest eigenvalue {d.min():.6g}); "
                             "kinetic energy must be positive")
        w = np.linalg.eigvalsh(np.linalg.solve(np.linalg.cholesky(mats["M"]),
                                               np.linalg.solve(np.linalg.cholesky(mats["M"]),
                                                               mats["A"]).T))
        if w.min() < -core.ZERO_TOL * max(float(np.abs(w).max()), 1e-300):
            raise ValueError(f"A: unstable equilibrium, ω² = {w.min():.6g} < 0 (A must be "
                             "positive semidefinite: the equilibrium must be a minimum of V)")


# --------------------------------------------------------------------------- presets
_CO2 = {  # r(C=O) = 1.16 Å; k in mdyn/Å, k_θ in mdyn·Å/rad² (valence force field)
    "title": "CO₂: a linear triatomic molecule (Fig. 5.1)",
    "atoms": [{"element": "O", "position": [-1.16, 0.0, 0.0]},
              {"element": "C", "position": [0.0, 0.0, 0.0]},
              {"element": "O", "position": [1.16, 0.0, 0.0]}],
    "bonds": [{"atoms": [0, 1], "k": 16.0}, {"atoms": [1, 2], "k": 16.0}],
    "angles": [{"atoms": [0, 1, 2], "k": 0.57}],
}
_HALF = math.radians(104.5) / 2
_H2O = {  # r(O–H) = 0.9572 Å, ∠HOH = 104.5°
    "title": "H₂O: a bent triatomic molecule",
    "atoms": [{"element": "H", "position": [-0.9572 * math.sin(_HALF), 0.9572 * math.cos(_HALF),
                                            0.0]},
              {"element": "O", "position": [0.0, 0.0, 0.0]},
              {"element": "H", "position": [0.9572 * math.sin(_HALF), 0.9572 * math.cos(_HALF),
                                            0.0]}],
    "bonds": [{"atoms": [0, 1], "k": 8.45}, {"atoms": [1, 2], "k": 8.45}],
    "angles": [{"atoms": [0, 1, 2], "k": 0.76}],
}


class NormalModesScene(Scene):
    kind = "normal_modes"
    order = 80
    summary = ("small oscillations A η = ω² M η of [[atoms]] with [[bonds]] and [[angles]] "
               "(zero-based atom indices), or top-level M and A matrices, a [chain] or "
               "[pendula]; rigid-body zero modes, 3n−6/3n−5 vibrations, mode shapes; "
               "[evolve] (displacement, t_end) adds a time evolution")
    Config = NormalModesConfig
    presets = {
        "co2": _CO2,
        "h2o": _H2O,
        "chain": {"title": "Chain of equal masses between fixed walls",
                  "chain": {"n": 6, "m": 1.0, "k": 1.0, "ends": "fixed"}},
        "coupled_pendula": {"title": "Two pendula coupled by a spring",
                            "pendula": {"n": 2, "m": 1.0, "l": 1.0, "g": 9.81, "k": 0.5}},
    }
    family_sections = (
        Section("frequencies_family", "Eigenfrequencies across the family",
                description="Each member's eigenfrequencies against the swept value, with "
                            "the closed form where the system has one."),
    )
    sections = (
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
                                        xlabel=path, ylabel="ω [rad/s]",
                                        label="ω", reference_label="closed form")
        facts = [("modes", str(len(numeric)))]
        if exact:
            worst = max(float(np.max(np.abs(n / e - 1))) for n, e in zip(numeric, exact,
                                                                         strict=True))
            facts.append(("max relative difference to the closed form", fmt_err(worst)))
        return SectionContent(figures=[cls.figure(
            "frequencies_family", fig, f"Eigenfrequencies ω_j of every member against {path}"
            + ("; dashed: the closed form." if exact else "."))], facts=facts)

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

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        if data.analysis["source"] != "molecule":
            names.remove("counting")
        if "main" not in data.runs:
            names = [n for n in names if n not in ("evolution", "error_vs_runtime")]
        return names

    # ------------------------------------------------------------------ system
    def molecule(self) -> core.Molecule:
        c = self.config
        masses = np.array([a.mass if a.mass is not None else core.ELEMENT_MASSES[a.element]
                           for a in c.atoms])
        positions = np.array([a.position for a in c.atoms], dtype=float)
        return core.Molecule(masses=masses, positions=positions,
                             bonds=tuple((b.atoms[0], b.atoms[1], b.k) for b in c.bonds),
                             angles=tuple((*a.atoms, a.k) for a in c.angles))

    def system(self) -> str:
        """Which way the config gives the system: molecule, chain, pendula or matrices."""
        c = self.config
        return ("molecule" if c.atoms else "chain" if c.chain is not None
                else "pendula" if c.pendula is not None else "matrices")

    def coordinate_names(self) -> list[str]:
        c = self.config
        if c.atoms:
            return [f"{ax}{a}" for a in range(len(c.atoms)) for ax in "xyz"]
        if c.chain is not None:
            return [f"q{s + 1}" for s in range(c.chain.n)]
        if c.pendula is not None:
            return [f"phi{s + 1}" for s in range(c.pendula.n)]
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
        return np.array(c.M, dtype=float), np.array(c.A, dtype=float)

    def exact_frequencies(self) -> tuple[np.ndarray, str] | None:
        """Closed-form frequencies of a generated system, ascending, and their source."""
        c = self.config
        if c.chain is not None:
            src = ("ω_j = 2√(k/m) sin(jπ/(2(N+1))), fixed ends (notes §5.1; Goldstein §6.4)"
                   if c.chain.ends == "fixed" else "ω_j = 2√(k/m) sin(jπ/(2N)), free ends")
            return core.chain_exact_frequencies(c.chain.n, c.chain.m, c.chain.k,
                                                c.chain.ends), src
        if c.pendula is not None:
            p = c.pendula
            return (core.pendula_exact_frequencies(p.n, p.m, p.l, p.g, p.k),
                    "ω_j² = g/l + (4k/m) sin²(jπ/(2N)) (Goldstein §6.3 for N = 2)")
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
        a.update({
            "source": system,
            "frequencies": modes.omega, "omega_squared": modes.omega2, "modes": modes.modes,
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
        a["mode_type"] = core.classify_modes(modes, M, system, mol, rigid_labels)
        a["stiffness_ratio"] = self._stiffness_ratio(modes)
        if mol is not None:
            self._molecule_analysis(results, mol, modes, M, ops)
        exact = self.exact_frequencies()
        if exact is not None:
            w_ex, src = exact
            w_num = modes.omega
            rel = np.abs(w_num - w_ex) / np.where(w_ex > 0, w_ex, 1.0)
            a["frequencies_exact"] = w_ex
            a["closed_form_max_rel_error"] = float(rel.max())
            a["closed_form_source"] = src
            j = int(np.argmax(rel))
            results.checks.append(Check(f"ω_{j + 1} (worst of {n})", float(w_num[j]),
                                        float(w_ex[j]), "rad/s", src))
            results.checks.append(Check(f"ω_{n} (highest)", float(w_num[-1]), float(w_ex[-1]),
                                        "rad/s", src))
        if c.chain is not None and c.chain.ends == "fixed":
            # the closed-form standing waves drawn over the lowest modes
            s, waves = core.chain_standing_waves(modes.modes[:, modes.n_zero:][:, :SHAPES_SHOWN])
            a["standing_waves"] = {"s": s, "amplitude": waves}
        if c.evolve is not None:
            self._evolve(results, M, A, modes, progress)
        return results

    def _molecule_analysis(self, results, mol, modes, M, ops):
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
        self._triatomic_checks(results, mol, modes)

    def _triatomic_checks(self, results, mol, modes):
        """Closed forms for symmetric XY₂ (Y–X–Y) molecules with one bend."""
        xy2 = core.symmetric_xy2(mol)
        if xy2 is None:
            return
        k, kb, my, mx, r = xy2.k, xy2.k_bend, xy2.m_y, xy2.m_x, xy2.r
        types = list(results.analysis["mode_type"])
        w = modes.omega

        def find(label):
            return [float(w[i]) for i, t in enumerate(types) if label in t]

        if xy2.linear:
            # Goldstein §6.4 (linear triatomic molecule); notes §5.1, Fig. 5.1
            src = "Goldstein §6.4: ω² = k/m_O, (k/m_O)(1 + 2m_O/m_C)"
            w_sym, w_asym = core.linear_xy2_frequencies(k, my, mx)
            sym, asym = find("longitudinal, symmetric"), find("longitudinal, antisymmetric")
            if sym:
                results.checks.append(Check("ω symmetric stretch", sym[0], w_sym, "", src))
            if asym:
                results.checks.append(Check("ω antisymmetric stretch", asym[0], w_asym, "", src))
            bend = find("transverse")
            if kb is not None and len(bend) == 2:
                results.checks.append(Check("ω bend (twofold)", bend[1],
                                            core.linear_xy2_bend_frequency(kb, my, mx, r), "",
                                            "ω² = (2k_θ/(m_O r²))(1 + 2m_O/m_C), linear bend"))
        elif kb is not None:
            src = "Herzberg (1945) ch. II, XY₂ valence force field"
            lam3, tot, prod = core.bent_xy2_eigenvalues(k, kb, my, mx, r, xy2.half_angle)
            asym = find("antisymmetric stretch")
            if len(asym) == 1:
                results.checks.append(Check("ω antisymmetric stretch", asym[0], math.sqrt(lam3),
                                            "", src))
            others = [float(v) ** 2 for i, v in enumerate(w)
                      if i >= modes.n_zero and "antisymmetric" not in types[i]]
            if len(others) == 2:
                results.checks.append(Check("ω₁² + ω₂² (symmetric block)", sum(others), tot, "",
                                            src))
                results.checks.append(Check("ω₁² ω₂² (symmetric block)", others[0] * others[1],
                                            prod, "", src))

    # ------------------------------------------------------------------ evolution
    def initial_state(self) -> tuple[np.ndarray, np.ndarray]:
        ev = self.config.evolve
        q0 = np.array(_flat(ev.displacement), dtype=float)
        v0 = np.array(_flat(ev.velocity), dtype=float) if ev.velocity is not None else (
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
        main.attrs["reference_label"] = ("modal superposition q = Σ η_k (a_k cos ω_k t + "
                                         "b_k sin ω_k t / ω_k), p = M q̇ (notes §5.1)")
        results.runs["main"] = main
        n = M.shape[0]
        err_q = np.abs(main.y[:, :n] - ref[:, :n])
        a["evolution_max_error"] = float(np.max(err_q))
        a["evolution_amplitude"] = float(np.max(np.abs(ref[:, :n])))
        a["stiff"] = stiff
        a["stiff_reason"] = (
            f"ω_max/ω_min = {ratio:.3g} ≥ {STIFF_RATIO:g}: an explicit method's step is bounded by "
            "the fastest mode (h ≲ 3/ω_max) while the motion lasts many slow periods; the modal "
            "superposition is exact at any t, and auto chooses an implicit method (Gauss–Legendre "
            "6, A-stable and symplectic)"
            if stiff else f"ω_max/ω_min = {ratio:.3g} < {STIFF_RATIO:g}: not stiff")
        c_idx = int(np.argmax(np.max(np.abs(ref[:, :n]), axis=0)))
        name = self.coordinate_names()[c_idx]
        results.checks.append(Check(f"{name}(t_end), direct integration",
                                    float(main.y[-1, c_idx]), float(ref[-1, c_idx]), "",
                                    "modal superposition q = Σ η_k a_k cos ω_k t (notes §5.1)"))
        if stiff:
            results.message = "; ".join(x for x in (results.message, (
                f"stiff: ω_max/ω_min = {ratio:.3g}; direct integration by "
                f"{main.attrs.get('method')}")) if x)
        t_study = np.linspace(0.0, run.t_end, 201)
        self.study(results, model, y0, t_study, reference=reference, progress=progress)

    # ------------------------------------------------------------------- report
    @staticmethod
    def _vib(data):
        a = data.analysis
        z = int(a["n_zero_modes"])
        return z, np.asarray(a["frequencies"])[z:], list(a["mode_type"])[z:]

    @classmethod
    def headline(cls, data):
        a = data.analysis
        z, w, types = cls._vib(data)
        out = [("system", cls._describe(a)),
               ("vibrations", f"{int(a['n_vibrational'])} of {int(a['n_dof'])} coordinates "
                              f"({z} zero modes)")]
        if w.size:
            out.append(("frequencies ω", ", ".join(fmt(x, 6) for x in w[:8]) +
                        (" …" if w.size > 8 else "")))
        if "closed_form_max_rel_error" in a:
            out.append(("max relative error against the closed form",
                        fmt_err(a["closed_form_max_rel_error"])))
        if "evolution_max_error" in a:
            out.append(("evolution: max |q_direct − q_modal|", fmt_err(a["evolution_max_error"])))
            if a.get("stiff"):
                out.append(("stiffness", a["stiff_reason"]))
        return out

    @staticmethod
    def _describe(a) -> str:
        src = a["source"]
        if src == "molecule":
            n = len(a["masses"])
            return (f"{'linear' if a['linear'] else 'non-linear'} molecule, {n} atoms, "
                    f"{len(a['bonds'])} bonds, {len(a['angles'])} angles")
        if src == "chain":
            return f"chain of {int(a['n_dof'])} masses"
        if src == "pendula":
            return f"{int(a['n_dof'])} coupled pendula"
        return f"M and A given ({int(a['n_dof'])} coordinates)"

    @classmethod
    def section_spectrum(cls, data):
        a = data.analysis
        z, w, types = cls._vib(data)
        groups = np.asarray(a["degenerate_group"])[z:]
        exact = a.get("frequencies_exact")
        fig = plots.spectrum(w, types, groups, exact=None if exact is None else
                             np.asarray(exact)[z:], unit=cls._omega_unit(a))
        rows = []
        w2 = np.asarray(a["omega_squared"])[z:]
        for i, (wi, t) in enumerate(zip(w, types, strict=True)):
            g = int(np.sum(groups == groups[i]))
            row = [str(z + i + 1), fmt(wi, 10), fmt(w2[i], 10), t, str(g)]
            if exact is not None:
                ex = float(np.asarray(exact)[z + i])
                row += [fmt(ex, 10), fmt_err(abs(wi - ex) / ex if ex else abs(wi))]
            rows.append(row)
        header = ["mode", "ω", "ω²", "type", "degeneracy"]
        if exact is not None:
            header += ["closed form", "relative error"]
        facts = [("eigenproblem", "A η = ω² M η (scipy.linalg.eigh on the pair), ηᵀ M η = 1"),
                 ("textbook three steps (diagonalize M, unit mass, diagonalize A′): max |Δω²|/ω²_max",
                  fmt_err(a["three_step_max_difference"])),
                 ("max |ηᵀ M η − 1|", fmt_err(a["orthonormality_error"]))]
        if w.size > 1:
            facts.append(("ω_max / ω_min", fmt(a["stiffness_ratio"], 6)))
        if exact is not None:
            facts.append(("closed form", str(a["closed_form_source"])))
        return SectionContent(
            figures=[cls.figure("spectrum", fig, "Vibrational frequencies; bar height is the "
                                "degeneracy" + ("; hollow circles: closed form." if exact is not
                                                None else "."))],
            tables=[Table("Vibrational modes (zero modes omitted), ascending ω", header, rows)],
            facts=facts)

    @staticmethod
    def _omega_unit(a) -> str:
        return "rad per time unit" if a["source"] == "molecule" else "rad/s"

    @classmethod
    def _titles(cls, data):
        z, w, types = cls._vib(data)
        return [f"ω{z + i + 1} = {fmt(wi, 5)}: {t}" for i, (wi, t) in
                enumerate(zip(w, types, strict=True))]

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
            elems = list(a["elements"])
            fig = plots.molecule_modes(pos[:, :2], a["masses"], elems, bonds, disps, titles)
            figs.append(cls.figure("modes", fig, "Each vibration at equilibrium: arrows are the "
                                   "mass-normalized displacement η (scaled to be visible); faint "
                                   "atoms the extreme phases ωt = 0, π; ⊙/⊗ motion toward/away "
                                   "from the viewer."))
            shown = min(len(disps), 6)
            snap = plots.molecule_snapshots(pos, a["masses"], elems, bonds, disps[:shown],
                                            [f"ω{z + i + 1} = {fmt(w[i], 4)}"
                                             for i in range(shown)])
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
            fig = plots.matrix_modes(modes[:, :shown], titles[:shown], list(a["coordinate_names"]))
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
        if linear:
            rows += [["longitudinal vibrations", str(int(a["n_longitudinal"])),
                      f"n − 1 = {int(a['expected_longitudinal'])}"],
                     ["transverse vibrations", str(int(a["n_transverse"])),
                      f"2(n − 2) = {int(a['expected_transverse'])}"]]
        notes = []
        if int(a["n_floppy"]):
            notes.append(f"{int(a['n_floppy'])} internal mode(s) have ω = 0: the force field "
                         "does not hold the shape (add bonds or angles).")
        return SectionContent(
            tables=[Table("Counting: found against expected", ["quantity", "found", "expected"],
                          rows)],
            facts=[("max ‖A v‖ / (‖A‖ ‖v‖) over the rigid-body vectors",
                    fmt_err(a["rigid_residual"])),
                   ("symmetry operations found", str(int(a["n_symmetry_operations"])))],
            notes=notes)

    @classmethod
    def section_error_vs_runtime(cls, data):
        content = super().section_error_vs_runtime(data)
        a = data.analysis
        if a.get("stiff"):  # what the diagram shows only a stiff scene needs said
            content.notes.insert(0, (
                f"This scene is stiff (ω_max/ω_min = {a['stiffness_ratio']:.3g} ≥ "
                f"{STIFF_RATIO:g}): explicit methods cannot step past the stability bound "
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
        unit = {"pendula": " [rad]", "molecule": " [length unit]"}.get(a["source"], "")
        names = [run.columns[i].replace("phi", "φ") + unit for i in show]
        fig = plots.evolution(run.t, run.y[:, show], q_ref[:, show], names,
                              time_unit="time units" if a["source"] == "molecule" else "s")
        facts = [("method", f"{run.attrs.get('method')} ({run.attrs.get('method_reason', '')})"),
                 ("max |q_direct − q_modal|", fmt_err(a["evolution_max_error"])),
                 ("largest amplitude", fmt(a["evolution_amplitude"], 6)),
                 ("stiffness", str(a["stiff_reason"]))]
        return SectionContent(
            figures=[cls.figure("evolution", fig, "Coordinates with the largest amplitude: direct "
                                "integration of M q̈ + A q = 0 against the exact modal "
                                "superposition; bottom: their largest difference.")],
            facts=facts)
