"""A shop-floor user's mistakes in data files and configurations: one line, exit code 2.

Every case below went wrong before this review (the comment says how): a traceback, a result
computed from an impossible input, or a silently ignored value.
"""

import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from tests.cli._assertions import one_error_line

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]
EX = ROOT / "examples"
H = "# target_unit=mm deviation_unit=um\ntarget,direction,run,deviation\n"
POS = H + "".join(f"{t},{d},{r},{0.1 * r}\n" for t in (0, 100, 200) for r in (1, 2, 3) for d in "+-")
ECMC = "UNIT=mm\nTGT_DATA[1]=0\nTGT_DATA[2]=10\nREF_DATA_FWD[1,1]=0\nREF_DATA_FWD[2,1]=10\n"
BALL = "# radius_mm=150\nangle,direction,deviation\n" + "".join(f"{a},ccw,0.5\n" for a in range(0, 360, 10))
DIAG = (EX / "squareness_diagonal_600x800.csv").read_text()
MOTION = (EX / "motion_indexing_table.toml").read_text()
MDATA = "run,angle_deg,ez_arcsec,ey_arcsec,ex_arcsec,dy_um,dz_um\n" + "".join(
    f"1,{a},0,0,0,0,0\n" for a in range(0, 360, 90))
LINEAR = (ROOT / "src/axiscal/data/demo_linear.toml").read_text()
ROTARY = (ROOT / "src/axiscal/data/demo_rotary.toml").read_text()
TURNTABLE = (EX / "rotary_turntable.toml").read_text()
TRUNNION = (EX / "rotary_trunnion.toml").read_text()
SCALE = (EX / "scale_single.toml").read_text()
GANTRY = (EX / "scale_gantry.toml").read_text()
BIG = "1" * 200_000   # over the csv module's field limit


def _sub(text, old, new):
    assert old in text, old
    return text.replace(old, new, 1)


