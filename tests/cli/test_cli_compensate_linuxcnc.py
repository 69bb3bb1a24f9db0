"""``axiscal compensate --read`` of a LinuxCNC file with the INI that names it (issue 27):
LinuxCNC's own configs/sim/screwcompX.dat and tklinuxcnc/servo_sim.ini (tests/data/linuxcnc)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

runner = CliRunner()
DATA = Path(__file__).resolve().parents[1] / "data" / "linuxcnc"
SCREWCOMP = DATA / "screwcompX.dat"


def test_read_takes_unit_and_type_from_the_ini_and_says_where():
    r = runner.invoke(app, ["compensate", "--read", str(SCREWCOMP)])
    assert r.exit_code == 0, r.output
    out = r.stdout
    assert "unit = inch ([TRAJ] LINEAR_UNITS = inch in" in out and "servo_sim.ini" in out
    assert "file_type = 0 ([JOINT_0] COMP_FILE_TYPE = 0" in out
    assert "11 points every 50.8 mm from -254 to 254 mm" in out
    assert "warning: forward trim spike at -101.6 mm: +5080 um" in out
    assert "0.198 inch in the file" in out


def test_read_json_has_the_inputs_and_the_flagged_trim():
    r = runner.invoke(app, ["compensate", "--read", str(SCREWCOMP), "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["controller"] == "linuxcnc"
    inputs = {i["name"]: i for i in d["inputs"]}
    assert inputs["unit"]["value"] == "inch" and inputs["unit"]["source"] == "ini"
    assert inputs["unit"]["assumed"] is False and "LINEAR_UNITS = inch" in inputs["unit"]["why"]
    assert inputs["file_type"]["value"] == 0 and inputs["axis_kind"]["value"] == "linear"
    assert d["table"]["positions"][0] == pytest.approx(-254.0)
    [j] = d["trim_jumps"]
    assert j["direction"] == "forward" and j["kind"] == "spike"
    assert j["position"] == pytest.approx(-101.6) and j["trim"] == pytest.approx(5080.0)


def test_a_contradicting_unit_is_refused_in_one_line():
    r = runner.invoke(app, ["compensate", "--read", str(SCREWCOMP), "-o", "unit=mm"])
    assert r.exit_code == 2 and r.stdout == ""
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.stderr
    assert "-o unit=mm contradicts [TRAJ] LINEAR_UNITS = inch in" in lines[0]


def test_ini_given_explicitly_and_the_pre_2_8_section(tmp_path):
    p = tmp_path / "screwcompX.dat"
    shutil.copy(SCREWCOMP, p)
    r = runner.invoke(app, ["compensate", "--read", str(p), "--json"])
    d = json.loads(r.stdout)
    unit = next(i for i in d["inputs"] if i["name"] == "unit")
    assert unit["assumed"] is True and unit["value"] == "mm" and unit["set_with"] == "-o unit=…"
    r = runner.invoke(app, ["compensate", "--read", str(p), "--ini",
                            str(DATA / "v2.7" / "servo_sim.ini"), "--json"])
    assert r.exit_code == 0, r.output
    unit = next(i for i in json.loads(r.stdout)["inputs"] if i["name"] == "unit")
    assert unit["value"] == "inch" and "[AXIS_0] COMP_FILE" in unit["why"]


def test_ini_with_another_controller_or_use_is_refused(tmp_path):
    p = tmp_path / "X.COM"
    p.write_text("BEGIN X.COM MM\nNR AXISPOS X\n0 +0.0000 +0.001\n1 +10.0000 -0.002\n[END]\n")
    r = runner.invoke(app, ["compensate", "--read", str(p), "--ini", str(DATA / "servo_sim.ini")])
    assert r.exit_code == 2 and "--ini is read with a LinuxCNC compensation file" in r.stderr
    r = runner.invoke(app, ["compensate", "--verify", "x.toml", "--ini", "a.ini"])
    assert r.exit_code == 2 and "does not use --ini" in r.stderr
