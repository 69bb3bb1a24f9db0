"""Refractive index of air: agreement with the NIST calculator, validity, humidity, sensitivities.

Test oracle: the PyPI package ``ref-index`` (Prasanth Nair, BSD licence), a transcription of the
equations of the NIST Engineering Metrology Toolbox refractive index of air calculator (Stone and
Zimmerman, Appendix A), whose own tests check it against the calculator's printed output. It is a
``dev`` dependency; the grid tests are skipped where it is not installed.
"""

from __future__ import annotations

import itertools
import warnings

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.physics import air

import ref_index  # the test oracle: a dev dependency (pyproject.toml), never optional here

NIST_TOLERANCE = 1e-9  # issue 3: agreement with the NIST calculator to better than 1e-9 in n


def _grid(equation):
    """Conditions spanning the validity of the NIST equations (issue 3)."""
    temps = [-40.0, -20.0, -0.5, 0.0, 10.0, 20.0, 30.0, 40.0, 60.0, 80.0, 100.0]
    pressures = [10e3, 50e3, 80e3, 101325.0, 120e3, 140e3]
    rhs = [0.0, 25.0, 50.0, 75.0, 100.0]
    waves_nm = [300.0, 400.0, 532.0, 632.991, 800.0, 1064.0, 1550.0, 1700.0]
    co2s = [0.0, 450.0, 2000.0] if equation == "ciddor" else [450.0]
    rows = []
    for t, p, rh, w, c in itertools.product(temps, pressures, rhs, waves_nm, co2s):
        pv = ref_index.rh2wvpp(rh, t)
        if ref_index.f_factor(p, t) * pv / p > 0.2:  # beyond the calculator's humidity range
            continue
        rows.append((t, p, rh, w, c))
    return np.array(rows)


@pytest.mark.parametrize("equation", ["ciddor", "birch-downs"])
def test_agrees_with_nist_calculator_over_grid(equation):
    """NIST EMT calculator (via ref-index): |Δn| < 1e-9 over T, p, RH, λ (and CO2 for Ciddor)."""
    g = _grid(equation)
    assert len(g) > 2000
    t, p, rh, w, c = g.T
    ours = air.refractive_index(t, p, rh, co2=c, vacuum_wavelength=w * 1e-9, equation=equation)
    if equation == "ciddor":
        theirs = [ref_index.ciddor(*row[[3, 0, 1, 2, 4]]) for row in g]
    else:
        theirs = [ref_index.edlen(*row[[3, 0, 1, 2]]) for row in g]
    diff = np.abs(np.asarray(ours) - np.asarray(theirs))
    assert diff.max() < NIST_TOLERANCE, g[np.argmax(diff)]


@pytest.mark.parametrize("equation", ["ciddor", "birch-downs"])
def test_dew_point_and_partial_pressure_agree_with_nist(equation):
    """NIST A-II: dew point gives p_v = p_sv,water(t_d); x_v = f p_v / p, f at the air
    temperature."""
    for t, p, td in [(20.0, 101325.0, 9.0), (35.0, 90e3, 25.0), (5.0, 120e3, -10.0),
                     (-10.0, 60e3, -15.0), (60.0, 101325.0, 40.0)]:
        pv = ref_index.dew_point_wvpp(td)
        for kw in ({"dew_point": td}, {"vapour_pressure": pv}):
            n = air.refractive_index(t, p, **kw, equation=equation)
            if equation == "ciddor":
                want = ref_index.ciddor_ri(632.991, t, p, ref_index.pp2mole_fraction(pv, p, t))
            else:
                want = ref_index.edlen_ri(632.991, t, p, pv)
            assert abs(n - want) < NIST_TOLERANCE


def test_nist_calculator_printed_values():
    """NIST calculator output at 20 °C, 101.325 kPa, 50 %RH, 450 µmol/mol (as recorded in the
    ref-index test suite, ``_test_nist_ciddor_1``): n to 9 decimals and the wavelength in air."""
    waves = [321.456, 500.0, 600.1234, 633.0, 700.0, 1000.987, 1500.8, 1700.0]
    nist_n = [1.000283543, 1.000273781, 1.000271818, 1.000271373, 1.000270657, 1.000269038,
              1.00026819, 1.000268041]
    nist_w = [321.364879, 499.863147, 599.96032, 632.828268, 699.810591, 1000.717769,
              1500.397608, 1699.544453]
    lam = np.array(waves) * 1e-9
    n = air.refractive_index(20.0, 101325.0, 50.0, vacuum_wavelength=lam)
    np.testing.assert_allclose(n, nist_n, rtol=0, atol=6e-10)  # printed to 9 decimals
    wl = air.air_wavelength(20.0, 101325.0, 50.0, vacuum_wavelength=lam) * 1e9
    np.testing.assert_allclose(wl, nist_w, rtol=0, atol=1e-6)


