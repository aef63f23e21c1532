"""The claims test of the three_body kind (see tests/claimgen and tests/test_claims.py)."""

from claimgen import claims_test

test_claims_hold = claims_test("three_body")
