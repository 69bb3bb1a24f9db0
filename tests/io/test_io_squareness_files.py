"""Readers of straightness, ballbar and diagonal CSV files (axiscal.io.straightness, .ballbar)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.errors import AxiscalError, DataFormatError, MissingFileError
from axiscal.io.ballbar import (
    BallbarData,
    format_ballbar,
    parse_ballbar,
    parse_diagonal,
    read_ballbar,
    read_diagonal,
)
from axiscal.io.straightness import (
    format_straightness,
    parse_straightness,
    read_straightness,
)
from axiscal.standards.iso230_4 import CircularRun


def test_straightness_units_and_round_trip(tmp_path):
    d = parse_straightness("# position_unit=m deviation_unit=mm axis=x direction=z\n"
                           "position,deviation\n0.0,0.001\n0.5,-0.002\n")
    assert d.positions.tolist() == [0.0, 0.5]
    assert d.deviations.tolist() == pytest.approx([1e-6, -2e-6])
    assert (d.axis, d.direction) == ("X", "Z")
    p = tmp_path / "s.csv"
    p.write_text(format_straightness(d))
    back = read_straightness(p)
    assert np.allclose(back.deviations, d.deviations, rtol=1e-9)
    assert back.source == str(p)
    assert parse_straightness("position,deviation\n0,1\n1,2\n", deviation_unit="nm"
                              ).deviations.tolist() == pytest.approx([1e-9, 2e-9])


@pytest.mark.parametrize("text, words", [
    ("pos,dev\n0,1\n", "lacks column"),
    ("position,deviation\n", "no data"),
    ("position,deviation\n0,1\n0,2\n", "one position"),
    ("position,deviation\n0,1\n1,inf\n", "finite"),
    ("# position_unit=furlong\nposition,deviation\n0,1\n1,2\n", "furlong"),
    ("position,deviation\n0\n", "cells"),
])
def test_straightness_errors_name_the_problem(text, words):
    with pytest.raises(DataFormatError, match=words):
        parse_straightness(text)


def test_missing_file():
    with pytest.raises(MissingFileError):
        read_straightness("/no/such/file.csv")


def test_ballbar_round_trip_and_directions(tmp_path):
    phi = np.radians(np.arange(0, 360, 5.0))
    runs = (CircularRun(phi, 1e-6 * np.sin(phi), "ccw"), CircularRun(phi, -1e-6 * np.cos(phi), "cw"))
    p = tmp_path / "b.csv"
    p.write_text(format_ballbar(BallbarData(0.1, runs, ("X", "Z"))))
    back = read_ballbar(p)
    assert back.radius == pytest.approx(0.1)
    assert back.axes == ("X", "Z")
    assert [r.direction for r in back.runs] == ["ccw", "cw"]
    assert np.allclose(back.runs[1].deviations, runs[1].deviations, atol=1e-15)
    assert read_ballbar(p, radius_mm=50).radius == pytest.approx(0.05)


@pytest.mark.parametrize("text, words", [
    ("angle,direction,deviation\n0,ccw,1\n", "radius"),
    ("# radius_mm=100\nangle,direction,deviation\n0,up,1\n", "ccw or cw"),
    ("# radius_mm=100 plane=XX\nangle,direction,deviation\n0,ccw,1\n", "plane"),
    ("# radius_mm=100\nangle,direction,deviation\n0,ccw,1\n", "at least 8"),
    ("# radius_mm=-1\nangle,direction,deviation\n0,ccw,1\n", "positive"),
])
def test_ballbar_errors(text, words):
    with pytest.raises(DataFormatError, match=words):
        parse_ballbar(text)


def test_diagonal_file(tmp_path):
    p = tmp_path / "d.csv"
    p.write_text("# length_x_mm=600 length_y_mm=800 error_unit=nm\ndiagonal,position,error\n"
                 "D1,0,0\nd1,1000,12\nD2,0,0\nD2,1000,-12\n")
    d = read_diagonal(p)
    assert (d.length_x, d.length_y) == (0.6, 0.8)
    assert d.errors_d1.tolist() == pytest.approx([0.0, 12e-9])
    with pytest.raises(DataFormatError, match="length_y_mm"):
        parse_diagonal("# length_x_mm=1\ndiagonal,position,error\nD1,0,0\n")
    with pytest.raises(DataFormatError, match="D3"):
        parse_diagonal("# length_x_mm=1 length_y_mm=1\ndiagonal,position,error\nD3,0,0\n")
    with pytest.raises(DataFormatError, match="D2 has 0"):
        parse_diagonal("# length_x_mm=1 length_y_mm=1\ndiagonal,position,error\nD1,0,0\nD1,1,0\n")


@settings(max_examples=150, deadline=None)
@given(st.text(max_size=300))
def test_parsers_raise_only_axiscal_errors_on_any_text(text):
    """CONVENTIONS habit 9: parsers never raise anything but AxiscalError on arbitrary text."""
    for parse in (parse_straightness, parse_ballbar, parse_diagonal):
        try:
            parse(text)
        except AxiscalError:
            pass
