"""Controller parsers on damaged files: a missing, repeated or impossible line is refused by name.

Found by the CLI review: ``fanuc.parse`` raised ``KeyError: 3626`` on a bidirectional file whose
parameter 3626 line was missing, and writers divided by a zero position unit.
"""

import re

import pytest

from axiscal.compensation.controllers import controller
from axiscal.compensation.tables import table_from_deviations
from axiscal.errors import ControllerLimitError, DataFormatError


def _table(bidirectional=True):
    down = [0.0, -3.0, 2.0, 1.0, -4.0] if bidirectional else None
    return table_from_deviations([0, 100, 200, 300, 400], [2.0, -1.0, 4.0, 3.0, -2.0], down,
                                 spacing=25, resolution=1.0, axis="X")


def _fanuc_text(bidirectional=True):
    return controller("fanuc").write(_table(bidirectional)).text


def _without(text, prefix):
    return "\n".join(x for x in text.splitlines() if not x.startswith(prefix)) + "\n"


def _replace(text, prefix, line):
    """``line`` in place of the line starting with ``prefix`` (inserted after the first line if
    the file has none: axiscal's tapes carry no N3605, a bit parameter set by hand)."""
    lines = text.splitlines()
    if not any(x.startswith(prefix) for x in lines):
        lines.insert(1, prefix)
    return "\n".join(line if x.startswith(prefix) else x for x in lines) + "\n"


def test_fanuc_bidirectional_file_without_3626_names_the_parameter():
    text = _without(_fanuc_text(), "N3626")
    with pytest.raises(DataFormatError, match="parameter 3626 is missing"):
        controller("fanuc").parse(text)


@pytest.mark.parametrize("param", ["N3620", "N3621", "N3622", "N3624"])
def test_fanuc_missing_required_parameter(param):
    with pytest.raises(DataFormatError, match=f"parameter {param[1:]} is missing"):
        controller("fanuc").parse(_without(_fanuc_text(), param))


def test_fanuc_missing_data_line_names_the_point():
    with pytest.raises(DataFormatError, match="point 3 is missing"):
        controller("fanuc").parse(_without(_fanuc_text(False), "N10003P"))


@pytest.mark.parametrize("line, rule", [
    ("N3622A1P10000000", "3621 < 3622"),           # a billion-point range: refused, not iterated
    ("N3622A1P0", "3621 < 3622"),                   # empty range (was IndexError)
    ("N3620A1P50", "3620 = 50"),                    # reference outside the points
    ("N3623A1P0", "3623 = 0"),                      # magnification outside 1 … 100
    ("N3624A1P0", "3624 = 0"),                      # zero interval
    ("N3605A1P00000002", "3605 = '00000002'"),      # not a bit pattern (was ValueError)
    ("N3626A1P1020", "3626 = 1020"),                # negative table beyond point 1023
    ("N3627A1P" + "9" * 400, "out of range"),       # was OverflowError in int -> float
])
def test_fanuc_impossible_parameters_are_refused_by_name(line, rule):
    text = _replace(_fanuc_text(), line[:5], line)
    with pytest.raises(DataFormatError, match=re.escape(rule)):
        controller("fanuc").parse(text)


def test_fanuc_repeated_line_is_refused_not_overwritten():
    lines = _fanuc_text().splitlines()
    i = next(k for k, x in enumerate(lines) if x.startswith("N10002P"))
    lines.insert(i + 1, "N10002P55")
    with pytest.raises(DataFormatError, match="N10002 is given twice"):
        controller("fanuc").parse("\n".join(lines) + "\n")


def test_fanuc_parse_refuses_a_zero_detection_unit():
    with pytest.raises(ValueError, match="detection_unit"):
        controller("fanuc").parse(_fanuc_text(), detection_unit=0.0)


def test_fanuc_round_trip_still_reads_back():
    """The checks leave a well-formed file alone: the table read back equals the one written."""
    cf = controller("fanuc").write(_table())
    back = controller("fanuc").parse(cf.text)
    assert back.up.tolist() == pytest.approx(cf.table.up.tolist())
    assert back.down.tolist() == pytest.approx(cf.table.down.tolist())


@pytest.mark.parametrize("name, option", [("fanuc", "detection_unit"),
                                          ("heidenhain", "position_resolution"),
                                          ("siemens-840d", "position_resolution")])
@pytest.mark.parametrize("value", [0.0, -0.001, float("nan")])
def test_writers_refuse_a_non_positive_position_unit_by_name(name, option, value):
    """Was ZeroDivisionError (0) or a misleading 'not a whole multiple' (negative, NaN)."""
    with pytest.raises(ControllerLimitError, match=f"{option} = .* must be a positive number"):
        controller(name).write(_table(), **{option: value})


def test_siemens_repeated_point_is_refused_not_overwritten():
    text = controller("siemens-840d").write(_table()).text
    lines = text.splitlines()
    i = next(k for k, x in enumerate(lines) if x.startswith("$AA_ENC_COMP[0,2,"))
    lines.insert(i + 1, lines[i].split("=")[0] + "=0.5")
    with pytest.raises(DataFormatError, match="point 2 is given twice"):
        controller("siemens-840d").parse("\n".join(lines) + "\n")


def test_siemens_point_index_of_5000_digits_is_a_format_error():
    """Was ValueError from int() (Python refuses more than 4300 digits)."""
    text = controller("siemens-840d").write(_table()).text.replace("[0,1,AX1]", "[0," + "1" * 5000 + ",AX1]")
    with pytest.raises(DataFormatError):
        controller("siemens-840d").parse(text)


@pytest.mark.parametrize("name", ["heidenhain", "linuxcnc", "csv"])
def test_huge_numbers_are_refused_by_the_reader(name):
    """1e308 mm passed the finite check and overflowed in the unit conversion."""
    text = controller(name).write(_table()).text
    lines = text.splitlines()
    i = len(lines) - 2
    lines[i] = re.sub(r"[-+]?\d+(\.\d+)?$", "1e308", lines[i].rstrip())
    assert lines[i].endswith("1e308")
    with pytest.raises(DataFormatError, match="out of range"):
        controller(name).parse("\n".join(lines) + "\n")


def test_linuxcnc_parse_refuses_an_unknown_file_type():
    """Was read silently as type 1."""
    text = controller("linuxcnc").write(_table()).text
    with pytest.raises(ValueError, match="file_type = 2"):
        controller("linuxcnc").parse(text, file_type=2)


@pytest.mark.parametrize("extra", ["Y", "BACKLASH  Y"])
def test_heidenhain_extra_column_is_refused_not_ignored(extra):
    """A fourth column not named BACKLASH (or a fifth) was read as BACKLASH or dropped."""
    lines = controller("heidenhain").write(_table(False)).text.splitlines()
    n_extra = len(extra.split())
    lines[1] += "  " + extra
    lines[2:-1] = [x + "  +0.0" * n_extra for x in lines[2:-1]]
    with pytest.raises(DataFormatError, match="has columns this reader would drop"):
        controller("heidenhain").parse("\n".join(lines) + "\n")
