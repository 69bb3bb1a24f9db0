"""Part programs from test plans (issue 41): goldens, LinuxCNC's interpreter, grammars, refusals.

* For each plan kind (linear, rotary full turn, pilgrim, ISO 230-4 circular, squareness lines,
  the ISO 230-3 linear-axis and spindle cycles, the ISO 230-2 drift check, a five-axis R-test) and
  each controller, the program axiscal writes is the golden one in ``tests/data/programs/``,
  reviewed by hand (``tests/programs/program_cases.py`` names the plans and machine options).
* The ISO dialects where LinuxCNC shares their syntax (Fanuc, Haas, LinuxCNC) go through
  LinuxCNC's own RS274/NGC interpreter (``rs274``, Debian linuxcnc-uspace 2.9): each reaches the
  end of program without an error, all three give the same canonical motion, the dwell read as
  LinuxCNC reads ``P`` (seconds: Fanuc's milliseconds come out 1000 times larger, as the two
  manuals' units differ), and the moves are the plan's steps in order.
* SINUMERIK and HEIDENHAIN Klartext lines are checked by a grammar of the block forms their
  manuals document (the examples below are those forms).
* Refusals: one line naming the option, exit code 2, nothing written.
"""

import math
import re

import numpy as np
import pytest
from typer.testing import CliRunner

import axiscal
from axiscal.cli import app
from axiscal.procedures.positioning import plan_linear
from axiscal.programs import CONTROLLERS, MachineOptions, ProgramError, write_program

from program_cases import cases, dwell, golden_path, program

KINDS = tuple(cases())
runner = CliRunner()


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("controller", CONTROLLERS)
def test_generation_reproduces_the_golden_program(kind, controller):
    """The reviewed golden file, byte for byte."""
    assert program(kind, controller) == golden_path(kind, controller).read_text()


# -- LinuxCNC's interpreter ---------------------------------------------------------------------
_CANON = re.compile(r"^\s*\d+\s+N\.+\s+(STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|DWELL|"
                    r"SET_FEED_RATE|PROGRAM_END)\((.*)\)\s*$")


def _canonical(rs274, text, tmp_path, name):
    """LinuxCNC's canonical calls for ``text``: [(call, (numbers...)), ...]."""
    f = tmp_path / name
    f.write_text(text)
    calls = []
    for line in rs274(f, timeout=60).splitlines():
        m = _CANON.match(line)
        if m:
            nums = tuple(float(v) for v in re.findall(r"-?\d+\.\d+|-?\d+", m.group(2)))
            calls.append((m.group(1), nums))
    assert calls and calls[-1][0] == "PROGRAM_END", "the interpreter did not reach the end"
    return calls


@pytest.mark.parametrize("kind", KINDS)
def test_iso_dialects_run_through_linuxcncs_interpreter(kind, tmp_path, rs274):
    """Fanuc, Haas and LinuxCNC programs give LinuxCNC the same motion; the dwells are the plan's
    in each controller's unit (Fanuc ms, Haas and LinuxCNC s)."""
    got = {c: _canonical(rs274, program(kind, c), tmp_path, f"{kind}.{c}.ngc")
           for c in ("linuxcnc", "fanuc", "haas")}
    plan, _ = cases()[kind]
    for c, factor in (("fanuc", 1000.0), ("haas", 1.0)):
        assert len(got[c]) == len(got["linuxcnc"])
        for (call, nums), (ref_call, ref) in zip(got[c], got["linuxcnc"]):
            assert call == ref_call
            want = tuple(v * factor for v in ref) if call == "DWELL" else ref
            assert nums == pytest.approx(want, abs=1e-4)
    dwells = [n[0] for call, n in got["linuxcnc"] if call == "DWELL"]
    if dwell(kind) is not None:     # a ballbar test contours without a stop; thermal: below
        assert dwells and all(d == pytest.approx(dwell(kind)) for d in dwells[:-1])


