"""Refractive index of air and the wavelength of light in air.

A laser interferometer or laser scale counts fringes of the wavelength *in air*,
:math:`\\lambda = \\lambda_{vac} / n`, so every length it measures scales with the refractive index
of the air in the beam. This module gives ``n`` by three equations:

``"ciddor"``
    Ciddor (1996), as implemented by the NIST Engineering Metrology Toolbox (Stone and Zimmerman,
    Appendix A-III). The reference equation of the International Association of Geodesy; valid
    over the widest range.
``"birch-downs"``
    The Edlén equation as updated by Birch and Downs (1993, corrected 1994) with the NIST
    modification of the water-vapour term (the factor :math:`292.75/T`), as in the NIST toolbox's
    "modified Edlén" calculator (Appendix A-IV).
``"edlen"``
    The original Edlén (1966) equation, in its published units (pressures in torr), for
    comparison with older instruments and papers.

Humidity is given as relative humidity (%RH), dew point (°C) or partial pressure of water vapour
(Pa); the conversions (saturation vapour pressure, enhancement factor, dew point, relative
humidity) live in :mod:`axiscal.physics.humidity` and are re-exported here. CO2 content in
µmol/mol (default 450); vacuum wavelength in metres (default the HeNe line 632.991 nm that seed
002 rounds to 0.633 µm). Every function broadcasts over NumPy arrays.

Inputs outside an equation's range of validity (table :data:`VALIDITY`) raise
:class:`~axiscal.errors.InputError` naming the parameter, the value and the range; with
``check="warn"`` they give an :class:`AirValidityWarning` instead and the value is computed anyway.

Examples
--------
>>> r = air_conditions(20.0, 101325.0, 50.0)
>>> print(f"{r.n:.9f}  {r.wavelength_nm:.5f} nm  {r.correction_ppm:.2f} ppm")
1.000271373  632.81927 nm  -271.30 ppm
>>> s = sensitivities(20.0, 101325.0, 50.0)
>>> print(f"{s.dn_dT_ppm_per_K:.3f} ppm/K  {s.dn_dp_ppm_per_kPa:.3f} ppm/kPa")
-0.955 ppm/K  2.683 ppm/kPa

References
----------
.. [1] P. E. Ciddor, "Refractive index of air: new equations for the visible and near infrared",
   Appl. Opt. 35, 1566-1573 (1996).
.. [2] B. Edlén, "The refractive index of air", Metrologia 2, 71-80 (1966).
.. [3] K. P. Birch and M. J. Downs, "An updated Edlén equation for the refractive index of air",
   Metrologia 30, 155-162 (1993); "Correction to the updated Edlén equation for the refractive
   index of air", Metrologia 31, 315-316 (1994).
.. [4] J. A. Stone and J. H. Zimmerman, "Index of refraction of air", NIST Engineering Metrology
   Toolbox (documentation of the refractive index of air calculator), Appendices A-I to A-IV.
.. [5] W. Wagner and A. Pruß, IAPWS-IF97 saturation-pressure equation; W. Wagner, A. Saul and
   A. Pruß, "International equations for the pressure along the melting and along the
   sublimation curve of ordinary water substance", J. Phys. Chem. Ref. Data 23, 515 (1994).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Literal

import numpy as np

from axiscal.errors import InputError
from axiscal.physics._validate import finite as _finite
from axiscal.physics._validate import refuse as _refuse
from axiscal.physics._validate import scalar_or_array as _out
from axiscal.physics.air_equations import birch_downs, ciddor, edlen_1966
from axiscal.physics.humidity import (
    dew_point,
    enhancement_factor,
    relative_humidity,
    saturation_vapour_pressure,
    water_vapour_pressure,
)

__all__ = [
    "HENE_VACUUM_WAVELENGTH",
    "EQUATIONS",
    "VALIDITY",
    "AirValidityWarning",
    "AirResult",
    "Sensitivities",
    "saturation_vapour_pressure",
    "water_vapour_pressure",
    "enhancement_factor",
    "relative_humidity",
    "dew_point",
    "refractive_index",
    "air_wavelength",
    "air_conditions",
    "compensation_factor",
    "sensitivities",
    "ciddor",
    "birch_downs",
    "edlen_1966",
]

#: Absolute zero, −273.15 °C, as a positive number of kelvin below 0 °C.
ABSOLUTE_ZERO_C = 273.15
#: Vacuum wavelength of the stabilised HeNe laser line, metres (Renishaw, Laser scale axis referencing: "0.633 microns").
HENE_VACUUM_WAVELENGTH = 632.991e-9

Equation = Literal["ciddor", "edlen", "birch-downs"]
Check = Literal["raise", "warn"]

#: The equations by their names, with the title used in messages.
EQUATIONS: dict[str, str] = {
    "ciddor": "Ciddor (1996)",
    "birch-downs": "modified Edlén (Birch and Downs 1993/1994, NIST water-vapour term)",
    "edlen": "Edlén (1966)",
}

#: Range of validity per equation: parameter -> (low, high, unit). Outside it ``check="raise"``
#: refuses the input. Ciddor and modified Edlén: the input limits of the NIST calculator
#: (Stone and Zimmerman, sections IV and VI: 300-1700 nm, 10-140 kPa, -40 to 100 °C,
#: 0-2000 µmol/mol CO2, water-vapour mole fraction up to 0.2). Inside them the calculator
#: still warns outside the narrower band where the equations were tested against measurements,
#: 350-1600 nm, 60-120 kPa, 0-40 °C, RH 1-85 % (as transcribed by the ``ref-index`` package
#: the tests use as oracle); the uncertainty grows there. (Ciddor's own dispersion data span
#: 0.23-1.69 µm, refractiveindex.info's summary of Ciddor 1996; the calculator's 1700 nm edge
#: is a 10 nm extrapolation, kept to agree with it.) The modified Edlén equation has no CO2
#: input in the NIST calculator (450 µmol/mol); the CO2 scaling here is Edlén's (1966) factor,
#: see :func:`birch_downs`. Edlén (1966): laboratory air, the conditions of the
#: measurements the equation was fitted to (axiscal's choice, stated here).
VALIDITY: dict[str, dict[str, tuple[float, float, str]]] = {
    "ciddor": {
        "vacuum_wavelength": (300e-9, 1700e-9, "m"),
        "temperature": (-40.0, 100.0, "°C"),
        "pressure": (10e3, 140e3, "Pa"),
        "co2": (0.0, 2000.0, "µmol/mol"),
        "water_mole_fraction": (0.0, 0.2, ""),
    },
    "birch-downs": {
        "vacuum_wavelength": (300e-9, 1700e-9, "m"),
        "temperature": (-40.0, 100.0, "°C"),
        "pressure": (10e3, 140e3, "Pa"),
        "co2": (0.0, 2000.0, "µmol/mol"),
        "water_mole_fraction": (0.0, 0.2, ""),
    },
    "edlen": {
        "vacuum_wavelength": (300e-9, 1700e-9, "m"),
        "temperature": (0.0, 40.0, "°C"),
        "pressure": (60e3, 120e3, "Pa"),
        "co2": (0.0, 2000.0, "µmol/mol"),
        "water_mole_fraction": (0.0, 0.2, ""),
    },
}



class AirValidityWarning(UserWarning):
    """An input lies outside the equation's range of validity (only with ``check="warn"``)."""


