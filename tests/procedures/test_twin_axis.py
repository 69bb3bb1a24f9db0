"""Twin-axis (gantry) homing with compensated laser feedback: the must-show items of issue 6.

Source: seed 002, "Referencing a twin axis with compensated laser feedback": X2 can move up to
256 output counts more than X1 during X1's stage 2 and vice versa; the total skew never exceeds
±256 counts; the skew limit must be set above ±256; deskew removes the skew; a lower output
resolution reduces the maximum skew.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.instruments.compensator import SineOutput
from axiscal.instruments.controller import Controller
from axiscal.procedures.twin_axis import (TwinAxis, phase_for_virtual, required_skew_limit,
                                          simulate_twin_homing, worst_case_runs)


def _gantry(n=256, period=20e-6, limit=10**6, offset=0, s1=1000, s2=1000, x1=0, x2=0, d=1):
    out = SineOutput(period, n)
    ctl = Controller(counts_per_period=n, count_size=out.count_size, skew_limit=limit,
                     offset=offset)
    return TwinAxis(out, ctl, s1, s2, x1, x2, d)


@pytest.mark.parametrize("s2,d", [(1000, 1), (990, 1), (700, 1), (1300, 1), (1000, -1),
                                  (1200, -1)])
def test_skew_before_sync_within_256_counts_for_every_combination_of_phases(s2, d):
    """Every combination of the two power-up phases (N = 64 exhaustively, 4096 runs; N = 256 on
    every 8th phase of each axis, and every phase of each axis against two of the other): the
    skew the homing adds stays within ±(N - 1) at every step, and the controller's skew is
    (switch_2 - switch_1) + d (v2 - v1)."""
    grid256 = [(a, b) for a in range(0, 256, 8) for b in range(0, 256, 8)]
    grid256 += [(a, b) for a in range(256) for b in (1, 130)]
    grid256 += [(b, a) for a in range(256) for b in (1, 130)]
    for n, phases in ((64, [(a, b) for a in range(64) for b in range(64)]), (256, grid256)):
        g = _gantry(n=n, s1=d * 1000, s2=d * s2, d=d)
        seen_max = 0
        for p1, p2 in phases:
            r = simulate_twin_homing(g, p1, p2)
            hs = r.homing_skew
            assert np.all(np.abs(hs) <= n - 1)
            assert r.skew_check.skew == d * (s2 - 1000) + d * (r.virtual_2 - r.virtual_1)
            assert r.home_1 == d * 1000 + d * 5 * n // 4
            assert r.home_2 == d * s2 + d * 5 * n // 4
            seen_max = max(seen_max, int(np.max(np.abs(hs))))
        assert seen_max >= n - 10


def test_extremes_reach_n_minus_1_and_reduce_with_the_output_resolution():
    """Seed 002: reducing the resolution of the sine/cosine outputs reduces the maximum skew by
    the same factor: the worst homing skew is N - 1 counts (one period less one count)."""
    worst = {}
    for n in (256, 128, 64):
        g = _gantry(n=n)
        a, b = worst_case_runs(g)
        assert (a.virtual_1, a.virtual_2, b.virtual_1, b.virtual_2) == (n - 1, 0, 0, n - 1)
        worst[n] = max(abs(a.skew_check.skew), abs(b.skew_check.skew))
        assert worst[n] == n - 1
        assert required_skew_limit(g) == n - 1
    assert worst[256] / worst[64] == pytest.approx(256 / 64, rel=0.02)
    assert worst[256] / worst[128] == pytest.approx(2, rel=0.01)
    # with the same count size, halving the period halves the largest skew in length too
    q40 = SineOutput(40e-6, 256).count_size
    q20 = SineOutput(20e-6, 128).count_size
    assert q40 == q20
    assert abs(worst_case_runs(_gantry(n=256, period=40e-6))[0].skew_check.skew) * q40 == \
        pytest.approx(2 * abs(worst_case_runs(_gantry(n=128, period=20e-6))[0].skew_check.skew)
                      * q20, rel=0.01)


def test_homing_skew_in_length_is_bounded_by_one_signal_period():
    """Issue 20: fewer counts per period at a fixed 20 µm period lower the worst skew in counts
    but not in length: 255 × 78.125 nm = 19.92 µm, 127 × 156.25 nm = 19.84 µm,
    63 × 312.5 nm = 19.69 µm, all just under the period. The output says so."""
    for n in (256, 128, 64):
        g = _gantry(n=n, period=20e-6)
        a, b = worst_case_runs(g)
        worst = max(abs(a.skew_check.skew), abs(b.skew_check.skew)) * g.output.count_size
        assert worst == pytest.approx((n - 1) / n * 20e-6, rel=1e-12)
        assert worst < 20e-6
        assert a.to_dict()["homing_skew_bound_um"] == pytest.approx(worst * 1e6, rel=1e-12)
        assert "bounded by one signal period" in str(a)


@pytest.mark.parametrize("limit", [0, 50, 255, 256, 300])
def test_alarm_fires_exactly_when_the_skew_exceeds_the_limit(limit):
    g = _gantry(limit=limit)
    seen = {True: 0, False: 0}
    for v1, v2 in itertools.product([0, 1, 50, 128, 200, 254, 255], repeat=2):
        r = simulate_twin_homing(g, phase_for_virtual(1000, v1, 256),
                                 phase_for_virtual(1000, v2, 256))
        assert (r.virtual_1, r.virtual_2) == (v1, v2)
        assert r.alarm == (abs(v2 - v1) > limit)
        seen[r.alarm] += 1
        if r.alarm:
            assert r.skew_after is None and 3 not in r.phase
    assert seen[False] > 0


def test_deskew_leaves_the_offset_parameter_and_squares_the_gantry():
    """After deskew p1 - p2 equals the offset parameter; with offset = switch_2 - switch_1 (the
    real offset of the reference marks) the gantry ends square whatever the phases and the
    skew it had before homing."""
    for x1, x2 in ((0, 0), (40, 0), (-15, 30)):
        g = _gantry(offset=-13, s1=1000, s2=987, x1=x1, x2=x2)
        for p1, p2 in [(0, 0), (3, 250), (250, 3), (128, 17)]:
            r = simulate_twin_homing(g, p1, p2)
            assert not r.alarm
            assert r.skew_after == -13
            assert r.real_1[-1] - r.real_2[-1] == 0  # square
            assert r.skew_check.skew == (x1 - x2) - 13 + (r.virtual_2 - r.virtual_1)
            assert abs(r.skew_check.skew) <= required_skew_limit(g)


def test_switch_errors_and_text():
    g = _gantry(limit=300)
    r = simulate_twin_homing(g, 10, 20, switch_error_1=3, switch_error_2=-2)
    assert r.home_1 == 1003 + 320 and r.home_2 == 998 + 320
    assert "deskew" in str(r) and "skew limit" in str(r)
    d = r.to_dict()
    assert d["skew_after_sync"] == 0 and d["required_skew_limit"] == 255
    assert required_skew_limit(g, switch_spread=5) == 260


def test_gantry_validation():
    with pytest.raises(InputError, match="not before its switch"):
        _gantry(x1=2000)
    with pytest.raises(InputError):
        TwinAxis(SineOutput(20e-6, 128), Controller())
