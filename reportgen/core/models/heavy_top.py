r"""The heavy symmetric top: compiled equations of motion and its conserved quantities.

The attitude is a unit quaternion ``q`` (body -> space) and the body angular
velocity ``omega``; the state is ``y = (q_w, q_x, q_y, q_z, omega_1, omega_2,
omega_3)``.  Euler's equations with the gravity torque
``tau = l e3 x (-M g z) = M g l (g2, -g1, 0)`` (``g`` = the space vertical in
body axes) and ``q' = q (x) (0, omega) / 2`` have no coordinate singularity:
the sleeping top (θ = 0) is an ordinary point.

The scene integrates the *spin-free* form (:func:`spin_free_model`) and maps it back
to this state: the body spins about its symmetry axis at the constant ω3, so the body
frame is the frame F' that follows the axis without spinning (angular velocity
Ω ⊥ axis), turned about the axis by ω3 t.  F' moves only on the nutation and
precession time scales, so DOP853 needs ~3x fewer steps than for the body frame
(whose quaternion turns at ω3): 289 against 935 steps at rtol 1e-10 on the top of
issue 15 (I1 = 1.3, I3 = 0.45, Mgl = 0.9, ω3 = 6, t = 60), for the same θ(t) error.
θ, φ, ψ (Goldstein's z-x-z
Euler angles) and the space-frame symmetry axis are derived afterwards
(:mod:`reportgen.core.heavy_top_kinematics`); the closed form the motion is checked
against is :mod:`reportgen.core.heavy_top_theory`.

References
----------
.. [1] Lecture notes §10.1, eqs. (10.21)-(10.50).
.. [2] Goldstein, Poole, Safko, *Classical Mechanics*, 3rd ed., §4.4, §4.9, §5.7.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..model import OdeModel

COLUMNS = ("q_w", "q_x", "q_y", "q_z", "omega_1", "omega_2", "omega_3")

# params = (I1, I3, Mgl)


@numba.njit(cache=True)
def rhs(t, y, params, out):
    i1, i3, mgl = params[0], params[1], params[2]
    qw, qx, qy, qz = y[0], y[1], y[2], y[3]
    w1, w2, w3 = y[4], y[5], y[6]
    n2 = qw * qw + qx * qx + qy * qy + qz * qz
    # space vertical in body axes: third row of R(q) / |q|²
    g1 = 2.0 * (qx * qz - qw * qy) / n2
    g2 = 2.0 * (qy * qz + qw * qx) / n2
    out[0] = -0.5 * (qx * w1 + qy * w2 + qz * w3)
    out[1] = 0.5 * (qw * w1 + qy * w3 - qz * w2)
    out[2] = 0.5 * (qw * w2 + qz * w1 - qx * w3)
    out[3] = 0.5 * (qw * w3 + qx * w2 - qy * w1)
    # Euler's equations, I2 = I1, torque M g l (g2, -g1, 0)
    out[4] = ((i1 - i3) * w2 * w3 + mgl * g2) / i1
    out[5] = ((i3 - i1) * w3 * w1 - mgl * g1) / i1
    out[6] = 0.0


def model(I1: float, I3: float, Mgl: float) -> OdeModel:
    """Compiled heavy symmetric top, state ``(q_w, q_x, q_y, q_z, ω1, ω2, ω3)``."""
    return OdeModel(name="heavy_top", columns=COLUMNS, rhs=rhs,
                    params=np.array([I1, I3, Mgl], dtype=np.float64))


SPIN_FREE_COLUMNS = ("p_w", "p_x", "p_y", "p_z", "Omega_1", "Omega_2")

# params = (I1, I3, Mgl, omega3, Mgl / I1, I3 omega3 / I1)


@numba.njit(cache=True, error_model="numpy")  # inlined in its driver: a 0 divisor gives inf
def spin_free_rhs(t, y, params, out):
    """F' (quaternion p, body -> space at ψ = 0) and its angular velocity Ω = (Ω1, Ω2, 0)
    in F' axes.  Euler's equations in the frame F' (which turns at Ω, not at ω):
    I1 Ω̇ = τ' − Ω × L' with L' = I1 Ω + I3 ω3 e3, so I1 Ω̇1 = M g l g2 − I3 ω3 Ω2 and
    I1 Ω̇2 = −M g l g1 + I3 ω3 Ω1 (g: the space vertical in F' axes)."""
    torque, spin = params[4], params[5]  # M g l / I1 and I3 ω3 / I1: one division per call
    pw, px, py, pz = y[0], y[1], y[2], y[3]
    o1, o2 = y[4], y[5]
    two_over_n2 = 2.0 / (pw * pw + px * px + py * py + pz * pz)
    g1 = (px * pz - pw * py) * two_over_n2
    g2 = (py * pz + pw * px) * two_over_n2
    out[0] = -0.5 * (px * o1 + py * o2)
    out[1] = 0.5 * (pw * o1 - pz * o2)
    out[2] = 0.5 * (pw * o2 + pz * o1)
    out[3] = 0.5 * (px * o2 - py * o1)
    out[4] = torque * g2 - spin * o2
    out[5] = spin * o1 - torque * g1


def spin_free_model(I1: float, I3: float, Mgl: float, omega3: float) -> OdeModel:
    """The top in the non-spinning frame F', state ``(p_w, p_x, p_y, p_z, Ω1, Ω2)``;
    params ``(I1, I3, Mgl, ω3, Mgl/I1, I3 ω3/I1)`` (the last two are what the equations use)."""
    return OdeModel(name="heavy_top_spin_free", columns=SPIN_FREE_COLUMNS, rhs=spin_free_rhs,
                    params=np.array([I1, I3, Mgl, omega3, Mgl / I1, I3 * omega3 / I1],
                                    dtype=np.float64), specialize=True)


def spin_free_initial_state(theta, theta_dot, phi_dot):
    """F' = the body frame at t = 0 (φ = ψ = 0): Ω = (θ̇, φ̇ sin θ)."""
    return np.concatenate([euler_to_quaternion(0.0, theta, 0.0),
                           [theta_dot, phi_dot * math.sin(theta)]])


def body_state(t, y, omega3):
    """Spin-free states ``y`` (N, 6) at times ``t`` -> the body state (N, 7) of :func:`rhs`.

    The body frame is F' turned by χ = ω3 t about e3: q = p ⊗ (cos χ/2, 0, 0, sin χ/2)
    and ω = R_z(−χ) Ω + ω3 e3."""
    t = np.asarray(t, dtype=np.float64)
    p = y[:, :4]
    c, s = np.cos(0.5 * omega3 * t), np.sin(0.5 * omega3 * t)
    q = np.column_stack([p[:, 0] * c - p[:, 3] * s, p[:, 1] * c + p[:, 2] * s,
                         p[:, 2] * c - p[:, 1] * s, p[:, 3] * c + p[:, 0] * s])
    cx, sx = np.cos(omega3 * t), np.sin(omega3 * t)
    o1, o2 = y[:, 4], y[:, 5]
    return np.column_stack([q, cx * o1 + sx * o2, cx * o2 - sx * o1,
                            np.full(t.shape, float(omega3))])


REDUCED_COLUMNS = ("w", "w_dot", "phi", "psi")

# params = (I1, I3, Mgl, omega3, k0, k1, k2, B, a)


@numba.njit(cache=True, error_model="numpy")
def reduced_rhs(t, y, params, out):
    """Lagrange's reduction in w = 1 − cos θ: ẇ² = g(w) (the energy integral with p_φ and
    p_ψ eliminated), so ẅ = g'(w)/2 = k0 + k1 w − k2 w², a polynomial with no singular
    point; φ̇ = (B + a w) / (w (2 − w)) and ψ̇ = ω3 − (1 − w) φ̇ are quadratures
    (Goldstein 5.62-5.71 in w).  Singular only where the axis reaches the vertical."""
    omega3, k0, k1, k2, b_, a = (params[3], params[4], params[5], params[6], params[7],
                                 params[8])
    w, w_dot = y[0], y[1]
    phi_dot = (b_ + a * w) / (w * (2.0 - w))
    out[0] = w_dot
    out[1] = k0 + (k1 - k2 * w) * w
    out[2] = phi_dot
    out[3] = omega3 - (1.0 - w) * phi_dot


def reduced_model(I1: float, I3: float, Mgl: float, omega3: float, A: float,
                  B: float) -> OdeModel:
    """The top reduced to its nutation ``(w, ẇ)`` plus the angles ``(φ, ψ)``, with
    A = α − β and B = b − a of the initial state
    (:class:`~reportgen.core.heavy_top_theory.TopConstants`).  g(w) = w (2 − w)(A + β w)
    − (B + a w)² gives ẅ = (A − a B) + (2β − A − a²) w − (3/2) β w²."""
    a, beta = I3 * omega3 / I1, 2.0 * Mgl / I1
    return OdeModel(name="heavy_top_reduced", columns=REDUCED_COLUMNS, rhs=reduced_rhs,
                    specialize=True,
                    params=np.array([I1, I3, Mgl, omega3, A - a * B, 2.0 * beta - A - a * a,
                                     1.5 * beta, B, a], dtype=np.float64))


def reduced_initial_state(theta, theta_dot):
    """(w, ẇ, φ, ψ) at t = 0: w = 2 sin²(θ/2), ẇ = θ̇ sin θ, φ = ψ = 0."""
    return np.array([2.0 * math.sin(0.5 * theta) ** 2, theta_dot * math.sin(theta), 0.0, 0.0])


def reduced_body_state(y, params):
    """Reduced states ``y`` (N, 4) -> the body state (N, 7) of :func:`rhs`:
    q from (φ, θ, ψ) (:func:`euler_to_quaternion`) and ω from Goldstein (4.87),
    ω1 = φ̇ sin θ sin ψ + θ̇ cos ψ, ω2 = φ̇ sin θ cos ψ − θ̇ sin ψ, ω3."""
    omega3, b_, a = params[3], params[7], params[8]
    w, w_dot, phi, psi = (y[:, i] for i in range(4))
    half_s, half_c = np.sqrt(0.5 * w), np.sqrt(1.0 - 0.5 * w)  # sin θ/2, cos θ/2
    sin_theta = 2.0 * half_s * half_c
    theta_dot = w_dot / sin_theta
    phi_dot = (b_ + a * w) / (w * (2.0 - w))
    plus, minus = 0.5 * (phi + psi), 0.5 * (phi - psi)
    q = np.column_stack([half_c * np.cos(plus), half_s * np.cos(minus), half_s * np.sin(minus),
                         half_c * np.sin(plus)])
    cs, sn = np.cos(psi), np.sin(psi)
    return np.column_stack([q, phi_dot * sin_theta * sn + theta_dot * cs,
                            phi_dot * sin_theta * cs - theta_dot * sn,
                            np.full(w.shape, float(omega3))])


# ----------------------------------------------------------------- quaternions
def euler_to_quaternion(phi, theta, psi):
    """Unit quaternion (w, x, y, z) of the z-x-z rotation R = Rz(φ) Rx(θ) Rz(ψ)."""
    c, s = math.cos(0.5 * theta), math.sin(0.5 * theta)
    return np.array([c * math.cos(0.5 * (phi + psi)), s * math.cos(0.5 * (phi - psi)),
                     s * math.sin(0.5 * (phi - psi)), c * math.sin(0.5 * (phi + psi))])


def initial_state(theta, theta_dot, phi_dot, omega3):
    """State y0 at φ = ψ = 0: ω1 = θ̇, ω2 = φ̇ sin θ (Goldstein eq. 4.87 with ψ = 0)."""
    q = euler_to_quaternion(0.0, theta, 0.0)
    return np.concatenate([q, [theta_dot, phi_dot * math.sin(theta), omega3]])



def rotation_matrices(q):
    """R(q) for unit quaternions q, shape (N, 4) -> (N, 3, 3)."""
    w, x, y, z = (q[:, i] for i in range(4))
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=1),
    ], axis=1)