_FUNCTIONS = {"ciddor": ciddor, "birch-downs": birch_downs, "edlen": edlen_1966}


# -- the public entry points ----------------------------------------------------------------
def refractive_index(
    temperature=20.0,
    pressure=101325.0,
    humidity=None,
    *,
    dew_point=None,
    vapour_pressure=None,
    co2=450.0,
    vacuum_wavelength=HENE_VACUUM_WAVELENGTH,
    equation: Equation = "ciddor",
    check: Check = "raise",
):
    """Refractive index of moist air.

    Parameters
    ----------
    temperature : array_like, degrees Celsius
        Air temperature.
    pressure : array_like, Pa
        Air pressure.
    humidity : array_like, percent relative humidity, optional
    dew_point : array_like, degrees Celsius, optional
    vapour_pressure : array_like, Pa, optional
        Humidity, given exactly one of these three ways (see :func:`water_vapour_pressure`).
        If none is given, the air is dry.
    co2 : array_like, µmol/mol
        Carbon dioxide content (450 is typical indoors).
    vacuum_wavelength : array_like, metres
        Default: HeNe, 632.991 nm.
    equation : {"ciddor", "birch-downs", "edlen"}
    check : {"raise", "warn"}
        What happens outside the equation's validity (:data:`VALIDITY`): an
        :class:`~axiscal.errors.InputError`, or an :class:`AirValidityWarning` and a value.

    Returns
    -------
    n : float or ndarray (broadcast shape of the inputs)

    Raises
    ------
    InputError
        Unknown equation, impossible humidity, or (``check="raise"``) an input outside validity.

    Notes
    -----
    The humidity becomes a partial pressure :math:`p_v` and a mole fraction
    :math:`x_v = f\\,p_v/p` (NIST A-II, :mod:`axiscal.physics.humidity`); the validity is checked
    on t, p, λ, CO2 and :math:`x_v`; then :func:`ciddor` (NIST A-III), :func:`birch_downs` (NIST
    A-IV) or :func:`edlen_1966` (Edlén 1966, eqs. 1, 12, 13) gives n; their Notes hold the
    equations.

    Examples
    --------
    >>> print(f"{refractive_index(20, 101325, 50, equation='birch-downs'):.9f}")
    1.000271375
    """
    name = _equation(equation)
    if check not in ("raise", "warn"):
        raise InputError(f"check = {check!r} is not 'raise' or 'warn'")
    t = _finite("temperature", temperature)
    p = _finite("pressure", pressure)
    _refuse("pressure", p, p <= 0, "Pa", "must be positive")
    lam = _finite("vacuum_wavelength", vacuum_wavelength)
    _refuse("vacuum_wavelength", lam, lam <= 0, "m", "must be positive")
    x_co2 = _finite("co2", co2)
    _refuse("co2", x_co2, x_co2 < 0, "µmol/mol", "cannot be negative")
    _refuse("temperature", t, t <= -ABSOLUTE_ZERO_C, "°C",
            f"is not above absolute zero ({-ABSOLUTE_ZERO_C:g} °C)")
    # Validity first (check="raise" names the range), then what no equation can compute at all.
    _check_validity(name, check, vacuum_wavelength=lam, temperature=t, pressure=p, co2=x_co2)
    pv = _vapour_pressure(t, humidity, dew_point, vapour_pressure)
    with np.errstate(over="ignore", invalid="ignore"):   # refused below if it overflows
        xv = np.asarray(enhancement_factor(p, t)) * pv / p
    _refuse("water_mole_fraction", xv, ~(xv < 1), "",
            "is not below 1: the water vapour pressure reaches the air pressure (no air is left)")
    _check_validity(name, check, water_mole_fraction=xv)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        n = _FUNCTIONS[name](lam, t, p, pv, x_co2)
    if not np.all(np.isfinite(n)):
        raise InputError(f"the {EQUATIONS[name]} equation gives no finite refractive index at "
                         "these inputs (temperature, pressure or wavelength far outside its "
                         "validity)")
    return n


