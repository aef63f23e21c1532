"""Heavy-top figures: nutation locus, Fig. 4.3 as printed, f(u), the ℘ period rectangle,
effective potential, time series, steady precession rates and the sleeping-top sweep.

Figure text avoids combining accents (φ̇ is written dφ/dt): the PDF engine draws the
combining dot of an SVG text as a dotted circle."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ...rendering.plots.style import (
    CONTEXT,
    HIGHLIGHT,
    REFERENCE,
    SEPARATRIX,
    new_figure,
    new_figure_grid,
)


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
    for th in (theta1, theta2):
        if np.isfinite(th):
            ax3.plot(*_circle_on_sphere(th), color=REFERENCE, linestyle="--", linewidth=1.0)
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
    for th, label in ((theta1, "θ1"), (theta2, "θ2")):
        if np.isfinite(th):
            phi = np.linspace(0, 2 * np.pi, 361)
            ax2.plot(th * np.cos(phi), th * np.sin(phi), color=REFERENCE, linestyle="--",
                     linewidth=1.0, label=f"turning circle {label} = {th:.4g} rad")
    ax2.plot(x, y, color=HIGHLIGHT, linewidth=1.0, label="axis path")
    ax2.plot(x[:1], y[:1], "ko", markersize=4, label="start")
    ax2.set_aspect("equal")
    ax2.set_xlabel("θ sin φ [rad]")
    ax2.set_ylabel("−θ cos φ [rad]")
    ax2.set_title("projection (radius = θ)")
    fig.legend(*ax2.get_legend_handles_labels(), loc="outside lower center", ncol=2, fontsize=9,
               frameon=False)
    return fig


def cubic(u, f, *, u1, u2, u3, b_over_a, u0, xlabel="u = cos θ", names=("u1", "u2", "u3"),
          ratio_label="b/a", ax=None):
    """f(u) = (1 − u²)(α − βu) − (b − au)² with its roots and the admissible interval.

    Near the vertical the scene passes w = 1 − u instead (``xlabel`` says so): the
    roots are then 1 − u2 ≤ 1 − u1 and the picture is mirrored.
    """
    fig, ax = new_figure(ax, figsize=(6.8, 4.4))
    label = "f(u)" if u[0] <= u3 <= u[-1] else f"f(u)  ({names[2]} = {u3:.6g} off scale)"
    ax.plot(u, f, color=REFERENCE, label=label)
    ax.axhline(0.0, color="k", linewidth=0.8)
    if np.isfinite(u1) and np.isfinite(u2):
        ax.axvspan(u1, u2, color=HIGHLIGHT, alpha=0.15, label="motion: f ≥ 0")
    for value, name in zip((u1, u2, u3), names, strict=True):
        if np.isfinite(value) and u[0] <= value <= u[-1]:
            ax.plot([value], [0.0], "o", color=HIGHLIGHT)
            ax.annotate(name, (value, 0.0), textcoords="offset points", xytext=(4, 6))
    if u[0] <= 1.0 <= u[-1]:
        ax.axvline(1.0, color=CONTEXT, linestyle=":", linewidth=1.0)
    if np.isfinite(b_over_a) and u[0] <= b_over_a <= u[-1]:
        ax.axvline(b_over_a, color=SEPARATRIX, linestyle="--", linewidth=1.2,
                   label=f"{ratio_label} = {b_over_a:.6g}")
    ax.plot([u0], [0.0], "k|", markersize=14, label=f"start: {u0:.6g}")
    finite = f[np.isfinite(f)]
    if finite.size:
        top = max(float(np.max(finite)), 1e-300)
        ax.set_ylim(-1.6 * top, 1.4 * top)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("f(u) = (du/dt)²  [1/s²]")
    ax.legend(loc="best")
    return fig


def effective_potential(theta, V, *, energy, theta1, theta2, ylabel="V'(θ) [J]", ax=None):
    """V'(θ) (10.28) with the energy line E' and the turning angles."""
    fig, ax = new_figure(ax, figsize=(6.8, 4.4))
    ax.plot(theta, V, color=REFERENCE, label=ylabel.split(" [")[0])
    ax.axhline(energy, color=HIGHLIGHT, linestyle="--", label=f"energy {energy:.6g} J")
    for th, name in ((theta1, "θ1"), (theta2, "θ2")):
        if np.isfinite(th):
            ax.axvline(th, color=CONTEXT, linestyle=":")
            ax.annotate(name, (th, energy), textcoords="offset points", xytext=(4, 6))
    finite = V[np.isfinite(V)]
    lo = float(np.min(finite))
    span = max(energy - lo, 1e-12)
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
                error_label="|cos θ − closed form|", figsize=(7.0, 7.2)):
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
    ax.legend(loc="upper right")
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
    """The two steady-precession rates (10.45) against ω3, with the existence bound (10.46)."""
    fig, ax = new_figure(ax, figsize=(6.8, 4.4))
    ax.semilogy(omega3, slow, color=REFERENCE, label="slow root")
    ax.semilogy(omega3, fast, color=SEPARATRIX, label="fast root")
    if np.isfinite(omega3_min):
        ax.axvline(omega3_min, color=CONTEXT, linestyle=":",
                   label=f"(10.46): ω3 ≥ {omega3_min:.4g} rad/s")
    ax.plot([omega3_config], [abs(rate_config)], "o", color=HIGHLIGHT, markersize=7,
            label="this scene (closed form)")
    if np.isfinite(rate_measured):
        ax.plot([omega3_config], [abs(rate_measured)], "x", color="k", markersize=9,
                label="mean dφ/dt of the integration")
    ax.set_xlabel("spin ω3 [rad/s]")
    ax.set_ylabel("|dφ/dt| steady precession [rad/s]")
    ax.legend(loc="best")
    return fig


def sleeping_sweep(t, theta, ratios, *, theta_max, figsize=(11.0, 4.6)):
    """Tilt θ(t) of nearly sleeping tops for several ω3/ω3_threshold, and the largest tilt."""
    fig = Figure(figsize=figsize, layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    cmap = _diverging(len(ratios))
    for k, r in enumerate(ratios):
        ax1.semilogy(t, np.maximum(theta[k], 1e-18), color=cmap[k],
                     label=f"ω3 = {r:.3g} × threshold")
    ax1.set_xlabel("time t [s]")
    ax1.set_ylabel("tilt θ [rad]")
    ax1.legend(loc="lower right", fontsize=8)
    ax1.set_title("growth of a small tilt")
    colours = [HIGHLIGHT if r < 1 else REFERENCE for r in ratios]
    ax2.scatter(ratios, theta_max, c=colours, zorder=3)
    ax2.set_yscale("log")
    ax2.axvline(1.0, color=SEPARATRIX, linestyle="--", label="ω3² = 4 I1 M g l / I3² (10.50)")
    ax2.set_xlabel("ω3 / ω3,threshold")
    ax2.set_ylabel("largest tilt θmax [rad]")
    ax2.set_title("unstable (red) below, stable (blue) above")
    fig.legend(*ax2.get_legend_handles_labels(), loc="outside lower center", ncol=2, fontsize=9,
               frameon=False)
    return fig


def _diverging(n):
    from matplotlib import colormaps

    cm = colormaps["coolwarm_r"]
    return [cm(x) for x in np.linspace(0.05, 0.95, max(n, 2))][:n]


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
                 title=("", "")):
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
    title : (str, str)
        Panel label and a second, smaller line.
    """
    basis = _view_basis(azimuth, elevation)
    limb = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(np.cos(limb), np.sin(limb), color=CONTEXT, linewidth=1.0)
    pole = basis[2][2]  # screen height of the north pole
    ax.plot([0.0, 0.0], [0.0, pole], color=CONTEXT, linestyle=":", linewidth=1.0)
    ax.annotate("z", (0.0, pole), textcoords="offset points", xytext=(4, 2), color="0.35",
                fontsize=10)
    psi = np.linspace(0.0, 2.0 * np.pi, 721)
    for th, name in ((theta1, "θ1"), (theta2, "θ2")):
        circle = np.column_stack([np.sin(th) * np.cos(psi), np.sin(th) * np.sin(psi),
                                  np.full_like(psi, np.cos(th))])
        (fx, fy), (bx, by) = _front_and_back(circle, basis)
        ax.plot(fx, fy, color=REFERENCE, linewidth=1.0)
        ax.plot(bx, by, color=REFERENCE, linewidth=0.8, linestyle="--", alpha=0.45)
        right = np.array([np.sin(th) * basis[1][0], np.sin(th) * basis[1][1], np.cos(th)])
        ax.annotate(name, (right @ basis[1], right @ basis[2]), textcoords="offset points",
                    xytext=(3, 0), color=REFERENCE, fontsize=11, va="center",
                    annotation_clip=False)
    (fx, fy), (bx, by) = _front_and_back(np.asarray(axis), basis)
    ax.plot(bx, by, color=HIGHLIGHT, linewidth=1.0, linestyle="--", alpha=0.4)
    ax.plot(fx, fy, color=HIGHLIGHT, linewidth=1.5)
    ax.plot([axis[0] @ basis[1]], [axis[0] @ basis[2]], "o", color="k", markersize=3.5)
    x0, x1, y0, y1 = _cap_limits(theta1, theta2, elevation)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.axis("off")
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


