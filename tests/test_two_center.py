"""two_center: energy and the separation constant (notes 7.59; Whittaker §50) conserved,
and the orbit confined to the region the separated equations allow."""

from __future__ import annotations

import numpy as np
import pytest

from reportgen.core.integrators import integrate
from reportgen.core.models import two_center as core
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, parse_config_text

TEXT = """
kind = "two_center"
[params]
mu = 1.0
a = 1.0
[initial]
x = {x}
y = {y}
vx = {vx}
vy = {vy}
[run]
t_end = 60.0
samples = 3001
study = false
"""


# the families as the literature names them (Waalkens, Dullin & Richter, Physica D 196
# (2004)): configs/two_center_planetary.toml's ring round both centres,
# configs/two_center_satellite.toml's orbit about one centre, and an orbit through the
# segment between the centres (β = −1.25 ≤ 0, q(1) = 0.17 ≥ 0)
@pytest.mark.parametrize("state, family", [((0.0, 1.6, 1.05, 0.0), "planetary"),
                                           ((1.6, 0.0, 0.0, 1.2), "satellite"),
                                           ((0.0, 0.5, 1.0, 0.0), "lemniscate")])
def test_constants_conserved_and_region(state, family):
    x, y, vx, vy = state
    r = load_scene(parse_config_text(TEXT.format(x=x, y=y, vx=vx, vy=vy))).simulate()
    run = r.runs["main"]
    E, C = run.invariants["energy"], run.invariants["separation_constant"]
    assert np.max(np.abs(E - E[0])) / abs(E[0]) <= 1e-9
    assert np.max(np.abs(C - C[0])) / abs(C[0]) <= 1e-9
    a = r.analysis
    assert a["family"] == family
    xi, eta = core.elliptic_coordinates(run["x"], run["y"], 1.0)
    lo, hi = np.asarray(a["xi_bounds"])
    assert np.all(xi <= hi + 1e-9) and np.all(xi >= lo - 1e-9)
    eta_lo = np.asarray(a["eta_abs_bounds"])[0]
    assert np.all(np.abs(eta) >= eta_lo - 1e-9)
    if family == "satellite":
        assert eta_lo > 0 and np.all(np.sign(eta) == np.sign(eta[0]))  # one side only
    assert r.status == "ok"
    # the coordinate lines the report draws lie on ξ = const and η = const
    grid = a["elliptic_grid"]
    for level, gx, gy in zip(grid["xi_levels"], grid["ellipses"]["x"], grid["ellipses"]["y"],
                             strict=True):
        assert np.allclose(core.elliptic_coordinates(gx, gy, 1.0)[0], level, atol=1e-9)
    assert grid["xi_levels"][-1] >= np.max(xi)  # the grid covers the orbit
    hyp_eta = np.repeat(grid["eta_levels"], 2)  # both branches of each hyperbola
    for level, gx, gy in zip(hyp_eta, grid["hyperbolas"]["x"], grid["hyperbolas"]["y"],
                             strict=True):
        assert np.allclose(core.elliptic_coordinates(gx, gy, 1.0)[1], level, atol=1e-9)
    bounds = a["motion_bounds"]
    for level, gx, gy in zip(bounds["xi"], bounds["ellipses"]["x"], bounds["ellipses"]["y"],
                             strict=True):
        assert np.allclose(core.elliptic_coordinates(gx, gy, 1.0)[0], level, atol=1e-9)
    assert np.max(bounds["xi"]) == pytest.approx(hi, rel=1e-15)
    if family == "satellite":
        # the |η| = η* hyperbola on the orbit's side, both branches
        assert bounds["eta"].tolist() == [np.sign(eta[0]) * eta_lo]
        assert bounds["hyperbolas"]["x"].shape[0] == 2
        assert np.allclose(core.elliptic_coordinates(bounds["hyperbolas"]["x"],
                                                     bounds["hyperbolas"]["y"], 1.0)[1],
                           np.sign(eta[0]) * eta_lo, atol=1e-9)
    else:
        assert "eta" not in bounds


