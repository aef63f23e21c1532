"""The figures' basic rules (issue 31), checked on shipped scenes drawn from their archives:
axis labels from the declared results (a symbol and a unit, never a config key), no
combining dot accent, series told apart, legends clear of the data, highlighted points
inside the limits, the inertia ellipsoid seen across its long axis, the Pythagorean
run's encounters enlarged.  Plus the pieces on their own: legend placement, the
ellipsoid's view, config keys as quantities."""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import to_rgb

from reportgen.rendering.report import kind_of_archive

REPO = Path(__file__).resolve().parent.parent
UNIT = re.compile(r"\[[^\]]+\]|dimensionless")
CONFIG_KEY = re.compile(r"\b(?:initial|params)\.\w+")


@pytest.fixture(scope="module")
def archives(shipped_archives):
    """scene name -> its archive, simulated once for the module (no study)."""
    return shipped_archives


def figures(data, section: str) -> dict:
    """The figures of one section, drawn from the archive and saved once (so that the
    layout is the saved file's)."""
    scene = kind_of_archive(data)
    out = {}
    for spec in getattr(scene, f"section_{section}")(data).figures:
        FigureCanvasAgg(spec.figure)
        spec.figure.savefig(io.BytesIO(), format="svg")
        out[spec.name] = spec.figure
    return out


def texts(fig) -> list[str]:
    from matplotlib.text import Text

    return [t.get_text() for t in fig.findobj(Text) if t.get_text()]


def axis_labels(fig) -> list[str]:
    out = []
    for ax in fig.axes:
        if ax.axison and ax.get_visible():
            out += [label for label in (ax.get_xlabel(), ax.get_ylabel()) if label]
    return out


def legend_covered_points(ax) -> int:
    """Data vertices of ``ax`` (lines in data coordinates, densified) inside its legend's
    frame, in display coordinates."""
    legend = ax.get_legend()
    if legend is None:
        return 0
    box = legend.get_window_extent(ax.figure.canvas.get_renderer())
    count = 0
    for line in ax.get_lines():
        if line.get_transform() != ax.transData or len(line.get_xydata()) < 2:
            continue
        xy = ax.transData.transform(line.get_xydata())
        fine = np.concatenate([xy[:-1] + f * (xy[1:] - xy[:-1]) for f in np.linspace(0, 1, 5)])
        count += int(np.sum((fine[:, 0] > box.x0) & (fine[:, 0] < box.x1)
                            & (fine[:, 1] > box.y0) & (fine[:, 1] < box.y1)))
    return count


# ------------------------------------------------------------------ shipped scenes
def test_pendulum_labels_have_units_and_no_combining_dot(archives):
    data = archives("pendulum_separatrix")
    for section in ("time_series", "phase_portrait", "period"):
        for name, fig in figures(data, section).items():
            for label in axis_labels(fig):
                assert UNIT.search(label), f"{section}/{name}: {label!r} has no unit"
            for text in texts(fig):
                assert "\u0307" not in text, f"{section}/{name}: combining dot in {text!r}"


def test_separatrix_scene_point_is_inside_the_axes(archives):
    """Near the separatrix the period (11.5 s) is far above four small-angle periods:
    the axis reaches up to it, so the scene's markers (and their legend entries) show."""
    fig = figures(archives("pendulum_separatrix"), "period")["period"]
    ax = fig.axes[0]
    (x0, x1), (y0, y1) = sorted(ax.get_xlim()), sorted(ax.get_ylim())
    points = [line for line in ax.get_lines() if len(line.get_xydata()) == 1]
    assert len(points) == 2
    for line in points:
        x, y = line.get_xydata()[0]
        assert x0 <= x <= x1 and y0 <= y <= y1, (line.get_label(), x, y)
    assert y > 11.0  # the point the limits were stretched for


def test_legends_leave_the_data_clear(archives):
    """Rigid body Dzhanibekov pages (ω against the exact solution, flips, drift): each
    legend covers no data vertex, in display coordinates."""
    data = archives("rigid_body_dzhanibekov")
    for section in ("omega", "stability", "invariants", "geometric_integrator"):
        for name, fig in figures(data, section).items():
            for ax in fig.axes:
                assert legend_covered_points(ax) == 0, f"{section}/{name}"


def test_stretch_modes_have_their_own_colours(archives):
    fig = figures(archives("normal_modes_co2"), "spectrum")["spectrum"]
    legend = fig.axes[0].get_legend()
    colours = {t.get_text(): to_rgb(h.get_color()[0] if np.ndim(h.get_color()) > 1
                                    else h.get_color())
               for t, h in zip(legend.get_texts(), legend.legend_handles, strict=True)}
    symmetric = next(c for t, c in colours.items() if t.endswith(", symmetric stretch"))
    antisymmetric = next(c for t, c in colours.items() if "antisymmetric" in t)
    assert symmetric != antisymmetric
    assert len(set(colours.values())) == len(colours)
    assert fig.axes[0].get_xlabel() == "wavenumber [cm⁻¹]"  # molecular units: ν̃ = ω/2πc


