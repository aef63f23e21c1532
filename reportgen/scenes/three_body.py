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
from ..lazy import lazy_module
from ..results import AuditCase, Check, Results
from .base import Scene, SceneConfig, Section, SectionContent, Table, fmt, fmt_err

plots = lazy_module("reportgen.plots.gravitation")
core = lazy_module("reportgen.core.models.nbody")
kepler_core = lazy_module("reportgen.core.models.kepler")
integrators = lazy_module("reportgen.core.integrators")

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
    order = 40
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
        return [core.model(self.config.params.G, self.masses)]

    def simulate(self, progress=None) -> Results:
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
        self.study(results, model, y0, np.linspace(0.0, run.t_end, 201))
        return results

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
        results.checks.append(Check("max |r_i(T) − r_i(0)| after one period", dpos, 0.0, "",
                                    "periodic orbit, T = 6.32591398 (Chenciner & Montgomery "
                                    "2000; Simó)" if T == FIGURE_EIGHT_PERIOD
                                    else f"periodic orbit, T = {T:g} (config)", scale=1.0))

    def _hierarchy(self, results, model, main):
        """Osculating Kepler elements of the primary pair and of body 3 about body 2; the
        Jacobi kinetic energy (3.33) against the Cartesian one; the curves the moon section
        draws (relative track, Jacobi coordinates)."""
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
        T_jac = core.jacobi_kinetic_energy(y, m)
        T_cart = core.cartesian_kinetic_energy(y, m)
        a["jacobi_kinetic_identity_error"] = float(np.max(np.abs(T_jac - T_cart) / T_cart))
        M, mu1, mu2 = core.jacobi_masses(m)
        a["jacobi_masses"] = np.array([M, mu1, mu2])
        (_, rho1, rho2), _ = core.jacobi(y, m)
        a["jacobi_coordinates"] = {"rho1": rho1, "rho2": rho2}
        el = kepler_core.orbital_elements(*pos[0, 1, :2] - pos[0, 0, :2],
                                          *vel[0, 1, :2] - vel[0, 0, :2], G * (m[0] + m[1]))
        a["earth_eccentricity"] = el["eccentricity"]

    # ------------------------------------------------------------------ report
    @staticmethod
    def _positions(run) -> np.ndarray:
        """The archived positions as (N, 3, 3): time, body, xyz (columns x1 … z3 first)."""
        return np.asarray(run.y)[:, :9].reshape(-1, 3, 3)

    @classmethod
    def default_sections(cls, data):
        names = [s.name for s in cls.sections]
        if not data.analysis.get("hierarchical", False):
            names.remove("moon")
        if data.config.period is None:
            names.remove("periodicity")
        return names

    @classmethod
    def headline(cls, data):
        p, a = data.config.params, data.analysis
        names = data.config.names
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
                        f"{data.config.time_unit} (Kepler two-body "
                        f"{fmt(a['moon_kepler_period'], 8)})"))
        return out

    @classmethod
    def section_orbits(cls, data):
        pos = cls._positions(data.runs["main"])
        names, unit = data.config.names, data.config.length_unit
        fig = plots.three_body_orbits(pos, labels=names, length_unit=unit)
        figures = [cls.figure("orbits", fig, "Tracks of the three bodies projected on the "
                              "x–y plane.")]
        if (np.ptp(pos[:, :, 2]) > 1e-3 * np.ptp(pos[:, :, :2])
                and not data.analysis.get("hierarchical", False)):
            fig2 = plots.three_body_orbits(pos, labels=names, length_unit=unit, plane=(0, 2))
            figures.append(cls.figure("orbits_xz", fig2, "The same tracks in the x–z plane."))
        return SectionContent(figures=figures)

    @classmethod
    def section_moon(cls, data):
        a = data.analysis
        names, unit = data.config.names, data.config.length_unit
        rel = np.asarray(a["moon_relative_position"])
        fig = plots.relative_track(rel[:, 0], rel[:, 1], label=f"{names[2]} − {names[1]}",
                                   centre_label=names[1], length_unit=unit)
        jac = a["jacobi_coordinates"]
        rho1, rho2 = np.asarray(jac["rho1"]), np.asarray(jac["rho2"])
        fig2 = plots.three_body_orbits(
            np.stack([rho1, rho2, np.zeros_like(rho1)], axis=1)[:, :2],
            labels=["ρ1 = r2 − r1", "ρ2 = r3 − (m1 r1 + m2 r2)/(m1 + m2)"],
            length_unit=unit)
        M, mu1, mu2 = np.asarray(a["jacobi_masses"])
        ratios = a["mass_ratios"]
        facts = [("mass ratios (3.35)", f"m2/m1 = {fmt(ratios['m2_m1'])}, "
                                        f"m3/m1 = {fmt(ratios['m3_m1'])}"),
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
            figures=[cls.figure("moon", fig, f"{names[2]}'s track relative to {names[1]}: a "
                                "near-Keplerian ellipse slowly perturbed by the Sun's tide."),
                     cls.figure("jacobi", fig2, "Jacobi coordinates (3.32): ρ1, the inner "
                                "pair's separation, and ρ2, the third body from the inner "
                                "pair's centre of mass (x–y projection).")],
            facts=facts,
            tables=[Table(caption=f"{names[2]}'s period about {names[1]} "
                                  f"[{data.config.time_unit}]", header=["", "value"],
                          rows=rows)])

    @classmethod
    def section_periodicity(cls, data):
        a = data.analysis
        return SectionContent(facts=[
            ("period T", fmt(a["period"], 12)),
            ("max |r_i(T) − r_i(0)|", fmt_err(a["return_position_error"])),
            ("max |v_i(T) − v_i(0)|", fmt_err(a["return_velocity_error"]))])

    @classmethod
    def section_encounters(cls, data):
        run, a = data.runs["main"], data.analysis
        d = a["pair_distances"]
        n = data.config.names
        fig = plots.closest_approach(run.t, {f"{n[0]}–{n[1]}": d["r12"],
                                             f"{n[0]}–{n[2]}": d["r13"],
                                             f"{n[1]}–{n[2]}": d["r23"]},
                                     time_unit=data.config.time_unit)
        return SectionContent(
            figures=[cls.figure("pair_distances", fig, "Distances between the bodies (log "
                                "scale); close encounters are the deep minima, sampled at the "
                                "stored times only.")],
            facts=[("smallest stored pair distance", f"{fmt(a['min_pair_distance'])} at t ≈ "
                                                     f"{fmt(a['min_pair_distance_time'])}")])

    @classmethod
    def section_invariants(cls, data):
        return cls.invariants_section(data, caption="Drift of energy (relative to the initial "
                                                    "potential energy), total momentum and "
                                                    "angular momentum (relative to natural "
                                                    "momentum scales).")
