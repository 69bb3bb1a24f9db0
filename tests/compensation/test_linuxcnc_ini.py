"""LinuxCNC compensation files read as the machine's INI declares them (issue 27): unit, type and
joint kind from the INI whose COMP_FILE names the file, implausible trims flagged, comment lines
after the data, and LinuxCNC's own sample (tests/data/linuxcnc, GPL-2.0, see its README)."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.compensation.controllers import CONTROLLERS, detect, linuxcnc
from axiscal.compensation.controllers.linuxcnc_ini import (
    comp_sections, comp_settings, parse_ini, read_options)
from axiscal.compensation.tables import CompensationTable, table_from_deviations
from axiscal.errors import AxiscalError, DataFormatError, InputError
from axiscal.io.linuxcnc_ini import find_comp_settings

DATA = Path(__file__).resolve().parents[1] / "data" / "linuxcnc"
SCREWCOMP = DATA / "screwcompX.dat"


def _read(path: Path, ini=None, **options):
    settings = find_comp_settings(path, ini)
    opts, inputs = read_options(settings, options, path.read_text(), str(path))
    return linuxcnc.parse(path.read_text(), str(path), **opts), {i.name: i for i in inputs}


def test_screwcomp_read_with_its_ini_as_inch_type_0():
    """LinuxCNC's configs/sim/tklinuxcnc/servo_sim.ini: [TRAJ] LINEAR_UNITS = inch, [JOINT_0]
    TYPE = LINEAR, COMP_FILE = screwcompX.dat, COMP_FILE_TYPE = 0. Type 0 stores the trims
    nominal − forward and nominal − reverse (src/emc/motion/usrmotintf.cc, usrmotLoadComp):
    at −10 in, −10 − (−10.001) = +0.001 in = +25.4 µm forward, −0.001 in = −25.4 µm reverse."""
    t, inputs = _read(SCREWCOMP)
    assert inputs["unit"].value == "inch" and inputs["unit"].source == "ini"
    assert "[TRAJ] LINEAR_UNITS = inch" in inputs["unit"].why
    assert "servo_sim.ini" in inputs["unit"].why and "[JOINT_0]" in inputs["unit"].why
    assert inputs["file_type"].value == 0 and "COMP_FILE_TYPE = 0" in inputs["file_type"].why
    assert inputs["axis_kind"].value == "linear" and not any(i.assumed for i in inputs.values())
    np.testing.assert_allclose(t.positions, np.arange(-10, 11, 2) * 25.4)
    assert t.up[0] == pytest.approx(25.4) and t.down[0] == pytest.approx(-25.4)
    assert t.up[3] == pytest.approx(0.2 * 25400)                # the -4 -4.2 -3.998 line
    assert t.up[-1] == pytest.approx(25.4) and t.down[-1] == pytest.approx(0.0)


def test_the_02_inch_trim_of_screwcomp_is_flagged_and_nothing_else():
    """The forward trim at −4 in is 0.2 in between 0.002 and 0.003 in: a spike of 0.198 in
    (5.03 mm), above both 10 × the median neighbour change (0.001 in) and 1 % of the 2 in
    spacing (0.02 in = 508 µm)."""
    t, _ = _read(SCREWCOMP)
    jumps = linuxcnc.trim_jumps(t)
    assert len(jumps) == 1
    j = jumps[0]
    assert (j.direction, j.kind) == ("forward", "spike")
    assert j.position == pytest.approx(-101.6) and j.trim == pytest.approx(5080.0)
    assert j.before == pytest.approx(50.8) and j.after == pytest.approx(76.2)
    assert j.jump == pytest.approx(5029.2) and j.threshold == pytest.approx(508.0)
    text = j.describe(t, "inch")
    assert "0.198 inch in the file" in text and "LinuxCNC would apply" in text


def test_a_smooth_table_and_a_real_pitch_error_are_not_flagged():
    """A lead error of 40 µm/m with a 5 µm wave and a 3 µm reversal, and a constant table
    (median change 0: only the 1 % slope rule applies), give no flag."""
    x = np.linspace(0, 500, 26)
    dev = 0.04 * x + 5 * np.sin(x / 40)
    t = table_from_deviations(x, dev, dev + 3, spacing=20)
    assert linuxcnc.trim_jumps(t) == ()
    flat = CompensationTable("X", "linear", "mm", "um", 0.0, 10.0, np.full(5, 7.0), np.zeros(5))
    assert linuxcnc.trim_jumps(flat) == ()


def test_a_step_is_flagged_as_a_step():
    """A single interval that jumps (and stays) is a step, not a spike."""
    t = CompensationTable("X", "linear", "mm", "um", 0.0, 10.0, [0., 1., 2., 900., 901., 902.],
                          np.zeros(6))
    [j] = linuxcnc.trim_jumps(t)
    assert (j.kind, j.position, j.jump) == ("step", 20.0, 898.0)


def test_a_unit_option_that_contradicts_the_ini_is_refused_in_one_line():
    with pytest.raises(InputError) as e:
        _read(SCREWCOMP, unit="mm")
    msg = str(e.value)
    assert "\n" not in msg
    assert "-o unit=mm contradicts [TRAJ] LINEAR_UNITS = inch in" in msg and "servo_sim.ini" in msg
    with pytest.raises(InputError, match="-o file_type=1 contradicts .JOINT_0. COMP_FILE_TYPE = 0"):
        _read(SCREWCOMP, file_type=1)
    t, inputs = _read(SCREWCOMP, unit="in")                  # the same unit in other words
    assert inputs["unit"].value == "inch" and t.up[0] == pytest.approx(25.4)


def test_the_pre_2_8_axis_section_is_read_too():
    """LinuxCNC 2.7's servo_sim.ini names the file in [AXIS_0] (tests/data/linuxcnc/v2.7)."""
    s = find_comp_settings(SCREWCOMP, DATA / "v2.7" / "servo_sim.ini")
    assert (s.section, s.unit, s.file_type, s.axis_kind) == ("AXIS_0", "inch", 0, "linear")


