"""Figures of the rigid body: polhodes on the angular-momentum sphere, the herpolhode on the
invariable plane, the inertia ellipsoid, the intermediate-axis flip."""

from __future__ import annotations

import numpy as np

from .style import CONTEXT, HIGHLIGHT, REFERENCE, SEPARATRIX, new_figure

AXIS_COLOURS = ("#1f4e79", "#4f8a3c", "#8064a2")


def _polhode_family(moments, n_curves: int, n_points: int = 400):
    """Curves l·l = 1, Σ l_k²/I_k = e on the unit L-sphere, for energies e between the axes.

    For curves about axis a (a = smallest or largest moment), with (b, c) the others:
    l_b = ρ cos φ, l_c = ρ sin φ, l_a = ±√(1 − ρ²),
    ρ² = (1/I_a − e) / (1/I_a − cos²φ/I_b − sin²φ/I_c).
    """
    I = np.asarray(moments, dtype=float)
    order = np.argsort(I)
    inv = 1.0 / I
    e_sep = inv[order[1]]
    phi = np.linspace(0.0, 2 * np.pi, n_points)
    curves = []
    for a, e_axis in ((order[0], inv[order[0]]), (order[2], inv[order[2]])):
        b, c = [k for k in range(3) if k != a]
        for f in np.linspace(0.0, 1.0, n_curves + 2)[1:-1]:
            e = e_axis + f * (e_sep - e_axis)
            rho2 = (inv[a] - e) / (inv[a] - np.cos(phi) ** 2 * inv[b] - np.sin(phi) ** 2 * inv[c])
            rho2 = np.clip(rho2, 0.0, 1.0)
            for sign in (1.0, -1.0):
                pts = np.empty((phi.size, 3))
                pts[:, a] = sign * np.sqrt(1.0 - rho2)
                pts[:, b] = np.sqrt(rho2) * np.cos(phi)
                pts[:, c] = np.sqrt(rho2) * np.sin(phi)
                curves.append(pts)
    return curves


def _separatrices(moments, n_points: int = 400):
    """The two great circles through the intermediate axis: Σ l_k²/I_k = 1/I2 on |l| = 1."""
    I = np.asarray(moments, dtype=float)
    s, m, l = np.argsort(I)
    inv = 1.0 / I
    # plane: l_s √(1/I_s − 1/I_m) = ± l_l √(1/I_m − 1/I_l)
    u, v = np.sqrt(inv[s] - inv[m]), np.sqrt(inv[m] - inv[l])
    phi = np.linspace(0.0, 2 * np.pi, n_points)
    out = []
    for sign in (1.0, -1.0):
        n = np.zeros(3)
        n[s], n[l] = v, sign * u  # direction in the (s, l) plane lying on the separatrix plane
        n /= np.linalg.norm(n)
        e2 = np.zeros(3)
        e2[m] = 1.0
        out.append(np.outer(np.cos(phi), n) + np.outer(np.sin(phi), e2))
    return out


def polhodes(moments, L_body, *, n_curves: int = 5, ax=None):
    """Polhodes on the unit angular-momentum sphere (body frame), separatrices, the scene's own.

    L_body : ndarray, shape (N, 3) — the body-frame angular momentum of the run.
    """
    fig, ax = new_figure(ax, figsize=(6.4, 6.0), projection="3d")
    u, v = np.mgrid[0:2 * np.pi:40j, 0:np.pi:20j]
    ax.plot_wireframe(np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v), color=CONTEXT,
                      linewidth=0.3, alpha=0.35, rasterized=True)
    distinct = len(set(np.round(np.asarray(moments) / np.max(moments), 12))) == 3
    with np.errstate(invalid="ignore", divide="ignore"):
        family = _polhode_family(moments, n_curves)
    for c in family:
        if np.all(np.isfinite(c)):
            ax.plot(c[:, 0], c[:, 1], c[:, 2], color=CONTEXT, linewidth=0.9)
    for k, c in enumerate(_separatrices(moments) if distinct else []):
        ax.plot(c[:, 0], c[:, 1], c[:, 2], color=SEPARATRIX, linewidth=1.6,
                label="separatrices (2E = L²/I2)" if k == 0 else None)
    track = np.asarray(L_body, dtype=float)
    track = track / np.linalg.norm(track, axis=1, keepdims=True)
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


def flips(t, omega, *, growth_rate=None, omega0=None, ax=None):
    """ω components against time, and (optionally) the linear growth envelope of the
    perturbation about the intermediate axis."""
    fig, ax = new_figure(ax, figsize=(7.0, 4.0))
    for k in range(3):
        ax.plot(t, omega[:, k], color=AXIS_COLOURS[k], label=f"ω{k + 1}")
    if growth_rate is not None and omega0 is not None:
        env = omega0 * np.exp(growth_rate * np.asarray(t))
        keep = env < 1.2 * np.max(np.abs(omega))
        ax.plot(t[keep], env[keep], "--", color=CONTEXT,
                label="perturbation ∝ exp(γt), γ from (10.14)")
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("body-frame ω [rad/s]")
    ax.legend(loc="upper right", ncols=2)
    return fig


def inertia_ellipsoid(moments, axes, *, points=None, masses=None, ax=None):
    """The inertia ellipsoid Σ I_k x_k² = 1 (principal frame turned into the lab by ``axes``)."""
    fig, ax = new_figure(ax, figsize=(6.0, 5.6), projection="3d")
    m = np.asarray(moments, dtype=float)
    semi = 1.0 / np.sqrt(m)
    u, v = np.mgrid[0:2 * np.pi:36j, 0:np.pi:18j]
    local = np.stack([semi[0] * np.cos(u) * np.sin(v), semi[1] * np.sin(u) * np.sin(v),
                      semi[2] * np.cos(v)], axis=-1)
    lab = local @ np.asarray(axes).T
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