CASES = [
    # csv module's own error escaped as a traceback (_csv.Error: field larger than field limit)
    ("iso230-2 f.csv", POS + f"0,+,4,{BIG}\n", ["f.csv:", "not a CSV line"]),
    ("straightness f.csv", f"position,deviation\n0,1\n1,{BIG}\n", ["f.csv:3", "not a CSV line"]),
    # run 1e300 made numpy allocate an array as wide as the number (ValueError / MemoryError)
    ("iso230-2 f.csv", POS + "0,+,1e300,1\n", ["f.csv:21", "run '1e300' is beyond the 19 readings"]),
    ("iso230-2 f.txt", ECMC + "REF_DATA_FWD[1,99999999999]=0\n", ["cycle 99999999999 is beyond the 3 readings"]),
    ("motion analyze f.csv", MDATA + "".join(f"1e300,{a},0,0,0,0,0\n" for a in range(0, 360, 90)),
     ["f.csv:6", "is beyond the 8 readings"]),
    # a ballbar angle given twice in one run was averaged in silently
    ("squareness circular f.csv", BALL + "20,ccw,0.7\n", ["f.csv:39", "angle 20 deg of the ccw run is given twice (first on line 5)"]),
    # a deviation larger than the radius gave a "result"
    ("squareness circular f.csv", _sub(BALL, "radius_mm=150", "radius_mm=0.0001"),
     ["f.csv:3", "not smaller than the radius 0.0001 mm"]),
    # the radius line was reported as line 0
    ("squareness circular f.csv", _sub(BALL, "radius_mm=150", "radius_mm=inf"), ["f.csv: radius_mm 'inf'"]),
    # a diagonal reading 5 m along a 1 m diagonal was used
    ("squareness diagonal --file f.csv", _sub(DIAG, "D1,100.000000", "D1,5000"),
     ["position 5000 mm lies off the diagonal, 0 to 1000 mm"]),
    ("squareness diagonal --file f.csv", _sub(DIAG, "D1,100.000000", "D1,-100"), ["lies off the diagonal"]),
    ("squareness diagonal --file f.csv", _sub(DIAG, "length_x_mm=600", "length_x_mm=-600"),
     ["length_x_mm=-600: a travel must be positive"]),
    # --file and the lengths: the lengths were ignored without a word
    ("squareness diagonal --file f.csv --d1 3 --x-length 600", DIAG, ["drop --x-length, --d1"]),
    # motion configuration: int(inf) / int(nan) raised OverflowError / ValueError
    ("motion simulate f.toml", _sub(MOTION, "[1, 18.0, 30.0]", "[inf, 18.0, 30.0]"), ["harmonics", "whole, 1 to 3600"]),
    ("motion simulate f.toml", _sub(MOTION, "[1, 18.0, 30.0]", "[nan, 18.0, 30.0]"), ["harmonics: entry"]),
    # an infinite drift rate ran and printed RuntimeWarnings and NaN
    ("motion simulate f.toml", _sub(MOTION, "rate_urad_per_h = [1.0, -0.7]", "rate_urad_per_h = [inf, -0.7]"),
     ["rate_urad_per_h", "2 finite numbers"]),
    # 10⁸ samples 1 s apart in a 30 s dwell: numpy ran out of memory
    ("motion simulate f.toml", _sub(MOTION, "samples = 10", "samples = 100000000"),
     ["[test] samples = 100000000 must be at most 1000"]),
    # and 50 readings 1 s apart in the same 30 s dwell
    ("motion simulate f.toml", _sub(MOTION, "samples = 10", "samples = 50"),
     ["samples = 50 readings 1 s apart do not fit in dwell_s = 30 s"]),
    # 2^32 + 1 runs: the simulation ran for ever (the command line's --runs stops at 100)
    ("motion repeatability f.toml", _sub(MOTION, "runs = 3", "runs = 4294967297"),
     ["[test] runs = 4294967297 must be at most 100"]),
    # positioning simulation: numpy refused the seed (traceback), or a string name became "5"
    ("simulate f.toml", _sub(LINEAR, "seed = 11", "seed = -1"), ["[axis] irregular seed = -1", ">= 0"]),
    ("simulate f.toml", _sub(LINEAR, "seed = 11", 'seed = "x"'), ["seed = 'x'"]),
    ("simulate f.toml", _sub(LINEAR, "seed = 11", "seed = 1.5"), ["seed = 1.5"]),
    ("simulate f.toml", _sub(LINEAR, "rms_um = 0.6", "rms_um = -0.6"), ["rms_um = -0.6 must be >= 0"]),
    ("simulate f.toml", _sub(LINEAR, 'name = "X"', "name = 5"), ["[axis] name = 5"]),
    ("simulate f.toml", _sub(LINEAR, "travel_mm = [-10, 810]", "travel_mm = [-10, inf]"),
     ["travel_mm", "pair of finite numbers"]),
    ("simulate f.toml", _sub(ROTARY, "orders = [5, 36]", "orders = [5, 100000000]"), ["irregular.orders", "3600"]),
    ("simulate f.toml", _sub(ROTARY, "orders = [5, 36]", "orders = [0, 36]"), ["irregular.orders"]),
    # rotary calibration configuration
    ("rotary simulate f.toml", "", ["no [axis] table"]),
    ("rotary simulate f.toml", "axis = 5\n", ["[axis] must be a table"]),
    ("rotary simulate f.toml", "seed = -1\n" + _sub(TURNTABLE, "seed = 7", ""), ["top level seed = -1", ">= 0"]),
    ("rotary simulate f.toml", _sub(TURNTABLE, "seed = 11", "seed = -11"), ["[calibrator] seed = -11"]),
    ("rotary simulate f.toml", _sub(TURNTABLE, "error_map = true", "map_points = 0"),
     ["[calibrator] map_points = 0 must be a whole number >= 2"]),
    ("rotary simulate f.toml", _sub(TURNTABLE, "graduation_error_rms_arcsec = 2.0", "graduation_error_rms_arcsec = -2.0"),
     ["graduation_error_rms_arcsec = -2.0 must be >= 0"]),
    ("rotary simulate f.toml", _sub(TURNTABLE, "[setup]", "[setup]\ndial_noise_mm = -1"), ["dial_noise_mm = -1 must be >= 0"]),
    ("rotary simulate f.toml", _sub(TRUNNION, "radius_mm = 150", "radius_mm = 0"), ["[offaxis] radius_mm = 0 must be positive"]),
    ("rotary simulate f.toml", _sub(TRUNNION, "interferometer_distance_mm = 600", "interferometer_distance_mm = 0"),
     ["interferometer_distance_mm = 0 must be positive"]),
    # laser scale configuration
    ("scale home f.toml", _sub(SCALE, "seed = 2", "seed = -2"), ["[homing] seed = -2 must be at least 0"]),
    ("scale home f.toml", _sub(SCALE, "start_mm = 99.96", "start_mm = 99.96\npower_up_phase = 256"),
     ["power_up_phase = 256 counts must lie in 0 to 255"]),
    ("scale home f.toml", _sub(SCALE, "target_mm = 1100.0", "target_mm = 1e12"), ["[move] target_mm = 1e12 mm must be at most 1e6 mm"]),
    ("scale home f.toml", _sub(SCALE, "repeatability_um = 0.5", "repeatability_um = -0.5"), ["[switch] repeatability_um"]),
    ("scale gantry f.toml", _sub(GANTRY, "seed = 5", "seed = -5"), ["[gantry] seed = -5"]),
    ("scale gantry f.toml", _sub(GANTRY, "switch_repeatability_um = 0.3", "switch_repeatability_um = -0.3"),
     ["switch_repeatability_um = -0.3 µm must be at least 0 µm"]),
    ("scale gantry f.toml", _sub(GANTRY, "switch_repeatability_um = 0.3", "switch_repeatability_um = 1e9"),
     ["switch_repeatability_um"]),
    ("scale gantry f.toml", _sub(GANTRY, "seed = 5", "seed = 5\npower_up_phase_1 = -1"), ["power_up_phase_1 = -1"]),
    ("scale gantry f.toml", _sub(GANTRY, "start_1_mm = 99.95", "start_1_mm = -1e6"), ["[gantry] start_1_mm"]),
]