@pytest.mark.parametrize("kind", ["linear", "rotary", "pilgrim"])
def test_linuxcnc_moves_are_the_plans_steps_in_order(kind, tmp_path, rs274):
    """Each feed move ends at the next step of the plan (machine coordinate = sign × plan); a
    dwell follows every measurement and no overrun."""
    plan, options = cases()[kind]
    calls = _canonical(rs274, program(kind, "linuxcnc"), tmp_path, "p.ngc")
    index = "XYZABC".index(plan.axis)
    sign = options.sign.get(plan.axis, 1)
    ends, after = [], []
    for k, (call, nums) in enumerate(calls):
        if call in ("STRAIGHT_FEED", "STRAIGHT_TRAVERSE"):
            ends.append(nums[index])
            after.append(calls[k + 1][0] if k + 1 < len(calls) else "")
    steps = plan.steps()
    want = [sign * s.position for s in steps]
    # the first step is the safe start itself (a rapid), the last move the return to it
    assert ends[0] == pytest.approx(want[0], abs=1e-4)
    assert ends[-1] == pytest.approx(want[0], abs=1e-4)
    assert ends[1:-1] == pytest.approx(want[1:], abs=1e-4)
    for s, nxt in zip(steps[1:], after[1:-1]):
        assert (nxt == "DWELL") == (s.kind == "measure")


def test_circular_program_contours_the_plans_arcs(tmp_path, rs274):
    """The circular program's arcs, as LinuxCNC reads them: about the plan's centre, at its
    radius, CCW then CW, 2 × (180 + 360 + 180)° in 180° pieces, at the feed."""
    plan, _ = cases()["circular"]
    calls = _canonical(rs274, program("circular", "linuxcnc"), tmp_path, "c.ngc")
    arcs = [n for call, n in calls if call == "ARC_FEED"]
    assert len(arcs) == 8
    for n in arcs:   # ARC_FEED(first_end, second_end, first_axis, second_axis, rotation, ...)
        assert (n[2], n[3]) == pytest.approx(plan.centre, abs=1e-4)
        assert math.hypot(n[0] - n[2], n[1] - n[3]) == pytest.approx(plan.radius, abs=1e-4)
    assert [int(np.sign(n[4])) for n in arcs] == [1] * 4 + [-1] * 4
    feeds = {n[0] for call, n in calls if call == "SET_FEED_RATE" and n[0] > 0}
    assert feeds == {plan.feed}


# -- grammars of the other dialects ------------------------------------------------------------
_SIN = re.compile(
    r"^(%_N_[A-Z0-9_]+_MPF|;\$PATH=/_N_MPF_DIR|;.*|G7[01] G17 G40 G90 G94|M30"
    r"|G0( [XYZABC]-?\d+\.\d{3,4})+|G1( [XYZABC]-?\d+\.\d{3,4})+ F\d+\.\d"
    r"|(G1[89] )?G[23]( [XYZ]-?\d+\.\d{3,4}){2}( [IJK]-?\d+\.\d{3,4}){2} F\d+\.\d"
    r"|G4 F\d+\.\d{3}|S\d+ M3|M5)$")
_HEI = re.compile(
    r"^(BEGIN PGM [A-Z0-9_]+ (MM|INCH)|END PGM [A-Z0-9_]+ (MM|INCH)|; .*"
    r"|L( [XYZABC][+-]\d+\.\d{3,4})+ R0 (FMAX|F\d+)( M30)?|CC( [XYZ][+-]\d+\.\d{3,4}){2}"
    r"|C( [XYZ][+-]\d+\.\d{3,4}){2} DR[+-] R0 F\d+"
    r"|CYCL DEF 9\.0 DWELL TIME|CYCL DEF 9\.1 DWELL \d+\.\d{3}|TOOL CALL Z S\d+|L M[35]|L M30)$")


def test_grammars_accept_the_manuals_block_forms():
    """The grammars accept the block forms the manuals document (SINUMERIK 840D sl
    Programming Manual Fundamentals: G4 dwell with F in seconds, G2/G3 with I, J; HEIDENHAIN
    TNC 640 Klartext: L … R0 FMAX, CC, C … DR+, Cycle 9) and refuse the other dialects' forms."""
    for line in ("G4 F2.500", "G1 X10.000 Y20.000 F300.0", "S1000 M3", "M5",
                 "G2 X50.000 Y40.000 I10.000 J-7.000 F300.0", "; comment", "M30", "%_N_TEST_MPF", ";$PATH=/_N_MPF_DIR"):
        assert _SIN.match(line), line
    for line in ("G04 P2000", "G4 P2.000", "L X+10 R0 FMAX", "(COMMENT)"):
        assert not _SIN.match(line), line
    for line in ("BEGIN PGM NEW MM", "L X+40.000 Y+50.000 R0 FMAX", "CC X+25.000 Y+25.000",
                 "C X+45.000 Y+25.000 DR+ R0 F200", "CYCL DEF 9.0 DWELL TIME",
                 "CYCL DEF 9.1 DWELL 1.500", "END PGM NEW MM", "TOOL CALL Z S3000", "L M3",
                 "L M5"):
        assert _HEI.match(line), line
    for line in ("L X40 R0 FMAX", "G04 P1000", "CYCL DEF 9.1 V.ZEIT 1.5", "C X+45 Y+25 DR+",
                 "S1000 M03", "TOOL CALL 1 Z S3000 M3"):
        assert not _HEI.match(line), line


