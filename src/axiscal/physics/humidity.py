"""Water vapour in air: saturation pressure, enhancement factor, humidity conversions.

The refractive index of air (:mod:`axiscal.physics.air`) needs the partial pressure of water
vapour :math:`p_v` and its mole fraction :math:`x_v = f\\,p_v/p`. A workshop states humidity as
relative humidity (%RH), dew point (°C) or partial pressure (Pa); this module converts between
them exactly as the NIST Engineering Metrology Toolbox refractive-index calculator does
(Stone and Zimmerman, Appendices A-I and A-II):

* saturation vapour pressure over water by the IAPWS-IF97 saturation-pressure equation, over ice
  by the sublimation equation of Wagner, Saul and Pruß (1994); below 0 °C a *relative* humidity
  refers to ice (the calculator's rule), a dew point to (supercooled) water;
* the enhancement factor :math:`f = \\alpha + \\beta p + \\gamma t^2` of moist air;
* the inverse of the water curve (IAPWS-IF97 saturation-temperature equation), giving the dew
  point of a partial pressure, and the relative humidity of a partial pressure.

Validity: the IAPWS-IF97 saturation curve holds from 273.15 K to 647.096 K (the NIST calculator
extrapolates it a little below 0 °C for dew points of supercooled water); the sublimation
equation from 50 K to 273.16 K. Every function broadcasts over NumPy arrays and returns a float
for scalar input.

References
----------
.. [1] J. A. Stone and J. H. Zimmerman, "Index of refraction of air", NIST Engineering Metrology
   Toolbox, Appendix A-I (saturation vapour pressure) and A-II (determining humidity).
.. [2] IAPWS, "Revised Release on the IAPWS Industrial Formulation 1997 for the Thermodynamic
   Properties of Water and Steam" (IAPWS-IF97), section 8 ("Region 4"), eqs. 30 and 31.
.. [3] W. Wagner, A. Saul and A. Pruß, "International equations for the pressure along the
   melting and along the sublimation curve of ordinary water substance", J. Phys. Chem. Ref.
   Data 23, 515 (1994).
"""

from __future__ import annotations

from typing import Literal

import numpy as np

from axiscal.errors import InputError
from axiscal.physics._validate import finite as _finite
from axiscal.physics._validate import refuse as _refuse
from axiscal.physics._validate import scalar_or_array as _out

__all__ = [
    "saturation_vapour_pressure",
    "water_vapour_pressure",
    "enhancement_factor",
    "relative_humidity",
    "dew_point",
    "SATURATION_RANGE",
    "check_saturation_range",
]

_T0 = 273.15  # K at 0 °C
#: Range where a saturation vapour pressure exists and the equations hold, °C: from 190 K, the low
#: end of the sublimation curve of Wagner, Saul and Pruß (1994), to the critical point of water,
#: 647.096 K (IAPWS-IF97 Region 4 ends there; above it there is no saturation).
SATURATION_RANGE = (190.0 - _T0, 647.096 - _T0)
#: IAPWS-IF97 Region 4 coefficients n1 ... n10 (NIST A-I calls them K1 ... K10).
_IAPWS = (1.16705214528e3, -7.24213167032e5, -1.70738469401e1, 1.20208247025e4,
          -3.23255503223e6, 1.49151086135e1, -4.82326573616e3, 4.05113405421e5,
          -2.38555575678e-1, 6.50175348448e2)


def saturation_vapour_pressure(temperature, over: Literal["auto", "water", "ice"] = "auto"):
    """Saturation pressure of water vapour, Pa.

    Parameters
    ----------
    temperature : array_like, degrees Celsius
    over : {"auto", "water", "ice"}
        ``"water"``: IAPWS-IF97 saturation curve; ``"ice"``: sublimation curve of Wagner et al.
        (1994); ``"auto"``: ice below 0 °C, water from 0 °C up (the NIST calculator's rule for a
        relative humidity).

    Returns
    -------
    p_sv : float or ndarray, Pa

    Notes
    -----
    Over water (NIST A-I; IAPWS-IF97 eq. 30), with :math:`T` in kelvin:

    .. math::
        \\Omega = T + K_9/(T - K_{10}),\\quad A = \\Omega^2 + K_1\\Omega + K_2,\\quad
        B = K_3\\Omega^2 + K_4\\Omega + K_5,\\quad C = K_6\\Omega^2 + K_7\\Omega + K_8,

        p_{sv} = 10^6 \\left( \\frac{2C}{-B + \\sqrt{B^2 - 4AC}} \\right)^4 .

    Over ice (NIST A-I; Wagner et al. 1994), with :math:`\\theta = T/273.16`:
    :math:`p_{sv} = 611.657 \\exp[A_1(1 - \\theta^{-1.5}) + A_2(1 - \\theta^{-1.25})]`,
    :math:`A_1 = -13.928169`, :math:`A_2 = 34.7078238`.

    Examples
    --------
    >>> round(saturation_vapour_pressure(20.0), 2)
    2339.21
    """
    t = _finite("temperature", temperature)
    check_saturation_range("temperature", t)
    if over == "water":
        out = _psv_water(t)
    elif over == "ice":
        out = _psv_ice(t)
    elif over == "auto":
        out = np.where(t < 0.0, _psv_ice(np.minimum(t, 0.0)), _psv_water(np.maximum(t, 0.0)))
    else:
        raise InputError(f"over = {over!r} is not 'auto', 'water' or 'ice'")
    return _out(out)


