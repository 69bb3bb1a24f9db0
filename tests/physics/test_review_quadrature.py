"""Review of physics/quadrature.py: a missing sample must not silently lose a signal period."""

from __future__ import annotations

import math

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.physics.quadrature import (SignalImperfections, heydemann_fit, interpolate_sincos,
                                        synthesize_sincos)


def _signals(periods=3.0, n=61):
    x = np.linspace(0.0, periods, n)
    return x, np.sin(2 * math.pi * x), np.cos(2 * math.pi * x)


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -float("inf")])
@pytest.mark.parametrize("channel", ["sin", "cos"])
def test_interpolation_refuses_a_non_finite_sample(bad, channel):
    """Before the review a NaN sine at x = 0.5 period (where the phase wraps through ±π) made
    the count miss the wrap: 2.0 periods at the end of a 3-period move, no tracking warning.
    An infinity gave arctan2 a finite, wrong phase. Both are refused, naming the sample."""
    x, s, c = _signals()
    (s if channel == "sin" else c)[10] = bad
    with pytest.raises(InputError, match=rf"{channel}\[10\]"):
        interpolate_sincos(s, c)


def test_interpolation_still_counts_every_period_of_clean_signals():
    x, s, c = _signals()
    r = interpolate_sincos(s, c)
    np.testing.assert_allclose(r.position, x, atol=1e-12)
    assert r.n_tracking_warnings == 0


def test_heydemann_fit_refuses_nan_with_the_reason():
    """Before the review a NaN gave the misleading 'sin and cos must vary'."""
    imp = SignalImperfections(0.02, -0.01, 1.05, 1.0, math.radians(3))
    s, c = synthesize_sincos(np.linspace(0, 1, 100, endpoint=False), imp)
    s[5] = np.nan
    with pytest.raises(InputError, match=r"sin\[5\].*finite"):
        heydemann_fit(s, c)


def test_heydemann_fit_recovers_a_hand_built_ellipse():
    """Independent check of the conic algebra: points on cos = 0.9 cos φ + 0.1,
    sin = 1.1 sin(φ + 4°) − 0.05 (built here, not by synthesize_sincos)."""
    phi = np.linspace(0.0, 2 * math.pi, 37)[:-1]
    c = 0.9 * np.cos(phi) + 0.1
    s = 1.1 * np.sin(phi + math.radians(4.0)) - 0.05
    h = heydemann_fit(s, c)
    assert (h.amplitude_cos, h.amplitude_sin) == pytest.approx((0.9, 1.1), abs=1e-9)
    assert (h.offset_cos, h.offset_sin) == pytest.approx((0.1, -0.05), abs=1e-9)
    assert math.degrees(h.phase_error) == pytest.approx(4.0, abs=1e-7)
