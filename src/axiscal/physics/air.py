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

#: Vacuum wavelength of the stabilised HeNe laser line, metres (seed 002: "0.633 microns").
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
#: the tests use as oracle); the uncertainty grows there. The modified Edlén equation has
#: no CO2 input in the NIST calculator (450 µmol/mol); the CO2 scaling here is Edlén's (1966)
#: factor, see :func:`birch_downs`. Edlén (1966): laboratory air, the conditions of the
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

_T0 = 273.15  # K at 0 °C
_TORR = 101325.0 / 760.0  # Pa per torr


class AirValidityWarning(UserWarning):
    """An input lies outside the equation's range of validity (only with ``check="warn"``)."""


# -- the three equations, on the partial pressure of water vapour -------------------------------
def ciddor(vacuum_wavelength, temperature, pressure, vapour_pressure, co2=450.0):
    """Refractive index of air by the Ciddor (1996) equation (NIST A-III). No range check.

    Parameters
    ----------
    vacuum_wavelength : array_like, metres
    temperature : array_like, degrees Celsius
    pressure : array_like, Pa
    vapour_pressure : array_like, Pa (partial pressure of water vapour)
    co2 : array_like, µmol/mol

    Returns
    -------
    n : float or ndarray

    Notes
    -----
    With :math:`S = 1/\\lambda^2` (λ in µm), :math:`x_v = f p_v / p`:

    .. math::
        n_{as} - 1 = 10^{-8}[k_1/(k_0 - S) + k_3/(k_2 - S)],\\qquad
        n_{ws} - 1 = 1.022\\times10^{-8}(w_0 + w_1 S + w_2 S^2 + w_3 S^3),

        n_{axs} - 1 = (n_{as} - 1)[1 + 0.534\\times10^{-6}(x_{CO_2} - 450)],\\quad
        M_a = 0.0289635 + 1.2011\\times10^{-8}(x_{CO_2} - 400),

        n - 1 = \\frac{\\rho_a}{\\rho_{axs}}(n_{axs} - 1) + \\frac{\\rho_v}{\\rho_{vs}}(n_{ws} - 1),

    the densities from the BIPM compressibility Z of moist air. Constants as in NIST A-III
    (R = 8.314472 J/(mol K)).
    """
    lam_um = np.asarray(vacuum_wavelength, dtype=float) * 1e6
    t = np.asarray(temperature, dtype=float)
    p = np.asarray(pressure, dtype=float)
    pv = np.asarray(vapour_pressure, dtype=float)
    x_co2 = np.asarray(co2, dtype=float)
    s = 1.0 / (lam_um * lam_um)
    n_as = 1e-8 * (5792105.0 / (238.0185 - s) + 167917.0 / (57.362 - s))
    n_ws = 1.022e-8 * (295.235 + 2.6422 * s - 0.03238 * s * s + 0.004028 * s * s * s)
    m_a = 0.0289635 + 1.2011e-8 * (x_co2 - 400.0)
    n_axs = n_as * (1.0 + 5.34e-7 * (x_co2 - 450.0))
    big_t = t + _T0
    xv = enhancement_factor(p, t) * pv / p
    p_t = p / big_t
    z = (1.0
         - p_t * (1.58123e-6 - 2.9331e-8 * t + 1.1043e-10 * t * t
                  + (5.707e-6 - 2.051e-8 * t) * xv + (1.9898e-4 - 2.376e-6 * t) * xv * xv)
         + p_t * p_t * (1.83e-11 - 0.765e-8 * xv * xv))
    r_gas = 8.314472
    rho_axs = 101325.0 * m_a / (0.9995922115 * r_gas * 288.15)
    rho_v = xv * p * 0.018015 / (z * r_gas * big_t)
    rho_a = (1.0 - xv) * p * m_a / (z * r_gas * big_t)
    return _out(1.0 + (rho_a / rho_axs) * n_axs + (rho_v / 0.00985938) * n_ws)


def birch_downs(vacuum_wavelength, temperature, pressure, vapour_pressure, co2=450.0):
    """Refractive index by the modified Edlén equation (NIST A-IV). No range check.

    Parameters as :func:`ciddor`.

    Notes
    -----
    With :math:`S = 1/\\lambda^2` (λ in µm), p and :math:`p_v` in Pa, t in °C, T in K:

    .. math::
        (n - 1)_s = 10^{-8}[8342.54 + 2406147/(130 - S) + 15998/(38.9 - S)],

        X = \\frac{1 + 10^{-8}(0.601 - 0.00972\\,t)\\,p}{1 + 0.003661\\,t},\\qquad
        n_{tp} - 1 = \\frac{p\\,(n - 1)_s X}{96095.43},

        n = n_{tp} - \\frac{292.75}{T}(3.7345 - 0.0401\\,S)\\,p_v \\times 10^{-10}.

    The factor 292.75/T is NIST's modification of Birch and Downs' water-vapour term. The
    equation holds for air with 450 µmol/mol CO2 (Birch and Downs' standard air); for another
    content the dry-air refractivity is scaled by Edlén's (1966) factor
    :math:`1 + 0.540(x - 0.00045)` (x as a volume fraction), which leaves the NIST value unchanged
    at the default 450.
    """
    s, t, p, pv = _edlen_inputs(vacuum_wavelength, temperature, pressure, vapour_pressure)
    n_s = 1e-8 * (8342.54 + 2406147.0 / (130.0 - s) + 15998.0 / (38.9 - s))
    n_s = n_s * _edlen_co2_factor(co2, 450.0)
    x = (1.0 + 1e-8 * (0.601 - 0.00972 * t) * p) / (1.0 + 0.003661 * t)
    n_tp = p * n_s * x / 96095.43
    return _out(1.0 + n_tp - 292.75 / (t + _T0) * (3.7345 - 0.0401 * s) * pv * 1e-10)


