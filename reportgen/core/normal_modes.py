r"""Small oscillations about a stable equilibrium: the eigenproblem A η = ω² M η.

Textbook ch. 5, §5.1 (Goldstein, Poole & Safko, *Classical Mechanics*, 3rd ed.,
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
.. [1] Textbook ch. 5, §5.1, Fig. 5.1 (molecule vibrations).
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

from .differences import central_difference_hessian
from .molecule_geometry import ELEMENT_MASSES, bond_angle  # noqa: F401 - part of this module's interface

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
    """The textbook route (textbook §5.1; Goldstein §6.2), step by step.

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
    """Exact motion by modal superposition (textbook §5.1; Goldstein eq. for q(t) in §6.2).

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
        frame = self.drawing_frame()
        normals = list(frame) + list(np.eye(3))
        cands = [-np.eye(3)] + [np.eye(3) - 2 * np.outer(nv, nv) for nv in normals]
        ops: list[np.ndarray] = []
        for Rm in cands:
            S = self._operation(Rm, A, tol)
            if S is not None and not any(np.allclose(S, s) for s in ops):
                ops.append(S)
        return ops

    def _operation(self, Rm: np.ndarray, A: np.ndarray, tol: float) -> np.ndarray | None:
        """The (3n, 3n) matrix of the orthogonal map ``Rm`` about the centre of mass, if it
        takes every atom onto an atom of equal mass and leaves A invariant; else None."""
        x = np.asarray(self.positions, dtype=float) - self.centre_of_mass()
        m = np.asarray(self.masses, dtype=float)
        n = self.n_atoms
        size = max(float(np.max(np.abs(x))), 1.0)
        y = x @ Rm.T
        S = np.zeros((3 * n, 3 * n))
        for a in range(n):
            d = np.linalg.norm(x - y[a], axis=1)
            b = int(np.argmin(d))
            if d[b] > tol * size or abs(m[b] - m[a]) > tol * m[a]:
                return None
            S[3 * b:3 * b + 3, 3 * a:3 * a + 3] = Rm
        if np.max(np.abs(S @ A @ S.T - A)) > 1e-9 * max(float(np.max(np.abs(A))), 1e-300):
            return None
        return S

    def inversion(self, A: np.ndarray | None = None, tol: float = 1e-9) -> np.ndarray | None:
        """The inversion x − x_cm → −(x − x_cm) as a (3n, 3n) matrix when the molecule and
        its force field (A, default :meth:`hessian`) have a centre of symmetry (CO₂, C₂H₂);
        None otherwise (H₂O)."""
        return self._operation(-np.eye(3), self.hessian() if A is None else A, tol)


def finite_difference_hessian(f, x0: np.ndarray, h: float = 1e-4) -> np.ndarray:
    """Central second differences of a scalar f at x0 (error O(h²)).  Shape (n, n)."""
    return central_difference_hessian(f, x0, h)


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


#: a mode is even (odd) under the inversion when ηᵀ M S η is within this of +1 (−1)
PARITY_TOL = 1e-6


def mode_parity(modes: np.ndarray, M: np.ndarray, inversion: np.ndarray | None) -> list[str]:
    """"g" (even) or "u" (odd) per column η of ``modes`` under the inversion S: S η = ±η,
    read from ηᵀ M S η / ηᵀ M η = ±1 (S permutes equal masses, so it commutes with M);
    "" for a mode of neither parity, and for every mode when there is no centre of symmetry.

    Parameters
    ----------
    modes : ndarray, shape (3n, k)
    M : ndarray, shape (3n, 3n)
    inversion : ndarray, shape (3n, 3n), or None (:meth:`Molecule.inversion`)

    Returns
    -------
    list of str, length k
    """
    if inversion is None:
        return [""] * modes.shape[1]
    out = []
    for k in range(modes.shape[1]):
        eta = modes[:, k]
        p = float(eta @ M @ inversion @ eta) / float(eta @ M @ eta)
        out.append("g" if p > 1 - PARITY_TOL else "u" if p < -1 + PARITY_TOL else "")
    return out


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
    (textbook §5.1 / Goldstein §6.4 loaded string); free ends: 2√(k/m) sin(jπ/(2N)), j = 0..N−1."""
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


