"""Optional numba kernels of the sine/cosine interpolation (the ``fast`` extra), private.

Imported only by :func:`axiscal.physics.quadrature.interpolate_sincos` for large arrays, and only
when numba is installed; compiled kernels are cached on disk by numba (``cache=True``), so the
compilation (~1 s) is paid once per machine. The NumPy implementation stays the reference and
the fallback; the tests compare the two.

The arctangent is Cephes ``atan`` (S. L. Moshier, Cephes Mathematical Library, atan.c: the
argument reduced to |u| <= tan(π/8) by ``(t − 1)/(t + 1)``, then ``u + u·z·P(z)/Q(z)`` with
z = u², a (4, 5) rational with relative error ~1e-16), extended to four quadrants by octant
symmetry, written without branches so that LLVM vectorises it: NumPy's ``arctan2`` calls the
scalar libm routine, which is why it alone costs 13-18x a copy of the array.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

_P0, _P1, _P2, _P3, _P4 = (-8.750608600031904122785e-1, -1.615753718733365076637e1,
                           -7.500855792314704667340e1, -1.228866684490136173410e2,
                           -6.485021904942025371773e1)
_Q0, _Q1, _Q2, _Q3, _Q4 = (2.485846490142306297962e1, 1.650270098316988542046e2,
                           4.328810604912902668951e2, 4.853903996359136964868e2,
                           1.945506571482613964425e2)
_MOREBITS = 6.123233995736765886130e-17   # π/4 in double precision falls short of π/4 by this/2
_TAN_PI_8 = 0.41421356237309504880
_PI = math.pi
_PI_2 = 0.5 * math.pi
_PI_4 = 0.25 * math.pi
_TWO_PI = 2.0 * math.pi

# no 'nsz' (signed zeros decide the quadrant) and no 'nnan'/'ninf' (inputs are checked finite)
_FLAGS = {"contract", "afn", "arcp", "reassoc"}


@njit(cache=True, fastmath=_FLAGS, error_model="numpy", nogil=True)
def phase(s, c, out):
    """atan2(s, c) elementwise into ``out`` (radians, in [−π, π], signed zeros as atan2).

    Returns 0.0 when every sample is finite, NaN otherwise (``0·x`` is NaN for an infinity or a
    NaN), so the finiteness check costs no extra pass over memory."""
    check = 0.0
    for i in range(s.size):
        y = s[i]
        x = c[i]
        check += 0.0 * y + 0.0 * x
        ay = abs(y)
        ax = abs(x)
        swap = ay > ax
        num = min(ax, ay)
        den = max(ax, ay)
        t = num / den if den > 0.0 else 0.0
        big = t > _TAN_PI_8
        u = (t - 1.0) / (t + 1.0) if big else t
        z = u * u
        p = (((_P0 * z + _P1) * z + _P2) * z + _P3) * z + _P4
        q = ((((z + _Q0) * z + _Q1) * z + _Q2) * z + _Q3) * z + _Q4
        r = u + u * (z * p / q)
        r = r + (_PI_4 + 0.5 * _MOREBITS) if big else r
        r = (_PI_2 - r) if swap else r
        r = (_PI - r) if math.copysign(1.0, x) < 0.0 else r
        out[i] = math.copysign(r, y)
    return check


@njit(cache=True, error_model="numpy", nogil=True)
def interpolate(s, c, initial_period, ph, position):
    """:func:`phase` then the period count, block by block so each block is counted while it is
    in cache (one pass over memory). Returns the number of tracking warnings, or −1 (nothing
    computed further) at the first block holding a NaN or an infinity."""
    n = s.size
    block = 8192
    turns = float(initial_period)
    bad = 0
    for lo in range(0, n, block):
        hi = min(lo + block, n)
        if phase(s[lo:hi], c[lo:hi], ph[lo:hi]) != 0.0:
            return -1
        if lo == 0:
            position[0] = ph[0] / _TWO_PI + turns
            start = 1
        else:
            start = lo
        for i in range(start, hi):
            d = ph[i] - ph[i - 1]
            if d < -_PI:
                turns += 1.0
            elif d > _PI:
                turns -= 1.0
            ad = abs(d)
            if ad > _PI_2 and ad < 3.0 * _PI_2:
                bad += 1
            position[i] = turns + ph[i] * (1.0 / _TWO_PI)
    return bad


@njit(cache=True, error_model="numpy", nogil=True)
def warnings(ph, count):
    """Indices of the samples counted by :func:`interpolate` as tracking warnings."""
    out = np.empty(count, np.int64)
    k = 0
    for i in range(1, ph.size):
        ad = abs(ph[i] - ph[i - 1])
        if ad > _PI_2 and ad < 3.0 * _PI_2:
            out[k] = i
            k += 1
    return out
