"""Laser head and reference switch (seed 002)."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.instruments.laser_scale import LaserHead, ReferenceSwitch
from axiscal.physics.air import refractive_index


def test_seed_002_wavelength_and_effective_pitch():
    """Seed 002: 'a very short wavelength of only 0.633 microns. The use of a reflector doubles
    the sensitivity, so the effective scale pitch is 0.316 microns (about 60 times finer than
    [a 20 µm scale])'; the head's quadrature resolution is 0.633 µm."""
    head = LaserHead()
    assert round(head.vacuum_wavelength * 1e6, 3) == 0.633
    assert round(head.count_size * 1e6, 3) == 0.633
    pitch = head.effective_pitch(refractive_index(20.0, 101325.0, 50.0))
    assert int(pitch * 1e9) == 316  # 0.3164 µm in air, 0.316 µm as the seed writes it
    assert 60 < 20e-6 / pitch < 65
    assert LaserHead(counts_per_wavelength=2).count_size == pytest.approx(head.effective_pitch())


def test_quadrature_is_gray_code_and_decodes_back():
    head = LaserHead()
    c = np.array([0, 1, 2, 3, 4, 3, 2, 1, 0, -1, -2])
    a, b = head.quadrature(c)
    state = (b.astype(int) << 1) | (a ^ b).astype(int)  # 0,1,2,3 along the Gray sequence
    assert np.array_equal(np.mod(c, 4), state)
    # exactly one of A and B changes per count
    assert np.all((a[1:] != a[:-1]) ^ (b[1:] != b[:-1]))


def test_counts_follow_optical_path_and_drift_with_the_air():
    """The count is n·L/(λ/k) from power-up: at rest, a change of n moves the uncompensated
    reading by the dead path times Δn/n (the drift of an uncompensated laser)."""
    head = LaserHead(dead_path=0.5)
    n0 = 1.000271
    x = np.array([0.0, 0.1, 0.1])
    n = np.array([n0, n0, n0 + 1e-6])
    c = head.counts(x, n, 0.0, n0, phase=0.3)
    assert c[0] == 0
    raw = head.uncompensated_position(c)
    assert raw[1] == pytest.approx(0.1 * n0, abs=head.count_size)  # 271 ppm long
    assert raw[2] - raw[1] == pytest.approx(0.6 * 1e-6, abs=head.count_size)


def test_analogue_fringes_have_the_effective_pitch():
    head = LaserHead()
    x = np.linspace(0.1, 4.1, 401) * head.effective_pitch()
    s, c = head.analogue(x)
    crossings = np.sum((s[:-1] < 0) & (s[1:] >= 0))
    assert crossings == 4


def test_raw_fringe_frequency_is_too_high_for_the_controller():
    """Seed 002: the raw resolution is too high for the controller's count frequency."""
    head = LaserHead()
    assert head.fringe_frequency(1.0) == pytest.approx(1.0 / 316.4955e-9, rel=1e-6)  # 3.16 MHz
    assert head.count_rate(1.0) == pytest.approx(1.0 / 632.991e-9)


def test_switch_trips_with_repeatability_and_validation():
    sw = ReferenceSwitch(position=0.1, repeatability=1e-6)
    rng = np.random.default_rng(0)
    trips = np.array([sw.trip_point(rng) for _ in range(4000)])
    assert trips.std() == pytest.approx(1e-6, rel=0.05)
    assert abs(trips.mean() - 0.1) < 1e-7
    assert sw.trip_point() == 0.1
    assert sw.state([0.0999, 0.1, 0.2]).tolist() == [False, True, True]
    low = ReferenceSwitch(0.1, active_above=False)
    assert low.state([0.0999, 0.1, 0.2]).tolist() == [True, True, False]
    with pytest.raises(InputError):
        ReferenceSwitch(0.1, repeatability=-1)
    with pytest.raises(InputError):
        LaserHead(counts_per_wavelength=0)
    with pytest.raises(InputError):
        LaserHead(vacuum_wavelength=10e-6)
