"""Heavy-top figures: nutation locus (Fig. 4.3 style), f(u), effective potential,
time series, steady precession rates and the sleeping-top sweep."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .style import CONTEXT, HIGHLIGHT, REFERENCE, SEPARATRIX, new_figure, new_figure_grid


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
    ax.set_ylabel("f(u) = u̇²  [1/s²]")
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
    ax.set_ylim(lo - 0.3 * span, energy + 1.5 * span)
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
    ax.set_ylabel("φ̇ [rad/s]")
    ax = axes[2, 0]
    ax.semilogy(t, np.maximum(np.abs(u_error), 1e-30), color=HIGHLIGHT)
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
                label="mean φ̇ of the integration")
    ax.set_xlabel("spin ω3 [rad/s]")
    ax.set_ylabel("|φ̇| steady precession [rad/s]")
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
