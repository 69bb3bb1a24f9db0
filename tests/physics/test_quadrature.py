"""Quadrature decoding, sine/cosine interpolation, imperfect signals and the Heydemann fit."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import InputError
from axiscal.physics import quadrature as q
from axiscal.physics.quadrature import (SignalImperfections, heydemann_fit, interpolate_sincos,
                                        synthesize_sincos)


def _random_walk(n, rng):
    steps = rng.integers(-1, 2, n)
    steps[0] = 0
    return np.cumsum(steps)


def test_decoding_is_exact_over_ten_million_transitions():
    """Issue 3: "quadrature decoding counts exactly (zero error over 10^7 simulated transitions
    without faults)". Every step of this walk is one legal transition (or none)."""
    rng = np.random.default_rng(11)
    steps = rng.choice(np.array([-1, 1]), 10**7)       # every sample is a transition
    counts = np.concatenate(([0], np.cumsum(steps)))
    a, b = q.encode_quadrature(counts)
    dec = q.decode_quadrature(a, b)
    assert dec.n_illegal == 0
    assert np.array_equal(dec.counts, counts)
    assert int(np.count_nonzero(np.diff(dec.counts))) == 10**7


def test_every_injected_illegal_transition_is_flagged():
    """Issue 3: "flags every injected illegal transition"; the count holds there (no silent
    loss: the indices are in the result)."""
    rng = np.random.default_rng(5)
    steps = rng.integers(-1, 2, 200_000)
    steps[0] = 0
    # a step of 2 counts between two samples changes both A and B: illegal
    bad = np.sort(rng.choice(np.arange(1, steps.size), 300, replace=False))
    steps[bad] = 2
    faulty = np.cumsum(steps)
    a, b = q.encode_quadrature(faulty)
    dec = q.decode_quadrature(a, b, initial_count=int(faulty[0]))
    assert dec.n_illegal == 300
    assert np.array_equal(dec.illegal, bad)
    # between illegal transitions the decoded count follows the true one exactly
    held = faulty - dec.counts
    assert held[-1] == 2 * 300
    assert np.all(np.diff(held)[np.setdiff1d(np.arange(steps.size - 1), bad - 1)] == 0)
    assert "300 illegal" in str(dec)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(-1, 1), min_size=1, max_size=400), st.integers(-10**6, 10**6))
def test_decode_of_encode_returns_the_counts(steps, start):
    """Property (issue 3): decoding the encoding of any trajectory returns its counts."""
    counts = start + np.concatenate(([0], np.cumsum(steps))).astype(np.int64)
    a, b = q.encode_quadrature(counts)
    dec = q.decode_quadrature(a, b, initial_count=start)
    assert np.array_equal(dec.counts, counts)
    assert dec.n_illegal == 0


def test_decode_refuses_mismatched_or_non_binary_input():
    with pytest.raises(InputError, match="same length"):
        q.decode_quadrature(np.zeros(3, bool), np.zeros(4, bool))
    with pytest.raises(InputError, match="0/1"):
        q.decode_quadrature(np.array([0, 2]), np.array([0, 1]))


def test_interpolation_counts_periods_and_interpolates():
    rng = np.random.default_rng(2)
    x = np.cumsum(rng.uniform(-0.2, 0.2, 100_000)) + 0.37
    s, c = np.sin(2 * np.pi * x), np.cos(2 * np.pi * x)
    r = q.interpolate_sincos(s, c, initial_period=0)
    assert np.max(np.abs(r.position - x)) < 1e-12
    assert r.n_tracking_warnings == 0


def test_interpolation_flags_undersampled_jumps():
    x = np.array([0.0, 0.1, 0.45, 0.5])   # a 0.35-period jump: more than a quarter
    r = q.interpolate_sincos(np.sin(2 * np.pi * x), np.cos(2 * np.pi * x))
    assert r.tracking_warnings.tolist() == [2]


def test_heydemann_correction_leaves_below_one_percent_of_the_sde():
    """Issue 3: with offsets, 5 % amplitude mismatch and 3° phase error, the corrected
    sub-divisional error is below 1 % of what it was, on a simulated signal with noise."""
    rng = np.random.default_rng(7)
    imp = q.SignalImperfections(offset_sin=0.03, offset_cos=-0.02, amplitude_sin=1.05,
                                amplitude_cos=1.0, phase_error=math.radians(3.0), noise=0.002)
    x = np.cumsum(rng.uniform(0.0, 0.01, 200_000))
    s, c = q.synthesize_sincos(x, imp, rng)
    true_phase = 2 * np.pi * x
    before = q.subdivisional_error(np.arctan2(s, c) - true_phase, true_phase)
    fit = q.heydemann_fit(s, c)
    # intermediate quantities: the fitted ellipse
    assert fit.offset_sin == pytest.approx(0.03, abs=5e-4)
    assert fit.offset_cos == pytest.approx(-0.02, abs=5e-4)
    assert fit.amplitude_sin / fit.amplitude_cos == pytest.approx(1.05, abs=5e-4)
    assert math.degrees(fit.phase_error) == pytest.approx(3.0, abs=0.05)
    s2, c2 = q.heydemann_correct(s, c, fit)
    after = q.subdivisional_error(np.arctan2(s2, c2) - true_phase, true_phase)
    assert before > 0.04                                    # about 0.07 rad before
    assert after < 0.01 * before
    # the analytic SDE of the model agrees with the sampled one
    analytic = np.max(np.abs(q.interpolation_error(np.linspace(0, 2 * np.pi, 2000), imp)))
    assert analytic == pytest.approx(before, rel=0.05)


def test_heydemann_refuses_points_not_on_an_ellipse():
    with pytest.raises(InputError, match="at least 5"):
        q.heydemann_fit([0, 1], [1, 0])
    x = np.linspace(-1, 1, 50)
    with pytest.raises(InputError):
        q.heydemann_fit(x, x**2)


def test_imperfections_validated():
    with pytest.raises(InputError, match="amplitude_sin"):
        q.SignalImperfections(amplitude_sin=0)
    with pytest.raises(InputError, match="rng"):
        q.synthesize_sincos([0.1], q.SignalImperfections(noise=0.1))


# -- Review of physics/quadrature.py: a missing sample must not silently lose a signal period. ----------

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
