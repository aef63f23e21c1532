"""``normal_modes`` config: the system (a molecule, M and A, a chain, coupled pendula, or a
potential written as formulas), the optional time evolution, presets.

Atom indices in ``[[bonds]]`` and ``[[angles]]`` are zero-based.
"""

from __future__ import annotations

import math
import re
from typing import Any, Literal

import numpy as np
from pydantic import Field, model_validator

from ...lazy import lazy_module
from ...scene.base import SceneConfig
from ...scene.config import Positive, Real, RunConfig, Strict
from ...scene.units import convert_items, convert_paths
from .results import MOLECULAR_OMEGA

core = lazy_module("reportgen.core.normal_modes")
geometry = lazy_module("reportgen.core.molecule_geometry")  # no scipy: validation uses it
expressions = lazy_module("reportgen.core.expressions")  # no SymPy: validation uses it

#: ω_max / ω_min (non-zero) at or above which direct integration is treated as stiff
STIFF_RATIO = 1e3
#: mode-shape panels drawn for a chain, row of pendula or matrix system (the lowest modes)
SHAPES_SHOWN = 8


class Atom(Strict):
    element: str | None = Field(None, description="chemical symbol; sets the mass (in u) if "
                                                    "`mass` is not given")
    mass: Positive | None = Field(None, description="mass (overrides the element's) "
                                                    "[per `units`: u or kg or m₀]")
    position: list[Real] = Field(description="equilibrium position [x, y, z] "
                                             "[per `units`: Å or m or dimensionless]")


class Bond(Strict):
    atoms: list[int] = Field(description="[i, j], zero-based atom indices")
    k: Positive = Field(description="stretch constant, V = ½ k (r − r0)² "
                                    "[per `units`: mdyn/Å or N/m or k₀]")


class Angle(Strict):
    atoms: list[int] = Field(description="[i, j, l], zero-based, j the vertex")
    k: Positive = Field(description="bend constant, V = ½ k (θ − θ0)² "
                                    "[per `units`: mdyn·Å/rad² or J/rad² or dimensionless]")


class Chain(Strict):
    """``[chain]``: N equal masses joined by equal springs.

    Dimensionless (masses in m₀, springs in k₀) unless ``units = "SI"``."""

    n: int = Field(ge=1, le=400, description="number of masses N")
    m: Positive = Field(1.0, description="mass of each bead [per `units`: kg or m₀]")
    k: Positive = Field(1.0, description="spring constant of each spring "
                                         "[per `units`: N/m or k₀]")
    ends: Literal["fixed", "free"] = Field("fixed", description="fixed (walls) or free ends")


class Pendula(Strict):
    """``[pendula]``: a row of equal plane pendula, neighbours coupled by springs (SI)."""

    n: int = Field(2, ge=1, le=400, description="number of pendula")
    m: Positive = Field(1.0, description="bob mass [kg]")
    l: Positive = Field(1.0, description="length [m]")
    g: Positive = Field(9.81, description="gravitational acceleration [m/s²]")
    k: Positive = Field(description="coupling spring between neighbouring bobs [N/m]")


class Potential(Strict):
    """``[system]``: small oscillations from formulas in named coordinates (textbook §5.1).

    A Lagrangian L(q, q̇), or a potential U(q) with a kinetic energy T(q, q̇) or a mass
    matrix M(q), in the coordinates and the constants of ``[params]``.  The equilibrium is
    sought from ``guess``; A = ∂²U/∂q∂q and M are taken there."""

    coordinates: list[str] = Field(min_length=1, max_length=12,
                                   description="names of the generalized coordinates q")
    L: str | None = Field(None, description="Lagrangian L(q, q̇) in q, <q>_dot and the "
                                            "constants: U = −L(q, 0), M = ∂²L/∂q̇∂q̇")
    U: str | None = Field(None, description="potential energy U(q) in q and the constants")
    T: str | None = Field(None, description="kinetic energy T(q, q̇), a quadratic form in "
                                            "<q>_dot (with U)")
    M: list[list[str | Real]] | None = Field(
        None, description="mass matrix M(q) row by row (with U): each entry a number or a "
                          "formula in q and the constants [config units]")
    guess: dict[str, Real] = Field(
        default_factory=dict, description="where the search for the equilibrium starts: a "
                                          "value per coordinate (default 0) [per "
                                          "`system.coordinate_unit`: rad or m]")
    coordinate_unit: Literal["rad", "m"] | None = Field(
        None, description='with units = "SI": the coordinates are angles (rad) or lengths (m)')