def air_wavelength(temperature=20.0, pressure=101325.0, humidity=None, **kwargs):
    """Wavelength of the light in air, :math:`\\lambda = \\lambda_{vac}/n`, metres.

    Parameters
    ----------
    temperature : array_like, degrees Celsius
    pressure : array_like, Pa
    humidity : array_like, percent relative humidity, optional
    **kwargs
        The other keywords of :func:`refractive_index` (``vacuum_wavelength`` in metres ...).

    Returns
    -------
    wavelength : float or ndarray, metres

    Notes
    -----
    Stone and Zimmerman (NIST), eq. 1: :math:`\\lambda = \\lambda_{vac}/n`.

    Examples
    --------
    >>> round(air_wavelength(20, 101325, 50) * 1e9, 5)
    632.81927
    """
    lam = np.asarray(kwargs.get("vacuum_wavelength", HENE_VACUUM_WAVELENGTH), dtype=float)
    return _out(lam / refractive_index(temperature, pressure, humidity, **kwargs))


def compensation_factor(temperature=20.0, pressure=101325.0, humidity=None, **kwargs):
    """Factor that turns a length counted in vacuum wavelengths into the true length: 1/n.

    Parameters
    ----------
    temperature : array_like, degrees Celsius
    pressure : array_like, Pa
    humidity : array_like, percent relative humidity, optional
    **kwargs
        The other keywords of :func:`refractive_index`.

    Returns
    -------
    factor : float or ndarray, dimensionless
        :math:`1/n`.

    Notes
    -----
    A fringe count N gives :math:`L = N\\lambda_{vac}/(2n)` (Yüksel et al., Position accuracy and repeatability calibration of turn tables eq. 22, d = λN/2 with the
    wavelength in air; Renishaw, Laser scale axis referencing, wavelength compensation), so a reading computed with the vacuum
    wavelength is multiplied by :math:`1/n`; the correction in ppm is :math:`(1/n - 1)\\times10^6`,
    about -271 ppm in a standard workshop.

    Examples
    --------
    >>> round((compensation_factor(20.0, 101325.0, 50.0) - 1) * 1e6, 2)
    -271.3
    """
    return _out(1.0 / np.asarray(refractive_index(temperature, pressure, humidity, **kwargs)))


