"""Seed 003 equations 1-9 and the resolutions of section 3 ("Measurement resolution")."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from axiscal.errors import InputError
from axiscal.physics import five_dof as eq
from axiscal.units import ARCSEC, UM


def test_angular_resolution_from_psd_and_focal_length():
    """Seed 003 §3: f = 200 mm and a PSD of 0.5 µm give 'the resolution can reach 0.26 arcsec'."""
    rad = eq.angular_resolution(0.5 * UM, 0.200)
    assert rad == pytest.approx(1.25e-6)  # intermediate: 0.5 µm / (2 x 200 mm)
    assert rad / ARCSEC == pytest.approx(0.26, abs=0.005)


def test_tilt_x_resolution_from_qd_and_separation():
    """Seed 003 §3: h = 30 mm with a 0.08 µm QD gives 'as high as 0.27 arcsec' for εx."""
    rad = eq.tilt_x_resolution(0.08 * UM, 0.030)
    assert rad == pytest.approx(0.08e-6 / 0.06)
    assert rad / ARCSEC == pytest.approx(0.27, abs=0.006)


def test_displacement_resolution_from_qd():
    """Seed 003 §3: 'the resolution of the radial and axial motion errors is 0.04 µm'."""
    assert eq.displacement_resolution(0.08 * UM) / UM == pytest.approx(0.04)
    r = eq.resolutions(0.2, 0.03, 0.5 * UM, 0.08 * UM)
    assert r.displacement == pytest.approx(0.04 * UM)
    assert "0.258 arcsec" in str(r)


def test_positioning_error_adds_reference_angle():
    """Eq. 3: εz = ΔY/(2 f1) + θref − θ; a reference turning back 3 arcsec more adds 3 arcsec."""
    e = eq.positioning_error(2 * 0.2 * 5 * ARCSEC, 0.2, math.radians(30) + 3 * ARCSEC, math.radians(30))
    assert e / ARCSEC == pytest.approx(8.0)


def test_tilt_x_and_drift():
    """Eqs. 6 and 7: εx = (ΔZ1 − ΔZ2)/2h; Δβ = ΔY_PSD2/f2."""
    assert eq.tilt_from_quadrants(1 * UM, -1 * UM, 0.03) == pytest.approx(2e-6 / 0.06)
    assert eq.beam_drift(1 * UM, 0.2) == pytest.approx(5e-6)


def test_compensation_signs_and_factor():
    """Eq. 8 (factor 1/2, + for εz, − for εy) and eq. 9 (+ l·Δ): the module's documented reading."""
    assert eq.compensate_angle(0.0, 2e-6, +1) == pytest.approx(1e-6)
    assert eq.compensate_angle(0.0, 2e-6, -1) == pytest.approx(-1e-6)
    assert eq.compensate_displacement(0.0, 2e-6, 0.25) == pytest.approx(0.5e-6)


@pytest.mark.parametrize("call", [
    lambda: eq.autocollimation_angle(1.0, 0.0),
    lambda: eq.tilt_from_quadrants(1.0, 0.0, -0.03),
    lambda: eq.beam_drift(1.0, float("nan")),
    lambda: eq.compensate_angle(0.0, 0.0, 2),
    lambda: eq.compensate_displacement(0.0, 0.0, -1.0),
    lambda: eq.resolutions(0.2, 0.03, 0.0, 0.08e-6),
])
def test_bad_parameters_are_refused(call):
    with pytest.raises(InputError):
        call()


@given(st.floats(-1e-3, 1e-3), st.floats(0.01, 1.0))
def test_autocollimation_inverts_mirror_doubling(angle, f):
    """A mirror tilt ε moves the spot by 2 f ε; eq. 1 gives ε back."""
    assert eq.autocollimation_angle(2 * f * angle, f) == pytest.approx(angle, abs=1e-15)


@given(st.floats(-1e-4, 1e-4), st.floats(-1e-4, 1e-4), st.floats(0.005, 0.1))
def test_common_z_shift_gives_no_tilt(common, tilt, h):
    """A common axial shift of both reflectors never shows as εx (eq. 6 is a difference)."""
    dz1, dz2 = common + tilt * h, common - tilt * h
    assert eq.tilt_from_quadrants(dz1, dz2, h) == pytest.approx(tilt, abs=1e-12)
    assert np.isfinite(eq.tilt_from_quadrants(dz1, dz2, h))
