"""Interferometry: fringes, dead path, cosine error, angular optics and their self-calibration."""

import math

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.physics import interferometry as itf
from axiscal.units import ARCSEC


def test_seed002_effective_pitch_of_0633um_light():
    """Seed 002: 0.633 µm light; "the use of a reflector doubles the sensitivity, so the effective
    scale pitch is 0.316 microns" (0.3165, truncated in the seed)."""
    pitch = itf.effective_pitch(0.633e-6, "linear")
    assert pitch == pytest.approx(0.3165e-6, rel=1e-12)
    assert math.floor(pitch * 1e9) / 1e3 == 0.316
    assert itf.effective_pitch(0.633e-6, "plane_mirror") == pytest.approx(pitch / 2)


def test_fringes_to_displacement_is_lambda_n_over_2():
    """Seed 001 eq. 22: d = λN/2, with λ the wavelength in air (λ_vac / n)."""
    lam_air = itf.HENE_VACUUM_WAVELENGTH / 1.00027
    d = itf.fringes_to_displacement(np.array([0.0, 1.0, 3160.5]), n=1.00027)
    assert np.allclose(d, lam_air * np.array([0.0, 1.0, 3160.5]) / 2, rtol=1e-14)
    # plane mirror optics: λ/4 per fringe
    assert itf.fringes_to_displacement(2.0, n=1.0, optics="plane_mirror") == pytest.approx(
        itf.HENE_VACUUM_WAVELENGTH / 2)
    with pytest.raises(InputError, match="optics"):
        itf.fringes_to_displacement(1.0, optics="wollaston")
    with pytest.raises(InputError, match="refractive index"):
        itf.fringes_to_displacement(1.0, n=0.9)


def test_dead_path_correction_recovers_true_displacement():
    """Optical path n_now(L_d + d) - n_datum L_d read with n_now; the correction gives d back."""
    ld, d, n0, n1 = 0.8, 0.25, 1.000271, 1.000271 - 2.7e-6
    reading = (n1 * (ld + d) - n0 * ld) / n1
    assert reading - d == pytest.approx(ld * (n1 - n0) / n1, rel=1e-9)   # about -2.2 µm
    assert itf.dead_path_correction(reading, ld, n0, n1) == pytest.approx(d, abs=1e-15)
    with pytest.raises(InputError, match="dead_path"):
        itf.dead_path_correction(0.1, -1.0, n0, n1)


def test_cosine_error_reads_short():
    e = itf.cosine_error(np.array([0.5, 1.0]), 2e-3)
    assert np.allclose(e, -np.array([0.5, 1.0]) * (1 - math.cos(2e-3)))
    assert np.all(e < 0)


def test_seed000_spacing_30_1_vs_30_0_mm_gives_12_arcsec_at_1_degree():
    """Seed 000, "Incorrect retro-reflector spacing": 30.1 mm instead of 30.0 mm at 1° gives
    "approximately 0.1mm/30mm x 1° = 0.0033° = 12 arcseconds"."""
    dl = itf.path_difference(math.radians(1.0), 30.1e-3)
    assert dl == pytest.approx(30.1e-3 * math.sin(math.radians(1.0)))   # intermediate: ΔL
    err = itf.angle_from_path_difference(dl, 30.0e-3) - math.radians(1.0)
    assert err / ARCSEC == pytest.approx(12.0, abs=0.05)
    assert itf.spacing_error_angle(math.radians(1.0), 30.1e-3, 30.0e-3) == pytest.approx(err)


def test_seed000_self_calibration_brings_spacing_error_below_0_1_arcsec():
    """Seed 000: after the optics calibration at 0, +5°, -5° "the 0.1 mm error in retro-reflector
    spacing will be compensated for and the measurement error reduced below 0.1 arcseconds".
    Readings carry 1 nm of laser noise and the reflector is 40 arcsec off at the datum."""
    rng = np.random.default_rng(3)
    s_true, s_nom, phi0 = 30.1e-3, 30.0e-3, 40 * ARCSEC
    a = math.radians(5.0)

    def reading(x):
        return s_true * (math.sin(phi0 + x) - math.sin(phi0)) + rng.normal(0, 1e-9)

    cal = itf.optics_self_calibration(reading(a), reading(-a), s_nom)
    assert cal.k == pytest.approx(s_true / s_nom, abs=2e-5)
    assert cal.datum_misalignment / ARCSEC == pytest.approx(40.0, abs=5.0)   # the sum of two readings carries φ0: 1 nm ~ 1 arcsec
    # after re-datum (reflector turned by -phi0), readings at 1° use K
    dl = itf.path_difference(math.radians(1.0), s_true)
    err = itf.angle_from_path_difference(dl, s_nom, cal.k) - math.radians(1.0)
    assert abs(err) / ARCSEC < 0.1
    assert "K =" in str(cal)


def test_self_calibration_refuses_readings_that_do_not_grow_with_angle():
    with pytest.raises(InputError, match="angular sign"):
        itf.optics_self_calibration(-1e-3, 1e-3, 30e-3)


def test_seed000_one_kelvin_with_2_5_degree_misalignment_is_about_0_01_arcsec():
    """Seed 000: "a 1°C change in air temperature, when the interferometer and reflector are
    misaligned by 2.5°, will only introduce a change in reading of about 0.05 micro-radians,
    (0.01 arcseconds)". dn/dT of standard air about -0.95e-6 /K (issue 3 rule of thumb)."""
    e = itf.refraction_angle_error(math.radians(2.5), -0.95e-6)
    assert abs(e) * 1e6 == pytest.approx(0.05, abs=0.01)
    assert abs(e) / ARCSEC == pytest.approx(0.01, abs=0.002)


def test_seed000_nonparallel_beams_half_arcsec_per_mm():
    """Seed 000: ±15 arcsec beam non-parallelism gives ±0.5 arcsec per mm of lateral motion, and
    ±0.25 arcsec for ±0.5 mm."""
    assert itf.nonparallel_beam_error(1e-3, 15 * ARCSEC, 30e-3) / ARCSEC == pytest.approx(0.5)
    assert itf.nonparallel_beam_error(0.5e-3, 15 * ARCSEC, 30e-3) / ARCSEC == pytest.approx(0.25)


def test_angle_beyond_spacing_is_refused():
    with pytest.raises(InputError, match=r"\|ΔL/\(K·S\)\|"):
        itf.angle_from_path_difference(0.04, 0.03)


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@settings(max_examples=80, deadline=None)
@given(st.floats(0.99, 1.01), st.floats(-0.01, 0.01), st.floats(1.0, 10.0), st.floats(-10.0, -1.0))
def test_self_calibration_recovers_any_k_and_datum_angle(k, phi0, step_p, step_m):
    """Property: for any spacing factor, datum misalignment and (asymmetric) reference steps, the
    two-step solution returns K and φ0 exactly (no noise)."""
    s = 30e-3
    a, b = math.radians(step_p), math.radians(step_m)

    def dl(x):
        return k * s * (math.sin(phi0 + x) - math.sin(phi0))

    cal = itf.optics_self_calibration(dl(a), dl(b), s, a, b)
    assert cal.k == pytest.approx(k, rel=1e-9)
    assert cal.datum_misalignment == pytest.approx(phi0, abs=1e-10)
    assert abs(cal.zero_return) < 1e-12
