"""Issue 20: every over-frequency burst detected, and the events measured, not assumed.

Physics (Renishaw, "Laser scale axis referencing with controllers with low bandwidth sine and
cosine inputs", seed 002, Figure 4): in stage 2 the compensator adds v virtual counts (0..N−1)
to N counts of real motion, so the controller's inputs run at (N + v)/N times the real signal
frequency f = speed / period for the N counts of real motion, N·q/speed seconds. At 1.9 m/s that
is 10.5 µs: shorter than the controller's 100 µs frequency gate.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from axiscal.instruments.compensator import Compensator, SineOutput
from axiscal.instruments.controller import Controller
from axiscal.instruments.laser_scale import LaserHead, ReferenceSwitch
from axiscal.procedures.referencing import AirHistory, ScaleAxis, simulate_referencing

N = 256
PERIOD = 20e-6
Q = PERIOD / N
SWITCH = 0.1


def _axis(rephase_periods=1, air=AirHistory()):
    laser = LaserHead()
    out = SineOutput(PERIOD, N)
    comp = Compensator(laser=laser, output=out, rephase_periods=rephase_periods)
    ctl = Controller(counts_per_period=N, count_size=Q, max_input_frequency=100e3,
                     frequency_gate=100e-6)
    return ScaleAxis(laser=laser, compensator=comp, switch=ReferenceSwitch(SWITCH), controller=ctl,
                     air=air)


def _home(speed, axis=None):
    return simulate_referencing(axis or _axis(), SWITCH - 40e-6, speed, power_up_phase=0)


def _burst_frequency(run, speed):
    """First principles: (N + v)/N × speed / period (no air, no work-piece: q is real)."""
    return (N + run.virtual) / N * speed / PERIOD


def test_a_burst_shorter_than_the_gate_is_alarmed():
    """The issue's case: 1.9 m/s from 40 µm before the switch, power-up phase 0. The real
    signal is 95 kHz (under the limit); stage 2 lasts ~10.5 µs at ~180 kHz. The gated monitor
    alone stays under the limit; the edge rate catches it and reports the true peak."""
    speed = 1.9
    run = _home(speed)
    ctl = run.axis.controller
    expected = _burst_frequency(run, speed)
    assert run.virtual > N // 2 and expected > 1.5 * ctl.max_input_frequency
    duration = N * Q / speed
    assert duration < 0.2 * ctl.frequency_gate                     # 10.5 µs against 100 µs
    gated = ctl.input_frequency(run.controller_side, run.time)
    assert gated.max() < ctl.max_input_frequency                   # the gate hides the burst
    assert len(run.alarms) == 1 and run.alarms[0].kind == "input frequency"
    alarm = run.alarms[0]
    # the reported peak is the burst's frequency, within 1 % (the staircase: ±2 counts in N)
    assert alarm.value == pytest.approx(expected, rel=0.01)
    assert run.peak_input_frequency == pytest.approx(expected, rel=0.01)
    # raised during stage 2, between A and B
    t_a, t_b = run.event("A").time, run.event("B").time
    assert t_a <= run.time[alarm.index] <= t_b
    assert f"{alarm.value / 1e3:.2f} kHz" in alarm.message


def test_a_burst_just_under_the_limit_is_not_alarmed():
    """The same homing at the speed that puts the stage-2 burst at 98 % of the limit (found
    from the first-principles formula with this run's v): no alarm, and the peak reported is
    the burst's, not quantised to the gate."""
    v = _home(0.005).virtual                       # v does not depend on the speed here
    speed = 0.98 * 100e3 * PERIOD * N / (N + v)
    run = _home(speed)
    assert run.virtual == v
    assert run.alarms == ()
    assert run.peak_input_frequency == pytest.approx(_burst_frequency(run, speed), rel=0.01)
    assert run.peak_input_frequency < 100e3
    # and 3 % over the limit is alarmed although the burst is far shorter than the gate
    over = _home(1.03 * 100e3 * PERIOD * N / (N + v))
    assert [a.kind for a in over.alarms] == ["input frequency"]


def test_spreading_the_rephasing_keeps_the_controller_within_its_limit():
    """Compensator setting: the virtual movement spread over k periods of real motion (k from
    rephase_periods_for) keeps the burst under the limit at 1.9 m/s, with the home still a fixed
    kN + N/4 counts beyond the switch (measured from the motion)."""
    from axiscal.instruments.compensator import rephase_periods_for

    k = rephase_periods_for(1.9, SineOutput(PERIOD, N), 100e3)
    run = _home(1.9, _axis(rephase_periods=k))
    assert k > 1 and run.alarms == ()
    assert run.peak_input_frequency < 100e3
    z = run.event("Z")
    assert z.nominal_counts == k * N + N // 4
    assert abs(z.counts_beyond_switch - z.nominal_counts) <= z.uncertainty_counts + 0.6
    assert run.homed


def test_events_are_measured_from_the_simulated_motion():
    """Each event's position is the true motion from the switch trip point at its sample (the
    simulation's x, no air change, no work-piece: the part is the axis), computed here from the
    trace; it lies within one laser count (0.633 µm = 8.1 output counts) of the design value,
    and that uncertainty is stated."""
    run = simulate_referencing(_axis(), SWITCH - 30e-6, 0.005, rng=np.random.default_rng(7))
    laser_count = run.axis.laser.count_size / run.n[0] / Q
    assert laser_count == pytest.approx(0.633 / 0.078125, rel=1e-3)
    for e, nominal in zip(run.events, (0, N, N + N // 4, N + N // 2)):
        truth = (run.position[e.index] - run.switch_trip) / Q
        assert e.counts_beyond_switch == pytest.approx(truth, abs=1e-9)
        assert e.nominal_counts == nominal
        assert e.uncertainty_counts == pytest.approx(laser_count, rel=1e-9)
        assert abs(truth - nominal) <= laser_count + 0.6
    d = run.to_dict()["events"][1]
    assert d["nominal_counts"] == N and d["uncertainty_counts"] == pytest.approx(8.1, abs=0.01)


def test_tracking_error_is_against_the_true_part_position():
    """After homing, a 5 mm move in warm air with a steel work-piece: the tracking error is the
    controller's position against the true part position referred to 20 °C, recomputed here from
    the simulation's truth (x, material temperature); it is within one laser count plus one
    output count (no dead path at power-up), and the pulse error is the separate < 1 count."""
    from axiscal.procedures.referencing import Move

    air = AirHistory(temperature=21.0, pressure=100500.0, humidity=40.0,
                     material_temperature=23.0)
    axis = _axis(air=air)
    axis = replace(axis, compensator=replace(axis.compensator, expansion_coefficient=11.5e-6))
    run = simulate_referencing(axis, SWITCH - 30e-6, 0.005, power_up_position=SWITCH - 30e-6,
                               moves=(Move(SWITCH + 5e-3, 0.05, 1.0),))
    t = run.tracking()
    kz = run.event("Z").index
    part = (run.position[kz:] - run.position[kz]) / (1 + 11.5e-6 * 3.0) / Q
    ctl = run.controller_position()[kz:] - run.controller_position()[kz]
    truth_error = float(np.max(np.abs(ctl - part)))
    assert t["max_count_error"] == pytest.approx(truth_error, rel=1e-9)
    assert t["max_count_error"] <= t["count_uncertainty"] + 1.0
    assert t["max_count_error"] > 1.0               # the laser count shows: not the pulse error
    assert t["max_pulse_error"] < 1.0


def test_no_spreading_helps_when_the_real_motion_exceeds_the_limit():
    """rephase_periods_for refuses by name a homing speed whose real signal (speed / period,
    plus 2 counts in N for whole counts) already reaches the limit: 2 m/s is 100 kHz at 20 µm."""
    from axiscal.errors import InputError
    from axiscal.instruments.compensator import rephase_periods_for

    with pytest.raises(InputError, match="100.00 kHz.*home slower"):
        rephase_periods_for(2.0, SineOutput(PERIOD, N), 100e3)
    assert rephase_periods_for(0.005, SineOutput(PERIOD, N), 100e3) == 1
