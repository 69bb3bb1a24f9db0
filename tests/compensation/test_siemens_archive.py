"""SINUMERIK files laid out as a series start-up archive holds them (issue 42): METRIC/CHANDATA
headers and CRLF, 25 points reserved and fewer used, both measuring systems, the axis kind from
the INITIAL.INI, every table read with one bad table not blocking the others, the nine CEC
tables, a builder's loader program. The files are in tests/data/siemens (README: made after the
K3 layout and the issue's description; no public archive was found)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.compensation.controllers import siemens_840d, siemens_machine_data
from axiscal.datasets import AxisKind
from axiscal.errors import AxiscalError, DataFormatError

DATA = Path(__file__).resolve().parents[1] / "data" / "siemens"


def _text(name: str) -> str:
    return (DATA / name).read_bytes().decode("cp1252")


EEC, INI = _text("AX_EEC.INI"), _text("INITIAL.INI")


def test_files_keep_the_nck_layout():
    """The test files are what the issue describes: METRIC, a blank line, CHANDATA(1), CRLF."""
    raw = (DATA / "AX_EEC.INI").read_bytes()
    assert raw.startswith(b"METRIC\r\n\r\nCHANDATA(1)\r\n") and b"%_N_" not in raw


def test_every_table_read_with_the_axis_kind_from_machine_data():
    r = siemens_840d.read_tables(EEC, "AX_EEC.INI", machine_data=INI,
                                 machine_data_source="INITIAL.INI")
    assert not r.refused
    got = {r.key(k): (t.axis, t.axis_kind, t.n_points, t.start, t.end) for k, t in r.tables.items()}
    assert got == {"AX1": ("X1", AxisKind.LINEAR, 20, 0.0, 950.0),
                   "AX1/2": ("X1", AxisKind.LINEAR, 9, -10.0, 790.0),
                   "AX2": ("Y1", AxisKind.LINEAR, 21, -400.0, 400.0),
                   "AX3": ("Z1", AxisKind.LINEAR, 25, -600.0, 0.0),
                   "AX4": ("A1", AxisKind.ROTARY, 15, -105.0, 105.0),
                   "AX5": ("C1", AxisKind.ROTARY, 25, 0.0, 360.0)}
    assert any("MD30310 $MA_ROT_IS_MODULO[AX4] = 0 in INITIAL.INI" in n and "not modulo" in n
               for n in r.notes)


def test_linear_axis_checked_by_hand():
    """AX_EEC.INI line ``$AA_ENC_COMP[0,1,AX1]=0.0011``: point 1 at MIN 0 + 1 x STEP 50 = 50 mm;
    the file holds the deviation (808D manual: a positive value moves the axis negative), so the
    correction is −1.1 µm. MAX 950 is point (950 − 0)/50 = 19: 20 of the 25 points are used
    (K3: the end position is interpolation point k)."""
    assert "$AA_ENC_COMP[0,1,AX1]=0.0011\r\n" in EEC.replace("\n", "\r\n").replace("\r\r", "\r")
    t = siemens_840d.parse(EEC, machine_axis="AX1", measuring_system=1, machine_data=INI)
    assert t.positions[1] == 50.0 and t.up[1] == pytest.approx(-1.1)
    assert t.correction_unit == "um" and t.n_points == 20 and t.end == 950.0
    assert (t.origin.machine_axis, t.origin.measuring_system, t.origin.unit) == ("AX1", 1, "mm")


def test_rotary_swivel_axis_checked_by_hand():
    """``$AA_ENC_COMP[0,1,AX4]=0.0004`` with MD30300 = 1, MD30310 = 0 (INITIAL.INI): 0.0004°
    = 1.44″ deviation at −105 + 15 = −90°, correction −1.44″ (not 0.4 µm at −90 mm)."""
    t = siemens_840d.parse(EEC, machine_axis="A1", machine_data=INI)
    assert t.axis_kind is AxisKind.ROTARY and not t.modulo
    assert (t.position_unit, t.correction_unit) == ("deg", "arcsec")
    assert t.positions[1] == -90.0 and t.up[1] == pytest.approx(-1.44)


def test_without_machine_data_the_linear_reading_is_said():
    r = siemens_840d.read_tables(EEC, "AX_EEC.INI")
    assert r.tables[("AX4", 1)].axis_kind is AxisKind.LINEAR
    assert any(n.startswith("assumed: AX4 is linear") and "--ini" in n for n in r.notes)
    assert r.tables[("AX5", 1)].axis_kind is AxisKind.ROTARY      # modulo: rotary from the file


def test_measuring_systems_kept_apart():
    """AX1 has a table per measuring system (first index 0 and 1): each with its own STEP, MIN,
    MAX and values; a parse naming only the axis asks for the measuring system."""
    one = siemens_840d.parse(EEC, machine_axis="AX1", measuring_system=1)
    two = siemens_840d.parse(EEC, machine_axis="X1", measuring_system=2, machine_data=INI)
    assert (one.start, one.spacing, one.n_points) == (0.0, 50.0, 20)
    assert (two.start, two.spacing, two.n_points) == (-10.0, 100.0, 9)
    assert two.up[1] == pytest.approx(0.8) and two.origin.measuring_system == 2
    with pytest.raises(DataFormatError, match="measuring_system=1 or 2"):
        siemens_840d.parse(EEC, machine_axis="AX1")


def test_one_bad_table_does_not_block_the_others():
    bad = EEC.replace("$AA_ENC_COMP_MAX[0,AX2]=400", "$AA_ENC_COMP_MAX[0,AX2]=410")
    r = siemens_840d.read_tables(bad, "AX_EEC.INI")
    assert list(r.refused) == [("AX2", 1)] and len(r.tables) == 5
    assert "(MAX 410 − MIN -400) / STEP 40 = 20.25 is not a whole number" in r.refused[("AX2", 1)]
    assert siemens_840d.parse(bad, machine_axis="AX3").n_points == 25
    with pytest.raises(DataFormatError, match="AX2: \\(MAX 410"):
        siemens_840d.parse(bad, machine_axis="AX2")


def test_unused_points_are_said_and_a_max_beyond_them_refused():
    r = siemens_840d.read_tables(EEC, "AX_EEC.INI")
    assert any(n.startswith("AX1: points 20 … 24 (5 of 25, reserved by MD38000) are not used")
               for n in r.notes)
    short = EEC.replace("$AA_ENC_COMP_MAX[0,AX3]=0", "$AA_ENC_COMP_MAX[0,AX3]=25")
    r = siemens_840d.read_tables(short, "x")
    assert "MAX 25 is interpolation point 25, but the file gives points 0 … 24" in \
        r.refused[("AX3", 1)]


def test_header_unit_read_and_contradiction_refused():
    (u,) = siemens_840d.inputs(EEC)
    assert (u.value, u.source) == ("mm", "file") and "METRIC" in u.why
    inch = EEC.replace("METRIC", "INCH", 1)
    t = siemens_840d.parse(inch, machine_axis="AX1", measuring_system=1)
    assert t.positions[1] == pytest.approx(50 * 25.4) and t.origin.unit == "inch"
    with pytest.raises(DataFormatError, match="contradicts"):
        siemens_840d.inputs(EEC + "$MN_SCALING_SYSTEM_IS_METRIC=0\n")


def test_machine_data_read_from_initial_ini():
    md = siemens_machine_data.parse(INI, "INITIAL.INI")
    assert md.names["AX4"] == "A1" and md.rotary["AX4"] and not md.modulo["AX4"]
    assert md.max_points[("AX1", 1)] == 25 and md.metric is True
    assert md.machine_axis("c1") == "AX5"


def test_nine_cec_tables_each_with_its_axes():
    tables, refused = siemens_840d.read_cross_axis(_text("NC_CEC.INI"), "NC_CEC.INI")
    assert not refused and [c.index for c in tables] == list(range(9))
    axes = [(c.input_axis, c.output_axis, c.direction) for c in tables]
    assert axes == [("AX2", "AX3", 0), ("AX1", "AX3", 0), ("AX1", "AX2", 0), ("AX3", "AX2", 0),
                    ("AX2", "AX1", 0), ("AX1", "AX3", 1), ("AX1", "AX3", -1), ("AX4", "AX3", 0),
                    ("AX4", "AX2", 0)]
    five = tables[5]
    assert (five.table.n_points, five.table.end) == (16, 900.0)
    assert "15.8333 is not a whole number of steps" in five.notes[0]
    with pytest.raises(DataFormatError, match="holds 9 CEC tables"):
        siemens_840d.parse_cross_axis(_text("NC_CEC.INI"))


def test_loader_program_read_for_its_table_and_statements_said():
    mpf = _text("EEC_A1.MPF")
    r = siemens_840d.read_tables(mpf, "EEC_A1.MPF", machine_data=INI)
    (t,) = r.tables.values()
    assert t.axis == "A1" and t.n_points == 15 and t.up[1] == pytest.approx(-1.44)
    said = " ".join(r.notes)
    for word in ("NEWCONF", "STOPRE", "MSG", "G4", "MD32700 $MA_ENC_COMP_ENABLE[0,AX4] = 0"):
        assert word in said
    with pytest.raises(DataFormatError, match="EEC_A1.MPF:7: 'IF R1==0 GOTOF END' is a statement"):
        siemens_840d.read_tables(mpf.replace('MSG("EEC', 'IF R1==0 GOTOF END\r\nMSG("EEC', 1),
                                 "EEC_A1.MPF")


def test_round_trip_of_every_table_keeps_axis_and_measuring_system():
    """Each table read, written for its own machine axis and measuring system, reads back the
    same (values, positions, origin)."""
    r = siemens_840d.read_tables(EEC, "AX_EEC.INI", machine_data=INI)
    for (ax, ms), t in r.tables.items():
        f = siemens_840d.write(t, zero_at_reference=False)
        assert f"[{ms - 1},0,{ax}]" in f.text
        back = siemens_840d.parse(f.text, axis_kind=t.axis_kind)
        np.testing.assert_allclose(back.up, t.up, atol=1e-9)
        np.testing.assert_allclose(back.positions, t.positions)
        assert (back.origin.machine_axis, back.origin.measuring_system) == (ax, ms)


def test_more_points_than_md38000_reserves_is_refused_for_that_table_only():
    """K3: 0 ≤ N ≤ MD38000 − 1. INITIAL.INI reserves 25 points for AX1 measuring system 2
    ($MA_MM_ENC_COMP_MAX_POINTS[1,AX1]=25) and 0 for AX2's: with 24 there the AX1/2 table
    (25 points listed) is refused, the others read."""
    ini = INI.replace("$MA_MM_ENC_COMP_MAX_POINTS[1,AX1]=25", "$MA_MM_ENC_COMP_MAX_POINTS[1,AX1]=24")
    r = siemens_840d.read_tables(EEC, "AX_EEC.INI", machine_data=ini)
    assert list(r.refused) == [("AX1", 2)]
    assert "25 points but MD38000 $MA_MM_ENC_COMP_MAX_POINTS[1,AX1] = 24" in r.refused[("AX1", 2)]


def test_cec_direction_and_multiplication_kept():
    """K3 §4.4.4: $AN_CEC_DIRECTION 0/1/−1 and $AN_CEC_MULT_BY_TABLE are read per table and
    kept with it (axiscal does not apply a multiplication: it reports it)."""
    text = _text("NC_CEC.INI").replace("$AN_CEC_MULT_BY_TABLE[4]=0", "$AN_CEC_MULT_BY_TABLE[4]=3")
    tables, _ = siemens_840d.read_cross_axis(text)
    assert [c.mult_by_table for c in tables] == [0, 0, 0, 0, 3, 0, 0, 0, 0]
    assert tables[4].to_dict()["mult_by_table"] == 3 and tables[6].direction == -1


_LINES = st.sampled_from([
    "METRIC", "INCH", "", "CHANDATA(1)", "%_N_AX_EEC_INI", "M17", "NEWCONF", "G4F4", "MSG()",
    "N38000 $MA_MM_ENC_COMP_MAX_POINTS[0,AX1]=2", "$MA_IS_ROT_AX[AX1]=1",
    "$MN_SCALING_SYSTEM_IS_METRIC=0", "$AA_ENC_COMP[0,0,AX1]=0.001", "$AA_ENC_COMP[0,1,AX1]=0",
    "$AA_ENC_COMP_STEP[0,AX1]=10", "$AA_ENC_COMP_MIN[0,AX1]=0", "$AA_ENC_COMP_MAX[0,AX1]=10",
    "$AA_ENC_COMP_IS_MODULO[0,AX1]=1", "$AN_CEC[0,0]=0", "$AN_CEC[0,1]=0.001",
    "$AN_CEC_STEP[0]=inf", "$AN_CEC_DIRECTION[0]=1e999", "$AN_CEC_MIN[0]=0", "$AN_CEC_MAX[0]=5",
    "$AN_CEC_INPUT_AXIS[0]=(AX1)", "$AN_CEC_OUTPUT_AXIS[0]=(AX2)", "$AA_ENC_COMP[²,0,AX1]=1",
    "$MN_AXCONF_MACHAX_NAME_TAB[0]=\"X1\"", "$MA_MM_ENC_COMP_MAX_POINTS[0,AX1]=²",
    # the real archive's shapes (tests/data/siemens/README.md)
    "N51000 $MNS_DISP_RES_MM=3", "_ZSD[0]=-1", "$P_UIFR[0]=CTRANS()", "$AN_CEC [0,2] = 0.004",
    "$AN_CEC_TYPE[0]=1", "$AN_CEC_INPUT_NCU[0]=nan", "$AN_CEC_STEP[0]=0",
    "$MA_CEC_ENABLE[AX1] = FALSE", "$SN_CEC_TABLE_ENABLE[0] = TRUE", "$AA_ENC_COMP[1,0,AX1]=0"])


@settings(max_examples=150, deadline=None)
@given(st.lists(_LINES | st.text(max_size=30), max_size=12))
def test_arbitrary_sinumerik_text_raises_only_axiscal_errors(lines):
    """Habit 9: the readers of tables, CEC tables and machine data raise nothing but AxiscalError."""
    text = "\r\n".join(lines)
    from axiscal.compensation.controllers.siemens_cec import loader_notes

    for f in (lambda: siemens_840d.read_tables(text, machine_data=text),
              lambda: siemens_840d.read_cross_axis(text),
              lambda: siemens_machine_data.parse(text), lambda: loader_notes(text)):
        try:
            f()
        except AxiscalError:
            pass


def test_md10240_of_the_machine_data_decides_a_silent_table():
    """A table without METRIC/INCH header read with an INITIAL.INI stating MD10240 = 0 is in
    inch (808D Parameter Manual §2.2), and that is said; the table's own header wins."""
    silent = EEC.replace("METRIC", "", 1)
    ini = INI.replace("$MN_SCALING_SYSTEM_IS_METRIC=1", "$MN_SCALING_SYSTEM_IS_METRIC=0")
    r = siemens_840d.read_tables(silent, "x", machine_data=ini, machine_data_source="INITIAL.INI")
    assert r.tables[("AX1", 1)].spacing == pytest.approx(50 * 25.4)
    assert "unit inch: MD10240 $MN_SCALING_SYSTEM_IS_METRIC = 0 in INITIAL.INI" in r.notes
    assert siemens_840d.read_tables(EEC, "x", machine_data=ini).tables[("AX1", 1)].spacing == 50


