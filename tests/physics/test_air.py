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
from axiscal.physics.air import air_conditions, refractive_index
from axiscal.physics.humidity import (SATURATION_RANGE, relative_humidity,
                                      saturation_vapour_pressure, water_vapour_pressure)
from axiscal.physics import air_equations, humidity

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


# -- Air inputs no equation can compute are refused before computing, naming the real problem. ----------
#
# CLI review: at 500 °C numpy printed "RuntimeWarning: invalid value encountered in sqrt" (the
# IAPWS-IF97 saturation curve ends at the critical point of water, 647.096 K = 373.946 °C) before
# the error line; with check="warn" the same input ended in "humidity/vapour_pressure must be
# finite", which names the wrong problem; a negative CO2 content was computed with a warning.

def test_saturation_range_ends_at_the_critical_point_and_190_K():
    """IAPWS-IF97: T_c = 647.096 K; Wagner, Saul and Pruß (1994) sublimation curve from 190 K."""
    assert SATURATION_RANGE == pytest.approx((190.0 - 273.15, 647.096 - 273.15))


@pytest.mark.parametrize("check", ["raise", "warn"])
def test_500_C_gives_no_runtime_warning(check):
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        warnings.simplefilter("ignore", UserWarning)      # AirValidityWarning with check="warn"
        with pytest.raises(InputError, match="temperature = 500"):
            air_conditions(500.0, 101325.0, 50.0, check=check)


def test_500_C_in_warn_mode_names_the_saturation_range_not_finiteness():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(InputError) as e:
            air_conditions(500.0, 101325.0, 50.0, check="warn")
    msg = str(e.value)
    assert "temperature = 500 °C" in msg and "critical point" in msg
    assert "finite" not in msg


