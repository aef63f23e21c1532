"""The restricted three-body problem's claim-carrying sentences (see
:mod:`reportgen.scene.claims`; imported by :mod:`.claims`): its formulation, the Lagrange
points' Jacobi constants (found again by root finding), the gates of the zero-velocity
curves and whether the orbit is confined."""

from __future__ import annotations

import math

import numpy as np

from ...scene.claims import claim
from .claims import _cached, _full


def _lagrange_jacobi(mu: float) -> np.ndarray:
    """C at L1 … L5 for mass ratio μ, the collinear points by root finding of ∂Ω/∂x."""
    from scipy.optimize import brentq

    def dx(x):
        r1, r2 = abs(x + mu), abs(x - 1 + mu)
        return x - (1 - mu) * (x + mu) / r1**3 - mu * (x - 1 + mu) / r2**3

    def two_omega(x, y=0.0):
        return x * x + y * y + 2 * (1 - mu) / math.hypot(x + mu, y) \
            + 2 * mu / math.hypot(x - 1 + mu, y)

    eps = 1e-12
    L1 = brentq(dx, -mu + eps, 1 - mu - eps, xtol=1e-15)
    L2 = brentq(dx, 1 - mu + eps, 3.0, xtol=1e-15)
    L3 = brentq(dx, -3.0, -mu - eps, xtol=1e-15)
    C45 = 3.0 - mu * (1 - mu)
    return np.array([two_omega(L1), two_omega(L2), two_omega(L3), C45, C45])


def _restricted(data):
    r = data.config.restricted
    mu = float(r.mu)
    C = float(data.analysis["jacobi_constant"])
    return mu, C, _cached(data, "lagrange", lambda: _lagrange_jacobi(mu))


@claim("three_body restricted regularized", r"The runs? uses? the Thiele–Burrau variables")
def restricted_regularized(data) -> bool | str:
    """the run's record (each member's, for a family) says it ran in the regularized
    variables"""
    if data.sweep is not None:
        forms = [str(f) for f in np.asarray(data.sweep.labels.get("formulation", []))]
        return True if all(f == "regularized" for f in forms) else f"formulations {forms}"
    form = data.runs["main"].attrs.get("formulation")
    return True if form == "regularized" else f"the run's formulation is {form!r}"


@claim("three_body restricted cartesian", r"integrates the Cartesian equations of the rotating")
def restricted_cartesian(data) -> bool | str:
    """the run's record says it ran in the Cartesian variables"""
    form = data.runs["main"].attrs.get("formulation")
    return True if form == "cartesian" else f"the run's formulation is {form!r}"


def _gates(C, CL) -> str:
    if C <= CL[3]:
        return "everywhere"
    open_ = [f"L{k + 1}" for k in range(3) if C < CL[k]]
    if not open_:
        return "closed"
    return open_[0] if len(open_) == 1 else ", ".join(open_[:-1]) + " and " + open_[-1]


@claim("three_body restricted gates",
       r"gates open(?: at this level)?: |the zero-velocity curves open at L|the level forbids "
       r"no region")
def restricted_gates(data) -> bool | str:
    """the gates the printed region names are those whose Jacobi constant, found again by
    root finding, lies above C"""
    if _full(data):
        return True
    a = data.analysis
    mu = float(data.config.restricted.mu)
    C = float(a.get("poincare_jacobi", a.get("jacobi_constant", math.nan)))
    CL = _cached(data, "lagrange", lambda: _lagrange_jacobi(mu))
    found, said_ = _gates(C, CL), str(a.get("region", ""))
    return True if found == said_ else f"C = {C:.8g} opens {found!r}, the page says {said_!r}"


@claim("three_body restricted Lagrange table", r"L ?[₁1] \S+ \S+ \S+ (?:open|closed)\b")
def restricted_lagrange_table(data) -> bool | str:
    """each Lagrange point's stored C agrees with the one found again, to 1e-9, so that
    its open/closed at the level C is the true one"""
    a = data.analysis
    mu = float(data.config.restricted.mu)
    CL = _cached(data, "lagrange", lambda: _lagrange_jacobi(mu))
    stored = np.asarray(a["lagrange_points"]["jacobi"], dtype=float)
    C = float(a.get("poincare_jacobi", a.get("jacobi_constant", math.nan)))
    if np.any((C < stored) != (C < CL)) or not np.allclose(stored, CL, rtol=1e-9):
        return f"C at L1 … L5 found again {CL.tolist()}, stored {stored.tolist()}"
    return True


def _start_inner(mu, C, x, y) -> bool:
    """Whether the start reaches a primary along a straight segment through the allowed
    region (2Ω ≥ C): the regions about the primaries are star-shaped about them."""
    for px in (-mu, 1 - mu):
        s = np.linspace(0.0, 1.0, 2001)[:-1]
        xs, ys = x + s * (px - x), y + s * (0.0 - y)
        two_omega = xs**2 + ys**2 + 2 * (1 - mu) / np.hypot(xs + mu, ys) \
            + 2 * mu / np.hypot(xs - 1 + mu, ys)
        if np.all(two_omega >= C):
            return True
    return False


def _confined(data) -> bool:
    mu, C, CL = _restricted(data)
    x0, y0 = (float(v) for v in np.asarray(data.runs["main"].y)[0, :2])
    return bool(C > CL[1] and _start_inner(mu, C, x0, y0))


@claim("three_body restricted bound", r"encloses the region of its start")
def restricted_bound(data) -> bool | str:
    """C above the value at L2 (found again), and the start joined to a primary by a
    straight segment in the allowed region"""
    return True if _confined(data) else "the start's region reaches the outside"


@claim("three_body restricted not confined", r"not confined: the region of its start")
def restricted_not_confined(data) -> bool | str:
    """the start's region is not enclosed (C below L2's, or the start in the outer region)"""
    return True if not _confined(data) else "the start's region is enclosed"


@claim("three_body restricted between L1 and L2", r"between the values at L ?[₂2] \(")
def restricted_between(data) -> bool | str:
    """the family's C lies between the values at L2 and L1, found again"""
    a = data.analysis
    mu = float(data.config.restricted.mu)
    CL = _cached(data, "lagrange", lambda: _lagrange_jacobi(mu))
    C = float(a.get("poincare_jacobi", a.get("jacobi_constant", math.nan)))
    return True if CL[1] < C < CL[0] else f"C = {C:.8g}, L2 {CL[1]:.8g}, L1 {CL[0]:.8g}"
