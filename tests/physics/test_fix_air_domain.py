"""Air inputs no equation can compute are refused before computing, naming the real problem.

CLI review: at 500 °C numpy printed "RuntimeWarning: invalid value encountered in sqrt" (the
IAPWS-IF97 saturation curve ends at the critical point of water, 647.096 K = 373.946 °C) before
the error line; with check="warn" the same input ended in "humidity/vapour_pressure must be
finite", which names the wrong problem; a negative CO2 content was computed with a warning.
"""

import warnings

import pytest

from axiscal.errors import InputError
from axiscal.physics.air import air_conditions, refractive_index
from axiscal.physics.humidity import (SATURATION_RANGE, relative_humidity,
                                      saturation_vapour_pressure, water_vapour_pressure)




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