def rigid_body_basis(mol: Molecule, M: np.ndarray) -> tuple[np.ndarray, list[str]]:
    """M-orthonormal rigid-body zero modes of a molecule, with their labels.

    Translations first, then the infinitesimal rotations (their M-Gram matrix is the
    inertia tensor); the rank of each block is found by :func:`m_orthonormalize`, so a
    linear molecule gets 3 translations and 2 rotations (textbook §5.1).

    Parameters
    ----------
    mol : Molecule
    M : ndarray, shape (3n, 3n)
        Mass matrix of ``mol``.

    Returns
    -------
    basis : ndarray, shape (3n, r), r = 5 or 6
    labels : list of str, length r: "translation" or "rotation"
    """
    vecs = mol.rigid_body_vectors()
    trans = m_orthonormalize(vecs[:, :3], M)
    rot = m_orthonormalize(vecs[:, 3:], M)
    return (np.column_stack([trans, rot]),
            ["translation"] * trans.shape[1] + ["rotation"] * rot.shape[1])


def classify_modes(modes: ModeSet, M: np.ndarray, system: str, mol: Molecule | None = None,
                   rigid_labels: list[str] | tuple[str, ...] = (),
                   names: list[str] | None = None) -> list[str]:
    """A type label per mode of ``modes`` (ascending ω).

    Zero modes take ``rigid_labels`` in order ("translation", "rotation"), then
    "zero mode (floppy)".  Vibrations of a molecule take ``names`` (one per vibration, by
    the internal coordinates that hold their energy: the kind's words) and, for a linear
    molecule, their geometry (:func:`mode_types_linear`: longitudinal, transverse in-plane
    / out-of-plane; a transverse vibration is named by its geometry alone).  A chain or
    row of pendula (``system`` "chain" or "pendula") names each mode by its node count
    (:func:`node_count`; two pendula: "in phase" / "out of phase", Goldstein §6.3); any
    other system: "normal mode".

    Parameters
    ----------
    modes : ModeSet
        From :func:`solve_modes`; columns η_k, shape (n, n).
    M : ndarray, shape (n, n)
    system : {"molecule", "chain", "pendula", "matrices"}
    mol : Molecule or None
        Required for ``system == "molecule"``.
    rigid_labels : sequence of str
    names : list of str or None
        A molecule's vibrations' names ("vibration" each when None).

    Returns
    -------
    list of str, length n
    """
    n = M.shape[0]
    zero = [rigid_labels[k] if k < len(rigid_labels) else "zero mode (floppy)"
            for k in range(modes.n_zero)]
    if mol is not None:
        names = list(names) if names is not None else ["vibration"] * (n - modes.n_zero)
        axis = mol.axis()
        if axis is not None:
            w1, _ = transverse_directions(axis)
            geo = mode_types_linear(modes.modes[:, modes.n_zero:], M, axis, w1)
            names = [g if g.startswith("transverse") else f"{g}, {name}"
                     for g, name in zip(geo, names, strict=True)]
        return zero + names
    types = list(zero)
    for k in range(modes.n_zero, n):
        eta = modes.modes[:, k]
        if system in ("chain", "pendula"):
            nodes = node_count(eta)
            if system == "pendula" and n == 2:
                types.append("in phase" if nodes == 0 else "out of phase")
            else:
                types.append(f"{nodes} node{'s' if nodes != 1 else ''}")
        else:
            types.append("normal mode")
    return types


# --------------------------------------------------------------- triatomic closed forms
@dataclass(frozen=True)
class SymmetricXY2:
    """A symmetric triatomic molecule Y–X–Y: two equal bonds to a centre atom X.

    Attributes
    ----------
    centre : int
        Index of X.
    ends : (int, int)
        Indices of the two Y atoms.
    k : float
        Stretch constant of both bonds [energy/length²].
    k_bend : float or None
        Bend constant of the angle at X [energy/rad²], None without one.
    r : float
        Bond length [length].
    m_y, m_x : float
        Masses of Y and X [mass].
    half_angle : float
        α, half the bond angle Y–X–Y [rad] (π/2 for a linear molecule).
    linear : bool
    """

    centre: int
    ends: tuple[int, int]
    k: float
    k_bend: float | None
    r: float
    m_y: float
    m_x: float
    half_angle: float
    linear: bool


