"""Timing helpers shared by the benchmarks (not a benchmark itself: no ``run()``)."""

from __future__ import annotations

import time


def best_of(fn, repeat: int = 5, number: int = 1) -> float:
    """Fastest wall time of ``repeat`` rounds of ``number`` calls, per call, in seconds.

    The minimum is the least disturbed estimate of the intrinsic cost on a loaded machine.
    """
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t0) / number)
    return best
