r"""The kinetic energy of a moving body split at its centre of mass, lecture notes
(8.38)–(8.42), measured from the body's point masses.

Each point mass sits at r_A = R + x_A (8.38), R the centre of mass, M R = Σ m_A r_A
(8.39), so Σ m_A x_A = 0 (8.40).  Its kinetic energy

    T = ½ Σ m_A (Ṙ + ẋ_A)² = ½ M Ṙ² + Σ m_A Ṙ·ẋ_A + ½ Σ m_A ẋ_A²       (8.41)

loses its cross term by (8.40), leaving T = ½ M Ṙ² + K (8.42), with K = ½ ω·I ω for a
rigid body (ẋ_A = ω × x_A).

The check: at a few samples of the run the body's quadrature nodes
(:meth:`~reportgen.kinds.inertia.config._ShapeBase.mass_elements`, from the closed-form
centre of mass) are turned by the integrated attitude, x_A = R(t) b_A, and moved at
ṙ_A = Ṙ + ω × x_A; Σ ½ m_A |ṙ_A|² is summed point by point and set against ½ M Ṙ² + ½ ω·I ω
from the stored state and the closed-form moments.  The quadrature is exact for the
first and second moments, so the two agree to rounding.
"""

from __future__ import annotations

import numpy as np

#: how many stored samples of the run the split is measured at (evenly spread, both ends)
SAMPLES = 6


def sample_indices(n: int, count: int = SAMPLES) -> np.ndarray:
    """``count`` indices evenly spread over ``n`` stored samples, the first and the last
    included (fewer when the run has fewer samples)."""
    return np.unique(np.round(np.linspace(0, n - 1, min(count, n))).astype(int))


def kinetic_energy_split(t, omega, rotation, moments, *, mass, cm_velocity, masses,
                         positions, count: int = SAMPLES) -> dict:
    """T summed over the point masses against ½ M Ṙ² + ½ ω·I ω, notes (8.38)–(8.42).

    Parameters
    ----------
    t : (N,) [s]; omega : (N, 3) body-frame ω [rad/s]; rotation : (N, 3, 3) attitude
    body -> space; moments : (3,) principal moments along the body axes [kg m²].
    mass : M [kg]; cm_velocity : (3,) Ṙ, space frame [m/s] (constant: no force).
    masses : (K,) [kg]; positions : (K, 3) [m] the body's point masses, body frame, from
    the centre of mass.

    Returns
    -------
    dict of the ``energy_split/…`` results (see ``results.py``), each sample's value
    along the ``energy_sample`` dimension.
    """
    idx = sample_indices(len(t), count)
    m = np.asarray(masses, dtype=float)
    b = np.asarray(positions, dtype=float)
    I = np.asarray(moments, dtype=float)
    V = np.asarray(cm_velocity, dtype=float)
    R = np.asarray(rotation, dtype=float)[idx]
    w_body = np.asarray(omega, dtype=float)[idx]
    w_space = np.einsum("nij,nj->ni", R, w_body)
    x = np.einsum("nij,kj->nki", R, b)  # x_A = R(t) b_A, (n, K, 3)
    x_dot = np.cross(w_space[:, None, :], x)  # ẋ_A = ω × x_A
    r_dot = V + x_dot  # (8.38) differentiated
    kinetic = 0.5 * np.einsum("k,nki,nki->n", m, r_dot, r_dot)
    translational = 0.5 * float(mass) * float(V @ V)
    rotational = 0.5 * np.einsum("ni,i,ni->n", w_body, I, w_body)
    split = translational + rotational  # (8.42), K = ½ ω·I ω
    first_moment = np.einsum("k,nki->ni", m, x)  # (8.40)
    cross = np.einsum("k,i,nki->n", m, V, x_dot)  # the middle term of (8.41)
    scale = float(np.sum(m)) * float(np.max(np.linalg.norm(b, axis=1)))
    rel = np.abs(kinetic - split) / split
    return {"nodes": int(len(m)), "times": np.asarray(t, dtype=float)[idx],
            "kinetic_points": kinetic, "translational": translational,
            "rotational": rotational, "kinetic_split": split,
            "first_moment": np.linalg.norm(first_moment, axis=1),
            "first_moment_scale": scale, "cross_term": cross, "relative_error": rel,
            "max_relative_error": float(np.max(rel)),
            "max_cross_term_share": float(np.max(np.abs(cross) / split))}