@pytest.mark.parametrize("kwargs", [dict(dew_point=10.0), dict(vapour_pressure=1000.0)])
def test_500_C_with_other_humidity_forms(kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        warnings.simplefilter("error", RuntimeWarning)
        with pytest.raises(InputError, match="temperature = 500 °C is outside"):
            air_conditions(500.0, 101325.0, check="warn", **kwargs)


def test_below_absolute_zero_is_refused_in_both_modes():
    for check in ("raise", "warn"):
        with pytest.raises(InputError, match=r"temperature = -300 °C is not above absolute zero"):
            refractive_index(-300.0, 101325.0, 50.0, check=check)


@pytest.mark.parametrize("check", ["raise", "warn"])
def test_negative_co2_is_refused(check):
    with pytest.raises(InputError, match="co2 = -100 µmol/mol cannot be negative"):
        refractive_index(20.0, 101325.0, 50.0, co2=-100.0, check=check)


def test_zero_co2_is_still_allowed():
    """0 µmol/mol is the low end of the validity (NIST calculator), CO2-free air."""
    assert refractive_index(20.0, 101325.0, 50.0, co2=0.0) > 1.0


def test_vapour_pressure_above_air_pressure_is_refused_in_warn_mode():
    """99 °C saturated air at 50 kPa: p_sv(99 °C) ≈ 98 kPa > p, a mole fraction above 1."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        with pytest.raises(InputError, match="water_mole_fraction = .* is not below 1"):
            refractive_index(99.0, 50000.0, 100.0, check="warn")


def test_warn_mode_still_computes_inside_the_saturation_range():
    """--allow-outside keeps its meaning: 200 °C is outside Ciddor's validity, computed anyway."""
    with pytest.warns(UserWarning, match="temperature = 200"):
        n = refractive_index(200.0, 101325.0, 0.0, check="warn")
    assert 1.0 < n < 1.0003


def test_humidity_functions_refuse_before_computing():
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        with pytest.raises(InputError, match="temperature = 400"):
            saturation_vapour_pressure(400.0)
        with pytest.raises(InputError, match="temperature = 400"):
            relative_humidity(400.0, 1000.0)
        with pytest.raises(InputError, match="temperature = -273"):
            water_vapour_pressure(-273.0, 50.0)


def test_dew_point_above_the_air_temperature_names_that_rule_first():
    with pytest.raises(InputError, match="dew_point = 500 °C cannot exceed the air temperature"):
        water_vapour_pressure(20.0, dew_point=500.0)


# -- Review of the water-vapour functions split out of physics/air.py into physics/humidity.py. ----------
#
# References: IAPWS-IF97 (Revised Release, 2007), computer-program verification values of the
# saturation-pressure equation (eq. 30, Table 35) and the saturation-temperature equation (eq. 31,
# Table 36); the NIST Engineering Metrology Toolbox refractive-index calculator (Stone and
# Zimmerman, A-I, A-II) through the ``ref-index`` package (a dev dependency, the same oracle as
# test_air.py).

def test_air_still_exports_the_humidity_functions():
    """The split keeps every public name of axiscal.physics.air importable from it."""
    for name in ("saturation_vapour_pressure", "water_vapour_pressure", "enhancement_factor",
                 "relative_humidity", "dew_point"):
        assert name in air.__all__
        assert getattr(air, name) is getattr(humidity, name)
    for name in ("ciddor", "birch_downs", "edlen_1966"):
        assert name in air.__all__
        assert getattr(air, name) is getattr(air_equations, name)
    from axiscal.physics.air import (  # noqa: F401  the old import line still works
        saturation_vapour_pressure, water_vapour_pressure, enhancement_factor, ciddor)


@pytest.mark.parametrize("kelvin, mpa", [(300.0, 0.353658941e-2), (500.0, 0.263889776e1),
                                          (600.0, 0.123443146e2)])
def test_saturation_pressure_iapws_if97_table_35(kelvin, mpa):
    """IAPWS-IF97 Table 35: p_s(T) of eq. 30 to the 9 digits printed."""
    p = humidity.saturation_vapour_pressure(kelvin - 273.15, over="water")
    assert p == pytest.approx(mpa * 1e6, rel=2e-9)


@pytest.mark.parametrize("mpa, kelvin", [(0.1, 0.372755919e3), (1.0, 0.453035632e3),
                                          (10.0, 0.584149488e3)])
def test_dew_point_iapws_if97_table_36(mpa, kelvin):
    """IAPWS-IF97 Table 36: T_s(p) of eq. 31 to the 9 digits printed."""
    assert humidity.dew_point(mpa * 1e6) + 273.15 == pytest.approx(kelvin, abs=1e-6)


def test_dew_point_inverts_the_saturation_curve_and_the_nist_dew_point():
    """dew_point(p_sv,water(t)) = t over the calculator's range, also below 0 °C (supercooled
    water, as NIST A-II uses for a dew point), against ref-index's own p_sv(t_d)."""
    td = np.linspace(-40.0, 100.0, 281)
    np.testing.assert_allclose(humidity.dew_point(humidity.saturation_vapour_pressure(
        td, over="water")), td, rtol=0, atol=1e-9)
    pv = np.array([ref_index.dew_point_wvpp(x) for x in td])
    np.testing.assert_allclose(humidity.dew_point(pv), td, rtol=0, atol=1e-9)


def test_relative_humidity_inverts_water_vapour_pressure_with_ice_below_zero():
    """NIST A-II: RH refers to ice below 0 °C; relative_humidity undoes humidity=."""
    t = np.array([-30.0, -5.0, -0.01, 0.0, 12.0, 20.0, 35.0, 80.0])
    rh = np.array([10.0, 40.0, 55.0, 50.0, 5.0, 50.0, 85.0, 100.0])
    pv = humidity.water_vapour_pressure(t, rh)
    want = [ref_index.rh2wvpp(r, x) for r, x in zip(rh, t)]
    np.testing.assert_allclose(pv, want, rtol=1e-12)
    np.testing.assert_allclose(humidity.relative_humidity(t, pv), rh, rtol=1e-12)


def test_air_conditions_reports_the_relative_humidity_of_a_dew_point():
    """A dew point equal to the air temperature is saturated air: 100 %RH."""
    r = air.air_conditions(20.0, 101325.0, dew_point=20.0)
    assert r.relative_humidity == pytest.approx(100.0, abs=1e-9)
    r = air.air_conditions(20.0, 101325.0, dew_point=9.0)
    assert humidity.dew_point(r.vapour_pressure) == pytest.approx(9.0, abs=1e-9)


@pytest.mark.parametrize("pv", [0.0, -1.0, 3e7, float("nan")])
def test_dew_point_refuses_impossible_pressures(pv):
    with pytest.raises(InputError, match="vapour_pressure"):
        humidity.dew_point(pv)


def test_enhancement_factor_nist_a2_by_hand():
    """NIST A-II: f = 1.00062 + 3.14e-8 p + 5.6e-7 t² = 1.00062 + 0.0031816 + 0.000224 at
    101325 Pa, 20 °C, computed by hand: 1.0040256."""
    assert humidity.enhancement_factor(101325.0, 20.0) == pytest.approx(1.0040256, abs=1e-7)
