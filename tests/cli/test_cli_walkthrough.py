"""What a newcomer saw in the terminal on the README's tour and in ``axiscal demo``, kept from
coming back: parameters in their ISO 230-2 symbols (B mean, A↑), never the ``--json`` keys
(B_mean, A_up), and units in table titles that Rich's markup had swallowed."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from axiscal.cli import app

ROOT = Path(__file__).resolve().parents[2]
ENV = {"COLUMNS": "120"}


def test_simulate_truth_table_speaks_in_symbols():
    r = CliRunner().invoke(app, ["simulate", str(ROOT / "src/axiscal/data/demo_linear.toml")],
                           env=ENV)
    assert r.exit_code == 0, r.output
    truth = r.output.split("Measured beside the simulation's truth [µm]")[1]
    assert "B mean" in truth and "B_mean" not in truth


def test_rotary_simulate_truth_table_has_its_unit_and_symbols():
    r = CliRunner().invoke(app, ["rotary", "simulate", str(ROOT / "examples/rotary_turntable.toml")],
                           env=ENV)
    assert r.exit_code == 0, r.output
    assert "Measured beside the truth [arcsec]" in r.output
    truth = r.output.split("Measured beside the truth [arcsec]")[1].split("set-up check")[0]
    assert "A↑" in truth and "B mean" in truth
    assert "A_up" not in truth and "B_mean" not in truth
