"""Figures of the rigid body: polhodes on the angular-momentum sphere, the herpolhode on the
invariable plane, the inertia ellipsoid, the intermediate-axis flip.

They draw what they are given: every curve (polhode family, separatrices, ellipsoid
surface, growth envelope) is computed in :mod:`reportgen.core` and read from the archive."""

from __future__ import annotations

import numpy as np

from .style import BLUE, CONTEXT, GREEN, HIGHLIGHT, PURPLE, REFERENCE, SEPARATRIX, new_figure

AXIS_COLOURS = (BLUE, GREEN, PURPLE)


def polhodes(family, separatrices, track, *, ax=None):
    """Polhodes on the unit angular-momentum sphere (body frame): a family, the
    separatrices and the scene's own, all given as unit vectors L/|L|.

    family : ndarray, shape (K, n, 3) — curves of a range of energies (grey).
    separatrices : ndarray, shape (S, n, 3) — S = 2, or 0 for a symmetric body.
    track : ndarray, shape (N, 3) — the run's body-frame L/|L|.
    """
    fig, ax = new_figure(ax, figsize=(6.4, 6.0), projection="3d")
    u, v = np.mgrid[0:2 * np.pi:40j, 0:np.pi:20j]
    ax.plot_wireframe(np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v), color=CONTEXT,
                      linewidth=0.3, alpha=0.35, rasterized=True)
    for c in family:
        ax.plot(c[:, 0], c[:, 1], c[:, 2], color=CONTEXT, linewidth=0.9)
    for k, c in enumerate(separatrices):
        ax.plot(c[:, 0], c[:, 1], c[:, 2], color=SEPARATRIX, linewidth=1.6,
                label="separatrices (2E = L²/I2)" if k == 0 else None)
    track = np.asarray(track, dtype=float)
    ax.plot(track[:, 0], track[:, 1], track[:, 2], color=HIGHLIGHT, linewidth=2.4,
            label="this scene's polhode")
    ax.scatter(*track[0], color=HIGHLIGHT, s=30, depthshade=False)
    for k in range(3):
        e = np.zeros(3)
        e[k] = 1.25
        ax.plot([-e[0], e[0]], [-e[1], e[1]], [-e[2], e[2]], color=AXIS_COLOURS[k],
                linewidth=1.0, linestyle=":")
        ax.text(*(1.32 * e / 1.25), f"{k + 1}", color=AXIS_COLOURS[k])
    ax.set_xlabel("L₁/|L|")
    ax.set_ylabel("L₂/|L|")
    ax.set_zlabel("L₃/|L|")
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=22, azim=35)
    ax.legend(loc="upper left")
    return fig


def herpolhode(x, y, *, ax=None):
    """The tip of ω in the invariable plane (space frame, perpendicular to L)."""
    fig, ax = new_figure(ax, figsize=(5.6, 5.2))
    ax.plot(x, y, color=HIGHLIGHT, linewidth=1.0)
    ax.plot(x[0], y[0], "o", color=HIGHLIGHT, label="start")
    ax.plot(0.0, 0.0, "+", color=REFERENCE, markersize=12, label="foot of L")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("ω·e₁ in the invariable plane [rad/s]")
    ax.set_ylabel("ω·e₂ in the invariable plane [rad/s]")
    ax.legend(loc="upper right")
    return fig


def flips(t, omega, *, envelope=None, ax=None):
    """ω components against time and (optionally) the linear growth envelope δ0 e^{γt} of
    the perturbation about the intermediate axis, shape (N,) like ``t``, drawn while it
    stays below 1.2 max |ω|."""
    fig, ax = new_figure(ax, figsize=(7.0, 4.0))
    for k in range(3):
        ax.plot(t, omega[:, k], color=AXIS_COLOURS[k], label=f"ω{k + 1}")
    if envelope is not None:
        env = np.asarray(envelope)
        keep = env < 1.2 * np.max(np.abs(omega))
        ax.plot(t[keep], env[keep], "--", color=CONTEXT,
                label="perturbation ∝ exp(γt), γ from (10.14)")
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("body-frame ω [rad/s]")
    ax.legend(loc="upper right", ncols=2)
    return fig


def inertia_ellipsoid(moments, axes, surface, semi_axes, *, points=None, masses=None,
                      ax=None):
    """The inertia ellipsoid Σ I_k x_k² = 1 with its principal axes.

    moments : (3,) principal moments [kg m²] (legend); axes : (3, 3) lab-frame principal
    axes (columns); surface : (n_u, n_v, 3) lab-frame points of the ellipsoid;
    semi_axes : (3,) 1/√I_k; points, masses : a point set drawn scaled into the ellipsoid.
    """
    fig, ax = new_figure(ax, figsize=(6.0, 5.6), projection="3d")
    m = np.asarray(moments, dtype=float)
    semi = np.asarray(semi_axes, dtype=float)
    lab = np.asarray(surface, dtype=float)
    ax.plot_surface(lab[..., 0], lab[..., 1], lab[..., 2], color=REFERENCE, alpha=0.18,
                    linewidth=0.2, edgecolor=REFERENCE, rasterized=True)
    for k in range(3):
        d = np.asarray(axes)[:, k] * semi[k] * 1.25
        ax.plot([-d[0], d[0]], [-d[1], d[1]], [-d[2], d[2]], color=AXIS_COLOURS[k],
                linewidth=2.0, label=f"axis {k + 1}: I = {m[k]:.4g} kg m²")
    if points is not None:
        p = np.asarray(points, dtype=float)
        p = p - np.average(p, axis=0, weights=masses)
        scale = semi.max() / max(np.linalg.norm(p, axis=1).max(), 1e-300)
        w = np.asarray(masses, dtype=float)
        ax.scatter(*(scale * p).T, s=40 * w / w.max(), color=HIGHLIGHT, depthshade=False,
                   label=f"masses (scaled ×{scale:.3g})")
    lim = semi.max() * 1.3
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_zlim(-lim, lim)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x [(kg m²)^−½]")
    ax.set_ylabel("y [(kg m²)^−½]")
    ax.set_zlabel("z [(kg m²)^−½]")
    ax.legend(loc="upper left")
    return fig