def test_coordinate_lines_closed_forms():
    # ellipse ξ: r1 + r2 = 2aξ; hyperbola η: r1 − r2 = 2aη (foci at (±a, 0), notes 7.46)
    a = 0.7
    x, y = core.coordinate_ellipse(1.3, a)
    r1, r2 = core.distances(x, y, a)
    assert np.allclose(r1 + r2, 2 * a * 1.3, rtol=1e-14)
    assert x[0] == pytest.approx(x[-1]) and y[0] == pytest.approx(y[-1], abs=1e-15)
    for sign in (1.0, -1.0):
        x, y = core.coordinate_hyperbola(-0.4, a, 2.0, sign=sign)
        r1, r2 = core.distances(x, y, a)
        assert np.allclose(r1 - r2, 2 * a * -0.4, rtol=1e-12)
        assert np.all(sign * y >= 0)
        assert np.max((r1 + r2) / (2 * a)) == pytest.approx(2.0, rel=1e-14)


def test_separation_constant_is_not_trivially_conserved():
    # a wrong sign in C is not conserved (guards the formula itself, cf. 7.59)
    y0 = np.array([0.3, 1.2, 0.5, 0.1])
    sol = integrate(core.model(1.0, 1.0), y0, np.linspace(0, 20, 401), rtol=1e-12, atol=1e-14)
    x, y, vx, vy = sol.y.T
    C = core.separation_constant(x, y, vx, vy, 1.0, 1.0)
    assert np.ptp(C) < 1e-9
    r1, r2 = core.distances(x, y, 1.0)
    wrong = ((x + 1) * vy - y * vx) * ((x - 1) * vy - y * vx) + 2 * ((x + 1) / r1 + (x - 1) / r2)
    assert np.ptp(wrong) > 1e-2


@pytest.mark.parametrize("change, key", [("mu = 1.0", "params.mu"), ("a = 1.0", "params.a")])
def test_non_positive_parameters_rejected(change, key):
    text = TEXT.format(x=0.0, y=1.6, vx=1.05, vy=0.0).replace(change, change.split("=")[0]
                                                                + "= -1.0")
    with pytest.raises(ConfigError) as exc:
        load_scene(parse_config_text(text))
    assert key in str(exc.value)


def test_start_at_a_centre_rejected():
    with pytest.raises(ConfigError) as exc:
        load_scene(parse_config_text(TEXT.format(x=1.0, y=0.0, vx=0.0, vy=1.0)))
    assert "initial.x" in str(exc.value)


def test_orbit_figure_legend_below_and_within_the_figure():
    # the orbit over the elliptic grid: a square box (equal aspect) whose legend, beside or
    # above it, ran past the figure's edge or into itself; under the axes it is neither
    import io

    from reportgen.rendering.gate import figure_findings
    from reportgen.rendering.plots import gravitation

    s = np.linspace(0.0, 2.0 * np.pi, 400)

    def ellipse(xi):  # ξ = const: semi-axes a ξ and a √(ξ² − 1), foci at (±a, 0)
        return xi * np.cos(s), np.sqrt(xi**2 - 1.0) * np.sin(s)

    grid = [ellipse(xi) for xi in (1.2, 1.5, 2.0)]
    fig = gravitation.elliptic_grid_orbit(
        1.9 * np.cos(7 * s), 1.6 * np.sin(7 * s), a=1.0, grid=grid,
        xi_bounds=[ellipse(1.85), ellipse(2.05)],
        eta_bounds=[(np.full(9, 0.6), np.linspace(-1, 1, 9))])
    fig.savefig(io.BytesIO(), format="svg")
    assert figure_findings(fig) == []
    fig.draw_without_rendering()  # the legend laid out at the figure's own dpi, as measured
    renderer = fig._get_renderer()
    (legend,) = fig.legends
    box, axes = legend.get_window_extent(renderer), fig.axes[0].get_window_extent(renderer)
    assert box.y1 <= axes.y0 and fig.bbox.x0 <= box.x0 and box.x1 <= fig.bbox.x1
    entries = [t.get_window_extent(renderer) for t in legend.texts]
    assert len(entries) == 4
    assert not any(a.overlaps(b) for i, a in enumerate(entries) for b in entries[i + 1:])


def test_family_results_are_labelled_with_their_units():
    # the sweep's table: the count of crossings (a number) and each bound by its symbol
    from reportgen.kinds.two_center.report import TwoCenterReport

    label = TwoCenterReport.result_quantity(None, "poincare_points").label()
    assert label == "crossings per orbit [dimensionless]"
    assert TwoCenterReport.result_quantity(None, "xi_bounds_1").label() == (
        r"$\xi_\mathrm{min}$ [dimensionless]")
