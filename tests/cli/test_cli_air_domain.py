"""``axiscal air`` outside what can be computed: one error line naming the real problem."""

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

runner = CliRunner()


def _one_line_error(r):
    assert r.exit_code == 2, r.output
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("axiscal: error: "), r.stderr
    return lines[0]


@pytest.mark.parametrize("extra", [[], ["--allow-outside"]])
def test_500_C_is_one_line(extra):
    line = _one_line_error(runner.invoke(app, ["air", "--temperature", "500", *extra]))
    assert "temperature = 500 °C" in line and "finite" not in line


def test_500_C_with_allow_outside_names_the_saturation_range():
    line = _one_line_error(runner.invoke(app, ["air", "-t", "500", "--allow-outside"]))
    assert "critical point" in line


@pytest.mark.parametrize("extra", [[], ["--allow-outside"]])
def test_negative_co2_is_refused(extra):
    line = _one_line_error(runner.invoke(app, ["air", "--co2", "-100", *extra]))
    assert "co2 = -100 µmol/mol cannot be negative" in line
