"""The heavy top's, pendulum's, oscillator's and FPUT chain's figures against the document
gate (issue 31), drawn from shipped scenes' archives (study off): the turning circles
told apart and named, legends off the data, every axis with a unit or "dimensionless",
no ASCII subscripts; and the Fig. 4.3 caption's spins in the report's 6 figures while a
config error keeps the 10 a config needs."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

from reportgen.core import heavy_top_theory as theory
from reportgen.kinds.heavy_top import plots as top_plots
from reportgen.kinds.heavy_top import report as top_report
from reportgen.rendering.gate import figure_findings
from reportgen.rendering.plots.finish import finish_figure
from reportgen.rendering.report import kind_of_archive
from reportgen.scene.content import fmt

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def archives(shipped_archives):
    """scene name -> its archive, simulated once for the module (no study)."""
    return shipped_archives


def drawn(data, section: str) -> dict:
    """name -> (figure, gate findings) of one section's figures, saved as the report
    saves them."""
    scene = kind_of_archive(data)
    out = {}
    for spec in getattr(scene, f"section_{section}")(data).figures:
        FigureCanvasAgg(spec.figure)
        finish_figure(spec.figure)  # typeset, multipliers folded, as save_figure does
        spec.figure.savefig(io.BytesIO(), format="svg")
        out[spec.name] = (spec.figure, figure_findings(spec.figure))
    return out


SECTIONS = [
    ("heavy_top_fig4.3", ("fig4_3", "cubic", "weierstrass", "time_series", "nutation_locus")),
    ("heavy_top_sleeping_unstable", ("nutation_locus", "cubic", "time_series",
                                     "sleeping_sweep")),
    ("heavy_top_steady_fast", ("nutation_locus", "cubic", "time_series")),
    ("fput_stiff_soft", ("energy_exchange",)),
    ("oscillator", ("hamilton", "canonical_swap", "hamilton_jacobi")),
    ("pendulum_period_sweep", ("period_family",)),
]


@pytest.mark.parametrize("scene,sections", SECTIONS, ids=[s for s, _ in SECTIONS])
def test_figures_pass_the_gate(archives, scene, sections):
    data = archives(scene)
    for section in sections:
        for name, (_fig, findings) in drawn(data, section).items():
            assert findings == [], f"{scene} {section}/{name}:\n" + "\n".join(findings)


def _circles(fig):
    """(label, colour, line style) of the turning circles in the locus figure's legend."""
    ax = fig.axes[1]
    return [(line.get_label(), line.get_color(), line.get_linestyle())
            for line in ax.get_lines() if "turning circle" in line.get_label()]


def test_turning_circles_are_told_apart_and_named(archives):
    """The upper circle θ1 and the lower θ2 differ in colour and line style, and the
    legend says which is which, with the report's numbers (1e-6, not 1e-06)."""
    data = archives("heavy_top_sleeping_unstable")
    fig, _ = drawn(data, "nutation_locus")["nutation_locus"]
    (upper, c1, s1), (lower, c2, s2) = _circles(fig)
    a = data.analysis
    assert upper == f"upper turning circle θ1 = {fmt(a['theta1'])} rad"
    assert lower == f"lower turning circle θ2 = {fmt(a['theta2'])} rad"
    assert "1e-6 rad" in upper and "e-06" not in upper
    assert c1 != c2 and s1 != s2


def test_a_steady_top_draws_its_one_circle_once(archives):
    """Steady precession: θ1 = θ2, one circle, and the caption speaks of one."""
    data = archives("heavy_top_steady_fast")
    fig, _ = drawn(data, "nutation_locus")["nutation_locus"]
    circles = _circles(fig)
    assert len(circles) == 1
    assert circles[0][0] == f"turning circle θ1 = θ2 = {fmt(data.analysis['theta1'])} rad " \
                            "(no nutation)"
    caption = kind_of_archive(data).section_nutation_locus(data).figures[0].caption
    assert "dash-dotted" not in caption and "θ1 = θ2" in caption


def test_turning_circle_labels_follow_the_number_rule():
    """Without an archive: a band whose circles differ only past 6 figures still draws two
    circles (they are different circles), labelled by :func:`fmt`."""
    labels = [label for _, _, label in top_plots._turning_circles(0.8726646, 1.0471976)]
    assert labels == ["upper turning circle θ1 = 0.872665 rad",
                      "lower turning circle θ2 = 1.0472 rad"]
    assert top_plots._turning_circles(np.nan, np.nan) == []
    assert len(top_plots._turning_circles(1.0, 1.0 + 1e-12)) == 1


def test_band_spins_in_the_caption_have_six_figures_and_errors_ten():
    spins = theory.band_spins(1.0, 0.5, 1.0, 0.6, 1.1)
    band = {"theta_min": spins.theta_min, "theta_max": spins.theta_max,
            "omega3_cusps": spins.omega3_cusps, "omega3_waves_min": spins.omega3_waves_min,
            "sigma": spins.sigma}
    text = top_report._spins_in_words(band)
    assert "cusps need |ω3| = 4.13432 rad/s" in text
    assert "waves |ω3| ≥ 3.19866 rad/s" in text
    # a config must hit the cusp spin to 1e-9: its error message keeps 10 figures
    assert "cusps need |ω3| = 4.134323029 rad/s" in spins.possible()


def test_fig43_caption_prints_the_spins_in_six_figures(archives):
    data = archives("heavy_top_fig4.3")
    content = kind_of_archive(data).section_fig4_3(data)
    caption = content.tables[0].caption
    cusps = fmt(data.analysis["band"]["omega3_cusps"])
    assert f"cusps need |ω3| = {cusps} rad/s" in caption
    assert len(cusps.replace(".", "")) <= 6
