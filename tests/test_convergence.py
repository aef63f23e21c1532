"""Convergence order of every fixed-order method: slope of log(error) vs log(h).

Reference: the harmonic oscillator q'' = -omega^2 q has q = q0 cos(omega t) +
p0/omega sin(omega t), p = q' (any mechanics text, e.g. Landau & Lifshitz,
Mechanics, 3rd ed., sec. 21).  Orders from
Hairer-Norsett-Wanner I (RK4 II.1, DOP853 II.10, RK45 II.5), Yoshida (1990) and
Hairer-Lubich-Wanner, Geometric Numerical Integration II.1 (Gauss, order 2s).
"""


import numba
import numpy as np
import pytest

from reportgen.core.integrators import METHODS, integrate
from reportgen.core.integrators.explicit_rk import DOP853, RK45
from reportgen.core.integrators.kernels import kernels_for
from reportgen.core.model import OdeModel, Separable

OMEGA = 1.3  # params = (omega^2,)


@numba.njit(cache=True)
def osc_rhs(t, y, params, out):
    out[0] = y[1]
    out[1] = -params[0] * y[0]


@numba.njit(cache=True)
def osc_jac(t, y, params, out):
    out[0, 0] = 0.0
    out[0, 1] = 1.0
    out[1, 0] = -params[0]
    out[1, 1] = 0.0


@numba.njit(cache=True)
def osc_drift(p, params, out):
    out[0] = p[0]


@numba.njit(cache=True)
def osc_kick(q, params, out):
    out[0] = -params[0] * q[0]


def oscillator(omega=OMEGA):
    return OdeModel(name="oscillator", columns=("q", "p"), rhs=osc_rhs,
                    params=np.array([omega**2]), separable=Separable(1, osc_drift, osc_kick),
                    jac=osc_jac)


def oscillator_exact(t, q0, p0, omega=OMEGA):
    c, s = np.cos(omega * t), np.sin(omega * t)
    return np.column_stack([q0 * c + p0 / omega * s, -q0 * omega * s + p0 * c])


Y0 = np.array([1.0, 0.5])
T_END = 6.0
# step counts over [0, T_END] in each method's asymptotic regime, errors above round-off
STEP_COUNTS = {
    "rk4": [40, 80, 160, 320],
    "verlet": [100, 200, 400, 800],
    "yoshida4": [40, 80, 160, 320],
    "yoshida6": [24, 48, 96, 192],
    "yoshida8": [48, 64, 96, 128],
    "gauss4": [20, 40, 80, 160],
    "gauss6": [8, 12, 16, 24],
    "dop853_fixed": [8, 12, 16, 24],
    "rk45_fixed": [20, 40, 80, 160],
}


def final_error(name, n):
    t = np.array([0.0, T_END])
    exact = oscillator_exact(t, *Y0)[-1]
    if name.endswith("_fixed"):
        method = {"dop853_fixed": DOP853(), "rk45_fixed": RK45()}[name].as_fixed_step()
        Y = np.full((2, 2), np.nan)
        model = oscillator()
        method.start(kernels_for(model), model, Y0, t, Y, 0, 0, T_END / n).advance(0, 2)
        y = Y[-1]
    else:
        y = integrate(oscillator(), Y0, t, method=name, h=T_END / n).y[-1]
    return float(np.max(np.abs(y - exact)))


FIXED_ORDER = [name for name, m in METHODS.items() if not m.adaptive and not m.peer]


def test_every_fixed_step_method_is_covered():
    assert set(FIXED_ORDER) <= set(STEP_COUNTS)


@pytest.mark.parametrize("name", sorted(STEP_COUNTS))
def test_convergence_order(name):
    order = {"dop853_fixed": 8, "rk45_fixed": 5}.get(name) or METHODS[name].order
    ns = np.array(STEP_COUNTS[name], dtype=float)
    errs = np.array([final_error(name, int(n)) for n in ns])
    assert np.all(errs > 1e-13), errs  # still above round-off
    slope = np.polyfit(np.log(T_END / ns), np.log(errs), 1)[0]
    assert abs(slope - order) < 0.3, (name, slope, errs)
