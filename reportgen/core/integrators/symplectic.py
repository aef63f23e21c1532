"""Symplectic methods: compositions of Stormer-Verlet, and Gauss-Legendre collocation.

A composition method is the list of weights gamma_i of Verlet sub-steps,
Phi_h = S(gamma_m h) o ... o S(gamma_1 h); symmetric weights give a symmetric method.

References
----------
.. [1] H. Yoshida, "Construction of higher order symplectic integrators",
       Phys. Lett. A 150 (1990) 262-268: triple jump (eq. 4.14-4.17) and the
       6th-order (Table 1, solution A) and 8th-order (Table 2, solution A) weights.
.. [2] Hairer, Lubich, Wanner, *Geometric Numerical Integration*, 2nd ed. (2006),
       II.4 (compositions), II.1.3 (Gauss collocation), VI.4 (symplecticity).
.. [3] Hairer & Wanner, *Solving ODEs II*, IV.5 Table 5.1-5.2 (Gauss tableaus).
"""

from __future__ import annotations

import math

import numpy as np

from .base import Method
from .explicit_rk import FixedStepRun


class Composition(Method):
    """Symmetric composition of kick-drift-kick Stormer-Verlet with weights ``gammas``."""

    symplectic = True
    symmetric = True
    needs_separable = True
    gammas: tuple[float, ...]

    def drift_kick_weights(self) -> tuple[np.ndarray, np.ndarray]:
        """Drift weights a_i = gamma_i and kick weights (half-kicks of neighbours merged)."""
        g = np.asarray(self.gammas, dtype=np.float64)
        kicks = np.empty(g.size + 1)
        kicks[0] = 0.5 * g[0]
        kicks[1:-1] = 0.5 * (g[:-1] + g[1:])
        kicks[-1] = 0.5 * g[-1]
        return g, kicks

    def start(self, kern, model, y0, t_eval, Y, rtol, atol, h, max_steps=None):
        a, bk = self.drift_kick_weights()
        return FixedStepRun(kern.splitting_fixed, (a, bk, model.separable.n),
                            t_eval, Y, y0, h, model.params)


def _palindrome(w: list[float]) -> tuple[float, ...]:
    """Yoshida's listing w_m, ..., w_1, w_0, w_1, ..., w_m with w_0 = 1 - 2 sum(w_i)."""
    w0 = 1.0 - 2.0 * math.fsum(w)
    return tuple(reversed(w)) + (w0,) + tuple(w)


class Verlet(Composition):
    name, label, order = "verlet", "Stormer-Verlet (numba)", 2
    gammas = (1.0,)


class Yoshida4(Composition):
    # triple jump [1] eq. (4.17): w1 = 1 / (2 - 2^(1/3)), w0 = -2^(1/3) w1
    name, label, order = "yoshida4", "Yoshida 4 (numba)", 4
    _w1 = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
    gammas = (_w1, 1.0 - 2.0 * _w1, _w1)


class Yoshida6(Composition):
    # [1] Table 1, solution A (w1, w2, w3)
    name, label, order = "yoshida6", "Yoshida 6 (numba)", 6
    gammas = _palindrome([-0.117767998417887e1, 0.235573213359357e0, 0.784513610477560e0])


class Yoshida8(Composition):
    # [1] Table 2, solution A (w1 ... w7)
    name, label, order = "yoshida8", "Yoshida 8 (numba)", 8
    gammas = _palindrome([
        -0.161582374150097e1, -0.244699182370524e1, -0.716989419708120e-2,
        0.244002732616735e1, 0.157739928123617e0, 0.182020630970714e1,
        0.104242620869991e1])


class GaussLegendre(Method):
    """s-stage Gauss-Legendre collocation: order 2s, A-stable, symplectic, symmetric."""

    implicit = True
    symplectic = True
    symmetric = True
    A: np.ndarray
    b: np.ndarray
    c: np.ndarray
    max_newton_iter = 50

    def start(self, kern, model, y0, t_eval, Y, rtol, atol, h, max_steps=None):
        A = np.ascontiguousarray(self.A, dtype=np.float64)
        dvec = np.linalg.solve(A.T, self.b)  # d^T = b^T A^{-1}, [3] IV.8 eq. (8.2b)
        run = FixedStepRun(kern.collocation_fixed, (A, np.asarray(self.c, float), dvec),
                           t_eval, Y, y0, h, model.params)
        run.tail_args = lambda: (self.max_newton_iter,)
        return run


_r3 = math.sqrt(3.0)
_r15 = math.sqrt(15.0)


class Gauss4(GaussLegendre):
    name, label, order = "gauss4", "Gauss-Legendre 2-stage (numba, implicit)", 4
    c = np.array([0.5 - _r3 / 6, 0.5 + _r3 / 6])
    A = np.array([[0.25, 0.25 - _r3 / 6], [0.25 + _r3 / 6, 0.25]])
    b = np.array([0.5, 0.5])


class Gauss6(GaussLegendre):
    name, label, order = "gauss6", "Gauss-Legendre 3-stage (numba, implicit)", 6
    c = np.array([0.5 - _r15 / 10, 0.5, 0.5 + _r15 / 10])
    A = np.array([
        [5 / 36, 2 / 9 - _r15 / 15, 5 / 36 - _r15 / 30],
        [5 / 36 + _r15 / 24, 2 / 9, 5 / 36 - _r15 / 24],
        [5 / 36 + _r15 / 30, 2 / 9 + _r15 / 15, 5 / 36]])
    b = np.array([5 / 18, 4 / 9, 5 / 18])