@dataclass(frozen=True)
class AirResult:
    """Refractive index and what follows from it, for one set of air conditions.

    Attributes
    ----------
    n : float
        Refractive index.
    wavelength : float, metres
        Wavelength in air.
    vacuum_wavelength : float, metres
    equation : str
        ``"ciddor"``, ``"birch-downs"`` or ``"edlen"``.
    temperature : float, degrees Celsius
    pressure : float, Pa
    vapour_pressure : float, Pa
    relative_humidity : float, percent
        The relative humidity the inputs amount to.
    co2 : float, µmol/mol
    """

    n: float
    wavelength: float
    vacuum_wavelength: float
    equation: str
    temperature: float
    pressure: float
    vapour_pressure: float
    relative_humidity: float
    co2: float

    @property
    def refractivity_ppm(self) -> float:
        """(n - 1) in parts per million."""
        return (self.n - 1.0) * 1e6

    @property
    def wavelength_nm(self) -> float:
        """Wavelength in air, nanometres."""
        return self.wavelength * 1e9

    @property
    def compensation_factor(self) -> float:
        """λ_air/λ_vac = 1/n: multiply a vacuum-wavelength length by it to get the true length."""
        return 1.0 / self.n

    @property
    def correction_ppm(self) -> float:
        """(1/n - 1) in ppm: the correction a compensator applies to vacuum-wavelength counts."""
        return (1.0 / self.n - 1.0) * 1e6

    def to_dict(self) -> dict:
        """Plain-data form (the ``axiscal air --json`` object)."""
        return {
            "n": self.n,
            "n_minus_1_ppm": self.refractivity_ppm,
            "wavelength_nm": self.wavelength_nm,
            "vacuum_wavelength_nm": self.vacuum_wavelength * 1e9,
            "compensation_factor": self.compensation_factor,
            "compensation_ppm": self.correction_ppm,
            "equation": self.equation,
            "temperature_c": self.temperature,
            "pressure_pa": self.pressure,
            "vapour_pressure_pa": self.vapour_pressure,
            "relative_humidity": self.relative_humidity,
            "co2_umol_per_mol": self.co2,
        }

    def __str__(self) -> str:
        return (
            f"{EQUATIONS[self.equation]} at {self.temperature:g} °C, {self.pressure:g} Pa, "
            f"{self.relative_humidity:.1f} %RH, {self.co2:g} µmol/mol CO2:\n"
            f"  n = {self.n:.9f}   (n - 1 = {self.refractivity_ppm:.3f} ppm)\n"
            f"  wavelength in air = {self.wavelength_nm:.5f} nm "
            f"(vacuum {self.vacuum_wavelength * 1e9:.3f} nm)\n"
            f"  compensation factor 1/n = {self.compensation_factor:.9f} "
            f"({self.correction_ppm:+.3f} ppm)"
        )


