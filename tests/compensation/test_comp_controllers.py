"""Controller formats: every writer round-trips, every limit is enforced, parsers fail cleanly."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.compensation.controllers import CONTROLLERS, controller
from axiscal.compensation.controllers import fanuc, heidenhain, linuxcnc, siemens_840d
from axiscal.compensation.tables import table_from_deviations
from axiscal.errors import AxiscalError, ControllerLimitError, DataFormatError, InputError
import re


def _linear(bidirectional=True, resolution=1.0):
    t = [0, 100, 200, 300, 400]
    up = [2.0, -1.0, 4.0, 3.0, -2.0]
    down = [0.0, -3.0, 2.0, 1.0, -4.0] if bidirectional else None
    return table_from_deviations(t, up, down, spacing=25, resolution=resolution, axis="X")


def _rotary(bidirectional=True, resolution=0.36):
    th = np.arange(0, 361, 30.0)
    dev = 3 * np.sin(np.radians(th)) + np.cos(2 * np.radians(th))
    return table_from_deviations(th, dev, dev - 1.5 if bidirectional else None, spacing=15,
                                 resolution=resolution, modulo=True, axis="C", axis_kind="rotary",
                                 position_unit="deg", correction_unit="arcsec")


def _read_back(name, written, table):
    mod = controller(name)
    kw = {"csv": {}, "fanuc": dict(axis_kind=table.axis_kind, reference_position=table.reference_position,
                                   detection_unit=0.0001),
          }.get(name, dict(axis_kind=table.axis_kind))
    return mod.parse(written.text, **kw)


# What each writer may change on purpose: Siemens and Fanuc re-reference to zero (Siemens on the
# mean of both directions); Siemens keeps one table plus a backlash value; Fanuc rounds to counts.
def _expected(name, table):
    if name == "fanuc":
        return table.zeroed_at_reference()
    if name in ("siemens-840d", "renishaw-ren"):   # .ren: one table and a mean reversal too
        z = table.zeroed_at_reference(on="mean") if name == "siemens-840d" else table
        return z if not z.bidirectional else z.__class__(**{**z.__dict__, "up": z.mean - z.backlash / 2,
                                                            "down": z.mean + z.backlash / 2})
    return table


@pytest.mark.parametrize("name", list(CONTROLLERS))
@pytest.mark.parametrize("make", [_linear, _rotary], ids=["linear", "rotary"])
@pytest.mark.parametrize("bidirectional", [True, False], ids=["bi", "uni"])
def test_round_trip_gives_the_same_corrections(name, make, bidirectional):
    """parse(write(t)) equals t (after the format's stated re-referencing) at every point."""
    table = make(bidirectional)
    opts = {"fanuc": dict(detection_unit=0.0001)}.get(name, {})
    written = controller(name).write(table, **opts)
    back = _read_back(name, written, table)
    expected = _expected(name, table)
    assert back.n_points == table.n_points
    assert back.start == pytest.approx(table.start) and back.spacing == pytest.approx(table.spacing)
    assert back.modulo == table.modulo
    assert back.bidirectional == table.bidirectional
    # within the format's number precision (1 nm; 1e-9 deg; one Fanuc count of 0.0001 deg or mm)
    tol = 0.36 / 2 + 1e-6 if name == "fanuc" and table.modulo else 0.05 if name == "fanuc" else 1e-5
    assert np.allclose(back.up, expected.up, atol=tol), (back.up, expected.up)
    assert np.allclose(back.down, expected.down, atol=tol)
    # and exactly what the writer says it wrote
    assert np.allclose(back.up, written.table.up, atol=1e-6)
    assert np.allclose(back.down, written.table.down, atol=1e-6)
    assert written.enable, "a writer says how to enable the table"


def test_siemens_file_layout_and_sign():
    """Siemens 840D sl FM K3 example layout; 808D FM: a positive value moves the axis negative,
    so the file holds +deviation (−correction) in mm."""
    t = table_from_deviations([-200, 600], [3.0, 3.0], spacing=1.0, axis="X")   # +3 µm everywhere
    f = siemens_840d.write(t, machine_axis="X1", zero_at_reference=False)
    lines = f.text.splitlines()
    assert lines[0] == "%_N_AX_EEC_INI" and lines[1] == "CHANDATA(1)" and lines[-1] == "M17"
    assert "$AA_ENC_COMP[0,0,X1]=0.003" in lines
    assert "$AA_ENC_COMP[0,800,X1]=0.003" in lines
    assert "$AA_ENC_COMP_STEP[0,X1]=1.0" in lines
    assert "$AA_ENC_COMP_MIN[0,X1]=-200.0" in lines and "$AA_ENC_COMP_MAX[0,X1]=600.0" in lines
    assert "$AA_ENC_COMP_IS_MODULO[0,X1]=0" in lines
    assert any("MD38000" in e and ">= 801" in e for e in f.enable)
    assert any("MD32700" in e for e in f.enable)


def test_fanuc_rotary_numbering_follows_0i_example_2():
    """0i-PB parameter manual Example 2: 360°, interval 45°, reference point 60 -> the negative
    end is 60, the positive end 60 + 360/45 = 68, and point 60 holds the value of point 68."""
    th = np.arange(0, 361, 45.0)
    dev = 36 * np.sin(np.radians(th))               # arcsec: 0.01 deg steps, whole counts
    t = table_from_deviations(th, dev, spacing=45, modulo=True, axis="C", axis_kind="rotary",
                              position_unit="deg", correction_unit="arcsec")
    text = fanuc.write(t, reference_number=60).text
    assert "N3620A1P60" in text and "N3621A1P60" in text and "N3622A1P68" in text
    assert "N3624A1P45000" in text and "N3625A1P360000" in text
    values = {int(ln[1:6]) - 10000: int(ln.split("P")[1]) for ln in text.splitlines()
              if ln.startswith("N1")}
    assert sum(values[k] for k in range(61, 69)) == 0
    assert values[60] == values[68]


def test_fanuc_increments_are_corrections_per_interval():
    """Deviation +2 µm per 10 mm from the reference: correction increments are −2 counts."""
    t = table_from_deviations([0, 40], [0.0, 8.0], spacing=10, axis="X")
    text = fanuc.write(t).text
    data = [ln for ln in text.splitlines() if ln.startswith("N1")]
    assert data == ["N10000P0", "N10001P-2", "N10002P-2", "N10003P-2", "N10004P-2"]
    assert "N3620A1P0" in text and "N3623A1P1" in text and "N3624A1P10000" in text


def test_linuxcnc_type0_holds_positions_reached():
    """usrmotLoadComp: type 0 stores trim = nominal − forward; the written forward value is the
    position the bare axis reaches, nominal + deviation."""
    t = table_from_deviations([0, 10], [5.0, 5.0], spacing=10, axis="X")   # +5 µm
    text = linuxcnc.write(t, file_type=0).text
    assert text.splitlines()[0] == "0.000000 0.005000 0.005000"
    text1 = linuxcnc.write(t, file_type=1).text
    assert text1.splitlines()[1] == "10.000000 -0.005000 -0.005000"
    assert np.allclose(linuxcnc.parse(text, file_type=0).up, [-5.0, -5.0])


def test_heidenhain_com_and_cma():
    f = heidenhain.write(_linear())
    lines = f.text.splitlines()
    assert lines[0] == "BEGIN X.COM MM" and lines[-1] == "[END]"
    assert lines[1].split() == ["NR", "AXISPOS", "X", "BACKLASH"]
    cma = f.extra_files["X.CMA"].splitlines()
    assert cma[1].split() == ["NR", "X", "ACTIVE"] and cma[2].split() == ["0", "X.COM", "*"]


# -- limits ------------------------------------------------------------------------------
def _long(n):
    return table_from_deviations([0, (n - 1) * 1.0], [0.0, 1.0], spacing=1.0, axis="X")


@pytest.mark.parametrize("name,limit", [("siemens-840d", 5000), ("heidenhain", 256),
                                        ("linuxcnc", 256), ("fanuc", 1024)])
def test_too_many_points(name, limit):
    controller(name).write(_long(limit))                  # at the limit: accepted
    with pytest.raises(ControllerLimitError, match="at most"):
        controller(name).write(_long(limit + 1))


@pytest.mark.parametrize("name", ["siemens-840d", "heidenhain", "fanuc"])
def test_spacing_must_be_a_multiple_of_the_resolution(name):
    t = table_from_deviations([0, 100], [0.0, 1.0], spacing=10.00005, axis="X")
    with pytest.raises(ControllerLimitError, match="not a whole multiple"):
        controller(name).write(t)


def test_heidenhain_power_of_two_spacing():
    ok = table_from_deviations([0, 100], [0.0, 1.0], spacing=8.192, axis="X")   # 2^13 µm
    heidenhain.write(ok, power_of_two=True)
    with pytest.raises(ControllerLimitError, match="power of two"):
        heidenhain.write(_linear(), power_of_two=True)


@pytest.mark.parametrize("name", list(CONTROLLERS))
def test_range_outside_travel(name):
    with pytest.raises(ControllerLimitError, match="outside the axis travel"):
        controller(name).write(_linear(), travel=(0.0, 350.0))


def test_fanuc_rotary_sum_must_be_zero():
    """A rotary table whose end does not return to its start would accumulate every turn."""
    t = _rotary(False, 0.36)
    broken = t.__class__(**{**t.__dict__, "up": t.up + np.linspace(0, 7.2, t.n_points),
                            "down": t.down + np.linspace(0, 7.2, t.n_points), "modulo": True})
    with pytest.raises(ControllerLimitError, match="sum to"):
        fanuc.write(broken, detection_unit=0.0001)
    with pytest.raises(ControllerLimitError, match="close on itself"):
        siemens_840d.write(broken)


def test_fanuc_value_range_and_magnification():
    """Increments beyond −128…127 counts take a magnification (3623) or are refused."""
    steep = table_from_deviations([0, 10], [0.0, 300.0], spacing=10, axis="X")   # 300 counts
    f = fanuc.write(steep)
    assert "N3623A1P3" in f.text
    with pytest.raises(ControllerLimitError, match="outside -128"):
        fanuc.write(steep, magnification=1)


def test_unknown_controller():
    with pytest.raises(InputError, match="not one of"):
        controller("mazak")


# -- parsers on garbage ----------------------------------------------------------------------
@pytest.mark.parametrize("name", list(CONTROLLERS))
@settings(max_examples=60, deadline=None)
@given(text=st.text(max_size=300))
def test_parsers_raise_only_axiscal_errors(name, text):
    try:
        controller(name).parse(text)
    except AxiscalError:
        pass


@pytest.mark.parametrize("name", ["siemens-840d", "fanuc", "heidenhain", "csv"])
def test_truncated_file_is_refused(name):
    f = controller(name).write(_linear())
    half = "\n".join(f.text.splitlines()[:3]) + "\n"
    with pytest.raises(DataFormatError):
        kw = {"fanuc": {}, "csv": {}}.get(name, {})
        controller(name).parse(half, **kw)


def test_linuxcnc_line_cut_short_is_refused():
    """LinuxCNC would silently stop reading at such a line; the parser says so instead."""
    text = linuxcnc.write(_linear()).text
    cut = text[: text.index("\n", 40) - 10] + "\n"
    with pytest.raises(DataFormatError, match="stops reading"):
        linuxcnc.parse(cut)


def test_siemens_zero_ends():
    """zero_ends forces the first and last values to 0 (the table fades out at its ends)."""
    f = siemens_840d.write(_linear(False), zero_ends=True)
    back = siemens_840d.parse(f.text)
    assert back.up[0] == 0.0 and back.up[-1] == 0.0
    assert np.allclose(back.up[1:-1], _expected("siemens-840d", _linear(False)).up[1:-1], atol=1e-6)


@settings(max_examples=25, deadline=None)
@given(values=st.lists(st.integers(-300, 300), min_size=2, max_size=40),
       step_counts=st.integers(1, 50000), start_counts=st.integers(-100000, 100000),
       bidirectional=st.booleans(), name=st.sampled_from(list(CONTROLLERS)))
def test_round_trip_property(values, step_counts, start_counts, bidirectional, name):
    """Any table on the controllers' grids (0.001 mm spacing, 0.1 µm values) comes back."""
    up = np.array(values) * 0.1
    down = up + 1.5 if bidirectional else up
    t0 = np.arange(len(values)) * step_counts * 0.001 + start_counts * 0.001
    table = table_from_deviations(t0, -up, -down if bidirectional else None,
                                  spacing=step_counts * 0.001, start=t0[0], end=t0[-1],
                                  resolution=0.1, axis="X")
    opts = {"fanuc": dict(detection_unit=0.0001)}.get(name, {})
    written = controller(name).write(table, **opts)
    back = _read_back(name, written, table)
    expected = _expected(name, table)
    assert back.n_points == table.n_points
    assert back.start == pytest.approx(table.start, abs=1e-6)
    # Fanuc rounds to one count x magnification (3623 grows when an increment exceeds 127)
    tol = back.resolution / 2 + 1e-6 if name == "fanuc" else 1e-5
    assert np.allclose(back.up, expected.up, atol=tol)
    assert np.allclose(back.down, expected.down, atol=tol)
    assert np.allclose(back.up, written.table.up, atol=1e-6)


# -- Controller parsers on damaged files: a missing, repeated or impossible line is refused by name. ----------
#
# Found by the CLI review: ``fanuc.parse`` raised ``KeyError: 3626`` on a bidirectional file whose
# parameter 3626 line was missing, and writers divided by a zero position unit.

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
