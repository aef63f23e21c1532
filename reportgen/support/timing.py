"""Wall time of a call, as the benchmarks take it: the minimum over repeats."""

from __future__ import annotations

import math
import time


def best_time(fn, repeats: int) -> tuple[float, object]:
    """(min wall time of ``repeats`` calls of ``fn``, the last call's result)."""
    best, result = math.inf, None
    for _ in range(repeats):
        start = time.perf_counter()
        result = fn()
        best = min(best, time.perf_counter() - start)
    return best, result
