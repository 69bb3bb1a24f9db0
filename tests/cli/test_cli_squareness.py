"""CLI: ``axiscal straightness`` and ``axiscal squareness ...`` (axiscal.cli.squareness)."""

import json

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.io.ballbar import BallbarData, format_ballbar
from axiscal.io.straightness import StraightnessData, format_straightness
from axiscal.machines.xy_plane import XYPlaneMachine, seed004_machine
from axiscal.procedures.squareness import (
    BallbarTest,
    BiaxialTest,
    measure_ballbar,
    measure_biaxial,
)

runner = CliRunner()


def _run(*args):
    return runner.invoke(app, [str(a) for a in args])


@pytest.fixture
def biaxial_files(tmp_path):
    """Machine 3, "L" 180 (corner top-right): +65 µm/m (seed 004 Figure 16)."""
    r = measure_biaxial(seed004_machine(3), BiaxialTest("L", 180))
    x = tmp_path / "x.csv"
    y = tmp_path / "y.csv"
    x.write_text(format_straightness(StraightnessData(r.x_positions, r.x_deviations, "X", "Y")))
    y.write_text(format_straightness(StraightnessData(r.y_positions, r.y_deviations, "Y", "X")))
    return x, y


@pytest.fixture
def ballbar_file(tmp_path):
    m = XYPlaneMachine(squareness=12e-6, scale_x=8e-6, scale_y=-4e-6, backlash_x=6e-6)
    runs = measure_ballbar(m, BallbarTest(radius=0.15, n_points=360))
    p = tmp_path / "bb.csv"
    p.write_text(format_ballbar(BallbarData(0.15, runs)))
    return p


def test_straightness_json_and_plot(biaxial_files, tmp_path):
    """Machine 3's X trajectory: 10 µm bend (seed 004 Appendix I), level line."""
    plot = tmp_path / "s.png"
    res = _run("straightness", biaxial_files[0], "--reference", "minimum-zone", "--json",
               "--plot", plot)
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)
    assert d["reference"] == "minimum_zone"
    assert d["straightness_um"] == pytest.approx(10.0, abs=1e-6)
    assert d["slope_um_per_m"] == pytest.approx(0.0, abs=1e-6)
    assert set(d["methods"]) == {"least_squares", "end_point", "minimum_zone"}
    assert d["methods"]["least_squares"]["straightness_um"] >= d["straightness_um"]
    assert plot.read_bytes()[:4] == b"\x89PNG"
    text = _run("straightness", biaxial_files[0])
    # the reference lines in words on the terminal (report/labels.py VALUES), keys in --json
    assert text.exit_code == 0 and "minimum zone" in text.stdout and "µm/m" in text.stdout
    assert "minimum_zone" not in text.stdout and "least_squares" not in text.stdout


def test_biaxial_gives_the_seed_value_and_both_conventions(biaxial_files):
    x, y = biaxial_files
    res = _run("squareness", "biaxial", x, y, "--config", "L", "--orientation", 180, "--json")
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)
    assert d["squareness"]["um_per_m"] == pytest.approx(65.0, abs=1e-6)
    assert d["squareness"]["iso_um_per_m"] == pytest.approx(65.0, abs=1e-6)
    assert "larger than 90" in d["squareness"]["angle_note"]
    ydatum = json.loads(_run("squareness", "biaxial", x, y, "--datum", "Y", "--json").stdout)
    assert ydatum["squareness"]["iso_um_per_m"] == pytest.approx(-65.0, abs=1e-6)
    prism = json.loads(_run("squareness", "biaxial", x, y, "--orientation", 90,
                            "--prism-error", 1.0, "--json").stdout)
    assert prism["correction_um_per_m"] == pytest.approx(-4.8481368, rel=1e-6)
    assert prism["squareness"]["um_per_m"] == pytest.approx(65.0 - 4.8481368, abs=1e-5)
    text = _run("squareness", "biaxial", x, y)
    assert "positive when the angle exceeds 90°" in text.stdout


