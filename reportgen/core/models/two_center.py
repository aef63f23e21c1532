r"""Euler's problem of two fixed centres in the plane (lecture notes §7, eqs. 7.46–7.61).

A test particle moves in V = −μ/r1 − μ/r2 (per unit mass) of two equal masses fixed
at C1 = (−a, 0) and C2 = (+a, 0); r1, r2 are the distances to them.  In elliptic
coordinates ξ = (r1 + r2)/2a ≥ 1, η = (r1 − r2)/2a ∈ [−1, 1] (x = a ξ η,
y = ±a √((ξ² − 1)(1 − η²))) the Hamilton–Jacobi equation separates:

    (ξ² − 1) p_ξ² − 4 a μ ξ − 2 a² E ξ² = β = −(1 − η²) p_η² − 2 a² E η²      (7.59)

In Cartesian form the second constant is (checked numerically in the tests)

    C = L1 L2 + 2 a μ (cos θ1 − cos θ2),   cos θ1 = (x + a)/r1,  cos θ2 = (x − a)/r2,

with L_i = (r − C_i) × v the angular momenta about each centre; β = −C − 2 a² E.

References
----------
.. [1] Lecture notes §7, eqs. (7.46)–(7.61).
.. [2] Whittaker, E. T., *A Treatise on the Analytical Dynamics of Particles and Rigid
       Bodies*, 4th ed. (1937), §50 (Euler's problem of two centres).
.. [3] Pars, L. A., *A Treatise on Analytical Dynamics* (1965), §14.7.
.. [4] Waalkens, H., Dullin, H. R., Richter, P. H., The problem of two fixed centers:
       bifurcations, actions, monodromy, *Physica D* 196, 265–310 (2004): the names of
       the orbit classes (after Charlier, *Die Mechanik des Himmels* (1902)): satellite
       (about one centre), planetary (round both), lemniscate (through the segment
       between them).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..model import OdeModel, Separable, SurfaceOfSection

# params = (mu, a)
COLUMNS = ("x", "y", "vx", "vy")


# inlined into its callers: see "Helpers" in reportgen.core.model
@numba.njit(cache=True, inline="always")
def _accel(x, y, params, out):
    mu, a = params[0], params[1]
    d1x, d2x = x + a, x - a
    r1s = d1x * d1x + y * y
    r2s = d2x * d2x + y * y
    c1 = mu / (r1s * math.sqrt(r1s))
    c2 = mu / (r2s * math.sqrt(r2s))
    out[0] = -c1 * d1x - c2 * d2x
    out[1] = -(c1 + c2) * y


@numba.njit(cache=True, error_model="numpy")  # inlined in its driver: a 0 divisor gives inf
def rhs(t, y, params, out):
    out[0] = y[2]
    out[1] = y[3]
    _accel(y[0], y[1], params, out[2:])


@numba.njit(cache=True)
def drift(p, params, out):
    out[0] = p[0]
    out[1] = p[1]


@numba.njit(cache=True)
def kick(q, params, out):
    _accel(q[0], q[1], params, out)


def model(mu: float, a: float) -> OdeModel:
    return OdeModel(name="two fixed centres", columns=COLUMNS, rhs=rhs,
                    params=np.array([mu, a]), separable=Separable(n=2, drift=drift, kick=kick),
                    specialize=True)


@numba.njit(cache=True)
def axis_factors(t, y, params, out):
    """The surface of section y = 0 (the line through the centres): its one factor."""
    out[0] = y[1]


#: the line through the centres, y = 0, crossed with ẏ > 0
AXIS_SECTION = SurfaceOfSection(factors=axis_factors, count=1)


def separation_constant_on_axis(x, vx, E, mu, a):
    """C at a point of the line y = 0 from x, ẋ and the energy E (ẏ² = 2(E − V) − ẋ²).

    On y = 0, L1 L2 = (x² − a²) ẏ² and cos θ1 − cos θ2 = sgn(x + a) − sgn(x − a), which is
    2 between the centres and 0 outside, so (7.59 in Cartesian form)

        C = (x² − a²) (2 (E + μ/|x + a| + μ/|x − a|) − ẋ²) + 4 a μ [|x| < a].

    The crossings of one orbit with the line lie on the curve C(x, ẋ) = C of the orbit:
    its surface of section y = 0 is a level curve of this function.

    Returns
    -------
    C, vy2 : ndarray
        C, and ẏ² (negative outside the region the energy allows).
    """
    x, vx = np.asarray(x, dtype=np.float64), np.asarray(vx, dtype=np.float64)
    vy2 = 2.0 * (E + mu / np.abs(x + a) + mu / np.abs(x - a)) - vx * vx
    between = np.abs(x) < a
    return (x * x - a * a) * vy2 + 4.0 * a * mu * between, vy2


def distances(x, y, a):
    """(r1, r2): distances to C1 = (−a, 0) and C2 = (+a, 0)."""
    return np.hypot(np.asarray(x) + a, y), np.hypot(np.asarray(x) - a, y)


def energy(x, y, vx, vy, mu, a):
    """E = v²/2 − μ/r1 − μ/r2 per unit mass."""
    r1, r2 = distances(x, y, a)
    return 0.5 * (np.asarray(vx) ** 2 + np.asarray(vy) ** 2) - mu / r1 - mu / r2


def separation_constant(x, y, vx, vy, mu, a):
    """C = L1 L2 + 2 a μ ((x + a)/r1 − (x − a)/r2), conserved (7.59 in Cartesian form)."""
    x, y, vx, vy = (np.asarray(v, dtype=np.float64) for v in (x, y, vx, vy))
    r1, r2 = distances(x, y, a)
    L1 = (x + a) * vy - y * vx
    L2 = (x - a) * vy - y * vx
    return L1 * L2 + 2.0 * a * mu * ((x + a) / r1 - (x - a) / r2)


def elliptic_coordinates(x, y, a):
    """(ξ, η) = ((r1 + r2)/2a, (r1 − r2)/2a)."""
    r1, r2 = distances(x, y, a)
    return (r1 + r2) / (2 * a), (r1 - r2) / (2 * a)


def beta(E, C, a):
    """The separation constant β of (7.59) from E and C: β = −C − 2 a² E."""
    return -C - 2.0 * a * a * E


def coordinate_bounds(E, C, mu, a):
    """Region of the motion from the separated equations (7.59).

    η: (1 − η²) p_η² = −β − 2a²E η² ≥ 0;  ξ: (ξ² − 1) p_ξ² = 2a²E ξ² + 4aμ ξ + β ≥ 0.

    Returns
    -------
    dict with ``beta``, ``xi_min``, ``xi_max`` (inf if unbounded) and ``eta_abs_min``,
    ``eta_abs_max`` (|η| range), and ``family``, named as in the literature (Charlier,
    *Die Mechanik des Himmels* (1902); Waalkens, Dullin & Richter, Physica D 196 (2004)):

    * "satellite": β > 0, |η| ≥ η* — about one centre;
    * "planetary": β ≤ 0 and q(1) = 2a²E + 4aμ + β < 0 — η free, ξ between two roots
      > 1: round both centres (like a planet round a binary), never on the segment;
    * "lemniscate": β ≤ 0 and q(1) ≥ 0 — η free, ξ from 1: through the segment between
      the centres, round them in alternating senses;
    * "unbound": E ≥ 0.
    """
    b = beta(E, C, a)
    out = {"beta": b}
    # η range
    if E < 0:
        eta_star2 = b / (2 * a * a * -E)
        if b > 0:
            out.update(eta_abs_min=math.sqrt(min(eta_star2, 1.0)), eta_abs_max=1.0)
        else:
            out.update(eta_abs_min=0.0, eta_abs_max=1.0)
    elif E > 0:
        lim2 = -b / (2 * a * a * E)
        out.update(eta_abs_min=0.0, eta_abs_max=math.sqrt(min(max(lim2, 0.0), 1.0)))
    else:
        out.update(eta_abs_min=0.0, eta_abs_max=1.0)
    # ξ range: roots of 2a²E ξ² + 4aμ ξ + β
    A, B = 2 * a * a * E, 4 * a * mu
    if E < 0:
        disc = B * B - 4 * A * b
        sq = math.sqrt(max(disc, 0.0))
        roots = sorted(((-B + sq) / (2 * A), (-B - sq) / (2 * A)))
        out.update(xi_min=max(1.0, roots[0]), xi_max=roots[1])
    else:
        out.update(xi_min=1.0, xi_max=math.inf)
    if E >= 0:
        out["family"] = "unbound"
    elif b > 0:
        out["family"] = "satellite"
    elif A + B + b < 0:  # q(1) < 0: ξ ≥ ξ_min > 1
        out["family"] = "planetary"
    else:
        out["family"] = "lemniscate"
    return out


def closest_approach_bound(E, C, mu, a):
    """Lower bound of min(r1, r2) over the whole motion: a (ξ_min − |η|_max).

    min(r1, r2) = a (ξ − |η|), and (7.59) confines ξ ≥ ξ_min and |η| ≤ |η|_max (see
    :func:`coordinate_bounds`; for E ≥ 0, ξ_min is the root of 2a²Eξ² + 4aμξ + β, which
    increases for ξ ≥ 1).  Zero when the region holds a centre: in the fictitious time
    ξ and η oscillate independently, so such an orbit comes arbitrarily close to it."""
    bounds = coordinate_bounds(E, C, mu, a)
    xi_min = bounds["xi_min"]
    if E >= 0:
        A, B, b = 2 * a * a * E, 4 * a * mu, bounds["beta"]
        if A + B + b >= 0:
            xi_min = 1.0
        elif A == 0.0:
            xi_min = -b / B
        else:
            xi_min = (-B + math.sqrt(B * B - 4 * A * b)) / (2 * A)
    return max(0.0, a * (xi_min - bounds["eta_abs_max"]))


def coordinate_ellipse(xi, a, samples=400):
    """The coordinate line ξ = const (ξ > 1): the ellipse with foci at (±a, 0).

    x = a ξ cos θ, y = a √(ξ² − 1) sin θ for θ in [0, 2π] (from x = a ξ η,
    y = a √((ξ² − 1)(1 − η²)) with η = cos θ).

    Parameters
    ----------
    xi : float
        Elliptic coordinate ξ = (r1 + r2)/2a ≥ 1 of the line.
    a : float
        Half the distance between the centres [m].
    samples : int
        Number of points on the closed curve.

    Returns
    -------
    x, y : ndarray, shape (samples,)
        Points of the ellipse [m], the first equal to the last.
    """
    th = np.linspace(0.0, 2 * np.pi, samples)
    return a * xi * np.cos(th), a * np.sqrt(xi**2 - 1) * np.sin(th)


def coordinate_hyperbola(eta, a, xi_max, sign=1.0, samples=300):
    """One branch of the coordinate line η = const: a hyperbola with foci at (±a, 0).

    x = a ξ η, y = ±a √((ξ² − 1)(1 − η²)) for ξ from 1 (on the x-axis) to ``xi_max``.

    Parameters
    ----------
    eta : float
        Elliptic coordinate η = (r1 − r2)/2a in [−1, 1] of the line.
    a : float
        Half the distance between the centres [m].
    xi_max : float
        ξ of the ellipse where the branch is cut off.
    sign : float
        +1.0 for the branch in y ≥ 0, −1.0 for its mirror image in y ≤ 0.
    samples : int
        Number of points on the branch.

    Returns
    -------
    x, y : ndarray, shape (samples,)
        Points of the branch [m].
    """
    xi = np.linspace(1.0, xi_max, samples)
    return a * xi * eta, sign * a * np.sqrt((xi**2 - 1) * (1 - eta**2))
