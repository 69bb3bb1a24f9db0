"""The optional numba kernels of sine/cosine interpolation against the NumPy reference (issue 12).

The NumPy path (``numpy.arctan2`` + block unwrap) is the reference and the fallback; the kernels
(Cephes atan, S. L. Moshier, extended to four quadrants) must give the same periods, phases
within 5e-16 rad (a few units in the last place of π) and the same tracking warnings. Without
numba the automatic path falls back to NumPy and ``accelerate=True`` is refused by name.
"""

from __future__ import annotations

import importlib.util
import sys

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.physics import quadrature
from axiscal.physics.quadrature import ACCELERATE_MIN_SAMPLES, interpolate_sincos

HAVE_NUMBA = importlib.util.find_spec("numba") is not None


def _record(n, rng):
    """A wandering position (periods) with some under-sampled jumps, plus the exact zeros and
    signed zeros at which atan2's quadrant rules matter."""
    x = np.cumsum(rng.uniform(-0.2, 0.2, n))
    x[n // 3] += 0.3                                    # a jump of more than a quarter period
    s, c = np.sin(2 * np.pi * x), np.cos(2 * np.pi * x)
    s[:8] = [0.0, -0.0, 0.0, -0.0, 1.0, -1.0, 1e-300, -1e-310]
    c[:8] = [1.0, 1.0, -1.0, -1.0, 0.0, -0.0, -1.0, -1.0]
    return s, c


def test_kernels_agree_with_the_numpy_reference():
    rng = np.random.default_rng(12)
    s, c = _record(ACCELERATE_MIN_SAMPLES + 12345, rng)
    ref = interpolate_sincos(s, c, 7, accelerate=False)
    if not HAVE_NUMBA:
        with pytest.raises(InputError, match="numba"):
            interpolate_sincos(s, c, 7, accelerate=True)
        return
    fast = interpolate_sincos(s, c, 7, accelerate=True)
    assert np.max(np.abs(fast.phase - ref.phase)) <= 5e-16
    assert np.array_equal(np.signbit(fast.phase[:8]), np.signbit(ref.phase[:8]))
    assert np.array_equal(fast.phase[:8], ref.phase[:8])
    assert np.max(np.abs(fast.position - ref.position)) <= 1e-15 * np.max(np.abs(ref.position))
    assert np.array_equal(np.round(fast.position - fast.phase / (2 * np.pi)),
                          np.round(ref.position - ref.phase / (2 * np.pi)))   # same periods
    assert fast.tracking_warnings.tolist() == ref.tracking_warnings.tolist()
    assert ref.n_tracking_warnings >= 1
    # the automatic choice takes the kernels for a record this long
    auto = interpolate_sincos(s, c, 7)
    assert np.array_equal(auto.position, fast.position)
    # a non-contiguous view is accepted
    view = interpolate_sincos(np.repeat(s, 2)[::2], np.repeat(c, 2)[::2], 7, accelerate=True)
    assert np.array_equal(view.position, fast.position)


def test_numpy_fallback_when_numba_is_missing(monkeypatch):
    """numba absent: the automatic path is NumPy and gives the reference result; asking for the
    kernels is one clear error."""
    rng = np.random.default_rng(3)
    s, c = _record(ACCELERATE_MIN_SAMPLES + 10, rng)
    ref = interpolate_sincos(s, c, accelerate=False)
    monkeypatch.setitem(sys.modules, "numba", None)              # import numba -> ImportError
    monkeypatch.delitem(sys.modules, "axiscal.physics._sincos_numba", raising=False)
    monkeypatch.setattr(quadrature, "_ACCEL", None)
    auto = interpolate_sincos(s, c)
    assert quadrature._ACCEL is False
    assert np.array_equal(auto.position, ref.position)
    assert np.array_equal(auto.phase, ref.phase)
    with pytest.raises(InputError, match="numba"):
        interpolate_sincos(s, c, accelerate=True)


def test_small_records_stay_on_numpy(monkeypatch):
    """Below ACCELERATE_MIN_SAMPLES the kernels are not even loaded (no import or compile cost
    for a short record)."""
    monkeypatch.setattr(quadrature, "_ACCEL", None)
    x = np.linspace(0, 3, 1000)
    r = interpolate_sincos(np.sin(2 * np.pi * x), np.cos(2 * np.pi * x))
    assert quadrature._ACCEL is None
    assert np.allclose(r.position - r.position[0], x - x[0], atol=1e-12)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_a_non_finite_sample_is_refused_by_index_on_both_paths(bad):
    rng = np.random.default_rng(5)
    s, c = _record(ACCELERATE_MIN_SAMPLES + 100, rng)
    c[ACCELERATE_MIN_SAMPLES - 3] = bad
    for accelerate in ((False, True) if HAVE_NUMBA else (False, None)):
        with pytest.raises(InputError, match=rf"cos\[{ACCELERATE_MIN_SAMPLES - 3}\]"):
            interpolate_sincos(s, c, accelerate=accelerate)