@pytest.mark.parametrize("kind", KINDS)
def test_sinumerik_and_heidenhain_programs_follow_the_grammar(kind):
    for line in program(kind, "sinumerik").splitlines():
        assert _SIN.match(line), line
    lines = program(kind, "heidenhain").splitlines()
    for n, line in enumerate(lines):
        number, _, block = line.partition(" ")
        assert number == str(n), line                 # blocks numbered from 0, one by one
        assert _HEI.match(block), line
    assert lines[-2].endswith(" M30") and lines[-1].split(" ", 1)[1].startswith("END PGM")


# -- numeric formats ---------------------------------------------------------------------------
def test_inch_programs_follow_each_controllers_unit_words():
    """Inch: G20 (Fanuc, LinuxCNC), G70 (SINUMERIK), INCH and F in 0.1 inch/min (HEIDENHAIN);
    four decimals (a tenth of a thou); 25.4 mm is 1.0000 inch; no "-0"."""
    p = plan_linear(25.4, n_targets=5, irregularity=0, runs=1, dwell=1.0, overrun=2.54)
    o = MachineOptions(feed=254.0, units="inch")
    fanuc = write_program(p, "fanuc", o)
    assert "G20 G17" in fanuc and "G01 X1.0000 F10.0" in fanuc and "G00 X-0.1000" in fanuc
    assert "G70 G17" in write_program(p, "sinumerik", o)
    h = write_program(p, "heidenhain", o)
    assert "BEGIN PGM AXISCAL INCH" in h and "L X+1.0000 R0 F100" in h
    assert "-0.000" not in write_program(plan_linear(10, n_targets=5, runs=1, dwell=1,
                                                     overrun=1, start=-5), "fanuc")


def test_origin_and_sign_give_machine_coordinates():
    """Machine = origin + sign × plan: plan 0…100 with origin 500 and sign −1 is 500…400."""
    p = plan_linear(100, n_targets=5, irregularity=0, runs=1, dwell=1.0, overrun=5)
    text = write_program(p, "linuxcnc", MachineOptions(origin={"X": 500.0}, sign={"X": -1},
                                                       limits={"X": (390.0, 510.0)}))
    moves = re.findall(r"^G[01] X(-?\d+\.\d+)", text, re.M)
    assert moves[:3] == ["505.000", "500.000", "475.000"] and "395.000" in moves


def test_api_plan_program_is_the_writer():
    """``axiscal.plan(...).program("fanuc")`` is :func:`write_program` of the same plan."""
    p = axiscal.plan("linear", length=200.0, n_targets=5, runs=2, dwell=2.0, overrun=3.0)
    plan, options = cases()["linear"]
    assert p.program("fanuc", feed=2000.0, limits={"X": (-10.0, 210.0)}) == \
        write_program(plan, "fanuc", options)
    c = axiscal.plan("circular", radius=100.0, centre=(200.0, 150.0), feed=1000.0)
    assert c.program("linuxcnc", limits={"X": (0.0, 400.0), "Y": (0.0, 300.0)},
                     name="AXISCAL_CIRCULAR") == program("circular", "linuxcnc")
    with pytest.raises(ProgramError, match="controller 'okuma'"):
        p.program("okuma")
    t = axiscal.plan("thermal", test="linear", run_h=300 / 3600, duration_h=420 / 3600)
    assert t.program("linuxcnc", limits={"X": (0.0, 800.0)}, max_feed=30000.0,
                     name="AXISCAL_THERMAL_LINEAR") == program("thermal_linear", "linuxcnc")
    f = axiscal.plan("fiveaxis")
    _, options = cases()["fiveaxis"]
    assert f.program("heidenhain", feed=1000.0, safe=options.safe, limits=options.limits,
                     name="AXISCAL_FIVEAXIS") == program("fiveaxis", "heidenhain")