def test_vectorised_matches_scalar_and_keeps_shape():
    t = np.linspace(15, 25, 12).reshape(3, 4)
    n = air.refractive_index(t, 101325.0, 50.0)
    assert n.shape == (3, 4)
    assert n[1, 2] == air.refractive_index(float(t[1, 2]), 101325.0, 50.0)
    assert isinstance(air.refractive_index(20.0, 101325.0, 50.0), float)


def test_edlen_1966_at_standard_air_is_the_dispersion_formula():
    """Edlén (1966): standard air is 15 °C, 760 torr, dry, 300 µmol/mol CO2; there n - 1 is the
    dispersion formula (n-1)_s·1e8 = 8342.13 + 2406030/(130 - σ²) + 15997/(38.9 - σ²)."""
    s = (1 / 0.632991) ** 2
    ns = 1e-8 * (8342.13 + 2406030 / (130 - s) + 15997 / (38.9 - s))
    n = air.refractive_index(15.0, 101325.0, co2=300.0, equation="edlen")
    # equal to the rounding of Edlén's constants (720.775 torr, 0.817, 0.0133): 4e-7 relative
    assert n - 1 == pytest.approx(ns, rel=1e-6)
    # CO2: (n-1)_x = [1 + 0.540 (x - 0.0003)] (n-1)_s
    n450 = air.refractive_index(15.0, 101325.0, co2=450.0, equation="edlen")
    assert (n450 - 1) / (n - 1) == pytest.approx(1 + 0.540 * 150e-6, rel=1e-12)


def test_edlen_1966_water_term_in_torr():
    """Edlén (1966): n_tpf - n_tp = -f (5.722 - 0.0457 σ²)·1e-8 with f in torr."""
    s = (1 / 0.632991) ** 2
    pv = 1333.22  # 10 torr
    dry = air.refractive_index(20.0, 101325.0, equation="edlen")
    wet = air.refractive_index(20.0, 101325.0, vapour_pressure=pv, equation="edlen")
    assert wet - dry == pytest.approx(-(pv * 760 / 101325) * (5.722 - 0.0457 * s) * 1e-8,
                                      rel=1e-9)


def test_edlen_1966_close_to_modified_edlen_in_dry_laboratory_air():
    """Birch and Downs (1993) changed the dry-air refractivity by a few parts in 1e8."""
    t, p = np.meshgrid(np.linspace(15, 25, 5), np.linspace(95e3, 105e3, 5))
    d = air.refractive_index(t, p, equation="edlen") - air.refractive_index(
        t, p, equation="birch-downs")
    assert np.max(np.abs(d)) < 3e-8


def test_three_equations_agree_to_a_few_parts_in_1e8_at_20c():
    n = {e: air.refractive_index(20.0, 101325.0, 50.0, equation=e) for e in air.EQUATIONS}
    assert abs(n["ciddor"] - n["birch-downs"]) < 1e-8
    assert abs(n["ciddor"] - n["edlen"]) < 1e-7


def test_sensitivities_match_rules_of_thumb():
    """Issue 3: about -0.95 ppm/K, +2.7 ppm/kPa, -0.0085 ppm/%RH at 20 °C, 101.325 kPa, 50 %RH."""
    for eq in ("ciddor", "birch-downs"):
        s = air.sensitivities(20.0, 101325.0, 50.0, equation=eq)
        assert s.dn_dT_ppm_per_K == pytest.approx(-0.95, abs=0.02)
        assert s.dn_dp_ppm_per_kPa == pytest.approx(2.7, abs=0.05)
        assert s.dn_dRH_ppm_per_percent == pytest.approx(-0.0085, abs=0.0003)
    # and they predict a 1 K, 1 kPa, 10 %RH change of n
    s = air.sensitivities()
    n0 = air.refractive_index(20.0, 101325.0, 50.0)
    assert air.refractive_index(21.0, 101325.0, 50.0) - n0 == pytest.approx(s.dn_dT, rel=0.01)
    assert air.refractive_index(20.0, 102325.0, 50.0) - n0 == pytest.approx(s.dn_dp * 1e3,
                                                                            rel=0.01)
    assert air.refractive_index(20.0, 101325.0, 60.0) - n0 == pytest.approx(s.dn_dRH * 10,
                                                                            rel=0.01)


