"""Simulated angular interferometer and rotary calibrator (seed 000)."""

import math

import numpy as np
import pytest

from axiscal.errors import InputError, SignalLossError
from axiscal.instruments.laser import SimulatedAngularInterferometer
from axiscal.instruments.rotary_calibrator import SimulatedRotaryCalibrator
from axiscal.physics.misalignment import reflector_pose
from axiscal.units import ARCSEC, DEG


def test_laser_path_difference_is_s_sin_theta_for_an_aligned_reflector():
    laser = SimulatedAngularInterferometer(spacing=30e-3)
    th = np.radians([-8.0, -1.0, 0.0, 2.0, 9.0])
    u, c = reflector_pose(th, 0.0, 0.0, 0.0, 0.0)
    assert np.allclose(laser.path_difference(u, c), 30e-3 * np.sin(th), atol=1e-15)


def test_laser_loses_signal_beyond_ten_degrees():
    """Seed 000: the interferometer alone is 'only suitable for checking angular movements over
    a range of about ±10°' because the returned beams are lost: a clear error, not a zero."""
    laser = SimulatedAngularInterferometer()
    u, _ = reflector_pose(np.radians([5.0, 9.9]), 0.0, 0.0, 0.0, 0.0)
    laser.check_signal(u)
    u, _ = reflector_pose(np.radians([5.0, 12.0]), 0.0, 0.0, 0.0, 0.0)
    with pytest.raises(SignalLossError, match=r"turned \+12.0°"):
        laser.check_signal(u)


def test_nonparallel_beams_read_lateral_motion_as_half_arcsec_per_mm():
    """Seed 000: 15 arcsec non-parallelism, 'a small measurement error of ±0.5 arcseconds for every
    millimetre of lateral motion', from the beam geometry of the simulator."""
    laser = SimulatedAngularInterferometer(spacing=30e-3, nonparallelism=15 * ARCSEC)
    u, c = reflector_pose(np.zeros(2), 0.0, 0.0, 0.0, 0.0)
    c = c + np.array([[0.0, 0.0, 0.0], [0.0, 1e-3, 0.0]])       # 1 mm sideways
    dl = laser.path_difference(u, c)
    assert abs(dl[1] - dl[0]) / 30e-3 / ARCSEC == pytest.approx(0.5, rel=1e-3)


def test_laser_refuses_out_of_spec_optics():
    with pytest.raises(InputError, match="nonparallelism"):
        SimulatedAngularInterferometer(nonparallelism=100 * ARCSEC)


def test_two_readheads_cancel_bearing_wander_and_eccentricity_one_does_not():
    """Seed 000: ±1 µm wander gives ±8.25 arcsec with one head; 'the use of two read-heads also
    conveniently removes errors due to any small off-centre mounting'."""
    rng = np.random.default_rng(4)
    angles = np.linspace(0, 2 * math.pi, 400, endpoint=False)
    two = SimulatedRotaryCalibrator(bearing_wander=1e-6, eccentricity=3e-6, eccentricity_phase=0.4)
    one = SimulatedRotaryCalibrator(bearing_wander=1e-6, eccentricity=3e-6, eccentricity_phase=0.4,
                                    heads_used=1)
    err_two = two.read(angles, rng) - angles
    err_one = one.read(angles, rng) - angles
    resolution = two.encoder.resolution
    assert np.max(np.abs(err_two)) <= 0.5 * resolution + 1e-12      # only quantisation left
    assert np.std(err_one) / ARCSEC > 8.0                           # 1 µm σ wander + 24.75" ecc.
    # the eccentricity alone: once per turn, 3 µm on 25 mm radius
    ecc_only = SimulatedRotaryCalibrator(eccentricity=3e-6, heads_used=1).systematic_error(angles)
    assert np.max(np.abs(ecc_only)) / ARCSEC == pytest.approx(3e-6 / 25e-3 / ARCSEC, rel=1e-3)


def test_error_map_removes_graduation_error():
    """Seed 000: graduations within ±0.5 µm (just over ±4 arcsec) are 'largely eliminated by error
    mapping'."""
    rng = np.random.default_rng(2)
    angles = np.linspace(0, 2 * math.pi, 997, endpoint=False)
    mapped = SimulatedRotaryCalibrator.xr20_like(rng, bearing_wander=0.0)
    raw = SimulatedRotaryCalibrator.xr20_like(np.random.default_rng(2), bearing_wander=0.0,
                                              error_map=False)
    before = raw.read(angles) - angles
    after = mapped.read(angles) - angles
    assert np.max(np.abs(before)) / ARCSEC > 2.0
    assert np.max(np.abs(after)) / ARCSEC < 0.35
    # the residual sub-divisional error of the heads is within the seed's ±0.25 arcsec
    sde = np.max(np.abs(SimulatedRotaryCalibrator(head_signals=mapped.head_signals)
                        .systematic_error(np.linspace(0, 3 * mapped.encoder.period, 600))))
    assert sde / ARCSEC < 0.25


def test_calibrator_validates():
    with pytest.raises(InputError, match="heads_used"):
        SimulatedRotaryCalibrator(heads_used=3)
    assert abs(SimulatedRotaryCalibrator().rotate_to(10 * DEG) - 10 * DEG) < 0.1 * ARCSEC