def air_conditions(
    temperature=20.0,
    pressure=101325.0,
    humidity=None,
    *,
    dew_point=None,
    vapour_pressure=None,
    co2=450.0,
    vacuum_wavelength=HENE_VACUUM_WAVELENGTH,
    equation: Equation = "ciddor",
    check: Check = "raise",
) -> AirResult:
    """The refractive index and the derived quantities for one (scalar) set of conditions.

    Same parameters (and units) as :func:`refractive_index`, scalars only.

    Returns
    -------
    AirResult
        n, the wavelength in air (m), the inputs, and the relative humidity they amount to
        (:func:`~axiscal.physics.humidity.relative_humidity`, %).

    Notes
    -----
    n as :func:`refractive_index`; wavelength :math:`\\lambda_{vac}/n` (NIST eq. 1).
    """
    kw = dict(dew_point=dew_point, vapour_pressure=vapour_pressure, co2=co2,
              vacuum_wavelength=vacuum_wavelength, equation=equation, check=check)
    for name, v in (("temperature", temperature), ("pressure", pressure), ("humidity", humidity),
                    ("dew_point", dew_point), ("vapour_pressure", vapour_pressure), ("co2", co2),
                    ("vacuum_wavelength", vacuum_wavelength)):
        if v is not None and np.ndim(v) != 0:
            raise InputError(f"{name} must be a single number here; use refractive_index() "
                             "for arrays")
    n = float(refractive_index(temperature, pressure, humidity, **kw))
    pv = float(_vapour_pressure(temperature, humidity, dew_point, vapour_pressure))
    rh = 0.0 if pv == 0.0 else float(relative_humidity(temperature, pv))
    return AirResult(n=n, wavelength=float(vacuum_wavelength) / n,
                     vacuum_wavelength=float(vacuum_wavelength), equation=_equation(equation),
                     temperature=float(temperature), pressure=float(pressure),
                     vapour_pressure=pv, relative_humidity=rh, co2=float(co2))


@dataclass(frozen=True)
class Sensitivities:
    """Partial derivatives of n at one set of conditions.

    Attributes
    ----------
    dn_dT : float, 1/K
    dn_dp : float, 1/Pa
    dn_dRH : float, 1/%RH
    """

    dn_dT: float
    dn_dp: float
    dn_dRH: float

    @property
    def dn_dT_ppm_per_K(self) -> float:
        """dn/dT in ppm per kelvin (rule of thumb: about -0.95)."""
        return self.dn_dT * 1e6

    @property
    def dn_dp_ppm_per_kPa(self) -> float:
        """dn/dp in ppm per kPa (rule of thumb: about +2.7)."""
        return self.dn_dp * 1e9

    @property
    def dn_dRH_ppm_per_percent(self) -> float:
        """dn/dRH in ppm per %RH (rule of thumb: about -0.0085)."""
        return self.dn_dRH * 1e6

    def __str__(self) -> str:
        return (f"dn/dT = {self.dn_dT_ppm_per_K:+.4f} ppm/K, "
                f"dn/dp = {self.dn_dp_ppm_per_kPa:+.4f} ppm/kPa, "
                f"dn/dRH = {self.dn_dRH_ppm_per_percent:+.5f} ppm/%RH")


