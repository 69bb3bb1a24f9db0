"""Every instrument simulator implements the typing.Protocol a real driver would implement
(ARCHITECTURE.md, layer 5), and its reading agrees with the vectorised physics the procedures
use."""

import math

import numpy as np
import pytest

from axiscal.errors import AxiscalError, SignalLossError
from axiscal.instruments.five_dof import FiveDofSensor, FiveDofSystem, SimulatedFiveDofSensor
from axiscal.instruments.laser import (
    AngularLaser, SimulatedAngularInterferometer, SimulatedAngularLaser)
from axiscal.instruments.laser_scale import (
    HomeSwitch, LaserHead, LaserScale, ReferenceSwitch, SimulatedHomeSwitch, SimulatedLaserScale)
from axiscal.instruments.rotary_calibrator import RotaryCalibrator, SimulatedRotaryCalibrator
from axiscal.machines.rotary import Pose
from axiscal.physics.misalignment import reflector_pose
from axiscal.units import ARCSEC, DEG, UM


def test_the_bare_simulators_do_not_pass_for_drivers():
    """runtime_checkable really checks: the vectorised simulator lacks read_angle, so only the
    adapter is an AngularLaser (guards against a protocol that accepts anything)."""
    assert not isinstance(SimulatedAngularInterferometer(), AngularLaser)
    assert not isinstance(LaserHead(), LaserScale)
    assert not isinstance(FiveDofSystem(), FiveDofSensor)
    assert not isinstance(ReferenceSwitch(0.1), HomeSwitch)


def test_angular_laser_adapter_implements_the_protocol_and_matches_the_chain():
    """The adapter's per-reading angle equals the vectorised read of _rotary_chain (same path
    difference from the datum, same K, same periscope drift), without noise."""
    optics = SimulatedAngularInterferometer(spacing=30.05e-3, nonparallelism=10 * ARCSEC,
                                            beam_tilt=0.8e-3)
    laser = SimulatedAngularLaser(optics)
    assert isinstance(laser, AngularLaser)
    theta = np.radians([0.0, 1.5, -4.0, 7.0])
    u, c = reflector_pose(theta, 0.0, 0.4e-3, 0.3, 1.2e-3, 0.05, (0.2e-3, -0.1e-3))
    laser.place(u[0], c[0])
    laser.zero()
    laser.set_correction(1.0016)
    dl = optics.path_difference(u, c) - optics.path_difference(u[:1], c[:1])
    expected = optics.read(dl, 1.0016, 0.3)
    for i in range(theta.size):
        laser.place(u[i], c[i], temperature_change=0.3)
        assert laser.read_angle() == pytest.approx(expected[i], abs=1e-15)
    assert laser.read_angle() == pytest.approx(math.radians(7.0), abs=5 * ARCSEC)


def test_angular_laser_adapter_loses_signal_and_refuses_bad_k():
    laser = SimulatedAngularLaser(SimulatedAngularInterferometer())
    with pytest.raises(AxiscalError, match="place"):
        laser.read_angle()
    laser.place(*reflector_pose(math.radians(12.0), 0.0, 0.0, 0.0, 0.0))
    with pytest.raises(SignalLossError, match=r"\+12.0°"):
        laser.read_angle()
    with pytest.raises(AxiscalError, match="k=0"):
        laser.set_correction(0.0)


def test_rotary_calibrator_implements_the_protocol():
    """rotate_to reads the encoder at the commanded angle: graduation error without wander."""
    cal = SimulatedRotaryCalibrator.xr20_like(np.random.default_rng(3), error_map=False)
    assert isinstance(cal, RotaryCalibrator)
    angle = 37.0 * DEG
    reading = cal.rotate_to(angle)
    assert isinstance(reading, float)
    assert reading == pytest.approx(angle + float(cal.systematic_error(angle)[0]),
                                    abs=cal.encoder.resolution)
    assert abs(reading - angle) > 0.05 * ARCSEC          # the graduation error is really read


