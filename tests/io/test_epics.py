"""EPICS camonitor logs (issue 29): the line layout of EPICS Base's camonitor
(``modules/ca/src/tools/tool_lib.c``, ``print_time_val_sts``), the stops of a setpoint, and a
log made from the steps of a real ecmc ISO 230-2 test giving that test's numbers."""

from __future__ import annotations

from datetime import datetime, timedelta
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError, DataFormatError
from axiscal.io import parse_positioning
from axiscal.io.ecmc import read_ecmc
from axiscal.io.epics import find_dwells, looks_like_camonitor, parse_camonitor, parse_epics
from axiscal.io.measured import parse_plan_csv
from axiscal.standards.iso230_2 import evaluate

DATA = Path(__file__).parents[1] / "data" / "ecmc"
T0 = datetime(2023, 12, 8, 12, 0, 0)
SP, REF = "IOC_TEST:Axis1-PosSet", "IOC_TEST:m0s012-Enc01-PosAct"


def _stamp(t: float) -> str:
    return (T0 + timedelta(seconds=t)).strftime("%Y-%m-%d %H:%M:%S.%f")


def _line(name: str, t: float, value, alarm: str = "") -> str:
    """One update as camonitor prints a scalar: the name padded to 30, the server stamp, the
    value, then status and severity or two separators (tool_lib.c)."""
    return f"{name:<30} {_stamp(t)} {float(value)!r}" + (f" {alarm}" if alarm else "  ")


def _ecmc_sequence(targets, up, down, overrun=0.5):
    """(setpoint, actual position at rest) in the order ecmc's ISO 230-2 script runs a cycle
    (the public log b02/x/rawdata/x_230_2.log: over-travel below the first target, the targets
    upwards, over-travel above the last, the targets downwards)."""
    seq = []
    for j in range(up.shape[1]):
        seq.append((targets[0] - overrun, targets[0] - overrun))
        seq += [(t, a) for t, a in zip(targets, up[:, j])]
        seq.append((targets[-1] + overrun, targets[-1] + overrun))
        seq += [(t, a) for t, a in reversed(list(zip(targets, down[:, j])))]
    return seq


def _log(seq, start, *, dwell=8.0, travel=3.0, rate=10.0, extras=True, sp=SP, ref=REF):
    """A camonitor log of a setpoint stepping through ``seq`` and a reference travelling to each
    rest position at ``rate`` Hz, then holding it (no update while it rests: the deadband)."""
    timed = [(-100.0, _line(sp, -100.0, start))]            # first line: the value as last set
    timed.append((-50.0, _line(ref, -50.0, start)))
    if extras:
        timed.append((-300.0, f"{'IOC_TEST:TestNumber':<30} <undefined> 0  "))
        timed.append((-20.0, _line("IOC_TEST:Axis1-PosAct", -20.0, start, "LOLO MAJOR")))
    t, pos = 0.0, start
    for k, (s, actual) in enumerate(seq):
        timed.append((t, _line(sp, t, s)))
        n = int(travel * rate)
        for i in range(1, n):
            timed.append((t + i / rate, _line(ref, t + i / rate, pos + (actual - pos) * i / n)))
        timed.append((t + travel, _line(ref, t + travel, actual)))
        if extras:
            timed.append((t + dwell - 0.1, _line("IOC_TEST:TestNumber", t + dwell - 0.1,
                                                  1000 + k)))
            timed.append((t + 1.0, _line("IOC_TEST:Axis1-PosAct", t + 1.0, s, "HIHI MAJOR")))
        pos, t = actual, t + dwell
    timed.append((t, _line(ref, t, pos)))
    head = [ln for tt, ln in timed if tt < 0]                # the initial values come first
    body = sorted(((tt, ln) for tt, ln in timed if tt >= 0), key=lambda x: x[0])
    return "\n".join(head + [ln for _, ln in body]) + "\n"


def _ecmc_log(path, **kw):
    ds = read_ecmc(path)
    tg = ds.targets
    up, down = tg[:, None] + ds.up * 1e-3, tg[:, None] + ds.down * 1e-3   # µm -> mm
    return ds, _log(_ecmc_sequence(tg, up, down), tg[0], **kw)


