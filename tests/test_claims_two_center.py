"""The claims test of the two_center kind (see tests/claimgen and tests/test_claims.py)."""

from claimgen import claims_test

test_claims_hold = claims_test("two_center")
