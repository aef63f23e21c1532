"""R(t) rebuilt from ω(t) by the time-ordered exponential, notes (8.36)–(8.37)
(reportgen.kinds.rotation.time_ordered): the series against the Euler matrix and against the
closed form exp(t[ω]×) R(0) of a constant ω; Magnus's method at order 4."""

from __future__ import annotations

import numpy as np
import pytest

from reportgen.core import rotations
from reportgen.kinds.rotation.time_ordered import _expm_skew, rebuild


def test_the_series_and_magnus_rebuild_the_shipped_path():
    k = rebuild([0.5, 0.8, 0.3], [0.7, 0.4, 1.5], "zyz", 4.0)
    assert k["series_best"] < 1e-12
    assert k["series_error"][-1] < 1e-12 and k["series_error"][0] > 1.0  # it converges
    assert k["series_largest_term"] > 10.0  # ... after its terms grew (|ω|t ≈ 8.4)
    assert abs(k["magnus_order"] - 4.0) < 0.1
    assert np.all(np.diff(k["magnus_error"]) < 0)


def test_a_constant_omega_is_exp_of_t_omega():
    """Only φ̇ ≠ 0 in z-x-z: ω = φ̇ e_z, constant; T exp = exp(t[ω]×), Rodrigues."""
    angles, rates, T = np.array([0.2, 0.9, -0.4]), np.array([1.3, 0.0, 0.0]), 2.5
    k = rebuild(angles, rates, "zxz", T)
    exact = _expm_skew(rotations.skew(np.array([0.0, 0.0, 1.3 * T]))) @ rotations.euler_matrix(*angles,
                                                                                       "zxz")
    R_end = rotations.euler_matrix(*(angles + T * rates), "zxz")
    assert np.max(np.abs(exact - R_end)) < 1e-15  # the reference is the closed form
    assert k["series_best"] < 1e-14 and k["magnus_error"][-1] < 1e-14


@pytest.mark.parametrize("duration", [0.05, 0.4])
def test_a_short_path_never_grows_its_terms(duration):
    k = rebuild([0.5, 0.8, 0.3], [0.7, 0.4, 1.5], "zxz", duration)
    assert k["series_largest_term"] <= 1.0 and k["series_best"] < 1e-15


def test_skew_of_many_vectors_is_each_ones_cross_product_matrix():
    v = np.array([[1.0, -2.0, 0.5], [0.0, 3.0, -1.0]])
    u = np.array([0.3, 0.7, -1.1])
    assert rotations.skew(v).shape == (2, 3, 3)
    assert np.array_equal(rotations.skew(v) @ u, np.cross(v, u))
    assert np.array_equal(rotations.skew(v[0]), rotations.skew(v)[0])
