"""FPUT stiff–soft chain figures: the exchange of oscillatory energy (GNI Fig. I.5.2)."""

from __future__ import annotations

import numpy as np

from ...rendering.plots.style import CONTEXT, RC, REFERENCE, new_figure_grid, place_legend

#: colours of I_1, I_2, … (the style's cycle without its first colour, which is I's)
_COLOURS = RC["axes.prop_cycle"].by_key()["color"][1:]


def energy_exchange(t, energies, total, scaled_deviation, *, relative: bool = True):
    """Top: I_1 … I_m and I = Σ I_j against t.  Bottom: ω (I(t) − I(0)) / I(0).

    ``energies``: (N, m) oscillatory energies; ``total``: (N,) their sum;
    ``scaled_deviation``: (N,) ω (I(t) − I(0)) / I(0), the adiabatic-invariant wobble scaled
    by ω (of order one when I − I(0) = O(1/ω)), drawn as given; ``relative=False``: it is
    ω (I(t) − I(0)), not divided (I(0) = 0).
    """
    energies, total = np.asarray(energies), np.asarray(total)
    fig, axes = new_figure_grid(2, 1, figsize=(7.2, 5.8), sharex=True)
    top, bottom = axes[:, 0]
    top.plot(t, total, color=REFERENCE, linewidth=2.2, label=r"$I = \Sigma_j I_j$")
    for j in range(energies.shape[1]):
        top.plot(t, energies[:, j], linewidth=1.3, color=_COLOURS[j % len(_COLOURS)],
                 label=f"$I_{{{j + 1}}}$")
    top.set_ylabel("$I_j$ and $I$ (dimensionless)")
    # room above the curves for the legend (I runs flat along the top)
    highest = max(float(np.max(total)), float(np.max(energies)))
    top.set_ylim(bottom=0.0, top=1.3 * highest if highest > 0 else 1.0)
    place_legend(top, loc="upper center", ncols=min(energies.shape[1] + 1, 6), fontsize=9)
    bottom.plot(t, scaled_deviation, color=CONTEXT, linewidth=0.6)
    bottom.axhline(0.0, color=REFERENCE, linewidth=0.8)
    bottom.set_ylabel("ω (I(t) − I(0)) / I(0) (dimensionless)" if relative else
                      "ω (I(t) − I(0)) (dimensionless)")
    bottom.set_xlabel("time t (dimensionless)")
    return fig
