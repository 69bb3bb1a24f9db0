"""Referencing of one axis with a compensated laser scale: the must-show items of issue 6.

Source of the sequence and numbers: seed 002 (Figure 4 and its text): Z 320 output counts beyond
the switch, 256 counts of 78 nm per 20 µm period, virtual movement only before homing.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.instruments.compensator import Compensator, SineOutput, synthesise
from axiscal.instruments.controller import Controller
from axiscal.instruments.laser_scale import LaserHead, ReferenceSwitch
from axiscal.procedures.referencing import (AirHistory, Move, ScaleAxis, simulate_referencing)


def _axis(n=256, period=20e-6, sigma=0.0, active_above=True, laser=None, alpha=0.0,
          air=AirHistory(), fmax=100e3, position=0.1):
    laser = laser or LaserHead()
    out = SineOutput(period, n)
    comp = Compensator(laser=laser, output=out, expansion_coefficient=alpha)
    ctl = Controller(counts_per_period=n, count_size=out.count_size, max_input_frequency=fmax)
    sw = ReferenceSwitch(position, sigma, active_above)
    return ScaleAxis(laser=laser, compensator=comp, switch=sw, controller=ctl, air=air)


def test_z_lands_exactly_320_counts_beyond_the_switch_over_thousands_of_runs():
    """Seed 002: 'This point is 320 output counts beyond the point at which the reference mark
    switch was activated'. 2000 runs with random power-up phases (output phase, fringe phase,
    power-up position), switch positions, air and switch repeatability; Z is 320 counts of real
    motion beyond A every time, at sine = cosine with the reference active."""
    rng = np.random.default_rng(2024)
    vs = set()
    for _ in range(2000):
        pos = float(rng.uniform(0.05, 0.5))
        air = AirHistory(temperature=float(rng.uniform(18, 24)),
                         pressure=float(rng.uniform(95e3, 104e3)),
                         humidity=float(rng.uniform(20, 70)))
        ax = _axis(sigma=0.5e-6, air=air, position=pos)
        start = pos - float(rng.uniform(10e-6, 60e-6))
        run = simulate_referencing(ax, start, rng=rng,
                                   power_up_position=start - float(rng.uniform(0, 0.3)))
        assert run.homed, run
        z = run.event("Z")
        # measured from the simulated motion: within one laser count (+ the sample spacing)
        for e, nominal in ((z, 320), (run.event("B"), 256)):
            assert e.nominal_counts == nominal
            assert abs(e.counts_beyond_switch - nominal) <= e.uncertainty_counts + 0.6
        assert run.controller_side[z.index] >= z.controller_count
        k = z.index
        assert run.reference[k]
        assert z.controller_count % 256 == 32  # phase 45°
        s, c = synthesise([z.controller_count], 256)
        assert abs(s[0] - c[0]) < 1e-12 and s[0] > 0
        vs.add(run.virtual)
    assert len(vs) > 200  # the virtual movement took almost every value 0..255


@pytest.mark.parametrize("active_above", [True, False])
def test_home_position_repeats_to_the_switch_and_laser_resolution(active_above):
    """The home position repeats whatever the power-up phase: its scatter is the switch's own
    repeatability plus at most one laser count (0.633 µm), and it lies 320 counts (25 µm) beyond
    the switch's trip point."""
    d = 1 if active_above else -1
    rng = np.random.default_rng(7)
    laser_count = LaserHead().count_size
    for sigma in (0.0, 1e-6):
        ax = _axis(sigma=sigma, active_above=active_above)
        homes, beyond = [], []
        for _ in range(300):
            start = 0.1 - d * float(rng.uniform(5e-6, 80e-6))
            run = simulate_referencing(ax, start, rng=rng)
            homes.append(run.home_position)
            beyond.append(d * (run.home_position - run.switch_trip))
        beyond = np.array(beyond)
        q = ax.output.count_size
        # 320 counts of compensated length are 320 q n (1 + ...) of true length
        assert np.all(np.abs(beyond - 320 * q) <= laser_count + 2 * q)
        if sigma == 0:
            assert np.ptp(homes) <= laser_count + 2 * q
        else:
            assert np.std(homes) == pytest.approx(np.hypot(sigma, laser_count / math.sqrt(12)),
                                                  rel=0.25)