@pytest.mark.parametrize("command, content, words", CASES, ids=[f"{i}-{c[0].split()[0]}" for i, c in enumerate(CASES)])
def test_file_mistakes_are_one_line(tmp_path, command, content, words):
    args = command.split()
    name = next(a for a in args if a.startswith("f."))
    (tmp_path / name).write_text(content)
    old = os.getcwd()
    os.chdir(tmp_path)
    try:
        before = sorted(os.listdir(tmp_path))
        r = runner.invoke(app, args)
    finally:
        os.chdir(old)
    one_error_line(r, *words)
    assert sorted(os.listdir(tmp_path)) == before


def test_biaxial_deviations_must_be_read_along_the_other_axis(tmp_path):
    """ISO 230-1 §3.6.7: the X trajectory's deviations along Y and the Y trajectory's along X; a
    Y file with deviations along Z used to give an XY squareness."""
    y = tmp_path / "y.csv"
    y.write_text((EX / "squareness_L180_y.csv").read_text().replace("direction=X", "direction=Z"))
    r = runner.invoke(app, ["squareness", "biaxial", str(EX / "squareness_L180_x.csv"), str(y)])
    assert r.exit_code == 2 and r.stdout == ""
    assert "reads the Y axis's deviations along Z; a bi-axial XY test needs them along X" in r.stderr


def test_budget_says_when_an_accuracy_is_out_of_reach():
    """Seed 000: the system alone gives ±0.8 arcsec; ±0.5 used to print 'align α within 0.000 mrad'."""
    r = runner.invoke(app, ["rotary", "budget", "--alpha", "1", "--beta", "1", "--accuracy", "0.5"])
    assert r.exit_code == 0, r.output
    assert "±0.5 arcsec cannot be reached at any alignment" in r.stdout
    assert "align α within" not in r.stdout
    r = runner.invoke(app, ["rotary", "budget", "--alpha", "1", "--beta", "1", "--accuracy", "2"])
    assert "align α within" in r.stdout


