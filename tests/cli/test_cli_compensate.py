"""``axiscal compensate``: tables from data or a result, --verify, --read, --json, user errors."""

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]
LINEAR = ROOT / "examples" / "compensation_linear.toml"
ROTARY = ROOT / "examples" / "compensation_rotary.toml"


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    d = tmp_path_factory.mktemp("comp")
    csv = d / "lin.csv"
    r = runner.invoke(app, ["simulate", str(ROOT / "src/axiscal/data/demo_linear.toml"), "--data", str(csv)])
    assert r.exit_code == 0, r.output
    res = runner.invoke(app, ["iso230-2", str(csv), "--json"])
    (d / "lin.json").write_text(res.stdout)
    return d


def _run(*args):
    return runner.invoke(app, [str(a) for a in args])


def test_table_from_data_prints_what_it_did(data):
    r = _run("compensate", data / "lin.csv", "--controller", "siemens-840d", "--spacing", 40,
             "--bidirectional", "--out", data / "x.ini")
    assert r.exit_code == 0, r.output
    for word in ("points", "spacing", "range", "reference point", "largest", "MD32700", "MD38000"):
        assert word in r.stdout
    text = (data / "x.ini").read_text()
    assert text.startswith("%_N_AX_EEC_INI") and "$AA_ENC_COMP_STEP[0,AX1]=40.0" in text


def test_result_json_and_data_give_the_same_table(data):
    a = json.loads(_run("compensate", data / "lin.csv", "--spacing", 40, "--json").stdout)
    b = json.loads(_run("compensate", data / "lin.json", "--spacing", 40, "--json").stdout)
    assert a["table"]["up"] == pytest.approx(b["table"]["up"], abs=1e-9)
    for key in ("controller", "file", "n_points", "spacing", "start", "end", "reference_position",
                "largest_correction", "enable", "notes", "table"):
        assert key in a
    assert a["n_points"] == 21 and a["spacing"] == 40


def test_heidenhain_writes_cma_next_to_com(data):
    r = _run("compensate", data / "lin.csv", "-c", "heidenhain", "--spacing", 40, "--axis", "X",
             "--out", data / "X.COM")
    assert r.exit_code == 0, r.output
    assert (data / "X.CMA").read_text().startswith("BEGIN CONFIG.CMA")


def test_read_back_and_compare(data):
    _run("compensate", data / "lin.csv", "-c", "linuxcnc", "--spacing", 20, "--out", data / "x.comp")
    r = _run("compensate", "--read", data / "x.comp", "-c", "linuxcnc", data / "lin.csv", "--json")
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["n_points"] == 41
    # at the targets the table cancels the measured mean deviation up to interpolation between
    # table points 20 mm apart and the 0.1 µm rounding (the demo axis has a 20 mm pitch wave)
    assert d["largest_residual"] < 3.0
    assert all(set(row) == {"target", "deviation", "correction", "residual"} for row in d["residual"])


def test_verify_json(tmp_path):
    r = _run("compensate", "--verify", ROTARY, "--json", "--out", tmp_path / "pitch.txt")
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["controller"] == "fanuc" and d["unit"] == "arcsec"
    assert d["reduction"] >= 0.8 and d["after"]["E"] <= d["budget_E"]
    assert set(d["before"]) >= {"A", "E", "M", "R", "B"}
    assert "N3625A1P3600000" in (tmp_path / "pitch.txt").read_text()


def test_verify_text_with_controller_override():
    r = _run("compensate", "--verify", LINEAR, "-c", "csv")
    assert r.exit_code == 0, r.output
    assert "E fell by" in r.stdout and "Budget for E after" in r.stdout and "csv table" in r.stdout


@pytest.mark.parametrize("args,message", [
    (["--spacing", "40.00001", "-c", "fanuc"], "not a whole multiple"),
    (["--spacing", "1", "-c", "heidenhain"], "at most 256"),
    (["--spacing", "40", "-c", "mazak"], "not one of"),
    (["--spacing", "40", "--travel", "0", "--travel", "500"], "outside the axis travel"),
    (["--spacing", "40", "--option", "nonsense"], "KEY=VALUE"),
    (["--spacing", "40", "-c", "fanuc", "--option", "colour=red"], "unknown option(s) colour"),
    (["--spacing", "40", "--extrapolation", "cubic"], "extrapolation"),
])
def test_user_errors_are_one_line_exit_2(data, args, message):
    r = _run("compensate", data / "lin.csv", *args)
    assert r.exit_code == 2, r.output
    assert message in r.stderr
    assert "Traceback" not in r.output and len(r.stderr.strip().splitlines()) == 1


def test_missing_inputs_and_files(tmp_path):
    for args, message in ((["compensate"], "give a data file"),
                          (["compensate", tmp_path / "none.csv"], "no such file"),
                          (["compensate", "--verify", tmp_path / "none.toml"], "no such file"),
                          (["compensate", "--read", tmp_path / "none.comp"], "no such file")):
        r = _run(*args)
        assert r.exit_code == 2 and message in r.stderr, (args, r.output)


def test_bad_config_names_the_key(tmp_path):
    cfg = tmp_path / "c.toml"
    cfg.write_text(LINEAR.read_text().replace("spacing = 10.0", "spacing = -3"))
    r = _run("compensate", "--verify", cfg)
    assert r.exit_code == 2 and "spacing" in r.stderr


def test_squareness_cross_axis_table(tmp_path):
    """Seed 004 Appendix II lathe example: XZ 40 µm/m, Z aligned: δz during X motion."""
    r = _run("compensate", "--squareness", 40, "--axes", "XZ", "--aligned", "Z", "--start", -200,
             "--end", 200, "--spacing", 100, "-c", "siemens-840d", "--json", "--out", tmp_path / "cec.ini")
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["driving_axis"] == "X" and d["compensated_axis"] == "Z"
    assert d["factor_um_per_m"] == pytest.approx(40.0)
    assert d["table"]["up"] == pytest.approx([-8.0, -4.0, 0.0, 4.0, 8.0])
    assert (tmp_path / "cec.ini").read_text().startswith("%_N_NC_CEC_INI")
    r = _run("compensate", "--squareness", 40, "--axes", "XZ", "--start", -200, "--end", 200,
             "--spacing", 100)
    assert r.exit_code == 2 and "aligned" in r.stderr


def test_verify_plot(tmp_path):
    r = _run("compensate", "--verify", LINEAR, "--plot", tmp_path / "loop.png")
    assert r.exit_code == 0, r.output
    assert (tmp_path / "loop.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    r = _run("compensate", "--verify", LINEAR, "--plot", tmp_path / "loop.gif")
    assert r.exit_code == 2 and ".png" in r.stderr
