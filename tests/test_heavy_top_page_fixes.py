"""Heavy-top figures on degenerate cases seen on printed pages (issue 31): steady
precession's effective potential and θ(t), coincident roots of f(u), the sleeping sweep's
colours."""

import numpy as np

from reportgen.kinds.heavy_top import plots


def test_effective_potential_of_steady_precession_shows_the_well():
    # E' at the bottom of the well; the grid misses the minimum, so min V > E' (by 1e-8):
    # the window used to be inverted and a round-off wide, with no curve in it
    theta = np.linspace(0.01, np.pi - 0.01, 400)
    V = 10.0 + 3.0 * (theta - 1.0) ** 2 + 1e-8
    fig = plots.effective_potential(theta, V, energy=10.0, theta1=1.0, theta2=1.0)
    ax = fig.axes[0]
    lo, hi = ax.get_ylim()
    assert lo < 10.0 < hi and hi - lo > 0.1
    shown = (V >= lo) & (V <= hi)
    assert shown.sum() > 20  # the well is drawn, not a single point
    texts = [t.get_text() for t in ax.texts]
    assert texts == ["θ1 = θ2"]


def test_effective_potential_keeps_a_nutation_window():
    theta = np.linspace(0.3, 2.0, 400)
    V = 0.6 + (theta - 1.0) ** 2
    fig = plots.effective_potential(theta, V, energy=0.65, theta1=0.78, theta2=1.22)
    lo, hi = fig.axes[0].get_ylim()
    assert lo < 0.6 and 0.65 < hi < 0.8  # E' − min V = 0.05 still sets the window
    assert sorted(t.get_text() for t in fig.axes[0].texts) == ["θ1", "θ2"]


def test_cubic_labels_a_double_root_once():
    u = np.linspace(-1.0, 1.2, 500)
    f = -(u - 0.54) ** 2 * (13.5 - u)
    fig = plots.cubic(u, f, u1=0.540302, u2=0.540302, u3=13.5, b_over_a=1.77, u0=0.540302)
    assert [t.get_text() for t in fig.axes[0].texts] == ["u1 = u2"]
    fig = plots.cubic(u, f, u1=-0.02, u2=1.0, u3=1.0 + 1e-13, b_over_a=1.0, u0=1.0)
    assert sorted(t.get_text() for t in fig.axes[0].texts) == ["u1", "u2 = u3"]


def test_time_series_of_constant_theta_has_no_offset():
    t = np.linspace(0.0, 10.0, 200)
    theta = 1.0 + 1e-12 * np.sin(t)
    fig = plots.time_series(t, theta, np.full_like(t, 1.0), np.full_like(t, 5.2),
                            np.full_like(t, 1e-15), theta1=1.0, theta2=1.0)
    ax = fig.axes[0]
    fig.canvas.draw()
    lo, hi = ax.get_ylim()
    assert hi - lo >= 0.02
    assert ax.yaxis.get_offset_text().get_text() == ""


def test_sleeping_sweep_colours_follow_the_threshold():
    ratios = np.array([0.5, 0.8, 0.9, 1.1, 1.25, 2.0])
    colours = plots._diverging(ratios)
    for r, (red, _, blue, _) in zip(ratios, colours, strict=True):
        assert (red > blue) == (r < 1.0)
    # uneven sides: still red below, blue above
    colours = plots._diverging(np.array([0.5, 1.5, 2.0, 3.0]))
    assert colours[0][0] > colours[0][2]
    assert all(c[2] > c[0] for c in colours[1:])
