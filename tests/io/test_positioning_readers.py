"""Readers of positioning data: tidy CSV, axiscal JSON, EPICS ecmc ISO 230-2 files."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.datasets import Environment, Metadata, PositioningDataset
from axiscal.errors import AxiscalError, DataFormatError, MissingFileError, UnitError
from axiscal.io import read_positioning
from axiscal.io.csv import format_positioning_csv, parse_positioning_csv
from axiscal.io.ecmc import format_ecmc, parse_ecmc
from axiscal.io.json import format_positioning_json, parse_positioning_json

CSV = """# target_unit=mm deviation_unit=um machine="VMC 800" axis=X
target,direction,run,deviation
0,+,1,1.0
0,+,2,2.0
100,+,1,3.0
100,+,2,4.0
0,down,1,-1.0
0,down,2,-2.0
100,bwd,1,0.5
100,bwd,2,
"""


def test_csv_with_units_metadata_and_a_missing_reading():
    ds = parse_positioning_csv(CSV)
    assert ds.metadata.machine == "VMC 800" and ds.metadata.axis == "X"
    assert ds.up.tolist() == [[1, 2], [3, 4]]
    assert ds.down[0].tolist() == [-1, -2] and np.isnan(ds.down[1, 1])
    assert ds.missing_count == 1


def test_csv_actual_column_gives_actual_minus_target_in_the_deviation_unit():
    text = "target,direction,run,actual\n0,+,1,0.001\n0,+,2,0.002\n50,+,1,50.004\n50,+,2,49.999\n"
    ds = parse_positioning_csv(text, target_unit="mm", deviation_unit="um")
    np.testing.assert_allclose(ds.up, [[1, 2], [4, -1]], atol=1e-9)


def test_csv_round_trip():
    ds = parse_positioning_csv(CSV)
    again = parse_positioning_csv(format_positioning_csv(ds))
    assert again.equals(ds)


@pytest.mark.parametrize("text, message", [
    ("target,dir,run,deviation\n0,+,1,1\n", "must name the columns"),
    ("target,direction,run,deviation\n0,+,1,abc\n", r"<text>:2: deviation 'abc' is not a number"),
    ("target,direction,run,deviation\n0,+,1,1\n0,sideways,2,1\n", r"<text>:3: direction 'sideways'"),
    ("target,direction,run,deviation\n0,+,0,1\n", "run '0' is not a whole number"),
    ("target,direction,run,deviation\n0,+,1,1\n0,+,1,2\n", "two readings for target 0"),
    ("", "empty file"),
    ("target,direction,run,deviation\n", "no readings"),
])
def test_csv_errors_name_the_problem(text, message):
    with pytest.raises(DataFormatError, match=message):
        parse_positioning_csv(text, target_unit="mm", deviation_unit="um")


def test_csv_units_are_required_and_checked():
    body = "target,direction,run,deviation\n0,+,1,1\n"
    with pytest.raises(DataFormatError, match="no target unit"):
        parse_positioning_csv(body)
    with pytest.raises(UnitError, match="unknown unit 'furlong'"):
        parse_positioning_csv(body, target_unit="furlong", deviation_unit="um")
    with pytest.raises(AxiscalError, match="not a length unit"):
        parse_positioning_csv(body, target_unit="mm", deviation_unit="arcsec")


def test_json_round_trip_is_exact():
    ds = PositioningDataset.from_arrays(
        "rotary", [0, 45.5, 90], [[0.1, 1 / 3], [np.nan, 2.0], [1e-12, -7.25]], [[0, 1], [2, 3], [4, 5]],
        metadata=Metadata(machine="TT", operator="A. N. Other", date="2026-11-22",
                          environment=Environment(20.1, (19.8, 20.3), 101000.0, 45.0, 11.5e-6)))
    again = parse_positioning_json(format_positioning_json(ds))
    assert again.equals(ds)
    assert again.metadata.environment.mean_material_temperature == pytest.approx(20.05)


def test_json_defects():
    with pytest.raises(DataFormatError, match="not valid JSON"):
        parse_positioning_json("{")
    with pytest.raises(DataFormatError, match="format"):
        parse_positioning_json('{"format": "other"}')
    bad = format_positioning_json(PositioningDataset.from_arrays("linear", [0, 1], [[1, 2], [3, 4]]))
    with pytest.raises(DataFormatError, match="not a number"):
        parse_positioning_json(bad.replace("3.0", '"x"'))


ECMC = """# Input data file for ISO230-2 calcs
REF_PV=IOC_TEST:m0s005-Enc01-PosAct
UNIT=mm
CYCLES=2
POSITIONS=3
DEC=5
TGT_DATA[1]=15
TGT_DATA[2]=25
TGT_DATA[3]=35
REF_DATA_FWD[1,1]=15.00161
REF_DATA_FWD[2,1]=25.02160
REF_DATA_FWD[3,1]=34.99089
REF_DATA_FWD[1,2]=15.00141
REF_DATA_FWD[2,2]=25.02120
REF_DATA_FWD[3,2]=34.99007
REF_DATA_BWD[1,1]=15.00181
REF_DATA_BWD[2,1]=25.02200
REF_DATA_BWD[3,1]=34.99100
REF_DATA_BWD[1,2]=15.00171
REF_DATA_BWD[2,2]=25.02180
REF_DATA_BWD[3,2]=34.99080
"""


def test_ecmc_file_values_are_actual_positions():
    """The layout of ecmc's ISO 230-2 data files (TGT_DATA[i], REF_DATA_FWD/BWD[i,j], UNIT,
    CYCLES, POSITIONS): values are reference-system actual positions, so the deviation of
    REF_DATA_FWD[1,1]=15.00161 at TGT_DATA[1]=15 is +1.61 µm."""
    ds = parse_ecmc(ECMC)
    assert ds.targets.tolist() == [15, 25, 35] and ds.deviation_unit == "um"
    np.testing.assert_allclose(ds.up[:, 0], [1.61, 21.60, -9.11], atol=1e-6)
    np.testing.assert_allclose(ds.down[:, 1], [1.71, 21.80, -9.20], atol=1e-6)
    assert ds.metadata.instrument == "IOC_TEST:m0s005-Enc01-PosAct"
    again = parse_ecmc(format_ecmc(ds))
    np.testing.assert_allclose(again.up, ds.up, atol=1e-6)


def test_ecmc_mismatch_and_defects_are_reported():
    with pytest.raises(DataFormatError, match="CYCLES=3 is declared but the data hold 2"):
        parse_ecmc(ECMC.replace("CYCLES=2", "CYCLES=3"))
    with pytest.raises(DataFormatError, match="no TGT_DATA"):
        parse_ecmc("UNIT=mm\nREF_DATA_FWD[1,1]=1\n")
    with pytest.raises(DataFormatError, match="position 4, which has no TGT_DATA"):
        parse_ecmc(ECMC + "REF_DATA_FWD[4,1]=1\n")
    with pytest.raises(DataFormatError, match=r"f:11: REF_DATA_FWD\[2,1\] 'x' is not a number"):
        parse_ecmc(ECMC.replace("REF_DATA_FWD[2,1]=25.02160", "REF_DATA_FWD[2,1]=x"), source="f")


def test_read_positioning_dispatches_by_content(tmp_path):
    (tmp_path / "a.csv").write_text(CSV)
    (tmp_path / "b.txt").write_text(ECMC)
    ds = parse_positioning_csv(CSV)
    (tmp_path / "c.json").write_text(format_positioning_json(ds))
    assert read_positioning(tmp_path / "a.csv").n_targets == 2
    assert read_positioning(tmp_path / "b.txt").n_targets == 3
    assert read_positioning(tmp_path / "c.json").equals(ds)
    with pytest.raises(MissingFileError, match="no such file"):
        read_positioning(tmp_path / "missing.csv")
    (tmp_path / "bin.csv").write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(DataFormatError, match="not UTF-8"):
        read_positioning(tmp_path / "bin.csv")


@given(st.text(max_size=300))
@settings(max_examples=300, deadline=None)
def test_parsers_raise_only_axiscal_errors_on_arbitrary_text(text):
    """CONVENTIONS habit 9: parsers never raise anything but AxiscalError on arbitrary text."""
    for parse in (lambda t: parse_positioning_csv(t, target_unit="mm", deviation_unit="um"),
                  parse_positioning_json, parse_ecmc):
        try:
            parse(text)
        except AxiscalError:
            pass


@given(st.lists(st.tuples(st.sampled_from(["0", "1", "2", "x", "", "1e3", "nan", "-0"]),
                          st.sampled_from(["+", "-", "up", "?", ""]),
                          st.sampled_from(["1", "2", "0", "1.5", "a"]),
                          st.sampled_from(["1", "-2.5", "", "inf", "q"])), max_size=12))
@settings(max_examples=300, deadline=None)
def test_csv_parser_on_structured_garbage(rows):
    text = "target,direction,run,deviation\n" + "\n".join(",".join(r) for r in rows)
    try:
        ds = parse_positioning_csv(text, target_unit="mm", deviation_unit="um")
    except AxiscalError:
        return
    assert ds.n_targets >= 2
