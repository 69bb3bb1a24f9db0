"""``axiscal compensate --read`` on Fanuc and 840D files (issue 27): the Fanuc reference position
from the tape or refused for a comparison, what each file does not carry shown as an input or an
assumption (terminal and --json), the 840D inch unit (MD10240), several Fanuc axes per line."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]
#: ESS MCU1025 acceptance test, a real ecmc ISO 230-2 file (tests/data/ecmc/README.md): targets
#: 15 … 55.8 mm; its mean bidirectional deviation at the first target, x̄(15 mm) = 7.019 µm
#: (ISO 230-2:2014 §2.13 from the file's five runs each way, as `axiscal iso230-2` prints it).
MCU1025 = ROOT / "tests" / "data" / "ecmc" / "mcu1025_fat_sat_ISO230.dat"
XBAR_AT_15 = 7.019


def _run(*args):
    return runner.invoke(app, [str(a) for a in args])


def _one_line_error(r):
    assert r.exit_code == 2, r.output
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("axiscal: error: "), r.stderr
    return lines[0]


@pytest.fixture(scope="module")
def tape(tmp_path_factory):
    """The Fanuc table axiscal writes from MCU1025 (reference position 15 mm, its first point)."""
    d = tmp_path_factory.mktemp("fanuc")
    r = _run("compensate", MCU1025, "--controller", "fanuc", "--axis", "X", "--out",
             d / "PITCH_X.TXT")
    assert r.exit_code == 0, r.output
    return d / "PITCH_X.TXT"


def test_fanuc_read_back_compares_at_the_tapes_reference_position(tape):
    """The table is zero at its reference point (15 mm): as written, every residual was x̄(15 mm)
    up to one count x magnification (largest 7.501 µm). The comparison undoes that shift (issue
    42) and says so: −x̄(15 mm) is added to every correction, and the residuals are within half a
    count x magnification of 0."""
    r = _run("compensate", "--read", tape, MCU1025, "--json")
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["start"] == 15.0
    step = d["table"]["resolution"]
    assert d["shift_undone"] == pytest.approx(-XBAR_AT_15, abs=1e-3)
    assert "zero at its reference point 15 mm" in d["comparison_note"]
    for row in d["residual"]:
        assert abs(row["residual"]) <= step / 2 + 1e-9, (row, step)
    assert d["largest_residual"] == pytest.approx(7.501 - XBAR_AT_15, abs=2e-3)
    ref = next(i for i in d["inputs"] if i["name"] == "reference_position")
    assert ref == dict(name="reference_position", value=15.0, unit="mm", assumed=False,
                       source="file", why="from the tape's comment",
                       set_with="-o reference_position=…")


def test_fanuc_tape_without_its_reference_position_is_not_compared(tape, tmp_path):
    foreign = tmp_path / "PITCH.TXT"
    foreign.write_text("".join(ln + "\n" for ln in tape.read_text().splitlines()
                               if not ln.startswith("(REFERENCE POSITION")))
    line = _one_line_error(_run("compensate", "--read", foreign, MCU1025))
    assert "does not record where the reference position" in line
    assert "give -o reference_position=… (mm)" in line
    r = _run("compensate", "--read", foreign, MCU1025, "-o", "reference_position=15", "--json")
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["largest_residual"] == pytest.approx(7.501 - XBAR_AT_15, abs=2e-3)
    r = _run("compensate", "--read", foreign, MCU1025, "-o", "reference_position=0", "--json")
    assert json.loads(r.stdout)["largest_residual"] > 20     # the wrong place: large residuals
    shown = _run("compensate", "--read", foreign)            # reading alone: said, not refused
    assert shown.exit_code == 0, shown.output
    assert ("assumed: reference_position = 0 mm (a Fanuc tape does not record where the "
            "reference position") in shown.stdout
    d = json.loads(_run("compensate", "--read", foreign, "--json").stdout)
    ref = next(i for i in d["inputs"] if i["name"] == "reference_position")
    assert ref["assumed"] is True and ref["value"] == 0.0 and ref["source"] == "default"


def test_fanuc_listing_with_several_axes(tmp_path):
    f = tmp_path / "PARAM.TXT"
    f.write_text("%\nN03620A1P0A2P10\nN03621A1P0A2P10\nN03622A1P2A2P12\nN03624A1P1000A2P2000\n"
                 "N10000P0\nN10001P1\nN10002P1\nN10010P0\nN10011P-2\nN10012P-2\n%\n")
    line = _one_line_error(_run("compensate", "--read", f))
    assert "axes 1, 2: choose one with axis_number=N" in line
    r = _run("compensate", "--read", f, "-o", "axis_number=2", "--json")
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["table"]["positions"] == [0.0, 2.0, 4.0] and d["table"]["up"] == [0.0, -2.0, -4.0]


#: 840D EEC file of an inch machine, MD10240 = 0 (tests/data/siemens/README.md).
INCH_EEC = ROOT / "tests" / "data" / "siemens" / "inch_AX_EEC.INI"


def test_840d_inch_file_read_and_md10240_shown(tmp_path):
    f = tmp_path / "AX_EEC.INI"
    f.write_text(INCH_EEC.read_text())
    r = _run("compensate", "--read", f)
    assert r.exit_code == 0, r.output
    assert "unit = inch (the file states MD10240 $MN_SCALING_SYSTEM_IS_METRIC = 0)" in r.stdout
    d = json.loads(_run("compensate", "--read", f, "--json").stdout)
    assert d["table"]["positions"] == pytest.approx([-25.4, -12.7, 0.0])
    assert d["table"]["up"] == pytest.approx([0.0, -2.54, 5.08])
    assert d["inputs"][0]["value"] == "inch" and d["inputs"][0]["assumed"] is False
    line = _one_line_error(_run("compensate", "--read", f, "-o", "unit=mm"))
    assert ("unit = mm contradicts the file (the file states MD10240 "
            "$MN_SCALING_SYSTEM_IS_METRIC = 0: inch)") in line


def test_840d_inch_written_from_data_states_md10240(tmp_path):
    out = tmp_path / "AX_EEC.INI"
    r = _run("compensate", MCU1025, "--controller", "siemens-840d", "--spacing", "12.7",
             "--start", "12.7", "-o", "unit=inch", "--out", out)
    assert r.exit_code == 0, r.output
    assert "MD10240 $MN_SCALING_SYSTEM_IS_METRIC = 0" in r.stdout      # the enable list
    text = out.read_text()
    assert "$AA_ENC_COMP_STEP[0,AX1]=0.5" in text and "$AA_ENC_COMP_MIN[0,AX1]=0.5" in text
    d = json.loads(_run("compensate", "--read", out, MCU1025, "--json").stdout)
    assert d["inputs"][0]["value"] == "inch" and d["start"] == pytest.approx(12.7)
