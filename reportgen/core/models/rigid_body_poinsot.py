r"""Poinsot's geometry of the free rigid body: polhodes on the inertia ellipsoid, the
invariable plane and the herpolhode.

Body frame = principal frame, moments I = diag(I1, I2, I3).  Both

    2T = ω·Iω          (the energy ellipsoid; lecture notes (10.15))
    L² = ω·I²ω         (|L| conserved)

are constant, so the body-frame ω moves on the intersection of two quadrics: the
polhode (Goldstein, 3rd ed., §5.6; Landau & Lifshitz §37).  With x = ω/√(2T) the first
is the inertia ellipsoid x·Ix = 1 (semi-axes 1/√I_k).  Poinsot's construction: in space,
that ellipsoid (centre fixed, moving with the body) touches the invariable plane
x·n = √(2T)/|L|, n = L/|L|, at the tip of x — the plane's distance is fixed because
x·L = 2T/√(2T) — and its normal there, ∝ Ix ∝ L, is the plane's: the ellipsoid rolls
on the plane without slipping (the contact point lies on the instantaneous axis).  The
contact point traces the polhode on the body and the herpolhode on the plane.

Polhode family: with D = L²/2T between the smallest and the largest moment, eliminating
x_a² between the two quadrics (a = the extreme axis the curve circles, b, c the others)
gives an ellipse in the (b, c) plane,

    I_b (I_b − I_a) x_b² + I_c (I_c − I_a) x_c² = D − I_a,

so x_b = A_b cos φ, x_c = A_c sin φ with A_k² = (D − I_a)/(I_k (I_k − I_a)) and
x_a = ±√((1 − I_b x_b² − I_c x_c²)/I_a): curves about the smallest axis for
I_min < D < I_mid, about the largest for I_mid < D < I_max.  The separatrices (D = I_mid)
are the two planar ellipses x = cos φ e_m/√I_m + sin φ (A_l e_l ± B e_s) through the
intermediate axis m, with A_l² = (I_m − I_s)/(I_l (I_l − I_s)), B² = (I_l − I_m)/
(I_s (I_l − I_s)) (s, l: smallest, largest moment).

Symmetric body (I1 = I2 = I⊥, axis 3): L = I⊥ω + (I3 − I⊥) ω3 e3, so the part of ω
normal to L is −(I3 − I⊥) ω3 (e3)⊥/I⊥ of constant length; e3 precesses uniformly about L
(Landau & Lifshitz §33), and the herpolhode is a circle about the foot of L of radius

    r = |I3 − I⊥| |ω3| ω⊥ / (|L| √(2T)),     ω⊥ = √(ω1² + ω2²)

in the units of x (since |(e3)⊥| = sin θ = I⊥ ω⊥/|L|).

References
----------
.. [1] Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed., §5.6 (Poinsot's
       construction, polhode, herpolhode, invariable plane).
.. [2] Landau & Lifshitz, *Mechanics*, 3rd ed., §33 (free symmetric top), §37 (polhodes).
.. [3] Lecture notes §10, eqs. (10.15)–(10.17).
"""

from __future__ import annotations

import numpy as np

from ..inertia import inertia_ellipsoid
from ..rotations import quat_to_matrix

#: moments equal to this relative tolerance are treated as equal (symmetric body)
EQUAL_MOMENTS = 1e-12


def _distinct(I, i: int, j: int) -> bool:
    return abs(I[i] - I[j]) > EQUAL_MOMENTS * float(np.max(I))