def symmetric_xy2(mol: Molecule) -> SymmetricXY2 | None:
    """The molecule as a symmetric Y–X–Y triatomic, or None if it is not one.

    It is one when it has 3 atoms and 2 bonds sharing one atom X, with equal
    stretch constants, equal end masses and equal bond lengths (relative 1e-12).
    """
    if mol.n_atoms != 3 or len(mol.bonds) != 2:
        return None
    (i1, j1, k1), (i2, j2, k2) = mol.bonds
    centre = ({i1, j1} & {i2, j2})
    if len(centre) != 1 or k1 != k2:
        return None
    cx = centre.pop()
    ends = [a for a in range(3) if a != cx]
    x = mol.positions
    r1, r2 = (np.linalg.norm(x[e] - x[cx]) for e in ends)
    my, mx = mol.masses[ends[0]], mol.masses[cx]
    if mol.masses[ends[1]] != my or abs(r1 - r2) > 1e-12 * r1:
        return None
    kb = next((g[3] for g in mol.angles if g[1] == cx), None)
    return SymmetricXY2(centre=cx, ends=(ends[0], ends[1]), k=k1, k_bend=kb, r=r1, m_y=my,
                        m_x=mx, half_angle=bond_angle(x, ends[0], cx, ends[1]) / 2,
                        linear=mol.axis() is not None)


def linear_xy2_frequencies(k: float, m_y: float, m_x: float) -> tuple[float, float]:
    """Stretch frequencies of a linear symmetric triatomic Y–X–Y (Goldstein §6.4; textbook
    §5.1, Fig. 5.1).

    ω_sym = √(k/m_Y) (X at rest), ω_asym = √((k/m_Y)(1 + 2 m_Y/m_X)).

    Returns
    -------
    (omega_symmetric, omega_antisymmetric) : floats [rad per time unit]
    """
    return math.sqrt(k / m_y), math.sqrt(k / m_y * (1 + 2 * m_y / m_x))


def linear_xy2_bend_frequency(k_bend: float, m_y: float, m_x: float, r: float) -> float:
    """Twofold bend frequency of a linear symmetric triatomic Y–X–Y.

    With the linear-bend coordinate ρ = Σ w·(δx_Y − δx_X)/r (:func:`bend_bvectors`) and
    the centre of mass at rest: ω² = (2 k_θ/(m_Y r²))(1 + 2 m_Y/m_X).
    """
    return math.sqrt(2 * k_bend / (m_y * r * r) * (1 + 2 * m_y / m_x))


def bent_xy2_eigenvalues(k: float, k_bend: float, m_y: float, m_x: float, r: float,
                         half_angle: float) -> tuple[float, float, float]:
    """Closed forms of a bent symmetric triatomic Y–X–Y in the valence force field.

    Herzberg (1945) ch. II, bond angle 2α:
    λ₃ = (1 + 2 m_Y sin²α / m_X) k/m_Y (antisymmetric stretch);
    λ₁ + λ₂ = (1 + 2 m_Y cos²α/m_X) k/m_Y + (2/m_Y)(1 + 2 m_Y sin²α/m_X) k_θ/r²;
    λ₁ λ₂ = 2 (1 + 2 m_Y/m_X) k k_θ / (m_Y² r²) (symmetric block), λ = ω².

    Returns
    -------
    (lambda3, lambda1 + lambda2, lambda1 * lambda2) : floats
    """
    s2, c2 = math.sin(half_angle) ** 2, math.cos(half_angle) ** 2
    lam3 = (1 + 2 * m_y * s2 / m_x) * k / m_y
    tot = (1 + 2 * m_y * c2 / m_x) * k / m_y + 2 / m_y * (1 + 2 * m_y * s2 / m_x) * k_bend / r**2
    prod = 2 * (1 + 2 * m_y / m_x) * k * k_bend / (m_y * m_y * r * r)
    return lam3, tot, prod