def _numbers(result):
    return np.array([result.A, result.E, result.M, result.R, result.B])


@pytest.mark.parametrize("name", ["mcu1025_fat_sat_ISO230.dat", "sls_fat_sat_ISO230.dat"])
def test_log_of_a_real_ecmc_test_gives_its_iso230_2_numbers(name):
    """tests/data/ecmc (paulscherrerinstitute/ecmccfg, GPL-3.0): the setpoint stepping through
    the test's targets with over-travel and the reference resting at the file's REF_DATA give
    the A, E, M, R, B of the ecmc file, and every deviation, within rounding."""
    ref_ds, text = _ecmc_log(DATA / name)
    ds = parse_epics(text, SP, REF)
    np.testing.assert_allclose(ds.targets, ref_ds.targets, atol=1e-12)
    np.testing.assert_allclose(ds.up, ref_ds.up, atol=1e-6)
    np.testing.assert_allclose(ds.down, ref_ds.down, atol=1e-6)
    np.testing.assert_allclose(_numbers(evaluate(ds)), _numbers(evaluate(ref_ds)), atol=1e-6)
    assert ds.metadata.axis == SP and ds.metadata.instrument == REF
    assert "over-travel" in ds.metadata.notes and "unit mm (assumed" in ds.metadata.notes


def test_the_mcu1025_numbers_themselves():
    """ecmccfg examples/ESS/mcu1025_fat_sat: the values axiscal's ISO 230-2:2014 gives for the
    file (µm), so that the log's numbers are pinned, not only equal to another reading."""
    ref_ds, text = _ecmc_log(DATA / "mcu1025_fat_sat_ISO230.dat")
    r = evaluate(parse_epics(text, SP, REF))
    expected = evaluate(ref_ds)
    assert r.n_runs == 5 and ref_ds.targets.tolist() == [15, 25.2, 35.4, 45.6, 55.8]
    for p in ("A", "E", "M", "R", "B"):
        assert getattr(r, p) == pytest.approx(getattr(expected, p), abs=1e-6)
    assert 0 < r.R <= r.A


def test_targets_given_and_plan_give_the_same():
    ref_ds, text = _ecmc_log(DATA / "sls_fat_sat_ISO230.dat")
    by_targets = parse_epics(text, SP, REF, targets=ref_ds.targets.tolist())
    np.testing.assert_allclose(by_targets.up, ref_ds.up, atol=1e-6)
    plan = parse_plan_csv(_plan_csv(ref_ds.targets, ref_ds.n_runs))
    by_plan = parse_epics(text, SP, REF, plan=plan)
    np.testing.assert_allclose(by_plan.down, ref_ds.down, atol=1e-6)
    assert "matched to the plan" in by_plan.metadata.notes


def _plan_csv(targets, runs, overrun=0.5):
    rows, seq = [], 0
    for r in range(1, runs + 1):
        steps = [("overrun", targets[0] - overrun, "-", "")]
        steps += [("measure", t, "+", i) for i, t in enumerate(targets)]
        steps += [("overrun", targets[-1] + overrun, "+", "")]
        steps += [("measure", t, "-", i) for i, t in reversed(list(enumerate(targets)))]
        for kind, pos, d, i in steps:
            seq += 1
            rows.append(f"{seq},{kind},{float(pos)!r},{d},{r},{i},{4 if kind == 'measure' else 0}")
    return ("# axis=X axis_kind=linear target_unit=mm\n"
            "seq,kind,position,direction,run,target_index,dwell_s\n" + "\n".join(rows) + "\n")


def test_plan_direction_disagreeing_with_the_step_is_refused():
    ref_ds, text = _ecmc_log(DATA / "sls_fat_sat_ISO230.dat")
    csv = _plan_csv(ref_ds.targets, ref_ds.n_runs).replace(",measure,-10.0,+,1,",
                                                           ",measure,-10.0,-,1,")
    with pytest.raises(DataFormatError, match="the setpoint came from below"):
        parse_epics(text, SP, REF, plan=parse_plan_csv(csv))


