"""Convex-hull machinery of the exact minimum-zone line (ISO 230-1), private.

:func:`hull_chains` gives the upper and lower convex chains of a point set (Qhull on scaled
coordinates to thin large sets, then Andrew's monotone chain with exact cross products);
:func:`band_widths` evaluates the vertical band width ``w(m) = max(y - m x) - min(y - m x)`` at
many slopes at once by rotating calipers (binary searches on the monotone edge slopes).

References
----------
A. M. Andrew, "Another efficient algorithm for convex hulls in two dimensions", Inf. Process.
Lett. 9, 216-219 (1979). G. T. Toussaint, "Solving geometric problems with the rotating
calipers", Proc. IEEE MELECON (1983).
"""

from __future__ import annotations

import numpy as np


def edge_slopes(xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """Slopes of the hull edges; an edge across a subnormal step of x gives ±inf (no warning)."""
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        return np.diff(ys) / np.diff(xs)


def band_widths(upper, lower, slopes: np.ndarray) -> np.ndarray:
    """w(m) for each slope: rotating calipers as binary searches on the monotone edge slopes."""
    xu, yu = upper
    xl, yl = lower
    su = edge_slopes(xu, yu)  # decreasing along the upper chain
    sl = edge_slopes(xl, yl)  # increasing along the lower chain
    ku = np.searchsorted(-su, -slopes, side="left")  # vertex maximising y - m x
    kl = np.searchsorted(sl, slopes, side="left")  # vertex minimising y - m x
    with np.errstate(over="ignore", invalid="ignore"):  # a huge slope gives inf: not the minimum
        return (yu[ku] - slopes * xu[ku]) - (yl[kl] - slopes * xl[kl])


def hull_chains(x: np.ndarray, y: np.ndarray):
    """Upper and lower convex chains, each sorted by x (distinct x, extreme y at ties).

    Readings in position order go straight to Qhull. Unsorted readings are not sorted whole:
    Qhull runs on them as they are and only its candidates (the hull's vertices and the two end
    columns) are sorted, a few dozen points instead of all. When Qhull refuses (exactly
    collinear or constant readings) every point is sorted and the chains are pruned by
    vectorised passes (:func:`_monotone_chain`).
    """
    if np.all(x[1:] > x[:-1]):  # the usual case: readings in increasing position order
        xs, ys = x, y
        cand = _qhull_candidates(xs, ys, as_mask=True) if xs.size > 64 else None
    else:
        idx = _qhull_candidates(x, y, as_mask=False) if x.size > 64 else None
        if idx is not None:
            x, y = x[idx], y[idx]
        order = np.lexsort((y, x))
        xs, ys = x[order], y[order]
        cand = None
    keep_hi = np.r_[xs[1:] != xs[:-1], True]  # highest y at each x
    keep_lo = np.r_[True, xs[1:] != xs[:-1]]  # lowest y at each x
    if cand is not None:
        keep_hi &= cand
        keep_lo &= cand
    upper = _monotone_chain(xs[keep_hi], ys[keep_hi], upper=True)
    lower = _monotone_chain(xs[keep_lo], ys[keep_lo], upper=False)
    return upper, lower


def _qhull_candidates(xs: np.ndarray, ys: np.ndarray, as_mask: bool):
    """Hull vertices found by Qhull on scaled coordinates, plus every point of the two end
    columns (so each chain starts and ends at the extreme positions): a boolean mask
    (``as_mask``) or their indices; None if Qhull refuses."""
    from scipy.spatial import ConvexHull, QhullError

    lo, hi = float(xs.min()), float(xs.max())
    sx, sy = hi - lo, float(np.ptp(ys))
    if sy == 0 or sx == 0:
        return None
    pts = np.empty((xs.size, 2))
    np.subtract(xs, lo, out=pts[:, 0])
    pts[:, 0] /= sx
    np.subtract(ys, ys.min(), out=pts[:, 1])
    pts[:, 1] /= sy
    try:
        hull = ConvexHull(pts)
    except (QhullError, ValueError):
        return None
    mask = (xs == lo) | (xs == hi)
    mask[hull.vertices] = True
    return mask if as_mask else np.flatnonzero(mask)


def _monotone_chain(xs: np.ndarray, ys: np.ndarray, upper: bool):
    """Andrew's monotone chain on x-sorted points with distinct x (floating cross products, with
    their rounding bound).

    The cross products are formed on a copy scaled by a power of two where the coordinates are
    huge or tiny (:func:`_pow2`), so that no product overflows, whatever the unit. Vectorised passes first
    drop, all at once, every point that is certainly not strictly convex against its present
    neighbours (such a point lies on or inside the segment of two other points, so it is no
    vertex whatever else is dropped); a point whose cross product is within its rounding bound
    (or whose products underflow) goes only while both its neighbours stay, since dropping two
    such neighbours at once can lose a vertex. A pass over the few points left finishes the chain.
    The chain is returned in the original coordinates.
    """
    sign = -1.0 if upper else 1.0
    X, Y = xs * _pow2(xs), ys * _pow2(ys)
    idx = np.arange(xs.size)
    eps, tiny = np.finfo(float).eps, np.finfo(float).tiny / np.finfo(float).eps
    for _ in range(64):
        if idx.size < 3:
            break
        x, y = X[idx], Y[idx]
        dxab, dyac = x[1:-1] - x[:-2], y[2:] - y[:-2]
        dyab, dxac = y[1:-1] - y[:-2], x[2:] - x[:-2]
        a, b = dxab * dyac, dyab * dxac
        cross = a - b
        # Within the rounding bound of the differences and products the sign is uncertain: a
        # true vertex beside a point a subnormal step away can round to 0. Points certainly not
        # convex go all at once; an uncertain one only where both its neighbours stay (every
        # other one per pass), so it lies within rounding of the segment that replaces it.
        bound = 4.0 * eps * (np.abs(a) + np.abs(b))
        exact_zero = ((dxab == 0) | (dyac == 0)) & ((dyab == 0) | (dxac == 0))
        underflow = (np.abs(a) + np.abs(b) < tiny) & ~exact_zero
        certain = (sign * cross <= -bound) & ~underflow
        uncertain = (sign * cross <= 0) & ~certain
        uncertain[1::2] = False
        uncertain[1:] &= ~(certain[:-1] | uncertain[:-1])
        uncertain[:-1] &= ~certain[1:]
        keep = np.r_[True, ~(certain | uncertain), True]
        if keep.all():
            break
        idx = idx[keep]
    hull: list[int] = []  # positions in idx
    xl, yl = X[idx].tolist(), Y[idx].tolist()
    for i in range(len(xl)):
        while len(hull) >= 2:
            p, q = hull[-2], hull[-1]
            cross = (xl[q] - xl[p]) * (yl[i] - yl[p]) - (yl[q] - yl[p]) * (xl[i] - xl[p])
            if sign * cross > 0:
                break
            hull.pop()
        hull.append(i)
    return xs[idx[hull]], ys[idx[hull]]


def _pow2(v: np.ndarray) -> float:
    """A power of two that brings the largest |v| near 1 when it lies outside [2**-500, 2**500],
    else 1. Scaling up is exact; scaling down is needed only for huge coordinates, where it
    rounds nothing but values 2**-500 below the largest (scaling every set would round a
    subnormal step to zero and lose a vertex)."""
    m = float(np.max(np.abs(v))) if v.size else 0.0
    if m == 0 or not np.isfinite(m) or 2.0 ** -500 <= m <= 2.0 ** 500:
        return 1.0
    return float(np.ldexp(1.0, min(-int(np.frexp(m)[1]), 1000)))  # 2**1000: no overflow
