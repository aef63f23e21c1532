r"""Special functions shared by the closed-form solutions in ``reportgen.core``.

Thin, documented wrappers over :mod:`scipy.special` in the conventions the models use:
the elliptic *parameter* m = k² throughout (scipy's convention, DLMF §19.2 and §22.2),
and real arguments extended beyond scipy's principal ranges where a closed form needs it.

References
----------
.. [1] NIST DLMF §19.2 (Legendre's integrals F(φ | m), K(m)), §19.2(ii) (quasi-periodicity
       F(φ + nπ | m) = F(φ | m) + 2nK(m)), §22.2 and §22.20 (Jacobi sn, cn, dn).
.. [2] Abramowitz & Stegun §16–17 (parameter m, not modulus k).
"""

from __future__ import annotations

import math

import numpy as np
import scipy


def ellipk(m: float) -> float:
    """Complete elliptic integral of the first kind K(m) = F(π/2 | m), m = k² (DLMF 19.2.8).

    Returns ``math.inf`` for m ≥ 1 (the logarithmic singularity at m = 1).
    """
    m = float(m)
    return float(scipy.special.ellipk(m)) if m < 1.0 else math.inf


def ellipf(phi: float, m: float) -> float:
    """Incomplete elliptic integral of the first kind F(φ | m) for any real φ [rad].

    scipy's ``ellipkinc`` is used on the principal range |φ| ≤ π/2 and continued
    quasi-periodically, F(φ + nπ | m) = F(φ | m) + 2n K(m) (DLMF 19.2.10), so that
    F is the odd, increasing inverse of the Jacobi amplitude am(u | m) on the whole line.

    Parameters
    ----------
    phi : float
        Amplitude φ [rad], any real value.
    m : float
        Parameter m = k², 0 ≤ m < 1 (m = 1 only with |φ| < π/2).
    """
    n = round(phi / math.pi)
    base = float(scipy.special.ellipkinc(phi - n * math.pi, m))
    return base if n == 0 else base + 2.0 * n * float(scipy.special.ellipk(m))


def jacobi_sn_cn_dn(u, m: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Jacobi elliptic functions sn(u | m), cn(u | m), dn(u | m) (DLMF §22.2), m = k².

    Parameters
    ----------
    u : array_like, shape (N,)
        Argument (dimensionless; e.g. λ t + τ0).
    m : float
        Parameter, 0 ≤ m ≤ 1 (m = 0: sin, cos, 1; m = 1: tanh, sech, sech).

    Returns
    -------
    sn, cn, dn : ndarray, shape (N,)
    """
    sn, cn, dn, _ = scipy.special.ellipj(np.asarray(u, dtype=float), m)
    return sn, cn, dn


# ----------------------------------------- complementary-parameter (mc = 1 − m) forms
# For k² → 1 the parameter m itself has no digits left: these take mc = 1 − m and
# evaluate through Carlson's symmetric integrals (DLMF §19.16, 19.25) or the AGM.


def ellipk_carlson(mc: float) -> float:
    """K(m) = R_F(0, mc, 1) from the complementary parameter mc = 1 − m (DLMF 19.25.1).

    Parameters
    ----------
    mc : float
        Complementary parameter 1 − k², 0 < mc ≤ 1; full relative accuracy as mc → 0.
    """
    return float(scipy.special.elliprf(0.0, mc, 1.0))


def ellipf_carlson(s2: float, mc: float) -> float:
    """F(φ | m) = sin φ R_F(cos²φ, 1 − m sin²φ, 1) for 0 ≤ φ ≤ π/2 (DLMF 19.25.5).

    Parameters
    ----------
    s2 : float
        sin²φ, 0 ≤ s2 ≤ 1 (given as sin²φ: a Jacobi sn² inverted directly).
    mc : float
        Complementary parameter 1 − m; 1 − m sin²φ = cos²φ + mc sin²φ has no cancellation.
    """
    return math.sqrt(s2) * float(scipy.special.elliprf(1.0 - s2, (1.0 - s2) + mc * s2, 1.0))


def ellippi_carlson(n: float, one_minus_n: float, mc: float) -> float:
    """Complete elliptic integral of the third kind Π(n | m), m = 1 − mc (DLMF 19.25.2).

    Π(n | m) = R_F(0, mc, 1) + (n/3) R_J(0, mc, 1, 1 − n).  1 − n is passed separately:
    for n → 1 (an axis passing close to the vertical) 1 − n computed by subtraction would
    lose its digits.

    Parameters
    ----------
    n : float
        Characteristic, n < 1 (negative allowed).
    one_minus_n : float
        1 − n, computed by the caller without cancellation.
    mc : float
        Complementary parameter 1 − m.
    """
    sp = scipy.special
    return sp.elliprf(0.0, mc, 1.0) + n / 3.0 * sp.elliprj(0.0, mc, 1.0, one_minus_n)


def jacobi_sn_agm(x, mc: float) -> np.ndarray:
    """sn(x | m), m = 1 − mc, by the arithmetic-geometric mean (DLMF 22.20(ii)).

    Takes the complementary parameter mc so that k² → 1 keeps full accuracy (scipy's
    ``ellipj`` switches to a first-order expansion for 1 − m < 1e-9, which loses all
    digits after a few periods of a slow, nearly separatrix motion).

    Parameters
    ----------
    x : array_like, shape (N,)
        Argument (dimensionless, e.g. λ t + τ0).
    mc : float
        Complementary parameter 1 − k², 0 ≤ mc ≤ 1.

    Returns
    -------
    ndarray, shape (N,)
    """
    x = np.asarray(x, dtype=np.float64)
    a, b = 1.0, math.sqrt(mc)
    cs = [math.sqrt(max(0.0, 1.0 - mc))]
    As = [a]
    while abs(cs[-1]) > 1e-17 * a and len(cs) < 60:
        a, b, cn = 0.5 * (a + b), math.sqrt(a * b), 0.5 * (a - b)
        cs.append(cn)
        As.append(a)
    n = len(cs) - 1
    phi = (2.0**n) * As[-1] * x
    for j in range(n, 0, -1):
        phi = 0.5 * (phi + np.arcsin(np.clip(cs[j] / As[j] * np.sin(phi), -1.0, 1.0)))
    return np.sin(phi)
