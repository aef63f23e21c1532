"""Heavy-top figures: nutation locus, textbook Fig. 4.3 as printed, f(u), the ℘ period rectangle,
effective potential, time series, steady precession rates and the sleeping-top sweep.

Figure text avoids combining accents (φ̇ is written dφ/dt): the PDF engine draws the
combining dot of an SVG text as a dotted circle."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ...rendering.plots import layout
from ...rendering.plots.layout import Size
from ...rendering.plots.style import (
    CONTEXT,
    GREEN,
    HIGHLIGHT,
    REFERENCE,
    SEPARATRIX,
    legend_below,
    new_figure,
    new_figure_grid,
    place_legend,
)
from ...scene.content import fmt


def _circle_on_sphere(theta, n=361):
    phi = np.linspace(0.0, 2.0 * np.pi, n)
    return np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.full(n, np.cos(theta))


def nutation_locus(axis, theta, *, theta1, theta2, figsize=(8.6, 5.0)):
    """The path of the symmetry axis on the unit sphere: 3-D view and flat projection.

    Parameters
    ----------
    axis : ndarray, shape (N, 3)
        Space components of the symmetry axis.
    theta : ndarray, shape (N,)
        Its polar angle [rad] (accurate near the vertical).
    theta1, theta2 : float
        Turning circles θ1 = arccos u2 ≤ θ2 = arccos u1 [rad] (NaN: not drawn).
    """
    fig = Figure(figsize=figsize, layout="constrained")
    fig.get_layout_engine().set(w_pad=0.15, wspace=0.12)  # room for the 3-D z label
    ax3 = fig.add_subplot(1, 2, 1, projection="3d")
    ax2 = fig.add_subplot(1, 2, 2)
    # 3-D: light sphere, turning circles, the locus
    uu, vv = np.meshgrid(np.linspace(0, 2 * np.pi, 37), np.linspace(0, np.pi, 19))
    ax3.plot_wireframe(np.cos(uu) * np.sin(vv), np.sin(uu) * np.sin(vv), np.cos(vv),
                       color=CONTEXT, linewidth=0.3, alpha=0.5, rasterized=True)
    circles = _turning_circles(theta1, theta2)
    for th, style, _ in circles:
        ax3.plot(*_circle_on_sphere(th), linewidth=1.0, **style)
    ax3.plot(axis[:, 0], axis[:, 1], axis[:, 2], color=HIGHLIGHT, linewidth=1.2)
    ax3.scatter([axis[0, 0]], [axis[0, 1]], [axis[0, 2]], color="k", s=15)
    ax3.set_xlabel("x")
    ax3.set_ylabel("y")
    ax3.set_zlabel("z (vertical)")
    for setter in (ax3.set_xticks, ax3.set_yticks, ax3.set_zticks):
        setter([-1.0, 0.0, 1.0])
    ax3.set_box_aspect((1, 1, 1))
    ax3.view_init(elev=25, azim=-60)
    ax3.set_title("symmetry axis on the unit sphere")
    # flat: azimuthal equidistant projection about the vertical, radius = θ
    rho = np.hypot(axis[:, 0], axis[:, 1])
    safe = np.where(rho > 0, rho, 1.0)
    x = np.where(rho > 0, theta * axis[:, 0] / safe, 0.0)
    y = np.where(rho > 0, theta * axis[:, 1] / safe, 0.0)
    phi = np.linspace(0, 2 * np.pi, 361)
    for th, style, label in circles:
        ax2.plot(th * np.cos(phi), th * np.sin(phi), linewidth=1.0, label=label, **style)
    ax2.plot(x, y, color=HIGHLIGHT, linewidth=1.0, label="axis path")
    ax2.plot(x[:1], y[:1], "ko", markersize=4, label="start")
    ax2.set_aspect("equal")
    ax2.set_xlabel("θ sin φ [rad]")
    ax2.set_ylabel("−θ cos φ [rad]")
    ax2.set_title("projection (radius = θ)")
    fig.legend(*ax2.get_legend_handles_labels(), loc="outside lower center", ncol=2, fontsize=9,
               frameon=False)
    return fig


#: line styles of the upper (θ1) and lower (θ2) turning circle in the locus figure
UPPER_CIRCLE = {"color": REFERENCE, "linestyle": "--"}
LOWER_CIRCLE = {"color": GREEN, "linestyle": "-."}


def _turning_circles(theta1, theta2):
    """(θ, line style, legend label) of each turning circle to draw: the upper θ1 dashed
    blue, the lower θ2 dash-dotted green; one circle when they coincide (steady
    precession: no nutation), none for NaN."""
    finite = [(th, style, name) for th, style, name in
              ((theta1, UPPER_CIRCLE, "upper turning circle θ1"),
               (theta2, LOWER_CIRCLE, "lower turning circle θ2")) if np.isfinite(th)]
    if len(finite) == 2 and fmt(theta1) == fmt(theta2):
        return [(theta1, UPPER_CIRCLE, f"turning circle θ1 = θ2 = {fmt(theta1)} rad "
                                       "(no nutation)")]
    return [(th, style, f"{name} = {fmt(th)} rad") for th, style, name in finite]


def cubic(u, f, *, u1, u2, u3, b_over_a, u0, xlabel="u = cos θ (dimensionless)",
          names=("u1", "u2", "u3"), ratio_label="b/a", ax=None):
    """f(u) = (1 − u²)(α − βu) − (b − au)² with its roots and the admissible interval.

    Near the vertical the scene passes w = 1 − u instead (``xlabel`` says so): the
    roots are then 1 − u2 ≤ 1 − u1 and the picture is mirrored.
    """
    fig, ax = new_figure(ax, figsize=(6.8, 4.4))
    label = "f(u)" if u[0] <= u3 <= u[-1] else f"f(u)  ({names[2]} = {fmt(u3)} off scale)"
    ax.plot(u, f, color=REFERENCE, label=label)
    ax.axhline(0.0, color="k", linewidth=0.8)
    if np.isfinite(u1) and np.isfinite(u2):
        ax.axvspan(u1, u2, color=HIGHLIGHT, alpha=0.15, label="motion: f ≥ 0")
    # roots that print alike (a double root: steady precession, an unstable sleeping top)
    # share one label, "u1 = u2", instead of two printed over each other
    shown: dict[str, list[str]] = {}
    for value, name in zip((u1, u2, u3), names, strict=True):
        if np.isfinite(value) and u[0] <= value <= u[-1]:
            shown.setdefault(fmt(value), []).append(name)
            if len(shown[fmt(value)]) == 1:
                ax.plot([value], [0.0], "o", color=HIGHLIGHT)
    for value, group in shown.items():
        ax.annotate(" = ".join(sorted(group)), (float(value), 0.0), textcoords="offset points",
                    xytext=(4, 6))
    if u[0] <= 1.0 <= u[-1]:
        ax.axvline(1.0, color=CONTEXT, linestyle=":", linewidth=1.0)
    if np.isfinite(b_over_a) and u[0] <= b_over_a <= u[-1]:
        ax.axvline(b_over_a, color=SEPARATRIX, linestyle="--", linewidth=1.2,
                   label=f"{ratio_label} = {fmt(b_over_a)}")
    ax.plot([u0], [0.0], "k|", markersize=14, label=f"start: {fmt(u0)}")
    finite = f[np.isfinite(f)]
    if finite.size:
        top = max(float(np.max(finite)), 1e-300)
        ax.set_ylim(-1.6 * top, 1.4 * top)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("f(u) = (du/dt)²  [1/s²]")
    # the shaded band fills the axes' height and the curve its corners: the legend under
    # the axes (inside an axes the caller passed, where it covers least)
    if len(fig.axes) == 1:
        legend_below(fig, fontsize=9, max_columns=2)
    else:
        ax.legend(loc="best")
    return fig


def effective_potential(theta, V, *, energy, theta1, theta2, ylabel="V'(θ) [J]", ax=None):
    """V'(θ) (notes (10.28)) with the energy line E' and the turning angles."""
    fig, ax = new_figure(ax, figsize=(6.8, 4.4))
    ax.plot(theta, V, color=REFERENCE, label=ylabel.split(" [")[0])
    ax.axhline(energy, color=HIGHLIGHT, linestyle="--", label=f"energy {fmt(energy)} J")
    # one turning angle where they print alike (steady precession: no nutation)
    turning = ((theta1, "θ1 = θ2"),) if fmt(theta1) == fmt(theta2) else \
        ((theta1, "θ1"), (theta2, "θ2"))
    for th, name in turning:
        if np.isfinite(th):
            ax.axvline(th, color=CONTEXT, linestyle=":")
            ax.annotate(name, (th, energy), textcoords="offset points", xytext=(4, 6))
    finite = V[np.isfinite(V)]
    lo = min(float(np.min(finite)), energy)
    span = max(energy - lo, 1e-12)
    if span <= 1e-9 * max(abs(energy), abs(lo)):
        # E' at the bottom of the well (steady precession): a window of round-off would
        # show no curve; show the well up to a tenth of V's rise over the grid instead
        span = max(0.1 * (float(np.median(finite)) - lo), 1e-12)
    top = energy + 1.5 * span
    ax.set_ylim(lo - 0.3 * span, top)
    # θ where the well shows under that window, with as much again on each side: a narrow
    # band is then a well, not a spike at the middle of [0, π]
    inside = np.asarray(theta)[np.isfinite(V) & (np.asarray(V) <= top)]
    if inside.size:
        a, b = float(inside.min()), float(inside.max())
        pad = max(b - a, 1e-6)
        ax.set_xlim(max(float(np.min(theta)), a - pad), min(float(np.max(theta)), b + pad))
    ax.set_xlabel("θ [rad]")
    ax.set_ylabel(ylabel)
    ax.legend(loc="upper right")
    return fig


def time_series(t, theta, theta_closed, phi_dot, u_error, *, theta1, theta2,
                error_label="|cos θ − closed form|\n(dimensionless)", figsize=(7.0, 7.2)):
    """θ(t) against the closed form, φ̇(t), and |cos θ − closed form|."""
    fig, axes = new_figure_grid(3, 1, figsize=figsize, sharex=True)
    ax = axes[0, 0]
    ax.plot(t, theta, color=HIGHLIGHT, label="integrated")
    ax.plot(t, theta_closed, color=REFERENCE, linestyle="--", linewidth=1.0,
            label="closed form (Jacobi sn²)")
    for th in (theta1, theta2):
        if np.isfinite(th):
            ax.axhline(th, color=CONTEXT, linestyle=":")
    ax.set_ylabel("θ [rad]")
    ax.ticklabel_format(axis="y", useOffset=False)  # no "1e−12+1" offsets: θ as it is
    lo, hi = float(np.nanmin(theta)), float(np.nanmax(theta))
    if hi == 0.0:  # exactly upright throughout: θ = 0, a small band about it
        ax.set_ylim(-1e-3, 1e-3)
    elif hi - lo <= 1e-6 * abs(hi):  # steady precession: round-off only, a band of ±2 %
        ax.set_ylim(0.98 * lo, 1.02 * hi)
    # above the axes: θ(t) fills the band between the circles, peaks in every corner
    fig.legend(*ax.get_legend_handles_labels(), loc="outside upper center", ncol=2,
               frameon=False)
    ax = axes[1, 0]
    ax.plot(t, phi_dot, color=HIGHLIGHT)
    ax.axhline(0.0, color="k", linewidth=0.8)
    ax.set_ylabel("dφ/dt [rad/s]")
    ax = axes[2, 0]
    # exact agreement (the start) left out: on a log axis it would stretch it to 1e-30
    err = np.abs(np.asarray(u_error, dtype=float))
    ax.semilogy(t, np.where(err > 0.0, err, np.nan), color=HIGHLIGHT)
    ax.set_ylabel(error_label)
    ax.set_xlabel("time t [s]")
    return fig


def steady_rates(omega3, slow, fast, *, omega3_min, omega3_config, rate_config, rate_measured,
                 ax=None):
    """The two steady-precession rates (notes (10.45)) against the spin, with the existence
    bound (notes (10.46)), in size: −ω3 mirrors the motion (φ̇ → −φ̇), and below the horizontal
    the fast root is negative, so |φ̇| against |ω3| draws every case on one log axis."""
    fig, ax = new_figure(ax, figsize=(6.8, 4.4))
    spin = np.abs(np.asarray(omega3, dtype=float))
    ax.semilogy(spin, np.abs(slow), color=REFERENCE, label="slow root")
    if np.any(np.isfinite(fast)):
        ax.semilogy(spin, np.abs(fast), color=SEPARATRIX, label="fast root")
    if np.isfinite(omega3_min):
        ax.axvline(omega3_min, color=CONTEXT, linestyle=":",
                   label=f"notes (10.46): |ω3| ≥ {fmt(omega3_min, 4)} rad/s")
    ax.plot([abs(omega3_config)], [abs(rate_config)], "o", color=HIGHLIGHT, markersize=7,
            label="this scene (closed form)")
    if np.isfinite(rate_measured):
        ax.plot([abs(omega3_config)], [abs(rate_measured)], "x", color="k", markersize=9,
                label="mean dφ/dt of the integration")
    ax.set_xlabel("spin |ω3| [rad/s]")
    ax.set_ylabel("|dφ/dt| steady precession [rad/s]")
    ax.legend(loc="best")
    return fig


def sleeping_sweep(t, theta, ratios, *, theta_max, figsize=(7.2, 4.0)):
    """Tilt θ(t) of nearly sleeping tops for several ω3/ω3_threshold, and the largest tilt."""
    fig = Figure(figsize=figsize, layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    cmap = _diverging(ratios)
    for k, r in enumerate(ratios):
        ax1.semilogy(t, np.maximum(theta[k], 1e-18), color=cmap[k],
                     label=f"ω3 = {fmt(r, 3)} × threshold")
    ax1.set_xlabel("time t [s]")
    ax1.set_ylabel("tilt θ [rad]")
    # each top in the same colour in both panels: red shades below the threshold, blue above
    ax2.scatter(ratios, theta_max, c=cmap, zorder=3)
    ax2.set_yscale("log")
    ax2.axvline(1.0, color=SEPARATRIX, linestyle="--", label="ω3² = 4 I1 M g l / I3², notes (10.50)")
    ax2.set_xlabel("ω3 / threshold ω3 (dimensionless)")
    ax2.set_ylabel("largest tilt θmax [rad]")
    ax2.set_title("largest tilt\nunstable (red) below, stable (blue) above", fontsize=10)
    ax1.set_title("growth of a small tilt\n", fontsize=10)
    handles, labels = ax1.get_legend_handles_labels()
    more = ax2.get_legend_handles_labels()
    # under both panels: the curves fill the left one, the points the right one
    fig.legend(handles + more[0], labels + more[1], loc="outside lower center", ncol=3,
               fontsize=8.5, frameon=False)
    return fig


def _diverging(ratios):
    """A colour per ω3/threshold: shades of red below 1 (unstable), of blue above, the
    palest kept clearly coloured (the middle of the map is grey)."""
    from matplotlib import colormaps

    cm = colormaps["coolwarm_r"]
    ratios = np.asarray(ratios, dtype=float)
    colours = [None] * len(ratios)
    for pick, lo, hi in ((ratios < 1.0, 0.0, 0.3), (ratios >= 1.0, 0.7, 1.0)):
        idx = np.nonzero(pick)[0][np.argsort(ratios[pick])]
        # in order of the ratio, the farthest from the threshold darkest
        shades = np.linspace(lo, hi, max(len(idx), 2))
        shades = shades[:len(idx)] if lo == 0.0 else shades[len(shades) - len(idx):]
        for i, x in zip(idx, shades, strict=True):
            colours[i] = cm(x)
    return colours


#: Fig. 4.3: the sphere is seen from this height above the horizon [rad], as printed
FIG43_ELEVATION = np.radians(28.0)


def _view_basis(azimuth, elevation):
    """Unit vectors (towards the viewer, screen right, screen up) of an orthographic view
    of the sphere from ``azimuth`` and ``elevation`` [rad]."""
    ca, sa, ce, se = np.cos(azimuth), np.sin(azimuth), np.cos(elevation), np.sin(elevation)
    return (np.array([ce * ca, ce * sa, se]), np.array([-sa, ca, 0.0]),
            np.array([-se * ca, -se * sa, ce]))


def _front_and_back(points, basis):
    """Screen coordinates of points (N, 3), split into the parts in front of the sphere
    and behind it (NaN elsewhere, so each draws as broken lines)."""
    toward, right, up = basis
    x, y = points @ right, points @ up
    front = points @ toward >= 0.0
    # keep each crossing point in both parts so the two lines meet
    edge = np.zeros_like(front)
    edge[:-1] |= front[:-1] != front[1:]
    edge[1:] |= front[:-1] != front[1:]
    show_front, show_back = front | edge, ~front | edge
    return ((np.where(show_front, x, np.nan), np.where(show_front, y, np.nan)),
            (np.where(show_back, x, np.nan), np.where(show_back, y, np.nan)))


def sphere_locus(ax, axis, *, theta1, theta2, azimuth, elevation=FIG43_ELEVATION,
                 title=("", ""), fontsize=10.0):
    """One panel of Fig. 4.3: the axis path on the unit sphere seen from outside, with the
    turning circles θ1, θ2 (orthographic view; dashed: behind the sphere).

    Parameters
    ----------
    ax : Axes
    axis : ndarray, shape (N, 3)
        Space components of the symmetry axis along the stretch to draw.
    theta1, theta2 : float
        Turning circles [rad].
    azimuth, elevation : float
        Direction of the viewer [rad]: the azimuth faces the viewer.
    title : (str, str) or None
        Panel label and a second, smaller line (None: no title; the caller sets it).
    fontsize : float
        Size [pt] of the labels of the circles and the vertical.
    """
    basis = _view_basis(azimuth, elevation)
    limb = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(np.cos(limb), np.sin(limb), color=CONTEXT, linewidth=1.0)
    pole = basis[2][2]  # screen height of the north pole
    ax.plot([0.0, 0.0], [0.0, pole], color=CONTEXT, linestyle=":", linewidth=1.0)
    ax.annotate("z", (0.0, pole), textcoords="offset points", xytext=(4, 2), color="0.35",
                fontsize=fontsize)
    psi = np.linspace(0.0, 2.0 * np.pi, 721)
    # the upper circle's label above its height, the lower's below: apart on any band
    for th, name, align in ((theta1, "θ1", "bottom"), (theta2, "θ2", "top")):
        circle = np.column_stack([np.sin(th) * np.cos(psi), np.sin(th) * np.sin(psi),
                                  np.full_like(psi, np.cos(th))])
        (fx, fy), (bx, by) = _front_and_back(circle, basis)
        ax.plot(fx, fy, color=REFERENCE, linewidth=1.0)
        ax.plot(bx, by, color=REFERENCE, linewidth=0.8, linestyle="--", alpha=0.45)
        # at the height of the circle's right end, right of both circles: clear of the
        # locus between them
        right = np.array([np.sin(th) * basis[1][0], np.sin(th) * basis[1][1], np.cos(th)])
        ax.annotate(name, (max(np.sin(theta1), np.sin(theta2)), right @ basis[2]),
                    textcoords="offset points", xytext=(3, 0), color=REFERENCE,
                    fontsize=fontsize, va=align, annotation_clip=False)
    (fx, fy), (bx, by) = _front_and_back(np.asarray(axis), basis)
    ax.plot(bx, by, color=HIGHLIGHT, linewidth=1.0, linestyle="--", alpha=0.4)
    ax.plot(fx, fy, color=HIGHLIGHT, linewidth=1.5)
    start = np.asarray(axis)[0]
    behind = start @ basis[0] < 0.0  # hollow: the release is behind the sphere
    ax.plot([start @ basis[1]], [start @ basis[2]], "o", color="k", markersize=4.0,
            markerfacecolor="white" if behind else "k", zorder=4)
    x0, x1, y0, y1 = _cap_limits(theta1, theta2, elevation)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.axis("off")
    if title is not None:
        ax.set_title(f"{title[0]}\n", fontsize=13, loc="center")
        ax.text(0.5, 1.0, title[1], transform=ax.transAxes, ha="center", va="bottom",
                fontsize=10, color="0.3")


def _cap_limits(theta1, theta2, elevation):
    """Screen box (x0, x1, y0, y1) of the cap that holds the band, as printed: the band's
    circles with a margin, the pole above them."""
    low = min(np.cos(th) * np.cos(elevation) - np.sin(th) * np.sin(elevation)
              for th in (theta1, theta2))
    high = max(np.cos(th) * np.cos(elevation) + np.sin(th) * np.sin(elevation)
               for th in (theta1, theta2))
    half = max(np.sin(theta1), np.sin(theta2))
    # room on the right for the circles' labels
    return (-half - 0.1, half + 0.24, max(low - 0.12, -1.05),
            min(max(high, np.cos(elevation)) + 0.1, 1.06))


#: Fig. 4.3 in the report: the page's text width [in] (A4 less 16 mm margins), and the
#: height it may take (a row of three, as printed)
FIG43_REPORT = Size("report", 7.0, 3.0)
#: print (only a width asked for): two rows may be as tall as the figure is wide
FIG43_PRINT_HEIGHT = 1.0
#: text sizes at report size [pt]: panel label, subtitle and the circles' labels
FIG43_FONTS = (11.0, 9.0)


def fig43(loci, *, theta1, theta2, labels, azimuths, elevation=FIG43_ELEVATION, size=None):
    """Fig. 4.3 as printed: the loops, waves and cusps loci on one band.

    Laid out for ``size`` (default: the size the export asks for, :func:`layout.requested`,
    else the report's page width): the panels in the arrangement that makes them largest,
    a row of three on a 16:9 slide and in the report, 2 + 1 on a printed page; text at
    ``size.font`` of :data:`FIG43_FONTS`.

    Parameters
    ----------
    loci : list of ndarray, shape (N_i, 3)
        Axis paths, one per panel.
    theta1, theta2 : float
        The band's turning circles [rad], the same in every panel.
    labels : list of (str, str)
        Panel label and subtitle (its lines separated by newlines).
    azimuths : list of float
        View azimuth of each panel [rad] (facing the middle of its locus).
    elevation : float
        Height of the viewer above the horizon [rad].
    size : layout.Size, optional
        What the figure is drawn for; a height of None: as tall as the panels need, at
        most ``FIG43_PRINT_HEIGHT`` × the width.
    """
    size = size or layout.requested() or FIG43_REPORT
    fill = size.height is not None and size is not FIG43_REPORT  # a slide: the whole box
    width = size.width
    height = size.height if size.height is not None else FIG43_PRINT_HEIGHT * width
    label_pt, sub_pt = (size.font(f) for f in FIG43_FONTS)
    label_pt = max(label_pt, sub_pt + 2.0)
    lines = max(1 + label.count("\n") for _, label in labels)
    pad = 0.06  # [in] around the figure and between a panel and its text
    head = (1.3 * label_pt + 1.25 * sub_pt * lines) / 72.0 + 2 * pad
    x0, x1, y0, y1 = _cap_limits(theta1, theta2, elevation)
    aspect = (x1 - x0) / (y1 - y0)
    grid = layout.panel_grid(len(loci), aspect, width - 2 * pad, height - 2 * pad, head=head)
    w, h = grid.panel, grid.panel / aspect
    used = grid.rows * (h + head)
    fig_h = height if fill else used + 2 * pad
    fig = Figure(figsize=(width, fig_h))
    # the grid centred in the figure
    gap_x = (width - grid.cols * w) / (grid.cols + 1)
    top = fig_h - 0.5 * (fig_h - used)
    for (row, col), axis, (label, sub), azimuth in zip(grid.slots(len(loci)), loci, labels,
                                                       azimuths, strict=True):
        left = gap_x + col * (w + gap_x)
        bottom = top - (row + 1) * (h + head)
        ax = fig.add_axes((left / width, bottom / fig_h, w / width, h / fig_h))
        sphere_locus(ax, axis, theta1=theta1, theta2=theta2, azimuth=azimuth,
                     elevation=elevation, title=None, fontsize=sub_pt)
        ax.text(0.5, 1.0 + pad / h, sub, transform=ax.transAxes, ha="center", va="bottom",
                fontsize=sub_pt, color="0.3", linespacing=1.15)
        ax.text(0.5, 1.0 + (head - pad) / h, label, transform=ax.transAxes, ha="center",
                va="top", fontsize=label_pt)
    layout.mark(fig, size)
    return fig


def weierstrass_rectangle(omega, omega_prime, x0, t_end, *, figsize=(5.4, 3.9), ax=None):
    """The period rectangle of ℘, its half-periods and poles, and the line of the motion.

    Parameters
    ----------
    omega, omega_prime : float
        Half-periods ω (real) and ω′/i [s].
    x0 : float
        z(0) = x0 + iω′ [s].
    t_end : float
        Length of the run [s] (how often the line is run through).
    """
    fig, ax = new_figure(ax, figsize=figsize)
    w, wp = omega, omega_prime
    ax.plot([0, 2 * w, 2 * w, 0, 0], [0, 0, 2 * wp, 2 * wp, 0], color=REFERENCE, linewidth=1.2)
    ax.plot([w, w], [0, 2 * wp], color=CONTEXT, linestyle=":", linewidth=1.0)
    ax.plot([0, 2 * w], [wp, wp], color=HIGHLIGHT, linewidth=2.4, solid_capstyle="butt",
            label="motion: z = x0 + t + ω′")
    ax.plot([0, 2 * w, 0, 2 * w], [0, 0, 2 * wp, 2 * wp], "x", color="k", markersize=7,
            clip_on=False, label="poles of ℘")
    # the half-periods and the values of ℘ there; labels off the motion's line
    for (x, y), name, offset, align in (((w, 0.0), "ω:  ℘ = e1", (0, -12), "center"),
                                        ((0.0, wp), "ω′:\n℘ = e3", (-7, 0), "right"),
                                        ((w, wp), "ω + ω′:  ℘ = e2", (6, -12), "left")):
        ax.plot([x], [y], "o", color=REFERENCE, markersize=5, zorder=4, clip_on=False)
        ax.annotate(name, (x, y), textcoords="offset points", xytext=offset, fontsize=9,
                    color=REFERENCE, ha=align, va="center")
    start = x0 % (2 * w)
    step = min(0.4 * w, max(t_end, 1e-12))
    ax.annotate("", xy=(min(start + step, 2 * w), wp), xytext=(start, wp),
                arrowprops={"arrowstyle": "-|>", "color": "k", "linewidth": 1.2}, zorder=5)
    ax.plot([start], [wp], "o", color="k", markersize=5, zorder=5)
    ax.annotate("t = 0", (start, wp), textcoords="offset points", xytext=(3, 10), fontsize=9,
                ha="left", va="center")
    ax.set_xlim(-0.55 * w, 2.12 * w)
    # room above the rectangle for the legend, clear of its top edge
    ax.set_ylim(-0.25 * wp, 2.6 * wp)
    ax.set_xlabel("Re z [s]")
    ax.set_ylabel("Im z [s]")
    ax.set_title(f"period rectangle of ℘ (the run: {fmt(t_end / (2 * omega), 3)} × 2ω)")
    place_legend(ax, loc="upper center", fontsize=8.5)
    return fig


def _case_boundaries(x, case):
    """(position, left case, right case) wherever the case changes between neighbouring
    members in ``x`` order: the midpoint between them."""
    order = np.argsort(x)
    xs, cs = np.asarray(x)[order], np.asarray(case)[order]
    return [(0.5 * (xs[i] + xs[i + 1]), cs[i], cs[i + 1]) for i in range(len(xs) - 1)
            if cs[i] != cs[i + 1]]


def nutation_family(x, *, theta1, theta2, case, xlabel, precession=None, threshold=None,
                    growth=None):
    """A sweep of tops: the nutation band [θ1, θ2] of each member against the swept value,
    coloured by its case, with the case boundaries marked; below, the precession per
    nutation period, or the sleeping top's growth rate with its threshold ω3 when the
    family crosses it."""
    lower = growth if growth is not None and np.any(np.asarray(growth) > 0) else precession
    rows = 2 if lower is not None else 1
    fig, axes = new_figure_grid(rows, 1, figsize=(6.4, 2.4 + 2.2 * rows), sharex=True)
    ax = axes[0, 0]
    x = np.asarray(x)
    order = np.argsort(x)
    ax.fill_between(x[order], np.degrees(theta1[order]), np.degrees(theta2[order]),
                    color=CONTEXT, alpha=0.18, linewidth=0)
    colours = {"loops": HIGHLIGHT, "waves": REFERENCE, "cusps": SEPARATRIX,
               "steady": "0.35", "sleeping": "0.55"}
    for name in dict.fromkeys(case):
        pick = np.asarray(case) == name
        colour = colours.get(name, "0.2")
        ax.plot(x[pick], np.degrees(theta1[pick]), "v", color=colour, ms=4, label=name)
        ax.plot(x[pick], np.degrees(theta2[pick]), "^", color=colour, ms=4)
    for k, (at, left, right) in enumerate(_case_boundaries(x, case)):
        for a in axes[:, 0]:
            a.axvline(at, color="0.3", linestyle="--", linewidth=0.9)
        # neighbouring boundaries' labels on alternate heights, so close ones stay apart
        ax.annotate(f"{left} | {right}", (at, 1.0), xycoords=("data", "axes fraction"),
                    xytext=(0, 2 + 10 * (k % 2)), textcoords="offset points", ha="center",
                    va="bottom", fontsize=8, color="0.3")
    ax.set_ylabel("θ1 (▼), θ2 (▲) [°]")
    ax.legend(loc="best", fontsize=8, title="case", title_fontsize=8)
    if lower is not None:
        ax2 = axes[1, 0]
        if lower is growth:
            ax2.plot(x[order], np.asarray(growth)[order], "o-", color=HIGHLIGHT, ms=3)
            ax2.set_ylabel("growth rate of a tilt [1/s]")
            if threshold is not None and np.isfinite(threshold):
                ax2.axvline(threshold, color=SEPARATRIX, linewidth=1.5,
                            label=f"sleeping threshold ω3 = {fmt(threshold, 4)} rad/s")
                ax2.legend(loc="best", fontsize=8)
        else:
            ax2.plot(x[order], np.asarray(precession)[order], "o-", color=HIGHLIGHT, ms=3)
            ax2.set_ylabel("Δφ per nutation period [rad]")
    axes[-1, 0].set_xlabel(xlabel)
    return fig


def loci_family(loci, *, theta1, theta2, labels, azimuths, elevation=FIG43_ELEVATION,
                width=9.6):
    """Small multiples of nutation loci, three to a row, each with its own turning
    circles (a sweep's kept members)."""
    n = len(loci)
    cols = min(3, n)
    rows = -(-n // cols)
    panel = width / cols
    fig = Figure(figsize=(width, rows * panel * 0.95 + 0.4), layout="constrained")
    axes = np.atleast_1d(fig.subplots(rows, cols)).ravel()
    for ax, axis, t1, t2, label, azimuth in zip(axes, loci, theta1, theta2, labels, azimuths,
                                               strict=False):
        sphere_locus(ax, axis, theta1=t1, theta2=t2, azimuth=azimuth, elevation=elevation,
                     title=label)
    for ax in axes[n:]:
        ax.set_visible(False)
    return fig
