"""Central-force figures of this kind alone: the radial momentum against ∂W/∂r."""

from __future__ import annotations

import numpy as np

from ...rendering.plots.style import HIGHLIGHT, REFERENCE, dots, new_figure, place_legend

#: stored samples drawn at most (a dense run is thinned evenly)
MAX_POINTS = 2000


def radial_momentum(r, p_r, curve_r, curve_p, marks_r, marks_p, *, ax=None):
    """The run's (r, pᵣ) over the two branches pᵣ = ±∂W/∂r of the characteristic function:
    the integrand's closed form as a line, the quadrature's central differences as marks."""
    fig, ax = new_figure(ax, figsize=(6.4, 4.4))
    for sign, label in ((1.0, "±∂W/∂r, the integrand"), (-1.0, None)):
        ax.plot(curve_r, sign * np.asarray(curve_p), color=REFERENCE, lw=1.2, label=label)
    for sign, label in ((1.0, "±∂W/∂r, W by quadrature"), (-1.0, None)):
        ax.plot(marks_r, sign * np.asarray(marks_p), "x", color=REFERENCE, ms=6, mew=1.2,
                ls="none", label=label)
    step = max(1, len(r) // MAX_POINTS)
    ax.plot(r[::step], p_r[::step], color=HIGHLIGHT, label="integrated", **dots(3.4))
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("r [m]")
    ax.set_ylabel("pᵣ [kg·m/s]")
    place_legend(ax)
    return fig
