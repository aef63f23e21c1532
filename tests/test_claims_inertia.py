"""The claims test of the inertia kind (see tests/claimgen and tests/test_claims.py)."""

from claimgen import claims_test

test_claims_hold = claims_test("inertia")
