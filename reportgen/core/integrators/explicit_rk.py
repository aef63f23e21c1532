"""Explicit Runge-Kutta methods: each class is its tableau; one compiled routine steps.

References
----------
.. [1] Hairer, Norsett, Wanner, *Solving ODEs I*, 2nd ed. (1993): II.1 (classic RK4,
       Table 1.2), II.5 (Dormand-Prince 5(4), Table 5.2), II.10 (DOP853).
.. [2] Dormand & Prince, J. Comput. Appl. Math. 6 (1980) 19-26.
"""

from __future__ import annotations

import math

import numpy as np

from . import _dop853_coefficients as dop853c
from .base import Method, Run


def _fixed_steps(t_eval: np.ndarray, h: float) -> np.ndarray:
    """Steps per output interval: the smallest count with step <= h (as the kernels do,
    :func:`.compiled.steps_in`), as floats: exact up to 2^53, and a count beyond any
    budget (a tiny h) stays a large number instead of overflowing an int."""
    dt = np.diff(t_eval)
    return np.maximum(1.0, np.ceil(dt / h * (1.0 - 1e-12)))


class FixedStepRun(Run):
    """Shared bookkeeping of the fixed-step kernels (they all take the same tail).

    Raises ValueError for a step ``h`` that is not positive and finite."""

    def __init__(self, kernel, head: tuple, t_eval, Y, y0, h, params):
        h = float(h)
        if not 0.0 < h < math.inf:
            raise ValueError(f"h: expected a positive finite step, got {h!r}")
        self.kernel, self.head = kernel, head
        self.t_eval, self.Y, self.h = t_eval, Y, h
        self.params = np.ascontiguousarray(params, dtype=np.float64)  # the callbacks' layout
        self.y = np.array(y0, dtype=np.float64)
        self.counters = np.zeros(3, dtype=np.int64)
        self.tfail = np.full(1, np.nan)
        Y[0] = self.y
        n = _fixed_steps(t_eval, h) if t_eval.size > 1 else np.ones(0)
        self.h_used = float(np.max(np.diff(t_eval) / n)) if n.size else h
        # steps to reach t_eval[j] (floats; compared with the budget before any is taken)
        self.steps_before = np.concatenate([[0.0], np.cumsum(n)])

    def advance(self, i0: int, i1: int) -> int:
        i0 = max(i0, 1)
        if i1 <= i0:
            return 0
        status = self.kernel(*self.head, self.t_eval, i0, i1, self.Y, self.y, self.h,
                             self.params, self.counters, self.tfail, *self.tail_args())
        self.t_fail = float(self.tfail[0])
        return int(status)

    def tail_args(self) -> tuple:
        return ()


class ExplicitRungeKutta(Method):
    """Fixed-step explicit RK defined by ``A``, ``b``, ``c`` (Butcher tableau)."""

    A: np.ndarray
    b: np.ndarray
    c: np.ndarray

    def start(self, kern, model, y0, t_eval, Y, rtol, atol, h, max_steps=None):
        A = np.ascontiguousarray(self.A, dtype=np.float64)
        head = (A, np.asarray(self.b, float), np.asarray(self.c, float), self.b.size)
        return FixedStepRun(kern.erk_fixed, head, t_eval, Y, y0, h, model.params)


class RK4(ExplicitRungeKutta):
    name, label, order = "rk4", "RK4 classic (numba, fixed step)", 4
    A = np.array([[0, 0, 0, 0], [0.5, 0, 0, 0], [0, 0.5, 0, 0], [0, 0, 1.0, 0]])
    b = np.array([1 / 6, 1 / 3, 1 / 3, 1 / 6])
    c = np.array([0, 0.5, 0.5, 1.0])


