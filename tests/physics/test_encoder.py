"""Encoder geometry, read-heads and error map (seed 000, "Inaccuracies in the rotary encoder")."""

import math

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.physics import encoder as enc
from axiscal.units import ARCSEC


def test_seed000_7850_graduations_165_arcsec_and_0_08_arcsec_at_2000x():
    """Seed 000: "7,850 graduations at 20 µm intervals around the periphery of the XR20's 50mm
    diameter encoder disk. Giving an effective angular interval ... of 165 arcseconds" and
    "sub-divide each angular interval by 2000x to give an angular resolution of ~0.08 arcseconds"."""
    g = enc.EncoderGeometry(graduations=7850, diameter=50e-3, interpolation=2000)
    assert g.pitch * 1e6 == pytest.approx(20.0, abs=0.02)        # intermediate: 20 µm pitch
    assert g.period / ARCSEC == pytest.approx(165.0, abs=0.2)
    assert g.resolution / ARCSEC == pytest.approx(0.08, abs=0.004)
    q = g.quantize(np.array([0.0, 0.3 * g.resolution, 0.7 * g.resolution]))
    assert np.allclose(q / g.resolution, [0, 0, 1])


def test_seed000_bearing_wander_8_25_arcsec_one_head_cancels_with_two():
    """Seed 000: "radial bearing wander of just ±1 micrometres, in combination with a 50mm diameter
    encoder disk, would produce a significant error of ±8.25 arcseconds"; with two diametrically
    opposed heads "the error is eliminated"."""
    t = np.array([-1e-6, 1e-6])
    head1 = enc.readhead_displacement_error(0.0, t, 0.0, 25e-3)
    head2 = enc.readhead_displacement_error(0.0, t, math.pi, 25e-3)
    assert np.allclose(head1 / ARCSEC, [-8.25, 8.25], atol=0.01)
    assert np.allclose(head2, -head1)
    assert np.max(np.abs(enc.average_readheads(head1, head2))) < 1e-15


def test_eccentricity_is_once_per_turn_on_one_head_and_cancels_on_two():
    ang = np.linspace(0, 2 * math.pi, 73)
    dx, dy = enc.eccentricity_displacement(ang, 5e-6, 0.3)
    h1 = enc.readhead_displacement_error(dx, dy, 0.0, 25e-3)
    h2 = enc.readhead_displacement_error(dx, dy, math.pi, 25e-3)
    assert np.max(np.abs(h1)) / ARCSEC == pytest.approx(5e-6 / 25e-3 / ARCSEC, rel=1e-3)
    assert np.max(np.abs((h1 + h2) / 2)) < 1e-15


def test_two_heads_cancel_odd_graduation_harmonics_and_keep_even():
    def g(x):
        return 3e-6 * np.sin(x) + 1e-6 * np.sin(2 * x + 0.4) + 0.5e-6 * np.sin(3 * x)
    ang = np.linspace(0, 2 * math.pi, 181)
    per, avg = enc.graduation_error_at_heads(ang, g)
    assert per.shape == (2, 181)
    assert np.allclose(avg, 1e-6 * np.sin(2 * ang + 0.4), atol=1e-15)


def test_error_map_correction_actual_is_reading_minus_error():
    """Seed 000: "Actual position = Average read-head position ± error map correction"."""
    def err(a):
        return 4 * ARCSEC * np.sin(2 * a + 0.2) + 1 * ARCSEC * np.cos(6 * a)
    m = enc.ErrorMap.from_function(err, 720)
    actual = np.linspace(0, 2 * math.pi, 1000, endpoint=False)
    reading = actual + err(actual)
    residual = m.correct(reading) - actual
    assert np.max(np.abs(residual)) / ARCSEC < 0.01
    assert np.max(np.abs(reading - actual)) / ARCSEC > 4.0
    with pytest.raises(InputError, match="increase strictly"):
        enc.ErrorMap(np.array([0.0, 1.0, 0.5]), np.zeros(3))


def test_geometry_refuses_bad_values():
    with pytest.raises(InputError, match="graduations"):
        enc.EncoderGeometry(graduations=2.5)
    with pytest.raises(InputError, match="diameter"):
        enc.EncoderGeometry(diameter=-1)