def test_molecule_atoms_are_labelled(archives):
    figs = figures(archives("normal_modes_co2"), "mode_shapes")
    words = texts(figs["modes"])
    assert words.count("C") >= 4 and words.count("O") >= 8  # four panels, one C and two O


def test_inertia_ellipsoid_is_seen_across_its_long_axis(archives):
    data = archives("inertia_cone")
    fig = figures(data, "tensor")["inertia_ellipsoid"]
    ax = next(a for a in fig.axes if a.name == "3d")
    elev, azim = np.radians(ax.elev), np.radians(ax.azim)
    view = np.array([np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim), np.sin(elev)])
    a = data.analysis
    semi = np.asarray(a["inertia_ellipsoid"]["semi_axes"])
    long_axis = np.asarray(a["principal_axes"])[:, int(np.argmax(semi))]
    angle = np.degrees(np.arccos(abs(float(view @ long_axis))))
    assert angle > 60, f"viewed {angle:.0f}° from the long axis"


def test_sweep_axes_name_the_quantity_not_the_config_key(archives):
    data = archives("pendulum_period_sweep")
    for section in ("sweep_results", "sweep_members", "period_family"):
        for name, fig in figures(data, section).items():
            for text in texts(fig):
                assert not CONFIG_KEY.search(text), f"{section}/{name}: {text!r}"
            for label in axis_labels(fig):
                assert UNIT.search(label), f"{section}/{name}: {label!r} has no unit"
    results = figures(data, "sweep_results")["results"]
    assert results.axes[-1].get_xlabel() == r"$\theta_0$ [rad]"
    assert [ax.get_ylabel() for ax in results.axes[:2]] == ["$T$ [s]", r"$T_\mathrm{meas}$ [s]"]


def test_pythagorean_encounters_are_enlarged_with_time_as_colour(archives):
    data = archives("three_body_pythagorean")
    figs = figures(data, "orbits")
    zoom = figs["encounters_zoom"]
    full, close = zoom.axes[0], zoom.axes[1]
    assert np.ptp(full.get_xlim()) > 3 * np.ptp(close.get_xlim())
    bar = zoom.axes[2]
    assert "time t" in bar.get_ylabel() and "dimensionless" in bar.get_ylabel()
    assert not any("[s]" in label for f in figs.values() for label in axis_labels(f))
    # a bound system fills its own picture: no zoom
    assert "encounters_zoom" not in figures(archives("three_body_figure_eight"), "orbits")


# ------------------------------------------------------------------ the pieces
def test_place_legend_moves_off_the_data_and_out_when_full():
    from reportgen.rendering.plots.style import new_figure, place_legend

    fig, ax = new_figure()
    x = np.linspace(0, 1, 50)
    ax.plot(x, 1 - 0.5 * x, label="falling line")  # fills the upper left
    ax.set_ylim(0, 1.05)
    legend = place_legend(ax, loc="upper left")
    FigureCanvasAgg(fig)
    fig.savefig(io.BytesIO(), format="svg")
    assert legend._loc != 2  # not the upper left it was asked for
    assert legend_covered_points(ax) == 0
    # a plot filled everywhere: the legend goes above the axes
    fig, ax = new_figure()
    rng = np.random.default_rng(1)
    ax.plot(rng.random(2000), rng.random(2000), "o", label="cloud")  # no free corner
    legend = place_legend(ax)
    FigureCanvasAgg(fig)
    fig.savefig(io.BytesIO(), format="svg")
    assert legend.get_window_extent().y0 >= ax.bbox.y1 - 1


def test_ellipsoid_view_is_across_a_prolate_long_axis():
    from reportgen.rendering.plots.rigid_body import ellipsoid_view

    rng = np.random.default_rng(3)
    for _ in range(20):
        axes, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        semi = np.array([1.0, 1.0, 3.0])[rng.permutation(3)]
        elev, azim = np.radians(ellipsoid_view(axes, semi))
        view = np.array([np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim),
                         np.sin(elev)])
        long_axis = axes[:, int(np.argmax(semi))]
        assert abs(float(view @ long_axis)) < 1e-12  # perpendicular to it
        assert elev >= 0


def test_config_key_as_a_quantity():
    from reportgen.kinds import get_kind
    from reportgen.scene.schema import config_quantity

    q = config_quantity(get_kind("pendulum").Config, "initial.theta", r"\theta_0")
    assert (q.unit, q.description, q.label()) == (
        "rad", "initial angle from the downward vertical", r"$\theta_0$ [rad]")
    bare = config_quantity(get_kind("pendulum").Config, "params.g")
    assert bare.label() == "gravitational acceleration [m/s²]"