# -- refusals ----------------------------------------------------------------------------------
REFUSALS = [
    (["linear", "--length", "100", "--feed", "0"], "--feed", "feed 0"),
    (["linear", "--length", "100", "--feed", "20000", "--max-feed", "10000"], "--feed",
     "beyond the machine's max-feed 10000"),
    (["linear", "--length", "100", "--dwell", "0.3", "--trigger", "0.5"], "--dwell",
     "dwell 0.3 s is shorter"),
    (["linear", "--length", "100", "--overrun", "5", "--limits", "-2:102"], "--overrun",
     "takes X to -5 mm, beyond the limits -2:102"),
    (["linear", "--length", "100", "--limits", "-10:90"], "--limits", "target 100 mm"),
    (["rotary", "--overrun", "5", "--limits", "0:365"], "--overrun", "takes C to -5 deg"),
    (["circular", "--radius", "100", "--limits", "X=-90:200", "--limits", "Y=-200:200"],
     "--radius", "X to -100"),
    (["linear", "--length", "100", "--controller", "okuma"], "--controller", "'okuma'"),
    (["linear", "--length", "100", "--limits", "0-100"], "--limits", "give LO:HI"),
    # the thermal and five-axis cycles
    (["thermal", "--test", "etve"], "--test", "no program running"),
    (["thermal", "--test", "spindle"], "--spindle-max", "highest speed"),
    (["thermal", "--test", "linear", "--max-feed", "1000"], "--duty",
     "beyond the machine's max-feed 1000"),
    (["thermal", "--test", "linear", "--limits", "X=100:800"], "--limits", "P1 40 mm"),
    (["thermal", "--test", "linear", "--interval-s", "10", "--duty", "0.95"], "--dwell",
     "dwell 0.25 s is shorter"),
    (["fiveaxis", "--machine", "ac"], "--safe", "safe Z"),
    (["fiveaxis", "--machine", "ac", "--safe", "Z=250", "--limits", "A=-60:30"], "--limits",
     "takes A to -90 deg"),
    (["fiveaxis", "--machine", "head", "--safe", "Z=250"], "--machine", "spindle head"),
]


@pytest.mark.parametrize("args, option, words", REFUSALS)
def test_bad_input_is_one_line_naming_the_option_and_nothing_written(args, option, words,
                                                                     tmp_path):
    prog, csv = tmp_path / "p.nc", tmp_path / "plan.csv"
    extra = ["--program", str(prog)] + (["--controller", "fanuc"] if "--controller" not in args
                                        else [])
    if args[0] == "linear":
        extra += ["--csv", str(csv)]
    r = runner.invoke(app, ["plan", *args, *extra])
    assert r.exit_code == 2, r.output
    err = r.stderr.strip()
    assert len(err.splitlines()) == 1 and option in err and words in err, err
    assert "Traceback" not in r.output
    assert not prog.exists() and not csv.exists()


def test_program_written_with_the_csv(tmp_path):
    """A plan that fits: the CSV and the program both written; the program is the library's."""
    prog, csv = tmp_path / "x.ngc", tmp_path / "x.csv"
    r = runner.invoke(app, ["plan", "linear", "--length", "200", "--targets", "5", "--runs", "2",
                            "--dwell", "2", "--overrun", "3", "--csv", str(csv), "--program",
                            str(prog), "--controller", "linuxcnc", "--feed", "2000",
                            "--limits=-10:210", "--name", "AXISCAL_LINEAR"])
    assert r.exit_code == 0, r.output
    assert prog.read_text() == program("linear", "linuxcnc") and csv.exists()


