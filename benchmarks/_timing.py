"""Timing helpers shared by the benchmarks (not a benchmark itself: no ``run()``)."""

from __future__ import annotations

import time


def best_of(fn, repeat: int = 5, number: int = 1, clock=time.perf_counter) -> float:
    """Fastest wall time of ``repeat`` rounds of ``number`` calls, per call, in seconds.

    The minimum is the least disturbed estimate of the intrinsic cost on a loaded machine.
    ``clock=time.thread_time`` gives the calling thread's CPU time instead: what the work costs
    when other processes share the cores (meaningful for single-threaded work only).
    """
    best = float("inf")
    for _ in range(repeat):
        t0 = clock()
        for _ in range(number):
            fn()
        best = min(best, (clock() - t0) / number)
    return best