def water_vapour_pressure(temperature, humidity=None, *, dew_point=None, vapour_pressure=None):
    """Partial pressure of water vapour from one of the three ways to state humidity, Pa.

    Parameters
    ----------
    temperature : array_like, degrees Celsius
        Air temperature.
    humidity : array_like, percent relative humidity, optional
        :math:`p_v = (RH/100)\\, p_{sv}(t)` (saturation over ice below 0 °C).
    dew_point : array_like, degrees Celsius, optional
        :math:`p_v = p_{sv,water}(t_d)`; it may not exceed the air temperature.
    vapour_pressure : array_like, Pa, optional
        Given directly; it may not exceed the saturation pressure at the air temperature.

    Exactly one of ``humidity``, ``dew_point`` and ``vapour_pressure`` is given.

    Returns
    -------
    p_v : float or ndarray, Pa

    Raises
    ------
    InputError
        If none or more than one is given, or the value is impossible (RH outside 0-100 %, a dew
        point above the air temperature, a negative or supersaturated vapour pressure).

    Notes
    -----
    NIST A-II (Stone and Zimmerman): relative humidity refers to the saturation pressure at the
    air temperature, a dew point gives the saturation pressure over water at the dew point.

    Examples
    --------
    >>> round(water_vapour_pressure(20.0, 50.0), 2)
    1169.61
    >>> round(water_vapour_pressure(20.0, dew_point=9.27), 1)
    1169.4
    """
    given = [k for k, v in (("humidity", humidity), ("dew_point", dew_point),
                            ("vapour_pressure", vapour_pressure)) if v is not None]
    if len(given) != 1:
        raise InputError(
            "give the humidity exactly one way: relative humidity (%RH), dew point (°C) or "
            f"water vapour partial pressure (Pa); got {', '.join(given) or 'none'}"
        )
    t = _finite("temperature", temperature)
    if humidity is not None:
        rh = _finite("humidity", humidity)
        _refuse("humidity", rh, (rh < 0) | (rh > 100), "%RH", "must lie between 0 and 100 %RH")
        return _out(rh / 100.0 * saturation_vapour_pressure(t))
    if dew_point is not None:
        td = _finite("dew_point", dew_point)
        t_b, td_b = np.broadcast_arrays(t, td)
        _refuse("dew_point", td_b, td_b > t_b + 1e-9, "°C",
                "cannot exceed the air temperature (the air would be supersaturated)")
        check_saturation_range("dew_point", td)
        return _out(saturation_vapour_pressure(td, over="water"))
    pv = _finite("vapour_pressure", vapour_pressure)
    _refuse("vapour_pressure", pv, pv < 0, "Pa", "cannot be negative")
    psv = np.asarray(saturation_vapour_pressure(t))
    pv_b, psv_b = np.broadcast_arrays(pv, psv)
    _refuse("vapour_pressure", pv_b, pv_b > psv_b * (1 + 1e-9), "Pa",
            "exceeds the saturation pressure at the air temperature")
    return _out(pv)


def enhancement_factor(pressure, temperature):
    """Enhancement factor f of water vapour in air, dimensionless.

    Parameters
    ----------
    pressure : array_like, Pa
        Total air pressure.
    temperature : array_like, degrees Celsius
        Air temperature.

    Returns
    -------
    f : float or ndarray, dimensionless

    Notes
    -----
    NIST A-II: :math:`f = \\alpha + \\beta p + \\gamma t^2` with :math:`\\alpha = 1.00062`,
    :math:`\\beta = 3.14\\times10^{-8}` Pa⁻¹, :math:`\\gamma = 5.60\\times10^{-7}` °C⁻²; the mole
    fraction of water vapour is :math:`x_v = f\\, p_v / p`.

    Examples
    --------
    >>> round(enhancement_factor(101325.0, 20.0), 6)
    1.004026
    """
    p = np.asarray(pressure, dtype=float)
    t = np.asarray(temperature, dtype=float)
    return _out(1.00062 + 3.14e-8 * p + 5.60e-7 * t * t)


