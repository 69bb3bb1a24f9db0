"""Review of the water-vapour functions split out of physics/air.py into physics/humidity.py.

References: IAPWS-IF97 (Revised Release, 2007), computer-program verification values of the
saturation-pressure equation (eq. 30, Table 35) and the saturation-temperature equation (eq. 31,
Table 36); the NIST Engineering Metrology Toolbox refractive-index calculator (Stone and
Zimmerman, A-I, A-II) through the ``ref-index`` package (a dev dependency, the same oracle as
test_air.py).
"""

from __future__ import annotations

import numpy as np
import pytest
import ref_index

from axiscal.errors import InputError
from axiscal.physics import air, air_equations, humidity


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