def test_two_pvs_are_found_and_the_one_updating_less_is_the_setpoint():
    tg = np.array([0.0, 10.0, 20.0])
    up = tg[:, None] + np.array([[0.001, 0.002], [0.001, 0.001], [0.002, 0.0]])
    down = tg[:, None] - np.full((3, 2), 0.001)
    ds = parse_epics(_log(_ecmc_sequence(tg, up, down), 0.0, extras=False))
    assert ds.metadata.axis == SP and ds.targets.tolist() == [0.0, 10.0, 20.0]
    np.testing.assert_allclose(ds.up, [[1.0, 2.0], [1.0, 1.0], [2.0, 0.0]], atol=1e-6)
    np.testing.assert_allclose(ds.down, np.full((3, 2), -1.0), atol=1e-6)


def test_an_axis_arriving_late_and_resting_briefly_is_read_at_its_rest():
    """The real log: a 5 mm step at 0.2 mm/s reaches the target 1.3 s before the next step;
    the reference rests at the previous target at the dwell's start (the axis starts late)."""
    lines = [_line(SP, 0.0, 0.0), _line(REF, 0.0, 0.0), _line(SP, 5.0, 5.0)]
    lines += [_line(REF, 5.0 + 0.1 * i, 0.0) for i in range(1, 20)]          # still at 0
    lines += [_line(REF, 7.0 + 0.1 * i, 0.02 * i) for i in range(1, 251)]     # travels 5 mm
    lines += [_line(REF, 32.1 + 0.1 * i, 5.0003 + (0.0002 if i % 2 else -0.0002))
              for i in range(13)]                                              # 1.3 s of rest
    lines += [_line(SP, 33.4, 10.0), _line(REF, 40.0, 10.0), _line(SP, 50.0, 15.0)]
    ds = parse_epics("\n".join(lines), SP, REF, targets=[5.0, 10.0])
    assert ds.up[0, 0] == pytest.approx(0.3, abs=0.05)      # µm: the rest, not the start


def test_an_axis_that_never_rests_is_refused():
    lines = [_line(SP, 0.0, 0.0), _line(REF, 0.0, 0.0), _line(SP, 5.0, 5.0)]
    lines += [_line(REF, 5.0 + 0.1 * i, 0.01 * i) for i in range(1, 100)]
    lines += [_line(SP, 15.0, 10.0)]
    with pytest.raises(DataFormatError, match="never stays within the window"):
        parse_epics("\n".join(lines), SP, REF, targets=[5.0])


@pytest.mark.parametrize("mode", ["relative", "incremental", "by-channel"])
def test_offset_time_stamps(mode):
    """camonitor -tsr/-tsi/-tsI: a PV's first line absolute, then '%+12.6f' offsets from the
    first stamp, the previous update, or the channel's previous update."""
    ref_ds, text = _ecmc_log(DATA / "sls_fat_sat_ISO230.dat", extras=False)
    out, first, last, seen = [], None, None, {}
    for ln in text.splitlines():
        name = ln[:30].strip()
        t = (datetime.strptime(ln[31:57], "%Y-%m-%d %H:%M:%S.%f") - T0).total_seconds()
        first = t if first is None else first
        if name in seen:
            base = {"relative": first, "incremental": last, "by-channel": seen[name]}[mode]
            ln = f"{ln[:31]}{' ' * 14}{t - base:+12.6f}{ln[57:]}"
        seen[name], last = t, t
        out.append(ln)
    ds = parse_epics("\n".join(out), SP, REF, offsets=mode)
    np.testing.assert_allclose(ds.up, ref_ds.up, atol=2e-3)


