"""``axiscal air``: output, JSON keys, errors as one line with exit code 2."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.physics import air

runner = CliRunner()


def test_air_prints_n_ppm_wavelength_and_compensation():
    r = runner.invoke(app, ["air", "--temperature", "20", "--pressure", "101325",
                            "--humidity", "50"])
    assert r.exit_code == 0, r.output
    assert "n = 1.000271373" in r.output
    assert "271.373 ppm" in r.output
    assert "632.81927 nm" in r.output
    assert "-271.299 ppm" in r.output


def test_air_json_keys_and_values():
    r = runner.invoke(app, ["air", "--json", "--equation", "birch-downs", "--co2", "400",
                            "--wavelength", "633.0", "--dew-point", "8"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    for key in ("n", "wavelength_nm", "equation", "n_minus_1_ppm", "compensation_ppm",
                "compensation_factor", "sensitivities", "warnings"):
        assert key in d
    assert d["equation"] == "birch-downs"
    want = air.refractive_index(20.0, 101325.0, dew_point=8.0, co2=400.0,
                                vacuum_wavelength=633e-9, equation="birch-downs")
    assert d["n"] == pytest.approx(want, abs=1e-15)
    assert d["wavelength_nm"] == pytest.approx(633.0 / want)


def test_air_outside_validity_is_one_line_error_or_warning():
    r = runner.invoke(app, ["air", "--temperature", "150"])
    assert r.exit_code == 2
    assert "temperature = 150" in r.output and "Traceback" not in r.output
    r = runner.invoke(app, ["air", "--temperature", "45", "--equation", "edlen",
                            "--allow-outside", "--json"])
    assert r.exit_code == 0
    assert json.loads(r.stdout)["warnings"]


def test_air_bad_equation_and_humidity():
    r = runner.invoke(app, ["air", "--equation", "lorentz"])
    assert r.exit_code == 2 and "equation" in r.output
    r = runner.invoke(app, ["air", "--humidity", "50", "--dew-point", "10"])
    assert r.exit_code == 2 and "exactly one" in r.output