def polhode_curve(moments, twice_energy: float, D: float, axis: int, sign: float,
                  n_points: int = 121) -> np.ndarray:
    """The polhode ω·Iω = 2T, ω·I²ω = 2T·D circling extreme axis ``axis`` on the side
    ``sign`` (±1) of it, shape (n_points, 3) [rad/s] (module docstring)."""
    I = np.asarray(moments, dtype=float)
    a = axis
    b, c = [k for k in range(3) if k != a]
    phi = np.linspace(0.0, 2 * np.pi, n_points)
    x = np.empty((n_points, 3))
    x[:, b] = np.sqrt((D - I[a]) / (I[b] * (I[b] - I[a]))) * np.cos(phi)
    x[:, c] = np.sqrt((D - I[a]) / (I[c] * (I[c] - I[a]))) * np.sin(phi)
    rest = (1.0 - I[b] * x[:, b] ** 2 - I[c] * x[:, c] ** 2) / I[a]
    x[:, a] = sign * np.sqrt(np.maximum(rest, 0.0))  # rounding may dip below 0 by 1e-17
    return np.sqrt(twice_energy) * x


def polhodes_on_ellipsoid(moments, omega0, n_curves: int = 4, n_points: int = 121,
                          mesh: tuple[int, int] = (25, 13)) -> dict:
    """Polhodes on the energy ellipsoid ω·Iω = 2T of the state ``omega0``.

    The family is a ladder of L² = 2T·D: ``n_curves`` values of D between each extreme
    moment and the intermediate one, at D = I_a + f² (I_m − I_a), f = k/(n_curves + 1)
    (equal steps in the curves' size, which grows like √(D − I_a)), both signs of x_a.

    Parameters
    ----------
    moments : array_like, shape (3,)  principal moments [kg m²], any order
    omega0 : array_like, shape (3,)  body-frame ω of the run [rad/s] (fixes 2T)

    Returns
    -------
    dict
        ``twice_energy`` 2T [J]; ``semi_axes`` (3,) √(2T/I_k) [rad/s]; ``surface``
        (n_u, n_v, 3) points of the ellipsoid [rad/s]; ``family`` (K, n_points, 3) [rad/s]
        and ``family_L_squared`` (K,) the L² of each curve; ``separatrices``
        (S, n_points, 3), S = 2 for three distinct moments, else 0;
        ``separatrix_L_squared`` = 2T·I_m; the run's own ``L_squared``, its
        ``separatrix_offset`` (L² − 2T·I_m)/(2T·I_m) and ``circled_axis``, the 1-based
        body axis its polhode circles (0 on the separatrix).  A spherical body has
        K = S = 0.
    """
    I = np.asarray(moments, dtype=float)
    w = np.asarray(omega0, dtype=float)
    T2 = float(np.sum(I * w**2))
    L2 = float(np.sum((I * w) ** 2))
    s, m, l = np.argsort(I, kind="stable")
    ell = inertia_ellipsoid(I, np.eye(3), *mesh)
    curves, ladder = [], []
    for a in (s, l):
        if not _distinct(I, a, m):
            continue  # a symmetric body: no curves about the equal pair
        for f in np.arange(1, n_curves + 1) / (n_curves + 1):
            D = I[a] + f * f * (I[m] - I[a])
            for sign in (1.0, -1.0):
                curves.append(polhode_curve(I, T2, D, a, sign, n_points))
                ladder.append(T2 * D)
    offset = (L2 - T2 * I[m]) / (T2 * I[m])
    seps = []
    if _distinct(I, s, m) and _distinct(I, m, l):
        phi = np.linspace(0.0, 2 * np.pi, n_points)
        A_l = np.sqrt((I[m] - I[s]) / (I[l] * (I[l] - I[s])))
        B = np.sqrt((I[l] - I[m]) / (I[s] * (I[l] - I[s])))
        for sign in (1.0, -1.0):
            x = np.zeros((n_points, 3))
            x[:, m] = np.cos(phi) / np.sqrt(I[m])
            x[:, l] = A_l * np.sin(phi)
            x[:, s] = sign * B * np.sin(phi)
            seps.append(np.sqrt(T2) * x)
    return {"twice_energy": T2,
            "semi_axes": np.sqrt(T2) * ell["semi_axes"],
            "surface": np.sqrt(T2) * ell["surface"],
            "family": np.array(curves) if curves else np.zeros((0, n_points, 3)),
            "family_L_squared": np.array(ladder),
            "separatrices": np.array(seps) if seps else np.zeros((0, n_points, 3)),
            "separatrix_L_squared": T2 * float(I[m]),
            "L_squared": L2,
            "separatrix_offset": offset,
            "circled_axis": 0 if offset == 0.0 else int((s if offset < 0 else l) + 1)}


