"""Renishaw .ren compensation exports, laid out as the public .REN → Siemens converter reads them.

The converter (public code index id 48250776003) takes the first number of the lines holding
``Compensation spacing``, ``Compensation start`` and ``Compensation end`` as $AA_ENC_COMP_STEP,
_MIN and _MAX, and the third number of each row after the header
``No.     Axis position        Combined`` as $AA_ENC_COMP[1,i,AXIS], i = 0, 1, … unchanged.
"""

import numpy as np
import pytest

from axiscal.compensation.controllers import CONTROLLERS, controller, detect
from axiscal.compensation.controllers import renishaw_ren as ren
from axiscal.compensation.controllers import siemens_840d
from axiscal.compensation.tables import table_from_deviations
from axiscal.errors import DataFormatError

ROWS = [(-100.0, 0.002), (-50.0, 0.001), (0.0, 0.0), (50.0, -0.0015), (100.0, -0.003)]


def ren_text(rows=ROWS, spacing="50.000000", start="-100.000000", end="100.000000",
             header="No.     Axis position        Combined"):
    lines = ["Axis : X", f"Compensation spacing : {spacing}", f"Compensation start : {start}",
             f"Compensation end : {end}", "", header]
    lines += [f"{i:<8d}{p:<21.6f}{v:.6f}" for i, (p, v) in enumerate(rows)]
    return "\r\n".join(lines) + "\r\n"


def test_a_ren_reads_as_the_table_the_converter_makes():
    """Combined = the Siemens value = axis error in mm: correction = −1000 × value µm."""
    t = ren.parse(ren_text())
    assert detect(ren_text()) == "renishaw-ren"
    assert (t.axis, t.start, t.spacing, t.n_points) == ("X", -100.0, 50.0, 5)
    assert t.up.tolist() == [-2.0, -1.0, 0.0, 1.5, 3.0] and t.correction_unit == "um"
    siemens = siemens_840d.write(t, zero_at_reference=False, machine_axis="X")
    values = [float(ln.split("=")[1]) for ln in siemens.text.splitlines()
              if ln.startswith("$AA_ENC_COMP[")]
    assert values == [v for _p, v in ROWS]            # what the converter would have copied
    for key, want in (("STEP", 50.0), ("MIN", -100.0), ("MAX", 100.0)):
        line = next(ln for ln in siemens.text.splitlines() if ln.startswith(f"$AA_ENC_COMP_{key}"))
        assert float(line.split("=")[1]) == want


@pytest.mark.parametrize("name", sorted(CONTROLLERS))
def test_a_ren_table_converted_to_each_controller_and_back(name):
    """Each controller's file reads back as the table written (up to its rounding and, where the
    controller re-references, one constant shift)."""
    t = ren.parse(ren_text())
    mod = controller(name)
    cf = mod.write(t)
    back = mod.parse(cf.text)
    assert back.n_points == t.n_points and back.positions.tolist() == t.positions.tolist()
    np.testing.assert_allclose(back.up, cf.table.up, atol=1e-6)
    shift = back.up - t.up
    assert np.ptp(shift) <= 0.5 + 1e-9          # Fanuc's 1 µm detection unit rounds by ≤ 0.5 µm
    again = ren.parse(ren.write(back).text)
    np.testing.assert_allclose(again.up, back.up, atol=1e-6)


def test_write_then_read_gives_the_written_table_and_crlf():
    t = table_from_deviations([0, 100, 200, 300], [2.0, -1.0, 4.0, 0.5], spacing=50, axis="Y")
    cf = ren.write(t)
    assert cf.text.count("\r\n") == cf.text.count("\n") and cf.filename == "Y.REN"
    back = ren.parse(cf.text)
    assert back.axis == "Y" and back.up.tolist() == cf.table.up.tolist() == t.up.tolist()
    bi = table_from_deviations([0, 100, 200], [2.0, -1.0, 4.0], [3.0, 0.0, 5.0], spacing=50)
    cf = ren.write(bi)
    assert any("mean of both directions" in n for n in cf.notes)
    back = ren.parse(cf.text)
    assert back.bidirectional and back.backlash == pytest.approx(bi.backlash, abs=1e-6)
    np.testing.assert_allclose(back.mean, bi.mean, atol=1e-6)
    np.testing.assert_allclose(back.up, cf.table.up, atol=1e-6)
    siemens = siemens_840d.parse(siemens_840d.write(bi, zero_at_reference=False).text)
    np.testing.assert_allclose(back.up, siemens.up, atol=1e-6)   # the same mean + backlash


@pytest.mark.parametrize("text, words", [
    (ren_text(spacing="40.000000"), "makes 6 points but the table has 5 rows"),
    (ren_text(rows=ROWS[:4]), "the table has 4 rows"),
    (ren_text().replace("0.001000", "0,001"), "'0,001' is not a number"),
    (ren_text().replace("Compensation end", "Compensation stop"), "Compensation end"),
    (ren_text(header="No. Position Value"), "no table header"),
    (ren_text().replace("-50.000000", "-40.000000"), "not at start + 1 × spacing"),
    (ren_text() + "Checksum 12\r\n", "a table row is No., position and value"),
])
def test_damaged_ren_refused_in_one_line(text, words):
    with pytest.raises(DataFormatError) as e:
        ren.parse(text, source="X.REN")
    assert words in str(e.value) and "\n" not in str(e.value), str(e.value)