def relative_humidity(temperature, vapour_pressure):
    """Relative humidity of air holding water vapour at ``vapour_pressure``, percent.

    Parameters
    ----------
    temperature : array_like, degrees Celsius
        Air temperature.
    vapour_pressure : array_like, Pa
        Partial pressure of water vapour.

    Returns
    -------
    RH : float or ndarray, percent
        :math:`100\\,p_v/p_{sv}(t)`, saturation over ice below 0 °C (NIST A-II), the inverse of
        :func:`water_vapour_pressure` with ``humidity``.

    Examples
    --------
    >>> round(relative_humidity(20.0, 1169.61), 3)
    50.0
    """
    t = _finite("temperature", temperature)
    pv = _finite("vapour_pressure", vapour_pressure)
    _refuse("vapour_pressure", pv, pv < 0, "Pa", "cannot be negative")
    return _out(100.0 * pv / np.asarray(saturation_vapour_pressure(t)))


def dew_point(vapour_pressure):
    """Dew point (over water) of a partial pressure of water vapour, degrees Celsius.

    Parameters
    ----------
    vapour_pressure : array_like, Pa
        Partial pressure of water vapour, > 0.

    Returns
    -------
    t_d : float or ndarray, degrees Celsius
        The temperature at which ``vapour_pressure`` is the saturation pressure over water: the
        inverse of ``saturation_vapour_pressure(t_d, over="water")``, as ``dew_point=`` of
        :func:`water_vapour_pressure` uses it.

    Raises
    ------
    InputError
        A partial pressure that is not positive, or above the critical pressure (22.064 MPa).

    Notes
    -----
    IAPWS-IF97 saturation-temperature equation (eq. 31), the algebraic inverse of eq. 30, with
    :math:`\\beta = (p_v / 1\\,\\mathrm{MPa})^{1/4}`:

    .. math::
        E = \\beta^2 + n_3\\beta + n_6,\\quad F = n_1\\beta^2 + n_4\\beta + n_7,\\quad
        G = n_2\\beta^2 + n_5\\beta + n_8,\\quad D = \\frac{2G}{-F - \\sqrt{F^2 - 4EG}},

        T_d = \\frac{n_{10} + D - \\sqrt{(n_{10} + D)^2 - 4(n_9 + n_{10} D)}}{2}\\ \\mathrm{K}.

    Examples
    --------
    >>> round(dew_point(1169.61), 3)
    9.273
    """
    pv = _finite("vapour_pressure", vapour_pressure)
    _refuse("vapour_pressure", pv, (pv <= 0) | (pv > 22.064e6), "Pa",
            "must be positive and below the critical pressure of water (22.064 MPa)")
    n = _IAPWS
    beta = (pv * 1e-6) ** 0.25
    e = beta * beta + n[2] * beta + n[5]
    f = n[0] * beta * beta + n[3] * beta + n[6]
    g = n[1] * beta * beta + n[4] * beta + n[7]
    d = 2.0 * g / (-f - np.sqrt(f * f - 4.0 * e * g))
    big_t = 0.5 * (n[9] + d - np.sqrt((n[9] + d) ** 2 - 4.0 * (n[8] + n[9] * d)))
    return _out(big_t - _T0)


def check_saturation_range(name: str, t) -> None:
    """Refuse a temperature (°C) where water has no saturation vapour pressure to convert by.

    Checked whatever the equation of the refractive index, and before anything is computed:
    outside :data:`SATURATION_RANGE` the saturation equations give NaN or nonsense, so no
    relative humidity, dew point or vapour-pressure ceiling can be evaluated there.
    """
    lo, hi = SATURATION_RANGE
    t = np.asarray(t, dtype=float)
    _refuse(name, t, (t < lo) | (t > hi), "°C",
            f"is outside {lo:g} to {hi:g} °C, where water has a saturation vapour pressure "
            "(190 K, Wagner et al. 1994, to the critical point, IAPWS-IF97): no humidity can "
            "be converted there")


# -- helpers --------------------------------------------------------------------------------
def _psv_water(t):
    k = _IAPWS
    big_t = np.asarray(t, dtype=float) + _T0
    om = big_t + k[8] / (big_t - k[9])
    a = om * om + k[0] * om + k[1]
    b = k[2] * om * om + k[3] * om + k[4]
    c = k[5] * om * om + k[6] * om + k[7]
    x = -b + np.sqrt(b * b - 4.0 * a * c)
    return 1e6 * (2.0 * c / x) ** 4


def _psv_ice(t):
    theta = (np.asarray(t, dtype=float) + _T0) / 273.16
    y = -13.928169 * (1.0 - theta ** -1.5) + 34.7078238 * (1.0 - theta ** -1.25)
    return 611.657 * np.exp(y)