def edlen_1966(vacuum_wavelength, temperature, pressure, vapour_pressure, co2=450.0):
    """Refractive index by the original Edlén (1966) equation. No range check.

    Parameters as :func:`ciddor`.

    Notes
    -----
    In Edlén's units (p and f in torr, σ in µm⁻¹, S = σ²), for standard air (15 °C, 760 torr,
    dry, 300 µmol/mol CO2):

    .. math::
        (n - 1)_s \\times 10^{8} = 8342.13 + \\frac{2406030}{130 - S} + \\frac{15997}{38.9 - S},

        (n - 1)_{tp} = \\frac{p\\,(n - 1)_s}{720.775}
            \\cdot \\frac{1 + p\\,(0.817 - 0.0133\\,t)\\times10^{-6}}{1 + 0.0036610\\,t},

        n_{tpf} - n_{tp} = -f\\,(5.722 - 0.0457\\,S)\\times 10^{-8},

    and for a CO2 volume fraction x: :math:`(n-1)_x = [1 + 0.540(x - 0.0003)](n-1)_s`.
    Pressures given in Pa are converted with 1 torr = 101325/760 Pa.
    """
    s, t, p, pv = _edlen_inputs(vacuum_wavelength, temperature, pressure, vapour_pressure)
    p_torr = p / _TORR
    f_torr = pv / _TORR
    n_s = 1e-8 * (8342.13 + 2406030.0 / (130.0 - s) + 15997.0 / (38.9 - s))
    n_s = n_s * _edlen_co2_factor(co2, 300.0)
    n_tp = p_torr * n_s / 720.775 * (1.0 + p_torr * (0.817 - 0.0133 * t) * 1e-6) / (
        1.0 + 0.0036610 * t)
    return _out(1.0 + n_tp - f_torr * (5.722 - 0.0457 * s) * 1e-8)


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
    if humidity is None and dew_point is None and vapour_pressure is None:
        pv = np.zeros_like(t)
    else:
        pv = np.asarray(water_vapour_pressure(t, humidity, dew_point=dew_point,
                                              vapour_pressure=vapour_pressure))
    xv = np.asarray(enhancement_factor(p, t)) * pv / p
    _check_validity(name, check, vacuum_wavelength=lam, temperature=t, pressure=p, co2=x_co2,
                    water_mole_fraction=xv)
    return _FUNCTIONS[name](lam, t, p, pv, x_co2)


def air_wavelength(temperature=20.0, pressure=101325.0, humidity=None, **kwargs):
    """Wavelength of the light in air, :math:`\\lambda = \\lambda_{vac}/n`, metres.

    Same parameters as :func:`refractive_index`.

    Examples
    --------
    >>> round(air_wavelength(20, 101325, 50) * 1e9, 5)
    632.81927
    """
    lam = np.asarray(kwargs.get("vacuum_wavelength", HENE_VACUUM_WAVELENGTH), dtype=float)
    return _out(lam / refractive_index(temperature, pressure, humidity, **kwargs))


def compensation_factor(temperature=20.0, pressure=101325.0, humidity=None, **kwargs):
    """Factor that turns a length counted in vacuum wavelengths into the true length: 1/n.

    A fringe count N gives :math:`L = N\\lambda_{vac}/(2n)`, so a reading computed with the vacuum
    wavelength is multiplied by :math:`1/n`; the correction in ppm is :math:`(1/n - 1)\\times10^6`,
    about -271 ppm in a standard workshop. Same parameters as :func:`refractive_index`.
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

    Same parameters as :func:`refractive_index`, scalars only.

    Returns
    -------
    AirResult
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
    if humidity is None and dew_point is None and vapour_pressure is None:
        pv = 0.0
    else:
        pv = float(water_vapour_pressure(temperature, humidity, dew_point=dew_point,
                                         vapour_pressure=vapour_pressure))
    rh = float(relative_humidity(temperature, pv))
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
    humidity : float, percent relative humidity (held constant when T changes)
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

    t, p, rh = float(temperature), float(pressure), float(humidity)
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
def _edlen_inputs(vacuum_wavelength, temperature, pressure, vapour_pressure):
    lam_um = np.asarray(vacuum_wavelength, dtype=float) * 1e6
    return (1.0 / (lam_um * lam_um), np.asarray(temperature, dtype=float),
            np.asarray(pressure, dtype=float), np.asarray(vapour_pressure, dtype=float))


def _edlen_co2_factor(co2, reference_umol):
    return 1.0 + 0.540 * (np.asarray(co2, dtype=float) - reference_umol) * 1e-6


def _equation(equation) -> str:
    key = str(equation).strip().lower().replace("_", "-").replace(" ", "-")
    key = {"edlen-1966": "edlen", "edlén": "edlen", "modified-edlen": "birch-downs",
           "birch-and-downs": "birch-downs"}.get(key, key)
    if key not in EQUATIONS:
        raise InputError(f"equation {equation!r} is not one of {', '.join(EQUATIONS)}")
    return key


def _check_validity(name: str, check: str, **values) -> None:
    for param, (lo, hi, unit) in VALIDITY[name].items():
        arr = np.asarray(values[param])
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
