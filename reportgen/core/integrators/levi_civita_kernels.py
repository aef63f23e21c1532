"""The compiled kernels of :class:`.regularized.LeviCivita` (Levi-Civita + Gauss–Legendre 6
on the regularized Kepler problem), kept apart so that importing the integrator registry
(``reportgen kinds``, ``validate``) loads no numba."""

from __future__ import annotations

import math

import numba
import numpy as np


@numba.njit(cache=True)
def _stage_weights(A, c, omega2, sigma, alpha, beta, M):
    """Gauss collocation's stages on the oscillator w' = v, v' = −ω² w, step ``sigma``.

    The stage equations W = w 1 + σ A V, V = v 1 − ω² σ A W are linear: eliminating V,
    (I + ω²σ² A²) W = w 1 + σ v A1 = w 1 + σ v c, so W_i = α_i w + β_i v with
    α = (I + μA²)⁻¹ 1 and β = σ (I + μA²)⁻¹ c, μ = ω²σ² (Gaussian elimination on the 3×3
    system: what the simplified Newton iteration with the exact Jacobian reaches in one
    iteration, without the iteration's round-off)."""
    s = c.size
    mu = omega2 * sigma * sigma  # M: work space, shape (s, s + 2)
    for i in range(s):
        for j in range(s):
            acc = 0.0
            for k in range(s):
                acc += A[i, k] * A[k, j]
            M[i, j] = mu * acc + (1.0 if i == j else 0.0)
        M[i, s] = 1.0
        M[i, s + 1] = sigma * c[i]
    for k in range(s):  # I + μA² is close to I for the steps used: no pivoting needed
        inv = 1.0 / M[k, k]
        for i in range(k + 1, s):
            f = M[i, k] * inv
            for j in range(k, s + 2):
                M[i, j] -= f * M[k, j]
    for i in range(s - 1, -1, -1):
        a = M[i, s]
        b = M[i, s + 1]
        for j in range(i + 1, s):
            a -= M[i, j] * alpha[j]
            b -= M[i, j] * beta[j]
        alpha[i] = a / M[i, i]
        beta[i] = b / M[i, i]


@numba.njit(cache=True)
def _step_matrix(A, b, c, omega2, sigma, alpha, beta, work, out):
    """One Gauss collocation step of size ``sigma`` on (LC) as numbers: ``out[:4]`` the
    matrix (r00, r01, r10, r11) taking each (w_k, w_k') to the new one, ``out[4:7]`` the
    coefficients (p, q, r) of the step's t increment σ Σ b_i |W_i|² (the quadrature of
    t' = |w|² on the stages) = p |w|² + 2 q w·w' + r |w'|²."""
    _stage_weights(A, c, omega2, sigma, alpha, beta, work)
    s = c.size
    # V_i = v − ω²σ (A W)_i; w_new = w + σ Σ b_i V_i, v_new = v − ω²σ Σ b_i W_i
    ba = 0.0
    bb = 0.0
    baa = 0.0
    bab = 0.0
    bbb = 0.0
    baA = 0.0
    bbA = 0.0
    for i in range(s):
        ba += b[i] * alpha[i]
        bb += b[i] * beta[i]
        baa += b[i] * alpha[i] * alpha[i]
        bab += b[i] * alpha[i] * beta[i]
        bbb += b[i] * beta[i] * beta[i]
        aa = 0.0
        ab = 0.0
        for j in range(s):
            aa += A[i, j] * alpha[j]
            ab += A[i, j] * beta[j]
        baA += b[i] * aa
        bbA += b[i] * ab
    k2 = omega2 * sigma * sigma
    out[0] = 1.0 - k2 * baA
    out[1] = sigma - k2 * bbA  # Σ b_i = 1
    out[2] = -omega2 * sigma * ba
    out[3] = 1.0 - omega2 * sigma * bb
    out[4] = sigma * baa
    out[5] = sigma * bab
    out[6] = sigma * bbb


@numba.njit(cache=True)
def _apply(m, u, out):
    """(w, w') = ``u`` through the step ``m`` of :func:`_step_matrix` into ``out``; the
    step's t increment."""
    ww = u[0] * u[0] + u[1] * u[1]
    wv = u[0] * u[2] + u[1] * u[3]
    vv = u[2] * u[2] + u[3] * u[3]
    for k in range(2):
        w = u[k]
        v = u[2 + k]
        out[k] = m[0] * w + m[1] * v
        out[2 + k] = m[2] * w + m[3] * v
    return m[4] * ww + 2.0 * m[5] * wv + m[6] * vv