def invariable_plane_basis(L_space) -> np.ndarray:
    """Rows (e1, e2, e3) of a right-handed orthonormal basis with e3 = −L/|L|: the picture
    frame of Poinsot's construction (the plane below, the ellipsoid resting on it)."""
    e3 = -np.asarray(L_space, dtype=float) / np.linalg.norm(L_space)
    e1 = np.cross(e3, [1.0, 0.0, 0.0] if abs(e3[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    return np.array([e1, np.cross(e3, e1), e3])


def poinsot_construction(omega, quat, moments, at: int = -1,
                         mesh: tuple[int, int] = (25, 13)) -> dict:
    """Poinsot's construction of a run, in the invariable-plane frame of
    :func:`invariable_plane_basis` (coordinates of x = ω/√(2T) [(kg m²)^−½]).

    Parameters
    ----------
    omega : ndarray, shape (N, 3)  body-frame ω [rad/s]
    quat : ndarray, shape (N, 4)  attitude quaternions (body -> space)
    moments : array_like, shape (3,)  [kg m²]
    at : int
        The sample at which the ellipsoid is drawn (default the last: the herpolhode
        ends at the contact point).

    Returns
    -------
    dict
        ``basis`` (3, 3) rows e1, e2, e3 (space frame); ``plane_height`` = −√(2T)/|L|,
        the plane's e3 coordinate (from the initial state); ``herpolhode`` (N, 3): the
        space-frame x(t) in the basis (its e3 column is the plane's height, to the
        integration error); ``contact_index`` the sample drawn (non-negative);
        ``polhode`` (N, 3): the body-frame track x(t) carried by the attitude of sample
        ``at`` (the polhode on the body's ellipsoid as it sits then); ``surface`` (n_u,
        n_v, 3) and ``semi_axes`` (3,) of the inertia ellipsoid x·Ix = 1 at that
        attitude; ``axes`` (3, 3): column k the semi-axis vector 1/√I_k of body axis k.
    """
    I = np.asarray(moments, dtype=float)
    omega = np.asarray(omega, dtype=float)
    T2 = float(np.sum(I * omega[0] ** 2))
    R = quat_to_matrix(quat)
    L0 = R[0] @ (I * omega[0])
    basis = invariable_plane_basis(L0)
    x = omega / np.sqrt(T2)
    her = np.einsum("nij,nj->ni", R, x) @ basis.T
    P = basis @ R[at]  # body components -> picture coordinates at sample `at`
    ell = inertia_ellipsoid(I, P, *mesh)
    return {"basis": basis,
            "plane_height": -np.sqrt(T2) / float(np.linalg.norm(L0)),
            "herpolhode": her,
            "contact_index": int(np.arange(len(x))[at]),
            "polhode": x @ P.T,
            "surface": ell["surface"],
            "semi_axes": ell["semi_axes"],
            "axes": P * ell["semi_axes"]}


def symmetric_herpolhode_radius(omega0, moments, axis: int) -> float:
    """Radius of the symmetric body's circular herpolhode, in units of x = ω/√(2T):
    |I_s − I⊥| |ω_s| ω⊥ / (|L| √(2T)) (module docstring; Landau & Lifshitz §33)."""
    I = np.asarray(moments, dtype=float)
    w = np.asarray(omega0, dtype=float)
    b, c = (axis + 1) % 3, (axis + 2) % 3
    T2 = float(np.sum(I * w**2))
    L = float(np.linalg.norm(I * w))
    return abs(I[axis] - I[b]) * abs(w[axis]) * float(np.hypot(w[b], w[c])) / (L * np.sqrt(T2))
