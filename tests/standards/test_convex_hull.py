"""The hull chains of the minimum-zone line against a plain monotone chain (issue 12 speed).

Reference: A. M. Andrew, "Another efficient algorithm for convex hulls in two dimensions",
Inf. Process. Lett. 9 (1979): sort every point by (x, y) and keep, with exact cross products,
only strict left/right turns. The fast paths (Qhull on unsorted points, candidates sorted; the
vectorised pruning when Qhull refuses exactly collinear or constant input) must give the same
chains.
"""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.standards._convex_hull import hull_chains
from axiscal.standards.iso230_1 import minimum_zone_line


def _andrew(x, y, upper):
    order = np.lexsort((y, x))
    xs, ys = x[order].tolist(), y[order].tolist()
    pts = []
    for px, py in zip(xs, ys):
        if pts and pts[-1][0] == px:          # one point per x: the extreme y
            if (py > pts[-1][1]) == upper:
                pts[-1] = (px, py)
            continue
        pts.append((px, py))
    sign = -1.0 if upper else 1.0
    h = []
    for p in pts:
        while len(h) >= 2:
            (ax, ay), (bx, by) = h[-2], h[-1]
            if sign * ((bx - ax) * (p[1] - ay) - (by - ay) * (p[0] - ax)) > 0:
                break
            h.pop()
        h.append(p)
    return np.array(h).T


def _cases():
    rng = np.random.default_rng(21)
    n = 3000
    x = np.linspace(0.0, 2.0, n)
    noisy = rng.normal(0, 1e-6, n) + 3e-6 * np.sin(3 * x)
    yield "noisy", x, noisy
    yield "collinear", x, 5e-6 * x                       # Qhull refuses: exactly on a line
    yield "constant", x, np.full(n, 2e-6)
    yield "duplicated x", np.repeat(x[:1000], 3), rng.normal(0, 1e-6, 3000)
    xi = np.round(rng.uniform(0, 1, n), 3)                # many ties in x
    yield "integer grid", xi, np.round(rng.normal(0, 1, n), 1)


@pytest.mark.parametrize("shuffle", [False, True])
def test_chains_equal_andrews_algorithm_on_all_points(shuffle):
    """Identical chains, except where the readings are collinear to rounding: there float
    cross products of ~1e-22 decide which of the (numerically collinear) points stay, so the
    chains must agree as lines: same end points, every vertex within 1e-18 of the reference
    chain (a thousand-millionth of the 1e-9 m resolution of any instrument)."""
    rng = np.random.default_rng(4)
    for name, x, y in _cases():
        if shuffle:
            p = rng.permutation(x.size)
            x, y = x[p], y[p]
        upper, lower = hull_chains(x, y)
        for got, want in ((upper, _andrew(x, y, True)), (lower, _andrew(x, y, False))):
            if name != "collinear":
                assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1]), name
                continue
            assert got[0][0] == want[0][0] and got[0][-1] == want[0][-1]
            assert np.max(np.abs(got[1] - np.interp(got[0], want[0], want[1]))) < 1e-18


def test_minimum_zone_line_does_not_depend_on_the_order_of_the_readings():
    rng = np.random.default_rng(8)
    x = np.linspace(0.0, 2.0, 20000)
    y = rng.normal(0.0, 1e-6, x.size) + 5e-6 * x
    p = rng.permutation(x.size)
    a, b = minimum_zone_line(x, y), minimum_zone_line(x[p], y[p])
    assert a == b
    line = minimum_zone_line(x, 5e-6 * x)                 # exactly collinear: zero zone
    assert line == minimum_zone_line(x[p], 5e-6 * x[p])
