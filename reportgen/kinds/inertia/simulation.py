"""``inertia`` simulation: the tensor of the shape in the lab frame, diagonalized; the
closed-form moments, the parallel-axis shift (8.49) and the stability of free spin about
each principal axis.  Nothing is integrated."""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from ...scene.results import Check, Results
from ...scene.simulation import Simulation
from .config import InertiaConfig
from .results import SCHEMA

core = lazy_module("reportgen.core.inertia")


class InertiaSimulation(Simulation):
    """The inertia tensor of a shape or point set and what follows from it."""

    schema = SCHEMA
    config: InertiaConfig

    def simulate(self, progress=None) -> Results:
        shape = self.config.shape
        tensor = shape.lab_tensor()
        moments, axes = core.principal_axes(tensor)
        results = Results()
        stab = core.axis_stability(moments)
        results.analysis.update({
            "tensor": tensor,
            "principal_moments": moments,
            "principal_axes": axes,
            "centre_of_mass": shape.centre_of_mass(),
            "mass": float(shape.mass),
            "shape": shape.describe(),
            "axis_stability": {f"axis_{k + 1}": s for k, s in enumerate(stab)},
            "inertia_ellipsoid": core.inertia_ellipsoid(moments, axes),
        })
        if shape.type == "points":
            results.analysis["points"] = {"positions": shape.lab_positions(),
                                          "masses": np.asarray(shape.masses, dtype=float)}
        else:
            closed = np.sort(np.diag(shape.body_tensor()))
            results.analysis["closed_form"] = {
                "principal_moments": closed, "source": shape.closed_form_source(),
                "max_relative_difference": float(np.max(np.abs(moments - closed)) / closed[2])}
            for k in range(3):
                results.checks.append(Check(
                    f"principal moment I{k + 1} (diagonalized lab tensor)", float(moments[k]),
                    float(closed[k]), "kg m²", shape.closed_form_source(),
                    scale=float(closed[2])))
        if shape.about is not None:
            d = np.asarray(shape.about, dtype=float) - shape.centre_of_mass()
            shifted = core.parallel_axis(tensor, shape.mass, d)
            m2, a2 = core.principal_axes(shifted)
            results.analysis["parallel_axis"] = {
                "about": np.asarray(shape.about, dtype=float), "tensor": shifted,
                "principal_moments": m2, "principal_axes": a2}
            if shape.type == "points":
                direct = core.tensor_points(shape.masses, shape.lab_positions(),
                                            about=shape.about)
                idx = np.unravel_index(np.argmax(np.abs(direct)), direct.shape)
                results.checks.append(Check(
                    f"I_{'xyz'[idx[0]]}{'xyz'[idx[1]]} about the shifted point", float(shifted[idx]),
                    float(direct[idx]), "kg m²", "(8.49) against the direct sum Σ m (r² δ − r r)"))
        return results
