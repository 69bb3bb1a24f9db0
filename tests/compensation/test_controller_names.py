"""Names in controller files (issue 27): an ecmc setpoint PV name as the axis name becomes what
each controller accepts, the source name stays in a comment, and every writer round-trips.

The data is a real PSI SLS ecmc ISO 230-2 file (tests/data/ecmc, see its README): its setpoint PV
``sls-sioc-ecat01:M1-PosSet`` is the dataset's axis name."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from axiscal.compensation.controllers import controller
from axiscal.compensation.controllers._common import SOURCE_COMMENT, safe_axis_name
from axiscal.compensation.tables import table_from_result
from axiscal.errors import ControllerLimitError
from axiscal.io.ecmc import read_ecmc
from axiscal.standards.iso230_2 import evaluate

ECMC = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "sls_fat_sat_ISO230.dat"
PV = "sls-sioc-ecat01:M1-PosSet"
#: The POSIX portable filename character set (IEEE Std 1003.1-2004 §3.276), which TNC file names
#: keep to (HEIDENHAIN TNC 640 User's Manual, File names) and which holds no character Windows
#: reserves (< > : " / \ | ? *).
PORTABLE = re.compile(r"^[A-Za-z0-9._-]+$")
#: Each writer's comment lines (Heidenhain's .COM has no documented comment: none).
COMMENT = {"siemens-840d": ";", "fanuc": "(", "linuxcnc": "#", "csv": "#"}


@pytest.fixture(scope="module")
def table():
    ds = read_ecmc(ECMC)
    assert ds.metadata.axis == PV
    return table_from_result(evaluate(ds), 0.512, axis=ds.metadata.axis)


@pytest.mark.parametrize("name", ["siemens-840d", "fanuc", "linuxcnc", "csv"])
def test_an_ecmc_pv_name_becomes_a_safe_name_kept_in_a_comment(table, name):
    f = controller(name).write(table)
    assert PORTABLE.match(f.filename), f.filename
    assert f.table.axis == "sls-sioc-ecat01_M1-PosSet"
    body = [ln for ln in f.text.splitlines() if not ln.startswith(COMMENT[name])]
    assert not any(PV in ln or ":M1" in ln for ln in body)
    comments = [ln for ln in f.text.splitlines() if SOURCE_COMMENT in ln.lower()]
    assert len(comments) == 1 and PV.lower() in comments[0].lower()
    assert comments[0].startswith(COMMENT[name])
    enable = " ".join(f.enable)
    assert PV not in enable and PV.lower() not in enable


@pytest.mark.parametrize("name", ["siemens-840d", "fanuc", "linuxcnc", "csv", "heidenhain"])
def test_every_writer_round_trips_the_ecmc_table(table, name):
    """parse(write(t)) gives the written table back: axis name, positions and corrections."""
    opts = {"axis": "X"} if name == "heidenhain" else {}
    f = controller(name).write(table, **opts)
    back = controller(name).parse(f.text)
    w = f.table
    assert back.axis == w.axis
    np.testing.assert_allclose(back.positions, w.positions, rtol=0, atol=1e-9)
    np.testing.assert_allclose(back.up, w.up, rtol=0, atol=1e-6)
    np.testing.assert_allclose(back.down, w.down, rtol=0, atol=1e-6)


def test_linuxcnc_comp_file_name_has_no_colon(table):
    f = controller("linuxcnc").write(table)
    assert f.filename == "sls-sioc-ecat01_m1-posset.comp"
    assert "[JOINT_0] COMP_FILE = sls-sioc-ecat01_m1-posset.comp" in f.enable
    assert f.text.splitlines()[-1] == f"# {SOURCE_COMMENT} {PV}"


def test_heidenhain_wants_an_axis_letter(table):
    """The value column is named by the axis key (MANUALplus 620, "Entering compensation
    values"): a PV name is refused naming -o axis=; with it, the column, file names and .CMA
    use the letter and the notes keep the PV name."""
    with pytest.raises(ControllerLimitError, match="axis letter .*give -o axis=X"):
        controller("heidenhain").write(table)
    f = controller("heidenhain").write(table, axis="z")
    assert f.filename == "Z.COM" and f.text.startswith("BEGIN Z.COM MM")
    assert f.text.splitlines()[1].split()[:3] == ["NR", "AXISPOS", "Z"]
    assert list(f.extra_files) == ["Z.CMA"] and PV not in f.extra_files["Z.CMA"]
    assert any(PV in n for n in f.notes)
    with pytest.raises(ControllerLimitError, match="-o axis= 'X:1' is not one"):
        controller("heidenhain").write(table, axis="X:1")


@pytest.mark.parametrize("source, expected", [
    ("X", "X"), ("sls-sioc-ecat01:M1-PosSet", "sls-sioc-ecat01_M1-PosSet"),
    ('a<b>c"d/e\\f|g?h*i', "a_b_c_d_e_f_g_h_i"), ("CON", "CON_"), ("com1", "com1_"),
    ("-x axis-", "x_axis"), ("Achse Ä 1", "Achse_1"), ("::", ""), ("y" * 100, "y" * 64)])
def test_safe_names_keep_to_the_portable_set(source, expected):
    """Windows reserves < > : " / \\ | ? * and the device names CON, COM1 … (Microsoft, "Naming
    Files, Paths, and Namespaces"); a POSIX portable name does not begin with '-'."""
    n = safe_axis_name(source, "test")
    assert n.name == expected
    assert n.changed == (source != expected)
    assert n.name == "" or PORTABLE.match(n.name)


def test_the_source_comment_cannot_end_early():
    n = safe_axis_name("a)b\nc", "fanuc")
    assert n.comment("(", ")", upper=True) == [f"({SOURCE_COMMENT.upper()} A?B?C)"]
    assert safe_axis_name("X", "fanuc").comment("(", ")") == []