@pytest.mark.parametrize("content, args, words", [
    # µm read as mm (a factor 1000) because the option silently overrode the file's declaration
    (POS, ["--deviation-unit", "mm"], ["declares deviation_unit=um but the option gives mm"]),
    (POS, ["--target-unit", "deg", "--deviation-unit", "arcsec"], ["declares target_unit=mm"]),
    (ECMC + "REF_DATA_FWD[1,2]=0\nREF_DATA_FWD[2,2]=10\n", ["--target-unit", "deg"], ["declares UNIT=mm"]),
    # pooling 0 and 360 deg was accepted (and did nothing) on a linear axis
    (POS, ["--full-turn", "merge"], ["--full-turn merge pools 0 and 360 deg", "linear axis"]),
    # the second tolerance replaced the first without a word
    (POS, ["--tolerance", "A=1", "--tolerance", "A=100"], ["--tolerance A is given twice"]),
])
def test_positioning_options_that_contradict_the_file(tmp_path, content, args, words):
    f = tmp_path / ("f.txt" if content.startswith("UNIT") else "f.csv")
    f.write_text(content)
    r = runner.invoke(app, ["iso230-2", str(f), *args])
    assert r.exit_code == 2 and r.stdout == "", r.output
    assert len(r.stderr.strip().splitlines()) == 1
    for w in words:
        assert w in r.stderr, (w, r.stderr)


def test_an_option_may_still_supply_an_undeclared_or_equal_unit(tmp_path):
    f = tmp_path / "f.csv"
    f.write_text(POS.replace("# target_unit=mm deviation_unit=um\n", ""))
    assert runner.invoke(app, ["iso230-2", str(f), "--target-unit", "mm", "--deviation-unit", "um"]).exit_code == 0
    f.write_text(POS)
    assert runner.invoke(app, ["iso230-2", str(f), "--deviation-unit", "µm"]).exit_code == 0


def test_json_metadata_that_is_not_an_object(tmp_path):
    """Used to say "dictionary update sequence element #0 has length 1; 2 is required"."""
    f = tmp_path / "d.json"
    f.write_text('{"format":"axiscal.positioning/1","axis_kind":"linear","target_unit":"mm",'
                 '"deviation_unit":"um","targets":[0,1],"up":[[1,2],[1,2]],"down":[[],[]],'
                 '"metadata":"VMC-800"}')
    r = runner.invoke(app, ["iso230-2", str(f)])
    assert r.exit_code == 2 and "d.json: 'metadata' must be a JSON object, not 'VMC-800'" in r.stderr


def test_text_in_another_encoding_is_not_called_binary(tmp_path):
    """A spreadsheet's Windows-1252 CSV (µ = 0xB5) was reported as 'is this a binary file?'."""
    f = tmp_path / "excel.csv"
    f.write_bytes(POS.replace("deviation_unit=um", "deviation_unit=µm").encode("cp1252"))
    r = runner.invoke(app, ["iso230-2", str(f)])
    assert r.exit_code == 2 and "byte 32 is 0xB5); save the file as UTF-8" in r.stderr, r.stderr
    f.write_bytes(bytes(range(256)))
    r = runner.invoke(app, ["iso230-2", str(f)])
    assert r.exit_code == 2 and "is this a binary file?" in r.stderr


def test_a_later_comment_does_not_silently_redeclare(tmp_path):
    """A second '# radius_mm=100' further down replaced the first declaration without a word."""
    f = tmp_path / "b.csv"
    f.write_text(BALL + "# radius_mm=100\n")
    r = runner.invoke(app, ["squareness", "circular", str(f)])
    assert r.exit_code == 2 and "b.csv:39: radius_mm=100 contradicts radius_mm=150" in r.stderr, r.stderr
    f.write_text(BALL + "# radius_mm=150 plane=XY\n")   # repeating the same value is fine
    assert runner.invoke(app, ["squareness", "circular", str(f)]).exit_code == 0


def test_axis_that_is_not_a_table(tmp_path):
    """simulate with 'axis = 5' raised AttributeError: 'int' object has no attribute 'get'."""
    f = tmp_path / "c.toml"
    f.write_text("axis = 5\n[test]\nlength_mm = 800\n")
    r = runner.invoke(app, ["simulate", str(f)])
    assert r.exit_code == 2 and "[axis] must be a table, got 5" in r.stderr, r.output


def test_positioning_file_pasted_from_two_units(tmp_path):
    """A second block '# target_unit=deg ...' below the mm block was ignored: degrees read as mm."""
    f = tmp_path / "two.csv"
    f.write_text(POS + "# target_unit=deg deviation_unit=arcsec\n0,+,4,1\n")
    r = runner.invoke(app, ["iso230-2", str(f)])
    assert r.exit_code == 2 and "two.csv:21: target_unit=deg contradicts target_unit=mm" in r.stderr, r.stderr


