"""``axiscal motion ...`` commands: output, --json, files, and user errors (exit 2, one line)."""

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

runner = CliRunner()
EXAMPLE = str(Path(__file__).resolve().parents[2] / "examples" / "motion_indexing_table.toml")


def _ok(args):
    r = runner.invoke(app, args)
    assert r.exit_code == 0, r.output
    return r


def test_simulate_json_keys_and_accuracy(tmp_path):
    """The example's measured errors stay near the truth: εz within 1 arcsec (the reference
    encoder's ±0.5 arcsec error plus the 0.9 % εy leak of a 0.5° turned PSD1 and noise), δz
    within 0.3 µm; resolutions are seed 003 §3's."""
    r = _ok(["motion", "simulate", EXAMPLE, "--json"])
    d = json.loads(r.stdout)
    assert {"config", "compensated", "positions", "max_abs_error", "resolutions", "crosstalk",
            "iso230_7"} <= set(d)
    assert len(d["positions"]) == 13 and d["positions"][1]["angle_deg"] == 30
    assert d["max_abs_error"]["ez_arcsec"] < 1.0 and d["max_abs_error"]["dz_um"] < 0.3
    assert d["resolutions"]["angular_arcsec"] == pytest.approx(0.258, abs=1e-3)
    assert d["resolutions"]["displacement_um"] == pytest.approx(0.04)
    assert len(d["crosstalk"]["matrix"]) == 5 and len(d["crosstalk"]["matrix"][0]) == 6
    assert {m["name"] for m in d["iso230_7"]["motions"]} == {"radial Y", "axial", "tilt X", "tilt Y"}


def test_simulate_writes_report_and_csv_that_analyze_reads(tmp_path):
    rep, csv = tmp_path / "sim.html", tmp_path / "sim.csv"
    r = _ok(["motion", "simulate", EXAMPLE, "--report", str(rep), "--csv", str(csv)])
    assert "Five errors per position" in r.stdout and "crosstalk" in r.stdout.lower()
    html = rep.read_text()
    assert html.count("<svg") >= 2 and "ISO 230-7" in html and "Crosstalk" in html
    a = _ok(["motion", "analyze", str(csv), "--json"])
    d = json.loads(a.stdout)
    assert d["iso230_7"]["n_runs"] == 1 and d["title"].startswith("HSD-200RT")
    rep2 = tmp_path / "an.html"
    _ok(["motion", "analyze", str(csv), "--report", str(rep2)])
    assert "<svg" in rep2.read_text()


def test_no_compensation_flag():
    d = json.loads(_ok(["motion", "simulate", EXAMPLE, "--json", "--no-compensation"]).stdout)
    assert d["compensated"] is False


def test_stability_json_of_seed_order(tmp_path):
    """Seed 003 §3.2 figures (0.05, 0.06, 0.19 arcsec; 0.04, 0.03 µm) within a factor 1.7."""
    rep = tmp_path / "stab.html"
    d = json.loads(_ok(["motion", "stability", "--json", "--report", str(rep)]).stdout)
    assert d["readings"] == 361
    for k, seed in d["published_std"].items():
        assert seed / 1.7 < d["std"][k] < seed * 1.7, k
    assert "Stability" in rep.read_text()
    short = _ok(["motion", "stability", EXAMPLE, "--duration-min", "5", "--interval-s", "10"])
    assert "31 readings" in short.stdout
    # the errors by their symbols on the terminal (the JSON keys stay in --json)
    assert "εz [″]" in short.stdout and "δz [µm]" in short.stdout and "_arcsec" not in short.stdout


def test_repeatability_json_and_files(tmp_path):
    csv, rep = tmp_path / "rep.csv", tmp_path / "rep.html"
    d = json.loads(_ok(["motion", "repeatability", EXAMPLE, "--json", "--csv", str(csv),
                        "--report", str(rep)]).stdout)
    assert d["runs"] == 3 and set(d["repeatability"]) == set(d["published_repeatability"])
    assert 0.5 < d["repeatability"]["ez_arcsec"] < 8
    assert d["iso230_7"]["motions"][0]["asynchronous"] is not None
    a = json.loads(_ok(["motion", "analyze", str(csv), "--json"]).stdout)
    assert a["iso230_7"]["n_runs"] == 3
    assert "Repeatability" in rep.read_text()
    text = _ok(["motion", "repeatability", EXAMPLE, "--runs", "2"]).stdout
    assert "±" in text and "εx [″]" in text and "dy_um" not in text


@pytest.mark.parametrize("content,needle", [
    ("[test]\nstep_deg = 'x'\n", "step_deg"),
    ("[test]\nstep_deg = 35\n", "step_deg"),
    ("[instrument]\nfocal = 1\n", "focal"),
    ("[axis.tilt_x]\nharmonics = [[0.5, 1.0, 0.0]]\n", "harmonics"),
    ("[test\n", "TOML"),
    ("[test]\ndrift_window = 4\n", "drift_window"),
    ("[mounting]\ndetector_rotation_deg = [1, 2]\n", "detector_rotation_deg"),
])
def test_bad_config_is_one_line_exit_2(tmp_path, content, needle):
    cfg = tmp_path / "bad.toml"
    cfg.write_text(content)
    r = runner.invoke(app, ["motion", "simulate", str(cfg)])
    assert r.exit_code == 2, r.output
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0] and "Traceback" not in r.output


@pytest.mark.parametrize("content,needle", [
    ("run,angle_deg,ez_arcsec\n1,0,0\n", "header"),
    ("run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um\n1,0,x,0,0,0,0\n", "not a number"),
    ("run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um\n1,0,0,0,0,0,0\n1,90,0,0,0,0,0\n", "angle"),
])
def test_bad_data_file_is_one_line_exit_2(tmp_path, content, needle):
    f = tmp_path / "bad.csv"
    f.write_text(content)
    r = runner.invoke(app, ["motion", "analyze", str(f)])
    assert r.exit_code == 2
    assert len(r.stderr.strip().splitlines()) == 1 and needle in r.stderr


def test_missing_files_and_bad_output_folder(tmp_path):
    r = runner.invoke(app, ["motion", "analyze", str(tmp_path / "nope.csv")])
    assert r.exit_code == 2 and "no such file" in r.stderr
    r = runner.invoke(app, ["motion", "simulate", EXAMPLE, "--report", str(tmp_path / "no" / "r.html")])
    assert r.exit_code == 2 and "does not exist" in r.stderr