def test_client_stamps_and_clock_only_stamps_across_midnight():
    seq = [(-1.0, -1.0), (0.0, 0.001), (1.0, 1.002), (2.0, 2.0), (1.0, 0.999), (0.0, 0.0)]
    text = _log(seq, -1.0, extras=False)
    both = "\n".join(f"{ln[:57]}({ln[31:57]}){ln[57:]}" for ln in text.splitlines())
    client = "\n".join(f"{ln[:31]}({ln[31:57]}){ln[57:]}" for ln in text.splitlines())
    base = parse_epics(text, SP, REF)
    for variant in (both, client):
        np.testing.assert_allclose(parse_epics(variant, SP, REF).up, base.up, atol=1e-9)
    night = []                                    # 23:59:00 onwards, the date dropped
    for ln in text.splitlines():
        t = (datetime.strptime(ln[31:57], "%Y-%m-%d %H:%M:%S.%f") - T0).total_seconds()
        clock = (datetime(2023, 12, 8, 23, 59, 0) + timedelta(seconds=t)).strftime("%H:%M:%S.%f")
        night.append(f"{ln[:31]}{clock}{ln[57:]}")
    np.testing.assert_allclose(parse_epics("\n".join(night), SP, REF).up, base.up, atol=1e-9)


def test_the_layout_of_camonitor_lines():
    log = parse_camonitor("\n".join([
        _line("IOC:a", 0.0, 1.5, "HIHI MAJOR"),
        f"IOC:wave {_stamp(0.1)} 3 1 2 3  ",
        f"{'IOC:bits':<30} {_stamp(0.2)} 0x1F  ",
        f"{'IOC:state':<30} {_stamp(0.3)} Moving Up  ",
        f"{'IOC:a':<30} {_stamp(0.4)} 2.5 READ INVALID",
        f"{'IOC:a':<30} {_stamp(0.5)} *** disconnected",
        f"{'IOC:gone':<30} *** Not connected (PV not found)",
        f"{'IOC:new':<30} <undefined> 0  ",
    ]))
    a = log.series("IOC:a")
    assert a.values[0] == 1.5 and np.isnan(a.values[1:]).all() and a.alarms == 1
    assert a.invalid == 2
    assert log.series("IOC:wave").elements == 3 and log.series("IOC:wave").values[0] == 1.0
    assert log.series("IOC:bits").values[0] == 31.0
    assert log.series("IOC:state").text and log.series("IOC:gone").times.size == 0
    assert log.series("IOC:new").undefined == 1 and log.start.startswith("2023-12-08 12:00:00")


def test_dwells_of_a_ramping_trajectory_setpoint():
    """ecmc's PosSet ramps every cycle while the axis moves: the ramp is not a stop."""
    lines = [_line(SP, 0.0, 0.0)]
    lines += [_line(SP, 2.0 + 0.01 * i, 0.1 * i) for i in range(1, 101)]     # 0 -> 10 in 1 s
    lines += [_line(SP, 10.0, 9.0), _line(REF, 0.0, 0.0)]
    log = parse_camonitor("\n".join(lines))
    d = find_dwells(log.series(SP), 20.0, dwell=1.0)
    assert [(x.value, x.arrival, x.departure) for x in d] == [(0.0, 0, 1), (10.0, 1, -1),
                                                              (9.0, -1, 0)]


@pytest.mark.parametrize("text, kw, words", [
    (_line(SP, 0, 1.0) + "\n" + _line(REF, 0, 1.0) + "\n" + _line("X", 0, 1.0), {},
     "holds 3 PVs .*--setpoint-pv and --reference-pv"),
    (_line(SP, 0, 1.0) + "\n" + _line(REF, 0, 1.0), {"setpoint_pv": "NOPE", "reference_pv": REF},
     "PV 'NOPE' is not in the log"),
    (_line(SP, 0, 1.0) + "\n" + _line(REF, 0, 1.0) + "\n" + _line(REF, 9, 1.0), {},
     "no approach to measure"),
    (_line(SP, 0, 1.0) + "\n" + _line(SP, 0.5, 2.0) + "\n" + _line(REF, 0.6, 1.0), {},
     "never holds a value for 1 s"),
    (_line(SP, 5, 1.0) + "\n" + _line(SP, 4, 2.0) + "\n" + _line(REF, 0, 1.0), {},
     "time of PV .* goes back"),
    (f"{SP} 1.0\n{REF} 2.0", {}, "without a time stamp"),
    (f"{SP} 2023-13-40 12:00:00.0 1\n{REF} 2023-01-01 12:00:00.0 1", {}, "not a date"),
    (f"IOC:w {_stamp(0)} 2 1 2\n" + _line(REF, 0, 1.0), {}, "arrays of 2 elements"),
    (_line(SP, 0, 1.0) + "\n" + _line(REF, 0, 1.0), {"dwell": float("nan")}, "dwell nan"),
    (_line(SP, 0, 1.0) + "\n" + _line(REF, 0, 1.0), {"window": -1.0}, "rest window -1: give a band wider than 0"),
    (_line(SP, 0, 1.0) + "\n" + _line(REF, 0, 1.0), {"reference_scale": 0.0}, "non-zero"),
    (_line(SP, 0, 1.0) + "\n" + _line(REF, 0, 1.0), {"offsets": "sideways"}, "offsets"),
])
def test_refusals_name_the_problem(text, kw, words):
    with pytest.raises(DataFormatError, match=words):
        parse_epics(text, **kw)


