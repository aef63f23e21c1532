r"""Three gravitating point masses in space: the lecture notes' relative coordinates and
Jacobi's (lecture notes §3).

State y = (q, v): q = (x1, y1, z1, x2, y2, z2, x3, y3, z3), v the velocities in the
same order.  H = Σ m_i v_i²/2 − Σ_{i<j} G m_i m_j / r_ij is separable: the drift
q̇ = v depends on v only, the kick v̇_i = −Σ_j G m_j (q_i − q_j)/r_ij³ on q only, so
splitting methods apply (velocities stand in for the momenta p_i = m_i v_i; the
splitting is the same).

The notes' coordinates (notes (3.32)–(3.34)): the centre of mass R and the positions
relative to body 1, r12 = r2 − r1, r13 = r3 − r1.  Their kinetic energy has a cross term,
T = ½ M Ṙ² + ½ [m2(m1 + m3)/M ṙ12² + m3(m1 + m2)/M ṙ13² − 2 m2 m3/M ṙ12·ṙ13],
M = m1 + m2 + m3 (:func:`notes_kinetic_energy`).

Jacobi coordinates (the standard hierarchical choice; not in the notes):
ρ1 = r2 − r1, ρ2 = r3 − (m1 r1 + m2 r2)/(m1 + m2), R the centre of mass; then T is
diagonal, T = ½ M Ṙ² + ½ μ1 ρ̇1² + ½ μ2 ρ̇2² with μ1 = m1 m2/(m1 + m2),
μ2 = m3 (m1 + m2)/M, so a hierarchical triple separates into two Kepler-like problems.

References
----------
.. [1] Lecture notes §3, eqs. (3.32)–(3.35).
.. [2] Chenciner, A. & Montgomery, R., "A remarkable periodic solution of the three-body
       problem in the case of equal masses", Ann. Math. 152, 881–901 (2000).
.. [3] Szebehely, V. & Peters, C. F., "Complete solution of a general problem of three
       bodies", Astron. J. 72, 876 (1967) (the Pythagorean problem).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..model import OdeModel, Separable

COLUMNS = tuple(f"{c}{b}" for b in (1, 2, 3) for c in "xyz") + tuple(
    f"v{c}{b}" for b in (1, 2, 3) for c in "xyz")

# params = (G, m1, m2, m3)


# inlined into its callers: see "Helpers" in reportgen.core.model
@numba.njit(cache=True, inline="always")
def _accelerations(q, params, out):
    for i in range(9):
        out[i] = 0.0
    G = params[0]
    for i in range(3):
        for j in range(i + 1, 3):
            dx = q[3 * j] - q[3 * i]
            dy = q[3 * j + 1] - q[3 * i + 1]
            dz = q[3 * j + 2] - q[3 * i + 2]
            r2 = dx * dx + dy * dy + dz * dz
            inv3 = G / (r2 * np.sqrt(r2))
            fi = params[1 + j] * inv3
            fj = params[1 + i] * inv3
            out[3 * i] += fi * dx
            out[3 * i + 1] += fi * dy
            out[3 * i + 2] += fi * dz
            out[3 * j] -= fj * dx
            out[3 * j + 1] -= fj * dy
            out[3 * j + 2] -= fj * dz


@numba.njit(cache=True, error_model="numpy")
def rhs(t, y, params, out):
    for i in range(9):
        out[i] = y[9 + i]
    _accelerations(y[:9], params, out[9:])


@numba.njit(cache=True)
def drift(p, params, out):
    for i in range(9):
        out[i] = p[i]


@numba.njit(cache=True)
def kick(q, params, out):
    _accelerations(q, params, out)


def model(G: float, masses) -> OdeModel:
    m = np.asarray(masses, dtype=np.float64)
    return OdeModel(name="three-body", columns=COLUMNS, rhs=rhs,
                    params=np.array([G, m[0], m[1], m[2]]),
                    separable=Separable(n=9, drift=drift, kick=kick), specialize=True)


def split(y):
    """(positions, velocities), each shape (N, 3, 3): time, body, xyz."""
    y = np.atleast_2d(y)
    return y[:, :9].reshape(-1, 3, 3), y[:, 9:].reshape(-1, 3, 3)


def pair_distances(pos):
    """r12, r13, r23, each shape (N,)."""
    return (np.linalg.norm(pos[:, 1] - pos[:, 0], axis=1),
            np.linalg.norm(pos[:, 2] - pos[:, 0], axis=1),
            np.linalg.norm(pos[:, 2] - pos[:, 1], axis=1))


def energy(y, G, masses):
    pos, vel = split(y)
    m = np.asarray(masses, dtype=np.float64)
    kin = 0.5 * np.einsum("b,nbk,nbk->n", m, vel, vel)
    r12, r13, r23 = pair_distances(pos)
    return kin - G * (m[0] * m[1] / r12 + m[0] * m[2] / r13 + m[1] * m[2] / r23)


def momentum(y, masses):
    """Total momentum P = Σ m_i v_i, shape (N, 3)."""
    _, vel = split(y)
    return np.einsum("b,nbk->nk", np.asarray(masses, dtype=np.float64), vel)


def angular_momentum(y, masses):
    """Total angular momentum L = Σ m_i r_i × v_i about the origin, shape (N, 3)."""
    pos, vel = split(y)
    return np.einsum("b,nbk->nk", np.asarray(masses, dtype=np.float64), np.cross(pos, vel))


def jacobi(y, masses):
    """Jacobi coordinates and velocities (the standard hierarchical choice; not the notes'):
    R, ρ1 = r2 − r1, ρ2 = r3 − (m1 r1 + m2 r2)/(m1 + m2) and their rates, each (N, 3)."""
    pos, vel = split(y)
    m1, m2, m3 = (float(v) for v in masses)
    M, m12 = m1 + m2 + m3, m1 + m2

    def transform(r):
        R = (m1 * r[:, 0] + m2 * r[:, 1] + m3 * r[:, 2]) / M
        rho1 = r[:, 1] - r[:, 0]
        rho2 = r[:, 2] - (m1 * r[:, 0] + m2 * r[:, 1]) / m12
        return R, rho1, rho2

    return transform(pos), transform(vel)


def jacobi_masses(masses):
    """(M, μ1, μ2) of the diagonal Jacobi kinetic energy: M = m1 + m2 + m3,
    μ1 = m1 m2/(m1 + m2), μ2 = m3 (m1 + m2)/M."""
    m1, m2, m3 = (float(v) for v in masses)
    M = m1 + m2 + m3
    return M, m1 * m2 / (m1 + m2), m3 * (m1 + m2) / M


def jacobi_kinetic_energy(y, masses):
    """T = ½ M Ṙ² + ½ μ1 ρ̇1² + ½ μ2 ρ̇2² in Jacobi coordinates, shape (N,)."""
    _, (Rd, r1d, r2d) = jacobi(y, masses)
    M, mu1, mu2 = jacobi_masses(masses)
    return 0.5 * (M * np.sum(Rd**2, 1) + mu1 * np.sum(r1d**2, 1) + mu2 * np.sum(r2d**2, 1))


def notes_coordinates(y, masses):
    """The notes' coordinates and velocities (notes (3.32)–(3.34)): the centre of mass R
    and the positions relative to body 1, r12 = r2 − r1 and r13 = r3 − r1, and their
    rates, each (N, 3)."""
    pos, vel = split(y)
    m = np.asarray(masses, dtype=np.float64)

    def transform(r):
        return (np.einsum("b,nbk->nk", m, r) / m.sum(), r[:, 1] - r[:, 0],
                r[:, 2] - r[:, 0])

    return transform(pos), transform(vel)


def notes_mass_matrix(masses):
    """K, shape (2, 2): the relative part of the notes' kinetic energy (notes (3.32)–(3.34))
    as ½ Σ_ab K_ab ṙ_a·ṙ_b over a, b ∈ (r12, r13).

    K = [[m2(m1 + m3), −m2 m3], [−m2 m3, m3(m1 + m2)]] / M, M = m1 + m2 + m3.

    Derivation: with R the centre of mass, r1 = R − (m2 r12 + m3 r13)/M, r2 = r1 + r12,
    r3 = r1 + r13.  Write sᵢ = rᵢ − R, so Σ mᵢ sᵢ = 0 and T = ½ M Ṙ² + ½ Σ mᵢ ṡᵢ².  With
    P = m2 ṙ12 + m3 ṙ13, ṡ1 = −P/M, ṡ2 = ṡ1 + ṙ12, ṡ3 = ṡ1 + ṙ13:
    Σ mᵢ ṡᵢ² = M ṡ1² + 2 ṡ1·P + m2 ṙ12² + m3 ṙ13² = m2 ṙ12² + m3 ṙ13² − P²/M
    = m2(M − m2)/M ṙ12² + m3(M − m3)/M ṙ13² − 2 m2 m3/M ṙ12·ṙ13,
    and M − m2 = m1 + m3, M − m3 = m1 + m2.  det K = m1 m2 m3/M = μ1 μ2: the map
    (r12, r13) → (ρ1, ρ2) = (r12, r13 − m2 r12/(m1 + m2)) has determinant 1, and it takes
    K to Jacobi's diagonal diag(μ1, μ2).
    """
    m1, m2, m3 = (float(v) for v in masses)
    M = m1 + m2 + m3
    return np.array([[m2 * (m1 + m3), -m2 * m3], [-m2 * m3, m3 * (m1 + m2)]]) / M


def notes_kinetic_cross_term(y, masses):
    """The cross term of the notes' kinetic energy, −(m2 m3/M) ṙ12·ṙ13, shape (N,)."""
    _, (_, r12d, r13d) = notes_coordinates(y, masses)
    return notes_mass_matrix(masses)[0, 1] * np.sum(r12d * r13d, 1)


def notes_kinetic_energy(y, masses):
    """T = ½ M Ṙ² + ½ [K11 ṙ12² + K22 ṙ13² + 2 K12 ṙ12·ṙ13] in the notes' coordinates
    (notes (3.32)–(3.34)), K from :func:`notes_mass_matrix`, shape (N,)."""
    _, (Rd, r12d, r13d) = notes_coordinates(y, masses)
    K = notes_mass_matrix(masses)
    M = float(np.sum(np.asarray(masses, dtype=np.float64)))
    return (0.5 * (M * np.sum(Rd**2, 1) + K[0, 0] * np.sum(r12d**2, 1)
                   + K[1, 1] * np.sum(r13d**2, 1))
            + notes_kinetic_cross_term(y, masses))


def cartesian_kinetic_energy(y, masses):
    _, vel = split(y)
    return 0.5 * np.einsum("b,nbk,nbk->n", np.asarray(masses, dtype=np.float64), vel, vel)


def natural_scales(y0, G, masses):
    """Natural sizes of the conserved quantities, the scales their drift is measured against.

    Parameters
    ----------
    y0 : array_like, shape (18,)
        Initial state (positions, then velocities, body by body).
    G : float
        Gravitational constant.
    masses : array_like, shape (3,)

    Returns
    -------
    dict
        ``energy``: max(|E(0)|, |U(0)|) with U = Σ G m_i m_j / r_ij the size of the potential
        energy; ``momentum_x|y|z``: max(Σ m_i |v_i(0)|, M √(G M/ℓ)) with ℓ the mean initial
        pair distance (the circular speed at ℓ); ``angular_momentum_x|y|z``:
        max(Σ m_i |r_i(0)| · max |v_i(0)|, M ℓ √(G M/ℓ)).
    """
    y0 = np.asarray(y0, dtype=np.float64)
    m = np.asarray(masses, dtype=np.float64)
    pos, vel = split(y0)
    r = np.array(pair_distances(pos))[:, 0]
    pot = G * (m[0] * m[1] / r[0] + m[0] * m[2] / r[1] + m[1] * m[2] / r[2])
    ell = float(np.mean(r))
    speed = math.sqrt(G * m.sum() / ell)
    p_scale = max(float(np.sum(m * np.linalg.norm(vel[0], axis=1))), float(m.sum()) * speed)
    l_scale = max(float(np.sum(m * np.linalg.norm(pos[0], axis=1)))
                  * float(np.max(np.linalg.norm(vel[0], axis=1))), float(m.sum()) * ell * speed)
    out = {"energy": max(abs(float(energy(y0, G, m)[0])), pot)}
    out.update({f"momentum_{c}": p_scale for c in "xyz"})
    out.update({f"angular_momentum_{c}": l_scale for c in "xyz"})
    return out


def osculating_orbit(r, v, K):
    """Osculating two-body orbit in space of a relative position and velocity.

    Parameters
    ----------
    r, v : array_like, shape (3,)
        Relative position and velocity (e.g. Moon − Earth), in length and length/time.
    K : float
        G (m_a + m_b) of the pair, length³/time².

    Returns
    -------
    dict
        ``normal``: unit vector along h = r × v, shape (3,); ``inclination``: angle of the
        orbit plane to the x–y plane, arccos(ĥ_z) [rad]; ``semi_major_axis``: a = −K/(2ε)
        with ε = v²/2 − K/r (vis-viva; negative for unbound orbits); ``period``: Kepler's
        third law 2π √(a³/K) (nan if unbound).

    References
    ----------
    Goldstein, *Classical Mechanics*, 3rd ed., eq. (3.71).
    """
    r = np.asarray(r, dtype=np.float64)
    v = np.asarray(v, dtype=np.float64)
    h = np.cross(r, v)
    normal = h / np.linalg.norm(h)
    eps = 0.5 * np.linalg.norm(v) ** 2 - K / np.linalg.norm(r)
    a = float(-K / (2 * eps))
    period = 2 * math.pi * math.sqrt(a**3 / K) if a > 0 else math.nan
    return {"normal": normal, "inclination": float(math.acos(normal[2])),
            "semi_major_axis": a, "period": period}


def revolutions(rel, normal):
    """Signed number of turns of a relative track about ``normal``.

    Parameters
    ----------
    rel : array_like, shape (N, 3)
        The relative position at successive times (sampled densely enough that the
        angle moves by less than π between samples).
    normal : array_like, shape (3,)
        Unit normal of the reference plane (e.g. the initial orbit plane); the angle is
        measured in that plane from the direction of ``rel[0]``.

    Returns
    -------
    float
        (φ(t_N) − φ(t_0)) / 2π with φ unwrapped; the mean sidereal period over the span
        is then (t_N − t_0) / turns.
    """
    rel = np.asarray(rel, dtype=np.float64)
    n_hat = np.asarray(normal, dtype=np.float64)
    e1 = rel[0] / np.linalg.norm(rel[0])
    e2 = np.cross(n_hat, e1)
    ang = np.unwrap(np.arctan2(rel @ e2, rel @ e1))
    return float((ang[-1] - ang[0]) / (2 * math.pi))