# --------------------------------------------------- linear four-atom closed forms
@dataclass(frozen=True)
class SymmetricLinearX2Y2:
    """A symmetric linear four-atom molecule X–Y–Y–X (acetylene H–C≡C–H).

    Attributes
    ----------
    ends : (int, int)
        Indices of the X atoms, ``ends[i]`` bonded to ``centre[i]``.
    centre : (int, int)
        Indices of the two Y atoms.
    k_end, k_centre : float
        Stretch constants of X–Y and Y–Y [energy/length²].
    k_bend : float or None
        Bend constant of the angles X–Y–Y at both Y [energy/rad²], None without bends.
    r_end, r_centre : float
        Bond lengths X–Y and Y–Y [length].
    m_end, m_centre : float
        Masses of X and Y [mass].
    """

    ends: tuple[int, int]
    centre: tuple[int, int]
    k_end: float
    k_centre: float
    k_bend: float | None
    r_end: float
    r_centre: float
    m_end: float
    m_centre: float


def symmetric_linear_x2y2(mol: Molecule) -> SymmetricLinearX2Y2 | None:
    """The molecule as a symmetric linear X–Y–Y–X, or None if it is not one.

    It is one when its 4 atoms lie on a line joined by 3 bonds in a path X–Y–Y–X, the two
    end bonds with equal constants and lengths (relative 1e-12), equal end and equal centre
    masses, and its angles are none or the two X–Y–Y bends at the two Y, with one constant.
    """
    if mol.n_atoms != 4 or len(mol.bonds) != 3 or mol.axis() is None:
        return None
    degree = np.bincount([a for i, j, _k in mol.bonds for a in (i, j)], minlength=4)
    if sorted(degree.tolist()) != [1, 1, 2, 2]:
        return None
    centre_bond = next(((i, j, k) for i, j, k in mol.bonds
                        if degree[i] == 2 and degree[j] == 2), None)
    if centre_bond is None:
        return None
    y1, y2, k_centre = centre_bond
    ends_k = {}
    for i, j, k in mol.bonds:
        for end, mid in ((i, j), (j, i)):
            if degree[end] == 1:
                ends_k[mid] = (end, k)
    if set(ends_k) != {y1, y2}:
        return None
    (x1, k1), (x2, k2) = ends_k[y1], ends_k[y2]
    x, m = np.asarray(mol.positions, dtype=float), np.asarray(mol.masses, dtype=float)
    r1, r2 = (float(np.linalg.norm(x[a] - x[b])) for a, b in ((x1, y1), (x2, y2)))
    if k1 != k2 or abs(r1 - r2) > 1e-12 * r1 or m[x1] != m[x2] or m[y1] != m[y2]:
        return None
    k_bend = None
    if mol.angles:
        wanted = {(y1, frozenset((x1, y2))), (y2, frozenset((x2, y1)))}
        given = {(j, frozenset((i, l))) for i, j, l, _k in mol.angles}
        constants = {k for *_idx, k in mol.angles}
        if len(mol.angles) != 2 or given != wanted or len(constants) != 1:
            return None
        k_bend = constants.pop()
    return SymmetricLinearX2Y2(ends=(x1, x2), centre=(y1, y2), k_end=k1, k_centre=k_centre,
                               k_bend=k_bend, r_end=r1,
                               r_centre=float(np.linalg.norm(x[y2] - x[y1])),
                               m_end=float(m[x1]), m_centre=float(m[y1]))