def test_a_target_never_reached_is_refused():
    seq = [(-1.0, -1.0), (0.0, 0.0), (1.0, 1.0), (2.0, 2.0), (1.0, 1.0), (0.0, 0.0)]
    text = _log(seq, -1.0, extras=False)
    with pytest.raises(DataFormatError, match="target 1.5 mm is never reached"):
        parse_epics(text, SP, REF, targets=[0, 1, 1.5, 2])


def test_reference_lost_during_the_rest_is_refused():
    text = _log([(0.0, 0.0), (1.0, 1.0), (2.0, 2.0)], 0.0, extras=False)
    lost = text.replace(_line(REF, 11.0, 1.0), f"{REF:<30} {_stamp(11.0)} *** disconnected")
    with pytest.raises(DataFormatError, match="stop at 1 .*unknown for 5 s of it"):
        parse_epics(lost, SP, REF, targets=[1.0])


def test_told_by_content_and_options_refused_for_other_files():
    text = _log([(0.0, 0.0), (1.0, 1.0), (2.0, 2.0), (1.0, 1.0)], 0.0, extras=False)
    assert looks_like_camonitor(text) and not looks_like_camonitor("time_s,target\n0,1\n")
    assert looks_like_camonitor(f"{'IOC:gone':<30} *** Not connected (PV not found)\n" + text)
    assert not looks_like_camonitor("UNIT=mm\nTGT_DATA[1]=15\n")
    ds = parse_positioning(text, "x.log", epics={"setpoint_pv": SP, "reference_pv": REF,
                                                  "targets": [1.0, 2.0]})
    assert ds.targets.tolist() == [1.0, 2.0]
    with pytest.raises(DataFormatError, match="--setpoint-pv applies to an EPICS camonitor"):
        parse_positioning("target,direction,run,deviation\n0,+,1,0\n", "x.csv",
                          epics={"setpoint_pv": SP})


def test_reference_scale_and_offset_as_ecmc_applies_them():
    """ecmcGetISO230DataFromCAFile.bash: REF_DATA = raw × REF_GR + REF_OFF."""
    seq = [(-1.0, -1.0), (0.0, 0.002), (1.0, 1.001), (2.0, 2.0), (1.0, 0.999), (0.0, 0.0)]
    raw = [(s, (a - 50.0) / -2.0) for s, a in seq]
    text = _log(raw, raw[0][1], extras=False)
    ds = parse_epics(text, SP, REF, reference_scale=-2.0, reference_offset=50.0)
    assert ds.up[:2, 0].tolist() == pytest.approx([2.0, 1.0], abs=1e-6)
    assert "position = -2 × reference + 50" in ds.metadata.notes


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet=st.sampled_from(list("IOC:ab -+.0123456789e\n()<>*#xINVALIDMAJOR")),
               max_size=300))
def test_only_axiscal_errors_on_arbitrary_text(text):
    try:
        parse_epics(text)
    except AxiscalError:
        pass


@settings(max_examples=25, deadline=None)
@given(st.integers(2, 6), st.integers(2, 5), st.integers(0, 2**32 - 1),
       st.sampled_from([2.0, 10.0, 50.0]))
