"""The controller's sine/cosine inputs, frequency monitor, home latch and skew check."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import InputError
from axiscal.instruments.compensator import synthesise
from axiscal.instruments.controller import Controller


@settings(max_examples=200, deadline=None)
@given(st.integers(-10**6, 10**6), st.lists(st.integers(-127, 127), min_size=1, max_size=200))
def test_decode_recovers_any_trajectory_sampled_within_half_a_period(start, steps):
    """Property: decoding the synthesised outputs returns the counts (up to a whole number of
    periods fixed at the first sample), whatever the trajectory."""
    ctl = Controller()
    m = start + np.concatenate(([0], np.cumsum(steps)))
    s, c = synthesise(m, 256)
    dec = ctl.decode(s, c)
    assert np.all(dec - m == dec[0] - m[0])
    assert (dec[0] - m[0]) % 256 == 0


def test_frequency_monitor_raises_alarm_above_the_limit():
    """Exceeding the controller's input frequency is detected and reported, never silent."""
    ctl = Controller(max_input_frequency=50e3)
    t = np.arange(0, 0.01, 1e-6)
    slow = np.floor(t * 40e3 * 256).astype(np.int64)   # 40 kHz
    fast = np.floor(t * 60e3 * 256).astype(np.int64)   # 60 kHz
    assert ctl.frequency_alarms(slow, t) == []
    alarms = ctl.frequency_alarms(fast, t)
    assert len(alarms) == 1 and alarms[0].kind == "input frequency"
    assert alarms[0].value == pytest.approx(60e3, rel=0.02)
    assert "exceeds" in str(alarms[0])
    assert ctl.max_speed() == pytest.approx(50e3 * 20e-6)


def test_find_home_latches_first_45_degree_count_inside_the_pulse():
    ctl = Controller(counts_per_period=256)
    m = np.arange(0, 700, 3)
    ref = (m >= 480) & (m < 608)  # a pulse from B = 480 (phase -45°) to C = 608
    latch = ctl.find_home(m, ref, 1)
    assert latch.count == 544 and latch.count % 256 == 32
    assert m[latch.index] >= 544 and m[latch.index - 1] < 544
    down = ctl.find_home(m[::-1], ref[::-1], -1)
    assert down.count == 544
    assert ctl.find_home(m, np.zeros_like(ref), 1) is None
    assert ctl.find_home(m[:170], ref[:170], 1) is None  # stopped before Z


@pytest.mark.parametrize("limit", [0, 100, 256, 300])
def test_skew_alarm_fires_exactly_beyond_the_limit(limit):
    ctl = Controller(skew_limit=limit, offset=7)
    for skew in (-limit - 1, -limit, 0, limit, limit + 1):
        chk = ctl.check_skew(1000 + skew, 1000)
        assert chk.skew == skew
        assert chk.alarm == (abs(skew) > limit)
        assert chk.deskew_move == (0 if chk.alarm else skew - 7)


def test_controller_validation():
    with pytest.raises(InputError):
        Controller(counts_per_period=100)
    with pytest.raises(InputError):
        Controller(max_input_frequency=0)
    with pytest.raises(InputError):
        Controller().decode([0.0, 1.0], [1.0])
