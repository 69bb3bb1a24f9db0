"""The compensator: exact pulse multiplication, sine/cosine synthesis, rephasing (seed 002)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import InputError
from axiscal.instruments.compensator import (FACTOR_BITS, Compensator, PulseMultiplier,
                                             SineOutput, compensation_summary, factor_to_integer,
                                             multiply, rephase, synthesise)
from axiscal.physics.air import refractive_index


def test_seed_output_format_256_counts_of_78_nm():
    """Seed 002: '20 µm = 256 counts of 78 nm'; periods 20, 25, 40, 50, 100 µm."""
    out = SineOutput(20e-6, 256)
    assert out.count_size == pytest.approx(78.125e-9)
    assert (out.stage2_counts, out.switch_to_home, out.pulse_counts) == (256, 320, 128)
    for p in (20, 25, 40, 50, 100):
        SineOutput(p * 1e-6, 256)
    with pytest.raises(InputError, match="period"):
        SineOutput(30e-6, 256)
    with pytest.raises(InputError, match="multiple of 8"):
        SineOutput(20e-6, 100)


def test_factor_from_air_and_work_piece():
    """R = (λ/k) / (n (1 + α Δt) q): about 8.1 output counts per 0.633 µm laser count."""
    comp = Compensator(expansion_coefficient=11.5e-6)
    n = refractive_index(20.0, 101325.0, 50.0)
    r = comp.ratio(20.0, 101325.0, 50.0, 25.0)
    assert r == pytest.approx(632.991e-9 / (n * (1 + 11.5e-6 * 5) * 78.125e-9), rel=1e-15)
    p = comp.factor(20.0, 101325.0, 50.0, 25.0)
    assert abs(p / 2 ** FACTOR_BITS - r) <= 2 ** -(FACTOR_BITS + 1)
    assert comp.correction_ppm(20.0, 101325.0, 50.0) == pytest.approx(-271.3, abs=0.05)


def test_factor_schedule_samples_and_holds():
    comp = Compensator(update_interval=1.0)
    t = np.arange(0.0, 3.0, 0.25)
    temp = 20.0 + t  # 1 K/s
    p = comp.factor_schedule(t, temp, 101325.0, 50.0)
    assert len(np.unique(p)) == 3
    assert np.all(p[:4] == comp.factor(20.0, 101325.0, 50.0))
    assert np.all(p[4:8] == comp.factor(21.0, 101325.0, 50.0))


@settings(max_examples=200, deadline=None)
@given(st.lists(st.integers(-10**6, 10**6), min_size=1, max_size=50),
       st.integers(2**30, 2**36))
def test_multiply_is_the_exact_floor(counts, p):
    """Every output count is ⌊c·P/2^B⌋ of exact rationals, for either sign."""
    out = multiply(counts, p)
    want = [int(Fraction(c * p, 2 ** FACTOR_BITS) // 1) for c in counts]
    assert out.tolist() == want


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(st.lists(st.integers(-40, 40), max_size=30),
                          st.integers(2**33, 2**35)), min_size=1, max_size=8))
def test_streaming_multiplier_equals_absolute_formula(chunks):
    """The Bresenham-like streaming multiplier with factor changes never drifts from
    ⌊c·P_now/2^B⌋: additions at a factor change re-scale the whole count."""
    mult = PulseMultiplier(chunks[0][1])
    total_in = 0
    total_out = 0
    for inc, p in chunks:
        total_out += mult.set_factor(p)
        out = mult.feed(inc)
        total_in += sum(inc)
        total_out += int(out.sum())
        assert mult.count == total_in
        assert total_out == mult.output == (total_in * p) >> FACTOR_BITS
        assert 0 <= mult.remainder < 1


def test_no_accumulating_error_over_a_long_move():
    """3.2 million laser counts (2 m at 0.633 µm): the output is within one count of c·R."""
    p = factor_to_integer(8.100086656326207)
    c = np.arange(0, 3_200_000, dtype=np.int64)
    out = multiply(c, p)
    assert int(out[-1]) == (3_199_999 * p) >> FACTOR_BITS
    err = c.astype(float) * (p / 2 ** FACTOR_BITS) - out
    assert err.min() >= 0 and err.max() < 1


def test_multiply_refuses_overflow():
    with pytest.raises(InputError, match="overflows"):
        multiply([2**40], 2**35)


def _sweep(n=256, start=-300, stop=800, switch_at=0, phi=0, d=1):
    o = np.arange(start, stop) * d
    sw = d * o >= switch_at
    return o, rephase(o, sw, n, d, phi)


@pytest.mark.parametrize("d", [1, -1])
@pytest.mark.parametrize("phi", [0, 1, 31, 32, 100, 200, 255])
def test_rephase_pulse_model(phi, d):
    """The documented pulse model: B at N, Z at 5N/4 (320), C at 3N/2 beyond the switch; the
    reference is active from B to C, sine = cosine > 0 at Z, and sin + cos > 0 over the pulse."""
    n = 256
    o, r = _sweep(n, phi=phi, d=d)
    assert 0 <= r.virtual < n
    assert r.m_b == r.m[np.flatnonzero(d * o == n)[0]]
    s, c = synthesise([r.m_z], n)
    assert abs(s[0] - c[0]) < 1e-12 and s[0] > 0
    ref_counts = d * o[r.reference]
    assert ref_counts.min() == 256 and ref_counts.max() == 383  # B = 256 to C = 384
    assert r.reference[np.flatnonzero(d * o == 320)[0]]
    s, c = synthesise(r.m[r.reference], n)
    assert np.all(s + c > -1e-12)  # zero only at B (phase -45°), positive after
    assert np.all(s[1:] + c[1:] > 0)
    # the controller sees N + v counts during stage 2 (256 to 511), N after
    k0, kb = np.flatnonzero(d * o == 0)[0], np.flatnonzero(d * o == 256)[0]
    assert d * (r.m[kb] - r.m[k0]) == n + r.virtual
    # virtual movement only in stage 2: m - o constant before A and after B
    assert np.all(r.m[:k0] - o[:k0] == phi)
    assert np.all(r.m[kb:] - o[kb:] == phi + d * r.virtual)
    # stage 2 is monotone: the spread never moves the outputs backwards
    assert np.all(d * np.diff(r.m) >= 1)


def test_rephase_all_phases_give_z_on_45_degrees():
    n = 256
    for phi in range(n):
        _, r = _sweep(n, phi=phi, switch_at=17)
        assert r.m_z % n == n // 8
    vs = {_sweep(n, phi=phi)[1].virtual for phi in range(n)}
    assert vs == set(range(n))  # "+0 to +256 output counts"


def test_rephase_reversal_in_stage_2_takes_back_and_latches_after_b():
    n = 64
    o = np.concatenate([np.arange(-10, 40), np.arange(40, -5, -1), np.arange(-5, 200),
                        np.arange(200, -20, -1)])
    r = rephase(o, o >= 0, n, 1, 5)
    k = np.flatnonzero(o == 0)
    assert r.m[k[0]] == r.m[k[1]]  # position-based spread: back at A, the extra is gone
    back = np.flatnonzero(o == -19)[0]
    assert r.m[back] - o[back] == 5 + r.virtual  # after B the phase is preserved for ever


def test_rephase_without_switch_and_bad_input():
    o = np.arange(100)
    r = rephase(o, np.zeros(100, bool), 256)
    assert r.index_a is None and not r.reference.any() and np.array_equal(r.m, o)
    with pytest.raises(InputError):
        rephase(o, np.zeros(99, bool))
    with pytest.raises(InputError):
        rephase(o, o > 5, 100)


def test_compensation_summary_errors_over_a_metre():
    comp = Compensator(expansion_coefficient=11.5e-6)
    s = compensation_summary(comp, 20.0, 101325.0, 50.0, material_temperature=21.0, length=1.0)
    assert s.raw_error == pytest.approx((s.n * s.growth - 1.0), rel=1e-12)
    assert s.material_error == pytest.approx(11.5e-6)
    assert s.weather_error == pytest.approx(0.0, abs=1e-12)
    dew = compensation_summary(comp, 20.0, 101325.0, dew_point=9.26)
    assert dew.n == pytest.approx(refractive_index(20.0, 101325.0, dew_point=9.26), abs=1e-15)
    # a 1 K warmer room: about -0.95 µm/m of weather error
    warm = compensation_summary(comp, 21.0, 101325.0, 50.0)
    assert warm.weather_error * 1e6 == pytest.approx(-0.95, abs=0.03)
    with pytest.raises(InputError):
        compensation_summary(comp, humidity=50.0, dew_point=9.0)


@settings(max_examples=150, deadline=None)
@given(st.lists(st.integers(-20, 20), min_size=2, max_size=300), st.integers(0, 63),
       st.integers(-50, 50), st.sampled_from([1, -1]))
def test_rephase_invariants_on_any_trajectory(steps, phi, switch_at, d):
    """Property: for any back-and-forth trajectory, the virtual movement lies in 0..N-1, is
    added only between A and completion, and the reference mark is active only where the
    controller count lies in the B-to-C window after completion."""
    n = 64
    o = np.concatenate(([-100 * d], -100 * d + np.cumsum(steps))).astype(np.int64)
    sw = d * o >= d * switch_at
    r = rephase(o, sw, n, d, phi)
    extra = d * (r.m - o - phi)
    assert np.all((extra >= 0) & (extra < n))
    if r.index_a is None:
        assert np.all(extra == 0) and not r.reference.any()
        return
    assert np.all(extra[:r.index_a] == 0)
    assert 0 <= r.virtual < n
    done = np.maximum.accumulate(d * o[r.index_a:]) >= d * r.count_a + n
    assert np.all(extra[r.index_a:][done] == r.virtual)
    assert not r.reference[:r.index_a].any()
    assert not r.reference[r.index_a:][~done].any()
    if r.reference.any():
        assert np.all(np.mod(r.m[r.reference] - r.m_z + n // 4, n) < n // 2)


@settings(max_examples=150, deadline=None)
@given(st.lists(st.integers(-10**4, 10**4), min_size=1, max_size=60))
def test_expand_counts_steps_by_one_through_every_count(values):
    """Property: the pulse train visits every sample's count, one count at a time."""
    from axiscal.instruments.compensator import expand_counts

    e = expand_counts(values)
    assert e[0] == values[0] and e[-1] == values[-1]
    assert np.all(np.abs(np.diff(e)) == 1)
    assert e.size == 1 + sum(abs(b - a) for a, b in zip(values, values[1:]))
