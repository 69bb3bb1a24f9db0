"""``axiscal fiveaxis ballbar plan | simulate | evaluate`` (issue 43, the ballbar tests of ISO
10791-6:2014 as axiscal reads them): one library call each, the same numbers on every path, and
bad input as one line with exit code 2 and nothing written."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.io.five_axis_ballbar import format_ballbar, parse_ballbar

runner = CliRunner()


def _json(*args):
    r = runner.invoke(app, [str(a) for a in args] + ["--json"])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def test_plan_says_what_each_set_up_sees():
    d = _json("fiveaxis", "ballbar", "plan", "--machine", "bc")
    assert d["tilt_axis"] == "B" and len(d["setups"]) == 6
    c_radial, c_axial, b_radial, five = (d["setups"][i] for i in (0, 2, 3, 5))
    assert c_radial["sensitivity"]["E_X0C"] == pytest.approx(2.0, abs=1e-6)
    assert "E_X0C" in c_axial["blind"] and "E_C0C" in five["blind"]
    assert b_radial["swept"] == "B" and b_radial["sensitivity"]["E_Z0B"] > 0.5
    assert five["kind"] == "five-axis" and d["units"]["E_B0C"] == "µm/µrad"
    assert c_radial["spindle_ball_mm"] == [250.0, 0.0, 40.0]


def test_simulate_writes_files_that_evaluate_reads_to_the_same_numbers(tmp_path):
    out = tmp_path / "bb"
    sim = _json("fiveaxis", "ballbar", "simulate", "--out", out, "--seed", 3)
    assert len(sim["files"]) == 6
    done = _json("fiveaxis", "ballbar", "evaluate", *sim["files"])
    for s, e in zip(sim["setups"], done["setups"]):
        assert e["range_um"] == pytest.approx(s["range_um"], abs=2e-4)     # 0.1 nm rounding
        assert e["U_um"] == pytest.approx(s["U_um"], abs=2e-4)
        assert abs(s["deviation_um"]) <= s["U_um"]
        assert e["budget"]["contributors"][0]["name"] == "u_NOISE"
    text = runner.invoke(app, ["fiveaxis", "ballbar", "evaluate", sim["files"][0]]).output
    assert "C radial: range" in text and "U =" in text


def test_a_file_round_trips():
    from axiscal.api import fiveaxis

    rec = fiveaxis.ballbar.simulate(_ac(), seed=1).records[5]
    back = parse_ballbar(format_ballbar(rec))
    assert back.tilt == "A" and back.swept == "both" and back.direction == "radial"
    assert abs(back.deviation - rec.deviation).max() < 1e-10
    assert back.evaluate().range == pytest.approx(rec.evaluate().range, abs=1e-10)


def _ac():
    from importlib import resources

    return resources.files("axiscal.data").joinpath("fiveaxis_ac.toml")


GOOD = ("# length_mm = 100\n# noise_um = 0.2\npose,A_deg,C_deg,X_mm,Y_mm,Z_mm,deviation_um\n"
        "1,0,0,250,0,40,0.1\n2,0,5,249,21,40,0.3\n3,0,10,246,43,40,0.2\n")


@pytest.mark.parametrize("text, message", [
    (GOOD.replace("2,0,5", "4,0,5"), "pose 2 is missing"),
    (GOOD.replace("0.3\n", "nan\n"), "deviation_um = nan"),
    (GOOD.replace("A_deg,C_deg", "A_deg,A_deg"), "rotary axis A named twice"),
    (GOOD.replace("# noise_um = 0.2\n", ""), "noise_um"),
    (GOOD.replace(",0.2\n", ",\n"), "empty"),
])
def test_a_bad_file_is_one_line_with_exit_2(tmp_path, text, message):
    f = tmp_path / "bad.csv"
    f.write_text(text)
    r = runner.invoke(app, ["fiveaxis", "ballbar", "evaluate", str(f)])
    assert r.exit_code == 2 and message in r.output, r.output
    assert len(r.output.strip().splitlines()) == 1 and "Traceback" not in r.output


def test_a_bad_configuration_writes_nothing(tmp_path):
    cfg = tmp_path / "m.toml"
    cfg.write_text(_ac().read_text("utf-8").replace("C_deg = [0, 360]\nA_deg = 0",
                                                    "C_deg = 10\nA_deg = 0", 1))
    out = tmp_path / "never"
    r = runner.invoke(app, ["fiveaxis", "ballbar", "simulate", str(cfg), "--out", str(out)])
    assert r.exit_code == 2 and "no rotary axis moves" in r.output, r.output
    assert not out.exists()


def test_the_commands_json_is_the_apis_to_dict():
    """One record, every path: ``--json`` is ``axiscal.fiveaxis.ballbar``'s ``to_dict()`` for the
    same input (docs/api.rst)."""
    from axiscal.api import fiveaxis

    assert _json("fiveaxis", "ballbar", "plan") == json.loads(json.dumps(
        fiveaxis.ballbar.plan(_ac()).to_dict()))
    assert _json("fiveaxis", "ballbar", "simulate", "--seed", 5) == json.loads(json.dumps(
        fiveaxis.ballbar.simulate(_ac(), seed=5).to_dict()))
