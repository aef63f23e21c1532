r"""The torque-free rigid body: Euler's equations with the attitude quaternion.

State ``y = (ω1, ω2, ω3, q_w, q_x, q_y, q_z)``: body-frame angular velocity about the
principal axes and the unit quaternion of the body -> space rotation
(``v_space = q v_body q*``, see :mod:`reportgen.core.rotations`).

    I1 ω̇1 = (I2 − I3) ω2 ω3   (and cyclic; lecture notes (10.5))
    q̇ = ½ q ⊗ (0, ω) + κ (1 − |q|²) q

The last term vanishes on |q| = 1 and makes that sphere attracting at rate 2κ.  It is
off by default (κ = 0): measured with DOP853 at rtol 1e-12, κ = |ω| doubled the
function evaluations and did not reduce the |q| error (2.6e-12 without it on the
Dzhanibekov case), so scenes renormalize the stored quaternion instead and report
the raw deviation.  Gauss–Legendre methods and the axis splitting keep |q| (a
quadratic invariant) to round-off anyway.

Invariants: 2T = Σ I_i ω_i², L² = Σ I_i² ω_i² (body frame), and the space-frame
angular momentum L = R(q) I ω.

Exact reference (Landau & Lifshitz §37; Jacobi 1849): for I1 < I2 < I3 and
L² > 2E I2,

    ω1 = A1 cn τ,  ω2 = ±A2 sn τ,  ω3 = ±A3 dn τ,   τ = λ t + τ0,
    A1² = (2E I3 − L²)/(I1 (I3 − I1)),  A2² = (2E I3 − L²)/(I2 (I3 − I2)),
    A3² = (L² − 2E I1)/(I3 (I3 − I1)),
    λ² = (I3 − I2)(L² − 2E I1)/(I1 I2 I3),  m = (I2 − I1)(2E I3 − L²)/((I3 − I2)(L² − 2E I1));

for L² < 2E I2 the roles of axes 1 and 3 are swapped.  Symmetric bodies (10.9)–(10.10):
ω3 constant and ω1 + i ω2 rotating at −Ω, Ω = (I1 − I3) ω3 / I1.

References
----------
.. [1] Landau & Lifshitz, *Mechanics*, 3rd ed., §36–37 (eqs. 36.5, 37.8–37.10).
.. [2] Lecture notes §10, eqs. (10.5), (10.9)–(10.14).
.. [3] NIST DLMF §22.16, §22.20 (Jacobi functions; scipy's ``ellipj`` takes m = k²).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .. import special
from ..model import OdeModel
from ..rotations import quat_rotate, quat_to_matrix

COLUMNS = ("omega_1", "omega_2", "omega_3", "q_w", "q_x", "q_y", "q_z")

# params = (I1, I2, I3, kappa)


@numba.njit(cache=True, error_model="numpy")  # inlined in its driver: a 0 divisor gives inf
def rhs(t, y, params, out):
    I1, I2, I3, kappa = params[0], params[1], params[2], params[3]
    w1, w2, w3 = y[0], y[1], y[2]
    out[0] = (I2 - I3) * w2 * w3 / I1
    out[1] = (I3 - I1) * w3 * w1 / I2
    out[2] = (I1 - I2) * w1 * w2 / I3
    qw, qx, qy, qz = y[3], y[4], y[5], y[6]
    c = kappa * (1.0 - (qw * qw + qx * qx + qy * qy + qz * qz))
    # ½ q ⊗ (0, ω)
    out[3] = 0.5 * (-qx * w1 - qy * w2 - qz * w3) + c * qw
    out[4] = 0.5 * (qw * w1 + qy * w3 - qz * w2) + c * qx
    out[5] = 0.5 * (qw * w2 + qz * w1 - qx * w3) + c * qy
    out[6] = 0.5 * (qw * w3 + qx * w2 - qy * w1) + c * qz


@numba.njit(cache=True)
def jac(t, y, params, out):
    I1, I2, I3, kappa = params[0], params[1], params[2], params[3]
    w1, w2, w3 = y[0], y[1], y[2]
    qw, qx, qy, qz = y[3], y[4], y[5], y[6]
    for i in range(7):
        for j in range(7):
            out[i, j] = 0.0
    out[0, 1] = (I2 - I3) * w3 / I1
    out[0, 2] = (I2 - I3) * w2 / I1
    out[1, 0] = (I3 - I1) * w3 / I2
    out[1, 2] = (I3 - I1) * w1 / I2
    out[2, 0] = (I1 - I2) * w2 / I3
    out[2, 1] = (I1 - I2) * w1 / I3
    # d/dω of ½ q ⊗ (0, ω)
    out[3, 0], out[3, 1], out[3, 2] = -0.5 * qx, -0.5 * qy, -0.5 * qz
    out[4, 0], out[4, 1], out[4, 2] = 0.5 * qw, -0.5 * qz, 0.5 * qy
    out[5, 0], out[5, 1], out[5, 2] = 0.5 * qz, 0.5 * qw, -0.5 * qx
    out[6, 0], out[6, 1], out[6, 2] = -0.5 * qy, 0.5 * qx, 0.5 * qw
    # d/dq of ½ q ⊗ (0, ω)
    out[3, 4], out[3, 5], out[3, 6] = -0.5 * w1, -0.5 * w2, -0.5 * w3
    out[4, 3], out[4, 5], out[4, 6] = 0.5 * w1, 0.5 * w3, -0.5 * w2
    out[5, 3], out[5, 4], out[5, 6] = 0.5 * w2, -0.5 * w3, 0.5 * w1
    out[6, 3], out[6, 4], out[6, 5] = 0.5 * w3, 0.5 * w2, -0.5 * w1
    # d/dq of κ (1 − |q|²) q
    n2 = qw * qw + qx * qx + qy * qy + qz * qz
    q = (qw, qx, qy, qz)
    for i in range(4):
        out[3 + i, 3 + i] += kappa * (1.0 - n2)
        for j in range(4):
            out[3 + i, 3 + j] -= 2.0 * kappa * q[i] * q[j]


def model(I1: float, I2: float, I3: float, kappa: float = 0.0) -> OdeModel:
    """Compiled free rigid body with principal moments I1, I2, I3 [kg m²]."""
    return OdeModel(name="rigid_body", columns=COLUMNS, rhs=rhs,
                    params=np.array([I1, I2, I3, kappa], dtype=float), jac=jac,
                    specialize=True)


# ------------------------------------------------------------------ invariants
def twice_energy(omega, moments) -> np.ndarray:
    """2T = Σ I_i ω_i² [J], omega shape (..., 3)."""
    return np.sum(np.asarray(moments) * np.asarray(omega) ** 2, axis=-1)


def angular_momentum_squared(omega, moments) -> np.ndarray:
    """L² = Σ I_i² ω_i² [(kg m²/s)²]."""
    return np.sum((np.asarray(moments) * np.asarray(omega)) ** 2, axis=-1)


def space_angular_momentum(omega, quat, moments) -> np.ndarray:
    """L in the space frame, R(q) I ω, shape (..., 3)."""
    return quat_rotate(quat, np.asarray(moments) * np.asarray(omega))


def invariants(y, moments) -> dict[str, np.ndarray]:
    """Conserved quantities of a trajectory ``y`` of shape (N, 7)."""
    omega, quat = y[:, :3], y[:, 3:7]
    L = space_angular_momentum(omega, quat, moments)
    return {
        "twice_energy": twice_energy(omega, moments),
        "L_squared": angular_momentum_squared(omega, moments),
        "L_x": L[:, 0], "L_y": L[:, 1], "L_z": L[:, 2],
        "quaternion_norm": np.linalg.norm(quat, axis=1),
    }


# --------------------------------------------------------------- exact solution
def _elliptic_sorted(t, w0, I):
    """Case L² > 2E·I_b with moments I = (Ia, Ib, Ic), Ib strictly between Ia and Ic.

    The formula of the module docstring, written with ratios of same-sign differences
    so that it also holds for Ia > Ib > Ic (the swapped branch).
    """
    Ia, Ib, Ic = I
    E2 = float(np.sum(I * w0**2))
    L2 = float(np.sum((I * w0) ** 2))
    A1 = math.sqrt(max((E2 * Ic - L2) / (Ia * (Ic - Ia)), 0.0))
    A2 = math.sqrt(max((E2 * Ic - L2) / (Ib * (Ic - Ib)), 0.0))
    A3 = math.sqrt(max((L2 - E2 * Ia) / (Ic * (Ic - Ia)), 0.0))
    lam = math.sqrt(max((Ic - Ib) * (L2 - E2 * Ia) / (Ia * Ib * Ic), 0.0))
    m = (Ib - Ia) * (E2 * Ic - L2) / ((Ic - Ib) * (L2 - E2 * Ia))
    m = min(max(m, 0.0), 1.0)
    s3 = 1.0 if w0[2] >= 0 else -1.0
    # signs fixed by Euler's equations: ω̇_b = (I_c − I_a) ω_c ω_a / I_b
    s2 = s3 * (1.0 if Ic > Ia else -1.0)
    t = np.asarray(t, dtype=float)
    if A1 == 0.0 or A2 == 0.0:  # steady rotation about the c axis
        return np.column_stack([np.zeros_like(t), np.zeros_like(t), np.full_like(t, w0[2])])
    cn0 = max(-1.0, min(1.0, w0[0] / A1))
    sn0 = max(-1.0, min(1.0, s2 * w0[1] / A2))
    tau0 = special.ellipf(math.atan2(sn0, cn0), m)
    sn, cn, dn = special.jacobi_sn_cn_dn(lam * t + tau0, m)
    return np.column_stack([A1 * cn, s2 * A2 * sn, s3 * A3 * dn])


def _symmetric_sorted(t, w0, I, axis):
    """Symmetric body, symmetry axis ``axis`` (0 or 2) of the sorted frame (10.9)–(10.10).

    With (s, b, c) cyclic, ω_s is constant and ω_b + i ω_c = (ω_b + i ω_c)(0) e^{−iΩt},
    Ω = (I_b − I_s) ω_s / I_b   (for s = 3: Ω = (I1 − I3) ω3 / I1).
    """
    s, b, c = axis, (axis + 1) % 3, (axis + 2) % 3
    Omega = (I[b] - I[s]) * w0[s] / I[b]
    z = (w0[b] + 1j * w0[c]) * np.exp(-1j * Omega * np.asarray(t, dtype=float))
    out = np.empty((z.size, 3))
    out[:, s], out[:, b], out[:, c] = w0[s], z.real, z.imag
    return out


def _permutation_parity(p) -> int:
    p = list(p)
    parity = 1
    for i in range(len(p)):
        while p[i] != i:
            j = p[i]
            p[i], p[j] = p[j], p[i]
            parity = -parity
    return parity


def exact_omega(t, omega0, moments, rtol: float = 1e-13) -> np.ndarray:
    """Exact body-frame ω(t) of the free rigid body, shape (N, 3), any ordering of the moments.

    The moments are sorted internally (I1 ≤ I2 ≤ I3) and the result mapped back; an
    odd sorting permutation reverses the sense of Euler's equations, i.e. time.
    """
    I = np.asarray(moments, dtype=float)
    w = np.asarray(omega0, dtype=float)
    t = np.asarray(t, dtype=float)
    perm = np.argsort(I, kind="stable")
    Is, ws = I[perm], w[perm]
    ts = t * _permutation_parity(perm)
    scale = Is[2]
    eq12 = abs(Is[1] - Is[0]) <= rtol * scale
    eq23 = abs(Is[2] - Is[1]) <= rtol * scale
    if eq12 and eq23:
        out_s = np.tile(ws, (t.size, 1))
    elif eq12:
        out_s = _symmetric_sorted(ts, ws, Is, 2)
    elif eq23:
        out_s = _symmetric_sorted(ts, ws, Is, 0)
    else:
        E2 = float(np.sum(Is * ws**2))
        L2 = float(np.sum((Is * ws) ** 2))
        if L2 >= E2 * Is[1]:
            out_s = _elliptic_sorted(ts, ws, Is)
        else:
            # swap axes 1 and 3: (ω3, −ω2, ω1) with (I3, I2, I1) obeys Euler's equations
            sw = np.array([ws[2], -ws[1], ws[0]])
            r = _elliptic_sorted(ts, sw, Is[::-1].copy())
            out_s = np.column_stack([r[:, 2], -r[:, 1], r[:, 0]])
    out = np.empty_like(out_s)
    out[:, perm] = out_s
    return out


def elliptic_parameters(omega0, moments) -> dict:
    """Branch, λ, m and the flip half-period 2K(m)/λ of the asymmetric body (sorted frame)."""
    I = np.sort(np.asarray(moments, dtype=float))
    perm = np.argsort(np.asarray(moments, dtype=float), kind="stable")
    w = np.asarray(omega0, dtype=float)[perm]
    E2 = float(np.sum(I * w**2))
    L2 = float(np.sum((I * w) ** 2))
    I1, I2, I3 = I
    if L2 >= E2 * I2:
        branch = "L² > 2E·I2 (polhode about the largest-moment axis)"
        lam2 = (I3 - I2) * (L2 - E2 * I1) / (I1 * I2 * I3)
        m = (I2 - I1) * (E2 * I3 - L2) / ((I3 - I2) * (L2 - E2 * I1))
    else:
        branch = "L² < 2E·I2 (polhode about the smallest-moment axis)"
        lam2 = (I2 - I1) * (E2 * I3 - L2) / (I1 * I2 * I3)
        m = (I3 - I2) * (L2 - E2 * I1) / ((I2 - I1) * (E2 * I3 - L2))
    lam = math.sqrt(max(lam2, 0.0))
    K = special.ellipk(m)
    return {"branch": branch, "lambda": lam, "m": m, "twice_energy": E2, "L_squared": L2,
            "period": 4.0 * K / lam if lam > 0 else math.inf}


def symmetric_precession_rate(moments, omega0) -> tuple[int, float] | None:
    """(symmetry axis index, Ω = (I⊥ − I_s) ω_s / I⊥) of a symmetric body, or None (10.10)."""
    I = np.asarray(moments, dtype=float)
    for s in range(3):
        b, c = (s + 1) % 3, (s + 2) % 3
        if abs(I[b] - I[c]) <= 1e-13 * I.max() and abs(I[s] - I[b]) > 1e-13 * I.max():
            return s, float((I[b] - I[s]) * omega0[s] / I[b])
    return None


# ------------------------------------------------------------------ initial state
def omega_after_impulse(omega, moments, r, P) -> np.ndarray:
    """Body-frame ω just after an impulse P applied at the point r (exercise 4.6c).

    The angular impulse about the centre of mass is ΔL = r × P, so (principal frame)
    ω⁺ = ω + I⁻¹ (r × P), i.e. Δω_k = (r × P)_k / I_k.

    Parameters
    ----------
    omega : array_like, shape (3,)
        Body-frame angular velocity before the impulse [rad/s].
    moments : array_like, shape (3,)
        Principal moments along the body axes [kg m²].
    r : array_like, shape (3,)
        Point of application relative to the centre of mass, body frame [m].
    P : array_like, shape (3,)
        Impulse, body frame [kg m/s].

    Returns
    -------
    ndarray, shape (3,)  [rad/s]
    """
    w = np.asarray(omega, dtype=float)
    return w + np.cross(np.asarray(r, dtype=float), np.asarray(P, dtype=float)) \
        / np.asarray(moments, dtype=float)


# --------------------------------------------------------------------- stability
def steady_rotation_growth_rate(moments, axis: int, spin: float) -> float:
    """Largest real part of the eigenvalues of the ω-block of the Jacobian of Euler's
    equations (10.5) at steady rotation ``spin`` e_axis [1/s].

    An independent (numerical) check of the closed-form rates (10.12)–(10.14) of
    :func:`reportgen.core.inertia.axis_stability`: Ω√((I2−I1)(I3−I2)/(I1 I3)) about the
    intermediate axis, 0 (purely imaginary eigenvalues) about the others.
    """
    y = np.zeros(7)
    y[axis] = spin
    y[3] = 1.0
    J = model(*np.asarray(moments, dtype=float)).jacobian(0.0, y)[:3, :3]
    return float(np.max(np.linalg.eigvals(J).real))


def growth_envelope(t, perturbation0: float, growth_rate: float) -> np.ndarray:
    """Linear growth δ(t) = δ0 e^{γt} of a perturbation about the intermediate axis (10.14),
    shape (N,) like ``t`` [rad/s]."""
    return perturbation0 * np.exp(growth_rate * np.asarray(t))


def flip_analysis(t, omega, axis: int, growth_rate: float, half_period_exact: float) -> dict:
    """Zero crossings of the intermediate component ω_b(t): the Dzhanibekov flips.

    Crossing times are located by linear interpolation between samples; their mean
    spacing is compared with half the elliptic period, 2K(m)/λ.

    Parameters
    ----------
    t : ndarray, shape (N,)  [s]
    omega : ndarray, shape (N, 3)  body-frame ω [rad/s]
    axis : int
        Index (0-based) of the intermediate axis b.
    growth_rate : float
        γ of (10.14) [1/s].
    half_period_exact : float
        2K(m)/λ [s] (NaN when not known).

    Returns
    -------
    dict
        ``axis`` (1-based), ``flip_times`` (K,), ``half_period_measured`` (NaN for
        fewer than two flips), ``half_period_exact``, ``growth_rate``,
        ``perturbation_initial`` = |ω⊥(0)| (the components off the axis) and
        ``growth_envelope`` = |ω⊥(0)| e^{γt}, shape (N,).
    """
    wb = omega[:, axis]
    # a sign change between samples that are not zero to rounding: a run started with
    # ω_b = 0 exactly (on a principal plane) has not flipped at t = 0
    kept = np.nonzero(np.abs(wb) > 1e-12 * float(np.max(np.abs(wb), initial=0.0)))[0]
    change = np.nonzero(np.sign(wb[kept[1:]]) != np.sign(wb[kept[:-1]]))[0]
    i, j = kept[change], kept[change + 1]
    times = t[i] - wb[i] * (t[j] - t[i]) / (wb[j] - wb[i])
    measured = float(np.mean(np.diff(times))) if times.size >= 2 else math.nan
    others = [i for i in range(3) if i != axis]
    perp0 = float(np.linalg.norm(omega[0, others]))
    return {"axis": axis + 1, "flip_times": times if times.size else np.zeros(0),
            "half_period_measured": measured, "half_period_exact": half_period_exact,
            "growth_rate": growth_rate, "perturbation_initial": perp0,
            "growth_envelope": growth_envelope(t, perp0, growth_rate)}


def symmetric_precession_analysis(t, omega, moments, axis: int, Omega: float) -> dict:
    """Measured body-frame precession of a symmetric body against (10.10).

    The phase of ω⊥ = ω_b + i ω_c turns at −Ω; its measured rate is minus the slope of
    a straight-line fit to the unwrapped phase (NaN when |ω⊥| is zero to 1e-8 of ω_s).
    Seen from space the figure axis precesses about L at |L|/I⊥.

    Parameters
    ----------
    t : ndarray, shape (N,)  [s]
    omega : ndarray, shape (N, 3)  body-frame ω [rad/s]
    moments : array_like, shape (3,)  [kg m²]
    axis : int
        0-based symmetry axis s (the odd moment).
    Omega : float
        Ω = (I⊥ − I_s) ω_s / I⊥ [rad/s] (10.10).

    Returns
    -------
    dict: ``axis`` (1-based), ``Omega``, ``Omega_measured``, ``omega_perp`` [rad/s],
    ``space_precession_rate`` = |L|/I⊥ [rad/s].
    """
    b, c = (axis + 1) % 3, (axis + 2) % 3
    angle = np.unwrap(np.arctan2(omega[:, c], omega[:, b]))
    perp = float(np.hypot(omega[0, b], omega[0, c]))
    measured = float(-np.polyfit(t, angle, 1)[0]) if perp > 1e-8 * abs(omega[0, axis]) \
        else math.nan
    I = np.asarray(moments, dtype=float)
    return {"axis": axis + 1, "Omega": Omega, "Omega_measured": measured,
            "omega_perp": perp,
            "space_precession_rate": float(np.linalg.norm(I * omega[0]) / I[b])}


# ----------------------------------------------------------- Poinsot geometry
def polhode_family(moments, n_curves: int = 5, n_points: int = 400) -> np.ndarray:
    """Polhodes of unit angular momentum: curves l·l = 1, Σ l_k²/I_k = e on the unit L-sphere
    (body frame), for energies e spread between each extreme axis and the separatrix.

    For curves about axis a (smallest or largest moment), with (b, c) the others::

        l_b = ρ cos φ,  l_c = ρ sin φ,  l_a = ±√(1 − ρ²),
        ρ² = (1/I_a − e) / (1/I_a − cos²φ/I_b − sin²φ/I_c)

    (Landau & Lifshitz §37, Fig. 52).  ``n_curves`` energies per axis, both signs of l_a.
    Curves that are not defined (degenerate moments: 0/0) are left out.

    Returns
    -------
    ndarray, shape (K, n_points, 3)
        K ≤ 4 n_curves closed curves of unit vectors L/|L|; K = 0 for a spherical top.
    """
    I = np.asarray(moments, dtype=float)
    order = np.argsort(I)
    phi = np.linspace(0.0, 2 * np.pi, n_points)
    curves = []
    with np.errstate(invalid="ignore", divide="ignore"):
        inv = 1.0 / I
        e_sep = inv[order[1]]
        for a, e_axis in ((order[0], inv[order[0]]), (order[2], inv[order[2]])):
            b, c = [k for k in range(3) if k != a]
            for f in np.linspace(0.0, 1.0, n_curves + 2)[1:-1]:
                e = e_axis + f * (e_sep - e_axis)
                rho2 = (inv[a] - e) / (inv[a] - np.cos(phi) ** 2 * inv[b]
                                       - np.sin(phi) ** 2 * inv[c])
                rho2 = np.clip(rho2, 0.0, 1.0)
                for sign in (1.0, -1.0):
                    pts = np.empty((phi.size, 3))
                    pts[:, a] = sign * np.sqrt(1.0 - rho2)
                    pts[:, b] = np.sqrt(rho2) * np.cos(phi)
                    pts[:, c] = np.sqrt(rho2) * np.sin(phi)
                    if np.all(np.isfinite(pts)):
                        curves.append(pts)
    return np.array(curves) if curves else np.zeros((0, n_points, 3))


def polhode_separatrices(moments, n_points: int = 400) -> np.ndarray:
    """The two separatrices 2E = L²/I2 on the unit L-sphere: great circles through the
    intermediate axis, in the planes l_s √(1/I_s − 1/I_m) = ± l_l √(1/I_m − 1/I_l)
    (s, m, l: smallest, intermediate, largest moment).

    Returns
    -------
    ndarray, shape (2, n_points, 3), or (0, n_points, 3) unless the three moments are
    distinct (to 12 digits): a symmetric body has no separatrix.
    """
    I = np.asarray(moments, dtype=float)
    phi = np.linspace(0.0, 2 * np.pi, n_points)
    if len(set(np.round(I / np.max(I), 12))) != 3:
        return np.zeros((0, n_points, 3))
    s, m, l = np.argsort(I)
    inv = 1.0 / I
    u, v = np.sqrt(inv[s] - inv[m]), np.sqrt(inv[m] - inv[l])
    out = []
    for sign in (1.0, -1.0):
        n = np.zeros(3)
        n[s], n[l] = v, sign * u  # direction in the (s, l) plane lying on the separatrix plane
        n /= np.linalg.norm(n)
        e2 = np.zeros(3)
        e2[m] = 1.0
        out.append(np.outer(np.cos(phi), n) + np.outer(np.sin(phi), e2))
    return np.array(out)


def polhode_track(omega, moments) -> np.ndarray:
    """The polhode of a trajectory: body-frame L/|L| = Iω/|Iω|, shape (N, 3)."""
    L = np.asarray(omega, dtype=float) * np.asarray(moments, dtype=float)
    return L / np.linalg.norm(L, axis=1, keepdims=True)


def herpolhode(omega, quat, moments) -> dict:
    """The herpolhode: the tip of the space-frame ω on the invariable plane (Poinsot).

    The plane is perpendicular to the (conserved) space-frame L, taken at the first
    sample; (e1, e2) is an orthonormal basis of it.  ω·L/|L| = 2T/|L| is constant.

    Parameters
    ----------
    omega : ndarray, shape (N, 3)  body-frame ω [rad/s]
    quat : ndarray, shape (N, 4)  attitude quaternions (body -> space)
    moments : array_like, shape (3,)  [kg m²]

    Returns
    -------
    dict: ``x``, ``y`` (N,) = ω·e1, ω·e2 [rad/s]; ``along_L`` (N,) = ω·L/|L| [rad/s].
    """
    I = np.asarray(moments, dtype=float)
    R = quat_to_matrix(quat)
    w_space = np.einsum("nij,nj->ni", R, omega)
    L = np.einsum("nij,nj->ni", R, omega * I)[0]
    n = L / np.linalg.norm(L)
    e1 = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    return {"x": w_space @ e1, "y": w_space @ e2, "along_L": w_space @ n}
