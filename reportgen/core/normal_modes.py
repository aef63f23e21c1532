r"""Small oscillations about a stable equilibrium: the eigenproblem A η = ω² M η.

Lecture notes ch. 5, §5.1 (Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed.,
ch. 6): near a minimum of V the Lagrangian is L = ½ q̇ᵀ M q̇ − ½ qᵀ A q, and the
motion is a superposition of normal modes q = Σ_k η_k (a_k cos ω_k t + b_k sin ω_k t)
with A η_k = ω_k² M η_k and η_kᵀ M η_l = δ_kl.

Molecules are given by atoms (mass, equilibrium position), bond stretches
V = ½ k (r − r0)² and angle bends V = ½ k (θ − θ0)², with r0, θ0 read from the
equilibrium geometry.  At equilibrium the Hessian of each term is k b bᵀ with b
the Wilson B-vector (gradient) of its internal coordinate; a linear angle
(θ0 = π) has no gradient and is two bend coordinates in perpendicular planes.

Pure numerics on ndarrays: no I/O, no plotting.

References
----------
.. [1] Lecture notes ch. 5, §5.1, Fig. 5.1 (molecule vibrations).
.. [2] Goldstein, Poole & Safko, 3rd ed., §6.2 (eigenvalue equation), §6.4 (linear
       triatomic molecule).
.. [3] Wilson, Decius & Cross, *Molecular Vibrations* (1955), ch. 4 (B-vectors).
.. [4] Herzberg, *Infrared and Raman Spectra* (1945), ch. II (XY₂ valence force field).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

#: standard atomic weights [u] (IUPAC 2021, abridged) for ``atoms[i].element``
ELEMENT_MASSES = {
    "H": 1.008, "D": 2.014, "He": 4.0026, "Li": 6.94, "B": 10.81, "C": 12.011,
    "N": 14.007, "O": 15.999, "F": 18.998, "Ne": 20.180, "Na": 22.990, "Si": 28.085,
    "P": 30.974, "S": 32.06, "Cl": 35.45, "Ar": 39.95, "Br": 79.904, "I": 126.90,
}

#: eigenvalues ω² with |ω²| ≤ ZERO_TOL · max|ω²| count as zero (round-off of eigh is ~1e-15)
ZERO_TOL = 1e-10
#: frequencies within DEGENERATE_RTOL · ω_max of each other form one degenerate set
DEGENERATE_RTOL = 1e-8
#: a geometry is linear when its second moment about the axis is below this share
LINEAR_TOL = 1e-10


# --------------------------------------------------------------------------- eigenproblem
def generalized_modes(M: np.ndarray, A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve A η = ω² M η (LAPACK sygvd via ``scipy.linalg.eigh``).

    Returns
    -------
    omega2 : ndarray, shape (n,), ascending
    modes : ndarray, shape (n, n), columns normalized ηᵀ M η = 1
    """
    w, v = scipy.linalg.eigh(A, M)
    return w, v