def invariants(y, I1, I3, Mgl):
    """Energy E, p_φ = L·ẑ and p_ψ = I3 ω3 along a trajectory y, shape (N, 7)."""
    q = y[:, :4] / np.linalg.norm(y[:, :4], axis=1)[:, None]
    w1, w2, w3 = y[:, 4], y[:, 5], y[:, 6]
    zb = rotation_matrices(q)[:, 2, :]  # space ẑ in body axes
    energy = 0.5 * I1 * (w1**2 + w2**2) + 0.5 * I3 * w3**2 + Mgl * zb[:, 2]
    p_phi = I1 * (w1 * zb[:, 0] + w2 * zb[:, 1]) + I3 * w3 * zb[:, 2]
    return {"energy": energy, "p_phi": p_phi, "p_psi": I3 * w3}



def euler_angle_rhs(I1: float, I3: float, Mgl: float):
    """The textbook script's right-hand side, the peer ``reportgen bench`` times us against:
    Lagrange's equations of L = I1/2 (θ̇² + φ̇² sin²θ) + I3/2 (ψ̇ + φ̇ cos θ)² − M g l cos θ
    (Goldstein §5.7) for ``y = (θ, φ, ψ, θ̇, φ̇, ψ̇)``, in plain Python as a user writes it
    for ``scipy.integrate.solve_ivp``.  Singular at sin θ = 0."""

    def f(t, y):
        theta, _phi, _psi, theta_dot, phi_dot, psi_dot = y
        s, c = math.sin(theta), math.cos(theta)
        omega3 = psi_dot + phi_dot * c
        theta_ddot = (I1 * phi_dot**2 * s * c - I3 * omega3 * phi_dot * s + Mgl * s) / I1
        phi_ddot = (I3 * omega3 * theta_dot - 2.0 * I1 * phi_dot * theta_dot * c) / (I1 * s)
        psi_ddot = phi_dot * theta_dot * s - phi_ddot * c
        return [theta_dot, phi_dot, psi_dot, theta_ddot, phi_ddot, psi_ddot]

    return f