def sensitivities(temperature=20.0, pressure=101325.0, humidity=50.0, *, co2=450.0,
                  vacuum_wavelength=HENE_VACUUM_WAVELENGTH,
                  equation: Equation = "ciddor") -> Sensitivities:
    """Sensitivities of n to temperature, pressure and relative humidity.

    Parameters
    ----------
    temperature : float, degrees Celsius
    pressure : float, Pa
    humidity : float, percent relative humidity (held constant when T changes); None for dry air
    co2 : float, µmol/mol
    vacuum_wavelength : float, metres
    equation : {"ciddor", "birch-downs", "edlen"}

    Returns
    -------
    Sensitivities

    Notes
    -----
    Central differences with steps of 0.01 K, 1 Pa and 0.1 %RH (the equations are smooth; the
    truncation error is far below the last digit reported). At 20 °C, 101.325 kPa, 50 %RH they
    reproduce the workshop rules of thumb: about -0.95 ppm/K, +2.7 ppm/kPa and -0.0085 ppm/%RH.
    """
    def n(t, p, rh):
        return float(refractive_index(t, p, rh, co2=co2, vacuum_wavelength=vacuum_wavelength,
                                      equation=equation, check="warn"))

    t, p = float(_finite("temperature", temperature)), float(_finite("pressure", pressure))
    rh = 0.0 if humidity is None else float(_finite("humidity", humidity))  # None: dry air
    dt, dp, drh = 0.01, 1.0, 0.1
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", AirValidityWarning)
        lo_rh, hi_rh = max(rh - drh, 0.0), min(rh + drh, 100.0)
        return Sensitivities(
            dn_dT=(n(t + dt, p, rh) - n(t - dt, p, rh)) / (2 * dt),
            dn_dp=(n(t, p + dp, rh) - n(t, p - dp, rh)) / (2 * dp),
            dn_dRH=(n(t, p, hi_rh) - n(t, p, lo_rh)) / (hi_rh - lo_rh),
        )


# -- helpers --------------------------------------------------------------------------------
def _equation(equation) -> str:
    key = str(equation).strip().lower().replace("_", "-").replace(" ", "-")
    key = {"edlen-1966": "edlen", "edlén": "edlen", "modified-edlen": "birch-downs",
           "birch-and-downs": "birch-downs"}.get(key, key)
    if key not in EQUATIONS:
        raise InputError(f"equation {equation!r} is not one of {', '.join(EQUATIONS)}")
    return key


def _vapour_pressure(t, humidity, dew_point, vapour_pressure) -> np.ndarray:
    """Partial pressure of water vapour (Pa) at ``t`` (°C) from whichever humidity is given
    (:func:`~axiscal.physics.humidity.water_vapour_pressure`, NIST A-I/A-II); 0 (dry air) when
    none is."""
    if humidity is None and dew_point is None and vapour_pressure is None:
        return np.zeros_like(np.asarray(t, dtype=float))
    return np.asarray(water_vapour_pressure(t, humidity, dew_point=dew_point,
                                            vapour_pressure=vapour_pressure))


def _check_validity(name: str, check: str, **values) -> None:
    for param, value in values.items():
        lo, hi, unit = VALIDITY[name][param]
        arr = np.asarray(value)
        bad = (arr < lo) | (arr > hi)
        if not np.any(bad):
            continue
        v = arr[bad].ravel()[0]
        if param == "vacuum_wavelength":
            shown, rng = f"{v * 1e9:g} nm", f"{lo * 1e9:g} to {hi * 1e9:g} nm"
        else:
            shown, rng = f"{v:g} {unit}".strip(), f"{lo:g} to {hi:g} {unit}".strip()
        msg = (f"{param} = {shown} is outside the validity of the {EQUATIONS[name]} equation, "
               f"{rng}")
        if check == "raise":
            raise InputError(msg + " (check='warn', or --allow-outside on the command line, "
                             "computes anyway)")
        warnings.warn(msg, AirValidityWarning, stacklevel=3)