def linear_x2y2_eigenvalues(mol: SymmetricLinearX2Y2) -> dict[str, float]:
    """ω² of a symmetric linear X–Y–Y–X in the valence force field, in closed form.

    Along the axis (the chain X–Y–Y–X of springs k1, k2, k1 and masses m, M, M, m) the
    displacements split by the inversion.  Even (x1 = −x4 = a, x2 = −x3 = b):
    m ä = −k1(a − b), M b̈ = −k1(b − a) − 2k2 b, whose ω² have the sum
    S = k1/m + (k1 + 2k2)/M and the product P = 2k1k2/(mM): ω² = [S ± √(S² − 4P)]/2
    (Σg: for C₂H₂ ν1, mostly C–H, and ν2, mostly C≡C).  Odd (x1 = x4, x2 = x3): the translation and
    ω² = k1(1/m + 1/M) (Σu: ν3).  Across the axis, with the linear-bend coordinates
    ρ = (y_X − y_Y)/r1 + (y_Y′ − y_Y)/r2 at each Y (:func:`bend_bvectors`; r1 = X–Y,
    r2 = Y–Y) and V = ½k_θ(ρ₁² + ρ₂²): even (trans bend, y_X′ = −y_X, y_Y′ = −y_Y) holds the
    rotation and ω² = k_θ[1/(m r1²) + (1/r1 + 2/r2)²/M] (Πg: ν4); odd (cis bend,
    y_X′ = y_X, y_Y′ = y_Y) holds the translation and ω² = k_θ(1/m + 1/M)/r1² (Πu: ν5),
    each twice (two planes).

    Returns
    -------
    dict with "stretch_even_high", "stretch_even_low", "stretch_odd" and, with bends,
    "bend_trans" (even) and "bend_cis" (odd) [1/time² in the molecule's units]
    """
    k1, k2, m, M = mol.k_end, mol.k_centre, mol.m_end, mol.m_centre
    total, product = k1 / m + (k1 + 2 * k2) / M, 2 * k1 * k2 / (m * M)
    high = 0.5 * (total + math.sqrt(total * total - 4 * product))
    out = {"stretch_even_high": high, "stretch_even_low": product / high,  # no cancellation
           "stretch_odd": k1 * (1 / m + 1 / M)}
    if mol.k_bend is not None:
        kb, r1, r2 = mol.k_bend, mol.r_end, mol.r_centre
        out["bend_trans"] = kb * (1 / (m * r1 * r1) + (1 / r1 + 2 / r2) ** 2 / M)
        out["bend_cis"] = kb * (1 / m + 1 / M) / (r1 * r1)
    return out


# ------------------------------------------------------------------ drawn curves
def chain_standing_wave(n: int, j: int, s: np.ndarray) -> np.ndarray:
    """Mode j of a uniform chain of N = n masses between fixed walls, sin(j s π/(N+1)).

    Textbook §5.1 / Goldstein §6.4; ``s`` (any shape) is the mass index, continuous
    between the walls at 0 and N + 1.  Returns an array shaped like ``s``.
    """
    return np.sin(j * np.asarray(s, dtype=float) * math.pi / (n + 1))


def chain_standing_waves(modes: np.ndarray, n_points: int = 200
                         ) -> tuple[np.ndarray, np.ndarray]:
    """The standing waves sin(j s π/(N+1)), j = 1..k, sampled between the walls for drawing
    over the computed modes (fixed-end uniform chain).

    Each wave is scaled so that its largest value at the masses s = 1..N is 1 and signed
    to match the mode's column.

    Parameters
    ----------
    modes : ndarray, shape (N, k)
        The lowest k modes, ascending.
    n_points : int

    Returns
    -------
    s : ndarray, shape (n_points,), from 0 to N + 1
    waves : ndarray, shape (n_points, k)
    """
    n, k = modes.shape
    s = np.linspace(0, n + 1, n_points)
    masses = np.arange(1, n + 1)
    waves = np.empty((n_points, k))
    for j in range(k):
        env = chain_standing_wave(n, j + 1, s)
        ref = chain_standing_wave(n, j + 1, masses)
        sgn = np.sign(ref @ modes[:, j]) or 1.0
        waves[:, j] = sgn * env / np.max(np.abs(ref))
    return s, waves


def drawing_projection(masses: np.ndarray, positions: np.ndarray, frame: np.ndarray,
                       modes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Equilibrium positions and mode displacements in a molecule's drawing frame.

    Parameters
    ----------
    masses : ndarray, shape (n,)
    positions : ndarray, shape (n, 3)
    frame : ndarray, shape (3, 3)
        Rows e1, e2, e3 (:meth:`Molecule.drawing_frame`).
    modes : ndarray, shape (3n, k)

    Returns
    -------
    positions : ndarray, shape (n, 3)
        x − x_cm in the frame (columns e1, e2, e3).
    displacements : ndarray, shape (k, n, 3)
        Each mode's per-atom displacement η_a in the frame.
    """
    x = np.asarray(positions, dtype=float)
    m = np.asarray(masses, dtype=float)
    xc = x - m @ x / np.sum(m)
    n = len(x)
    disps = np.array([modes[:, k].reshape(n, 3) @ frame.T for k in range(modes.shape[1])])
    return xc @ frame.T, disps.reshape(modes.shape[1], n, 3)
