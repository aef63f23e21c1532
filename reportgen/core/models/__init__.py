"""Compiled models of motion: right-hand sides, invariants and exact references."""