def test_controller_file_in_utf16_is_read(tmp_path):
    """A Windows tool's UTF-16 export (BOM FF FE) of an EEC file reads as its CRLF text does."""
    from axiscal.io._files import read_controller_text

    p = tmp_path / "AX_EEC.INI"
    p.write_bytes(b"\xff\xfe" + EEC.encode("utf-16-le"))
    text, enc = read_controller_text(p)
    assert enc == "utf-16" and text == EEC


def test_cec_table_of_a_rotary_input_axis_in_degrees_with_the_machine_data():
    """Table 7 is driven by AX4 (A1, rotary by MD30300 in INITIAL.INI): its positions are
    degrees (−105 … 105°) with the machine data, mm when the file alone is read (said in the
    docstring: the file does not say)."""
    cec = _text("NC_CEC.INI")
    with_md, _ = siemens_840d.read_cross_axis(cec, "NC_CEC.INI", machine_data=INI)
    alone, _ = siemens_840d.read_cross_axis(cec, "NC_CEC.INI")
    assert with_md[7].table.position_unit == "deg" and alone[7].table.position_unit == "mm"
    assert with_md[7].table.positions[1] == -90.0 and with_md[7].table.correction_unit == "um"
    assert "every 15 ° from -105 to 105 °" in str(with_md[7])
