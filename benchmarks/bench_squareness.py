"""Squareness and straightness benchmarks (issue 5).

* The exact minimum-zone line of 10^6 readings (aim: under 0.5 s and within 5x
  ``numpy.polyfit`` of the same readings, measured in the same run), with readings in position
  order, shuffled (Qhull on the unsorted points, only its candidates sorted), and exactly
  collinear or constant (Qhull refuses: every point sorted, vectorised pruning).
* The full method comparison of seed 004 Machine 5 (ballbar, diagonal, "+", four "T", four "L",
  averages), global and local (five locations), compared with evaluating the machine model once
  on as many commanded positions as the comparison uses.
"""

from __future__ import annotations


import numpy as np

from axiscal.machines.xy_plane import seed004_machine
from axiscal.procedures.squareness_study import compare_methods
from axiscal.standards.iso230_1 import minimum_zone_line

from _timing import best_of




def run() -> list[dict]:
    rng = np.random.default_rng(0)
    n = 1_000_000
    x = np.linspace(0.0, 2.0, n)
    y = rng.normal(0.0, 1e-6, n) + 3e-6 * np.sin(3 * x) + 5e-6 * x
    shuffle = rng.permutation(n)
    xs, ys = x[shuffle], y[shuffle]
    rows = []
    ref = best_of(lambda: np.polyfit(x, y, 1))
    minimum_zone_line(x[:100], y[:100])              # import scipy.spatial outside the timing
    line = 5e-6 * x                                  # collinear to rounding: Qhull refuses
    flat = np.full(n, 2e-6)                          # constant
    cases = (("in position order", (x, y)), ("shuffled", (xs, ys)),
             ("collinear, shuffled", (xs, line[shuffle])),
             ("constant, shuffled", (xs, flat)))
    for label, (px, py) in cases:
        t = best_of(lambda: minimum_zone_line(px, py))
        rows.append(dict(name=f"minimum-zone line, 10^6 readings {label} (time / polyfit)",
                         value=t, unit="s", reference=f"np.polyfit {ref:.3f} s",
                         ratio=t / ref, aim="< 0.5 s and ratio <= 5"))
    machine = seed004_machine(5)
    for scope, tests in (("global", 11), ("local", 55)):
        t = best_of(lambda: compare_methods(machine, scope))
        points = tests * 400  # about as many commanded positions as the tests use
        gx = rng.uniform(-0.4, 0.4, points)
        gy = rng.uniform(-0.4, 0.4, points)
        r = best_of(lambda: machine.deviation(gx, gy))
        rows.append(dict(name=f"method comparison, Machine 5, {scope} ({tests} tests) "
                              "(time / model)", value=t, unit="s",
                         reference=f"model on {points} points {r * 1e3:.2f} ms", ratio=t / r,
                         aim="interactive (< 1 s)"))
    return rows
