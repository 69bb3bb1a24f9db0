"""The three published equations for the refractive index of air, unchecked.

:func:`ciddor` (Ciddor 1996 as in NIST A-III), :func:`birch_downs` (the modified Edlén equation of
NIST A-IV) and :func:`edlen_1966` (Edlén 1966) take the vacuum wavelength (m), temperature (°C),
pressure (Pa), partial pressure of water vapour (Pa) and CO2 content (µmol/mol) and return n.
They do no range checking: :func:`axiscal.physics.air.refractive_index` validates the inputs,
converts the humidity and calls them, and :mod:`axiscal.physics.air` re-exports them.

References
----------
.. [1] P. E. Ciddor, "Refractive index of air: new equations for the visible and near infrared",
   Appl. Opt. 35, 1566-1573 (1996).
.. [2] B. Edlén, "The refractive index of air", Metrologia 2, 71-80 (1966).
.. [3] K. P. Birch and M. J. Downs, "An updated Edlén equation for the refractive index of air",
   Metrologia 30, 155-162 (1993); "Correction to the updated Edlén equation for the refractive
   index of air", Metrologia 31, 315-316 (1994).
.. [4] J. A. Stone and J. H. Zimmerman, "Index of refraction of air", NIST Engineering Metrology
   Toolbox, Appendices A-III and A-IV.
"""

from __future__ import annotations

import numpy as np

from axiscal.physics._validate import scalar_or_array as _out
from axiscal.physics.humidity import enhancement_factor

__all__ = ["ciddor", "birch_downs", "edlen_1966"]

_T0 = 273.15  # K at 0 °C
_TORR = 101325.0 / 760.0  # Pa per torr


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

    Parameters as :func:`ciddor` (metres, °C, Pa, Pa, µmol/mol).

    Returns
    -------
    n : float or ndarray, dimensionless

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

    Parameters as :func:`ciddor` (metres, °C, Pa, Pa, µmol/mol).

    Returns
    -------
    n : float or ndarray, dimensionless

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


# -- helpers --------------------------------------------------------------------------------
def _edlen_inputs(vacuum_wavelength, temperature, pressure, vapour_pressure):
    lam_um = np.asarray(vacuum_wavelength, dtype=float) * 1e6
    return (1.0 / (lam_um * lam_um), np.asarray(temperature, dtype=float),
            np.asarray(pressure, dtype=float), np.asarray(vapour_pressure, dtype=float))



def _edlen_co2_factor(co2, reference_umol):
    return 1.0 + 0.540 * (np.asarray(co2, dtype=float) - reference_umol) * 1e-6
