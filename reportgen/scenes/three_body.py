r"""``three_body``: three gravitating bodies (lecture notes §3, eqs. 3.32–3.35).

Arbitrary masses and states, and presets: the Sun–Earth–Moon system with the
notes' mass ratios m2/m1 ~ 1e-6, m3/m1 ~ 1e-8 (3.35) and its Jacobi coordinates
(3.32–3.34); the Chenciner–Montgomery figure-eight; Burrau's Pythagorean problem
with its close encounters.  Energy, total momentum and angular momentum are the
conserved quantities; a run whose energy error exceeds ``energy_tolerance`` is
flagged unstable, never drawn silently.

Archive columns: x1, y1, z1, x2, y2, z2, x3, y3, z3 (positions body by body), then
vx1, vy1, vz1, …, vz3 in the same order.
"""

from __future__ import annotations

import math
from typing import Annotated

import numpy as np
from pydantic import Field, model_validator

from ..config import Positive, Real, RunConfig, Strict
from ..core.models import kepler as kepler_core
from ..core.models import nbody as core
from ..plots import gravitation as plots
from ..results import Check, Results
from .base import Scene, SceneConfig, Section, SectionContent, Table, fmt, fmt_err
from .shared import error_vs_runtime_section, invariants_section

Vector3 = Annotated[list[Real], Field(min_length=3, max_length=3)]


class Params(Strict):
    G: Positive = Field(1.0, description="gravitational constant (in the config's units)")
    masses: list[Positive] = Field(min_length=3, max_length=3,
                                   description="[m1, m2, m3]")


class Initial(Strict):
    positions: list[Vector3] = Field(min_length=3, max_length=3,
                                     description="[[x, y, z] × 3] of bodies 1, 2, 3")
    velocities: list[Vector3] = Field(min_length=3, max_length=3,
                                      description="[[vx, vy, vz] × 3] of bodies 1, 2, 3")


class ThreeBodyConfig(SceneConfig):
    params: Params
    initial: Initial
    run: RunConfig
    names: list[str] = Field(["body 1", "body 2", "body 3"], min_length=3, max_length=3,
                             description="labels of the bodies in figures")
    length_unit: str = Field("", max_length=20, description="unit of length shown on axes")
    time_unit: str = Field("", max_length=20, description="unit of time shown on axes")
    period: Positive | None = Field(None, description="known period of a periodic orbit: "
                                                      "checks the return to the start")
    energy_tolerance: Positive = Field(1e-8, description="relative energy error above which "
                                                         "the run is flagged unstable")

    @model_validator(mode="after")
    def _no_collision(self):
        pos = np.asarray(self.initial.positions, dtype=float)
        for i in range(3):
            for j in range(i + 1, 3):
                if np.array_equal(pos[i], pos[j]):
                    raise ValueError(f"initial.positions: bodies {i + 1} and {j + 1} start at "
                                     f"the same point {pos[i].tolist()} (a collision)")
        return self


def _sun_earth_moon() -> dict:
    """Sun, Earth, Moon in AU, years, solar masses (G = 4π²); centre of mass at rest at 0.

    Masses: Earth/Sun 3.0035e-6, Moon/Sun 3.6943e-8 (IAU 2012 values; the notes' ~1e-6 and
    ~1e-8, 3.35).  Earth on a circular orbit at 1 AU, the Moon at 384 400 km = 0.0025696 AU
    on a circular orbit about the Earth inclined 5.145° to the ecliptic.
    """
    G = 4 * math.pi**2
    m = np.array([1.0, 3.0035e-6, 3.6943e-8])
    d, inc = 0.0025696, math.radians(5.145)
    r = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0 + d, 0.0, 0.0]])
    v_earth = math.sqrt(G * m.sum())
    v_moon = math.sqrt(G * (m[1] + m[2]) / d)
    v = np.array([[0.0, 0.0, 0.0], [0.0, v_earth, 0.0],
                  [0.0, v_earth + v_moon * math.cos(inc), v_moon * math.sin(inc)]])
    r -= m @ r / m.sum()
    v -= m @ v / m.sum()
    return {"params": {"G": G, "masses": m.tolist()},
            "initial": {"positions": r.tolist(), "velocities": v.tolist()},
            "names": ["Sun", "Earth", "Moon"], "length_unit": "AU", "time_unit": "yr",
            "run": {"t_end": 1.0, "samples": 8001}}


