"""SINUMERIK files in the layout of a real series start-up archive (issue 42).

The public archive of a DMG DMU 85 five-axis machining centre (github.com/halitcan/
Sinumerik_Archive_helper, ``test_environment/test.arc``, commit
8581efa4c3a4ada9ed2db653ff3dcc33fbfcf4db) carries no licence, so its bytes are not kept; the files in ``tests/data/siemens/archive_layout``
repeat what reading it showed (values invented, README there): the ``INITIAL.INI``'s display
machine data (``$MNS_``, ``$SNS_``), user variables without ``$`` (GUD), frames and tool data;
measuring system 2 (``[1,…]``) only, MD38000 = 25 with fewer points used; ``$AN_CEC_INPUT_NCU``,
``$AN_CEC_OUTPUT_NCU``, ``$AN_CEC_TYPE`` and a reserved CEC table not in use (STEP 0); a builder's
CEC loader writing ``$AN_CEC [1,0]`` with a blank before the bracket, Windows-1252 comments, and
MD32710/SD41300 switched ``FALSE``/``TRUE``; a loader whose values are for one measuring system
and STEP/MIN/MAX for the other; a dispatcher of ``CALL``s.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.compensation.controllers import detect, siemens_840d, siemens_machine_data
from axiscal.compensation.controllers.siemens_cec import in_error, loader_notes
from axiscal.compensation.controllers.siemens_text import statements
from axiscal.datasets import AxisKind
from axiscal.errors import DataFormatError

DATA = Path(__file__).resolve().parents[1] / "data" / "siemens" / "archive_layout"


def _text(name: str) -> str:
    return (DATA / name).read_bytes().decode("cp1252")


INI = _text("INITIAL.INI")


def test_initial_ini_with_display_data_user_variables_and_frames_is_read():
    """The real INITIAL.INI was refused at ``$MNS_DISP_RES_MM=3`` (three letters after ``$``);
    it also holds GUD variables (``_ZSD[0]=-1``), frames (``CTRANS()``) and tool data."""
    kinds = {s.name: s.kind for s in statements(INI, "INITIAL.INI")}
    assert kinds["MNS_DISP_RES_MM"] == kinds["P_UIFR"] == kinds["SNS_TM_FUNCTION_MASK_SET"] == \
        "assign"
    assert kinds["_ZSD"] == kinds["_SC_NCK_ROU_S"] == "user"
    md = siemens_machine_data.parse(INI, "INITIAL.INI")
    assert md.names["AX4"] == "C1" and md.names["AX5"] == "A1" and md.metric is True
    assert md.kind("AX4")[:2] == ("rotary", True) and md.kind("A1")[:2] == ("rotary", False)
    assert md.max_points[("AX1", 0)] == 0 and md.max_points[("AX1", 1)] == 25
    assert md.enabled[("AX5", 1)] and not md.enabled[("AX5", 0)]


def test_a_user_variable_in_a_table_file_is_refused_naming_it():
    eec = _text("AX_EEC.INI").replace("M17", "_ZSD[0]=-1\nM17")
    with pytest.raises(DataFormatError, match=r"_ZSD \(a user variable\) is not a compensation"):
        siemens_840d.read_tables(eec, "AX_EEC.INI")


def test_measuring_system_2_only_with_25_points_reserved():
    """``$AA_ENC_COMP[1,11,AX4]=0.0051``: measuring system 2, point 11 at 0 + 11 x 15 = 165°,
    0.0051° = 18.36″, correction −18.36″ (K3: MIN is point 0; the file holds the deviation)."""
    r = siemens_840d.read_tables(_text("AX_EEC.INI"), "AX_EEC.INI", machine_data=INI,
                                 machine_data_source="INITIAL.INI")
    assert not r.refused and sorted(r.tables) == [("AX1", 2), ("AX4", 2), ("AX5", 2)]
    c1 = r.tables[("AX4", 2)]
    assert (c1.axis, c1.axis_kind, c1.n_points, c1.modulo) == ("C1", AxisKind.ROTARY, 25, True)
    assert c1.positions[11] == 165.0 and c1.up[11] == pytest.approx(-18.36)
    a1 = r.tables[("AX5", 2)]
    assert (a1.axis, a1.n_points, a1.start, a1.end) == ("A1", 17, -120.0, 120.0)
    assert any("AX5/2: points 17 … 24 (8 of 25, reserved by MD38000)" in n for n in r.notes)


def test_cec_tables_with_ncu_type_and_a_reserved_table_not_in_use():
    """Table 0: (MAX 0 − MIN −850)/STEP 100 = 8.5, read to point 8 at −50 mm; table 1: A1 drives
    C1, ``$AN_CEC[1,14]=-0.0006`` at −120 + 14 x 15 = 90°, 0.0006° = 2.16″ (correction +2.16″);
    table 2 (STEP 0, axes (X)) is reserved but not in use: named, not an error."""
    tables, refused = siemens_840d.read_cross_axis(_text("NC_CEC.INI"), "NC_CEC.INI",
                                                   machine_data=INI)
    assert [(c.index, c.input_axis, c.output_axis) for c in tables] == [(0, "AX2", "AX1"),
                                                                        (1, "AX5", "AX4")]
    assert tables[0].table.end == -50.0 and "8.5 is not a whole number" in tables[0].notes[0]
    one = tables[1].table
    assert one.position_unit == "deg" and one.correction_unit == "arcsec"
    assert one.positions[14] == 90.0 and one.up[14] == pytest.approx(2.16)
    assert list(refused) == [2] and not in_error(refused)
    assert "not in use (STEP 0" in refused[2] and "input axis X" in refused[2]


def test_cec_type_and_ncu_other_than_default_are_said():
    text = _text("NC_CEC.INI").replace("$AN_CEC_TYPE[0]=0", "$AN_CEC_TYPE[0]=1") \
        .replace("$AN_CEC_INPUT_NCU[0]=1", "$AN_CEC_INPUT_NCU[0]=2")
    tables, _ = siemens_840d.read_cross_axis(text, "NC_CEC.INI")
    said = " ".join(tables[0].notes)
    assert "cylinder error compensation" in said and "$AN_CEC_INPUT_NCU = 2" in said


def test_builders_cec_loader_with_a_blank_before_the_bracket():
    mpf = _text("CEC_A1.MPF")
    assert "$AN_CEC [1,0]" in mpf and "Stützpunktabstand" in mpf and detect(mpf) == "siemens-840d"
    tables, refused = siemens_840d.read_cross_axis(mpf, "CEC_A1.MPF", machine_data=INI)
    assert not refused and tables[0].table.up[14] == pytest.approx(2.16)
    said = " ".join(loader_notes(mpf, "CEC_A1.MPF"))
    for word in ("MD32710 $MA_CEC_ENABLE[AX4] = FALSE", "SD41300 $SN_CEC_TABLE_ENABLE[1] = TRUE",
                 "NEWCONF", "MSG", "G4"):
        assert word in said


def test_values_of_one_measuring_system_with_steps_of_the_other_refused_naming_both():
    """A builder's loader (the archive's ``G_A_NC_DIREKT.MPF``) writes the values for measuring
    system 1 and STEP/MIN/MAX for measuring system 2: never combined, both named."""
    r = siemens_840d.read_tables(_text("EEC_A1_MIXED.MPF"), "EEC_A1_MIXED.MPF", machine_data=INI)
    assert not r.tables and set(r.refused) == {("AX5", 1), ("AX5", 2)}
    assert all("values are for measuring system 1 ([0,…]), STEP/MIN/MAX for measuring system 2"
               in v for v in r.refused.values())


def test_cli_reads_the_archive_files_and_refuses_a_dispatcher_of_calls():
    run = CliRunner().invoke
    ok = run(app, ["compensate", "--read", str(DATA / "NC_CEC.INI"), "--ini",
                   str(DATA / "INITIAL.INI")])
    assert ok.exit_code == 0, ok.output
    assert "reserved: CEC table 2: not in use" in ok.output
    eec = run(app, ["compensate", "--read", str(DATA / "AX_EEC.INI"), "--ini",
                    str(DATA / "INITIAL.INI"), "-o", "machine_axis=C1"])
    assert eec.exit_code == 0 and "axis C1 (rotary)" in eec.output
    assert "unit = mm (the file states the header line METRIC)" in eec.output
    mixed = run(app, ["compensate", "--read", str(DATA / "EEC_A1_MIXED.MPF"), "--ini",
                      str(DATA / "INITIAL.INI")])
    assert mixed.exit_code == 2 and "2 of 2 tables refused (listed above)\n" in mixed.output
    calls = run(app, ["compensate", "--read", str(DATA / "KOMP_TABLES.MPF"), "-c",
                      "siemens-840d"])
    assert calls.exit_code == 2
    assert "KOMP_TABLES.MPF:2: 'CALL\"/_N_WKS_DIR" in calls.output
    assert "Traceback" not in calls.output


def test_md10240_of_the_ini_states_the_unit_of_a_loader_without_header(tmp_path):
    """A loader program has no METRIC line: the ``--ini``'s MD10240 states the unit (shown as
    stated there, not as an assumption)."""
    mpf = tmp_path / "EEC_C1.MPF"
    mpf.write_text(_text("AX_EEC.INI").replace("METRIC", ""), encoding="utf-8")
    out = CliRunner().invoke(app, ["compensate", "--read", str(mpf), "--ini",
                                   str(DATA / "INITIAL.INI"), "-o", "machine_axis=C1"]).output
    assert "unit = mm (MD10240 $MN_SCALING_SYSTEM_IS_METRIC = 1 in --ini)" in out
    assert "assumed" not in out


def test_measuring_system_2_tables_round_trip_and_are_refused_where_no_format_holds_them():
    """Each table of measuring system 2 written back for its own axis reads back exact, kind and
    all; a conversion to a format without measuring systems is refused naming it."""
    from axiscal.compensation.controllers.convert import convert
    from axiscal.errors import ControllerLimitError

    r = siemens_840d.read_tables(_text("AX_EEC.INI"), "AX_EEC.INI", machine_data=INI)
    for (ax, ms), t in r.tables.items():
        f = convert(t, "siemens-840d", zero_at_reference=False)
        assert f"$AA_ENC_COMP[1,0,{ax}]=" in f.text
        back = siemens_840d.read_tables(f.text, machine_data=INI).tables[(ax, 2)]
        assert back.up.tolist() == t.up.tolist() and back.positions.tolist() == t.positions.tolist()
        assert (back.axis, back.axis_kind, back.modulo) == (t.axis, t.axis_kind, t.modulo)
        with pytest.raises(ControllerLimitError, match=f"measuring system 2 of {ax}"):
            convert(t, "fanuc", axis_number=1)


def test_a_user_variable_or_r_parameter_in_a_cec_loader_is_refused_naming_it():
    mpf = _text("CEC_A1.MPF").replace("NEWCONF", "R1=5", 1)
    with pytest.raises(DataFormatError, match=r"CEC_A1.MPF:8: R1 \(a user variable\) is not a CEC"):
        siemens_840d.read_cross_axis(mpf, "CEC_A1.MPF")
    frame = _text("CEC_A1.MPF").replace("NEWCONF", "$P_UIFR[1]=CTRANS()", 1)
    with pytest.raises(DataFormatError, match=r"CEC_A1.MPF:8: \$P_UIFR is not a CEC table"):
        siemens_840d.read_cross_axis(frame, "CEC_A1.MPF")
