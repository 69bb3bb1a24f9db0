"""The shipped example files: their provenance and what the CLI makes of them."""

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.io.squareness_examples import example_files

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
runner = CliRunner()


def _json(*args):
    res = runner.invoke(app, [*map(str, args), "--json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_example_files_are_what_the_simulation_makes():
    """Provenance: every examples/squareness_*.csv equals the seeded simulation's output."""
    for name, text in example_files().items():
        assert (EXAMPLES / name).read_text() == text, name


def test_L180_example_gives_machine3_value():
    """Seed 004 Figure 16: Machine 3, "L" at the right-hand corner: +65 µm/m (noise 0.05 µm on
    17 points: budget ±0.5 µm/m)."""
    d = _json("squareness", "biaxial", EXAMPLES / "squareness_L180_x.csv",
              EXAMPLES / "squareness_L180_y.csv", "--config", "L", "--orientation", 180)
    assert d["squareness"]["um_per_m"] == pytest.approx(65.0, abs=0.5)
    s = _json("straightness", EXAMPLES / "squareness_L180_x.csv")
    assert s["straightness_um"] == pytest.approx(10.0, abs=0.3)  # Machine 3's 10 µm bend


def test_ballbar_and_diagonal_examples_recover_the_injected_errors():
    """Truth: squareness 12 µm/m, scale mismatch 12 µm/m, backlash 6 / -3 µm (noise 0.1 µm,
    budget 0.3); diagonal 15 µm/m (noise 0.05 µm, budget 0.3)."""
    b = _json("squareness", "circular", EXAMPLES / "squareness_ballbar_150mm.csv")
    assert b["squareness"]["um_per_m"] == pytest.approx(12.0, abs=0.3)
    assert b["scale_mismatch_um_per_m"] == pytest.approx(12.0, abs=0.3)
    assert b["backlash_x_um"] == pytest.approx(6.0, abs=0.3)
    assert b["backlash_y_um"] == pytest.approx(-3.0, abs=0.3)
    d = _json("squareness", "diagonal", "--file", EXAMPLES / "squareness_diagonal_600x800.csv")
    assert d["squareness"]["um_per_m"] == pytest.approx(15.0, abs=0.3)
