"""Renishaw .rtx dynamic captures (issue 12), built to the layout a public converter reads
(T. Pani, rtx2csv, github.com/TanmayPani/rtx2csv, rtx_to_csv.py)."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import AxiscalError
from axiscal.io.rtx import format_rtx, read_rtx


def _file(tmp_path, values=None, rate=50000.0, **fields):
    v = np.linspace(0, 1000, 2001) if values is None else values
    p = tmp_path / "cap.rtx"
    p.write_bytes(format_rtx(v, rate, **fields))
    return p, v


def test_read_to_si_with_the_header(tmp_path):
    p, v = _file(tmp_path, Machine="VMC-800", Axis="X", Date="10/02/2025 12:58:22")
    r = read_rtx(p)
    np.testing.assert_array_equal(r.readings, v * 1e-6)          # µm by default
    assert r.sample_rate == 50000.0 and r.times[1] == pytest.approx(2e-5)
    assert r.header["Owner"] == "CARTO-Dynamic" and r.header["Axis"] == "X"
    assert r.header["Date"] == "10/02/2025 12:58:22"
    assert read_rtx(p, unit="mm").readings[-1] == pytest.approx(1.0)
    assert read_rtx(p, unit="arcsec").kind == "rotary"


def test_header_starting_the_first_line_with_a_key(tmp_path):
    """The converter also accepts 'HEADER::' followed directly by the keys."""
    p, _ = _file(tmp_path)
    data = p.read_bytes().replace(b"HEADER::\r\nOwner", b"HEADER::\r\nFile:: x\r\nOwner", 1)
    p.write_bytes(data)
    assert read_rtx(p).readings.size == 2001


@pytest.mark.parametrize("damage, words", [
    (lambda b: b[:-7], "truncated"),
    (lambda b: b[:-12] + b"EOF::\r\n", "whole number"),
    (lambda b: b"HEADR::" + b[8:], "does not start with 'HEADER::'"),
    (lambda b: b.replace(b"Data:\r\n", b"Dat:\r\n"), "no 'Data:' line"),
    (lambda b: b.replace(b"Actual sample rate: 50000", b"Actual sample rate: fast"),
     "not a number"),
])
def test_damaged_files_are_refused_by_name(tmp_path, damage, words):
    p, _ = _file(tmp_path)
    p.write_bytes(damage(p.read_bytes()))
    with pytest.raises(AxiscalError, match=words):
        read_rtx(p)


def test_nan_readings_refused(tmp_path):
    p, _ = _file(tmp_path, values=np.array([0.0, np.nan, 1.0]))
    with pytest.raises(AxiscalError, match="NaN"):
        read_rtx(p)


# -- a reading count unlike the header's Sample no (issue 29) ----------------------------------
def test_fewer_readings_than_sample_no_are_read_and_the_shortfall_stated(tmp_path):
    """rtx2csv reads every reading between 'Data:' and 'EOF::' at the header's Actual sample
    rate, whatever Sample no says (rtx_to_csv.py, read_rtx_file): so does axiscal, and it says
    that the capture stopped early."""
    v = np.linspace(0, 1000, 2001)
    p, _ = _file(tmp_path, values=v, Sample_no="2500")
    r = read_rtx(p)
    np.testing.assert_array_equal(r.readings, v * 1e-6)
    assert r.times[-1] == pytest.approx(2000 / 50000.0)
    assert r.notes == ("the file holds 2001 readings, its header's Sample no 2500: the capture "
                       "stopped early (499 readings short); the readings present are read at "
                       "the header's rate",)


@pytest.mark.parametrize("filler", [0.0, np.nan, 1e308])
def test_a_constant_tail_beyond_sample_no_is_padding_dropped_and_stated(tmp_path, filler):
    v = np.linspace(0, 1000, 2001)
    p, _ = _file(tmp_path, values=np.concatenate([v, np.full(47, filler)]), Sample_no="2001")
    r = read_rtx(p)
    np.testing.assert_array_equal(r.readings, v * 1e-6)
    assert r.notes == (f"47 readings of {filler:g} after the header's Sample no 2001 dropped "
                       "as padding",)


def test_a_varying_tail_beyond_sample_no_is_ambiguous_and_refused(tmp_path):
    p, _ = _file(tmp_path, values=np.linspace(0, 1000, 2001), Sample_no="1990")
    with pytest.raises(AxiscalError, match="the 11 beyond it vary: which readings are the "
                                           "capture is ambiguous"):
        read_rtx(p)


@pytest.mark.parametrize("key, value, words", [
    ("Sample no", "nan", "Sample no: 'nan' is not a finite number"),
    ("Sample no", "1e308", "Sample no: '1e308' is not a whole number"),
    ("Sample no", "-5", "Sample no: '-5' is not a whole number"),
    ("Sample no", "20.5", "Sample no: '20.5' is not a whole number"),
    ("Actual sample rate", "nan", "Actual sample rate: 'nan' is not a finite number"),
    ("Actual sample rate", "-50000", "Actual sample rate: '-50000' is not a sample rate"),
    ("Actual sample rate", "0", "Actual sample rate: '0' is not a sample rate"),
    ("Actual sample rate", "1e308", "Actual sample rate: '1e308' is not a sample rate"),
    ("Actual sample rate", "inf", "not a finite number"),
])
def test_header_values_that_are_not_numbers_of_a_capture_are_refused(tmp_path, key, value,
                                                                     words):
    p, _ = _file(tmp_path, **{key: value})
    with pytest.raises(AxiscalError, match=words):
        read_rtx(p)


def test_the_shortfall_is_carried_into_the_capture(tmp_path):
    """A capture of an .rtx whose header promised more readings: the result and its dataset say
    so (capture_test's warnings)."""
    from axiscal.io.measured import parse_plan_csv
    from axiscal.procedures.capture import capture_test

    rate, dwell = 1000.0, 2.0
    targets = [0.0, 10.0, 20.0]
    steps = []
    for r in (1, 2):
        steps += [("overrun", -5.0, "-", r)] + [("measure", t, "+", r) for t in targets]
        steps += [("overrun", 25.0, "+", r)] + [("measure", t, "-", r) for t in targets[::-1]]
    rows = [f"{i + 1},{k},{t},{d},{r},{targets.index(t) if k == 'measure' else ''},"
            f"{dwell if k == 'measure' else 0}" for i, (k, t, d, r) in enumerate(steps)]
    plan = parse_plan_csv("# axis=X axis_kind=linear target_unit=mm\n"
                          "seq,kind,position,direction,run,target_index,dwell_s\n"
                          + "\n".join(rows) + "\n")
    reading, here = [], 0.0                   # µm from the datum at 0: a 0.2 s move, a rest
    for _, t, _, _ in steps:
        there = t * 1000.0 + 0.5
        reading += list(np.linspace(here, there, 200)) + [there] * int(dwell * rate)
        here = there
    p, _ = _file(tmp_path, values=np.array(reading), rate=rate, Sample_no=str(len(reading) + 10))
    rec = read_rtx(p)
    result = capture_test(rec, plan, window=1.0)
    assert result.warnings == rec.notes and "stopped early (10 readings short)" in rec.notes[0]
    assert "stopped early" in result.dataset.metadata.notes
    assert result.summary()["warnings"] == list(rec.notes)


def test_capture_refuses_a_damaged_header_in_one_line_and_writes_nothing(tmp_path):
    from typer.testing import CliRunner

    from axiscal.cli import app

    p, _ = _file(tmp_path, **{"Actual sample rate": "-50000"})
    plan = tmp_path / "plan.csv"
    plan.write_text("seq,kind,position,direction,run,target_index,dwell_s\n"
                    "1,measure,0,+,1,0,1\n2,measure,10,+,1,1,1\n")
    out = tmp_path / "data.csv"
    r = CliRunner().invoke(app, ["capture", str(p), "--plan", str(plan), "--out", str(out)])
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert r.output.strip().splitlines() == [
        f"axiscal: error: {p}: header Actual sample rate: '-50000' is not a sample rate "
        "(above 0, at most 1e+07 Hz)"]
    assert not out.exists()