def test_virtual_movement_only_before_homing():
    """Seed 002: the virtual movement 'occurs before the axis is homed': from B on, the
    controller count and the real output count differ by a constant."""
    rng = np.random.default_rng(11)
    for _ in range(50):
        run = simulate_referencing(_axis(), 0.1 - 30e-6, rng=rng,
                                   moves=(Move(0.1 + 2e-3, 0.05), Move(0.1 - 1e-3, 0.05)))
        kb = run.event("B").index
        diff = run.controller_side[kb:] - run.output_counts[kb:]
        assert np.all(diff == diff[0])
        assert diff[0] == run.power_up_phase + run.virtual
        ka = run.event("A").index
        assert np.all(run.controller_side[:ka] - run.output_counts[:ka] == run.power_up_phase)


def test_long_move_under_changing_air_never_drifts():
    """Issue 6: after homing, over a long move (2 x 1 m) under changing air, the controller's
    position equals the exact compensated position ⌊c·P/2^B⌋ - o_Z, within one output count of
    c·P/2^B, at every sample (checked with Python fractions on every 50th sample and in floating
    point on all)."""
    air = AirHistory(temperature=20.3, pressure=100900.0, humidity=45.0,
                     temperature_rate=0.01, pressure_rate=3.0, humidity_rate=0.05,
                     material_temperature=21.0, material_rate=0.005)
    ax = _axis(air=air, alpha=11.5e-6, laser=LaserHead(dead_path=0.2))
    run = simulate_referencing(ax, 0.1 - 30e-6, rng=np.random.default_rng(5),
                               moves=(Move(1.1, 0.5, 1.0), Move(0.1, 0.5, 1.0)))
    assert not run.alarms
    assert len(np.unique(run.factor)) > 3  # the factor changed during the move
    kz = run.event("Z").index
    p = run.controller_position()
    exact = run.exact_compensated_counts(slice(kz, None, 50))
    assert all(math.floor(e) == pp for e, pp in zip(exact, p[kz::50].tolist()))
    assert run.tracking()["max_pulse_error"] < 1.0


def test_compensated_position_is_the_true_part_position():
    """Truth test: with no dead path at power-up, changing air and a warm steel work-piece, the
    controller's position is the true displacement referred to 20 °C, within one laser count
    plus one output count; the uncompensated scale is ~270 ppm out."""
    air = AirHistory(temperature=21.0, pressure=100500.0, humidity=40.0, temperature_rate=0.02,
                     pressure_rate=5.0, material_temperature=23.0)
    ax = _axis(air=air, alpha=11.5e-6, position=0.01)
    run = simulate_referencing(ax, 0.0, power_up_position=0.0,
                               moves=(Move(1.0, 0.5, 1.0),))
    t = run.tracking()
    laser_count = ax.laser.count_size
    assert t["max_part_error_um"] * 1e-6 < laser_count + ax.output.count_size
    assert t["end_part_mm"] == pytest.approx(t["end_true_mm"] / (1 + 11.5e-6 * 3), rel=1e-12)
    assert (t["end_uncompensated_mm"] / t["end_part_mm"] - 1) * 1e6 == pytest.approx(
        (run.n[-1] * (1 + 11.5e-6 * 3) - 1) * 1e6, abs=0.7)  # one 0.633 µm count in 1 m