# Chenciner & Montgomery (2000), initial conditions of Simó: x1 = −x2, x3 = 0,
# v1 = v2 = −v3/2, G = m = 1; period 6.32591398 (Simó 2002, Table 1).
_V3 = (-0.93240737, -0.86473146)
FIGURE_EIGHT_PERIOD = 6.32591398

PRESETS = {
    "sun_earth_moon": _sun_earth_moon(),
    "figure_eight": {
        "params": {"G": 1.0, "masses": [1.0, 1.0, 1.0]},
        "initial": {"positions": [[0.97000436, -0.24308753, 0.0],
                                  [-0.97000436, 0.24308753, 0.0], [0.0, 0.0, 0.0]],
                    "velocities": [[-_V3[0] / 2, -_V3[1] / 2, 0.0],
                                   [-_V3[0] / 2, -_V3[1] / 2, 0.0], [_V3[0], _V3[1], 0.0]]},
        "period": FIGURE_EIGHT_PERIOD,
        "run": {"t_end": FIGURE_EIGHT_PERIOD, "samples": 2001},
    },
    # Burrau's problem: masses 3, 4, 5 at rest at the vertices of a 3-4-5 triangle, each
    # opposite the side of its own length (Szebehely & Peters 1967).
    "pythagorean": {
        "params": {"G": 1.0, "masses": [3.0, 4.0, 5.0]},
        "initial": {"positions": [[1.0, 3.0, 0.0], [-2.0, -1.0, 0.0], [1.0, -1.0, 0.0]],
                    "velocities": [[0.0, 0.0, 0.0]] * 3},
        "run": {"t_end": 70.0, "samples": 14001, "rtol": 1e-13, "atol": 1e-15},
    },
}

#: m3/m2 and m2/m1 below this make a hierarchical triple (planet + moon; Moon/Earth = 0.0123)
HIERARCHY_RATIO = 0.05


