"""``inertia`` simulation: the tensor of the shape in the lab frame, diagonalized; the
closed-form moments, the parallel-axis shift, notes (8.49), and the stability of free spin about
each principal axis.  Nothing is integrated."""

from __future__ import annotations

import re

import numpy as np

from ...lazy import lazy_module
from ...scene.results import Check, Results
from ...scene.simulation import Simulation
from .config import EQUAL_MOMENTS_RTOL, InertiaConfig, body_symmetry
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
        stab = core.axis_stability(moments, rtol=EQUAL_MOMENTS_RTOL)
        results.analysis.update({
            "tensor": tensor,
            "principal_moments": moments,
            "principal_axes": axes,
            "centre_of_mass": shape.centre_of_mass(),
            "mass": float(shape.mass),
            "shape": shape.describe(),
            "axis_stability": {f"axis_{k + 1}": s for k, s in enumerate(stab)},
            "top": body_symmetry(moments)[0],
            "equal_moments_rtol": EQUAL_MOMENTS_RTOL,
            "inertia_ellipsoid": core.inertia_ellipsoid(moments, axes),
        })
        if shape.type == "points":
            results.analysis["points"] = {"positions": shape.lab_positions(),
                                          "masses": np.asarray(shape.masses, dtype=float)}
        else:
            for k, words in enumerate(principal_axis_words(shape, moments, axes)):
                results.analysis["axis_stability"][f"axis_{k + 1}"]["shape_axis"] = words
            self._quadrature(results)
            closed = np.sort(np.diag(shape.body_tensor()))
            results.analysis["closed_form"] = {
                "principal_moments": closed, "source": shape.closed_form_source(),
                "max_relative_difference": float(np.max(np.abs(moments - closed)) / closed[2])}
            for k in range(3):
                results.checks.append(Check(
                    f"principal moment I{k + 1} (diagonalized lab tensor)", float(moments[k]),
                    float(closed[k]), "kg m²", cite(shape.closed_form_source()),
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
                    float(direct[idx]), "kg m²", "notes (8.49) against the direct sum Σ m (r² δ − r r)"))
        return results

    def _quadrature(self, results) -> None:
        """The body as point masses at quadrature nodes: volume, centre of mass and the
        tensor by volume integration, against the closed forms (and, for the cone, the
        centre of mass 3h/4 below the apex, textbook ex. 4.6)."""
        shape = self.config.shape
        m, r, vol = shape.mass_elements()
        cm = core.centre_of_mass(m, r)
        T = core.tensor_points(m, r)
        closed = np.diag(shape.body_tensor())
        scale = float(np.max(closed))
        diff = np.abs(np.diag(T) - closed)
        q = {"nodes": int(len(m)), "volume": float(vol), "volume_closed": float(shape.volume()),
             "centre_of_mass": cm, "moments": np.diag(T).copy(), "moments_closed": closed,
             "products_max": float(np.max(np.abs(T - np.diag(np.diag(T))))),
             "max_relative_difference": float(np.max(diff) / scale)}
        if shape.type == "cone":
            q["apex_distance"] = float(shape.apex()[2] - cm[2])
            q["apex_distance_closed"] = float(core.cone_apex_height(shape.height))
            results.checks.append(Check(
                "centre of mass below the apex (quadrature)", q["apex_distance"],
                q["apex_distance_closed"], "m", "3h/4 (textbook ex. 4.6)"))
        results.analysis["quadrature"] = q
        k = int(np.argmax(diff))
        results.checks.append(Check(
            f"moment about the shape's {'xyz'[k]} axis by quadrature (worst of x, y, z)",
            float(np.diag(T)[k]), float(closed[k]), "kg m²", cite(shape.closed_form_source()),
            scale=scale))


def cite(source: str) -> str:
    """A closed form's source for a checks table: "closed form, <its citation>" (the
    parenthesis the source ends with), the formula itself left to the report's text."""
    found = re.search(r"\(([^()]*)\)$", source)
    return f"closed form, {found.group(1)}" if found else source


def principal_axis_words(shape, moments, axes, rtol: float | None = None) -> list[str]:
    """Each principal axis as the shape's own axis it lies along ("x, along the side a"),
    from the lab-frame axes turned back into the shape's frame; an axis of a degenerate
    pair is "any axis ⊥ z" (z the odd axis), of a spherical body "any axis"."""
    rtol = EQUAL_MOMENTS_RTOL if rtol is None else rtol
    words = shape.axis_words()
    own = shape.rotation().T @ np.asarray(axes, dtype=float)
    scale = float(np.max(moments))
    out = []
    for k in range(3):
        equal = [j for j in range(3)
                 if j != k and abs(float(moments[j] - moments[k])) <= rtol * scale]
        if len(equal) == 2:
            out.append("any axis (three equal moments)")
        elif len(equal) == 1:
            odd = ({0, 1, 2} - {k, equal[0]}).pop()
            out.append(f"any axis ⊥ {'xyz'[int(np.argmax(np.abs(own[:, odd])))]}")
        else:
            out.append(words["xyz"[int(np.argmax(np.abs(own[:, k])))]])
    return out