def test_truth_any_test_through_its_log(n_targets, runs, seed, rate):
    """Truth test (habit 8): known deviations written as a log of setpoint steps and a
    reference that travels and rests are read back exactly, whatever the targets, the runs and
    the reference's update rate; the lines of the other PVs interleave anywhere."""
    rng = np.random.default_rng(seed)
    tg = np.cumsum(rng.uniform(1.0, 50.0, n_targets)) - 10.0
    up = rng.normal(0.0, 5.0, (n_targets, runs))            # µm
    down = rng.normal(0.0, 5.0, (n_targets, runs))
    seq = _ecmc_sequence(tg, tg[:, None] + up * 1e-3, tg[:, None] + down * 1e-3)
    ds = parse_epics(_log(seq, tg[0], rate=rate), SP, REF)
    np.testing.assert_allclose(ds.targets, tg, atol=1e-12)
    np.testing.assert_allclose(ds.up, up, atol=1e-6)
    np.testing.assert_allclose(ds.down, down, atol=1e-6)


def test_a_setpoint_rounded_by_camonitors_default_format_meets_the_target_given():
    """camonitor's default %g (tool_lib.c, dblFormatStr) prints six significant digits: a
    target of 123.4567 mm is logged 123.457; the deviation is taken from the target given."""
    lines = [_line(SP, 0.0, 100.0), _line(REF, 0.0, 100.0), _line(SP, 5.0, 123.457),
             _line(REF, 6.0, 123.4572), _line(SP, 15.0, 150.0), _line(REF, 16.0, 150.0),
             _line(SP, 25.0, 160.0)]
    ds = parse_epics("\n".join(lines), SP, REF, targets=[123.4567, 150.0])
    assert ds.up[0, 0] == pytest.approx(0.5, abs=1e-6)        # µm: 123.4572 − 123.4567


def _ramping_log(seq, start, *, dwell=8.0, travel=3.0, sp_rate=100.0, rate=10.0):
    """As :func:`_log`, but the setpoint ramps to each stop as a motion controller's trajectory
    setpoint does (``sp_rate`` samples a second over ``travel`` s), the reference following."""
    lines = [(-100.0, _line(SP, -100.0, start)), (-50.0, _line(REF, -50.0, start))]
    t, s0, pos = 0.0, start, start
    for s, actual in seq:
        n = int(travel * sp_rate)
        lines += [(t + i / sp_rate, _line(SP, t + i / sp_rate, s0 + (s - s0) * i / n))
                  for i in range(1, n + 1)]
        m = int(travel * rate)
        lines += [(t + i / rate, _line(REF, t + i / rate, pos + (actual - pos) * i / m))
                  for i in range(1, m + 1)]
        s0, pos, t = s, actual, t + travel + dwell
    lines.append((t, _line(REF, t, pos)))
    head = [ln for tt, ln in lines if tt < 0]
    return "\n".join(head + [ln for _, ln in sorted((x for x in lines if x[0] >= 0),
                                                     key=lambda x: x[0])]) + "\n"


def test_ramping_setpoint_reads_as_a_jumping_one():
    """Issue 42: the MCU1025 readings (tests/data/ecmc, errors up to 93 µm) with a setpoint that
    ramps at 100 Hz (34 µm a sample between targets 10.2 mm apart) were refused ("rests only
    nearer the setpoint before"): the setpoint "before" was the last ramp sample. Compared with
    the previous stop, the log gives the test's numbers exactly, with the targets found or
    given."""
    ref_ds = read_ecmc(DATA / "mcu1025_fat_sat_ISO230.dat")
    tg = ref_ds.targets
    up, down = tg[:, None] + ref_ds.up * 1e-3, tg[:, None] + ref_ds.down * 1e-3
    text = _ramping_log(_ecmc_sequence(tg, up, down), tg[0])
    for kw in ({}, {"targets": tg.tolist()}):
        ds = parse_epics(text, SP, REF, **kw)
        np.testing.assert_allclose(ds.up, ref_ds.up, atol=1e-6)
        np.testing.assert_allclose(ds.down, ref_ds.down, atol=1e-6)
        np.testing.assert_allclose(_numbers(evaluate(ds)), _numbers(evaluate(ref_ds)), atol=1e-6)
    d = find_dwells(parse_camonitor(text).series(SP), 1e9)
    assert (d[3].value, d[3].came_from) == (tg[1], tg[0])    # the stop before, not 25.166