class ThreeBodyScene(Scene):
    kind = "three_body"
    summary = "three gravitating bodies: Sun–Earth–Moon (Jacobi coordinates), figure-eight, " \
              "Pythagorean problem"
    Config = ThreeBodyConfig
    presets = PRESETS
    sections = (
        Section("orbits", "Orbits", integrates=True),
        Section("moon", "The light body about its primary; Jacobi coordinates",
                integrates=True),
        Section("periodicity", "Return after one period", integrates=True),
        Section("encounters", "Pair distances and close encounters", integrates=True),
        Section("invariants", "Energy, momentum and angular momentum", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

    @classmethod
    def audit_cases(cls):
        from ..audit import AuditCase

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
        return m[1] / m[0] < HIERARCHY_RATIO and m[2] / m[1] < HIERARCHY_RATIO

    def default_sections(self):
        names = [s.name for s in self.sections]
        if not self.hierarchical:
            names.remove("moon")
        if self.config.period is None:
            names.remove("periodicity")
        return names

    def _y0(self):
        ini = self.config.initial
        return np.concatenate([np.ravel(ini.positions), np.ravel(ini.velocities)]).astype(float)

    def _scales(self) -> dict:
        """Natural sizes: |potential energy|, and momenta m √(G M/ℓ) for the mean distance ℓ."""
        G, m = self.config.params.G, self.masses
        pos, _ = core.split(self._y0())
        r = np.array(core.pair_distances(pos))[:, 0]
        pot = G * (m[0] * m[1] / r[0] + m[0] * m[2] / r[1] + m[1] * m[2] / r[2])
        ell = float(np.mean(r))
        speed = math.sqrt(G * m.sum() / ell)
        y0 = self._y0()
        _, vel = core.split(y0)
        p_scale = max(float(np.sum(m * np.linalg.norm(vel[0], axis=1))), float(m.sum()) * speed)
        l_scale = max(float(np.sum(m * np.linalg.norm(pos[0], axis=1)))
                      * float(np.max(np.linalg.norm(vel[0], axis=1))), float(m.sum()) * ell * speed)
        out = {"energy": max(abs(float(core.energy(y0, G, m)[0])), pot)}
        out.update({f"momentum_{c}": p_scale for c in "xyz"})
        out.update({f"angular_momentum_{c}": l_scale for c in "xyz"})
        return out

    def _invariants(self, t, y):
        G, m = self.config.params.G, self.masses
        P, L = core.momentum(y, m), core.angular_momentum(y, m)
        inv = {"energy": core.energy(y, G, m)}
        inv.update({f"momentum_{c}": P[:, i] for i, c in enumerate("xyz")})
        inv.update({f"angular_momentum_{c}": L[:, i] for i, c in enumerate("xyz")})
        return inv

    # --------------------------------------------------------------- simulation
    def simulate(self, progress=None) -> Results:
        run, cfg = self.config.run, self.config
        G, m = cfg.params.G, self.masses
        model = core.model(G, m)
        y0 = self._y0()
        t = np.linspace(0.0, run.t_end, run.samples)
        results = Results()
        main = self.integrate(model, y0, t, invariants=self._invariants,
                              invariant_scales=self._scales(), progress=progress,
                              n_periods=run.t_end / cfg.period if cfg.period else None)
        results.runs["main"] = main
        a = results.analysis
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
                                    "P(0), conserved", scale=self._scales()["momentum_x"]))
        pos, _ = core.split(main.y)
        dists = np.array(core.pair_distances(pos))
        a["min_pair_distance"] = float(np.min(dists))
        a["min_pair_distance_time"] = float(main.t[np.argmin(np.min(dists, axis=0))])
        if cfg.period is not None:
            self._periodicity(results, model, y0, main)
        if self.hierarchical:
            self._hierarchy(results, main)
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201))
        return results

    def _periodicity(self, results, model, y0, main):
        """Integrate exactly to t = period (same method and tolerances) and compare with y0."""
        from ..core.integrators import integrate

        T, run = self.config.period, self.config.run
        sol = integrate(model, y0, np.array([0.0, T]), method=str(main.attrs["method"]),
                        rtol=run.rtol, atol=run.atol, h=run.h)
        pos0, vel0 = core.split(y0)
        pos1, vel1 = core.split(sol.y[-1])
        dpos = float(np.max(np.linalg.norm(pos1[0] - pos0[0], axis=1)))
        dvel = float(np.max(np.linalg.norm(vel1[0] - vel0[0], axis=1)))
        results.analysis.update({"period": T, "return_position_error": dpos,
                                 "return_velocity_error": dvel})
        results.checks.append(Check("max |r_i(T) − r_i(0)| after one period", dpos, 0.0, "",
                                    "periodic orbit, T = 6.32591398 (Chenciner & Montgomery "
                                    "2000; Simó)" if T == FIGURE_EIGHT_PERIOD
                                    else f"periodic orbit, T = {T:g} (config)", scale=1.0))

    def _hierarchy(self, results, main):
        """Osculating Kepler elements of the primary pair and of body 3 about body 2; the
        Jacobi kinetic energy (3.33) against the Cartesian one."""
        G, m = self.config.params.G, self.masses
        y = main.y
        pos, vel = core.split(y)
        a = results.analysis
        rel = pos[:, 2] - pos[:, 1]
        relv = vel[:, 2] - vel[:, 1]
        # the Moon's osculating orbit about the Earth (two-body elements, K = G(m2 + m3))
        h_vec = np.cross(rel[0], relv[0])
        n_hat = h_vec / np.linalg.norm(h_vec)
        a["moon_inclination"] = float(math.acos(n_hat[2]))
        K = G * (m[1] + m[2])
        r0, v0 = np.linalg.norm(rel[0]), np.linalg.norm(relv[0])
        eps = 0.5 * v0**2 - K / r0
        a["moon_semi_major_axis"] = -K / (2 * eps)
        a["moon_kepler_period"] = 2 * math.pi * math.sqrt(a["moon_semi_major_axis"] ** 3 / K)
        # sidereal period measured from the angle of the relative track in its initial plane
        e1 = rel[0] / np.linalg.norm(rel[0])
        e2 = np.cross(n_hat, e1)
        ang = np.unwrap(np.arctan2(rel @ e2, rel @ e1))
        turns = (ang[-1] - ang[0]) / (2 * math.pi)
        if turns >= 1.0:  # compared in the report, not a check: the Sun's tide shifts it
            a["moon_period_measured"] = float(main.t[-1] - main.t[0]) / turns
        from ..core.integrators import integrate

        tight = integrate(core.model(G, m), self._y0(), main.t[[0, -1]], method="dop853",
                          rtol=1e-14, atol=1e-16)
        pos_ref, _ = core.split(tight.y[-1])
        d_ref = float(np.linalg.norm((pos_ref[0, 2] - pos_ref[0, 1]) - rel[-1]))
        a["moon_reference_error"] = d_ref
        results.checks.append(Check(f"{self.config.names[2]} about {self.config.names[1]} at "
                                    "t_end: |Δr| against a DOP853 run at rtol 1e-14", d_ref, 0.0,
                                    self.config.length_unit, "independent tighter integration",
                                    scale=float(np.linalg.norm(rel[0]))))
        T_jac = core.jacobi_kinetic_energy(y, m)
        T_cart = core.cartesian_kinetic_energy(y, m)
        a["jacobi_kinetic_identity_error"] = float(np.max(np.abs(T_jac - T_cart) / T_cart))
        M, mu1, mu2 = core.jacobi_masses(m)
        a["jacobi_masses"] = np.array([M, mu1, mu2])
        el = kepler_core.orbital_elements(*pos[0, 1, :2] - pos[0, 0, :2],
                                          *vel[0, 1, :2] - vel[0, 0, :2], G * (m[0] + m[1]))
        a["earth_eccentricity"] = el["eccentricity"]

    # ------------------------------------------------------------------ report
    def headline(self, data):
        p, a = self.config.params, data.analysis
        names = self.config.names
        out = [("bodies", ", ".join(f"{n}: m = {fmt(x)}" for n, x in zip(names, p.masses,
                                                                          strict=True))
                + f"; G = {fmt(p.G)}"),
               ("energy error", f"max relative |E(t) − E(0)|/|E(0)| = "
                                f"{fmt_err(a['energy_error_max'])} (tolerance "
                                f"{fmt_err(a['energy_tolerance'])})"),
               ("closest approach", f"{fmt(a['min_pair_distance'])} at t ≈ "
                                    f"{fmt(a['min_pair_distance_time'])}")]
        if "return_position_error" in a:
            out.append(("return after one period",
                        f"max |r_i(T) − r_i(0)| = {fmt_err(a['return_position_error'])}"))
        if "moon_period_measured" in a:
            out.append(("Moon about the Earth", f"period {fmt(a['moon_period_measured'], 8)} "
                        f"{self.config.time_unit} (Kepler two-body "
                        f"{fmt(a['moon_kepler_period'], 8)})"))
        return out

    def section_orbits(self, data):
        run = data.runs["main"]
        pos, _ = core.split(run.y)
        fig = plots.three_body_orbits(pos, labels=self.config.names,
                                      length_unit=self.config.length_unit)
        figures = [self.figure("orbits", fig, "Tracks of the three bodies projected on the "
                               "x–y plane.")]
        if np.ptp(pos[:, :, 2]) > 1e-3 * np.ptp(pos[:, :, :2]) and not self.hierarchical:
            fig2 = plots.three_body_orbits(pos, labels=self.config.names,
                                           length_unit=self.config.length_unit, plane=(0, 2))
            figures.append(self.figure("orbits_xz", fig2, "The same tracks in the x–z plane."))
        return SectionContent(figures=figures)

    def section_moon(self, data):
        run, a = data.runs["main"], data.analysis
        pos, _ = core.split(run.y)
        names, unit = self.config.names, self.config.length_unit
        rel = pos[:, 2] - pos[:, 1]
        fig = plots.relative_track(rel[:, 0], rel[:, 1], label=f"{names[2]} − {names[1]}",
                                   centre_label=names[1], length_unit=unit)
        (_, rho1, rho2), _ = core.jacobi(run.y, self.masses)
        fig2 = plots.three_body_orbits(
            np.stack([rho1, rho2, np.zeros_like(rho1)], axis=1)[:, :2],
            labels=["ρ1 = r2 − r1", "ρ2 = r3 − (m1 r1 + m2 r2)/(m1 + m2)"],
            length_unit=unit)
        M, mu1, mu2 = np.asarray(a["jacobi_masses"])
        facts = [("mass ratios (3.35)", f"m2/m1 = {fmt(self.masses[1] / self.masses[0])}, "
                                        f"m3/m1 = {fmt(self.masses[2] / self.masses[0])}"),
                 ("Jacobi masses (3.33)", f"M = {fmt(M)}, μ1 = {fmt(mu1)}, μ2 = {fmt(mu2)}"),
                 ("max |T_Jacobi − T_Cartesian| / T", fmt_err(a["jacobi_kinetic_identity_error"])),
                 (f"{names[2]}'s orbit about {names[1]}",
                  f"a = {fmt(a['moon_semi_major_axis'])} {unit}, inclination "
                  f"{fmt(math.degrees(a['moon_inclination']), 5)}°")]
        rows = []
        if "moon_period_measured" in a:
            rows.append(["sidereal period, measured", fmt(a["moon_period_measured"], 10)])
        rows.append(["two-body Kepler period", fmt(a["moon_kepler_period"], 10)])
        return SectionContent(
            figures=[self.figure("moon", fig, f"{names[2]}'s track relative to {names[1]}: a "
                                 "near-Keplerian ellipse slowly perturbed by the Sun's tide."),
                     self.figure("jacobi", fig2, "Jacobi coordinates (3.32): ρ1, the inner "
                                 "pair's separation, and ρ2, the third body from the inner "
                                 "pair's centre of mass (x–y projection).")],
            facts=facts,
            tables=[Table(caption=f"{names[2]}'s period about {names[1]} "
                                  f"[{self.config.time_unit}]", header=["", "value"],
                          rows=rows)])

    def section_periodicity(self, data):
        a = data.analysis
        return SectionContent(facts=[
            ("period T", fmt(a["period"], 12)),
            ("max |r_i(T) − r_i(0)|", fmt_err(a["return_position_error"])),
            ("max |v_i(T) − v_i(0)|", fmt_err(a["return_velocity_error"]))])

    def section_encounters(self, data):
        run = data.runs["main"]
        pos, _ = core.split(run.y)
        r12, r13, r23 = core.pair_distances(pos)
        n = self.config.names
        fig = plots.closest_approach(run.t, {f"{n[0]}–{n[1]}": r12, f"{n[0]}–{n[2]}": r13,
                                             f"{n[1]}–{n[2]}": r23},
                                     time_unit=self.config.time_unit)
        a = data.analysis
        return SectionContent(
            figures=[self.figure("pair_distances", fig, "Distances between the bodies (log "
                                 "scale); close encounters are the deep minima, sampled at the "
                                 "stored times only.")],
            facts=[("smallest stored pair distance", f"{fmt(a['min_pair_distance'])} at t ≈ "
                                                     f"{fmt(a['min_pair_distance_time'])}")])

    def section_invariants(self, data):
        return invariants_section(self, data, scales=self._scales(),
                                  caption="Drift of energy (relative to the initial potential "
                                          "energy), total momentum and angular momentum "
                                          "(relative to natural momentum scales).")

    def section_error_vs_runtime(self, data):
        return error_vs_runtime_section(self, data)
