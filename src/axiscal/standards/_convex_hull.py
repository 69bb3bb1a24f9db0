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
    return np.diff(ys) / np.diff(xs)


def band_widths(upper, lower, slopes: np.ndarray) -> np.ndarray:
    """w(m) for each slope: rotating calipers as binary searches on the monotone edge slopes."""
    xu, yu = upper
    xl, yl = lower
    su = edge_slopes(xu, yu)  # decreasing along the upper chain
    sl = edge_slopes(xl, yl)  # increasing along the lower chain
    ku = np.searchsorted(-su, -slopes, side="left")  # vertex maximising y - m x
    kl = np.searchsorted(sl, slopes, side="left")  # vertex minimising y - m x
    return (yu[ku] - slopes * xu[ku]) - (yl[kl] - slopes * xl[kl])


def hull_chains(x: np.ndarray, y: np.ndarray):
    """Upper and lower convex chains, each sorted by x (distinct x, extreme y at ties)."""
    if np.all(x[1:] > x[:-1]):  # the usual case: readings in increasing position order
        xs, ys = x, y
    else:
        order = np.lexsort((y, x))
        xs, ys = x[order], y[order]
    keep_hi = np.r_[xs[1:] != xs[:-1], True]  # highest y at each x
    keep_lo = np.r_[True, xs[1:] != xs[:-1]]  # lowest y at each x
    if xs.size > 64:
        cand = _qhull_candidates(xs, ys)
        if cand is not None:
            keep_hi &= cand
            keep_lo &= cand
    upper = _monotone_chain(xs[keep_hi], ys[keep_hi], upper=True)
    lower = _monotone_chain(xs[keep_lo], ys[keep_lo], upper=False)
    return upper, lower


def _qhull_candidates(xs: np.ndarray, ys: np.ndarray):
    """Mask of hull vertices found by Qhull on scaled coordinates (None if Qhull refuses)."""
    from scipy.spatial import ConvexHull, QhullError

    sx, sy = np.ptp(xs), np.ptp(ys)
    if sy == 0:
        return None
    pts = np.column_stack(((xs - xs[0]) / sx, (ys - ys.min()) / sy))
    try:
        hull = ConvexHull(pts)
    except (QhullError, ValueError):
        return None
    mask = np.zeros(xs.size, dtype=bool)
    mask[hull.vertices] = True
    # keep the end columns whole so each chain starts and ends at the extreme positions
    mask |= (xs == xs[0]) | (xs == xs[-1])
    return mask


def _monotone_chain(xs: np.ndarray, ys: np.ndarray, upper: bool):
    """Andrew's monotone chain on x-sorted points with distinct x (exact cross products)."""
    sign = -1.0 if upper else 1.0
    hx: list[float] = []
    hy: list[float] = []
    for px, py in zip(xs.tolist(), ys.tolist()):
        while len(hx) >= 2:
            cross = (hx[-1] - hx[-2]) * (py - hy[-2]) - (hy[-1] - hy[-2]) * (px - hx[-2])
            if sign * cross > 0:
                break
            hx.pop()
            hy.pop()
        hx.append(px)
        hy.append(py)
    return np.array(hx), np.array(hy)