class Evolve(Strict):
    """``[evolve]``: a time evolution from an initial displacement and velocity."""

    displacement: list[Real] | list[list[Real]] = Field(
        description="initial displacement from equilibrium: one number per coordinate, or "
                    "[dx, dy, dz] per atom [per `units`: Å or m or dimensionless; rad for "
                    "pendula; the coordinate_unit of formulas]")
    velocity: list[Real] | list[list[Real]] | None = Field(
        None, description="initial velocity (same shape; default at rest) "
                          "[per `units`: Å/τ or m/s or dimensionless; rad/s for pendula; the "
                          "coordinate_unit of formulas per s]")
    t_end: Positive = Field(description="end time of the evolution "
                                        "[per `units`: τ = 4.075 fs or s or dimensionless]")


class NormalModesRun(RunConfig):
    """``[run]``: how the evolution is integrated (t_end: [evolve] gives it)."""

    t_end: Positive = Field(description="end time of the integration, equal to evolve.t_end "
                                        "[per `units`: τ = 4.075 fs or s or dimensionless]")
    h: Positive | None = Field(None, description="step size of fixed-step methods "
                                                 "[per `units`: τ or s or dimensionless]")


def flat_values(value) -> list[float] | None:
    if value is None:
        return None
    if value and isinstance(value[0], list):
        return [float(x) for row in value for x in row]
    return [float(x) for x in value]


#: the units a molecule's numbers are in, by unit system: a value given as text with a
#: unit ("500 N/m") is converted to these (a dimensionless system takes plain numbers)
SYSTEM_UNITS = {
    "SI": {("atoms", "mass"): "kg", ("atoms", "position"): "m", ("bonds", "k"): "N/m",
           ("angles", "k"): "J/rad^2"},
    "molecular": {("atoms", "mass"): "u", ("atoms", "position"): "Å", ("bonds", "k"): "mdyn/Å",
                  ("angles", "k"): "mdyn Å/rad^2"},
}
#: the molecular unit of time τ = √(u/(mdyn/Å)) [s] (4.075 fs)
_TAU = 1.0 / MOLECULAR_OMEGA
_RUN_TIME = {"SI": "s", "molecular": f"{_TAU!r} s"}
#: the units of the keys of tables and matrices, by unit system and by the way the system
#: is given (a molecule, chain, pendula or matrices): text is converted to these
TABLE_UNITS = {
    "SI": {("chain", "m"): "kg", ("chain", "k"): "N/m", ("M",): "kg", ("A",): "N/m",
           ("evolve", "displacement"): "m", ("evolve", "velocity"): "m/s"},
    "molecular": {("evolve", "displacement"): "Å", ("evolve", "velocity"): f"{1 / _TAU!r} Å/s"},
}
#: a potential's coordinates in SI: its evolution's numbers in their unit
_SYSTEM_EVOLVE = {unit: {("evolve", "displacement"): unit, ("evolve", "velocity"): f"{unit}/s"}
                  for unit in ("rad", "m")}
#: pendula move by angles
_PENDULA_EVOLVE = {("evolve", "displacement"): "rad", ("evolve", "velocity"): "rad/s"}


_GREEK = {"alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "zeta": "ζ",
          "eta": "η", "theta": "θ", "iota": "ι", "kappa": "κ", "lambda": "λ", "mu": "μ",
          "nu": "ν", "xi": "ξ", "rho": "ρ", "sigma": "σ", "tau": "τ", "phi": "φ",
          "chi": "χ", "psi": "ψ", "omega": "ω"}
_INDEX = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def name_as_symbol(name: str) -> str:
    """A coordinate's name as the symbol a title shows: ``theta1`` -> θ₁, ``x`` -> x (a
    Greek letter spelt out, trailing digits as subscripts; other names as written)."""
    found = re.fullmatch(r"([A-Za-z]+?)_?(\d*)", name)
    if found is None:
        return name
    head, index = found.groups()
    return _GREEK.get(head, head) + index.translate(_INDEX)


def unit_system(config) -> str:
    """The config's unit system (``units``), or its system's default: SI for pendula,
    molecular (u, Å, mdyn/Å) for a molecule, dimensionless for a chain or matrices."""
    if getattr(config, "units", None):
        return config.units
    return {"pendula": "SI", "molecule": "molecular"}.get(system_of(config), "dimensionless")


def system_of(config) -> str:
    """Which way ``config`` (the validated config, or an archive's resolved one) gives the
    system: molecule, chain, pendula, potential (formulas in ``[system]``) or matrices."""
    return ("molecule" if config.atoms else "chain" if config.chain is not None
            else "pendula" if config.pendula is not None
            else "potential" if getattr(config, "system", None) is not None else "matrices")