@numba.njit(cache=True)
def _grid_state(u0, omega, phi, n, out):
    """(LC)'s (w, w') after n gauss6 steps: the step's matrix is a rotation of
    (w, w'/ω) by φ (it conserves ω²|w|² + |w'|², a quadratic invariant), so its n-th
    power is the rotation by nφ, evaluated directly rather than by n products (whose
    round-off would accumulate)."""
    ang = n * phi
    cs = math.cos(ang)
    sn = math.sin(ang)
    for k in range(2):
        w = u0[k]
        v = u0[2 + k]
        out[k] = cs * w + sn * v / omega
        out[2 + k] = -omega * sn * w + cs * v


@numba.njit(cache=True)
def lc_gauss6_outputs(A, b, c, h, ds, u0, t_out, i0, i1, Y, carry, max_steps):
    """gauss6 on (LC) at the fixed step ``ds`` from (w, w') = ``u0`` at t = ``t_out[0]``,
    the states at the physical times ``t_out[i0:i1]`` into ``Y`` (rows (w, w', t)).

    ``carry`` = (steps n taken, t_n, Kahan compensation of t_n) from the previous call.
    Each output t lies in a step [t_n, t_{n+1}]; its state is one gauss6 step of size σ
    from the grid state u_n, σ solved from t_n + τ(σ) = t (τ: the step's t increment,
    Newton with the slope |w|² at σ).  Returns 0 (ok), 1 (more than ``max_steps`` grid
    steps) or 2 (an output's σ did not converge)."""
    omega2 = -0.5 * h
    omega = math.sqrt(omega2)
    alpha = np.empty(c.size)
    beta = np.empty(c.size)
    work = np.empty((c.size, c.size + 2))
    grid = np.empty(7)
    m = np.empty(7)
    un = np.empty(4)
    nxt = np.empty(4)
    out = np.empty(4)
    _step_matrix(A, b, c, omega2, ds, alpha, beta, work, grid)
    # the step's rotation angle of (w, w'/ω): r00 = cos φ, r10 = −ω sin φ
    phi = math.atan2(-grid[2] / omega, grid[0])
    n = int(carry[0])
    tn = carry[1]
    comp = carry[2]
    _grid_state(u0, omega, phi, n, un)
    dt = _apply(grid, un, nxt)
    for j in range(i0, i1):
        target = t_out[j]
        while tn + dt < target:
            inc = dt - comp  # Kahan: t_n over ~1e6 steps stays at one rounding
            total = tn + inc
            comp = (total - tn) - inc
            tn = total
            n += 1
            if n > max_steps:
                carry[0] = n
                return 1
            _grid_state(u0, omega, phi, n, un)
            dt = _apply(grid, un, nxt)
        gap = (target - tn) + comp  # t_n − comp: the compensated sum
        # first guess: x = σ/ds on the quintic Hermite interpolant of t over the step
        # (t, t' = |w|², t'' = 2 w·w' at both ends; error O(ds⁶), gauss6's order)
        d0 = ds * (un[0] * un[0] + un[1] * un[1])
        d1 = ds * (nxt[0] * nxt[0] + nxt[1] * nxt[1])
        s0 = 2.0 * ds * ds * (un[0] * un[2] + un[1] * un[3])
        s1 = 2.0 * ds * ds * (nxt[0] * nxt[2] + nxt[1] * nxt[3])
        c3 = 10.0 * dt - 6.0 * d0 - 4.0 * d1 - 1.5 * s0 + 0.5 * s1
        c4 = -15.0 * dt + 8.0 * d0 + 7.0 * d1 + 1.5 * s0 - s1
        c5 = 6.0 * dt - 3.0 * d0 - 3.0 * d1 - 0.5 * s0 + 0.5 * s1
        x = gap / dt if dt > 0.0 else 0.0
        for _ in range(6):
            val = ((((c5 * x + c4) * x + c3) * x + 0.5 * s0) * x + d0) * x - gap
            slope = (((5.0 * c5 * x + 4.0 * c4) * x + 3.0 * c3) * x + s0) * x + d0
            if slope <= 0.0:
                break
            x -= val / slope
        sigma = x * ds
        ok = False
        for _ in range(30):
            _step_matrix(A, b, c, omega2, sigma, alpha, beta, work, m)
            tau = _apply(m, un, out)
            step = (tau - gap) / (out[0] * out[0] + out[1] * out[1])  # t' = |w|²
            if abs(step) <= 1e-14 * ds:  # t within 1e-14 ds |w|² of the output's
                ok = True
                break
            sigma -= step
        if not ok:
            carry[0] = n
            return 2
        for k in range(4):
            Y[j, k] = out[k]
        Y[j, 4] = target
    carry[0] = n
    carry[1] = tn
    carry[2] = comp
    return 0
