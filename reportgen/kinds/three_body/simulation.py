"""``three_body`` simulation: the Cartesian run with its conserved quantities, pair
distances, the return after one period and, for a hierarchical triple, the light body's
osculating orbit, the lecture notes' coordinates relative to body 1 (notes (3.32)–(3.34))
and Jacobi coordinates (the standard hierarchical choice; not in the notes).  A config
with ``[restricted]`` runs the restricted problem instead (:mod:`.simulation_restricted`)."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.content import fmt, fmt_err
from ...scene.results import AuditCase, Check, Results
from ...scene.schema import ResultsSchema
from .config import FIGURE_EIGHT_PERIOD, ThreeBodyConfig
from .encounters import PAIRS, closest_approaches, distance_to_track, hierarchy, turning
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

    budget_schema = results_schema  # a choice by the config: nothing to work out

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
        e = main.invariants["energy"]
        e_err = float(np.max(np.abs(e - e[0]))) / abs(e[0]) if e[0] != 0 else math.nan
        a["energy_error_max"] = e_err
        a["energy_tolerance"] = cfg.energy_tolerance
        results.checks.append(Check("energy E(t_end)", float(e[-1]), float(e[0]), "",
                                    "E(0), conserved"))
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
        a.update(self._hierarchy_class(main))
        a.update(self._encounters(model, main, a))
        a.update(self._burrau())
        if not (e_err <= cfg.energy_tolerance):
            why = ("the close encounters are not resolved" if a["close_encounters"]
                   else "the steps do not follow the orbits")
            results.flag("unstable", f"relative energy error {fmt_err(e_err)} exceeds the "
                                     f"energy tolerance {fmt_err(cfg.energy_tolerance)}: "
                                     f"{why}; tighten the run's rtol")
        if cfg.period is not None:
            returned = self._periodicity(results, model, y0, main)
            a.update(self._choreography(main, returned))
        if a["hierarchical"]:
            self._hierarchy(results, model, main)
        # chaotic (the Pythagorean problem): the study ends before the Lyapunov time
        horizon = self.divergence(results, model, y0, t)
        if horizon < run.t_end:
            a["study_t_end"] = horizon
        a["fate"], a["behaviour"] = self._fate(main, a)
        self.study(results, model, y0, np.linspace(0.0, horizon, 201))
        return results

    #: a collision: a pair closer than this fraction of the initial size (a verdict word)
    COLLISION_FRACTION = 1e-6
    #: an escaping body is at least this many times farther from the other two's centre of
    #: mass than they are from each other
    ESCAPE_DISTANCE_RATIO = 3.0
    #: a hierarchical triple: a pair bound throughout whose largest separation is below this
    #: fraction of the third body's smallest distance from the pair's centre of mass
    HIERARCHY_SEPARATION = 0.2
    #: a close encounter: a pair's closest approach (on the continuous solution) below this
    #: fraction of its scale: the system's initial size (largest initial pair distance), or
    #: for the inner pair of a hierarchical triple its own median separation
    CLOSE_FRACTION = 0.05
    #: a periodic orbit: back after the configured period within this fraction of the initial
    #: size (the figure-eight's initial data, known to 8 digits, return to ~1e-7)
    PERIODIC_FRACTION = 1e-3
    #: a choreography: equal masses on a periodic orbit, each body starting on body 1's track
    #: over one period within this fraction of the initial size
    CHOREOGRAPHY_FRACTION = 1e-3

    @staticmethod
    def _size0(y0) -> float:
        pos0 = np.asarray(y0[:9], dtype=float).reshape(3, 3)
        return float(max(np.linalg.norm(pos0[i] - pos0[j]) for i, j in PAIRS))

    def _hierarchy_class(self, main) -> dict:
        """Whether the run is a hierarchical triple (:attr:`HIERARCHY_SEPARATION`), its
        inner pair and the scales of both orbits (:func:`.encounters.hierarchy`)."""
        h = hierarchy(main.y, self.config.params.G, self.masses)
        i, j = h["pair"]
        return {"hierarchical": bool(h["ratio"] < self.HIERARCHY_SEPARATION),
                "hierarchy_ratio": float(h["ratio"]),
                "hierarchy_threshold": self.HIERARCHY_SEPARATION,
                "inner_pair": np.array([i + 1, j + 1]),
                "inner_separation": np.array(h["inner"]),
                "outer_distance": np.array(h["outer"])}

    def _encounters(self, model, main, a) -> dict:
        """Each pair's closest approach on the continuous solution
        (:func:`.encounters.closest_approaches`), the closest of all, and whether any is a
        close encounter (:attr:`CLOSE_FRACTION` of the pair's scale)."""
        cfg = self.config
        found = closest_approaches(model.rhs, model.params, main.t, main.y, cfg.params.G,
                                   self.masses, cfg.run.rtol, cfg.run.atol)
        size0 = self._size0(main.y[0])
        scales = np.full(3, size0)
        if a["hierarchical"]:
            inner = tuple(int(v) - 1 for v in a["inner_pair"])
            scales[PAIRS.index(inner)] = float(a["inner_separation"][1])
        threshold = self.CLOSE_FRACTION * scales
        d = np.asarray(found["distance"])
        p = int(np.argmin(d))
        return {"pair_closest": d, "pair_closest_time": np.asarray(found["time"]),
                "encounter_threshold": threshold,
                "close_encounters": bool(np.any(d < threshold)),
                "closest_approach": float(d[p]),
                "closest_approach_time": float(found["time"][p]),
                "closest_approach_pair": np.array([PAIRS[p][0] + 1, PAIRS[p][1] + 1])}

    def _burrau(self) -> dict:
        """Burrau's configuration (Szebehely & Peters 1967), from the initial data: at rest,
        masses in the ratio 3 : 4 : 5 and each body opposite the side of its own length
        (to 1e-9)."""
        y0 = self._y0()
        m = self.masses
        pos = y0[:9].reshape(3, 3)
        opposite = np.array([np.linalg.norm(pos[j] - pos[k]) for j, k in ((1, 2), (0, 2),
                                                                            (0, 1))])
        ratio = opposite / m
        burrau = bool(np.all(y0[9:] == 0.0)
                      and np.allclose(np.sort(m) / np.min(m), [1.0, 4 / 3, 5 / 3], rtol=1e-9)
                      and np.ptp(ratio) <= 1e-9 * float(np.max(ratio)))
        return {"burrau": burrau}

    def _choreography(self, main, returned) -> dict:
        """Periodic (back within :attr:`PERIODIC_FRACTION` of the initial size after the
        configured period), a choreography (equal masses, each body starting on body 1's
        track over one period, :attr:`CHOREOGRAPHY_FRACTION`) and a figure-eight (a planar
        choreography whose track turns its tangent by 0 in one period, a simple loop by
        ±2π)."""
        a_period = float(self.config.period)
        size0 = self._size0(main.y[0])
        returned = float(np.max(np.linalg.norm(returned, axis=-1)))
        periodic = bool(returned < self.PERIODIC_FRACTION * size0)
        out = {"periodic": periodic, "periodic_threshold": self.PERIODIC_FRACTION * size0,
               "choreography": False, "figure_eight": False}
        m = self.masses
        one = main.t <= a_period * (1.0 + 1e-9)
        if not (periodic and np.all(m == m[0]) and main.t[-1] >= a_period * (1.0 - 1e-9)
                and np.count_nonzero(one) >= 50):
            return out
        pos, vel = core.split(main.y[one])
        gap = distance_to_track(pos[0, 1:], pos[:, 0])
        out["choreography"] = bool(np.max(gap) < self.CHOREOGRAPHY_FRACTION * size0)
        planar = float(np.ptp(pos[:, :, 2])) <= 1e-9 * max(float(np.ptp(pos[:, :, :2])), 1e-300)
        out["figure_eight"] = bool(out["choreography"] and planar
                                   and abs(turning(vel[:, 0, 0], vel[:, 0, 1])) < math.pi)
        return out

    def _fate(self, main, a: dict) -> tuple[str, str]:
        """(fate, behaviour in words) at t_end: "collision" (the closest approach below
        :attr:`COLLISION_FRACTION` of the initial size), "escape" (a body with positive
        energy relative to the other two's centre of mass, moving away from it and
        :attr:`ESCAPE_DISTANCE_RATIO` times farther from it than they are apart; the two a
        binary if their pair energy is negative), "bound" (a bound pair, and the third body
        bound to it: negative energy relative to the pair's centre of mass) or "unbound"
        (neither: no body has left yet); chaotic when ``lyapunov_time`` is known."""
        G, m, names = self.config.params.G, self.masses, self.config.names
        pos, vel = core.split(main.y[-1:])
        pos, vel = pos[0], vel[0]
        size0 = self._size0(main.y[0])
        chaos = (f"; chaotic: nearby orbits separate as exp(t/T), Lyapunov time T ≈ "
                 f"{fmt(a['lyapunov_time'], 2)}" if "lyapunov_time" in a else "")
        if a["closest_approach"] < self.COLLISION_FRACTION * size0:
            return "collision", (f"collision: two bodies come within "
                                 f"{fmt(a['closest_approach'], 2)} at t = "
                                 f"{fmt(a['closest_approach_time'], 4)}{chaos}")
        bound_to, pair_bound = {}, {}
        for i in range(3):
            j, k = (n for n in range(3) if n != i)
            mjk = m[j] + m[k]
            centre = (m[j] * pos[j] + m[k] * pos[k]) / mjk
            centre_v = (m[j] * vel[j] + m[k] * vel[k]) / mjk
            r, v = pos[i] - centre, vel[i] - centre_v
            mu = m[i] * mjk / (m[i] + mjk)
            energy = 0.5 * mu * float(v @ v) - G * m[i] * mjk / float(np.linalg.norm(r))
            pair = float(np.linalg.norm(pos[j] - pos[k]))
            dv = vel[j] - vel[k]
            pair_energy = 0.5 * m[j] * m[k] / mjk * float(dv @ dv) - G * m[j] * m[k] / pair
            bound_to[i], pair_bound[i] = energy < 0.0, pair_energy < 0.0
            if (energy > 0.0 and float(r @ v) > 0.0
                    and np.linalg.norm(r) > self.ESCAPE_DISTANCE_RATIO * pair):
                rest = (f"{names[j]} and {names[k]} form a binary" if pair_energy < 0.0
                        else f"{names[j]} and {names[k]} separate too")
                return "escape", (f"escape: {names[i]} (m = {fmt(m[i])}) leaves on a "
                                  f"hyperbolic orbit; {rest}{chaos}")
        end = fmt(float(main.t[-1]), 4)
        for i in range(3):
            if pair_bound[i] and bound_to[i]:
                j, k = (n for n in range(3) if n != i)
                return "bound", (f"bound: at t = {end} {names[j]} and {names[k]} are a bound "
                                 f"pair and {names[i]} is bound to it{chaos}")
        return "unbound", (f"no escape yet: at t = {end} no body is bound to a bound pair, but "
                           f"none has left{chaos}")

    def _periodicity(self, results, model, y0, main) -> np.ndarray:
        """Integrate exactly to t = period (same method and tolerances) and compare with y0;
        returns r_i(T) − r_i(0), shape (3, 3)."""
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
            return pos1[0] - pos0[0]
        results.checks.append(Check("max |rᵢ(T) − rᵢ(0)| after one period", dpos, 0.0, "",
                                    "periodic orbit, T = 6.32591398 (Chenciner & Montgomery "
                                    "2000; Simó)" if preset == "figure_eight"
                                    and T == FIGURE_EIGHT_PERIOD
                                    else f"periodic orbit, T = {fmt(T)} (config)", scale=1.0))
        return pos1[0] - pos0[0]

    #: the inner pair's relative orbit is near-Keplerian when its osculating semi-major
    #: axis varies by less than this fraction of its mean over the run
    KEPLER_SPREAD = 0.1

    def _hierarchy(self, results, model, main):
        """Osculating Kepler elements of the inner pair's lighter body about the heavier
        (the first when equal): the "moon" about its "primary"; the kinetic energy in the
        notes' coordinates (notes (3.32)–(3.34), with its cross term) and in Jacobi
        coordinates, each against the Cartesian one; the curves the moon section draws
        (relative track, both sets of coordinates)."""
        G, m, names = self.config.params.G, self.masses, self.config.names
        y = main.y
        pos, vel = core.split(y)
        a = results.analysis
        i, j = (int(v) - 1 for v in a["inner_pair"])
        primary, moon = (j, i) if m[i] < m[j] else (i, j)
        a["moon_pair"] = np.array([primary + 1, moon + 1])
        a["mass_ratios"] = {"m2_m1": float(m[1] / m[0]), "m3_m1": float(m[2] / m[0])}
        rel = pos[:, moon] - pos[:, primary]
        relv = vel[:, moon] - vel[:, primary]
        a["moon_relative_position"] = rel
        # the moon's osculating orbit about its primary (two-body elements, K = G(mp + mm))
        K = G * (m[primary] + m[moon])
        orbit = core.osculating_orbit(rel[0], relv[0], K)
        a["moon_inclination"] = orbit["inclination"]
        a["moon_semi_major_axis"] = orbit["semi_major_axis"]
        a["moon_kepler_period"] = orbit["period"]
        along = 1.0 / (2.0 / np.linalg.norm(rel, axis=1) - np.sum(relv * relv, axis=1) / K)
        a["moon_semi_major_axis_spread"] = float(np.ptp(along) / abs(np.mean(along)))
        a["kepler_spread_threshold"] = self.KEPLER_SPREAD
        # sidereal period measured from the angle of the relative track in its initial plane
        turns = core.revolutions(rel, orbit["normal"])
        if turns >= 1.0:  # compared in the report, not a check: the tide shifts it
            a["moon_period_measured"] = float(main.t[-1] - main.t[0]) / turns
        tight = self.reference_run(model, self._y0(), main.t[[0, -1]])
        pos_ref, _ = core.split(tight[-1])
        d_ref = float(np.linalg.norm((pos_ref[0, moon] - pos_ref[0, primary]) - rel[-1]))
        a["moon_reference_error"] = d_ref
        results.checks.append(Check(f"{names[moon]} about {names[primary]} at t_end: |Δr| "
                                    "against a DOP853 run at rtol 1e-14", d_ref, 0.0,
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