def test_dead_path_error_of_the_laser_is_modelled():
    """With a dead path L0 at power-up, a change Δn of the air moves the compensated reading by
    L0·Δn/n (the classic dead-path error) even though pulse multiplication is exact."""
    air = AirHistory(temperature=20.0, temperature_rate=0.5)  # 0.5 K/s: Δn ≈ -0.48 ppm/s
    ax = _axis(air=air, position=0.5, laser=LaserHead(dead_path=1.0))
    run = simulate_referencing(ax, 0.5 - 20e-6, moves=(Move(0.5 + 60e-6, 5e-6, 1.0),))
    # during the slow final move (4 s, 2 K) the reading shifts by L0 (n - n_Z) / n, about
    # -1.5 m x 1.9 ppm = -2.9 µm, less the sensors' lag (up to one update interval, 0.7 µm)
    t = run.tracking()
    kz = run.event("Z").index
    l0 = 1.0 + 0.5 - 20e-6
    predicted = l0 * (run.n[-1] - run.n[kz]) / run.n[-1]
    error = t["end_controller_mm"] * 1e-3 - t["end_part_mm"] * 1e-3
    assert predicted < -2.5e-6
    assert error == pytest.approx(predicted, abs=0.75e-6 + ax.laser.count_size)


def test_exceeding_the_controller_input_frequency_is_reported():
    """Issue 6: exceeding the controller's input frequency is detected and reported."""
    ax = _axis(fmax=50e3)  # 1 m/s at 20 µm is 50 kHz
    ok = simulate_referencing(ax, 0.1 - 30e-6, moves=(Move(0.6, 0.9, 5.0),))
    assert ok.alarms == ()
    bad = simulate_referencing(ax, 0.1 - 30e-6, moves=(Move(0.6, 1.2, 5.0),))
    assert len(bad.alarms) == 1
    assert bad.alarms[0].kind == "input frequency"
    assert bad.alarms[0].value == pytest.approx(60e3, rel=0.02)


@pytest.mark.parametrize("n,period", [(128, 20e-6), (64, 20e-6), (256, 40e-6), (512, 100e-6)])
def test_other_output_formats_home_at_five_quarters_of_a_period(n, period):
    rng = np.random.default_rng(n)
    for _ in range(40):
        ax = _axis(n=n, period=period)
        run = simulate_referencing(ax, 0.1 - 3 * period, rng=rng)
        for name, nominal in (("Z", 5 * n // 4), ("C", 3 * n // 2)):
            e = run.event(name)
            assert e.nominal_counts == nominal
            assert abs(e.counts_beyond_switch - nominal) <= e.uncertainty_counts + 0.6


def test_result_text_and_dict():
    run = simulate_referencing(_axis(), 0.1 - 30e-6, rng=np.random.default_rng(1))
    d = run.to_dict()
    assert [e["name"] for e in d["events"]] == ["A", "B", "Z", "C"]
    assert [e["nominal_counts"] for e in d["events"]] == [0, 256, 320, 384]
    for e in d["events"]:
        assert abs(e["counts_beyond_switch"] - e["nominal_counts"]) <= e["uncertainty_counts"] + 0.6
    assert "home (Z)" in str(run)


def test_start_beyond_the_switch_is_refused():
    with pytest.raises(InputError, match="not before the switch"):
        simulate_referencing(_axis(), 0.2)
    with pytest.raises(InputError, match="counts"):
        ScaleAxis(controller=Controller(counts_per_period=128, count_size=20e-6 / 128))


def test_a_jump_the_controller_cannot_follow_is_reported():
    """A sudden large factor change (the sensors' reading steps by 10 K at an update, far from
    the laser's power-up point) adds hundreds of output pulses at once; the model reports it
    rather than letting the decoder miscount silently."""
    air = AirHistory(temperature=20.0, temperature_rate=10.0)
    ax = _axis(air=air, position=0.01, fmax=1e9)
    run = simulate_referencing(ax, 0.0, moves=(Move(1.5, 0.5, 1.0),))
    assert "signal step" in {a.kind for a in run.alarms}
    quiet = simulate_referencing(_axis(position=0.01, fmax=1e9), 0.0, moves=(Move(1.5, 0.5, 1.0),))
    assert quiet.alarms == ()