def test_compensation_factor_and_ppm():
    r = air.air_conditions(20.0, 101325.0, 50.0)
    assert r.compensation_factor * r.n == pytest.approx(1.0, abs=1e-15)
    assert r.correction_ppm == pytest.approx(-271.3, abs=0.05)
    assert r.refractivity_ppm == pytest.approx(271.37, abs=0.01)
    assert r.wavelength == pytest.approx(632.991e-9 / r.n, rel=1e-15)
    assert air.compensation_factor(20.0, 101325.0, 50.0) == r.compensation_factor
    assert r.relative_humidity == pytest.approx(50.0)
    assert "632.81927" in str(r)


def test_seed_002_wavelength_is_0_633_um():
    """Seed 002: 'The light waves have a very short wavelength of only 0.633 microns'."""
    assert round(air.HENE_VACUUM_WAVELENGTH * 1e6, 3) == 0.633
    assert round(air.air_wavelength(20.0, 101325.0, 50.0) * 1e6, 3) == 0.633


@pytest.mark.parametrize("equation,param,kwargs", [
    ("ciddor", "temperature", {"temperature": 120.0}),
    ("ciddor", "pressure", {"pressure": 5e3}),
    ("ciddor", "vacuum_wavelength", {"vacuum_wavelength": 250e-9}),
    ("ciddor", "co2", {"co2": 3000.0}),
    ("birch-downs", "temperature", {"temperature": -45.0}),
    ("edlen", "temperature", {"temperature": 45.0}),
    ("edlen", "pressure", {"pressure": 50e3}),
    ("ciddor", "water_mole_fraction", {"temperature": 80.0, "humidity": 100.0}),
])
def test_outside_validity_raises_or_warns(equation, param, kwargs):
    args = {"temperature": 20.0, "pressure": 101325.0, "humidity": 10.0, **kwargs}
    with pytest.raises(InputError, match=param):
        air.refractive_index(**args, equation=equation)
    with pytest.warns(air.AirValidityWarning, match=param):
        n = air.refractive_index(**args, equation=equation, check="warn")
    assert np.isfinite(n)


def test_validity_message_names_value_and_range():
    with pytest.raises(InputError) as e:
        air.refractive_index([20.0, 120.0], 101325.0, 50.0)
    assert "temperature = 120 °C" in str(e.value) and "-40 to 100 °C" in str(e.value)
    assert "Ciddor" in str(e.value)


def test_humidity_inputs_checked():
    with pytest.raises(InputError, match="exactly one"):
        air.refractive_index(20.0, 101325.0, 50.0, dew_point=10.0)
    with pytest.raises(InputError, match="humidity = 120"):
        air.refractive_index(20.0, 101325.0, 120.0)
    with pytest.raises(InputError, match="dew_point"):
        air.refractive_index(20.0, 101325.0, dew_point=25.0)
    with pytest.raises(InputError, match="saturation"):
        air.refractive_index(20.0, 101325.0, vapour_pressure=3000.0)
    with pytest.raises(InputError, match="finite"):
        air.refractive_index(np.nan, 101325.0, 50.0)
    with pytest.raises(InputError, match="equation"):
        air.refractive_index(20.0, 101325.0, 50.0, equation="lorentz")


def test_saturation_vapour_pressure_matches_nist():
    """NIST A-I (IAPWS-IF97 over water, Wagner et al. over ice), via ref-index."""
    for t in [-30.0, -5.0, 0.0, 15.0, 20.0, 37.5, 60.0, 100.0]:
        assert air.saturation_vapour_pressure(t, over="water") == pytest.approx(
            ref_index.svp_water(t), rel=1e-13)
    for t in [-40.0, -20.0, -0.01]:
        assert air.saturation_vapour_pressure(t) == pytest.approx(ref_index.svp_ice(t), rel=1e-13)
    # the triple point, 611.657 Pa, is where the two curves meet
    assert air.saturation_vapour_pressure(0.01, over="ice") == pytest.approx(611.657, rel=1e-6)
    assert air.saturation_vapour_pressure(0.01, over="water") == pytest.approx(611.657, rel=2e-5)


def test_dry_air_when_no_humidity_given():
    assert air.refractive_index(20.0, 101325.0) == air.refractive_index(20.0, 101325.0, 0.0)


def test_air_conditions_refuses_arrays():
    with pytest.raises(InputError, match="single number"):
        air.air_conditions([20.0, 21.0], 101325.0, 50.0)


def test_no_warning_inside_validity():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        air.refractive_index(20.0, 101325.0, 50.0, check="warn")
