r"""The heavy symmetric top: compiled equations of motion and its conserved quantities.

The attitude is a unit quaternion ``q`` (body -> space) and the body angular
velocity ``omega``; the state is ``y = (q_w, q_x, q_y, q_z, omega_1, omega_2,
omega_3)``.  Euler's equations with the gravity torque
``tau = l e3 x (-M g z) = M g l (g2, -g1, 0)`` (``g`` = the space vertical in
body axes) and ``q' = q (x) (0, omega) / 2`` have no coordinate singularity:
the sleeping top (θ = 0) is an ordinary point.  θ, φ, ψ (Goldstein's z-x-z
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