def test_an_ini_that_does_not_name_the_file_is_refused(tmp_path):
    other = tmp_path / "other.dat"
    shutil.copy(SCREWCOMP, other)
    with pytest.raises(InputError, match="no \\[JOINT_n\\] COMP_FILE names other.dat \\(it names "
                                         "screwcompX.dat in \\[JOINT_0\\]\\)"):
        find_comp_settings(other, DATA / "servo_sim.ini")
    assert find_comp_settings(other) is None          # no INI beside it


def test_without_an_ini_every_value_is_shown_as_assumed(tmp_path):
    """No INI beside the file: unit and joint kind assumed (mm, linear) and said so; the type
    told from the content (read as type 1 screwcompX's trims would be as large as its
    positions, so only type 0 is plausible)."""
    p = tmp_path / "screwcompX.dat"
    shutil.copy(SCREWCOMP, p)
    t, inputs = _read(p)
    assert inputs["unit"].assumed and inputs["unit"].value == "mm"
    assert "no INI beside the file names it" in inputs["unit"].why
    assert inputs["file_type"].assumed and inputs["file_type"].value == 0
    assert "the only type whose trims are plausible" in inputs["file_type"].why
    assert t.up[0] == pytest.approx(1.0)                # 0.001 read as mm: 1 µm
    t, inputs = _read(p, unit="inch")
    assert inputs["unit"].source == "option" and t.up[0] == pytest.approx(25.4)


def test_two_inis_that_disagree_are_refused(tmp_path):
    shutil.copy(SCREWCOMP, tmp_path / "screwcompX.dat")
    text = (DATA / "servo_sim.ini").read_text()
    (tmp_path / "a.ini").write_text(text)
    (tmp_path / "b.ini").write_text(text.replace("LINEAR_UNITS = inch", "LINEAR_UNITS = mm"))
    with pytest.raises(InputError, match="named by .*a.ini \\[JOINT_0\\] \\(inch, type 0\\) and "
                                         ".*b.ini \\[JOINT_0\\] \\(mm, type 0\\): give --ini"):
        find_comp_settings(tmp_path / "screwcompX.dat")
    (tmp_path / "b.ini").write_text(text)                    # agreeing INIs are fine
    assert find_comp_settings(tmp_path / "screwcompX.dat").unit == "inch"


