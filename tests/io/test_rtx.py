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
    (lambda b: b[:-15] + b"EOF::\r\n", "Sample no"),
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
