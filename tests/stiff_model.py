"""A stiff scalar test problem (Prothero & Robinson 1974): y = cos t for any λ."""

import math

import numba
import numpy as np

from reportgen.core.model import OdeModel


@numba.njit(cache=True)
def rhs(t, y, params, out):
    # Prothero-Robinson: y' = -lam (y - cos t) - sin t, solution y = cos t
    out[0] = -params[0] * (y[0] - math.cos(t)) - math.sin(t)

@numba.njit(cache=True)
def jac(t, y, params, out):
    out[0, 0] = -params[0]

def model(lam):
    return OdeModel(name="prothero_robinson", columns=("y",), rhs=rhs, params=np.array([lam]), jac=jac)
