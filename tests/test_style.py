"""One figure style: a colour-blind-safe palette, and no colour picked outside it."""

from __future__ import annotations

import itertools
import re
from pathlib import Path

import numpy as np
import pytest
from matplotlib.colors import to_rgb

from reportgen.rendering.plots import style

PLOTS = Path(style.__file__).parent

# Machado, Oliveira & Fernandes (2009), "A physiologically-based model for simulation of
# color vision deficiency", IEEE TVCG 15(6): severity-1.0 matrices on linear RGB.
CVD = {
    "deuteranopia": [[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413],
                     [-0.011820, 0.042940, 0.968881]],
    "protanopia": [[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216],
                   [-0.003882, -0.048116, 1.051998]],
    "tritanopia": [[1.255528, -0.076749, -0.178779], [-0.078411, 0.930809, 0.147602],
                   [0.004733, 0.691367, 0.303900]],
    "normal": np.eye(3),
}


def _linear(c):
    c = np.asarray(c, dtype=float)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def _lab(linear_rgb):
    """CIELAB (D65) of a linear-RGB colour (sRGB primaries), clipped to the gamut."""
    xyz = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722],
                    [0.0193, 0.1192, 0.9505]]) @ np.clip(linear_rgb, 0, 1)
    xyz = xyz / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > 0.008856, np.cbrt(xyz), 7.787 * xyz + 16 / 116)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


def _closest_pair(colours, matrix):
    labs = [_lab(np.asarray(matrix) @ _linear(to_rgb(c))) for c in colours]
    return min(float(np.linalg.norm(labs[i] - labs[j]))
               for i, j in itertools.combinations(range(len(labs)), 2))


@pytest.mark.parametrize("vision", sorted(CVD))
def test_palette_and_meaningful_colours_stay_apart(vision):
    assert _closest_pair(style.PALETTE, CVD[vision]) >= 15
    meaning = (style.HIGHLIGHT, style.REFERENCE, style.CONTEXT, style.SEPARATRIX)
    assert _closest_pair(meaning, CVD[vision]) >= 15


def test_the_old_palette_would_fail():
    """The check can fail: the palette before Okabe-Ito had a red and a green that
    deuteranopes cannot tell apart."""
    assert _closest_pair(["#c0504d", "#4f8a3c"], CVD["deuteranopia"]) < 5


def test_figures_take_their_colours_from_the_style():
    hex_colour = re.compile(r"#[0-9a-fA-F]{6}\b")
    for path in sorted(PLOTS.glob("*.py")):
        if path.name == "style.py":
            continue
        found = hex_colour.findall(path.read_text())
        assert not found, f"{path.name} picks its own colours {found}: name them in style.py"


def test_the_cycle_is_the_palette():
    import matplotlib

    cycle = [c["color"] for c in matplotlib.rcParams["axes.prop_cycle"]]
    assert [to_rgb(c) for c in cycle] == [to_rgb(c) for c in style.PALETTE]


@pytest.mark.parametrize("studied", ["all", "separable", "coupled_pendula"])
def test_the_work_precision_legend_fits_the_figure_and_tells_every_method_apart(studied):
    """The methods of a study, long labels included: the legend stays inside the figure's
    width (the coupled pendula's twelve in three columns ran past both edges), and no two
    methods share colour, marker and line style (past the palette's 7 colours the
    markers and the line change)."""
    from reportgen.core.integrators import METHODS
    from reportgen.rendering.plots.common import work_precision

    names = [n for n, m in METHODS.items() if (m.compiled or m.peer)
             and (studied == "all" or not m.needs_kepler)
             and (studied != "coupled_pendula" or n != "scipy_lsoda")]
    dtype = [("method", object), ("label", object), ("status", object),
             ("error_max", float), ("wall_time_s", float)]
    rows = np.array([(n, METHODS[n].label, "ok", 10.0 ** -(k % 12), 1e-4 * (k + 1))
                     for n in names for k in range(2)], dtype=dtype)
    fig = work_precision(rows)
    legend = fig.legends[0]
    assert legend.get_window_extent().width <= fig.bbox.width
    looks = {(line.get_color(), line.get_marker(), line.get_linestyle(),
              line.get_markerfacecolor()) for line in fig.axes[0].get_lines()}
    assert len(looks) == len(names)
