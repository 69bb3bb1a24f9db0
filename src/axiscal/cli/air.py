"""``axiscal air``: refractive index of air, wavelength in air and the compensation factor.

JSON output (``--json``), stable keys: ``n``, ``n_minus_1_ppm``, ``wavelength_nm`` (in air),
``vacuum_wavelength_nm``, ``compensation_factor`` (1/n), ``compensation_ppm`` ((1/n - 1)·10⁶),
``equation``, ``temperature_c``, ``pressure_pa``, ``vapour_pressure_pa``, ``relative_humidity``,
``co2_umol_per_mol``, ``sensitivities`` (``dn_dT_ppm_per_K``, ``dn_dp_ppm_per_kPa``,
``dn_dRH_ppm_per_percent``) and ``warnings`` (list of text).
"""

from __future__ import annotations

import warnings
from typing import Optional

import typer

from axiscal.cli._common import print_json

__all__ = ["register", "air"]


def air(
    temperature: float = typer.Option(20.0, "--temperature", "-t", help="Air temperature, °C."),
    pressure: float = typer.Option(101325.0, "--pressure", "-p", help="Air pressure, Pa."),
    humidity: Optional[float] = typer.Option(
        None, "--humidity", help="Relative humidity, %RH (default 50 unless --dew-point or "
        "--vapour-pressure is given)."),
    dew_point: Optional[float] = typer.Option(None, "--dew-point", help="Dew point, °C."),
    vapour_pressure: Optional[float] = typer.Option(
        None, "--vapour-pressure", help="Partial pressure of water vapour, Pa."),
    co2: float = typer.Option(450.0, "--co2", help="CO2 content, µmol/mol."),
    wavelength: float = typer.Option(632.991, "--wavelength", help="Vacuum wavelength, nm."),
    equation: str = typer.Option("ciddor", "--equation", "-e",
                                 help="ciddor, edlen (1966) or birch-downs (NIST modified Edlén)."),
    allow_outside: bool = typer.Option(
        False, "--allow-outside", help="Compute outside the equation's validity, with a warning."),
    json_out: bool = typer.Option(False, "--json", help="Print JSON (stable keys, see the docs)."),
) -> None:
    """Refractive index of air, wavelength in air and compensation factor (Ciddor, Edlén).

    Example: axiscal air --temperature 20 --pressure 101325 --humidity 50
    """
    from axiscal.physics.air import AirValidityWarning, air_conditions, sensitivities

    if humidity is None and dew_point is None and vapour_pressure is None:
        humidity = 50.0
    check = "warn" if allow_outside else "raise"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", AirValidityWarning)
        result = air_conditions(temperature, pressure, humidity, dew_point=dew_point,
                                vapour_pressure=vapour_pressure, co2=co2,
                                vacuum_wavelength=wavelength * 1e-9, equation=equation,
                                check=check)
        sens = sensitivities(temperature, pressure, result.relative_humidity, co2=co2,
                             vacuum_wavelength=wavelength * 1e-9, equation=result.equation)
    notes = sorted({str(w.message) for w in caught})
    if json_out:
        d = result.to_dict()
        d["sensitivities"] = {
            "dn_dT_ppm_per_K": sens.dn_dT_ppm_per_K,
            "dn_dp_ppm_per_kPa": sens.dn_dp_ppm_per_kPa,
            "dn_dRH_ppm_per_percent": sens.dn_dRH_ppm_per_percent,
        }
        d["warnings"] = notes
        print_json(d)
        return
    typer.echo(str(result))
    typer.echo(f"  sensitivities: {sens}")
    for n in notes:
        typer.echo(f"warning: {n}", err=True)


def register(app: typer.Typer) -> None:
    """Add the ``air`` command to the application."""
    app.command("air")(air)