def fig43(loci, *, theta1, theta2, labels, azimuths, elevation=FIG43_ELEVATION, width=9.6):
    """Fig. 4.3 as printed: the loops, waves and cusps loci on one band, side by side.

    Parameters
    ----------
    loci : list of ndarray, shape (N_i, 3)
        Axis paths, one per panel.
    theta1, theta2 : float
        The band's turning circles [rad], the same in every panel.
    labels : list of (str, str)
        Panel label and subtitle.
    azimuths : list of float
        View azimuth of each panel [rad] (facing the middle of its locus).
    elevation : float
        Height of the viewer above the horizon [rad].
    width : float
        Figure width [in]; the height follows from the cap the band needs.
    """
    x0, x1, y0, y1 = _cap_limits(theta1, theta2, elevation)
    panel = width / len(loci)
    fig = Figure(figsize=(width, panel * (y1 - y0) / (x1 - x0) + 0.7), layout="constrained")
    axes = fig.subplots(1, len(loci))
    for ax, axis, label, azimuth in zip(axes, loci, labels, azimuths, strict=True):
        sphere_locus(ax, axis, theta1=theta1, theta2=theta2, azimuth=azimuth,
                     elevation=elevation, title=label)
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
    ax.legend(loc="upper center", fontsize=8.5)
    ax.set_xlim(-0.55 * w, 2.12 * w)
    ax.set_ylim(-0.25 * wp, 2.12 * wp)
    ax.set_xlabel("Re z [s]")
    ax.set_ylabel("Im z [s]")
    ax.set_title(f"period rectangle of ℘ (the run: {t_end / (2 * omega):.3g} × 2ω)")
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
    ax.set_ylabel("θ1 (▼), θ2 (▲) [deg]")
    ax.legend(loc="best", fontsize=8, title="case", title_fontsize=8)
    if lower is not None:
        ax2 = axes[1, 0]
        if lower is growth:
            ax2.plot(x[order], np.asarray(growth)[order], "o-", color=HIGHLIGHT, ms=3)
            ax2.set_ylabel("growth rate of a tilt [1/s]")
            if threshold is not None and np.isfinite(threshold):
                ax2.axvline(threshold, color=SEPARATRIX, linewidth=1.5,
                            label=f"sleeping threshold ω3 = {threshold:.4g} rad/s")
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