# -- the thermal and five-axis cycles ----------------------------------------------------------
def test_thermal_linear_cycle_keeps_the_plans_duty(tmp_path, rs274):
    """ISO 230-3 linear-axis test, as LinuxCNC reads the program: one cycle P1-P2-P1 per sampling
    interval, moving ``duty`` of it (2 |P2 - P1| / F = 0.8 x 60 s = 48 s), a dwell of
    (1 - duty) x interval / 2 = 6 s at each end, then at P1 for the stop: the program lasts the
    plan's duration (7 min) within the rapid's time."""
    plan, _ = cases()["thermal_linear"]
    calls = _canonical(rs274, program("thermal_linear", "linuxcnc"), tmp_path, "t.ngc")
    feed = {n[0] for call, n in calls if call == "SET_FEED_RATE" and n[0] > 0}
    ends = [n[0] for call, n in calls if call == "STRAIGHT_FEED"]
    p1, p2 = (t * 1e3 for t in plan.targets)
    assert ends == pytest.approx([p2, p1] * 5, abs=1e-9)
    (f,) = feed
    moving = 2 * (p2 - p1) / (f / 60.0)
    assert moving == pytest.approx(plan.duty * plan.interval, rel=1e-9)
    dwells = [n[0] for call, n in calls if call == "DWELL"]
    assert dwells[:-1] == [pytest.approx(6.0)] * 10
    total = sum(dwells) + 5 * moving
    assert total == pytest.approx(plan.duration, rel=1e-9)


def test_spindle_program_follows_the_speed_programme():
    """ISO 230-3 spindle test: the programme's steps (25 % for 10 min, 100 % for 5 min of
    12 000 rpm) repeated through the 30 min run, then M5 and 15 min stopped (the dwells, in ms
    for Fanuc, add up to the plan's duration)."""
    text = program("thermal_spindle", "fanuc")
    assert re.findall(r"^S(\d+) M03$", text, re.M) == ["3000", "12000", "3000", "12000"]
    dwell_ms = [int(v) for v in re.findall(r"^G04 P(\d+)$", text, re.M)]
    assert dwell_ms == [600000, 300000, 600000, 300000, 900000]
    assert text.index("M05") < text.rindex("G04 P900000")


def test_five_axis_program_visits_every_r_test_pose():
    """The shipped A/C example's R-test set-up: one dwell per pose (18), the probing set-ups
    named as not programmed; at A = 0 the nest is its table place turned by C about the C axis
    (the nominal kinematics, ISO 230-1 Annex A's table rotation written out), and every approach
    point is the clearance (10 mm) from the nest, straight up (+Z) at A = 0."""
    job, _ = cases()["fiveaxis"]
    (setup,) = [s for s in job.plan.setups if s.kind == "r-test"]
    text = program("fiveaxis", "linuxcnc")
    assert text.count("G4 P1.000") == setup.poses == 18
    assert text.count("IS NOT PROGRAMMED") == 2
    nests = [tuple(map(float, m)) for m in re.findall(
        r"^G1 X(-?[\d.]+) Y(-?[\d.]+) Z(-?[\d.]+) F1000.0\nG4", text, re.M)]
    outs = [tuple(map(float, m)) for m in re.findall(
        r"^G4 P1.000\nG1 X(-?[\d.]+) Y(-?[\d.]+) Z(-?[\d.]+)", text, re.M)]
    cx, cy = (v * 1e3 for v in job.machine.geometry.c_position)
    x0, y0, z0 = (v * 1e3 for v in setup.place)
    for k, (a, c) in enumerate(np.degrees(np.column_stack([setup.tilt_angle, setup.c_angle]))):
        assert math.dist(nests[k], outs[k]) == pytest.approx(10.0, abs=2e-3)
        if a == 0:
            t = math.radians(c)
            want = (cx + (x0 - cx) * math.cos(t) - (y0 - cy) * math.sin(t),
                    cy + (x0 - cx) * math.sin(t) + (y0 - cy) * math.cos(t), z0)
            assert nests[k] == pytest.approx(want, abs=1e-3)
            assert outs[k][2] - nests[k][2] == pytest.approx(10.0, abs=1e-3)


def test_five_axis_plan_without_an_r_test_is_refused():
    """Probing set-ups alone: nothing to program (the touches are the controller's cycle)."""
    from axiscal.procedures.five_axis import FiveAxisPlan
    from axiscal.programs import FiveAxisProgram

    job, options = cases()["fiveaxis"]
    probing = FiveAxisPlan(tuple(s for s in job.plan.setups if s.kind != "r-test"))
    with pytest.raises(ProgramError, match="no R-test set-up") as e:
        write_program(FiveAxisProgram(probing, job.machine), "fanuc", options)
    assert e.value.option == "setup"
