"""Fanuc and Siemens 840D files as machines hold them (issue 27): punched listings with every axis
on one line, full listings with 3625-3627 at zero, the reference position a Fanuc tape does not
carry, 840D tables on an inch machine (MD10240 = 0), and every writer round-tripping in mm and
inch."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.compensation.controllers import controller, fanuc, siemens_840d
from axiscal.compensation.tables import table_from_deviations
from axiscal.errors import DataFormatError

#: A punched parameter listing of a three-axis machine as the control outputs it (FANUC Series
#: 15i/150i-MODEL A Parameter Manual B-63330EN/03 §3: an axis-type parameter holds every axis on
#: one line, N***** A* P****** A* P****** …; a bit parameter's eight digits count bit 0 from the
#: right): 3605#0 = 0 and 3625-3627 present and zero on every axis, other parameters around them,
#: one line with the Q1 of the 30i series (B-63950EN/02 §3.3).
LISTING = """%
N00000P00001100
N01420A1P4000.0A2P4000.0A3P4000.0
N03605Q1A1P00000000A2P00000000A3P00000000
N03620A1P2A2P40A3P80
N03621A1P0A2P38A3P80
N03622A1P4A2P42A3P82
N03623A1P1A2P2A3P1
N03624A1P10000A2P20000A3P5000
N03625A1P0A2P0A3P0
N03626A1P0A2P0A3P0
N03627A1P0A2P0A3P0
N10000P0
N10001P3
N10002P-2
N10003P1
N10004P4
N10038P1
N10039P-1
N10040P2
N10041P0
N10042P-3
N10080P7
N10081P-1
N10082P1
%
"""

#: Each axis of LISTING by hand (0i-PB Parameter Manual B-63980EN/01 §4, parameters 3620-3624:
#: the value at point N is the increment over the interval ending at N, times 3623; zero at the
#: reference point 3620; positions (N − 3620) × 3624 from the reference, 1 count = 0.001 mm):
#: axis 1 increments 3, −2, 1, 4 after point 0 -> absolute 0, 3, 1, 2, 6 -> minus point 2 (1);
#: axis 2 increments (−1, 2, 0, −3) × 2 -> 0, −2, 2, 2, −4 -> minus point 40 (2);
#: axis 3 increments −1, 1 -> 0, −1, 0 (reference point 80 is the first).
EXPECTED = {1: ([-20, -10, 0, 10, 20], [-1, 2, 0, 1, 5]),
            2: ([-40, -20, 0, 20, 40], [-2, -4, 0, 0, -6]),
            3: ([0, 5, 10], [0, -1, 0])}


@pytest.mark.parametrize("axis_number", [1, 2, 3])
def test_punched_listing_every_axis_read_to_the_right_values(axis_number):
    t = fanuc.parse(LISTING, axis_number=axis_number, reference_position=0.0)
    positions, um = EXPECTED[axis_number]
    assert t.positions.tolist() == pytest.approx(positions)
    assert t.up.tolist() == pytest.approx(um) and t.down.tolist() == pytest.approx(um)
    assert not t.bidirectional and not t.modulo      # 3605#0 = 0, 3625 = 0


def test_punched_listing_with_several_axes_names_them_without_a_choice():
    with pytest.raises(DataFormatError, match=r"axes 1, 2, 3: choose one with axis_number"):
        fanuc.parse(LISTING)
    with pytest.raises(DataFormatError, match="no pitch error parameters for axis 4; the "
                                              "listing holds axes 1, 2, 3"):
        fanuc.parse(LISTING, axis_number=4)


def test_full_listing_with_zero_3625_to_3627_is_one_table():
    """Was refused as 'pitch error data for point 0 is missing' (3626 = 0 read as a negative
    table at point 0). A-77810E §2 table (a): 3605#0 = 0 disables bidirectional compensation, so
    3626/3627 are unused; without 3605 on the tape, 3626 = 3627 = 0 are unset as well."""
    one_axis = "\n".join(ln.split("A2")[0] if ln.startswith("N03") else ln
                         for ln in LISTING.splitlines()) + "\n"
    assert "N03626A1P0\n" in one_axis
    t = fanuc.parse(one_axis, reference_position=0.0)
    assert t.up.tolist() == pytest.approx(EXPECTED[1][1]) and not t.bidirectional
    without_3605 = "".join(ln + "\n" for ln in one_axis.splitlines() if "N03605" not in ln)
    assert not fanuc.parse(without_3605, reference_position=0.0).bidirectional
    on = one_axis.replace("N03605Q1A1P00000000", "N03605Q1A1P00000001")
    with pytest.raises(DataFormatError, match="3626 = 0: the negative-direction points 0 … 4 "
                                              "overlap the positive-direction points 0 … 4"):
        fanuc.parse(on, reference_position=0.0)   # 3605#0 = 1 with 3626 = 0: one table twice


def test_fanuc_tape_carries_its_reference_position_and_a_foreign_one_assumes_zero():
    """The control puts point 3620 where the reference return ends (0i-PB §4 Example 1 draws it
    at machine coordinate 0); the tape holds no coordinate, so axiscal states it in a comment."""
    t = table_from_deviations([15.0, 25.2, 35.4], [7.0, 13.7, -26.6], spacing=10.2, axis="X")
    cf = fanuc.write(t)
    assert "(REFERENCE POSITION 15 MM AT POINT 0)" in cf.text
    back = fanuc.parse(cf.text)
    assert back.positions.tolist() == pytest.approx([15.0, 25.2, 35.4])
    got = {i.name: i for i in fanuc.inputs(cf.text)}
    assert got["reference_position"].source == "file" and got["reference_position"].value == 15
    foreign = cf.text.replace("(REFERENCE POSITION 15 MM AT POINT 0)\n", "")
    assert fanuc.parse(foreign).start == 0.0
    ref = {i.name: i for i in fanuc.inputs(foreign)}["reference_position"]
    assert ref.assumed and ref.needed_to_compare and ref.value == 0.0
    assert fanuc.parse(foreign, reference_position=15).start == 15.0
    with pytest.raises(DataFormatError, match=re.escape(
            "reference_position = 0 mm contradicts the file (from the tape's comment: 15 mm)")):
        fanuc.parse(cf.text, reference_position=0.0)


def test_fanuc_detection_unit_and_axis_kind_come_from_the_comment():
    th = np.arange(0, 361, 45.0)
    t = table_from_deviations(th, 3.6 * np.sin(np.radians(th)), spacing=45, modulo=True,
                              axis="C", axis_kind="rotary", position_unit="deg",
                              correction_unit="arcsec")
    cf = fanuc.write(t, detection_unit=0.0001)
    back = fanuc.parse(cf.text)                  # no options: the comment says 0.0001 DEG
    assert back.axis_kind.value == "rotary" and back.spacing == pytest.approx(45.0)
    np.testing.assert_allclose(back.up, cf.table.up, atol=1e-6)
    with pytest.raises(DataFormatError, match=re.escape(
            "detection_unit = 0.001 deg contradicts the file (from the tape's comment: 0.0001")):
        fanuc.parse(cf.text, detection_unit=0.001)


#: An EEC file as an inch machine holds it (tests/data/siemens/README.md: the SINUMERIK 840D sl
#: Function Manual Extended Functions K3 layout; MD10240 = 0: values, STEP, MIN and MAX in inch,
#: 808D ADVANCED Parameter Manual §2.2): −1 … 0 inch every 0.5 inch, deviations 0, +0.0001 and
#: −0.0002 inch.
INCH_EEC = (Path(__file__).resolve().parents[1] / "data" / "siemens"
            / "inch_AX_EEC.INI").read_text()


def test_840d_inch_table_read_to_the_right_values():
    """Positions −25.4, −12.7, 0 mm; corrections = −deviation = 0, −2.54, +5.08 µm."""
    t = siemens_840d.parse(INCH_EEC)
    assert t.positions.tolist() == pytest.approx([-25.4, -12.7, 0.0])
    assert t.up.tolist() == pytest.approx([0.0, -2.54, 5.08])
    (unit,) = siemens_840d.inputs(INCH_EEC)
    assert unit.value == "inch" and unit.source == "file" and "MD10240" in unit.why
    archive = INCH_EEC.replace("; MD10240 $MN_SCALING_SYSTEM_IS_METRIC = 0",
                               "$MN_SCALING_SYSTEM_IS_METRIC=0")
    assert siemens_840d.parse(archive).up.tolist() == pytest.approx([0.0, -2.54, 5.08])
    silent = INCH_EEC.replace("; MD10240 $MN_SCALING_SYSTEM_IS_METRIC = 0\n", "")
    assert siemens_840d.parse(silent).positions.tolist() == pytest.approx([-1.0, -0.5, 0.0])
    assert siemens_840d.inputs(silent)[0].assumed        # mm, said as an assumption
    assert siemens_840d.parse(silent, unit="inch").up.tolist() == pytest.approx([0, -2.54, 5.08])


def test_840d_unit_contradicting_the_file_is_refused():
    with pytest.raises(DataFormatError, match=re.escape(
            "unit = mm contradicts the file (the file states MD10240 "
            "$MN_SCALING_SYSTEM_IS_METRIC = 0: inch)")):
        siemens_840d.parse(INCH_EEC, unit="mm")
    both = INCH_EEC.replace("CHANDATA(1)", "CHANDATA(1)\n$MN_SCALING_SYSTEM_IS_METRIC=1")
    with pytest.raises(DataFormatError, match="contradicts an earlier line"):
        siemens_840d.parse(both)


def test_840d_inch_file_states_md10240_in_comment_and_enable_list():
    t = table_from_deviations([0, 25.4, 50.8], [1.0, 3.0, 5.0], [-1.0, 1.0, 3.0], spacing=12.7,
                              axis="X")
    cf = siemens_840d.write(t, unit="inch")
    assert "; MD10240 $MN_SCALING_SYSTEM_IS_METRIC = 0: values, STEP, MIN and MAX in inch" in cf.text
    assert "$AA_ENC_COMP_STEP[0,AX1]=0.5" in cf.text and "$AA_ENC_COMP_MAX[0,AX1]=2.0" in cf.text
    assert any(e.startswith("MD10240 $MN_SCALING_SYSTEM_IS_METRIC = 0") for e in cf.enable)
    assert "SCALING_SYSTEM_IS_METRIC = 1" in siemens_840d.write(t).text


# -- every writer round-trips: write -> read -> the same table, in mm and in inch ----------------
#: The controllers that have inch machines, and what each needs to read its file back: the
#: Fanuc tape and the 840D file state their unit in comments, Heidenhain's BEGIN line says INCH,
#: a LinuxCNC file carries no unit (the INI's LINEAR_UNITS gives it).
UNITS = [(name, "mm") for name in ("siemens-840d", "fanuc", "heidenhain", "linuxcnc", "csv")] + [
    ("fanuc", "inch"), ("siemens-840d", "inch"), ("heidenhain", "inch"), ("linuxcnc", "inch")]
WRITE = {("fanuc", "mm"): dict(detection_unit=0.0001),
         ("fanuc", "inch"): dict(detection_unit=0.0001, unit="inch")}
READ = {("linuxcnc", "inch"): dict(unit="inch")}


@settings(max_examples=40, deadline=None)
@given(values=st.lists(st.integers(-400, 400), min_size=2, max_size=30),
       reversal=st.lists(st.integers(-40, 40), min_size=30, max_size=30),
       step=st.integers(1, 400), start=st.integers(-4000, 4000), reference=st.integers(0, 29),
       bidirectional=st.booleans(), case=st.sampled_from(UNITS))
def test_every_writer_round_trips_in_mm_and_inch(values, reversal, step, start, reference,
                                                 bidirectional, case):
    """parse(write(t)) is the table the writer says it wrote, point for point; and that keeps
    the shape of t (mean corrections relative to the reference point, mean reversal) within
    the format's rounding. Positions on a grid of 0.005 inch = 0.127 mm, which is a whole
    number of every controller's position unit in mm and in inch."""
    name, unit = case
    n = len(values)
    up = np.array(values, dtype=float) * 0.25
    down = up + np.array(reversal[:n]) * 0.25 if bidirectional else None
    x = (start + step * np.arange(n)) * 0.127
    t = table_from_deviations(x, -up, None if down is None else -down, spacing=step * 0.127,
                              reference=x[min(reference, n - 1)], axis="X")
    opts = dict(WRITE.get(case, {}))
    if unit == "inch" and name != "fanuc":
        opts["unit"] = "inch"
    written = controller(name).write(t, **opts)
    back = controller(name).parse(written.text, **READ.get(case, {}))
    w = written.table
    assert back.n_points == w.n_points
    # a LinuxCNC file has no flag: equal forward and reverse trims read back as one table
    assert back.bidirectional == w.bidirectional or np.array_equal(w.up, w.down)
    np.testing.assert_allclose(back.positions, w.positions, rtol=0, atol=1e-9)
    np.testing.assert_allclose(back.up, w.up, rtol=0, atol=1e-6)
    np.testing.assert_allclose(back.down, w.down, rtol=0, atol=1e-6)
    tol = back.resolution + 1e-6 if name == "fanuc" else 0.01       # µm
    r = t.reference_index
    np.testing.assert_allclose(w.mean - w.mean[r], t.mean - t.mean[r], rtol=0, atol=tol)
    assert abs(w.backlash - t.backlash) <= tol