def test_diagonal_two_lengths_and_file(tmp_path):
    res = _run("squareness", "diagonal", "--x-length", 800, "--y-length", 800, "--d1", 6,
               "--d2", -6, "--json")
    d = json.loads(res.stdout)
    assert d["squareness"]["um_per_m"] == pytest.approx(12 / 1.1313708, rel=1e-6)
    assert d["slope_d1_um_per_m"] is None and "D1" in d["labels"]
    f = tmp_path / "diag.csv"
    f.write_text("# length_x_mm=600 length_y_mm=800\ndiagonal,position,error\n"
                 "D1,0,0\nD1,500,6\nD1,1000,12\nD2,0,0\nD2,500,-6\nD2,1000,-12\n")
    d = json.loads(_run("squareness", "diagonal", "--file", f, "--json").stdout)
    assert d["squareness"]["um_per_m"] == pytest.approx(25.0, rel=1e-9)
    assert d["slope_d1_um_per_m"] == pytest.approx(12.0)


def test_circular_recovers_the_injected_errors(ballbar_file, tmp_path):
    plot = tmp_path / "bb.svg"
    res = _run("squareness", "circular", ballbar_file, "--json", "--plot", plot)
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)
    assert d["squareness"]["um_per_m"] == pytest.approx(12.0, abs=0.05)
    assert d["scale_mismatch_um_per_m"] == pytest.approx(12.0, abs=0.05)
    assert d["backlash_x_um"] == pytest.approx(6.0, abs=0.05)
    assert d["backlash_y_um"] == pytest.approx(0.0, abs=0.05)
    assert plot.read_text().lstrip().startswith("<?xml")


def test_simulate_json_lists_every_method(tmp_path):
    plot = tmp_path / "m3.png"
    res = _run("squareness", "simulate", "--machine", 3, "--json", "--plot", plot)
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)
    methods = {r["method"]: r["um_per_m"] for r in d["results"]}
    assert methods["L 0"] == pytest.approx(-35.0, abs=0.01)
    assert methods["L 180"] == pytest.approx(65.0, abs=0.01)
    assert methods["ballbar"] == pytest.approx(15.0, abs=0.01)
    assert len(d["results"]) == 11 and len(d["averages"]) == 4
    assert plot.stat().st_size > 10_000
    local = json.loads(_run("squareness", "simulate", "--machine", 2, "--scope", "local",
                            "--json").stdout)
    assert len(local["results"]) == 55
    text = _run("squareness", "simulate", "--machine", 6)
    assert "adjacent ballbar tests" in text.stdout


@pytest.mark.parametrize("args, words", [
    (["squareness", "simulate", "--machine", "9"], "machine=9"),
    (["squareness", "simulate", "--scope", "everywhere"], "scope"),
    (["squareness", "diagonal", "--x-length", "800"], "missing"),
    (["squareness", "biaxial", "nope.csv", "nope.csv"], "nope.csv"),
    (["straightness", "nope.csv"], "nope.csv"),
    (["squareness", "circular", "nope.csv"], "nope.csv"),
    (["squareness", "simulate", "--plot", "/no/such/folder/p.png"], "does not exist"),
])
def test_user_errors_are_one_line_exit_2(args, words):
    res = runner.invoke(app, args)
    assert res.exit_code == 2, res.output
    assert words in res.stderr
    assert "Traceback" not in res.output
    assert len(res.stderr.strip().splitlines()) == 1


def test_bad_file_contents_and_options(biaxial_files, tmp_path):
    x, y = biaxial_files
    bad = tmp_path / "bad.csv"
    bad.write_text("position,deviation\n0,1\n100,abc\n")
    res = _run("straightness", bad)
    assert res.exit_code == 2 and "bad.csv:3" in res.stderr
    for args in (["--config", "Q"], ["--orientation", "45"], ["--reference", "best"]):
        res = _run("squareness", "biaxial", x, y, *args)
        assert res.exit_code == 2, args
        assert len(res.stderr.strip().splitlines()) == 1
    bb = tmp_path / "bb.csv"
    bb.write_text("angle,direction,deviation\n" + "\n".join(f"{a},ccw,0" for a in range(0, 360, 10)))
    res = _run("squareness", "circular", bb)
    assert res.exit_code == 2 and "radius" in res.stderr
    half = tmp_path / "half.csv"
    half.write_text("# radius_mm=100\nangle,direction,deviation\n"
                    + "\n".join(f"{a},ccw,0" for a in range(0, 180, 5)))
    res = _run("squareness", "circular", half)
    assert res.exit_code == 2 and "220" in res.stderr
