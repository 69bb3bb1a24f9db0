"""Drift-check files (io/drift.py): the readings of a still set-up, E_VE their range
(ISO 230-2:2014 Annex A.5)."""

import pytest

from axiscal.errors import DataFormatError
from axiscal.io.drift import parse_drift_check
from axiscal.standards.iso230_9 import environmental_variation


@pytest.mark.parametrize("text, readings", [
    ("# still, 30 min\ntime_s,reading\n0,0.00\n600,0.21\n1200,-0.09\n", [0.0, 0.21, -0.09]),
    ("deviation\n1e-3\n-2.5E-1\n", [0.001, -0.25]),
    ("0.3\n.5\n+1\n", [0.3, 0.5, 1.0]),
    ("time_s,air,reading\r\n0,20.1,0.4\r\n5,20.2,0.1\r\n", [0.4, 0.1]),
])
def test_readings_in_file_order(text, readings):
    assert parse_drift_check(text).tolist() == readings


def test_E_VE_is_the_range():
    r = parse_drift_check("reading\n0.00\n0.21\n-0.09\n0.15\n")
    assert environmental_variation(r) == pytest.approx(0.30, abs=1e-12)


@pytest.mark.parametrize("text, message", [
    ("", "no readings"),
    ("# only a comment\n", "no readings"),
    ("time_s,temperature\n0,20\n", "no 'reading' or 'deviation' column"),
    ("reading\n0.1\n", "1 reading: a drift check needs at least 2"),
    ("reading\n0.1\nnan\n", "not a finite number"),
    ("time_s,reading\n0,0.1\n5\n", "the reading is column 2"),
    ("reading\n0.1\nx\n", "is not a number"),
])
def test_damaged_files_refused_by_name(text, message):
    with pytest.raises(DataFormatError, match=message):
        parse_drift_check(text, "drift.csv")
