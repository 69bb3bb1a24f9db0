"""The five-axis probing and R-test CSV files (axiscal.io.five_axis): round trip, and each bad
input refused with one line naming the line of the file (issue 43: a missing pose, a NaN, a sphere
radius that contradicts the data, a rotary axis named twice)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from axiscal.api import fiveaxis
from axiscal.errors import AxiscalError, DataFormatError, InputError
from axiscal.io.five_axis import format_five_axis, parse_five_axis

HEADER = "# sphere_radius_mm = 12.5\n# stylus_radius_mm = 1.5\npose,A_deg,C_deg,x_mm,y_mm,z_mm\n"
TOUCH = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, 1.0]]) * 14.0


def _rows(pose, a, c, centre=(100.0, 0.0, 50.0)):
    return "".join(f"{pose},{a},{c},{p[0]},{p[1]},{p[2]}\n" for p in TOUCH + centre)


@pytest.fixture(scope="module")
def records():
    from importlib import resources

    from axiscal.io._files import load_toml
    sim = fiveaxis.simulate(load_toml(resources.files("axiscal.data").joinpath("fiveaxis_ac.toml")),
                            seed=3)
    return sim.records


def test_written_files_read_back_to_the_same_identification(records):
    back = [parse_five_axis(format_five_axis(r)) for r in records]
    assert [b.kind for b in back] == ["probing", "probing", "r-test"]
    for r, b in zip(records, back):
        np.testing.assert_allclose(b.tilt_angle, r.tilt_angle, atol=1e-8)
        a, bb = r.setup().values, b.setup().values
        np.testing.assert_allclose(bb, a, atol=2e-10)      # 0.1 nm / 0.1 nm·µm of the format
    assert back[0].label == "sphere 1" and back[2].u_gain == 0.001


def test_a_minimal_probing_file():
    rec = parse_five_axis(HEADER + _rows(1, 0, 0) + _rows(2, -30, 90))
    assert rec.tilt == "A" and len(rec.touches) == 2
    np.testing.assert_allclose(rec.setup().values[0], [0.1, 0.0, 0.05], atol=1e-12)


@pytest.mark.parametrize("text, rule", [
    (HEADER + _rows(1, 0, 0) + _rows(3, 0, 90), r"<text>:9: pose 2 is missing"),
    (HEADER + _rows(1, 0, 0).replace("114.0", "nan", 1), r"<text>:5: x_mm = nan is not a finite"),
    (HEADER + "1,0,,1,2,3\n", r"<text>:4: C_deg is empty"),
    (HEADER.replace("12.5", "12.45") + _rows(1, 0, 0),
     r"pose 1: fitted radius 14.0000 mm differs from the expected 13.9500 mm"),
    (HEADER.replace("pose,A_deg,C_deg", "pose,A_deg,A_deg") + _rows(1, 0, 0),
     r"<text>:3: rotary axis A named twice in the header"),
    (HEADER.replace("pose,A_deg,C_deg", "pose,A_deg,B_deg") + _rows(1, 0, 0),
     r"names A and B tilting axis"),
    (HEADER + _rows(1, 0, 0)[:-30].rsplit("\n", 1)[0] + "\n", r"pose 1 has 4 touches|at least 4"),
    (HEADER + _rows(1, 0, 0) + "1,10,0,1,2,3\n", r"rows of pose 1 give different angles"),
    ("# stylus_radius_mm = 1\npose,A_deg,C_deg,x_mm,y_mm,z_mm\n" + _rows(1, 0, 0),
     r"no '# sphere_radius_mm"),
    ("# sphere_raduis_mm = 1\n" + HEADER + _rows(1, 0, 0), r"unknown setting 'sphere_raduis_mm'"),
    ("pose,A_deg,C_deg,X_mm,Y_mm,Z_mm,dx_um,dy_um,dz_um\n1,0,0,1,2,3,0,0,0\n1,0,0,1,2,3,0,0,0\n",
     r"pose 1 given twice"),
])
def test_bad_files_are_refused_with_one_line(text, rule):
    with pytest.raises(AxiscalError, match=rule) as e:
        parse_five_axis(text)
    assert "\n" not in str(e.value) and isinstance(e.value, (DataFormatError, InputError))


@settings(max_examples=60, deadline=None)
@given(st.text(max_size=300))
def test_the_parser_raises_only_axiscal_errors(text):
    try:
        parse_five_axis(HEADER + text)
    except AxiscalError:
        pass