def three_step_modes(M: np.ndarray, A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The textbook route (notes §5.1; Goldstein §6.2), step by step.

    1. diagonalize M = U D Uᵀ;
    2. rescale to unit mass: q = U D^(-1/2) q'; then T = ½ q̇'ᵀ q̇' and A' = D^(-1/2) Uᵀ A U D^(-1/2);
    3. diagonalize A' = V Λ Vᵀ; the modes are η = U D^(-1/2) V, with ηᵀ M η = Vᵀ V = 1.
    """
    d, U = np.linalg.eigh(M)
    if np.any(d <= 0):
        raise ValueError(f"M is not positive definite (eigenvalue {d.min():.3g})")
    S = U / np.sqrt(d)
    A1 = S.T @ A @ S
    A1 = 0.5 * (A1 + A1.T)
    lam, V = np.linalg.eigh(A1)
    return lam, S @ V


def omega_from_omega2(omega2: np.ndarray, zero_tol: float = ZERO_TOL) -> np.ndarray:
    """ω = √ω², with round-off negatives of zero modes set to 0; a real negative ω² raises."""
    omega2 = np.asarray(omega2, dtype=float)
    scale = max(float(np.max(np.abs(omega2))), 1e-300) if omega2.size else 1.0
    bad = omega2 < -zero_tol * scale
    if np.any(bad):
        raise ValueError(f"unstable equilibrium: ω² = {omega2[bad].min():.6g} < 0 "
                         "(A is not positive semidefinite)")
    return np.sqrt(np.clip(omega2, 0.0, None))


def degenerate_groups(omega: np.ndarray, rtol: float = DEGENERATE_RTOL) -> np.ndarray:
    """Group id per mode (ascending ω): neighbours within rtol · ω_max share a group."""
    omega = np.asarray(omega, dtype=float)
    groups = np.zeros(omega.size, dtype=np.int64)
    tol = rtol * max(float(np.max(np.abs(omega))), 1e-300) if omega.size else 0.0
    for i in range(1, omega.size):
        groups[i] = groups[i - 1] + (0 if omega[i] - omega[i - 1] <= tol else 1)
    return groups


def m_orthonormalize(V: np.ndarray, M: np.ndarray, tol: float = 1e-10) -> np.ndarray:
    """Columns spanning range(V), orthonormal in the metric M (rank-revealing)."""
    G = V.T @ M @ V
    w, U = np.linalg.eigh(0.5 * (G + G.T))
    keep = w > tol * max(float(w.max()), 1e-300)
    return V @ (U[:, keep] / np.sqrt(w[keep]))


def canonical_basis(E: np.ndarray, M: np.ndarray) -> np.ndarray:
    """A basis of a degenerate subspace that does not depend on the solver's rotation.

    Pivoted QR on Eᵀ picks the coordinates that the subspace moves most; the new
    basis is reduced so that mode i moves pivot coordinate i and not the earlier
    pivots (a "row echelon" basis), then M-orthonormalized in that order.
    """
    _, _, piv = scipy.linalg.qr(E.T, pivoting=True)
    g = E.shape[1]
    B = E @ np.linalg.solve(E[piv[:g], :], np.eye(g))  # B[piv[i], j] = δ_ij
    out = []
    for j in range(g):  # M-Gram–Schmidt in pivot order
        v = B[:, j].copy()
        for u in out:
            v -= (u @ M @ v) * u
        v /= math.sqrt(v @ M @ v)
        out.append(v * np.sign(v[np.argmax(np.abs(v))]))
    return np.column_stack(out)


def symmetry_adapted_basis(E: np.ndarray, M: np.ndarray, ops: list[np.ndarray]) -> np.ndarray:
    """Rotate a degenerate set E (M-orthonormal columns) to diagonalize the symmetry ops.

    Each op S (n×n, an exact symmetry: S M Sᵀ = M, S A Sᵀ = A) maps the
    eigenspace to itself; the basis that diagonalizes a generic combination
    Σ c_k Eᵀ M S_k E is the joint eigenbasis (e.g. in-plane / out-of-plane for the
    CO₂ bend).  Characters it cannot separate are resolved by :func:`canonical_basis`.
    """
    g = E.shape[1]
    if g == 1:
        return E * np.sign(E[np.argmax(np.abs(E[:, 0])), 0])
    C = np.zeros((g, g))
    coeffs = [1.0, math.sqrt(2.0), math.sqrt(3.0), math.sqrt(5.0), math.sqrt(7.0),
              math.sqrt(11.0), math.sqrt(13.0), math.sqrt(17.0)]
    for c, S in zip(coeffs, ops, strict=False):
        R = E.T @ M @ S @ E
        C += c * 0.5 * (R + R.T)
    w, U = np.linalg.eigh(C)
    order = np.argsort(-w, kind="stable")  # symmetric (+1 characters) first
    w, U = w[order], U[:, order]
    basis = E @ U
    out = np.empty_like(basis)
    i = 0
    while i < g:  # clusters of equal character: resolve canonically
        j = i + 1
        while j < g and abs(w[j] - w[i]) < 1e-6:
            j += 1
        out[:, i:j] = canonical_basis(basis[:, i:j], M) if j - i > 1 else (
            basis[:, i:j] * np.sign(basis[np.argmax(np.abs(basis[:, i])), i]))
        i = j
    return out


@dataclass
class ModeSet:
    """Normal modes of (M, A), ascending in ω.

    Attributes
    ----------
    omega2, omega : ndarray, shape (n,)
    modes : ndarray, shape (n, n); columns η_k with η_kᵀ M η_l = δ_kl
    n_zero : int
        modes with ω = 0 (rigid-body modes first, then any floppy internal modes)
    groups : ndarray of int, shape (n,); equal ids = one degenerate set
    """

    omega2: np.ndarray
    omega: np.ndarray
    modes: np.ndarray
    n_zero: int
    groups: np.ndarray
    n_rigid: int = 0
    rigid_residual: float = 0.0
    extra: dict = field(default_factory=dict)


def solve_modes(M: np.ndarray, A: np.ndarray, rigid: np.ndarray | None = None,
                ops: list[np.ndarray] | None = None) -> ModeSet:
    """Normal modes with the rigid-body subspace ``rigid`` (columns) projected out.

    The rigid vectors are checked to be zero modes (‖A v‖ relative to ‖A‖ ‖v‖) and
    removed exactly: the eigenproblem is solved in an M-orthonormal basis of their
    M-orthogonal complement, so the remaining count of zero ω² is a check, not an
    assumption.  Degenerate sets get a basis from ``ops`` (exact symmetries).
    """
    n = M.shape[0]
    ops = ops or []
    a_norm = max(float(np.linalg.norm(A, 2)), 1e-300)
    if rigid is not None and rigid.shape[1]:
        R = m_orthonormalize(rigid, M)
        residual = float(np.max(np.linalg.norm(A @ R, axis=0) /
                                (a_norm * np.linalg.norm(R, axis=0))))
        # complement: eigenvectors of the M-projector I − R Rᵀ M with eigenvalue 1
        P = np.eye(n) - R @ R.T @ M
        Q = m_orthonormalize(P, M)
        w, V = scipy.linalg.eigh(Q.T @ A @ Q)
        omega2 = np.concatenate([np.zeros(R.shape[1]), w])
        modes = np.column_stack([R, Q @ V])
    else:
        R = np.zeros((n, 0))
        residual = 0.0
        omega2, modes = generalized_modes(M, A)
    omega = omega_from_omega2(omega2)
    scale = max(float(np.max(np.abs(omega2))), 1e-300)
    zero = np.abs(omega2) <= ZERO_TOL * scale
    omega[zero], omega2 = 0.0, np.where(zero, 0.0, omega2)
    order = np.argsort(omega, kind="stable")
    omega, omega2, modes = omega[order], omega2[order], modes[:, order]
    groups = degenerate_groups(omega)
    for gid in np.unique(groups):  # symmetry-adapted basis in every degenerate set
        idx = np.flatnonzero(groups == gid)
        if omega[idx[0]] == 0.0:
            continue  # the zero-mode set keeps its rigid-body basis (translations, rotations)
        modes[:, idx] = symmetry_adapted_basis(modes[:, idx], M, ops)
    return ModeSet(omega2=omega2, omega=omega, modes=modes, n_zero=int(np.sum(zero)),
                   groups=groups, n_rigid=R.shape[1], rigid_residual=residual)


def modal_evolution(modes: np.ndarray, omega: np.ndarray, M: np.ndarray, q0: np.ndarray,
                    v0: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exact motion by modal superposition (notes §5.1; Goldstein eq. for q(t) in §6.2).

    q(t) = Σ_k η_k (a_k cos ω_k t + b_k sin ω_k t / ω_k), a_k = η_kᵀ M q0, b_k = η_kᵀ M v0;
    a zero mode moves uniformly: η_k (a_k + b_k t).

    Returns q, v : ndarray, shape (N, n)
    """
    t = np.asarray(t, dtype=float)[:, None]
    a = modes.T @ M @ q0
    b = modes.T @ M @ v0
    w = np.asarray(omega, dtype=float)
    wt = w[None, :] * t
    safe = np.where(w > 0, w, 1.0)
    sinc_t = np.where(w > 0, np.sin(wt) / safe, t)  # sin(ωt)/ω → t for ω = 0
    coord = a * np.cos(wt) + b * sinc_t
    rate = -a * w * np.sin(wt) + b * np.cos(wt)
    return coord @ modes.T, rate @ modes.T


# ------------------------------------------------------------------------- molecules
def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def stretch_bvector(x: np.ndarray, i: int, j: int) -> np.ndarray:
    """∂r/∂x of r = |x_j − x_i| (Wilson B-vector): −e on atom i, +e on atom j.  Shape (3n,)."""
    b = np.zeros(x.size)
    e = _unit(x[j] - x[i])
    b[3 * i:3 * i + 3], b[3 * j:3 * j + 3] = -e, e
    return b


def bond_angle(x: np.ndarray, i: int, j: int, l: int) -> float:
    """θ at vertex j between bonds j→i and j→l (atan2 form: accurate near 0 and π)."""
    u, v = x[i] - x[j], x[l] - x[j]
    return math.atan2(float(np.linalg.norm(np.cross(u, v))), float(u @ v))


def is_linear_angle(x: np.ndarray, i: int, j: int, l: int, tol: float = 1e-8) -> bool:
    return math.pi - bond_angle(x, i, j, l) < tol


def transverse_directions(axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors w1, w2 ⊥ axis, w1 × w2 ∥ axis; Cartesian when the axis is.

    w1 is the Cartesian direction least aligned with the axis, made orthogonal to
    it: for a molecule along x this gives w1 = ŷ (in the drawing plane), w2 = ẑ.
    """
    e = _unit(axis)
    # least-aligned Cartesian direction; ties go to y, then x, then z
    pick = min((1, 0, 2), key=lambda c: (round(abs(float(e[c])), 12), (1, 0, 2).index(c)))
    w1 = np.eye(3)[pick]
    w1 = _unit(w1 - (w1 @ e) * e)
    w2 = np.cross(e, w1)
    return w1, w2


def bend_bvectors(x: np.ndarray, i: int, j: int, l: int) -> list[np.ndarray]:
    """B-vectors of the bend at vertex j: one for a bent angle, two for a linear one.

    Bent (Wilson, Decius & Cross ch. 4; differentiate cos θ = û·v̂):
    ∂θ/∂x_i = (cos θ û − v̂)/(|u| sin θ), ∂θ/∂x_l = (cos θ v̂ − û)/(|v| sin θ),
    ∂θ/∂x_j = −(∂θ/∂x_i + ∂θ/∂x_l); u = x_i − x_j, v = x_l − x_j.

    Linear (θ0 = π): (θ − π)² = ρ₁² + ρ₂² to second order, with the linear-bend
    coordinates ρ_w = w·(δx_i − δx_j)/|u| + w·(δx_l − δx_j)/|v| for w = w1, w2 ⊥ axis.
    """
    u, v = x[i] - x[j], x[l] - x[j]
    ru, rv = float(np.linalg.norm(u)), float(np.linalg.norm(v))
    out = []
    if is_linear_angle(x, i, j, l):
        for w in transverse_directions(v - u):
            b = np.zeros(x.size)
            b[3 * i:3 * i + 3] = w / ru
            b[3 * l:3 * l + 3] = w / rv
            b[3 * j:3 * j + 3] = -w * (1 / ru + 1 / rv)
            out.append(b)
        return out
    eu, ev = u / ru, v / rv
    cos, sin = float(eu @ ev), float(np.linalg.norm(np.cross(eu, ev)))
    gi = (cos * eu - ev) / (ru * sin)
    gl = (cos * ev - eu) / (rv * sin)
    b = np.zeros(x.size)
    b[3 * i:3 * i + 3], b[3 * l:3 * l + 3], b[3 * j:3 * j + 3] = gi, gl, -(gi + gl)
    return [b]


@dataclass(frozen=True)
class Molecule:
    """Atoms at equilibrium with their valence force field.

    masses : (n,); positions : (n, 3); bonds : tuples (i, j, k);
    angles : tuples (i, j, l, k) with j the vertex.  Indices are zero-based.
    """

    masses: np.ndarray
    positions: np.ndarray
    bonds: tuple[tuple[int, int, float], ...] = ()
    angles: tuple[tuple[int, int, int, float], ...] = ()

    @property
    def n_atoms(self) -> int:
        return len(self.masses)

    def mass_matrix(self) -> np.ndarray:
        """M = diag(m1, m1, m1, m2, …): T = ½ Σ m_a |ẋ_a|².  Shape (3n, 3n)."""
        return np.diag(np.repeat(np.asarray(self.masses, dtype=float), 3))

    def internal_coordinates(self) -> list[tuple[str, float, np.ndarray]]:
        """(label, force constant, B-vector) of every stretch and bend coordinate."""
        x = np.asarray(self.positions, dtype=float)
        out = []
        for i, j, k in self.bonds:
            out.append((f"stretch {i}–{j}", k, stretch_bvector(x, i, j)))
        for i, j, l, k in self.angles:
            bs = bend_bvectors(x, i, j, l)
            names = [f"bend {i}–{j}–{l}"] if len(bs) == 1 else [
                f"bend {i}–{j}–{l} (in-plane)", f"bend {i}–{j}–{l} (out-of-plane)"]
            out += [(name, k, b) for name, b in zip(names, bs, strict=True)]
        return out

    def hessian(self) -> np.ndarray:
        """A = Σ k b bᵀ over internal coordinates: the exact Hessian of V at equilibrium."""
        n3 = 3 * self.n_atoms
        A = np.zeros((n3, n3))
        for _, k, b in self.internal_coordinates():
            A += k * np.outer(b, b)
        return A

    def potential(self, xflat: np.ndarray) -> float:
        """V(x) = Σ ½k(r − r0)² + Σ ½k(θ − θ0)², r0 and θ0 from the equilibrium geometry."""
        x0 = np.asarray(self.positions, dtype=float)
        x = np.asarray(xflat, dtype=float).reshape(-1, 3)
        v = 0.0
        for i, j, k in self.bonds:
            r0 = np.linalg.norm(x0[j] - x0[i])
            v += 0.5 * k * (np.linalg.norm(x[j] - x[i]) - r0) ** 2
        for i, j, l, k in self.angles:
            v += 0.5 * k * (bond_angle(x, i, j, l) - bond_angle(x0, i, j, l)) ** 2
        return float(v)

    def centre_of_mass(self) -> np.ndarray:
        m = np.asarray(self.masses, dtype=float)
        return m @ np.asarray(self.positions, dtype=float) / m.sum()

    def axis(self) -> np.ndarray | None:
        """Unit vector of the molecular axis if all atoms lie on one line, else None."""
        x = np.asarray(self.positions, dtype=float) - self.centre_of_mass()
        if self.n_atoms < 2:
            return None
        _, s, vt = np.linalg.svd(x, full_matrices=False)
        if s.size < 2 or s[1] <= math.sqrt(LINEAR_TOL) * max(s[0], 1e-300):
            return vt[0] * np.sign(vt[0][np.argmax(np.abs(vt[0]))])
        return None

    def rigid_body_vectors(self) -> np.ndarray:
        """Translations (3) and infinitesimal rotations ω × (x − x_cm) (3), shape (3n, 6).

        For a linear molecule the rotation about the axis is the zero vector; the
        rank (5 or 6) is found by :func:`m_orthonormalize`, not assumed.
        """
        x = np.asarray(self.positions, dtype=float) - self.centre_of_mass()
        cols = []
        for a in range(3):
            t = np.zeros((self.n_atoms, 3))
            t[:, a] = 1.0
            cols.append(t.ravel())
        for a in range(3):
            cols.append(np.cross(np.eye(3)[a], x).ravel())
        return np.column_stack(cols)

    def drawing_frame(self) -> np.ndarray:
        """Rows e1, e2, e3: the drawing plane (e1, e2) and its normal e3.

        Linear: e1 the axis, e2 = w1 (the in-plane transverse direction).  Otherwise
        the two directions of largest spread (the molecular plane for a planar one).
        """
        ax = self.axis()
        if ax is not None:
            w1, w2 = transverse_directions(ax)
            return np.array([ax, w1, w2])
        x = np.asarray(self.positions, dtype=float) - self.centre_of_mass()
        _, _, vt = np.linalg.svd(x)
        e1, e2 = vt[0], vt[1]
        e1 = e1 * (np.sign(e1[np.argmax(np.abs(e1))]) or 1.0)
        e2 = e2 * (np.sign(e2[np.argmax(np.abs(e2))]) or 1.0)
        return np.array([e1, e2, np.cross(e1, e2)])

    def symmetry_operations(self, A: np.ndarray, tol: float = 1e-9) -> list[np.ndarray]:
        """Exact symmetries of the molecule and its force field as (3n, 3n) matrices.

        Candidates: inversion through the centre of mass and reflections through
        planes through it, normal to the drawing-frame axes and to x, y, z.  A
        candidate is kept if it maps every atom onto an atom of equal mass and
        leaves A invariant (S A Sᵀ = A).
        """
        x = np.asarray(self.positions, dtype=float) - self.centre_of_mass()
        m = np.asarray(self.masses, dtype=float)
        n = self.n_atoms
        size = max(float(np.max(np.abs(x))), 1.0)
        frame = self.drawing_frame()
        normals = list(frame) + list(np.eye(3))
        cands = [-np.eye(3)] + [np.eye(3) - 2 * np.outer(nv, nv) for nv in normals]
        ops, seen = [], []
        a_scale = max(float(np.max(np.abs(A))), 1e-300)
        for Rm in cands:
            y = x @ Rm.T
            perm = []
            for a in range(n):
                d = np.linalg.norm(x - y[a], axis=1)
                b = int(np.argmin(d))
                if d[b] > tol * size or abs(m[b] - m[a]) > tol * m[a]:
                    break
                perm.append(b)
            else:
                S = np.zeros((3 * n, 3 * n))
                for a, b in enumerate(perm):
                    S[3 * b:3 * b + 3, 3 * a:3 * a + 3] = Rm
                if np.max(np.abs(S @ A @ S.T - A)) > 1e-9 * a_scale:
                    continue
                if any(np.allclose(S, s) for s in seen):
                    continue
                seen.append(S)
                ops.append(S)
        return ops


def finite_difference_hessian(f, x0: np.ndarray, h: float = 1e-4) -> np.ndarray:
    """Central second differences of a scalar f at x0 (error O(h²)).  Shape (n, n)."""
    x0 = np.asarray(x0, dtype=float)
    n = x0.size
    H = np.empty((n, n))
    def at(i, j, si, sj):
        x = x0.copy()
        x[i] += si * h
        x[j] += sj * h
        return f(x)

    for i in range(n):
        for j in range(i, n):
            H[i, j] = H[j, i] = (at(i, j, 1, 1) - at(i, j, 1, -1) - at(i, j, -1, 1)
                                 + at(i, j, -1, -1)) / (4 * h * h)
    return H


# ----------------------------------------------------------------- classification
def mode_types_linear(modes: np.ndarray, M: np.ndarray, axis: np.ndarray,
                      w1: np.ndarray) -> list[str]:
    """'longitudinal' / 'transverse (in-plane)' / 'transverse (out-of-plane)' / 'mixed'.

    By the share of the mode's kinetic weight m|η|² along the axis (> 1 − 1e-6
    longitudinal); transverse modes by their share along w1 (the drawing plane).
    """
    out = []
    n = modes.shape[0] // 3
    m = np.diag(M)[0::3]
    for k in range(modes.shape[1]):
        d = modes[:, k].reshape(n, 3)
        tot = float(np.sum(m * np.sum(d * d, axis=1)))
        along = float(np.sum(m * (d @ axis) ** 2)) / tot
        inpl = float(np.sum(m * (d @ w1) ** 2)) / tot
        if along > 1 - 1e-6:
            out.append("longitudinal")
        elif along < 1e-6:
            trans = 1.0 - along
            if inpl > trans * (1 - 1e-6):
                out.append("transverse (in-plane)")
            elif inpl < trans * 1e-6:
                out.append("transverse (out-of-plane)")
            else:
                out.append("transverse")
        else:
            out.append("mixed")
    return out


def stretch_character(mode: np.ndarray, coords: list[tuple[str, float, np.ndarray]]) -> str:
    """'symmetric stretch' / 'antisymmetric stretch' / 'bend' from the potential-energy split.

    The mode's potential energy ½ Σ k (b·η)² is split over internal coordinates;
    the larger of the stretch and bend shares names the mode; stretches that all
    lengthen together are symmetric (Herzberg's ν1/ν3 convention).
    """
    stretch, bend, signs = 0.0, 0.0, []
    for label, k, b in coords:
        s = float(b @ mode)
        e = 0.5 * k * s * s
        if label.startswith("stretch"):
            stretch += e
            if abs(s) > 1e-8 * max(1.0, np.linalg.norm(mode)):
                signs.append(np.sign(s))
        else:
            bend += e
    if bend >= stretch:
        return "bend"
    if len(signs) > 1 and len(set(signs)) > 1:
        return "antisymmetric stretch"
    return "symmetric stretch"


def node_count(mode: np.ndarray, tol: float = 1e-9) -> int:
    """Sign changes along a one-dimensional chain (zeros skipped)."""
    v = mode[np.abs(mode) > tol * np.max(np.abs(mode))]
    return int(np.sum(np.sign(v[1:]) != np.sign(v[:-1])))


# ---------------------------------------------------------------------- generators
def chain_matrices(masses, springs) -> tuple[np.ndarray, np.ndarray]:
    """Longitudinal chain: masses m_1..m_N, springs k_0..k_N (fixed ends) or k_1..k_{N−1} (free).

    V = ½ Σ k_s (q_{s+1} − q_s)², q_0 = q_{N+1} = 0 for fixed ends.
    """
    m = np.asarray(masses, dtype=float)
    k = np.asarray(springs, dtype=float)
    n = m.size
    A = np.zeros((n, n))
    if k.size == n + 1:  # fixed ends
        for s in range(n + 1):
            left, right = s - 1, s
            if left >= 0:
                A[left, left] += k[s]
            if right < n:
                A[right, right] += k[s]
            if left >= 0 and right < n:
                A[left, right] -= k[s]
                A[right, left] -= k[s]
    elif k.size == n - 1:  # free ends
        for s in range(n - 1):
            A[s, s] += k[s]
            A[s + 1, s + 1] += k[s]
            A[s, s + 1] -= k[s]
            A[s + 1, s] -= k[s]
    else:
        raise ValueError(f"chain: {n} masses need {n + 1} springs (fixed ends) or {n - 1} "
                         f"(free ends), got {k.size}")
    return np.diag(m), A


def chain_exact_frequencies(n: int, m: float, k: float, ends: str = "fixed") -> np.ndarray:
    """Uniform chain, ascending.  Fixed ends: ω_j = 2√(k/m) sin(jπ/(2(N+1))), j = 1..N
    (notes §5.1 / Goldstein §6.4 loaded string); free ends: 2√(k/m) sin(jπ/(2N)), j = 0..N−1."""
    if ends == "fixed":
        j = np.arange(1, n + 1)
        return 2 * math.sqrt(k / m) * np.sin(j * math.pi / (2 * (n + 1)))
    j = np.arange(n)
    return 2 * math.sqrt(k / m) * np.sin(j * math.pi / (2 * n))


def pendula_matrices(n: int, m: float, l: float, g: float, k: float):
    """N equal pendula (mass m, length l) in a row, neighbours coupled by springs k at the bobs.

    Small angles φ_i: T = ½ m l² Σ φ̇_i², V = ½ m g l Σ φ_i² + ½ k l² Σ (φ_{i+1} − φ_i)².
    """
    M = m * l * l * np.eye(n)
    L = np.zeros((n, n))
    for s in range(n - 1):
        L[s, s] += 1
        L[s + 1, s + 1] += 1
        L[s, s + 1] -= 1
        L[s + 1, s] -= 1
    return M, m * g * l * np.eye(n) + k * l * l * L


def pendula_exact_frequencies(n: int, m: float, l: float, g: float, k: float) -> np.ndarray:
    """ω_j² = g/l + (4k/m) sin²(jπ/(2N)), j = 0..N−1 (free-end chain Laplacian eigenvalues;
    N = 2: ω = √(g/l) in phase, √(g/l + 2k/m) out of phase — Goldstein §6.3)."""
    j = np.arange(n)
    return np.sqrt(g / l + 4 * k / m * np.sin(j * math.pi / (2 * n)) ** 2)