@pytest.mark.parametrize("command, content, words", [
    ("rotary simulate", _sub(TRUNNION, 'yaw_sign = "auto"', "yaw_sign = true"), ["yaw_sign = True"]),
    ("simulate", _sub(ROTARY, "order = 1,", "order = true,"), ["order = True must be a whole number"]),
])
def test_true_is_not_the_number_one(tmp_path, command, content, words):
    """TOML true passed 'in (1, -1)' and 'isinstance(v, int)' checks and became 1."""
    f = tmp_path / "c.toml"
    f.write_text(content)
    r = runner.invoke(app, [*command.split(), str(f)])
    assert r.exit_code == 2, r.output
    for w in words:
        assert w in r.stderr, r.stderr


@pytest.mark.parametrize("old, new, words", [
    ("runs = 5", 'runs = "five"', ["[test] runs = 'five' must be a whole number >= 1"]),   # ValueError
    ("runs = 5", "runs = 2.7", ["[test] runs = 2.7"]),                                     # became 2
    ("dwell_s = 2.0", "dwell_s = []", ["[test] dwell_s = [] must be a finite number"]),    # TypeError
    ("step_deg = 45", 'step_deg = "45"', ["[test] step_deg = '45'"]),                      # accepted
])
def test_rotary_test_table_types(tmp_path, old, new, words):
    f = tmp_path / "c.toml"
    f.write_text(_sub(TURNTABLE, old, new))
    r = runner.invoke(app, ["rotary", "simulate", str(f)])
    assert r.exit_code == 2 and r.stdout == "", r.output
    for w in words:
        assert w in r.stderr, r.stderr


def test_rotary_bidirectional_must_be_a_boolean(tmp_path):
    f = tmp_path / "c.toml"
    f.write_text(_sub(TURNTABLE, "runs = 5", 'runs = 5\nbidirectional = "no"'))   # "no" was true
    r = runner.invoke(app, ["rotary", "simulate", str(f)])
    assert r.exit_code == 2 and "[test] bidirectional = 'no' must be true or false" in r.stderr


def test_gantry_position_beyond_any_machine(tmp_path):
    """Found by the property test: start_1_mm = 1.4e304 overflowed int(round(inf)) in counts."""
    f = tmp_path / "g.toml"
    f.write_text(_sub(GANTRY, "start_1_mm = 99.95", "start_1_mm = 1.4e304"))
    r = runner.invoke(app, ["scale", "gantry", str(f)])
    assert r.exit_code == 2 and "[gantry] start_1_mm = 1.4e304 mm must be at most 1e6 mm" in r.stderr


@pytest.mark.parametrize("old, new, words", [
    ("step_deg = 45", "n_targets = 1000000000000", ["[test] n_targets = 1000000000000 is more than 10000"]),
    ("step_deg = 45", "step_deg = 1e-9", ["gives more than 10000 targets"]),
    ("travel_deg = 360", "travel_deg = 1e300", ["[test] travel_deg = 1e+300 is more than 36000"]),
])
def test_rotary_test_table_that_would_exhaust_memory(tmp_path, old, new, words):
    """Found by the property test: n_targets = 10**12 made plan_rotary allocate 7 TiB."""
    f = tmp_path / "c.toml"
    f.write_text(_sub(TURNTABLE, old, new))
    r = runner.invoke(app, ["rotary", "simulate", str(f)])
    assert r.exit_code == 2, r.output
    for w in words:
        assert w in r.stderr, r.stderr


def test_motion_readings_are_bounded_together(tmp_path):
    """Each allowed alone, a 0.1° step with 1000 samples a stop (and --runs 100) asked for tens of
    millions of simulated readings: the product is bounded and named."""
    f = tmp_path / "m.toml"
    f.write_text(_sub(_sub(_sub(MOTION, "step_deg = 30", "step_deg = 0.1"), "samples = 10",
                           "samples = 1000"), "dwell_s = 30", "dwell_s = 3600"))
    r = runner.invoke(app, ["motion", "simulate", str(f)])
    assert r.exit_code == 2 and "make 1.08e+07 readings; at most 1e+06" in r.stderr, r.stderr