class NormalModesConfig(SceneConfig):
    atoms: list[Atom] = Field([], description="the molecule's atoms (zero-based indices)")
    bonds: list[Bond] = []
    angles: list[Angle] = []
    M: list[list[Real]] | None = Field(None, description="kinetic (mass) matrix, symmetric "
                                                         "positive definite "
                                                         "[per `units`: kg or m₀]")
    A: list[list[Real]] | None = Field(None, description="potential Hessian at equilibrium "
                                                         "[per `units`: N/m or k₀]")
    chain: Chain | None = None
    pendula: Pendula | None = None
    system: Potential | None = None
    params: dict[str, Real] = Field(default_factory=dict,
                                    description="named constants of the system's formulas "
                                                "[config units]")
    evolve: Evolve | None = None
    run: NormalModesRun | None = None
    units: Literal["SI", "molecular", "dimensionless"] | None = Field(
        None, description="unit system of the numbers: SI (kg, m, N/m, s), molecular (masses "
                          "in u, lengths in Å, force constants in mdyn/Å; ω reported in rad/s "
                          "and cm⁻¹, time in τ = 4.075 fs) or dimensionless (masses and springs "
                          "in units of a reference m₀ and k₀). Default: SI for pendula, "
                          "molecular for atoms, dimensionless for a chain or M and A")

    @model_validator(mode="before")
    @classmethod
    def _quantities_in_system(cls, data: Any):
        """Text quantities ("500 N/m", "10 fs") in the unit system's units: of atoms, bonds
        and angles, of the chain, M and A, and of the evolution and its run.  A
        dimensionless system converts nothing (its keys take plain numbers)."""
        if not isinstance(data, dict):
            return data
        system = data.get("units")
        if not isinstance(system, str):
            system = ("molecular" if data.get("atoms") else
                      "SI" if data.get("pendula") is not None else None)
        if system not in SYSTEM_UNITS:
            return data
        paths = dict(TABLE_UNITS[system])
        if data.get("pendula") is not None and not data.get("atoms"):
            paths.update(_PENDULA_EVOLVE)
        formulas = data.get("system")
        if isinstance(formulas, dict) and formulas.get("coordinate_unit") in _SYSTEM_EVOLVE:
            paths.update(_SYSTEM_EVOLVE[formulas["coordinate_unit"]])
        for table in ("evolve", "run"):
            paths[(table, "t_end")] = _RUN_TIME[system]
        paths[("run", "h")] = _RUN_TIME[system]
        return convert_paths(convert_items(data, SYSTEM_UNITS[system]), paths)

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
            ("chain", self.chain is not None), ("pendula", self.pendula is not None),
            ("system", self.system is not None)) if present]
        if len(sources) != 1:
            raise ValueError("atoms / M and A / chain / pendula / system: give exactly one "
                             f"system (got {', '.join(sources) or 'none'})")
        if self.params and self.system is None:
            name, value = next(iter(self.params.items()))
            raise ValueError(f"params.{name}: named constants are for the formulas of "
                             f"[system], which this config does not give (got {value!r})")
        if (self.bonds or self.angles) and not self.atoms:
            raise ValueError("bonds / angles: need [[atoms]]")
        if self.run is not None and self.evolve is None:
            raise ValueError("run: a normal-mode scene integrates only a time evolution; "
                             "[run] needs an [evolve] table")
        if self.evolve is not None and self.run.t_end != self.evolve.t_end:
            raise ValueError(f"run.t_end: must equal evolve.t_end (got {self.run.t_end} and "
                             f"{self.evolve.t_end}); give it once, in [evolve]")
        if self.units == "molecular" and not self.atoms:
            raise ValueError(f"units: 'molecular' (u, Å, mdyn/Å) is for atoms; give SI or "
                             f"dimensionless for {sources[0]}")
        if self.pendula is not None and self.units not in (None, "SI"):
            raise ValueError(f"units: pendula are given in SI (kg, m, m/s², N/m); got "
                             f"{self.units!r}")
        if self.units in ("SI", "dimensionless") and self.atoms:
            by_element = [a for a, atom in enumerate(self.atoms) if atom.mass is None]
            if by_element:
                raise ValueError(f"atoms[{by_element[0]}]: units = {self.units!r} needs `mass` "
                                 "(an element's mass is in u: molecular units)")
        if self.atoms:
            self._check_molecule()
        elif sources == ["M/A"]:
            self._check_matrices()
        elif self.system is not None:
            self._check_potential()
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
                if len(flat_values(value)) != n:
                    raise ValueError(f"evolve.{key}: expected {n} numbers (one per coordinate), "
                                     f"got {len(flat_values(value))}")
            if not any(flat_values(self.evolve.displacement)) and not any(
                    flat_values(self.evolve.velocity) or [0.0]):
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
        if self.system is not None:
            return len(self.system.coordinates)
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

    def _check_potential(self):
        """Names and formulas of ``[system]`` against the allow-list (no SymPy: the
        equilibrium itself is sought when the models are built, so ``validate`` refuses what
        ``run`` would)."""
        sys_ = self.system
        coords = list(sys_.coordinates)
        for c in coords:
            problem = expressions.name_problem(c)
            if problem is not None:
                raise ValueError(f"system.coordinates: not a usable name: {problem}")
        if len(set(coords)) != len(coords):
            raise ValueError(f"system.coordinates: names must not repeat (got {coords})")
        alias = expressions.alias_problem(coords)
        if alias is not None:
            raise ValueError(f"system.coordinates: aliased names: {alias}")
        velocities = [f"{c}_dot" for c in coords]
        if len(self.params) > expressions.MAX_CONSTANTS:
            raise ValueError(f"params: at most {expressions.MAX_CONSTANTS} named constants "
                             f"(got {len(self.params)})")
        for name, value in self.params.items():
            problem = expressions.name_problem(name)
            if problem is not None:
                raise ValueError(f"params.{name}: not a usable name: {problem}")
            if name in coords or name in velocities:
                raise ValueError(f"params.{name}: a constant may not take the name of a "
                                 f"coordinate or velocity (got {value!r})")
        if sys_.L is not None and (sys_.U, sys_.T, sys_.M) != (None, None, None):
            raise ValueError("system: give L alone, or U with one of T and M (got L and "
                             + ", ".join(k for k in ("U", "T", "M")
                                         if getattr(sys_, k) is not None) + ")")
        if sys_.L is None and (sys_.U is None or (sys_.T is None) == (sys_.M is None)):
            given = [k for k in ("U", "T", "M") if getattr(sys_, k) is not None]
            raise ValueError("system: give L alone, or U with one of T and M (got "
                             f"{', '.join(given) or 'none'})")
        constants = list(self.params)
        used: set[str] = set()

        def check(key: str, text: str, names: list[str]) -> None:
            try:
                used.update(expressions.check_expression(text, names + constants))
            except expressions.ExpressionError as exc:
                hint = ("; small oscillations are about a time-independent equilibrium"
                        if "'t'" in str(exc) else "")
                raise ValueError(f"{key}: {exc}{hint}") from None

        for key in ("L", "T"):
            if getattr(sys_, key) is not None:
                check(f"system.{key}", getattr(sys_, key), coords + velocities)
        if sys_.U is not None:
            check("system.U", sys_.U, coords)
        if sys_.M is not None:
            n = len(coords)
            if len(sys_.M) != n or any(len(row) != n for row in sys_.M):
                raise ValueError(f"system.M: must be {n} × {n}, one row of {n} entries per "
                                 f"coordinate (got {[len(row) for row in sys_.M]} entries "
                                 "per row)")
            for i, row in enumerate(sys_.M):
                for j, entry in enumerate(row):
                    if isinstance(entry, str):
                        check(f"system.M.{i}.{j}", entry, coords)
        for name, value in self.params.items():
            if name not in used:
                raise ValueError(f"params.{name}: a constant no formula uses (a misspelt "
                                 f"name?) (got {value!r})")
        for name, value in sys_.guess.items():
            if name not in coords:
                raise ValueError(f"system.guess.{name}: not a coordinate of the system "
                                 f"(expected {', '.join(coords)}; got {value!r})")
        if self.units == "SI" and sys_.coordinate_unit is None:
            raise ValueError('system.coordinate_unit: units = "SI" needs the coordinates\' '
                             'unit: "rad" (angles) or "m" (lengths)')
        if self.units != "SI" and sys_.coordinate_unit is not None:
            raise ValueError(f"system.coordinate_unit: only with units = \"SI\" (got "
                             f"{sys_.coordinate_unit!r} with {unit_system(self)!r} units)")

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
    "title": "CO₂: a linear triatomic molecule (textbook Fig. 5.1)",
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


#: the classic cases, one line each (explicit keys override)
PRESETS = {
    "co2": _CO2,
    "h2o": _H2O,
    "chain": {"title": "Chain of equal masses between fixed walls",
              "chain": {"n": 6, "m": 1.0, "k": 1.0, "ends": "fixed"}},
    "coupled_pendula": {"title": "Two pendula coupled by a spring",
                        "pendula": {"n": 2, "m": 1.0, "l": 1.0, "g": 9.81, "k": 0.5}},
}
