"""``three_body`` simulation: the Cartesian run with its conserved quantities, pair
distances, the return after one period and, for a hierarchical triple, the light body's
osculating orbit, the lecture notes' coordinates relative to body 1 (notes (3.32)–(3.34))
and Jacobi coordinates (the standard hierarchical choice; not in the notes).  A config
with ``[restricted]`` runs the restricted problem instead (:mod:`.simulation_restricted`)."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.results import AuditCase, Check, Results
from ...scene.schema import ResultsSchema
from .config import FIGURE_EIGHT_PERIOD, HIERARCHY_RATIO, ThreeBodyConfig
from .results import RESTRICTED_SCHEMA, SCHEMA
from .simulation_restricted import SECTION, RestrictedSimulation

core = lazy_module("reportgen.core.models.nbody")
kepler_core = lazy_module("reportgen.core.models.kepler")
integrators = lazy_module("reportgen.core.integrators")


class ThreeBodySimulation(RestrictedSimulation):
    """Three bodies under Newtonian gravity, integrated in Cartesian coordinates (or, with
    ``[restricted]``, the restricted problem: :class:`.RestrictedSimulation`)."""

    #: labels of both problems' results (the report's); each run stores its own
    #: (:meth:`results_schema`)
    schema = SCHEMA.merged(RESTRICTED_SCHEMA)
    config: ThreeBodyConfig
    #: a restricted sweep's members compute their crossings only for its section
    computed_on_request = ("error_vs_runtime", SECTION)

    def results_schema(self) -> ResultsSchema:
        return RESTRICTED_SCHEMA if self.config.restricted is not None else SCHEMA

    @classmethod
    def audit_cases(cls):
        return [AuditCase(
            name="Pythagorean three-body problem to t = 70",
            what="masses 3, 4, 5 from rest: close encounters down to ~1e-4 before a binary "
                 "forms and the lightest body escapes (Szebehely & Peters 1967)",
            methods=("dop853", "gauss6"),
            config={"kind": "three_body", "title": "Pythagorean", "preset": "pythagorean"})]

    @property
    def masses(self) -> np.ndarray:
        return np.asarray(self.config.params.masses, dtype=np.float64)

    @property
    def hierarchical(self) -> bool:
        m = self.masses
        return bool(m[1] / m[0] < HIERARCHY_RATIO and m[2] / m[1] < HIERARCHY_RATIO)

    def _y0(self):
        ini = self.config.initial
        return np.concatenate([np.ravel(ini.positions), np.ravel(ini.velocities)]).astype(float)

    def _invariants(self, t, y):
        G, m = self.config.params.G, self.masses
        P, L = core.momentum(y, m), core.angular_momentum(y, m)
        inv = {"energy": core.energy(y, G, m)}
        inv.update({f"momentum_{c}": P[:, i] for i, c in enumerate("xyz")})
        inv.update({f"angular_momentum_{c}": L[:, i] for i, c in enumerate("xyz")})
        return inv

    # --------------------------------------------------------------- simulation
    def models(self) -> list:
        if self.config.restricted is not None:
            return [self.restricted_model()]
        return [core.model(self.config.params.G, self.masses)]

    def simulate(self, progress=None) -> Results:
        if self.config.restricted is not None:
            return self.simulate_restricted(progress)
        run, cfg = self.config.run, self.config
        G, m = cfg.params.G, self.masses
        (model,) = self.models()
        y0 = self._y0()
        t = np.linspace(0.0, run.t_end, run.samples)
        scales = core.natural_scales(y0, G, m)
        results = Results()
        main = self.integrate(model, y0, t, invariants=self._invariants,
                              invariant_scales=scales, progress=progress,
                              n_periods=run.t_end / cfg.period if cfg.period else None)
        results.runs["main"] = main
        a = results.analysis
        a["hierarchical"] = self.hierarchical
        e = main.invariants["energy"]
        e_err = float(np.max(np.abs(e - e[0]))) / abs(e[0]) if e[0] != 0 else math.nan
        a["energy_error_max"] = e_err
        a["energy_tolerance"] = cfg.energy_tolerance
        results.checks.append(Check("energy E(t_end)", float(e[-1]), float(e[0]), "",
                                    "E(0), conserved"))
        if not (e_err <= cfg.energy_tolerance):
            results.flag("unstable", f"relative energy error {e_err:.2e} exceeds "
                                     f"energy_tolerance = {cfg.energy_tolerance:.0e}: the "
                                     "close encounters are not resolved; tighten run.rtol")
        P = core.momentum(main.y, m)
        results.checks.append(Check("|P(t_end) − P(0)| (total momentum)",
                                    float(np.linalg.norm(P[-1] - P[0])), 0.0, "",
                                    "P(0), conserved", scale=scales["momentum_x"]))
        pos, _ = core.split(main.y)
        r12, r13, r23 = core.pair_distances(pos)
        dists = np.array([r12, r13, r23])
        a["pair_distances"] = {"r12": r12, "r13": r13, "r23": r23}
        a["min_pair_distance"] = float(np.min(dists))
        a["min_pair_distance_time"] = float(main.t[np.argmin(np.min(dists, axis=0))])
        if cfg.period is not None:
            self._periodicity(results, model, y0, main)
        if self.hierarchical:
            self._hierarchy(results, model, main)
        # chaotic (the Pythagorean problem): the study ends before the Lyapunov time
        horizon = self.divergence(results, model, y0, t)
        if horizon < run.t_end:
            a["study_t_end"] = horizon
        a["behaviour"] = self._fate(main, a)
        self.study(results, model, y0, np.linspace(0.0, horizon, 201))
        return results

    #: a pair closer than this fraction of the initial size has collided (a verdict word)
    COLLISION_FRACTION = 1e-6
    #: an escaping body is at least this many times farther from the other two's centre of
    #: mass than they are from each other
    ESCAPE_DISTANCE_RATIO = 3.0

    def _fate(self, main, a: dict) -> str:
        """The physical behaviour at t_end, in words: a collision, an escape (a body on a
        hyperbolic orbit away from the other two's centre of mass, the two a binary if
        their pair energy is negative), or bound; chaotic when ``lyapunov_time`` is known."""
        G, m, names = self.config.params.G, self.masses, self.config.names
        pos, vel = core.split(main.y[-1:])
        pos, vel = pos[0], vel[0]
        pos0 = core.split(main.y[:1])[0][0]
        size0 = float(np.max(np.linalg.norm(pos0[:, None] - pos0[None], axis=-1)))
        chaos = (f"; chaotic: nearby orbits separate as exp(t/T), Lyapunov time T ≈ "
                 f"{a['lyapunov_time']:.2g}" if "lyapunov_time" in a else "")
        if a["min_pair_distance"] < self.COLLISION_FRACTION * size0:
            return (f"collision: two bodies come within {a['min_pair_distance']:.2g} at t = "
                    f"{a['min_pair_distance_time']:.4g}{chaos}")
        for i in range(3):
            j, k = (n for n in range(3) if n != i)
            mjk = m[j] + m[k]
            centre = (m[j] * pos[j] + m[k] * pos[k]) / mjk
            centre_v = (m[j] * vel[j] + m[k] * vel[k]) / mjk
            r, v = pos[i] - centre, vel[i] - centre_v
            mu = m[i] * mjk / (m[i] + mjk)
            energy = 0.5 * mu * float(v @ v) - G * m[i] * mjk / float(np.linalg.norm(r))
            pair = float(np.linalg.norm(pos[j] - pos[k]))
            if (energy > 0.0 and float(r @ v) > 0.0
                    and np.linalg.norm(r) > self.ESCAPE_DISTANCE_RATIO * pair):
                dv = vel[j] - vel[k]
                pair_energy = (0.5 * m[j] * m[k] / mjk * float(dv @ dv)
                               - G * m[j] * m[k] / pair)
                rest = (f"{names[j]} and {names[k]} form a binary" if pair_energy < 0.0
                        else f"{names[j]} and {names[k]} separate too")
                return (f"escape: {names[i]} (m = {m[i]:g}) leaves on a hyperbolic orbit; "
                        f"{rest}{chaos}")
        return f"bound: no body escapes by t = {main.t[-1]:.4g}{chaos}"

    def _periodicity(self, results, model, y0, main):
        """Integrate exactly to t = period (same method and tolerances) and compare with y0."""
        T, run = self.config.period, self.config.run
        sol = integrators.integrate(model, y0, np.array([0.0, T]),
                                    method=str(main.attrs["method"]),
                                    rtol=run.rtol, atol=run.atol, h=run.h)
        pos0, vel0 = core.split(y0)
        pos1, vel1 = core.split(sol.y[-1])
        dpos = float(np.max(np.linalg.norm(pos1[0] - pos0[0], axis=1)))
        dvel = float(np.max(np.linalg.norm(vel1[0] - vel0[0], axis=1)))
        results.analysis.update({"period": T, "return_position_error": dpos,
                                 "return_velocity_error": dvel})
        preset = self.config.preset
        if (preset is not None and self.presets.get(preset, {}).get("period") == T
                and self.preset_as_given(self.config) is None):
            # the preset's period inherited by a changed scene (the figure-eight with one
            # mass changed): not this orbit's period, so no check against a return; the
            # report states the return distance as the physics
            return
        results.checks.append(Check("max |rᵢ(T) − rᵢ(0)| after one period", dpos, 0.0, "",
                                    "periodic orbit, T = 6.32591398 (Chenciner & Montgomery "
                                    "2000; Simó)" if preset == "figure_eight"
                                    and T == FIGURE_EIGHT_PERIOD
                                    else f"periodic orbit, T = {T:g} (config)", scale=1.0))

    def _hierarchy(self, results, model, main):
        """Osculating Kepler elements of the primary pair and of body 3 about body 2; the
        kinetic energy in the notes' coordinates (notes (3.32)–(3.34), with its cross term)
        and in Jacobi coordinates, each against the Cartesian one; the curves the moon
        section draws (relative track, both sets of coordinates)."""
        G, m = self.config.params.G, self.masses
        y = main.y
        pos, vel = core.split(y)
        a = results.analysis
        a["mass_ratios"] = {"m2_m1": float(m[1] / m[0]), "m3_m1": float(m[2] / m[0])}
        rel = pos[:, 2] - pos[:, 1]
        relv = vel[:, 2] - vel[:, 1]
        a["moon_relative_position"] = rel
        # the Moon's osculating orbit about the Earth (two-body elements, K = G(m2 + m3))
        orbit = core.osculating_orbit(rel[0], relv[0], G * (m[1] + m[2]))
        a["moon_inclination"] = orbit["inclination"]
        a["moon_semi_major_axis"] = orbit["semi_major_axis"]
        a["moon_kepler_period"] = orbit["period"]
        # sidereal period measured from the angle of the relative track in its initial plane
        turns = core.revolutions(rel, orbit["normal"])
        if turns >= 1.0:  # compared in the report, not a check: the Sun's tide shifts it
            a["moon_period_measured"] = float(main.t[-1] - main.t[0]) / turns
        tight = self.reference_run(model, self._y0(), main.t[[0, -1]])
        pos_ref, _ = core.split(tight[-1])
        d_ref = float(np.linalg.norm((pos_ref[0, 2] - pos_ref[0, 1]) - rel[-1]))
        a["moon_reference_error"] = d_ref
        results.checks.append(Check(f"{self.config.names[2]} about {self.config.names[1]} at "
                                    "t_end: |Δr| against a DOP853 run at rtol 1e-14", d_ref, 0.0,
                                    self.config.length_unit, "independent tighter integration",
                                    scale=float(np.linalg.norm(rel[0]))))
        T_cart = core.cartesian_kinetic_energy(y, m)
        # the notes' coordinates r12 = r2 − r1, r13 = r3 − r1 (notes (3.32)–(3.34)): their
        # kinetic energy, cross term included, from the stored velocities
        (_, r12, r13), _ = core.notes_coordinates(y, m)
        a["notes_coordinates"] = {"r12": r12, "r13": r13}
        a["notes_mass_matrix"] = core.notes_mass_matrix(m)
        T_notes = core.notes_kinetic_energy(y, m)
        a["notes_kinetic_identity_error"] = float(np.max(np.abs(T_notes - T_cart) / T_cart))
        a["notes_cross_term_share"] = float(np.max(np.abs(core.notes_kinetic_cross_term(y, m))
                                                   / T_cart))
        # Jacobi coordinates (the standard hierarchical choice; not in the notes)
        T_jac = core.jacobi_kinetic_energy(y, m)
        a["jacobi_kinetic_identity_error"] = float(np.max(np.abs(T_jac - T_cart) / T_cart))
        M, mu1, mu2 = core.jacobi_masses(m)
        a["jacobi_masses"] = np.array([M, mu1, mu2])
        (_, rho1, rho2), _ = core.jacobi(y, m)
        a["jacobi_coordinates"] = {"rho1": rho1, "rho2": rho2}
        el = kepler_core.orbital_elements(*pos[0, 1, :2] - pos[0, 0, :2],
                                          *vel[0, 1, :2] - vel[0, 0, :2], G * (m[0] + m[1]))
        a["earth_eccentricity"] = el["eccentricity"]

    # ------------------------------------------------------------------ sweeps
    @staticmethod
    def member_points(results) -> dict:
        return RestrictedSimulation.restricted_points(results)

    def sweep_extras(self, sweep) -> dict:
        return self.restricted_extras(sweep) if self.config.restricted is not None else {}

    def sweep_checks(self, sweep) -> list[Check]:
        return self.restricted_checks(sweep) if self.config.restricted is not None else []
