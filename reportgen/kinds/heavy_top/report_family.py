"""``heavy_top`` report, a family's sections: each member's turning circles against the
swept value, and the kept members' loci on the sphere."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.content import SectionContent, fmt
from ...scene.report import kept_members
from .locus import FIG43_ELEVATION_DEG, locus_stretch

plots = lazy_module("reportgen.kinds.heavy_top.plots")

#: swept config keys -> the declared result holding the member's value (axis labels)
SWEPT_RESULTS = {"initial.theta": "theta0", "initial.theta_dot": "theta_dot0",
                 "initial.phi_dot": "phi_dot0", "initial.omega3": "omega3",
                 "band.omega3": "omega3", "band.theta_min": "band/theta_min",
                 "band.theta_max": "band/theta_max"}


class FamilySections:
    """The sections of a heavy-top sweep (mixed into :class:`.report.HeavyTopReport`)."""

    @classmethod
    def section_nutation_family(cls, data):
        sweep = data.sweep
        a, ok = sweep.analysis, sweep.ok
        path, x = next(iter(sweep.values.items()))
        case = np.asarray(sweep.labels.get("case", np.full(sweep.size, "")), dtype=str)
        threshold = a.get("sleeping_threshold_omega3")
        swept_omega3 = path == "initial.omega3"
        fig = plots.nutation_family(
            x[ok], theta1=a["theta1"][ok], theta2=a["theta2"][ok], case=case[ok],
            xlabel=cls.label(SWEPT_RESULTS[path]) if path in SWEPT_RESULTS else path,
            precession=a["precession_per_period"][ok] if "precession_per_period" in a else None,
            growth=a["sleeping_growth_rate"][ok] if "sleeping_growth_rate" in a else None,
            threshold=float(np.nanmedian(threshold[ok])) if threshold is not None
            and swept_omega3 else None)
        names, counts = np.unique(case[ok], return_counts=True)
        boundaries = plots._case_boundaries(x[ok], case[ok])
        facts = [("cases", ", ".join(f"{n} {c}" for n, c in zip(names, counts, strict=True)))]
        if boundaries:
            facts.append(("case changes", "; ".join(
                f"{left} → {right} near {cls.config_value_words(data, path, at)}"
                for at, left, right in boundaries)))
        return SectionContent(figures=[cls.figure(
            "nutation_family", fig, f"Turning circles θ1 (▼) and θ2 (▲) of each member against "
            f"{cls.config_words(data, path)}, by case; the band between them shaded.")],
            facts=facts)

    @classmethod
    def section_loci_family(cls, data):
        sweep = data.sweep
        members = kept_members(data)
        loci, theta1, theta2, labels, azimuths = [], [], [], [], []
        a = sweep.analysis
        case = sweep.labels.get("case", np.full(sweep.size, ""))
        for i, name in members:
            run = data.runs[name]
            period = a["nutation_period"][i]
            if not (np.isfinite(period) and period > 0):  # no nutation: the whole run
                period = math.inf
            stop, _, azimuth = locus_stretch(run, period, a["precession_per_period"][i],
                                             full_turn=False)
            loci.append(np.column_stack([run["axis_x"], run["axis_y"], run["axis_z"]])[:stop])
            theta1.append(a["theta1"][i])
            theta2.append(a["theta2"][i])
            azimuths.append(azimuth)
            labels.append((str(case[i]) or f"member {i}", cls._member_label(sweep, i)))
        fig = plots.loci_family(loci, theta1=theta1, theta2=theta2, labels=labels,
                                azimuths=azimuths,
                                elevation=math.radians(FIG43_ELEVATION_DEG))
        return SectionContent(figures=[cls.figure(
            "loci_family", fig, "The symmetry axis of each kept member on the unit sphere, "
            "with its own turning circles θ1, θ2 (a few nutation periods from the release; "
            "dashed: behind the sphere).")])

    @classmethod
    def _member_label(cls, sweep, i) -> str:
        """A member's swept values for a figure: the quantity's symbol and unit where the
        kind declares it (``dφ/dt(0) = −1 rad/s``), else the config key's last part."""
        parts = []
        for path, values in sweep.values.items():
            if path in SWEPT_RESULTS:
                q = cls.schema.quantity(SWEPT_RESULTS[path])
                parts.append(f"{q.math} = {fmt(float(values[i]), 4)} {q.unit}".rstrip())
            else:
                parts.append(f"{path.rsplit('.', 1)[-1]} = {fmt(float(values[i]), 4)}")
        return ", ".join(parts)
