"""``three_body`` report: the tracks, the light body about its primary in Jacobi
coordinates, the return after one period, pair distances and the conserved quantities."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.base import Section
from ...scene.content import SectionContent, Table, fmt, fmt_err
from ...scene.report import Report
from .results import SCHEMA

plots = lazy_module("reportgen.rendering.plots.gravitation")


class ThreeBodyReport(Report):
    """The three-body sections, drawn from the archive alone."""

    schema = SCHEMA
    sections = (
        Section("orbits", "Orbits", integrates=True),
        Section("moon", "The light body about its primary; Jacobi coordinates",
                integrates=True),
        Section("periodicity", "Return after one period", integrates=True),
        Section("encounters", "Pair distances and close encounters", integrates=True),
        Section("invariants", "Energy, momentum and angular momentum", integrates=True),
        Section("error_vs_runtime", "Error against run time", integrates=True),
    )

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
        names, unit = _plain(data.config.names), _plain(data.config.length_unit)
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
        shown = _plain(names)
        fig = plots.relative_track(rel[:, 0], rel[:, 1], label=f"{shown[2]} − {shown[1]}",
                                   centre_label=shown[1], length_unit=_plain(unit))
        jac = a["jacobi_coordinates"]
        rho1, rho2 = np.asarray(jac["rho1"]), np.asarray(jac["rho2"])
        fig2 = plots.three_body_orbits(
            np.stack([rho1, rho2, np.zeros_like(rho1)], axis=1)[:, :2],
            labels=["ρ1 = r2 − r1", "ρ2 = r3 − (m1 r1 + m2 r2)/(m1 + m2)"],
            length_unit=_plain(unit))
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
        n = _plain(data.config.names)
        fig = plots.closest_approach(run.t, {f"{n[0]}–{n[1]}": d["r12"],
                                             f"{n[0]}–{n[2]}": d["r13"],
                                             f"{n[1]}–{n[2]}": d["r23"]},
                                     time_unit=_plain(data.config.time_unit))
        return SectionContent(
            figures=[cls.figure("pair_distances", fig, "Distances between the bodies (log "
                                "scale); close encounters are the deep minima, sampled at the "
                                "stored times only.")],
            facts=[("smallest stored pair distance", f"{fmt(a['min_pair_distance'])} at t ≈ "
                                                     f"{fmt(a['min_pair_distance_time'])}")])

    @classmethod
    def section_invariants(cls, data):
        labels = {q.name: q.description for q in cls.schema.invariants}
        return cls.invariants_section(data, labels=labels, caption=(
            "Drift of energy (relative to the initial potential energy), total momentum and "
            "angular momentum (relative to natural momentum scales)."))


def _plain(text):
    """Config text (body names, units) for matplotlib: ``$`` escaped, so that a name is
    drawn as written and never parsed as mathtext (``$\\frac{`` would not parse)."""
    if isinstance(text, str):
        return text.replace("$", r"\$")
    return [_plain(t) for t in text]