def test_ini_syntax_as_linuxcnc_documents_it():
    """INI Configuration, "The INI File Components": ; and # comment lines, '#' inside a value
    is part of it, the first of two equal variables wins, a trailing backslash continues."""
    s = parse_ini("# c\n[TRAJ]\n; c\nLINEAR_UNITS = mm\nLINEAR_UNITS = inch\n[JOINT_3]\n"
                  "TYPE = ANGULAR\nCOMP_FILE = a#b.comp\nCOMP_FILE_TYPE = 1\nX = 1 \\\n 2\n"
                  "[JOINT_4]\nCOMP_FILE =\n")
    assert s["TRAJ"]["LINEAR_UNITS"] == "mm" and s["JOINT_3"]["COMP_FILE"] == "a#b.comp"
    assert s["JOINT_3"]["X"] == "1  2"
    assert comp_sections(s) == [("JOINT_3", "a#b.comp")]
    with pytest.raises(DataFormatError, match="no \\[TRAJ\\] ANGULAR_UNITS"):
        comp_settings(s, "JOINT_3", "m.ini")


def test_a_rotary_joint_in_its_angular_units():
    """[JOINT_n] TYPE = ANGULAR takes [TRAJ] ANGULAR_UNITS; [JOINT_n] UNITS overrides it (INI
    Configuration, [JOINT_<num>] UNITS). A file in gon (0.9° each) is read in degrees."""
    s = parse_ini("[TRAJ]\nLINEAR_UNITS = mm\nANGULAR_UNITS = degree\n[JOINT_3]\nTYPE = ANGULAR\n"
                  "UNITS = gon\nCOMP_FILE = c.comp\nCOMP_FILE_TYPE = 1\n")
    cs = comp_settings(s, "JOINT_3", "m.ini")
    assert (cs.axis_kind, cs.unit, cs.unit_from) == ("rotary", "gon", "[JOINT_3] UNITS = gon")
    text = "0 0 0\n100 0.001 -0.001\n200 0 0\n300 0 0\n400 0 0\n"
    opts, _ = read_options(cs, {}, text)
    t = linuxcnc.parse(text, **opts)
    assert t.positions.tolist() == [0.0, 90.0, 180.0, 270.0, 360.0] and t.modulo
    assert t.up[1] == pytest.approx(0.001 * 0.9 * 3600)                   # arcsec


IRREGULAR_INCH = """-10.0 -10.0012 -9.9991
-7.3 -7.3009 -7.2993
-2.15 -2.1504 -2.1497
3.8 3.8003 3.8008
10.0 10.0011 10.0014
; measured 2026-11-20 with the laser, type 0, inch
"""


def test_an_irregular_inch_type_0_file_with_a_trailing_comment_is_told_by_content(tmp_path):
    """A comment line after the data is never read by LinuxCNC (usrmotLoadComp stops at the
    first line that is not three numbers), so the file is recognised and read whole."""
    assert detect(IRREGULAR_INCH) == "linuxcnc"
    assert linuxcnc.trailing_lines(IRREGULAR_INCH) == 1
    p = tmp_path / "x.comp"
    p.write_text(IRREGULAR_INCH)
    t, inputs = _read(p, unit="inch")
    assert inputs["file_type"].value == 0 and inputs["file_type"].assumed
    assert not t.equidistant and t.positions[1] == pytest.approx(-7.3 * 25.4)
    assert t.up[0] == pytest.approx(0.0012 * 25400) and t.down[1] == pytest.approx(-0.0007 * 25400)
    assert linuxcnc.trim_jumps(t) == ()


def test_a_comment_before_data_or_a_last_line_cut_short_is_refused():
    with pytest.raises(DataFormatError, match="LinuxCNC stops reading at this line"):
        linuxcnc.parse("# header\n0 0 0\n10 0 0\n")
    with pytest.raises(DataFormatError, match="stops reading") as e:    # a point would be lost
        linuxcnc.parse("0 0 0\n10 0 0\n20 0.001\n")
    assert str(e.value).startswith("<text>:3:")                          # the line is named
    assert detect("# header\n0 0 0\n10 0 0\n") is None


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet=st.sampled_from(list("[]=;#\\ \n_JOINTAXISCOMPFILETYPEUNITS0123.-inchmdegra")),
               max_size=300))
def test_arbitrary_ini_and_comp_text_raise_only_axiscal_errors(text):
    """Habit 9: a parser never raises anything but AxiscalError on arbitrary text."""
    sections = parse_ini(text)
    for section, _ in comp_sections(sections):
        try:
            read_options(comp_settings(sections, section, "m.ini"), {}, "0 0 0\n1 0 0\n")
        except AxiscalError:
            pass
    try:
        linuxcnc.parse(text)
    except AxiscalError:
        pass
    found = detect(text)
    assert found is None or found in CONTROLLERS