class EmbeddedRungeKutta(Method):
    """Adaptive explicit RK: tableau + error weights ``E`` + dense-output matrix ``P``.

    ``dense_kind`` 0: y(t + x h) = y + h K^T P [x, x^2, ...] (RK45);
    1: DOP853 interpolant with extra stages ``A[n_stages + 1:]`` and matrix ``D``.
    ``E``/``E3`` have ``n_stages + 1`` entries (the last weights f(t + h, y_new)).
    """

    adaptive = True
    #: stepped by the driver with this tableau written out (:mod:`._dop853_unrolled`)
    unrolled = False
    error_estimator_order: int
    n_stages: int
    dense_kind: int
    A: np.ndarray
    b: np.ndarray
    c: np.ndarray
    E: np.ndarray
    E3: np.ndarray
    P: np.ndarray

    def start(self, kern, model, y0, t_eval, Y, rtol, atol, h, max_steps=10_000_000):
        return EmbeddedRun(self, kern, model, y0, t_eval, Y, rtol, atol, max_steps)

    def driver_args(self) -> tuple:
        """The method's leading arguments of :func:`.compiled.erk_adaptive`, after ``rhs``:
        ``(A, b, c, E, E3, P, n_stages, dense_kind, err_exp, order)``."""
        return (np.ascontiguousarray(self.A, dtype=float), np.asarray(self.b, float),
                np.asarray(self.c, float), np.asarray(self.E, float),
                np.asarray(self.E3, float), np.ascontiguousarray(self.P, dtype=float),
                self.n_stages, self.dense_kind, -1.0 / (self.error_estimator_order + 1),
                self.order)

    def as_fixed_step(self) -> ExplicitRungeKutta:
        """The same tableau without error control (used by the convergence tests)."""
        s = self.n_stages
        return type(self.name + "_fixed", (ExplicitRungeKutta,), dict(
            name=self.name + "_fixed", label=self.label + " fixed step", order=self.order,
            A=np.ascontiguousarray(self.A[:s, :s]), b=np.asarray(self.b[:s]),
            c=np.asarray(self.c[:s])))()


class EmbeddedRun(Run):
    def __init__(self, method, kern, model, y0, t_eval, Y, rtol, atol, max_steps):
        m = method
        d = y0.size
        n_rows = m.A.shape[0] if m.dense_kind == 1 else m.n_stages + 1
        self.kern, self.m, self.t_eval, self.Y = kern, m, t_eval, Y
        self.args = None if m.unrolled else m.driver_args()
        self.y = np.array(y0, dtype=np.float64)
        self.y_old = self.y.copy()
        self.K = np.zeros((n_rows, d))
        self.F = np.zeros((7 if m.dense_kind == 1 else 1, d))
        self.state = np.array([t_eval[0], 0.0, t_eval[0], 0.0, 0.0])
        self.counters = np.zeros(3, dtype=np.int64)
        self.params = np.ascontiguousarray(model.params, dtype=np.float64)
        self.rtol, self.atol, self.max_steps = rtol, atol, max_steps

    def advance(self, i0, i1):
        tail = (self.t_eval, i0, i1, self.Y, self.y, self.y_old, self.K, self.F, self.state,
                self.counters, self.params, float(self.rtol), float(self.atol),
                int(self.max_steps))
        if self.m.unrolled:
            status = self.kern.dop853_adaptive(*tail)
        else:
            status = self.kern.erk_adaptive(*self.args, *tail)
        self.t_fail = float(self.state[0])
        return int(status)


class RK45(EmbeddedRungeKutta):
    """Dormand-Prince 5(4), FSAL, 4th-order dense output (Shampine 1986), tableau as scipy."""

    name, label, order = "rk45", "Dormand–Prince RK45 (numba)", 5
    error_estimator_order, n_stages, dense_kind = 4, 6, 0
    c = np.array([0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1])
    A = np.array([
        [0, 0, 0, 0, 0, 0],
        [1 / 5, 0, 0, 0, 0, 0],
        [3 / 40, 9 / 40, 0, 0, 0, 0],
        [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
        [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
        [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0]])
    b = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
    E = np.array([-71 / 57600, 0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
    E3 = np.zeros(7)
    P = np.array([
        [1, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
        [0, 0, 0, 0],
        [0, 131558114200 / 32700410799, -68118460800 / 10900136933,
         87487479700 / 32700410799],
        [0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
        [0, 127303824393 / 49829197408, -318862633887 / 49829197408,
         701980252875 / 199316789632],
        [0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
        [0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423]])


class DOP853(EmbeddedRungeKutta):
    """Dormand-Prince 8(5,3) with the 7th-order dense output of Hairer's dop853.f."""

    name, label, order = "dop853", "DOP853 (numba)", 8
    unrolled = True
    error_estimator_order, n_stages, dense_kind = 7, dop853c.N_STAGES, 1
    A = dop853c.A
    b = dop853c.B
    c = dop853c.C
    E = dop853c.E5
    E3 = dop853c.E3
    P = dop853c.D


assert math.isclose(RK4.b.sum(), 1.0) and math.isclose(DOP853.b.sum(), 1.0)