def test_five_dof_adapter_implements_the_protocol_and_matches_the_system():
    system = FiveDofSystem().with_realistic_mounting().noiseless()
    sensor = SimulatedFiveDofSensor(system)
    assert isinstance(sensor, FiveDofSensor)
    pose = Pose(*(np.array([v]) for v in (0.6, 5 * ARCSEC, 2 * ARCSEC, -3 * ARCSEC, 0.0,
                                          1 * UM, -0.5 * UM)))
    sensor.place(pose, -0.6, (1e-6, -2e-6))
    spots = sensor.read_detectors()
    ref = system.read(pose, -0.6, (1e-6, -2e-6))
    for got, want in zip(spots, (ref.psd1, ref.psd2, ref.qd1, ref.qd2)):
        assert got.shape == (2,)
        assert np.allclose(got, want[0], rtol=0, atol=1e-15)
    assert np.abs(spots[0]).max() > 1 * UM             # a 5 arcsec yaw moves the PSD spot
    with pytest.raises(AxiscalError, match="one angle"):
        sensor.place(Pose(*(np.zeros(2),) * 7), 0.0)


def test_laser_scale_adapter_counts_like_the_head():
    """One count per λ_vac (0.633 µm, seed 002) of motion in vacuum; fewer in air, as the head."""
    head = LaserHead()
    scale = SimulatedLaserScale(head, position=0.010, n=1.00027, phase=0.25)
    assert isinstance(scale, LaserScale)
    assert scale.read_counts() == 0
    for x in (0.010 + 6.33e-6, 0.0105, 0.2):
        scale.move_to(x)
        assert scale.read_counts() == int(head.counts([x], [1.00027], 0.010, 1.00027, 0.25)[0])
    scale.move_to(0.010 + 1e-3, n=1.0)
    assert scale.read_counts() == int(head.counts([0.011], [1.0], 0.010, 1.00027, 0.25)[0])


def test_home_switch_adapter_trips_at_its_drawn_trip_point():
    switch = ReferenceSwitch(0.100, repeatability=2 * UM)
    sim = SimulatedHomeSwitch(switch, np.random.default_rng(8))
    assert isinstance(sim, HomeSwitch)
    trip = sim.trip
    assert trip != 0.100 and abs(trip - 0.100) < 10 * UM
    sim.move_to(trip - 0.1 * UM)
    assert sim.is_on() is False
    sim.move_to(trip + 0.1 * UM)
    assert sim.is_on() is True


def test_compensator_unit_adapter_gives_the_counts_of_the_vectorised_chain():
    """Streaming through the adapter (feed, sensor update, feed) gives exactly
    floor(c·P/2^32) with the factor in force at each sample, as referencing computes it."""
    from axiscal.instruments.compensator import (
        Compensator, CompensatorUnit, SimulatedCompensatorUnit, multiply)

    comp = Compensator()
    unit = SimulatedCompensatorUnit(comp, 20.0, 101325.0, 50.0)
    assert isinstance(unit, CompensatorUnit)
    rng = np.random.default_rng(5)
    inc1, inc2 = rng.integers(-30, 4000, 500), rng.integers(-30, 4000, 500)   # about 0.6 m
    out = list(np.cumsum(unit.feed(inc1)))
    added = unit.update_sensors(24.0, 99000.0, 30.0, 21.0)
    out2 = out[-1] + added + np.cumsum(unit.feed(inc2))
    counts = np.cumsum(np.concatenate([inc1, inc2]))
    p1, p2 = comp.factor(20.0, 101325.0, 50.0), comp.factor(24.0, 99000.0, 30.0, 21.0)
    expected = multiply(counts, np.r_[np.full(500, p1), np.full(500, p2)])
    assert np.array_equal(np.r_[out, out2], expected)
    assert added != 0                                   # the weather change re-scales the count
